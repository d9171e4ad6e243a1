"""The only place with unit factors: user units <-> SI.

Inside dyade everything is SI (m, rad, s, kg, N); files and reports may use others.
"""

from __future__ import annotations

import math

LENGTH_FACTORS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6}  # [m per unit]
ANGLE_FACTORS = {"deg": math.pi / 180.0, "rad": 1.0}  # [rad per unit]
RPM = 2.0 * math.pi / 60.0  # [rad/s per rpm]
DEG = math.pi / 180.0  # [rad per degree]


def rpm_to_rad_per_s(rpm: float) -> float:
    """Crank speed [rpm] -> angular velocity [rad/s]."""
    return rpm * RPM
