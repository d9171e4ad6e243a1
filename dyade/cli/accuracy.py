"""``dyade accuracy``: what each accuracy knob buys and costs, for the user's mechanism."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.cli import main
from dyade.cli.common import load
from dyade.cli.options import MECHANISM_FILE, set_option
from dyade.cli.output import progress, show, write_json, write_rows


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@set_option
@click.option("--repeats", type=click.IntRange(min=1), default=3, show_default=True, metavar="N",
              help="Runs per setting; the best time counts.")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def accuracy(mechanism_file: Path, assignments, repeats: int, fmt: str, output) -> None:
    """What accuracy costs in time, for MECHANISM_FILE.

    Crank step (5° … 0.05°): engine time and the error of the peak drive torque, the
    peak force of every joint and the clearance peaks against the finest step — where
    the peaks stop moving, and how coarse steps miss narrow peaks near dead centres.
    With friction: passes of the friction solution, time and change of the peaks per
    friction tolerance.
    With clearance data: the closed form against the direct simulation.
    """
    import dyade
    from dyade.report import accuracy as report

    mechanism = load(mechanism_file, assignments).mechanism
    with progress(f"{mechanism.name}: accuracy studies") as tick:
        records = report.records(dyade.accuracy_studies(mechanism, repeats=repeats,
                                                        progress=tick))
    if fmt == "csv":
        write_rows(records, report.COLUMNS, output)
    elif fmt == "json":
        from dyade.report.document import document

        write_json(document("accuracy", {name: [r[name] for r in records]
                                         for name in report.COLUMNS},
                            report.UNITS, {"mechanism": mechanism.name}, [],
                            mechanism=mechanism.name), output)
    else:
        show(report.tables(mechanism.name, records), output)
