"""Self-locking: the jam of a pushed block in closed form, the slotted lever that never
locks, the shipped press slide, the drive torque towards a friction dead centre, an
independent check of every verdict, random mechanisms, the command line."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, strategies as st
from scipy import optimize

import dyade
from dyade.linkage.sweep import analyse_si
from dyade.cli import main
from dyade.errors import DyadeError
from dyade.files import mechanism as toml_input
from dyade.model.mechanism import Prismatic, Revolute
from dyade.report.notes import say
from dyade.linkage import friction, kinematics, kinetostatics, motion as joints, sweep as analysis
from tests.helpers import TEMPLATES, mechanism_from, shipped
from tests.strategies import dyad_files
from tests.test_friction import block_pressure, coulomb_law_errors, with_friction
from tests.test_kinetostatics import with_masses

# The pushed block (README, "Friction and self-locking"): crank r, rod l (massless, its
# pins frictionless: a two-force member), a block of length L and height H in a guide
# along x with friction μ, its pin e above the block's centre, a load R resisting the
# outward stroke. Crank pivot level with the pin, so the rod's angle to the guide is
# sin β = −r·sin φ/l. e = 63 mm on a 48 mm block: a push straight along the guide moves
# it (3·μ·e/L = 0.984 < 1), a push down jams it at the angle below.
R, LENGTH, E, L, H, MU, LOAD = 80.0, 200.0, 63.0, 48.0, 30.0, 0.25, 400.0


def pushed_block(direction: str = "ccw", **friction_keys):
    return mechanism_from({
        "units": {"length": "mm", "angle": "deg"},
        "frame": {"points": {"O": [0, E]}},
        "crank": {"pivot": "O", "length": R, "speed_rpm": 10, "direction": direction},
        "dyad": [{"kind": "RRP", "links": [3, 4], "length": LENGTH, "variant": 1,
                  "A": {"link": 2, "point": "tip"},
                  "C": {"link": 1, "point": [0, 0], "angle": 0, "slider_point": [0, -E],
                        "friction": MU, "slider_length": L, "slider_height": H,
                        **friction_keys}}],
        "load": [{"link": 4, "point": [0, -E], "force": [-LOAD, 0]}]})


def tilt_per_push(t: float, up: bool) -> float:
    """M'/P_x, the tilting moment per unit push along the guide at tan |β| = t: the
    guide's moment about the block's centre e·P_x less (pushing up: the friction at the
    top face relieves the tilt) or plus (pushing down) ½·FN·H·μ, with |FN| = t·P_x."""
    side = 1.0 if up else -1.0
    return E - side * 0.5 * H * MU * t


def jam_angle(up: bool) -> float:
    """|β| [°] at which the block jams: P_x = μ·∫|p| dx. Per unit P_x, |FN| = t = tan |β|
    and M' = m = e ∓ ½·H·μ·t (``tilt_per_push``); with 6·m > t·L (the pressure changes
    sign over the block) ∫|p| dx = t²·L/(12·m) + 3·m/L, and 1 = μ·(t²·L/(12·m) + 3·m/L)
    is the quadratic (μ·L² + 36·μ·k²)·t² + (12·L·k − 72·μ·e·k)·t + 36·μ·e² − 12·L·e = 0
    with m = e − k·t, k = ±½·H·μ: its least positive root (inf: none)."""
    k = (1.0 if up else -1.0) * 0.5 * H * MU
    a = MU * L ** 2 + 36.0 * MU * k ** 2
    b = 12.0 * L * k - 72.0 * MU * E * k
    c = 36.0 * MU * E ** 2 - 12.0 * L * E
    roots = [(-b + sign * math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a) for sign in (1.0, -1.0)]
    t = min((root for root in roots if root > 0.0), default=math.inf)
    assert 6.0 * tilt_per_push(t, up) > t * L or t == math.inf  # the region assumed
    return math.degrees(math.atan(t))


def crank_angle_at(beta: float, up: bool) -> float:
    """The crank angle [°] on the outward stroke where |β| first reaches ``beta`` [°]."""
    phi = math.degrees(math.asin(LENGTH * math.sin(math.radians(beta)) / R))
    return 180.0 + phi if up else phi  # ccw: outward on 180°–360°; cw: on 0°–180°


def test_pushed_block_locks_at_the_closed_form_jam_angle():
    up = False
    jam = jam_angle(up)
    assert 5.0 < jam < 20.0  # the rod reaches 23.6°: the push down locks inside the sweep
    mechanism = pushed_block("cw")
    onset = crank_angle_at(jam, up)
    angles = np.deg2rad(onset + np.linspace(-0.05, 0.05, 201))
    result = analyse_si(mechanism, crank_angle=angles)
    locks = result.locking[(1, 4)].locks
    assert locks.any() and not locks.all()
    first = int(np.argmax(locks))  # |β| grows with φ in the window: the lock starts
    cols = result.columns()
    beta = np.abs(cols["phi_3_deg"])  # the rod's frame: ξ from A to B
    for k in (first - 1, first):
        assert beta[k] == pytest.approx(jam, abs=0.01)
    # the paper's inequality is the conservative margin: ≤ 0 wherever the block locks
    margin = cols["lock_margin_1_4"]
    assert np.all(margin[locks] <= 0.0) and np.all(margin <= cols["friction_det_2"] + 1e-12)
    # and it runs the whole range where the rod is steeper than the jam angle
    whole = dyade.analyse(mechanism, step_deg=0.25)
    locked = np.rad2deg(whole.crank_angle[whole.locking[(1, 4)].locks])
    lo, hi = onset, 180.0 - onset
    assert locked.min() == pytest.approx(lo, abs=0.25) and locked.max() == pytest.approx(hi, abs=0.25)
    assert not (whole.friction.locks.keys() - {(1, 4)})


@pytest.mark.parametrize("up", [True, False], ids=["push-up", "push-down"])
def test_pushed_block_determinant_and_margin_in_closed_form(up):
    # with friction only in the guide the dyad's determinant is the exact jam condition,
    # 1 − μ·∫|p| dx per unit push along the guide, and the lock margin the paper's
    # bound 1 − μ·(|FN| + 3·|M'|/L): both read off the rod's angle β
    mechanism = pushed_block("ccw" if up else "cw")
    result = dyade.analyse(mechanism, step_deg=1.0)
    cols = result.columns()
    t = np.tan(np.deg2rad(np.abs(cols["phi_3_deg"])))
    m = tilt_per_push(t, up)
    pushing = (result.crank_angle > np.pi) if up else (result.crank_angle < np.pi)
    pushing &= t > 1e-9
    solved = pushing & ~result.locking[(1, 4)].locks
    exact = 1.0 - MU * np.where(6.0 * m > t * L, t * t * L / (12.0 * m) + 3.0 * m / L, t)
    bound = 1.0 - MU * (t + 3.0 * np.abs(m) / L)
    assert np.allclose(cols["friction_det_2"][solved], exact[solved], rtol=1e-9, atol=1e-12)
    assert np.allclose(cols["lock_margin_1_4"][pushing], bound[pushing], rtol=1e-9, atol=1e-12)
    if up:  # the push up relieves the tilt: no lock, though the paper's margin says < 0
        assert math.isinf(jam_angle(up)) or jam_angle(up) > 23.6
        assert not result.locking[(1, 4)].locks.any() and (bound[pushing] < 0.0).any()


def test_drive_torque_grows_like_the_inverse_distance_to_the_lock():
    # towards a friction dead centre det(I + K) falls linearly, the forces grow as 1/det
    up = False
    mechanism = pushed_block("cw")
    onset = np.deg2rad(crank_angle_at(jam_angle(up), up))
    distance = np.logspace(-5, -3, 9)  # [rad] before the onset
    kin = kinematics.sweep(mechanism, onset - distance)
    solved = friction.solve(mechanism, kin)
    assert solved.converged.all() and not solved.locked.any()
    torque = np.abs(solved.forces.drive_torque)
    slope = np.polyfit(np.log(distance), np.log(torque), 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.1)
    assert solved.forces.valid.sum() == 0  # all of it within the near-locking band


@pytest.mark.parametrize("mu", [0.01, 0.1, 0.2])
def test_slotted_lever_never_locks(mu):
    mechanism = toml_input.read_mechanism(TEMPLATES / "slotted-lever.toml", overrides={
        "friction.coefficient": mu, "friction.pin_radius": 5, "friction.slider_length": 40,
        "friction.slider_height": 20})
    result = dyade.analyse(mechanism)
    kinds = {note.kind for note in result.notes}
    assert not kinds & {"self_locking", "near_self_locking", "friction_not_converged"}
    cols = result.columns()
    assert np.nanmin(cols["lock_margin_3_4"]) > 0.99  # the slot passes both pivots
    assert np.nanmin(cols["friction_det_2"]) > 1.0 - 2 * mu
    assert cols["forces_valid"].all()


def test_press_slide_locks_where_its_comment_says():
    result = dyade.analyse(dyade.read_mechanism(shipped("self-locking.toml")))
    locks = result.locking[(1, 4)].locks
    angles = np.rad2deg(result.crank_angle[locks])
    assert angles.min() == pytest.approx(90.0) and angles.max() == pytest.approx(179.0)
    assert np.allclose(np.diff(angles), 1.0)  # one range
    note, = [note for note in result.notes if note.kind == "self_locking"]
    assert note.subject == "slider (1,4)"
    assert say(note, result.mechanism).startswith("slider (1,4) locks (self-locking) at crank angles 90.0°–179.0°")
    near, = [note for note in result.notes if note.kind == "near_self_locking"]
    assert say(near, result.mechanism).startswith("dyad 2 (kind 2 RRP, links 3-4) is near self-locking at crank "
                                "angles 8.0°–89.0°")
    cols = result.columns()
    blank = ~cols["forces_valid"].astype(bool)
    assert np.isnan(cols["M_drive"][blank]).all()
    assert np.isfinite(cols["lock_margin_1_4"]).all() and np.isfinite(cols["friction_det_2"]).all()
    assert np.all(cols["friction_det_2"][locks] <= 0.0)
    # on the return stroke the load drives the slide and the rod brakes it: not a lock,
    # although the jammed solution (det < 0) exists there too
    back = result.crank_angle > np.pi
    assert not locks[back].any() and np.all(cols["friction_det_2"][back] > 0.9)


def test_press_slide_with_less_friction_does_not_lock():
    mechanism = dyade.read_mechanism(shipped("self-locking.toml"),
                                     overrides={"friction.coefficient": 0.1})
    result = dyade.analyse(mechanism)
    assert not any(note.kind.endswith("self_locking") for note in result.notes)
    cols = result.columns()
    assert np.min(cols["lock_margin_1_4"]) > 0.5 and np.min(cols["friction_det_2"]) > 0.5


def dyade16_with_friction():
    return dyade.read_mechanism(shipped("dyade-16.toml"), overrides={
        "friction.coefficient": 0.1, "friction.pin_radius": 5, "friction.slider_length": 40,
        "friction.slider_height": 20})


def test_dyade16_with_friction_does_not_lock():
    result = dyade.analyse(dyade16_with_friction())
    assert not any("lock" in note.kind for note in result.notes)
    cols = result.columns()
    assert cols["forces_valid"].all()
    dets = [cols[f"friction_det_{k}"] for k in range(2, 9)]
    assert min(np.min(det) for det in dets) > 0.7  # dyad 5, the Scotch yoke: 0.72
    margins = [cols[name] for name in cols if name.startswith("lock_margin")]
    assert len(margins) == 6 and min(np.min(margin) for margin in margins) > 0.7


# -- an independent check: the dyad's Coulomb equilibrium written again, solved by scipy
def _dyad_residual(mechanism, kin, q, position):
    """F(W_B) = 0, the friction equilibrium of the first dyad at one position, from the
    joints' unit twists and the laws written here (not dyade's); its frictionless
    matrix Mᵀ and solution."""
    group = kin.groups[0]
    i, j = group.links
    screws = [np.array([float(np.asarray(c)[position]) if np.ndim(c) else float(c) for c in s])
              for s in group.screws]
    q_i, q_j = q[i][:, position], q[j][:, position]
    rates = [float(group.rate(k)[position]) for k in range(3)]
    typical = abs(mechanism.crank.speed) * np.array([1.0, mechanism.crank.length])

    def law(k, wrench):  # τ_k: the load along the freedom S_k on the link group.on[k]
        joint = group.joints[k]
        if joint.friction == 0.0:
            return 0.0
        if isinstance(joint, Revolute):
            if abs(rates[k]) <= 1e-9 * typical[0]:
                return 0.0
            return -joint.friction * joint.pin_radius * np.hypot(*wrench[:2]) * np.sign(rates[k])
        d = screws[k][:2] * (1.0 if group.on[k] == joint.slider else -1.0)
        on_slider = wrench if group.on[k] == joint.slider else -wrench
        slider_point = kin.motion.point(joint.slider, joint.slider_point)[position]
        speed = joints.travel(joint, kin.motion)[1][position]
        s = 0.0 if abs(speed) <= 1e-9 * typical[1] else np.sign(speed)
        normal = d[0] * on_slider[1] - d[1] * on_slider[0]
        moment = on_slider[2] - (slider_point[0] * on_slider[1] - slider_point[1] * on_slider[0])
        tilt = moment + 0.5 * normal * joint.slider_height * joint.friction * s
        size = float(block_pressure(normal, tilt, joint.slider_length)) if joint.edge_friction else abs(normal)
        return -joint.friction * size * s  # on the slider along d: S_k·W_k = ζd·ζf = d·f

    def residual(w_b):
        wrenches = (w_b - q_i, w_b, -q_j - w_b)
        return np.array([screws[k] @ wrenches[k] - law(k, wrenches[k]) for k in range(3)])

    matrix = np.array([screws[0], screws[1], -screws[2]])
    frictionless = np.linalg.solve(matrix, [screws[0] @ q_i, 0.0, screws[2] @ q_j])
    return residual, matrix, frictionless


def _independent_verdict(mechanism, kin, q, position, reported):
    """(found, det): scipy finds a consistent solution with det > 0 from several starts
    (the reported one, the frictionless one and scaled copies), and its det(J)/det(Mᵀ)
    by central differences."""
    residual, matrix, w0 = _dyad_residual(mechanism, kin, q, position)
    scale = max(np.abs(w0[:2]).max(), 1e-12)
    starts = [w0] + [w0 * f for f in (3.0, 10.0, -1.0, -3.0)] + (
        [reported] if np.isfinite(reported).all() else [])
    for start in starts:
        root = optimize.root(residual, start, method="hybr", options={"xtol": 1e-14})
        if np.max(np.abs(residual(root.x))) > 1e-9 * scale:
            continue
        step = 1e-7 * max(np.abs(root.x).max(), scale)
        jac = np.array([(residual(root.x + step * e) - residual(root.x - step * e)) / (2 * step)
                        for e in np.eye(3)]).T
        det = np.linalg.det(jac) / np.linalg.det(matrix)
        if det > 0.0:
            return True, det, root.x
    return False, np.nan, None


def test_every_verdict_of_the_press_slide_is_confirmed_independently():
    mechanism = dyade.read_mechanism(shipped("self-locking.toml"))
    kin = kinematics.sweep(mechanism, np.deg2rad(np.arange(0.0, 360.0, 3.0)))
    q = kinetostatics.applied_loads(mechanism, kin)
    result = friction.solve(mechanism, kin, tol=1e-13)
    w_b = result.forces.wrenches[(3, 4)][1]  # W_B: on link 4 from link 3
    for position in range(kin.crank_angle.size):
        found, det, root = _independent_verdict(mechanism, kin, q, position, w_b[:, position])
        if result.locked[position]:
            assert not found, np.rad2deg(kin.crank_angle[position])
            continue
        assert found, np.rad2deg(kin.crank_angle[position])
        assert det == pytest.approx(result.determinant[2][position], rel=1e-5, abs=1e-7)
        assert np.allclose(root, w_b[:, position], rtol=1e-7, atol=1e-9 * np.nanmax(np.abs(w_b)))


# -- random mechanisms ----------------------------------------------------------------
@given(data=dyad_files(), mu=st.floats(0.001, 0.5), seed=st.integers(0, 100),
       sizes=st.tuples(st.floats(0.01, 0.3), st.floats(0.2, 3.0), st.floats(0.1, 1.0)))
def test_random_mechanisms_are_solved_locked_or_flagged(data, mu, seed, sizes):
    # every position is solved consistently, or self-locks, or is flagged invalid
    # (dead centre, near self-locking, not solved); no valid force beyond the
    # plausibility bound: friction raises no joint force of the dyad (its largest
    # component) more than 1/sin(dead_centre)-fold over the frictionless solution
    try:
        mechanism = mechanism_from(data)
    except DyadeError:
        return
    size = mechanism.crank.length
    pin, length, height = (f * size for f in sizes)
    mechanism = replace(with_friction(with_masses(mechanism, gravity=(0.0, -9.81), seed=seed),
                                      mu, pin=pin, length=length, height=height),
                        friction_tol=1e-12)
    try:
        result = analysis.analyse(mechanism, allow_partial=True)
    except DyadeError:
        return
    rows = result.rows
    rubbing, forces = result.friction, result.forces
    valid = forces.valid & rows
    for name, (error, wrong_sense) in coulomb_law_errors(mechanism, result.kinematics, rubbing,
                                                         valid).items():
        assert error < 1e-7, name
        assert not wrong_sense, name
    assert np.all(rubbing.power[valid] >= 0.0)
    flagged = set()
    for note in result.notes:
        for first, last in note.ranges:
            flagged |= set(np.flatnonzero((result.crank_angle >= first)
                                          & (result.crank_angle <= last)))
    assert set(np.flatnonzero(rows & ~forces.valid)) <= flagged
    assert not (valid & (rubbing.locked | rubbing.unsolved)).any()
    plain = kinetostatics.solve(mechanism, result.kinematics)

    def largest(solution):
        parts = [np.abs(f).max(axis=1) for f in solution.revolute.values()]
        parts += [np.abs(f) for f in solution.normal.values()]  # |FN| ≤ the force's size
        parts += [np.hypot(*solution.on(j.name, j.slider)[:2]) for j in mechanism.joints
                  if isinstance(j, Prismatic)]
        return np.max(parts, axis=0)

    bound = largest(plain)[valid] / np.sin(mechanism.dead_centre_angle)
    assert np.all(largest(forces)[valid] <= bound * (1.0 + 1e-9) * np.sqrt(2.0))
    assert np.all(np.isfinite(result.columns()["M_drive"][forces.valid[rows]]))


# -- the command line -----------------------------------------------------------------
def test_self_locking_exit_status():
    def run(*extra):  # exceptions propagate: exit code 1 must come from --fail-on-lock
        return CliRunner().invoke(main, args + list(extra), catch_exceptions=False)

    args = ["analyse", str(shipped("self-locking.toml")), "--format", "csv"]
    passing = run()
    assert passing.exit_code == 0
    failing = run("--fail-on-lock")
    assert failing.exit_code == 1
    assert ("Error: the mechanism self-locks (see the warning above); --fail-on-lock was "
            "given.") in failing.stderr
    assert "slider (1,4) locks (self-locking)" in failing.stderr
    header = passing.stdout.splitlines()[0].split(",")
    for name in ("MR_1_2", "MR_2_3", "MR_3_4", "FR_1_4", "P_friction", "friction_iterations",
                 "lock_margin_1_4", "friction_det_2"):
        assert name in header
    assert header[-5:] == ["forces_valid", "friction_det_2", "J_red", "dJ_red", "M_load"]


def test_slotted_lever_with_friction_says_nothing_about_locking(tmp_path):
    out = CliRunner().invoke(main, ["analyse", str(TEMPLATES / "slotted-lever.toml"),
                                    "--set", "friction.coefficient=0.1",
                                    "--set", "friction.pin_radius=5",
                                    "--set", "friction.slider_length=40",
                                    "--set", "friction.slider_height=20", "--fail-on-lock",
                                    "--all"], catch_exceptions=False)
    assert out.exit_code == 0
    assert "lock" not in out.stderr
    assert "lock_margin_3_4 min (no lock)" in " ".join(out.stdout.split())


@pytest.mark.parametrize("fmt", ["json", "table"])
def test_a_sweep_locked_throughout_gives_no_drive_torque_and_no_warning(fmt):
    """100°–120° of the press lie inside its self-locking range: no position has forces,
    so the summary's drive torque is not given (JSON null, the table leaves it out),
    and no numpy warning (All-NaN slice) reaches the user."""
    import json

    result = CliRunner().invoke(main, ["analyse", str(shipped("self-locking.toml")),
                                       "--start", "100", "--stop", "120", "--format", fmt])
    assert result.exit_code == 0, result.output
    assert "RuntimeWarning" not in result.output and "locks (self-locking)" in result.output
    if fmt == "json":
        summary = json.loads(result.stdout)["summary"]
        assert summary["M_drive_max"]["value"] is None and summary["M_drive_min"]["value"] is None
        assert "where" not in summary["M_drive_max"]


@pytest.mark.parametrize("passes", [1, 2, 7])
def test_too_few_friction_passes_give_no_self_locking_verdict(passes):
    """The press self-locks at 90°–179° (found with 8 passes or more). With fewer the
    search from every forced pattern is cut short: one pass once called 30°–90° and
    216°–332° self-locking, where 30°–90° has a friction equilibrium. Now such positions
    are "not solved", with the reason, and no slider is said to lock."""
    mechanism = toml_input.read_mechanism(shipped("self-locking.toml"))
    short = analysis.analyse(mechanism, friction_max_iter=passes)
    assert not short.friction.locked.any() and short.friction.unsolved.any()
    assert not any(note.kind == "self_locking" for note in short.notes)
    note = next(note for note in short.notes if note.kind == "friction_not_converged")
    assert "give no self-locking verdict" in say(note, mechanism)
    full = analysis.analyse(mechanism, friction_max_iter=8)
    locked = np.rad2deg(full.crank_angle[full.friction.locked])
    assert locked.min() == pytest.approx(90.0) and locked.max() == pytest.approx(179.0)
    # every position left unsolved is solved or locked with the whole search
    assert not (short.friction.unsolved & ~full.friction.locked & ~full.friction.converged).any()
