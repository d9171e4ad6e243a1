"""The writers of `dyade analyse`: a whole result as CSV, JSON or tables (``write``), and
a sweep streamed block by block (``streamed``), each as a ``dyade.cli.analyse.Job``
describes it."""

from __future__ import annotations

import itertools
import os
import sys
from collections.abc import Mapping

from dyade.cli.common import options_named, warn
from dyade.cli.output import atomic, progress, show, write_json


def write(job, result, every, cols, output: str | None, loaded, summarise) -> None:
    """The CSV, the JSON document or the tables of a result (a whole ``Result`` or a
    stream's ``outcome()``) as ``job`` (``analyse.Job``) asks: ``every`` its columns,
    ``cols`` those chosen, ``summarise()`` its summary (of every column)."""
    mechanism = result.mechanism
    if job.fmt == "csv":
        from dyade.report import csv_rows

        if output:
            with atomic(output) as handle:
                csv_rows.write(cols, handle)
        else:
            csv_rows.write(cols, sys.stdout)
    elif job.fmt == "json":
        from dyade.linkage.columns import unit_of
        from dyade.report.document import document

        write_json(document("analyse", cols, {name: unit_of(name) for name in cols},
                            selected_summary(summarise(), cols),
                            [note.text for note in result.notes],
                            mechanism=mechanism.name, source=loaded.label,
                            positions=int(every["angle_deg"].size)), output)
    else:
        from dyade.report import tables

        unit = mechanism.units[0] if job.units == "file" else "m"
        summary = summarise() if result.drive is not None or not (
            job.columns or job.show_all) else None
        motion = (tables.motion_table(result, summary) if result.drive is not None
                  else None)
        if job.columns:
            parts = [tables.sweep_summary(result, cols, unit)]
        elif job.show_all:
            parts = [tables.sweep_summary(result, cols, unit),
                     tables.force_summary(result, cols), motion,
                     tables.clearance_summary(result)]
        else:
            parts = [tables.key_results(result, cols, summary, unit), motion]
        show(parts, output)


def streamed(job, mechanism, loaded, path: str, output: str | None) -> None:
    """The sweep block by block (``dyade.linkage.stream``) as ``job`` (``analyse.Job``)
    asks: CSV rows written as soon as
    they are computed; for JSON and the tables the blocks go to a ``Spool`` on disk,
    from which the summary and the JSON arrays take one column at a time."""
    from dyade.linkage.stream import Spool, stream
    from dyade.report import csv_rows

    with options_named():
        sweep_ = stream(mechanism, block_size=job.block_size,
                        allow_partial=job.allow_partial, friction_tol=job.friction_tol,
                        friction_max_iter=job.friction_max_iter, max_memory=job.max_memory,
                        dead_centre=job.dead_centre,
                        transmission_warning=job.transmission_warning,
                        constant_speed=job.constant_speed, run_up=job.run_up)
        blocks = sweep_.blocks()
        with progress(f"{os.path.basename(path)}: checking the sweep",
                      show=long_run(sweep_)) as tick:
            sweep_.progress = tick
            first = next(blocks)  # the assembly check fails here, before any output
    names = list(job.chosen(first))  # a wrong --columns fails before any output

    def analysing():
        return progress(f"{os.path.basename(path)}: analysing", show=long_run(sweep_))

    def emit(handle) -> None:
        writer = csv_rows.Writer(names, handle)
        writer.header()
        with analysing() as tick:
            sweep_.progress = tick
            writer.rows(first)
            for cols in blocks:
                writer.rows(cols)
        writer.close()

    if job.fmt != "csv":
        with analysing() as tick:
            sweep_.progress = tick
            spool = Spool(itertools.chain([first], blocks))
        with spool:
            from dyade.linkage.summary import summary

            outcome = sweep_.outcome()
            cols = Chosen(spool, names) if job.columns else spool
            write(job, outcome, spool, cols, output, loaded, lambda: summary(outcome, spool))
    elif output:
        with atomic(output) as handle:
            emit(handle)
    else:
        emit(sys.stdout)
    warn(sweep_.notes, f"{os.path.basename(path)}: " if output else "")
    job.check_locks(sweep_.outcome())


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


def selected_summary(summary: dict, cols) -> dict:
    """The summary of the whole sweep with the extremes of the chosen columns only."""
    return {**summary, "columns": {name: extremes for name, extremes in
                                   summary["columns"].items() if name in cols}}


SECOND = 8e6
"""values (positions × columns) a streamed CSV computes and writes in about a second"""


def long_run(sweep_) -> bool:
    """A streamed sweep expected to take more than about a second."""
    from dyade.linkage.sweep import BYTES_PER_VALUE, memory_estimate

    values = (memory_estimate(sweep_.mechanism, sweep_.crank_angle.size) - (50 << 20)) \
        / BYTES_PER_VALUE
    return values > SECOND
