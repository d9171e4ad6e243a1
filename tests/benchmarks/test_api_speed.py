"""The public API against the engine (issue 25): ``dyade.analyse(...).columns()`` beside
the engine's own sweep (``kinematics.sweep`` then ``kinetostatics.solve``, or
``friction.solve``) on the same mechanism and angles, in one run:

    pytest tests/benchmarks/test_api_speed.py -m benchmark --benchmark-enable \
        --benchmark-columns=min,median,rounds

The target: the API within 1.5 × the engine plus 1 ms at 3600 positions, within 1.5 ×
at 360 000 (the four-bar, and dyade-16 with μ = 0.1 in every joint)."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.linkage.sweep import analyse_si
from dyade.files import mechanism as toml_input
from dyade.linkage import friction, kinematics, kinetostatics
from tests.benchmarks.test_benchmarks import _angles, _with_friction
from tests.helpers import shipped

CASES = {"fourbar": ("fourbar.toml", False), "dyade-16-friction": ("dyade-16.toml", True)}


def _case(name: str):
    file, rubbing = CASES[name]
    mechanism = toml_input.read_mechanism(shipped(file))
    return (_with_friction(mechanism) if rubbing else mechanism), rubbing


@pytest.mark.parametrize("count", [3600, 360_000])
@pytest.mark.parametrize("name", list(CASES))
def test_engine(benchmark, name, count):
    mechanism, rubbing = _case(name)
    angles = _angles(count)

    def engine():
        kin = kinematics.sweep(mechanism, angles)
        return (friction.solve(mechanism, kin).forces if rubbing
                else kinetostatics.solve(mechanism, kin))

    forces = benchmark(engine)
    columns = analyse_si(mechanism, crank_angle=angles).columns()
    given = forces.valid
    assert np.array_equal(columns["M_drive"][given], forces.drive_torque[given])


@pytest.mark.parametrize("count", [3600, 360_000])
@pytest.mark.parametrize("name", list(CASES))
def test_api_columns(benchmark, name, count):
    mechanism, _ = _case(name)
    angles = _angles(count)
    columns = benchmark(lambda: analyse_si(mechanism, crank_angle=angles).columns())
    assert columns["angle_deg"].size == count
