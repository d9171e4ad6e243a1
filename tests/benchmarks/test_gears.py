"""Gear-drive benchmarks (issue 13), disabled in the normal test run (each body runs once
as a smoke test); measure in one run, side by side with the yardstick:

    pytest tests/benchmarks/test_gears.py --benchmark-enable --benchmark-columns=min,median,rounds

- the modes of a drive of 1500 coordinates (two-stage.toml with 80, 48 and 116 shaft
  segments) against ``numpy.linalg.eigh`` of a symmetric matrix of the reduced size
  (1498), random and the drive's own: the floor any symmetric solution pays;
- a Campbell diagram over 1000 speeds against one modal analysis (no gyroscopic terms:
  the modes do not depend on speed, so the diagram adds only its lines and crossings).
"""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.vibration.gears.assembly import assemble
from tests.helpers import shipped

SEGMENTS = {"shaft.1.segments": 80, "shaft.2.segments": 48, "shaft.3.segments": 116}


@pytest.fixture(scope="module")
def large():
    drive = dyade.read_gears(shipped("gears/two-stage.toml"), SEGMENTS)
    system = assemble(drive)
    assert system.size == 1500
    return drive, system


def test_modes_1500_coordinates(benchmark, large):
    _, system = large
    benchmark.pedantic(dyade.gear_modes, (system,), rounds=5, iterations=1, warmup_rounds=1)


def test_eigh_of_the_reduced_size_yardstick(benchmark, large):
    _, system = large
    size = system.size - system.constraints.shape[1]
    a = np.random.default_rng(13).standard_normal((size, size))
    a = a + a.T
    benchmark.pedantic(np.linalg.eigh, (a,), rounds=5, iterations=1, warmup_rounds=1)


def test_eigh_of_the_drives_own_matrix_yardstick(benchmark, large):
    """The same floor on the drive's reduced standard matrix C⁻¹·NᵀKN·C⁻ᵀ itself: its
    structure lets the divide-and-conquer eigensolver deflate, a random matrix does not."""
    from dyade.vibration.gears.modes import reduce

    _, system = large
    a = reduce(system).standard
    benchmark.pedantic(np.linalg.eigh, (a,), rounds=5, iterations=1, warmup_rounds=1)


def test_modes_two_stage(benchmark):
    drive = dyade.read_gears(shipped("gears/two-stage.toml"))
    benchmark(dyade.gear_modes, drive)


def test_campbell_1000_speeds(benchmark):
    drive = dyade.read_gears(shipped("gears/two-stage.toml"))
    speeds = np.linspace(0.0, 3000.0, 1000)
    benchmark(lambda: dyade.campbell(drive, speeds))


def test_response_991_frequencies(benchmark):
    drive = dyade.read_gears(shipped("gears/two-stage.toml"))
    frequencies = np.arange(10.0, 1001.0)
    benchmark(dyade.gear_response, drive, frequencies)
