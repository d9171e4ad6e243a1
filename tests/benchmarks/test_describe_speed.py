"""``dyade describe`` of a mechanism with many named frame points (issue 42: 200 000
points took 130 s, rich's tree growing quadratically), beside its yardstick, reading the
same file, in one run:

    pytest tests/benchmarks/test_describe_speed.py -m benchmark --benchmark-enable \\
        --benchmark-columns=min,median,rounds

Targets: describe's own cost (the command less the reading) at most 1.5 × the reading,
and linear in the number of points (4 × the points at most 6 × the time; quadratic would
be 16 ×). Timed only with ``--benchmark-enable``; in the normal run each body runs once.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import with_frame_points

COUNTS = (3_000, 12_000)


def _describe(path) -> None:
    result = CliRunner().invoke(main, ["describe", str(path)], catch_exceptions=False)
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("count", COUNTS)
def test_reading_yardstick(benchmark, tmp_path, count):
    path = with_frame_points(tmp_path, count)
    benchmark.pedantic(dyade.read_mechanism, args=(path,), rounds=3, warmup_rounds=0)


@pytest.mark.parametrize("count", COUNTS)
def test_describe(benchmark, tmp_path, count):
    path = with_frame_points(tmp_path, count)
    benchmark.pedantic(_describe, args=(path,), rounds=3, warmup_rounds=0)
