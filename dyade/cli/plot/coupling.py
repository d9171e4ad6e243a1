"""``dyade plot coupling``: the stiff coupling's transfer functions."""

from __future__ import annotations

import os

import click

from dyade.cli.coupling import coupling_options, solve
from dyade.cli.plot.output import figure_for, finish, output_options, single_target


@click.command("coupling")
@coupling_options
@click.option("--log", is_flag=True, help="A logarithmic axis for the transfer functions.")
@output_options()
def coupling_figure(coupling_file, log, output, fmt, show, dpi, **options) -> None:
    """The stiff coupling's transfer functions V_φ, V_ψ, V_q, V_r against η with their
    phases (Strümpfel), η0 and the operating points marked; an undamped resonance is a
    gap, never a spike. The options and file of `dyade coupling`:

        dyade plot coupling mechanisms/coupling/stiff-coupling.toml -o coupling.png
    """
    name = (f"{os.path.splitext(coupling_file.name)[0]}-coupling" if coupling_file
            else "coupling")
    target, announce = single_target(output, fmt, show, dpi, name)
    model, response, operating = solve(coupling_file, options).result
    from dyade.plot import coupling as figure

    finish(figure.figure(model, response, operating, log=log, fig=figure_for(target)),
           target, announce)
