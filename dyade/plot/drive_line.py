"""The elastic drive line (``dyade.linkage.drive_line``): the resonance curve, the
stability chart (unstable speeds shaded) or map, the shaft torque over the cycle against
the rigid drive's, and the run-up."""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.machine.drive_line import UNSTABLE_MARGIN
from dyade.plot import canvas
from dyade.units import RAD_PER_S_TO_RPM

UNSTABLE = dict(facecolor="0.80", edgecolor="0.45", hatch="////", linewidth=0.0, alpha=0.7,
                zorder=0)


def _shade_unstable(ax, speed_rpm, unstable, label: bool = True) -> None:
    """Shade each run of unstable speeds, half a step beyond its ends."""
    half = 0.5 * float(np.min(np.diff(speed_rpm))) if speed_rpm.size > 1 else 0.5
    first = None
    for k, bad in enumerate(list(unstable) + [False]):
        if bad and first is None:
            first = k
        if not bad and first is not None:
            ax.axvspan(speed_rpm[first] - half, speed_rpm[k - 1] + half,
                       label="unstable (|μ| > 1)" if label else None, **UNSTABLE)
            label, first = False, None


def _resonance_marks(ax, curve, label: bool = True) -> None:
    """Forced resonances Ω = ω̄/k dotted, parametric Ω = 2ω̄/k dashed; the labels turned
    upright along the lines, so that close ones stay legible."""
    for k, speed, kind in curve.resonances:
        speed_rpm = speed * RAD_PER_S_TO_RPM
        ax.axvline(speed_rpm, color="0.5", linestyle=":" if kind == "forced" else "--",
                   linewidth=0.8, zorder=1)
        if label:
            ax.annotate(f"{'ω̄' if kind == 'forced' else '2ω̄'}/{k}", (speed_rpm, 0.98),
                        xycoords=("data", "axes fraction"), fontsize=6, ha="right",
                        va="top", rotation=90, color="0.35")


def resonance(curve, fig: Figure | None = None) -> Figure:
    """Peak shaft torque (with the rigid drive's), twist amplitude and speed fluctuation
    against the crank speed, the expected resonances Ω = ω̄/k (dotted) and parametric
    ones Ω = 2ω̄/k (dashed) marked, unstable speeds shaded.

    Parameters
    ----------
    curve : ResonanceCurve
        ``dyade.linkage.drive_line.resonance_curve(...)``.
    fig : Figure, optional
    """
    first = curve.solution == 1  # the first solution at each speed: one line
    speed = curve.speed[first] * RAD_PER_S_TO_RPM
    with canvas.style():
        fig = canvas.new(7.0, 6.4, fig)
        axes = fig.subplots(3, 1, sharex=True)
        ax = axes[0]
        ax.plot(speed, curve.peak_torque[first], label="drive line", **canvas.line(0))
        ax.plot(speed, curve.rigid_peak_torque[first], label="rigid drive", **canvas.line(1))
        ax.set_ylabel("peak shaft torque [N·m]")
        axes[1].plot(speed, np.degrees(curve.twist_amplitude[first]), **canvas.line(0))
        axes[1].set_ylabel("twist amplitude [°]")
        axes[2].plot(speed, curve.fluctuation[first], **canvas.line(0))
        axes[2].set_ylabel("speed fluctuation δ [-]")
        axes[2].set_xlabel("crank speed Ω [rpm]")
        for k, axis in enumerate(axes):
            _shade_unstable(axis, speed, curve.unstable[first], label=k == 0)
            _resonance_marks(axis, curve) if k == 0 else None
            axis.set_xlim(speed[0], speed[-1])
        top = axes[0].secondary_xaxis("top", functions=(
            lambda s: s / RAD_PER_S_TO_RPM / curve.omega_bar,
            lambda e: e * curve.omega_bar * RAD_PER_S_TO_RPM))
        top.set_xlabel("η = Ω/ω̄")
        ax.legend(loc="upper left", fontsize=8)
        fig.suptitle(f"Resonance curve of the drive line "
                     f"(ω̄ = {curve.omega_bar * RAD_PER_S_TO_RPM:.5g} rpm)")
    return fig


def branches(ax, curve) -> None:
    """The largest twist over the period against speed along the followed branches,
    stable solid, unstable dashed, the folds (jump speeds) marked; the solutions at the
    scan's speeds as dots (a cross where not converged: no verdict), the period-2
    motions (``--period-two``) as diamonds, filled where stable."""
    labelled = set()
    styles = {False: ("stable branch", dict(linestyle="-", color="C0", linewidth=1.4)),
              True: ("unstable branch", dict(linestyle="--", color="C3", linewidth=1.2))}

    def draw(xs, ys, bad):
        label, style = styles[bool(bad)]
        ax.plot(xs, ys, label=None if label in labelled else label, **style)
        labelled.add(label)

    for speed, twist, unstable, _, modulus in curve.branches:
        rpm = speed * RAD_PER_S_TO_RPM
        deg = np.degrees(twist)
        for i in range(rpm.size - 1):  # a segment changing stability: split where |μ| = 1
            if unstable[i] == unstable[i + 1]:
                draw(rpm[i:i + 2], deg[i:i + 2], unstable[i])
                continue
            edge = 1.0 + UNSTABLE_MARGIN
            f = (edge - modulus[i]) / (modulus[i + 1] - modulus[i])
            x = rpm[i] + f * (rpm[i + 1] - rpm[i])
            y = deg[i] + f * (deg[i + 1] - deg[i])
            draw([rpm[i], x], [deg[i], y], unstable[i])
            draw([x, rpm[i + 1]], [y, deg[i + 1]], unstable[i + 1])
    ok = curve.converged
    speed = curve.speed * RAD_PER_S_TO_RPM
    ax.plot(speed[ok], np.degrees(curve.twist_max[ok]), "o", color="k", markersize=2.0,
            label="solutions at the speeds asked")
    if (~ok).any():  # on the axis's foot: they have no value
        ax.plot(speed[~ok], np.full(int((~ok).sum()), 0.02), "x", color="C1", markersize=5,
                transform=ax.get_xaxis_transform(), clip_on=False,
                label="not converged (no verdict)")
    two = _period_two(curve)
    if two is not None:
        found = two.found
        stable = found & ~(two.stability > 1.0 + UNSTABLE_MARGIN)
        x, y = two.speed * RAD_PER_S_TO_RPM, np.degrees(two.twist_max)
        for which, words, face in ((stable, "stable", "C4"), (found & ~stable, "unstable",
                                                               "none")):
            if which.any():
                ax.plot(x[which], y[which], "D", color="C4", markerfacecolor=face,
                        markersize=4.0, label=f"period-2 motion, {words}")
    for fold, upper in curve.folds:
        ax.axvline(fold * RAD_PER_S_TO_RPM, color="0.4", linewidth=0.8, linestyle=":")
        ax.annotate("jump ↑ sweep" if upper else "jump ↓ sweep", (fold * RAD_PER_S_TO_RPM,
                                                                   0.02),
                    xycoords=("data", "axes fraction"), rotation=90, fontsize=7,
                    ha="right", va="bottom", color="0.3")
    ax.set_ylabel("largest twist [°]")


def _period_two(curve):
    """The scan's period-2 motions where it has found any (``--period-two``), else
    None."""
    two = getattr(curve, "period_two", None)
    return two if two is not None and two.found.any() else None


def stability(curve, fig: Figure | None = None) -> Figure:
    """The largest twist over the period along the followed branches (stable solid,
    unstable dashed, folds marked) and the largest \\|Floquet multiplier\\| of every
    solution against the crank speed, 1 marked, unstable speeds shaded.

    Parameters
    ----------
    curve : ResonanceCurve
        From ``dyade.linkage.drive_line.resonance_curve``.
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import dyade
    >>> from dyade.linkage import drive_line
    >>> from dyade.plot import drive_line as figures
    >>> line = dyade.read_mechanism("mechanisms/dyade-16.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    >>> curve = drive_line.resonance_curve(line, [3450.0, 3575.0, 3700.0], follow=False)
    >>> figures.stability(curve).axes[-1].get_xlabel()
    'crank speed Ω [rpm]'
    """
    speed = curve.speed * RAD_PER_S_TO_RPM
    first = curve.solution == 1
    with canvas.style():
        fig = canvas.new(7.0, 6.0, fig)
        axes = fig.subplots(2, 1, sharex=True)
        branches(axes[0], curve)
        ax = axes[1]
        ok = curve.converged
        ax.plot(speed[first & ok], curve.stability[first & ok], label="largest |μ|",
                **canvas.line(0, marker=True))
        more = ~first & ok
        if more.any():
            ax.plot(speed[more], curve.stability[more], "s", color="C2", markersize=3,
                    label="largest |μ|, further solutions")
        two = _period_two(curve)
        if two is not None:
            ax.plot(two.speed[two.found] * RAD_PER_S_TO_RPM, two.stability[two.found], "D",
                    color="C4", markersize=4.0, label="largest |μ| over two revolutions, "
                                                      "period-2 motion")
        ax.axhline(1.0, color="0.3", linewidth=0.8)
        _shade_unstable(ax, speed[first], curve.unstable[first])
        _resonance_marks(ax, curve)
        ax.set_xlim(speed.min(), speed.max())
        ax.set_xlabel("crank speed Ω [rpm]")
        ax.set_ylabel("largest |Floquet multiplier| [-]")
        canvas.legend_above(axes[0], most=3, fontsize=7)
        ax.legend(loc="best", fontsize=7)
        fig.suptitle("Periodic solutions and their stability (linearised about each)")
    return fig


def stability_map(result, fig: Figure | None = None) -> Figure:
    """The largest |Floquet multiplier| over speed × stiffness or damping, the unstable
    cells hatched, the contour |μ| = 1 of the cells drawn and the traced boundary points
    (``StabilityMap.edges``: a multiplier at −1 or +1, solved between the cells) marked."""
    speed = result.speed * RAD_PER_S_TO_RPM
    unit = "N·m/rad" if result.parameter == "stiffness" else "N·m·s/rad"
    with canvas.style():
        fig = canvas.new(7.0, 4.6, fig)
        ax = fig.subplots()
        values = np.where(np.isfinite(result.stability), result.stability, np.nan)
        mesh = ax.pcolormesh(speed, result.values, values, shading="nearest", cmap="Greys",
                             vmin=np.nanmin(values), vmax=max(np.nanmax(values), 1.0))
        if result.unstable.any() and (~result.unstable).any() and min(values.shape) > 1:
            # |μ| = 1 up to the margin: an undamped line's stable multipliers lie on the
            # unit circle, and their round-off must not draw a boundary
            ax.contour(speed, result.values, values, levels=[1.0 + UNSTABLE_MARGIN],
                       colors="k", linewidths=1.0)
        ax.contourf(speed, result.values, result.unstable.astype(float), levels=[0.5, 1.5],
                    hatches=["////"], colors="none")
        edges = getattr(result, "edges", None)
        if edges is not None and edges.speed.size:
            for n, kind in enumerate(sorted(set(edges.kind))):
                pick = np.array([k == kind for k in edges.kind])
                sigma = "−1" if kind == "period doubling" else "+1"
                ax.plot(edges.speed[pick] * RAD_PER_S_TO_RPM, edges.values[pick],
                        linestyle="none", marker="o" if n == 0 else "s", markersize=5,
                        markerfacecolor="white", markeredgecolor=f"C{n + 1}",
                        label=f"traced boundary (μ = {sigma}, {kind})")
            ax.legend(loc="upper right", fontsize=7)
        fig.colorbar(mesh, ax=ax, label="largest |μ| [-]")
        ax.set_xlabel("crank speed Ω [rpm]")
        ax.set_ylabel(f"{result.parameter} [{unit}]")
        fig.suptitle(f"Stability map over speed × {result.parameter} (hatched: unstable)")
    return fig


def steady(state, fig: Figure | None = None) -> Figure:
    """Shaft torque, crank speed and twist over one revolution, next to the rigid
    drive's torque and speed.

    Parameters
    ----------
    state : SteadyState
        From ``dyade.linkage.drive_line.steady_state``.
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import dyade
    >>> from dyade.linkage import drive_line
    >>> from dyade.plot import drive_line as figures
    >>> line = dyade.read_mechanism("mechanisms/dyade-16.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    >>> fig = figures.steady(drive_line.steady_state(line))
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['shaft torque [N·m]', 'crank speed [rpm]', 'twist [°]']
    """
    angle = np.degrees(state.crank_angle)
    with canvas.style():
        fig = canvas.new(7.0, 6.0, fig)
        axes = fig.subplots(3, 1, sharex=True)
        axes[0].plot(angle, state.shaft_torque, label="drive line", **canvas.line(0))
        axes[0].plot(angle, state.rigid_torque, label="rigid drive", **canvas.line(1))
        axes[0].set_ylabel("shaft torque [N·m]")
        canvas.legend_above(axes[0], fontsize=8)
        axes[1].plot(angle, state.crank_speed * RAD_PER_S_TO_RPM, **canvas.line(0))
        axes[1].plot(angle, state.rigid_speed * RAD_PER_S_TO_RPM, **canvas.line(1))
        axes[1].set_ylabel("crank speed [rpm]")
        axes[2].plot(angle, np.degrees(state.twist), **canvas.line(0))
        axes[2].set_ylabel("twist [°]")
        axes[2].set_xlabel("crank angle φ21 [°]")
        axes[2].set_xlim(angle[0], angle[-1])
        f = state.figures
        fig.suptitle(f"Steady state at {f['speed_mean'] * RAD_PER_S_TO_RPM:.5g} rpm, "
                     f"η = {f['eta']:.3g}, largest |μ| = {f['stability']:.4g}")
    return fig


def run_up(run, fig: Figure | None = None) -> Figure:
    """Crank and motor speed and the shaft torque against time, the largest torque
    marked."""
    with canvas.style():
        fig = canvas.new(7.0, 5.0, fig)
        axes = fig.subplots(2, 1, sharex=True)
        axes[0].plot(run.time, run.crank_speed * RAD_PER_S_TO_RPM, label="crank",
                     **canvas.line(0))
        axes[0].plot(run.time, run.motor_speed * RAD_PER_S_TO_RPM, label="motor (reduced)",
                     **canvas.line(1))
        axes[0].set_ylabel("speed [rpm]")
        canvas.legend_above(axes[0], fontsize=8)
        axes[1].plot(run.time, run.shaft_torque, **canvas.line(0))
        f = run.figures
        axes[1].plot([f["peak_time"]], [f["peak_torque"]], "o", color="k", markersize=4)
        axes[1].annotate(f"{f['peak_torque']:.4g} N·m at "
                         f"{f['peak_speed'] * RAD_PER_S_TO_RPM:.4g} rpm",
                         (f["peak_time"], f["peak_torque"]), textcoords="offset points",
                         xytext=(6, 0), fontsize=8, va="center")
        axes[1].set_ylabel("shaft torque [N·m]")
        axes[1].set_xlabel("time [s]")
        axes[1].set_xlim(run.time[0], run.time[-1])
        fig.suptitle("Run-up from rest")
    return fig
