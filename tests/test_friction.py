"""Coulomb friction: limits, energy, the laws read back, hand solutions, the direct
solution against the fixed-point iteration, convergence, notes and the command line.
(Self-locking: tests/test_self_locking.py.)"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.linkage import sweep as analysis, friction, motion as joints, kinematics, kinetostatics, self_locking
from dyade.files import mechanism as toml_input
from dyade.model.mechanism import Prismatic
from dyade.report.notes import say
from dyade.cli import main
from tests import fixed_point
from tests.conftest import SHIPPED
from tests.helpers import TEMPLATES, shipped
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


@pytest.mark.parametrize("method", [friction.solve, fixed_point.iterate], ids=["direct", "fixed-point"])
def test_zero_friction_is_the_frictionless_solution_exactly(method):
    mechanism = loaded(shipped("dyade-16.toml"), 0.0)
    kin = kinematics.sweep(mechanism)
    plain = kinetostatics.solve(mechanism, kin)
    rubbed = method(mechanism, kin)
    assert np.array_equal(plain.drive_torque, rubbed.forces.drive_torque)
    for name in plain.revolute:
        assert np.array_equal(plain.revolute[name], rubbed.forces.revolute[name])


def test_tiny_friction_tends_to_the_frictionless_solution():
    base = with_masses(toml_input.read_mechanism(shipped("dyade-16.toml")), gravity=(0, -9.81))
    kin = kinematics.sweep(base)
    plain = kinetostatics.solve(base, kin).drive_torque
    for mu, bound in ((1e-4, 1e-3), (1e-8, 1e-7)):
        rubbed = friction.solve(with_friction(base, mu), kin).forces.drive_torque
        # the change is first order in μ: |ΔM| ≲ 10·μ·max|M|
        assert np.max(np.abs(rubbed - plain)) < bound * np.max(np.abs(plain))


def assert_energy_balance(mechanism, kin, result, valid) -> None:
    """M_drive·Ω − dE/dt + P_loads = P_friction ≥ 0 at the ``valid`` positions."""
    balance = (result.forces.drive_torque * mechanism.crank.speed
               - kinetic_energy_rate(mechanism, kin.motion)
               + applied_power(mechanism, kin.motion, kin.crank_angle))
    scale = np.max(np.abs(result.forces.drive_torque[valid] * mechanism.crank.speed))
    assert np.allclose(balance[valid], result.power[valid], rtol=1e-8, atol=1e-8 * scale)
    assert np.all(result.power[valid] >= 0.0)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_energy_identity_with_friction_everywhere(path):
    # M_drive·Ω − dE/dt + P_loads = P_friction ≥ 0 at every valid crank position
    mechanism = replace(loaded(path, 0.1), friction_tol=1e-13)
    kin = kinematics.sweep(mechanism)
    result = friction.solve(mechanism, kin)
    valid = result.forces.valid
    assert valid.sum() > 0.8 * valid.size
    assert_energy_balance(mechanism, kin, result, valid)
    assert np.mean(result.power[valid]) > 0.0


def block_pressure(normal, tilt, length):
    """∫|p| dx over a block of length L of the linear pressure p(x) = FN/L + 12·M'·x/L³
    (x from the block's centre), integrated here by its zero: where p keeps its sign over
    the block |FN|, else the two triangles |p(−L/2)|·(x₀ + L/2)/2 + |p(L/2)|·(L/2 − x₀)/2."""
    normal, tilt = np.broadcast_arrays(np.asarray(normal, float), np.asarray(tilt, float))
    half = 0.5 * length
    left = normal / length - 12.0 * tilt * half / length ** 3
    right = normal / length + 12.0 * tilt * half / length ** 3
    with np.errstate(divide="ignore", invalid="ignore"):
        zero = -normal * length ** 2 / (12.0 * tilt)
    turns = (left * right < 0.0)
    split = np.where(turns, zero, 0.0)
    triangles = np.abs(left) * (split + half) / 2.0 + np.abs(right) * (half - split) / 2.0
    return np.where(turns, triangles, np.abs(normal))


def coulomb_law_errors(mechanism, kin, result, valid=None):
    """Per joint with friction: the largest |law − reported| relative to the law's
    size, and whether a friction load ever pushes along the relative motion, at the
    valid positions; read back from the reported forces: |MR| = μ·r_z·|F| and
    |FR| = μ·∫|p| dx (``block_pressure``), the reported M being the tilting moment M'."""
    ok = result.forces.valid if valid is None else valid
    out = {}
    for joint in mechanism.joints:
        if joint.friction == 0.0 or joint.name in result.never_moves:  # no law applies
            continue
        lower, higher = sorted(joint.links)
        if isinstance(joint, Prismatic):
            rubbing = result.friction_forces[joint.name][ok]
            normal = np.abs(result.forces.normal[joint.name][ok])
            tilt = np.abs(result.forces.moment[joint.name][ok])
            total = block_pressure(normal, tilt, joint.slider_length) if joint.edge_friction else normal
            size = joint.friction * total
            sliding = joints.travel(joint, kin.motion)[1][ok]
            relative = sliding if higher == joint.slider else -sliding
        else:
            rubbing = result.moments[joint.name][ok]
            size = joint.friction * joint.pin_radius * np.hypot(*result.forces.revolute[joint.name][ok].T)
            relative = (kin.motion.omega[:, higher] - kin.motion.omega[:, lower])[ok]
        moving = ~result.at_rest[joint.name][ok]
        scale = max(float(np.max(size, initial=0.0)), 1e-300)
        error = np.max(np.abs(np.abs(rubbing[moving]) - size[moving]), initial=0.0) / scale
        out[joint.name] = (error, bool(np.any(rubbing[moving] * relative[moving] > 0.0)))
    return out


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_coulomb_law_holds_in_every_joint(path):
    mechanism = replace(loaded(path, 0.1), friction_tol=1e-13)
    kin = kinematics.sweep(mechanism)
    result = friction.solve(mechanism, kin)
    for name, (error, wrong_sense) in coulomb_law_errors(mechanism, kin, result).items():
        assert error < 1e-9, name
        assert not wrong_sense, name


def test_friction_columns_follow_the_joint_order():
    mechanism = loaded(shipped("dyade-16.toml"), 0.1)
    names = list(analysis.analyse(mechanism).columns())
    rubbing = [name for name in names if name.startswith(("MR_", "FR_"))]
    expected = ([f"MR_{i}_{j}" for i, j in (k.name for k in mechanism.joints
                                           if not isinstance(k, Prismatic))]
                + [f"FR_{i}_{j}" for i, j in (k.name for k in mechanism.joints
                                             if isinstance(k, Prismatic))])
    assert rubbing == expected
    # new columns come after forces_valid: the determinant of every dyad, then the
    # reduced inertia and load torque (issue 18)
    tail = names[names.index("forces_valid") + 1:]
    assert tail == [f"friction_det_{dyad.number}" for dyad in mechanism.dyads] + [
        "J_red", "dJ_red", "M_load"]


def scotch_yoke(edges: bool):
    return toml_input.read_mechanism(shipped("scotch-yoke.toml"), overrides={
        "gravity": True, "links.3.mass": 2.0, "dyad.2.A.friction": 0.2,
        "dyad.2.A.slider_length": 40.0, "dyad.2.A.slider_height": 20.0,
        "dyad.2.A.edge_friction": edges})


def test_scotch_yoke_by_hand_without_edge_friction():
    # yoke (m) slides on a horizontal frame guide with μ; slot and pins frictionless:
    # FN = m·g, slot force N = m·a_x + μ·m·g·sign(v), M_drive = −r·sin φ·N
    #   = m·r²·Ω²·sin φ·cos φ + μ·m·g·r·|sin φ|
    mechanism = scotch_yoke(edges=False)
    result = analysis.analyse(mechanism)
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


def test_scotch_yoke_by_hand_with_edge_friction():
    # The slot force N acts on the yoke at the crank pin, y = r·sin φ above the guide,
    # so the guide carries the moment M = y·N and the tilting moment
    # u = M' = y·N + c₀, c₀ = ½·FN·H·μ·s (s = sign v, FN = m·g), and
    # N = m·a_x + μ·s·P(FN, u) with the block's total pressure P:
    #   6·|u| ≤ FN·L: P = FN, so N = m·a_x + μ·s·FN (and u follows);
    #   beyond, with σ = sign u: P = FN²·L/(12·σ·u) + 3·σ·u/L, and N = (u − c₀)/y turns
    #   the balance into the quadratic
    #   (1/y − 3·μ·s·σ/L)·u² − (c₀/y + m·a_x)·u − μ·s·σ·FN²·L/12 = 0.
    # Every candidate is checked for consistency (its region and its σ): exactly one is.
    mechanism = scotch_yoke(edges=True)
    result = analysis.analyse(mechanism)
    phi = result.crank_angle
    m, r, omega, mu, g, length, height = 2.0, 0.05, mechanism.crank.speed, 0.2, 9.80665, 0.04, 0.02
    v = -r * omega * np.sin(phi)
    s = np.where(np.abs(v) > 1e-9, np.sign(v), 0.0)
    y, a_x, normal = r * np.sin(phi), -r * omega ** 2 * np.cos(phi), m * g
    c0 = 0.5 * normal * height * mu * s
    candidates = []
    inner = m * a_x + mu * s * normal  # the pressure keeps its sign
    tilt = y * inner + c0
    candidates.append((inner, 6.0 * np.abs(tilt) <= normal * length))
    with np.errstate(divide="ignore", invalid="ignore"):
        for sigma in (1.0, -1.0):
            a = 1.0 / y - 3.0 * mu * s * sigma / length
            b = -(c0 / y + m * a_x)
            c = -mu * s * sigma * normal ** 2 * length / 12.0
            root = np.sqrt(b * b - 4.0 * a * c)
            for u in ((-b + root) / (2.0 * a), (-b - root) / (2.0 * a)):
                ok = (np.sign(u) == sigma) & (6.0 * np.abs(u) > normal * length) & (y != 0.0)
                candidates.append(((u - c0) / y, ok))
    count = sum(ok.astype(int) for _, ok in candidates)
    assert np.all(count == 1)
    force = sum(np.where(ok, n, 0.0) for n, ok in candidates)
    expected = -r * np.sin(phi) * force
    assert np.allclose(result.forces.drive_torque, expected, rtol=1e-9, atol=1e-9 * np.max(np.abs(expected)))
    tilt = y * force + c0  # M' on the yoke, as reported
    assert np.allclose(result.forces.moment[(1, 3)], tilt, rtol=1e-9, atol=1e-12)
    fr = result.friction.friction_forces[(1, 3)]
    total = block_pressure(normal, tilt, length)
    assert np.allclose(fr, -mu * s * total, rtol=1e-9, atol=1e-12)
    plain = analysis.analyse(scotch_yoke(edges=False)).forces.drive_torque
    assert np.max(np.abs(result.forces.drive_torque - plain)) > 0.1  # the edges matter here
    # both regions occur: near the dead centres (y → 0) the pressure keeps its sign
    inside = 6.0 * np.abs(tilt) <= normal * length
    assert inside.any() and (~inside).any()


def test_iterations_grow_as_the_tolerance_shrinks():
    mechanism = loaded(shipped("dyade-16.toml"), 0.1)
    kin = kinematics.sweep(mechanism)
    counts, torques = [], []
    for tol in (1e-3, 1e-6, 1e-9, 1e-12):
        result = fixed_point.iterate(mechanism, kin, tol=tol, max_iter=200)
        assert result.converged.all()
        assert np.max(result.residual) <= tol
        counts.append(result.iterations.mean())
        torques.append(result.forces.drive_torque)
    assert counts == sorted(counts) and counts[-1] > counts[0]
    # the answer settles: each tolerance step changes the torque less
    deltas = [np.max(np.abs(torques[k] - torques[-1])) for k in range(3)]
    assert deltas == sorted(deltas, reverse=True)


def test_direct_solution_converges_quadratically():
    # Newton: the error squares with every pass, so a millionfold tighter tolerance
    # costs at most two more passes, where the fixed-point iteration needs many
    mechanism = loaded(shipped("dyade-16.toml"), 0.1)
    kin = kinematics.sweep(mechanism)
    passes = [friction.solve(mechanism, kin, tol=tol).iterations.max() for tol in (1e-6, 1e-12)]
    steps = [fixed_point.iterate(mechanism, kin, tol=tol, max_iter=200).iterations.max()
             for tol in (1e-6, 1e-12)]
    assert passes[0] <= 4 and passes[1] - passes[0] <= 2
    assert steps[1] - steps[0] >= 4


def agreement_cases():
    """(label, mechanism): the shipped files and the slotted-lever template with μ = 0.1
    and 0.3 everywhere, and the self-locking press slide as shipped with μ = 0.1 (with
    the test's slider sizes its iteration diverges nearly everywhere)."""
    for path in SHIPPED + [TEMPLATES / "slotted-lever.toml"]:
        if path.stem == "self-locking":
            yield path.stem, toml_input.read_mechanism(path, {"friction.coefficient": 0.1})
            continue
        for mu in (0.1, 0.3):
            yield f"{path.stem}-{mu}", loaded(path, mu)


@pytest.mark.parametrize("label, mechanism", list(agreement_cases()),
                         ids=[label for label, _ in agreement_cases()])
def test_fixed_point_iteration_agrees_with_the_direct_solution(label, mechanism):
    # two independent algorithms for the same laws: wherever the iteration converges
    # (it diverges towards self-locking, and wherever an eigenvalue of K passes ±1)
    # they agree
    kin = kinematics.sweep(mechanism)
    direct = friction.solve(mechanism, kin, tol=1e-13)
    fixed = fixed_point.iterate(mechanism, kin, tol=1e-14, max_iter=400)
    both = fixed.converged & direct.converged & kin.valid
    assert both.sum() > 0.3 * both.size
    for name, (link, wrench) in direct.forces.wrenches.items():
        other = fixed.forces.on(name, link)
        scale = np.max(np.abs(other[:2, both]))
        assert np.max(np.abs(wrench[:, both] - other[:, both])) <= 1e-9 * scale, name
    assert not (fixed.converged & direct.locked).any()


def test_unsolved_positions_are_reported_and_blanked():
    mechanism = replace(loaded(shipped("dyade-16.toml"), 0.1), friction_max_iter=1)
    result = analysis.analyse(mechanism)
    unsolved = result.friction.unsolved
    assert unsolved.any() and not result.friction.converged[unsolved].any()
    note, = [note for note in result.notes if note.kind == "friction_not_converged"]
    assert "no consistent friction solution was found in 1 passes" in say(note, mechanism)
    cols = result.columns()
    assert np.all(cols["forces_valid"][unsolved] == 0.0)
    assert np.isnan(cols["M_drive"][unsolved]).all() and np.isnan(cols["F_3_4"][unsolved]).all()


def test_no_friction_no_friction_stage(monkeypatch):
    def must_not_run(*args, **kwargs):
        raise AssertionError("a stage ran that the file does not call for")

    monkeypatch.setattr(friction, "solve", must_not_run)
    monkeypatch.setattr(self_locking, "test", must_not_run)
    result = analysis.analyse(toml_input.read_mechanism(shipped("dyade-16.toml")))
    assert result.forces is not None and result.friction is None
    out = CliRunner().invoke(main, ["analyse", str(shipped("slider-crank.toml")), "--format", "csv"],
                             catch_exceptions=False)
    assert "P_friction" not in out.stdout.splitlines()[0]


def test_pin_friction_only_skips_the_slider_margin(monkeypatch):
    def must_not_run(*args, **kwargs):
        raise AssertionError("slider margins computed without a slider with friction")

    monkeypatch.setattr(self_locking, "test", must_not_run)
    mechanism = toml_input.read_mechanism(shipped("slider-crank.toml"), overrides={
        "crank.friction": 0.1, "crank.pin_radius": 8.0})
    result = analysis.analyse(mechanism)
    assert result.plan.friction == ((1, 2),) and result.plan.self_locking == ()
    assert result.friction.moments[(1, 2)].any()
    assert not any(name.startswith("lock_margin") for name in result.columns())


def test_friction_without_pin_radius_is_a_clear_error():
    with pytest.raises(toml_input.InputError, match=r"`crank.pin_radius` is missing: the joint has friction"):
        toml_input.read_mechanism(shipped("fourbar.toml"), overrides={"crank.friction": 0.1})


def test_describe_lists_friction_and_self_locking():
    out = CliRunner(env={"COLUMNS": "200"}).invoke(
        main, ["describe", str(shipped("self-locking.toml"))], catch_exceptions=False)
    text = " ".join(out.stdout.split())
    assert ("Coulomb friction (solved per dyad) in joints (1,2), (2,3), (3,4), (1,4); "
            "self-locking (friction dead centres) of their dyads") in text
    assert "self-locking margin of sliders (1,4)" in text


def test_edge_friction_is_a_file_key():
    mechanism = toml_input.read_mechanism(shipped("self-locking.toml"),
                                          overrides={"friction.edge_friction": False})
    assert not mechanism.dyads[0].joints[2].edge_friction
    with pytest.raises(toml_input.InputError, match=r"`friction.edge_friction` must be true or false"):
        toml_input.read_mechanism(shipped("self-locking.toml"), overrides={"friction.edge_friction": 1})
    with pytest.raises(toml_input.InputError, match=r"`dyad.2.C.edge_friction` must be true or false"):
        toml_input.read_mechanism(shipped("self-locking.toml"), overrides={"dyad.2.C.edge_friction": "no"})


def test_the_force_floor_median_is_numpys():
    """friction.scales.median replaces np.median (whose first call imports numpy.ma):
    the same value to the bit, for odd and even counts."""
    from dyade.linkage.friction.scales import median

    rng = np.random.default_rng(7)
    for size in range(1, 120):
        values = rng.random(size) * 10.0 ** rng.integers(-5, 5, size)
        assert median(values) == float(np.median(values)), size


# -- the block's total pressure (issue 28): ∫|p| dx, never |FN| + 3·|M'|/L
def test_block_pressure_law_limits_and_continuity():
    from dyade.linkage.friction.laws import pressure

    length = 0.04
    rng = np.random.default_rng(28)
    normal = rng.normal(size=2000) * 10.0 ** rng.integers(-3, 3, 2000)
    tilt = rng.normal(size=2000) * 10.0 ** rng.integers(-5, 1, 2000)
    # the law against the pressure integrated here by its zero
    assert np.allclose(pressure(normal, tilt, length), block_pressure(normal, tilt, length),
                       rtol=1e-12, atol=0.0)
    # FN = 0: the edge friction of a pure tilting moment, 3·|M'|/L
    assert np.allclose(pressure(0.0, tilt, length), 3.0 * np.abs(tilt) / length, rtol=1e-15)
    # 6·|M'| ≤ |FN|·L: the pressure keeps its sign, N = |FN| exactly
    inside = 6.0 * np.abs(tilt) <= np.abs(normal) * length
    assert inside.any() and np.array_equal(pressure(normal, tilt, length)[inside],
                                           np.abs(normal)[inside])
    # never above the paper's bound |FN| + 3·|M'|/L, never below |FN| or 3·|M'|/L... of it
    total = pressure(normal, tilt, length)
    assert np.all(total <= (np.abs(normal) + 3.0 * np.abs(tilt) / length) * (1 + 1e-15))
    assert np.all(total >= np.abs(normal) * (1 - 1e-15))
    # continuous at the bound 6·|M'| = |FN|·L, from both sides
    edge = np.abs(normal) * length / 6.0
    for side in (1.0 - 1e-12, 1.0 + 1e-12):
        assert np.allclose(pressure(normal, edge * side, length), np.abs(normal), rtol=1e-11)


def slider_crank_with_friction(mu, length, height, edges=True):
    """The shipped slider-crank, μ in the guide only: the conrod's force passes through
    the slider point, so the guide's moment is only the friction's own offset ½·FN·H·μ."""
    return toml_input.read_mechanism(shipped("slider-crank.toml"), overrides={
        "gravity": True, "dyad.2.C.friction": mu, "dyad.2.C.slider_length": length,
        "dyad.2.C.slider_height": height, "dyad.2.C.edge_friction": edges})


@pytest.mark.parametrize("length", [12.0, 40.0], ids=["3muH=L", "long"])
def test_slider_crank_with_its_own_friction_offset_has_point_contact_friction(length):
    # 3·μ·H ≤ L: 6·|M'| = 3·μ·H·|FN| ≤ |FN|·L, the pressure keeps its sign and the
    # friction is exactly μ·|FN|: the point-contact solution, to the last digits
    mu, height = 0.2, 20.0  # 3·μ·H = 12 mm
    edged = analysis.analyse(slider_crank_with_friction(mu, length, height))
    point = analysis.analyse(slider_crank_with_friction(mu, length, height, edges=False))
    fr = edged.friction.friction_forces[(1, 4)]
    normal = edged.forces.normal[(1, 4)]
    moving = ~edged.friction.at_rest[(1, 4)]
    assert np.allclose(np.abs(fr[moving]), mu * np.abs(normal[moving]), rtol=1e-12, atol=0.0)
    scale = np.max(np.abs(point.forces.drive_torque))
    assert np.allclose(edged.forces.drive_torque, point.forces.drive_torque, rtol=0.0,
                       atol=1e-12 * scale)
    # a block shorter than 3·μ·H tilts beyond the bound: more than point contact
    short = analysis.analyse(slider_crank_with_friction(mu, 0.5 * 3 * mu * height, height))
    more = np.abs(short.friction.friction_forces[(1, 4)][moving])
    assert np.all(more >= mu * np.abs(short.forces.normal[(1, 4)][moving]) * (1 - 1e-12))
    assert np.any(more > 1.01 * mu * np.abs(short.forces.normal[(1, 4)][moving]))


@pytest.mark.parametrize("path", [p for p in SHIPPED if "friction" in p.read_text()],
                         ids=lambda p: p.stem)
def test_energy_and_coulomb_laws_hold_on_the_shipped_files_with_friction(path):
    # as shipped (the press slide: μ = 0.25, a block tilting in its guide), not loaded
    mechanism = replace(toml_input.read_mechanism(path), friction_tol=1e-13)
    kin = kinematics.sweep(mechanism)
    result = friction.solve(mechanism, kin)
    valid = result.forces.valid
    assert valid.sum() > 0.3 * valid.size
    assert_energy_balance(mechanism, kin, result, valid)
    for name, (error, wrong_sense) in coulomb_law_errors(mechanism, kin, result).items():
        assert error < 1e-9, name
        assert not wrong_sense, name
