"""Motor characteristics and the drive of a machine (the ``[drive]`` table of a file),
SI: the data; what is computed from a characteristic beyond its own torque
(``operating_speed``) is in ``dyade.machine.motor``.

A characteristic gives the torque m(w) [N·m] the motor applies in its running direction
at the speed w ≥ 0 [rad/s] of the crank shaft (for a gear motor: of its output shaft),
and its slope dm/dw. The equation of motion (``dyade.machine.equation``) turns it into
the crank's sense of rotation.

>>> motor = Asynchronous(rated_torque=10.0, rated_speed=30.0, synchronous_speed=31.4)
>>> round(motor.torque(30.0), 6), round(motor.torque(31.4), 6)
(10.0, 0.0)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

import numpy as np

from dyade.arrays import FloatArray
from dyade.units import RAD_PER_S_TO_RPM


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class ConstantTorque:
    """A motor of constant torque, whatever the speed."""

    torque: float | None
    """[N·m]; None: the torque that holds the crank's nominal mean speed (the mean drive
    torque), found with the periodic state"""

    name = "constant torque"

    def at(self, speed: float) -> tuple[float, float]:
        """(m, dm/dw) at the speed w [rad/s]."""
        return (self.torque or 0.0), 0.0

    def torques(self, speed: FloatArray) -> FloatArray:
        """m at the speeds w [rad/s]."""
        return np.full_like(speed, self.torque or 0.0)

    def describe(self) -> str:
        if self.torque is None:
            return "constant torque (the mean drive torque at the nominal speed)"
        return f"constant torque {self.torque:g} N·m"


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Asynchronous:
    """An asynchronous (induction) motor near its synchronous speed, linear in the slip:
    m = M_N·(ω_s − w)/(ω_s − ω_N)."""

    rated_torque: float
    """M_N [N·m]"""
    rated_speed: float
    """ω_N [rad/s], below ω_s"""
    synchronous_speed: float
    """ω_s [rad/s]"""

    name = "asynchronous (linear near synchronous speed)"

    @property
    def stiffness(self) -> float:
        """−dm/dw = M_N/(ω_s − ω_N) [N·m·s/rad]"""
        return self.rated_torque / (self.synchronous_speed - self.rated_speed)

    def torque(self, speed):
        """m at the speed(s) w [rad/s]."""
        return self.stiffness * (self.synchronous_speed - speed)

    torques = torque

    def at(self, speed: float) -> tuple[float, float]:
        k = self.stiffness
        return k * (self.synchronous_speed - speed), -k

    def describe(self) -> str:
        rpm = RAD_PER_S_TO_RPM
        return (f"asynchronous, M_N = {self.rated_torque:g} N·m at {self.rated_speed * rpm:g} "
                f"rpm, synchronous {self.synchronous_speed * rpm:g} rpm")


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class TorqueSpeedTable:
    """A measured characteristic: torque over speed, interpolated linearly."""

    speeds: FloatArray
    """(k,) w [rad/s], rising"""
    values: FloatArray
    """(k,) m [N·m] at those speeds"""

    name = "torque-speed table"

    def at(self, speed: float) -> tuple[float, float]:
        w, m = self.speeds, self.values
        k = int(np.clip(np.searchsorted(w, speed, side="right") - 1, 0, w.size - 2))
        slope = (m[k + 1] - m[k]) / (w[k + 1] - w[k])
        return float(m[k] + slope * (speed - w[k])), float(slope)

    def torques(self, speed: FloatArray) -> FloatArray:
        """m at the speeds w [rad/s] (the end segments extended beyond the table)."""
        w, m = self.speeds, self.values
        k = np.clip(np.searchsorted(w, speed, side="right") - 1, 0, w.size - 2)
        return m[k] + (m[k + 1] - m[k]) / (w[k + 1] - w[k]) * (speed - w[k])

    def covers(self, speed: float) -> bool:
        """True when ``speed`` [rad/s] lies within the table (to round-off)."""
        span = self.speeds[-1] - self.speeds[0]
        return bool(self.speeds[0] - 1e-9 * span <= speed <= self.speeds[-1] + 1e-9 * span)

    def describe(self) -> str:
        rpm = RAD_PER_S_TO_RPM
        return (f"torque-speed table, {self.speeds.size} points "
                f"{self.speeds[0] * rpm:g}–{self.speeds[-1] * rpm:g} rpm")


Motor = Union[ConstantTorque, Asynchronous, TorqueSpeedTable]


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Drive:
    """The drive of a machine: its motor, a flywheel on the crank shaft, and how the
    equation of motion is solved."""

    motor: Motor
    flywheel_inertia: float = 0.0
    """J_F [kg·m²] on the crank shaft (counted as part of the crank, link 2)"""
    steps: int | None = None
    """integration steps per revolution (None: from the sweep step, at least 720)"""
    tol: float = 1e-10
    """relative change of the kinetic energy over one revolution at which the motion
    counts as periodic [-]"""
    max_revolutions: int = 500
    """most revolutions of a run-up"""
