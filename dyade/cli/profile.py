"""``dyade profile``: a motion profile over the machine cycle (VDI 2143 laws)."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.analyses.profile import ENTRIES
from dyade.cli import contract, main

ENTRY = ENTRIES["profile"]


def profile_options(command):
    """Decorate a command with the profile file and the entry's options (shared with
    ``dyade plot profile``)."""
    command = contract.declare(ENTRY)(command)
    return click.argument("file", type=click.Path(exists=True, dir_okay=False,
                                                  path_type=Path))(command)


def solve(file: Path, options: dict):
    """The entry run on the file and the command's options: an Outcome."""
    return contract.run(ENTRY, file, options)


@main.command()
@profile_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="csv: every row, for a motion controller (master, s, v, a, j, segment "
                   "in the file's units). [default: table on stdout; with -o: from its "
                   "suffix (.csv, .json, .txt)]")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
@click.option("--plot", "plot_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Also draw s, v, a, j over the cycle to this figure file (.png, .svg, "
                   ".pdf).")
def profile(file: Path, fmt, output, plot_file, **options) -> None:
    """A motion profile over one machine cycle: the output's position s, velocity v,
    acceleration a and jerk j at every master angle (or time), each segment's law with
    its boundary classes, its characteristic values C_v, C_a, C_j, C_M and its peaks.

    FILE is a profile file or a mechanism file with a [profile] table (dyade init profile
    writes one). The derivatives are with respect to the master, in the file's units
    (mm/°, mm/°², mm/°³ for a cam angle; per second with --speed or a time master). A
    jump in position or velocity is refused naming the segment (exit 2); a jump in
    acceleration that a law's class allows is said as a note.

    \b
        dyade profile mechanisms/profiles/indexing.toml
        dyade profile mechanisms/profiles/indexing.toml --speed 60 --format csv -o cam.csv
        dyade profile mechanisms/profiles/indexing.toml --plot indexing.png

    Laws: simple-harmonic, cycloid, inclined-sine, modified-sine, modified-trapezoid,
    polynomial-345, polynomial-4567, polynomial, harmonic-combination,
    acceleration-trapezoid, quintic-spline, constant-velocity
    (`dyade help motion-laws`).
    """
    from dyade.cli.common import infer_format

    fmt = fmt or infer_format(None if output is None else str(output))
    if fmt not in ("table", "csv", "json"):  # .parquet: not written by this command
        raise click.BadParameter(f"{output}: dyade profile writes .csv, .json or .txt (the "
                                 f"table); or give --format table|csv|json.", param_hint="-o")
    outcome = solve(file, options)
    tables = None
    if fmt == "table":
        from dyade.report import profile as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables, width=160 if output else None)
    contract.notes(outcome)
    if plot_file is not None:
        from dyade.cli.plot.output import finish, single_target

        target, _ = single_target(str(plot_file), None, False, None, file.stem)
        from dyade.plot import profile as figure

        finish(figure.figure(outcome), target, True)
