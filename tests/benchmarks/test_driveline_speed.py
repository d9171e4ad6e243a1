"""The drive line's stability scan (issue 37) against its yardstick, the scan dyade had
before: every speed alone, one batch of Newton iterations on 720 steps from the linear
response (``machine.drive_line.periodic``: no accuracy check, no continuation). dyade-16
on 1000 N·m/rad and 0.04 N·m·s/rad over 3000–4495 rpm in steps of 5 (300 speeds; 10
under CI=true, where the benchmarks run once untimed):

    pytest tests/benchmarks/test_driveline_speed.py --benchmark-enable \
        --benchmark-columns=min,median,rounds

The issue asks for the new scan (steps by accuracy, the branch followed by
continuation, every solution at each speed, the energy balance) within 5x of the old.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

import dyade
from dyade.linkage import drive_line as api
from dyade.linkage.drive import crank_shaft
from dyade.machine import drive_line as engine
from tests.helpers import shipped

LINE = {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.04}
SPEEDS = (np.linspace(3000.0, 4495.0, 10) if os.environ.get("CI")
          else np.arange(3000.0, 4496.0, 5.0))  # [rpm]


@pytest.fixture(scope="module")
def mechanism():
    return dyade.read_mechanism(shipped("dyade-16.toml"), LINE)


def old_scan(mechanism):
    """The scan before issue 37: one batch, 720 steps, Newton from the linear guess."""
    shaft = crank_shaft(mechanism)
    line = shaft.ideal_line
    tables = shaft.tables_at(engine.MIN_STEPS)
    lanes = engine.Lanes.of(line, SPEEDS / engine_rpm())
    solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
    engine.integrate(line, tables, lanes, solution.start)
    return solution


def engine_rpm() -> float:
    from dyade.units import RAD_PER_S_TO_RPM

    return RAD_PER_S_TO_RPM


def test_stability_scan(benchmark, mechanism):
    curve = benchmark.pedantic(api.resonance_curve, (mechanism, SPEEDS), rounds=1,
                               iterations=1)
    assert curve.converged.all()


def test_stability_scan_before_yardstick(benchmark, mechanism):
    solution = benchmark.pedantic(old_scan, (mechanism,), rounds=1, iterations=1)
    assert solution.converged.all()


def test_the_same_verdicts(mechanism):
    """Like for like: where both have a solution, the same largest |μ| (the old one on
    720 steps, to its accuracy)."""
    curve = api.resonance_curve(mechanism, SPEEDS[:: max(1, SPEEDS.size // 10)],
                                follow=False)
    shaft = crank_shaft(mechanism)
    line = shaft.ideal_line
    tables = shaft.tables_at(engine.MIN_STEPS)
    lanes = engine.Lanes.of(line, curve.speed)
    old = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
    assert np.allclose(curve.stability, old.stability, atol=1e-6)
