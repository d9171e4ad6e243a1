"""``dyade gears``: natural frequencies, Campbell diagram, forced response of a gear drive
(Berczyński, Maćkowiak and Marchelek 1978); the registry's ``gear-modes``,
``gear-campbell`` and ``gear-response`` entries (``dyade.analyses.gears``)."""

from __future__ import annotations

import click

from dyade.analyses.gears import ENTRIES, FREQUENCY_RANGE, SPEED_RANGE
from dyade.cli import contract, main

MODES, CAMPBELL, RESPONSE = (ENTRIES[name] for name in ("gear-modes", "gear-campbell",
                                                       "gear-response"))


def read_source(gear_file: str):
    """The gear file's path, or standard input's text for "-"."""
    if gear_file != "-":
        return gear_file
    import sys

    from dyade.analyses.inputs import Text

    return Text(sys.stdin.read())


def gear_options(entries, skip: tuple[str, ...] = ()):
    """Decorate a command with the options of the gear ``entries``, each once (former
    flags such as ``--campbell`` as hidden aliases), less those in ``skip`` (API
    names)."""
    def decorate(command):
        for option in reversed(contract.declared(entries, skip)):
            command = contract.click_option(option)(command)
        return command

    return decorate


def chosen(options: dict) -> object:
    """The entry the options ask for: one analysis per run."""
    asked = [(flag, entry) for flag, entry, given in (
        ("--speed-range", CAMPBELL, options.get(SPEED_RANGE.api)),
        ("--frequency-range", RESPONSE, options.get(FREQUENCY_RANGE.api)),
        ("--check", MODES, options.get("check"))) if given]
    if len(asked) > 1:
        raise click.UsageError(f"{' and '.join(flag for flag, _ in asked)}: one analysis per run.")
    return asked[0][1] if asked else MODES


@main.command()
@click.argument("gear_file", type=click.Path(exists=True, dir_okay=False, allow_dash=True))
@gear_options((MODES, CAMPBELL, RESPONSE))
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every mode, resonance or frequency.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write the result to this file instead of standard output (-: standard "
                   "output; a missing folder is created).")
def gears(gear_file: str, fmt: str, output: str | None, **options) -> None:
    """Natural frequencies and modes of the gear drive in GEAR_FILE (rigid finite elements,
    or the torsional model): each mode's energy shares (torsion, lateral, axial per shaft
    and bearing; elastic meshes), the dominant part and the modal mesh forces. Rigid-body
    modes are reported as such, never as 0 Hz resonances.

    \b
        dyade gears mechanisms/gears/two-stage.toml
        dyade gears mechanisms/gears/two-stage.toml --speed-range 0:3000:10
        dyade gears mechanisms/gears/two-stage.toml --frequency-range 10:1000:1 --format csv

    `dyade help gear-file` documents every key of a gear-drive file.
    """
    entry = chosen(options)
    outcome = contract.run(entry, read_source(gear_file), options)
    tables = None
    if fmt == "table":
        from dyade.report import gears as report

        layout = {"gear-campbell": report.campbell_tables,
                  "gear-response": report.response_tables}.get(entry.name, report.mode_tables)
        if entry is MODES and outcome.result.elimination is not None:
            layout = report.check_tables
        tables = layout(outcome)
    contract.emit(outcome, fmt, output, tables)
    contract.notes(outcome)
