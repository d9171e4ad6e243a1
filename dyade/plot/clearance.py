"""The clearance peak force (Dresig & Thümmel): f(τ) with the operating points, the peak
force against crank speed, and the simulated force history next to the closed form.

Panels, left to right: f(τ) of eq. (36) on logarithmic axes with the soft-impact range
τ < 2 shaded and every reversal (or the standalone case) placed at its τ; with a speed
range, the peak force F12max against the crank speed (the largest of each joint's
reversals, or the standalone case with its clearance share 6·c·s/τ); with a simulation,
the contact force of the two-mass model over time next to eq. (26) and the rigid ramp.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

from typing import NamedTuple

import numpy as np
from matplotlib.figure import Figure

from dyade import clearance as engine
from dyade.plot import canvas

PANEL = (3.6, 3.3)  # [in] one panel


class Case(NamedTuple):
    """One reversal (or a standalone case) and its closed-form peak."""

    label: str
    peak: engine.Peak


class History(NamedTuple):
    """A simulated reversal: the case and the simulation with ``history=True``."""

    case: Case
    simulation: engine.Simulation


def cases(checks) -> list[Case]:
    """Every reversal of a mechanism's clearance check (``dyade.check_clearance``),
    labelled as ``dyade clearance`` numbers them: "(5,6) #1"."""
    return [Case(f"({c.joint[0]},{c.joint[1]}) #{k}", rev.peak)
            for c in checks for k, rev in enumerate(c.reversals, 1)]


def speed_lines(study) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """From ``dyade.clearance_speed_study``: per joint, the speeds [rpm] and the largest
    peak force of its reversals at each [N] (NaN where it has none)."""
    joints = {check.joint: None for _, checks in study for check in checks if check.applies}
    out = {}
    for joint in joints:
        peaks = [max((r.peak.force for c in checks if c.joint == joint for r in c.reversals),
                     default=np.nan) for _, checks in study]
        out[f"({joint[0]},{joint[1]})"] = (np.array([rpm for rpm, _ in study]), np.array(peaks))
    return out


def standalone_speeds(peaks) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """From ``dyade.clearance.peaks_over_speed``: the peak and its clearance share."""
    rpm = np.array([speed for speed, _ in peaks])
    return {"F12max, eq. (27)": (rpm, np.array([p.force for _, p in peaks])),
            "clearance share 6·c·s/τ": (rpm, np.array([p.clearance_share for _, p in peaks]))}


def figure(points: list[Case], *, speeds: dict | None = None, history: History | None = None,
           fig: Figure | None = None, title: str = "Clearance peak force") -> Figure:
    """f(τ) with the cases, and optionally the peaks over speed and a force history.

    Parameters
    ----------
    points : list of Case
        The operating points on f(τ) (``cases`` of a check, or one standalone case).
    speeds : dict, optional
        label -> (speeds [rpm], peak forces [N]) (``speed_lines``, ``standalone_speeds``).
    history : History, optional
        A simulated reversal to draw against the closed form.
    fig : Figure, optional
        A figure to draw on (default: a new one).
    title : str
        The figure's title.

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot import clearance as plot
    >>> peak = dyade.peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5)
    >>> fig = plot.figure([plot.Case("paper, section 4", peak)])
    >>> fig.axes[0].get_lines()[1].get_xydata().round(4).tolist()    # τ, f(τ)
    [[3.0285, 4.3638]]
    """
    count = 1 + (speeds is not None) + (history is not None)
    with canvas.style():
        fig = canvas.new(PANEL[0] * count, PANEL[1] + 0.4, fig)
        axes = list(fig.subplots(1, count, squeeze=False).ravel())
        _f_of_tau(axes.pop(0), points)
        if speeds is not None:
            _over_speed(axes.pop(0), speeds)
        if history is not None:
            _history(axes.pop(0), history)
        fig.suptitle(f"{title} (Dresig & Thümmel)")
    return fig


def _f_of_tau(ax, points: list[Case]) -> None:
    taus = np.array([case.peak.tau for case in points]) if points else np.array([2.0])
    low = min(0.1, 0.5 * float(taus.min()))
    high = max(100.0, 2.0 * float(taus.max()))
    tau = np.geomspace(low, high, 400)
    ax.plot(tau, engine.f_of_tau(tau), gid="f_tau", label="f(τ), eq. (36)", **canvas.line(0))
    ax.axvspan(low, 2.0, facecolor="0.9", edgecolor=canvas.GREY, hatch="////", linewidth=0.0,
               zorder=0, label="τ < 2: soft impact")
    groups: dict[str, list[Case]] = {}
    for case in points:  # the reversals of one joint share a marker
        groups.setdefault(case.label.split(" #")[0], []).append(case)
    for k, (name, group) in enumerate(groups.items()):
        forces = ", ".join(f"{case.peak.force:.4g}" for case in group)
        ax.plot([c.peak.tau for c in group], [c.peak.f_tau for c in group], linestyle="none",
                marker=canvas.MARKERS[k % len(canvas.MARKERS)], markersize=5,
                markerfacecolor=canvas.COLOURS[(k + 1) % len(canvas.COLOURS)],
                markeredgecolor="black", zorder=5, gid=f"cases-{name}",
                label=f"{name}: {forces} N")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(low, high)
    ax.set_xlabel("τ = ω·t1 [-]")
    ax.set_ylabel("f(τ) = F12max/(c·s) [-]")
    ax.legend(loc="upper right", fontsize=6.0 if len(groups) > 4 else None,
              ncols=2 if len(groups) > 8 else 1)


def _over_speed(ax, speeds: dict) -> None:
    for k, (label, (rpm, force)) in enumerate(speeds.items()):
        ax.plot(rpm, force, label=label, gid=f"speed-{label}",
                **canvas.line(k, marker=True, markevery=1))
    ax.set_xlabel("crank speed [rpm]")
    ax.set_ylabel("peak force F12max [N]")
    ax.set_ylim(bottom=0.0)
    ax.legend(loc="upper left", fontsize=6.0 if len(speeds) > 4 else None,
              ncols=2 if len(speeds) > 6 else 1)


def _history(ax, history: History) -> None:
    case, sim = history
    peak = case.peak
    time = sim.time
    ax.plot(1e3 * time, sim.contact_force, gid="simulated",
            label=f"simulated (RK4, {sim.steps} steps)", **canvas.line(0))
    fine = np.linspace(0.0, float(time[-1]), 2000)
    ax.plot(1e3 * fine, engine.contact_force(peak, fine), gid="closed-form",
            label="closed form, eq. (26)", **canvas.line(1))
    ax.plot(1e3 * fine, peak.slope * fine, gid="rigid", label="rigid ramp F0/t0·t",
            **canvas.line(2))
    ax.plot([1e3 * peak.time_to_peak], [peak.force], linestyle="none", marker="D",
            markersize=5, markerfacecolor="white", markeredgecolor="black", zorder=5,
            gid="peak", label=f"F12max = {peak.force:.4g} N")
    ax.axvline(1e3 * peak.t1, color=canvas.GREY, linestyle=canvas.DASHES[2], linewidth=0.8,
               gid="impact")
    ax.annotate("impact t1", (1e3 * peak.t1, 0.0), xycoords=("data", "axes fraction"),
                xytext=(-2, 4), textcoords="offset points", ha="right", va="bottom",
                rotation=90, fontsize=6.5)
    contact = float(time[-1]) - peak.t1  # a long free flight would hide the contact
    ax.set_xlim(1e3 * max(0.0, peak.t1 - 2.0 * contact), 1e3 * float(time[-1]))
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("time from the reversal [ms]")
    ax.set_ylabel("joint force [N]")
    ax.set_title(case.label + (f": the masses separate at {1e3 * sim.separation_time:.3g} ms"
                               if sim.separates else ": contact holds"), fontsize=7.5)
    ax.legend(loc="upper left")
