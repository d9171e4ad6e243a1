"""Progress bars (issue 17): on stderr, and only when it is a terminal."""

from __future__ import annotations

import io

import pytest
from click.testing import CliRunner

from dyade.analyses import sweep
from dyade.cli import main, output
from tests.helpers import shipped


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_bar_only_on_a_terminal(monkeypatch):
    quiet, loud = io.StringIO(), Terminal()
    for stream in (quiet, loud):
        monkeypatch.setattr(output.sys, "stderr", stream)
        monkeypatch.delenv("NO_COLOR", raising=False)
        with output.progress("working", total=4) as tick:
            for done in range(1, 5):
                tick(done)
                tick.note(f"{done} a second")  # how it goes, beside the bar
    assert quiet.getvalue() == ""
    assert "working" in loud.getvalue() and "a second" in loud.getvalue()


@pytest.mark.parametrize("args", [
    ["analyse", shipped("fourbar.toml"), "--format", "csv", "--block-size", "50"],
    ["accuracy", shipped("fourbar.toml"), "--repeats", "1", "--format", "csv"],
    ["clearance", shipped("dyade-16.toml"), "--joint", "2,7", "--speed-range", "100:400:25",
     "--format", "csv"],
], ids=["analyse", "accuracy", "clearance speeds"])
def test_no_progress_output_when_stderr_is_not_a_terminal(args, monkeypatch):
    monkeypatch.setattr(sweep, "SECOND", 1.0)  # every sweep counts as a long one
    result = CliRunner().invoke(main, [str(a) for a in args],
                                                 catch_exceptions=False)
    assert result.exit_code == 0, result.stderr
    for trace in ("\x1b", "\r", "analysing", "checking the sweep", "accuracy studies",
                  "clearance at"):  # warnings of the analysis itself may be there
        assert trace not in result.stderr
