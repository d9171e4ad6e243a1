"""``dyade plot clearance``: the clearance peak force (Dresig & Thümmel)."""

from __future__ import annotations

import os

import click

from dyade.cli.clearance import FLAGS as CLEARANCE_FLAGS
from dyade.cli.clearance import (clearance_options, inputs, mechanism_check, mechanism_options,
                                 standalone_check)
from dyade.cli.options import MECHANISM_FILE
from dyade.cli.output import console, flags
from dyade.cli.plot.output import figure_for, finish, output_options, single_target


@click.command("clearance")
@click.argument("mechanism_file", type=MECHANISM_FILE, required=False)
@clearance_options
@output_options()
def clearance_figure(mechanism_file, joints, masses, stiffness, gap, slope, speed_rpm,
                     speed_range, simulate, sim_steps, max_wander, output, fmt, show,
                     dpi) -> None:
    """The clearance peak force (Dresig & Thümmel): f(τ) of eq. (36) with the operating
    points; with --speed-range the peak force against crank speed; with --simulate the
    simulated force history next to the closed form, eq. (26) (over a mechanism: of its
    largest peak). The options and file of `dyade clearance`:

        dyade plot clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000 \\
            --speed-rpm 300 --speed-range 100:600:50 --simulate
    """
    import dyade
    from dyade import clearance as engine
    from dyade.plot import clearance as figure
    from dyade.report import clearance as clearance_report
    from dyade.units import RPM

    given = inputs(joints, masses, stiffness, gap, slope, speed_rpm, speed_range, simulate,
                   sim_steps, max_wander)
    name = (f"{os.path.splitext(os.path.basename(mechanism_file))[0]}-clearance"
            if mechanism_file else "clearance")
    if mechanism_file:
        mechanism_check(given)
    else:
        standalone_check(given)
    target, announce = single_target(output, fmt, show, dpi, name)
    speeds = None
    with flags(CLEARANCE_FLAGS):
        if mechanism_file:
            mechanism = dyade.read_mechanism(mechanism_file)
            checks = dyade.check_clearance(mechanism, **mechanism_options(given))
            _, skipped = clearance_report.mechanism_rows([(None, checks)], False, 0)
            for line in clearance_report.mechanism_warnings(skipped, []):
                console(stderr=True).print(line)
            cases, title = figure.cases(checks), mechanism.name
            speed_rpm = mechanism.crank.speed / RPM
            if given.speeds:
                speeds = figure.speed_lines(dyade.clearance_speed_study(
                    mechanism, given.speeds, **mechanism_options(given)))
        else:
            peak = engine.peak_force(given.mass, given.stiffness, clearance=given.gap,
                                     slope=given.slope)
            cases, title = [figure.Case("standalone", peak)], "Clearance peak force"
            speed_rpm = given.speed_rpm
            if given.speeds:
                speeds = figure.standalone_speeds(engine.peaks_over_speed(
                    given.mass, given.stiffness, clearance=given.gap, slope=given.slope,
                    speed_rpm=given.speed_rpm, speeds_rpm=given.speeds))
        history = None
        if given.simulate and cases:
            worst = max(cases, key=lambda case: case.peak.force)
            p = worst.peak
            history = figure.History(worst, engine.simulate(
                p.mass, p.stiffness, clearance=p.clearance, slope=p.slope,
                steps_per_period=given.sim_steps, history=True))
    operating = figure.operating_points(cases, speed_rpm) if speed_rpm else None
    finish(figure.figure(cases, speeds=speeds, history=history, title=title,
                          operating=operating, fig=figure_for(target, (10.8, 3.7))),
           target, announce)
