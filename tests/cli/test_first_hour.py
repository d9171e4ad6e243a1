"""A new user's first hour (issue 42): messages that name the file, the column and the
flag as typed, and ranges that say what is accepted."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.helpers import shipped
from tests.hostile_common import expect

TWO_STAGE = shipped("gears/two-stage.toml")
COUPLING = shipped("coupling/stiff-coupling.toml")


def _curve(path, angles, load=None):
    """A torque CSV: M_drive = 10 + sin φ at ``angles`` [as written], M_load if given."""
    lines = ["angle_deg,M_drive" + (",M_load" if load is not None else "")]
    for angle in angles:
        lines.append(f"{angle},{10 + math.sin(math.radians(angle))}"
                     + (f",{load}" if load is not None else ""))
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_torque_curve_short_of_a_revolution_names_the_file_and_the_column(tmp_path):
    csv = _curve(tmp_path / "short.csv", np.arange(0.0, 200.0, 1.0))
    expect(["flywheel", csv, "--speed", "300", "--fluctuation", "0.02"], 2,
           "short.csv: column angle_deg must cover one revolution")


def test_a_load_that_does_not_balance_names_the_file_and_the_column(tmp_path):
    csv = _curve(tmp_path / "unbalanced.csv", np.arange(0.0, 361.0, 1.0), load=5)
    expect(["flywheel", csv, "--speed", "300", "--fluctuation", "0.02"], 2,
           "unbalanced.csv: column M_load does not balance the drive torque")


def test_a_curve_in_radians_rounded_to_five_digits_is_recognised(tmp_path):
    csv = tmp_path / "radians.csv"
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    csv.write_text("angle_deg,M_drive\n" + "".join(f"{a:.5f},{10 + math.sin(a)}\n"
                                                   for a in angle))
    assert "6.28319" in csv.read_text()
    expect(["flywheel", csv, "--speed", "300", "--fluctuation", "0.02"], 2,
           "radians.csv", "look like radians")


def test_the_campbell_range_says_it_starts_at_rest():
    expect(["gears", TWO_STAGE, "--speed-range", "0:2e6:1e5"], 2, "0…1e+06 rpm")
    expect(["gears", TWO_STAGE, "--speed-range", "0:100:50", "--format", "json"], 0)


def test_a_flywheel_sweep_too_large_advises_what_the_command_has():
    result = expect(["flywheel", shipped("dyade-16.toml"), "--fluctuation", "0.02",
                     "--max-memory", "1"], 2, "--max-memory", "coarser step")
    assert "shorter range" not in result.output


@pytest.mark.parametrize("args, old, new", [
    (["gears", TWO_STAGE, "--campbell", "0:-5:1"], "--campbell", "--speed-range"),
    (["coupling", COUPLING, "--speed-rpm", "-5"], "--speed-rpm", "--speed"),
    (["flywheel", shipped("torque/engine.csv"), "--speed-rpm", "1e-300",
      "--fluctuation", "0.02"], "--speed-rpm", "--speed"),
])
def test_a_message_about_a_renamed_option_says_it_was_renamed(args, old, new):
    expect(args, 2, f"{new} (renamed from {old})")
    current = expect([new if a == old else a for a in args], 2, new)
    assert "renamed" not in current.output


def test_an_option_for_another_analysis_under_its_old_name_says_it_was_renamed():
    expect(["driveline", shipped("dyade-16.toml"), "--set", "drive_line.stiffness=1000",
            "--analysis", "steady", "--speeds-rpm", "100:200:100"], 2,
           "--speed-range (renamed from --speeds-rpm) is for --analysis")


def test_the_old_and_the_new_name_together_give_every_value():
    both = expect(["coupling", COUPLING, "--speed-rpm", "500", "--speed", "700", "--format",
                   "json"], 0)
    assert "500" in both.output and "700" in both.output


# -- no confident wrong number: every position withheld exits 1 --------------------------
FOURBAR = shipped("fourbar.toml")
RACING = ["--set", "crank.speed_rpm=1e9"]  # every row beyond what a machine has
HEAVY = ["--set", "crank.speed_rpm=1e6", "--set", "links.3.mass=1e7"]  # forces only


@pytest.mark.parametrize("command", [["accuracy"], ["clearance"], ["balance"],
                                     ["flywheel", "--fluctuation", "0.02"]])
def test_every_position_withheld_exits_1_saying_so(command):
    result = expect([command[0], FOURBAR, *command[1:], *RACING], 1, "nothing to report")
    assert "carr" not in result.output  # never "the joints carry no force"


def test_a_balance_whose_forces_are_all_withheld_exits_1():
    expect(["balance", FOURBAR, *HEAVY], 1, "no crank position of the sweep has its forces given")


@pytest.mark.parametrize("kind", ["polar", "curves", "mechanism"])
def test_a_figure_of_a_sweep_with_nothing_given_draws_nothing(kind, tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / f"{kind}.png"
    expect(["plot", kind, FOURBAR, *RACING, "-o", out], 1,
           "no position of the sweep has its kinematics given", "nothing to draw")
    assert not out.exists()


def test_a_polar_diagram_of_withheld_forces_draws_nothing(tmp_path):
    pytest.importorskip("matplotlib")
    expect(["plot", "polar", FOURBAR, *HEAVY, "-o", tmp_path / "p.png"], 1,
           "no position of the sweep has its joint forces given")
