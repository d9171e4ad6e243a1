"""The servo over its cycle: the motor's torque–speed points over the motor's envelope
(left), and the profile's s, v, a, j over the cycle time with the segments' boundaries
marked (right).

The envelope is the chosen catalogue motor's (its peak torque at each speed up to the top
speed, and its rated torque as the thermal line the RMS torque must stay under); without
a catalogue only the cycle's points, the peak and the RMS torque are drawn.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas
from dyade.units import RAD_PER_S_TO_RPM

PROFILE = (("s", "s", ""), ("v", "v", "/s"), ("a", "a", "/s²"), ("j", "j", "/s³"))
"""column, label, the unit's time part"""


def figure(outcome, fig: Figure | None = None) -> Figure:
    """The torque–speed points of a ``servo`` Outcome over its motor's envelope, and the
    profile's s, v, a, j.

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot import servo as plot
    >>> fig = plot.figure(dyade.run("servo", "mechanisms/servo/fourbar.toml"))
    >>> len(fig.axes)
    5
    """
    run = outcome.result
    columns = outcome.columns
    speed = columns["n_motor_rpm"]
    torque = columns["M_motor"]
    with canvas.style():
        fig = canvas.new(11.0, 5.6, fig)
        outer = fig.add_gridspec(1, 2, width_ratios=(1.15, 1.0), wspace=0.25)
        left = fig.add_subplot(outer[0])
        right = outer[1].subgridspec(4, 1, hspace=0.12)
        braking = torque * speed < 0.0
        left.plot(speed, torque, color="0.75", lw=0.8, zorder=1)
        left.scatter(speed[~braking], torque[~braking], s=6, color=canvas.line(0)["color"],
                     label="motoring", zorder=2)
        left.scatter(speed[braking], torque[braking], s=6, color=canvas.line(1)["color"],
                     label="braking (fed back)", zorder=2)
        rms = outcome.value("motor_torque_rms")
        left.axhline(rms, color="0.3", ls=":", lw=1.0, label=f"RMS {rms:.3g} N·m")
        left.axhline(-rms, color="0.3", ls=":", lw=1.0)
        if run.chosen is not None:
            motor = run.chosen.motor
            top = motor.top_speed * RAD_PER_S_TO_RPM
            w = np.linspace(0.0, motor.top_speed, 200)
            envelope = motor.envelope(w)
            for sign in (1.0, -1.0):
                for direction in (1.0, -1.0):
                    left.plot(direction * w * RAD_PER_S_TO_RPM, sign * envelope, color="k",
                              lw=1.4, label=f"{motor.name}: peak envelope"
                              if sign > 0 and direction > 0 else None)
                    left.plot([direction * top] * 2, [0.0, sign * envelope[-1]], color="k",
                              lw=1.4)
                left.axhline(sign * motor.rated_torque, color="k", ls="--", lw=1.0,
                             label=f"rated {motor.rated_torque:g} N·m" if sign > 0 else None)
        left.axhline(0.0, color="0.5", lw=0.6)
        left.axvline(0.0, color="0.5", lw=0.6)
        left.set_xlabel("motor speed [rpm]")
        left.set_ylabel("motor torque [N·m]")
        ratio = outcome.value("ratio")
        left.set_title(f"Torque–speed over the cycle (i = {ratio:.4g})", fontsize="medium")
        left.legend(fontsize="small", loc="best")
        unit = outcome.units["s"]
        t = columns["t"]
        boundaries = _boundaries(run)
        axes = []
        for k, (name, label, per) in enumerate(PROFILE):
            ax = fig.add_subplot(right[k], sharex=axes[0] if axes else None)
            values = columns[name]
            factor, shown = (1000.0, "mm") if unit.startswith("m") else (180.0 / np.pi, "°")
            ax.plot(t, values * factor, **canvas.line(k))
            ax.set_ylabel(f"{label} [{shown}{per}]")
            for x in boundaries:
                ax.axvline(x, color="0.6", lw=0.7, ls="--")
            if k < 3:
                ax.tick_params(labelbottom=False)
            axes.append(ax)
        axes[0].set_title(f"Profile of {outcome.meta.get('output')} (segments dashed)",
                          fontsize="medium")
        axes[-1].set_xlabel("time [s]")
    return fig


def _boundaries(run) -> list[float]:
    """The instants of the segments' boundaries inside the cycle [s]."""
    profile = run.mechanism.servo.profile
    period = run.cycle.period
    scale = period / profile.period
    return [(segment.start - profile.start) * scale for segment in profile.segments[1:]]
