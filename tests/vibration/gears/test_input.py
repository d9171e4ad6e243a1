"""Bad gear-drive files: a clear error naming the file and the key, exit status 2 and no
traceback from the command line."""

from __future__ import annotations

import copy

import pytest
import tomlkit
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.vibration.gears.drives import single_stage


def _break(change):
    data = single_stage()
    change(data)
    return data


def _set(path, value):
    def change(data):
        target = data
        for part in path[:-1]:
            target = target[part]
        target[path[-1]] = value
    return change


def _duplicate_mesh(data):
    data["mesh"].append(copy.deepcopy(data["mesh"][0]) | {"name": "again"})


def _same_body(data):
    data["gear"].append({"name": "q", "body": "pinion", "teeth": 30, "module": 0.004})
    data["mesh"][0]["driven"] = "q"


def _triangle(data):
    data["model"] = "torsional"  # (six coordinates could not even place the third gear)
    data["body"].append({"name": "idler", "diameter": 0.1, "width": 0.04, "bore": 0.03})
    data["gear"] += [{"name": "i", "body": "idler", "teeth": 25, "module": 0.004},
                     {"name": "p2", "body": "pinion", "teeth": 20, "module": 0.004,
                      "offset": 0.05}]
    data["mesh"] += [{"driving": "w", "driven": "i", "angle": 90.0},
                     {"driving": "i", "driven": "p2", "angle": 180.0}]


CASES = {
    "gear on no body": (_set(("gear", 0, "body"), "shaft"), "`gear.1.body` names no body"),
    "gear without a body": (lambda d: d["gear"][0].pop("body"), "`gear.1.body` is missing"),
    "mesh between gears of one body": (_same_body, "`mesh.1` joins gears \"p\" and \"q\", which "
                                                   "are both on body \"pinion\""),
    "modules that do not match": (_set(("gear", 1, "module"), 0.005),
                                  "`mesh.1` joins \"p\" (module 0.004 m) and \"w\" (module "
                                  "0.005 m): meshing gears need the same normal module"),
    "zero mass": (_set(("body", 0, "mass"), 0.0), "`body.1.mass` must be positive [kg], got 0"),
    "the same motion constrained twice": (_duplicate_mesh, "`mesh.2` constrains a motion that "
                                                           "the meshes before it already fix "
                                                           "(gᵀM⁻¹g is singular)"),
    "gear ratios around a loop": (_triangle, "`mesh.3` closes a loop whose gear ratios disagree: "
                                             "around it body \"pinion\" would turn at two speeds"),
    "helical gears of one hand": (lambda d: d["gear"][0].update(helix_angle=15, hand="left")
                                  or d["gear"][1].update(helix_angle=15, hand="left"),
                                  "`mesh.1` joins two left-hand gears"),
    "helix without a hand": (_set(("gear", 0, "helix_angle"), 10.0), "`gear.1.hand` is missing"),
    "different helix angles": (lambda d: d["gear"][0].update(helix_angle=15, hand="left"),
                               "`mesh.1` joins \"p\" and \"w\" with different helix angles"),
    "misspelt key": (_set(("gear", 0, "modul"), 0.004), "unknown key `gear.1.modul`. Did you "
                                                        "mean `module`?"),
    "negative stiffness": (_set(("bearing", 0, "radial"), -1.0),
                           "`bearing.1.radial` must not be negative [N/m], got -1"),
    "fractional segments": (_set(("shaft", 0, "segments"), 2.5),
                            "`shaft.1.segments` must be a whole number"),
    "no sense of rotation": (lambda d: d.pop("speed"), "`mesh.1.rotation` is missing"),
    "a rotation against [speed]": (_set(("mesh", 0, "rotation"), "left"),
                                   "`mesh.1.rotation` is \"left\", but [speed] makes gear \"p\" "
                                   "turn right-handed"),
    "non-parallel shafts": (lambda d: d["body"][2].update(axis=[0, 1, 0])
                            or d["body"][3].update(axis=[0, 1, 0]),
                            "`mesh.1` joins gears on bodies \"pinion\" and \"wheel\" whose axes "
                            "are not parallel"),
    "damping on an ideal mesh": (_set(("mesh", 0, "damping"), 100.0),
                                 "`mesh.1.damping` needs `stiffness`"),
    "a torsional stiffness in six coordinates": (_set(("shaft", 0, "torsional_stiffness"), 1e4),
                                                 "`shaft.1.torsional_stiffness` is for the "
                                                 "torsional model only"),
    "a body placed twice": (lambda d: d["body"][0].update(position=[0, 0, 0])
                            or d["body"][3].update(position=[0.9, 0, 0]),
                            "`shaft.2` places body \"load\""),
}


@pytest.mark.parametrize("case", CASES)
def test_bad_input_is_named(case, tmp_path):
    change, message = CASES[case]
    data = _break(change)
    with pytest.raises(dyade.InputError) as err:
        dyade.gear_modes(dyade.build_gears(data, tmp_path / "drive.toml"))
    assert message in str(err.value)
    assert str(err.value).startswith("drive.toml: ")
    path = tmp_path / "drive.toml"
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    run = CliRunner().invoke(main, ["gears", str(path)])
    assert run.exit_code == 2, run.output
    assert message in run.output and "Traceback" not in run.output


def test_bad_options_are_named(tmp_path):
    path = tmp_path / "drive.toml"
    path.write_text(tomlkit.dumps(single_stage()), encoding="utf-8")
    cases = [(["--dof", "motor.qx", "--frequency-range", "1:2:1"], "--dof names 'motor.qx'"),
             (["--dof", "motor.qx", "--response", "1:2:1"], "--dof names 'motor.qx'"),  # old
             (["--speed-range", "0:100"], "--speed-range"),
             (["--campbell", "0:100"], "--speed-range"),  # the old name, a hidden alias
             (["--speed-range", "0:100:1", "--check"], "--speed-range and --check: one analysis")]
    for args, message in cases:
        run = CliRunner().invoke(main, ["gears", str(path), *args])
        assert run.exit_code == 2 and message in run.output, run.output
    no_speed = single_stage(mesh={"rotation": "right"})
    no_speed.pop("speed")
    path.write_text(tomlkit.dumps(no_speed), encoding="utf-8")
    run = CliRunner().invoke(main, ["gears", str(path), "--campbell", "0:100:1"])
    assert run.exit_code == 2 and "drive.toml: `[speed]` is not given" in run.output
