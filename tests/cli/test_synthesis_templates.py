"""`dyade init` writes a synthesis template for every target, each valid TOML whose
comments teach its keys and units and which `dyade synthesise` runs as written; every
target estimates its time before the work, so that `--max-time` refuses an over-long run
(exit 2, the estimate named) before it starts."""

from __future__ import annotations

import json
import re
import tomllib

import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.cli.init import TEMPLATES
from dyade.errors import InputError

KINDS = sorted(k for k in TEMPLATES if k.startswith("synthesis"))
CHEAP = {"synthesis-function", "synthesis-slider"}
"""the templates run in the default suite (the rest, up to a few seconds each, are slow;
`synthesis`, the closed coupler curve, runs as docs/guide/synthesis.md shows it in
tests/test_readme.py)"""


def written(tmp_path, kind: str):
    path = tmp_path / f"{kind}.toml"
    out = CliRunner().invoke(main, ["init", kind, str(path)])
    assert out.exit_code == 0, out.output
    assert "dyade synthesise" in out.output
    return path


def test_there_is_a_template_for_every_target_and_topology_kind():
    targets = set()
    for kind in KINDS:
        data = tomllib.loads(TEMPLATES_TEXT[kind])
        targets.add((data["target"]["kind"], data.get("topology", "fourbar")))
    assert {"function", "path", "line", "poses"} <= {t for t, _ in targets}
    assert {"fourbar", "slider-crank", "stephenson-sixbar"} <= {t for _, t in targets}
    assert ("function", "stephenson-sixbar") in targets
    assert ("poses", "stephenson-sixbar") in targets


TEMPLATES_TEXT = {kind: CliRunner().invoke(main, ["init", kind, "-"]).output
                  for kind in KINDS}


@pytest.mark.parametrize("kind", KINDS)
def test_each_template_teaches_its_keys_and_units(kind):
    text = TEMPLATES_TEXT[kind]
    data = tomllib.loads(text)  # valid TOML
    assert data["units"] == {"length": "mm", "angle": "deg"}
    assert text.count("#") >= 8 and "dyade synthesise THIS_FILE" in text
    assert "[deg]" in text or "[mm]" in text  # the units where the numbers are


@pytest.mark.parametrize("kind", KINDS)
def test_a_tiny_max_time_refuses_every_target_before_the_work(tmp_path, kind):
    path = written(tmp_path, kind)
    out = CliRunner().invoke(main, ["synthesise", str(path), "--max-time", "1e-6"])
    assert out.exit_code == 2, out.output
    assert "--max-time is 1e-06 s" in out.output and "would take about" in out.output
    assert "Traceback" not in out.output
    heard = []  # the API: refused before any candidate is traced
    with pytest.raises(InputError, match="would take about"):
        dyade.run("synthesis", str(path), max_time_s=1e-6,
                  progress=lambda done, total: heard.append(done))
    assert heard == []


@pytest.mark.parametrize("kind", [kind if kind in CHEAP else
                                  pytest.param(kind, marks=pytest.mark.slow)
                                  for kind in KINDS if kind != "synthesis"])
def test_every_template_runs_as_written(tmp_path, kind):
    path = written(tmp_path, kind)
    out = CliRunner().invoke(main, ["synthesise", str(path), "--max-time", "60",
                                    "--write", str(tmp_path / "designs")])
    assert out.exit_code == 0, out.output
    assert "nan" not in out.output and "Traceback" not in out.output
    analysed = CliRunner().invoke(main, ["analyse", str(tmp_path / "designs" /
                                                         "design-1.toml"), "--format", "json",
                                         "-o", str(tmp_path / "a.json")])
    assert analysed.exit_code == 0, analysed.output
    least = tomllib.loads(TEMPLATES_TEXT[kind]).get("search", {}).get("min_transmission")
    if least is not None:  # the design obeys the file's limit through dyade's engine
        summary = json.loads((tmp_path / "a.json").read_text(encoding="utf-8"))["summary"]
        angles = [v["value"] for k, v in summary.items() if re.fullmatch(r"mu_\d+_min_deg", k)]
        assert len(angles) == (2 if "sixbar" in kind else 1) and min(angles) >= least
