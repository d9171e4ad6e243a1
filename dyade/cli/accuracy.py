"""``dyade accuracy``: what each accuracy knob buys and costs, for the user's mechanism;
the registry's ``accuracy`` entry (``dyade.analyses.accuracy``)."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.analyses.accuracy import ENTRIES
from dyade.cli import contract, main
from dyade.cli.machine import source_of
from dyade.cli.options import MECHANISM_FILE

ENTRY = ENTRIES["accuracy"]


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@contract.declare(ENTRY)
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def accuracy(mechanism_file: str, fmt: str, output, **options) -> None:
    """What accuracy costs in time, for MECHANISM_FILE.

    Crank step (5° … 0.05°): engine time and the error of the peak drive torque, the
    peak force of every joint and the clearance peaks against the finest step — where
    the peaks stop moving, and how coarse steps miss narrow peaks near dead centres.
    With friction: passes of the friction solution, time and change of the peaks per
    friction tolerance.
    With clearance data: the closed form against the direct simulation.
    """
    outcome = contract.run(ENTRY, source_of(mechanism_file),
                           options, what=f"{Path(mechanism_file).name}: accuracy studies")
    tables = None
    if fmt == "table":
        from dyade.report import accuracy as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome, prefix="note: ")
