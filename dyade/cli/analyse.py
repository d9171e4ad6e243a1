"""``dyade analyse``, ``dyade describe`` and ``dyade init``."""

from __future__ import annotations

import math
import os
import sys
from typing import Any, NamedTuple

import click

from dyade.cli import main
from dyade.cli.output import atomic, console, flags, show, write_json

# paths stay strings on the way of `dyade analyse`: pathlib alone costs 5 ms of start-up
MECHANISM_FILE = click.Path(exists=True, dir_okay=False)
SUFFIX = {"csv": ".csv", "json": ".json", "table": ".txt"}
FLAGS = {"friction_tol": "--friction-tol", "friction_max_iter": "--friction-max-iter",
         "start": "--start", "stop": "--stop", "step": "--step"}
"""API parameter -> the flag it comes from"""

set_option = click.option(
    "--set", "assignments", multiple=True, metavar="KEY=VALUE",
    help="Override a key of the file without editing it, with its dotted path as in the file "
         "(repeatable): --set crank.speed_rpm=600 --set dyad.1.lengths=[200,150]. Validated "
         "like the file.")


class SweepOptions(NamedTuple):
    """--start/--stop/--step [°], None where not given. (Option bundles are NamedTuples:
    each is 0.4 ms cheaper to create at start-up than a frozen dataclass.)"""

    start: float | None = None
    stop: float | None = None
    step: float | None = None


def load(path: str, assignments: tuple[str, ...] = (), sweep: SweepOptions = SweepOptions()):
    """Read a mechanism with --set overrides and --start/--stop/--step [°]; returns the
    mechanism and the effective TOML data (for --save-as)."""
    from dyade.files import mechanism as reader
    from dyade.files import schema
    from dyade.linkage.sweep import with_sweep

    overrides = dict(schema.parse_assignment(a) for a in assignments)
    data = reader.load_data(path, overrides, "--set")
    mechanism = reader.build(data, path)
    if sweep.start is None and sweep.stop is None and sweep.step is None:
        return mechanism, data
    current = mechanism.sweep  # the sweep options are in degrees whatever the file's unit
    start = math.radians(sweep.start) if sweep.start is not None else current.start
    stop = (math.radians(sweep.stop) if sweep.stop is not None
            else (start + 2 * math.pi if sweep.start is not None else current.stop))
    step = math.radians(sweep.step) if sweep.step is not None else current.step
    if step <= 0:
        raise click.BadParameter(f"must be positive, got {sweep.step:g}.", param_hint="--step")
    if stop < start:
        raise click.BadParameter(f"must not be below the start angle, got {sweep.stop:g}.",
                                 param_hint="--stop")
    return with_sweep(mechanism, start, stop, step), data


def save_as(data: dict[str, Any], path: str) -> None:
    """Write the effective mechanism (after --set) as TOML, atomically."""
    from dyade.files.mechanism import dumps

    with atomic(path) as handle:
        handle.write("# written by dyade --save-as: the effective mechanism after --set\n")
        handle.write(dumps(data))


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@set_option
def describe(mechanism_file: str, assignments: tuple[str, ...]) -> None:
    """Show MECHANISM_FILE in assembly order: crank, dyads, joints, link points, mobility,
    and which effects an analysis will simulate."""
    from dyade.linkage.sweep import plan
    from dyade.report import tables

    mechanism, _ = load(mechanism_file, assignments)
    show([tables.describe(mechanism, plan(mechanism))])


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="table: a summary (min/max and where); csv: the whole sweep, one row per crank "
                   "position; json: the CSV columns as arrays plus the summary and warnings. "
                   "[default: table on stdout; with -o: from its suffix (.json, .txt), else csv]")
@click.option("-o", "--output", type=click.Path(writable=True),
              help="Write to this file instead of standard output; with several input files a "
                   "directory, which gets one result per input (NAME.csv, NAME.json, NAME.txt).")
@click.option("--start", type=float, help="First crank angle [°] (overrides [sweep] start).")
@click.option("--stop", type=float, help="Last crank angle [°] (default: start + 360).")
@click.option("--step", type=float, help="Crank angle step [°] (overrides [sweep] step).")
@set_option
@click.option("--save-as", type=click.Path(dir_okay=False, writable=True),
              help="Write the effective mechanism (after --set) to this TOML file, to keep a "
                   "variant; one input file only.")
@click.option("--allow-partial", is_flag=True,
              help="Analyse only the crank angles where every dyad closes; the others are "
                   "left out of the output (and named on stderr) instead of failing.")
@click.option("--friction-tol", type=click.FloatRange(min=0.0, min_open=True),
              help="Accept a position's friction solution when a fixed-point step would "
                   "change its joint forces or friction loads by less than this [-]  "
                   "[default: file's [friction] tol, 1e-9].")
@click.option("--friction-max-iter", type=click.IntRange(min=1),
              help="Most passes of the friction solution per dyad and position  [default: "
                   "file's [friction] max_iter, 50]; positions not solved are named on stderr.")
@click.option("--fail-on-lock", is_flag=True,
              help="Exit with status 1 when the mechanism self-locks (otherwise self-locking "
                   "is a finding: reported, exit status 0).")
def analyse(mechanism_files: tuple[str, ...], fmt: str, output: str | None,
            start: float | None, stop: float | None, step: float | None,
            assignments: tuple[str, ...], save_as: str | None, allow_partial: bool,
            friction_tol: float | None, friction_max_iter: int | None,
            fail_on_lock: bool) -> None:
    """Sweep the crank of MECHANISM_FILES: positions, velocities and accelerations of every
    link, joint and named point.

    With masses, loads or springs in the file: joint forces, driving torque and shaking
    force; with friction coefficients: Coulomb friction, solved dyad by dyad, with
    self-locking (friction dead centres) and the margin of every slider with friction;
    with clearance data: the clearance peak check.

    Several files in one call (a batch) need -o DIR; a file that fails does not stop the
    others, and the failures are listed at the end (exit status 1).

    Units: SI (m, m/s, m/s², rad/s, rad/s², N, N·m, W) except angles in degrees. Exit
    status 1 when a dyad cannot close over part of the sweep (the message names the dyad
    and the crank-angle ranges) or, with --fail-on-lock, when it self-locks; 2 for a bad
    file or option.
    """
    from dyade.errors import DyadeError

    fmt = fmt or infer_format(output)
    job = Job(fmt, SweepOptions(start, stop, step), assignments, allow_partial, friction_tol,
              friction_max_iter, fail_on_lock)
    if len(mechanism_files) == 1 and not (output and os.path.isdir(output)):
        job.run(mechanism_files[0], output, save_as)
        return
    if save_as:
        raise click.UsageError("--save-as takes one input file.")
    if output is None:
        raise click.UsageError(f"{len(mechanism_files)} input files need -o DIR: one result file "
                               f"per input is written there.")
    if os.path.exists(output) and not os.path.isdir(output):
        raise click.UsageError(f"-o {output}: not a directory (several input files write one "
                               f"result each into a directory).")
    os.makedirs(output, exist_ok=True)
    failures = batch(mechanism_files, output, job.run, SUFFIX[fmt])
    if failures:
        lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
        raise DyadeError(f"{len(failures)} of {len(mechanism_files)} files failed:\n{lines}")


def infer_format(output: str | None) -> str:
    """table on stdout; with -o, from the suffix (.json, .txt), else csv."""
    if output is None:
        return "table"
    return {".json": "json", ".txt": "table"}.get(os.path.splitext(output)[1].lower(), "csv")


def batch(paths, directory: str, run_one, suffix: str) -> list[tuple[str, str]]:
    """Run ``run_one(path, target)`` for every path; a progress bar on stderr when it is
    a terminal; returns the failures (path, reason) instead of stopping."""
    from dyade.errors import DyadeError

    targets = _targets(paths, directory, suffix)
    failures = []
    progress = None
    if sys.stderr.isatty():
        from rich.progress import Progress

        progress = Progress(console=console(stderr=True), transient=True)
        task = progress.add_task("analysing", total=len(paths))
        progress.start()
    try:
        for path, target in zip(paths, targets):
            try:
                run_one(path, target, None)
            except (DyadeError, click.ClickException) as err:
                message = err.format_message() if isinstance(err, click.ClickException) else str(err)
                failures.append((path, message))
            if progress is not None:
                progress.advance(task)
    finally:
        if progress is not None:
            progress.stop()
    return failures


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


class Job(NamedTuple):
    """One analysis as the options describe it, applied to a file."""

    fmt: str
    sweep: SweepOptions
    assignments: tuple[str, ...]
    allow_partial: bool
    friction_tol: float | None
    friction_max_iter: int | None
    fail_on_lock: bool

    def run(self, path: str, output: str | None, save_as_path: str | None) -> None:
        from dyade.errors import AssemblyError, DyadeError
        from dyade.linkage.sweep import analyse

        mechanism, data = load(path, self.assignments, self.sweep)
        if save_as_path:
            save_as(data, save_as_path)
        try:
            with flags(FLAGS):
                result = analyse(mechanism, allow_partial=self.allow_partial,
                                 friction_tol=self.friction_tol,
                                 friction_max_iter=self.friction_max_iter)
        except AssemblyError as err:
            if not err.partial:
                raise
            raise AssemblyError("; ".join(err.problems) + ". Change the dimensions or the sweep, "
                                "or use --allow-partial to analyse only where it closes.",
                                err.problems, err.partial) from None
        cols = result.columns()
        if self.fmt == "csv":
            from dyade.report import csv_rows

            if output:
                with atomic(output) as handle:
                    csv_rows.write(cols, handle)
            else:
                csv_rows.write(cols, sys.stdout)
        elif self.fmt == "json":
            write_json(cols | {"summary": result.summary(cols),
                               "warnings": [note.text for note in result.notes]}, output)
        else:
            from dyade.report import tables

            show([tables.sweep_summary(result, cols), tables.force_summary(result, cols),
                  tables.clearance_summary(result)], output)
        if result.notes:  # rich is only loaded when there is something to say
            err = console(stderr=True)
            prefix = f"{os.path.basename(path)}: " if output else ""
            for note in result.notes:
                err.print(f"warning: {prefix}{note}")
        locks = any(lock.locks[result.rows].any() for lock in (result.locking or {}).values())
        if self.fail_on_lock and locks:
            raise DyadeError("the mechanism self-locks (see the warning above); --fail-on-lock "
                             "was given.")


TEMPLATES = {"fourbar": "RRR", "slider-crank": "RRP", "slotted-lever": "RPR",
             "tangent-drive": "PRP", "scotch-yoke": "PPR"}
KIND_ALIASES = {"rrr": "fourbar", "four-bar": "fourbar", "rrp": "slider-crank",
                "rpr": "slotted-lever", "prp": "tangent-drive", "ppr": "scotch-yoke"}


@main.command()
@click.argument("kind", type=click.Choice(sorted(TEMPLATES) + sorted(KIND_ALIASES),
                                          case_sensitive=False))
@click.argument("file", type=click.Path(dir_okay=False, writable=True))
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
def init(kind: str, file: str, force: bool) -> None:
    """Write a commented starting mechanism FILE for KIND: fourbar (RRR), slider-crank
    (RRP), slotted-lever (RPR), tangent-drive (PRP) or scotch-yoke (PPR). The file is
    valid and analysable as written: edit the numbers, then `dyade analyse FILE`."""
    from importlib.resources import files

    name = KIND_ALIASES.get(kind.lower(), kind.lower())
    if os.path.exists(file) and not force:
        raise click.UsageError(f"{file} exists; give --force to overwrite it.")
    text = files("dyade").joinpath("templates", f"{name}.toml").read_text(encoding="utf-8")
    with atomic(file) as handle:
        handle.write(text)
    console(stderr=True).print(f"wrote {file} ({name}, dyad kind {TEMPLATES[name]}); next: "
                               f"dyade describe {file}")
