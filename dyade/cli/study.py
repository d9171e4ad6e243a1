"""``dyade study``: many variants of one mechanism file, one row each; the registry's
``study`` entry (``dyade.study.entry``)."""

from __future__ import annotations

import os

import click

from dyade.study.entry import ENTRIES
from dyade.cli import contract, main

ENTRY = ENTRIES["study"]
FORMATS = ("table", "csv", "json", "parquet")


def study_options(command):
    """The options ``dyade study`` and ``dyade plot study`` share: the entry's (the
    journal and --resume are each command's own), -j."""
    command = contract.declare(ENTRY, skip=("jobs", "journal", "resume"))(command)
    return click.option("-j", "--jobs", "jobs", type=click.IntRange(min=0), default=1,
                        show_default=True, metavar="N",
                        help=ENTRY.option("jobs").help + ".")(command)


@main.command("study")
@click.argument("study_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
              help="Write the table here, its format from the suffix (.csv, .json, .parquet, "
                   ".txt); the rows stream to it (or to OUTPUT.part.csv) block by block.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default=None,
              help="table: the answers on the terminal; csv, json, parquet: one row per "
                   "variant (JSON with the answers)  [default: table, or from -o].")
@click.option("--resume", is_flag=True,
              help="Keep the rows already in -o (an interrupted study) and compute only the "
                   "others.")
@study_options
def study(study_file: str, output: str | None, fmt: str | None, resume: bool,
          **options) -> None:
    """Run the design study of STUDY_FILE: one row per variant of its mechanism file,
    the parameters first (by their --set key paths, in the file's units), then status
    and reason (ok, locks, does not close, refused, failed, withheld), then every key
    result of `dyade analyse`'s summary (SI; angles in degrees).

    The study file names the parameters (lists, ranges, distributions), the plan (grid,
    latin-hypercube, monte-carlo, sensitivity, optimise) and the question (tolerance
    limits, objectives); `dyade init study FILE` writes a commented one, and
    `dyade help study-file` documents every key.

    \b
        dyade study tolerance.toml -j 0 -o tolerance.csv
        dyade study tolerance.toml -j 0 -o tolerance.csv --resume
        dyade study tolerance.toml --samples 20 --seed 2 --set crank.speed_rpm=600

    Exit status 2 for a bad study file or an unreachable --scheduler; a variant that
    fails is a row with its reason, not an error.
    """
    if output == "-":  # standard output: a stream, written at the end
        output, fmt = None, fmt or "csv"
    fmt = fmt or _format(output)
    if fmt == "table" and output and not output.endswith(".txt"):
        fmt = "csv"
    if fmt == "parquet" and not output:
        raise click.UsageError("--format parquet needs -o FILE.parquet (a binary table, not "
                               "for a terminal).")
    if output:
        writable_folder(output)
    if resume and not output:
        raise click.UsageError("--resume needs -o FILE: the rows of the interrupted run.")
    journal = journal_of(output, fmt)
    outcome = solve(study_file, options, journal, resume)
    write(outcome, output, fmt)
    if journal and journal != output and os.path.exists(journal):
        os.unlink(journal)
    if output and fmt != "table":  # the table went to the file: the answers on the terminal
        from dyade.cli.output import show
        from dyade.report.study import tables as report_tables

        show(report_tables(outcome), None)
    contract.notes(outcome, prefix="note: ")
    if output:
        from dyade.cli.output import console

        console(stderr=True).print(wrote(output, outcome.summary["variants"].value,
                                         outcome.meta["evaluations"], resume))


def wrote(output: str, total: int, computed: int, resume: bool) -> str:
    """What ``dyade study -o`` says it wrote: with --resume, how many variants it computed
    and how many it kept (all of them: the study was already complete)."""
    text = f"wrote {output}: {total} variant{'s' * (total != 1)}"
    if not resume:
        return text
    kept = total - computed
    if computed == 0:
        return f"{text} (all kept from {output}: the study was already complete, none computed)"
    if kept == 0:
        return f"{text} ({computed} computed; none was there to keep)"
    return f"{text} ({computed} computed, {kept} kept from the interrupted run)"


def journal_of(output: str | None, fmt: str) -> str | None:
    """The CSV the rows stream to: -o itself for a CSV, OUTPUT.part.csv beside another
    format (removed at the end), none on standard output."""
    if not output:
        return None
    return output if fmt == "csv" else output + ".part.csv"


def writable_folder(output: str) -> None:
    """Create -o's missing folders before the study runs; exit 2 naming -o when a part of
    its folder is a file or cannot be made."""
    folder = os.path.dirname(output)
    try:
        if folder:
            os.makedirs(folder, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        raise click.BadParameter(f"{output}: a part of its folder {folder} is a file, not a "
                                 f"folder.", param_hint="-o") from None
    except OSError as err:
        raise click.BadParameter(f"{output}: cannot make its folder ({err.strerror}).",
                                 param_hint="-o") from None


def _format(output: str | None) -> str:
    if not output:
        return "table"
    suffix = os.path.splitext(output)[1].lower()
    return {".csv": "csv", ".json": "json", ".parquet": "parquet", ".txt": "table"}.get(
        suffix, "csv")


def solve(study_file: str, params: dict, journal: str | None, resume: bool):
    """The entry run on the study file with the command's options (on -j processes or the
    --scheduler's cluster), errors naming the flags, the variants' bar on a terminal."""
    from dyade.cli.output import console, flags

    options = contract.options_of(ENTRY, params)
    options.update({"journal": journal} if journal else {})
    options.update({"resume": True} if resume else {})
    err = console(stderr=True)
    names = contract.flags(ENTRY) | {"journal": "-o", "jobs": "-j"}
    with flags(names), bar() as tick:
        return ENTRY(study_file, progress=tick, told=lambda text: err.print(text, markup=False),
                     **options)


def bar():
    """A progress bar on stderr, with the rate and the time left, only on a terminal."""
    import sys
    from contextlib import contextmanager

    @contextmanager
    def shown():
        if not sys.stderr.isatty():
            yield None
            return
        from rich.progress import (BarColumn, MofNCompleteColumn, Progress, ProgressColumn,
                                   TaskProgressColumn, TextColumn, TimeRemainingColumn)
        from rich.text import Text

        from dyade.cli.output import console

        class Rate(ProgressColumn):
            def render(self, task):
                return Text(f"{task.speed:.3g} variants/s" if task.speed else "")

        progress = Progress(TextColumn("variants"), BarColumn(), MofNCompleteColumn(),
                            TaskProgressColumn(), Rate(), TimeRemainingColumn(),
                            console=console(stderr=True), transient=True)
        task = progress.add_task("variants", total=None)

        def tick(done: int, total: int) -> None:
            if not progress.live.is_started:
                progress.start()
            progress.update(task, completed=done, total=total)

        try:
            yield tick
        finally:
            progress.stop()

    return shown()


def write(outcome, output: str | None, fmt: str) -> None:
    """The study in its format: csv (the one CSV writer, over the journal that streamed
    to -o), json (the Outcome's document), parquet (units per column), or the tables."""
    if fmt == "parquet":
        from dyade.study import tables

        tables.write_parquet(outcome.columns, outcome.units, output,
                             {"dyade.study": outcome.meta["study"]})
        return
    report = None
    if fmt == "table":
        from dyade.report.study import tables as report_tables

        report = report_tables(outcome)
    contract.emit(outcome, fmt, output, report)
