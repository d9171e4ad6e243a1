"""The writers of `dyade analyse`: the ``sweep`` entry (``dyade.analyses.sweep``) run
block by block, its CSV rows written as they come (the one writer,
``report.csv_rows.Writer``), its JSON (``Outcome.to_document``), Parquet or tables
from its Outcome, whose columns wait in a ``Spool`` on disk; each as a
``dyade.cli.analyse.Job`` describes it."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from contextlib import contextmanager

from dyade.cli.output import atomic, progress, show, write_json


@contextmanager
def named(entry):
    """Errors of the entry named as the command line gives its options: its flags for
    API names, in the message's text too (``start_deg`` is ``--start``, the API's
    ``crank_angle_deg=[...]`` is ``--at DEG``); a mechanism that closes over part of the
    sweep suggests --allow-partial."""
    from dyade.cli.contract import flags
    from dyade.errors import AssemblyError, InputError

    names = flags(entry)
    try:
        yield
    except InputError as err:
        if not err.parameters:
            raise
        import re

        named = err.naming(names)
        text = str(named)
        if str(err).startswith(", ".join(err.parameters) + ": "):  # "a, b: reason"
            text = f"{' and '.join(named.parameters)}: {named.reason}"
        text = re.sub(r"crank_angle_deg=\[\.\.\.\]|at_deg=\[\.\.\.\]", "--at DEG", text)
        text = re.sub(r"\b(" + "|".join(map(re.escape, names)) + r")\b(=?)",
                      lambda match: names[match.group(1)] + (" " if match.group(2) else ""),
                      text)
        out = InputError(text, key=named.key, value=named.value, unit=named.unit,
                         reason=named.reason)
        out.parameters = named.parameters
        raise out from None
    except AssemblyError as err:
        if not err.partial:
            raise
        raise AssemblyError("; ".join(err.problems) + ". Change the dimensions or the "
                            "sweep, or use --allow-partial to analyse only where it "
                            "closes.", err.problems, err.partial) from None


def streamed(job, source, path: str, output: str | None) -> None:
    """The sweep of ``source`` block by block as ``job`` (``analyse.Job``) asks: CSV rows
    written as soon as they are computed; for JSON, Parquet and the tables the blocks go
    to a ``Spool`` on disk, from which the summary and every writer take one column at a
    time. Nothing is written where no position has its kinematics given (exit 1, saying
    why); with --fail-on-lock the output is written, then exit 1 where it self-locks."""
    from dyade.analyses.base import budget
    from dyade.analyses.sweep import ENTRIES, Sweep, refuse_lock

    label = os.path.basename(path)
    entry = ENTRIES["sweep"]
    with named(entry), progress(f"{label}: analysing") as tick:
        checked = entry.checked(job.options)
        sweep = Sweep(source, checked, budget(checked, progress=tick,
                                              told=lambda text: say(text)))
        names = job.chosen(sweep.first)  # a wrong --columns fails before any output
        if job.fmt == "csv":
            outcome = write_csv(sweep, names, output)
        else:
            outcome = write(job, sweep, names, output)
    warn(outcome.notes, f"{label}: " if output else "")
    if job.fail_on_lock:
        refuse_lock(outcome, "the mechanism self-locks (see the warning above); "
                             "--fail-on-lock was given.")


def write_csv(sweep, names: list[str], output: str | None):
    """The CSV of a sweep under way, row by row as its blocks come (the blocks before
    the first that gives a position are held back, on disk: a sweep that gives none
    writes nothing); its Outcome (no summary)."""
    from dyade.report import csv_rows

    held = None
    started = False
    with atomic(output or "-") as handle:
        writer = csv_rows.Writer(names, handle)

        def start() -> None:
            writer.header()
            if held is not None:
                for part in held.parts(names):
                    writer.rows(part)
                held.close()

        for cols in sweep.blocks():
            if not started and not cols["kinematics_valid"].any():
                if held is None:
                    from dyade.analyses.spool import Spool

                    held = Spool(())
                held.add(cols)
                continue
            if not started:
                start()
                started = True
            writer.rows(cols)
        outcome = sweep.outcome()  # refused here where no position is given
        if not started:  # (a sweep that reports no position)
            start()
        writer.close()
    return outcome


def write(job, sweep, names: list[str], output: str | None):
    """The JSON document, the Parquet file or the tables of a sweep under way, as ``job``
    asks (its blocks kept in a ``Spool``); its Outcome."""
    from dyade.analyses.spool import Spool

    spool = Spool(sweep.blocks())
    with spool:
        outcome = sweep.outcome(spool, names)
        if job.columns:
            outcome.columns = Chosen(spool, names)
        if job.fmt == "parquet":
            from dyade.study.tables import write_parquet

            write_parquet(outcome.columns, {name: outcome.units[name] for name in names},
                          output, {"dyade.mechanism": outcome.meta["name"],
                                   "dyade.source": outcome.meta["source"] or ""})
        elif job.fmt == "json":
            write_json(outcome.to_document(), output)
        else:
            from dyade.report import tables

            show(tables.sweep_tables(outcome, "m" if job.units == "si" else None,
                                     everything=job.show_all, chosen=bool(job.columns)),
                 output)
    return outcome


class Chosen(Mapping):
    """Some of a mapping's columns, in their order (the others are not read)."""

    def __init__(self, columns, names: list[str]) -> None:
        self.columns, self.names = columns, names
        self.float_columns = getattr(columns, "float_columns", False)

    def __getitem__(self, name: str):
        if name not in self.names:
            raise KeyError(name)
        return self.columns[name]

    def __iter__(self):
        return iter(self.names)

    def __len__(self) -> int:
        return len(self.names)

    def __contains__(self, name: object) -> bool:
        return name in self.names


def say(text: str) -> None:
    """A line on stderr (the time estimate of a long run)."""
    sys.stderr.write(text + "\n")


def warn(notes: list[str], prefix: str = "") -> None:
    """A sweep's notes on stderr, each a warning: one line each, as they are, into a pipe
    or a file (or a batch worker's capture); through rich on a terminal, which wraps them
    (rich is loaded only then: about 20 ms of every batch worker's start)."""
    if not notes:
        return
    if not sys.stderr.isatty():
        sys.stderr.write("".join(f"warning: {prefix}{note}\n" for note in notes))
        return
    from dyade.cli.output import console

    err = console(stderr=True)
    for note in notes:
        err.print(f"warning: {prefix}{note}", markup=False)
