"""Start-up cost (issue 7): what the commands import. Not timed: the times are measured by
tests/benchmarks/command_time.py; these tests keep heavy modules off the paths where the
measurement showed they cost (numpy for --help; rich, pathlib, json, the other commands
and the stages a file does not call for when writing a CSV). Modules already loaded at
interpreter start-up are not counted: an editable install loads pathlib there, so that
check bites in a regular install (as in CI)."""

from __future__ import annotations

import subprocess
import sys

from tests.helpers import shipped

PROBE = """
import sys
before = set(sys.modules)
from dyade.cli import main
try:
    main({args!r})
except SystemExit:
    pass
print("MODULES", " ".join(sorted(set(sys.modules) - before)))
"""


def _imported(args: list[str]) -> set[str]:
    run = subprocess.run([sys.executable, "-c", PROBE.format(args=args)], capture_output=True,
                         text=True, check=True)
    line = [text for text in run.stdout.splitlines() if text.startswith("MODULES")][-1]
    return set(line.split()[1:])


def test_help_imports_no_numpy():
    modules = _imported(["--help"])
    assert "numpy" not in modules
    assert not any(name.startswith(("rich", "matplotlib")) for name in modules)
    assert "dyade.cli.plot" in modules  # listed, so its module was read: lazily enough


def test_plot_help_imports_no_matplotlib():
    for args in (["plot", "--help"], ["plot", "polar", "--help"], ["plot", "campbell", "--help"],
                 ["plot", "modes", "--help"]):
        modules = _imported(args)
        assert "numpy" not in modules
        assert not any(name.startswith(("matplotlib", "dyade.plot")) for name in modules)


def test_csv_run_imports_only_what_it_uses():
    modules = _imported(["analyse", str(shipped("fourbar.toml")), "--format", "csv"])
    assert "numpy" in modules and "dyade.linkage.kinetostatics" in modules  # it did run
    unwanted = {"pathlib", "json", "difflib", "tomlkit", "dyade.cli.clearance",
                "dyade.cli.coupling", "dyade.cli.accuracy", "dyade.linkage.friction",
                "dyade.linkage.self_locking", "dyade.clearance", "dyade.report.tables"}
    assert not (modules & unwanted)
    assert not any(name.startswith(("rich", "matplotlib", "dyade.plot", "dyade.cli.plot"))
                   for name in modules)


def test_gears_help_imports_no_numpy():
    modules = _imported(["gears", "--help"])
    assert "dyade.cli.gears" in modules  # it did load the command
    assert "numpy" not in modules
    assert not any(name.startswith(("matplotlib", "dyade.plot")) for name in modules)
