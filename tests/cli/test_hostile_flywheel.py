"""Hostile input of `dyade flywheel` (issue 31): each case with its exit code and the key
words of its message."""

from __future__ import annotations

import math

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect, run

ENGINE = shipped("torque/engine.csv")
FOURBAR = shipped("fourbar.toml")

FLAGS = {  # extra arguments on the engine CSV -> words (exit 2)
    "tiny speed": (["--speed", "1e-300", "--fluctuation", "0.02"],
                   ["--speed must lie in 0.01…1e+06 rpm"]),
    "huge speed": (["--speed-rpm", "1e300", "--fluctuation", "0.02"], ["--speed"]),
    "nan speed": (["--speed-rpm", "nan", "--fluctuation", "0.02"], ["finite"]),
    "huge fluctuation": (["--speed-rpm", "300", "--fluctuation", "1e300"],
                         ["--fluctuation", "1e-06…1"]),
    "huge inertia": (["--speed-rpm", "300", "--inertia", "1e300"], ["--inertia", "kg·m²"]),
    "negative inertia": (["--speed-rpm", "300", "--inertia", "-1"], ["--inertia"]),
    "both": (["--speed-rpm", "300", "--inertia", "1", "--fluctuation", "0.1"], ["either"]),
}


@pytest.mark.parametrize("case", FLAGS)
def test_absurd_flags_are_refused(case):
    args, words = FLAGS[case]
    expect(["flywheel", ENGINE, *args], 2, *words)


def test_a_flywheel_too_small_to_keep_the_speed_is_an_analysis_problem():
    expect(["flywheel", ENGINE, "--speed-rpm", "300", "--inertia", "1e-300"], 1,
           "the machine stalls", "at least")


def test_mechanism_steps():
    expect(["flywheel", FOURBAR, "--fluctuation", "0.02", "--step", "400"], 2,
           "--step", "at most 90 °", "got 400")
    expect(["flywheel", FOURBAR, "--fluctuation", "0.02", "--step", "1e-6"], 2,
           "--max-memory", "360,000,000 positions")


CSVS = {  # file text -> words (exit 2)
    "duplicate": ("angle_deg,M_drive\n0,1\n90,2\n90,3\n270,4\n",
                  ["c.csv: line 4, column angle_deg: 90 repeats line 3's 90"]),
    "unsorted": ("angle_deg,M_drive\n0,1\n\n90,2\n80,3\n270,4\n",
                 ["c.csv: line 5, column angle_deg: 80 is below line 4's 90"]),
    "empty cell": ("Angle_deg , M_drive\n0,1\n90,\n180,3\n270,4\n",
                   ["c.csv: line 3, column M_drive: empty"]),
    "nan": ("angle_deg,Torque\n", ["no column M_drive", "line 1: angle_deg, Torque"]),
    "nan cell": ("angle_deg,M_drive\n0,1\n90,nan\n180,3\n270,4\n",
                 ["line 3, column M_drive: not a finite number: 'nan'"]),
    "inf cell": ("angle_deg,M_drive\n0,1\n90,-inf\n180,3\n270,4\n",
                 ["line 3, column M_drive: not a finite number: '-inf'"]),
    "huge torque": ("angle_deg,M_drive\n0,1\n90,1e300\n180,3\n270,4\n",
                    ["line 3, column M_drive: 1e300 N·m is beyond what a machine has"]),
    "radians": ("angle_deg,M_drive\n" + "".join(f"{k * 2 * math.pi / 50},{100 + k}\n"
                                                for k in range(50)),
                ["column angle_deg runs from 0 to", "look like radians", "180/π"]),
    "ragged": ("angle_deg,M_drive\n0,1\n90\n", ["line 3 has 1 fields"]),
    "empty": ("", ["the file is empty"]),
}


@pytest.mark.parametrize("case", CSVS)
def test_csv_messages_name_file_column_and_line(tmp_path, case):
    text, words = CSVS[case]
    path = tmp_path / "c.csv"
    path.write_text(text, encoding="utf-8")
    expect(["flywheel", path, "--speed-rpm", "100", "--fluctuation", "0.1"], 2, *words)


def test_a_byte_order_mark_is_read(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_bytes("\ufeff".encode() + ENGINE.read_bytes())
    plain = run(["flywheel", ENGINE, "--speed-rpm", "250", "--fluctuation", "0.02", "--format",
                 "csv"])
    marked = run(["flywheel", path, "--speed-rpm", "250", "--fluctuation", "0.02", "--format",
                  "csv"])
    assert plain.exit_code == marked.exit_code == 0 and plain.stdout == marked.stdout


def test_standard_input_and_output(tmp_path):
    args = ["--speed-rpm", "250", "--fluctuation", "0.02", "--format", "csv"]
    direct = run(["flywheel", ENGINE, *args])
    piped = expect(["flywheel", "-", *args, "-o", "-"], 0, stdin=ENGINE.read_text())
    assert piped.stdout == direct.stdout and direct.stdout.startswith("speed_rpm,")
    mechanism = expect(["flywheel", "-", "--fluctuation", "0.02"], 0, "Flywheel",
                       stdin=FOURBAR.read_text())
    assert "J_flywheel" in mechanism.stdout
    expect(["flywheel", ENGINE, *args, "-o", tmp_path / "a" / "b.csv"], 0)
    assert (tmp_path / "a" / "b.csv").read_text() == direct.stdout


def test_notes_keep_their_brackets():
    result = expect(["flywheel", ENGINE, "--speed-rpm", "250", "--fluctuation", "0.5"], 0)
    assert "([drive] table)" in result.output
