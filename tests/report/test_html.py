"""`dyade report` (issue 29): one self-contained HTML page per mechanism or gear file.

The page is checked as text here (the browser checks are tests/report/test_browser.py):
the same file gives the same bytes, nothing in it points outside the page, it holds the
sections the file calls for, and the motion's frames are the analysis: each pin of each
frame, mapped back from the drawing's coordinates, is the CSV's joint position.
"""

from __future__ import annotations

import json
import re
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.cli import main  # noqa: E402
from dyade.report import html as report_html  # noqa: E402
from tests.conftest import SHIPPED  # noqa: E402
from tests.helpers import shipped  # noqa: E402

GEAR_FILES = [shipped("gears/two-stage.toml"), shipped("gears/friswell-geared.toml")]
LIMIT = 2_000_000  # [B] a report's size


def write(path, tmp_path, name: str, *extra: str) -> str:
    target = tmp_path / name
    out = CliRunner().invoke(main, ["report", str(path), "-o", str(target), *extra],
                             catch_exceptions=False)
    assert out.exit_code == 0, out.output
    assert f"wrote {target}" in out.output
    return target.read_text(encoding="utf-8")


def outside(page: str) -> list[str]:
    """Everything in the page that would load something from outside it."""
    found = re.findall(r'\b(?:src|href|action|poster)\s*=\s*"(?!#)([^"]*)"', page)
    found += re.findall(r'url\(\s*[\'"]?(?!#)([^)\'"]+)', page)
    found += re.findall(r"@import[^;]*", page)
    found += re.findall(r"<(?:link|iframe|object|embed|img)\b[^>]*>", page)
    found += re.findall(r"\b(?:fetch|XMLHttpRequest|WebSocket|EventSource)\b", page)
    return found


def motion(page: str) -> dict:
    data = re.search(r'<script type="application/json" id="motion-data">(.*?)</script>',
                     page, re.S)
    return json.loads(data.group(1).replace("<\\/", "</"))


def test_same_file_same_bytes_and_nothing_from_outside(tmp_path):
    path = shipped("slotted-lever.toml")
    first = write(path, tmp_path, "a.html")
    assert write(path, tmp_path / "elsewhere", "b.html") == first
    assert outside(first) == []
    assert str(shipped("")) not in first  # the file by name, not by where it lies
    assert len(first.encode()) < LIMIT
    ids = re.findall(r'\bid="([^"]+)"', first)
    assert len(ids) == len(set(ids))  # the figures' ids prefixed: unique on the page
    headings = re.findall(r"<h2>(.*?)</h2>", first)
    assert headings == ["Key results",
                        "Notes: where the model holds, friction, self-locking, clearance",
                        "The linkage", "The motion",
                        "Drive torque, power and transmission angles",  # no forces: no polar
                        "The file in assembly order (dyade describe)"]


def test_motion_frames_are_the_analysis_one_per_position(tmp_path):
    path = shipped("slotted-lever.toml")
    page = write(path, tmp_path, "a.html")
    data = motion(page)
    result = dyade.analyse(dyade.read_mechanism(path))
    cols = result.columns()
    assert data["angles"] == pytest.approx(cols["angle_deg"], abs=1e-6)
    count = len(data["angles"])
    assert f'max="{count - 1}"' in page
    from dyade.plot.mechanism import geometry

    x0, x1, y0, y1 = geometry(result).limits
    scale = report_html.MOTION_WIDTH / (x1 - x0)
    revolute = [j.name for j in result.mechanism.joints if j.kind == "R"]
    assert len(data["pins"]) == len(revolute)
    tolerance = 0.51 * 10.0 ** -report_html.DECIMALS / scale  # [m] the rounding
    for pin, (a, b) in zip(data["pins"], revolute):
        xy = np.array(pin["xy"]).reshape(count, 2)
        assert np.allclose(x0 + xy[:, 0] / scale, cols[f"x_{a}_{b}"], atol=tolerance, rtol=0)
        assert np.allclose(y1 - xy[:, 1] / scale, cols[f"y_{a}_{b}"], atol=tolerance, rtol=0)


def test_a_coupling_reports_its_resonance_and_transfer_functions(tmp_path):
    """The shipped stiff coupling: ω_t = sqrt((c1 + c2)/J) and the peak of V_φ as
    ``dyade coupling`` computes them, its two operating points, one figure, the same
    bytes twice, nothing from outside; a bad eta_range is refused naming the key."""
    path = shipped("coupling/stiff-coupling.toml")
    page = write(path, tmp_path, "a.html")
    assert write(path, tmp_path / "elsewhere", "b.html") == page and outside(page) == []
    assert re.findall(r"<h2>(.*?)</h2>", page) == [
        "Torsional resonance", "Notes", "Transfer functions and phases", "Tables"]
    coupling = dyade.read_coupling(path)
    data = tomllib.loads(path.read_text())
    assert coupling.natural_frequency == pytest.approx(
        np.sqrt((data["c1"] + data["c2"]) / data["J"]), rel=1e-12)
    assert f'<td class="number">{coupling.natural_frequency:.5g}</td>' in page
    peak = dyade.coupling_response(coupling, np.arange(0, 3.001, 0.01)).transfer["V_phi"].max()
    assert f"{peak:.5g} at η" in page
    assert all(f'<td class="number">{rpm:.5g}</td>' in page for rpm in data["speed_rpm"])
    assert page.count("</figure>") == 1
    bad = tmp_path / "bad.toml"
    bad.write_text(path.read_text().replace('eta_range = "0:3:0.01"', 'eta_range = "0:3:x"'))
    out = CliRunner().invoke(main, ["report", str(bad), "-o", str(tmp_path / "r.html")])
    assert out.exit_code == 2 and "`eta_range` must be START:STOP:STEP" in out.output
    assert not (tmp_path / "r.html").exists()


def test_not_a_mechanism_nor_a_gear_file_is_bad_input(tmp_path):
    bad = tmp_path / "coupling.toml"
    bad.write_text('name = "x"\n[other]\nvalue = 1\n')
    out = CliRunner().invoke(main, ["report", str(bad), "-o", str(tmp_path / "r.html")])
    assert out.exit_code == 2 and "neither a mechanism file" in out.output
    assert not (tmp_path / "r.html").exists()
    out = CliRunner().invoke(main, ["report", str(shipped("fourbar.toml")), "--set",
                                    "crank.length=-1", "-o", str(tmp_path / "r.html")])
    assert out.exit_code == 2 and "crank.length" in out.output


@pytest.mark.slow
@pytest.mark.parametrize("path", SHIPPED + GEAR_FILES, ids=lambda p: p.stem)
def test_every_shipped_file_reports(path, tmp_path):
    page = write(path, tmp_path, "r.html")
    assert len(page.encode()) < LIMIT and outside(page) == []
    headings = re.findall(r"<h2>(.*?)</h2>", page)
    if path in GEAR_FILES:
        drive = dyade.read_gears(path)
        assert "Mode shapes" in headings
        assert ("Campbell diagram" in headings) == (drive.speed is not None)
        modes = dyade.gear_modes(drive)
        assert all(f"<td class=\"number\">{k + 1}</td>" in page
                   for k in range(modes.frequencies.size))
        return
    mechanism = dyade.read_mechanism(path)
    result = dyade.analyse(mechanism)
    assert ("Joint forces: polar diagrams" in headings) == (result.forces is not None)
    assert ("Clearance check" in headings) == any(getattr(j, "clearance", None) is not None
                                                  for j in mechanism.joints)
    assert len(motion(page)["angles"]) == len(result.columns()["angle_deg"])
    notes = re.search(r"<h2>Notes.*?</h2>(.*?)</section>", page, re.S).group(1)
    assert notes.count("<li>") == len(result.notes)
    expected = 3 + ("Joint forces: polar diagrams" in headings) + ("Clearance check" in headings)
    assert page.count("<figure") == page.count("</figure>") == expected


@pytest.mark.slow
def test_a_drive_reports_its_speed_and_motor(tmp_path):
    from tests.machine.test_machine import FLYWHEEL_ONLY

    path = tmp_path / "drive.toml"
    path.write_text('name = "Flywheel drive"\n' + FLYWHEEL_ONLY)
    page = write(path, tmp_path, "r.html")
    headings = re.findall(r"<h2>(.*?)</h2>", page)
    assert "The drive: crank speed and motor" in headings
    rpm = dyade.analyse(dyade.read_mechanism(path)).summary()["speed_mean_rpm"]
    assert f'<td class="number">{rpm:.6g}</td>' in page  # 1470 rpm: k·(ω_s − ω) = 5 N·m
    assert rpm == pytest.approx(1470.0, rel=1e-9)
    assert "Crank speed from the equation of motion" in page


@pytest.mark.slow
def test_a_study_reports_its_tables_and_question(tmp_path):
    path = shipped("studies/press-slide-tolerance.toml")
    page = write(path, tmp_path, "r.html")
    assert re.findall(r"<h2>(.*?)</h2>", page) == ["Results", "The question"]
    assert outside(page) == [] and page.count("</figure>") == 1
    assert "100 variants of self-locking.toml" in page
    # the shipped study has outputs equal in every variant (a stroke): one bar each, drawn
    out = CliRunner().invoke(main, ["plot", "study", str(path), "-o", str(tmp_path / "s.png")])
    assert out.exit_code == 0, out.output


@pytest.mark.slow  # two reports of dyade-16, one with its drive line's steady state: ~8 s
def test_a_drive_line_reports_its_natural_frequency_and_steady_state(tmp_path):
    """A file with a [drive_line] gets the drive line's section: ω̄ and its range, the VDI
    2149 ratio and verdict, the steady state next to the rigid drive; one without does not."""
    from dyade.linkage import drive_line as api

    line = {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.04}
    page = report_html.report(str(shipped("dyade-16.toml")), line)
    headings = re.findall(r"<h2>(.*?)</h2>", page)
    assert "The elastic drive line (dyade driveline)" in headings
    freq = api.natural_frequency(dyade.read_mechanism(shipped("dyade-16.toml"), line))
    # ω̄ = √(c/J̄) [rad/s], the ratio Ω/ω̄ with the crank's Ω: what the page prints
    assert freq.ratio == pytest.approx(dyade.read_mechanism(shipped("dyade-16.toml")).crank.speed
                                       / freq.omega_bar, rel=1e-12)
    assert f"{freq.omega_bar * 30 / np.pi:.6g}" in page and f"{freq.ratio:.6g}" in page
    assert '<figure id="figure-driveline">' in page and "rigid drive" in page
    plain = report_html.report(str(shipped("dyade-16.toml")))
    assert "The elastic drive line" not in plain


# -- issue 36: the report takes the commands' options -----------------------------------
SHORT = ["--set", "dyad.2.lengths=[200,60]"]
"""the four-bar with its rocker shortened: it closes for crank angles 0°-95° and
265°-360° only (|A B0| ranges 200..300 mm, coupler + rocker = 260 mm)"""


def test_a_mechanism_that_closes_over_part_of_the_turn_needs_allow_partial(tmp_path):
    out = CliRunner().invoke(main, ["report", str(shipped("fourbar.toml")), *SHORT, "-o",
                                    str(tmp_path / "r.html")], catch_exceptions=False)
    assert out.exit_code == 1
    assert "--allow-partial" in out.output and "allow_partial=True" not in out.output
    assert "96.0°–264.0°" in out.output
    assert not (tmp_path / "r.html").exists()


def test_a_partial_mechanism_is_reported_over_the_part_that_closes(tmp_path):
    page = write(shipped("fourbar.toml"), tmp_path, "r.html", *SHORT, "--allow-partial")
    # said in the notes ...
    assert "cannot close for crank angles 96.0°–264.0°" in page
    assert "192 of 361 kept" in page
    # ... shaded in the figures (the curves' partial band) ...
    assert 'id="curves-note-partial"' in page
    # ... and the motion is the part that closes: one frame per closed position
    data = motion(page)
    angles = np.array(data["angles"])
    assert angles.size == 192
    assert not np.any((angles > 95.5) & (angles < 264.5))
    # the API gives the same page
    api = report_html.report(str(shipped("fourbar.toml")), {"dyad.2.lengths": [200, 60]},
                             allow_partial=True)
    assert api.replace(str(shipped("")), "") == page.replace(str(shipped("")), "")


def test_the_report_sweeps_as_asked_and_refuses_options_that_do_not_apply(tmp_path):
    page = write(shipped("fourbar.toml"), tmp_path, "r.html", "--start", "0", "--stop", "90",
                 "--step", "2")
    assert motion(page)["angles"] == pytest.approx(np.arange(0, 92, 2))
    out = CliRunner().invoke(main, ["report", str(shipped("coupling/stiff-coupling.toml")),
                                    "--allow-partial", "-o", str(tmp_path / "c.html")],
                             catch_exceptions=False)
    assert out.exit_code == 2 and "--allow-partial apply to a mechanism file" in out.output


def test_a_cam_file_refuses_a_mechanism_s_sweep_and_headers_keep_their_units(tmp_path):
    """Cheap (no figure): a cam file's report refuses the sweep options of a mechanism
    and --set before computing anything; a table's "[mm]" is a unit, not markup."""
    from rich.table import Table

    path = str(shipped("cams/translating-roller.toml"))
    for extra in (["--start", "10"], ["--set", "cam.base_radius=50"]):
        out = CliRunner().invoke(main, ["report", path, *extra, "-o", str(tmp_path / "r.html")])
        assert out.exit_code == 2 and extra[0] in out.output and "cam file" in out.output
        assert not (tmp_path / "r.html").exists()
    table = Table(title="[x] t")
    table.add_column("s [mm]")
    table.add_row("[rpm]")
    assert "<th>s [mm]</th>" in report_html.table_html(table)
    assert "<td>[rpm]</td>" in report_html.table_html(table)


@pytest.mark.slow
def test_a_cam_reports_its_checks_notes_and_figure(tmp_path):
    """The shipped feeder cam at --step 5: its checks, notes, figure and table over the
    turn as ``dyade cam`` computes them (the largest pressure angle in the page, each
    note once, a unit in every header of the table), nothing from outside."""
    path = shipped("cams/translating-roller.toml")
    page = write(path, tmp_path, "a.html", "--step", "5")
    assert outside(page) == [] and len(page.encode()) < LIMIT
    assert re.findall(r"<h2>(.*?)</h2>", page) == [
        "The cam&#x27;s checks", "Notes: pressure angle, undercut, lift-off, the profile",
        "The cam and its follower", "Over the turn"]
    outcome = dyade.run("cam", str(path), step_deg=5.0)
    alpha = outcome.summary["pressure_angle_max_deg"].value
    assert f'<td class="number">{alpha:.6g} (limit 30)</td>' in page
    assert 0 < alpha < 30
    notes = re.search(r"<h2>Notes.*?</h2>(.*?)</section>", page, re.S).group(1)
    assert notes.count("<li>") == len(outcome.notes) >= 1
    assert page.count("<figure") == page.count("</figure>") == 1
    turn = re.search(r"<h2>Over the turn</h2>(.*?)</section>", page, re.S).group(1)
    assert "(72 rows, every 2nd shown" in turn
    headers = re.findall(r"<th>(.*?)</th>", turn)
    assert "s [mm]" in headers and "contact_force [N]" in headers
    assert all("[" in h for h in headers if h != "undercut")  # no unit eaten as markup


@pytest.mark.slow
def test_a_cam_report_is_the_same_bytes_twice(tmp_path):
    path = shipped("cams/cam-linkage.toml")
    page = write(path, tmp_path, "a.html")
    assert write(path, tmp_path / "elsewhere", "b.html") == page
    ids = re.findall(r'\bid="([^"]+)"', page)
    assert len(ids) == len(set(ids))
