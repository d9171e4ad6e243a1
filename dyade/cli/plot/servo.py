"""``dyade plot servo``: the motor's torque–speed points over its envelope and the
profile's s, v, a, j."""

from __future__ import annotations

import click

from dyade.cli.plot.output import figure_for, finish, output_options, single_target, stem
from dyade.cli.servo import servo_options, solve


@click.command("servo")
@servo_options
@output_options()
def servo_figure(mechanism_file, output, fmt, show, dpi, **options) -> None:
    """The servo's cycle: the motor's torque–speed points over the chosen motor's
    envelope (peak torque up to its top speed, rated torque dashed; braking points
    marked), and the profile's s, v, a, j over the cycle time with the segments' ends
    dashed. The options and file of `dyade servo`:

        dyade plot servo mechanisms/servo/press.toml -o press-servo.png
    """
    target, announce = single_target(output, fmt, show, dpi, f"{stem(mechanism_file)}-servo")
    outcome = solve(mechanism_file, options)
    from dyade.plot import servo as figure

    finish(figure.figure(outcome, fig=figure_for(target, (11.0, 5.6))), target, announce)
