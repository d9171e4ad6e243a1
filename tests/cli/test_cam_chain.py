"""A cam in the chain through the commands (issue 40): `dyade analyse` sweeps a
mechanism whose [cam] drives link 2 over the cam angle, `dyade describe` says so,
`dyade cam` checks the same cam and agrees, a study over a cam key equals direct runs,
and a [cam] that does not fit the chain is refused naming the key and the fix."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import InputError

EXAMPLE = "mechanisms/cams/cam-rocker.toml"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


@pytest.fixture(scope="module")
def analysed():
    result = run("analyse", EXAMPLE, "--step", 6, "--format", "json")
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def test_analyse_gives_the_contact_force_and_the_cam_torque(analysed):
    columns, summary = analysed["columns"], analysed["summary"]
    assert analysed["units"]["F_cam"] == "N"
    contact = np.array(columns["F_cam"], dtype=float)
    # at rest on the base circle (θ = 0, no motion) the cam carries the spring's preload
    # k·s0 + F, the follower's weight and the stem's pull from the chain
    assert summary["F_cam_min"]["value"] == pytest.approx(np.min(contact))
    assert np.all(contact > 0.0)


def test_describe_says_the_chain_is_cam_driven():
    result = run("describe", EXAMPLE)
    assert result.exit_code == 0, result.output
    flat = " ".join(result.output.split())
    assert "cam-driven: a disc cam (base radius 30 mm)" in flat
    assert "joint (1,2) prismatic: link 2 slides along its guide at 90°" in flat
    assert "kinetostatics" in flat


def test_dyade_cam_on_the_mechanism_agrees_with_analyse(analysed):
    result = run("cam", EXAMPLE, "--format", "json")
    assert result.exit_code == 0, result.output
    checks = json.loads(result.stdout)
    theta = np.array(checks["columns"]["angle_deg"], dtype=float)
    every = np.array(analysed["columns"]["angle_deg"], dtype=float)
    assert np.array_equal(theta[::6], every[:-1])  # the sweep's own angles, every 6°
    mine = np.array(analysed["columns"]["F_cam"], dtype=float)[:-1]
    theirs = np.array(checks["columns"]["contact_force"], dtype=float)[::6]
    assert np.allclose(mine, theirs, rtol=1e-12)


@pytest.mark.slow  # (0.8 s: the study's probe and two direct runs)
def test_a_study_over_a_cam_key_equals_direct_runs():
    spec = dyade.study.parse({"mechanism": EXAMPLE, "set": {"sweep.step": 10},
                              "parameters": {"cam.base_radius": [28, 34]}})
    table = dyade.study(spec).columns()
    for k, radius in enumerate((28, 34)):
        alone = dyade.run("sweep", dyade.read_mechanism(
            EXAMPLE, {"cam.base_radius": radius, "sweep.step": 10}))
        for name in ("M_drive_rms", "F_cam_min", "F_cam_max"):
            assert table[name][k] == pytest.approx(alone.summary[name].value, rel=1e-12), name


@pytest.mark.parametrize("change, key, fix", [
    ({"crank": {"length": 20, "speed_rpm": 100}}, "`crank`", "leave out [crank]"),
    ({"servo": {"ratio": 2}}, "`servo`", "keep one of the two"),
    ({"follower.mass": 0.5}, "`follower.mass`", "give `links.2.mass`"),
    ({"cam.centre": [0, 0, 0]}, "`cam.centre`", "the cam centre [x, y]"),
])
def test_a_cam_that_does_not_fit_the_chain_is_refused(change, key, fix):
    with pytest.raises(InputError) as caught:
        dyade.read_mechanism(EXAMPLE, change)
    assert key in str(caught.value) and fix in str(caught.value)
    name, value = next(iter(change.items()))
    if name not in ("crank", "servo"):  # (a whole table is no --set value)
        result = run("analyse", EXAMPLE, "--set", f"{name}={json.dumps(value)}")
        assert result.exit_code == 2 and key in result.output


def test_an_oscillating_follower_in_a_mechanism_file_is_the_cam_files_chain():
    """cam-linkage.toml's lever (a cam file's [chain]) written as a mechanism file's
    [cam]: link 2 the lever about its pivot 90 mm along `direction = 0` from the cam
    centre; the same contact force and cam torque by both ways in."""
    import tomllib

    from dyade.cam import checks
    from dyade.files.cam import read_cam

    with open("mechanisms/cams/lever-slider.toml", "rb") as handle:
        data = tomllib.load(handle)
    with open("mechanisms/cams/cam-linkage.toml", "rb") as handle:
        cam = tomllib.load(handle)
    del data["crank"], data["frame"]
    data["cam"] = {key: value for key, value in cam["cam"].items()} | {"centre": [0, 0],
                                                                      "direction": 0}
    data["follower"], data["profile"] = cam["follower"], cam["profile"]
    data["sweep"] = {"step": 15}
    mechanism = dyade.build_mechanism(data, "mechanisms/cams/lever-in-file.toml")
    assert not mechanism.crank.sliding and mechanism.crank.pivot == pytest.approx((0.09, 0.0))
    swept = dyade.run("sweep", mechanism).columns
    alone = checks.check(read_cam("mechanisms/cams/cam-linkage.toml"), np.radians(15.0),
                         make=False)
    scale = np.max(np.abs(alone.drive_torque))
    assert np.allclose(np.asarray(swept["M_drive"])[:-1], alone.drive_torque, rtol=0,
                       atol=1e-12 * scale)
    assert np.allclose(np.asarray(swept["F_cam"])[:-1], alone.contact_force, rtol=1e-12)


def test_where_the_follower_lifts_off_no_force_is_given():
    """Above the lift-off speed a spring-closed follower would need a pull: those cam
    angles are withheld with a note, the same angles `dyade cam` finds lifted."""
    fast = dyade.read_mechanism(EXAMPLE, {"cam.speed_rpm": 900, "sweep.step": 10})
    outcome = dyade.run("sweep", fast)
    contact = np.asarray(outcome.columns["F_cam"], dtype=float)[:-1]
    checked = dyade.run("cam", EXAMPLE, speed_rpm=900, step_deg=10)
    lifted = np.asarray(checked.columns["contact_force"], dtype=float)
    assert np.isnan(lifted).any() and np.array_equal(np.isnan(contact), np.isnan(lifted))
    said = [note for note in outcome.notes if "lifts off at cam angles" in note]
    assert said and "at 900 rpm" in said[0]
