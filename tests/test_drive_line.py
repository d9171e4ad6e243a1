"""The elastic drive line (``dyade.machine.drive_line``, ``dyade.linkage.drive_line``):
closed forms, the Mathieu equation, the energy balance, the files and the command."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import drive_line as engine
from dyade.machine.motor import Asynchronous


def disc(steps: int, inertia: float, load: np.ndarray | None = None,
         epsilon: float = 0.0) -> engine.Tables:
    """A crank shaft of inertia J0·(1 + ε·cos 2u) with a load torque table."""
    u = math.pi / steps * np.arange(2 * steps)
    return engine.Tables(inertia * (1.0 + epsilon * np.cos(2 * u)),
                         -2.0 * epsilon * inertia * np.sin(2 * u),
                         np.zeros(2 * steps) if load is None else load, np.zeros(2 * steps))


def test_two_mass_forced_response_is_the_closed_form():
    """A disc (constant inertia) behind a shaft, an asynchronous motor with its rotor, a
    harmonic load torque M̂·sin(2φ): the steady state is the closed-form forced response
    of the two-mass system J_M·ÿ = −c·ẏ − k(y − x) − b(ẏ − ẋ), J·ẍ = k(y − x) + b(ẏ − ẋ)
    + M̂·sin(2Ωt) (c the motor's slope), to 1e-9. M̂ is small enough that the load's
    dependence on the vibrating angle (φ = Ωt + x) stays below that."""
    steps, crank, rotor, k, b, n = 1200, 0.5, 0.3, 5000.0, 3.0, 2
    ws, slope, amplitude = 100.0, 2.0, 1e-12
    u = math.pi / steps * np.arange(2 * steps)
    tables = disc(steps, crank, amplitude * np.sin(n * u))
    line = engine.Line((rotor,), (k,), (b,), Asynchronous(slope * 5.0, ws - 5.0, ws))
    lanes = engine.Lanes.of(line, [ws])
    solution = engine.periodic(line, tables, lanes, engine.rest_guess(line, tables, lanes))
    assert solution.converged.all()
    orbit = engine.integrate(line, tables, lanes, solution.start)
    w = n * ws
    kc = k + 1j * w * b
    system = np.array([[kc - w * w * rotor + 1j * w * slope, -kc], [-kc, kc - w * w * crank]])
    y, x = np.linalg.solve(system, np.array([0.0, -1j * amplitude]))  # sin: phasor −i
    t = orbit.step * np.arange(steps + 1) / ws
    twist = ((y - x) * np.exp(1j * w * t)).real
    speed = (1j * w * x * np.exp(1j * w * t)).real
    assert np.max(np.abs(orbit.state[:, 0, 1] - twist)) <= 1e-9 * np.max(np.abs(twist))
    assert np.max(np.abs(orbit.state[:, 0, 0] - speed)) <= 1e-9 * np.max(np.abs(speed))


def edges(epsilon: float, damping_ratio: float = 0.0) -> np.ndarray:
    """η = Ω/ω0 where the principal parametric region of J0·(1 + ε·cos 2φ) on a shaft
    (ideal motor, no load) starts and ends: where the largest |μ| crosses 1 (linear
    interpolation between 161 speeds)."""
    inertia, k = 2.0, 800.0
    omega0 = math.sqrt(k / inertia)
    eta = np.linspace(1.0 - epsilon, 1.0 + epsilon, 161)
    tables = disc(720, inertia, epsilon=epsilon)
    line = engine.Line((0.0,), (k,), (2.0 * damping_ratio * inertia * omega0,))
    lanes = engine.Lanes.of(line, eta * omega0)
    solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
    assert solution.converged.all()
    if damping_ratio == 0.0:  # det M = 1: unstable where |tr M| > 2
        measure = np.abs(np.sum(solution.multipliers, axis=1).real) - 2.0
    else:
        measure = np.abs(solution.multipliers[:, 0]) - 1.0
    cross = np.flatnonzero(np.diff(np.sign(measure)) != 0)
    return np.array([eta[i] - measure[i] * (eta[i + 1] - eta[i]) / (measure[i + 1] - measure[i])
                     for i in cross])


@pytest.mark.parametrize("epsilon", [pytest.param(0.02, marks=pytest.mark.slow), 0.04])
def test_first_parametric_region_is_mathieus(epsilon):
    """Linearised about the periodic motion, J = J0·(1 + ε·cos 2φ) on a shaft k gives
    d/dt(J·δẋ) + (k + ½·J″·Ω²)·δx = 0; with τ = Ωt and y = √J·δx (Liouville) it is,
    to first order in ε, Mathieu's y″ + (a − 2q·cos 2τ)·y = 0 with a = (ω0/Ω)², q = a·ε/2.
    Its first region of instability lies between a = 1 − q and a = 1 + q (Abramowitz &
    Stegun 20.2.25, b₁ and a₁ to first order in q; also Nayfeh & Mook, *Nonlinear
    Oscillations*, §5.2), so at η = Ω/ω0 = √(1 − ε/2) … √(1 + ε/2), to O(ε²)."""
    found = edges(epsilon)
    expected = np.sqrt([1.0 - epsilon / 2.0, 1.0 + epsilon / 2.0])
    assert found.size == 2
    assert np.all(np.abs(found - expected) <= 0.05 * epsilon ** 2)  # found: 0.016·ε²


@pytest.mark.slow
def test_damping_shrinks_the_region_and_removes_it_above_the_theory():
    """With viscous damping b (D = b/(2·J0·ω0)) the region is (a − 1)² = q² − 4β² with
    2β = b/(J0·Ω) (the same harmonic balance as A&S's first order): it shrinks, and it
    vanishes for D > ε/4."""
    epsilon = 0.04
    undamped = np.diff(edges(epsilon))[0]
    damped = edges(epsilon, damping_ratio=epsilon / 8.0)
    assert damped.size == 2 and np.diff(damped)[0] < 0.9 * undamped
    width = math.sqrt(1.0 + math.sqrt((epsilon / 2) ** 2 - (epsilon / 4) ** 2)) - math.sqrt(
        1.0 - math.sqrt((epsilon / 2) ** 2 - (epsilon / 4) ** 2))
    assert abs(np.diff(damped)[0] - width) <= epsilon ** 2
    assert edges(epsilon, damping_ratio=epsilon / 4.0 * 1.2).size == 0
