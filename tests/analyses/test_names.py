"""One set of names (issue 36): every output of a study is a figure of the sweep's
summary, of the same name and value, on the shipped four-bar and dyade-16; a study file
that names an output by its old name (an old study output, a key of the former nested
JSON summary) is refused, naming the new one; docs/reference/json.md's table of old and
new names is the code's."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.linkage.summary import renamed
from tests.helpers import shipped
from tests.study.test_study import FRICTION, study_file

ROOT = Path(__file__).resolve().parents[2]


def same(a, b) -> bool:
    """Equal values, to the bit; a missing one (NaN in a study, None in a summary) as
    missing."""
    missing = (a is None or (isinstance(a, float) and math.isnan(a)),
               b is None or (isinstance(b, float) and math.isnan(b)))
    if any(missing):
        return all(missing)
    return a == b


@pytest.mark.parametrize("mechanism, parameters, fixed, stacked", [
    # numbers of the file: the variants run together (pipeline.prepare_variants)
    ("fourbar.toml", {"dyad.2.lengths.1": "[190, 205]", "links.4.mass": "[0.8, 1.1]"}, None,
     True),
    ("dyade-16.toml", {"dyad.2.lengths.2": "[145, 155]"}, None, True),
    # with friction each variant is swept alone (dyade.analyse), as `dyade analyse` does
    ("dyade-16.toml", {"dyad.2.lengths.2": "[145, 155]"}, FRICTION, False),
    ("fourbar.toml", {"crank.speed_rpm": "[200, 300]"}, FRICTION, False),
])
def test_every_study_output_is_a_summary_figure_of_the_same_name_and_value(
        tmp_path, mechanism, parameters, fixed, stacked):
    from dyade.study import plans
    from dyade.study import run as study_run

    path = study_file(tmp_path, mechanism, parameters, fixed=fixed)
    spec = dyade.study.read(path)
    evaluator = study_run.evaluator_for(spec)
    matrix = plans.variants(spec)
    rows = evaluator((0, matrix))
    assert evaluator.together == (len(matrix) if stacked else 0)  # the path under test
    result = dyade.study(path)
    assert "F_shake_max" in result.outputs and "F_shake_rms" in result.outputs
    for (_, status, _, outputs), values in zip(rows, matrix):
        assert status == "ok"
        overrides = {**(fixed or {}), **dict(zip((p.key for p in spec.parameters), values))}
        summary = dyade.run("sweep", str(shipped(mechanism)),
                            set=tuple(f"{k}={v}" for k, v in overrides.items())).summary
        assert set(outputs) == set(result.outputs)
        for name, value in outputs.items():  # the same name, the same value: to the bit
            assert name in summary, name
            assert same(value, summary[name].value), (name, value, summary[name].value)
            assert result.units[name] == summary[name].unit, name


def test_a_studys_clearance_outputs_are_summary_figures(tmp_path):
    path = study_file(tmp_path, "dyade-16.toml", {"dyad.2.lengths.2": "[150]"},
                      extra="[outputs]\nextra = [\"clearance\"]\n")
    result = dyade.study(path)
    summary = dyade.run("sweep", str(shipped("dyade-16.toml")),
                        set=("dyad.2.lengths.2=150",)).summary
    for name in ("F_clearance_2_7_max", "amplification_2_7_max"):
        assert result.columns()[name][0] == summary[name].value
        assert summary[name].where["angle_deg"] in (0.0, 180.0)


@pytest.mark.parametrize("old, new", [
    ("drive.M_rms", "M_drive_rms"), ("drive.M_max", "M_drive_max"),
    ("joint_peaks[F_1_2].value", "F_1_2_peak"), ("joint_peaks.F_1_4", "F_1_4_peak"),
    ("transmission[2].min_deg", "mu_2_min_deg"), ("swings.4.swing_deg", "swing_4_deg"),
    ("M_shake_max", "M_shake_abs_max"), ("motion.speed_mean_rpm", "speed_mean_rpm"),
])
@pytest.mark.parametrize("where", ["minimise", "maximise", "bounds"])
def test_a_study_naming_an_old_output_is_refused_naming_the_new(tmp_path, old, new, where):
    table = (f'[optimise]\nminimise = "M_drive_rms"\n[optimise.bounds]\n"{old}" = [0, 5]\n'
             if where == "bounds" else f'[optimise]\n{where} = "{old}"\n')
    path = study_file(tmp_path, "fourbar.toml",
                      {"links.4.mass": "{ range = [0.8, 1.2], count = 3 }"},
                      'kind = "optimise"', extra=table)
    with pytest.raises(dyade.InputError, match=re.escape(f"'{old}', which is now '{new}'")):
        dyade.study.read(path)
    out = CliRunner().invoke(main, ["study", path])
    assert out.exit_code == 2 and f"which is now '{new}'" in out.output


def test_the_new_names_are_accepted(tmp_path):
    path = study_file(tmp_path, "fourbar.toml",
                      {"links.4.mass": "{ range = [0.8, 1.2], count = 3 }"},
                      'kind = "optimise"', extra='[optimise]\nminimise = "M_shake_abs_max"\n'
                                                 '[optimise.bounds]\nF_1_2_peak = [0, 500]\n')
    spec = dyade.study.read(path)
    assert spec.optimise["objectives"] == [("M_shake_abs_max", 1.0)]


def old_and_new() -> list[tuple[str, str]]:
    """The rows of docs/reference/json.md's table of old and new names: (old, new)."""
    text = (ROOT / "docs" / "reference" / "json.md").read_text(encoding="utf-8")
    table = text.split("## Old names and new", 1)[1]
    rows = re.findall(r"^\| `([^`]+)` \| `([^`]+)` \|", table, re.MULTILINE)
    assert len(rows) > 20
    return rows


SUMMARY_TABLES = ("transmission", "strokes", "swings", "columns", "drive.", "joint_peaks",
                  "friction.", "self_locking", "motion.")
"""the tables of the former nested summary, whose keys ``renamed`` maps"""


def test_the_docs_table_of_old_names_is_the_codes(tmp_path):
    from dyade.study.evaluate import RENAMED
    from tests.machine.test_machine import _drive_file

    (tmp_path / "asynchronous").mkdir()
    rows = old_and_new()
    friction = ("friction.coefficient=0.1", "friction.pin_radius=5",
                "friction.slider_length=40", "friction.slider_height=20")
    drive = str(_drive_file(tmp_path / "asynchronous", {
        "motor": "asynchronous", "rated_torque": 4.0, "rated_speed_rpm": 290,
        "synchronous_speed_rpm": 302}))
    (tmp_path / "constant").mkdir()
    constant = str(_drive_file(tmp_path / "constant", {"motor": "constant"}))
    names = set()
    for source, options in ((shipped("dyade-16.toml"), {"set": friction}),
                            (shipped("self-locking.toml"), {}), (drive, {}),
                            (drive, {"run_up": True}),
                            (constant, {})):
        names |= set(dyade.run("sweep", str(source), **options).summary)
    checked = 0
    for old, new in rows:
        if old.startswith(SUMMARY_TABLES) or old in RENAMED:
            assert (RENAMED.get(old) or renamed(old)) == new, (old, new)
            checked += 1
        if old.startswith(SUMMARY_TABLES) or old.startswith("clearance"):
            assert new in names, new
    assert checked > 30


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml"])
def test_every_figure_name_is_an_identifier_with_a_unit(name):
    for figure_name, figure in dyade.run("sweep", str(shipped(name))).summary.items():
        assert re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", figure_name)
        assert figure.unit
        # the unit is in Figure.unit, not in the name, but for _deg and _rpm
        assert not re.search(r"_(mm|m|s|N|W|Nm|rad)$", figure_name) or figure_name.endswith(
            ("_min", "_max")), figure_name
    assert np.isfinite(dyade.run("sweep", str(shipped(name))).summary["F_shake_rms"].value)
