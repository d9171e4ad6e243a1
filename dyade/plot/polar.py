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
from dyade.linkage.joint_clearance import MAX_WANDER_DEG, NO_FORCE, force_lines
from dyade.linkage.options import radians
from dyade.plot import canvas
from dyade.plot.labels import Placer, leader, merge

MARK_EVERY = 30.0  # [°] crank-angle marks along the curve
PANEL = 3.3  # [in] width and height of one panel
LEFT, RIGHT, ABOVE, BELOW = 0.78, 0.12, 0.45, 0.45  # [in] a panel's margins around its axes
TOP = 0.4  # [in] the figure's title
EQUAL = 0.5  # [-] equal axes only where the shorter range is at least this share of the longer
MARGIN = 0.1  # [-] space around the curve, share of its range
SAME_SPOT = 4.0  # [pt] crank-angle marks closer than this share one label
MARK_SIZE, NUMBER_SIZE = 6.5, 8.0  # [pt] font sizes of the angle marks and reversal numbers


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
                         "masses, loads or springs (add mass data, see `dyade help mechanism-file`).")
    lines = force_lines(result, joints, max_wander=radians(max_wander_deg, "max_wander_deg"))
    cols = result.columns()
    rows, columns = canvas.grid(len(lines))
    with canvas.style():  # margins by hand: the labels are placed in the final panels
        width, height = PANEL * columns, PANEL * rows + TOP
        fig = canvas.new(width, height, fig, layout=None)
        box = PANEL - LEFT - RIGHT, PANEL - ABOVE - BELOW  # [in] one axes
        axes = fig.subplots(rows, columns, squeeze=False, gridspec_kw={
            "left": LEFT / width, "right": 1 - RIGHT / width, "bottom": BELOW / height,
            "top": 1 - (TOP + ABOVE) / height, "wspace": (LEFT + RIGHT) / box[0],
            "hspace": (ABOVE + BELOW) / box[1]}).ravel()
        for ax in axes[len(lines):]:
            ax.set_visible(False)
        drawn = [_panel(ax, result, cols, line) for ax, line in zip(axes, lines)]
        fig.suptitle(f"{result.mechanism.name}: joint forces over the crank cycle",
                     y=1 - 0.12 / height, va="top")
        for ax, (curve, marked, line) in zip(axes, drawn):
            _labels(ax, curve, marked, line)
    return fig


def _panel(ax, result, cols, line):
    """The curve, its crank-angle marks and reversal markers, scaled; returns what
    ``_labels`` needs once the layout is final."""
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
    if line.applies:
        ax.axline((0.0, 0.0), (np.cos(line.line_angle), np.sin(line.line_angle)),
                  color=canvas.COLOURS[2], linestyle=canvas.DASHES[1], linewidth=0.9, zorder=2,
                  gid=f"line-of-action-{a}-{b}")
        forces = line.reversal_forces
        ax.plot(forces[:, 0], forces[:, 1], linestyle="none", marker="D", markersize=5.0,
                markerfacecolor="white", markeredgecolor=canvas.COLOURS[1], zorder=6,
                gid=f"reversals-{a}-{b}")
    gaps = int(np.count_nonzero(~(np.isfinite(fx) & np.isfinite(fy))))
    status = status_line(line) + (f"; gaps at {gaps} positions" if gaps else "")
    scale(ax, fx, fy)
    ax.set_title(f"joint ({a},{b}): force on link {b}\n{status}", fontsize=7.5)
    ax.set_xlabel(f"Fx_{a}_{b} [N]")
    ax.set_ylabel(f"Fy_{a}_{b} [N]")
    curve = np.stack([fx, fy], axis=1)
    return curve, (wanted[shown], np.stack([mx[shown], my[shown]], axis=1)), line


def scale(ax, fx: np.ndarray, fy: np.ndarray) -> bool:
    """Limits around the curve and the origin; equal axes (a force's direction true to
    the eye) unless they would leave more than half of the panel empty. Returns whether
    the axes are equal."""
    given = np.isfinite(fx) & np.isfinite(fy)
    if not given.any():
        return False
    low = np.minimum([fx[given].min(), fy[given].min()], 0.0)
    high = np.maximum([fx[given].max(), fy[given].max()], 0.0)
    span = np.maximum(high - low, 1e-9 * max(float(np.max(high - low)), 1e-12))
    if span.min() >= EQUAL * span.max():
        ax.update_datalim([(0.0, 0.0)])  # the origin in view: the force's length true
        ax.margins(MARGIN)
        ax.set_aspect("equal", adjustable="datalim")
        return True
    centre, half = 0.5 * (low + high), 0.5 * span * (1.0 + 2.0 * MARGIN)
    ax.set_xlim(centre[0] - half[0], centre[0] + half[0])
    ax.set_ylim(centre[1] - half[1], centre[1] + half[1])
    return False


def _labels(ax, curve: np.ndarray, marked, line) -> None:
    """The reversal numbers and the crank-angle marks, off the curve and apart (the
    axes in their final place)."""
    places = Placer(ax, curve)
    angles, at = marked
    places.avoid(at)
    a, b = line.joint
    if line.applies:
        forces = line.reversal_forces
        places.avoid(forces)
        for number, xy in enumerate(forces, 1):
            offset = places.place(xy, str(number), NUMBER_SIZE, "bold",
                                  first=np.deg2rad(45.0 + 90.0 * (number - 1)))
            ax.annotate(str(number), xy, xytext=offset, textcoords="offset points",
                        ha="center", va="center", fontsize=NUMBER_SIZE, fontweight="bold",
                        color=canvas.COLOURS[1], zorder=7, gid=f"reversal-number-{a}-{b}",
                        arrowprops={"arrowstyle": "-", "color": canvas.COLOURS[1],
                                    "linewidth": 0.6, "shrinkA": 0, "shrinkB": 2})
    # marks on one spot share a label; the quarter turns placed first
    spots = places.display(at)
    groups: list[list[int]] = []
    for k in range(len(angles)):
        for group in groups:
            if np.hypot(*(spots[group[0]] - spots[k])) * 72.0 / ax.figure.dpi < SAME_SPOT:
                group.append(k)
                break
        else:
            groups.append([k])
    first = sorted(groups, key=lambda g: not any(angles[k] % 90.0 == 0 for k in g))
    centre = np.nanmean(curve, axis=0) if np.isfinite(curve).any() else np.zeros(2)
    offsets = {}
    for group in first:  # the quarter turns take their places first
        outward = places.display(at[group[0]])[0] - places.display(centre)[0]
        offsets[group[0]] = places.place(at[group[0]], _text(angles, group), MARK_SIZE,
                                         first=float(np.arctan2(outward[1], outward[0])))
    for group in groups:  # drawn in crank-angle order
        offset = offsets[group[0]]
        ax.annotate(_text(angles, group), at[group[0]], xytext=offset,
                    textcoords="offset points", ha="center", va="center", fontsize=MARK_SIZE,
                    color="0.25", zorder=5, gid=f"crank-angle-{a}-{b}",
                    arrowprops=leader(offset))


def _text(angles: np.ndarray, group: list[int]) -> str:
    return merge([float(angles[k]) for k in group], MARK_EVERY)


def status_line(line) -> str:
    """What the panel says of the line of action, short."""
    if np.isnan(line.line_angle):
        return "no force" if line.reason == NO_FORCE else "force not given"
    if not line.applies:
        return f"no reversals: the force turns {np.rad2deg(line.wander):.0f}° off its line"
    direction = f"line of action {np.rad2deg(line.line_angle):.0f}°"
    if not len(line.reversal_angles):
        return f"one sense, {direction}"
    found = ", ".join(f"{k} at {np.rad2deg(a) % 360:.1f}°"
                      for k, a in enumerate(line.reversal_angles, 1))
    return f"reversals {found} ({direction})"
