"""``dyade gears``: the issue's "done when" commands and the outputs' contracts."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import shipped

FRISWELL = str(shipped("gears/friswell-geared.toml"))
TWO_STAGE = str(shipped("gears/two-stage.toml"))


def read_csv(text: str) -> dict[str, np.ndarray]:
    """Columns of numbers as float arrays (empty fields NaN), text columns as lists."""
    rows = list(csv.DictReader(io.StringIO(text)))
    out = {}
    for name in rows[0]:
        values = [row[name] for row in rows]
        try:
            out[name] = np.array([float(v) if v else np.nan for v in values])
        except ValueError:
            out[name] = values
    return out


def _run(*args):
    run = CliRunner().invoke(main, ["gears", *args], catch_exceptions=False)
    assert run.exit_code == 0, run.output
    return run


def test_friswell_csv_has_the_three_frequencies():
    cols = read_csv(_run(FRISWELL, "--format", "csv").stdout)
    assert np.round(cols["f_Hz"], 1).tolist() == [425.4, 634.1, 3247.2]
    assert np.allclose(cols["U_torsion"], 1.0)


def test_two_stage_prints_modes_with_energy_shares():
    run = _run(TWO_STAGE)
    assert "Natural frequencies" in run.stdout and "energy shares" in run.stdout
    for head in ("T tors", "U lat", "dominant (strain)", "F stage1", "F stage2"):
        assert head in run.stdout
    assert "1 rigid-body mode" in run.stderr
    cols = read_csv(_run(TWO_STAGE, "--format", "csv").stdout)
    modes = dyade.gear_modes(dyade.read_gears(TWO_STAGE))
    assert np.allclose(cols["f_Hz"], modes.frequencies, rtol=1e-14)
    shares = sum(cols[c] for c in cols if c.startswith("U_") and c.count("_") >= 2)
    assert cols["dominant"][0] == "output torsion"
    assert np.allclose(shares, 1.0)  # U_<owner>_<motion> add up to the whole


def test_mode_shapes():
    cols = read_csv(_run(TWO_STAGE, "--modes", "2", "--format", "csv").stdout)
    shapes = [name for name in cols if name.endswith(("_ux", "_uy", "_uz", "_rx", "_ry", "_rz"))]
    assert len(shapes) == 6 * 9  # 6 bodies + 3 shaft segments, six coordinates each
    assert cols["motor_rx"].size == 51  # one row per elastic mode ...
    values = np.array([cols[name] for name in shapes])
    assert np.all(np.isfinite(values[:, :2])) and np.all(np.isnan(values[:, 2:]))  # ... 2 shapes
    # M-orthonormal: φᵀMφ = 1 with the bodies' masses and inertias
    modes = dyade.gear_modes(dyade.read_gears(TWO_STAGE))
    phi = values[:, :2]
    assert np.allclose(phi.T @ (modes.system.mass[:, None] * phi), np.eye(2), atol=1e-9)


def test_campbell_resonances_lie_on_their_lines():
    _run(TWO_STAGE, "--campbell", "0:3000:10")
    text = _run(TWO_STAGE, "--campbell", "0:3000:10", "--format", "json").stdout
    data = json.loads(text)
    assert list(data) == ["columns", "units", "summary", "notes", "analysis", "options", "meta",
                          "schema"]  # one shape
    assert data["analysis"] == "gear-campbell"
    summary = {name: figure["value"] for name, figure in data["summary"].items()}
    slope = dict(zip(summary["lines"], summary["line_slopes"]))
    offset = dict(zip(summary["lines"], summary["line_offsets"]))
    resonances = data["columns"]
    assert len(resonances["speed_rpm"]) == summary["resonances"] > 10
    for speed, f, order in zip(resonances["speed_rpm"], resonances["f_Hz"], resonances["order"]):
        assert 0 <= speed <= 3000
        assert abs(offset[order] + slope[order] * speed - f) < 1e-9 * f  # on its line
        assert f in summary["natural_frequencies"]
    # the first stage's tooth-mesh line: 20 teeth at the motor's speed
    assert slope["stage1 ×1"] == pytest.approx(20 / 60) and offset["stage1 ×1"] == 0
    assert slope["stage2 ×1"] == pytest.approx(20 / 3 / 60)


def test_response_and_check_run():
    run = _run(TWO_STAGE, "--response", "10:1000:1", "--format", "csv")
    cols = read_csv(run.stdout)
    assert cols["f_Hz"].size == 991 and np.all(np.isfinite(cols["F_stage1_N"]))
    _run(TWO_STAGE, "--response", "10:1000:1")
    run = _run(TWO_STAGE, "--check", "--format", "json")
    data = json.loads(run.stdout)
    summary = {name: figure["value"] for name, figure in data["summary"].items()}
    assert summary["extra_zeros"] == summary["ideal_meshes"] == 2 and summary["rigid_zeros"] == 1
    assert summary["largest_rel_diff"] < 1e-9
    assert max(data["columns"]["rel_diff"]) == summary["largest_rel_diff"]
    assert "one per mesh" in _run(TWO_STAGE, "--check").stdout


def test_output_file_and_set(tmp_path):
    out = tmp_path / "modes.csv"
    _run(TWO_STAGE, "--set", "shaft.1.segments=4", "--format", "csv", "-o", str(out))
    cols = read_csv(out.read_text())
    assert cols["f_Hz"].size == 51 + 3 * 6  # three more segments on the input shaft
