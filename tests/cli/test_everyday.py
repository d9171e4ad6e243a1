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
@pytest.mark.parametrize("name", ["x.feather", "x.xlsx", "x.CSV2"])
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


def _ctrl_c_as_on_a_terminal() -> None:
    """In the child, before it runs: SIGINT at its default, as a shell gives a foreground
    command. A process started with SIGINT ignored (a job started with `&` by a shell
    without job control, and every process it starts) keeps it ignored, Python too: the
    SIGINT below then did nothing and the sweep ended with 0 (issue 42)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_ctrl_c_exits_130_without_a_traceback():
    """A real SIGINT to a real process, in the middle of a long sweep; whatever this
    process does with SIGINT (here: ignores it, as a background job does)."""
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    ours = signal.signal(signal.SIGINT, signal.SIG_IGN)  # the case that failed, on purpose
    try:
        process = subprocess.Popen([sys.executable, "-m", "dyade", "analyse",
                                    str(shipped("fourbar.toml")), "--step", "0.0005", "--format",
                                    "csv", "-o", os.devnull], cwd=ROOT, env=env,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                   preexec_fn=_ctrl_c_as_on_a_terminal)
    finally:
        signal.signal(signal.SIGINT, ours)
    estimate = process.stderr.readline()  # said before the sweep starts: it runs now
    time.sleep(0.3)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert "the sweep of 720,001 positions: about" in estimate, estimate
    assert process.returncode == 130, (process.returncode, estimate + err)
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
    assert "dyad 2 ([[dyad]] table 1): kind 1 RRR" in described


# -- 11. version ---------------------------------------------------------------------------
def test_version_names_python_and_numpy():
    import platform
    from importlib.metadata import version

    text = run("--version").stdout
    assert f"Python {platform.python_version()}" in text and f"numpy {version('numpy')}" in text


# -- 2. JSON that loads as a table --------------------------------------------------------
JSON_RUNS = {
    "analyse": ["analyse", shipped("dyade-16.toml"), "--format", "json"],
    "clearance": ["clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance",
                  "1e-4", "--format", "json"],
    "coupling": ["coupling", shipped("coupling/stiff-coupling.toml"), "--format", "json"],
    "accuracy": ["accuracy", shipped("fourbar.toml"), "--repeats", "1", "--format", "json"],
}


ANALYSIS = {"analyse": "sweep", "clearance": "clearance-check"}
"""command -> the registry entry it runs, where the names differ"""


@pytest.mark.parametrize("command", JSON_RUNS)
def test_every_json_has_one_shape_and_loads_as_a_table(command):
    pandas = pytest.importorskip("pandas")
    obj = json.loads(run(*JSON_RUNS[command]).stdout)
    assert list(obj) == ["columns", "units", "summary", "notes", "analysis", "options", "meta",
                         "schema"]
    assert obj["analysis"] == ANALYSIS.get(command, command)
    assert set(obj["units"]) == set(obj["columns"])
    frame = pandas.DataFrame(obj["columns"])
    assert len(frame) > 0 and list(frame.columns) == list(obj["columns"])


@pytest.mark.parametrize("command, csv_args", [
    ("analyse", ["analyse", shipped("dyade-16.toml"), "--format", "csv"]),
    ("coupling", ["coupling", shipped("coupling/stiff-coupling.toml"), "--format", "csv"]),
])
def test_json_numbers_are_the_csv_numbers(command, csv_args):
    """Each JSON number is the CSV field read as a number (no 3.0000000000000004 where the
    CSV says 3), and each empty CSV field is null."""
    obj = json.loads(run(*JSON_RUNS[command]).stdout)["columns"]
    lines = run(*csv_args).stdout.strip().splitlines()
    names = lines[0].split(",")
    for row, line in enumerate(lines[1:]):
        for name, field in zip(names, line.split(",")):
            value = obj[name][row]
            assert (value is None) if field == "" else value == float(field), (name, row)


def test_coupling_json_has_operating_points_and_peaks():
    summary = json.loads(run(*JSON_RUNS["coupling"]).stdout)["summary"]
    assert summary["order"]["value"] == 2.0
    assert [summary[f"V_phi_op{k}"]["where"]["speed_rpm"] for k in (1, 2)] == [1450.0, 2900.0]
    assert all(summary[f"V_{v}_op{k}"]["where"]["eta"] > 0 for v in ("phi", "psi", "q", "r")
               for k in (1, 2))
    assert summary["V_phi_unbounded"]["value"] is False and summary["V_phi_max"]["value"] > 1


# -- 8. coupling: an undamped peak is unbounded, not a grid value -----------------------------
def test_an_undamped_peak_is_unbounded_at_eta0_on_any_grid():
    for grid in ("0:3:0.01", "0:3.003:0.0100001"):
        text = run("coupling", "--J", 1, "--c1", 1, "--c2", 1, "--eta-range", grid).stdout
        assert "peak of V_phi" in text and "unbounded at η0 = 0.7071" in text
        assert "every 8. of" not in text and "301 rows, every 8th" in text
    damped = run("coupling", "--J", 1, "--c1", 1, "--c2", 1, "--b2", "0.1").stdout
    assert "unbounded" not in damped and "peak of V_phi (in the range)" in damped
    with_speeds = run("coupling", "--J", 1, "--c1", 1, "--c2", 1, "--speed-rpm", 5).stdout
    assert "speed [rpm]" in with_speeds and "η [-]" in with_speeds  # units on every header


# -- 3. a summary a designer reads in ten seconds -----------------------------------------
def test_the_default_table_shows_the_key_results_first():
    text = run("analyse", shipped("dyade-16.toml")).stdout
    lines = text.splitlines()
    assert len(lines) < 80  # the full table (--all) is over 300 lines
    first = next(k for k, line in enumerate(lines) if "drive torque max" in line)
    assert first < 5 and "omega_3" not in text
    assert "peak force F_2_5" in text and "smallest transmission angle, dyad 7" in text
    assert "stroke of slider (1,12)" in text and "time ratio" in text
    full = run("analyse", shipped("dyade-16.toml"), "--all").stdout
    assert "omega_3" in full and len(full.splitlines()) > 250


def test_round_off_and_constant_columns_are_not_numbers_to_read():
    """dyade-16's slider (1,9) carries no normal force: 1e-14 N of round-off is shown as
    0; the frame joints' constant coordinates are named once in the caption."""
    text = run("analyse", shipped("dyade-16.toml")).stdout
    row = next(line for line in text.splitlines() if "FN_1_9" in line)
    assert row.split()[3] == "0"
    full = run("analyse", shipped("dyade-16.toml"), "--all").stdout
    assert "constant over the sweep:" in full
    assert not any(line.startswith("x_1_2 ") for line in full.splitlines())


def test_columns_choose_and_units_file_shows_millimetres(tmp_path):
    csv = read_csv(run("analyse", shipped("fourbar.toml"), "--format", "csv",
                       "--columns", "M_drive,F_*").stdout)
    assert list(csv) == ["angle_deg", "F_1_2", "F_2_3", "F_3_4", "F_1_4", "M_drive"]
    none = run("analyse", shipped("fourbar.toml"), "--columns", "nothing*")
    assert none.exit_code == 2 and "no column matches nothing*" in none.output
    si = run("analyse", shipped("slider-crank.toml"), "--columns", "s_1_4", "--units",
             "si").stdout
    mm = run("analyse", shipped("slider-crank.toml"), "--columns", "s_1_4").stdout  # file's
    si_row = next(line for line in si.splitlines() if line.startswith("s_1_4"))
    mm_row = next(line for line in mm.splitlines() if line.startswith("s_1_4"))
    assert si_row.split()[1] == "m" and mm_row.split()[1] == "mm"
    assert float(mm_row.split()[2]) == pytest.approx(1e3 * float(si_row.split()[2]), rel=1e-5)


def test_time_ratios_equal_the_closed_forms():
    """Offset slider-crank (r 40, l 160, e 10 mm): Q = (180° + α)/(180° − α) with
    α = asin(e/(l − r)) − asin(e/(l + r)); crank and slotted lever (r 60, pivots 150 mm
    apart): the return stroke takes 2·acos(r/d) of crank angle."""
    import math

    import dyade

    alpha = math.degrees(math.asin(10 / 120) - math.asin(10 / 200))
    slider = dyade.analyse(dyade.read_mechanism(shipped("slider-crank.toml"))).summary()
    assert slider["time_ratio_1_4"] == pytest.approx((180 + alpha) / (180 - alpha), rel=1e-5)
    back = 2 * math.degrees(math.acos(60 / 150))
    lever = dyade.analyse(dyade.read_mechanism(shipped("slotted-lever.toml"))).summary()
    assert lever["time_ratio_4"] == pytest.approx((360 - back) / back, rel=1e-4)
    # the stroke: the slider's extreme positions, crank and rod in line
    stroke = math.sqrt(200 ** 2 - 10 ** 2) - math.sqrt(120 ** 2 - 10 ** 2)
    assert slider["stroke_1_4"] == pytest.approx(stroke * 1e-3, rel=1e-4)


# -- 4. describe shows what will be computed with -----------------------------------------
def test_describe_shows_the_data_in_the_files_units():
    text = " ".join(run("describe", shipped("dyade-16.toml")).stdout.split())
    assert "lengths in mm" in text
    assert "link 3: joint distance 200 mm; mass 1.2 kg, centre (100, 0) mm (ξ, η), J_s 0.004" in text
    assert "guide on link 1 through (0, 30) mm at 180°" in text
    assert "A: joint (2,7) revolute; clearance 2s = 0.1 mm, contact stiffness 2e+08 N/m" in text
    assert "gravity (0, -9.80665) m/s²" in text and "spring table return spring" in text
    assert "load 1 on link 6 at (0, 0) mm, world (x, y): table of 5 rows" in text
    friction = " ".join(run("describe", shipped("self-locking.toml")).stdout.split())
    assert "μ = 0.25" in friction and "slider L =" in friction


@pytest.mark.parametrize("lengths, kind", [
    ("[200, 150]", "Grashof crank-rocker"),       # 50 + 250 < 200 + 150
    ("[120, 100]", "non-Grashof"),                # 50 + 250 > 120 + 100
    ("[200, 100]", "Grashof change point"),       # 50 + 250 = 200 + 100
])
def test_describe_gives_the_grashof_type(lengths, kind):
    text = " ".join(run("describe", shipped("fourbar.toml"), "--set",
                        f"dyad.2.lengths={lengths}").stdout.split())
    assert kind in text


def test_describe_gives_stroke_and_time_ratio_of_a_slider_crank():
    text = " ".join(run("describe", shipped("slider-crank.toml")).stdout.split())
    assert "slider-crank: crank 40 mm, connecting rod 160 mm" in text
    assert "slider stroke 80.1" in text and "time ratio 1.021" in text
    rocker = " ".join(run("describe", shipped("fourbar.toml")).stdout.split())
    assert "rocker swing 38.99°, time ratio 1.015" in rocker


# -- 7. clearance over a mechanism: rebound and every speed accounted for ---------------------
def test_clearance_simulation_over_a_mechanism_shows_the_rebound():
    result = run("clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance",
                 "1e-4", "--joint", "2,7", "--simulate")
    assert "rebound [m/s]" in result.stdout
    assert "joint (2,7) reversal 1: after the peak the masses separate" in result.stderr
    import csv
    import io

    rows = list(csv.DictReader(io.StringIO(run(
        "clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance", "1e-4",
        "--joint", "2,7", "--simulate", "--format", "csv").stdout)))
    assert len(rows) == 2
    assert all(r["separates"] == "1" and float(r["rebound_speed"]) > 0 for r in rows)


def test_a_speed_range_accounts_for_every_joint_at_every_speed():
    """The four-bar's frame-side joints cannot be checked (no reduced mass, or a force that
    turns round the bearing): each appears at each speed with its reason."""
    text = run("clearance", shipped("fourbar.toml"), "--stiffness", "1e8", "--clearance", "1e-4",
               "--speed-range", "100:300:100", "--format", "json").stdout
    cols = json.loads(text)["columns"]
    seen = {(rpm, joint) for rpm, joint in zip(cols["speed_rpm"], cols["joint"])}
    assert seen == {(rpm, joint) for rpm in (100.0, 200.0, 300.0)
                    for joint in ("1-2", "2-3", "3-4", "1-4")}
    notes = [n for n in cols["note"] if n]
    assert any("no reduced mass: give --mass" in n for n in notes)
    assert any("wanders up to" in n for n in notes)


# -- 9. narrow terminals ------------------------------------------------------------------------
NARROW = [
    ["analyse", shipped("dyade-16.toml")],
    ["analyse", shipped("dyade-16.toml"), "--all"],
    ["describe", shipped("dyade-16.toml")],
    ["clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance", "1e-4",
     "--simulate"],
    ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
     "360000", "--speed-rpm", "300", "--speed-range", "100:600:100", "--simulate"],
    ["coupling", shipped("coupling/stiff-coupling.toml")],
    ["accuracy", shipped("dyade-16.toml"), "--repeats", "1"],
]


@pytest.mark.parametrize("args", NARROW, ids=lambda a: " ".join(str(x) for x in a[:2]))
def test_an_80_column_terminal_wraps_and_never_cuts(args):
    result = CliRunner(env={"COLUMNS": "80"}).invoke(main, [str(a) for a in args],
                                                      catch_exceptions=False)
    assert result.exit_code == 0
    assert "…" not in result.stdout
    assert max(len(line) for line in result.stdout.splitlines()) <= 80


def test_every_table_header_carries_its_unit():
    """A number without its unit is half a result: the headers of the numeric columns
    say it in brackets (or a unit column does)."""
    import re

    texts = [run("clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance",
                 "1e-4").stdout,
             run("coupling", shipped("coupling/stiff-coupling.toml")).stdout,
             run("accuracy", shipped("fourbar.toml"), "--repeats", "1").stdout]
    for header in ("φ21 [°]", "F0/t0 [N/s]", "τ [-]", "F12max [N]", "× [-]", "speed [rpm]",
                   "η [-]", "V_φ [-]", "time [ms]", "relative error [-]"):
        assert any(header in text for text in texts), header
    assert not re.search(r"\btime\s{2,}note", texts[2])  # "[ms]" used to vanish as markup


def test_help_examples_are_not_rewrapped():
    result = CliRunner(env={"COLUMNS": "60"}).invoke(main, ["clearance", "--help"])
    assert "    dyade clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000" \
        in result.output
    assert "_DYADE_COMPLETE=bash_source dyade" in run("--help").output


# -- 6. examples that make physical sense -------------------------------------------------------
def test_every_shipped_example_says_what_to_look_for():
    for path in sorted((ROOT / "mechanisms").glob("*.toml")):
        if path.name == "self-locking.toml":  # explained at length in its own header
            continue
        assert "# What to look for" in path.read_text(), path.name


def test_dyade16_drive_supplies_the_cutting_work():
    """The cutting force resists the knife, so the mean drive power is the (positive)
    work the cut takes per revolution over its period: independently, −mean(F·v) of the
    load at the knife slide; gravity and the return spring are conservative."""
    import numpy as np

    import dyade

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    cols = dyade.analyse(mechanism).columns()
    load, = mechanism.loads
    angle = np.deg2rad(cols["angle_deg"])
    fx = np.interp(angle, load.angles, load.fx, period=2 * np.pi)
    load_power = fx * cols["vx_5_6"]  # the knife slide 6 moves with its pin (5,6)
    mean = np.trapezoid(load_power, angle) / (2 * np.pi)
    drive = np.trapezoid(cols["P_drive"], angle) / (2 * np.pi)
    assert mean < -50.0 and drive == pytest.approx(-mean, rel=1e-6)


# -- 3 (files). one rule for missing folders, unwritable targets --------------------------------
def test_missing_folders_are_created_and_unwritable_targets_are_named(tmp_path):
    target = tmp_path / "new" / "deeper" / "fourbar.csv"
    assert run("analyse", shipped("fourbar.toml"), "-o", target).exit_code == 0
    assert target.read_text().startswith("angle_deg,")
    saved = tmp_path / "variants" / "long.toml"
    assert run("analyse", shipped("fourbar.toml"), "--save-as", saved, "--format",
               "csv").exit_code == 0 and saved.exists()
    blocker = tmp_path / "file"
    blocker.write_text("")
    bad = run("analyse", shipped("fourbar.toml"), "-o", blocker / "x.csv")
    assert bad.exit_code == 2 and "cannot write the file" in bad.output


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (Linux)")
@pytest.mark.parametrize("args", [["analyse", "mechanisms/fourbar.toml", "--format", "csv"],
                                  ["analyse", "mechanisms/dyade-16.toml", "--format", "json"],
                                  ["describe", "mechanisms/fourbar.toml"]])
def test_a_full_disk_is_an_error_not_a_traceback(args):
    """Standard output on a full disk (/dev/full): one line naming the problem, exit 1
    (it was a Python traceback from the writer, or from rich)."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "dyade", *args], cwd=root, stdout=full,
                              stderr=subprocess.PIPE, text=True, timeout=60)
    assert done.returncode == 1
    assert done.stderr.strip() == "Error: could not write the output: No space left on device."


def test_the_command_in_a_process_has_the_output_and_exit_status_of_main(tmp_path):
    """``python -m dyade`` (as the console script, ``dyade.cli:main``): the bytes and the
    exit status are those of ``main`` run in this process (standard output buffered, as
    it is unless PYTHONUNBUFFERED is set)."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    cases = [(["analyse", "mechanisms/dyade-16.toml", "--format", "csv"], 0),
             (["analyse", "mechanisms/missing.toml"], 2),
             (["analyse", "mechanisms/self-locking.toml", "--fail-on-lock", "--format", "json"],
              1)]
    for args, status in cases:
        buffered = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
        done = subprocess.run([sys.executable, "-m", "dyade", *args], cwd=root, env=buffered,
                              capture_output=True, timeout=120)
        inside = CliRunner().invoke(main, args)
        assert done.returncode == inside.exit_code == status, args
        assert done.stdout == inside.stdout_bytes, args
        # the same messages (a usage line names the program as it was called)
        assert done.stderr.splitlines()[-1:] == inside.stderr_bytes.splitlines()[-1:], args
