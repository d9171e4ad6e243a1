"""``dyade cam`` and ``dyade init cam`` (issue 40): outputs and exit codes."""

from __future__ import annotations

import json
from pathlib import Path

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
