"""``dyade plot synthesis``: a synthesis's target against its designs, and the designs
drawn."""

from __future__ import annotations

import os

import click

from dyade.cli.plot.output import figure_for, finish, output_options, single_target
from dyade.cli.synthesise import solve, synthesis_options


@click.command("synthesis")
@synthesis_options
@output_options()
def synthesis_figure(synthesis_file, output, fmt, show, dpi, **options) -> None:
    """The target (a function's table or profile, a path's points, poses) against what
    the best designs do, through dyade's engine (left), and the designs drawn with
    their frame pivots and coupler point (right). The file and options of
    `dyade synthesise`:

        dyade plot synthesis coupler-curve.toml --candidates 2000 -o designs.png
    """
    name = f"{os.path.splitext(synthesis_file.name)[0]}-synthesis"
    target, announce = single_target(output, fmt, show, dpi, name)
    outcome = solve(synthesis_file, options)
    from dyade.plot import synthesis as figure

    finish(figure.figure(outcome.result, fig=figure_for(target)), target, announce)
