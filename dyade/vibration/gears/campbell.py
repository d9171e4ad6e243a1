"""Campbell diagram of a gear drive: natural frequencies against the input speed, the
excitation orders, and the resonance speeds where they cross.

The model has no gyroscopic terms (the paper neglects them, as dyade does): the natural
frequencies do not depend on speed, so one modal analysis serves every speed and the
diagram costs about one modal analysis however many speeds it has. The excitation lines
are straight through the origin: each shaft line's speed (order 1; the bodies joined by
shafts and elements turn together), each mesh's tooth-mesh frequency z·n/60 and its
harmonics, and the orders of the file's excitations.

At each crossing of a mode with a line inside the speed range, a resonance: the mode's
strain-energy share in the elastic meshes, and, for a mesh line, the mode's modal mesh
stiffness F²/ω² [N/m] at that mesh (``Modes.mesh_stiffness``): the dynamic mesh force a
unit transmission error drives at that resonance is F²/(2ζ·ω²), so it ranks crossings also
for ideal meshes, which store no strain energy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.limits import BYTES_PER_VALUE, check_memory
from dyade.model.gears import FRAME, GearDrive
from dyade.vibration.gears.modes import Modes, coordinate_count, gear_modes


@dataclass(frozen=True, slots=True)
class Order:
    """An excitation line: frequency = slope·(input speed) [+ a fixed frequency]."""

    name: str
    kind: str
    """"shaft", "mesh" or "excitation" """
    slope: float
    """[Hz per input rpm]; 0 for a fixed frequency"""
    frequency: float = 0.0
    """a fixed frequency [Hz] (excitations with `frequency`)"""
    mesh: int | None = None
    """the mesh of a tooth-mesh line or a transmission error (index into drive.meshes)"""


@dataclass(frozen=True, slots=True)
class Crossing:
    """A resonance: a mode met by an excitation line inside the speed range."""

    speed_rpm: float
    """input speed [rpm]"""
    mode: int
    """the elastic mode, 1-based"""
    frequency: float
    """[Hz]"""
    order: str
    kind: str
    mesh_share: float
    """the mode's strain-energy share in all elastic meshes (NaN: every mesh is ideal)"""
    mesh_stiffness: float
    """F²/ω² of the line's mesh [N/m] (NaN for a shaft line)"""
    dominant: str
    """where the mode's strain energy is largest: "owner motion share" """


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Campbell:
    """A Campbell diagram: the excitation lines over the speeds and their crossings with
    the natural frequencies (which do not depend on speed in this model)."""

    speeds_rpm: FloatArray
    """(s,) input speeds [rpm]"""
    modes: Modes
    orders: tuple[Order, ...]
    lines: FloatArray
    """(orders, s) each line's frequency at each speed [Hz]"""
    crossings: tuple[Crossing, ...]
    """ordered by speed"""


def default_speeds(rpm: float, points: int = 200) -> np.ndarray:
    """Input speeds [rpm] from 0 to 1.5 × the operating speed ``rpm``, rounded up to two
    significant digits, in ``points`` equal steps."""
    if not (math.isfinite(rpm) and rpm > 0.0):
        raise ValueError(f"an operating speed must be positive, got {rpm!r}")
    top = 1.5 * rpm
    unit = 10.0 ** (math.floor(math.log10(top)) - 1)
    stop = math.ceil(top / unit - 1e-9) * unit
    return np.linspace(0.0, stop, points + 1)


def shaft_lines(drive: GearDrive) -> list[tuple[str, list[str]]]:
    """The groups of bodies that turn together (joined by shafts or elements), named by
    their first shaft (or their first body)."""
    parent = {b.name: b.name for b in drive.bodies}

    def root(name: str) -> str:
        while parent[name] != name:
            name = parent[name]
        return name

    joins = [(s.name, s.ends) for s in drive.shafts] + [(e.name, e.ends) for e in drive.elements]
    names: dict[str, str] = {}
    for name, (a, b) in joins:
        if b != FRAME and root(a) != root(b):
            parent[root(a)] = root(b)
    for name, (a, b) in joins:
        if b != FRAME:
            names.setdefault(root(a), name)
    groups: dict[str, list[str]] = {}
    for body in drive.bodies:
        groups.setdefault(root(body.name), []).append(body.name)
    return [(names.get(r, members[0]), members) for r, members in groups.items()]


def orders(drive: GearDrive, harmonics: int = 3) -> tuple[Order, ...]:
    """The excitation lines of ``drive``: shaft speeds, tooth-mesh harmonics 1…
    ``harmonics``, and the file's excitations."""
    if drive.speed is None:
        raise InputError.parameter("speed", "is not given: a Campbell diagram needs [speed] "
                                            "body (the input shaft whose speed is its axis).")
    if harmonics < 0:
        raise InputError.parameter("harmonics", f"must be 0 or more, got {harmonics}.")
    omega = drive.speed_ratios()
    speed = {name: float(np.linalg.norm(w)) for name, w in omega.items()}
    out = []
    for name, members in shaft_lines(drive):
        if members[0] in speed:
            out.append(Order(f"{name} ×1", "shaft", speed[members[0]] / 60.0))
    for k, mesh in enumerate(drive.meshes):
        p = drive.gear(mesh.driving)
        if p.body not in speed:
            continue
        for h in range(1, harmonics + 1):
            out.append(Order(f"{mesh.name} ×{h}", "mesh", h * p.teeth * speed[p.body] / 60.0,
                             mesh=k))
    meshes = {m.name: k for k, m in enumerate(drive.meshes)}
    for excitation in drive.excitations:
        mesh = meshes.get(excitation.target) if excitation.kind == "transmission_error" else None
        if excitation.frequency is not None:
            out.append(Order(excitation.name, "excitation", 0.0, excitation.frequency, mesh))
            continue
        if excitation.order is None:
            continue
        body = (drive.gear(drive.meshes[mesh].driving).body if mesh is not None
                else excitation.target)
        if body in speed:
            out.append(Order(excitation.name, "excitation",
                             excitation.order * speed[body] / 60.0, mesh=mesh))
    return tuple(out)


def campbell_size(drive: GearDrive, speeds: int, harmonics: int) -> float:
    """What a Campbell diagram of ``speeds`` speeds and ``harmonics`` tooth-mesh
    harmonics takes [B], before anything is computed: its lines (8 B per line and
    speed) and at most one crossing per line and mode (a row of the table each)."""
    lines = harmonics * len(drive.meshes) + len(drive.bodies) + len(drive.excitations)
    modes = coordinate_count(drive)
    return 8.0 * lines * speeds + 8 * BYTES_PER_VALUE * lines * modes + (50 << 20)


def campbell(drive: GearDrive, speeds_rpm, *, harmonics: int = 3,
             modes: Modes | None = None, max_memory: float | None = None) -> Campbell:
    """Natural frequencies against input speed, the excitation lines and the resonances.

    Parameters
    ----------
    drive : GearDrive
        With a ``[speed]`` body (the input shaft).
    speeds_rpm : array_like
        Input speeds [rpm], ascending.
    harmonics : int
        Tooth-mesh harmonics to draw (1 … harmonics).
    modes : Modes, optional
        ``gear_modes(drive)``, if already computed.
    max_memory : float, optional
        Bound on what the diagram may take [B] (default ``dyade.limits.MAX_MEMORY``),
        checked before anything is computed.

    Returns
    -------
    Campbell
        The lines at every speed and the crossings (resonance speeds) in the range.

    Examples
    --------
    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> diagram = dyade.campbell(drive, range(0, 3001, 10))
    >>> first = diagram.crossings[0]
    >>> first.order, round(first.speed_rpm), first.mode
    ('stage1 ×3', 79, 1)
    """
    speeds = np.asarray(speeds_rpm, dtype=float)
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(
            speeds < 0) or np.any(np.diff(speeds) <= 0):
        raise InputError.parameter("speeds_rpm", "must be ascending speeds ≥ 0 [rpm].",
                                   unit="rpm")
    if isinstance(harmonics, bool) or not isinstance(harmonics, (int, np.integer)) or harmonics < 0:
        raise InputError.parameter("harmonics", f"must be a whole number ≥ 0, got {harmonics!r}.",
                                   value=harmonics)
    check_memory(campbell_size(drive, speeds.size, int(harmonics)),
                 f"a Campbell diagram of {speeds.size:,} speeds and {harmonics:,} tooth-mesh "
                 f"harmonics", max_memory, "Ask for fewer speeds or harmonics")
    lines = orders(drive, harmonics)
    modes = modes if modes is not None else gear_modes(drive, max_memory=max_memory)
    slopes = np.array([o.slope for o in lines])
    fixed = np.array([o.frequency for o in lines])
    values = slopes[:, None] * speeds[None, :] + fixed[:, None]
    f = modes.frequencies
    with np.errstate(divide="ignore", invalid="ignore"):  # fixed lines (slope 0) never cross
        at = (f[:, None] - fixed[None, :]) / slopes[None, :]
    inside = (slopes[None, :] > 0) & np.isfinite(at) & (at >= speeds[0]) & (at <= speeds[-1])
    totals = modes.totals("strain")["mesh"]
    elastic = any(m.stiffness is not None for m in drive.meshes)
    stiffness = modes.mesh_stiffness
    dominant = modes.dominant()
    found = []
    for k, o in zip(*np.nonzero(inside)):
        line = lines[o]
        owner, motion, share = dominant[k]
        found.append(Crossing(float(at[k, o]), int(k) + 1, float(f[k]), line.name, line.kind,
                              float(totals[k]) if elastic else float("nan"),
                              float(stiffness[line.mesh, k]) if line.mesh is not None
                              else float("nan"),
                              f"{owner} {motion} {share:.0%}"))
    found.sort(key=lambda c: (c.speed_rpm, c.mode))
    return Campbell(speeds, modes, lines, values, tuple(found))
