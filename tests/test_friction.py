"""Coulomb friction and self-locking: limits, energy, a hand solution, convergence."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.linkage import sweep as analysis, friction, motion as joints, kinematics, kinetostatics, self_locking
from dyade.files import mechanism as toml_input
from dyade.cli import main
from dyade.linkage.model import Prismatic
from tests.conftest import SHIPPED
from tests.helpers import shipped
from tests.test_kinetostatics import applied_power, kinetic_energy_rate, with_masses


def with_friction(mechanism, mu, pin=0.005, length=0.04, height=0.02):
    """μ in every joint, with r_z, L, H."""
    def rub(joint):
        if isinstance(joint, Prismatic):
            return replace(joint, friction=mu, slider_length=length, slider_height=height)
        return replace(joint, friction=mu, pin_radius=pin)

    crank = replace(mechanism.crank, joint=rub(mechanism.crank.joint))
    dyads = tuple(replace(d, joints=tuple(rub(j) for j in d.joints)) for d in mechanism.dyads)
    return replace(mechanism, crank=crank, dyads=dyads)


def loaded(path, mu, gravity=(0.0, -9.81)):
    return with_friction(with_masses(toml_input.read_mechanism(path), gravity=gravity), mu)


def test_zero_friction_is_the_frictionless_solution_exactly():
    mechanism = loaded(shipped("dyade-16.toml"), 0.0)
    kin = kinematics.sweep(mechanism)
    plain = kinetostatics.solve(mechanism, kin)
    rubbed = friction.iterate(mechanism, kin)
    assert np.array_equal(plain.drive_torque, rubbed.forces.drive_torque)
    for name in plain.revolute:
        assert np.array_equal(plain.revolute[name], rubbed.forces.revolute[name])


def test_tiny_friction_tends_to_the_frictionless_solution():
    base = with_masses(toml_input.read_mechanism(shipped("dyade-16.toml")), gravity=(0, -9.81))
    kin = kinematics.sweep(base)
    plain = kinetostatics.solve(base, kin).drive_torque
    for mu, bound in ((1e-4, 1e-3), (1e-8, 1e-7)):
        rubbed = friction.iterate(with_friction(base, mu), kin).forces.drive_torque
        # the change is first order in μ: |ΔM| ≲ 10·μ·max|M|
        assert np.max(np.abs(rubbed - plain)) < bound * np.max(np.abs(plain))


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_energy_identity_with_friction_everywhere(path):
    # M_drive·Ω − dE/dt + P_loads = P_friction ≥ 0 at every crank position
    mechanism = replace(loaded(path, 0.1), friction_tol=1e-13, friction_max_iter=200)
    kin = kinematics.sweep(mechanism)
    result = friction.iterate(mechanism, kin)
    at_rest = np.zeros(kin.crank_angle.size, dtype=bool)
    for mask in result.at_rest.values():
        at_rest |= mask
    assert result.converged[~at_rest].all()
    balance = (result.forces.drive_torque * mechanism.crank.speed
               - kinetic_energy_rate(mechanism, kin.motion)
               + applied_power(mechanism, kin.motion, kin.crank_angle))
    scale = np.max(np.abs(result.forces.drive_torque * mechanism.crank.speed))
    assert np.allclose(balance, result.power, rtol=1e-8, atol=1e-8 * scale)
    assert np.all(result.power >= 0.0)
    assert np.mean(result.power) > 0.0


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_coulomb_law_holds_in_every_joint(path):
    # read back from the reported forces: |MR| = μ·r_z·|F| and |FR| = μ·|FN|, each
    # against the relative motion of the higher-numbered link
    mechanism = replace(loaded(path, 0.1), friction_tol=1e-13, friction_max_iter=200)
    kin = kinematics.sweep(mechanism)
    result = friction.iterate(mechanism, kin)
    ok = kin.valid
    for joint in mechanism.joints:
        lower, higher = sorted(joint.links)
        if isinstance(joint, Prismatic):
            rubbing = result.friction_forces[joint.name][ok]
            size = 0.1 * np.abs(result.forces.normal[joint.name][ok])
            sliding = joints.travel(joint, kin.motion)[1][ok]
            relative = sliding if higher == joint.slider else -sliding
        else:
            rubbing = result.moments[joint.name][ok]
            size = 0.1 * 0.005 * np.hypot(*result.forces.revolute[joint.name][ok].T)
            relative = (kin.motion.omega[:, higher] - kin.motion.omega[:, lower])[ok]
        moving = ~result.at_rest[joint.name][ok]
        scale = max(float(np.max(size)), 1e-300)
        assert np.allclose(np.abs(rubbing[moving]), size[moving], rtol=1e-9, atol=1e-12 * scale)
        assert np.all(rubbing[moving] * relative[moving] <= 0.0)


def test_friction_columns_follow_the_joint_order():
    from dyade.linkage import columns

    mechanism = loaded(shipped("dyade-16.toml"), 0.1)
    names = list(columns.columns(analysis.run(mechanism)))
    rubbing = [name for name in names if name.startswith(("MR_", "FR_"))]
    expected = ([f"MR_{i}_{j}" for i, j in (k.name for k in mechanism.joints
                                           if not isinstance(k, Prismatic))]
                + [f"FR_{i}_{j}" for i, j in (k.name for k in mechanism.joints
                                             if isinstance(k, Prismatic))])
    assert rubbing == expected


def test_scotch_yoke_by_hand():
    # yoke (m) slides on a horizontal frame guide with μ; slot and pins frictionless:
    # FN = m·g, slot force N = m·a_x + μ·m·g·sign(v), M_drive = −r·sin φ·N
    #   = m·r²·Ω²·sin φ·cos φ + μ·m·g·r·|sin φ|
    mechanism = toml_input.read_mechanism(shipped("scotch-yoke.toml"), overrides={
        "gravity": True, "links.3.mass": 2.0, "dyad.2.A.friction": 0.2,
        "dyad.2.A.slider_length": 40.0, "dyad.2.A.slider_height": 20.0})
    result = analysis.run(mechanism)
    assert result.plan.friction == ((1, 3),)
    phi = result.crank_angle
    m, r, omega, mu, g = 2.0, 0.05, mechanism.crank.speed, 0.2, 9.80665
    expected = m * r ** 2 * omega ** 2 * np.sin(phi) * np.cos(phi) + mu * m * g * r * np.abs(np.sin(phi))
    assert np.allclose(result.forces.drive_torque, expected, rtol=1e-9, atol=1e-9 * np.max(np.abs(expected)))
    fr = result.friction.friction_forces[(1, 3)]  # on the yoke, along +x
    v = -r * omega * np.sin(phi)
    moving = np.abs(v) > 1e-9
    assert np.allclose(fr[moving], -mu * m * g * np.sign(v[moving]), rtol=1e-9)
    assert result.friction.at_rest[(1, 3)].sum() == 3  # 0°, 180°, 360°


def test_iterations_grow_as_the_tolerance_shrinks():
    mechanism = loaded(shipped("dyade-16.toml"), 0.1)
    kin = kinematics.sweep(mechanism)
    counts, torques = [], []
    for tol in (1e-3, 1e-6, 1e-9, 1e-12):
        result = friction.iterate(mechanism, kin, tol=tol)
        assert result.converged.all()
        assert np.max(result.residual) <= tol
        counts.append(result.iterations.mean())
        torques.append(result.forces.drive_torque)
    assert counts == sorted(counts) and counts[-1] > counts[0]
    # the answer settles: each tolerance step changes the torque less
    deltas = [np.max(np.abs(torques[k] - torques[-1])) for k in range(3)]
    assert deltas == sorted(deltas, reverse=True)


def test_not_converged_positions_are_reported():
    mechanism = replace(loaded(shipped("dyade-16.toml"), 0.1), friction_max_iter=2)
    result = analysis.run(mechanism)
    assert not result.friction.converged.all()
    assert any("did not converge" in note.text for note in result.notes)


def test_self_locking_example_locks_where_its_comment_says():
    result = analysis.run(toml_input.read_mechanism(shipped("self-locking.toml")))
    locks = result.locking[(1, 4)].locks
    angles = np.rad2deg(result.crank_angle[locks])
    assert angles.min() == pytest.approx(271.0) and angles.max() == pytest.approx(319.0)
    assert np.all(np.diff(angles) == 1.0)  # one range
    assert any("locks (self-locking) at crank angles 271.0°–319.0°" in n.text for n in result.notes)


def test_low_friction_variant_does_not_lock():
    mechanism = toml_input.read_mechanism(shipped("self-locking.toml"),
                                          overrides={"friction.coefficient": 0.1})
    result = analysis.run(mechanism)
    assert not result.locking[(1, 4)].locks.any()
    assert np.all(result.locking[(1, 4)].margin[result.locking[(1, 4)].driving_force > 0] > 0)


def test_self_locking_exit_status():
    def run(*extra):  # exceptions propagate: exit code 1 must come from --fail-on-lock
        return CliRunner().invoke(main, args + list(extra), catch_exceptions=False)

    args = ["analyse", str(shipped("self-locking.toml")), "--format", "csv"]
    passing = run()
    assert passing.exit_code == 0
    failing = run("--fail-on-lock")
    assert failing.exit_code == 1
    assert "Error: a slider self-locks (see the warning above); --fail-on-lock was given." in failing.stderr
    assert "slider (1,4) locks (self-locking)" in failing.stderr
    header = passing.stdout.splitlines()[0].split(",")
    for name in ("MR_1_2", "MR_2_3", "MR_3_4", "FR_1_4", "P_friction", "friction_iterations",
                 "lock_margin_1_4"):
        assert name in header


def test_no_friction_no_friction_stage(monkeypatch):
    def must_not_run(*args, **kwargs):
        raise AssertionError("a stage ran that the file does not call for")

    monkeypatch.setattr(friction, "iterate", must_not_run)
    monkeypatch.setattr(self_locking, "test", must_not_run)
    result = analysis.run(toml_input.read_mechanism(shipped("dyade-16.toml")))
    assert result.forces is not None and result.friction is None
    out = CliRunner().invoke(main, ["analyse", str(shipped("slider-crank.toml")), "--format", "csv"],
                             catch_exceptions=False)
    assert "P_friction" not in out.stdout.splitlines()[0]


def test_pin_friction_only_skips_the_self_locking_test(monkeypatch):
    def must_not_run(*args, **kwargs):
        raise AssertionError("self-locking test ran without a slider with friction")

    monkeypatch.setattr(self_locking, "test", must_not_run)
    mechanism = toml_input.read_mechanism(shipped("slider-crank.toml"), overrides={
        "crank.friction": 0.1, "crank.pin_radius": 8.0})
    result = analysis.run(mechanism)
    assert result.plan.friction == ((1, 2),) and result.plan.self_locking == ()
    assert result.friction.moments[(1, 2)].any()


def test_friction_without_pin_radius_is_a_clear_error():
    with pytest.raises(toml_input.InputError, match=r"`crank.pin_radius` is missing: the joint has friction"):
        toml_input.read_mechanism(shipped("fourbar.toml"), overrides={"crank.friction": 0.1})


def test_describe_lists_friction_and_self_locking():
    out = CliRunner(env={"COLUMNS": "200"}).invoke(
        main, ["describe", str(shipped("self-locking.toml"))], catch_exceptions=False)
    text = " ".join(out.stdout.split())
    assert "Coulomb friction (iterated per dyad) in joints (1,2), (2,3), (3,4), (1,4)" in text
    assert "self-locking test for sliders (1,4)" in text
