"""Hostile input (issue 14): every bad file, value, option and target through every
command. Each case must exit 2 (bad input) or 1 (analysis problem) with a message that
names the file and key or the flag, and never a traceback or a Python warning."""

from __future__ import annotations

import os
import stat
import sys

import pytest
from click.testing import CliRunner

from dyade.cli import main
from tests.helpers import shipped

FOURBAR = shipped("fourbar.toml").read_text()
COUPLING = shipped("coupling/stiff-coupling.toml").read_text()


def invoke(args, tmp_path=None):
    result = CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=True)
    assert not isinstance(result.exception, Exception) or isinstance(result.exception, SystemExit), \
        f"unhandled {type(result.exception).__name__}: {result.exception}"
    assert "Traceback" not in result.output and "Warning:" not in result.output
    return result


def bad_file(tmp_path, text: str | bytes, name="m.toml"):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode("utf-8"))
    return path


# -- files that are not UTF-8 TOML -----------------------------------------------------------
FILES = {
    "binary": b"\x00\x01\x02\xff\xfe dyade",
    "latin-1": FOURBAR.replace("Four-bar", "Gelenkviereck für Wälzlager").encode("latin-1"),
    "utf-16": FOURBAR.encode("utf-16"),
    "not toml": "name = \"x\"\n[crank\nlength = 1\n",
    "nested": "x = " + "[" * 50_000 + "]" * 50_000 + "\n",
    "empty": "",
}


@pytest.mark.parametrize("command", ["analyse", "describe", "clearance", "accuracy"])
@pytest.mark.parametrize("kind", FILES)
def test_a_file_that_is_not_a_mechanism_is_named(tmp_path, command, kind):
    path = bad_file(tmp_path, FILES[kind])
    result = invoke([command, path], tmp_path)
    assert result.exit_code == 2, result.output
    assert "m.toml" in result.output


@pytest.mark.parametrize("kind", ["binary", "latin-1", "not toml", "nested"])
def test_a_coupling_file_that_is_not_toml_is_named(tmp_path, kind):
    result = invoke(["coupling", bad_file(tmp_path, FILES[kind], "c.toml")])
    assert result.exit_code == 2 and "c.toml" in result.output


# -- values that are not finite, in every place a number is read ----------------------------------
NON_FINITE = [
    ("A0 = [0, 0]", "A0 = [nan, 0]", "`frame.points.A0`"),
    ("B0 = [250, 0]", "B0 = [250, inf]", "`frame.points.B0`"),
    ("length = 50", "length = nan", "`crank.length`"),
    ("speed_rpm = 300", "speed_rpm = inf", "`crank.speed_rpm`"),
    ("lengths = [200, 150]", "lengths = [200, nan]", "`dyad.2.lengths.2`"),
    ("centre = [100, 0]", "centre = [nan, 0]", "`links.3.centre`"),
    ("mass = 1.2", "mass = inf", "`links.3.mass`"),
    ("inertia = 0.004", "inertia = nan", "`links.3.inertia`"),
    ("K = [100, 40]", "K = [100, -inf]", "`links.3.points.K`"),
    ("step = 1", "step = nan", "`sweep.step`"),
    ("stop = 360", "stop = 1e20", "`sweep`"),
    ("stop = 360", "stop = inf", "`sweep.stop`"),
    ("step = 1", "step = 1e-15", "`sweep`"),
]


@pytest.mark.parametrize("old, new, key", NON_FINITE, ids=[c[1] for c in NON_FINITE])
def test_non_finite_values_in_a_mechanism_are_named(tmp_path, old, new, key):
    assert old in FOURBAR
    result = invoke(["analyse", bad_file(tmp_path, FOURBAR.replace(old, new, 1))])
    assert result.exit_code == 2, result.output
    assert "m.toml" in result.output and key in result.output


LOADS = [
    ("[[load]]\nlink = 3\nforce = [nan, 0]\n", "`load.1.force`"),
    ("[[load]]\nlink = 3\nmoment = inf\n", "`load.1.moment`"),
    ("[[load]]\nlink = 3\ntable = [[0, 1, 2, 3], [90, nan, 0, 0]]\n", "`load.1.table.2`"),
    ("[[load]]\nlink = 3\ntable = [[0, 1, 2, 3], [inf, 0, 0, 0]]\n", "`load.1.table.2`"),
    ("[[spring]]\nfrom = { link = 1, point = [0, 0] }\nto = { link = 3 }\nstiffness = nan\n"
     "free_length = 10\n", "`spring.1.stiffness`"),
    ("[[spring]]\nfrom = { link = 1, point = [0, 0] }\nto = { link = 3 }\nstiffness = 10\n"
     "free_length = inf\n", "`spring.1.free_length`"),
    ("[gravity]\nx = 0\ny = nan\n", "`gravity.y`"),
    ("[friction]\ncoefficient = nan\n", "`friction.coefficient`"),
]


@pytest.mark.parametrize("text, key", LOADS, ids=[c[1] for c in LOADS])
def test_non_finite_loads_springs_gravity_friction_are_named(tmp_path, text, key):
    result = invoke(["analyse", bad_file(tmp_path, FOURBAR + "\n" + text)])
    assert result.exit_code == 2, result.output
    assert key in result.output


COUPLING_KEYS = [("J = 0.012", "J = nan", "`J`"), ("c1 = 4.0e4", "c1 = inf", "`c1`"),
                 ("b2 = 1.5", "b2 = -1.5", "`b2`"), ("moment = 50", "moment = 0", "`moment`"),
                 ("order = 2", "order = nan", "`order`"),
                 ("speed_rpm = [1450, 2900]", "speed_rpm = [1450, -2900]", "`speed_rpm`")]


@pytest.mark.parametrize("old, new, key", COUPLING_KEYS, ids=[c[1] for c in COUPLING_KEYS])
def test_bad_coupling_values_are_named_with_the_file(tmp_path, old, new, key):
    assert old in COUPLING
    result = invoke(["coupling", bad_file(tmp_path, COUPLING.replace(old, new), "c.toml")])
    assert result.exit_code == 2 and f"c.toml: {key}" in result.output, result.output


# -- options ----------------------------------------------------------------------------------------
FOUR = str(shipped("fourbar.toml"))
OPTIONS = [
    (["analyse", FOUR, "--start", "nan"], "--start"),
    (["analyse", FOUR, "--stop", "inf"], "--stop"),
    (["analyse", FOUR, "--step", "nan"], "--step"),
    (["analyse", FOUR, "--step", "0"], "--step"),
    (["analyse", FOUR, "--step", "-1"], "--step"),
    (["analyse", FOUR, "--start", "1e20"], "--start"),
    (["analyse", FOUR, "--start", "10", "--stop", "5"], "--stop"),
    (["analyse", FOUR, "--friction-tol", "nan"], "--friction-tol"),
    (["analyse", FOUR, "--friction-tol", "0"], "--friction-tol"),
    (["analyse", FOUR, "--friction-max-iter", "0"], "--friction-max-iter"),
    (["analyse", FOUR, "--step", "1e-6"], "--max-memory"),
    (["analyse", FOUR, "--step", "1e-9"], "the sweep (--start, --stop, --step)"),
    (["analyse", FOUR, "--columns", "zzz*"], "--columns"),
    (["analyse", FOUR, "--set", "crank.speed_rpm=nan"], "`crank.speed_rpm`"),
    (["analyse", FOUR, "--set", "dyad.9.variant=1"], "dyad.9.variant"),
    (["analyse", FOUR, "-o", "x.feather"], "x.feather"),
    (["clearance", "--mass", "nan", "--stiffness", "1e7", "--clearance", "1e-4", "--slope", "1"],
     "--mass"),
    (["clearance", "--mass", "3.6", "--stiffness", "inf", "--clearance", "1e-4", "--slope", "1"],
     "--stiffness"),
    (["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "-1e-4", "--slope",
      "1"], "--clearance"),
    (["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
      "3.6e5", "--speed-rpm", "0", "--speed-range", "100:200:100"], "--speed"),
    (["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
      "3.6e5", "--speed-rpm", "-300", "--speed-range", "100:200:100"], "--speed"),
    (["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
      "3.6e5", "--speed-rpm", "300", "--speed-range", "0:inf:100"], "--speed-range"),
    (["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
      "3.6e5", "--speed-rpm", "300", "--speed-range", "nan:200:100"], "--speed-range"),
    (["clearance", FOUR, "--stiffness", "1e8", "--clearance", "1e-4", "--max-wander", "nan"],
     "--max-wander"),
    (["clearance", FOUR, "--stiffness", "1e8", "--clearance", "1e-4", "--joint", "9,9"],
     "--joint"),
    (["clearance", FOUR, "--stiffness", "1e8"], "--clearance"),
    (["coupling", "--J", "nan", "--c1", "1", "--c2", "1"], "--J"),
    (["coupling", "--J", "1", "--c1", "inf", "--c2", "1"], "--c1"),
    (["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--eta-range", "0:inf:1"], "--eta-range"),
    (["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--eta-range", "0:3"], "--eta-range"),
    (["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--moment", "inf"], "--moment"),
    (["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--speed-rpm", "100", "--order", "0"],
     "--order"),
    (["coupling", "--J", "1", "--c1", "0", "--c2", "1"], "--c1 and --b1"),
    (["accuracy", FOUR, "--repeats", "0"], "--repeats"),
    (["init", "hexapod", "x.toml"], "'hexapod' is not one of"),
]


@pytest.mark.parametrize("args, named", OPTIONS, ids=[" ".join(a[2:] if a[0] != "coupling"
                                                                 else a[1:])[:60] for a, _ in OPTIONS])
def test_bad_options_are_named(args, named):
    result = invoke(args)
    assert result.exit_code == 2, result.output
    assert named in result.output, result.output


# -- sizes ------------------------------------------------------------------------------------------
def test_an_absurd_sweep_is_refused_before_anything_is_allocated():
    result = invoke(["analyse", shipped("dyade-16.toml"), "--step", "1e-7"])
    assert result.exit_code == 2
    assert "3,600,000,001 positions" in result.output and "TB" in result.output
    import dyade
    from dyade.linkage.options import memory_estimate

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    with pytest.raises(dyade.InputError, match="max_memory"):
        dyade.analyse(mechanism, step_deg=1e-7)
    # the estimate is of the right size: dyade-16 at 36 001 positions peaked at 845 MB
    assert 0.8e9 < memory_estimate(mechanism, 36_001) < 1.2e9


# -- analysis problems -----------------------------------------------------------------------------
def test_accuracy_on_a_mechanism_that_does_not_close_fails_like_analyse(tmp_path):
    short = bad_file(tmp_path, FOURBAR.replace("lengths = [200, 150]", "lengths = [200, 60]"))
    for command in ("analyse", "accuracy"):
        result = invoke([command, short])
        assert result.exit_code == 1 and "cannot close for crank angles" in result.output


# -- targets --------------------------------------------------------------------------------------------
def test_targets_missing_folders_files_in_the_way_and_read_only_folders(tmp_path):
    made = invoke(["init", "fourbar", tmp_path / "new" / "f.toml"])
    assert made.exit_code == 0 and (tmp_path / "new" / "f.toml").exists()
    (tmp_path / "blocker").write_text("")
    for args in (["analyse", FOUR, "-o", tmp_path / "blocker" / "x.csv"],
                 ["analyse", FOUR, "--save-as", tmp_path / "blocker" / "x.toml"],
                 ["init", "fourbar", tmp_path / "blocker" / "x.toml"],
                 ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "-o",
                  tmp_path / "blocker" / "c.csv"]):
        result = invoke(args)
        assert result.exit_code == 2 and "cannot write" in result.output, (args, result.output)
    if os.geteuid() != 0:  # root writes anywhere
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(stat.S_IRUSR | stat.S_IXUSR)
        result = invoke(["analyse", FOUR, "-o", locked / "x.csv"])
        assert result.exit_code == 2 and "cannot write" in result.output


def test_sigterm_leaves_no_partial_file(tmp_path):
    import signal
    import subprocess
    import time

    target = tmp_path / "big.csv"
    process = subprocess.Popen([sys.executable, "-m", "dyade", "analyse", FOUR, "--step",
                                "0.0005", "-o", str(target)], stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60.0  # the partial file there: the handler is set (a
    while not any(tmp_path.iterdir()) and time.monotonic() < deadline:  # fixed second was
        time.sleep(0.05)  # too short for a loaded machine: killed before its handler)
    assert any(tmp_path.iterdir()) and process.poll() is None
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 143, err
    assert "Traceback" not in err and list(tmp_path.iterdir()) == []


# -- continuous angles -------------------------------------------------------------------------------
@pytest.mark.parametrize("path", sorted(shipped("").glob("*.toml")), ids=lambda p: p.stem)
def test_angle_columns_are_continuous_from_a_first_value_in_the_half_open_circle(path):
    """dyade-16's phi_5_deg used to jump from −179.96° to 180°, so its min and max meant
    nothing; every angle column now runs on across ±180°."""
    import numpy as np

    import dyade

    result = dyade.analyse(dyade.read_mechanism(path), start_deg=-725.0,
                           allow_partial=True)
    cols = result.columns()
    for name, values in cols.items():
        if name.startswith("phi_") and name != "phi_2_deg":
            finite = values[np.isfinite(values)]
            assert -180.0 < finite[0] <= 180.0, name
            assert np.max(np.abs(np.diff(finite)), initial=0.0) < 90.0, name
    crank = cols["phi_2_deg"]
    given = crank[np.isfinite(crank)]  # rows in the dead-centre band are empty
    assert crank[0] == pytest.approx(-5.0) and np.all(np.diff(given) > 0)
