"""A motion profile of several segments: continuous where its classes require, its
derivatives those of its position, its checks naming the segment and key."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.model.profile import Profile, Segment
from dyade.motion.profile import at_speed, boundaries, check, evaluate, peaks, segment_laws

DEG = math.pi / 180


def seg(kind, start, end, lift_from, lift_to, law=None, **more):
    return Segment(kind, start * DEG, end * DEG, lift_from * 1e-3, lift_to * 1e-3, law, **more)


def indexing() -> Profile:
    """dwell, rise (modified sine), constant velocity entered and left by matched
    polynomials, return (4-5-6-7), dwell: lift in mm, master in degrees."""
    return Profile((
        seg("dwell", 0, 40, 0, 0),
        seg("rise", 40, 120, 0, 30, "modified-sine"),
        seg("rise", 120, 160, 30, 40, "polynomial", start_velocity=0.0,
            start_acceleration=0.0),
        seg("constant-velocity", 160, 200, 40, 60),
        seg("rise", 200, 230, 60, 70, "polynomial"),
        seg("return", 230, 330, 70, 0, "polynomial-4567"),
        seg("dwell", 330, 360, 0, 0)), period=2 * math.pi)


def test_continuous_to_1e_12_where_the_classes_require():
    profile = indexing()
    for boundary in boundaries(profile):
        ds, dv, da, _ = boundary.jumps
        assert abs(ds) < 1e-12 and abs(dv) < 1e-12 and abs(da) < 1e-12, boundary
    assert check(profile) == ()
    x = np.array([b.x for b in boundaries(profile)])
    for h in (1e-12, -1e-12):                 # the evaluated motion on both sides
        near = evaluate(profile, x + h)
        at = evaluate(profile, x)
        assert np.max(np.abs(near.s - at.s)) < 1e-11
        assert np.max(np.abs(near.v - at.v)) < 1e-11
        assert np.max(np.abs(near.a - at.a)) < 1e-10


def test_matched_polynomial_takes_its_neighbours():
    profile = indexing()
    laws = segment_laws(profile)
    assert [law.boundary if law else None for law in laws] == [
        None, "R-R", "R-G", "G-G", "G-R", "R-R", None]


def test_derivatives_are_those_of_the_position_over_the_cycle():
    profile = indexing()
    x = np.linspace(1.0, 359.0, 23) * DEG            # away from the boundaries
    motion = evaluate(profile, x)
    errors = []
    for h in (2e-4, 1e-4):
        ahead, behind = evaluate(profile, x + h), evaluate(profile, x - h)
        errors.append([np.max(np.abs((getattr(ahead, f) - getattr(behind, f)) / (2 * h)
                                     - getattr(motion, g)))
                       for f, g in (("s", "v"), ("v", "a"), ("a", "j"))])
    for coarse, fine in zip(*errors):
        assert fine < 1e-6 * (1 + np.max(np.abs(motion.j)))
        assert coarse / fine == pytest.approx(4.0, rel=0.05)


def test_periodic_and_advancing():
    profile = indexing()
    x = np.linspace(0, 2 * math.pi, 50)
    one, next_cycle = evaluate(profile, x), evaluate(profile, x + 2 * math.pi)
    np.testing.assert_allclose(next_cycle.s, one.s, atol=1e-15)
    table = Profile((seg("rise", 0, 270, 0, 90, "cycloid"), seg("dwell", 270, 360, 90, 90)),
                    period=2 * math.pi, unit="deg")
    np.testing.assert_allclose(evaluate(table, np.array([3 * math.pi])).s,
                               evaluate(table, np.array([math.pi])).s + 0.09)
    assert check(table) == ()


def test_peaks_are_the_sampled_maxima():
    profile = indexing()
    motion = evaluate(profile, np.linspace(0, 2 * math.pi, 200001))
    rise = peaks(profile)[1]
    assert rise.law == "modified-sine" and rise.boundary == "R-R"
    # h·C_v/T of the modified sine: 30 mm over 80°
    assert rise.velocity == pytest.approx(0.03 * 1.7596 / (80 * DEG), rel=1e-4)
    assert max(p.velocity for p in peaks(profile)) == pytest.approx(
        np.max(np.abs(motion.v)), rel=1e-6)
    assert max(p.acceleration for p in peaks(profile)) == pytest.approx(
        np.max(np.abs(motion.a)), rel=1e-6)


def test_at_speed_scales_the_derivatives():
    motion = evaluate(indexing(), np.array([1.0]))
    timed = at_speed(motion, 2.0)
    assert (timed.x[0], timed.v[0], timed.a[0], timed.j[0]) == pytest.approx(
        (0.5, 2 * motion.v[0], 4 * motion.a[0], 8 * motion.j[0]))


def test_acceleration_jump_allowed_by_the_class_is_a_note():
    profile = Profile((seg("rise", 0, 180, 0, 10, "simple-harmonic"),
                       seg("dwell", 180, 200, 10, 10),
                       seg("return", 200, 360, 10, 0, "cycloid")), period=2 * math.pi)
    notes = check(profile)
    assert len(notes) == 2 and "simple harmonic, class U-U" in notes[0]


def test_velocity_jump_refused_naming_the_segment():
    profile = Profile((seg("rise", 0, 180, 0, 10, "cycloid"),
                       seg("constant-velocity", 180, 270, 10, 20),
                       seg("return", 270, 360, 20, 0, "polynomial")), period=2 * math.pi)
    with pytest.raises(InputError, match=r"segment 2 \(constant-velocity.*velocity jump") as err:
        check(profile)
    assert err.value.key == "profile.segment.2.law"


def test_given_acceleration_that_does_not_meet_is_refused():
    profile = Profile((seg("rise", 0, 180, 0, 10, "polynomial", end_acceleration=1.0),
                       seg("return", 180, 360, 10, 0, "cycloid")), period=2 * math.pi)
    with pytest.raises(InputError, match="segment 1 .*`end_acceleration` does not meet"):
        check(profile)


def test_declared_class_checked():
    profile = Profile((seg("rise", 0, 180, 0, 10, "simple-harmonic", boundary="R-R"),
                       seg("return", 180, 360, 10, 0, "simple-harmonic")), period=2 * math.pi)
    with pytest.raises(InputError, match="`boundary` = \"R-R\" but the law simple-harmonic"):
        check(profile)


@pytest.mark.parametrize("segments, key, words", [
    ([seg("rise", 0, 180, 0, 10, "cycloid"), seg("return", 190, 360, 10, 0, "cycloid")],
     "profile.segment.2.start", "does not meet the end of segment 1"),
    ([seg("rise", 0, 180, 0, 10, "cycloid"), seg("return", 180, 360, 12, 0, "cycloid")],
     "profile.segment.2.from", "a jump in position"),
    ([seg("rise", 0, 180, 0, 10, "cycloid"), seg("dwell", 180, 180, 10, 10),
      seg("return", 180, 360, 10, 0, "cycloid")],
     "profile.segment.2.end", "positive duration, got 0"),
    ([seg("rise", 0, 200, 0, 10, "cycloid"), seg("return", 200, 180, 10, 0, "cycloid")],
     "profile.segment.2.end", "positive duration, got -0.349"),
    ([seg("rise", 0, 180, 0, 10, "cycloid"), seg("return", 180, 300, 10, 0, "cycloid")],
     "profile.segment.2.end", "the period is 6.28319"),
    ([seg("rise", 0, 180, 10, 0, "cycloid"), seg("return", 180, 360, 0, 10, "cycloid")],
     "profile.segment.1.to", "a rise goes up"),
    ([seg("rise", 0, 180, 0, 10), seg("return", 180, 360, 10, 0, "cycloid")],
     "profile.segment.1.law", "is missing"),
    ([seg("rise", 0, 180, 0, 10, "cycloid"), seg("dewll", 180, 360, 10, 10)],
     "profile.segment.2.kind", "Did you mean `dwell`?"),
])
def test_bad_segments_name_segment_and_key(segments, key, words):
    with pytest.raises(InputError, match=re.escape(words)) as err:
        Profile(tuple(segments), period=2 * math.pi)
    assert err.value.key == key


def test_misspelt_law_named_with_its_segment():
    profile = Profile((seg("rise", 0, 180, 0, 10, "cycloid"),
                       seg("return", 180, 360, 10, 0, "modifed-sine")), period=2 * math.pi)
    with pytest.raises(InputError, match=r"segment 2 \(return, modifed-sine\): `law` = "
                                         r"\"modifed-sine\" is not a motion law. Did you mean "
                                         r"`modified-sine`\?"):
        segment_laws(profile)


import re  # noqa: E402  (used by the parametrised test above)


def test_polynomial_takes_a_neighbours_acceleration():
    # the simple harmonic ends in a reversal (U: a ≠ 0); the quintic return takes its
    # velocity and acceleration there, so only the start at the dwell keeps a jump of a
    profile = Profile((seg("dwell", 0, 30, 0, 0),
                       seg("rise", 30, 150, 0, 10, "simple-harmonic"),
                       seg("return", 150, 270, 10, 0, "polynomial"),
                       seg("dwell", 270, 360, 0, 0)), period=2 * math.pi)
    hand_over = boundaries(profile)[2]
    assert abs(hand_over.left[2]) > 1e-3                   # the reversal's acceleration
    assert max(abs(jump) for jump in hand_over.jumps[:3]) < 1e-12
    notes = check(profile)
    assert len(notes) == 1 and "start of segment 2" in notes[0]
    assert segment_laws(profile)[2].boundary == "U-R"
