"""Mode shapes of a gear drive, shaft by shaft (Berczyński, Maćkowiak and Marchelek 1978).

One row of panels per elastic mode (the first ``count``, rigid-body modes left out as the
API leaves them out), one panel per shaft line (the bodies that turn together, joined by
shafts or elements, as ``dyade.vibration.gears.campbell.shaft_lines`` groups them): the
bodies and the shafts' rigid elements at their axial position along the line's axis
against their modal displacements in each body's own axes — torsion, lateral uy and uz,
axial ux — each with its own line style and marker.

Normalisation (the y axis says it): torsion is drawn as ρ·rx, the rotation times the
body's radius of gyration ρ = √(J_x/m) about its axis, so that every curve is a
displacement [m] whose square weighs as kinetic energy (m·(ρ·rx)² = J_x·rx²); each mode
is divided by its largest entry over all bodies and motions, and signed so that this
entry is +1. In the torsional model (rx only) the rotation itself is normalised.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from dyade.model.gears import FRAME
from dyade.plot import canvas
from dyade.vibration.gears.campbell import shaft_lines

MOTIONS = (("rx", 3, "torsion ρ·rx"), ("uy", 1, "lateral uy"), ("uz", 2, "lateral uz"),
           ("ux", 0, "axial ux"))
"""drawn motion, its coordinate among (ux … rz), its label"""


@dataclass(frozen=True, slots=True)
class Line:
    """The bodies of one shaft line in the order of their axial position."""

    name: str
    bodies: tuple[int, ...]
    """indices into ``system.bodies``"""
    position: np.ndarray
    """(b,) along the line's axis [m]; 0, 1, 2 … without geometry"""
    measured: bool = True
    """False: the drive gives no positions (torsional model); ``position`` is the order"""


def shaft_groups(modes) -> list[Line]:
    """The drive's shaft lines with their bodies (the file's and the shafts' rigid
    elements), each sorted by the position along the axis of its first body."""
    system = modes.system
    drive = system.drive
    groups = shaft_lines(drive)
    where = {body: g for g, (_, members) in enumerate(groups) for body in members}
    shafts = {s.name: s for s in drive.shafts}
    members: list[list[int]] = [[] for _ in groups]
    for i, (body, owner) in enumerate(zip(system.bodies, system.owners)):
        name = body.name if not owner else next(e for e in shafts[owner].ends if e != FRAME)
        members[where[name]].append(i)
    out = []
    for (name, _), indices in zip(groups, members):
        axis = np.asarray(system.bodies[indices[0]].axis, dtype=float)
        position = np.array([np.asarray(system.bodies[i].position) @ axis for i in indices])
        if len(indices) > 1 and np.ptp(position) == 0.0:  # no geometry (torsional model)
            chain = _chain(system, indices)
            out.append(Line(name, tuple(chain), np.arange(len(chain), dtype=float), False))
            continue
        order = np.argsort(position, kind="stable")
        out.append(Line(name, tuple(indices[j] for j in order), position[order]))
    return out


def _chain(system, indices: list[int]) -> list[int]:
    """The bodies of a line without positions in the order the elements join them: from
    a body with one neighbour, depth first."""
    inside = set(indices)
    names = {system.bodies[i].name: i for i in indices}
    links: dict[int, list[int]] = {i: [] for i in indices}
    for element in system.elements:
        a, b = element.ends
        if a in names and b in names and names[a] != names[b]:
            links[names[a]].append(names[b])
            links[names[b]].append(names[a])
    start = next((i for i in indices if len(links[i]) <= 1), indices[0])
    order, todo = [], [start]
    while todo:
        i = todo.pop()
        if i in order:
            continue
        order.append(i)
        todo.extend(reversed([j for j in links[i] if j in inside and j not in order]))
    return order + [i for i in indices if i not in order]


def normalised(modes, k: int) -> dict[str, np.ndarray]:
    """Mode ``k`` (0-based) as drawn: motion ("rx", "uy", "uz", "ux") -> (bodies,) values
    over ``modes.system.bodies``, torsion as ρ·rx, divided by the largest entry (see the
    module's notes); only "rx" in the torsional model."""
    system = modes.system
    per = system.per_body
    shape = modes.shapes[:, k].reshape(-1, per)
    if per == 1:
        values = {"rx": shape[:, 0].copy()}
    else:
        mass = np.array([b.mass for b in system.bodies])
        radius = np.sqrt(np.array([b.inertia[0] for b in system.bodies]) / mass)
        values = {name: shape[:, column] * (radius if name == "rx" else 1.0)
                  for name, column, _ in MOTIONS}
    stacked = np.concatenate(list(values.values()))
    largest = stacked[np.argmax(np.abs(stacked))]
    return {name: v / largest for name, v in values.items()}


def figure(modes, count: int = 4, *, fig: Figure | None = None) -> Figure:
    """Shapes of the first ``count`` elastic modes of ``modes`` (``dyade.gear_modes``),
    per shaft line.

    Parameters
    ----------
    modes : Modes
    count : int
        Elastic modes to draw (fewer if the drive has fewer).
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import numpy as np, dyade
    >>> from dyade.plot import modes as plot
    >>> modes = dyade.gear_modes(dyade.read_gears("mechanisms/gears/two-stage.toml"))
    >>> fig = plot.figure(modes, 2)
    >>> rx = [l for l in fig.axes[0].get_lines() if l.get_gid() == "shape-1-input-rx"][0]
    >>> bool(np.max(np.abs(rx.get_ydata())) <= 1.0)
    True
    """
    from dyade.errors import InputError

    if count < 1:
        raise InputError.parameter("count", f"must be 1 or more, got {count}.", value=count)
    count = min(count, modes.frequencies.size)
    lines = shaft_groups(modes)
    system = modes.system
    motions = MOTIONS if system.per_body == 6 else MOTIONS[:1]
    dominant = modes.dominant()
    with canvas.style():
        fig = canvas.new(max(3.2, 2.6 * len(lines)) + 0.6, 1.75 * count + 0.9, fig)
        rows = fig.subfigures(count, 1) if count > 1 else [fig.subfigures(1, 1)]
        for k, row in enumerate(rows):
            values = normalised(modes, k)
            axes = np.atleast_1d(row.subplots(1, len(lines), sharey=True))
            for ax, line in zip(axes, lines):
                for m, (name, _, label) in enumerate(motions):
                    ax.plot(line.position * (1e3 if line.measured else 1.0),
                            values[name][list(line.bodies)],
                            label=label if system.per_body == 6 else "torsion rx", gid=f"shape-{k + 1}-{line.name}-{name}",
                            **canvas.line(m, True, markevery=1, markersize=3.2))
                ax.axhline(0.0, color="0.4", linewidth=0.6, zorder=0)
                ax.set_ylim(-1.12, 1.12)
                ax.set_title(line.name, fontsize=8)
                _body_ticks(ax, system, line, last=k == count - 1)
            axes[0].set_ylabel("normalised [-]")
            owner, motion, share = dominant[k]
            f = modes.frequencies[k]
            frequency = f"{f:.5g} Hz" if np.isfinite(f) else "below the resolution"
            part = f"; dominant: {owner} {motion} {share:.0%} of the strain energy" if owner else ""
            row.suptitle(f"mode {k + 1}: {frequency}{part}", fontsize=8.5, ha="left", x=0.01)
        handles, labels = rows[0].axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncols=len(motions))
        fig.suptitle(f"{system.drive.name}: mode shapes per shaft line\n(each body's own axes; "
                     f"torsion as ρ·rx, ρ = √(J_x/m); each mode divided by its largest entry)"
                     if system.per_body == 6 else
                     f"{system.drive.name}: mode shapes per shaft line\n(torsional model: the "
                     f"rotation rx; each mode divided by its largest entry)", fontsize=8.5)
    return fig


def _body_ticks(ax, system, line: Line, last: bool) -> None:
    """x ticks at the file's bodies, named (with their position in the last row)."""
    named = [j for j, i in enumerate(line.bodies) if not system.owners[i]]
    x = line.position[named] * (1e3 if line.measured else 1.0)
    ax.set_xticks(x)
    names = [system.bodies[line.bodies[j]].name for j in named]
    if last and line.measured:
        names = [f"{n}\n{p:.0f}" for n, p in zip(names, x)]
    ax.set_xticklabels(names, fontsize=6.5)
    if last:
        ax.set_xlabel("axial position [mm]" if line.measured else "bodies in the order the "
                                                                   "shafts join them")
    every = line.position * (1e3 if line.measured else 1.0)
    span = float(np.ptp(every))
    pad = 0.1 * span if span > 0 else 1.0
    ax.set_xlim(every[0] - pad, every[-1] + pad)
