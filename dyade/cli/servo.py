"""``dyade servo``: the servo-driven crank sized over its cycle; the registry's ``servo``
entry (``dyade.analyses.servo``)."""

from __future__ import annotations

import click

from dyade.analyses.servo import ENTRIES
from dyade.cli import contract, main
from dyade.cli.common import infer_format

ENTRY = ENTRIES["servo"]


def source_of(path: str):
    """A file path as the entry reads it; "-": standard input's text."""
    if path != "-":
        return path
    import sys

    from dyade.analyses.inputs import Text

    return Text(sys.stdin.read())


def servo_options(command):
    """Decorate a command with the mechanism file and the entry's options (shared with
    ``dyade plot servo``)."""
    command = contract.declare(ENTRY)(command)
    return click.argument("mechanism_file", type=click.Path(exists=True, dir_okay=False,
                                                            allow_dash=True))(command)


def solve(mechanism_file: str, options: dict):
    """The entry run on the file and the command's options: an Outcome."""
    return contract.run(ENTRY, source_of(mechanism_file), options)


@main.command()
@servo_options
@click.option("--controller", "controller", type=click.Path(dir_okay=False, allow_dash=True),
              help="Also write the crank's motion over the cycle as a motion controller's "
                   "cam table (CSV: t [s], position_deg, velocity_deg_s, acceleration_deg_s2; "
                   "-: standard output).")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="table, csv (one row per instant of the cycle) or json. [default: table "
                   "on stdout; with -o: from its suffix]")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write the result to this file instead of standard output.")
def servo(mechanism_file: str, controller: str | None, fmt: str | None, output: str | None,
          **options) -> None:
    """Size the servo motor of MECHANISM_FILE's [servo] table.

    The crank follows the [profile] over the cycle time (or the profile moves an output,
    a slider's travel s_i_j or a link's angle phi_N, and is inverted through the linkage
    to the crank's motion, refused beyond the output's dead centres); the torque the crank
    needs comes from the sweep at the real crank speed and acceleration of every instant,
    M_c = J·φ̈ + ½·J′·φ̇² − M_L + M_F, and the motor's behind the gear (ratio i, efficiency
    η, its inertia) with the rotor's inertia. Reported: peak and RMS motor torque, top
    speed, the inertia ratio λ, the energy fed back per cycle; over a range of ratios the
    RMS optimum; with a motor catalogue every motor checked (thermal by RMS, peak within
    its envelope at its speed, top speed, λ) and the smallest that passes named.

    \b
        dyade servo mechanisms/servo/press.toml
        dyade servo mechanisms/servo/press.toml --ratio-range 3:40:1
        dyade servo mechanisms/servo/press.toml --ratio-range 2:40 --catalogue mechanisms/servo/motors.csv
        dyade servo mechanisms/servo/fourbar.toml --controller cam-table.csv

    `dyade init servo FILE` writes a commented example; `dyade plot servo` draws the
    torque-speed points over the motor's envelope and the profile's s, v, a, j.
    """
    fmt = fmt or infer_format(output)
    if fmt not in ("table", "csv", "json"):  # .parquet: not written by this command
        raise click.BadParameter(f"{output}: dyade servo writes .csv, .json or .txt (the "
                                 f"table); or give --format table|csv|json.", param_hint="-o")
    outcome = solve(mechanism_file, options)
    if controller:
        write_controller(outcome, controller)
    tables = None
    if fmt == "table":
        from dyade.report import servo as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables, width=150 if output else None)
    contract.notes(outcome)


def write_controller(outcome, path: str) -> None:
    """--controller: the cam table, to a file or standard output."""
    import sys

    from dyade.cli.output import atomic, to_file
    from dyade.report import servo as report

    if to_file(path):
        with atomic(path) as handle:
            report.write_controller(outcome, handle)
    else:
        report.write_controller(outcome, sys.stdout)
