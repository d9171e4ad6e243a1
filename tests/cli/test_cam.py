"""``dyade cam`` and ``dyade init cam`` (issue 40): outputs and exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dyade.cli import main

FILE = Path("mechanisms/cams/translating-roller.toml")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def test_table_points_and_json(tmp_path):
    result = run("cam", FILE, "--points", tmp_path / "w.csv", "--cutter-points",
                 tmp_path / "c.csv")
    assert result.exit_code == 0
    assert "largest |pressure angle| α" in result.stdout and "(limit 30)" in result.stdout
    assert "spring keeps the follower on the cam up to 492.7 rpm" in result.stderr
    assert "points of the working curve within 0.005 mm" in result.stderr
    assert (tmp_path / "w.csv").read_text().startswith("angle_deg,x_mm,y_mm\n")
    document = json.loads(run("cam", FILE, "--format", "json", "--step", "2").stdout)
    assert document["analysis"] == "cam" and len(document["columns"]["angle_deg"]) == 180
    assert document["units"]["rho_working"] == "m" and "nan" not in json.dumps(document)
    csv = run("cam", FILE, "--format", "csv").stdout.splitlines()
    assert csv[0].startswith("angle_deg,s,v,a,j,pressure_angle_deg,rho_pitch") and len(csv) == 361


def test_init_cam_writes_an_analysable_file(tmp_path):
    target = tmp_path / "my-cam.toml"
    assert run("init", "cam", target).exit_code == 0
    assert run("cam", target).exit_code == 0


def test_exit_codes_of_bad_cams(tmp_path):
    text = FILE.read_text(encoding="utf-8")
    never = tmp_path / "never.toml"
    never.write_text(text.replace("preload = 10 ", "preload = -50 "), encoding="utf-8")
    result = run("cam", never)
    assert result.exit_code == 1
    assert "never.toml: the follower can never keep contact" in result.output
    assert "`follower.preload`" in result.output
    misspelt = tmp_path / "misspelt.toml"
    misspelt.write_text(text.replace("roller_radius", "roler_radius"), encoding="utf-8")
    result = run("cam", misspelt)
    assert result.exit_code == 2 and "unknown key `follower.roler_radius`" in result.output
    assert "Did you mean `roller_radius`?" in result.output
    big = tmp_path / "big.toml"
    big.write_text(text.replace("base_radius = 40", "base_radius = 8").replace(
        "roller_radius = 10", "roller_radius = 30").replace("offset = 8 ", "offset = 0 "),
        encoding="utf-8")
    result = run("cam", big)
    assert result.exit_code == 0  # a warning, not a refusal
    assert "is larger than the base circle" in result.stderr


@pytest.mark.parametrize("args, code, message", [
    (["--step", "0"], 2, "'--step': must be positive"),
    (["--step", "45"], 2, "--step must be at most 30 [°]"),
    (["--step", "nan"], 2, "must be a finite number"),
    (["--speed", "-5"], 2, "'--speed': must be positive"),
    (["-o", "{tmp}/out.png"], 2, "dyade does not write .png files"),
    (["-o", "{tmp}/out.parquet"], 2, "dyade cam writes .csv, .json or .txt"),
    (["--points", "{tmp}/p.dxf"], 2, "--points writes CSV points: name the file .csv"),
    (["--dxf", "{tmp}/d.csv"], 2, "--dxf writes a DXF drawing: name the file .dxf"),
    (["--points", "-"], 2, "--points writes CSV points"),
    (["--outer-points", "{tmp}/o.csv"], 2, "is not a grooved cam (`cam.closure`"),
    (["--cutter-points", "{tmp}/c.txt", "-o", "{tmp}/t.csv"], 0, ""),
])
def test_hostile_options(tmp_path, args, code, message):
    result = run("cam", FILE, *[a.replace("{tmp}", str(tmp_path)) for a in args])
    assert result.exit_code == code, result.output
    assert message in result.output and "Traceback" not in result.output
    if code == 0:  # -o's suffix gives the format: CSV, not a table
        assert (tmp_path / "t.csv").read_text().startswith("angle_deg,s,v,a,j,")
    else:
        assert not list(tmp_path.iterdir())  # nothing written before the refusal


@pytest.mark.parametrize("old, new, code, message", [
    ("pressure_angle_max = 30", "pressure_angle_max = 0", 2,
     "`cam.pressure_angle_max` must lie between 0° and 90°"),
    ("pressure_angle_max = 30", "pressure_angle_max = -5", 2,
     "`cam.pressure_angle_max` must lie between 0° and 90°"),
    ("speed_rpm = 300", "speed_rpm = -1", 2, "`cam.speed_rpm` must not be negative"),
    ("stiffness = 2000", "stiffness = 0\nload = -0", 1, "nothing presses it on"),
    ("load = 5 ", "load = -500 ", 1, "the spring and the load pull it off (k·(s + s0) + F = -480 N)"),
    ('closure = "spring"', 'closure = "grove"', 2, '`cam.closure` must be "spring" or "groove"'),
    ("end = 320\nto = 0", "end = 320\nto = 5", 2,
     "`profile.segment.5.to` = 5 mm does not come back to where the turn starts"),
    ("period = 360", "period = 300", 2, "the segments cover 360°, the period is 300°"),
])
def test_hostile_files(tmp_path, old, new, code, message):
    text = FILE.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "hostile.toml"
    text = text.replace(old, new, 1)
    if "to = 5" in new:  # the last dwell stays at 5 mm: the law does not close
        text = text.replace('kind = "dwell"\nend = 360', 'kind = "dwell"\nend = 360\nto = 5')
    if "load = -0" in new:
        text = text.replace("preload = 10 ", "preload = 0 ").replace("load = 5 ", "# ")
    path.write_text(text, encoding="utf-8")
    result = run("cam", path)
    assert result.exit_code == code and message in result.output, result.output
    assert "hostile.toml" in result.output and "Traceback" not in result.output
