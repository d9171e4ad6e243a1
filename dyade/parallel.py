"""A function over items on several processes, the results in the items' order.

``ordered_map(function, items, workers)`` is ``map(function, items)`` on ``workers``
processes: this one and ``workers − 1`` forked children. Every process takes the next
item from one queue as soon as it is free (so a slow item does not hold the others
back) and the results come back in the items' order, each as soon as it and all before
it are done. Nothing is pickled but the results: ``function`` may be a closure.

Why not ``concurrent.futures.ProcessPoolExecutor``: for a batch of small sweeps (the 8
shipped mechanisms at 5 speeds each take about half a second in all) its costs decide
the gain: the calling process waits idle while its workers compute, every item and
result crosses a pickling queue served by a thread, and the workers fork from a
process whose helper threads are already running. Here the caller is one of the
workers, the queue is a pipe of 4-byte item numbers, and the children fork before
anything else runs.

The queue: the item numbers are written into a pipe in slices of at most ``PIPE_BUF``
bytes (so each write is atomic) and every process reads exactly 4 bytes per item: the
kernel hands each number to one reader. Results (pickled, with their item number) come
back on one pipe per child. A child that ends without a result (killed, out of memory)
is noticed at the end of its pipe; its item gets ``lost(item, reason)``.

Where ``os.fork`` does not exist (Windows), or for one worker, the items run here one
after another.

Examples
--------
>>> list(ordered_map(lambda x: x * x, range(6), workers=2))
[0, 1, 4, 9, 16, 25]
"""

from __future__ import annotations

import os
import pickle
import select
import signal
import struct
from collections.abc import Callable, Iterable, Iterator
from typing import Any, TypeVar

Item = TypeVar("Item")
Result = TypeVar("Result")

_NUMBER = struct.Struct("=I")
_HEADER = struct.Struct("=IQ")
"""a result's item number and the length of its pickle"""
_SLICE = 1024
"""item numbers per write: 4 kB, at most PIPE_BUF on Linux and macOS (atomic)"""


def available() -> bool:
    """Whether items can run on several processes here (``os.fork`` exists)."""
    return hasattr(os, "fork")


def ordered_map(function: Callable[[Item], Result], items: Iterable[Item], workers: int,
                lost: Callable[[Item, str], Result] | None = None) -> Iterator[Result]:
    """``function(item)`` for every item, on ``workers`` processes (this one included),
    yielded in the items' order.

    Parameters
    ----------
    function
        Called once per item, in this process or in a forked child; its result must
        pickle. An exception in a child is raised here, at that item's place.
    items
        The items (read at once).
    workers
        Processes in all, this one included; 1 (or no ``os.fork``): one after another.
    lost
        ``lost(item, reason)`` gives the result for an item whose child ended without
        one (killed by a signal, out of memory); ``None``: raise ``ChildProcessError``.

    The children are forked on the first ``next()``, before anything else runs; they
    are ended when the iterator is closed or garbage-collected.
    """
    items = list(items)
    workers = min(workers, len(items))
    if workers <= 1 or not available():
        return map(function, items)
    return _Pool(function, items, workers, lost).results()


class _Pool:
    def __init__(self, function, items: list, workers: int, lost) -> None:
        self.function = function
        self.items = items
        self.workers = workers
        self.lost = lost
        self.done: dict[int, tuple[bool, Any]] = {}
        self.children: dict[int, tuple[int, bytearray]] = {}
        """result pipe's read end -> (pid, bytes received and not yet taken)"""
        self.queued = 0
        """item numbers written into the queue so far"""
        self.ended = "its worker process ended"
        """how the last child that ended did (for the items it took with it)"""

    def results(self) -> Iterator:
        self.queue_r, self.queue_w = os.pipe()
        try:
            self._fork()
            os.set_blocking(self.queue_w, False)
            os.set_blocking(self.queue_r, False)  # shared with the children: they wait in select
            self._fill()
            for index in range(len(self.items)):
                while index not in self.done:
                    self._step()
                ok, value = self.done.pop(index)
                if not ok:
                    raise value
                yield value
        finally:
            self._end()

    def _fork(self) -> None:
        for _ in range(self.workers - 1):
            result_r, result_w = os.pipe()
            try:
                pid = os.fork()
            except OSError:  # no more processes allowed: work with those there are
                os.close(result_r)
                os.close(result_w)
                break
            if pid == 0:  # the child
                os.close(result_r)
                os.close(self.queue_w)
                for fd in self.children:
                    os.close(fd)
                _child(self.function, self.items, self.queue_r, result_w)
            os.close(result_w)
            self.children[result_r] = (pid, bytearray())

    def _fill(self) -> None:
        """Write as many item numbers into the queue as it takes (without waiting); close
        it after the last, so that readers see its end."""
        while self.queued < len(self.items):
            stop = min(self.queued + _SLICE, len(self.items))
            data = b"".join(_NUMBER.pack(k) for k in range(self.queued, stop))
            try:
                os.write(self.queue_w, data)
            except BlockingIOError:
                return
            self.queued = stop
        if self.queue_w >= 0:
            os.close(self.queue_w)
            self.queue_w = -1

    def _step(self) -> None:
        """Take in what the children sent; then do the next item here, or (the queue
        ended) wait for a child."""
        self._receive(timeout=0.0)
        self._fill()
        number = _take(self.queue_r, wait=False)
        if number is not None:
            try:
                self.done[number] = (True, self.function(self.items[number]))
            except Exception as err:
                self.done[number] = (False, err)
        elif self.children:
            self._receive(timeout=None)
        elif self.queue_w < 0:  # everything queued and taken, no child left
            self._mark_lost()

    def _receive(self, timeout: float | None) -> None:
        if not self.children:
            return
        ready, _, _ = select.select(list(self.children), [], [], timeout)
        for fd in ready:
            pid, data = self.children[fd]
            chunk = os.read(fd, 1 << 16)
            if not chunk:  # the child ended
                os.close(fd)
                del self.children[fd]
                self.ended = _ending(pid)
                continue
            data += chunk
            while len(data) >= _HEADER.size:
                index, size = _HEADER.unpack_from(data)
                if len(data) < _HEADER.size + size:
                    break
                self.done[index] = pickle.loads(bytes(data[_HEADER.size:_HEADER.size + size]))
                del data[:_HEADER.size + size]

    def _mark_lost(self) -> None:
        """No child is left and the queue has ended: the first item without a result was
        taken by a child that ended (so are the others: one at a time)."""
        reason = self.ended
        for index in range(len(self.items)):
            if index not in self.done:
                if self.lost is None:
                    self.done[index] = (False, ChildProcessError(
                        f"item {index}: {reason} without a result"))
                else:
                    self.done[index] = (True, self.lost(self.items[index], reason))
                break

    def _end(self) -> None:
        """Close the pipes; stop and reap the children still running."""
        for fd in (self.queue_r, self.queue_w):
            if fd >= 0:
                os.close(fd)
        self.queue_r = self.queue_w = -1
        for fd, (pid, _) in self.children.items():
            os.close(fd)
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
            _ending(pid)
        self.children.clear()


def _ending(pid: int) -> str:
    """Reap a child; how it ended, in words."""
    try:
        _, status = os.waitpid(pid, 0)
    except ChildProcessError:
        return "its worker process ended"
    if os.WIFSIGNALED(status):
        number = os.WTERMSIG(status)
        return f"its worker process was killed by signal {number} ({signal.strsignal(number)})"
    return f"its worker process ended with code {os.waitstatus_to_exitcode(status)}"


def _take(queue_r: int, wait: bool) -> int | None:
    """The next item number from the queue (non-blocking for everyone); None when the
    queue has ended, or (``wait`` false) has nothing right now."""
    while True:
        try:
            number = os.read(queue_r, 4)
        except BlockingIOError:
            if not wait:
                return None
            select.select([queue_r], [], [])
            continue
        return _NUMBER.unpack(number)[0] if number else None


def _child(function, items: list, queue_r: int, result_w: int) -> None:
    """A child's life: the next item number from the queue, its result back, until the
    queue ends; then ``os._exit``: nothing of the parent's clean-up runs here, and what
    the parent had buffered for its standard streams is not written twice."""
    code = 1
    try:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        while (index := _take(queue_r, wait=True)) is not None:
            try:
                outcome: tuple[bool, Any] = (True, function(items[index]))
            except Exception as err:
                outcome = (False, err)
            try:
                data = pickle.dumps(outcome, pickle.HIGHEST_PROTOCOL)
            except Exception as err:
                data = pickle.dumps((False, RuntimeError(
                    f"item {index}: its result could not be sent back: {err!r}")))
            message = _HEADER.pack(index, len(data)) + data
            view = memoryview(message)
            while view:
                view = view[os.write(result_w, view):]
        code = 0
    finally:
        os._exit(code)
