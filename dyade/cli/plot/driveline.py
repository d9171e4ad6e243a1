"""``dyade plot driveline``: the elastic drive line's figures."""

from __future__ import annotations

import os

import click

from dyade.cli.options import MECHANISM_FILE, Renamed, set_option
from dyade.cli.plot.output import figure_for, finish, output_options, single_target

KINDS = click.Choice(["resonance", "stability", "map", "steady", "run-up"])


@click.command("driveline")
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--analysis", "what", type=KINDS, default="resonance", show_default=True,
              help="resonance: peak shaft torque, twist, fluctuation over --speed-range; "
                   "stability: the largest Floquet multiplier over them, unstable shaded; "
                   "map: over --speed-range × --map; steady: shaft torque over the cycle "
                   "against the rigid drive's; run-up: from rest.")
@click.option("--speed-range", "speeds_rpm", cls=Renamed, old=("--speeds-rpm",),
              metavar="START:STOP:STEP",
              help="Crank speeds of an ideal motor [rpm] (resonance, stability, map).")
@click.option("--map", "map_range", metavar="stiffness|damping=START:STOP:STEP",
              help="The parameter mapped against speed (map).")
@set_option
@output_options()
def driveline_figure(mechanism_file, what, speeds_rpm, map_range, assignments, output, fmt,
                     show, dpi) -> None:
    """Figures of the elastic drive line of MECHANISM_FILE (see `dyade driveline`):

        dyade plot driveline mech.toml --speed-range 300:6000:25 -o resonance.png
    """
    from dyade.cli.common import load
    from dyade.cli.driveline import FLAGS, speed_range
    from dyade.cli.output import flags
    from dyade.linkage import drive_line as api

    name = f"{os.path.splitext(os.path.basename(mechanism_file))[0]}-driveline-{what}"
    target, announce = single_target(output, fmt, show, dpi, name)
    mechanism = load(mechanism_file, assignments).mechanism
    if what in ("resonance", "stability", "map") and not speeds_rpm:
        raise click.UsageError(f"--analysis {what} needs --speed-range START:STOP:STEP.")
    from dyade.plot import drive_line as figures

    fig = figure_for(target)
    with flags(FLAGS):
        if what in ("resonance", "stability"):
            curve = api.resonance_curve(mechanism, speed_range(speeds_rpm, "--speed-range"))
            made = (figures.resonance if what == "resonance" else figures.stability)(curve,
                                                                                     fig=fig)
        elif what == "map":
            if not map_range or "=" not in map_range or map_range.split("=")[0] not in (
                    "stiffness", "damping"):
                raise click.UsageError("--analysis map needs --map stiffness=START:STOP:STEP "
                                       "or damping=START:STOP:STEP.")
            key, text = map_range.split("=", 1)
            result = api.stability_map(mechanism, speed_range(speeds_rpm, "--speed-range"),
                                       **{key: speed_range(text, "--map", key)})
            made = figures.stability_map(result, fig=fig)
        elif what == "steady":
            made = figures.steady(api.steady_state(mechanism, accuracy=False), fig=fig)
        else:
            made = figures.run_up(api.run_up(mechanism), fig=fig)
    finish(made, target, announce)
