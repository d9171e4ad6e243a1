"""Forced response of a gear drive to harmonic torques and transmission errors, and its
statics.

Every excitation of the file acts at the frequency f of the sweep with its amplitude and
phase (the `order` and `frequency` keys place it on the Campbell diagram; the sweep is a
frequency response to the file's pattern of excitations). A torque T̂ acts about its
body's axis; a transmission error ê at an ideal mesh makes the constraint gᵀq = e, and at
an elastic mesh it is a displacement in series with the mesh spring. With
Z(ω) = K + iω·L − ω²·M, the response is q = N·r + q_e (q_e = g(gᵀg)⁻¹e, gᵀq_e = e),

    NᵀZN·r = Nᵀ(P − Z·q_e),

solved for all frequencies at once (batched ``numpy.linalg.solve``), and the dynamic
mesh forces follow from the multipliers λ = (gᵀM⁻¹g)⁻¹gᵀM⁻¹(Z·q − P) (compression
positive: F = −λ), the bearing forces from the bearings' stiffness and damping.

Statics (ω = 0) needs balanced loads when the drive can turn freely: torques that would
spin a rigid-body mode are refused.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.limits import BYTES_PER_VALUE, check_memory
from dyade.model.gears import DOFS, FRAME, GearDrive, frame
from dyade.vibration.gears.assembly import System, assemble
from dyade.vibration.gears.modes import (Modes, NullSpace, gear_modes, multipliers, rigid_modes,
                                         sizeless)

BATCH_BYTES = 32e6  # [B] complex matrices solved at once
BALANCE_RTOL = 1e-9  # [-] loads with more than this share on a rigid-body mode: unbalanced


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Response:
    """Complex amplitudes over frequency: x(t) = Re(x̂·e^{iΩt})."""

    frequencies: FloatArray
    """(F,) [Hz]"""
    coordinates: tuple[tuple[str, str], ...]
    """(body, dof) of the columns of ``displacement``"""
    displacement: np.ndarray
    """(F, c) complex amplitudes [m or rad]"""
    mesh_forces: np.ndarray
    """(F, meshes) complex dynamic mesh forces along n, compression positive [N]"""
    mesh_names: tuple[str, ...]
    supports: tuple[str, ...]
    """the bearings and frame-connected elements of ``support_forces``"""
    support_forces: np.ndarray
    """(F, supports, 6) complex forces and moments each support transmits to the frame,
    in its own axes (x along its axis) [N, N·m]"""
    unbounded: np.ndarray
    """(F,) bool: no finite response (f = 0 with a rigid-body mode, or an undamped
    resonance hit exactly); NaN there"""
    solution: np.ndarray
    """(F, n) every coordinate"""

    def radial(self) -> FloatArray:
        """(F, supports) the largest radial force over a cycle [N]: the semi-major axis of
        the ellipse the two radial components trace."""
        a, b = self.support_forces[..., 1], self.support_forces[..., 2]
        return np.sqrt((np.abs(a) ** 2 + np.abs(b) ** 2 + np.abs(a * a + b * b)) / 2.0)


def excitation_vectors(system: System) -> tuple[np.ndarray, np.ndarray]:
    """(P, e): complex generalized forces (n,) and mesh transmission errors (meshes,) of
    the drive's excitations at unit frequency response."""
    drive = system.drive
    load = np.zeros(system.size, dtype=complex)
    error = np.zeros(len(drive.meshes), dtype=complex)
    names = {m.name: k for k, m in enumerate(drive.meshes)}
    for excitation in drive.excitations:
        phasor = excitation.amplitude * np.exp(1j * excitation.phase)
        if excitation.kind == "torque":
            load[system.coordinate(excitation.target, "rx")] += phasor
        else:
            error[names[excitation.target]] += phasor
    return load, error


def _coordinates(system: System, coordinates) -> tuple[tuple[str, str], ...]:
    if coordinates is None:
        return tuple((b.name, "rx") for b in system.drive.bodies)
    out = []
    for item in coordinates:
        body, _, dof = item.partition(".") if isinstance(item, str) else (item[0], "", item[1])
        if body not in {b.name for b in system.bodies} or dof not in DOFS:
            raise InputError.parameter("coordinates", f"names {item!r}: give BODY.DOF with a "
                                                      f"body of the drive and DOF one of "
                                                      f"{', '.join(DOFS)}.", value=item)
        system.coordinate(body, dof)  # the torsional model has rx only
        out.append((body, dof))
    return tuple(out)


def response_size(system: System, frequencies: int, coordinates: int) -> float:
    """What a forced response at ``frequencies`` frequencies takes [B], before anything
    is solved: the complex amplitudes of the coordinates, meshes and supports (two table
    columns each: amplitude and phase) and the reduced right-hand sides."""
    supports = sum(e.ends[1] == FRAME for e in system.elements)
    columns = 1 + 2 * (coordinates + len(system.drive.meshes) + 6 * supports)
    return (BYTES_PER_VALUE * columns + 16.0 * system.size) * frequencies + (50 << 20)


def gear_response(drive: GearDrive | System, frequencies, *, coordinates=None,
                  load: np.ndarray | None = None, error: np.ndarray | None = None,
                  max_memory: float | None = None) -> Response:
    """Forced response to the drive's excitations, over ``frequencies`` [Hz].

    Parameters
    ----------
    drive : GearDrive or System
    frequencies : array_like
        [Hz], ≥ 0.
    coordinates : list of str, optional
        "BODY.DOF" (DOF one of ux, uy, uz, rx, ry, rz, in the body's own axes) to report;
        default: rx of every body of the file.
    load, error : ndarray, optional
        Complex generalized forces (n,) and transmission errors per mesh instead of the
        file's excitations.
    max_memory : float, optional
        Bound on what the response may take [B] (default ``dyade.limits.MAX_MEMORY``),
        checked before anything is solved.

    Returns
    -------
    Response
        Complex amplitudes of the coordinates, dynamic mesh forces and support forces.

    Examples
    --------
    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> response = dyade.gear_response(drive, [50.0, 100.0])
    >>> [round(float(abs(f))) for f in response.mesh_forces[:, 0]]      # stage 1 [N]
    [100, 122]
    """
    system = drive if isinstance(drive, System) else assemble(drive)
    freq = np.atleast_1d(np.asarray(frequencies, dtype=float))
    if freq.ndim != 1 or not np.all(np.isfinite(freq)) or np.any(freq < 0):
        raise InputError.parameter("frequencies", "must be finite and ≥ 0 [Hz].", unit="Hz")
    picked = _coordinates(system, coordinates)
    check_memory(response_size(system, freq.size, len(picked)),
                 f"a response at {freq.size:,} frequencies", max_memory,
                 "Ask for fewer frequencies (a larger step or a shorter range)")
    p, e = excitation_vectors(system)
    p = p if load is None else np.asarray(load, dtype=complex)
    e = e if error is None else np.asarray(error, dtype=complex)
    omega = 2.0 * np.pi * freq
    g, ideal = system.constraints, list(system.ideal)
    elastic = [k for k in range(len(system.drive.meshes)) if k not in system.ideal]
    null = NullSpace.of(g)
    e_ideal = np.concatenate([e[ideal], np.zeros(len(system.supports))])  # supports: gᵀq = 0
    fixed = g @ np.linalg.solve(g.T @ g, e_ideal) if ideal else np.zeros(system.size)
    k, c, m = system.stiffness, system.damping, np.diag(system.mass)
    k_r, c_r, m_r = null.reduce(k), null.reduce(c), null.reduce(m)
    # right-hand side: P + (k_m + iω·c_m)·w·e at elastic meshes − Z·q_e
    rhs = np.tile(p, (freq.size, 1))
    for j in elastic:
        mesh = system.drive.meshes[j]
        rhs += np.outer(mesh.stiffness + 1j * omega * mesh.damping, system.mesh_rows[:, j] * e[j])
    rhs -= (k @ fixed)[None, :] + 1j * omega[:, None] * (c @ fixed)[None, :] - (
        omega[:, None] ** 2) * (m @ fixed)[None, :]
    reduced_rhs = null.project(rhs.T).T  # Nᵀ·rhs for every frequency at once
    size = null.size
    unbounded = np.zeros(freq.size, dtype=bool)
    if rigid_modes(system).shape[1]:
        unbounded |= freq == 0.0
    r = np.full((freq.size, size), np.nan, dtype=complex)
    batch = max(1, int(BATCH_BYTES // (16 * size * size)))
    for start in range(0, freq.size, batch):  # batches bound the memory, not a loop per f
        part = slice(start, start + batch)
        w = omega[part]
        z = k_r[None] + 1j * w[:, None, None] * c_r[None] - (w ** 2)[:, None, None] * m_r[None]
        good = ~unbounded[part]
        try:
            r[part][good] = np.linalg.solve(z[good], reduced_rhs[part][good][..., None])[..., 0]
        except np.linalg.LinAlgError:  # an undamped resonance hit exactly: find which
            for i in np.flatnonzero(good):
                try:
                    r[start + i] = np.linalg.solve(z[i], reduced_rhs[start + i])
                except np.linalg.LinAlgError:
                    unbounded[start + i] = True
    q = null.expand(r.T).T + fixed[None, :]  # N·r for every frequency at once
    q[unbounded] = np.nan
    # dynamic mesh forces: F = −λ (ideal), (k + iωc)(w·q − e) (elastic)
    forces = np.zeros((freq.size, len(system.drive.meshes)), dtype=complex)
    reactions = np.zeros((freq.size, g.shape[1]), dtype=complex)
    if g.shape[1]:
        z_q = (q @ k.T) + 1j * omega[:, None] * (q @ c.T) - (omega[:, None] ** 2) * (q * system.mass)
        reactions = multipliers(system, (z_q - p[None, :]).T).T
        forces[:, ideal] = -reactions[:, :len(ideal)]
    for j in elastic:
        mesh = system.drive.meshes[j]
        forces[:, j] = (mesh.stiffness + 1j * omega * mesh.damping) * (q @ system.mesh_rows[:, j]
                                                                      - e[j])
    forces *= system.senses[None, :]
    forces[:, sizeless(system)] = np.nan  # per unit module: not in newtons
    supports, support_forces = _support_forces(system, q, omega, reactions)
    columns = [system.coordinate(body, dof) for body, dof in picked]
    return Response(freq, picked, q[:, columns], forces,
                    tuple(m.name for m in system.drive.meshes), supports, support_forces,
                    unbounded, q)


def _support_forces(system: System, q: np.ndarray, omega: FloatArray, reactions: np.ndarray
                    ) -> tuple[tuple[str, ...], np.ndarray]:
    """The force and moment each frame-connected element transmits to the frame, in its
    own axes: (k + iωc)·(the body's displacement at it), and in a rigid direction the
    constraint's multiplier λ (``reactions``: (positions, columns of g)), which takes the
    place of −k·Δ in the equations."""
    names, out = [], []
    offset = len(system.ideal)
    for e, element in enumerate(system.elements):
        if element.ends[1] != FRAME:
            continue
        deform = q[:, system.element_dofs[e]] @ system.element_maps[e].T  # Δ = −(body at point)
        coefficient = system.element_stiffness[e][None, :] + 1j * omega[:, None] * (
            system.element_damping[e][None, :])
        force = -coefficient * deform
        for column, (owner, d) in enumerate(system.supports, offset):
            if owner == e:
                force[:, d] = reactions[:, column]
        names.append(element.name)
        out.append(force)
    return tuple(names), np.stack(out, axis=1) if out else np.zeros((q.shape[0], 0, 6), complex)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Statics:
    """The static deflection under constant torques."""

    displacement: FloatArray
    """(n,) every coordinate [m, rad]; no component along the rigid-body modes"""
    mesh_forces: FloatArray
    """(meshes,) along n, compression positive [N]"""
    supports: tuple[str, ...]
    forces: FloatArray
    """(supports, 3) force of the frame on the drive at each support, global [N]"""
    moments: FloatArray
    """(supports, 3) moment of the frame on the drive at each support, global [N·m]"""
    points: FloatArray
    """(supports, 3) where each support acts [m]"""


def gear_statics(drive: GearDrive | System, torques: dict[str, float], *,
                 modes: Modes | None = None) -> Statics:
    """The static deflection, mesh forces and support reactions under constant torques
    about the bodies' axes.

    Parameters
    ----------
    drive : GearDrive or System
    torques : dict
        body name -> torque about its axis [N·m] (right-hand rule). On a drive that can
        turn freely they must balance through the gear ratios.
    modes : Modes, optional
        ``gear_modes(drive)``, if already computed.

    Returns
    -------
    Statics

    Examples
    --------
    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> statics = dyade.gear_statics(drive, {"load": -1000.0, "motor": 1000.0 / 10.5})
    >>> [round(float(f)) for f in statics.mesh_forces]        # T/r_b of each stage [N]
    [2534, 6081]
    """
    system = drive if isinstance(drive, System) else assemble(drive)
    modes = modes if modes is not None else gear_modes(system)
    load = np.zeros(system.size)
    for body, torque in torques.items():
        if body not in {b.name for b in system.drive.bodies}:
            raise InputError.parameter("torques", f"names no body of the drive: {body!r}.")
        load[system.coordinate(body, "rx")] += float(torque)
    rigid = modes.rigid
    if rigid.shape[1] and np.max(np.abs(rigid.T @ load)) > BALANCE_RTOL * np.linalg.norm(load) * (
            np.max(np.abs(rigid))):
        raise InputError.parameter("torques", "do not balance: the drive turns freely and they "
                                              "would accelerate it (a rigid-body mode); add the "
                                              "reaction torque at the input (T_in = T_out / "
                                              "ratio, opposite in sense).")
    if np.any(modes.unresolved):
        raise InputError.parameter("drive", "has modes too soft to resolve: no statics.")
    shapes = modes.shapes
    q = shapes @ ((shapes.T @ load) / modes.eigenvalues)
    forces = np.zeros(len(system.drive.meshes))
    reactions = np.zeros((1, system.constraints.shape[1]))
    if system.constraints.shape[1]:
        reactions[0] = multipliers(system, system.stiffness @ q - load)
        forces[list(system.ideal)] = -reactions[0, :len(system.ideal)]
    for j, mesh in enumerate(system.drive.meshes):
        if mesh.stiffness is not None:
            forces[j] = mesh.stiffness * system.mesh_rows[:, j] @ q
    forces *= system.senses
    forces[sizeless(system)] = np.nan
    names, on_frame = _support_forces(system, q[None, :], np.zeros(1), reactions)
    supports = [e for e in system.elements if e.ends[1] == FRAME]
    axes = [np.array(frame(e.axis)).T for e in supports]  # element axes -> global
    reactions = -on_frame[0].real  # the frame on the drive, in each element's axes
    f = [a @ r[:3] for a, r in zip(axes, reactions)]
    mo = [a @ r[3:] for a, r in zip(axes, reactions)]
    at = [e.point for e in supports]
    return Statics(q, forces, tuple(names), np.array(f).reshape(-1, 3),
                   np.array(mo).reshape(-1, 3), np.array(at, dtype=float).reshape(-1, 3))
