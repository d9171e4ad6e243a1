"""The cam file reader (issue 40): keys in the file's units, errors naming the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from dyade.errors import InputError
from dyade.files.cam import read_cam

CAMS = Path("mechanisms/cams")


def test_the_examples_read_in_si():
    cam = read_cam(CAMS / "oscillating-roller.toml")
    assert cam.follower == "oscillating-roller" and cam.arm_length == pytest.approx(0.07)
    assert cam.preload == pytest.approx(0.5235987755982988)  # 30° in rad
    assert cam.profile.unit == "deg" and cam.cutter_radius == pytest.approx(0.008)
    flat = read_cam(CAMS / "flat-faced.toml")
    assert flat.roller_radius == 0.0 and flat.chord_tolerance == pytest.approx(5e-6)
    chained = read_cam(CAMS / "cam-linkage.toml")
    assert chained.chain.crank.length == pytest.approx(0.07) and chained.chain_centre == (0.0, 0.0)


@pytest.mark.parametrize("old, new, message", [
    ('follower = "translating-roller"', 'follower = "translating-rolle"',
     "`cam.follower` must be a follower kind, got \"translating-rolle\". Did you mean "
     "`translating-roller`?"),
    ("offset = 8 ", "pivot_distance = 8 ",
     "`follower.pivot_distance` is not a key of a translating-roller follower"),
    ("roller_radius = 10", "roller_radius = -10", "`follower.roller_radius` must be positive"),
    ("offset = 8 ", "offset = 60 ", "`follower.offset` must be less than the pitch radius"),
    ('unit = "mm"\nperiod = 360', 'unit = "deg"\nperiod = 360',
     "`profile.unit` must be a length (m, cm, mm, um) for a translating-roller follower"),
    ('rotation = "ccw"', 'rotation = "clockwise"', '`cam.rotation` must be "ccw" or "cw"'),
    ("chord_tolerance = 0.005", "chord_tolerance = 0.00001",
     "`manufacture.chord_tolerance` must be at least 1e-07 m"),
])
def test_errors_name_the_key(tmp_path, old, new, message):
    text = (CAMS / "translating-roller.toml").read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "cam.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(InputError) as err:
        read_cam(path)
    assert str(err.value).startswith("cam.toml: ") and message in str(err.value)


def test_a_chain_whose_crank_is_not_the_lever(tmp_path):
    text = (CAMS / "cam-linkage.toml").read_text(encoding="utf-8")
    (tmp_path / "lever-slider.toml").write_text(
        (CAMS / "lever-slider.toml").read_text(encoding="utf-8"), encoding="utf-8")
    path = tmp_path / "chain.toml"
    path.write_text(text.replace("centre = [0, 0]", "centre = [5, 0]"), encoding="utf-8")
    with pytest.raises(InputError, match=r"chain.toml: `chain.centre` puts the cam centre "
                                         r"0.085 m from the chain's crank pivot"):
        read_cam(path)
