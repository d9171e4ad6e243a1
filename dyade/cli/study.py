"""``dyade study``: many variants of one mechanism file, one row each."""

from __future__ import annotations

import os

import click

from dyade.cli import main

FORMATS = ("table", "csv", "json", "parquet")


def study_options(command):
    """The options ``dyade study`` and ``dyade plot study`` share."""
    for option in reversed([
            click.option("-j", "--jobs", type=click.IntRange(min=0), default=1,
                         show_default=True, metavar="N",
                         help="Run the variants on N processes (0: all cores); the same "
                              "table as one process gives."),
            click.option("--scheduler", metavar="ADDRESS",
                         help="Run the blocks on a Dask distributed cluster instead "
                              "(tcp://host:8786; needs pip install \"dyade[dask]\")."),
            click.option("--block-size", type=click.IntRange(min=1), default=None,
                         metavar="N", help="Variants per task  [default: at least 0.1 s of "
                                           "work, every worker busy]."),
    ]):
        command = option(command)
    return command


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
def study(study_file: str, output: str | None, fmt: str | None, resume: bool, jobs: int,
          scheduler: str | None, block_size: int | None) -> None:
    """Run the design study of STUDY_FILE: one row per variant of its mechanism file,
    the parameters first (by their --set key paths, in the file's units), then status
    and reason (ok, locks, does not close, refused), then every key result of
    `dyade analyse`'s summary (SI; angles in degrees).

    The study file names the parameters (lists, ranges, distributions), the plan (grid,
    latin-hypercube, monte-carlo, sensitivity, optimise) and the question (tolerance
    limits, objectives); `dyade init study FILE` writes a commented one, and
    docs/reference/study-file.md documents every key.

    \b
        dyade study tolerance.toml -j 0 -o tolerance.csv
        dyade study tolerance.toml -j 0 -o tolerance.csv --resume

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
    result = run(study_file, output if fmt in ("csv",) else
                 (output + ".part.csv" if output else None), resume, jobs, scheduler,
                 block_size)
    write(result, output, fmt)
    if output:
        from dyade.cli.output import console

        total = len(result.columns()["variant"])
        kept = total - result.evaluations
        console(stderr=True).print(f"wrote {output}: {total} variants"
                                   + (f" ({result.evaluations} computed, {kept} kept from the "
                                      f"interrupted run)" if resume else ""))


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


def run(study_file: str, journal: str | None, resume: bool, jobs: int, scheduler: str | None,
        block_size: int | None):
    """The study, on -j processes or the --scheduler's cluster, with a progress bar on a
    terminal."""
    from dyade.cli.batch import workers_for
    from dyade.study import study as run_study

    client = connect(scheduler) if scheduler else None
    executor = client.get_executor() if client is not None else None
    try:
        with bar() as tick:
            result = run_study(study_file, jobs=workers_for(jobs), executor=executor,
                               output=journal, resume=resume, block_size=block_size,
                               progress=tick)
    finally:
        if client is not None:
            client.close()
    return result


def connect(address: str):
    """A Dask client of the scheduler at ``address``; exit 2 naming it when it does not
    answer within 5 s."""
    from dyade.study import needs

    needs("distributed", "--scheduler", extra="dask")
    import logging

    from distributed import Client

    logging.getLogger("distributed").setLevel(logging.CRITICAL)
    reachable(address)
    try:
        return Client(address, timeout="5s")
    except (OSError, TimeoutError, ValueError) as err:
        raise click.BadParameter(f"no Dask scheduler answers at {address} ({err}).",
                                 param_hint="--scheduler") from None


def reachable(address: str, timeout: float = 3.0) -> None:
    """Refuse at once a tcp:// address where nothing listens (Dask's client would try
    again until its timeout)."""
    import socket

    if not address.startswith("tcp://"):
        return
    host, _, port = address[len("tcp://"):].rpartition(":")
    try:
        number = int(port.strip("/"))
    except ValueError:
        raise click.BadParameter(f"{address}: give tcp://HOST:PORT.",
                                 param_hint="--scheduler") from None
    try:
        socket.create_connection((host.strip("[]"), number), timeout=timeout).close()
    except OSError as err:
        raise click.BadParameter(f"no Dask scheduler answers at {address} "
                                 f"({err.strerror or err}).", param_hint="--scheduler") from None


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


def write(result, output: str | None, fmt: str) -> None:
    """The table in its format (the CSV is written already, as it streamed)."""
    from dyade.study import tables

    journal = output + ".part.csv" if output and fmt != "csv" else None
    if fmt == "csv" and output is None:
        import sys

        names = list(result.columns())
        click.echo(",".join(names))
        cols = result.columns()
        for i in range(len(cols["variant"])):
            sys.stdout.write(",".join(_csv(tables.cell(cols[n][i])) for n in names) + "\n")
        return
    if fmt == "table":
        from dyade.cli.output import show
        from dyade.report.study import tables as report

        show(report(result), output)
    elif fmt == "json":
        from dyade.cli.output import jsonable

        tables.write_json(result.columns(), result.units, output,
                          {"study": result.spec.label, "answers": jsonable(result.answers())})
    elif fmt == "parquet":
        tables.write_parquet(result.columns(), result.units, output,
                             {"dyade.study": result.spec.label})
    if journal and os.path.exists(journal):
        os.unlink(journal)


def _csv(text: str) -> str:
    return f"\"{text.replace(chr(34), chr(34) * 2)}\"" if any(c in text for c in ",\"\n") else text
