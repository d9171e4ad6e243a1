"""Hostile input of `dyade plot` and the command line as a whole (issue 31): streams,
folders, sizes, a closed pipe, misspelt commands, the older commands' cases."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect, run

pytest.importorskip("matplotlib")

FOURBAR = shipped("fourbar.toml")
TWO_STAGE = shipped("gears/two-stage.toml")


def test_a_mechanism_from_standard_input_is_named_stdin(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    expect(["plot", "polar", "-"], 0, "wrote stdin-polar.png", stdin=FOURBAR.read_text())
    assert (tmp_path / "stdin-polar.png").exists() and not (tmp_path / "--polar.png").exists()


def test_figures_to_standard_output_and_new_folders(tmp_path):
    png = run(["plot", "curves", FOURBAR, "-o", "-"])
    assert png.exit_code == 0 and png.stdout_bytes.startswith(b"\x89PNG")
    svg = run(["plot", "campbell", TWO_STAGE, "-o", "-", "--format", "svg"])
    assert svg.exit_code == 0 and svg.stdout.startswith("<?xml")
    expect(["plot", "curves", FOURBAR, "-o", tmp_path / "new" / "sub" / "p.png"], 0)
    assert (tmp_path / "new" / "sub" / "p.png").exists()
    (tmp_path / "file").write_text("x")
    expect(["plot", "curves", FOURBAR, "-o", tmp_path / "file" / "p.png"], 2,
           "is a file, not a folder")


def test_sizes_are_estimated_first(tmp_path):
    expect(["plot", "animate", FOURBAR, "--step", "0.001", "-o", tmp_path / "a.gif"], 2,
           "--max-memory", "360,001 frames")
    expect(["plot", "campbell", TWO_STAGE, "--harmonics", "100000", "-o", tmp_path / "c.png"],
           2, "--max-memory", "100,000 tooth-mesh harmonics")
    expect(["plot", "modes", TWO_STAGE, "--set", "shaft.1.segments=100000", "-o",
            tmp_path / "m.png"], 2, "--max-memory", "coordinates")


def test_one_rule_for_modes(tmp_path):
    """As `dyade gears --modes`: more than there are gives all, with a note (the cap of 24
    rows of panels is said the same way; tests.gears covers the figure itself)."""
    expect(["plot", "modes", shipped("gears/friswell-geared.toml"), "--modes", "999", "-o",
            tmp_path / "m.png"], 0, "--modes 999: the drive has 3 elastic modes; giving the "
                                    "first 3")


def test_did_you_mean():
    expect(["analyze", FOURBAR], 2, "No such command 'analyze'. Did you mean `analyse`?")


def test_step_beyond_the_sweep():
    expect(["analyse", FOURBAR, "--step", "400"], 2, "--step is 400°, more than one revolution",
           "It is in degrees: --step 0.5 sweeps every half degree")


def test_a_closed_pipe_ends_quietly_with_sigpipe_status():
    """`dyade analyse … -o - | head -c 10`: status 141 (128 + SIGPIPE), no message."""
    command = (f"{sys.executable} -m dyade analyse {FOURBAR} --step 0.01 --format csv -o - "
               f"| head -c 10; echo \" ${{PIPESTATUS[0]}}\"")
    out = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=120)
    assert out.stdout.endswith(" 141\n"), out
    assert out.stderr == "", out.stderr
