"""The clearance check of a mechanism from its file: analysed here
(``joint_clearance`` checks a sweep's forces), and over a range of crank speeds."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from dyade.errors import InputError
from dyade.linkage.joint_clearance import (MAX_WANDER_DEG, MISSING, JointCheck, check_mechanism,
                                          needs_forces)
from dyade.linkage.options import radians
from dyade.linkage.sweep import analyse
from dyade.model.mechanism import ClearanceData, Mechanism, Revolute
from dyade.units import RPM


def check(mechanism: Mechanism, *, joints=None, stiffness: float | None = None,
          clearance: float | None = None, mass: float | None = None,
          max_wander_deg: float = MAX_WANDER_DEG, result=None, allow_partial: bool = False,
          **renamed) -> list[JointCheck]:
    """The clearance check of a mechanism's revolute joints over its cycle.

    Parameters
    ----------
    mechanism : Mechanism
        With masses, loads or springs (the check needs the rigid joint forces).
    joints : iterable of (int, int), optional
        The revolute joints to check (default: every revolute joint).
    stiffness, clearance : float, optional
        Contact stiffness c [N/m] and clearance 2s [m] for every joint checked, together;
        default: each joint's clearance data from the file.
    mass : float, optional
        Reduced mass m [kg] for every joint; default: the file's, or the reduced mass of
        the joint's two links (eq. 17; the frame counts as rigid).
    max_wander_deg : float
        How far [°] the force may leave its dominant line of action for the model to
        apply (forces of at least 25 % of the peak count).
    result : Result, optional
        An analysis of ``mechanism`` to reuse (default: analysed here).
    allow_partial : bool
        Where ``mechanism`` closes over part of the sweep only, check the forces where it
        closes (as ``dyade.analyse`` does) instead of failing.
    **renamed
        The former ``max_wander`` [rad] is refused with an ``InputError`` naming
        ``max_wander_deg``.

    Returns
    -------
    list of JointCheck
        One per joint, in the order asked: its line of action, whether the model
        applies (else why not), and every reversal with its peak force. Where the sweep
        gives the forces at no position (all withheld), every check says so
        (``missing == "forces"``).

    Examples
    --------
    >>> import dyade
    >>> mechanism = dyade.read_mechanism("mechanisms/dyade-16.toml")
    >>> checks = dyade.check_clearance(mechanism, joints=[(2, 7)], stiffness=1e8,
    ...                                clearance=1e-4)
    >>> [round(r.peak.force) for r in checks[0].reversals]
    [318, 738]
    """
    InputError.refuse_renamed("check_clearance", renamed, {"max_wander": "max_wander_deg"})
    max_wander = radians(max_wander_deg, "max_wander_deg")
    if (stiffness is None) != (clearance is None):
        raise InputError.parameter("stiffness", "and clearance go together (or neither, to use "
                                                "the clearance data of the mechanism).")
    override = ClearanceData(clearance, stiffness, None) if stiffness is not None else None
    if joints is None:
        joints = [j.name for j in mechanism.joints if isinstance(j, Revolute)]
    joints = [(a, b) if a < b else (b, a) for a, b in joints]
    result = analyse(mechanism, allow_partial=allow_partial) if result is None else result
    needs_forces(result, "the clearance check")
    if not np.any(result.forces_valid[result.rows]):  # every position withheld
        return [JointCheck(name, np.nan, np.nan, False, MISSING["forces"], (), "", "forces")
                for name in joints]
    return check_mechanism(mechanism, result, result.forces.revolute, joints, override, mass,
                           max_wander)


def speed_study(mechanism: Mechanism, speeds_rpm, progress=None, workers: int = 1,
                **options) -> list[tuple[float, list]]:
    """The clearance check at each crank speed (the crank keeps its sense of rotation).

    Parameters
    ----------
    mechanism : Mechanism
        With masses, loads or springs, as for ``check_clearance``.
    speeds_rpm : iterable of float
        Crank speeds [rpm], positive.
    progress : callable, optional
        ``progress(done, total)`` is called after each speed.
    workers : int
        Processes that check the speeds (the same results, in the same order).
    **options
        As for ``check_clearance`` (``joints``, ``stiffness``, ``clearance``, ``mass``,
        ``max_wander_deg``, ``allow_partial``).

    Returns
    -------
    list of (float, list of JointCheck)
        (speed [rpm], the checks) per speed.

    Examples
    --------
    >>> import dyade
    >>> mechanism = dyade.read_mechanism("mechanisms/dyade-16.toml")
    >>> study = dyade.clearance_speed_study(mechanism, [100, 200], joints=[(2, 7)],
    ...                                     stiffness=1e8, clearance=1e-4)
    >>> [(rpm, len(checks[0].reversals)) for rpm, checks in study]
    [(100.0, 0), (200.0, 2)]
    """
    speeds_rpm = list(speeds_rpm)
    for rpm in speeds_rpm:
        if not np.isfinite(rpm) or rpm <= 0:
            raise InputError.parameter("speeds_rpm", f"must be positive speeds [rpm], got "
                                                     f"{rpm:g}.", value=rpm, unit="rpm")
    from dyade import parallel

    tasks = [(mechanism, rpm, options) for rpm in speeds_rpm]
    return _collect(speeds_rpm, parallel.ordered_map(_at_speed, tasks, workers), progress)


def _at_speed(task) -> list:
    """The clearance check of (mechanism, crank speed [rpm], options); the crank keeps
    its sense of rotation."""
    mechanism, rpm, options = task
    sign = 1.0 if mechanism.crank.speed > 0 else -1.0
    faster = replace(mechanism, crank=replace(mechanism.crank, speed=sign * rpm * RPM))
    return check(faster, **options)


def _collect(speeds_rpm, checks, progress) -> list[tuple[float, list]]:
    out = []
    for rpm, result in zip(speeds_rpm, checks):
        out.append((float(rpm), result))
        if progress is not None:
            progress(len(out), len(speeds_rpm))
    return out
