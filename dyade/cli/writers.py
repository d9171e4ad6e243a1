"""The writers of `dyade analyse`: a sweep computed block by block (``streamed``) and
written as CSV rows as they come, or as JSON or tables from a spool of its columns
(``write``), each as a ``dyade.cli.analyse.Job`` describes it."""

from __future__ import annotations

import itertools
import os
import sys
from collections.abc import Mapping

from dyade.cli.common import options_named, warn
from dyade.cli.output import atomic, progress, show, write_json


def write(job, result, every, cols, output: str | None, loaded, summarise) -> None:
    """The CSV, the JSON document or the tables of a sweep's outcome (``result``) as
    ``job`` (``analyse.Job``) asks: ``every`` its columns, ``cols`` those chosen,
    ``summarise()`` its summary (of every column)."""
    mechanism = result.mechanism
    if job.fmt == "csv":
        from dyade.report import csv_rows

        if output:
            with atomic(output) as handle:
                csv_rows.write(cols, handle)
        else:
            csv_rows.write(cols, sys.stdout)
    elif job.fmt == "parquet":
        from dyade.linkage.columns import unit_of
        from dyade.study.tables import write_parquet

        write_parquet(cols, {name: unit_of(name) for name in cols}, output,
                      {"dyade.mechanism": mechanism.name, "dyade.source": loaded.label})
    elif job.fmt == "json":
        from dyade.linkage.columns import unit_of
        from dyade.report.document import document
        from dyade.report.effects import with_effects
        from dyade.report.notes import say

        write_json(document("analyse", cols, {name: unit_of(name) for name in cols},
                            selected_summary(with_effects(summarise(), result.plan), cols),
                            [say(note, mechanism) for note in result.notes],
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
    """The sweep block by block (``dyade.analyse_in_blocks``) as ``job``
    (``analyse.Job``) asks: CSV rows written as soon as they are computed; for JSON and
    the tables the blocks go to a ``Spool`` on disk, from which the summary and the JSON
    arrays take one column at a time."""
    from dyade.linkage.sweep import analyse_in_blocks
    from dyade.report import csv_rows

    with options_named():
        run = analyse_in_blocks(mechanism, block_size=sys.maxsize if job.block_size == 0
                                else job.block_size,
                                allow_partial=job.allow_partial, friction_tol=job.friction_tol,
                                friction_max_iter=job.friction_max_iter,
                                max_memory=job.max_memory, dead_centre_deg=job.dead_centre,
                                transmission_warning_deg=job.transmission_warning,
                                constant_speed=job.constant_speed, run_up=job.run_up)
        blocks = (block.columns for block in run)
        with progress(f"{os.path.basename(path)}: checking the sweep",
                      show=long_run(run)) as tick:
            run.progress = tick
            first = next(blocks)  # the assembly check fails here, before any output
    names = list(job.chosen(first))  # a wrong --columns fails before any output

    def analysing():
        return progress(f"{os.path.basename(path)}: analysing", show=long_run(run))

    def emit(handle) -> None:
        writer = csv_rows.Writer(names, handle)
        writer.header()
        with analysing() as tick:
            run.progress = tick
            writer.rows(first)
            for cols in blocks:
                writer.rows(cols)
        writer.close()

    if job.fmt != "csv":
        from dyade.report.spool import Spool

        with analysing() as tick:
            run.progress = tick
            spool = Spool(itertools.chain([first], blocks))
        with spool:
            from dyade.linkage.summary import summary

            outcome = run.outcome
            cols = Chosen(spool, names) if job.columns else spool
            write(job, outcome, spool, cols, output, loaded, lambda: summary(outcome, spool))
    elif output:
        with atomic(output) as handle:
            emit(handle)
    else:
        emit(sys.stdout)
    warn(run.outcome.notes, mechanism, f"{os.path.basename(path)}: " if output else "")
    outcome = run.outcome
    if outcome.rows.any() and not outcome.valid[outcome.rows].any():  # an all-empty table
        from dyade.errors import DyadeError

        raise DyadeError(f"{mechanism.name}: no position of the sweep has its kinematics "
                         f"given (the warnings above say why); the output holds only empty "
                         f"rows.")
    job.check_locks(run.outcome)


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


def long_run(run) -> bool:
    """A sweep (``pipeline.Run``) expected to take more than about a second."""
    from dyade.linkage.options import BYTES_PER_VALUE, memory_estimate

    values = (memory_estimate(run.setup.mechanism, run.setup.positions) - (50 << 20)) \
        / BYTES_PER_VALUE
    return values > SECOND
