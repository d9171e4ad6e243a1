"""A torque curve as a CSV file gives it, SI: the crank angles and the torques on the
crank shaft over one revolution (``dyade.files.torque_curve`` reads it; the flywheel's
``dyade.machine.flywheel.table_curve`` makes the ``TorqueCurve`` it sizes a flywheel for).
"""

from __future__ import annotations

from dataclasses import dataclass

from dyade.arrays import FloatArray


@dataclass(frozen=True, slots=True, eq=False)  # holds arrays: no meaningful ==
class TorqueTable:
    """The columns of a torque-curve CSV, in SI."""

    angle: FloatArray
    """(n,) crank angles φ, rising [rad] (the file's ``angle_deg``)"""
    drive: FloatArray
    """(n,) the torque driving the crank shaft [N·m] (``M_drive``)"""
    load: FloatArray | None = None
    """(n,) the load torque, positive where it drives the machine [N·m] (``M_load``);
    None: not given"""
    inertia: FloatArray | None = None
    """(n,) the machine's reduced moment of inertia [kg·m²] (``J_red``); None: not given"""
    speed: FloatArray | None = None
    """(n,) the crank speed [rad/s] (``omega_2``); None: not given"""
    machine: bool = False
    """a CSV of ``dyade analyse`` (it has ``dJ_red``): ``drive`` is a machine's drive
    torque at constant speed, its loads included"""
    source: str = ""
    """the file's name, for reports"""
