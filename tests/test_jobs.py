"""-j N (issue 17): several files, or speeds, on several processes give the files and
messages of the serial run, in the same order; failures stay per file."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from dyade.cli import main
from tests.conftest import SHIPPED


def _run(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def _files(folder):
    return {path.name: path.read_bytes() for path in sorted(folder.iterdir())}


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_analyse_batch_on_two_processes_is_the_serial_batch(tmp_path, fmt):
    broken = tmp_path / "broken.toml"
    broken.write_text("[crank]\nlength = -1\n")
    inputs = [*SHIPPED, broken]
    outcomes = []
    for jobs in ("1", "2", "0"):
        folder = tmp_path / f"j{jobs}"
        result = _run("analyse", *inputs, "--format", fmt, "--allow-partial", "-j", jobs,
                      "-o", folder)
        outcomes.append((result.exit_code, result.stdout, result.stderr, _files(folder)))
    assert outcomes[0][0] == 1 and "broken.toml" in outcomes[0][2]  # the failure is kept
    assert len(outcomes[0][3]) == len(SHIPPED)
    assert outcomes[1] == outcomes[0]
    assert outcomes[2] == outcomes[0]


def test_clearance_batch_and_speed_range_on_two_processes(tmp_path):
    dyade16 = SHIPPED[0].parent / "dyade-16.toml"
    serial = _run("clearance", dyade16, "--joint", "2,7", "--speed-range", "100:400:50",
                  "--format", "csv")
    parallel = _run("clearance", dyade16, "--joint", "2,7", "--speed-range", "100:400:50",
                    "--format", "csv", "-j", "2")
    assert serial.exit_code == parallel.exit_code == 0
    assert (parallel.stdout, parallel.stderr) == (serial.stdout, serial.stderr)
    outcomes = []
    for jobs in ("1", "2"):
        folder = tmp_path / f"j{jobs}"
        result = _run("clearance", dyade16, SHIPPED[1], "--stiffness", "1e8", "--clearance",
                      "1e-4", "--format", "json", "-j", jobs, "-o", folder)
        outcomes.append((result.exit_code, result.stderr, _files(folder)))
    assert outcomes[1] == outcomes[0]
