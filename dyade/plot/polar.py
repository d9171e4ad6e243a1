"""Joint-force polar diagrams: Fy against Fx over the crank cycle, one panel per joint.

The picture designers read first (Dresig & Thümmel, Bild 1): which joints keep one line of
action and where the force reverses its sense. Each panel shows the force on the
higher-numbered link (the CSV's sign rule) with equal axes, the crank angle marked every
30°, the dominant line of action and its sense reversals numbered as ``dyade clearance``
numbers them (``dyade.linkage.joint_clearance.force_lines``: the same computation), and
gaps where the forces are not given.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.errors import InputError
from dyade.linkage.joint_clearance import MAX_WANDER_DEG, force_lines
from dyade.linkage.options import radians
from dyade.plot import canvas

MARK_EVERY = 30.0  # [°] crank-angle marks along the curve
PANEL = 3.3  # [in] width and height of one panel


def marks(result) -> tuple[np.ndarray, np.ndarray]:
    """The crank angles [°] to mark (multiples of 30° within the sweep, a full turn's end
    left out), and the computed positions' crank angles [°]."""
    angle = np.rad2deg(result.crank_angle)
    first = np.ceil(angle[0] / MARK_EVERY - 1e-9) * MARK_EVERY
    wanted = np.arange(first, angle[-1] + 1e-9, MARK_EVERY)
    wanted = wanted[wanted - angle[0] < 360.0 - 1e-9]
    return wanted, angle


def _at(angle: np.ndarray, values: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    """values [n] at the angles ``wanted``: exact on grid points, else linear between two
    given neighbours (NaN next to a gap)."""
    index = np.clip(np.searchsorted(angle, wanted), 0, angle.size - 1)
    exact = np.isclose(angle[index], wanted, rtol=0.0, atol=1e-9)
    lower = np.clip(index - 1, 0, angle.size - 1)
    span = angle[index] - angle[lower]
    with np.errstate(invalid="ignore", divide="ignore"):  # equal neighbours: exact anyway
        share = np.where(span > 0, (wanted - angle[lower]) / span, 0.0)
    between = values[lower] + share * (values[index] - values[lower])
    return np.where(exact, values[index], between)


def figure(result, joints=None, *, max_wander_deg: float = MAX_WANDER_DEG,
           fig: Figure | None = None, **renamed) -> Figure:
    """Polar diagrams of revolute joints' forces.

    Parameters
    ----------
    result : Result
        An analysis with joint forces (``dyade.analyse``).
    joints : iterable of (int, int), optional
        The revolute joints, one panel each (default: every revolute joint).
    max_wander_deg : float
        How far [°] a force may leave its line of action for reversals to be given
        (as ``dyade clearance --max-wander``).
    fig : Figure, optional
        A figure to draw on (default: a new one).
    **renamed
        The former ``max_wander`` [rad] is refused with an ``InputError`` naming
        ``max_wander_deg``.

    Examples
    --------
    Two joints of the 16-link drive, one with two reversals, one whose force turns
    around its bearing:

    >>> import dyade
    >>> from dyade.plot import polar
    >>> drive = dyade.read_mechanism("mechanisms/dyade-16.toml")
    >>> fig = polar.figure(dyade.analyse(drive), [(5, 6), (1, 2)])
    >>> for ax in fig.axes[:2]:
    ...     print(ax.get_title())
    joint (5,6): force on link 6
    reversals 1 at 104.4°, 2 at 329.2° (line of action 180°)
    joint (1,2): force on link 2
    no reversals: the force turns 87° off its line
    """
    InputError.refuse_renamed("polar.figure", renamed, {"max_wander": "max_wander_deg"})
    if result.forces is None:
        raise InputError("joint-force polar diagrams need joint forces: the mechanism has no "
                         "masses, loads or springs (add mass data, see mechanisms/README.md).")
    lines = force_lines(result, joints, max_wander=radians(max_wander_deg, "max_wander_deg"))
    cols = result.columns()
    rows, columns = canvas.grid(len(lines))
    with canvas.style():
        fig = canvas.new(PANEL * columns, PANEL * rows + 0.4, fig)
        axes = fig.subplots(rows, columns, squeeze=False).ravel()
        for ax in axes[len(lines):]:
            ax.set_visible(False)
        for ax, line in zip(axes, lines):
            _panel(ax, result, cols, line)
        fig.suptitle(f"{result.mechanism.name}: joint forces over the crank cycle")
    return fig


def _panel(ax, result, cols, line) -> None:
    a, b = line.joint
    fx = canvas.on_grid(result, cols[f"Fx_{a}_{b}"])
    fy = canvas.on_grid(result, cols[f"Fy_{a}_{b}"])
    ax.axhline(0.0, color=canvas.GREY, linewidth=0.6, zorder=1)
    ax.axvline(0.0, color=canvas.GREY, linewidth=0.6, zorder=1)
    ax.plot(fx, fy, **canvas.line(0), zorder=3, gid=f"force-{a}-{b}")
    wanted, angle = marks(result)
    mx, my = _at(angle, fx, wanted), _at(angle, fy, wanted)
    shown = np.isfinite(mx) & np.isfinite(my)
    ax.plot(mx[shown], my[shown], linestyle="none", marker="o", markersize=3.0,
            color="black", zorder=4, gid=f"crank-angles-{a}-{b}")
    for deg, x, y in zip(wanted[shown], mx[shown], my[shown]):
        ax.annotate(f"{deg % 360:.0f}°", (x, y), xytext=(3, 3), textcoords="offset points",
                    fontsize=6.5, color="0.25", zorder=5)
    if line.applies:
        ax.axline((0.0, 0.0), (np.cos(line.line_angle), np.sin(line.line_angle)),
                  color=canvas.COLOURS[2], linestyle=canvas.DASHES[1], linewidth=0.9, zorder=2,
                  gid=f"line-of-action-{a}-{b}")
        forces = line.reversal_forces
        ax.plot(forces[:, 0], forces[:, 1], linestyle="none", marker="D", markersize=5.0,
                markerfacecolor="white", markeredgecolor=canvas.COLOURS[1], zorder=6,
                gid=f"reversals-{a}-{b}")
        for number, (x, y) in enumerate(forces, 1):
            turn = np.deg2rad(45.0 + 90.0 * (number - 1))  # neighbours' labels apart
            ax.annotate(str(number), (x, y), xytext=(14 * np.cos(turn), 14 * np.sin(turn)),
                        textcoords="offset points", ha="center", va="center", fontsize=8.0,
                        fontweight="bold", color=canvas.COLOURS[1], zorder=7,
                        arrowprops={"arrowstyle": "-", "color": canvas.COLOURS[1],
                                    "linewidth": 0.6, "shrinkA": 0, "shrinkB": 2})
    gaps = int(np.count_nonzero(~(np.isfinite(fx) & np.isfinite(fy))))
    status = status_line(line) + (f"; gaps at {gaps} positions" if gaps else "")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(f"joint ({a},{b}): force on link {b}\n{status}", fontsize=7.5)
    ax.set_xlabel(f"Fx_{a}_{b} [N]")
    ax.set_ylabel(f"Fy_{a}_{b} [N]")


def status_line(line) -> str:
    """What the panel says of the line of action, short."""
    if np.isnan(line.line_angle):
        return "no force"
    if not line.applies:
        return f"no reversals: the force turns {np.rad2deg(line.wander):.0f}° off its line"
    direction = f"line of action {np.rad2deg(line.line_angle):.0f}°"
    if not len(line.reversal_angles):
        return f"one sense, {direction}"
    found = ", ".join(f"{k} at {np.rad2deg(a) % 360:.1f}°"
                      for k, a in enumerate(line.reversal_angles, 1))
    return f"reversals {found} ({direction})"
