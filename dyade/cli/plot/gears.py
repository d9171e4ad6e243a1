"""Figures of a gear drive: ``dyade plot campbell`` and ``dyade plot modes``."""

from __future__ import annotations

import os

import click

from dyade.cli.options import max_memory_option
from dyade.cli.output import flags
from dyade.cli.plot.output import figure_for, finish, output_options, single_target


GEAR_FILE = click.Path(exists=True, dir_okay=False, allow_dash=True)
GEAR_FLAGS = {"speeds_rpm": "--speed-range", "harmonics": "--harmonics", "count": "--modes",
              "max_memory": "--max-memory"}
MOST_MODES = 24  # rows of panels a figure of mode shapes holds
"""API parameter -> the flag of `dyade plot campbell`/`modes` it comes from"""


def _gear_drive(gear_file: str, assignments: tuple[str, ...]):
    """The drive of GEAR_FILE with the --set overrides, and the flag names for errors."""
    from dyade.cli.common import read_gear_file

    drive, label = read_gear_file(gear_file, assignments)
    return drive, GEAR_FLAGS | {"speed": f"{label}: `[speed]`"}


def _stem(path: str) -> str:
    from dyade.cli.plot.output import stem

    return stem(path)


gear_set_option = click.option(
    "--set", "assignments", multiple=True, metavar="KEY=VALUE",
    help="Override a key of the gear file by its dotted path (repeatable), as in `dyade gears`.")


@click.command("campbell")
@click.argument("gear_file", type=GEAR_FILE)
@click.option("--speed-range", "speed_range", metavar="START:STOP:STEP",
              help="Input speeds [rpm], as `dyade gears --speed-range`  [default: 0 to 1.5 × the "
                   "file's [speed] rpm, in 200 steps].")
@click.option("--harmonics", type=click.IntRange(min=0), default=3, show_default=True,
              metavar="N", help="Tooth-mesh harmonics drawn.")
@gear_set_option
@output_options()
@max_memory_option
def campbell_figure(gear_file, speed_range, harmonics, assignments, output, fmt, show,
                    dpi, max_memory) -> None:
    """Campbell diagram of the gear drive in GEAR_FILE: the natural frequencies against the
    input speed (horizontal: no gyroscopic terms in this model), the excitation lines (shaft
    speeds, tooth-mesh frequency z·n/60 and its harmonics, the file's excitation orders) and
    the resonance crossings of `dyade gears --speed-range`, each sized by the modal mesh
    stiffness of the exciting mesh.

        dyade plot campbell mechanisms/gears/two-stage.toml -o campbell.png
    """
    from dyade.cli.options import value_range_checked

    target, announce = single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-campbell")
    drive, names = _gear_drive(gear_file, assignments)
    from dyade.plot import campbell as figure
    from dyade.vibration.gears.campbell import campbell, orders

    with flags(names):
        orders(drive, harmonics)  # a [speed] body and harmonics ≥ 0, before the speeds
        if speed_range:
            speeds = value_range_checked(speed_range, "--speed-range", " [rpm]", "speed_rpm")
        elif drive.speed.rpm:
            speeds = figure.default_speeds(drive.speed.rpm)
        else:
            raise click.UsageError(f"{os.path.basename(gear_file)} gives no operating speed "
                                   f"([speed] rpm): give the speeds with --speed-range "
                                   f"START:STOP:STEP.")
        diagram = campbell(drive, speeds, harmonics=harmonics, max_memory=max_memory * 2 ** 20)
    finish(figure.figure(diagram, fig=figure_for(target, (8.5, 7.0))), target, announce)


@click.command("modes")
@click.argument("gear_file", type=GEAR_FILE)
@click.option("--modes", "count", type=click.IntRange(min=1), default=4, metavar="N",
              show_default=True, help="The first N elastic modes, one row of panels each "
                                      "(at most 24).")
@gear_set_option
@output_options()
@max_memory_option
def modes_figure(gear_file, count, assignments, output, fmt, show, dpi, max_memory) -> None:
    """Mode shapes of the gear drive in GEAR_FILE per shaft line: for each of the first N
    elastic modes (rigid-body modes left out), the bodies along each shaft against their
    modal displacements — torsion ρ·rx, lateral uy and uz, axial ux — each mode divided by
    its largest entry, with its frequency and dominant part.

        dyade plot modes mechanisms/gears/two-stage.toml --modes 6 -o modes.svg
    """
    target, announce = single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-modes")
    drive, names = _gear_drive(gear_file, assignments)
    from dyade.plot import modes as figure
    from dyade.vibration.gears.modes import gear_modes

    from dyade.cli.options import modes_asked

    with flags(names):
        modes = gear_modes(drive, max_memory=max_memory * 2 ** 20)
        if not modes.frequencies.size:
            raise click.UsageError(f"{os.path.basename(gear_file)}: nothing to vibrate: every "
                                   f"motion of the drive is a rigid-body mode.")
        count, note = modes_asked(count, modes.frequencies.size, MOST_MODES)
        if note:
            click.echo(f"note: {note}", err=True)
        finish(figure.figure(modes, count, fig=figure_for(target)), target, announce)
