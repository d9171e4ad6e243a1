"""Hostile input of `dyade driveline` (issue 31): each case with its exit code and the
key words of its message."""

from __future__ import annotations

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect

SLIDER = shipped("slider-crank.toml")
LINE = [SLIDER, "--set", "drive_line.stiffness=1000", "--set", "drive_line.damping=0.05",
        "--set", "links.2.inertia=0.01"]
KEYS = {"stiffness": "1e-06…1e+13 N·m/rad", "damping": "0…1e+10 N·m·s/rad",
        "ratio": "0.0001…10000", "rotor_inertia": "1e-12…1e+07 kg·m²"}
SETS = {f"drive_line.{k}={v}": (f"`drive_line.{k}`", words)
        for k in KEYS for v, words in (("1e300", KEYS[k]), ("nan", "finite"), ("'x'", "number"))}
SETS.update({
    "drive_line.stiffness=1e-300": ("`drive_line.stiffness`", KEYS["stiffness"]),
    "drive_line.stiffness=0": ("`drive_line.stiffness`", "positive"),
    "drive_line.stiffness=-5": ("`drive_line.stiffness`", "positive"),
    "drive_line.damping=-1": ("`drive_line.damping`", "negative"),
    "drive_line.ratio=1e-300": ("`drive_line.ratio`", KEYS["ratio"]),
    "drive_line.steps=100000000": ("`drive_line.steps`", "100,000"),
    "drive_line.steps=10": ("`drive_line.steps`", "36"),
    "drive_line.steps=1e300": ("`drive_line.steps`", "whole number"),
    "drive_line.stiffnes=1": ("Did you mean `stiffness`",),
})


@pytest.mark.parametrize("assignment", SETS)
def test_bad_drive_line_numbers_are_refused(assignment):
    expect(["driveline", *LINE, "--set", assignment], 2, *SETS[assignment])


RANGES = {"0:100:10": None, "-100:100:10": None, "100:50:1": "START <= STOP",
          "nan:1:1": "finite", "1:2": "START:STOP:STEP", "a:b:c": "START:STOP:STEP",
          "100:6000:1e-300": "speeds", "1:1e9:1e6": "1e+06 rpm",
          "1e-300:1e-299:1e-301": "0.01…"}


@pytest.mark.parametrize("text", RANGES)
def test_bad_speed_ranges_are_refused(text):
    words = [RANGES[text]] if RANGES[text] else []
    expect(["driveline", *LINE, "--analysis", "resonance", "--speed-range", text], 2,
           "--speed-range", *words)


@pytest.mark.parametrize("text", ["0", "-5", "nan", "1e300"])
def test_bad_steady_speeds_are_refused(text):
    expect(["driveline", *LINE, "--speed-rpm", text], 2, "--speed")


@pytest.mark.parametrize("name,words", [("gears/two-stage.toml", "a gear-drive file"),
                                        ("studies/press-slide-tolerance.toml", "a study file"),
                                        ("torque/engine.csv", "CSV")])
def test_a_file_of_another_kind(name, words):
    expect(["driveline", shipped(name)], 2, words)


@pytest.mark.slow  # computes the whole result twice (1.5-3.5 s)
def test_output_under_a_file_and_a_missing_folder(tmp_path):
    (tmp_path / "afile").write_text("x")
    expect(["driveline", *LINE, "-o", tmp_path / "afile" / "x.csv"], 2, "not a folder")
    expect(["driveline", *LINE, "-o", tmp_path / "new" / "x.csv"], 0)
    assert (tmp_path / "new" / "x.csv").read_text().strip()


MAPS = {"stiffness=0:1000:100": "1e-06…", "stiffness=1:1e300:1e299": "1e+13",
        "damping=1e300:1e301:1e300": "1e+10", "foo=1:2:1": "stiffness or damping",
        "stiffness=1:2": "START:STOP:STEP", "stiffness=-1:10:1": "positive"}


@pytest.mark.parametrize("text", MAPS)
def test_bad_maps_are_refused(text):
    expect(["driveline", *LINE, "--analysis", "map", "--speed-range", "300:600:100", "--map",
            text], 2, "--map", MAPS[text])
    expect(["plot", "driveline", *LINE, "--analysis", "map", "--speed-range", "300:600:100",
            "--map", text], 2, "--map")


def test_a_line_too_stiff_to_integrate_is_refused_before_stepping():
    """1e13 N·m/rad ran past a minute (12.7 million steps per revolution)."""
    expect(["driveline", *LINE, "--set", "drive_line.stiffness=1e13"], 2,
           "1.27e+07 steps per revolution", "at most 100,000", "`drive_line.stiffness`")


@pytest.mark.parametrize("command", [["driveline"], ["report"], ["analyse"]])
def test_an_absurd_crank_speed_is_refused_where_read(command):
    """1e300 rpm: a traceback (OverflowError) in analyse, a RuntimeWarning in report."""
    expect([*command, SLIDER, "--set", "crank.speed_rpm=1e300"], 2, "`crank.speed_rpm`",
           "at most 1e+12 rpm")
