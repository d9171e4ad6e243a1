"""Figures of a gear drive: ``dyade plot campbell`` and ``dyade plot modes``, from the
Outcomes of the ``gear-campbell`` and ``gear-modes`` entries."""

from __future__ import annotations

import click

from dyade.cli import contract
from dyade.cli.gears import CAMPBELL, MODES, gear_options, read_source
from dyade.cli.plot.output import figure_for, finish, output_options, single_target

GEAR_FILE = click.Path(exists=True, dir_okay=False, allow_dash=True)
MOST_MODES = 24  # rows of panels a figure of mode shapes holds


def _stem(path: str) -> str:
    from dyade.cli.plot.output import stem

    return stem(path)


@click.command("campbell")
@click.argument("gear_file", type=GEAR_FILE)
@gear_options((CAMPBELL,))
@output_options()
def campbell_figure(gear_file, output, fmt, show, dpi, **options) -> None:
    """Campbell diagram of the gear drive in GEAR_FILE: the natural frequencies against the
    input speed (horizontal: no gyroscopic terms in this model), the excitation lines (shaft
    speeds, tooth-mesh frequency z·n/60 and its harmonics, the file's excitation orders) and
    the resonance crossings of `dyade gears --speed-range`, each sized by the modal mesh
    stiffness of the exciting mesh.

        dyade plot campbell mechanisms/gears/two-stage.toml -o campbell.png
    """
    target, announce = single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-campbell")
    diagram = contract.run(CAMPBELL, read_source(gear_file), options).result
    from dyade.plot import campbell as figure

    finish(figure.figure(diagram, fig=figure_for(target, (8.5, 7.0))), target, announce)


@click.command("modes")
@click.argument("gear_file", type=GEAR_FILE)
@click.option("--modes", "count", type=click.IntRange(min=1), default=4, metavar="N",
              show_default=True, help="The first N elastic modes, one row of panels each "
                                      "(at most 24).")
@gear_options((MODES,), skip=("modes", "check"))
@output_options()
def modes_figure(gear_file, count, output, fmt, show, dpi, **options) -> None:
    """Mode shapes of the gear drive in GEAR_FILE per shaft line: for each of the first N
    elastic modes (rigid-body modes left out), the bodies along each shaft against their
    modal displacements — torsion ρ·rx, lateral uy and uz, axial ux — each mode divided by
    its largest entry, with its frequency and dominant part.

        dyade plot modes mechanisms/gears/two-stage.toml --modes 6 -o modes.svg
    """
    from dyade.analyses.gears import modes_asked

    target, announce = single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-modes")
    modes = contract.run(MODES, read_source(gear_file), options).result.modes
    from dyade.plot import modes as figure

    count, note = modes_asked(count, modes.frequencies.size, MOST_MODES)
    if note:
        click.echo(f"note: {note}", err=True)
    finish(figure.figure(modes, count, fig=figure_for(target)), target, announce)
