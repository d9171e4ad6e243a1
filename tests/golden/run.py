#!/usr/bin/env python3
"""Golden run of dyade: run a broad, fixed set of CLI commands on a source tree and
record each command's stdout, stderr and exit code, normalised so that two runs of the
same tree are byte-identical.

    python3 tests/golden/run.py TREE OUTDIR      (tests/golden/compare.sh: against a baseline)

TREE is a dyade checkout (the directory holding dyade/ and mechanisms/); nothing is
installed: each command runs as `PYTHON -m dyade ...` with cwd=TREE and PYTHONPATH=TREE.
OUTDIR gets, per command, <name>.out, <name>.err and <name>.rc, plus
<name>.file.<path> for every file a command writes (-o DIR, --save-as, init FILE), and
commands.txt (name -> argv). OUTDIR is emptied first.

PYTHON: this script's interpreter (sys.executable), which needs dyade's dependencies
(numpy, click, rich, tomlkit); a baseline and its comparison must use the same one. If a
venv/ folder stands beside this script and GOLDEN_NO_VENV is not set, the script
re-executes itself under it. Issue 25 compared every output of its tree with the
baseline daeb9f0 this way: 423 commands, 1314 files, identical.

Stdlib only. Commands run on 2 threads (ThreadPoolExecutor). Runs on the same machine
are serialised by an flock on /tmp/golden-run.lock, because the hostile-input files and
the output targets live at fixed paths (/tmp/golden-hostile/<case>/,
/tmp/golden-out/<case>/), recreated fresh on each run, so that paths in messages do not
vary.

Normalisation (mask_times / normalise below), found by diffing two runs of the baseline:
  - the tree's absolute path -> <TREE> (none occurs in the baseline's outputs today);
  - wall-clock timings -> <T>:
      `dyade accuracy` table "setting  time [ms]  note": the time field of each row;
      `dyade clearance --simulate` (standalone) table rows "time: closed form" and
        "time: simulation";
      CSV columns time_ms (accuracy), sim_time_s and closed_time_s (clearance --simulate);
      the same keys in JSON ("time_ms": [...] / number -> "<T>").
    In tables the masked field keeps its width ("spaces + number" becomes a run of the
    same length ending in <T>), so alignment is still compared.
Everything else must be byte-identical.

The hostile cases are written out here, not imported from tests/cli/test_hostile.py: the run
must give the same commands to an old tree and a new one, whatever their tests say. A per-command wall-time list goes to
OUTDIR.timings.tsv (beside OUTDIR, not in it).
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

VENV_PYTHON = Path(__file__).resolve().parent / "venv" / "bin" / "python"
HOSTILE = Path("/tmp/golden-hostile")
WRITTEN = Path("/tmp/golden-out")
LOCK = Path("/tmp/golden-run.lock")
TIMEOUT = 90  # s per command; a slower command is recorded as rc "timeout"

FORMATS = ["table", "csv", "json"]
FRICTION = ["--set", "friction.coefficient=0.1", "--set", "friction.pin_radius=5",
            "--set", "friction.slider_length=40", "--set", "friction.slider_height=20"]
DRIVE = ["--set", "drive.motor=asynchronous", "--set", "drive.rated_torque=3.5",
         "--set", "drive.rated_speed_rpm=298", "--set", "drive.synchronous_speed_rpm=310",
         "--set", "drive.flywheel_inertia=0.44"]


class Case:
    def __init__(self, name, args, *, stdin=None, scratch=None, setup=None, special=None,
                 weight=1.0):
        self.name = name          # unique, file-name safe
        self.args = [str(a) for a in args]   # after `python -m dyade`
        self.stdin = stdin        # path (relative to TREE) fed to stdin, or None
        self.scratch = scratch    # a fixed directory whose files are recorded afterwards
        self.setup = setup        # callable(tree) run just before the command
        self.special = special    # callable(case, tree, python, env) -> (out, err, rc)
        self.weight = weight      # rough cost, to start the slow ones first


def safe(text: str) -> str:
    name = re.sub(r"[^A-Za-z0-9._=,+-]+", "_", text).strip("_")
    if len(name) > 110:
        name = name[:96] + "~" + hashlib.sha1(text.encode()).hexdigest()[:8]
    return name


# ---------------------------------------------------------------------------------------------
# the command list

def build_cases(tree: Path) -> list[Case]:
    cases: list[Case] = []
    names: set[str] = set()

    def add(name, args, **kw):
        name = safe(name)
        assert name not in names, f"duplicate case name {name}"
        names.add(name)
        cases.append(Case(name, args, **kw))

    def tag(args):
        return "_".join(a.replace("mechanisms/", "").replace(".toml", "") for a in args)

    mechanisms = sorted(p.relative_to(tree).as_posix() for p in (tree / "mechanisms").glob("*.toml"))
    gears = sorted(p.relative_to(tree).as_posix() for p in (tree / "mechanisms/gears").glob("*.toml"))
    couplings = sorted(p.relative_to(tree).as_posix()
                       for p in (tree / "mechanisms/coupling").glob("*.toml"))

    # -- help -------------------------------------------------------------------------------
    add("help", ["--help"])
    add("help-short", ["-h"])
    add("version", ["--version"])
    add("no-command", [])
    for sub in ["accuracy", "analyse", "balance", "clearance", "coupling", "describe", "flywheel",
                "gears", "init", "plot"]:
        add(f"help-{sub}", [sub, "--help"])
    for sub in ["animate", "campbell", "clearance", "coupling", "curves", "mechanism", "modes",
                "polar"]:
        add(f"help-plot-{sub}", ["plot", sub, "--help"])
    add("unknown-command", ["frobnicate"])

    # -- analyse: every mechanism, every format, --all, block sizes, friction -----------------
    for m in mechanisms:
        t = tag([m])
        for fmt in FORMATS:
            add(f"analyse-{t}-{fmt}", ["analyse", m, "--format", fmt])
            for bs in ("0", "7") if fmt != "table" else ():   # the table: see --all bs0, bs7
                add(f"analyse-{t}-{fmt}-bs{bs}", ["analyse", m, "--format", fmt, "--block-size", bs])
            add(f"analyse-{t}-{fmt}-friction", ["analyse", m, "--format", fmt, *FRICTION])
        add(f"analyse-{t}-all", ["analyse", m, "--all"])
        for bs in ("0", "7"):
            add(f"analyse-{t}-all-bs{bs}", ["analyse", m, "--all", "--block-size", bs])
        add(f"analyse-{t}-all-friction", ["analyse", m, "--all", *FRICTION])
        add(f"analyse-{t}-csv-friction-bs7", ["analyse", m, "--format", "csv", "--block-size", "7",
                                              *FRICTION])
        add(f"analyse-{t}-units-file", ["analyse", m, "--units", "file"])
        add(f"describe-{t}", ["describe", m])
        add(f"describe-{t}-friction", ["describe", m, *FRICTION])

    # analyse: README invocations and other options
    add("analyse-slider-crank-columns-units-file",
        ["analyse", "mechanisms/slider-crank.toml", "--columns", "s_*,v_*", "--units", "file"])
    add("analyse-fourbar-columns-csv",
        ["analyse", "mechanisms/fourbar.toml", "--columns", "M_drive,F_*,mu_*", "--format", "csv"])
    add("analyse-fourbar-step0.1-csv",
        ["analyse", "mechanisms/fourbar.toml", "--step", "0.1", "--format", "csv"], weight=2)
    add("analyse-fourbar-start-stop-step-json",
        ["analyse", "mechanisms/fourbar.toml", "--start", "-30", "--stop", "400", "--step", "2.5",
         "--format", "json"])
    add("analyse-fourbar-speed600-csv",
        ["analyse", "mechanisms/fourbar.toml", "--set", "crank.speed_rpm=600", "--format", "csv"])
    add("analyse-fourbar-lengths-all",
        ["analyse", "mechanisms/fourbar.toml", "--set", "dyad.2.lengths=[210,150]", "--all"])
    add("analyse-fourbar-dead-centre-transmission",
        ["analyse", "mechanisms/fourbar.toml", "--dead-centre", "5", "--transmission-warning", "70",
         "--all"])
    add("analyse-dyade-16-friction-tol-iter",
        ["analyse", "mechanisms/dyade-16.toml", *FRICTION, "--friction-tol", "1e-6",
         "--friction-max-iter", "3", "--all"])
    add("analyse-self-locking-max-iter-2",
        ["analyse", "mechanisms/self-locking.toml", "--friction-max-iter", "2"])
    add("analyse-self-locking-fail-on-lock",
        ["analyse", "mechanisms/self-locking.toml", "--fail-on-lock"])
    add("analyse-self-locking-frictionless-pins",
        ["analyse", "mechanisms/self-locking.toml", "--set", "crank.friction=0",
         "--set", "dyad.2.A.friction=0", "--set", "dyad.2.B.friction=0", "--all"])
    add("analyse-fourbar-short-allow-partial",
        ["analyse", "mechanisms/fourbar.toml", "--set", "dyad.2.lengths=[200,60]",
         "--allow-partial", "--format", "csv"])
    # the README's press: a [drive] on dyade-16 with friction
    for variant, extra in [("steady", []), ("constant-speed", ["--constant-speed"])]:
        for fmt in FORMATS:
            add(f"analyse-press-{variant}-{fmt}",
                ["analyse", "mechanisms/dyade-16.toml", *FRICTION, *DRIVE, *extra, "--format", fmt],
                weight=3)
    add("analyse-press-steady-csv-bs7",
        ["analyse", "mechanisms/dyade-16.toml", *FRICTION, *DRIVE, "--format", "csv",
         "--block-size", "7"], weight=3)
    add("analyse-press-run-up-csv",
        ["analyse", "mechanisms/dyade-16.toml", *FRICTION, *DRIVE, "--run-up", "--format", "csv"],
        weight=5)
    add("analyse-press-save-as",
        ["analyse", "mechanisms/dyade-16.toml", *FRICTION, *DRIVE, "--save-as",
         WRITTEN / "press" / "press.toml"], scratch=WRITTEN / "press", weight=3)
    add("analyse-fourbar-save-as-long",
        ["analyse", "mechanisms/fourbar.toml", "--set", "dyad.2.lengths=[210,150]",
         "--save-as", WRITTEN / "fourbar-long" / "fourbar-long.toml"],
        scratch=WRITTEN / "fourbar-long")
    add("analyse-stdin-csv-stdout", ["analyse", "-", "--format", "csv", "-o", "-"],
        stdin="mechanisms/slider-crank.toml")
    add("analyse-stdin-table", ["analyse", "-"], stdin="mechanisms/fourbar.toml")
    for suffix in ("csv", "json", "txt"):
        d = WRITTEN / f"analyse-o-{suffix}"
        add(f"analyse-fourbar-o-{suffix}",
            ["analyse", "mechanisms/fourbar.toml", "-o", d / f"fourbar.{suffix}"], scratch=d)
    # batches
    for fmt, jobs in [("csv", "1"), ("json", "1"), ("txt", "1"), ("csv", "2")]:
        d = WRITTEN / f"batch-{fmt}-j{jobs}"
        args = ["analyse", *mechanisms, "-o", d]
        if fmt != "csv":
            args += ["--format", "table" if fmt == "txt" else fmt]
        add(f"analyse-batch-{fmt}-j{jobs}", [*args, "-j", jobs], scratch=d, weight=4)
    add("analyse-batch-no-o", ["analyse", "mechanisms/fourbar.toml", "mechanisms/slider-crank.toml"])

    # -- clearance ------------------------------------------------------------------------------
    standalone = ["--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope", "360000"]
    for fmt in FORMATS:
        add(f"clearance-standalone-{fmt}", ["clearance", *standalone, "--format", fmt])
        add(f"clearance-standalone-simulate-{fmt}",
            ["clearance", *standalone, "--simulate", "--format", fmt])
        add(f"clearance-standalone-range-simulate-{fmt}",
            ["clearance", *standalone, "--speed-rpm", "300", "--speed-range", "100:600:50",
             "--simulate", "--format", fmt])
        add(f"clearance-dyade-16-{fmt}",
            ["clearance", "mechanisms/dyade-16.toml", "--stiffness", "1e8", "--clearance", "1e-4",
             "--format", fmt])
        add(f"clearance-dyade-16-simulate-{fmt}",
            ["clearance", "mechanisms/dyade-16.toml", "--stiffness", "1e8", "--clearance", "1e-4",
             "--simulate", "--format", fmt])
        add(f"clearance-dyade-16-joint-2,7-range-{fmt}",
            ["clearance", "mechanisms/dyade-16.toml", "--joint", "2,7", "--stiffness", "1e8",
             "--clearance", "1e-4", "--speed-range", "100:1000:100", "--format", fmt], weight=2)
    add("clearance-standalone-two-masses",
        ["clearance", "--mass", "3.6", "--mass", "5", "--stiffness", "1e7", "--clearance", "1e-4",
         "--slope", "360000", "--simulate", "--sim-steps", "50"])
    add("clearance-dyade-16-joint-range-j2",
        ["clearance", "mechanisms/dyade-16.toml", "--joint", "2,7", "--stiffness", "1e8",
         "--clearance", "1e-4", "--speed-range", "100:1000:100", "-j", "2"], weight=2)
    add("clearance-dyade-16-joints-wander",
        ["clearance", "mechanisms/dyade-16.toml", "--joint", "5,6", "--joint", "2,7",
         "--stiffness", "1e8", "--clearance", "1e-4", "--max-wander", "40", "--mass", "0.5"])
    for m in mechanisms:
        add(f"clearance-{tag([m])}", ["clearance", m, "--stiffness", "1e8", "--clearance", "1e-4"])
    for jobs in ("1", "2"):
        d = WRITTEN / f"clearance-batch-j{jobs}"
        add(f"clearance-batch-j{jobs}",
            ["clearance", "mechanisms/dyade-16.toml", "mechanisms/slider-crank.toml",
             "--stiffness", "1e8", "--clearance", "1e-4", "-o", d, "-j", jobs], scratch=d)

    # -- accuracy (its timings are masked) -----------------------------------------------------
    for m in mechanisms:
        add(f"accuracy-{tag([m])}", ["accuracy", m, "--repeats", "1"], weight=4)
    for fmt in ("csv", "json"):
        add(f"accuracy-fourbar-{fmt}", ["accuracy", "mechanisms/fourbar.toml", "--repeats", "1",
                                        "--format", fmt], weight=2)
    for fmt in ("table", "json"):
        add(f"accuracy-dyade-16-friction-{fmt}",
            ["accuracy", "mechanisms/dyade-16.toml", *FRICTION, "--repeats", "1", "--format", fmt],
            weight=8)

    # -- flywheel ----------------------------------------------------------------------------
    for fmt in FORMATS:
        add(f"flywheel-dyade-16-{fmt}",
            ["flywheel", "mechanisms/dyade-16.toml", "--fluctuation", "0.02", "--format", fmt])
        add(f"flywheel-dyade-16-friction-{fmt}",
            ["flywheel", "mechanisms/dyade-16.toml", "--fluctuation", "0.02", *FRICTION,
             "--format", fmt], weight=2)
        add(f"flywheel-engine-csv-{fmt}",
            ["flywheel", "mechanisms/torque/engine.csv", "--speed-rpm", "250", "--fluctuation",
             "0.005", "--format", fmt])
        add(f"flywheel-fourbar-inertia-{fmt}",
            ["flywheel", "mechanisms/fourbar.toml", "--inertia", "0.05", "--format", fmt])
    add("flywheel-fourbar-step1", ["flywheel", "mechanisms/fourbar.toml", "--fluctuation", "0.01",
                                   "--step", "1"])
    for m in mechanisms:
        add(f"flywheel-{tag([m])}", ["flywheel", m, "--fluctuation", "0.02"])

    # -- balance -------------------------------------------------------------------------------
    for m in mechanisms:
        add(f"balance-{tag([m])}", ["balance", m])
    for fmt in ("csv", "json"):
        add(f"balance-fourbar-{fmt}", ["balance", "mechanisms/fourbar.toml", "--format", fmt])
        add(f"balance-dyade-16-{fmt}", ["balance", "mechanisms/dyade-16.toml", "--format", fmt])
    add("balance-fourbar-save-as",
        ["balance", "mechanisms/fourbar.toml", "--save-as", WRITTEN / "balance" / "balanced.toml"],
        scratch=WRITTEN / "balance")
    add("balance-dyade-16-link-radius",
        ["balance", "mechanisms/dyade-16.toml", "--link", "2", "--radius", "0.05"])
    add("balance-fourbar-link4", ["balance", "mechanisms/fourbar.toml", "--link", "4"])

    # -- gears ---------------------------------------------------------------------------------
    for g in gears:
        t = tag([g]).replace("gears/", "")
        for fmt in FORMATS:
            add(f"gears-{t}-{fmt}", ["gears", g, "--format", fmt])
            add(f"gears-{t}-modes3-{fmt}", ["gears", g, "--modes", "3", "--format", fmt])
            if fmt == "table" or "friswell" not in g:   # friswell: no [speed], an error
                add(f"gears-{t}-campbell-{fmt}", ["gears", g, "--campbell", "0:3000:10",
                                                  "--format", fmt])
        add(f"gears-{t}-check", ["gears", g, "--check"])
    for fmt in FORMATS:
        add(f"gears-two-stage-response-{fmt}",
            ["gears", "mechanisms/gears/two-stage.toml", "--response", "10:1000:1", "--dof",
             "gear1.uy", "--format", fmt], weight=2)
    add("gears-two-stage-response-default-dof",
        ["gears", "mechanisms/gears/two-stage.toml", "--response", "10:1000:1"], weight=2)
    add("gears-two-stage-campbell-harmonics2",
        ["gears", "mechanisms/gears/two-stage.toml", "--campbell", "0:3000:10", "--harmonics", "2"])
    add("gears-two-stage-set-segments",
        ["gears", "mechanisms/gears/two-stage.toml", "--set", "shaft.1.segments=8"])

    # -- coupling ------------------------------------------------------------------------------
    for c in couplings:
        t = tag([c]).replace("coupling/", "")
        for fmt in FORMATS:
            add(f"coupling-{t}-{fmt}", ["coupling", c, "--format", fmt])
        add(f"coupling-{t}-override", ["coupling", c, "--moment", "10", "--speed-rpm", "1000",
                                       "--order", "1", "--eta-range", "0:2:0.05"])
    opts = ["--J", "1", "--c1", "1", "--c2", "1", "--b1", "0.05", "--b2", "0.05"]
    for fmt in FORMATS:
        add(f"coupling-options-{fmt}", ["coupling", *opts, "--eta-range", "0:3:0.01", "--format", fmt])
    add("coupling-options-moment-speed",
        ["coupling", *opts, "--moment", "2", "--speed-rpm", "5", "--speed-rpm", "9", "--order", "2"])
    add("coupling-undamped", ["coupling", "--J", "1", "--c1", "1", "--c2", "1"])
    add("coupling-undamped-csv", ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--format", "csv"])

    # -- init ----------------------------------------------------------------------------------
    for kind in ["fourbar", "scotch-yoke", "slider-crank", "slotted-lever", "tangent-drive",
                 "four-bar", "ppr", "prp", "rpr", "rrp", "rrr"]:
        add(f"init-{kind}-stdout", ["init", kind, "-"])
    add("init-fourbar-file", ["init", "fourbar", WRITTEN / "init" / "f.toml"],
        scratch=WRITTEN / "init")

    # -- hostile input (tests/cli/test_hostile.py) ---------------------------------------------------
    cases.extend(hostile_cases(tree, add_name=names))
    return cases


def hostile_cases(tree: Path, add_name: set[str]) -> list[Case]:
    """The CLI invocations of tests/cli/test_hostile.py, with its files at fixed paths."""
    out: list[Case] = []
    FOURBAR = (tree / "mechanisms/fourbar.toml").read_text(encoding="utf-8")
    COUPLING = (tree / "mechanisms/coupling/stiff-coupling.toml").read_text(encoding="utf-8")
    FOUR = "mechanisms/fourbar.toml"

    def add(name, args, **kw):
        name = safe("hostile-" + name)
        assert name not in add_name, f"duplicate case name {name}"
        add_name.add(name)
        out.append(Case(name, args, **kw))

    def with_file(case_dir: str, content, filename="m.toml"):
        """A setup that recreates /tmp/golden-hostile/<case>/<filename> fresh."""
        directory = HOSTILE / safe(case_dir)
        data = content if isinstance(content, bytes) else content.encode("utf-8")

        def setup(_tree):
            shutil.rmtree(directory, ignore_errors=True)
            directory.mkdir(parents=True)
            (directory / filename).write_bytes(data)
        return directory / filename, setup

    FILES = {
        "binary": b"\x00\x01\x02\xff\xfe dyade",
        "latin-1": FOURBAR.replace("Four-bar", "Gelenkviereck für Wälzlager").encode("latin-1"),
        "utf-16": FOURBAR.encode("utf-16"),
        "not toml": "name = \"x\"\n[crank\nlength = 1\n",
        "nested": "x = " + "[" * 50_000 + "]" * 50_000 + "\n",
        "empty": "",
    }
    for command in ["analyse", "describe", "clearance", "accuracy"]:
        for kind, content in FILES.items():
            case = f"file-{command}-{kind}"
            path, setup = with_file(case, content)
            add(case, [command, path], setup=setup)
    for kind in ["binary", "latin-1", "not toml", "nested"]:
        case = f"coupling-file-{kind}"
        path, setup = with_file(case, FILES[kind], "c.toml")
        add(case, ["coupling", path], setup=setup)

    NON_FINITE = [
        ("A0 = [0, 0]", "A0 = [nan, 0]"), ("B0 = [250, 0]", "B0 = [250, inf]"),
        ("length = 50", "length = nan"), ("speed_rpm = 300", "speed_rpm = inf"),
        ("lengths = [200, 150]", "lengths = [200, nan]"), ("centre = [100, 0]", "centre = [nan, 0]"),
        ("mass = 1.2", "mass = inf"), ("inertia = 0.004", "inertia = nan"),
        ("K = [100, 40]", "K = [100, -inf]"), ("step = 1", "step = nan"),
        ("stop = 360", "stop = 1e20"), ("stop = 360", "stop = inf"), ("step = 1", "step = 1e-15"),
    ]
    for old, new in NON_FINITE:
        assert old in FOURBAR, old
        case = f"nonfinite-{new}"
        path, setup = with_file(case, FOURBAR.replace(old, new, 1))
        add(case, ["analyse", path], setup=setup)

    LOADS = [
        ("load-force", "[[load]]\nlink = 3\nforce = [nan, 0]\n"),
        ("load-moment", "[[load]]\nlink = 3\nmoment = inf\n"),
        ("load-table-nan", "[[load]]\nlink = 3\ntable = [[0, 1, 2, 3], [90, nan, 0, 0]]\n"),
        ("load-table-inf", "[[load]]\nlink = 3\ntable = [[0, 1, 2, 3], [inf, 0, 0, 0]]\n"),
        ("spring-stiffness", "[[spring]]\nfrom = { link = 1, point = [0, 0] }\nto = { link = 3 }\n"
                             "stiffness = nan\nfree_length = 10\n"),
        ("spring-free-length", "[[spring]]\nfrom = { link = 1, point = [0, 0] }\nto = { link = 3 }\n"
                               "stiffness = 10\nfree_length = inf\n"),
        ("gravity-y", "[gravity]\nx = 0\ny = nan\n"),
        ("friction-coefficient", "[friction]\ncoefficient = nan\n"),
    ]
    for label, text in LOADS:
        case = f"loads-{label}"
        path, setup = with_file(case, FOURBAR + "\n" + text)
        add(case, ["analyse", path], setup=setup)

    COUPLING_KEYS = [("J = 0.012", "J = nan"), ("c1 = 4.0e4", "c1 = inf"), ("b2 = 1.5", "b2 = -1.5"),
                     ("moment = 50", "moment = 0"), ("order = 2", "order = nan"),
                     ("speed_rpm = [1450, 2900]", "speed_rpm = [1450, -2900]")]
    for old, new in COUPLING_KEYS:
        assert old in COUPLING, old
        case = f"coupling-{new}"
        path, setup = with_file(case, COUPLING.replace(old, new), "c.toml")
        add(case, ["coupling", path], setup=setup)

    OPTIONS = [
        ["analyse", FOUR, "--start", "nan"],
        ["analyse", FOUR, "--stop", "inf"],
        ["analyse", FOUR, "--step", "nan"],
        ["analyse", FOUR, "--step", "0"],
        ["analyse", FOUR, "--step", "-1"],
        ["analyse", FOUR, "--start", "1e20"],
        ["analyse", FOUR, "--start", "10", "--stop", "5"],
        ["analyse", FOUR, "--friction-tol", "nan"],
        ["analyse", FOUR, "--friction-tol", "0"],
        ["analyse", FOUR, "--friction-max-iter", "0"],
        ["analyse", FOUR, "--step", "1e-6"],
        ["analyse", FOUR, "--step", "1e-9"],
        ["analyse", FOUR, "--columns", "zzz*"],
        ["analyse", FOUR, "--set", "crank.speed_rpm=nan"],
        ["analyse", FOUR, "--set", "dyad.9.variant=1"],
        ["analyse", FOUR, "-o", "x.parquet"],
        ["clearance", "--mass", "nan", "--stiffness", "1e7", "--clearance", "1e-4", "--slope", "1"],
        ["clearance", "--mass", "3.6", "--stiffness", "inf", "--clearance", "1e-4", "--slope", "1"],
        ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "-1e-4", "--slope", "1"],
        ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
         "3.6e5", "--speed-rpm", "0", "--speed-range", "100:200:100"],
        ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
         "3.6e5", "--speed-rpm", "-300", "--speed-range", "100:200:100"],
        ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
         "3.6e5", "--speed-rpm", "300", "--speed-range", "0:inf:100"],
        ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
         "3.6e5", "--speed-rpm", "300", "--speed-range", "nan:200:100"],
        ["clearance", FOUR, "--stiffness", "1e8", "--clearance", "1e-4", "--max-wander", "nan"],
        ["clearance", FOUR, "--stiffness", "1e8", "--clearance", "1e-4", "--joint", "9,9"],
        ["clearance", FOUR, "--stiffness", "1e8"],
        ["coupling", "--J", "nan", "--c1", "1", "--c2", "1"],
        ["coupling", "--J", "1", "--c1", "inf", "--c2", "1"],
        ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--eta-range", "0:inf:1"],
        ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--eta-range", "0:3"],
        ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--moment", "inf"],
        ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--speed-rpm", "100", "--order", "0"],
        ["coupling", "--J", "1", "--c1", "0", "--c2", "1"],
        ["accuracy", FOUR, "--repeats", "0"],
        ["init", "hexapod", "x.toml"],
    ]
    for k, args in enumerate(OPTIONS, 1):
        label = " ".join(a.replace("mechanisms/", "").replace(".toml", "") for a in args)
        add(f"option-{k:02d}-{label}", args)

    add("absurd-sweep", ["analyse", "mechanisms/dyade-16.toml", "--step", "1e-7"])

    for command in ("analyse", "accuracy"):
        case = f"not-closing-{command}"
        path, setup = with_file(case, FOURBAR.replace("lengths = [200, 150]", "lengths = [200, 60]"))
        add(case, [command, path], setup=setup)

    # targets: missing folders, files in the way, read-only folders
    targets = HOSTILE / "targets"

    def setup_targets(_tree):
        # every "targets" case shares this folder; it is (re)made once per run, in main()
        pass

    add("targets-init-new-folder", ["init", "fourbar", targets / "new" / "f.toml"],
        scratch=targets / "new", setup=setup_targets)
    blocker = targets / "blocker"
    for label, args in [
            ("analyse-o", ["analyse", FOUR, "-o", blocker / "x.csv"]),
            ("analyse-save-as", ["analyse", FOUR, "--save-as", blocker / "x.toml"]),
            ("init", ["init", "fourbar", blocker / "x.toml"]),
            ("coupling-o", ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "-o",
                            blocker / "c.csv"])]:
        add(f"targets-blocker-{label}", args)
    if os.geteuid() != 0:  # root writes anywhere (the test skips this case too)
        add("targets-locked", ["analyse", FOUR, "-o", targets / "locked" / "x.csv"])

    add("sigterm-no-partial-file",
        ["analyse", FOUR, "--step", "0.0005", "-o", HOSTILE / "sigterm" / "big.csv"],
        special=run_sigterm, weight=3)
    return out


def setup_targets_dir():
    targets = HOSTILE / "targets"
    if targets.exists():
        for p in targets.rglob("*"):
            if p.is_dir():
                p.chmod(0o755)
    shutil.rmtree(targets, ignore_errors=True)
    targets.mkdir(parents=True)
    (targets / "blocker").write_text("")
    (targets / "locked").mkdir()
    (targets / "locked").chmod(0o500)


def run_sigterm(case, tree, python, env):
    """tests/cli/test_hostile.py::test_sigterm_leaves_no_partial_file: SIGTERM while writing;
    the exit status must be 143 and the target folder empty. Records rc, stderr and the
    files left in the folder."""
    directory = HOSTILE / "sigterm"
    shutil.rmtree(directory, ignore_errors=True)
    directory.mkdir(parents=True)
    process = subprocess.Popen([python, "-m", "dyade", *case.args], cwd=tree, env=env,
                               stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    # as the test: SIGTERM after 1 s; and (so that a loaded machine gives the same record)
    # not before the output has been started (a file in the folder: the handler is set)
    started = time.monotonic()
    while process.poll() is None and time.monotonic() - started < 20:
        if time.monotonic() - started >= 1.0 and any(directory.iterdir()):
            break
        time.sleep(0.02)
    process.send_signal(signal.SIGTERM)
    out, err = process.communicate(timeout=60)
    left = sorted(p.name for p in directory.iterdir())
    err += ("\n[golden] files left in the target folder: %r\n" % left).encode()
    return out, err, str(process.returncode)


# ---------------------------------------------------------------------------------------------
# normalisation

# Wall-clock timings, found by diffing two runs of the baseline. Each is replaced by <T>;
# in the tables the masked field keeps its width (the time columns are right-aligned, so
# "spaces + number" is replaced by a run of the same length ending in <T>): alignment and
# everything else on the line are still compared byte for byte.
TIME_COLUMNS = ("time_ms", "sim_time_s", "closed_time_s")   # CSV columns and JSON keys
NUMBER = r"-?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"


def normalise(text: str, tree: Path, case: Case) -> str:
    # the tree's absolute path (tracebacks, absolute paths in messages)
    text = text.replace(str(tree), "<TREE>")
    return mask_times(text)


def same_width(match) -> str:
    return " " * (len(match.group(0)) - 3) + "<T>"


def mask_times(text: str) -> str:
    # JSON: "time_ms": [numbers...] or "time_ms": number (also sim_time_s, closed_time_s)
    keys = "|".join(TIME_COLUMNS)
    text = re.sub(rf'("(?:{keys})":\s*)(\[[^\]]*\]|{NUMBER})',
                  lambda m: m.group(1) + re.sub(NUMBER, '"<T>"', m.group(2)), text)
    out = []
    csv_cols = None   # indices of timing columns in the current CSV header
    in_cost = False   # inside `dyade accuracy`'s "cost of each setting" table
    for line in text.split("\n"):
        if csv_cols is not None and "," in line:
            out.append(mask_csv_line(line, csv_cols))
            continue
        csv_cols = None
        if "," in line and not line.startswith(" "):
            header = line.split(",")
            cols = [k for k, name in enumerate(header) if name.strip() in TIME_COLUMNS]
            if cols:
                csv_cols = cols
                out.append(line)
                continue
        # accuracy: "setting  time [ms]  note" then one row per setting: the 2nd field
        if re.match(r"^\s*setting\s+time \[ms\]", line):
            in_cost = True
            out.append(line)
            continue
        if in_cost:
            m = re.match(rf"^(\S+(?: \S+)*?)( +{NUMBER})(?=  |\s*$)", line)
            if m:
                out.append(m.group(1) + same_width(re.match(r".*", m.group(2))) + line[m.end():])
                continue
            in_cost = False
        # clearance --simulate (standalone table): "time: closed form   0.00012628  s"
        m = re.match(rf"^(\s*time: [^0-9]*?)( +{NUMBER})(?=  |\s*$)", line)
        if m:
            out.append(m.group(1) + same_width(re.match(r".*", m.group(2))) + line[m.end():])
            continue
        out.append(line)
    return "\n".join(out)


def mask_csv_line(line: str, cols) -> str:
    if '"' in line:
        import csv
        import io
        fields = next(csv.reader([line]))
        for k in cols:
            if k < len(fields) and fields[k]:
                fields[k] = "<T>"
        buf = io.StringIO()
        csv.writer(buf, lineterminator="").writerow(fields)
        return buf.getvalue()
    fields = line.split(",")
    for k in cols:
        if k < len(fields) and fields[k]:
            fields[k] = "<T>"
    return ",".join(fields)


# ---------------------------------------------------------------------------------------------
# running

def environment(tree: Path) -> dict[str, str]:
    env = {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "HOME": os.environ.get("HOME", "/root"),
        "PYTHONPATH": str(tree),
        "PYTHONDONTWRITEBYTECODE": "1",
        "PYTHONHASHSEED": "0",
        "PYTHONIOENCODING": "utf-8",
        "LANG": "C.UTF-8",
        "LC_ALL": "C.UTF-8",
        "CI": "true",
        "COLUMNS": "100",
        "LINES": "50",
        "NO_COLOR": "1",
        "TERM": "dumb",
        "TMPDIR": "/tmp",
    }
    return env


def run_case(case: Case, tree: Path, python: str, env, outdir: Path):
    start = time.monotonic()
    if case.setup:
        case.setup(tree)
    if case.scratch is not None and case.scratch.parent != HOSTILE / "targets":
        shutil.rmtree(case.scratch, ignore_errors=True)
    if case.special:
        out, err, rc = case.special(case, tree, python, env)
    else:
        stdin = (tree / case.stdin).read_bytes() if case.stdin else None
        try:
            proc = subprocess.run([python, "-m", "dyade", *case.args], cwd=tree, env=env,
                                  input=stdin, stdin=None if stdin is not None else subprocess.DEVNULL,
                                  capture_output=True, timeout=TIMEOUT)
            out, err, rc = proc.stdout, proc.stderr, str(proc.returncode)
        except subprocess.TimeoutExpired as e:
            out, err, rc = e.stdout or b"", e.stderr or b"", "timeout"
    elapsed = time.monotonic() - start
    write(outdir / f"{case.name}.out", out, tree, case)
    write(outdir / f"{case.name}.err", err, tree, case)
    (outdir / f"{case.name}.rc").write_text(rc + "\n")
    if case.scratch is not None and case.scratch.exists():
        for p in sorted(case.scratch.rglob("*")):
            if p.is_file():
                rel = p.relative_to(case.scratch).as_posix().replace("/", "__")
                write(outdir / f"{case.name}.file.{rel}", p.read_bytes(), tree, case)
    return case.name, rc, elapsed


def write(path: Path, data: bytes, tree: Path, case: Case):
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        path.write_bytes(data)
        return
    path.write_text(normalise(text, tree, case), encoding="utf-8")


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        print("usage: python run.py TREE OUTDIR")
        return 2
    if (VENV_PYTHON.exists() and Path(sys.prefix).resolve() != VENV_PYTHON.parent.parent.resolve()
            and not os.environ.get("GOLDEN_NO_VENV")):
        os.execv(str(VENV_PYTHON), [str(VENV_PYTHON), os.path.abspath(__file__), *argv[1:]])
    tree = Path(argv[1]).resolve()
    outdir = Path(argv[2]).resolve()
    if not (tree / "dyade").is_dir() or not (tree / "mechanisms").is_dir():
        print(f"{tree}: not a dyade tree (no dyade/ or mechanisms/)", file=sys.stderr)
        return 2
    python = sys.executable
    env = environment(tree)
    check = subprocess.run([python, "-c", "import numpy, click, rich, tomlkit"], env=env,
                           capture_output=True, text=True)
    if check.returncode:
        print(f"{python} lacks dyade's dependencies (numpy, click, rich, tomlkit):\n"
              f"{check.stderr}", file=sys.stderr)
        return 2
    LOCK.touch()
    with open(LOCK) as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        start = time.monotonic()
        shutil.rmtree(outdir, ignore_errors=True)
        outdir.mkdir(parents=True)
        for d in (HOSTILE, WRITTEN):
            if d.exists():
                for p in d.rglob("*"):
                    if p.is_dir():
                        p.chmod(0o755)
            shutil.rmtree(d, ignore_errors=True)
            d.mkdir(parents=True)
        setup_targets_dir()
        cases = build_cases(tree)
        with open(outdir / "commands.txt", "w") as f:
            for c in cases:
                line = " ".join(c.args)
                if c.stdin:
                    line += f" < {c.stdin}"
                f.write(f"{c.name}\t{line}\n")
        order = sorted(cases, key=lambda c: -c.weight)
        results = []
        with ThreadPoolExecutor(max_workers=2) as pool:
            for r in pool.map(lambda c: run_case(c, tree, python, env, outdir), order):
                results.append(r)
        total = time.monotonic() - start
    counts: dict[str, int] = {}
    for c in cases:
        key = "hostile" if c.name.startswith("hostile-") else (
            "help/version" if c.name.startswith(("help", "version", "no-command", "unknown"))
            else c.args[0])
        counts[key] = counts.get(key, 0) + 1
    slow = sorted(results, key=lambda r: -r[2])[:5]
    with open(str(outdir) + ".timings.tsv", "w") as f:   # beside OUTDIR, not in it
        for n, rc, t in sorted(results, key=lambda r: -r[2]):
            f.write(f"{t:.2f}\t{rc}\t{n}\n")
    print(f"golden run of {tree} -> {outdir}: {len(cases)} commands in {total:.1f} s "
          f"({python})")
    print("per command: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    print("slowest: " + ", ".join(f"{n} {t:.1f}s" for n, _, t in slow))
    timeouts = [n for n, rc, _ in results if rc == "timeout"]
    if timeouts:
        print("TIMED OUT: " + ", ".join(timeouts))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
