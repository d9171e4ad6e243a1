"""A function over items on several processes, the results in the items' order.

``ordered_map(function, items, workers)`` is ``map(function, items)`` on a
``concurrent.futures.ProcessPoolExecutor`` of ``workers`` processes: every process takes
the next item as soon as it is free (so a slow item does not hold the others back), and
the results come back in the items' order, each as soon as it and all before it are
done. One worker (or one item): the items run here, one after another, without a pool.

On Linux the workers are forked (the ``fork`` start method): ``function`` and the items
are inherited, not pickled, so ``function`` may be a closure; only each item's number
goes out and its result comes back. Elsewhere (the platform's start method, ``spawn`` on
macOS and Windows) ``function`` and the items must pickle.

A worker that ends without a result (killed, out of memory) breaks the executor, which
ends the other workers too. The items then running are run again, each alone in a pool
of its own: one that ends its worker again gets ``lost(item, reason)``; the items not
yet started go on in a new pool.

Examples
--------
>>> list(ordered_map(lambda x: x * x, range(6), workers=2))
[0, 1, 4, 9, 16, 25]
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, TypeVar

Item = TypeVar("Item")
Result = TypeVar("Result")


def ordered_map(function: Callable[[Item], Result], items: Iterable[Item], workers: int,
                lost: Callable[[Item, str], Result] | None = None) -> Iterator[Result]:
    """``function(item)`` for every item, on ``workers`` processes, yielded in the items'
    order.

    Parameters
    ----------
    function
        Called once per item, in a worker process; its result must pickle. An exception
        it raises is raised here, at that item's place.
    items
        The items (read at once).
    workers
        Processes; 1: the items run in this process, one after another.
    lost
        ``lost(item, reason)`` gives the result for an item whose worker ended without
        one (killed by a signal, out of memory); ``None``: raise ``ChildProcessError``.

    The workers start on the first ``next()``; they are ended when the iterator is
    closed or garbage-collected before its end.
    """
    items = list(items)
    workers = min(workers, len(items))
    if workers <= 1:
        return map(function, items)
    return _results(function, items, workers, lost)


def _results(function, items: list, workers: int, lost) -> Iterator:
    """The pools' results in order; after a break, its suspects alone, then a new pool."""
    finished: dict[int, Future] = {}
    """index -> the finished future of an item done by a pool that then broke"""
    start = 0
    while start < len(items):
        begun = start
        pool = _Pool(function, items, workers)
        clean = False
        try:
            futures: dict[int, Future] = {}
            try:
                for index in range(start, len(items)):
                    if index not in finished:
                        futures[index] = pool.submit(index)
            except OSError:  # no process can be started (a process limit): work here
                for index in range(start, len(items)):
                    future = finished.pop(index, None)
                    yield future.result() if future else function(items[index])
                return  # (not clean: a worker started before the refusal is ended)
            except BrokenProcessPool:  # broken while the items were handed out: the
                pass  # rest wait for the next pool
            for index in range(start, len(items)):
                future = finished.pop(index, None) or futures.get(index)
                if future is None:  # not handed out before the break
                    break
                try:
                    value = future.result()
                except BrokenProcessPool:
                    break
                start = index + 1
                clean = start == len(items)  # all done: a caller that stops after the
                yield value  # last item (zip with the items) ends the pool cleanly too
            clean = True
        finally:
            pool.end(clean)
        if start == len(items):
            return
        suspects, done = [], 0
        for index, future in futures.items():
            if index < start or future.cancelled():
                continue
            if future.done() and not isinstance(future.exception(), BrokenProcessPool):
                finished[index] = future  # its result, or its own exception
                done += 1
            elif pool.started[index]:
                suspects.append(index)
        if start == begun and not (suspects or done):  # no worker took up an item
            raise ChildProcessError(f"the worker processes ended before any item: "
                                    f"{pool.ending()}")
        for index in suspects:  # each alone: a second break names its item
            finished[index] = _alone(function, items, index, lost)


def _alone(function, items: list, index: int, lost) -> Future:
    """Item ``index`` in a pool of one process: its finished future, or one holding the
    ``lost`` verdict (or ``ChildProcessError``) when its worker ended without a result."""
    pool = _Pool(function, items, 1)
    try:
        future = pool.submit(index)
        try:
            future.result()
            return future
        except BrokenProcessPool:
            pass
        except Exception:  # its own exception, raised at its place
            return future
    finally:
        pool.end(True)
    outcome: Future = Future()
    reason = pool.ending()
    if lost is None:
        outcome.set_exception(ChildProcessError(f"item {index}: {reason} without a result"))
    else:
        outcome.set_result(lost(items[index], reason))
    return outcome


class _Pool:
    """A ``ProcessPoolExecutor`` whose workers know ``function`` and the items, and mark
    in ``started`` (by their pid) the items they took up."""

    def __init__(self, function, items: list, workers: int) -> None:
        self.context = _context()
        self.started = self.context.RawArray("l", len(items))
        self.executor = ProcessPoolExecutor(workers, mp_context=self.context,
                                            initializer=_install,
                                            initargs=(function, items, self.started))

    def submit(self, index: int) -> Future:
        return self.executor.submit(_call, index)

    def end(self, clean: bool) -> None:
        """Shut the executor down and wait for it: ``clean``, its workers end when idle;
        else (the iterator closed early, an error, Ctrl-C) they are killed first (SIGKILL:
        one forked a moment ago may still have the command's SIGTERM handler, and the
        executor waits for every worker to end). Always waiting: an executor thread still
        running at the interpreter's exit races its shutdown hook (``OSError: [Errno 9]
        Bad file descriptor`` on stderr)."""
        if not clean:
            for process in self.context.processes:
                if process.pid is not None and process.exitcode is None:  # started, running
                    process.kill()
        self.executor.shutdown(wait=True, cancel_futures=True)

    def ending(self) -> str:
        """How a worker that ended without a result did, in words."""
        codes = [p.exitcode for p in self.context.processes if p.exitcode]
        if not codes:
            return "its worker process ended"
        if codes[0] < 0:
            number = -codes[0]
            return f"its worker process was killed by signal {number} ({signal.strsignal(number)})"
        return f"its worker process ended with code {codes[0]}"


def _context():
    """The start method's context (``fork`` on Linux, else the platform's), keeping the
    processes it starts: how a worker ended is read from its exit code."""
    method = ("fork" if sys.platform == "linux" else
              multiprocessing.get_start_method(allow_none=True)
              or multiprocessing.get_all_start_methods()[0])
    base = type(multiprocessing.get_context(method))

    class Keeping(base):  # type: ignore[misc,valid-type]
        def __init__(self) -> None:
            self.processes: list = []

        def Process(self, *args, **kwargs):  # noqa: N802 - the context's name
            process = base.Process(*args, **kwargs)
            self.processes.append(process)
            return process

    return Keeping()


_task: tuple[Callable, list, Any] | None = None
"""in a worker: (function, items, started) of its pool"""


def _install(function, items: list, started) -> None:
    """A worker's start: its pool's function and items; SIGTERM ends it (the command's
    handler, inherited by fork, would unwind it) and Ctrl-C is the calling process's to
    handle (it ends the workers)."""
    global _task
    _task = (function, items, started)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _call(index: int):
    """In a worker: the result of item ``index``."""
    function, items, started = _task
    started[index] = os.getpid()
    return function(items[index])


def connect(address: str):
    """A Dask client of the scheduler at ``address``; an InputError on ``scheduler``
    when it does not answer within 5 s."""
    import importlib.util
    import logging

    from dyade.errors import InputError, MissingExtra

    if importlib.util.find_spec("distributed") is None:
        raise MissingExtra("scheduler needs distributed, which is not installed: "
                           "pip install \"dyade[dask]\".")

    from distributed import Client

    logging.getLogger("distributed").setLevel(logging.CRITICAL)
    reachable(address)
    try:
        return Client(address, timeout="5s")
    except (OSError, TimeoutError, ValueError) as err:
        raise InputError.parameter("scheduler", f"{address}: no Dask scheduler answers there "
                                                f"({err}).", value=address) from None


def reachable(address: str, timeout: float = 3.0) -> None:
    """Refuse at once a tcp:// address where nothing listens (Dask's client would try
    again until its timeout)."""
    import socket

    from dyade.errors import InputError

    if not address.startswith("tcp://"):
        return
    host, _, port = address[len("tcp://"):].rpartition(":")
    try:
        number = int(port.strip("/"))
    except ValueError:
        raise InputError.parameter("scheduler", f"{address}: give tcp://HOST:PORT.",
                                   value=address) from None
    try:
        socket.create_connection((host.strip("[]"), number), timeout=timeout).close()
    except OSError as err:
        raise InputError.parameter("scheduler", f"{address}: no Dask scheduler answers there "
                                                f"({err.strerror or err}).",
                                   value=address) from None
