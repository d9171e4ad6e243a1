"""Forced response: the reduced solution against a direct complex solve of the full
equations with their multipliers, and against a time integration (scipy)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lsim

import dyade
from dyade.vibration.gears.assembly import assemble
from dyade.vibration.gears.modes import NullSpace, multipliers
from dyade.vibration.gears.response import excitation_vectors
from tests.vibration.gears.drives import build, single_stage
from tests.helpers import shipped


def _direct(system, f, p, e):
    """[[K + iωL − ω²M, −g], [gᵀ, 0]]·[q; λ] = [P; e] for the ideal meshes, with the
    transmission error of an elastic mesh as a force (k + iωc)·w·e; K and L summed here
    from the elements' maps and the elastic meshes' rows, not taken from the assembly."""
    n, l = system.constraints.shape
    w = 2 * np.pi * f
    z = -w ** 2 * np.diag(system.mass).astype(complex)
    for e_map, dofs, k, c in zip(system.element_maps, system.element_dofs,
                                 system.element_stiffness, system.element_damping):
        z[np.ix_(dofs, dofs)] += e_map.T @ ((k + 1j * w * c)[:, None] * e_map)
    for j, mesh in enumerate(system.drive.meshes):
        if mesh.stiffness is not None:
            row = system.mesh_rows[:, j]
            z += (mesh.stiffness + 1j * w * mesh.damping) * np.outer(row, row)
    a = np.zeros((n + l, n + l), dtype=complex)
    a[:n, :n], a[:n, n:], a[n:, :n] = z, -system.constraints, system.constraints.T
    rhs = np.concatenate([p.astype(complex), e[list(system.ideal)]])
    for j, mesh in enumerate(system.drive.meshes):
        if mesh.stiffness is not None:
            rhs[:n] += (mesh.stiffness + 1j * w * mesh.damping) * system.mesh_rows[:, j] * e[j]
    x = np.linalg.solve(a, rhs)
    return x[:n], x[n:]


def _drives():
    elastic = single_stage(mesh={"stiffness": 5e8, "damping": 300.0}, damping=1e-5)
    elastic["excitation"] = [{"kind": "transmission_error", "mesh": "m", "amplitude": 1e-5,
                              "phase": 30.0}, {"kind": "torque", "body": "load", "amplitude": 20}]
    return [dyade.read_gears(shipped("gears/two-stage.toml")), build(elastic)]


@pytest.mark.parametrize("drive", _drives(), ids=["two-stage", "elastic mesh"])
def test_response_equals_a_direct_solve_with_multipliers(drive):
    system = assemble(drive)
    frequencies = np.array([3.0, 79.0, 151.5, 400.0, 2500.0])
    response = dyade.gear_response(system, frequencies)
    p, e = excitation_vectors(system)
    assert np.any(p) and np.any(e)
    for k, f in enumerate(frequencies):
        q, lam = _direct(system, f, p, e)
        scale = np.max(np.abs(q))
        assert np.max(np.abs(response.solution[k] - q)) < 1e-9 * scale
        for j, mesh in enumerate(system.drive.meshes):
            if mesh.stiffness is None:
                column = system.ideal.index(j)
                expected = -system.senses[j] * lam[column]
            else:
                w = 2 * np.pi * f
                expected = system.senses[j] * (mesh.stiffness + 1j * w * mesh.damping) * (
                    system.mesh_rows[:, j] @ q - e[j])
            assert abs(response.mesh_forces[k, j] - expected) < 1e-9 * abs(expected)


def test_a_time_integration_reaches_the_same_steady_amplitude():
    """Integrate the reduced equations Nᵀ(M·q'' + L·q' + K·q) = NᵀP(t) from rest
    (scipy.signal.lsim: exact exponential steps, the force linear between 400 samples a
    period); after 60 periods (the slowest transient has decayed by e⁻¹⁴) the amplitude of
    the motor's rotation and of the mesh force over the last two periods equal the
    frequency-domain ones, and gᵀq stays at round-off (q = N·r satisfies the constraint
    by construction)."""
    data = single_stage(damping=1e-3)
    data["element"] = [{"bodies": ["load", "frame"], "stiffness": [0, 0, 0, 2e4, 0, 0],
                        "damping": [0, 0, 0, 20.0, 0, 0]}]  # the load held: no rigid mode
    data["excitation"] = [{"kind": "torque", "body": "motor", "amplitude": 40.0,
                           "phase": 40.0}]  # 40·cos(Ωt + 40°)
    system = assemble(build(data))
    f = 60.0
    response = dyade.gear_response(system, [f], coordinates=["motor.rx"])
    null = NullSpace.of(system.constraints)
    n = null.matrix()
    m, c, k = (n.T @ a @ n for a in (np.diag(system.mass), system.damping, system.stiffness))
    p, _ = excitation_vectors(system)
    size = n.shape[1]
    minv = np.linalg.inv(m)
    a = np.block([[np.zeros((size, size)), np.eye(size)], [-minv @ k, -minv @ c]])
    torque = np.zeros(system.size)
    torque[system.coordinate("motor", "rx")] = 40.0
    b = np.concatenate([np.zeros(size), minv @ (n.T @ torque)])[:, None]
    t = np.arange(60 * 400 + 1) / (400 * f)
    forcing = np.cos(2 * np.pi * f * t + np.radians(40.0))
    _, _, states = lsim((a, b, np.eye(2 * size), np.zeros((2 * size, 1))), forcing, t)
    q = n @ states[-801:, :size].T  # the last two periods
    motor = q[system.coordinate("motor", "rx")]
    # amplitude and phase: the signal is Re(x̂·e^{iΩt})
    steady = (response.displacement[0, 0] * np.exp(2j * np.pi * f * t[-801:])).real
    assert np.max(np.abs(motor - steady)) < 1e-4 * abs(response.displacement[0, 0])
    lam = multipliers(system, system.stiffness @ q + system.damping @ (n @ states[-801:, size:].T)
                      - np.outer(torque, forcing[-801:]))
    # the inertia term of eq. (27) vanishes: gᵀM⁻¹·M·q'' = gᵀq'' = 0
    assert (lam.max() - lam.min()) / 2 == pytest.approx(abs(response.mesh_forces[0, 0]),
                                                        rel=1e-4)
    drift = np.abs(system.constraints.T @ q) / (np.linalg.norm(system.constraints) *
                                                np.max(np.abs(q)))
    assert np.max(drift) < 1e-14


def test_no_response_at_zero_frequency_when_the_drive_turns_freely():
    response = dyade.gear_response(dyade.read_gears(shipped("gears/two-stage.toml")), [0.0, 5.0])
    assert response.unbounded.tolist() == [True, False]
    assert np.all(np.isnan(response.displacement[0]))
    assert np.all(np.isfinite(response.displacement[1]))


def test_an_empty_frequency_list_gives_empty_results_in_full_coordinates():
    drive = dyade.read_gears(shipped("gears/two-stage.toml"))
    empty, one = dyade.gear_response(drive, []), dyade.gear_response(drive, [5.0])
    assert empty.displacement.shape == (0,) + one.displacement.shape[1:]


def test_the_radial_force_is_the_largest_over_a_cycle():
    """The semi-major axis of the ellipse (Re(a·e^{iΩt}), Re(b·e^{iΩt})), against a
    brute-force maximum over a cycle."""
    from dyade.vibration.gears.response import Response

    rng = np.random.default_rng(5)
    forces = rng.standard_normal((4, 3, 6)) + 1j * rng.standard_normal((4, 3, 6))
    response = Response(np.arange(4.0), (), np.zeros((4, 0)), np.zeros((4, 0)), (),
                        ("a", "b", "c"), forces, np.zeros(4, bool), np.zeros((4, 0)))
    phase = np.exp(1j * np.linspace(0, 2 * np.pi, 200001))
    y = (forces[..., 1, None] * phase).real
    z = (forces[..., 2, None] * phase).real
    assert np.allclose(response.radial(), np.sqrt(y ** 2 + z ** 2).max(axis=-1), rtol=1e-9)
