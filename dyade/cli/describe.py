"""``dyade describe``: a mechanism file in assembly order; the registry's ``describe``
entry (``dyade.analyses.describe``)."""

from __future__ import annotations

import click

from dyade.analyses.describe import ENTRIES
from dyade.cli import contract, main
from dyade.cli.options import MECHANISM_FILE

ENTRY = ENTRIES["describe"]


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@contract.declare(ENTRY)
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table",
              show_default=True, help="json: the plan and the mechanism's figures "
                                      "(`dyade help json`).")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
              help="Write to this file instead of standard output.")
def describe(mechanism_file: str, fmt: str, output: str | None, **options) -> None:
    """Show MECHANISM_FILE in assembly order: crank, dyads, joints, link points, mobility,
    and which effects an analysis will simulate."""
    from dyade.analyses.inputs import Text

    source = Text(click.get_text_stream("stdin").read()) if mechanism_file == "-" \
        else mechanism_file
    outcome = contract.run(ENTRY, source, options)
    tables = None
    if fmt == "table":
        from dyade.report import describe as report

        tables = [report.describe(outcome)]
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome)
