"""Hostile input of `dyade balance` (issue 31)."""

from __future__ import annotations

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect, run

FOURBAR = shipped("fourbar.toml")

CASES = {
    "no such link": (["--link", "99"], ["--link 99: there is no link 99 (the links are 1, 2, 3, 4)"]),
    "the frame": (["--link", "1"], ["does not turn about a frame pivot"]),
    "tiny radius": (["--radius", "1e-300"], ["--radius must lie in 1e-07…1000 m"]),
    "huge radius": (["--radius", "1e300"], ["--radius must lie in"]),
    "nan radius": (["--radius", "nan"], ["--radius", "finite"]),
}


@pytest.mark.parametrize("case", CASES)
def test_bad_options_are_named(case):
    args, words = CASES[case]
    expect(["balance", FOURBAR, *args], 2, *words)


def test_standard_input_and_output(tmp_path):
    direct = run(["balance", FOURBAR, "--format", "csv"])
    piped = expect(["balance", "-", "--format", "csv", "-o", "-"], 0,
                   stdin=FOURBAR.read_text())
    assert piped.stdout == direct.stdout and direct.stdout.startswith("link,")
    saved = expect(["balance", FOURBAR, "--save-as", "-", "--format", "csv", "-o",
                    tmp_path / "w.csv"], 0)
    assert saved.stdout.startswith("# written by dyade balance --save-as")
    assert not (tmp_path / "-").exists()
    expect(["balance", FOURBAR, "-o", tmp_path / "new" / "sub" / "b.csv"], 0)
    assert (tmp_path / "new" / "sub" / "b.csv").exists()
    (tmp_path / "file").write_text("x")
    expect(["balance", FOURBAR, "-o", tmp_path / "file" / "b.csv"], 2, "is a file, not a folder")
