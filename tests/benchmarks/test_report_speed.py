"""`dyade report` (issue 29) beside its yardstick, the same figures drawn to SVG by
`dyade.plot` alone (the page, its tables and the motion's data are the difference):

    pytest tests/benchmarks/test_report_speed.py -m benchmark --benchmark-enable \
        --benchmark-columns=min,median,rounds

The target: every shipped report under 5 s on the 2-core machine (dyade-16, the largest,
is the case here), the report within 1.5 × its figures."""

from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.plot import canvas, curves, mechanism, polar  # noqa: E402
from dyade.report.html import report  # noqa: E402
from tests.helpers import shipped  # noqa: E402

FILE = shipped("dyade-16.toml")


def test_report(benchmark):
    page = benchmark(report, str(FILE))
    assert len(page.encode()) < 2_000_000


def test_figures_alone(benchmark):
    def figures() -> int:
        result = dyade.analyse(dyade.read_mechanism(FILE))
        made = [mechanism.figure(result), curves.figure(result), polar.figure(result)]
        return sum(len(canvas.render(fig, "svg")) for fig in made)

    assert benchmark(figures) > 0
