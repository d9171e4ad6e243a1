"""The scan's verdicts confirmed by long integrations (issue 37): on the slider-crank of
the issue with J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad (``slider-crank-line.toml``), a
sample of speeds in η 0.6–1.3 (stable, the flip region, the turning-back branch, the
unstable branch beyond the fold): the periodic orbit dyade finds, perturbed and
integrated for many periods by scipy's DOP853 (an integrator that shares nothing with
the engine's RK4), grows or decays per period as dyade's |μ| says."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import drive_line as engine
from dyade.machine import periodic
from tests.linkage.test_drive_line_branches import slider

SAMPLE = (  # η, solved in time (the crank turns back there), what the row is
    (0.6, False, "stable"),
    (0.8, False, "the flip region: unstable, a multiplier below −1"),
    (1.0, True, "the crank turns back for a moment: stable, a complex pair"),
    (1.05, True, "the unstable branch beyond the fold: a multiplier above +1"),
    (1.3, False, "stable, a complex pair"),
)
EPSILON = 1e-6  # [-] the perturbation, of the state's scale, at most
GROWN = 1e-3  # [-] ... and smaller where it would grow beyond this (still linear)
PERIODS = 6  # [-] periods integrated (a complex pair: the area ratio holds from the first)
SETTLE = 12  # [-] ... for a real μ: the other multiplier's share dies out (μ2/μ1 ≤ 0.51)


def rates_of(shaft, speed: float, in_time: bool):
    """The line's rates for scipy, several states at once (columns of x): in the crank
    angle u or in time s = Ω·t, the tables as Fourier series (``engine.Periodic1D``)."""
    tables = shaft.tables_at(720)
    series = [engine.Periodic1D(values[0::2]) for values in (tables.inertia, tables.slope,
                                                             tables.load)]

    def at(table):  # the series at several angles at once
        return lambda phi: (np.exp(1j * np.multiply.outer(phi, table.orders))
                            @ table.coefficients).real

    inertia, slope, load = (at(table) for table in series)
    k, b = shaft.line.stiffness[0], shaft.line.damping[0]

    def rates(s, flat):
        x = flat.reshape(2, -1)
        phi = s - x[1] if in_time else np.full(x.shape[1], s)
        v = speed + x[0]
        torque = k * x[1] - b * x[0]
        accel = torque + load(phi) - 0.5 * slope(phi) * v * v
        out = (np.array([accel / (inertia(phi) * speed), -x[0] / speed]) if in_time
               else np.array([accel / (inertia(phi) * v), -x[0] / v]))
        return out.ravel()

    return rates


def growth(shaft, speed: float, start, direction, in_time: bool, periods: int,
           pair: bool) -> float:
    """|μ| seen by DOP853 (rtol 1e-11): the orbit and the orbit perturbed by
    ``direction`` integrated side by side for ``periods`` periods; their difference
    d_k after k periods grows as |μ|^k: for a complex ``pair`` of multipliers the
    square root of the area ratio det[d_k, d_(k+1)]/det[d_(k−1), d_k] (= μ·μ̄ per
    period for any perturbation), the geometric mean over the periods after the first;
    for a real μ the ratio |d_k|/|d_(k−1)| over the last two periods (the other
    multiplier's share died out by then)."""
    integrate = pytest.importorskip("scipy.integrate")
    x0 = np.column_stack([start, start + direction]).ravel()
    ends = 2 * math.pi * np.arange(1, periods + 1)
    out = integrate.solve_ivp(rates_of(shaft, speed, in_time), (0.0, ends[-1]), x0,
                              method="DOP853", rtol=1e-11, atol=1e-14, t_eval=ends)
    assert out.success
    runs = out.y.reshape(2, 2, -1)  # (state, run, period)
    d = np.concatenate([direction[:, None], runs[:, 1] - runs[:, 0]], axis=1)  # (2, k)
    if pair:
        area = np.abs(d[0, :-1] * d[1, 1:] - d[1, :-1] * d[0, 1:])
        return float((area[-1] / area[1]) ** (0.5 / (area.size - 2)))
    size = np.linalg.norm(d, axis=0)
    return float((size[-1] / size[-3]) ** 0.5)


@pytest.fixture(scope="module")
def rows():
    """dyade's periodic orbits at the sample's speeds: shot in crank angle, or in time
    where the crank turns back (as the scan does), all of a kind at once."""
    shaft = slider(0.01, 0.7526)
    line = shaft.ideal_line
    eta = np.array([row[0] for row in SAMPLE])
    timed = np.array([row[1] for row in SAMPLE])
    p = engine.parameters(line, eta * shaft.frequency.omega_bar)
    guess = engine.linear_guess(line, shaft.tables_at(720), engine.Lanes.of(line, p[:, 0]))
    start = np.empty((eta.size, 2))
    monodromy = np.empty((eta.size, 2, 2))
    scale = np.empty((eta.size, 2))
    for in_time in (False, True):
        idx = np.flatnonzero(timed == in_time)
        problem = (engine.problem_in_time if in_time else engine.problem)(
            line, shaft.tables_at, 720)
        found = periodic.shoot(problem, p[idx], guess[idx])
        assert found.converged.all(), found.reason
        start[idx], monodromy[idx] = found.start, found.monodromy
        scale[idx] = problem.scale(p[idx])
    return shaft, p[:, 0], start, monodromy, scale


@pytest.mark.slow
@pytest.mark.parametrize("k", range(len(SAMPLE)), ids=[f"eta={row[0]}" for row in SAMPLE])
def test_a_perturbation_grows_or_decays_per_period_as_the_multiplier_says(rows, k):
    shaft, speed, start, monodromy, scale = rows
    eta, in_time, what = SAMPLE[k]
    mu = complex(periodic.ordered(np.linalg.eigvals(monodromy[k])[None, :])[0, 0])
    pair = abs(mu.imag) > periodic.REAL * abs(mu)
    periods = PERIODS if pair or abs(mu) > 1.5 else SETTLE
    size = min(EPSILON, GROWN / max(abs(mu), 1.0) ** periods)
    direction = size * scale[k] * np.array([1.0, 0.7])  # no eigenvector: any direction
    seen = growth(shaft, float(speed[k]), start[k], direction, in_time, periods, pair)
    assert seen == pytest.approx(abs(mu), rel=1e-3), what
    # the verdict: unstable exactly where the long integration grows
    assert (seen > 1.0) == (abs(mu) > 1.0 + periodic.UNSTABLE_MARGIN)
