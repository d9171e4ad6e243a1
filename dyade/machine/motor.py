"""What is computed from a motor's characteristic beyond its own torque (the
characteristics themselves, the data of a ``[drive]`` table, are in ``dyade.model.drive``).
"""

from __future__ import annotations

import numpy as np

from dyade.model.drive import Asynchronous, Motor, TorqueSpeedTable


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
