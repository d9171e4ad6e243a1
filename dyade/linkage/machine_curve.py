"""The machine's torque curve at constant speed, for sizing a flywheel
(``dyade.machine.flywheel``)."""

from __future__ import annotations

import math

import numpy as np

from dyade.cycle import mean as cycle_mean
from dyade.errors import DyadeError, InputError
from dyade.linkage.options import check_size, radians
from dyade.linkage.sweep import analyse_si
from dyade.machine.flywheel import TorqueCurve, machine_curve
from dyade.model.mechanism import Mechanism

FINE_STEP = math.radians(0.1)  # [rad] largest default step of a torque curve


def torque_curve(mechanism: Mechanism, *, step_deg: float | None = None,
                 max_memory: float | None = None, **renamed) -> TorqueCurve:
    """The machine's torque curve at constant speed, for the flywheel.

    The drive torque M_drive over one revolution from the sweep's start, against a
    motor of constant torque, with the machine's mean reduced inertia
    (``dyade.machine.flywheel``). A ``[drive]`` table is ignored.

    Parameters
    ----------
    mechanism : Mechanism
        With masses, loads or springs (a drive torque to size a flywheel by).
    step_deg : float, optional
        The crank-angle step [°], below 90° (default: the sweep's, at most 0.1°, since
        load tables put kinks in the curve that only a fine step integrates well).
    max_memory : float, optional
        Bound on the sweep's size [B] (``dyade.limits``), checked before anything is
        allocated.
    **renamed
        The former ``step`` [rad] is refused with an ``InputError`` naming ``step_deg``.

    Returns
    -------
    TorqueCurve

    Examples
    --------
    >>> import dyade
    >>> curve = dyade.mechanism_torque_curve(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> flywheel = dyade.size_flywheel(curve, 0.02)
    >>> round(flywheel.delta_energy, 4), round(flywheel.flywheel, 4)     # [J], [kg·m²]
    (1.4385, 0.0705)
    """
    InputError.refuse_renamed("mechanism_torque_curve", renamed, {"step": "step_deg"})
    step = min(mechanism.sweep.step, FINE_STEP) if step_deg is None else radians(step_deg,
                                                                                 "step_deg")
    if not (0.0 < step < math.pi / 2):
        raise InputError.parameter("step_deg", f"must be a crank-angle step below 90° [°], got "
                                               f"{step_deg}.", value=step_deg, unit="°")
    if not mechanism.has_dynamics:
        raise InputError(f"{mechanism.name}: no masses, loads or springs, so no drive torque to "
                         f"size a flywheel by (add mass data, see `dyade help mechanism-file`).")
    count = int(math.ceil(2.0 * math.pi / step - 1e-9))
    check_size(mechanism, count, max_memory,
               advice="Use a coarser step_deg (the curve covers one revolution)")
    angle = mechanism.sweep.start + step * np.arange(count)
    result = analyse_si(mechanism, crank_angle=angle, constant_speed=True)
    cols = result.columns()
    torque, inertia = cols["M_drive"], cols["J_red"]  # NaN where not given
    if not np.isfinite(torque).any():  # the rule every analysis shares: exit 1, say so
        err = DyadeError(f"{mechanism.name}: no crank position of the revolution has its drive "
                         f"torque given (every one is withheld by the sweep's notes), so no "
                         f"flywheel can be sized from it: nothing to report.")
        err.notes = result.notes  # why (``dyade.linkage.notes``), for the caller to word
        raise err
    if not np.all(np.isfinite(torque)):
        raise DyadeError(f"{mechanism.name}: the drive torque is not given over the whole "
                         f"revolution (a dead centre), so no flywheel can be sized from it.")
    return machine_curve(angle, torque, speed=mechanism.crank.speed,
                         machine_inertia=cycle_mean(angle, inertia), source=mechanism.name)
