"""Shared fixtures; a deterministic hypothesis profile under CI=true."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile("ci", derandomize=True, max_examples=60, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", max_examples=60, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=600, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("DYADE_HYPOTHESIS")
                      or ("ci" if os.environ.get("CI") == "true" else "dev"))

MECHANISMS = Path(__file__).resolve().parent.parent / "mechanisms"
SHIPPED = sorted(MECHANISMS.glob("*.toml"))


@pytest.fixture
def mechanisms_dir() -> Path:
    return MECHANISMS


BENCHMARKS = Path(__file__).resolve().parent / "benchmarks"


def pytest_collection_modifyitems(config, items):
    """Everything under tests/benchmarks is a benchmark: out of the default run
    (``-m "not slow and not benchmark"`` in pyproject.toml), run by CI once with
    ``--benchmark-disable`` (``pytest -m "slow or benchmark"``)."""
    for item in items:
        if BENCHMARKS in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.benchmark)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_auto_num_workers(config):
    """``-n auto`` (pyproject.toml's addopts: the tests on every core) is one process
    when the benchmarks are timed (``--benchmark-enable``): pytest-benchmark times
    nothing under xdist, and a timing beside other tests' load would mean little.
    ``-n 0`` runs any selection in one process."""
    if config.getoption("benchmark_enable", default=False):
        return 0
    return None


TERMINAL = ("COLUMNS", "LINES")
"""what the tables' width comes from (dyade.cli.output.console); xdist's workers start
with COLUMNS=80 and LINES=24 of their own: given back the values of the pytest run"""


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    node.workerinput["terminal"] = {name: os.environ.get(name) for name in TERMINAL}


def pytest_configure(config):
    for name, value in getattr(config, "workerinput", {}).get("terminal", {}).items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value
