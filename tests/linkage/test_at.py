"""A sweep's result answers by column and at an angle (issue 42): ``result["F_2_3"]``
and ``result.at(deg)``, the sweep's own row or computed exactly there."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from tests.helpers import shipped


@pytest.fixture(scope="module")
def fourbar():
    return dyade.read_mechanism(shipped("fourbar.toml"))


def _same(a: float, b: float) -> bool:
    return (np.isnan(a) and np.isnan(b)) or a == b


def test_a_column_by_its_name(fourbar):
    result = dyade.analyse(fourbar)
    assert result["F_2_3"] is result.columns()["F_2_3"] and "F_2_3" in result
    with pytest.raises(KeyError, match="Did you mean F_2_3"):
        result["F23"]


def test_at_a_position_of_the_sweep_is_its_own_row(fourbar):
    result = dyade.analyse(fourbar, step_deg=0.5)
    row = result.at(37)
    k = int(np.flatnonzero(result["angle_deg"] == 37.0)[0])
    assert set(row) == set(result.columns())
    assert all(_same(row[name], float(column[k])) for name, column in result.columns().items())


@pytest.mark.parametrize("name, overrides", [
    ("fourbar.toml", {}),
    ("self-locking.toml", {}),  # friction: the fixed point solved at that angle
    ("dyade-16.toml", {"drive": {"motor": "constant", "flywheel_inertia": 0.5}}),  # motion
])
def test_between_positions_it_is_the_finer_sweeps_row(name, overrides):
    """At 37.25° a 1° sweep computes the position alone; a 0.25° sweep has it as a row:
    the same values (to round-off), every column."""
    mechanism = dyade.read_mechanism(shipped(name), overrides)
    coarse = dyade.analyse(mechanism, start_deg=30, stop_deg=40, step_deg=1)
    fine = dyade.analyse(mechanism, start_deg=30, stop_deg=40, step_deg=0.25)
    at, k = coarse.at(37.25), int(np.flatnonzero(np.isclose(fine["angle_deg"], 37.25))[0])
    assert at["angle_deg"] == 37.25
    for column, values in fine.columns().items():
        if mechanism.drive is not None and column in ("omega_2", "epsilon_2"):
            continue  # the steady state of a sweep's own grid: compared below
        assert np.isclose(at[column], values[k], rtol=1e-9, atol=1e-9, equal_nan=True), column
    if mechanism.drive is not None:  # the same rule as dyade analyse --at
        alone = dyade.analyse(mechanism, crank_angle_deg=[37.25]).columns()
        assert all(_same(at[c], float(alone[c][0])) for c in at if c != "t")  # t: from 30°


def test_outside_the_swept_range_it_is_refused(fourbar):
    result = dyade.analyse(fourbar, start_deg=10, stop_deg=100, step_deg=5)
    with pytest.raises(dyade.InputError, match="swept range 10°…100°") as caught:
        result.at(120)
    assert caught.value.key == "angle_deg"
    with pytest.raises(dyade.InputError):
        result.at(float("nan"))
    assert result.at(100)["angle_deg"] == 100.0
