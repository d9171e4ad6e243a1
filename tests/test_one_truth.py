"""One period, one truth (issue 28): a statistic over a revolution counts the position at
0° and 360° once and is computed by one function (``dyade.cycle``), so every command
and figure prints the same figure."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade import cycle
from dyade.cli import main
from tests.helpers import shipped


def run_json(*args):
    out = CliRunner().invoke(main, [*args, "--format", "json"], catch_exceptions=False)
    assert out.exit_code == 0, out.output
    return json.loads(out.stdout)


def run_table(*args):
    out = CliRunner(env={"COLUMNS": "200"}).invoke(main, list(args), catch_exceptions=False)
    assert out.exit_code == 0, out.output
    return out.stdout


def test_a_revolution_counts_its_repeated_position_once():
    # 0°..360° holds 0° twice: the mean is the mean of the 360 distinct positions, the
    # same for the sweep without its repeated end, and the trapezoid rule over 0..360
    phi = np.deg2rad(np.arange(0.0, 361.0, 1.0))
    values = np.exp(np.sin(phi)) + 0.3 * np.cos(3 * phi)
    distinct = values[:-1].mean()
    assert cycle.mean(phi, values) == pytest.approx(distinct, rel=1e-14)
    assert cycle.mean(phi[:-1], values[:-1]) == pytest.approx(distinct, rel=1e-14)
    assert cycle.rms(phi, values) == pytest.approx(np.sqrt(np.mean(values[:-1] ** 2)), rel=1e-14)
    # counting 0° twice (np.mean over all 361) is a different, wrong figure
    assert abs(np.mean(values) - distinct) > 5e-5
    # part of a revolution: the trapezoid rule over the sweep's own span
    part = phi[:91]
    assert cycle.mean(part, np.sin(part)) == pytest.approx(2 / np.pi, rel=1e-4)


def test_fourbar_drive_torque_rms_is_the_same_in_analyse_and_balance():
    analysed = run_json("analyse", str(shipped("fourbar.toml")))["summary"]["M_drive_rms"]["value"]
    balanced = run_json("balance", str(shipped("fourbar.toml")))["summary"]
    api = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"))).summary()["M_drive_rms"]
    assert analysed == balanced["M_drive_rms_before"]["value"]
    assert api == pytest.approx(analysed, rel=1e-14)
    assert analysed == pytest.approx(1.02233, abs=5e-6)
    # the tables print it alike
    text = run_table("analyse", str(shipped("fourbar.toml")))
    assert f"{analysed:.6g}" in text
    assert f"{analysed:.6g}" in run_table("balance", str(shipped("fourbar.toml")))


def test_dyade16_energy_fluctuation_is_the_same_in_flywheel_and_the_curves_plot():
    pytest.importorskip("matplotlib")
    from dyade.plot import curves

    flywheel = run_json("flywheel", str(shipped("dyade-16.toml")), "--fluctuation", "0.02")
    delta = flywheel["columns"]["delta_E"][0]
    result = dyade.analyse(dyade.read_mechanism(shipped("dyade-16.toml")))
    figure = curves.figure(result)
    title = figure.axes[0].get_title()
    assert f"ΔE = {delta:.4g} J" in title
    # the mean line too is the flywheel's mean drive torque
    mean_line = next(line for line in figure.axes[0].get_lines() if line.get_gid() == "M_mean")
    assert mean_line.get_ydata()[0] == pytest.approx(flywheel["columns"]["M_mean"][0], rel=1e-12)
    # the 1° samples alone (a load table's kinks need the fine step) are 1.5e-4 off
    plotted = curves.energy_surplus(result.crank_angle, result.columns()["M_drive"])[1]
    assert plotted == pytest.approx(delta, rel=1e-3)
