"""The only place with unit factors: user units <-> SI.

Inside dyade everything is SI (m, rad, s, kg, N); files and reports may use others.
Each factor is named by what it turns into what: ``RPM`` [rad/s per rpm] takes a speed
in rpm to rad/s (multiply), ``RAD_PER_S_TO_RPM`` [rpm per rad/s] a speed in rad/s to rpm.
"""

from __future__ import annotations

import math

LENGTH_FACTORS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6}  # [m per unit]
ANGLE_FACTORS = {"deg": math.pi / 180.0, "rad": 1.0}  # [rad per unit]
RPM = 2.0 * math.pi / 60.0  # [rad/s per rpm]
RAD_PER_S_TO_RPM = 30.0 / math.pi  # [rpm per rad/s]
DEG = math.pi / 180.0  # [rad per degree]


def rpm_to_rad_per_s(rpm: float) -> float:
    """Crank speed [rpm] -> angular velocity [rad/s]."""
    return rpm * RPM


def rad_per_s_to_rpm(speed: float) -> float:
    """Angular velocity [rad/s] -> speed [rpm]."""
    return speed * RAD_PER_S_TO_RPM
