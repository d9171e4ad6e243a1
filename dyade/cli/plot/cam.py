"""``dyade plot cam``: the cam with its follower, the pressure angle, the curvature, the
motion and the forces over the turn."""

from __future__ import annotations

import click

from dyade.cli.cam import cam_options, solve
from dyade.cli.plot.output import figure_for, finish, output_options, single_target


@click.command("cam")
@cam_options
@click.option("--at", "at_deg", type=float, multiple=True, metavar="DEG",
              help="Cam angle [°] to draw the cam and its follower at (repeatable; the "
                   "first solid)  [default: 0]")
@output_options()
def cam_figure(cam_file, at_deg, output, fmt, show, dpi, **options) -> None:
    """A disc cam and its follower: the cam turned to the angles of --at with its
    follower and the common normal, the pressure angle against its limit, the radii of
    curvature (undercut shaded), s, s′, s″, s‴ and the contact force and drive torque
    over the turn. The options and file of `dyade cam`:

    \b
        dyade plot cam mechanisms/cams/translating-roller.toml --at 0 --at 90 -o cam.png
    """
    name = f"{cam_file.stem}-cam"
    target, announce = single_target(output, fmt, show, dpi, name)
    outcome = solve(cam_file, options)
    from dyade.plot import cam as figure

    finish(figure.figure(outcome, at_deg or (0.0,), fig=figure_for(target, (11.0, 7.5))),
           target, announce)
