"""``dyade/units.py`` is the only place with unit factors (issue 36): no other module
writes a speed factor of its own (30/π, π/30, 60/(2π), 2π/60) or binds ``RPM`` to one,
and the two speed factors of units.py are each other's inverse."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from dyade import units

PACKAGE = Path(__file__).resolve().parent.parent / "dyade"
PI = r"(?:math|np|numpy)\.pi"
FACTOR = re.compile(
    rf"\b30(?:\.0*)?\s*/\s*{PI}|{PI}\s*/\s*30(?:\.0*)?\b"          # 30/π, π/30
    rf"|\b60(?:\.0*)?\s*/\s*\(\s*2(?:\.0*)?\s*\*\s*{PI}\s*\)"       # 60/(2π)
    rf"|\b2(?:\.0*)?\s*\*\s*{PI}\s*/\s*60(?:\.0*)?\b"               # 2π/60
    r"|^\s*RPM\s*=", re.M)                                          # a local RPM factor


def offences(text: str) -> list[str]:
    return [match.group(0).strip() for match in FACTOR.finditer(text)]


def test_no_module_but_units_has_a_speed_factor():
    found = [f"{path.relative_to(PACKAGE.parent)}:{text.count(chr(10), 0, m.start()) + 1}: "
             f"{m.group(0).strip()}"
             for path in sorted(PACKAGE.rglob("*.py")) if path.name != "units.py"
             for text in [path.read_text(encoding="utf-8")] for m in FACTOR.finditer(text)]
    assert not found, ("unit factors belong in dyade/units.py (RPM [rad/s per rpm], "
                       "RAD_PER_S_TO_RPM [rpm per rad/s]):\n  " + "\n  ".join(found))


@pytest.mark.parametrize("text", ["x * 30.0 / math.pi", "speed_rpm * math.pi / 30.0",
                                  "w * 60.0 / (2.0 * np.pi)", "order * n * 2 * np.pi / 60",
                                  "x * 30 / np.pi", "RPM = 9.5"])
def test_the_scan_finds_a_factor(text):
    assert offences(text)


def test_the_scan_passes_what_is_no_speed_factor():
    assert not offences("angle = 2.0 * math.pi / steps\nh = math.pi / 300\nRPM_X = 1\n"
                        "speed * RAD_PER_S_TO_RPM\nx = 130 / np.pi")


def test_the_two_speed_factors():
    assert units.RPM == 2.0 * math.pi / 60.0 and units.RAD_PER_S_TO_RPM == 30.0 / math.pi
    assert units.RPM * units.RAD_PER_S_TO_RPM == pytest.approx(1.0, rel=1e-15)
    assert units.rpm_to_rad_per_s(60.0) == pytest.approx(2.0 * math.pi, rel=1e-15)
    assert units.rad_per_s_to_rpm(math.pi) == pytest.approx(30.0, rel=1e-15)
