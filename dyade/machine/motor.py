"""Motor characteristics and the drive of a machine (the ``[drive]`` table of a file).

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
        rpm = 60.0 / (2.0 * np.pi)
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
        rpm = 60.0 / (2.0 * np.pi)
        return (f"torque-speed table, {self.speeds.size} points "
                f"{self.speeds[0] * rpm:g}–{self.speeds[-1] * rpm:g} rpm")


Motor = Union[ConstantTorque, Asynchronous, TorqueSpeedTable]


def operating_speed(motor: Motor, torque: float, default: float) -> float:
    """The speed [rad/s] at which ``motor`` gives ``torque`` [N·m]: on an asynchronous
    motor's straight line (when positive), at the last crossing of a torque-speed table
    (not on a flat piece); ``default`` where there is none (a constant-torque motor)."""
    if isinstance(motor, Asynchronous):
        speed = motor.synchronous_speed - torque / motor.stiffness
        return speed if speed > 0.0 else default
    if isinstance(motor, TorqueSpeedTable):
        w, m = motor.speeds, motor.values
        crossing = np.flatnonzero((m[:-1] - torque) * (m[1:] - torque) <= 0.0)
        if crossing.size and m[crossing[-1] + 1] != m[crossing[-1]]:
            k = crossing[-1]
            return float(w[k] + (torque - m[k]) * (w[k + 1] - w[k]) / (m[k + 1] - m[k]))
    return default


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


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class DriveLineData:
    """The ``[drive_line]`` table of a mechanism file (SI): the elastic element between
    the motor and the crank shaft. Stiffness and damping are those the crank shaft
    sees (behind the gear); the rotor's inertia is on the motor shaft and enters reduced
    by ratio²; a ``[drive]`` motor's characteristic is on the crank shaft, as without a
    drive line."""

    stiffness: float | None
    """k [N·m/rad] of a shaft; None with a coupling"""
    damping: float = 0.0
    """b [N·m·s/rad]"""
    ratio: float = 1.0
    """i = motor speed / crank speed [-]"""
    rotor_inertia: float | None = None
    """J_rotor [kg·m²] on the motor shaft (needed with a ``[drive]`` motor)"""
    coupling: object | None = None
    """a ``dyade.vibration.coupling.Coupling`` in the line instead of the shaft: its
    primary side (c1, b1), where Strümpfel's exciting moment acts, faces the linkage,
    its secondary side (c2, b2) the motor"""
    coupling_file: str | None = None
    """the coupling file as the mechanism file names it"""
    steps: int | None = None
    """RK4 steps per revolution (None: 64 per period of the highest natural frequency,
    at least 720)"""

    def describe(self) -> str:
        if self.coupling is not None:
            text = f"coupling {self.coupling_file}"
        else:
            text = f"shaft {self.stiffness:g} N·m/rad, damping {self.damping:g} N·m·s/rad"
        if self.rotor_inertia:
            text += f", rotor {self.rotor_inertia:g} kg·m²"
        if self.ratio != 1.0:
            text += f", ratio {self.ratio:g}"
        return text
