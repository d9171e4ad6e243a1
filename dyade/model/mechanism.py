"""The mechanism as dyade sees it inside: frozen dataclasses, SI units, validated.

Every link has its own frame (origin and ξ axis, as in the DYADE paper, Thümmel &
Bartke 1987); every joint is stated in the frames of the two links it joins. The file
reader (``dyade.files.mechanism``) turns the designer's per-kind description into these
objects, so the engine never needs to know which link of a prismatic pair was written
as guide and which as slider. The link frames of the two links a dyad places are part
of its kind's description (``DyadKind.frames``; the kinds are in ``dyade.model.dyad_kinds``,
documented in ``docs/reference/mechanism-file.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Union

import numpy as np

from dyade.arrays import FloatArray, Vec
from dyade.model.dyad_kinds import DyadKind

if TYPE_CHECKING:
    from dyade.model.cam import CamDrive
    from dyade.model.drive import Drive
    from dyade.model.drive_line import DriveLineData
    from dyade.model.servo import Servo

FRAME = 1  # link number of the frame
CRANK = 2  # link number of the crank



def joint_name(a: int, b: int) -> tuple[int, int]:
    """A joint's name: the two links it joins, lower number first."""
    return (a, b) if a < b else (b, a)


def toward_higher(name: tuple[int, int], link: int) -> float:
    """The sign rule of the DYADE paper (Thümmel & Bartke 1987, section 2): a joint's
    force, moment or friction load is reported as it acts on the element of the
    higher-numbered link. +1 when ``link`` is that link of joint ``name``, −1 when it
    is the other one: multiply a load on ``link`` by it to report it."""
    return 1.0 if link == max(name) else -1.0


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class ClearanceData:
    """Data of a revolute joint with clearance for the peak-force check (Dresig & Thümmel)."""

    clearance: float
    """radial play 2s [m]"""
    stiffness: float
    """contact stiffness c [N/m]"""
    mass: float | None = None
    """reduced mass m [kg]; None: estimate from the two links' masses"""


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Revolute:
    """A revolute joint (Drehgelenk): point ``points[0]`` of ``links[0]`` coincides with
    point ``points[1]`` of ``links[1]`` (link-fixed coordinates ξ, η [m])."""

    links: tuple[int, int]
    points: tuple[Vec, Vec]
    pin_radius: float | None = None
    """Pin radius r_z [m] for Coulomb friction (None: not given)."""
    friction: float = 0.0
    """Coulomb friction coefficient μ [-]."""
    clearance: ClearanceData | None = None
    """Clearance data for the peak-force check (None: no check unless asked)."""

    @property
    def name(self) -> tuple[int, int]:
        return joint_name(*self.links)

    @property
    def kind(self) -> str:
        return "R"


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Prismatic:
    """A prismatic joint (Schubgelenk) between a guide and a slider.

    The ``carrier`` link carries a guide line through ``guide_point`` with direction
    angle ``guide_angle`` (both in the carrier's frame); point ``slider_point`` of the
    ``slider`` link stays on that line, and the two links keep the relative angle
    φ_slider − φ_carrier = ``relative_angle``. The slider travel is
    s = (S − G)·d, with S the slider point, G the guide point and d the guide direction.
    """

    carrier: int
    slider: int
    guide_point: Vec
    guide_angle: float
    slider_point: Vec
    relative_angle: float
    slider_length: float | None = None
    """Slider length L [m] for friction and self-locking (None: not given)."""
    slider_height: float | None = None
    """Slider height H [m] for friction (None: not given)."""
    friction: float = 0.0
    """Coulomb friction coefficient μ [-]."""
    edge_friction: bool = True
    """The block's tilting moment M' enters its friction (with μ > 0): μ times the total
    pressure of a linear distribution over L (``dyade.linkage.friction.laws``); False:
    point contact, μ·|FN|."""

    @classmethod
    def through(cls, carrier: int, point: Vec, theta: float, offset: float, slider: int,
                slider_point: Vec, relative_angle: float, **extra) -> Prismatic:
        """A prismatic joint whose guide passes ``point`` of the carrier in direction
        ``theta`` [rad], shifted so that the slider point lies ``offset`` [m] to its left;
        ``extra``: friction data (``friction``, ``slider_length``, ``slider_height``,
        ``edge_friction``)."""
        shifted = (point[0] - offset * math.sin(theta), point[1] + offset * math.cos(theta))
        return cls(carrier, slider, shifted, theta, slider_point, relative_angle, **extra)

    @property
    def links(self) -> tuple[int, int]:
        return (self.carrier, self.slider)

    @property
    def name(self) -> tuple[int, int]:
        return joint_name(self.carrier, self.slider)

    @property
    def kind(self) -> str:
        return "P"


Joint = Union[Revolute, Prismatic]


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Load:
    """An applied force and/or moment on a link, constant or tabulated over the crank
    angle (interpolated periodically)."""

    link: int
    point: Vec
    """Point of application, link-fixed (ξ, η) [m]."""
    angles: FloatArray | None
    """Crank angles of the table [rad], ascending within one period; None: constant."""
    fx: FloatArray
    """Force x components [N] (world frame), one per table row (or one value)."""
    fy: FloatArray
    moment: FloatArray
    """Moment [N·m], counter-clockwise positive."""
    local: bool = False
    """True: (fx, fy) are given in the link frame (ξ, η) and turn with it."""


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Spring:
    """A linear spring between a point of one link and a point of another."""

    links: tuple[int, int]
    points: tuple[Vec, Vec]
    stiffness: float
    """[N/m]"""
    free_length: float
    """[m]"""
    name: str


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Link:
    """A link: its named points and (optionally) its mass data."""

    number: int
    points: dict[str, Vec] = field(default_factory=dict)
    """Named link points (coupler points), link-fixed (ξ, η) [m]."""
    mass: float = 0.0
    """[kg]"""
    centre: Vec = (0.0, 0.0)
    """Centre of mass (ξ_s, η_s) [m]."""
    inertia: float = 0.0
    """Moment of inertia about the centre of mass J_s [kg·m²]."""

    @property
    def has_mass(self) -> bool:
        return bool(np.any(self.mass > 0.0) or np.any(self.inertia > 0.0))


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Dyad:
    """A two-link group: links i, j placed by joints A (i–g), B (i–j), C (j–h)."""

    number: int
    """k in the paper: the crank is dyad 1, the first file dyad is 2."""
    kind: DyadKind
    """The dyad kind (``dyade.model.dyad_kinds``): number 1-5, name RRR … PPR; its
    closure is the engine's (``dyade.linkage.dyads``)."""
    links: tuple[int, int]
    known: tuple[int, int]
    """(g, h): the already-placed links that A and C attach to."""
    joints: tuple[Joint, Joint, Joint]
    """A, B, C."""
    variant: int
    """Assembly variant ±1 for kinds 1–3, 0 for kinds 4 and 5 (one closure)."""

    @property
    def label(self) -> str:
        i, j = self.links
        return f"dyad {self.number} (kind {self.kind.number} {self.kind.name}, links {i}-{j})"


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Crank:
    """Link 2, the chain's input: turning about a frame point at constant speed (or,
    with a drive, at the speed the equation of motion gives; ``speed`` is then its
    nominal speed), or, with ``guide`` set, sliding along a frame guide (a cam's
    translating follower: ``Mechanism.cam`` gives its travel over the cam angle).

    The input's coordinate q is the crank angle φ21 [rad] (turning) or the travel s [m]
    of link 2's origin from ``pivot`` along the guide (sliding); its unit twist S₁₂ is
    (y_p, −x_p, 1) about the pivot or (cos γ, sin γ, 0) along the guide at angle γ
    (``dyade.linkage.kinematics.crank_screw``), and the drive is the load along it: a
    torque about the pivot, or a force along the guide.
    """

    pivot: Vec
    """Frame point of joint (1,2) [m] (sliding: link 2's origin at zero travel)."""
    length: float
    """[m]; the point ``tip`` of the crank is (length, 0) in its frame (sliding: the
    follower's stroke, the length scale of its speeds)."""
    speed: float
    """Ω [rad/s], counter-clockwise positive (with a cam: the cam's speed, in its own
    sense of rotation)."""
    joint: Joint
    """Joint (1,2): a revolute joint, or (sliding) a prismatic one on the frame."""
    guide: float | None = None
    """The guide's angle γ [rad] of a sliding input (link 2's ξ axis along it); None:
    link 2 turns about ``pivot``."""

    @property
    def sliding(self) -> bool:
        """Link 2 slides along a frame guide (its drive a force)."""
        return self.guide is not None


MAX_SWEEP_ANGLE = 2.0 * math.pi * 1e4  # [rad] 10 000 revolutions: beyond, steps blur
MIN_SWEEP_STEP = 1e-9  # [rad] finer steps are below double precision at large angles


def sweep_problem(start: float, stop: float, step: float) -> str | None:
    """Why a crank-angle sweep [rad] cannot be computed as asked, or None."""
    if not all(math.isfinite(v) for v in (start, stop, step)):
        return "needs finite angles"
    if max(abs(start), abs(stop)) > MAX_SWEEP_ANGLE:
        return (f"reaches {math.degrees(max(abs(start), abs(stop))):.6g}°: crank angles must "
                f"lie within ±{math.degrees(MAX_SWEEP_ANGLE):.0f}° (10 000 revolutions), where "
                f"double precision still tells the positions apart")
    if step < MIN_SWEEP_STEP:
        return f"has a step of {math.degrees(step):.3g}°, below {math.degrees(MIN_SWEEP_STEP):.1e}°"
    if stop < start:
        return "stops below its start"
    return None


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Sweep:
    """Crank angles φ21 from ``start`` to ``stop`` (inclusive) in steps of ``step`` [rad]."""

    start: float
    stop: float
    step: float

    @property
    def count(self) -> int:
        """The number of positions."""
        return int(np.floor((self.stop - self.start) / self.step + 1e-9)) + 1

    def angles(self) -> FloatArray:
        return self.start + self.step * np.arange(self.count, dtype=np.float64)


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Mechanism:
    """A whole linkage in assembly order, SI units: the crank, the dyads, the links with
    their points and mass data, loads, springs, gravity and the crank-angle sweep.
    Made by ``dyade.read_mechanism`` (a file) or ``dyade.build_mechanism`` (a dict
    with the same keys), which validate it.

    >>> import dyade
    >>> sixbar = dyade.read_mechanism("mechanisms/watt-sixbar.toml")
    >>> sixbar.name, [dyad.number for dyad in sixbar.dyads], sixbar.sweep.count
    ('Watt II six-bar', [2, 3], 361)
    >>> round(sixbar.crank.speed, 4)                    # Ω [rad/s]: SI inside
    20.944
    """

    name: str
    source: str | None
    """the file it was read from"""
    crank: Crank
    dyads: tuple[Dyad, ...]
    links: dict[int, Link]
    sweep: Sweep
    gravity: Vec = (0.0, 0.0)
    """Gravitational acceleration (x, y) [m/s²]; (0, 0): off."""
    loads: tuple[Load, ...] = ()
    springs: tuple[Spring, ...] = ()
    dead_centre_angle: float = np.deg2rad(2.0)
    """The hard band: transmission angles within this of 0° or 180° are a dead centre,
    where nothing is given [rad]."""
    friction_tol: float = 1e-9
    friction_max_iter: int = 50
    transmission_warning: float = np.deg2rad(40.0)
    """The soft band: transmission angles below this (and above 180° minus it) are
    reported with a warning [rad]; 40° is the designers' rule since H. Alt (1932)."""
    units: tuple[str, str] = ("m", "deg")
    """The file's length and angle units (for showing results as the file has them)."""
    drive: Drive | None = None
    """The motor and flywheel of a ``[drive]`` table (the flywheel is already counted in
    link 2's inertia); None: the crank turns at its constant speed."""
    drive_line: DriveLineData | None = None
    """The elastic element between motor and crank of a ``[drive_line]`` table
    (``dyade.model.drive_line``); None: a rigid drive."""
    max_memory: float | None = None
    """The bound [B] on what one run may take (``dyade.limits``; None: its default), set
    by ``analyse``'s ``max_memory``: the [drive]'s equation of motion checks it too."""
    servo: Servo | None = None
    """The servo of a ``[servo]`` table: the crank follows a motion profile over the cycle
    time (``dyade.model.servo``; ``dyade servo`` sizes it); None: no servo. ``analyse``
    sweeps such a mechanism at its constant ``crank.speed_rpm``."""
    cam: CamDrive | None = None
    """The disc cam of a ``[cam]`` table that drives link 2 (its follower): the sweep
    runs over the cam angle θ (``crank_angle``) at the cam's speed, link 2 follows the
    cam's motion profile (``dyade.model.cam.CamDrive``); None: link 2 is driven itself."""

    @property
    def joints(self) -> list[Joint]:
        """Every joint: (1,2) first, then A, B, C of each dyad in assembly order."""
        out: list[Joint] = [self.crank.joint]
        for dyad in self.dyads:
            out.extend(dyad.joints)
        return out

    @property
    def moving_links(self) -> list[int]:
        """Moving links in assembly order: the crank, then i, j of each dyad."""
        out = [CRANK]
        for dyad in self.dyads:
            out.extend(dyad.links)
        return out

    @property
    def max_link(self) -> int:
        return max(self.moving_links)

    @property
    def named_points(self) -> list[tuple[str, int, Vec]]:
        """(name, link, local point) of every named link point; the frame's points and
        the crank's built-in ``tip`` (it is joint (2,3) or wherever A attaches) excluded."""
        return [(name, link.number, point)
                for link in self.links.values() if link.number != FRAME
                for name, point in link.points.items()
                if not (link.number == CRANK and name == "tip")]

    @property
    def friction_sliders(self) -> list[Prismatic]:
        """Prismatic joints with μ > 0: the sliders the self-locking test applies to."""
        return [j for j in self.joints if isinstance(j, Prismatic) and j.friction > 0.0]

    @property
    def has_dynamics(self) -> bool:
        """True when something loads the mechanism: masses, loads or springs."""
        return (any(link.has_mass for link in self.links.values())
                or bool(self.loads) or bool(self.springs))
