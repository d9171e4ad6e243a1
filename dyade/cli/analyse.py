"""``dyade analyse``, ``dyade describe`` and ``dyade init``."""

from __future__ import annotations

import itertools
import math
import os
import sys
from collections.abc import Mapping
from typing import Any, NamedTuple

import click

from dyade.cli import main
from dyade.cli.options import FINITE, POSITIVE
from dyade.cli.output import atomic, console, flags, progress, show, write_json

# paths stay strings on the way of `dyade analyse`: pathlib alone costs 5 ms of start-up
MECHANISM_FILE = click.Path(exists=True, dir_okay=False, allow_dash=True)
SUFFIX = {"csv": ".csv", "json": ".json", "table": ".txt"}
FLAGS = {"friction_tol": "--friction-tol", "friction_max_iter": "--friction-max-iter",
         "start": "--start", "stop": "--stop", "step": "--step",
         "sweep": "the sweep (--start, --stop, --step)", "max_memory": "--max-memory",
         "dead_centre": "--dead-centre", "transmission_warning": "--transmission-warning",
         "run_up": "--run-up", "block_size": "--block-size"}
"""API parameter -> the flag it comes from"""

set_option = click.option(
    "--set", "assignments", multiple=True, metavar="KEY=VALUE",
    help="Override a key of the file without editing it, with its dotted path as in the file "
         "(repeatable): --set crank.speed_rpm=600 --set dyad.2.lengths=[200,150]. Validated "
         "like the file.")


jobs_option = click.option(
    "-j", "--jobs", type=click.IntRange(min=0), default=1, show_default=True, metavar="N",
    help="Analyse several files (or speeds) on N processes at once (0: all cores); the "
         "output is that of a serial run, in the same order.")


class SweepOptions(NamedTuple):
    """--start/--stop/--step [°], None where not given. (Option bundles are NamedTuples:
    each is 0.4 ms cheaper to create at start-up than a frozen dataclass.)"""

    start: float | None = None
    stop: float | None = None
    step: float | None = None


class Loaded(NamedTuple):
    """A mechanism as read, with what --save-as needs to write it again."""

    mechanism: Any
    text: str
    """the file's text as read (or standard input's)"""
    overrides: dict[str, Any]
    """--set key -> value"""
    label: str


def read_input(path: str) -> tuple[str, str]:
    """The text of an input file, or of standard input for "-"; and its name."""
    from dyade.files import schema

    if path == "-":
        return sys.stdin.read(), "<stdin>"
    return schema.read_text(path), path


def load(path: str, assignments: tuple[str, ...] = (), sweep: SweepOptions = SweepOptions()
         ) -> Loaded:
    """Read a mechanism ("-": standard input) with --set overrides and
    --start/--stop/--step [°]."""
    from dyade.files import mechanism as reader
    from dyade.files import schema
    from dyade.linkage.sweep import with_sweep

    overrides = dict(schema.parse_assignment(a) for a in assignments)
    text, label = read_input(path)
    data = reader.load_data(label, overrides, "--set", text)
    mechanism = reader.build(data, label)
    if sweep.start is None and sweep.stop is None and sweep.step is None:
        return Loaded(mechanism, text, overrides, label)
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
    with flags(FLAGS):
        return Loaded(with_sweep(mechanism, start, stop, step), text, overrides, label)


def save_as(loaded: Loaded, path: str) -> None:
    """Write the effective mechanism (after --set) as TOML, atomically: the input's text
    with the overridden values replaced, its comments and layout kept."""
    from dyade.files.mechanism import edited

    text = edited(loaded.text, loaded.overrides, os.path.basename(loaded.label), "--set")
    with atomic(path) as handle:
        handle.write("# written by dyade --save-as: the effective mechanism after --set\n")
        handle.write(text)


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@set_option
def describe(mechanism_file: str, assignments: tuple[str, ...]) -> None:
    """Show MECHANISM_FILE in assembly order: crank, dyads, joints, link points, mobility,
    and which effects an analysis will simulate."""
    from dyade.linkage.sweep import plan
    from dyade.report import describe as report
    from dyade.report import tables

    mechanism = load(mechanism_file, assignments).mechanism
    the_plan = plan(mechanism)
    show([report.describe(mechanism, the_plan, tables.skipped(the_plan))])


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="table: a summary (min/max and where); csv: the whole sweep, one row per crank "
                   "position; json: the CSV columns as arrays plus the summary and warnings. "
                   "[default: table on stdout; with -o: from its suffix (.json, .txt), else csv]")
@click.option("-o", "--output", type=click.Path(writable=True),
              help="Write to this file instead of standard output; with several input files a "
                   "directory, which gets one result per input (NAME.csv, NAME.json, NAME.txt).")
@click.option("--start", type=FINITE, help="First crank angle [°] (overrides [sweep] start).")
@click.option("--stop", type=FINITE, help="Last crank angle [°] (default: start + 360).")
@click.option("--step", type=POSITIVE, help="Crank angle step [°] (overrides [sweep] step).")
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
@click.option("--friction-max-iter", type=click.IntRange(min=1),
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
    if run_up and constant_speed:
        raise click.UsageError("--run-up and --constant-speed exclude each other.")
    chosen = tuple(p.strip() for p in patterns.split(",") if p.strip()) if patterns else ()
    job = Job(fmt, SweepOptions(start, stop, step), assignments, allow_partial, friction_tol,
              friction_max_iter, fail_on_lock, show_all, chosen, units, max_memory * 2 ** 20,
              None if dead_centre is None else math.radians(dead_centre),
              None if transmission_warning is None else math.radians(transmission_warning),
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


FORMATS = {".csv": "csv", ".json": "json", ".txt": "table", "": "csv"}
"""suffix of -o -> format (no suffix, or a directory: csv)"""


def infer_format(output: str | None) -> str:
    """table on stdout; with -o, from the suffix (.csv, .json, .txt); an unknown suffix
    is an error that lists the formats."""
    if output is None or output == "-":
        return "table"
    if os.path.isdir(output):
        return "csv"
    suffix = os.path.splitext(output)[1].lower()
    if suffix not in FORMATS:
        raise click.BadParameter(f"{output}: dyade does not write {suffix} files. It writes "
                                 f".csv (the sweep), .json (columns, units, summary, warnings) "
                                 f"and .txt (the summary table); or give --format "
                                 f"table|csv|json.", param_hint="-o")
    return FORMATS[suffix]


def batch(paths, directory: str, run_one, suffix: str, jobs: int = 1,
          modules: tuple[str, ...] = ()) -> list[tuple[str, str]]:
    """Run ``run_one(path, target, None)`` for every path, on ``jobs`` processes (0: all
    cores; see ``dyade.parallel``); a progress bar on stderr when it
    is a terminal; returns the failures (path, reason) instead of stopping. With several
    processes each file's warnings are kept and printed in the order of the files, as in
    a serial run, and ``modules`` (those every file needs) are imported once, before the
    other processes are forked, instead of once in each."""
    from dyade import parallel

    targets = _targets(paths, directory, suffix)
    workers = min(workers_for(jobs), len(paths))
    capture = workers > 1
    if capture:
        import importlib

        for name in modules:
            importlib.import_module(name)

    def one(task):
        path, target = task
        return attempt(run_one, path, target, capture)

    def lost(task, reason):
        return f"{reason} before {task[0]} was done (rerun it alone)", ""

    failures = []
    outcomes = parallel.ordered_map(one, list(zip(paths, targets)), workers, lost)
    with progress("analysing", total=len(paths)) as tick:
        for done, (path, (failure, said)) in enumerate(zip(paths, outcomes), start=1):
            if said:
                sys.stderr.write(said)
            if failure is not None:
                failures.append((path, failure))
            tick(done)
    return failures


SWEEP = ("dyade.files.mechanism", "dyade.linkage.sweep", "dyade.linkage.kinetostatics",
         "dyade.linkage.reduced", "dyade.linkage.columns", "dyade.linkage.dyads.rrr",
         "dyade.linkage.dyads.rrp", "dyade.linkage.dyads.rpr", "dyade.linkage.dyads.prp",
         "dyade.linkage.dyads.ppr")
"""what every sweep of a mechanism file imports (friction only where a file has it)"""
NEEDS = {"csv": SWEEP + ("dyade.linkage.stream", "dyade.report.csv_rows"),
         "json": SWEEP + ("dyade.linkage.summary", "dyade.report.document"),
         "table": SWEEP + ("dyade.linkage.summary", "dyade.report.tables")}
"""modules ``analyse`` needs for every file, by output format"""


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
    """[rad]"""
    transmission_warning: float | None = None
    """[rad]"""
    run_up: bool = False
    constant_speed: bool = False
    block_size: int | None = None
    """positions per block of a streamed CSV (None: the default, 0: the whole sweep)"""

    def run(self, path: str, output: str | None, save_as_path: str | None) -> None:
        output = None if output == "-" else output  # -o -: standard output
        loaded = load(path, self.assignments, self.sweep)
        mechanism = loaded.mechanism
        if save_as_path:
            save_as(loaded, save_as_path)
        if self.block_size != 0:
            self.streamed(mechanism, loaded, path, output)
            return
        result = sweep(mechanism, self.allow_partial, self.friction_tol, self.friction_max_iter,
                       max_memory=self.max_memory, dead_centre=self.dead_centre,
                       transmission_warning=self.transmission_warning, run_up=self.run_up,
                       constant_speed=self.constant_speed)
        every = result.columns()
        self.write(result, every, self.chosen(every), output, loaded,
                   lambda: result.summary(every))
        warn(result.notes, f"{os.path.basename(path)}: " if output else "")
        self.check_locks(result)

    def check_locks(self, result) -> None:
        """--fail-on-lock: exit status 1 when the mechanism self-locks somewhere (a whole
        ``Result`` or a stream's ``outcome()``)."""
        from dyade.errors import DyadeError

        locks = any(lock.locks[result.rows].any() for lock in (result.locking or {}).values())
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
                                     f"(mechanisms/README.md lists them).",
                                     param_hint="--columns")
        return Chosen(every, names)

    def write(self, result, every, cols, output: str | None, loaded, summarise) -> None:
        """The CSV, the JSON document or the tables of a result (a whole ``Result`` or a
        stream's ``outcome()``): ``every`` its columns, ``cols`` those chosen,
        ``summarise()`` its summary (of every column)."""
        mechanism = result.mechanism
        if self.fmt == "csv":
            from dyade.report import csv_rows

            if output:
                with atomic(output) as handle:
                    csv_rows.write(cols, handle)
            else:
                csv_rows.write(cols, sys.stdout)
        elif self.fmt == "json":
            from dyade.linkage.columns import unit_of
            from dyade.report.document import document

            write_json(document("analyse", cols, {name: unit_of(name) for name in cols},
                                selected_summary(summarise(), cols),
                                [note.text for note in result.notes],
                                mechanism=mechanism.name, source=loaded.label,
                                positions=int(every["angle_deg"].size)), output)
        else:
            from dyade.report import tables

            unit = mechanism.units[0] if self.units == "file" else "m"
            summary = summarise() if result.drive is not None or not (
                self.columns or self.show_all) else None
            motion = (tables.motion_table(result, summary) if result.drive is not None
                      else None)
            if self.columns:
                parts = [tables.sweep_summary(result, cols, unit)]
            elif self.show_all:
                parts = [tables.sweep_summary(result, cols, unit),
                         tables.force_summary(result, cols), motion,
                         tables.clearance_summary(result)]
            else:
                parts = [tables.key_results(result, cols, summary, unit), motion]
            show(parts, output)

    def streamed(self, mechanism, loaded, path: str, output: str | None) -> None:
        """The sweep block by block (``dyade.linkage.stream``): CSV rows written as soon as
        they are computed; for JSON and the tables the blocks go to a ``Spool`` on disk,
        from which the summary and the JSON arrays take one column at a time."""
        from dyade.linkage.stream import Spool, stream
        from dyade.report import csv_rows

        with options_named():
            sweep_ = stream(mechanism, block_size=self.block_size,
                            allow_partial=self.allow_partial, friction_tol=self.friction_tol,
                            friction_max_iter=self.friction_max_iter, max_memory=self.max_memory,
                            dead_centre=self.dead_centre,
                            transmission_warning=self.transmission_warning,
                            constant_speed=self.constant_speed, run_up=self.run_up)
            blocks = sweep_.blocks()
            with progress(f"{os.path.basename(path)}: checking the sweep",
                          show=long_run(sweep_)) as tick:
                sweep_.progress = tick
                first = next(blocks)  # the assembly check fails here, before any output
        names = list(self.chosen(first))  # a wrong --columns fails before any output

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

        if self.fmt != "csv":
            with analysing() as tick:
                sweep_.progress = tick
                spool = Spool(itertools.chain([first], blocks))
            with spool:
                from dyade.linkage.summary import summary

                outcome = sweep_.outcome()
                cols = Chosen(spool, names) if self.columns else spool
                self.write(outcome, spool, cols, output, loaded, lambda: summary(outcome, spool))
        elif output:
            with atomic(output) as handle:
                emit(handle)
        else:
            emit(sys.stdout)
        warn(sweep_.notes, f"{os.path.basename(path)}: " if output else "")
        self.check_locks(sweep_.outcome())


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


class options_named:
    """Errors of the API named as the options give them: flags for parameters, and a
    partial closure suggests --allow-partial."""

    def __enter__(self) -> None:
        pass

    def __exit__(self, exc_type, exc, tb) -> bool:
        from dyade.errors import AssemblyError, InputError

        if isinstance(exc, InputError):
            raise exc.naming(FLAGS) from None
        if isinstance(exc, AssemblyError) and exc.partial:
            raise AssemblyError("; ".join(exc.problems) + ". Change the dimensions or the "
                                "sweep, or use --allow-partial to analyse only where it "
                                "closes.", exc.problems, exc.partial) from None
        return False


def sweep(mechanism, allow_partial: bool, friction_tol: float | None = None,
          friction_max_iter: int | None = None, **options):
    """``dyade.analyse`` with the options' names in its errors (a partial closure
    suggests --allow-partial); ``options``: its other keywords."""
    from dyade.linkage.sweep import analyse

    with options_named():
        return analyse(mechanism, allow_partial=allow_partial, friction_tol=friction_tol,
                       friction_max_iter=friction_max_iter, **options)


def warn(notes, prefix: str = "") -> None:
    """The result's notes on stderr, each a warning: one line each, as they are, into a
    pipe or a file (or a batch worker's capture); through rich on a terminal, which
    wraps them (rich is loaded only then: about 20 ms of every batch worker's start)."""
    if not notes:
        return
    if not sys.stderr.isatty():
        sys.stderr.write("".join(f"warning: {prefix}{note}\n" for note in notes))
        return
    err = console(stderr=True)
    for note in notes:
        err.print(f"warning: {prefix}{note}", markup=False)


TEMPLATES = {"fourbar": "RRR", "slider-crank": "RRP", "slotted-lever": "RPR",
             "tangent-drive": "PRP", "scotch-yoke": "PPR"}
KIND_ALIASES = {"rrr": "fourbar", "four-bar": "fourbar", "rrp": "slider-crank",
                "rpr": "slotted-lever", "prp": "tangent-drive", "ppr": "scotch-yoke"}


@main.command()
@click.argument("kind", type=click.Choice(sorted(TEMPLATES) + sorted(KIND_ALIASES),
                                          case_sensitive=False))
@click.argument("file", type=click.Path(dir_okay=False, writable=True, allow_dash=True))
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
def init(kind: str, file: str, force: bool) -> None:
    """Write a commented starting mechanism FILE for KIND: fourbar (RRR), slider-crank
    (RRP), slotted-lever (RPR), tangent-drive (PRP) or scotch-yoke (PPR). The file is
    valid and analysable as written: edit the numbers, then `dyade analyse FILE`.
    FILE "-" prints the template."""
    from importlib.resources import files

    name = KIND_ALIASES.get(kind.lower(), kind.lower())
    text = files("dyade").joinpath("templates", f"{name}.toml").read_text(encoding="utf-8")
    if file == "-":
        click.echo(text, nl=False)
        return
    if os.path.exists(file) and not force:
        raise click.UsageError(f"{file} exists; give --force to overwrite it.")
    with atomic(file) as handle:
        handle.write(text)
    console(stderr=True).print(f"wrote {file} ({name}, dyad kind {TEMPLATES[name]}); next: "
                               f"dyade describe {file}")
