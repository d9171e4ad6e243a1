"""``dyade analyse``: the crank sweep of one or several mechanism files."""

from __future__ import annotations

import os
from typing import NamedTuple

import click

from dyade.cli import main, writers
from dyade.cli.batch import SUFFIX, SWEEP, batch
from dyade.cli.common import SweepOptions, infer_format, load, save_as
from dyade.cli.options import FINITE, MECHANISM_FILE, POSITIVE, jobs_option, set_option


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json", "parquet"]),
              default=None,
              help="table: a summary (min/max and where); csv: the whole sweep, one row per crank "
                   "position; json: the CSV columns as arrays plus the summary and warnings; "
                   "parquet: the CSV's columns with their units (needs -o and the parquet "
                   "extra). "
                   "[default: table on stdout; with -o: from its suffix (.json, .txt), else csv]")
@click.option("-o", "--output", type=click.Path(writable=True),
              help="Write to this file instead of standard output; with several input files a "
                   "directory, which gets one result per input (NAME.csv, NAME.json, NAME.txt).")
@click.option("--start", type=FINITE, metavar="DEG",
              help="First crank angle [°] (overrides [sweep] start).")
@click.option("--stop", type=FINITE, metavar="DEG",
              help="Last crank angle [°] (default: start + 360).")
@click.option("--step", type=POSITIVE, metavar="DEG",
              help="Crank angle step [°] (overrides [sweep] step).")
@set_option
@click.option("--save-as", type=click.Path(dir_okay=False, writable=True),
              help="Write the effective mechanism (after --set) to this TOML file, to keep a "
                   "variant; one input file only.")
@click.option("--allow-partial", is_flag=True,
              help="Analyse only the crank angles where every dyad closes; the others are "
                   "left out of the output (and named on stderr) instead of failing.")
@click.option("--friction-tol", type=POSITIVE,
              help="Accept a position's friction solution when a fixed-point step would "
                   "change its joint forces or friction loads by less than this [-]  "
                   "[default: file's [friction] tol, 1e-9].")
@click.option("--friction-max-iter", type=click.IntRange(min=1), metavar="N",
              help="Most passes of the friction solution per dyad and position  [default: "
                   "file's [friction] max_iter, 50]; positions not solved are named on stderr.")
@click.option("--all", "show_all", is_flag=True,
              help="Table: min and max of every column and where, the force summary and the "
                   "clearance peaks (default: the key results only).")
@click.option("--columns", "patterns", metavar="PATTERN",
              help="Only the columns whose names match these comma-separated glob patterns "
                   "(every format; angle_deg always): --columns 'M_drive,F_*,mu_*'.")
@click.option("--units", type=click.Choice(["si", "file"]), default="si", show_default=True,
              help="Table lengths in SI (m) or in the file's length unit ([units] length); "
                   "CSV and JSON stay SI.")
@click.option("--dead-centre", type=FINITE, metavar="DEG",
              help="Hard band [°]: within this of a dead centre (transmission angle 0° or "
                   "180°) nothing is given  [default: file's [sweep] dead_centre, 2].")
@click.option("--transmission-warning", type=FINITE, metavar="DEG",
              help="Soft band [°]: transmission angles below this are reported with a "
                   "warning  [default: file's [sweep] transmission_warning, 40 (H. Alt's "
                   "rule)].")
@click.option("--max-memory", type=POSITIVE, default=4096, show_default=True, metavar="MB",
              help="Refuse, before computing, a sweep estimated to need more memory [MB] "
                   "(in memory, with --block-size 0: positions × columns × 90 B; streamed: a "
                   "block's, and about 100 B per position).")
@click.option("--block-size", type=click.IntRange(min=0), default=None, metavar="N",
              help="Compute the sweep N positions at a time, in memory that does not grow "
                   "with the sweep (0: all at once)  [default: 2048]: CSV rows are written "
                   "as they come; for JSON and the tables the columns wait in a temporary "
                   "file (8 B per value, in TMPDIR).")
@click.option("--fail-on-lock", is_flag=True,
              help="Exit with status 1 when the mechanism self-locks (otherwise self-locking "
                   "is a finding: reported, exit status 0).")
@click.option("--run-up", is_flag=True,
              help="With a [drive] table: the run-up from rest at the start angle, revolution "
                   "after revolution until the speed repeats, instead of the periodic steady "
                   "state; the rows are the whole run-up at the sweep's step (column t: time).")
@click.option("--constant-speed", is_flag=True,
              help="Ignore the [drive] table: the crank at its constant speed_rpm (to compare "
                   "with the real speed).")
@jobs_option
def analyse(mechanism_files: tuple[str, ...], fmt: str, output: str | None,
            start: float | None, stop: float | None, step: float | None,
            assignments: tuple[str, ...], save_as: str | None, allow_partial: bool,
            friction_tol: float | None, friction_max_iter: int | None,
            show_all: bool, patterns: str | None, units: str, dead_centre: float | None,
            transmission_warning: float | None, max_memory: float, block_size: int | None,
            fail_on_lock: bool, run_up: bool, constant_speed: bool, jobs: int) -> None:
    """Sweep the crank of MECHANISM_FILES: positions, velocities and accelerations of every
    link, joint and named point.

    With masses, loads or springs in the file: joint forces, driving torque and shaking
    force, reduced inertia and load torque; with friction coefficients: Coulomb friction,
    solved dyad by dyad, with self-locking (friction dead centres) and the margin of every
    slider with friction; with clearance data: the clearance peak check; with a [drive]
    table: the crank's real speed from the equation of motion (steady state, or --run-up),
    and everything at that speed.

    Several files in one call (a batch) need -o DIR; a file that fails does not stop the
    others, and the failures are listed at the end (exit status 1).

    Units: SI (m, m/s, m/s², rad/s, rad/s², N, N·m, W) except angles in degrees. Exit
    status 1 when a dyad cannot close over part of the sweep (the message names the dyad
    and the crank-angle ranges) or, with --fail-on-lock, when it self-locks; 2 for a bad
    file or option.
    """
    from dyade.errors import DyadeError

    fmt = fmt or infer_format(output)
    if fmt == "parquet" and (output is None or output == "-"):
        raise click.UsageError("--format parquet needs -o FILE (Parquet is not written to a "
                               "terminal).")
    if run_up and constant_speed:
        raise click.UsageError("--run-up and --constant-speed exclude each other.")
    chosen = tuple(p.strip() for p in patterns.split(",") if p.strip()) if patterns else ()
    job = Job(fmt, SweepOptions(start, stop, step), assignments, allow_partial, friction_tol,
              friction_max_iter, fail_on_lock, show_all, chosen, units, max_memory * 2 ** 20,
              dead_centre, transmission_warning,
              run_up, constant_speed, block_size)
    if len(mechanism_files) == 1 and not (output and os.path.isdir(output)):
        job.run(mechanism_files[0], output, save_as)
        return
    if save_as:
        raise click.UsageError("--save-as takes one input file.")
    if "-" in mechanism_files:
        raise click.UsageError("standard input (-) can be the only input file.")
    if output is None or output == "-":
        raise click.UsageError(f"{len(mechanism_files)} input files need -o DIR: one result file "
                               f"per input is written there.")
    if os.path.exists(output) and not os.path.isdir(output):
        raise click.UsageError(f"-o {output}: not a directory (several input files write one "
                               f"result each into a directory).")
    os.makedirs(output, exist_ok=True)
    failures = batch(mechanism_files, output, job.run, SUFFIX[fmt], jobs, NEEDS[fmt])
    if failures:
        lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
        raise DyadeError(f"{len(failures)} of {len(mechanism_files)} files failed:\n{lines}")


NEEDS = {"csv": SWEEP + ("dyade.report.csv_rows",),
         "json": SWEEP + ("dyade.linkage.summary", "dyade.report.document",
                          "dyade.report.spool", "dyade.report.notes", "dyade.report.effects"),
         "parquet": SWEEP + ("dyade.report.spool", "dyade.study.tables"),
         "table": SWEEP + ("dyade.linkage.summary", "dyade.report.tables",
                           "dyade.report.spool", "dyade.report.notes")}
"""modules ``analyse`` needs for every file, by output format"""


class Job(NamedTuple):
    """One analysis as the options describe it, applied to a file."""

    fmt: str
    sweep: SweepOptions
    assignments: tuple[str, ...]
    allow_partial: bool
    friction_tol: float | None
    friction_max_iter: int | None
    fail_on_lock: bool
    show_all: bool = False
    columns: tuple[str, ...] = ()
    """glob patterns of the columns to keep (all when empty)"""
    units: str = "si"
    max_memory: float | None = None
    """[B]"""
    dead_centre: float | None = None
    """[°]"""
    transmission_warning: float | None = None
    """[°]"""
    run_up: bool = False
    constant_speed: bool = False
    block_size: int | None = None
    """positions per block (None: the default, 0: the whole sweep as one)"""

    def run(self, path: str, output: str | None, save_as_path: str | None) -> None:
        output = None if output == "-" else output  # -o -: standard output
        loaded = load(path, self.assignments, self.sweep)
        if save_as_path:
            save_as(loaded, save_as_path)
        writers.streamed(self, loaded.mechanism, loaded, path, output)

    def check_locks(self, outcome) -> None:
        """--fail-on-lock: exit status 1 when the mechanism self-locks somewhere (a
        sweep's ``outcome``)."""
        from dyade.errors import DyadeError

        locks = any(lock.locks[outcome.rows].any() for lock in (outcome.locking or {}).values())
        if self.fail_on_lock and locks:
            raise DyadeError("the mechanism self-locks (see the warning above); --fail-on-lock "
                             "was given.")

    def chosen(self, every):
        """The columns --columns names (all of them without it): a view, nothing copied."""
        if not self.columns:
            return every
        from dyade.report.tables import select

        names = list(select(dict.fromkeys(every, 0), list(self.columns)))
        if len(names) == 1:
            raise click.BadParameter(f"no column matches {', '.join(self.columns)}; the "
                                     f"columns are {', '.join(list(every)[:12])}, … "
                                     f"(docs/reference/mechanism-file.md lists them).",
                                     param_hint="--columns")
        return writers.Chosen(every, names)
