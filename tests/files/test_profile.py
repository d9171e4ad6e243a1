"""The profile reader: keys in the file's units to SI, errors naming file, segment, key."""

from __future__ import annotations

import math

import pytest

from dyade.errors import InputError
from dyade.files.profile import read_profile

HEAD = '[profile]\nmaster = "angle"\nperiod = 360\nunit = "mm"\n'


def write(tmp_path, body, head=HEAD, name="p.toml"):
    path = tmp_path / name
    path.write_text(head + body, encoding="utf-8")
    return path


def segment(**keys):
    lines = ["[[profile.segment]]"]
    for key, value in keys.items():
        key = {"frm": "from"}.get(key, key)
        lines.append(f"{key} = {value!r}".replace("'", '"'))
    return "\n".join(lines) + "\n"


GOOD = (segment(kind="dwell", end=60) + segment(kind="rise", law="cycloid", end=180, to=40)
        + segment(kind="return", law="polynomial-345", end=360, to=0))


def test_reads_to_si(tmp_path):
    profile = read_profile(write(tmp_path, GOOD))
    rise = profile.segments[1]
    assert (rise.start, rise.end) == pytest.approx((math.pi / 3, math.pi))
    assert (rise.lift_from, rise.lift_to) == pytest.approx((0.0, 0.04))
    assert profile.period == pytest.approx(2 * math.pi) and profile.name == "p"


def test_given_end_conditions_in_the_files_units(tmp_path):
    body = (segment(kind="rise", law="polynomial", end=180, to=10, end_velocity=0.05)
            + segment(kind="constant-velocity", end=200, to=11)
            + segment(kind="return", law="cycloid", end=360, to=0))
    rise = read_profile(write(tmp_path, body)).segments[0]
    assert rise.end_velocity == pytest.approx(0.05e-3 / (math.pi / 180))   # mm/° -> m/rad


def test_profile_table_in_a_mechanism_file():
    profile = read_profile("mechanisms/profiles/indexing.toml")
    assert profile.name == "indexing stroke"


@pytest.mark.parametrize("body, key, words", [
    (segment(kind="rise", law="cycloid", end=180, to=10)
     + segment(kind="return", law="cycloid", start=190, end=360, to=0),
     "profile.segment.2.start", "= 190° does not meet the end of segment 1 (180°)"),
    (segment(kind="rise", law="cycloid", end=180, to=10)
     + segment(kind="return", law="cycloid", end=360, frm=12, to=0),
     "profile.segment.2.from", "a jump in position"),
    (segment(kind="rise", law="cycloid", end=180, to=10) + segment(kind="dwell", end=180)
     + segment(kind="return", law="cycloid", end=360, to=0),
     "profile.segment.2.end", "positive duration, got 0°"),
    (segment(kind="rise", law="cycloid", end=180, to=10) + segment(kind="dwell", end=150)
     + segment(kind="return", law="cycloid", end=360, to=0),
     "profile.segment.2.end", "positive duration, got -30°"),
    (segment(kind="rise", law="cycloid", end=180, to=10)
     + segment(kind="return", law="cycloid", end=300, to=0),
     "profile.segment.2.end", "the period is 360°"),
    (segment(kind="rise", law="cycloid", end=360, to=10, lenght=3),
     "profile.segment.1.lenght", "unknown key"),
    (segment(kind="rise", end=360, to=10), "profile.segment.1.law", "is missing"),
    (segment(kind="rise", law="cycloid", end=360), "profile.segment.1.to", "is missing"),
    (segment(kind="rise", law="cycloid", end=360, to=10, start_velocity=1.0),
     "profile.segment.1.start_velocity", "of the law \"polynomial\" only"),
])
def test_bad_files_name_file_and_key(tmp_path, body, key, words):
    with pytest.raises(InputError) as err:
        read_profile(write(tmp_path, body))
    assert str(err.value).startswith(f"p.toml: `{key}`") or key in str(err.value)
    assert words in str(err.value)
    assert err.value.key == key


def test_no_profile_table(tmp_path):
    with pytest.raises(InputError, match="has no \\[profile\\] table"):
        read_profile(write(tmp_path, "", head='name = "x"\n'))


def test_constant_velocity_runs_its_own_law(tmp_path):
    body = (segment(kind="rise", law="cycloid", end=180, to=10)
            + segment(kind="constant-velocity", law="cycloid", end=200, to=11)
            + segment(kind="return", law="cycloid", end=360, to=0))
    with pytest.raises(InputError, match=r"p.toml: segment 2 \(constant-velocity, cycloid\): "
                                         r"`law` = 'cycloid' for a constant velocity") as err:
        read_profile(write(tmp_path, body))
    assert err.value.key == "profile.segment.2.law"


def test_a_segment_shorter_than_the_meeting_tolerance_is_refused(tmp_path):
    body = segment(kind="rise", law="cycloid", end=1e-300, to=10) + segment(kind="dwell",
                                                                            end=360)
    with pytest.raises(InputError, match="profile.segment.1.end.*positive duration"):
        read_profile(write(tmp_path, body))
