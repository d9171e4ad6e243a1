"""``dyade plot``: figures of the analyses (the optional extra ``dyade[plot]``).

Each subcommand parses its options, calls the API and hands the result to its module of
``dyade.plot``; matplotlib is imported only there, when a figure is made. The output
format comes from the suffix of -o; without -o (and without --show) the figure is
written to NAME-KIND.png in the current directory. One module per analysis: ``linkage``
(polar, curves, mechanism, animate), ``coupling``, ``clearance`` and ``gears``
(campbell, modes); ``output`` holds what they share.
"""

from __future__ import annotations

from dyade.cli import main
from dyade.cli.plot import (cam, clearance, coupling, driveline, gears, linkage, profile,
                             servo, study, synthesis)


@main.group()
def plot() -> None:
    """Figures: polar diagrams, curves, the mechanism still and in motion, the coupling's
    resonance, the clearance peak force, and a gear drive's Campbell diagram and mode
    shapes.

    Needs the plot extra: pip install "dyade[plot]" (matplotlib). The format follows the
    suffix of -o (.png, .svg, .pdf; .gif for `plot animate`); without -o the figure is
    written to NAME-KIND.png here. --show opens a window instead, where a display exists.

        dyade plot polar mechanisms/fourbar.toml -o fourbar-polar.svg

        dyade plot animate mechanisms/slotted-lever.toml --step 5 -o motion.gif
    """


for command in (linkage.polar, linkage.curves, linkage.mechanism, linkage.animate,
                coupling.coupling_figure, clearance.clearance_figure, gears.campbell_figure,
                gears.modes_figure, driveline.driveline_figure, study.study_figure,
                profile.profile_figure, servo.servo_figure, cam.cam_figure,
                synthesis.synthesis_figure):
    plot.add_command(command)
