"""A servo-driven crank (the ``[servo]`` table of a mechanism file), its gear and the
motors of a catalogue, SI: the data. What is computed from them (the motor's torque
over the cycle, the sizing checks) is in ``dyade.machine.servo``; the crank's motion
from a profile and the linkage's torque in ``dyade.linkage.servo``.

>>> gear = Gear(ratio=5.0, efficiency=0.9, inertia=1e-4)
>>> motor = ServoMotor("M1", rated_torque=2.0, peak_torque=6.0, rated_speed=314.16,
...                    top_speed=628.3, rotor_inertia=2e-4)
>>> [float(t) for t in motor.envelope([0.0, 600.0, 700.0])]   # [N·m] at [rad/s]
[6.0, 6.0, 0.0]
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dyade.arrays import FloatArray


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Gear:
    """The gear between the servo motor and the crank shaft."""

    ratio: float = 1.0
    """i = motor speed / crank speed [-]"""
    efficiency: float = 1.0
    """η [-] in (0, 1]: the motor side gives M/(i·η) while it drives the crank, takes
    M·η/i back while the crank drives it (braking)"""
    inertia: float = 0.0
    """J_G [kg·m²], the gear's own moment of inertia on the motor shaft"""


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class ServoMotor:
    """One servo motor of a catalogue (or the ``[servo]`` table's own rotor)."""

    name: str
    rated_torque: float
    """M_N [N·m], the continuous (thermal) torque: the RMS torque of a cycle must not
    exceed it"""
    peak_torque: float
    """M_max [N·m], the peak torque at low speed"""
    rated_speed: float
    """n_N [rad/s]"""
    top_speed: float
    """n_max [rad/s]"""
    rotor_inertia: float
    """J_M [kg·m²]"""
    envelope_speeds: FloatArray | None = None
    """(k,) speeds of the peak-torque envelope [rad/s], rising; None: the peak torque
    holds up to the top speed"""
    envelope_torques: FloatArray | None = None
    """(k,) the peak torque available at those speeds [N·m]"""

    def envelope(self, speed: Any) -> FloatArray:
        """The peak torque available at the motor speeds ``speed`` [rad/s] (their
        magnitude), linear between the envelope's points and 0 beyond the top speed [N·m]."""
        w = np.abs(np.asarray(speed, dtype=np.float64))
        if self.envelope_speeds is None:
            torque = np.full(w.shape, self.peak_torque)
        else:
            torque = np.interp(w, self.envelope_speeds, self.envelope_torques)
        return np.where(w <= self.top_speed * (1.0 + 1e-12), torque, 0.0)


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Catalogue:
    """Servo motors of a catalogue file (CSV), in the file's order."""

    motors: tuple[ServoMotor, ...]
    source: str | None = None
    """the file as the user named it"""


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Servo:
    """The ``[servo]`` table: the crank follows a motion profile over the cycle time,
    through a gear, driven by a servo motor (its rotor inertia, or a catalogue to choose
    one from)."""

    profile: Any
    """the motion profile (``dyade.model.profile.Profile``)"""
    output: str = "crank"
    """what the profile moves: ``"crank"`` (the crank angle) or a column of the sweep, a
    slider's travel ``s_i_j`` [m] or a link's angle ``phi_N`` [rad]: then the profile is
    inverted through the linkage to the crank's motion"""
    start: float = 0.0
    """the crank angle at the cycle's start [rad]"""
    gear: Gear = field(default_factory=Gear)
    rotor_inertia: float | None = None
    """J_M [kg·m²] of the servo motor (None: from the catalogue's motors only)"""
    catalogue: Catalogue | None = None
    ratio_range: tuple[float, float] | None = None
    """(i_min, i_max): the gear ratios to size over (None: the gear's ratio only)"""
    samples: int = 720
    """time points per cycle [-]"""
    max_inertia_ratio: float = 10.0
    """the largest load-to-motor inertia ratio a motor passes with [-]"""
    cycle_time: float | None = None
    """T [s], the time of one cycle when the profile's master is an angle (a virtual
    line shaft turning once per ``profile.period``); None: the profile's master is time
    and its period is the cycle time"""
