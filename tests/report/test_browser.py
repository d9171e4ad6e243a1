"""`dyade report` in a real browser (issue 29): headless Chromium (Debian's package,
driven over its DevTools pipe by tests/browser.py) loads the report of every shipped
mechanism and gear file: no console error, no request leaves the file, every figure has
a size, the crank-angle slider moved by the keyboard draws another frame, and the page
prints to PDF. Slow (a browser per run) and marked ``browser``: `pytest -m browser`.

Without a Chromium the tests are skipped with a message saying how to install one
(`.ci/run` installs it where apt-get can).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

from dyade.cli import main  # noqa: E402
from tests import browser  # noqa: E402
from tests.conftest import SHIPPED  # noqa: E402
from tests.helpers import shipped  # noqa: E402

pytestmark = [pytest.mark.slow, pytest.mark.browser]

FILES = SHIPPED + [shipped("gears/two-stage.toml"), shipped("gears/friswell-geared.toml"),
                   shipped("studies/press-slide-tolerance.toml"),
                   shipped("coupling/stiff-coupling.toml")]
SHOTS = os.environ.get("DYADE_REPORT_SHOTS")
"""a folder to keep each report's screenshot in (to look at them), else none kept"""


@pytest.fixture(scope="module")
def chromium():
    executable = browser.find()
    if executable is None:
        pytest.skip("no Chromium found (chromium, chromium-browser, google-chrome; or set "
                    "CHROMIUM): on Debian `apt-get install -y chromium`, as .ci/run does")
    with browser.Browser(executable) as running:
        yield running


LINE = ["--set", "drive_line.stiffness=1000", "--set", "drive_line.damping=0.04"]
CASES = [pytest.param(path, [], id=path.stem) for path in FILES] + [
    pytest.param(shipped("dyade-16.toml"), LINE, id="dyade-16-drive-line")]


@pytest.mark.parametrize("path, extra", CASES)
def test_report_in_chromium(path: Path, extra: list, chromium, tmp_path):
    target = tmp_path / f"{path.stem}.html"
    out = CliRunner().invoke(main, ["report", str(path), "-o", str(target), *extra],
                             catch_exceptions=False)
    assert out.exit_code == 0, out.output
    page = chromium.page()
    url = target.resolve().as_uri()
    page.load(url)
    sizes = page.evaluate("Array.from(document.querySelectorAll('figure svg')).map("
                          "s => { const r = s.getBoundingClientRect(); "
                          "return [s.closest('figure').id, r.width, r.height]; })")
    assert len(sizes) >= 1
    assert all(width > 50 and height > 50 for _, width, height in sizes), sizes
    if path.parent.name not in ("gears", "studies", "coupling"):  # a linkage: its motion
        before = page.evaluate("document.getElementById('motion').innerHTML")
        assert page.evaluate("document.getElementById('motion').getAttribute('data-frame')") == "0"
        page.evaluate("document.getElementById('motion-slider').focus()")
        for _ in range(3):
            page.key("ArrowRight", 39)
        assert page.evaluate("document.getElementById('motion').getAttribute('data-frame')") == "3"
        after = page.evaluate("document.getElementById('motion').innerHTML")
        assert after != before  # another frame drawn
        assert page.evaluate("document.getElementById('motion-angle').textContent").startswith(
            "φ21 = ")
    pdf = page.pdf()
    assert pdf.startswith(b"%PDF") and pdf.count(b"/Type /Page") >= 2
    if SHOTS:
        Path(SHOTS).mkdir(parents=True, exist_ok=True)
        (Path(SHOTS) / f"{path.stem}.png").write_bytes(page.screenshot())
    assert page.errors() == []
    assert [u for u in page.requests() if u != url] == []
