"""`dyade report` of a synthesis file and `dyade plot synthesis` (issue 41): the page
holds the search's summary, the designs, the notes, the figure and each design's
mechanism file; the same file gives the same bytes; nothing points outside the page."""

from __future__ import annotations

import re
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

from dyade.cli import main  # noqa: E402
from dyade.synthesis import closed  # noqa: E402

FUNCTION = """name = "Three points"
units = { length = "mm", angle = "deg" }
[target]
kind = "function"
crank = [40, 75, 110]
output = [70, 95, 128]
[scores]
frame = 100
"""


def _page(path, target):
    out = CliRunner().invoke(main, ["report", str(path), "-o", str(target)],
                             catch_exceptions=False)
    assert out.exit_code == 0, out.output
    return target.read_text(encoding="utf-8")


@pytest.mark.slow
def test_a_synthesis_file_reports_its_designs_figure_and_files(tmp_path):
    path = tmp_path / "three.toml"
    path.write_text(FUNCTION)
    page = _page(path, tmp_path / "a.html")
    (tmp_path / "elsewhere").mkdir()
    assert _page(path, tmp_path / "elsewhere" / "b.html") == page
    assert re.findall(r"<h2>(.*?)</h2>", page) == [
        "Synthesis", "Designs", "Notes", "Target and designs", "Mechanism files"]
    assert page.count("</figure>") == 1 and "<svg" in page
    assert not re.findall(r'\b(?:src|href)\s*=\s*"(?!#)([^"]*)"', page)
    # the design's file on the page is Freudenstein's four-bar (d = 100 mm = 0.1 m)
    text = re.search(r"<pre>(.*?)</pre>", page, re.S).group(1)
    text = text.replace("&quot;", '"').replace("&#x27;", "'").replace("&lt;", "<")
    data = tomllib.loads(text)
    linkage = closed.freudenstein(np.deg2rad([40.0, 75.0, 110.0]),
                                  np.deg2rad([70.0, 95.0, 128.0]), frame=0.1)
    assert data["crank"]["length"] == pytest.approx(abs(linkage.a), rel=1e-12)
    assert data["dyad"][0]["lengths"] == pytest.approx([linkage.b, abs(linkage.c)], rel=1e-12)
    # the structural error at every row is in the page's table
    assert "structural error" in page.lower() or "error_deg" in page


def test_plot_synthesis_writes_the_figure(tmp_path):
    path = tmp_path / "three.toml"
    path.write_text(FUNCTION)
    out = CliRunner().invoke(main, ["plot", "synthesis", str(path), "-o",
                                    str(tmp_path / "s.png")])
    assert out.exit_code == 0, out.output
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    out = CliRunner().invoke(main, ["plot", "synthesis", str(path), "--candidates", "0"])
    assert out.exit_code == 2
