"""A joint's line of action says "no force" only where its force is given and zero,
never where it is withheld (issue 42)."""

from __future__ import annotations

import numpy as np

from dyade.linkage.joint_clearance import NO_FORCE, NOT_GIVEN, force_line

ANGLE = np.linspace(0.0, 2.0 * np.pi, 37)


def test_a_withheld_force_is_not_a_zero_force():
    withheld = force_line((3, 4), ANGLE, np.full((ANGLE.size, 2), np.nan), True)
    zero = force_line((3, 4), ANGLE, np.zeros((ANGLE.size, 2)), True)
    assert withheld.reason == NOT_GIVEN and "not given" in withheld.reason
    assert zero.reason == NO_FORCE == "the joint carries no force"
    given = np.stack([np.cos(ANGLE), np.zeros_like(ANGLE)], axis=1)  # along x, reversing
    line = force_line((3, 4), ANGLE, given, True)
    assert line.applies and np.isclose(np.sin(line.line_angle), 0.0)
