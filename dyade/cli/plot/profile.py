"""``dyade plot profile``: a motion profile's s, v, a, j over the cycle."""

from __future__ import annotations

import click

from dyade.cli.plot.output import figure_for, finish, output_options, single_target
from dyade.cli.profile import profile_options, solve


@click.command("profile")
@profile_options
@output_options()
def profile_figure(file, output, fmt, show, dpi, **options) -> None:
    """A motion profile's position, velocity, acceleration and jerk over one machine
    cycle, in four panels with the segments marked (number and law). The options and
    file of `dyade profile`:

        dyade plot profile mechanisms/profiles/indexing.toml -o indexing.png
    """
    target, announce = single_target(output, fmt, show, dpi, f"{file.stem}-profile")
    outcome = solve(file, options)
    from dyade.plot import profile as figure

    finish(figure.figure(outcome, fig=figure_for(target, (7.0, 7.2))), target, announce)
