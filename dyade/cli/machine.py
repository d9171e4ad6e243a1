"""``dyade flywheel`` and ``dyade balance``: the machine in motion; the registry's
``flywheel`` and ``balance`` entries (``dyade.analyses.machine``)."""

from __future__ import annotations

import click

from dyade.analyses.machine import ENTRIES
from dyade.cli import contract, main
from dyade.cli.common import infer_format

FLYWHEEL, BALANCE = ENTRIES["flywheel"], ENTRIES["balance"]
FORMAT = click.Choice(["table", "csv", "json"])


def source_of(path: str):
    """A file path as the entry reads it; "-": standard input's text."""
    if path != "-":
        return path
    import sys

    from dyade.analyses.inputs import Text

    return Text(sys.stdin.read())


def output_options(what: str):
    """--format and -o of both commands."""
    def decorate(command):
        command = click.option(
            "-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
            help="Write to this file instead of standard output (-: standard output; a "
                 "missing folder is created).")(command)
        return click.option(
            "--format", "fmt", type=FORMAT, default=None,
            help=f"table, csv ({what}) or json. [default: table on stdout; with -o: from its "
                 f"suffix]")(command)
    return decorate


@main.command()
@click.argument("source", type=click.Path(exists=True, dir_okay=False, allow_dash=True))
@contract.declare(FLYWHEEL)
@output_options("one row: the keys below")
def flywheel(source: str, fmt: str | None, output: str | None, **options) -> None:
    """The flywheel from the torque curve over one revolution.

    SOURCE is a mechanism file, analysed at its constant crank speed (its drive torque
    M_drive against a motor of constant torque), or a CSV file with the columns
    angle_deg and M_drive [N·m] and optionally M_load [N·m] (positive where the load
    drives the machine; without it a constant load equal to the mean drive torque); a
    CSV written by `dyade analyse` is read as the machine's need at constant speed.

    With --fluctuation δ: the energy fluctuation delta_E [J] (the integral of the net
    torque over the cycle, max − min), the flywheel J_flywheel = ΔE/(δ·Ω²) − J_machine
    [kg·m²] and the crank angles of the highest and lowest speed. With --inertia J:
    the resulting fluctuation.

        dyade flywheel mechanisms/dyade-16.toml --fluctuation 0.02
    """
    fmt = fmt or infer_format(output)
    outcome = contract.run(FLYWHEEL, source_of(source), options)
    tables = None
    if fmt == "table":
        from dyade.report import machine as report

        tables = [report.flywheel_table(outcome)]
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome, prefix="note: ")


@main.command()
@click.argument("mechanism_file", type=click.Path(exists=True, dir_okay=False, allow_dash=True))
@contract.declare(BALANCE)
@click.option("--save-as", "save_path", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write the balanced mechanism (counterweights merged into the links' mass "
                   "data) to this TOML file, for `dyade analyse` (-: standard output).")
@output_options("one row per counterweight")
def balance(mechanism_file: str, save_path: str | None, fmt: str | None, output: str | None,
            **options) -> None:
    """Counterweights against the shaking force of MECHANISM_FILE.

    Counterweights (first moment m·r [kg·m] and angle in the link's frame) on links
    turning about frame pivots, fitted by linear least squares to make the shaking
    force (the resultant of the inertia forces) smallest over the sweep; a four-bar
    comes out fully force-balanced (Berkof & Lowen). Reports the counterweights, the
    residual shaking force and how the shaking moment, the drive torque and the joint
    forces change (at the constant crank speed).

        dyade balance mechanisms/fourbar.toml --save-as fourbar-balanced.toml
    """
    fmt = fmt or infer_format(output)
    outcome = contract.run(BALANCE, source_of(mechanism_file), options)
    if save_path:
        save(outcome, save_path)
    tables = None
    if fmt == "table":
        from dyade.report import machine as report

        tables = report.balance_tables(outcome)
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome, prefix="note: ")


def save(outcome, path: str) -> None:
    """--save-as: the mechanism file with the counterweights merged into its links."""
    from dyade.cli.output import atomic
    from dyade.files.mechanism import edited, load_data

    result, loaded = outcome.result
    data = load_data(loaded.label, loaded.overrides, "--set", loaded.text)
    overrides, removals = result.file_changes(data)
    text = edited(loaded.text, loaded.overrides | overrides, loaded.label, "--set", removals)
    with atomic(path) as handle:
        handle.write("# written by dyade balance --save-as: the mechanism with its "
                     "counterweights\n")
        handle.write(text)
