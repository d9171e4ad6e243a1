"""The drive line on the periodic-orbit engine (issue 37): steps by accuracy, no verdict
from an orbit that is not periodic, every solution at a speed, speeds as η. The
slider-crank of the issue: r = 0.1 m, l = 0.4 m, a 5 kg slider, crank and rod massless,
J_c on the crank, an ideal motor through k = 1e4 N·m/rad and damping d
(``slider-crank-line.toml`` beside this file)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import dyade
from dyade.registry import REGISTRY
from dyade.linkage.drive import crank_shaft
from dyade.machine import drive_line as engine
from dyade.machine import periodic
from tests.helpers import shipped

HERE = Path(__file__).parent
SLIDER = str(HERE / "slider-crank-line.toml")
LINE = {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.04}


def slider(inertia: float, damping: float):
    mechanism = dyade.read_mechanism(SLIDER, {"links.2.inertia": inertia,
                                              "drive_line.damping": damping})
    return crank_shaft(mechanism)


def rates_of(shaft, speed: float, in_time: bool):
    """The line's rates for scipy, of one state or of several at once (the columns of
    x): in the crank angle u, or in time s = Ω·t (the crank at φ = s − twist), the crank
    shaft's tables as Fourier series (``engine.Periodic1D``): they share nothing with
    the engine's RK4 on its grid."""
    tables = shaft.tables_at(720)
    inertia, slope, load = (engine.Periodic1D(values[0::2]).at
                            for values in (tables.inertia, tables.slope, tables.load))
    k, b = shaft.line.stiffness[0], shaft.line.damping[0]

    def rates(s, flat):
        x = np.reshape(flat, (2, -1))
        phi = s - x[1] if in_time else np.full(x.shape[1], s)
        v = speed + x[0]
        accel = k * x[1] - b * x[0] + load(phi) - 0.5 * slope(phi) * v * v
        pace = speed if in_time else v  # ds/dt = Ω; du/dt = the crank's speed
        return np.array([accel / (inertia(phi) * pace), -x[0] / pace]).reshape(np.shape(flat))

    return rates


def independent(shaft, speed: float, start, revolutions: int = 1):
    """x(2π·revolutions) of the line by scipy's DOP853 at rtol 1e-11 over u
    (``rates_of``): an integrator that shares nothing with the engine's RK4 on the
    grid."""
    integrate = pytest.importorskip("scipy.integrate")
    rates = rates_of(shaft, speed, False)
    out = integrate.solve_ivp(rates, (0.0, 2 * math.pi * revolutions), start, method="DOP853",
                              rtol=1e-11, atol=1e-13)
    return out.y[:, -1]


@pytest.mark.slow
def test_no_verdict_without_a_periodic_orbit_and_multipliers_converge_with_the_steps():
    """J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad. At η = 0.58 the shooting from the linear
    response does not converge (the crank turns back in the iterations): no verdict (not
    converged, no |μ|, not unstable, a reason). At η = 0.6 (the crank falls to 37 % of
    Ω in the cycle) the multipliers converge like RK4's h⁴ as the steps grow (360, 720,
    1440: the change falls by more than 8 per doubling) and agree with an independent
    integration of the same orbit (scipy's DOP853): periodic there too, the same |μ|."""
    shaft = slider(0.01, 0.7526)
    line = shaft.ideal_line
    problem = engine.problem(line, shaft.tables_at, 720)

    def shot(eta, doublings):
        speed = eta * shaft.frequency.omega_bar
        p = engine.parameters(line, [speed])
        guess = engine.linear_guess(line, shaft.tables_at(720), engine.Lanes.of(line, [speed]))
        return speed, p, periodic.shoot(problem, p, guess, doublings=doublings)

    _, _, lost = shot(0.58, 1)
    assert not lost.converged[0] and "did not converge" in lost.reason[0]
    assert np.isnan(lost.stability[0]) and not lost.unstable[0]
    speed, p, found = shot(0.6, 2)
    assert found.converged[0], found.reason
    assert found.accuracy[0] <= periodic.ACCURACY
    mu = []
    for n in (360, 720, 1440):
        _, ok, _, jac, _ = periodic.newton(problem, n, p, found.start, problem.scale(p))
        assert ok[0]
        mu.append(np.max(np.abs(np.linalg.eigvals(jac[0]))))
    assert abs(mu[2] - mu[1]) < abs(mu[1] - mu[0]) / 8.0  # RK4: 1/16 per doubling
    start = found.start[0]
    scale = problem.scale(p)[0]
    assert np.all(np.abs(independent(shaft, speed, start) - start) <= 1e-6 * scale)
    seen = largest_multiplier(lambda x: independent(shaft, speed, x), start, scale)
    assert seen == pytest.approx(found.stability[0], abs=1e-5)


def test_eta_range_gives_the_rows_of_the_equivalent_speed_range():
    omega_bar = crank_shaft(dyade.read_mechanism(shipped("dyade-16.toml"), LINE)).frequency.omega_bar
    settings = [f"{key}={value}" for key, value in LINE.items()]
    by_eta = REGISTRY["driveline-stability"](shipped("dyade-16.toml"), set=settings,
                                             eta_range="1.95:1.95:0.05")
    speeds = [eta * omega_bar * 30.0 / math.pi for eta in (1.95,)]
    by_speed = REGISTRY["driveline-stability"](shipped("dyade-16.toml"), set=settings,
                                               speed_range_rpm=speeds)
    assert list(by_eta.columns) == list(by_speed.columns)
    for name, values in by_eta.columns.items():
        other = by_speed.columns[name]
        if np.asarray(values).dtype.kind == "f":
            assert np.allclose(values, other, rtol=1e-9, equal_nan=True), name
        else:
            assert list(values) == list(other), name
    assert np.allclose(by_eta.columns["eta"], [1.95])
    # the energy balance over the period closes (motor = damping − loads' work) and the
    # solution did not change with twice the steps
    assert by_eta.columns["converged"].all() and np.max(by_eta.columns["balance"]) < 1e-7
    assert np.max(by_eta.columns["accuracy"]) <= periodic.ACCURACY
    assert by_eta.options["eta_range"] == "1.95:1.95:0.05"


class Ran(Exception):
    pass


@pytest.mark.parametrize("entry, options, work", [
    ("driveline-steady", {"set": ["drive_line.stiffness=1e7"]}, "steady_state"),
    ("driveline-stability", {"set": ["drive_line.stiffness=1e7"],
                             "speed_range_rpm": "300:400:50"}, "resonance_curve"),
])
def test_a_stiff_line_says_its_estimate_before_the_work(monkeypatch, entry, options, work):
    """Issue 42: a line of 1e7 N·m/rad (41 354 steps per revolution) is estimated from
    its steps and a measured rate before anything is integrated: refused above
    --max-time, said above 5 s. A slow rate (monkeypatched) keeps the test cheap."""
    from dyade.analyses import drive_line as entries
    from dyade.errors import InputError
    from dyade.linkage import drive_line as api

    monkeypatch.setattr(entries, "SECONDS_PER_STEP", 1e-2)

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(api, work, ran)
    with pytest.raises(InputError, match="max_time_s.*about"):
        REGISTRY[entry](shipped("dyade-16.toml"), **options, max_time_s=1.0)
    told = []
    with pytest.raises(Ran):
        REGISTRY[entry](shipped("dyade-16.toml"), **options, told=told.append)
    assert told and "about" in told[0] and "steps per revolution" in told[0]


@pytest.mark.slow
def test_the_speed_reaches_the_natural_frequency_block():
    """--speed is the run's speed everywhere: Ω and η = Ω/ω̄ of the natural-frequency
    block are at it, not at the file's 300 rpm."""
    outcome = REGISTRY["driveline-frequency"](shipped("dyade-16.toml"), set=["drive_line.stiffness=1000"])
    assert outcome.value("speed_rpm") == pytest.approx(300.0)
    steady = REGISTRY["driveline-steady"](shipped("dyade-16.toml"), set=[
        "drive_line.stiffness=1000", "drive_line.damping=0.04", "drive_line.steps=360"],
        speed_rpm=150.0)
    assert steady.value("speed_rpm") == pytest.approx(150.0)
    assert steady.value("speed_ratio") == pytest.approx(
        150.0 * math.pi / 30.0 / steady.value("omega_bar"), rel=1e-12)
    assert steady.value("eta") == pytest.approx(steady.value("speed_ratio"), rel=1e-3)


@pytest.mark.parametrize("args, words", [
    (["--eta-range", "1:2:0.1", "--speed-range", "100:200:10"], "give one of the two"),
    (["--eta-range", "0:2:0.1"], "must lie in (0, 100]"),
])
def test_a_bad_eta_range_exits_2_naming_the_flag(args, words):
    from click.testing import CliRunner

    from dyade.cli import main

    out = CliRunner().invoke(main, ["driveline", str(shipped("dyade-16.toml")), "--set",
                                    "drive_line.stiffness=1000", "--analysis", "stability",
                                    *args])
    assert out.exit_code == 2 and "--eta-range" in out.output and words in out.output
    assert "Traceback" not in out.output


@pytest.mark.slow
def test_a_near_stop_speed_on_a_mesh_of_its_own_against_an_independent_integration():
    """J_c = 0.2 kg·m², d = 1.899 N·m·s/rad, η = 0.506: the uniform grid's shooting fails
    up to 11 520 steps (the crank falls to a quarter of Ω). Shot from the neighbouring
    speed's solution on a mesh of its own (the nodes gathered by (Ω/v)² where the crank
    is slow), the solution converges on 1 440 steps to 1e-6 and is periodic for scipy's
    DOP853 at rtol 1e-11 too, with the same largest |μ| (its monodromy matrix by central
    differences of DOP853 runs): a perturbation decays as |μ| says."""
    shaft = slider(0.2, 1.899)
    line = shaft.ideal_line
    problem = engine.problem(line, shaft.tables_at, 1440)
    omega_bar = shaft.frequency.omega_bar

    def p_of(eta):
        return engine.parameters(line, [eta * omega_bar])

    p = p_of(0.512)
    guess = engine.linear_guess(line, shaft.tables_at(1440), engine.Lanes.of(line, p[:, 0]))
    x, p_from, mesh = periodic.shoot(problem, p, guess).start, p, None
    for eta in (0.509, 0.506):
        mesh = periodic.mesh_of(problem, 2880 if mesh is None else 0, x, p_from, 1440, mesh)
        found = periodic.shoot(problem, p_of(eta), x, mesh=mesh)
        assert found.converged[0], found.reason
        x, p_from, mesh = found.start, p_of(eta), np.array(found.mesh)
    assert found.steps[0] <= 2880 and found.accuracy[0] <= periodic.ACCURACY
    path = periodic.trajectory(problem, 0, x, p_from, mesh=mesh)
    speed = float(p_from[0, 0])
    assert np.min(speed + path[:, 0, 0]) < 0.3 * speed  # the crank nearly stops
    start = x[0]
    scale = problem.scale(p_from)[0]
    assert np.all(np.abs(independent(shaft, speed, start) - start) <= 1e-6 * scale)
    seen = largest_multiplier(lambda x: independent(shaft, speed, x), start, scale)
    assert seen == pytest.approx(found.stability[0], abs=1e-5)


def largest_multiplier(period_map, start, scale) -> float:
    """The largest |μ| of the orbit through ``start``: the monodromy matrix of
    ``period_map`` (a state -> the state a period later, e.g. ``independent``) by central
    differences, steps of 1e-4 of ``scale``."""
    delta = scale * 1e-4
    columns = [(period_map(start + delta[i] * np.eye(2)[i])
                - period_map(start - delta[i] * np.eye(2)[i])) / (2 * delta[i])
               for i in range(2)]
    return float(np.max(np.abs(np.linalg.eigvals(np.column_stack(columns)))))


def independent_in_time(shaft, speed: float, start, periods: int = 1, every: bool = False):
    """x(2π·periods) of the line in time (s = Ω·t, the crank at φ = s − twist) by
    scipy's DOP853 at rtol 1e-11 (``rates_of``): shares nothing with
    ``engine.problem_in_time``'s RK4. ``every``: x at each period."""
    integrate = pytest.importorskip("scipy.integrate")
    rates = rates_of(shaft, speed, True)
    ends = 2 * math.pi * np.arange(1, periods + 1)
    out = integrate.solve_ivp(rates, (0.0, ends[-1]), start, method="DOP853", rtol=1e-11,
                              atol=1e-13, t_eval=ends if every else None)
    return out.y.T if every else out.y[:, -1]


@pytest.mark.slow
def test_where_the_crank_turns_back_the_line_is_solved_in_time():
    """J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad (issue 37: 12 of 141 speeds at η 0.965–1.02
    were "not converged"). At η = 1 the crank turns back for a moment in the stable
    periodic motion (its slowest speed below zero): its angle is no variable there, time
    is. In time (``engine.problem_in_time``) the shooting converges (steps by accuracy);
    scipy's DOP853 in time finds the orbit periodic, the same |μ| (central differences of
    its runs), and a perturbation integrated for 30 periods decays as |μ| per period. At
    η = 0.6 (the crank never slow) the multipliers in time are those in crank angle (the
    two period maps are conjugate)."""
    shaft = slider(0.01, 0.7526)
    line = shaft.ideal_line
    omega_bar = shaft.frequency.omega_bar
    eta = np.array([0.6, 1.0])
    p = engine.parameters(line, eta * omega_bar)
    guess = engine.linear_guess(line, shaft.tables_at(720), engine.Lanes.of(line, p[:, 0]))
    in_time = engine.problem_in_time(line, shaft.tables_at, 720)
    found = periodic.shoot(in_time, p, guess)
    assert found.converged.all(), found.reason
    # η = 0.6 in crank angle: the same multipliers
    in_angle = engine.problem(line, shaft.tables_at, 720)
    angle = periodic.shoot(in_angle, p[:1], guess[:1])
    assert angle.converged[0]
    assert np.allclose(np.sort_complex(angle.multipliers[0]),
                       np.sort_complex(found.multipliers[0]), atol=2e-6)
    # η = 1: the crank turns back; DOP853 in time agrees
    path = periodic.trajectory(in_time, int(found.steps[1]), found.start[1:], p[1:])
    speed = float(p[1, 0])
    assert np.min(speed + path[:, 0, 0]) < -0.05 * speed
    start = found.start[1]
    scale = in_time.scale(p[1:])[0]
    assert np.all(np.abs(independent_in_time(shaft, speed, start) - start) <= 1e-6 * scale)
    delta = scale * 1e-4
    columns = [(independent_in_time(shaft, speed, start + delta[i] * np.eye(2)[i])
                - independent_in_time(shaft, speed, start - delta[i] * np.eye(2)[i]))
               / (2 * delta[i]) for i in range(2)]
    mu = float(found.stability[1])
    assert np.max(np.abs(np.linalg.eigvals(np.column_stack(columns)))) == pytest.approx(
        mu, abs=1e-5)
    assert mu < 1.0
    # Liouville: det M = exp(∮ trace) = exp(−b·∫ dt/J(φ)) (J′·φ̇/J integrates to zero over
    # the period), the integral by DOP853 along the orbit: a closed form of μ1·μ2
    integrate = pytest.importorskip("scipy.integrate")
    inertia = engine.Periodic1D(shaft.tables_at(720).inertia[0::2])
    twist = engine.Periodic1D(path[:-1, 0, 1])  # the orbit's twist as its Fourier series
    dwell = integrate.quad(lambda s: 1.0 / (inertia(s - twist(s)) * speed), 0.0, 2 * math.pi,
                           limit=400, epsabs=1e-13, epsrel=1e-12)[0]
    assert np.prod(found.multipliers[1]).real == pytest.approx(
        math.exp(-line.damping[0] * dwell), rel=1e-7)
    runs = independent_in_time(shaft, speed, start + 1e-3 * scale, periods=30, every=True)
    distance = np.max(np.abs(runs - start) / scale, axis=1)
    assert (distance[-1] / distance[9]) ** (1.0 / 20.0) == pytest.approx(mu, rel=0.02)


@pytest.mark.slow
def test_the_period_two_motion_where_the_period_one_orbit_flips():
    """J_c = 0.01, d = 0.7526, η = 0.8 (the flip region η ≈ 0.67–0.92): the only period-1
    orbit is unstable, a multiplier below −1. ``period_two`` finds the period-2 orbit
    from it; scipy's DOP853 started on the unstable period-1 orbit (displaced by 1e-2 of
    the scale) leaves it and settles on that period-2 motion, and the period-2
    multipliers by central differences of DOP853 runs over two revolutions agree."""
    from dyade.linkage import drive_line as api

    shaft = slider(0.01, 0.7526)
    speed = 0.8 * shaft.frequency.omega_bar
    two = api.period_two(shaft.mechanism, [speed * 30.0 / math.pi], shaft=shaft)
    assert two.found[0], two.reason
    assert np.real(two.single[0, 0]) < -1.0  # the period-1 orbit flips
    mu = float(two.stability[0])
    assert mu < 1.0  # the period-2 motion is stable
    start = two.start[0]
    problem = engine.problem_in_time(shaft.ideal_line, shaft.tables_at, 720)
    scale = problem.scale(engine.parameters(shaft.ideal_line, [speed]))[0]
    after_one = independent_in_time(shaft, speed, start)
    assert np.all(np.abs(independent_in_time(shaft, speed, after_one) - start) <= 1e-6 * scale)
    assert np.max(np.abs(after_one - start) / scale) > 1e-2  # not the period-1 orbit
    assert largest_multiplier(lambda x: independent_in_time(shaft, speed, x, 2), start,
                              scale) == pytest.approx(mu, abs=1e-5)
    # the unstable period-1 orbit: from the linear response, in time
    line = shaft.ideal_line
    p = engine.parameters(line, [speed])
    guess = engine.linear_guess(line, shaft.tables_at(720), engine.Lanes.of(line, p[:, 0]))
    single = periodic.shoot(problem, p, guess).start[0]
    runs = independent_in_time(shaft, speed, single + 1e-2 * scale, periods=100, every=True)
    settled = runs[-2:]  # the last two revolutions: the two points of the period-2 motion
    miss = min(np.max(np.abs(settled[0] - a) / scale) + np.max(np.abs(settled[1] - b) / scale)
               for a, b in ((start, after_one), (after_one, start)))
    assert miss < 1e-4
