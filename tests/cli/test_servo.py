"""`dyade servo` (issue 39): the shipped servo press and four-bar, the catalogue's choice,
the cam table for a motion controller, and bad input with its exit code and message."""

from __future__ import annotations

import csv
import io
import json
import shutil

import numpy as np
import pytest

import dyade
from tests.helpers import shipped
from tests.hostile_common import expect

PRESS = shipped("servo/press.toml")
FOURBAR = shipped("servo/fourbar.toml")


@pytest.fixture(scope="module")
def press():
    return dyade.run("servo", PRESS, ratio_count=5)


def test_press_sizes_a_motor_over_the_ratio_range(press):
    summary = press.summary
    # the RMS optimum of the range is a true minimum among the range's ratios
    sizing = press.result.sizing
    assert summary["ratio_optimum"].value == pytest.approx(
        sizing.ratio[np.argmin(sizing.rms_torque)])
    assert np.all(sizing.rms_torque >= summary["ratio_optimum"].value * 0 + sizing.rms_torque.min())
    # the chosen motor passes, and every smaller one of the catalogue fails at every ratio
    chosen = press.result.chosen
    assert summary["motor"].value == chosen.motor.name
    assert min(summary[f"margin_{k}"].value for k in ("thermal", "peak", "speed", "inertia")) >= 0
    for check in press.result.checks:
        if check.motor.rated_torque < chosen.motor.rated_torque:
            assert check.best is None
    # the slider follows its profile: the ram's travel rises 60 mm and comes back
    assert np.max(press.columns["s"]) == pytest.approx(0.06, rel=1e-12)
    assert press.units["s"] == "m" and press.units["M_motor"] == "N·m"


def test_command_table_json_csv_and_the_controller_table(tmp_path):
    result = expect(["servo", FOURBAR], 0, "RMS motor torque", "inertia ratio")
    assert "nan" not in result.output and "True" not in result.output
    document = json.loads(expect(["servo", FOURBAR, "--format", "json"], 0).output)
    assert document["analysis"] == "servo"
    assert document["summary"]["motor_torque_rms"]["unit"] == "N·m"
    rows = list(csv.reader(io.StringIO(expect(["servo", FOURBAR, "--format", "csv"], 0).output)))
    assert rows[0][:3] == ["t", "angle_deg", "omega_2"] and len(rows) == 722
    table = tmp_path / "cam.csv"
    expect(["servo", FOURBAR, "--controller", table, "-o", tmp_path / "out.json"], 0)
    cam = np.loadtxt(table, delimiter=",", skiprows=1)
    assert table.read_text().splitlines()[0] == \
        "t,position_deg,velocity_deg_s,acceleration_deg_s2"
    assert cam[0, 1] == 0 and cam[-1, 1] == pytest.approx(360.0, rel=1e-12)
    # the velocity column is the derivative of the position (central differences)
    dt = cam[1, 0] - cam[0, 0]
    middle = (cam[2:, 1] - cam[:-2, 1]) / (2 * dt)
    assert np.max(np.abs(middle - cam[1:-1, 2])) < 1e-3 * np.max(cam[:, 2])


def servo_file(tmp_path, text: str, name: str = "m.toml"):
    """The shipped press with ``text`` replaced as asked, in tmp_path with its catalogue."""
    shutil.copy(shipped("servo/motors.csv"), tmp_path / "motors.csv")
    path = tmp_path / name
    path.write_text(text)
    return path


PRESS_TEXT = PRESS.read_text()
BAD = {
    "velocity jump": (PRESS_TEXT.replace('kind = "dwell"          # pressing',
                                         'kind = "rise"\nlaw = "constant-velocity"\nto = 61'),
                      2, ("segment 3", "velocity jump", "m.toml")),
    "cycle time": (PRESS_TEXT.replace("period = 0.5", "period = 0"), 2,
                   ("`profile.period`", "positive")),
    "cycle time of an angle master": (
        FOURBAR.read_text().replace('master = "time"', 'master = "angle"').replace(
            "period = 0.4", "period = 360").replace("end = 0.3", "end = 270").replace(
            "end = 0.4", "end = 360").replace("ratio = 8", "ratio = 8\ncycle_time = -0.5"),
        2, ("`servo.cycle_time`", "positive")),
    "drive and servo": (PRESS_TEXT.replace("[servo]", '[drive]\nmotor = "constant"\n\n[servo]'),
                        2, ("`servo`", "[drive]", "Keep one")),
    "drive line's own ratio": (PRESS_TEXT.replace(
        "[servo]", '[drive_line]\nstiffness = 1000\nratio = 2\n\n[servo]'), 2,
        ("`drive_line.ratio`", "servo.ratio")),
    "unknown output": (PRESS_TEXT.replace('output = "s_1_4"', 'output = "s_1_5"'), 2,
                       ("`servo.output`", "s_i_j")),
    "odd samples": (PRESS_TEXT.replace("samples = 720", "samples = 721"), 2,
                    ("`servo.samples`", "even")),
    "a crank that does not come round": (FOURBAR.read_text().replace("to = 360", "to = 180"),
                                         2, ("`profile.segment.2.to`", "180°", "whole")),
    "an output that does not come back": (PRESS_TEXT.replace("to = 0\n", "to = 5\n"), 2,
                                          ("`profile.segment.5.to`", "5 mm", "s_1_4 back")),
    "beyond a dead centre": (PRESS_TEXT.replace("to = 60", "to = 90").replace(
        "to = 0\n", "to = 0\n", 1), 1, ("m.toml: the profile moves", "beyond a dead centre", "2.86599°", "184.78°")),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_input_is_refused_with_its_code(tmp_path, case):
    text, code, words = BAD[case]
    expect(["servo", servo_file(tmp_path, text)], code, *words)


def test_catalogue_missing_a_column_names_the_file_and_column(tmp_path):
    bad = tmp_path / "short.csv"
    bad.write_text("name,rated_torque,peak_torque,rated_speed_rpm,top_speed_rpm\nX,1,3,3000,6000\n")
    expect(["servo", PRESS, "--catalogue", bad], 2, "short.csv", "`rotor_inertia`", "is missing")


def test_a_motor_too_small_for_every_ratio_exits_1_naming_the_catalogue(tmp_path):
    small = tmp_path / "small.csv"
    small.write_text("name,rated_torque,peak_torque,rated_speed_rpm,top_speed_rpm,rotor_inertia\n"
                     "tiny,0.05,0.15,3000,6000,1e-5\n")
    expect(["servo", PRESS, "--catalogue", small, "--ratio-count", "5"], 1,
           "no motor of small.csv passes at any gear ratio 3–40", "tiny", "thermal (RMS)")


def test_a_file_without_servo_is_refused():
    expect(["servo", shipped("fourbar.toml")], 2, "no [servo] table", "dyade init servo")


def test_init_servo_writes_a_file_that_sizes_as_written(tmp_path):
    path = tmp_path / "servo.toml"
    expect(["init", "servo", path], 0, "dyade servo")
    expect(["servo", path, "--ratio-count", "3"], 0, "RMS-optimal gear ratio")
    expect(["analyse", path, "--format", "csv"], 0, "M_drive")   # at its constant speed


@pytest.mark.slow
def test_elastic_line_under_a_cycloid_matches_the_forced_oscillator(tmp_path):
    # the four-bar with only its crank's inertia J0 (J constant, no loads), turned once per
    # cycle T by a cycloid through a shaft k, b: the crank's lag e = φ − φ_p obeys
    # J0·ë + b·ė + k·e = −J0·φ̈_p, φ̈_p = A·sin Ωt (A = 2π·2π/T², Ω = 2π/T), whose
    # periodic solution is e = −J0·A·((k − J0·Ω²)·sin Ωt − b·Ω·cos Ωt)/D²
    J0, k, b, T = 0.01, 400.0, 0.3, 0.4
    text = FOURBAR.read_text()
    text = text[:text.index("[[profile.segment]]")] + (
        '[[profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 0.4\nto = 360\n')
    text = text.replace("mass = 1.2", "mass = 0").replace("mass = 0.9", "mass = 0").replace(
        "inertia = 0.004", "inertia = 0").replace("inertia = 0.0017", "inertia = 0")
    text += f"\n[links.2]\ninertia = {J0}\n\n[drive_line]\nstiffness = {k}\ndamping = {b}\n"
    path = servo_file(tmp_path, text)
    outcome = dyade.run("servo", path)
    t = outcome.columns["t"]
    A, omega = 4 * np.pi ** 2 / T ** 2, 2 * np.pi / T
    D2 = (k - J0 * omega ** 2) ** 2 + (b * omega) ** 2
    lag = -J0 * A * ((k - J0 * omega ** 2) * np.sin(omega * t) - b * omega * np.cos(omega * t)) / D2
    # RK4 at ≥ 40 steps per natural period (here 360 per cycle, ω̄·Δt = 0.22): ~1e-6
    scale = np.max(np.degrees(np.abs(lag)))
    assert np.degrees(lag) == pytest.approx(outcome.columns["lag_deg"], abs=1e-5 * scale)
    # the shaft's torque −(k·e + b·ė) and the rigid torque J0·φ̈_p differ by the line's dynamics
    line = -(k * lag + b * np.gradient(lag, t))
    assert np.max(np.abs(outcome.columns["M_line"] - line)) < 2e-3 * np.max(np.abs(line))
    assert outcome.value("line_frequency") == pytest.approx(np.sqrt(k / J0))


@pytest.mark.slow
def test_joint_friction_dissipates_through_the_crank():
    # Coulomb friction in every pin (μ = 0.1, r = 5 mm): its share of the crank torque
    # M_F (from the joint forces) takes power from the crank at every instant, never gives
    outcome = dyade.run("servo", FOURBAR, set=("friction.coefficient=0.1",
                                               "friction.pin_radius=5"), samples=120)
    power = outcome.columns["M_friction"] * outcome.columns["omega_2"]
    assert power.min() >= -1e-12 * power.max() and power.max() > 1.0      # [W]
    assert any("M_friction" in note for note in outcome.notes)


def test_a_profile_over_a_master_angle_with_its_cycle_time_is_the_same_cycle(tmp_path):
    # 360° of a virtual master shaft in servo.cycle_time = 0.4 s is the time profile of
    # 0.4 s: the derivatives per degree scaled by the master's speed
    text = (FOURBAR.read_text().replace('master = "time"', 'master = "angle"')
            .replace("period = 0.4 ", "period = 360 ").replace("end = 0.3\n", "end = 270\n")
            .replace("end = 0.4\n", "end = 360\n")
            .replace("ratio = 8\n", "ratio = 8\ncycle_time = 0.4\n"))
    by_angle = dyade.run("servo", servo_file(tmp_path, text), samples=120)
    by_time = dyade.run("servo", FOURBAR, samples=120)
    assert by_angle.columns["M_motor"] == pytest.approx(by_time.columns["M_motor"], abs=1e-12)


def test_the_profile_may_be_a_file_of_its_own(tmp_path):
    text = FOURBAR.read_text()
    cut = text.index("[profile]")
    (tmp_path / "turn.toml").write_text(text[cut:])
    own = 'ratio = 8\nprofile = "turn.toml"\n'
    path = servo_file(tmp_path, text[:cut].replace("ratio = 8\n", own))
    alone = dyade.run("servo", path, samples=120)
    assert alone.value("motor_torque_rms") == pytest.approx(
        dyade.run("servo", FOURBAR, samples=120).value("motor_torque_rms"), rel=1e-14)
    both = servo_file(tmp_path, text.replace("ratio = 8\n", 'ratio = 8\nprofile = "turn.toml"\n'),
                      "both.toml")
    expect(["servo", both], 2, "`servo.profile`", "keep one")
    none = servo_file(tmp_path, text[:cut], "none.toml")
    expect(["servo", none], 2, "`servo`", "needs a motion profile")


def test_where_a_peak_occurs_is_a_time_with_its_unit(press):
    from dyade.report.format import where

    shown = where(press.summary["motor_torque_peak"].where)
    assert shown.startswith("time ") and shown.endswith(" s"), shown


def test_parquet_is_refused_not_written_as_a_table(tmp_path):
    from click.testing import CliRunner

    from dyade.cli import main

    out = CliRunner().invoke(main, ["servo", str(PRESS), "-o", str(tmp_path / "s.parquet")])
    assert out.exit_code == 2 and "writes .csv, .json or .txt" in out.output
    assert not (tmp_path / "s.parquet").exists()


@pytest.mark.parametrize("flags, words", [
    (["--rotor-inertia", "1e300"], ("--rotor-inertia", "servo.rotor_inertia", "1e+300")),
    (["--ratio-range", "1e-300:40"], ("--ratio-range", "1e-300")),
    (["--set", "servo.gear_inertia=1e300"], ("`servo.gear_inertia`",)),
    (["--samples", "1000000"], ("--samples", "200000")),
])
def test_numbers_beyond_any_machine_are_refused_before_they_overflow(flags, words):
    expect(["servo", PRESS, *flags], 2, "press.toml", *words)


def test_a_profile_beyond_any_machine_ends_without_a_warning(tmp_path):
    import warnings

    text = FOURBAR.read_text().replace("to = 360", "to = 3.6e300")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = expect(["servo", servo_file(tmp_path, text)], 1, "not given")
    assert "Traceback" not in result.output


def test_the_help_examples_name_files_that_exist():
    from pathlib import Path

    from click.testing import CliRunner

    from dyade.cli import main

    root = Path(__file__).resolve().parents[2]
    text = CliRunner().invoke(main, ["servo", "--help"]).output
    examples = [line.split() for line in text.splitlines()
                if line.strip().startswith("dyade servo ")]
    assert examples
    for words in examples:
        given = [words[2]] + [b for a, b in zip(words, words[1:]) if a == "--catalogue"]
        for name in given:
            assert (root / name).is_file(), (name, words)


def test_ratio_range_is_start_stop_step_as_every_range_of_dyade():
    outcome = dyade.run("servo", FOURBAR, ratio_range="4:12:2", samples=72)
    sizing, optimum = outcome.result.sizing, outcome.result.optimum
    assert 4 < optimum < 12
    assert np.allclose(sizing.ratio, sorted([4, 6, 8, 10, 12, optimum]), rtol=0, atol=1e-12)
    # LOW:HIGH (two numbers) keeps its meaning: --ratio-count log-spaced ratios
    two = dyade.run("servo", FOURBAR, ratio_range="4:12", ratio_count=3, samples=72)
    assert np.allclose(np.delete(two.result.sizing.ratio, np.flatnonzero(
        two.result.sizing.ratio == two.result.optimum)), [4, np.sqrt(48), 12], rtol=1e-12)
    assert two.result.optimum == pytest.approx(optimum, rel=1e-8)
    expect(["servo", str(FOURBAR), "--ratio-range", "4:12:2", "--ratio-count", "3"], 2,
           "--ratio-count", "gives its own")
    expect(["servo", str(FOURBAR), "--ratio-range", "12:4:1"], 2,
           "START:STOP:STEP with 0 < START < STOP and STEP > 0")
