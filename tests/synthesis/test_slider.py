"""Function generation with a slider-crank: the slider's position s over the crank
angle. Three precision points in closed form (the loop equation, linear in three
constants) reproduced to 1e-12 through dyade's engine; a table and a motion law with
the structural error at every row (dyade's engine against the closed form); bad input
with its key and exit code."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import DyadeError
from dyade.files.synthesis import parse
from dyade.synthesis import slider

KNOWN = slider.SliderCrank(0.1, 0.35, 0.03, 1)
PHI = np.radians([20.0, 75.0, 140.0])


@pytest.mark.parametrize("known", [KNOWN, slider.SliderCrank(-0.1, 0.35, -0.05, -1)])
def test_three_precision_points_in_closed_form(known):
    s = slider.position(known, PHI)
    made = slider.precision(PHI, s)
    assert (made.a, made.b, made.e, made.variant) == pytest.approx(
        (known.a, known.b, known.e, known.variant), rel=1e-12)
    # the mechanism file's slider, through dyade's positions stage, passes through them
    assert np.abs(slider.traced(made, PHI) - s).max() < 1e-12


def test_the_file_reproduces_three_points_and_its_table_says_every_one():
    s = slider.position(KNOWN, PHI)
    problem = parse({"topology": "slider-crank", "units": {"length": "mm", "angle": "deg"},
                     "target": {"kind": "function", "crank": [20, 75, 140],
                                "output": (1000 * s).tolist()}})
    outcome = dyade.run("synthesis", problem)
    assert outcome.units["output_m"] == "m" and outcome.units["error_m"] == "m"
    assert np.abs(outcome.columns["error_m"]).max() < 1e-12
    assert outcome.summary["error"].value < 1e-12 and outcome.summary["error"].unit == "m"
    # the design's file: a slider-crank whose pin P is the slider's, the crank angle kept
    data = outcome.result.designs[0].data
    assert data["dyad"][0]["kind"] == "RRP"
    assert data["links"]["3"]["points"]["P"] == pytest.approx([KNOWN.b, 0.0])


def test_a_table_reports_the_structural_error_at_every_row():
    phi = np.radians(np.linspace(0.0, 150.0, 31))
    s = 0.3 + 0.05 * (1 - np.cos(phi * 180 / 150))
    for method in ("chebyshev", "fit"):
        made = slider.generate(phi, s, method)
        # dyade's engine against the closed form of the same linkage, at every row
        assert np.abs(made.traced - slider.position(made.linkage, phi)).max() < 1e-12
        assert made.error == pytest.approx(made.traced - s, abs=1e-15)
    cheb = slider.generate(phi, s, "chebyshev")
    wanted = np.interp(cheb.precision, phi, s)  # exact at the three Chebyshev points
    assert np.abs(slider.position(cheb.linkage, cheb.precision) - wanted).max() < 1e-12
    fitted = slider.generate(phi, s, "fit")
    assert np.sqrt(np.mean(fitted.error ** 2)) <= np.sqrt(np.mean(cheb.error ** 2)) + 1e-15


def test_a_slider_cranks_own_law_gives_it_back():
    phi = np.radians(np.linspace(10.0, 160.0, 31))
    s = slider.position(KNOWN, phi)
    made = slider.from_law(phi, s - s[0], "fit")  # the law's lift: its start unknown
    assert made.start == pytest.approx(s[0], rel=1e-9)
    assert np.abs(made.error).max() < 1e-10
    assert (made.linkage.a, made.linkage.b, made.linkage.e) == pytest.approx(
        (KNOWN.a, KNOWN.b, KNOWN.e), rel=1e-8)


def test_points_on_both_branches_are_a_branch_defect():
    s = np.array([0.2, -0.2, 0.25])  # before and behind the crank pin
    with pytest.raises(DyadeError, match="branch defect|no slider-crank"):
        slider.precision(np.radians([0.0, 90.0, 180.0]), s)


HEAD = 'topology = "slider-crank"\nunits = { length = "mm", angle = "deg" }\n[target]\n'
BAD = [
    ('kind = "function"\ncrank = [0, 10]\noutput = [1, 2]\n', 2, "at least three rows"),
    ('kind = "function"\nrange = [0, 120]\n[target.profile]\nunit = "deg"\nperiod = 360\n'
     '[[target.profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 120\nto = 30\n'
     '[[target.profile.segment]]\nkind = "return"\nlaw = "cycloid"\nend = 360\nto = 0\n', 2,
     "gives an angle (deg): a slider-crank's function is the slider's position"),
    ('kind = "function"\ncrank = [0, 90, 180]\noutput = [200, -200, 250]\n', 1,
     "branch defect"),
]


@pytest.mark.parametrize("text, code, words", BAD)
def test_bad_input_exits_with_its_code(tmp_path, text, code, words):
    path = tmp_path / "s.toml"
    path.write_text(HEAD + text)
    result = CliRunner().invoke(main, ["synthesise", str(path)])
    assert result.exit_code == code, result.output
    assert words in " ".join(result.output.split())
    assert "Traceback" not in result.output


def test_a_motion_law_target_in_a_file(tmp_path):
    path = tmp_path / "law.toml"
    path.write_text('topology = "slider-crank"\nunits = { length = "mm", angle = "deg" }\n'
                    '[target]\nkind = "function"\nrange = [0, 150]\nrows = 31\n'
                    '[target.profile]\nunit = "mm"\nperiod = 360\n'
                    '[[target.profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 150\n'
                    'to = 100\n[[target.profile.segment]]\nkind = "return"\n'
                    'law = "cycloid"\nend = 360\nto = 0\n')
    outcome = dyade.run("synthesis", str(path))
    made = outcome.result.function
    assert outcome.columns["error_m"].size == 31
    lift = outcome.columns["output_m"] - outcome.summary["output_zero"].value
    assert lift[0] == pytest.approx(0.0, abs=1e-12) and lift[-1] == pytest.approx(0.1)
    assert np.abs(made.traced - slider.position(made.linkage, made.crank)).max() < 1e-12
    assert math.isfinite(outcome.summary["error"].value)
