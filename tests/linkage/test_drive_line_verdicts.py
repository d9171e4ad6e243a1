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


def confirm(inertia: float, stiffness: float, damping: float, speed, start, in_time, scale,
            expected, periods: int = PERIODS, rtol: float = RTOL,
            damping_sign: float = 1.0) -> Confirmed:
    """Integrate every row at once (see the module's docstring). ``speed`` (n,) Ω
    [rad/s], ``start`` (n, 2) the row's state (δv [rad/s], twist [rad]) at u = 0 or, where
    ``in_time``, at s = 0; ``scale`` (n, 2) the state's scale; ``expected`` (n,) a |μ|
    that sizes the perturbation (it stays below GROWN of the scale)."""
    import time

    integrate = pytest.importorskip("scipy.integrate")
    n = speed.size
    s0 = np.where(in_time, 0.0, start[:, 1])  # φ = s − twist = 0 there
    size = np.minimum(EPSILON, GROWN / np.maximum(expected, 1.0) ** periods)
    push = size[:, None] * scale * np.array([1.0, 0.7])  # any direction

    def rates(t, flat):
        y = flat.reshape(8, n)
        out = np.empty_like(y)
        for a in (0, 2):  # the orbit, the perturbed orbit
            inertia_, slope, curve = closed_form(t + s0 - y[a + 1], inertia)
            v = speed + y[a]
            out[a] = ((stiffness * y[a + 1] - damping_sign * damping * y[a]
                       - 0.5 * slope * v * v) / (inertia_ * speed))
            out[a + 1] = -y[a] / speed
            if a == 0:  # A = ∂f/∂x along the orbit
                a00 = (-damping_sign * damping - slope * v) / (inertia_ * speed)
                a01 = ((stiffness + 0.5 * curve * v * v) / (inertia_ * speed)
                       + out[0] * slope / inertia_)
                a10 = -1.0 / speed
        phi = y[4:].reshape(2, 2, n)
        out[4:6] = a00 * phi[0] + a01 * phi[1]
        out[6:8] = a10 * phi[0]
        return out.ravel()

    y0 = np.concatenate([start.T, (start + push).T, np.repeat(np.eye(2).reshape(4, 1), n, 1)])
    ends = 2.0 * math.pi * np.arange(1, periods + 1)
    clock = time.perf_counter()
    out = integrate.solve_ivp(rates, (0.0, ends[-1]), y0.ravel(), method="DOP853", rtol=rtol,
                              atol=1e-14, t_eval=ends)
    seconds = time.perf_counter() - clock
    assert out.success, out.message
    y = out.y.reshape(8, n, periods)
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


def confirmed(shaft, curve, scale, inertia: float, damping: float, **options) -> Confirmed:
    """``confirm`` of every converged row of a scan (``curve``) of ``shaft``."""
    ok = curve.converged
    return confirm(inertia, float(shaft.line.stiffness[0]), damping, curve.speed[ok], curve.start[ok],
                   curve.in_time[ok], scale[ok], curve.stability[ok], **options)


LOW = (0.01, 0.7526)  # J_c [kg·m²], d [N·m·s/rad]: the flip region, the crank turning back
LOW_ETA = np.round(np.arange(0.6, 1.3 + 1e-9, 0.025), 6)  # 29 speeds: a full scan costs
# 41 s (0.005: 141 speeds, 163 s; the continuation's 400 single-lane integrations are 65 %)


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


@pytest.mark.slow
def test_every_verdict_in_the_flip_region_and_beyond_is_confirmed(low):
    """J_c = 0.01 kg·m², d = 0.7526 N·m·s/rad, η 0.6–1.3 every 0.025: stable rows, the
    flip region (a multiplier below −1, η ≈ 0.67–0.92), a saddle beside a stable orbit
    (η = 0.925), saddles (a multiplier above +1) — every row confirmed."""
    shaft, curve, scale, seen = low
    check_every_row(curve, seen, LOW_ETA)
    rows = kinds_of(curve)
    assert rows["coexisting"].any() and rows[periodic.FLIP].any() and rows[periodic.FOLD].any()
    print(f"\nη 0.6–1.3: {curve.speed.size} rows, DOP853 {seen.seconds:.1f} s; worst |Δμ| "
          + ", ".join(f"{k}: {v:.1e}" for k, v in worst(curve, seen).items()))

