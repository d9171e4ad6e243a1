"""The validity policy (issue 14): a per-position quality of each dyad from its own
geometry, a hard band where nothing is given, a soft band with a warning, and a
plausibility bound; no number poses as valid that is not."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import read_csv, shipped

SLOTTED = shipped("slotted-lever.toml").read_text()


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def test_the_quality_of_a_dyad_does_not_depend_on_the_sweep():
    """The RPR dyad's dead-centre test used to measure its lever arm against the largest
    pivot distance over the sweep: the same position was good or bad with --start."""
    mechanism = dyade.read_mechanism(shipped("slotted-lever.toml"))
    whole = dyade.analyse(mechanism)
    part = dyade.analyse(mechanism, start_deg=80.0, stop_deg=100.0)
    at = np.flatnonzero(np.isclose(np.rad2deg(whole.crank_angle), 90.0))[0]
    assert part.kinematics.conditioning[10, 0] == whole.kinematics.conditioning[at, 0]
    # independently: sin μ = lever arm / pivot distance, and the distance ≥ the crank
    c = whole.columns()
    assert np.all(whole.kinematics.conditioning[:, 0] == pytest.approx(
        np.abs(np.sin(np.deg2rad(c["mu_2_deg"]))), abs=1e-12))


def test_an_exact_rpr_dead_centre_is_a_dead_centre_not_a_failure(tmp_path):
    """Pivot distance d = 150, crank r = 60, slot offset 90 = d − r: at 270° the block
    passes the lever's foot point exactly (lever arm 0)."""
    path = tmp_path / "lever.toml"
    path.write_text(SLOTTED.replace("B = { guide = 4, offset = 0 }", "B = { guide = 4, offset = 90 }"))
    result = run("analyse", path, "--format", "csv")
    assert result.exit_code == 0, result.output
    assert "cannot close" not in result.output
    assert "within 2° of a dead centre" in result.stderr and "269.0°–271.0°" in result.stderr
    cols = read_csv(result.stdout)
    row = np.flatnonzero(cols["angle_deg"] == 270.0)[0]
    assert cols["kinematics_valid"][row] == 0 and np.isnan(cols["omega_4"][row])
    assert cols["mu_2_deg"][row] == pytest.approx(0.0, abs=1e-6)  # the angle is still shown


def test_the_soft_band_warns_with_the_smallest_transmission_angle():
    result = run("analyse", shipped("dyade-16.toml"), "--format", "csv")
    assert ("dyad 7 (kind 1 RRR, links 13-14) has a transmission angle below 40°"
            in result.stderr)
    assert "29.5° at the least (crank angle 162.0°): results are given" in result.stderr
    cols = read_csv(result.stdout)
    assert np.all(cols["kinematics_valid"] == 1)  # warned, not withheld
    quiet = run("analyse", shipped("dyade-16.toml"), "--format", "csv",
                "--transmission-warning", "25")
    assert "transmission angle below" not in quiet.stderr


def test_a_wider_hard_band_withholds_more_rows_everywhere():
    narrow = read_csv(run("analyse", shipped("dyade-16.toml"), "--format", "csv").stdout)
    wide_run = run("analyse", shipped("dyade-16.toml"), "--format", "csv", "--dead-centre",
                   "31", "--transmission-warning", "45")
    wide = read_csv(wide_run.stdout)
    withheld = wide["kinematics_valid"] == 0
    mu = wide["mu_8_deg"]
    assert withheld.any() and np.all(narrow["kinematics_valid"] == 1)
    # exactly the rows where some dyad is within 31° of a dead centre
    near = np.zeros_like(withheld)
    for name, values in wide.items():
        if name.startswith("mu_"):
            near |= np.minimum(values, 180 - values) <= 31
    assert np.array_equal(withheld, near)
    for name, values in wide.items():
        if name not in ("angle_deg", "kinematics_valid", "forces_valid") and not name.startswith("mu_"):
            assert np.all(np.isnan(values[withheld])), name
    assert np.isfinite(mu[withheld]).all()
    obj = json.loads(run("analyse", shipped("dyade-16.toml"), "--format", "json",
                         "--dead-centre", "31", "--transmission-warning", "45").stdout)
    k = int(np.flatnonzero(withheld)[0])
    assert obj["columns"]["omega_3"][k] is None and obj["columns"]["M_drive"][k] is None
    valid = wide["omega_3"][~withheld]
    assert obj["summary"]["omega_3_max"]["value"] == pytest.approx(np.max(valid), rel=1e-14)


def test_values_beyond_the_plausibility_bound_are_not_given():
    fast = dyade.read_mechanism(shipped("fourbar.toml"), overrides={"crank.speed_rpm": 1e8})
    result = dyade.analyse(fast)
    cols = result.columns()
    assert not result.valid.any() and np.all(cols["kinematics_valid"] == 0)
    assert any(note.kind == "implausible" for note in result.notes)
    for name, values in cols.items():
        if name not in ("angle_deg", "kinematics_valid", "forces_valid") and not name.startswith("mu_"):
            assert not np.isfinite(values).any(), name
    ordinary = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")))
    assert ordinary.valid.all()
