"""Hostile input of `dyade report` (issue 31): each case with its exit code and the key
words of its message."""

from __future__ import annotations

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect

pytest.importorskip("matplotlib")
SLIDER = shipped("slider-crank.toml")

FILES = {  # a file report cannot read -> words of the message (exit 2)
    "torque/engine.csv": ("a CSV file", "dyade flywheel"),
}


@pytest.mark.parametrize("name", FILES)
def test_files_of_another_kind(name):
    expect(["report", shipped(name)], 2, *FILES[name])


def test_a_coupling_file_takes_no_set(tmp_path):
    """A coupling file's report is of the file as it stands (its keys are flat; --set
    edits mechanism files): refused, nothing written."""
    expect(["report", shipped("coupling/stiff-coupling.toml"), "--set", "J=0.02", "-o",
            tmp_path / "r.html"], 2, "neither a mechanism file", "without --set")
    assert not (tmp_path / "r.html").exists()


def test_bad_toml_and_missing_files(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("crank = \n")
    expect(["report", bad], 2, "bad.toml", "not valid TOML")
    expect(["report", tmp_path / "none.toml"], 2, "does not exist")


SETS = {"crank.speed_rpm=1e300": "at most 1e+12 rpm", "crank.speed_rpm=nan": "finite",
        "crank.speed_rpm=-1": "positive", "crank.lenght=1": "Did you mean `length`",
        "links.2.mass=1e300": "`links.2.mass`"}


@pytest.mark.parametrize("assignment", SETS)
def test_bad_overrides(assignment):
    expect(["report", SLIDER, "--set", assignment], 2, SETS[assignment])


@pytest.mark.slow  # computes the whole result twice (1.5-3.5 s)
def test_output_under_a_file_and_a_missing_folder(tmp_path):
    (tmp_path / "afile").write_text("x")
    expect(["report", SLIDER, "-o", tmp_path / "afile" / "r.html"], 2, "is a file, not a folder")
    expect(["report", SLIDER, "-o", tmp_path / "new" / "r.html"], 0)
    assert (tmp_path / "new" / "r.html").read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


@pytest.mark.slow
def test_standard_output():
    assert expect(["report", SLIDER, "-o", "-"], 0).output.startswith("<!DOCTYPE html>")
