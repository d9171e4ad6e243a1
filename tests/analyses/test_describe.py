"""The ``describe`` entry (``dyade describe``): the plan and the mechanism's figures in
its Outcome, one contract with the API, the tree unchanged in content."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

import dyade
from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.cli import main
from tests.analyses.test_registry import REPR, check_document
from tests.helpers import shipped, with_frame_points


def run(*args):
    return CliRunner().invoke(main, ["describe", *map(str, args)], catch_exceptions=False)


@pytest.mark.parametrize("name, options, flags", [
    ("fourbar.toml", {}, []),
    ("dyade-16.toml", {"set": ("friction.coefficient=0.1", "friction.pin_radius=5",
                               "friction.slider_length=40", "friction.slider_height=20")},
     ["--set", "friction.coefficient=0.1", "--set", "friction.pin_radius=5",
      "--set", "friction.slider_length=40", "--set", "friction.slider_height=20"]),
])
def test_the_commands_json_is_the_apis_document(name, options, flags):
    api = json.loads(json.dumps(jsonable(REGISTRY["describe"](str(shipped(name)),
                                                              **options).to_document())))
    out = run(shipped(name), *flags, "--format", "json")
    assert out.exit_code == 0, out.output
    cli = json.loads(out.stdout)
    check_document(cli)
    assert cli == api and cli["columns"] == {}


@pytest.mark.parametrize("name, stages", [
    ("fourbar.toml", ["kinematics", "kinetostatics"]),
    ("self-locking.toml", ["kinematics", "kinetostatics", "friction", "self_locking"]),
    ("dyade-16.toml", ["kinematics", "kinetostatics", "clearance"]),
])
def test_the_summary_holds_the_plan(name, stages):
    outcome = dyade.run("describe", str(shipped(name)))
    plan = dyade.plan(dyade.read_mechanism(shipped(name)))
    for stage in ("kinematics", "kinetostatics", "friction", "self_locking", "clearance",
                  "equation_of_motion", "drive_line"):
        figure = outcome.summary[stage]
        assert figure.value is (stage in stages) and figure.unit == "-"
        assert figure.value is bool(getattr(plan, stage))
    assert outcome.meta["stages"] == stages
    for name_, figure in outcome.summary.items():
        assert figure.unit and figure.description, name_


def test_the_mechanisms_figures():
    summary = {name: figure.value
               for name, figure in dyade.run("describe", str(shipped("fourbar.toml"))).summary.items()}
    # four links, four revolute joints: F = 3·(4 − 1) − 2·4 = 1
    assert (summary["links"], summary["revolute_joints"], summary["prismatic_joints"]) == (4, 4, 0)
    assert summary["mobility"] == 1 and summary["dyads"] == 2
    assert summary["loop"] == "four-bar" and summary["loop_grashof"] == "crank-rocker"
    assert (summary["loop_crank"], summary["loop_coupler"], summary["loop_rocker"],
            summary["loop_ground"]) == pytest.approx((0.05, 0.2, 0.15, 0.25))
    assert summary["speed_rpm"] == pytest.approx(300.0) and summary["positions"] == 361


def test_the_slider_cranks_stroke_is_the_closed_form():
    # offset slider-crank r 40, l 160, e 10 mm: the slider's extreme positions are those
    # with crank and rod in line, sqrt((l + r)² − e²) − sqrt((l − r)² − e²) apart
    outcome = dyade.run("describe", str(shipped("slider-crank.toml")))
    stroke = math.sqrt(200 ** 2 - 10 ** 2) - math.sqrt(120 ** 2 - 10 ** 2)
    assert outcome.summary["loop_stroke"].value == pytest.approx(stroke * 1e-3, rel=1e-4)
    assert outcome.summary["loop_stroke"].unit == "m"
    alpha = math.degrees(math.asin(10 / 120) - math.asin(10 / 200))
    assert outcome.summary["loop_time_ratio"].value == pytest.approx(
        (180 + alpha) / (180 - alpha), rel=1e-5)


def test_a_loop_that_does_not_close_says_so():
    outcome = dyade.run("describe", str(shipped("fourbar.toml")), set=("dyad.2.lengths=[200,60]",))
    assert outcome.summary["loop_closes"].value is False
    assert "loop_swing_deg" not in outcome.summary
    text = " ".join(run(shipped("fourbar.toml"), "--set", "dyad.2.lengths=[200,60]").stdout.split())
    assert "it does not close over the whole revolution" in text


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml", "slider-crank.toml",
                                  "self-locking.toml", "slotted-lever.toml"])
def test_the_tree_shows_no_python_repr(name):
    out = run(shipped(name))
    assert out.exit_code == 0 and out.stdout
    assert not REPR.findall(out.stdout)


def test_the_tree_is_the_one_it_was():
    text = " ".join(run(shipped("fourbar.toml")).stdout.split())
    assert ("four-bar (Grashof crank-rocker: s + l < p + q, the crank is the shortest link): "
            "crank 50 mm, coupler 200 mm, rocker 150 mm, ground 250 mm") in text
    assert "rocker swing 38.99°, time ratio 1.015" in text
    assert "mobility (Grübler) F = 3·(4−1) − 2·4 = 1" in text


def test_the_frame_shows_at_most_50_points_like_a_link(tmp_path):
    """Issue 42: 200 000 frame points took 130 s, each printed (rich's tree grows
    quadratically); now 50 and how many more, as a link's."""
    result = run(with_frame_points(tmp_path, 2000))
    assert result.exit_code == 0, result.output
    assert "point P47 =" in result.output and "point P48 =" not in result.output
    assert "link 1: 1,952 more named points (P48 … P1999)" in result.output
    assert len(result.output.splitlines()) < 80
