"""The ``sweep`` entry (``dyade analyse``): one contract with the API, the summary's
figures with their units, the tables without a Python repr, the withheld rule, single
positions (``--at``) and the one-position rule, the shaking force's figures."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.cli import main
from tests.analyses.test_registry import REPR, check_document
from tests.helpers import shipped

FRICTION = ["--set", "friction.coefficient=0.1", "--set", "friction.pin_radius=5",
            "--set", "friction.slider_length=40", "--set", "friction.slider_height=20"]


def run(*args):
    return CliRunner().invoke(main, ["analyse", *map(str, args)], catch_exceptions=False)


def document(outcome) -> dict:
    return json.loads(json.dumps(jsonable(outcome.to_document())))


@pytest.mark.parametrize("name, options, flags", [
    ("fourbar.toml", {}, []),
    ("self-locking.toml", {"start_deg": 10.0, "stop_deg": 200.0, "step_deg": 2.0,
                           "block_size": 7}, ["--start", "10", "--stop", "200", "--step", "2",
                                              "--block-size", "7"]),
    ("dyade-16.toml", {"set": ("crank.speed_rpm=200",), "dead_centre_deg": 5.0},
     ["--set", "crank.speed_rpm=200", "--dead-centre", "5"]),
    ("slider-crank.toml", {"at_deg": (30.0, 95.5)}, ["--at", "30,95.5"]),
])
def test_the_commands_json_is_the_apis_document(name, options, flags):
    api = document(REGISTRY["sweep"](str(shipped(name)), **options))
    out = run(shipped(name), *flags, "--format", "json")
    assert out.exit_code == 0, out.output
    cli = json.loads(out.stdout)
    check_document(cli)
    assert cli == api
    assert cli["analysis"] == "sweep" and cli["meta"]["name"]
    assert set(cli["options"]) >= set(options)


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml", "self-locking.toml",
                                  "slider-crank.toml", "scotch-yoke.toml"])
def test_every_figure_has_a_unit_and_the_summary_is_the_apis(name):
    outcome = dyade.run("sweep", str(shipped(name)))
    assert outcome.summary and outcome.notes is not None
    for figure_name, figure in outcome.summary.items():
        assert figure.unit, figure_name
        assert figure.description, figure_name
        assert figure.value is None or type(figure.value) in (int, float, bool, str)
    result = dyade.analyse(dyade.read_mechanism(shipped(name)))
    # one function gives both: the Outcome's figures (from its columns on disk) are the
    # Result's summary (its columns in memory), name by name and value by value
    assert {n: f.value for n, f in outcome.summary.items()} == result.summary()


@pytest.mark.parametrize("args", [[], ["--all"], ["--columns", "mu_*,F_*"], ["--at", "0,45"],
                                  ["--units", "si"], FRICTION, ["--all", *FRICTION]])
@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml", "self-locking.toml",
                                  "slider-crank.toml"])
def test_the_tables_show_no_python_repr(name, args):
    out = run(shipped(name), *args)
    assert out.exit_code == 0, out.output
    found = REPR.findall(out.stdout)
    assert not found, f"{name} {' '.join(args)} shows {found[:5]}"


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_a_sweep_whose_every_position_is_withheld_exits_1_saying_so(fmt, tmp_path):
    # at 1e9 rpm every acceleration is beyond the plausibility bound: no row is given
    out = run(shipped("fourbar.toml"), "--set", "crank.speed_rpm=1e9", "--format", fmt)
    assert out.exit_code == 1
    assert out.stdout == ""  # never a table of blanks
    assert "no position of the sweep has its kinematics given" in out.stderr
    assert "beyond 1e+12" in out.stderr  # and why
    target = tmp_path / f"out.{fmt}"
    assert run(shipped("fourbar.toml"), "--set", "crank.speed_rpm=1e9", "--format", fmt,
               "-o", target).exit_code == 1
    assert not target.exists()
    with pytest.raises(dyade.DyadeError, match="no position of the sweep"):
        dyade.run("sweep", str(shipped("fourbar.toml")), set=("crank.speed_rpm=1e9",))


def test_single_positions_are_those_of_the_sweep():
    out = run(shipped("fourbar.toml"), "--at", "37", "--at", "90,181", "--format", "csv")
    assert out.exit_code == 0, out.output
    lines = out.stdout.splitlines()
    sweep = run(shipped("fourbar.toml"), "--format", "csv").stdout.splitlines()
    assert lines[0] == sweep[0]
    assert lines[1:] == [sweep[1 + 37], sweep[1 + 90], sweep[1 + 181]]
    outcome = dyade.run("sweep", str(shipped("fourbar.toml")), at_deg=[37.0, 90.0, 181.0])
    api = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")),
                        crank_angle_deg=[37.0, 90.0, 181.0]).columns()
    for name, values in api.items():
        assert np.array_equal(outcome.columns[name], values, equal_nan=True), name
    # single positions have no cycle: no mean, RMS or time ratio
    assert "M_drive_rms" not in outcome.summary and "P_drive_mean" not in outcome.summary
    assert not any(name.startswith("time_ratio_") for name in outcome.summary)
    assert outcome.summary["positions"].value == 3


def test_a_sweep_of_one_position_is_refused_naming_at():
    out = run(shipped("fourbar.toml"), "--start", "37", "--stop", "37")
    assert out.exit_code == 2
    assert "--start and --stop: the sweep from 37° to 37°" in out.stderr
    assert "--at DEG for single positions" in out.stderr and "_deg" not in out.stderr
    with pytest.raises(dyade.InputError, match=r"at_deg=\[\.\.\.\] for single positions"):
        dyade.run("sweep", str(shipped("fourbar.toml")), start_deg=37, stop_deg=37)
    both = run(shipped("fourbar.toml"), "--at", "30", "--step", "2")
    assert both.exit_code == 2 and "--at and --step exclude each other" in both.stderr
    bad = run(shipped("fourbar.toml"), "--at", "30,x")
    assert bad.exit_code == 2 and "--at" in bad.stderr


def test_the_shaking_force_is_the_resultant_of_the_frame_bearings():
    # the four-bar's frame holds the crank (1,2) and the rocker (1,4): the shaking force
    # is the resultant of the two bearing forces (d'Alembert: −Σ m·a_S), and its peak
    # and RMS over the cycle are the summary's F_shake_max and F_shake_rms
    outcome = dyade.run("sweep", str(shipped("fourbar.toml")), step_deg=0.5)
    cols = outcome.columns
    bearing = np.hypot(cols["Fx_1_2"] + cols["Fx_1_4"], cols["Fy_1_2"] + cols["Fy_1_4"])
    k = int(np.argmax(bearing))
    figure = outcome.summary["F_shake_max"]
    assert figure.value == pytest.approx(bearing[k], rel=1e-12) and figure.unit == "N"
    assert figure.where == {"angle_deg": float(cols["angle_deg"][k])}
    # RMS over one revolution, each position once (0° and 360° are one)
    rms = math.sqrt(np.mean(bearing[:-1] ** 2))
    assert outcome.summary["F_shake_rms"].value == pytest.approx(rms, rel=1e-9)
    moment = np.abs(cols["M_shake"])
    assert outcome.summary["M_shake_abs_max"].value == pytest.approx(moment.max(), rel=1e-15)
    # the shaking moment's largest magnitude, of either sign: dyade-16's is its trough
    sixteen = dyade.run("sweep", str(shipped("dyade-16.toml"))).summary
    assert sixteen["M_shake_abs_max"].value == -sixteen["M_shake_min"].value
    assert sixteen["M_shake_abs_max"].where == sixteen["M_shake_min"].where
    assert sixteen["M_shake_max"].value < sixteen["M_shake_abs_max"].value
    # a machine without losses, loads or gravity at constant speed: its kinetic energy
    # is periodic, so the drive's mean power over a revolution is zero
    assert outcome.summary["P_drive_mean"].value == 0.0


def test_fail_on_lock_writes_the_output_then_fails():
    out = run(shipped("self-locking.toml"), "--fail-on-lock", "--format", "csv")
    assert out.exit_code == 1 and out.stdout.startswith("angle_deg,")
    assert "--fail-on-lock was given" in out.stderr
    with pytest.raises(dyade.DyadeError, match="self-locks"):
        dyade.run("sweep", str(shipped("self-locking.toml")), fail_on_lock=True)
    assert dyade.run("sweep", str(shipped("fourbar.toml")), fail_on_lock=True).summary


def test_tables_show_lengths_in_the_files_unit_unless_si_is_asked_for():
    mm = run(shipped("slider-crank.toml")).stdout
    si = run(shipped("slider-crank.toml"), "--units", "si").stdout
    assert "lengths in mm" in " ".join(mm.split()) and "lengths in" not in si

    def stroke(text):
        row = next(line for line in text.splitlines() if line.startswith("stroke of slider"))
        return row.split()[-2:]

    value = dyade.run("sweep", str(shipped("slider-crank.toml"))).summary["stroke_1_4"].value
    assert stroke(mm) == [f"{value * 1e3:.6g}", "mm"] and stroke(si) == [f"{value:.6g}", "m"]
    # CSV and JSON stay SI
    csv = run(shipped("slider-crank.toml"), "--format", "json").stdout
    assert json.loads(csv)["summary"]["stroke_1_4"] == {"value": float(f"{value:.15g}"),
                                                       "unit": "m"}


def test_the_summary_of_chosen_columns_keeps_the_key_figures():
    out = run(shipped("fourbar.toml"), "--columns", "F_1_2", "--format", "json")
    summary = json.loads(out.stdout)["summary"]
    assert "F_1_2_max" in summary and "F_2_3_max" not in summary  # extremes: chosen ones
    assert "M_drive_rms" in summary and "mu_2_min_deg" in summary  # key figures: all


def test_a_long_sweep_is_announced_and_bounded_by_max_time():
    with pytest.raises(dyade.InputError, match="max_time_s is 0.001 s, and the sweep of "
                                               "3,600,001 positions would take about"):
        dyade.run("sweep", str(shipped("dyade-16.toml")), step_deg=1e-4, max_time_s=1e-3)
    told = []
    dyade.run("sweep", str(shipped("fourbar.toml")), step_deg=0.01, told=told.append)
    assert told == []  # a run of a second or so is not announced
