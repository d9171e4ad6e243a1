"""The gear-drive model (SI, validated): rigid bodies, shafts, bearings, spring-damper
elements, gears, meshes, excitations and the input speed.

Berczyński, Maćkowiak and Marchelek (1978) model a multistage gear drive as rigid finite
elements (RFE) with six coordinates each (three translations, three small rotations along
and about the element's own axes), joined by linear spring-damper elements (SDE), with
every gear mesh an ideal constraint on its plane of action. The classes here hold what a
gear-drive file says, in SI units; ``dyade.vibration.gears.assembly`` turns them into the
matrices M, K, L and g. Nothing here imports numpy: reading a file stays cheap.

Every body has a local frame (e1, e2, e3): e1 along its axis, e2 and e3 fixed by
``frame`` (for the default axis x they are y and z). Its six coordinates are
(ux, uy, uz, rx, ry, rz) along and about those axes, so its mass matrix is diagonal
(m, m, m, J_x, J_y, J_z).

>>> from dyade.model.gears import Gear
>>> gear = Gear("pinion", "shaft", teeth=20, module=0.004, pressure_angle=0.3490658503988659)
>>> round(gear.pitch_radius, 6), round(gear.base_radius, 6)
(0.04, 0.037588)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

Vector = tuple[float, float, float]

DOFS = ("ux", "uy", "uz", "rx", "ry", "rz")
"""the six coordinates of a body, along and about its local axes (e1, e2, e3)"""
FRAME = "frame"
"""the name that stands for the fixed frame (housing) in a shaft's or element's ends"""
RIGID = math.inf
"""a stiffness coefficient of an element or bearing that does not give: the direction is
an exact constraint (the limit that stiffer and stiffer springs converge to)"""
PARALLEL_TOL = 1e-9  # [-] 1 - |cos| below this: two axes are parallel


def unit(vector: Vector) -> Vector:
    """``vector`` scaled to length 1 (it must not be zero)."""
    length = math.sqrt(sum(c * c for c in vector))
    return (vector[0] / length, vector[1] / length, vector[2] / length)


def cross(a: Vector, b: Vector) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a: Vector, b: Vector) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def add(a: Vector, b: Vector, scale: float = 1.0) -> Vector:
    """a + scale·b"""
    return (a[0] + scale * b[0], a[1] + scale * b[1], a[2] + scale * b[2])


def frame(axis: Vector) -> tuple[Vector, Vector, Vector]:
    """The local frame (e1, e2, e3) of a body whose axis is ``axis``: e1 = axis, e2 the
    first of the global y, z, x axes that is not nearly along e1, made perpendicular to
    it, and e3 = e1 × e2 (right-handed). For the default axis x: (x, y, z)."""
    e1 = unit(axis)
    for ref in ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)):
        if abs(dot(ref, e1)) < 0.9:
            e2 = unit(add(ref, e1, -dot(ref, e1)))
            return e1, e2, cross(e1, e2)
    raise AssertionError("unreachable: one of three axes is never within 26° of another two")


@dataclass(frozen=True, slots=True)
class Material:
    """An isotropic elastic material."""

    E: float = 2.1e11
    """Young's modulus [Pa] (steel by default)"""
    G: float = 8.1e10
    """shear modulus [Pa]"""
    density: float = 7850.0
    """[kg/m³]"""


@dataclass(frozen=True, slots=True)
class Body:
    """A rigid element: a gear, a rotor, a motor, or a segment of a shaft."""

    name: str
    mass: float
    """m [kg] (0 in a torsional model that gives only J_x)"""
    inertia: Vector
    """principal moments of inertia (J_x about its own axis, J_y, J_z) [kg·m²]"""
    position: Vector = (0.0, 0.0, 0.0)
    """its reference point (centre of mass) [m]"""
    axis: Vector = (1.0, 0.0, 0.0)
    """unit vector e1 of its own axis"""

    @property
    def axes(self) -> tuple[Vector, Vector, Vector]:
        """(e1, e2, e3): the local frame its coordinates and inertias refer to"""
        return frame(self.axis)


def disk(density: float, diameter: float, width: float, bore: float = 0.0
         ) -> tuple[float, Vector]:
    """Mass [kg] and principal inertias (J_x, J_y, J_z) [kg·m²] of a hollow cylinder of
    outer ``diameter``, ``width`` along its axis and inner ``bore`` [m].

    >>> m, (jx, jy, jz) = disk(7850.0, 0.2, 0.05)
    >>> round(m, 4), round(jx, 6), round(jy, 6)
    (12.3308, 0.061654, 0.033396)
    """
    area = math.pi / 4.0 * (diameter ** 2 - bore ** 2)
    mass = density * area * width
    radii2 = (diameter ** 2 + bore ** 2) / 4.0  # r_o² + r_i²
    jx = mass * radii2 / 2.0
    jy = mass * (radii2 / 4.0 + width ** 2 / 12.0)
    return mass, (jx, jy, jy)


@dataclass(frozen=True, slots=True)
class Shaft:
    """A round shaft between two bodies (or a body and the frame), split into segments by
    the RFE method: each segment a rigid element, its flexibility in spring-damper
    elements between neighbours."""

    name: str
    ends: tuple[str, str]
    """the bodies at its two ends; the second may be ``"frame"`` (clamped to the housing)"""
    length: float
    """flexible length between the two ends' reference points [m]"""
    diameter: float = 0.0
    """outer diameter [m] (0 with an explicit ``torsional_stiffness``)"""
    bore: float = 0.0
    """inner diameter [m]"""
    material: Material = field(default_factory=Material)
    segments: int = 1
    """rigid elements it is split into; 0: massless (one spring-damper element)"""
    shear_factor: float = 0.9
    """κ of the shear stiffness κ·G·A/l (about 0.9 for a solid round section)"""
    damping: float = 0.0
    """stiffness-proportional damping: every coefficient c = damping·k [s]"""
    torsional_stiffness: float | None = None
    """explicit torsional stiffness [N·m/rad] (torsional model only), instead of G·I_p/L"""

    @property
    def area(self) -> float:
        """A [m²]"""
        return math.pi / 4.0 * (self.diameter ** 2 - self.bore ** 2)

    @property
    def second_moment(self) -> float:
        """I about a diameter [m⁴]; the polar moment I_p is twice this"""
        return math.pi / 64.0 * (self.diameter ** 4 - self.bore ** 4)


@dataclass(frozen=True, slots=True)
class Element:
    """A spring-damper element between two bodies or a body and the frame, with six
    stiffness and six damping coefficients along and about its own axes (e1 along
    ``axis``, e2 and e3 as ``frame`` makes them)."""

    name: str
    ends: tuple[str, str]
    """the two bodies; the second may be ``"frame"``"""
    point: Vector
    """where it acts [m]"""
    axis: Vector
    stiffness: tuple[float, ...]
    """(k_x, k_y, k_z, k_rx, k_ry, k_rz) [N/m, N/m, N/m, N·m/rad, N·m/rad, N·m/rad];
    ``RIGID`` (math.inf) in a direction that does not give: an exact constraint there,
    eliminated like an ideal mesh (no penalty stiffness)"""
    damping: tuple[float, ...] = (0.0,) * 6
    """(c_x, …, c_rz) [N·s/m, …, N·m·s/rad]"""
    kind: str = "element"
    """"element", "bearing" or "shaft" (a piece of a shaft)"""
    owner: str = ""
    """the file's name of the shaft, bearing or element it comes from"""


@dataclass(frozen=True, slots=True)
class Gear:
    """A cylindrical (spur or helical) gear on a body."""

    name: str
    body: str
    teeth: int
    module: float | None
    """normal module m_n [m]; None in a torsional model that gives only the ratio"""
    pressure_angle: float = math.radians(20.0)
    """normal pressure angle α_n [rad]"""
    helix_angle: float = 0.0
    """β [rad] (0 for spur gears)"""
    hand: int = 0
    """+1 right-hand, -1 left-hand helix (0 for spur gears)"""
    width: float = 0.0
    """face width [m] (documentation; no load distribution along it)"""
    offset: float = 0.0
    """position of its mid-plane along the body's axis from the body's reference point [m]"""

    @property
    def pitch_radius(self) -> float:
        """r = z·m_n/(2·cos β) [m] (per unit module when the module is not given)"""
        return self.teeth * (self.module or 1.0) / (2.0 * math.cos(self.helix_angle))

    @property
    def transverse_pressure_angle(self) -> float:
        """α_t = atan(tan α_n / cos β) [rad]"""
        return math.atan(math.tan(self.pressure_angle) / math.cos(self.helix_angle))

    @property
    def base_radius(self) -> float:
        """r_b = r·cos α_t [m]"""
        return self.pitch_radius * math.cos(self.transverse_pressure_angle)


@dataclass(frozen=True, slots=True)
class Mesh:
    """Two gears in mesh: the driving gear p pushes the driven gear r."""

    name: str
    driving: str
    driven: str
    rotation: int = 0
    """+1 when the driving gear turns right-handed about its body's axis, -1 left-handed
    (i = 0 or 1 of the paper); 0 when not known (torsional model)"""
    angle: float = 0.0
    """direction of the line of centres, from the driving body's e2 towards its e3 [rad]"""
    stiffness: float | None = None
    """along the line of action [N/m]; None: ideal (the paper's constraint)"""
    damping: float = 0.0
    """along the line of action [N·s/m] (elastic meshes only)"""


@dataclass(frozen=True, slots=True)
class Excitation:
    """A harmonic excitation: a torque about a body's axis, or a transmission error at a
    mesh (the constraint becomes n·(contact displacement difference) = e(t))."""

    name: str
    kind: str
    """"torque" or "transmission_error" """
    target: str
    """the body (torque) or the mesh (transmission error)"""
    amplitude: float
    """[N·m] or [m]"""
    phase: float = 0.0
    """[rad]: the excitation is amplitude·cos(Ωt + phase)"""
    order: float | None = None
    """multiple of the speed of ``target``'s body (of the driving gear's body for a mesh)"""
    frequency: float | None = None
    """a fixed frequency [Hz] instead of an order"""


@dataclass(frozen=True, slots=True)
class Speed:
    """The input shaft: the body whose speed the Campbell diagram's axis gives."""

    body: str
    rotation: int = 0
    """+1 right-handed about its axis, -1 left-handed, 0 not given"""
    rpm: float | None = None
    """operating speed [rpm]"""


@dataclass(frozen=True, slots=True)
class GearDrive:
    """A gear drive as a gear-drive file describes it (SI, validated).

    ``model`` is "rfe" (six coordinates per body, the paper's model) or "torsional" (one
    rotation per body, shafts as torsion springs, meshes by the gear ratio).

    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> drive.name, drive.model, len(drive.bodies), len(drive.meshes)
    ('Two-stage spur drive', 'rfe', 6, 2)
    """

    name: str
    bodies: tuple[Body, ...]
    shafts: tuple[Shaft, ...] = ()
    elements: tuple[Element, ...] = ()
    """bearings and explicit elements (kind "bearing" or "element")"""
    gears: tuple[Gear, ...] = ()
    meshes: tuple[Mesh, ...] = ()
    excitations: tuple[Excitation, ...] = ()
    speed: Speed | None = None
    model: str = "rfe"
    source: str | None = None

    def body(self, name: str) -> Body:
        return next(b for b in self.bodies if b.name == name)

    def gear(self, name: str) -> Gear:
        return next(g for g in self.gears if g.name == name)

    def mesh(self, name: str) -> Mesh:
        return next(m for m in self.meshes if m.name == name)

    @property
    def torsional(self) -> bool:
        return self.model == "torsional"

    def speed_ratios(self) -> dict[str, Vector]:
        """Each body's angular velocity vector per unit input speed (ω of the input body
        = its axis times ±1), carried through shafts and elements (which turn with the
        bodies they join) and meshes (ω_r = −(z_p/z_r)·ω_p for external gears on parallel
        axes). Bodies that no path reaches are left out."""
        if self.speed is None:
            return {}
        links: dict[str, list[tuple[str, float]]] = {b.name: [] for b in self.bodies}
        for ends in [s.ends for s in self.shafts] + [e.ends for e in self.elements]:
            if FRAME not in ends:
                links[ends[0]].append((ends[1], 1.0))
                links[ends[1]].append((ends[0], 1.0))
        for mesh in self.meshes:
            p, r = self.gear(mesh.driving), self.gear(mesh.driven)
            links[p.body].append((r.body, -p.teeth / r.teeth))
            links[r.body].append((p.body, -r.teeth / p.teeth))
        start = self.body(self.speed.body)
        sign = self.speed.rotation or 1
        omega = {start.name: tuple(sign * c for c in unit(start.axis))}
        todo = [start.name]
        while todo:
            name = todo.pop()
            for other, ratio in links[name]:
                if other not in omega:
                    omega[other] = tuple(ratio * c for c in omega[name])
                    todo.append(other)
        return omega


def mesh_frame(mesh: Mesh, driving_axis: Vector) -> tuple[Vector, Vector, Vector]:
    """The mesh frame at the pitch point (Z1, Z2, Z3): Z1 along the driving body's axis,
    Z2 along the line of centres towards the driven gear's axis (``mesh.angle`` from the
    driving body's e2 towards its e3), Z3 = Z1 × Z2 (right-handed)."""
    e1, e2, e3 = frame(driving_axis)
    z2 = add(tuple(math.cos(mesh.angle) * c for c in e2), e3, math.sin(mesh.angle))
    return e1, z2, cross(e1, z2)


def mesh_step(p: Gear, r: Gear, mesh: Mesh, axis_p: Vector, axis_r: Vector) -> Vector:
    """From the driving body's reference point to the driven body's [m]."""
    _, z2, _ = mesh_frame(mesh, axis_p)
    step = add(tuple(p.offset * c for c in axis_p), z2, p.pitch_radius + r.pitch_radius)
    return add(step, axis_r, -r.offset)


def plane_of_action(p: Gear, mesh: Mesh, driving_axis: Vector) -> tuple[Vector, Vector]:
    """The unit normal n of the plane of action and the pitch point relative to the driving
    body's reference point [m], both global.

    In the mesh frame n = (A, B, C) = (−h·cos α_n·sin β, s·sin α_n, cos α_n·cos β), the
    paper's ((−1)^j·cos α_n·sin β, (−1)^i·sin α_n, cos α_n·cos β) with (−1)^i = s = +1 when
    the driving gear turns right-handed about its axis (the pitch point then moves along
    +Z3 and the load has B > 0, pushing the gears apart), and (−1)^j = −h with h = +1 for a
    right-hand driving gear: its tooth line at the pitch point runs along
    cos β·Z1 + h·sin β·Z3, and n is perpendicular to it. (The paper fixes the hand by its
    local axes x_p1, x_p3, which the text does not orient; this choice is the standard hand
    of a screw.) A²+B²+C² = 1 for every α_n and β.
    """
    z1, z2, z3 = mesh_frame(mesh, driving_axis)
    alpha, beta = p.pressure_angle, p.helix_angle
    a = -p.hand * math.cos(alpha) * math.sin(beta)
    b = (mesh.rotation or 1) * math.sin(alpha)
    c = math.cos(alpha) * math.cos(beta)
    normal = add(add(tuple(a * x for x in z1), z2, b), z3, c)
    pitch_point = add(tuple(p.offset * x for x in z1), z2, p.pitch_radius)
    return normal, pitch_point
