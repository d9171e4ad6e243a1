"""``dyade plot clearance``: the clearance peak force (Dresig & Thümmel), from the
Outcomes of the ``clearance-peak``, ``clearance-check`` and ``clearance-speeds``
entries."""

from __future__ import annotations

import os

import click

from dyade.analyses.clearance import SPEED_RANGE
from dyade.cli import contract
from dyade.cli.clearance import CHECK, PEAK, SPEEDS, clearance_options, entry_for, source_of
from dyade.cli.options import MECHANISM_FILE
from dyade.cli.plot.output import figure_for, finish, output_options, single_target


@click.command("clearance")
@click.argument("mechanism_file", type=MECHANISM_FILE, required=False)
@clearance_options
@output_options()
def clearance_figure(mechanism_file, output, fmt, show, dpi, **options) -> None:
    """The clearance peak force (Dresig & Thümmel): f(τ) of eq. (36) with the operating
    points; with --speed-range the peak force against crank speed; with --simulate the
    simulated force history next to the closed form, eq. (26) (over a mechanism: of its
    largest peak). The options and file of `dyade clearance`:

        dyade plot clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000 \\
            --speed 300 --speed-range 100:600:50 --simulate
    """
    entry = entry_for(bool(mechanism_file), options)
    name = (f"{os.path.splitext(os.path.basename(mechanism_file))[0]}-clearance"
            if mechanism_file else "clearance")
    target, announce = single_target(output, fmt, show, dpi, name)
    from dyade.plot import clearance as figure

    speeds = history = None
    if entry is PEAK:
        peaks = contract.run(PEAK, None, options).result
        cases, title = [figure.Case("standalone", peaks.peak)], "Clearance peak force"
        speed_rpm = peaks.speed_rpm
        if peaks.over_speed is not None:
            speeds = figure.standalone_speeds(peaks.over_speed)
        worst = peaks.history
    else:
        source = source_of(mechanism_file)
        at_speed = {key: value for key, value in options.items() if key != SPEED_RANGE.api}
        check = contract.run(CHECK, source, at_speed)
        contract.notes(check)
        checked = check.result
        checks = checked.study[0][1]
        cases, title, speed_rpm = figure.cases(checks), checked.mechanism.name, checked.speed_rpm
        if entry is SPEEDS:
            quick = {key: value for key, value in options.items()  # the history: the check's
                     if key not in ("simulate", "sim_steps")}
            study = contract.run(SPEEDS, source, quick).result.study
            speeds = figure.speed_lines(study)
        worst = checked.history
    if worst is not None:
        history = figure.History(figure.Case(worst.label, worst.peak), worst.simulation)
    operating = figure.operating_points(cases, speed_rpm) if speed_rpm else None
    finish(figure.figure(cases, speeds=speeds, history=history, title=title,
                         operating=operating, fig=figure_for(target, (10.8, 3.7))),
           target, announce)
