"""``dyade plot study``: a design study's figures."""

from __future__ import annotations

import os

import click

from dyade.cli.plot.output import figure_for, finish, output_options, single_target
from dyade.cli.study import solve, study_options


@click.command("study")
@click.argument("study_file", type=click.Path(exists=True, dir_okay=False))
@click.option("--table", type=click.Path(dir_okay=False),
              help="The study's CSV (dyade study -o): its rows are read, the missing ones "
                   "computed and added (as --resume does).")
@click.option("--x", "x", metavar="KEY", help="The parameter along the x axis  [default: the "
                                              "first].")
@click.option("--y", "y", metavar="KEY", help="A second parameter: a map over x and y.")
@click.option("--show-output", "outputs", metavar="NAME", multiple=True,
              help="The output to plot (repeatable)  [default: M_drive_rms, or every one for "
                   "histograms and bars].")
@study_options
@output_options()
def study_figure(study_file, table, x, y, outputs, output, fmt, show, dpi, **options) -> None:
    """The figure of STUDY_FILE's question: a tolerance study's histograms with their
    limits, a sensitivity study's bars (% output per % parameter), the Pareto front of
    several objectives with the chosen design; otherwise an output against one
    parameter (--x) or a map over two (--x, --y).

    \b
        dyade plot study study.toml --table study.csv -o study.png \\
            --x dyad.2.lengths.1 --y dyad.2.lengths.2
    """
    name = f"{os.path.splitext(os.path.basename(study_file))[0]}-study"
    target, announce = single_target(output, fmt, show, dpi, name)
    result = solve(study_file, options, table,
                   table is not None and os.path.exists(table)).result
    from dyade.plot import study as figure

    for key in (x, y):
        if key is not None and key not in result.parameters:
            raise click.BadParameter(f"{key} is not a parameter of {study_file}: "
                                     f"{', '.join(result.parameters)}.", param_hint="--x/--y")
    for key in outputs:
        if key not in result.outputs:
            from dyade.files.schema import suggest

            raise click.BadParameter(f"{key} is not an output.{suggest(key, set(result.outputs))}",
                                     param_hint="--show-output")
    picture = figure.question_figure(result, list(outputs), x, y, fig=figure_for(target))
    finish(picture, target, announce)
