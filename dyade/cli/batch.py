"""Batches: one command over several files, on ``-j N`` processes (``dyade.parallel``),
the files, their contents and the warnings those of a serial run, in the same order."""

from __future__ import annotations

import os
import sys
from typing import Any, NamedTuple

import click

from dyade.cli.output import progress

SUFFIX = {"csv": ".csv", "json": ".json", "table": ".txt", "parquet": ".parquet"}
"""output format -> the suffix of each file a batch writes"""


def batch(paths, directory: str, run_one, suffix: str, jobs: int = 1,
          modules: tuple[str, ...] = ()) -> list[tuple[str, str]]:
    """Run ``run_one(path, target, None)`` for every path, on ``jobs`` processes (0: all
    cores; see ``dyade.parallel``); a progress bar on stderr when it is a terminal;
    returns the failures (path, reason) instead of stopping. With several processes each
    file's warnings are kept and printed in the order of the files, as in a serial run,
    and ``modules`` (those every file needs) are imported once, before the worker
    processes are forked, instead of once in each."""
    from dyade import parallel

    targets = _targets(paths, directory, suffix)
    workers = min(workers_for(jobs), len(paths))
    capture = workers > 1
    if capture:
        import importlib

        for name in modules:
            importlib.import_module(name)
    failures = []
    outcomes = parallel.ordered_map(Attempt(run_one, capture), list(zip(paths, targets)),
                                    workers, lost)
    with progress("analysing", total=len(paths)) as tick:
        for done, (path, (failure, said)) in enumerate(zip(paths, outcomes), start=1):
            if said:
                sys.stderr.write(said)
            if failure is not None:
                failures.append((path, failure))
            tick(done)
    return failures


class Attempt(NamedTuple):
    """One file of a batch: ``attempt(run_one, path, target, capture)`` for a (path,
    target) task (a class, not a closure: it pickles where workers are not forked)."""

    run_one: Any
    capture: bool

    def __call__(self, task: tuple[str, str]) -> tuple[str | None, str]:
        path, target = task
        return attempt(self.run_one, path, target, self.capture)


def lost(task: tuple[str, str], reason: str) -> tuple[str, str]:
    """The failure of a file whose worker process ended without its result."""
    return f"{reason} before {task[0]} was done (rerun it alone)", ""


SWEEP = ("dyade.files.mechanism", "dyade.linkage.sweep", "dyade.linkage.kinetostatics",
         "dyade.linkage.reduced", "dyade.linkage.columns", "dyade.linkage.dyads.rrr",
         "dyade.linkage.dyads.rrp", "dyade.linkage.dyads.rpr", "dyade.linkage.dyads.prp",
         "dyade.linkage.dyads.ppr")
"""what every sweep of a mechanism file imports (friction only where a file has it)"""


def workers_for(jobs: int) -> int:
    """Processes for -j N: N, or every core for 0."""
    return jobs if jobs > 0 else (os.cpu_count() or 1)


def attempt(run_one, path, target, capture: bool) -> tuple[str | None, str]:
    """``run_one(path, target, None)``: (None or the reason it failed, what it wrote on
    stderr when ``capture``)."""
    import contextlib
    import io

    from dyade.errors import DyadeError

    said = io.StringIO()
    with contextlib.redirect_stderr(said) if capture else contextlib.nullcontext():
        try:
            run_one(path, target, None)
        except (DyadeError, click.ClickException) as err:
            return (err.format_message() if isinstance(err, click.ClickException)
                    else str(err)), said.getvalue()
    return None, said.getvalue()


def _targets(paths, directory: str, suffix: str) -> list[str]:
    """One output name per input: the stem, made unique when two inputs share it."""
    seen: dict[str, int] = {}
    out = []
    for path in paths:
        stem = os.path.splitext(os.path.basename(path))[0]
        seen[stem] = seen.get(stem, 0) + 1
        name = stem if seen[stem] == 1 else f"{stem}-{seen[stem]}"
        out.append(os.path.join(directory, f"{name}{suffix}"))
    return out
