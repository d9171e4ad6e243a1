"""``dyade profile`` and ``dyade plot profile``: the table, the CSV for a motion
controller, the exit codes of bad files (2, naming the file, the segment and the key)."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from dyade.cli import main
from tests.helpers import shipped

INDEXING = str(shipped("profiles/indexing.toml"))
CONVEYOR = str(shipped("profiles/conveyor.toml"))


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_csv_for_a_motion_controller():
    out = run("profile", INDEXING, "--format", "csv")
    assert out.exit_code == 0, out.output
    lines = out.stdout.splitlines()
    assert lines[0] == "angle_deg,s,v,a,j,segment" and len(lines) == 362
    row = dict(zip(lines[0].split(","), lines[1 + 105].split(",")))   # 105°: mid-rise
    # modified sine at its middle: s = h/2, v = h·C_v/T [mm/°]
    assert float(row["s"]) == pytest.approx(20.0, abs=1e-9)
    assert float(row["v"]) == pytest.approx(40 * 4 * math.pi / (math.pi + 4) / 90, rel=1e-12)


def test_in_time_at_a_master_speed():
    out = run("profile", INDEXING, "--speed", "60", "--format", "csv", "--points", "5")
    assert out.exit_code == 0, out.output
    lines = out.stdout.splitlines()
    assert lines[0] == "angle_deg,time_s,s,v,a,j,segment"
    assert lines[-1].split(",")[:2] == ["360", "1"]           # one revolution in 1 s


def test_table_and_notes():
    out = run("profile", CONVEYOR)
    assert out.exit_code == 0, out.output
    assert "R-G" in out.stdout and "G-R" in out.stdout and "polynomial" in out.stdout
    assert "Traceback" not in out.output


@pytest.mark.parametrize("body, words", [
    ('[[profile.segment]]\nkind = "rise"\nlaw = "modifed-sine"\nend = 180\nto = 10\n'
     '[[profile.segment]]\nkind = "return"\nlaw = "cycloid"\nend = 360\nto = 0\n',
     'segment 1 (rise, modifed-sine): `law` = "modifed-sine" is not a motion law. '
     'Did you mean `modified-sine`?'),
    ('[[profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 180\nto = 10\n'
     '[[profile.segment]]\nkind = "return"\nlaw = "cycloid"\nstart = 170\nend = 360\nto = 0\n',
     "`profile.segment.2.start` = 170° does not meet the end of segment 1 (180°)"),
    ('[[profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 180\nto = 10\n'
     '[[profile.segment]]\nkind = "dwell"\nend = 180\n'
     '[[profile.segment]]\nkind = "return"\nlaw = "cycloid"\nend = 360\nto = 0\n',
     "`profile.segment.2.end` = 180° is not after the segment's start (180°)"),
    ('[[profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 180\nto = 10\n'
     '[[profile.segment]]\nkind = "constant-velocity"\nend = 270\nto = 20\n'
     '[[profile.segment]]\nkind = "return"\nlaw = "polynomial"\nend = 360\nto = 0\n',
     "segment 2 (constant-velocity): `law` makes the velocity jump from 0 mm/° to "
     "0.111111 mm/° at its start (master 180°)"),
])
def test_bad_files_exit_2_naming_file_segment_and_key(tmp_path, body, words):
    path = tmp_path / "bad.toml"
    path.write_text('[profile]\nperiod = 360\n' + body, encoding="utf-8")
    out = run("profile", path)
    assert out.exit_code == 2, out.output
    assert "bad.toml: " in out.output and words in " ".join(out.output.split())
    assert "Traceback" not in out.output


def test_speed_needs_an_angle_master():
    out = run("profile", CONVEYOR, "--speed", "60")
    assert out.exit_code == 2 and "--speed applies to an angle master only" in out.output


def test_init_profile_runs_as_written(tmp_path):
    path = tmp_path / "p.toml"
    assert run("init", "profile", path).exit_code == 0
    out = run("profile", path, "--format", "json")
    assert out.exit_code == 0, out.output
    summary = json.loads(out.stdout)["summary"]
    assert summary["segment2_boundary"]["value"] == "R-G"        # matched to its neighbours
    assert summary["segment4_boundary"]["value"] == "G-R"


@pytest.mark.slow
def test_plot_profile(tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "p.png"
    out = run("plot", "profile", INDEXING, "-o", png)
    assert out.exit_code == 0, out.output
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_the_format_of_o_comes_from_its_suffix(tmp_path):
    out = run("profile", INDEXING, "--points", "3", "-o", tmp_path / "cam.csv")
    assert out.exit_code == 0, out.output
    assert (tmp_path / "cam.csv").read_text().startswith("angle_deg,s,v,a,j,segment")
    out = run("profile", INDEXING, "--points", "3", "-o", tmp_path / "cam.parquet")
    assert out.exit_code == 2 and "writes .csv, .json or .txt" in out.output
    assert not (tmp_path / "cam.parquet").exists()
