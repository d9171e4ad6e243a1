"""Hostile input of the older commands (issue 31): analyse with a [drive], an all-empty
sweep, describe of a huge file, clearance with nothing to compute."""

from __future__ import annotations

import re

from tests.helpers import shipped
from tests.hostile_common import expect

FOURBAR = shipped("fourbar.toml")
DYADE16 = shipped("dyade-16.toml")
DRIVE = ["--set", "drive.motor=asynchronous", "--set", "drive.rated_torque=3.5",
         "--set", "drive.rated_speed_rpm=298", "--set", "drive.synchronous_speed_rpm=310",
         "--set", "drive.flywheel_inertia=0.44"]


def test_drive_sizes_are_estimated_first():
    expect(["analyse", DYADE16, *DRIVE, "--set", "drive.steps=100000000"], 2,
           "--max-memory", "100,000,000 steps per revolution", "drive.steps")
    expect(["analyse", DYADE16, *DRIVE, "--set", "drive.max_revolutions=1000000000",
            "--run-up"], 2, "--max-memory", "1,000,000,000 revolutions", "drive.max_revolutions")


def test_the_heading_gives_the_speed_of_the_equation_of_motion():
    """The asynchronous motor runs the press at its own mean speed, not the file's 300."""
    out = expect(["analyse", DYADE16, *DRIVE], 0).stdout
    heading = re.search(r"at a mean ([\d.]+) rpm \(equation of\s+motion\)", out)
    mean = re.search(r"mean speed 2π/T\s+rpm\s+([\d.]+)", out)
    assert heading and mean and abs(float(heading[1]) - float(mean[1])) < 0.05, out
    assert "at 300 rpm" not in out


def test_a_sweep_with_no_position_given_says_why_and_exits_1(tmp_path):
    text = FOURBAR.read_text()
    for old, new in (('length = "mm"', 'length = "m"'), ("\nlength = 50\n", "\nlength = 1000000\n"),
                     ("B0 = [250, 0]", "B0 = [5000000, 0]"),
                     ("lengths = [200, 150]", "lengths = [4000000, 3000000]"),
                     ("K = [100, 40]", "K = [1, 1]")):
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "huge.toml"
    path.write_text(text)  # lengths of 1000 km: refused where they are read (issue 42)
    expect(["analyse", path, "--format", "csv"], 2, "huge.toml", "`frame.points.B0`",
           "must lie in 1e-07…1000 m")
    expect(["analyse", FOURBAR, "--set", "crank.speed_rpm=1e9", "--format", "csv"], 1,
           "beyond 1e+12", "no position of the sweep has its kinematics given")


def test_describe_of_a_file_with_many_named_points(tmp_path):
    points = ", ".join(f"P{k} = [{k % 100}, {k % 37}]" for k in range(3000))
    text = FOURBAR.read_text().replace("points = { K = [100, 40] }",
                                       "points = { K = [100, 40], " + points + " }")
    path = tmp_path / "points.toml"
    path.write_text(text)
    out = expect(["describe", path], 0, "link 3: 2,951 more named points (P49 … P2999").stdout
    assert "P48 =" in out and "P49 =" not in out and "rocker swing 38.99°" in out


def test_clearance_with_nothing_to_compute():
    expect(["clearance", FOURBAR], 2, "fourbar.toml: nothing to compute",
           "--stiffness and --clearance")


def test_max_memory_reaches_the_equation_of_motion():
    """--max-memory bounds the [drive]'s grid too: a small bound refuses 100 000 steps,
    a large one lets through what the default (4 GiB) refuses."""
    expect(["analyse", DYADE16, *DRIVE, "--set", "drive.steps=100000", "--max-memory", "100"],
           2, "--max-memory", "100,000 steps per revolution")
    expect(["analyse", DYADE16, *DRIVE, "--set", "drive.max_revolutions=1000000000",
            "--run-up", "--max-memory", "1e12"], 0, "crank positions")  # it reaches speed first
