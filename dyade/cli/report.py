"""``dyade report``: the design report of a mechanism, gear, study, coupling or cam file, one
HTML page."""

from __future__ import annotations

import os

import click

from dyade.analyses.inputs import ALLOW_PARTIAL, SET, SWEEP
from dyade.cli import main
from dyade.cli.contract import click_option

OPTIONS = (SET, *SWEEP, ALLOW_PARTIAL)
"""the options of the analyses a report composes (a mechanism's sweep), as the commands
declare them"""


def report_options(command):
    for option in reversed(OPTIONS):
        command = click_option(option)(command)
    return command


@main.command()
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
              help="The HTML file to write  [default: NAME-report.html here].")
@report_options
@click.option("--units", type=click.Choice(["file", "si"]), default="file", show_default=True,
              help="The tables' lengths in the mechanism file's length unit or in SI (m), "
                   "as dyade analyse's.")
def report(file: str, output: str | None, units: str, **options) -> None:
    """The design report of FILE (a mechanism, gear, study, coupling or cam file) as one
    self-contained HTML page to read, share or print: what `dyade describe` says, the key
    results, the notes on where the model holds, the figures of `dyade plot` and the
    motion with a crank-angle slider; for a gear file its modes, Campbell diagram and mode
    shapes; for a study its tables and the figure of its question; for a coupling file
    its torsional resonance, transfer functions and phases; for a cam file the cam's
    checks, notes and figure of `dyade cam` (--step: the cam-angle step).

    The options of `dyade analyse` that choose the sweep (--start, --stop, --step,
    --allow-partial) choose the report's: a mechanism that closes over part of the turn is
    reported over that part with --allow-partial, the gaps shaded in the figures and said
    in the notes.

    The page needs no network (figures inline as SVG, no external scripts or fonts) and
    the same file gives the same bytes. Needs the plot extra: pip install "dyade[plot]".

        dyade report mechanisms/dyade-16.toml -o dyade-16.html
    """
    from dyade.cli.common import FLAGS, options_named
    from dyade.cli.contract import options_of_declared
    from dyade.cli.output import atomic, console, flags
    from dyade.files import schema
    from dyade.plot import require
    from dyade.report.html import report as design_report

    require()
    given = options_of_declared(OPTIONS, options)
    overrides = dict(schema.parse_assignment(a) for a in given.pop(SET.api, ()))
    with flags({option.api: option.flag for option in OPTIONS} | FLAGS), options_named():
        page = design_report(file, overrides or None, **given,
                             **({"units": "si"} if units == "si" else {}))
    output = output or f"{os.path.splitext(os.path.basename(file))[0]}-report.html"
    with atomic(output) as handle:
        handle.write(page)
    console(stderr=True).print(f"wrote {output} ({len(page.encode('utf-8')) / 1e6:.2f} MB)")
