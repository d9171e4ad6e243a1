"""The clearance entries (``clearance-peak``, ``clearance-check``, ``clearance-speeds``):
the command line writes the entries' Outcomes, the figures have units, the tables no
Python repr, a run whose every position is withheld is refused, and the paper's peak
force comes out of the entry."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.cli import main
from dyade.errors import DyadeError, InputError
from tests.helpers import shipped

DYADE_16 = str(shipped("dyade-16.toml"))
PAPER = {"mass": 3.6, "stiffness": 1e7, "clearance": 1e-4, "slope": 3.6e5}
PAPER_FLAGS = ["--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope", "360000"]
DATA = ["--stiffness", "1e8", "--clearance", "1e-4"]
RUNS = {  # id: (command line, entry, source, API options)
    "paper": (PAPER_FLAGS, "clearance-peak", None, PAPER),
    "paper over speed": (PAPER_FLAGS + ["--speed-rpm", "300", "--speed-range", "100:600:50"],
                         "clearance-peak", None,
                         {**PAPER, "speed_rpm": 300, "speed_range_rpm": "100:600:50"}),
    "two masses": (["--mass", "3.6", "--mass", "5", *PAPER_FLAGS[2:]], "clearance-peak", None,
                   {**PAPER, "mass": (3.6, 5.0)}),
    "dyade-16": ([DYADE_16, *DATA], "clearance-check", DYADE_16,
                 {"stiffness": 1e8, "clearance": 1e-4}),
    "dyade-16 joints": ([DYADE_16, *DATA, "--joint", "5,6", "--joint", "2,7", "--max-wander", "40",
                         "--mass", "0.5", "--step", "2"], "clearance-check", DYADE_16,
                        {"stiffness": 1e8, "clearance": 1e-4, "joint": ("5,6", "2,7"),
                         "max_wander_deg": 40, "mass": 0.5, "step_deg": 2}),
    "dyade-16 file data": ([DYADE_16, "--joint", "2,7"], "clearance-check", DYADE_16,
                           {"joint": [(2, 7)]}),
    "dyade-16 speeds": ([DYADE_16, *DATA, "--joint", "2,7", "--speed-range", "100:1000:100"],
                        "clearance-speeds", DYADE_16,
                        {"stiffness": 1e8, "clearance": 1e-4, "joint": ("2,7",),
                         "speed_range_rpm": "100:1000:100"}),
}
REPR = re.compile(r"np\.float64\(|\bnan\b|\bTrue\b|\bFalse\b|\bNone\b|\(np\.|array\(")


def run(*args, code: int = 0):
    result = CliRunner().invoke(main, ["clearance", *map(str, args)], catch_exceptions=False)
    assert result.exit_code == code, result.output
    return result


@pytest.mark.parametrize("case", RUNS)
def test_the_json_is_the_entrys_document(case):
    args, name, source, options = RUNS[case]
    written = json.loads(run(*args, "--format", "json").stdout)
    outcome = REGISTRY[name](source, **options)
    document = json.loads(json.dumps(jsonable(outcome.to_document())))
    if written["options"] != document["options"]:  # the same options, as each gave them
        assert {k: v for k, v in written["options"].items() if k != "joint"} == \
            {k: v for k, v in document["options"].items() if k != "joint"}
        written["options"] = document["options"]
    assert written == document
    assert written["analysis"] == name
    for figure in outcome.summary.values():  # every figure has its unit ("-": none)
        assert figure.unit, figure.name
        assert re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", figure.name), figure.name
    for column, unit in outcome.units.items():
        text = column in ("joint", "note")
        assert bool(unit) != text, column  # numbers (and flags) have a unit, text has none
    csv_head = run(*args, "--format", "csv").stdout.splitlines()[0]
    assert csv_head.split(",") == list(outcome.columns)


@pytest.mark.parametrize("case", RUNS)
def test_tables_show_no_python_repr(case):
    text = run(*RUNS[case][0]).stdout
    assert not REPR.search(text), REPR.search(text)


def test_the_papers_peak_force_through_the_entry():
    # Dresig & Thümmel, section 4 (needle drive, joint (5,6)): the paper prints 2182 N
    outcome = REGISTRY["clearance-peak"](**PAPER, simulate=True)
    assert outcome.value("F_max") == pytest.approx(2182, rel=5e-4)  # printed to 4 digits
    assert outcome.summary["F_max"].unit == "N"
    assert outcome.value("tau") == pytest.approx(3.0285, abs=5e-5)
    # the two-mass model integrated directly: the same peak (RK4 error, 400 steps a period)
    assert outcome.value("F_sim") == pytest.approx(outcome.value("F_max"), rel=1e-8)
    assert outcome.result.history.simulation.force == outcome.value("F_sim")
    text = run(*PAPER_FLAGS).stdout
    assert "peak force F12max = c·s·f(τ)      2181.9  N" in text


def test_the_check_and_the_speed_study_agree_at_the_files_speed():
    """The speed study at the file's crank speed is the check; the summary's largest
    peak and amplification are those of the rows (amplification = peak / rigid force)."""
    mechanism = dyade.read_mechanism(DYADE_16)
    rpm = abs(mechanism.crank.speed) * 30 / np.pi
    check = REGISTRY["clearance-check"](DYADE_16, stiffness=1e8, clearance=1e-4)
    speeds = REGISTRY["clearance-speeds"](DYADE_16, stiffness=1e8, clearance=1e-4,
                                          speed_range_rpm=f"{rpm:.12g}:{2 * rpm:.12g}:{rpm:.12g}")
    at = np.isclose(speeds.columns["speed_rpm"], rpm, rtol=1e-12)
    for name in ("angle_deg", "slope", "F_max", "F_rigid", "amplification"):
        values = speeds.columns[name][at]
        assert np.array_equal(values[np.isfinite(values)], check.columns[name]), name
    cols = check.columns
    assert np.allclose(cols["amplification"], cols["F_max"] / cols["F_rigid"], rtol=1e-14)
    k = int(np.argmax(cols["F_max"]))
    assert check.value("F_max") == cols["F_max"][k]
    assert check.summary["F_max"].where == {"joint": cols["joint"][k],
                                            "angle_deg": cols["angle_deg"][k]}
    assert check.value("amplification_max") == cols["amplification"].max()
    assert check.value("reversals") == len(cols["joint"])


def test_a_linkage_whose_every_position_is_withheld_exits_1():
    """At 1e9 rpm no position of the sweep is plausible: the check says so and exits 1,
    never a table of blanks; so does a speed study whose every speed is withheld."""
    fast = ["--set", "crank.speed_rpm=1e9"]
    for path in (DYADE_16, shipped("slider-crank.toml")):
        result = run(path, *DATA, *fast, code=1)
        assert "no crank position of the sweep has its joint forces given" in result.output
        assert "withheld" in result.output and result.stdout == ""
    result = run(DYADE_16, *DATA, "--speed-range", "5e8:1e9:5e8", code=1)
    assert "no crank speed of the study has its joint forces given" in result.output
    with pytest.raises(DyadeError, match="every position is withheld"):
        REGISTRY["clearance-check"](DYADE_16, stiffness=1e8, clearance=1e-4,
                                    set=("crank.speed_rpm=1e9",))
    # a study where some speeds are withheld gives the others, and says why at each
    mixed = REGISTRY["clearance-speeds"](DYADE_16, stiffness=1e8, clearance=1e-4,
                                         joint=("2,7",), speed_range_rpm="300:1e9:999999700")
    notes = [n for n, rpm in zip(mixed.columns["note"], mixed.columns["speed_rpm"]) if rpm > 1e6]
    assert notes and all("every position is withheld" in n for n in notes)
    assert np.all(np.isfinite(mixed.columns["F_max"][mixed.columns["speed_rpm"] == 300]))


def test_a_simulation_is_estimated_before_it_starts():
    with pytest.raises(InputError, match=r"max_time_s is 0.01 s, and the direct simulation "
                                         r"of 11 cases would take about"):
        REGISTRY["clearance-peak"](**PAPER, speed_rpm=300, speed_range_rpm="100:600:50",
                                   simulate=True, sim_steps=4000, max_time_s=0.01)
    result = run(*PAPER_FLAGS, "--simulate", "--sim-steps", "100000", "--max-time", "1", code=2)
    assert "--max-time is 1 s, and the direct simulation of 1 case" in result.output


def test_options_that_do_not_apply_are_refused():
    assert "--slope and --speed are for the standalone check" in run(
        DYADE_16, *DATA, "--slope", "1", code=2).output
    assert "--joint: for a check over a mechanism" in run(*PAPER_FLAGS, "--joint", "2,7",
                                                           code=2).output
    assert "--sim-steps must be at least 10" in run(*PAPER_FLAGS, "--sim-steps", "5",
                                                    code=2).output
    assert "--max-wander must lie in 0…90" in run(DYADE_16, *DATA, "--max-wander", "100",
                                                  code=2).output
