"""``dyade driveline``: a linkage driven through an elastic shaft or coupling; each
``--analysis`` is an entry of the registry (``dyade.analyses.drive_line``)."""

from __future__ import annotations

import click

from dyade.analyses.base import COMMON
from dyade.analyses.drive_line import (ENTRIES, ETA_RANGE, MAP, PERIOD_TWO, SPEED_RANGE,
                                       SPEED_RPM)
from dyade.analyses.inputs import SET
from dyade.cli import contract, main
from dyade.cli.options import MECHANISM_FILE, Renamed, as_given

ANALYSES = ("frequency", "steady", "resonance", "stability", "map", "run-up")
"""``--analysis`` -> the entry ``driveline-<analysis>``"""


def driveline_options(command):
    """Decorate a command with the options of every drive-line entry, each declared once
    (``--speed-range`` keeps its old name ``--speeds-rpm`` as a hidden alias)."""
    for option in reversed((SET, SPEED_RANGE, ETA_RANGE, SPEED_RPM, MAP, PERIOD_TWO,
                             *COMMON)):
        if option is SPEED_RANGE:
            command = click.option(option.flag, option.api, cls=Renamed, old=("--speeds-rpm",),
                                   metavar=option.metavar, help=option.text)(command)
        else:
            command = contract.click_option(option)(command)
    return command


def solve(what: str, mechanism_file: str, params: dict):
    """The entry of ``--analysis what`` run on the file with the command's options; an
    option that is not the entry's is refused naming the analyses it is for."""
    import sys

    from dyade.analyses.inputs import Text

    entry = ENTRIES[f"driveline-{what}"]
    own = {option.api for option in entry.every_option}
    for option in (SPEED_RANGE, ETA_RANGE, SPEED_RPM, MAP, PERIOD_TWO):
        if params.get(option.api) not in (None, False) and option.api not in own:
            users = [name.removeprefix("driveline-") for name, other in ENTRIES.items()
                     if option in other.options]
            raise click.UsageError(f"{as_given(option.flag)} is for --analysis "
                                   f"{' and '.join(users)}, not {what}.")
    source = Text(sys.stdin.read()) if mechanism_file == "-" else mechanism_file
    return contract.run(entry, source, params)


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--analysis", "what", type=click.Choice(ANALYSES), default="steady",
              show_default=True,
              help="frequency: ω̄ over the cycle; steady: the periodic state at the operating "
                   "speed next to the rigid drive's; resonance: peak shaft torque, twist and "
                   "speed fluctuation over --speed-range; stability: the Floquet multipliers "
                   "over --speed-range; map: the largest multiplier over --speed-range × "
                   "--map; run-up: from rest under the [drive] motor.")
@driveline_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="table, csv or json. [default: table on stdout; with -o: from its suffix]")
@click.option("-o", "--output", type=click.Path(writable=True, dir_okay=False),
              help="Write to this file instead of standard output.")
def driveline(mechanism_file: str, what: str, fmt: str | None, output: str | None,
              **params) -> None:
    """The elastic drive line of MECHANISM_FILE ([drive_line] table): motor → shaft or
    coupling → the linkage's crank shaft with its reduced inertia J(φ).

    Always: ω̄, the lowest natural frequency with the mean inertia J̄, its range over the
    cycle, η = Ω/ω̄ and the VDI 2149 check (the rigid model holds for η ≤ 0.1). Then
    the analysis asked for:

    \b
        dyade driveline mech.toml                       # steady state vs rigid
        dyade driveline mech.toml --analysis resonance --speed-range 300:6000:50
        dyade driveline mech.toml --analysis stability --eta-range 0.2:1.6:0.01
        dyade driveline mech.toml --analysis stability --eta-range 0.6:0.9:0.1 --period-two
        dyade driveline mech.toml --analysis map --speed-range 300:6000:50 \\
            --map stiffness=500:2000:100
        dyade driveline mech.toml --analysis run-up

    Resonance curves, stability charts and maps scan an ideal motor's speed (a [drive]
    motor is replaced by one); steady state and run-up use the [drive] motor if the file
    has one. Forced resonances lie near Ω = ω̄/k, parametric instability near
    Ω = 2ω̄/k, k a harmonic of J(φ) or M_L(φ). A run-up that never reaches speed, and a
    scan where no speed has a periodic state, exit 1.
    """
    from dyade.cli.common import infer_format

    fmt = fmt or infer_format(output)
    outcome = solve(what, mechanism_file, params)
    tables = None
    if fmt == "table":
        from dyade.report import drive_line as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome, "note: ")
