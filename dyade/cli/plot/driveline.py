"""``dyade plot driveline``: the elastic drive line's figures, drawn from the Outcome of
the entry ``driveline-<analysis>`` (``dyade.analyses.drive_line``)."""

from __future__ import annotations

import os

import click

from dyade.cli.driveline import driveline_options, solve
from dyade.cli.options import MECHANISM_FILE
from dyade.cli.plot.output import figure_for, finish, output_options, single_target

KINDS = ("resonance", "stability", "map", "steady", "run-up")
"""the analyses with a figure (not ``frequency``)"""


@click.command("driveline")
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--analysis", "what", type=click.Choice(KINDS), default="resonance",
              show_default=True,
              help="resonance: peak shaft torque, twist, fluctuation over --speed-range; "
                   "stability: the largest Floquet multiplier over them, unstable shaded; "
                   "map: over --speed-range × --map; steady: shaft torque over the cycle "
                   "against the rigid drive's; run-up: from rest.")
@driveline_options
@output_options()
def driveline_figure(mechanism_file, what, output, fmt, show, dpi, **params) -> None:
    """Figures of the elastic drive line of MECHANISM_FILE (see `dyade driveline`):

        dyade plot driveline mech.toml --speed-range 300:6000:25 -o resonance.png
    """
    name = f"{os.path.splitext(os.path.basename(mechanism_file))[0]}-driveline-{what}"
    target, announce = single_target(output, fmt, show, dpi, name)
    found = solve(what, mechanism_file, params).result
    from dyade.plot import drive_line as figures

    draw = {"resonance": figures.resonance, "stability": figures.stability,
            "map": figures.stability_map, "steady": figures.steady,
            "run-up": figures.run_up}[what]
    finish(draw(found, fig=figure_for(target)), target, announce)
