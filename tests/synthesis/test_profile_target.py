"""Function generation to a motion profile (``dyade.motion``): the output angle over the
crank angle given as a profile of motion laws, the placement of the profile on the
four-bar (the crank angle of its master zero, the output angle of its s = 0) found by
the synthesis, the structural error at every row through dyade's engine."""

from __future__ import annotations

import math

import numpy as np
import pytest

import dyade
from dyade.files.synthesis import parse
from dyade.model.profile import Profile, Segment
from dyade.synthesis import closed, function

KNOWN = closed.FourBar(0.35, 0.9, 0.7, 1.0, variant=1)
START, SPAN = math.radians(40.0), math.radians(120.0)


def _known_profile():
    """A quintic rise over 120° of master that meets the known four-bar's output angle,
    its slope and its curvature at both ends (so the four-bar follows it closely, not
    exactly), then a cycloid return."""
    h = 1e-4
    ends = []
    for at in (START, START + SPAN):
        psi = closed.output_angle(KNOWN, np.array([at - h, at, at + h]))
        ends.append((psi[1], (psi[2] - psi[0]) / (2 * h), (psi[2] - 2 * psi[1] + psi[0]) / h**2))
    lift = ends[1][0] - ends[0][0]
    rise = Segment("rise", 0.0, SPAN, 0.0, lift, law="polynomial",
                   start_velocity=ends[0][1], start_acceleration=ends[0][2],
                   end_velocity=ends[1][1], end_acceleration=ends[1][2])
    back = Segment("return", SPAN, 2 * math.pi, lift, 0.0, law="cycloid")
    return Profile((rise, back), period=2 * math.pi, unit="deg"), ends[0][0]


@pytest.mark.slow
def test_a_profile_that_a_known_four_bar_follows_closely_is_met_as_well():
    from dyade.motion.profile import evaluate

    profile, psi0 = _known_profile()
    master = np.linspace(0.0, SPAN, 41)
    lift = evaluate(profile, master).s
    known = np.abs(function.wrap(closed.output_angle(KNOWN, START + master) - psi0 - lift))
    assert 1e-5 < known.max() < math.radians(0.5)  # close, not exact
    made, offsets = function.from_profile(master, lift, "fit", frame=1.0)
    assert offsets.fitted
    # every row's structural error, traced through dyade's positions-only stage
    assert made.error.shape == (41,) and np.isfinite(made.error).all()
    assert np.allclose(made.crank - offsets.crank, master, atol=1e-12)
    assert np.abs(made.error).max() <= known.max() * (1 + 1e-6)
    # the traced output is the closed form's (an independent check of the figures)
    direct = closed.output_angle(made.linkage, made.crank)
    assert np.abs(function.wrap(direct - made.traced)).max() < 1e-10


def test_a_four_bars_own_function_as_a_profile_gives_it_back():
    psi = closed.output_angle(KNOWN, START + np.linspace(0.0, SPAN, 31))
    made, offsets = function.from_profile(np.linspace(0.0, SPAN, 31), psi - psi[0], "fit",
                                          frame=1.0)
    assert np.abs(made.error).max() < 1e-9
    # the same linkage, up to the pins' sides: a negative a puts the crank pin at
    # φ0 + 180°, a negative c the rocker's at ψ0 + 180°
    linkage = made.linkage
    assert (abs(linkage.a), linkage.b, abs(linkage.c)) == pytest.approx(
        (KNOWN.a, KNOWN.b, KNOWN.c), rel=1e-6)
    pin = math.degrees(offsets.crank) + (180.0 if linkage.a < 0 else 0.0)
    assert (pin - 40.0 + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=1e-6)


def test_the_synthesis_file_takes_a_profile_and_reports_every_row(tmp_path):
    profile = tmp_path / "rocker.toml"
    profile.write_text('[profile]\nunit = "deg"\nperiod = 360\n'
                       '[[profile.segment]]\nkind = "rise"\nlaw = "cycloid"\nend = 120\n'
                       'to = 40\n[[profile.segment]]\nkind = "return"\nlaw = "cycloid"\n'
                       'end = 360\nto = 0\n')
    path = tmp_path / "s.toml"
    path.write_text('units = { length = "mm", angle = "deg" }\n[target]\nkind = "function"\n'
                    'profile = "rocker.toml"\nrange = [0, 120]\nrows = 25\n'
                    'crank_zero = 60\noutput_zero = 80\nmethod = "chebyshev"\n'
                    '[scores]\nframe = 100\n')
    outcome = dyade.run("synthesis", str(path))
    assert outcome.columns["master_deg"] == pytest.approx(np.linspace(0, 120, 25))
    assert outcome.columns["crank_deg"] == pytest.approx(np.linspace(60, 180, 25))
    assert outcome.columns["output_deg"][0] == pytest.approx(80.0)
    assert np.isfinite(outcome.columns["error_deg"]).all()
    # exact at the three Chebyshev points of the range (the profile's own values there)
    made = outcome.result.function
    at = function.traced(made.linkage, made.precision)
    from dyade.motion.profile import evaluate

    wanted = math.radians(80.0) + evaluate(outcome.result.problem.target.profile,
                                           made.precision - math.radians(60.0)).s
    assert np.abs(function.wrap(at - wanted)).max() < 1e-12


@pytest.mark.parametrize("target, key, words", [
    ({"profile": {"unit": "mm", "period": 360, "segment": [
        {"kind": "rise", "law": "cycloid", "end": 360, "to": 10}]}, "range": [0, 90]},
     "target.profile", "length"),
    ({"profile": "missing.toml"}, "target.profile", "not a file"),
    ({"profile": {"unit": "deg", "period": 360, "segment": [
        {"kind": "rise", "law": "cycloid", "end": 360, "to": 10}]}}, "target.range",
     "come back"),
    ({"profile": {"unit": "deg", "period": 360, "segment": [
        {"kind": "rise", "law": "cycloid", "end": 360, "to": 10}]}, "output": [1, 2, 3]},
     "target.output", "not both"),
])
def test_bad_profile_targets_name_the_key(target, key, words):
    from dyade.errors import InputError

    with pytest.raises(InputError) as err:
        parse({"units": {"angle": "deg"}, "target": {"kind": "function", **target}}, "s.toml")
    assert key in str(err.value) and words in str(err.value)
