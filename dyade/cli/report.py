"""``dyade report``: the design report of a mechanism, gear, study or coupling file, one
HTML page."""

from __future__ import annotations

import os

import click

from dyade.cli import main
from dyade.cli.options import set_option


@main.command()
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
              help="The HTML file to write  [default: NAME-report.html here].")
@set_option
def report(file: str, output: str | None, assignments: tuple[str, ...]) -> None:
    """The design report of FILE (a mechanism, gear, study or coupling file) as one
    self-contained HTML page to read, share or print: what `dyade describe` says, the key
    results, the notes on where the model holds, the figures of `dyade plot` and the
    motion with a crank-angle slider; for a gear file its modes, Campbell diagram and mode
    shapes; for a study its tables and the figure of its question; for a coupling file
    its torsional resonance, transfer functions and phases.

    The page needs no network (figures inline as SVG, no external scripts or fonts) and
    the same file gives the same bytes. Needs the plot extra: pip install "dyade[plot]".

        dyade report mechanisms/dyade-16.toml -o dyade-16.html
    """
    from dyade.cli.output import atomic, console
    from dyade.files import schema
    from dyade.plot import require
    from dyade.report.html import report as design_report

    require()
    overrides = dict(schema.parse_assignment(a) for a in assignments)
    page = design_report(file, overrides or None)
    output = output or f"{os.path.splitext(os.path.basename(file))[0]}-report.html"
    with atomic(output) as handle:
        handle.write(page)
    console(stderr=True).print(f"wrote {output} ({len(page.encode('utf-8')) / 1e6:.2f} MB)")
