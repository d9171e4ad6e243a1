"""Rigid supports and joints (issue 42): a direction written "rigid" is an exact constraint,
eliminated like an ideal mesh, and gives the limit that stiffer and stiffer springs
converge to — with the error of a spring k falling as 1/k."""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import InputError
from dyade.vibration.gears.assembly import assemble
from dyade.vibration.gears.modes import gear_modes
from tests.vibration.gears.drives import build, single_stage, two_stage_data


def _radial(data, value):
    out = copy.deepcopy(data)
    for bearing in out["bearing"]:
        if "radial" in bearing:
            bearing["radial"] = value
            bearing.pop("radial_damping", None)
    return out


@pytest.fixture(scope="module")
def two_stage():
    data = two_stage_data()
    return {k: gear_modes(build(_radial(data, k))).frequencies
            for k in ("rigid", 1e11, 1e12)}


def test_rigid_bearings_are_the_limit_of_stiffer_ones(two_stage):
    """f(k) = f_rigid + C/k + O(1/k²): two stiffnesses a decade apart differ from the
    rigid drive by 10:1, and their Richardson extrapolation is the rigid drive. (The
    springs add modes of the bodies on their bearings, above 7 kHz here, which go to
    infinity with k: the modes below 2 kHz are compared.)"""
    low = two_stage["rigid"] < 2000.0
    rigid, f10, f11 = (two_stage[k][:low.sum()] for k in ("rigid", 1e11, 1e12))
    assert np.all(f10 < 2100.0) and np.all(f11 < 2100.0)
    moved = np.abs(f10 - rigid) > 1e-9 * rigid  # the modes the radial bearings take part in
    assert moved.sum() >= 4
    ratio = (f10 - rigid)[moved] / (f11 - rigid)[moved]
    np.testing.assert_allclose(ratio, 10.0, rtol=1e-2)
    extrapolated = f11 + (f11 - f10) / 9.0  # what the springs' sequence converges to
    np.testing.assert_allclose(extrapolated, rigid, rtol=5e-7)
    assert np.max(np.abs(f11 / rigid - 1.0)) > 20 * np.max(np.abs(extrapolated / rigid - 1.0))


def test_a_rigid_joint_is_one_body():
    """Torsional model: a rigid element between two bodies gives the drive in which the
    two are one body with the sum of their inertias, to round-off."""
    data = {
        "model": "torsional",
        "body": [{"name": "motor", "J_x": 0.02}, {"name": "hub", "J_x": 0.005},
                 {"name": "rotor", "J_x": 0.03}, {"name": "load", "J_x": 0.5}],
        "shaft": [{"bodies": ["motor", "hub"], "torsional_stiffness": 2e4},
                  {"bodies": ["rotor", "load"], "torsional_stiffness": 8e3}],
        "element": [{"bodies": ["hub", "rotor"], "stiffness": [0, 0, 0, "rigid", 0, 0]}],
    }
    merged = {
        "model": "torsional",
        "body": [{"name": "motor", "J_x": 0.02}, {"name": "hub", "J_x": 0.035},
                 {"name": "load", "J_x": 0.5}],
        "shaft": [{"bodies": ["motor", "hub"], "torsional_stiffness": 2e4},
                  {"bodies": ["hub", "load"], "torsional_stiffness": 8e3}],
    }
    joined, one = gear_modes(build(data)), gear_modes(build(merged))
    np.testing.assert_allclose(joined.frequencies, one.frequencies, rtol=1e-12)
    assert joined.rigid.shape[1] == one.rigid.shape[1] == 1
    shape = joined.shapes[:, 0]
    assert abs(shape[1] - shape[2]) < 1e-12 * np.abs(shape).max()  # hub and rotor move as one


def test_the_rigid_supports_reaction_is_the_stiff_springs_limit():
    """Statics: a rigid radial bearing carries what a very stiff one carries."""
    torques = {"load": 800.0, "motor": 800.0 * 20 / 50}
    rigid = dyade.gear_statics(build(single_stage(radial="rigid")), torques)
    stiff = dyade.gear_statics(build(single_stage(radial=1e12)), torques)
    assert rigid.supports == stiff.supports
    np.testing.assert_allclose(rigid.forces, stiff.forces, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(rigid.mesh_forces, stiff.mesh_forces, rtol=1e-8)
    assert np.abs(rigid.forces).max() > 100.0  # the bearings do carry the mesh force
    # equilibrium of the whole drive: the frame's forces balance (no external force)
    np.testing.assert_allclose(rigid.forces.sum(axis=0), 0.0, atol=1e-6)


def test_the_eliminated_form_has_one_extra_zero_per_constraint():
    drive = build(single_stage(radial="rigid"))
    system = assemble(drive)
    assert len(system.supports) == 8  # four bearings, two radial directions each
    result = dyade.check_elimination(drive)
    assert result.extra_zeros == system.constraints.shape[1] == 9
    assert result.difference < 1e-8


def test_rigid_in_a_file_and_its_errors(tmp_path):
    drive = build(single_stage(radial="rigid"))
    assert np.isinf(drive.elements[0].stiffness[1])
    with pytest.raises(InputError, match="radial_damping.*rigid"):
        data = single_stage(radial="rigid")
        data["bearing"][0]["radial_damping"] = 10.0
        build(data)
    with pytest.raises(InputError, match='stiffness.*or "rigid"'):
        build(single_stage(radial="rigd"))
    with pytest.raises(InputError, match='written "rigid"'):
        build(single_stage(radial=1e14))  # above what a machine has: the message says how


def test_a_rigid_drive_runs_on_the_command_line(tmp_path):
    import tomlkit

    path = tmp_path / "rigid.toml"
    path.write_text(tomlkit.dumps(single_stage(radial="rigid")))
    out = tmp_path / "modes.json"
    result = CliRunner().invoke(main, ["gears", str(path), "--format", "json", "-o", str(out)])
    assert result.exit_code == 0, result.output
    document = json.loads(out.read_text())
    assert document["meta"]["rigid_directions"] == 8


def test_a_long_eigenproblem_says_its_estimate_first(monkeypatch, tmp_path):
    """A gear eigenproblem estimated above a few seconds says so before it starts, and
    --max-time refuses it before any work (a tiny rate makes the small drive "long")."""
    from dyade.analyses import gears
    from tests.helpers import shipped

    monkeypatch.setattr(gears, "MODES_TIME", 1e-3)  # [s per coordinate³]: 54³ → 157 s
    result = CliRunner().invoke(main, ["gears", str(shipped("gears/two-stage.toml")),
                                       "--max-time", "60"])
    assert result.exit_code == 2
    assert "--max-time" in result.output and "about 157 s" in result.output
    assert "Traceback" not in result.output
    monkeypatch.setattr(gears, "MODES_TIME", 1e-4)  # 15.7 s: said, then run
    result = CliRunner().invoke(main, ["gears", str(shipped("gears/two-stage.toml"))])
    assert result.exit_code == 0
    assert "the modes of 54 coordinates: about 15.7 s." in result.output
