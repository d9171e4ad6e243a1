"""Batch runs and scripting through the CLI: many files, --set, --save-as, init,
formats, plain piped output, atomic writes."""

from __future__ import annotations

import csv
import io
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner
from rich.table import Table

from dyade.cli import main, output
from dyade.report import csv_rows
from tests.conftest import SHIPPED
from tests.helpers import ROOT, read_csv, shipped

BOX = set("─│┌┐└┘├┤┬┴┼━┃┏┓┗┛┣┫┳┻╋╇┡┩╭╮╰╯═║")


def run(*args, **kwargs):
    return CliRunner(**kwargs).invoke(main, [str(a) for a in args], catch_exceptions=False)


def test_batch_writes_one_csv_per_file_and_reports_the_broken_one(tmp_path):
    broken = tmp_path / "broken.toml"
    broken.write_text('name = "broken"\n[crank]\nlength = 1\n')
    out_dir = tmp_path / "out"
    result = run("analyse", *SHIPPED, broken, "-o", out_dir)
    assert result.exit_code == 1
    assert f"1 of {len(SHIPPED) + 1} files failed" in result.output
    assert "broken.toml: `crank.speed_rpm` is missing." in result.output
    written = sorted(p.name for p in out_dir.iterdir())
    assert written == sorted(f"{p.stem}.csv" for p in SHIPPED)
    for path in SHIPPED:  # each equals the single-file run
        single = run("analyse", path, "--format", "csv").stdout
        assert (out_dir / f"{path.stem}.csv").read_text() == single


def test_batch_needs_a_directory(tmp_path):
    result = run("analyse", shipped("fourbar.toml"), shipped("slider-crank.toml"))
    assert result.exit_code == 2 and "need -o DIR" in result.output


def test_set_overrides_nested_keys_like_the_file():
    base = read_csv(run("analyse", shipped("fourbar.toml"), "--format", "csv").stdout)
    faster = read_csv(run("analyse", shipped("fourbar.toml"), "--format", "csv",
                          "--set", "crank.speed_rpm=600").stdout)
    assert np.allclose(faster["omega_3"], 2 * base["omega_3"])
    assert np.allclose(faster["alpha_3"], 4 * base["alpha_3"])
    longer = read_csv(run("analyse", shipped("fourbar.toml"), "--format", "csv",
                          "--set", "dyad.2.lengths=[210, 150]").stdout)
    assert not np.allclose(longer["x_3_4"], base["x_3_4"])


@pytest.mark.parametrize("assignment, message", [
    ("crank.speed_rpm=fast", "`crank.speed_rpm` must be a number [rpm], got \"fast\""),
    ("dyad.2.lengths=[200, -1]", "`dyad.2.lengths.2` must be positive [mm], got -1"),
    ("dyad.3.variant=1", "--set dyad.3.variant: the entries of `dyad` are numbered 2…2, got 3 (dyads are numbered as in DYADE"),
    ("dyad.2.varient=1", "unknown key `dyad.2.varient`. Did you mean `variant`?"),
    ("speed", "expected KEY=VALUE"),
])
def test_set_with_a_bad_value_is_a_clear_error(assignment, message):
    result = run("analyse", shipped("fourbar.toml"), "--set", assignment)
    assert result.exit_code == 2
    assert message in result.output


def test_save_as_round_trip(tmp_path):
    saved = tmp_path / "variant.toml"
    first = run("analyse", shipped("dyade-16.toml"), "--format", "csv", "--set",
                "crank.speed_rpm=450", "--set", "links.3.mass=1.5", "--save-as", saved)
    assert first.exit_code == 0 and saved.exists()
    again = run("analyse", saved, "--format", "csv")
    assert again.stdout == first.stdout  # identical results, digit for digit


def test_init_files_analyse_as_written(tmp_path):
    for kind in ("fourbar", "slider-crank", "slotted-lever", "tangent-drive", "scotch-yoke", "PPR"):
        path = tmp_path / f"{kind}.toml"
        assert run("init", kind, path).exit_code == 0
        result = run("analyse", path, "--format", "csv")
        assert result.exit_code == 0, (kind, result.output)
        assert "M_drive" in result.stdout.splitlines()[0]
    again = run("init", "fourbar", tmp_path / "fourbar.toml")
    assert again.exit_code == 2 and "--force" in again.output


def test_json_has_the_csv_names_summary_and_warnings():
    text = run("analyse", shipped("self-locking.toml"), "--format", "json").stdout
    obj = json.loads(text)
    names = run("analyse", shipped("self-locking.toml"), "--format", "csv").stdout.splitlines()[0]
    for name in names.split(","):
        assert name in obj["columns"] and len(obj["columns"][name]) == 361
    assert obj["summary"]["locks_1_4"] == {"value": True, "unit": "-"}
    assert any("locks" in note for note in obj["notes"])
    clearance = json.loads(run("clearance", "--mass", 3.6, "--stiffness", 1e7, "--clearance",
                               1e-4, "--slope", 360000, "--format", "json").stdout)
    assert clearance["columns"]["F_max"][0] == pytest.approx(2181.89, abs=0.01)
    coupling = json.loads(run("coupling", "--J", 1, "--c1", 1, "--c2", 1, "--eta-range",
                              "0:2:0.70710678118654752", "--format", "json").stdout)
    assert coupling["columns"]["V_phi"][1] is None
    assert coupling["summary"]["eta0"]["value"] == pytest.approx(2 ** -0.5)


@pytest.mark.parametrize("args", [
    ["analyse", shipped("dyade-16.toml")],
    ["analyse", shipped("dyade-16.toml"), "--all"],
    ["describe", shipped("dyade-16.toml")],
    ["clearance", shipped("dyade-16.toml")],
    ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--b1", "0.1"],
    ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope", "3.6e5"],
])
def test_piped_output_is_plain(args):
    result = run(*args)
    assert result.exit_code == 0, result.output
    text = result.stdout
    assert "\x1b[" not in text
    assert not (set(text) & BOX), sorted(set(text) & BOX)


class FakeTerminal(io.StringIO):
    """A stream that says it is a terminal (under pytest stdout never is)."""

    def isatty(self) -> bool:
        return True


def _table() -> Table:
    table = Table("quantity", "value")
    table.add_row("omega_3", "12.5")
    return table


def test_no_color_is_plain_on_a_terminal(monkeypatch):
    monkeypatch.delenv("NO_COLOR", raising=False)
    assert not output.plain(FakeTerminal())
    monkeypatch.setenv("NO_COLOR", "1")
    assert output.plain(FakeTerminal())


def test_a_terminal_gets_boxes_and_colour(monkeypatch):
    # the counter-check of the plain-output tests: the same table on a terminal is boxed
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TERM", "xterm-256color")
    tty = FakeTerminal()
    output.console(file=tty).print(_table())
    text = tty.getvalue()
    assert set(text) & BOX and "\x1b[" in text, repr(text)


def test_no_color_makes_shown_tables_plain_on_a_terminal(monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    monkeypatch.setenv("TERM", "xterm-256color")
    tty = FakeTerminal()
    monkeypatch.setattr(sys, "stdout", tty)
    output.show([_table()])
    text = tty.getvalue()
    assert "omega_3" in text and "12.5" in text
    assert "\x1b[" not in text and not set(text) & BOX, repr(text)


def test_piped_output_of_the_real_command_is_plain():
    # a user's shell: a colour terminal, no NO_COLOR; only stdout is a pipe
    env = {k: v for k, v in os.environ.items() if k != "NO_COLOR"} | {"TERM": "xterm-256color"}
    run = subprocess.run([sys.executable, "-m", "dyade", "analyse", str(shipped("dyade-16.toml")),
                          "--all"],
                         capture_output=True, text=True, encoding="utf-8", env=env, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert "omega_3" in run.stdout
    assert "\x1b[" not in run.stdout
    assert not set(run.stdout) & BOX, sorted(set(run.stdout) & BOX)


def test_interrupted_write_leaves_no_partial_file(tmp_path, monkeypatch):
    target = tmp_path / "result.csv"

    def explode(writer, block):
        writer.out.write("half a line")
        raise KeyboardInterrupt

    monkeypatch.setattr(csv_rows.Writer, "rows", explode)  # streamed or whole
    result = run("analyse", shipped("fourbar.toml"), "-o", target)
    assert result.exit_code == 130 and "Interrupted." in result.output  # Ctrl-C: 128 + SIGINT
    assert list(tmp_path.iterdir()) == []  # neither the result nor its temporary file


def test_failed_analysis_leaves_the_old_result_untouched(tmp_path):
    target = tmp_path / "result.csv"
    target.write_text("previous result\n")
    bad = tmp_path / "bad.toml"
    bad.write_text(shipped("fourbar.toml").read_text().replace("lengths = [200, 150]",
                                                                "lengths = [200, 60]"))
    result = run("analyse", bad, "-o", target)  # a bug would raise here, not exit 1
    assert result.exit_code == 1
    assert "dyad 2 (kind 1 RRR, links 3-4) cannot close" in " ".join(result.output.split())
    assert target.read_text() == "previous result\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml", "result.csv"]


def test_clearance_over_files(tmp_path):
    out_dir = tmp_path / "peaks"
    result = run("clearance", shipped("dyade-16.toml"), shipped("slider-crank.toml"),
                 "--stiffness", "1e8", "--clearance", "1e-4", "--format", "csv", "-o", out_dir)
    assert result.exit_code == 0
    rows = list(csv.DictReader(io.StringIO((out_dir / "dyade-16.csv").read_text())))
    assert rows and all(float(r["F_max"]) > 0 for r in rows)
    assert (out_dir / "slider-crank.csv").exists()


def test_stable_column_order():
    first = run("analyse", shipped("watt-sixbar.toml"), "--format", "csv").stdout.splitlines()[0]
    second = run("analyse", shipped("watt-sixbar.toml"), "--format", "csv").stdout.splitlines()[0]
    assert first == second and first.startswith("angle_deg,phi_2_deg,omega_2,alpha_2,phi_3_deg")
