"""-j N (issue 17): several files, or speeds, on several processes give the files and
messages of the serial run, in the same order; failures stay per file."""

from __future__ import annotations

import sys

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


# dyade.parallel: the pool under the batches and speed ranges (forked workers on Linux: the
# functions below are closures, and the barriers and events they share are inherited)

fork_only = pytest.mark.skipif(sys.platform != "linux", reason="closures need forked workers")
WAIT = 30.0  # [s] a barrier or event not reached by then: the test fails (never reached
#               when the code is right; only a hung pool would take this long)


@fork_only
def test_ordered_map_gives_the_results_in_order_from_as_many_processes():
    """Three workers: items 0-2 wait at a barrier of three, which only three processes
    computing at once can pass (it used to count the processes that happened to take
    an item from a shared queue: one started late could find none left)."""
    import multiprocessing
    import os
    import time

    from dyade.parallel import ordered_map

    barrier = multiprocessing.get_context("fork").Barrier(3, timeout=WAIT)

    def square(x):
        if x < 3:
            barrier.wait()  # BrokenBarrierError (raised here) with fewer processes
        time.sleep(0.01 if x % 3 else 0.0)
        return x * x, os.getpid()

    out = list(ordered_map(square, range(12), workers=3))
    assert [value for value, _ in out] == [x * x for x in range(12)]
    assert len({pid for _, pid in out[:3]}) == 3
    assert os.getpid() not in {pid for _, pid in out}


@fork_only
def test_ordered_map_gives_each_result_as_soon_as_those_before_are_done():
    """The last item waits until the first result has arrived here: results come as
    they are done, not after the last."""
    import multiprocessing

    from dyade.parallel import ordered_map

    first_seen = multiprocessing.get_context("fork").Event()

    def item(x):
        return first_seen.wait(WAIT) if x == 5 else x

    results = ordered_map(item, range(6), workers=2)
    assert next(results) == 0
    first_seen.set()
    assert list(results) == [1, 2, 3, 4, True]


@fork_only
def test_ordered_map_raises_an_error_at_its_place_and_names_a_killed_worker():
    import os
    import signal

    from dyade.parallel import ordered_map

    def fragile(x):
        if x == 2:
            raise ValueError("item two")
        return x

    seen = []
    with pytest.raises(ValueError, match="item two"):
        for value in ordered_map(fragile, range(6), workers=2):
            seen.append(value)
    assert seen == [0, 1]

    def killed(x):  # item 3 ends its worker; the others (run again if need be) do not
        if x == 3:
            os.kill(os.getpid(), signal.SIGKILL)
        return x

    out = list(ordered_map(killed, range(8), workers=2, lost=lambda x, why: (x, why)))
    assert out == [0, 1, 2, (3, "its worker process was killed by signal 9 (Killed)"),
                   4, 5, 6, 7]
    with pytest.raises(ChildProcessError, match="item 3: its worker process was killed"):
        list(ordered_map(killed, range(8), workers=2))


@fork_only
def test_ordered_map_closed_early_ends_its_workers():
    import multiprocessing
    import time

    from dyade.parallel import ordered_map

    results = ordered_map(lambda x: time.sleep(WAIT) if x else x, range(3), workers=2)
    assert next(results) == 0
    assert multiprocessing.active_children()  # the workers, one still busy
    results.close()
    deadline = time.monotonic() + 10.0
    while multiprocessing.active_children() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not multiprocessing.active_children()


@fork_only
def test_ordered_map_says_so_when_no_worker_lives_to_take_an_item(monkeypatch):
    import os

    from dyade import parallel

    monkeypatch.setattr(parallel, "_install", lambda *task: os._exit(3))
    with pytest.raises(ChildProcessError, match="ended before any item: .* with code 3"):
        list(parallel.ordered_map(abs, [1, -2, 3], workers=2))


def test_ordered_map_with_many_items():
    from dyade.parallel import ordered_map

    count = 2_000
    assert list(ordered_map(abs, range(-count, 0), workers=2)) == list(range(count, 0, -1))


def test_ordered_map_works_on_when_no_process_can_be_started():
    """fork refused (a process limit): the calling process does every item itself."""
    from unittest import mock

    from dyade.parallel import ordered_map

    refused = BlockingIOError(11, "Resource temporarily unavailable")
    with mock.patch("os.fork", side_effect=refused):
        assert list(ordered_map(lambda x: x + 1, range(5), workers=3)) == [1, 2, 3, 4, 5]
