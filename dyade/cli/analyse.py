"""``dyade analyse``: the crank sweep of one or several mechanism files; the registry's
``sweep`` entry (``dyade.analyses.sweep``)."""

from __future__ import annotations

import os
from typing import Any, NamedTuple

import click

from dyade.analyses import inputs
from dyade.analyses.sweep import AT, ENTRIES, FAIL_ON_LOCK
from dyade.cli import contract, main, writers
from dyade.cli.batch import SUFFIX, SWEEP, batch
from dyade.cli.common import infer_format
from dyade.cli.options import MECHANISM_FILE, jobs_option

ENTRY = ENTRIES["sweep"]
EARLIER = tuple(option.api for option in (inputs.SET, *inputs.SWEEP, AT))
"""the options --help lists before --at: the file's and the sweep's"""
LATER = tuple(option.api for option in ENTRY.every_option if option.api not in EARLIER[:-1])
"""the others, listed after it"""


def angles(ctx, param, values: tuple[str, ...]) -> tuple[float, ...]:
    """--at DEG, repeatable or a comma list: the crank angles [°]."""
    import math

    out = []
    for value in values:
        for part in value.split(","):
            try:
                angle = float(part)
            except ValueError:
                angle = math.nan
            if not math.isfinite(angle):
                raise click.BadParameter(f"must be crank angles [°] (numbers, repeatable or "
                                         f"a comma list: --at 30,60), got {value!r}.",
                                         ctx, param)
            out.append(angle)
    return tuple(out)


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json", "parquet"]),
              default=None,
              help="table: the key results (--all: min/max of every column and where); csv: "
                   "the whole sweep, one row per crank position; json: the columns as arrays "
                   "with their units, the summary's figures, the notes "
                   "(`dyade help json`); parquet: the CSV's columns with their units "
                   "(needs -o and the parquet extra). "
                   "[default: table on stdout; with -o: from its suffix (.json, .txt), else csv]")
@click.option("-o", "--output", type=click.Path(writable=True),
              help="Write to this file instead of standard output; with several input files a "
                   "directory, which gets one result per input (NAME.csv, NAME.json, NAME.txt).")
@contract.declare(ENTRY, skip=LATER)
@click.option("--at", AT.api, multiple=True, metavar="DEG", callback=angles, help=AT.text)
@contract.declare(ENTRY, skip=EARLIER)
@click.option("--save-as", type=click.Path(dir_okay=False, writable=True),
              help="Write the effective mechanism (after --set) to this TOML file, to keep a "
                   "variant; one input file only.")
@click.option("--all", "show_all", is_flag=True,
              help="Table: min and max of every column and where, the force summary and the "
                   "clearance peaks (default: the key results only).")
@click.option("--columns", "patterns", metavar="PATTERN",
              help="Only the columns whose names match these comma-separated glob patterns "
                   "(every format; angle_deg always): --columns 'M_drive,F_*,mu_*'.")
@click.option("--units", type=click.Choice(["file", "si"]), default="file", show_default=True,
              help="Table lengths in the file's length unit ([units] length) or in SI (m); "
                   "CSV, JSON and Parquet stay SI.")
@jobs_option
def analyse(mechanism_files: tuple[str, ...], fmt: str | None, output: str | None,
            save_as: str | None, show_all: bool, patterns: str | None, units: str, jobs: int,
            **params: Any) -> None:
    """Sweep the crank of MECHANISM_FILES: positions, velocities and accelerations of every
    link, joint and named point.

    With masses, loads or springs in the file: joint forces, driving torque and shaking
    force, reduced inertia and load torque; with friction coefficients: Coulomb friction,
    solved dyad by dyad, with self-locking (friction dead centres) and the margin of every
    slider with friction; with clearance data: the clearance peak check; with a [drive]
    table: the crank's real speed from the equation of motion (steady state, or --run-up),
    and everything at that speed. --at DEG: single crank positions instead of a sweep.
    With a [cam] table the cam drives link 2, its follower: the sweep runs over the cam
    angle θ at the cam's speed_rpm, and F_cam [N] is the cam's contact force (docs/guide/
    cams.md):

        dyade analyse mechanisms/cams/cam-rocker.toml --set cam.base_radius=34

    Several files in one call (a batch) need -o DIR; a file that fails does not stop the
    others, and the failures are listed at the end (exit status 1).

    Units: SI (m, m/s, m/s², rad/s, rad/s², N, N·m, W) except angles in degrees; tables
    show lengths in the file's unit (--units). Exit status 1 when a dyad cannot close over
    part of the sweep (the message names the dyad and the crank-angle ranges), when no
    position has its kinematics given or, with --fail-on-lock, when it self-locks; 2 for a
    bad file or option.
    """
    from dyade.errors import DyadeError

    fmt = fmt or infer_format(output)
    if fmt == "parquet" and (output is None or output == "-"):
        raise click.UsageError("--format parquet needs -o FILE (Parquet is not written to a "
                               "terminal).")
    chosen = tuple(p.strip() for p in patterns.split(",") if p.strip()) if patterns else ()
    options = {name: value for name, value in contract.options_of(ENTRY, params).items()
               if value is not False}  # (a flag not given)
    job = Job(fmt, options, show_all, chosen, units)
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


ANALYSES = ("dyade.analyses.sweep", "dyade.analyses.inputs", "dyade.analyses.notes")
NEEDS = {"csv": SWEEP + ANALYSES + ("dyade.report.csv_rows",),
         "json": SWEEP + ANALYSES + ("dyade.analyses.spool", "dyade.linkage.summary",
                                     "dyade.report.document"),
         "parquet": SWEEP + ANALYSES + ("dyade.analyses.spool", "dyade.study.tables"),
         "table": SWEEP + ANALYSES + ("dyade.analyses.spool", "dyade.linkage.summary",
                                      "dyade.report.tables")}
"""modules ``analyse`` needs for every file, by output format"""


class Job(NamedTuple):
    """One analysis as the options describe it, applied to a file."""

    fmt: str
    options: dict[str, Any]
    """the entry's options given on the command line (API names)"""
    show_all: bool = False
    columns: tuple[str, ...] = ()
    """glob patterns of the columns to keep (all when empty)"""
    units: str = "file"
    """table lengths: "file" (the file's length unit) or "si\""""

    def run(self, path: str, output: str | None, save_as_path: str | None) -> None:
        import sys

        from dyade.analyses.inputs import Text

        output = None if output == "-" else output  # -o -: standard output
        source = Text(sys.stdin.read()) if path == "-" else path
        if save_as_path:
            from dyade.analyses.inputs import SET, load
            from dyade.cli.common import save_as

            with writers.named(ENTRY):
                save_as(load(source, {SET.api: self.options.get(SET.api)}), save_as_path)
        writers.streamed(self, source, path, output)

    @property
    def fail_on_lock(self) -> bool:
        return bool(self.options.get(FAIL_ON_LOCK.api))

    def chosen(self, every) -> list[str]:
        """The columns --columns names (all of them without it)."""
        if not self.columns:
            return list(every)
        from fnmatch import fnmatchcase

        names = [name for name in every if name == "angle_deg"
                 or any(fnmatchcase(name, p) for p in self.columns)]
        if len(names) == 1:
            raise click.BadParameter(f"no column matches {', '.join(self.columns)}; the "
                                     f"columns are {', '.join(list(every)[:12])}, … "
                                     f"(`dyade help columns` lists them).",
                                     param_hint="--columns")
        return names
