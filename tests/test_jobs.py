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


# dyade.parallel: the pool under the batches and speed ranges

def test_ordered_map_gives_the_results_in_order_from_every_process():
    import os
    import time

    from dyade.parallel import ordered_map

    parent = os.getpid()

    def slow_square(x):  # a closure: nothing but the results is pickled
        time.sleep(0.02 if x % 3 else 0.0)
        return x * x, os.getpid()

    out = list(ordered_map(slow_square, range(12), workers=3))
    assert [square for square, _ in out] == [x * x for x in range(12)]
    pids = {pid for _, pid in out}
    assert parent in pids and len(pids) == 3  # the caller works too


def test_ordered_map_raises_an_error_at_its_place_and_names_a_killed_worker():
    import os
    import signal
    import time

    from dyade.parallel import ordered_map

    parent = os.getpid()

    def fragile(x):
        if x == 2:
            raise ValueError("item two")
        return x

    seen = []
    with pytest.raises(ValueError, match="item two"):
        for value in ordered_map(fragile, range(6), workers=2):
            seen.append(value)
    assert seen == [0, 1]

    def killed(x):  # every child dies on its first item
        time.sleep(0.05)
        if os.getpid() != parent:
            os.kill(os.getpid(), signal.SIGKILL)
        return x

    out = list(ordered_map(killed, range(8), workers=2, lost=lambda x, why: (x, why)))
    lost = [value for value in out if isinstance(value, tuple)]
    assert len(lost) == 1 and "killed by signal 9" in lost[0][1]
    assert out == [lost[0] if x == lost[0][0] else x for x in range(8)]


def test_ordered_map_with_more_items_than_the_queue_holds():
    from dyade.parallel import ordered_map

    count = 40_000  # 160 kB of item numbers: the queue (a pipe) is refilled as it drains
    assert list(ordered_map(lambda x: x, range(count), workers=2)) == list(range(count))


def test_ordered_map_works_on_when_no_process_can_be_forked():
    """fork refused (a process limit): the calling process does every item itself."""
    from unittest import mock

    from dyade.parallel import ordered_map

    refused = BlockingIOError(11, "Resource temporarily unavailable")
    with mock.patch("os.fork", side_effect=refused):
        assert list(ordered_map(lambda x: x + 1, range(5), workers=3)) == [1, 2, 3, 4, 5]
