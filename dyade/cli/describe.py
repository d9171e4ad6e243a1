"""``dyade describe``: a mechanism file in assembly order."""

from __future__ import annotations

import click

from dyade.cli import main
from dyade.cli.common import load
from dyade.cli.options import MECHANISM_FILE, set_option
from dyade.cli.output import show


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@set_option
def describe(mechanism_file: str, assignments: tuple[str, ...]) -> None:
    """Show MECHANISM_FILE in assembly order: crank, dyads, joints, link points, mobility,
    and which effects an analysis will simulate."""
    from dyade.linkage.plan import plan
    from dyade.report import describe as report
    from dyade.report import tables

    mechanism = load(mechanism_file, assignments).mechanism
    the_plan = plan(mechanism)
    show([report.describe(mechanism, the_plan, tables.skipped(the_plan))])
