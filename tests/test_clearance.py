"""Clearance peak force (SPEC §2): paper value, f(τ) everywhere, simulation, mechanisms."""

from __future__ import annotations

import csv
import io
from decimal import Decimal, getcontext

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.optimize import minimize_scalar

import dyade
from dyade.linkage import sweep as analysis
from dyade import clearance
from dyade.linkage import joint_clearance
from dyade.files import mechanism as toml_input
from dyade.cli import main
from dyade.model.mechanism import ClearanceData
from tests.helpers import read_csv, shipped

getcontext().prec = 60


def _atan(x: Decimal) -> Decimal:
    """arctan to 60 digits: halve the argument until small, then the Taylor series."""
    halvings = 0
    while abs(x) > Decimal("0.01"):
        x = x / (1 + (1 + x * x).sqrt())
        halvings += 1
    term, total, k, x2 = x, x, 1, x * x
    while abs(term) > Decimal(10) ** -70:
        term = -term * x2
        total += term / (2 * k + 1)
        k += 1
    return total * (2 ** halvings)


def _f_reference(tau: float) -> float:
    """f(τ) = 6/τ + 12/τ² + 12·θ*/τ³ with θ* = 2·atan2(τ, τ − 2), in 60-digit decimals."""
    t = Decimal(tau)
    pi = 4 * _atan(Decimal(1))
    if t > 2:
        theta = 2 * _atan(t / (t - 2))
    elif t == 2:
        theta = pi
    else:
        theta = 2 * (pi - _atan(t / (2 - t)))
    return float(6 / t + 12 / t ** 2 + 12 * theta / t ** 3)


def test_peak_force_matches_paper():
    # Dresig & Thümmel, section 4 (needle drive, joint (5,6)): the paper prints 2182 N and
    # SPEC §2 repeats τ ≈ 3.0285, t1 ≈ 1.817 ms, f(τ) ≈ 4.3638 (printed to 4-5 digits)
    peak = clearance.peak_force(mass=3.6, stiffness=1e7, clearance=1e-4, slope=3.6e5)
    assert peak.force == pytest.approx(2182, abs=1)
    assert peak.tau == pytest.approx(3.0285, abs=5e-5)
    assert peak.t1 == pytest.approx(1.817e-3, rel=5e-4)
    assert peak.f_tau == pytest.approx(4.3638, abs=5e-4)


SHARE_CASES = [                   # mass, stiffness, clearance, slope
    (3.6, 1e7, 1e-4, 3.6e5),      # the paper: τ ≈ 3.03
    (0.2, 1e8, 5e-5, 1e4),        # stiff, slow ramp: τ ≈ 41
    (10.0, 1e6, 2e-4, 5e6),       # soft, fast ramp: τ ≈ 0.42
    (1.0, 4e6, 1e-4, 2.4e6),      # τ ≈ 1.26: the peak after the first half-wave
    (2.0, 1e8, 2e-5, 1.2e7),      # τ ≈ 1.92, just below 2
    (2.0, 1e8, 2e-5, 7e6),        # τ ≈ 2.30, just above 2
]


@pytest.mark.parametrize("mass, stiffness, gap, slope", SHARE_CASES)
def test_shares_are_the_impact_and_the_rigid_ramp(mass, stiffness, gap, slope):
    # F12max = c·s·(6/τ + 12/τ² + 12θ*/τ³); with k = 12·m·s/t1³ and m = c/ω² the last two
    # terms are k·t1 + k·θ*/ω: the rigid force k·t reached at the peak, t = t1 + θ*/ω
    peak = clearance.peak_force(mass, stiffness, clearance=gap, slope=slope)
    omega = np.sqrt(stiffness / mass)
    assert peak.t1 == pytest.approx(np.cbrt(12 * mass * (gap / 2) / slope), rel=1e-14)  # eq. (15)
    tau = omega * peak.t1
    assert peak.soft == (tau < 2)
    # 1e-12: a few roundings, and F − 6cs/τ loses up to log10(τ/2) digits to cancellation
    assert peak.rigid_share == pytest.approx(slope * peak.time_to_peak, rel=1e-12)
    assert peak.clearance_share == pytest.approx(6 * stiffness * (gap / 2) / tau, rel=1e-12)


def test_share_cases_cover_soft_and_hard_impacts():
    taus = [clearance.peak_force(*case[:2], clearance=case[2], slope=case[3]).tau for case in SHARE_CASES]
    for low, high in ((0, 1), (1, 2), (2, 2.5), (10, np.inf)):  # soft ... around 2 ... stiff
        assert any(low < tau < high for tau in taus), (low, high)


def test_cli_reproduces_the_paper_as_csv():
    out = CliRunner().invoke(main, ["clearance", "--mass", "3.6", "--stiffness", "1e7",
                                    "--clearance", "1e-4", "--slope", "360000", "--format", "csv"],
                             catch_exceptions=False)
    assert out.exit_code == 0
    cols = read_csv(out.stdout)
    assert list(cols) == ["mass", "stiffness", "clearance", "slope", "t1", "v1", "tau", "f_tau",
                          "F_max", "F_clearance", "F_rigid_share"]
    assert cols["F_clearance"][0] + cols["F_rigid_share"][0] == pytest.approx(cols["F_max"][0])
    assert cols["F_max"][0] == pytest.approx(2182, abs=1)
    assert cols["tau"][0] == pytest.approx(3.0285, abs=5e-5)


def test_two_masses_give_the_reduced_mass():
    out = CliRunner().invoke(main, ["clearance", "--mass", "6", "--mass", "9", "--stiffness", "1e7",
                                    "--clearance", "1e-4", "--slope", "360000", "--format", "csv"],
                             catch_exceptions=False)
    assert read_csv(out.stdout)["mass"][0] == pytest.approx(3.6)  # 6·9/15


@pytest.mark.parametrize("tau", np.logspace(-6, 6, 49).tolist() + [1.999999, 2.0, 2.000001])
def test_f_of_tau_against_high_precision(tau):
    assert float(clearance.f_of_tau(tau)) == pytest.approx(_f_reference(tau), rel=1e-13)


@pytest.mark.parametrize("tau", [0.05, 0.3, 1.0, 1.9, 2.0, 2.5, 3.0285, 10.0, 100.0])
def test_f_of_tau_is_the_first_maximum_of_eq_26(tau):
    # eq. (26)/(c·s): (12/τ²)[1 + θ/τ + A sin θ − cos θ], A = τ/2 − 1/τ, θ = ω·t̃
    a = tau / 2 - 1 / tau
    def force(theta):
        return 12 / tau ** 2 * (1 + theta / tau + a * np.sin(theta) - np.cos(theta))
    def slope(theta):
        return 12 / tau ** 2 * (1 / tau + a * np.cos(theta) + np.sin(theta))
    def curvature(theta):
        return 12 / tau ** 2 * (-a * np.sin(theta) + np.cos(theta))

    theta_star = float(clearance.peak_angle(tau))
    assert force(theta_star) == pytest.approx(float(clearance.f_of_tau(tau)), rel=1e-12)
    assert abs(slope(theta_star)) < 1e-9 * (12 / tau ** 3)   # stationary ...
    assert curvature(theta_star) < 0                           # ... a maximum ...
    grid = np.linspace(0, theta_star, 4001)[1:-1]
    assert np.all(slope(grid) > 0)                             # ... and the first one
    if tau >= 2:  # a clear peak: the brute-force maximum of the first half-wave
        found = minimize_scalar(lambda t: -force(t), bounds=(0, np.pi), method="bounded",
                                options={"xatol": 1e-12})
        assert -found.fun == pytest.approx(float(clearance.f_of_tau(tau)), rel=1e-10)


def test_paper_eq_36_is_our_f_for_tau_at_least_2():
    tau = np.logspace(np.log10(2.01), 6, 200)
    eq36 = 6 / tau + 12 / tau ** 2 + 12 / tau ** 3 * np.arccos((4 - 2 * tau ** 3 - 2 * tau ** 2) / (4 + tau ** 4))
    assert np.allclose(clearance.f_of_tau(tau), eq36, rtol=1e-9)


@pytest.mark.parametrize("mass, stiffness, gap, slope", [
    (3.6, 1e7, 1e-4, 3.6e5),      # the paper (τ ≈ 3)
    (0.2, 1e8, 5e-5, 1e4),        # stiff, slow ramp (τ ≈ 70)
    (10.0, 1e6, 2e-4, 5e6),       # soft, fast ramp (τ < 2)
])
def test_simulation_agrees_with_closed_form(mass, stiffness, gap, slope):
    closed = clearance.peak_force(mass, stiffness, clearance=gap, slope=slope)
    sim = clearance.simulate(mass, stiffness, clearance=gap, slope=slope, steps_per_period=400)
    assert sim.contact_to_peak
    assert sim.t1 == pytest.approx(closed.t1, rel=1e-9)
    assert sim.force == pytest.approx(closed.force, rel=1e-7)
    assert sim.time_to_peak == pytest.approx(closed.time_to_peak, rel=1e-6)


def test_simulation_error_falls_at_fourth_order():
    closed = clearance.peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5).force
    errors = [abs(clearance.simulate(3.6, 1e7, clearance=1e-4, slope=3.6e5, steps_per_period=n).force - closed) for n in (50, 100, 200)]
    assert errors[0] / errors[1] > 4 and errors[1] / errors[2] > 4


def test_large_tau_rebounds_after_the_peak():
    # stiff contact, slow ramp: the pin bounces off after the first half-wave
    sim = clearance.simulate(0.2, 1e8, clearance=5e-5, slope=1e4, steps_per_period=400)
    assert sim.separates and sim.rebound_speed > 0
    assert sim.separation_time > sim.time_to_peak


@pytest.mark.parametrize("flag", ["--mass", "--stiffness", "--clearance", "--slope"])
@pytest.mark.parametrize("value", ["0", "-1"])
def test_non_positive_inputs_are_rejected(flag, value):
    args = {"--mass": "3.6", "--stiffness": "1e7", "--clearance": "1e-4", "--slope": "360000"}
    args[flag] = value
    out = CliRunner().invoke(main, ["clearance", *[x for kv in args.items() for x in kv]],
                             catch_exceptions=False)
    assert out.exit_code == 2
    assert f"'{flag}': must be positive" in out.output


def test_missing_standalone_input_is_a_usage_error():
    out = CliRunner().invoke(main, ["clearance", "--mass", "3.6", "--stiffness", "1e7"],
                             catch_exceptions=False)
    assert out.exit_code == 2 and "--clearance and --slope must be given" in out.output


def test_synthetic_reversals_and_slope():
    # F = (A·cos φ, 0): reverses at 90° and 270° with |dF/dφ| = A; F0/t0 = A·Ω
    phi = np.deg2rad(np.arange(0.0, 360.5, 0.5))
    force = np.stack((500.0 * np.cos(phi), np.zeros_like(phi)), axis=-1)
    check = joint_clearance.check_joint((5, 6), phi, force, 10.0, ClearanceData(1e-4, 1e7), 3.6,
                                  "given", True)
    assert check.applies and len(check.reversals) == 2
    assert [np.rad2deg(r.crank_angle) for r in check.reversals] == pytest.approx([90, 270], abs=1e-9)
    for rev in check.reversals:
        assert rev.peak.slope == pytest.approx(500.0 * 10.0, rel=1e-4)  # secant over 0.5°


def test_wandering_force_is_refused_with_the_reason():
    phi = np.deg2rad(np.arange(0.0, 361.0))
    force = 100.0 * np.stack((np.cos(phi), np.sin(phi)), axis=-1)  # turns all around
    check = joint_clearance.check_joint((2, 3), phi, force, 10.0, ClearanceData(1e-4, 1e7), 1.0,
                                  "given", True)
    assert not check.applies and not check.reversals
    assert "wanders up to 90°" in check.reason


def test_every_revolute_joint_gets_peaks_or_a_reason():
    for name in ("slider-crank.toml", "dyade-16.toml"):
        out = CliRunner(env={"COLUMNS": "200"}).invoke(
            main, ["clearance", str(shipped(name)), "--stiffness", "1e8", "--clearance", "1e-4",
                   "--format", "csv"], catch_exceptions=False)
        assert out.exit_code == 0, out.output
        rows = list(csv.DictReader(io.StringIO(out.stdout)))
        in_csv = {row["joint"] for row in rows}
        mechanism = toml_input.read_mechanism(shipped(name))
        for joint in mechanism.joints:
            if joint.kind != "R":
                continue
            a, b = joint.name
            told = f"joint ({a},{b}):" in out.stderr
            assert told != (f"{a}-{b}" in in_csv), (name, joint.name)
        for row in rows:
            assert float(row["F_max"]) > float(row["F_rigid"]) > 0


def test_a_mechanism_without_forces_is_an_input_error():
    out = CliRunner().invoke(main, ["clearance", str(shipped("scotch-yoke.toml")), "--joint", "2,4",
                                    "--stiffness", "1e8", "--clearance", "1e-4"],
                             catch_exceptions=False)
    assert out.exit_code == 2  # no masses in the file: no forces to check
    assert "needs joint forces" in out.output


def test_speed_study_slope_grows_with_the_cube_of_speed(tmp_path):
    # scotch yoke with a 2 kg yoke: the pin force is m·r·Ω²·cos φ, so F0/t0 = m·r·Ω³
    path = tmp_path / "yoke.toml"
    path.write_text(shipped("scotch-yoke.toml").read_text().replace(
        'points = { R = [120, 0] }', 'points = { R = [120, 0] }\nmass = 2.0'))
    out = CliRunner().invoke(main, ["clearance", str(path), "--joint", "2,4", "--stiffness", "1e8",
                                    "--clearance", "1e-4", "--mass", "1", "--speed-range",
                                    "300:900:300", "--format", "csv"], catch_exceptions=False)
    assert out.exit_code == 0, out.output
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    speed = np.array([float(r["speed_rpm"]) for r in rows])
    slope = np.array([float(r["slope"]) for r in rows])
    assert speed.tolist() == [300, 300, 600, 600, 900, 900]
    omega = speed * 2 * np.pi / 60
    assert np.allclose(slope, 2.0 * 0.05 * omega ** 3, rtol=2e-4)  # secant over 1°


def test_analyse_runs_the_check_only_with_clearance_data(monkeypatch):
    result = analysis.analyse(toml_input.read_mechanism(shipped("dyade-16.toml")))
    assert result.plan.clearance == ((2, 7),)
    assert len(result.clearance) == 1 and len(result.clearance[0].reversals) == 2

    def must_not_run(*args, **kwargs):
        raise AssertionError("clearance check ran without clearance data")

    monkeypatch.setattr(joint_clearance, "check_mechanism", must_not_run)
    assert analysis.analyse(toml_input.read_mechanism(shipped("fourbar.toml"))).clearance is None


def test_max_wander_reaches_the_check():
    args = ["clearance", str(shipped("dyade-16.toml")), "--joint", "13,14", "--stiffness", "1e8",
            "--clearance", "1e-4", "--format", "csv"]
    strict = CliRunner().invoke(main, args, catch_exceptions=False)
    assert "joint (13,14): not checked" in strict.stderr and "wanders up to 33°" in strict.stderr
    relaxed = CliRunner().invoke(main, args + ["--max-wander", "40"], catch_exceptions=False)
    assert "\n13-14," in relaxed.stdout


def test_force_lines_are_the_reversals_of_the_check():
    # the polar diagram's reversals and the clearance check's come from one computation
    result = analysis.analyse(toml_input.read_mechanism(shipped("dyade-16.toml")))
    lines = joint_clearance.force_lines(result)
    checks = dyade.check_clearance(result.mechanism, stiffness=1e8, clearance=1e-4,
                                   result=result)
    assert [line.joint for line in lines] == [check.joint for check in checks]
    assert sum(len(line.reversal_angles) for line in lines) > 2
    for line, check in zip(lines, checks):
        assert line.applies == check.applies
        found = np.mod(line.reversal_angles, 2 * np.pi)
        assert found.tolist() == [rev.crank_angle for rev in check.reversals]
        if line.applies:  # at a reversal the force is across its line of action
            u = np.array([np.cos(line.line_angle), np.sin(line.line_angle)])
            size = np.linalg.norm(line.reversal_forces, axis=1)
            assert np.all(np.abs(line.reversal_forces @ u) <= 1e-9 * (1 + size))


def test_force_lines_need_forces_and_a_revolute_joint():
    result = analysis.analyse(toml_input.read_mechanism(shipped("scotch-yoke.toml")))
    with pytest.raises(analysis.InputError, match="needs joint forces"):
        joint_clearance.force_lines(result)
    result = analysis.analyse(toml_input.read_mechanism(shipped("slider-crank.toml")))
    with pytest.raises(analysis.InputError, match="no revolute joint \\(1,4\\)"):
        joint_clearance.force_lines(result, [(4, 1)])


@pytest.mark.parametrize("mass, stiffness, gap, slope", [
    (3.6, 1e7, 1e-4, 3.6e5), (0.2, 1e8, 5e-5, 1e4), (10.0, 1e6, 2e-4, 5e6)])
def test_contact_force_solves_the_contact_equation(mass, stiffness, gap, slope):
    # eq. (26) is the solution of m·u'' + c·u = k·t with u(t1) = 0, u'(t1) = v1 and
    # F = c·u: check the ODE by central differences, the initial values and the peak
    peak = clearance.peak_force(mass, stiffness, clearance=gap, slope=slope)
    omega = np.sqrt(stiffness / mass)
    h = 1e-3 / omega
    t = peak.t1 + np.linspace(0.1, 6.0, 50) / omega
    force = clearance.contact_force(peak, t)
    second = (clearance.contact_force(peak, t + h) - 2 * force
              + clearance.contact_force(peak, t - h)) / h ** 2
    residual = mass * second / stiffness + force - slope * t
    assert np.max(np.abs(residual)) < 1e-5 * np.max(np.abs(slope * t))
    assert clearance.contact_force(peak, [0.0, 0.5 * peak.t1, peak.t1]).tolist() == [0, 0, 0]
    small = 1e-6 / omega
    start = clearance.contact_force(peak, peak.t1 + small) / small / stiffness
    assert start == pytest.approx(peak.v1, rel=1e-5)       # forward difference: O(ω·small)
    fine = peak.t1 + np.linspace(0.0, peak.time_to_peak - peak.t1, 20001)
    assert clearance.contact_force(peak, fine).max() == pytest.approx(peak.force, rel=1e-9)


def test_simulated_history_follows_the_closed_form_to_the_peak():
    peak = clearance.peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5)
    sim = clearance.simulate(3.6, 1e7, clearance=1e-4, slope=3.6e5, history=True)
    assert sim.time.size == sim.contact_force.size == sim.steps + 1
    assert np.all(np.diff(sim.time) > 0)
    assert np.all(sim.contact_force[sim.time < sim.t1 * (1 - 1e-12)] == 0.0)
    until = sim.time <= sim.time_to_peak
    closed = clearance.contact_force(peak, sim.time[until])
    assert np.max(np.abs(sim.contact_force[until] - closed)) < 1e-6 * peak.force
    plain = clearance.simulate(3.6, 1e7, clearance=1e-4, slope=3.6e5)
    assert plain.time is None and plain.force == sim.force
