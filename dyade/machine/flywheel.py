"""The flywheel from a torque curve: energy fluctuation, flywheel inertia, speed
fluctuation (Dresig & Holzweißig, *Maschinendynamik*; VDI 2149).

Over one revolution at the mean speed Ω, the torque that accelerates the crank shaft
is the excess ΔM(φ) of the driving torque over the resisting one (zero on average).
Its integral E(φ) = ∫ΔM dφ is the kinetic energy gained since the start; it is highest
where the shaft runs fastest and lowest where it runs slowest, and

    ΔE = max E − min E,   δ = (ω_max − ω_min)/ω_mean ≈ ΔE/(J·Ω²),

so a total inertia J = ΔE/(δ·Ω²) keeps the speed fluctuation near δ; the flywheel is J
less the machine's own mean reduced inertia. E(φ) is integrated from the samples with
the cubic Hermite interpolant of the torque (slopes by three-point differences, fourth
order for smooth curves), and its extremes are found between the samples, where the
interpolant crosses zero.

>>> import numpy as np
>>> theta = np.deg2rad(np.arange(0.0, 360.0, 1.0))        # one revolution
>>> engine = 10000 + 2000 * np.sin(2 * theta) - 1800 * np.cos(2 * theta)   # [N·m]
>>> from dyade.units import RPM                             # [rad/s per rpm]
>>> curve = excess_curve(theta, engine, speed=250 * RPM)   # against a constant load
>>> result = size_flywheel(curve, 0.005)
>>> round(result.power / 1e3, 3), round(result.delta_energy, 3), round(result.flywheel, 2)
(261.799, 2690.725, 785.17)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dyade.arrays import FloatArray
from dyade.cycle import integrals, mean as cycle_mean, segments
from dyade.errors import DyadeError, InputError
from dyade.units import rpm_to_rad_per_s

if TYPE_CHECKING:
    from dyade.model.torque_table import TorqueTable

LARGE_FLUCTUATION = 0.1  # [-] above this the small-fluctuation estimate δ ≈ ΔE/(J·Ω²) is rough
MEAN_RTOL = 1e-3  # [-] mean excess torque (share of the mean |drive torque|) still periodic


@dataclass(frozen=True, slots=True, eq=False)  # holds arrays: no meaningful ==
class TorqueCurve:
    """The torques on the crank shaft over one revolution at the mean speed."""

    angle: FloatArray
    """(n,) crank angles φ of one revolution, rising, less than 2π apart [rad]"""
    excess: FloatArray
    """(n,) ΔM: driving less resisting torque, the torque that accelerates the shaft
    (zero mean) [N·m]"""
    speed: float
    """Ω, the mean crank speed [rad/s] (negative: clockwise)"""
    mean_torque: float
    """the mean drive torque [N·m]: the mean power is mean_torque·Ω"""
    machine_inertia: float = 0.0
    """the machine's own mean reduced moment of inertia [kg·m²] (0: not known)"""
    source: str = ""
    """where the curve came from, for reports"""
    notes: tuple[str, ...] = ()
    """what was assumed in making the curve"""


@dataclass(frozen=True, slots=True)
class Flywheel:
    """A flywheel sized for a fluctuation, or the fluctuation of a given flywheel."""

    speed: float
    """Ω [rad/s]"""
    mean_torque: float
    """mean drive torque [N·m]"""
    power: float
    """mean power M_mean·Ω [W]"""
    delta_energy: float
    """ΔE = max − min of ∫ΔM dφ over the cycle [J]"""
    angle_max_speed: float
    """crank angle of the highest speed (E largest) [rad], in [0, 2π)"""
    angle_min_speed: float
    """crank angle of the lowest speed (E smallest) [rad], in [0, 2π)"""
    machine_inertia: float
    """the machine's own mean reduced inertia [kg·m²]"""
    flywheel: float
    """the flywheel's moment of inertia J_F [kg·m²] (sized, or as given)"""
    fluctuation: float
    """δ = (ω_max − ω_min)/ω_mean ≈ ΔE/((J_F + J_machine)·Ω²) [-] (asked, or resulting)"""
    notes: tuple[str, ...] = field(default=())
    """what the numbers rest on: assumptions, a flywheel not needed, a rough estimate"""


RENAMED = {"angle": "angle_deg", "speed": "speed_rpm"}
"""former parameter names of ``torque_curve`` and ``read_torque_curve`` (SI) -> the
names that carry the unit"""


def torque_curve(angle_deg, drive, load=None, *, speed_rpm: float | None = None,
                 machine_inertia: float = 0.0, source: str = "", **renamed) -> TorqueCurve:
    """A torque curve from a driving torque and, optionally, a load torque.

    Parameters
    ----------
    angle_deg : array_like
        Crank angles φ [°] of one revolution, rising (a last value 360° after the first
        repeats it and is dropped).
    drive : array_like
        The torque driving the crank shaft (an engine's turning moment) [N·m].
    load : array_like, optional
        The load torque on the crank shaft [N·m], positive where it drives the machine
        (as dyade's ``M_load``): a resisting load is negative. Default: a constant load
        equal to the mean drive torque.
    speed_rpm : float
        The mean crank speed [rpm].
    machine_inertia : float
        The machine's own mean reduced inertia [kg·m²].
    source : str
        Where the curve came from, for reports.
    **renamed
        The former ``angle`` [rad] and ``speed`` [rad/s] are refused with an
        ``InputError`` naming ``angle_deg`` and ``speed_rpm``.

    Returns
    -------
    TorqueCurve
        In SI units (its ``angle`` [rad], ``speed`` [rad/s]).

    Raises
    ------
    InputError
        The angles do not cover one revolution, or drive and load do not balance on
        average (no periodic state), naming the parameter.

    Examples
    --------
    An engine's turning moment against a constant load, at 250 rpm:

    >>> import numpy as np, dyade
    >>> angle = np.arange(0.0, 360.0, 1.0)
    >>> engine = 10000 + 2000 * np.sin(np.deg2rad(2 * angle))     # [N·m]
    >>> curve = dyade.torque_curve(angle, engine, speed_rpm=250)
    >>> round(dyade.size_flywheel(curve, 0.005).flywheel, 1)    # [kg·m²]
    583.6
    """
    InputError.refuse_renamed("torque_curve", renamed, RENAMED)
    if speed_rpm is None:
        raise InputError.parameter("speed_rpm", "is needed: the mean crank speed [rpm].",
                                   unit="rpm")
    try:
        angle = np.deg2rad(np.asarray(angle_deg, dtype=np.float64))
        speed = rpm_to_rad_per_s(float(speed_rpm))
    except (TypeError, ValueError):
        raise InputError.parameter(("angle_deg", "speed_rpm"), "must be numbers [°], [rpm]."
                                   ) from None
    try:
        return excess_curve(angle, drive, load, speed=speed, machine_inertia=machine_inertia,
                            source=source)
    except InputError as err:
        raise err.naming({"angle": "angle_deg", "speed": "speed_rpm", "load": "load",
                          "machine_inertia": "machine_inertia"}) from None


def excess_curve(angle, drive, load=None, *, speed: float, machine_inertia: float = 0.0,
                 source: str = "") -> TorqueCurve:
    """``torque_curve`` in SI units, for the engine's own callers: ``angle`` [rad] of one
    revolution, rising (a last value 2π after the first repeats it and is dropped),
    ``speed`` Ω [rad/s]; ``drive``, ``load``, ``machine_inertia`` and ``source`` as
    there. Errors name these parameters."""
    angle, drive = _revolution(angle, drive, "angle")
    if not (math.isfinite(speed) and speed != 0.0):
        raise InputError.parameter("speed", f"must be a finite, non-zero speed [rad/s], got "
                                            f"{speed}.", value=speed, unit="rad/s")
    if not (math.isfinite(machine_inertia) and machine_inertia >= 0.0):
        raise InputError.parameter("machine_inertia", f"must not be negative [kg·m²], got "
                                                      f"{machine_inertia}.",
                                   value=machine_inertia, unit="kg·m²")
    mean = cycle_mean(angle, drive)
    notes = []
    if load is None:
        excess = drive - mean
        notes.append(f"a constant load equal to the mean drive torque {mean:.6g} N·m")
    else:
        load = np.asarray(load, dtype=np.float64)[:angle.size]
        if load.shape != angle.shape or not np.all(np.isfinite(load)):
            raise InputError.parameter("load", "must give one finite torque [N·m] per angle.")
        excess = drive + load
        unbalanced = cycle_mean(angle, excess)
        scale = cycle_mean(angle, np.abs(drive))
        if abs(unbalanced) > MEAN_RTOL * scale:
            raise InputError.parameter(
                "load", f"does not balance the drive torque: their mean sum is "
                        f"{unbalanced:.6g} N·m (drive {mean:.6g} N·m, load "
                        f"{cycle_mean(angle, load):.6g} N·m), so the machine would speed up or "
                        f"slow down every revolution. The load is positive where it drives "
                        f"the machine: a resisting load is negative.", unit="N·m")
        if abs(unbalanced) > 1e-9 * scale:
            notes.append(f"the load shifted by {-unbalanced:.3g} N·m to close the cycle")
        excess = excess - unbalanced
    return TorqueCurve(angle, excess, float(speed), mean, machine_inertia, source, tuple(notes))


def machine_curve(angle, drive_torque, *, speed: float, machine_inertia: float = 0.0,
                  source: str = "") -> TorqueCurve:
    """The torque curve of a machine that needs ``drive_torque`` [N·m] at constant speed
    (dyade's ``M_drive``), driven by a motor of constant torque equal to its mean: the
    excess is M_mean − M_drive(φ)."""
    angle, drive = _revolution(angle, drive_torque, "angle")
    mean = cycle_mean(angle, drive)
    return TorqueCurve(angle, mean - drive, float(speed), mean, machine_inertia, source,
                       (f"a motor of constant torque, the mean drive torque {mean:.6g} N·m",))


def _revolution(angle, values, name: str) -> tuple[FloatArray, FloatArray]:
    angle = np.asarray(angle, dtype=np.float64).ravel()
    values = np.asarray(values, dtype=np.float64).ravel()
    if angle.shape != values.shape or angle.size < 4:
        raise InputError.parameter(name, "needs at least 4 crank angles, one torque each.")
    if not (np.all(np.isfinite(angle)) and np.all(np.isfinite(values))):
        bad = angle[~(np.isfinite(angle) & np.isfinite(values))]
        where = f" (first at {np.rad2deg(bad[0]):.6g}°)" if np.isfinite(bad[0]) else ""
        raise InputError.parameter(name, f"and its torques must be finite numbers{where}: the "
                                         f"curve must cover the whole revolution.")
    steps = np.diff(angle)
    if np.any(steps <= 0.0):
        raise InputError.parameter(name, "must rise strictly.")
    span = angle[-1] - angle[0]
    full = 2.0 * math.pi
    if abs(span - full) <= 1e-9 * full:  # the last angle repeats the first
        angle, values = angle[:-1], values[:-1]
        span = angle[-1] - angle[0]
    if span >= full or full - span > 1.5 * float(np.max(steps)):
        raise InputError.parameter(name, f"must cover one revolution (360°) in steps, got "
                                         f"{np.rad2deg(angle[0]):.6g}° to "
                                         f"{np.rad2deg(angle[-1]):.6g}°.", unit="rad")
    return angle, values


def energy(curve: TorqueCurve) -> FloatArray:
    """E(φ) = ∫ΔM dφ from the first angle, at the curve's angles [J]."""
    return np.concatenate(([0.0], np.cumsum(integrals(curve.angle, curve.excess))[:-1]))


def energy_extremes(curve: TorqueCurve) -> tuple[float, float, float, float]:
    """(E_max, φ at E_max, E_min, φ at E_min), between the samples where ΔM crosses zero."""
    angle, f = curve.angle, curve.excess
    h, slope = segments(angle, f)
    start = energy(curve)
    f1, d1 = np.roll(f, -1), np.roll(slope, -1)
    change = np.flatnonzero(np.sign(f) != np.sign(f1))
    lo, hi = np.zeros(change.size), np.ones(change.size)
    a, b, da, db, hk = f[change], f1[change], slope[change], d1[change], h[change]

    def cubic(t):
        t2, t3 = t * t, t * t * t
        return ((2 * t3 - 3 * t2 + 1) * a + (t3 - 2 * t2 + t) * hk * da + (3 * t2 - 2 * t3) * b
                + (t3 - t2) * hk * db)

    for _ in range(60):  # bisection on the sign change
        mid = 0.5 * (lo + hi)
        same = np.sign(cubic(mid)) == np.sign(a)
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    t = 0.5 * (lo + hi)
    t2, t3, t4 = t * t, t ** 3, t ** 4
    inside = hk * ((t - t3 + t4 / 2) * a + (t2 / 2 - 2 * t3 / 3 + t4 / 4) * hk * da
                   + (t3 - t4 / 2) * b + (t4 / 4 - t3 / 3) * hk * db)
    candidates = np.concatenate((start, start[change] + inside))
    where = np.concatenate((angle, angle[change] + t * hk))
    top, bottom = int(np.argmax(candidates)), int(np.argmin(candidates))
    turn = 2.0 * math.pi
    return (float(candidates[top]), float(where[top] % turn), float(candidates[bottom]),
            float(where[bottom] % turn))


def _result(curve: TorqueCurve, flywheel: float, fluctuation: float, notes: list) -> Flywheel:
    top, at_top, bottom, at_bottom = energy_extremes(curve)
    if fluctuation > LARGE_FLUCTUATION:
        notes.append(f"a fluctuation of {fluctuation:.3g} is large: δ ≈ ΔE/(J·Ω²) holds for "
                     f"small fluctuations; solve the equation of motion ([drive] table) for the "
                     f"real speed")
    return Flywheel(abs(curve.speed), curve.mean_torque, curve.mean_torque * curve.speed,
                    top - bottom, at_top, at_bottom, curve.machine_inertia, flywheel,
                    fluctuation, tuple(curve.notes) + tuple(notes))


def size_flywheel(curve: TorqueCurve, fluctuation: float) -> Flywheel:
    """The flywheel J_F = ΔE/(δ·Ω²) − J_machine that keeps the speed fluctuation near δ.

    Parameters
    ----------
    curve : TorqueCurve
        From ``torque_curve``, ``machine_curve``, ``read_torque_curve`` or
        ``dyade.linkage.drive.torque_curve`` (a mechanism).
    fluctuation : float
        δ = (ω_max − ω_min)/ω_mean [-], e.g. 0.02.

    Returns
    -------
    Flywheel
        ``delta_energy`` ΔE [J], ``flywheel`` J_F [kg·m²], the angles of the highest and
        lowest speed, and notes on what the estimate rests on.

    Examples
    --------
    >>> import dyade
    >>> curve = dyade.read_torque_curve("mechanisms/torque/engine.csv", speed_rpm=250)
    >>> flywheel = dyade.size_flywheel(curve, 0.005)
    >>> round(flywheel.delta_energy, 3), round(flywheel.flywheel, 3)    # [J], [kg·m²]
    (2690.725, 785.167)
    """
    if not (math.isfinite(fluctuation) and fluctuation > 0.0):
        raise InputError.parameter("fluctuation", f"must be a positive number [-], got "
                                                  f"{fluctuation}.", value=fluctuation)
    top, _, bottom, _ = energy_extremes(curve)
    needed = (top - bottom) / (fluctuation * curve.speed ** 2)
    notes = []
    flywheel = needed - curve.machine_inertia
    if flywheel < 0.0:
        notes.append(f"no flywheel needed: the machine's own inertia "
                     f"{curve.machine_inertia:.4g} kg·m² keeps the fluctuation below "
                     f"{fluctuation:g}")
        flywheel = 0.0
    return _result(curve, flywheel, fluctuation, notes)


def speed_fluctuation(curve: TorqueCurve, inertia: float) -> Flywheel:
    """The speed fluctuation δ ≈ ΔE/((J_F + J_machine)·Ω²) with a flywheel on the crank
    shaft.

    Parameters
    ----------
    curve : TorqueCurve
        From ``torque_curve``, ``read_torque_curve`` or ``mechanism_torque_curve``.
    inertia : float
        The flywheel's moment of inertia J_F [kg·m²], ≥ 0.

    Returns
    -------
    Flywheel
        With the resulting ``fluctuation`` δ [-].

    Examples
    --------

    >>> import dyade
    >>> curve = dyade.read_torque_curve("mechanisms/torque/engine.csv", speed_rpm=250)
    >>> round(dyade.speed_fluctuation(curve, 1000.0).fluctuation, 6)
    0.003926
    """
    if not (math.isfinite(inertia) and inertia >= 0.0):
        raise InputError.parameter("inertia", f"must not be negative [kg·m²], got {inertia}.",
                                   value=inertia, unit="kg·m²")
    total = inertia + curve.machine_inertia
    if total <= 0.0:
        raise InputError.parameter("inertia", "must be positive: the curve gives no inertia "
                                              "of the machine.", value=inertia, unit="kg·m²")
    top, _, bottom, _ = energy_extremes(curve)
    fluctuation = (top - bottom) / (total * curve.speed ** 2)
    if not fluctuation < 1.0:
        raise DyadeError(f"with J = {total:.4g} kg·m² the energy fluctuation {top - bottom:.4g} J "
                         f"would change the speed by more than its mean (δ ≈ {fluctuation:.3g}): "
                         f"the machine stalls and the small-fluctuation estimate does not hold. "
                         f"A flywheel of at least {(top - bottom) / curve.speed ** 2:.4g} kg·m² "
                         f"keeps δ below 1; solve the equation of motion ([drive] table) for "
                         f"the real speed.")
    return _result(curve, inertia, fluctuation, [])


def table_curve(table: TorqueTable, speed: float | None = None) -> TorqueCurve:
    """The torque curve of a table read from a CSV (``dyade.files.torque_curve``) at the
    mean crank speed ``speed`` [rad/s]: against its ``M_load`` (positive where it drives;
    default a constant load equal to the mean drive torque).

    A CSV written by ``dyade analyse`` (``table.machine``) is a machine's drive torque at
    constant speed, with its loads already in it: it is taken as by ``machine_curve``, with
    the machine's mean ``J_red`` and, unless ``speed`` is given, its crank speed.

    Parameters
    ----------
    table : TorqueTable
        From ``dyade.files.torque_curve.read_table``.
    speed : float, optional
        The mean crank speed [rad/s]; required unless the table is dyade's.

    Returns
    -------
    TorqueCurve
    """
    label = table.source
    if table.machine:
        if speed is None:
            omega = table.speed
            if omega is None or not np.all(np.isfinite(omega)):
                raise InputError.parameter("speed_rpm", "is needed: the file has no crank "
                                                        "speed omega_2.", unit="rpm")
            speed = float(np.mean(omega))
        if table.inertia is None:
            raise InputError(f"{label}: no column J_red: a CSV of dyade analyse (it has "
                             f"dJ_red) gives the machine's reduced inertia too.",
                             source=label, key="J_red")
        inertia = cycle_mean(*_revolution(table.angle, table.inertia, "angle"))
        curve = machine_curve(table.angle, table.drive, speed=speed, machine_inertia=inertia,
                              source=label)
        return TorqueCurve(curve.angle, curve.excess, curve.speed, curve.mean_torque,
                           curve.machine_inertia, label, curve.notes + (
                               "a dyade analyse CSV: M_drive is the machine's need at constant "
                               "speed, its loads included",))
    if speed is None:
        raise InputError.parameter("speed_rpm", "is needed with a torque CSV: the mean crank "
                                                "speed.", unit="rpm")
    return excess_curve(table.angle, table.drive, table.load, speed=speed, source=label)
