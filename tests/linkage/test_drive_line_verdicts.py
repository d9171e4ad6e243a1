"""Every verdict of the drive line's scan confirmed by an independent integration (issue
37), on the slider-crank of the issue (``slider-crank-line.toml``: r = 0.1 m, l = 0.4 m,
a 5 kg slider, crank and rod massless, J_c on the crank, an ideal motor through
k = 1e4 N·m/rad and damping d).

The confirmation shares nothing with the engine: the crank shaft in closed form (the
slider's x(φ) and its derivatives, not the engine's tables), the line in time s = Ω·t
for every row (the crank at φ = s − twist; a row the scan solved in the crank angle u
starts at s₀ = its twist at u = 0, where φ = 0: the two period maps are conjugate, the
multipliers the same), scipy's DOP853 at rtol 1e-11 on ONE stacked state of all rows
(each row: the orbit, a perturbed orbit and the variational equations Φ' = A·Φ). After
one period: the orbit is periodic, Φ(2π) is the monodromy matrix (its |μ| against the
scan's); over ``PERIODS`` periods the perturbation grows or decays per period as |μ|
says (projected on the dominant multiplier's left eigenvector for a real one, the area
spanned by successive perturbations for a complex pair). At rtol 1e-12 the |μ| change by
7e-11 and the periodicity by 5e-12 (of the state's scale): the integration is not what
the tolerances below measure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from dyade.machine import drive_line as engine
from dyade.machine import periodic
from tests.linkage.test_drive_line_branches import slider

CRANK, ROD, SLIDER = 0.1, 0.4, 5.0  # [m], [m], [kg]: slider-crank-line.toml
PERIODS = 8  # [-] periods of the long integration
RTOL = 1e-11  # [-] DOP853's relative tolerance
EPSILON = 1e-6  # [-] the perturbation, of the state's scale, at most ...
GROWN = 1e-3  # [-] ... and smaller where it would grow beyond this in PERIODS (linear)
PERIODIC = 1e-6  # [-] x(2π) − x(0) of a row's orbit for DOP853, of the state's scale
SAME_MU = 1e-6  # [-] |μ| of the scan against the variational equations (the scan's
# own accuracy: periodic.ACCURACY)
SAME_GROWTH = 1e-3  # [-] relative: the perturbation's growth per period against |μ|


def closed_form(phi, inertia: float):
    """J(φ) [kg·m²], J′(φ) [kg·m²/rad] and J″(φ) [kg·m²/rad²] of the slider-crank
    without offset: x = r·cos φ + √(l² − r²·sin² φ), J = J_c + m·x′²; with
    q = r·cos φ/w, p = r·sin φ/w (w = √(l² − r²·sin² φ)): x′ = −r·sin φ·(1 + q),
    q′ = −p·(1 − q²), p′ = q·(1 + p²)."""
    s, c = np.sin(phi), np.cos(phi)
    w = np.sqrt(ROD * ROD - CRANK * CRANK * s * s)
    q, p = CRANK * c / w, CRANK * s / w
    dq = -p * (1.0 - q * q)
    ddq = -q * (1.0 + p * p) * (1.0 - q * q) + 2.0 * p * q * dq
    x1 = -CRANK * s * (1.0 + q)
    x2 = -CRANK * c * (1.0 + q) - CRANK * s * dq
    x3 = CRANK * s * (1.0 + q) - 2.0 * CRANK * c * dq - CRANK * s * ddq
    return (inertia + SLIDER * x1 * x1, 2.0 * SLIDER * x1 * x2,
            2.0 * SLIDER * (x2 * x2 + x1 * x3))


@dataclass
class Confirmed:
    """What DOP853 saw of each row (n rows)."""

    miss: np.ndarray  # (n,) max |x(2π) − x(0)| over the state's scale [-]
    monodromy: np.ndarray  # (n, 2, 2) Φ(2π) [-]
    stability: np.ndarray  # (n,) its largest |μ| [-]
    pair: np.ndarray  # (n,) bool: that μ is one of a complex pair
    growth: np.ndarray  # (n,) the perturbation's growth per period [-]
    seconds: float


@dataclass
class Line:
    """The line of the confirmation: J_c [kg·m²], k [N·m/rad], d [N·m·s/rad]; the
    damping's sign is a handle for a mutation test."""

    inertia: float
    stiffness: float
    damping: float
    damping_sign: float = 1.0


def phase(start, in_time):
    """The motor's angle s₀ [rad] of each row's start: 0 in time; in the crank angle its
    twist (u = 0: φ = s − twist = 0)."""
    return np.where(in_time, 0.0, start[:, 1])


def flow(line: Line, speed, s0, span, start, push, periods: int, rtol: float = RTOL):
    """DOP853 on one stacked state of n runs, the independent variable σ ∈ [0, periods]
    with the motor's angle s = s0 + span·σ per run: (8, n, periods) at σ = 1 … periods,
    per run the orbit from ``start`` (n, 2), the orbit from ``start + push`` and Φ
    (∂x/∂x(0), row by row); the seconds it took."""
    import time

    integrate = pytest.importorskip("scipy.integrate")
    n = speed.size
    k, b = line.stiffness, line.damping_sign * line.damping

    def rates(sigma, flat):
        y = flat.reshape(8, n)
        out = np.empty_like(y)
        for a in (0, 2):  # the orbit, the perturbed orbit
            inertia, slope, curve = closed_form(s0 + span * sigma - y[a + 1], line.inertia)
            v = speed + y[a]
            out[a] = (k * y[a + 1] - b * y[a] - 0.5 * slope * v * v) / (inertia * speed)
            out[a + 1] = -y[a] / speed
            if a == 0:  # A = ∂f/∂x along the orbit
                a00 = (-b - slope * v) / (inertia * speed)
                a01 = (k + 0.5 * curve * v * v) / (inertia * speed) + out[0] * slope / inertia
                a10 = -1.0 / speed
        phi = y[4:].reshape(2, 2, n)
        out[4:6] = a00 * phi[0] + a01 * phi[1]
        out[6:8] = a10 * phi[0]
        return (out * span).ravel()

    y0 = np.concatenate([start.T, (start + push).T, np.repeat(np.eye(2).reshape(4, 1), n, 1)])
    ends = np.arange(1, periods + 1, dtype=float)
    clock = time.perf_counter()
    out = integrate.solve_ivp(rates, (0.0, ends[-1]), y0.ravel(), method="DOP853", rtol=rtol,
                              atol=1e-14, t_eval=ends)
    assert out.success, out.message
    return out.y.reshape(8, n, periods), time.perf_counter() - clock


def confirm(line: Line, speed, start, in_time, scale, expected, periods: int = PERIODS,
            rtol: float = RTOL) -> Confirmed:
    """Integrate every row at once (see the module's docstring). ``speed`` (n,) Ω
    [rad/s], ``start`` (n, 2) the row's state (δv [rad/s], twist [rad]) at u = 0 or, where
    ``in_time``, at s = 0; ``scale`` (n, 2) the state's scale; ``expected`` (n,) a |μ|
    that sizes the perturbation (it stays below GROWN of the scale)."""
    n = speed.size
    size = np.minimum(EPSILON, GROWN / np.maximum(expected, 1.0) ** periods)
    push = size[:, None] * scale * np.array([1.0, 0.7])  # any direction
    y, seconds = flow(line, speed, phase(start, in_time), 2.0 * math.pi, start, push, periods,
                      rtol)
    miss = np.max(np.abs(y[0:2, :, 0].T - start) / scale, axis=1)
    monodromy = np.moveaxis(y[4:, :, 0].reshape(2, 2, n), 2, 0)
    mu, vectors = np.linalg.eig(monodromy)
    top = np.argmax(np.abs(mu), axis=1)
    lead = mu[np.arange(n), top]
    pair = np.abs(lead.imag) > periodic.REAL * np.abs(lead)
    d = np.concatenate([push.T[:, :, None], y[2:4] - y[0:2]], axis=2)  # (2, n, periods + 1)
    # a complex pair: the area spanned by successive perturbations shrinks by μ·μ̄ per
    # period, whatever the direction
    area = np.abs(d[0, :, :-1] * d[1, :, 1:] - d[1, :, :-1] * d[0, :, 1:])
    by_area = (area[:, -1] / area[:, 0]) ** (0.5 / max(periods - 1, 1))
    # a real μ: the share along its left eigenvector grows by |μ| per period exactly
    left = np.linalg.inv(vectors)[np.arange(n), top]  # (n, 2)
    share = np.abs(np.einsum("nj,jnk->nk", left, d))
    along = (share[:, -1] / share[:, 0]) ** (1.0 / periods)
    return Confirmed(miss, monodromy, np.abs(lead), pair, np.where(pair, by_area, along),
                     seconds)


NEWTON = 1e-10  # [-] the residual of x(2π) − x(0), of the state's scale, of an orbit found
LEAP, LOST = 0.5, 5.0  # [-] Newton's longest step and the residual it gives up at (scale)
SAME_ORBIT = 1e-5  # [-] two states on one orbit, of the state's scale (the scan's: 1e-6)


def newton(line: Line, speed, s0, guess, scale, iterations: int = 12):
    """Periodic orbits of the line by Newton's method on DOP853's period map from the
    motor's angle ``s0`` (n,), Φ(2π) − I its Jacobian, all runs at once (each step at
    most LEAP of the state's scale; a run whose residual exceeds LOST of it is given up):
    the states (n, 2) and which converged to NEWTON."""
    x = np.array(guess, dtype=float)
    done = np.zeros(speed.size, dtype=bool)
    live = np.ones(speed.size, dtype=bool)
    for _ in range(iterations):
        go = np.flatnonzero(live & ~done)
        if not go.size:
            break
        y, _ = flow(line, speed[go], s0[go], 2.0 * math.pi, x[go], np.zeros((go.size, 2)), 1)
        residual = y[0:2, :, 0].T - x[go]
        size = np.max(np.abs(residual) / scale[go], axis=1)
        done[go] = size <= NEWTON
        live[go] = np.isfinite(size) & (size <= LOST)
        jacobian = np.moveaxis(y[4:, :, 0].reshape(2, 2, -1), 2, 0) - np.eye(2)
        step = -np.linalg.solve(jacobian, residual[:, :, None])[:, :, 0]
        leap = np.max(np.abs(step) / scale[go], axis=1)
        step *= np.minimum(1.0, LEAP / np.where(leap > 0.0, leap, 1.0))[:, None]
        move = live[go] & ~done[go]
        x[go[move]] += step[move]
    return x, done


def on_orbit(line: Line, speed, s0, x, s1, target, scale):
    """(n,) bool: the orbit through ``x`` at the motor's angle ``s0`` passes ``target`` at
    ``s1`` (carried from s0 to s1 by DOP853)."""
    span = np.mod(s1 - s0, 2.0 * math.pi)
    y, _ = flow(line, speed, s0, span, x, np.zeros_like(x), 1)
    return np.all(np.abs(y[0:2, :, 0].T - target) <= SAME_ORBIT * scale, axis=1)


def unlisted(line: Line, curve, scale) -> list:
    """The periodic orbits one speed step away from a row that the scan does not list:
    each row's orbit continued to the neighbouring speeds by Newton on DOP853's period
    map (the continuation the scan claims to do), each orbit found compared with every
    row at that speed: (η, |μ|, the seed's number) of each orbit not listed."""
    ok = curve.converged
    eta = np.round(curve.eta[ok], 9)
    speeds, index = np.unique(eta, return_inverse=True)
    speed, start, s0 = curve.speed[ok], curve.start[ok], phase(curve.start[ok],
                                                                curve.in_time[ok])
    seeds = [(r, j) for r in range(eta.size) for j in (index[r] - 1, index[r] + 1)
             if 0 <= j < speeds.size]
    rows_at = [np.flatnonzero(index == j) for j in range(speeds.size)]
    to = np.array([rows_at[j][0] for _, j in seeds])  # a row of the target speed
    frm = np.array([r for r, _ in seeds])
    x, done = newton(line, speed[to], s0[frm], start[frm], scale[to])
    found = []  # distinct orbits per target speed: (seed, target)
    pairs = [(i, r) for i, (_, j) in enumerate(seeds) if done[i] for r in rows_at[j]]
    if pairs:
        i, r = np.array(pairs).T
        listed = on_orbit(line, speed[r], s0[frm[i]], x[i], s0[r], start[r], scale[r])
        for k in np.flatnonzero(done):
            if not listed[i == k].any():
                found.append(k)
    out = []
    for k in found:  # one per distinct orbit
        j = seeds[k][1]
        y, _ = flow(line, speed[to[k:k + 1]], s0[frm[k:k + 1]], 2.0 * math.pi, x[k:k + 1],
                    np.zeros((1, 2)), 1)
        mu = float(np.max(np.abs(np.linalg.eigvals(y[4:, 0, 0].reshape(2, 2)))))
        if not any(abs(e - speeds[j]) < 1e-12 and abs(m - mu) < 1e-6 for e, m, _ in out):
            out.append((float(speeds[j]), mu, k))
    return out


def test_the_closed_form_is_the_files_crank_shaft():
    """The confirmation's crank shaft is the file's: J and J′ against the engine's tables
    (on 1 440 points) to round-off, J″ against a central difference of J′, no load."""
    shaft = slider(0.01, 0.7526)
    tables = shaft.tables_at(720)
    phi = np.arange(tables.inertia.size) * math.pi / 720
    inertia, slope, curve = closed_form(phi, 0.01)
    assert np.max(np.abs(inertia - tables.inertia)) < 1e-15
    assert np.max(np.abs(slope - tables.slope)) < 1e-15
    assert not np.any(tables.load) and not np.any(tables.friction)
    h = 1e-5
    numeric = (closed_form(phi + h, 0.01)[1] - closed_form(phi - h, 0.01)[1]) / (2 * h)
    assert np.max(np.abs(curve - numeric)) < 1e-8 * np.max(np.abs(curve))


def scan(inertia: float, damping: float, eta):
    from dyade.linkage import drive_line as api

    shaft = slider(inertia, damping)
    rpm = np.asarray(eta) * shaft.frequency.omega_bar * 30.0 / math.pi
    curve = api.resonance_curve(shaft.mechanism, rpm, shaft=shaft)
    line = shaft.ideal_line
    scale = engine.problem(line, shaft.tables_at, 720).scale(
        engine.parameters(line, curve.speed))
    return shaft, curve, scale


def line_of(shaft, inertia: float, damping: float, damping_sign: float = 1.0) -> Line:
    return Line(inertia, float(shaft.line.stiffness[0]), damping, damping_sign)


def confirmed(shaft, curve, scale, inertia: float, damping: float, damping_sign: float = 1.0,
              **options) -> Confirmed:
    """``confirm`` of every converged row of a scan (``curve``) of ``shaft``."""
    ok = curve.converged
    return confirm(line_of(shaft, inertia, damping, damping_sign), curve.speed[ok],
                   curve.start[ok], curve.in_time[ok], scale[ok], curve.stability[ok],
                   **options)


LOW = (0.01, 0.7526)  # J_c [kg·m²], d [N·m·s/rad]: the flip region, the crank turning back
LOW_ETA = np.round(np.arange(0.6, 1.3 + 1e-9, 0.025), 6)  # 29 speeds: the scan costs
# 38 s (0.005: 141 speeds, 163 s; the continuation's 400 single-lane integrations are 65 %)


@pytest.fixture(scope="module")
def low():
    """The scan of η 0.6–1.3 with J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad and DOP853's
    view of every converged row."""
    shaft, curve, scale = scan(*LOW, LOW_ETA)
    return shaft, curve, scale, confirmed(shaft, curve, scale, *LOW)


def kinds_of(curve) -> dict:
    """The rows by kind: stable in u, stable in time (the crank nearly stops or turns
    back), each kind of instability; and coexisting (a speed with several rows)."""
    ok = curve.converged
    eta = np.round(curve.eta[ok], 9)
    _, inverse, counts = np.unique(eta, return_inverse=True, return_counts=True)
    kind = np.array(curve.kind, dtype=object)[ok]
    out = {"stable": (kind == "") & ~curve.in_time[ok],
           "stable in time": (kind == "") & curve.in_time[ok],
           "coexisting": counts[inverse] > 1}
    for name in set(kind) - {""}:
        out[name] = kind == name
    return out


def check_every_row(curve, seen: Confirmed, eta) -> None:
    """Every speed asked has a converged row (no row without one); every converged row
    is periodic for DOP853, its |μ| is Φ(2π)'s to SAME_MU, its verdict is Φ(2π)'s and
    the long integration's: a perturbation grows or decays per period as |μ| says."""
    assert np.all(curve.converged), [r for r in curve.reason if r]
    have = np.unique(np.round(curve.eta, 9))
    assert np.allclose(have, eta, rtol=0, atol=1e-9)
    mu = curve.stability
    assert np.max(seen.miss) <= PERIODIC
    assert np.max(np.abs(seen.stability - mu)) <= SAME_MU
    margin = 1.0 + periodic.UNSTABLE_MARGIN
    assert np.array_equal(seen.stability > margin, curve.unstable)
    assert np.max(np.abs(seen.growth / mu - 1.0)) <= SAME_GROWTH
    clear = np.abs(mu - 1.0) > 2 * SAME_GROWTH  # the growth tells the verdict there
    assert np.array_equal((seen.growth > 1.0)[clear], curve.unstable[clear])
    # the kind: a complex pair is a Neimark–Sacker row, a real μ beyond −1 a flip, +1 a fold
    kind = np.array(curve.kind, dtype=object)
    lead = np.array([complex(periodic.ordered(np.linalg.eigvals(m)[None, :])[0, 0])
                     for m in seen.monodromy])
    unstable = curve.unstable
    assert np.all((kind[unstable] == periodic.TORUS) == seen.pair[unstable])
    assert np.all((kind[unstable] == periodic.FLIP) == (~seen.pair & (lead.real < 0))[unstable])
    assert np.all((kind[unstable] == periodic.FOLD) == (~seen.pair & (lead.real > 0))[unstable])


def worst(curve, seen: Confirmed) -> dict:
    """The worst |μ| disagreement per kind of row (for the report)."""
    gap = np.abs(seen.stability - curve.stability)
    return {name: float(np.max(gap[rows])) for name, rows in kinds_of(curve).items()
            if rows.any()}


MISSED = (1.075, 1.1, 1.125)  # η where the scan of LOW_ETA does not list the orbit
# DOP853's Newton continues from a neighbouring row: saddles (|μ| = 2.54, 2.32, 2.06) of
# the unstable stretch between the folds at η 0.9778 and 1.1131 (the scan reports the
# folds; it carries stable motions only). Every stable one is listed since the carried
# branches are continued where a shot one speed step on fails (before: also the
# turning-back motion at 0.975 and 1.025 and the 0.89 family at 1.025 and 1.15).


@pytest.mark.slow
def test_every_verdict_in_the_flip_region_and_beyond_is_confirmed(low):
    """J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad, η 0.6–1.3 every 0.025: stable rows, the
    flip region (a multiplier below −1, η ≈ 0.67–0.92), a saddle beside a stable orbit
    (η = 0.925), saddles (a multiplier above +1) — every row confirmed; and each row's
    orbit continued one speed step by Newton on DOP853's period map is a row there,
    except at the speeds of MISSED (issue 37's open end): a coexisting row dropped (the
    stable orbit beside the saddle at η = 0.925) is seen. (One test: the scan is made
    once, whichever worker runs it.)"""
    shaft, curve, scale, seen = low
    check_every_row(curve, seen, LOW_ETA)
    rows = kinds_of(curve)
    assert rows["coexisting"].any() and rows[periodic.FLIP].any() and rows[periodic.FOLD].any()
    print(f"\nη 0.6–1.3: {curve.speed.size} rows, DOP853 {seen.seconds:.1f} s; worst |Δμ| "
          + ", ".join(f"{k}: {v:.1e}" for k, v in worst(curve, seen).items()))
    missing = unlisted(line_of(shaft, *LOW), curve, scale)
    print("unlisted:", [(eta, mu) for eta, mu, _ in missing])
    assert {round(eta, 6) for eta, _, _ in missing} <= set(MISSED), missing


HIGH = (0.2, 1.899)  # J_c [kg·m²], d [N·m·s/rad]: the crank at 5.6 % of Ω near η = 0.5
HIGH_ETA = np.round(np.arange(0.46, 0.54 + 1e-9, 0.002), 6)  # 41 speeds: 45 s (0.48–0.52,
# 21 speeds: 42 s; 0.49–0.51 alone converges nowhere; 0.2–1.6, 701 speeds: 102 s, the
# continuation's 400 single-lane integrations 64 %, the meshes' shootings 26 %; DOP853
# confirms all 701 rows in 2.8 s); the steady state at η = 0.5 costs 39 s (reached from
# 0.9·Ω on 11 520 steps)


@pytest.fixture(scope="module")
def high():
    """The scan of the near-stop stretch η 0.46–0.54 every 0.002 with J_c = 0.2 kg·m²,
    d = 1.899 N·m·s/rad, DOP853's view of every row, the steady state at η = 0.5."""
    from dyade.linkage import drive_line as api

    shaft, curve, scale = scan(*HIGH, HIGH_ETA)
    steady = api.steady_state(shaft.mechanism, shaft=shaft,
                              speed_rpm=0.5 * shaft.frequency.omega_bar * 30.0 / math.pi)
    return shaft, curve, scale, confirmed(shaft, curve, scale, *HIGH), steady


def works(line: Line, speed: float, start) -> tuple[float, float]:
    """The motor's work ∮ T·Ω dt = ∮ T ds and the damping's ∮ d·δv² dt [J] over one
    period of the orbit from ``start`` (at u = 0) by DOP853 (T = k·twist − d·δv)."""
    integrate = pytest.importorskip("scipy.integrate")
    s0 = float(start[1])

    def rates(s, y):
        inertia, slope, _ = closed_form(s - y[1], line.inertia)
        v = speed + y[0]
        torque = line.stiffness * y[1] - line.damping * y[0]
        return [(torque - 0.5 * slope * v * v) / (inertia * speed), -y[0] / speed, torque,
                line.damping * y[0] ** 2 / speed]

    out = integrate.solve_ivp(rates, (s0, s0 + 2.0 * math.pi), [start[0], start[1], 0.0, 0.0],
                              method="DOP853", rtol=RTOL, atol=1e-14)
    return float(out.y[2, -1]), float(out.y[3, -1])


@pytest.mark.slow
def test_every_verdict_where_the_crank_nearly_stops_is_confirmed(high):
    """J_c = 0.2 kg·m², d = 1.899 N·m·s/rad (issue 37: 10 of 701 speeds near η = 0.5
    had no periodic state): a converged periodic solution at every η in 0.46–0.54 every
    0.002, the crank down to 5.6 % of Ω, each verdict confirmed. And at η = 0.5
    (the crank at 5.6 % of Ω): ``steady_state`` finds the scan's stable orbit; over the period the motor's work is the damping's (no load: the slider runs
    level) to 1e-6 of it in its own figures, and its motor's work is DOP853's along its
    orbit to 1e-6 (where it closes to 2e-9, the energy the start's 1e-8 off periodic).
    (One test: the scan is made once, whichever worker runs it.)"""
    shaft, curve, scale, seen, steady = high
    check_every_row(curve, seen, HIGH_ETA)
    assert np.min(curve.slowest) < 0.06
    print(f"\nη 0.46–0.54: {curve.speed.size} rows, DOP853 {seen.seconds:.1f} s; worst |Δμ| "
          + ", ".join(f"{k}: {v:.1e}" for k, v in worst(curve, seen).items()))
    row = int(np.argmin(np.abs(curve.eta - 0.5)))
    speed = float(curve.speed[row])
    assert steady.stable and np.abs(steady.multipliers[0]) == pytest.approx(
        curve.stability[row], abs=SAME_MU)
    start = np.array([steady.crank_speed[0] - speed, steady.twist[0]])
    assert np.all(np.abs(start - curve.start[row]) <= 1e-5 * scale[row])
    assert min(steady.crank_speed) / speed == pytest.approx(curve.slowest[row], abs=1e-4)
    f = steady.figures
    motor, damping = f["work_motor"], f["work_damping"]
    assert abs(f["work_load"]) < 1e-12 and abs(f["work_friction"]) < 1e-12
    balance = abs(motor - damping) / motor
    assert balance <= 1e-6
    seen_motor, seen_damping = works(line_of(shaft, *HIGH), speed, start)
    assert seen_motor == pytest.approx(seen_damping, rel=1e-8)  # the start: periodic to 1e-8
    assert motor == pytest.approx(seen_motor, rel=1e-6)
    print(f"\nη = 0.5: motor {motor:.6g} J, damping {damping:.6g} J, balance {balance:.1e}; "
          f"DOP853 {seen_motor:.6g} J")
