"""Hostile input of `dyade gears` (issue 31): each case with its exit code and the key
words of its message."""

from __future__ import annotations

import pytest
import tomlkit

from tests.helpers import shipped
from tests.hostile_common import expect, run

TWO_STAGE = shipped("gears/two-stage.toml")
FRISWELL = shipped("gears/friswell-geared.toml")


def drive(tmp_path, data: dict, name="d.toml"):
    path = tmp_path / name
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    return path


def bodies(*names):
    return [{"name": n, "J_x": 1.0} for n in names]


LOCKED = {"model": "torsional", "body": bodies("a", "b"),
          "shaft": [{"bodies": ["a", "b"], "torsional_stiffness": 1e4}],
          "gear": [{"name": "ga", "body": "a", "teeth": 20}, {"name": "gb", "body": "b", "teeth": 20}],
          "mesh": [{"driving": "ga", "driven": "gb"}]}
LOOP = {"model": "torsional", "body": bodies("a", "b", "c"),
        "shaft": [{"bodies": ["a", "frame"], "torsional_stiffness": 1e4}],
        "gear": [{"name": "ga", "body": "a", "teeth": 20}, {"name": "gb", "body": "b", "teeth": 30},
                 {"name": "gc", "body": "c", "teeth": 40}],
        "mesh": [{"driving": "ga", "driven": "gb"}, {"driving": "gb", "driven": "gc"},
                 {"driving": "gc", "driven": "ga"}]}
STRUCTURE = {
    "one body": ({"model": "torsional", "body": bodies("a")}, "nothing to vibrate"),
    "two bodies, nothing between": ({"model": "torsional", "body": bodies("a", "b")},
                                    "nothing to vibrate"),
    "mesh on one shaft line": (LOCKED, "`mesh.1` joins bodies \"a\" and \"b\""),
    "loop of disagreeing ratios": (LOOP, "`mesh.3` closes a loop whose gear ratios disagree"),
}


@pytest.mark.parametrize("case", STRUCTURE)
def test_structural_impossibilities_are_refused_without_speed(tmp_path, case):
    data, words = STRUCTURE[case]
    expect(["gears", drive(tmp_path, data)], 2, "d.toml", words)


def test_a_loop_whose_ratios_agree_is_a_drive(tmp_path):
    agreeing = {**LOOP, "gear": [{"name": "ga", "body": "a", "teeth": 20},
                                  {"name": "gb", "body": "b", "teeth": 20},
                                  {"name": "gc", "body": "c", "teeth": 20}],
                "mesh": LOOP["mesh"][:2]}
    expect(["gears", drive(tmp_path, agreeing)], 0)


SETS = {  # --set KEY=VALUE -> words of the message (exit 2)
    "bearing.1.radial=1e300": "`bearing.1.radial` must lie in 1e-06…1e+13 N/m",
    "mesh.1.stiffness=1e30": "`mesh.1.stiffness` must lie in",
    "body.1.mass=1e-300": "`body.1.mass` must lie in 1e-09…1e+07 kg",
    "body.1.J_x=1e300": "`body.1.J_x` must lie in",
    "shaft.1.length=1e9": "`shaft.1.length` must lie within",
    "gear.1.teeth=100000000": "`gear.1.teeth` must be at most 10,000",
    "excitation.2.amplitude=1e300": "`excitation.2.amplitude` must lie in",
    "speed.rpm=1e300": "`speed.rpm` must lie in 0.01…1e+06 rpm",
    "material.E=1e300": "`material.E` must lie in",
    "shaft.1.damping=1e5": "`shaft.1.damping` must lie in 0…10 s",
}


@pytest.mark.parametrize("assignment", SETS)
def test_absurd_values_are_refused_naming_key_and_range(assignment):
    expect(["gears", TWO_STAGE, "--set", assignment], 2, "two-stage.toml", SETS[assignment],
           "what a machine has")


SIZES = {  # options -> words (exit 2): refused before anything is allocated
    "100 000 segments": (["--set", "shaft.1.segments=100000"],
                         ["--max-memory", "600,048 coordinates", "segments"]),
    "1000 segments per shaft": (["--set", "shaft.1.segments=1000", "--set",
                                 "shaft.2.segments=1000"], ["--max-memory", "12,042 coordinates"]),
    "a million harmonics": (["--speed-range", "0:3000:10", "--harmonics", "1000000"],
                            ["--max-memory", "1,000,000 tooth-mesh harmonics"]),
    "ten million frequencies": (["--frequency-range", "0:999999:0.1"],
                                ["--max-memory", "9,999,991 frequencies"]),
    "frequencies beyond a machine": (["--frequency-range", "0:9999998:1"],
                                     ["--frequency-range", "0…1e+06 Hz"]),
    "speeds beyond a machine": (["--speed-range", "0:1e300:1e298"], ["--speed-range", "rpm"]),
    "an infinite range": (["--speed-range", "0:1e308:1e-308"], ["--speed-range", "at most"]),
}


@pytest.mark.parametrize("case", SIZES)
def test_sizes_are_estimated_before_anything_is_computed(case):
    args, words = SIZES[case]
    expect(["gears", TWO_STAGE, *args], 2, *words)


def test_the_bound_is_raised_by_its_flag():
    expect(["gears", TWO_STAGE, "--max-memory", "1"], 2, "--max-memory is 1.05 MB",
           "the eigenproblem of 54 coordinates")
    expect(["gears", TWO_STAGE, "--max-memory", "8192"], 0)


def test_standard_input_and_output(tmp_path):
    text = TWO_STAGE.read_text()
    piped = expect(["gears", "-", "--format", "csv", "-o", "-"], 0, "mode,f_Hz", stdin=text)
    direct = run(["gears", TWO_STAGE, "--format", "csv"])
    assert piped.stdout == direct.stdout
    assert not (tmp_path / "-").exists()
    expect(["gears", TWO_STAGE, "--format", "csv", "-o", tmp_path / "new" / "sub" / "m.csv"], 0)
    assert (tmp_path / "new" / "sub" / "m.csv").read_text() == direct.stdout
    blocker = tmp_path / "file"
    blocker.write_text("x")
    expect(["gears", TWO_STAGE, "-o", blocker / "m.csv"], 2, "is a file, not a folder")


def test_files_of_another_kind_are_recognised(tmp_path):
    expect(["gears", shipped("fourbar.toml")], 2, "a mechanism file", "dyade describe, analyse")
    expect(["gears", shipped("coupling/stiff-coupling.toml")], 2, "a coupling file",
           "dyade coupling")
    expect(["gears", shipped("torque/engine.csv")], 2, "a CSV file", "dyade flywheel")
    expect(["analyse", TWO_STAGE], 2, "a gear-drive file", "dyade gears")


def test_one_rule_for_modes():
    result = expect(["gears", FRISWELL, "--modes", "999", "--format", "csv"], 0,
                    "--modes 999: the drive has 3 elastic modes; giving the first 3")
    assert {line.split(",")[0] for line in result.stdout.splitlines()[1:]} == {"1", "2", "3"}
    expect(["gears", FRISWELL, "--modes", "0"], 2, "--modes")


def test_old_option_names_still_work():
    new = run(["gears", TWO_STAGE, "--speed-range", "0:3000:100", "--format", "csv"])
    old = run(["gears", TWO_STAGE, "--campbell", "0:3000:100", "--format", "csv"])
    assert new.exit_code == old.exit_code == 0 and new.stdout == old.stdout
    help_text = run(["gears", "--help"]).output
    assert "--speed-range" in help_text and "--campbell" not in help_text
