"""The drive line's branches carried (issue 37): the turning-back motion of the
slider-crank (J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad, ``slider-crank-line.toml``)
beyond the speeds where the crank-angle shooting fails, its fold, and the period-2
motion of dyade-16 where the period-1 orbit flips; each claim checked by scipy's
DOP853 (an integrator that shares nothing with the engine's RK4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import drive_line as engine
from dyade.machine import periodic
from tests.linkage.test_drive_line_branches import (independent_in_time,
                                                     largest_multiplier, rates_of,
                                                     slider)

# the turning-back motion at η = 1.1011 (its state at s = 0 [rad/s, rad]), as the scan's
# carried in-time branch passes it: a guess of the shooting, not an answer
TURNING_BACK = (1.10113, [688.3917, 0.440641])


@pytest.mark.slow
def test_the_turning_back_motion_lives_past_the_gap_and_ends_in_a_fold():
    """The stable motion with |μ| ≈ 0.80 whose crank turns back (η 0.965–1.02 in the
    scan before) exists beyond η = 1.025: shot in time at η = 1.10 it converges, the
    crank turns back (slowest speed below zero), DOP853 finds it periodic, and DOP853
    started at η = 1.10 from it perturbed by 1e-2 of the scale settles back on it (a
    stable motion the machine keeps). Continued in time in speed, the branch turns back
    at the fold η ≈ 1.1131 (|μ| → +1 there): beyond the fold DOP853 from the branch's
    last state leaves it."""
    shaft = slider(0.01, 0.7526)
    line = shaft.ideal_line
    omega_bar = shaft.frequency.omega_bar
    in_time = engine.problem_in_time(line, shaft.tables_at, 720)
    eta, guess = TURNING_BACK
    p = engine.parameters(line, [1.10 * omega_bar])
    found = periodic.shoot(in_time, p, np.array([guess]))
    assert found.converged[0], found.reason
    mu = float(found.stability[0])
    assert 0.79 < mu < 0.81
    speed = float(p[0, 0])
    start = found.start[0]
    scale = in_time.scale(p)[0]
    path = periodic.trajectory(in_time, int(found.steps[0]), found.start, p)
    assert np.min(speed + path[:, 0, 0]) < -0.3 * speed  # the crank turns back
    assert np.all(np.abs(independent_in_time(shaft, speed, start) - start) <= 1e-6 * scale)
    runs = independent_in_time(shaft, speed, start + 1e-2 * scale, periods=40, every=True)
    distance = np.max(np.abs(runs - start) / scale, axis=1)
    assert np.max(distance[-5:]) < 1e-3 and np.max(distance[-5:]) < np.max(distance[:5])
    # the fold: continuation in time from η = 1.10 upwards
    branch = periodic.continuation(in_time, start, p[0], (speed, 1.12 * omega_bar),
                                   steps=1440, direction=1.0, most=30, ds=0.1,
                                   integrations=100, width=0.7 * omega_bar)
    upper = [fold for fold in branch.folds if fold.upper]
    assert upper, branch.stopped
    assert upper[0].parameter / omega_bar == pytest.approx(1.1131, abs=2e-4)
    # beyond the fold (η = 1.115) the motion from the branch's state before the fold
    # goes elsewhere: after 60 revolutions far from where it started
    last = upper[0].index
    runs = independent_in_time(shaft, 1.115 * omega_bar, branch.start[last], periods=60,
                               every=True)
    assert np.max(np.abs(runs[-1] - branch.start[last]) / scale) > 0.1


@pytest.mark.slow
def test_dyade_16_flips_at_3575_rpm_into_a_large_period_two_motion():
    """dyade-16 on k = 1000 N·m/rad, d = 0.04 N·m·s/rad at 3575 rpm (η ≈ 2.0, the
    principal parametric resonance): the period-1 orbit flips (μ ≈ −1.039) and no
    period-2 orbit lies within the pushes along its flip direction. A long integration
    from it (DOP853, 400 revolutions) settles on a period-2 motion about 1.7 rad of twist
    away; ``period_two`` finds that orbit (through its own long integration): DOP853
    finds it periodic over two revolutions and not over one, the same |μ| over two
    revolutions (central differences of DOP853 runs), and the long run ends on it."""
    import dyade
    from dyade.linkage import drive_line as api
    from dyade.linkage.drive import crank_shaft
    from tests.helpers import shipped

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"), {
        "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    shaft = crank_shaft(mechanism)
    two = api.period_two(mechanism, [3575.0], shaft=shaft)
    assert two.found[0], two.reason
    assert np.real(two.single[0, 0]) < -1.03  # the period-1 orbit flips
    mu = float(two.stability[0])
    assert mu < 1.0 and two.twist_amplitude[0] > 1.0  # stable, and large
    speed = 3575.0 * math.pi / 30.0
    line = shaft.ideal_line
    p = engine.parameters(line, [speed])
    scale = engine.problem_in_time(line, shaft.tables_at, 720).scale(p)[0]
    start = two.start[0]
    after_one = independent_in_time(shaft, speed, start)
    assert np.all(np.abs(independent_in_time(shaft, speed, after_one) - start) <= 1e-6 * scale)
    assert np.max(np.abs(after_one - start) / scale) > 1.0  # not the period-1 orbit
    assert largest_multiplier(lambda x: independent_in_time(shaft, speed, x, 2), start,
                              scale) == pytest.approx(mu, abs=1e-4)
    # what the machine does: from the unstable period-1 orbit, pushed by 1e-1 of the
    # scale, it leaves it and settles on the period-2 motion (either of its two phases)
    in_time = engine.problem_in_time(line, shaft.tables_at, 720)
    guess = engine.linear_guess(line, shaft.tables_at(720), engine.Lanes.of(line, p[:, 0]))
    single = periodic.shoot(in_time, p, guess).start[0]
    integrate = pytest.importorskip("scipy.integrate")
    rates = rates_of(shaft, speed, True)
    end = integrate.solve_ivp(rates, (0.0, 2 * math.pi * 400),
                              single + 0.1 * scale * np.array([-1.0, 0.0]), method="DOP853",
                              rtol=1e-8, atol=1e-10).y[:, -1]
    # the phases 1.7 rad of twist apart, the period-1 orbit as far: within 3 % of the scale
    miss = min(np.max(np.abs(end - point) / scale) for point in (start, after_one))
    assert miss < 3e-2 and np.max(np.abs(end - single) / scale) > 1.0
