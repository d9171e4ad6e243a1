"""The periodic-orbit engine (``dyade.machine.periodic``) on a forced Duffing oscillator
x'' + c·x' + α·x + β·x³ = F·cos(ωt), written in τ = ωt over one period 2π."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import periodic as P


def duffing(c: float, alpha: float, beta: float, force: float, steps: int = 128) -> P.Problem:
    def field(n):
        cos = np.cos(math.pi / n * np.arange(2 * n + 1))

        def f(k, x, p):
            w = p[:, 0]
            out = np.empty_like(x)
            out[:, 0] = x[:, 1]
            out[:, 1] = (force * cos[k] - c * w * x[:, 1] - alpha * x[:, 0]
                         - beta * x[:, 0] ** 3) / w ** 2
            return out
        return f
    def field_at(s, x, p):
        w = p[:, 0]
        return np.column_stack((x[:, 1], (force * np.cos(s) - c * w * x[:, 1] - alpha * x[:, 0]
                                          - beta * x[:, 0] ** 3) / w ** 2))

    def pace(x, p):  # nodes gathered where |x| is large (a test of the mesh)
        return 1.0 + 10.0 * x[..., 0] ** 2 / np.max(x[..., 0] ** 2, axis=0)

    return P.Problem(2, field, lambda p: np.ones((p.shape[0], 2)), steps=steps,
                     field_at=field_at, pace=pace)


def backbone(amplitude: float, alpha: float = 1.0, beta: float = 1.0) -> float:
    """The exact frequency of the free undamped Duffing oscillator of amplitude A:
    ω = π·√(α + βA²) / (2·K(m)), m = βA² / (2(α + βA²))."""
    special = pytest.importorskip("scipy.special")
    m = beta * amplitude ** 2 / (2.0 * (alpha + beta * amplitude ** 2))
    return math.pi * math.sqrt(alpha + beta * amplitude ** 2) / (2.0 * special.ellipk(m))


def test_the_undamped_backbone_against_the_elliptic_integral():
    # a forcing of 1e-7 holds the orbit on the backbone: its amplitude x(0) (x'(0) = 0)
    # at the frequency ω_bb(A) reads back as ω_bb(x(0)) = ω to 1e-6. (On the backbone of
    # an undamped oscillator the amplitude is ill-conditioned, ∂A/∂ω large: the solution
    # changes by more than the tolerance with the steps; the frequency is what is sharp.)
    problem = duffing(0.0, 1.0, 1.0, 1e-7)
    amplitude = np.array([0.5, 1.0, 1.5])
    omega = np.array([backbone(a) for a in amplitude])
    found = P.shoot(problem, omega[:, None], np.column_stack((amplitude, 0 * amplitude)),
                    steps=512, doublings=0)
    assert np.isfinite(found.start).all(), found.reason
    assert not found.converged.any()  # no second step count compared: no verdict
    # the amplitude from the energy α·A²/2 + β·A⁴/4 = α·x²/2 + β·x⁴/4 + (ω·dx/dτ)²/2
    x, y = found.start[:, 0], found.start[:, 1]
    energy = x ** 2 / 2 + x ** 4 / 4 + (omega * y) ** 2 / 2
    reached = np.sqrt(np.sqrt(1.0 + 4.0 * energy) - 1.0)
    error = [backbone(a) / w - 1.0 for a, w in zip(reached, omega)]
    assert np.max(np.abs(error)) < 1e-6, error


def test_a_linear_oscillator_against_its_closed_form():
    # β = 0: x = X·cos τ with X = F/(α − ω²) (c = 0); the multipliers exp(±2πi·√α/ω)
    problem = duffing(0.0, 1.0, 0.0, 0.3, steps=64)
    omega = np.array([0.7, 1.7])
    found = P.shoot(problem, omega[:, None], np.zeros((2, 2)))
    assert found.converged.all()
    assert np.allclose(found.start[:, 0], 0.3 / (1.0 - omega ** 2), rtol=1e-6)
    angle = np.sort(np.abs(np.angle(found.multipliers)), axis=1)[:, 0]
    expected = np.mod(2 * np.pi / omega, 2 * np.pi)
    expected = np.minimum(expected, 2 * np.pi - expected)
    assert np.allclose(angle, expected, atol=1e-6)


def test_a_mesh_of_its_own_per_lane_against_the_closed_form():
    """Each lane on its own mesh (``mesh_of``: nodes by the pace, here gathered where
    |x| is large, up to 11 times denser): the same closed form as on the uniform grid,
    the steps halved (``refined``) until the solution changes by less than 1e-6, and the
    mesh's RK4 converges like h⁴ (the change falls 16-fold per halving)."""
    problem = duffing(0.0, 1.0, 0.0, 0.3, steps=64)
    omega = np.array([0.7, 1.7])
    exact = 0.3 / (1.0 - omega ** 2)
    guess = np.column_stack((exact, 0.0 * exact))
    mesh = P.mesh_of(problem, 64, guess, omega[:, None], 48)
    widths = np.diff(mesh, axis=1)
    assert np.allclose(mesh[:, -1], 2 * np.pi) and (widths > 0).all()
    assert np.all(widths.max(axis=1) / widths.min(axis=1) > 5.0)  # not uniform
    found = P.shoot(problem, omega[:, None], np.zeros((2, 2)), mesh=mesh)
    assert found.converged.all(), found.reason
    assert np.allclose(found.start[:, 0], exact, rtol=1e-6)
    angle = np.sort(np.abs(np.angle(found.multipliers)), axis=1)[:, 0]
    expected = np.mod(2 * np.pi / omega, 2 * np.pi)
    expected = np.minimum(expected, 2 * np.pi - expected)
    assert np.allclose(angle, expected, atol=1e-6)
    assert [m.size for m in found.mesh] == list(found.steps + 1)
    errors = [abs(P.flow(problem, 0, guess, omega[:, None], mesh=m)[:, 0] - exact).max()
              for m in (mesh, P.refined(mesh))]
    assert 10.0 < errors[0] / errors[1] < 24.0


def test_no_verdict_where_the_shooting_fails():
    problem = duffing(0.1, 1.0, 1.0, 0.5, steps=8)  # far too coarse: changes with the steps
    found = P.shoot(problem, [[1.2]], [[0.0, 0.0]], doublings=1, tol=1e-12)
    assert not found.converged[0] and found.reason[0]
    assert np.isnan(found.stability[0]) and not found.unstable[0]


def ramp_jump(c, alpha, beta, force, start, stop, rate, points=48):
    """The speed at which a slowly ramped forcing frequency jumps: RK4 in time with
    ω(t) = start ± rate·t (pure floats), the largest |x| of each forcing period; the jump
    is where that first changes by more than 1 % from one period to the next (after
    the start's transient, 60 periods; along a branch it changes by 0.03 % a period)."""
    x, v, theta, t, w = 0.0, 0.0, 0.0, 0.0, start
    sign = 1.0 if stop > start else -1.0
    h0 = 2 * math.pi / points
    peaks, speeds, peak, turn = [], [], 0.0, 1

    def acc(x, v, th):
        return force * math.cos(th) - c * v - alpha * x - beta * x * x * x

    while sign * (stop - w) > 0.0:
        h = h0 / w
        k1x, k1v = v, acc(x, v, theta)
        th2 = theta + 0.5 * h * w + 0.125 * sign * rate * h * h
        k2x, k2v = v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v, th2)
        k3x, k3v = v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v, th2)
        th4 = theta + h * w + 0.5 * sign * rate * h * h
        k4x, k4v = v + h * k3v, acc(x + h * k3x, v + h * k3v, th4)
        x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        theta, t, w = th4, t + h, w + sign * rate * h
        peak = max(peak, abs(x))
        if theta >= 2 * math.pi * turn:
            turn += 1
            peaks.append(peak)
            speeds.append(w)
            peak = 0.0
            if len(peaks) > 60 and abs(peaks[-1] / peaks[-2] - 1.0) > 0.01:
                return speeds[-2]
    return math.nan


@pytest.mark.slow
def test_fold_speeds_against_a_slow_ramp():
    c, alpha, beta, force = 0.2, 1.0, 1.0, 0.3
    problem = duffing(c, alpha, beta, force, steps=32)
    first = P.shoot(problem, [[0.6]], [[0.0, 0.0]], tol=1e-5)
    assert first.converged[0]
    branch = P.continuation(problem, first.start[0], [0.6], (0.6, 2.6),
                            steps=int(first.steps[0]) // 2)
    assert branch.stopped == ""
    upper = [f.parameter for f in branch.folds if f.upper]
    lower = [f.parameter for f in branch.folds if not f.upper]
    assert len(upper) == 1 and len(lower) == 1
    # between the folds the middle branch is a saddle: a real multiplier beyond +1
    between = (branch.parameter[:, 0] > lower[0]) & (branch.parameter[:, 0] < upper[0])
    assert {kind for kind, inside in zip(branch.kind, between) if inside} >= {P.FOLD}
    # a slow ramp jumps late by a delay ∝ rate^(2/3) (slow passage through a saddle-node,
    # Haberman 1979): two rates, extrapolated to rate 0
    r = 2.0 ** (-2.0 / 3.0)
    jumps = []
    for begin, end in ((0.9, 2.6), (2.0, 0.9)):
        fast, slow = (ramp_jump(c, alpha, beta, force, begin, end, rate)
                      for rate in (4e-5, 2e-5))
        jumps.append((slow - r * fast) / (1.0 - r))
    assert jumps[0] == pytest.approx(upper[0], rel=1e-3)
    assert jumps[1] == pytest.approx(lower[0], rel=1e-3)


# -- stability boundaries traced in a plane of two parameters ---------------------------
def mathieu(steps: int = 64) -> P.Problem:
    """Mathieu's equation x'' + (δ + ε·cos s)·x = 0, p = (δ, ε), over one period 2π."""
    def field(n):
        cos = np.cos(math.pi / n * np.arange(2 * n + 1))

        def f(k, x, p):
            return np.column_stack((x[:, 1], -(p[:, 0] + p[:, 1] * cos[k]) * x[:, 0]))
        return f
    return P.Problem(2, field, lambda p: np.ones((p.shape[0], 2)), steps=steps)


TONGUE_EPSILON = np.linspace(0.05, 0.01, 6)


@pytest.fixture(scope="module")
def first_tongue():
    """Both edges of Mathieu's first tongue traced from ε = 0.05 down to 0.01 (multiplier
    −1), each from a rough first guess δ = 1/4 ∓ 0.02."""
    problem = mathieu()
    return [P.boundary(problem, np.column_stack((np.full(TONGUE_EPSILON.size, guess),
                                                 TONGUE_EPSILON)),
                       np.zeros(2), crossing=-1.0, block=3)
            for guess in (0.23, 0.27)]


def test_the_traced_tongue_is_mathieus(first_tongue):
    """The edges of the first tongue: δ = 1/4 ± ε/2 to first order, the neglected term
    −ε²/8; with it, δ = 1/4 ± ε/2 − ε²/8 ∓ ε³/32 (Abramowitz & Stegun 20.2.25 with
    a = 4δ, q = −2ε)."""
    eps = TONGUE_EPSILON
    for edge, sign in zip(first_tongue, (-1.0, 1.0)):
        assert edge.converged.all(), edge.reason
        assert edge.kind == P.FLIP
        assert np.all(edge.accuracy <= P.ACCURACY)
        assert np.allclose(edge.multipliers, -1.0, atol=1e-6)
        delta = edge.parameter[:, 0]
        first = 0.25 + sign * eps / 2.0
        # to first order: off by the neglected term, −ε²/8 (not more, not less)
        assert np.all(np.abs((delta - first) / eps ** 2 + 0.125) <= 0.005)
        # to second order: off by the third-order term ∓ε³/32
        second = first - eps ** 2 / 8.0
        assert np.all(np.abs(delta - second) <= eps ** 3 / 32.0 * 1.1)
        third = second - sign * eps ** 3 / 32.0
        assert np.all(np.abs(delta - third) <= 1e-7)


def test_a_sampled_grid_agrees_with_the_traced_boundary(first_tongue):
    """Cells of a (δ, ε) grid shot one by one: unstable (a multiplier beyond −1) exactly
    inside the traced edges."""
    lower, upper = (edge.parameter[:, 0] for edge in first_tongue)
    delta = np.linspace(0.2013, 0.2987, 40)  # no cell on an edge
    eps = TONGUE_EPSILON[[0, 2, 5]]
    grid = np.array([(d, e) for e in eps for d in delta])
    cells = P.shoot(mathieu(), grid, np.zeros((grid.shape[0], 2)), doublings=1)
    assert cells.converged.all()
    inside = np.concatenate([(delta > lo) & (delta < hi) for lo, hi in
                             zip(lower[[0, 2, 5]], upper[[0, 2, 5]])])
    assert inside.any() and not inside.all()
    np.testing.assert_array_equal(cells.unstable, inside)
    assert set(k for k, i in zip(cells.kind, inside) if i) == {P.FLIP}


@pytest.mark.slow
def test_the_second_tongue_is_bounded_by_folds():
    """Mathieu's second tongue (multiplier +1): δ = 1 − ε²/12 + 5ε⁴/3456 and
    δ = 1 + 5ε²/12 − 763ε⁴/3456 to fourth order, off by the neglected terms
    −289ε⁶/4976640 and +1002401ε⁶/4976640 (A&S 20.2.25, b₂ and a₂ with a = 4δ,
    q = −2ε); with them, to O(ε⁸)."""
    problem = mathieu()
    eps = np.linspace(0.3, 0.1, 8)
    for guess, exact, sixth in ((0.99, 1 - eps ** 2 / 12 + 5 * eps ** 4 / 3456, -289.0),
                                (1.04, 1 + 5 * eps ** 2 / 12 - 763 * eps ** 4 / 3456,
                                 1002401.0)):
        edge = P.boundary(problem, np.column_stack((np.full(eps.size, guess), eps)),
                          np.zeros(2), crossing=1.0, block=4, reach=0.005)
        assert edge.converged.all(), edge.reason
        assert edge.kind == P.FOLD
        miss = edge.parameter[:, 0] - exact
        assert np.all(np.abs(miss - sixth / 4976640.0 * eps ** 6) <= 0.3 * eps ** 8 + 2e-8)
    # the upper edge's sixth-order term (2e-7 … 1.5e-4) is what the fourth order misses
    assert np.all(np.abs(miss / (sixth / 4976640.0 * eps ** 6) - 1.0) <= 0.1)
