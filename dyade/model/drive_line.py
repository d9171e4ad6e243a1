"""The elastic drive line of a mechanism file (the ``[drive_line]`` table), SI: the data.

The line the engine integrates is built from it with the motor of the ``[drive]`` table
(``dyade.machine.drive_line.line_from``); the linkage enters it as the crank shaft
(``dyade.linkage.drive_line``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from dyade.model.coupling import Coupling


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
    coupling: Coupling | None = None
    """a stiff coupling (``dyade.model.coupling``) in the line instead of the shaft: its
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
