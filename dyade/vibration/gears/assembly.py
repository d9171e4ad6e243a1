"""Assembly of a gear drive: the mass matrix M (diagonal per body), stiffness K and damping
L from the spring-damper elements, and the mesh constraint matrix g (Berczyński,
Maćkowiak and Marchelek 1978, eqs. (1)-(22)).

Shafts are split into rigid elements by the RFE method (Kruszewski et al. 1975): a shaft
of length L in n segments of length l = L/n gives n rigid elements (each with its
segment's mass and inertia, at the segment's centre) and n + 1 spring-damper elements
between neighbours, spanning l/2, l, …, l, l/2 and sitting at the middle of the span they
stand for, with the stiffnesses of a span of length d: axial E·A/d, shear κ·G·A/d,
torsion G·I_p/d, bending E·I/d. ``segments = 0`` is a massless shaft: one element over L.

Every element's relative displacement in its own frame is Δ = S_b·q_b − S_a·q_a, with
S = (frame rotation)·(rigid transfer to the element's point)·(body frame), so that its
strain energy is ½·Δᵀ·diag(k)·Δ and K = Σ Sᵀ·diag(k)·S. A mesh between gears p and r is
the row T_p·q_p − T_r·q_r with T = [nᵀ, (d × n)ᵀ]·(body frame): the displacement of each
gear's material point at the pitch point (d from the body's reference point) along the
plane-of-action normal n (``model.plane_of_action``). An ideal mesh is a column of g
(gᵀq = 0); an elastic one adds k·w·wᵀ to K and c·w·wᵀ to L.

The torsional model keeps one coordinate per body (its rotation about its own axis): the
same rows, restricted to that coordinate, and only the torsional coefficients.

>>> import dyade
>>> from dyade.vibration.gears.assembly import assemble
>>> system = assemble(dyade.read_gears("mechanisms/gears/friswell-geared.toml"))
>>> system.size, system.constraints.shape
(5, (5, 1))
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.model.gears import (
    DOFS,
    FRAME,
    RIGID,
    Body,
    Element,
    GearDrive,
    Shaft,
    add,
    disk,
    frame,
    mesh_step,
    plane_of_action,
)

UNIT_TOL = 1e-12  # [-] |n| - 1 above this: a plane-of-action normal is not of unit length
RANK_RTOL = 1e-8  # [-] a mesh column of M^-1/2·g with less than this share left after the
#                   earlier ones constrains nothing new (gᵀM⁻¹g singular)
CATEGORY = ("axial", "lateral", "lateral", "torsion", "lateral", "lateral")
"""what each of an element's six directions deforms (x along its axis)"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class System:
    """The assembled equations M·q'' + L·q' + K·q = P + g·λ, gᵀ·q = e."""

    drive: GearDrive
    bodies: tuple[Body, ...]
    """the drive's bodies, then the rigid elements of the shafts (named "shaft.k")"""
    owners: tuple[str, ...]
    """per body: "" for a body of the file, else the shaft it is a segment of"""
    per_body: int
    """coordinates per body: 6, or 1 in the torsional model"""
    mass: FloatArray
    """(n,) the diagonal of M [kg, kg·m²]"""
    stiffness: FloatArray
    """(n, n) K"""
    damping: FloatArray
    """(n, n) L"""
    constraints: FloatArray
    """(n, l) g: one column per ideal mesh"""
    ideal: tuple[int, ...]
    """the meshes (indices into drive.meshes) of the columns of g"""
    mesh_rows: FloatArray
    """(n, meshes) w of every mesh: w·q = n·(u_p − u_r) at the pitch point [m]"""
    normals: FloatArray
    """(meshes, 3) plane-of-action normals (global, unit)"""
    senses: FloatArray
    """(meshes,) +1 or −1: the load on the driven gear acts along senses·n (the driving
    gear's sense of rotation, +1 when unknown), so that a mesh force
    senses·(−λ) or senses·k·w·q is positive in compression"""
    elements: tuple[Element, ...]
    """every spring-damper element, the shafts' pieces included"""
    element_dofs: tuple[np.ndarray, ...]
    """per element: the coordinates it acts on"""
    element_maps: tuple[FloatArray, ...]
    """per element: S = [−S_a, S_b] (6 × its coordinates): Δ = S·q[dofs]"""
    element_stiffness: FloatArray
    """(elements, 6) the coefficients that act (torsional model: rx only)"""
    element_damping: FloatArray
    """(elements, 6)"""
    element_rigid: np.ndarray = None
    """(elements, 6) bool: the directions that are ``RIGID`` (exact constraints: the
    columns ``supports`` of g; their ``element_stiffness`` is 0)"""
    supports: tuple[tuple[int, int], ...] = ()
    """(element, direction) of every rigid direction, in the order of g's columns after
    the ideal meshes'"""

    @property
    def size(self) -> int:
        """n, the number of coordinates"""
        return self.mass.size

    def index(self, body: str) -> int:
        return next(k for k, b in enumerate(self.bodies) if b.name == body)

    def dofs_of(self, body: str) -> np.ndarray:
        k = self.index(body)
        return np.arange(k * self.per_body, (k + 1) * self.per_body)

    def coordinate(self, body: str, dof: str) -> int:
        """The index of coordinate ``dof`` ("ux" … "rz") of ``body``."""
        if self.per_body == 1:
            if dof != "rx":
                raise InputError.parameter("coordinates", f"{body}.{dof}: the torsional model "
                                                          f"has only rx (the rotation about the "
                                                          f"body's axis).")
            return self.index(body)
        return self.index(body) * 6 + DOFS.index(dof)

    def to_global(self, body: int) -> FloatArray:
        """(6, per_body): the body's coordinates -> global (δ, φ) of its reference point."""
        e = np.array(self.bodies[body].axes).T  # columns e1, e2, e3
        if self.per_body == 1:
            return np.concatenate([np.zeros(3), e[:, 0]])[:, None]
        out = np.zeros((6, 6))
        out[:3, :3] = out[3:, 3:] = e
        return out


def assemble(drive: GearDrive) -> System:
    """M, K, L, g and the element maps of ``drive`` (see the module's notes)."""
    torsional = drive.torsional
    per_body = 1 if torsional else 6
    bodies, owners, pieces = list(drive.bodies), [""] * len(drive.bodies), []
    for shaft in drive.shafts:
        segments, elements = split(shaft, {b.name: b for b in drive.bodies})
        bodies += segments
        owners += [shaft.name] * len(segments)
        pieces += elements
    system_elements = tuple(pieces) + drive.elements
    n = per_body * len(bodies)
    mass = np.concatenate([np.array([b.inertia[0]]) if torsional
                           else np.array([b.mass] * 3 + list(b.inertia)) for b in bodies])
    system = System(drive, tuple(bodies), tuple(owners), per_body, mass, np.zeros((n, n)),
                    np.zeros((n, n)), np.zeros((n, 0)), (), np.zeros((n, 0)), np.zeros((0, 3)),
                    np.ones(len(drive.meshes)), system_elements, (), (), np.zeros((0, 6)),
                    np.zeros((0, 6)))
    _elements(system)
    _meshes(system)
    _supports(system)
    return system


def split(shaft: Shaft, bodies: dict[str, Body]) -> tuple[list[Body], list[Element]]:
    """The RFE division of ``shaft``: its rigid elements (segments) and spring-damper
    elements (named "shaft.k" and owned by the shaft)."""
    a, b = shaft.ends
    start, axis = bodies[a].position, bodies[a].axis
    n, length = shaft.segments, shaft.length
    material = shaft.material
    if n == 0:
        spans = [(length / 2.0, length)]  # (position of the element along the axis, span)
    else:
        step = length / n
        spans = ([(step / 4.0, step / 2.0)] + [(k * step, step) for k in range(1, n)]
                 + [(length - step / 4.0, step / 2.0)])
    segments = []
    for k in range(1, n + 1):
        mass, inertia = disk(material.density, shaft.diameter, length / n, shaft.bore)
        segments.append(Body(f"{shaft.name}.{k}", mass, inertia,
                             add(start, axis, (k - 0.5) * length / n), axis))
    names = [a] + [s.name for s in segments] + [b]
    elements = []
    for k, (where, span) in enumerate(spans):
        stiffness = _span_stiffness(shaft, span)
        elements.append(Element(f"{shaft.name}:{k + 1}", (names[k], names[k + 1]),
                                add(start, axis, where), axis, stiffness,
                                tuple(shaft.damping * s for s in stiffness), "shaft", shaft.name))
    return segments, elements


def _span_stiffness(shaft: Shaft, span: float) -> tuple[float, ...]:
    """(E·A, κ·G·A, κ·G·A, G·I_p, E·I, E·I)/d of a span d [N/m, N·m/rad]."""
    if shaft.torsional_stiffness is not None:
        return (0.0, 0.0, 0.0, shaft.torsional_stiffness, 0.0, 0.0)  # massless: one span
    e, g = shaft.material.E, shaft.material.G
    area, second = shaft.area, shaft.second_moment
    shear = shaft.shear_factor * g * area
    return tuple(v / span for v in (e * area, shear, shear, g * 2.0 * second, e * second,
                                    e * second))


def transfer(point, origin) -> FloatArray:
    """(6, 6): global (δ, φ) of a body's reference point ``origin`` -> (δ, φ) of its
    material point at ``point``: δ + φ × (point − origin), φ."""
    d = np.asarray(point, dtype=float) - np.asarray(origin, dtype=float)
    out = np.eye(6)
    out[:3, 3:] = [[0.0, d[2], -d[1]], [-d[2], 0.0, d[0]], [d[1], -d[0], 0.0]]  # −[d]×
    return out


def _elements(system: System) -> None:
    index = {b.name: k for k, b in enumerate(system.bodies)}
    per = system.per_body
    dofs, maps, stiffness, damping, rigid = [], [], [], [], []
    for element in system.elements:
        rotate = np.zeros((6, 6))
        rotate[:3, :3] = rotate[3:, 3:] = np.array(frame(element.axis))  # rows e1, e2, e3
        blocks, where = [], []
        for sign, name in zip((-1.0, 1.0), element.ends):
            if name == FRAME:
                continue
            k = index[name]
            body = system.bodies[k]
            blocks.append(sign * rotate @ transfer(element.point, body.position)
                          @ system.to_global(k))
            where.append(np.arange(k * per, (k + 1) * per))
        s = np.hstack(blocks)
        k_e, c_e = np.array(element.stiffness), np.array(element.damping)
        acting = np.ones(6, dtype=bool) if per == 6 else np.arange(6) == 3
        rigid.append((k_e == RIGID) & acting)
        k_e = np.where(k_e == RIGID, 0.0, k_e)  # a rigid direction is a constraint, not a spring
        if per == 1:  # torsional model: the rotation about the element's axis only
            k_e, c_e = k_e * acting, c_e * acting
        idx = np.concatenate(where)
        system.stiffness[np.ix_(idx, idx)] += s.T @ (k_e[:, None] * s)
        system.damping[np.ix_(idx, idx)] += s.T @ (c_e[:, None] * s)
        dofs.append(idx)
        maps.append(s)
        stiffness.append(k_e)
        damping.append(c_e)
    system.element_dofs, system.element_maps = tuple(dofs), tuple(maps)
    system.element_stiffness = np.array(stiffness).reshape(-1, 6)
    system.element_damping = np.array(damping).reshape(-1, 6)
    system.element_rigid = np.array(rigid, dtype=bool).reshape(-1, 6)


def _meshes(system: System) -> None:
    drive = system.drive
    label = os.path.basename(drive.source) if drive.source else "gear drive"
    rows, normals, ideal = [], [], []
    for k, mesh in enumerate(drive.meshes):
        p, r = drive.gear(mesh.driving), drive.gear(mesh.driven)
        bp, br = drive.body(p.body), drive.body(r.body)
        normal, pitch = plane_of_action(p, mesh, bp.axis)
        length = math.sqrt(sum(c * c for c in normal))
        if abs(length - 1.0) > UNIT_TOL:
            raise AssertionError(f"mesh {mesh.name}: |n| = {length!r} is not 1")  # a bug, not input
        # the pitch point from each body's reference point, by the gears' geometry (the
        # torsional model places no bodies): driving d_p, driven d_p − (r_p + r_r)·Z2 + …
        driven = add(pitch, mesh_step(p, r, mesh, bp.axis, br.axis), -1.0)
        row = np.zeros(system.size)
        for sign, body, arm in ((1.0, bp, pitch), (-1.0, br, driven)):
            i = system.index(body.name)
            at_point = transfer(arm, (0.0, 0.0, 0.0)) @ system.to_global(i)
            row[system.dofs_of(body.name)] += sign * (np.asarray(normal) @ at_point[:3])
        rows.append(row)
        normals.append(normal)
        if mesh.stiffness is None:
            ideal.append(k)
        else:
            system.stiffness += mesh.stiffness * np.outer(row, row)
            system.damping += mesh.damping * np.outer(row, row)
    n = system.size
    system.mesh_rows = np.array(rows).T.reshape(n, -1)
    system.normals = np.array(normals).reshape(-1, 3)
    system.ideal = tuple(ideal)
    system.senses = np.array([float(m.rotation or 1) for m in drive.meshes])
    system.constraints = system.mesh_rows[:, ideal]


def _supports(system: System) -> None:
    """The rigid directions of elements and bearings as columns of g after the ideal
    meshes' (the row of the element's map S in that direction: its deformation there is
    0), then the check that gᵀM⁻¹g is invertible: each constraint must fix a motion the
    ones before it do not."""
    drive = system.drive
    label = os.path.basename(drive.source) if drive.source else "gear drive"
    n = system.size
    supports, columns = [], []
    for e, directions in enumerate(system.element_rigid):
        for d in np.flatnonzero(directions):
            column = np.zeros(n)
            column[system.element_dofs[e]] = system.element_maps[e][d]
            supports.append((e, int(d)))
            columns.append(column)
    system.supports = tuple(supports)
    if columns:
        system.constraints = np.hstack([system.constraints, np.array(columns).T])
    scaled = system.constraints / np.sqrt(system.mass)[:, None]
    if not scaled.shape[1]:
        return
    _, triangle = np.linalg.qr(scaled)
    left = np.abs(np.diag(triangle)) / np.linalg.norm(scaled, axis=0)
    for column, share in enumerate(left):
        if share >= RANK_RTOL:
            continue
        if column < len(system.ideal):
            k = system.ideal[column]
            raise InputError.in_file(label, f"mesh.{k + 1}", "constrains a motion that the "
                                     "meshes before it already fix (gᵀM⁻¹g is singular): "
                                     "remove it, or make it elastic with `stiffness`.",
                                     source=drive.source)
        e, d = system.supports[column - len(system.ideal)]
        element = system.elements[e]
        raise InputError.in_file(label, element.owner or element.name,
                                 f"is \"rigid\" in {DOFS[d]}, a motion that the meshes and rigid "
                                 f"directions before it already fix (the constraints are "
                                 f"dependent): give that direction a stiffness, or leave it "
                                 f"free (0).", source=drive.source)
