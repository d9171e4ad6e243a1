"""Everyday use (issue 19): what a new user stumbles on, one CLI test per item."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest
from click.testing import CliRunner

from dyade.cli import main
from tests.helpers import ROOT, read_csv, shipped


def run(*args, input=None):
    return CliRunner().invoke(main, [str(a) for a in args], input=input, catch_exceptions=False)


# -- 1. standard input and output ------------------------------------------------------
def test_dash_reads_the_mechanism_from_stdin_and_writes_to_stdout(tmp_path):
    text = shipped("slider-crank.toml").read_text()
    piped = run("analyse", "-", "--format", "csv", "-o", "-", input=text)
    from_file = run("analyse", shipped("slider-crank.toml"), "--format", "csv")
    assert piped.exit_code == 0 and piped.stdout == from_file.stdout
    bad = run("analyse", "-", input=text.replace("speed_rpm", "speed_rmp"))
    assert bad.exit_code == 2 and "<stdin>: unknown key `crank.speed_rmp`" in bad.output


def test_init_dash_prints_the_template():
    printed = run("init", "slider-crank", "-")
    assert printed.exit_code == 0 and "[[dyad]]" in printed.stdout
    analysed = run("analyse", "-", "--format", "csv", input=printed.stdout)
    assert analysed.exit_code == 0 and analysed.stdout.startswith("angle_deg,")


# -- 10. formats and signals -----------------------------------------------------------
@pytest.mark.parametrize("name", ["x.parquet", "x.xlsx", "x.CSV2"])
def test_an_unknown_output_suffix_lists_the_formats(tmp_path, name):
    result = run("analyse", shipped("fourbar.toml"), "-o", tmp_path / name)
    assert result.exit_code == 2
    assert "writes .csv" in result.output and ".json" in result.output and ".txt" in result.output
    assert not (tmp_path / name).exists()


def test_a_known_suffix_or_an_explicit_format_writes(tmp_path):
    assert run("analyse", shipped("fourbar.toml"), "-o", tmp_path / "a.json").exit_code == 0
    json.loads((tmp_path / "a.json").read_text())
    assert run("analyse", shipped("fourbar.toml"), "-o", tmp_path / "a.dat", "--format",
               "csv").exit_code == 0
    assert (tmp_path / "a.dat").read_text().startswith("angle_deg,")


def test_ctrl_c_exits_130_without_a_traceback():
    """A real SIGINT to a real process, in the middle of a long sweep."""
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    process = subprocess.Popen([sys.executable, "-m", "dyade", "analyse",
                                str(shipped("fourbar.toml")), "--step", "0.0005", "--format",
                                "csv", "-o", os.devnull], cwd=ROOT, env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)  # well inside the run: interpreter, imports and sweep start
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 130, (process.returncode, err)
    assert "Traceback" not in err and "Interrupted." in err


def test_save_as_keeps_the_file_layout_and_comments(tmp_path):
    source = shipped("fourbar.toml").read_text()
    saved = tmp_path / "long.toml"
    result = run("analyse", shipped("fourbar.toml"), "--set", "dyad.2.lengths=[210, 150]",
                 "--set", "crank.speed_rpm=600", "--save-as", saved, "--format", "csv")
    assert result.exit_code == 0
    text = saved.read_text()
    body = text.split("\n", 1)[1]  # after dyade's own header line
    changed = [(a, b) for a, b in zip(source.splitlines(), body.splitlines()) if a != b]
    assert len(source.splitlines()) == len(body.splitlines())
    assert changed == [("speed_rpm = 300", "speed_rpm = 600"),
                       ("lengths = [200, 150]              # |AB| coupler, |B0B| rocker",
                        "lengths = [210, 150]              # |AB| coupler, |B0B| rocker")]
    again = run("analyse", saved, "--format", "csv")
    assert again.stdout == result.stdout


# -- 5. one numbering of dyads ----------------------------------------------------------
def test_keys_messages_and_columns_count_dyads_alike(tmp_path):
    """The first [[dyad]] table is dyad 2 in --set keys, file errors, messages and the
    mu_2_deg column; dyad 1 is the crank."""
    short = run("analyse", shipped("fourbar.toml"), "--set", "dyad.2.lengths=[200, 60]")
    assert short.exit_code == 1 and "dyad 2 (kind 1 RRR, links 3-4) cannot close" in short.output
    bad = run("analyse", shipped("fourbar.toml"), "--set", "dyad.2.lengths=[200, -60]")
    assert bad.exit_code == 2 and "`dyad.2.lengths.2` must be positive" in bad.output
    crank = run("analyse", shipped("fourbar.toml"), "--set", "dyad.1.variant=-1")
    assert crank.exit_code == 2 and "the crank is dyad 1" in crank.output
    header = run("analyse", shipped("fourbar.toml"), "--format", "csv").stdout.splitlines()[0]
    assert "mu_2_deg" in header.split(",")
    described = run("describe", shipped("fourbar.toml")).stdout
    assert "dyad 2:" in described


# -- 11. version ---------------------------------------------------------------------------
def test_version_names_python_and_numpy():
    import platform
    from importlib.metadata import version

    text = run("--version").stdout
    assert f"Python {platform.python_version()}" in text and f"numpy {version('numpy')}" in text
