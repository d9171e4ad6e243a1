"""``dyade synthesise``: tables, JSON, CSV, the mechanism files it writes, its figure,
its exit codes."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from dyade.cli import main

FUNCTION = """name = "Three precision points"
units = { length = "mm", angle = "deg" }
[target]
kind = "function"
crank = [40, 75, 110]
output = [70, 95, 128]
[scores]
frame = 100
speed_rpm = 120
mass_per_length = 2.0
"""


def test_function_generation_writes_files_that_dyade_analyses(tmp_path):
    path = tmp_path / "function.toml"
    path.write_text(FUNCTION, encoding="utf-8")
    runner = CliRunner()
    out = runner.invoke(main, ["synthesise", str(path), "--write", str(tmp_path / "designs")])
    assert out.exit_code == 0, out.output
    assert "Structural error at every row" in out.output and "design-1.toml" in out.output
    assert "nan" not in out.output and "True" not in out.output
    written = tmp_path / "designs" / "design-1.toml"
    analysed = runner.invoke(main, ["analyse", str(written), "--format", "json", "-o",
                                    str(tmp_path / "a.json")])
    assert analysed.exit_code == 0, analysed.output
    document = json.loads((tmp_path / "a.json").read_text(encoding="utf-8"))
    out = runner.invoke(main, ["synthesise", str(path), "--format", "json", "-o",
                               str(tmp_path / "s.json")])
    assert out.exit_code == 0, out.output
    synthesis = json.loads((tmp_path / "s.json").read_text(encoding="utf-8"))
    assert synthesis["units"]["error_deg"] == "°"
    assert max(abs(e) for e in synthesis["columns"]["error_deg"]) < 1e-12
    assert synthesis["summary"]["M_drive_rms"]["value"] == pytest.approx(
        document["summary"]["M_drive_rms"]["value"], rel=1e-12)


SHORT = ('[bounds]\nf = [0.01, 0.02]\ng = [0.01, 0.02]\n[search]\ncandidates = 200\n'
         'rounds = 1\n')
"""bounds no six-bar assembles with, and a short search"""


@pytest.mark.parametrize("text, code, words", [
    ('[target]\nkind = "function"\ncrank = [10, 20]\noutput = [1, 2]\n', 2, "at least three"),
    ('[target]\nkind = "path"\npoints = [[0, 0], [1, 0], [1, 1]]\n', 2, "at least 8"),
    ('[target]\nkind = "poses"\nposes = [[0, 0, 0], [1, 0, 10]]\n', 2, "three poses"),
    ('[target]\nkind = "line"\nstretch = 90\n[bounds]\na = [2, 3]\nb = [0.1, 0.2]\n'
     'c = [0.1, 0.2]\n[search]\ncandidates = 100\nrounds = 1\n', 2, "bounds"),
    ('[target]\nkind = "function"\ncrank = [0, 90, 180]\noutput = [0, 0, 0]\n'
     'method = "precision"\n', 1, "singular"),
    # six-bars whose second dyad (f, g ≪ its joints' distance) never closes: the bounds'
    ('topology = "stephenson-sixbar"\n[target]\nkind = "function"\n'
     'crank = [0, 15, 30, 45, 60, 75, 90, 105, 120]\noutput = [0, 1, 2, 3, 4, 5, 6, 7, 8]\n'
     + SHORT, 2, "none of the 200 Stephenson III six-bars drawn closes"),
    ('topology = "watt1-sixbar"\n[target]\nkind = "poses"\n'
     'poses = [[0, 0, 0], [1, 0, 10], [1, 1, 20]]\n' + SHORT, 2,
     "none of the 200 Watt I six-bars drawn turns its crank fully"),
    ('topology = "watt-sixbar"\n[target]\nkind = "poses"\nposes = [[0, 0, 0], [1, 0, 10]]\n',
     2, "3 to 7 poses"),
])
def test_bad_input_exits_with_its_code_and_no_traceback(tmp_path, text, code, words):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    out = CliRunner().invoke(main, ["synthesise", str(path)])
    assert out.exit_code == code, out.output
    assert words in out.output and "Traceback" not in out.output


@pytest.mark.slow
def test_poses_no_six_bar_reaches_exit_1_with_the_best_error_and_why(tmp_path):
    path = tmp_path / "seven.toml"
    path.write_text('topology = "stephenson-sixbar"\n[target]\nkind = "poses"\nposes = [\n'
                    '[0, 0, 0], [1, 0, 90], [0, 1, 180], [-1, 0, 270], [0, -1, 0],\n'
                    '[0.5, 0.5, 45], [-0.5, 0.2, 200]]\n[search]\ncandidates = 200\n'
                    'rounds = 1\n', encoding="utf-8")
    out = CliRunner().invoke(main, ["synthesise", str(path)])
    assert out.exit_code == 1, out.output
    assert "misses them by" in out.output and "21 equations for its 22 unknowns" in out.output


# `dyade init synthesis`, `dyade synthesise --write --plot` and `dyade analyse` of its
# design run as docs/guide/synthesis.md shows them (tests/test_readme.py, slow).
