"""A batch on -j 2 ends without a word on stderr, even when the interpreter's exit races
the process pool: dyade.parallel waits for its executor, so no executor thread is still
running when Python's shutdown hook for concurrent.futures wakes them (an unlocked write
to a pipe that thread closes: ``OSError: [Errno 9] Bad file descriptor`` under load)."""

from __future__ import annotations

import subprocess
import sys
import threading

import pytest

from dyade import parallel
from tests.conftest import MECHANISMS, SHIPPED

PREEMPT = """
import os, sys, threading, time
import concurrent.futures.process as process
import multiprocessing.connection as connection

send = connection.Connection._send

def _send(self, buf, write=os.write):  # the main thread preempted in the shutdown hook's
    if threading.current_thread() is threading.main_thread() and process._global_shutdown:
        handle = self._handle  # write, as a loaded machine may do: any executor thread
        time.sleep(0.2)        # still running closes its pipe meanwhile
        write(handle, buf)
        return
    send(self, buf)

connection.Connection._send = _send
from dyade.cli import main
sys.argv = ["dyade", *sys.argv[1:]]
main()
"""


def _batch(folder, *files, script=None):
    head = ["-c", script] if script else ["-m", "dyade"]
    return subprocess.run([sys.executable, *head, "analyse", *map(str, files), "-j", "2",
                           "--format", "csv", "-o", str(folder)],
                          capture_output=True, text=True, timeout=120)


def test_a_batch_on_two_processes_is_quiet_when_its_exit_is_preempted(tmp_path):
    run = _batch(tmp_path, MECHANISMS / "fourbar.toml", MECHANISMS / "slider-crank.toml",
                 script=PREEMPT)
    assert run.stderr == "" and run.returncode == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fourbar.csv", "slider-crank.csv"]


def test_ordered_map_taken_as_far_as_its_items_leaves_no_thread_running():
    """As dyade.cli.batch takes it: zip with the items stops before asking for more."""
    before = set(threading.enumerate())
    items = list(range(5))
    results = parallel.ordered_map(lambda x: x * x, items, workers=2)
    assert [r for _, r in zip(items, results)] == [x * x for x in items]
    del results  # closed here, after its last item
    assert set(threading.enumerate()) <= before


@pytest.mark.slow
def test_many_batches_under_load_are_quiet(tmp_path):
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
    try:
        for attempt in range(10):
            run = _batch(tmp_path / str(attempt), *SHIPPED)
            assert run.returncode == 0, run.stderr
            said = [line for line in run.stderr.splitlines() if not line.startswith("warning: ")]
            assert said == [], f"attempt {attempt}: {run.stderr}"
    finally:
        for process in busy:
            process.kill()
            process.wait()
