"""The CSV contract: a block of a sweep -> ordered named columns.

One row per reported crank position; SI units except angles in degrees. The names are
documented in ``docs/reference/columns.md`` and are stable: scripts rely on them.
"""

from __future__ import annotations

import math

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.block import Block, Columns
from dyade.linkage.components import magnitude
from dyade.linkage.kinematics import joint_anchor
from dyade.linkage.motion import travel
from dyade.linkage.reduced import reduced
from dyade.model.mechanism import CRANK, FRAME, Mechanism, Prismatic, Revolute


UNITS = {"kinematics": "1/0", "angle_deg": "°", "phi": "°", "omega": "rad/s",
         "alpha": "rad/s²", "x": "m", "y": "m",
         "vx": "m/s", "vy": "m/s", "ax": "m/s²", "ay": "m/s²", "s": "m", "v": "m/s",
         "a": "m/s²", "mu": "°", "Fx": "N", "Fy": "N", "F": "N", "FN": "N", "M": "N·m",
         "P": "W", "forces": "1/0", "MR": "N·m", "FR": "N", "lock": "-", "friction": "-",
         "J": "kg·m²", "dJ": "kg·m²/rad", "t": "s"}


POINT = ("x", "y", "vx", "vy", "ax", "ay")
"""the columns of a point, in contract order (``Motion.point_motion``)"""
MACHINE = ("J_red", "dJ_red", "M_load")
"""the columns of the linkage reduced to the crank (``force_columns`` with ``machine``)"""


def _tag(name: tuple[int, int]) -> str:
    return f"{name[0]}_{name[1]}"


def kinematic_columns(mech: Mechanism, block: Block, phases: dict[int, Continuous],
                      points: bool = True, own: bool = True) -> Columns:
    """Every kinematic column of a block, in contract order; ``phases``: link ->
    its angle's unwrapping, carried on from the blocks before; without ``points``, not
    the motion of the revolute joints and named points (x_, y_, vx_, vy_, ax_, ay_);
    without ``own``, a link's ω and α may be views of the block's motion."""
    kin, rows = block.kinematics, block.rows
    motion = kin.motion
    every = bool(rows.all())  # (every position reported: no copies by a mask)
    out: Columns = {"angle_deg": np.rad2deg(kin.crank_angle)}
    follower = kin.follower
    if follower is not None:  # a cam drives link 2: its speed and pressure angle
        n = kin.crank_angle.shape[0]
        out["omega_cam"] = np.broadcast_to(np.asarray(follower.speed, dtype=np.float64),
                                           (n,)).copy()
        out["pressure_angle_deg"] = np.rad2deg(follower.pressure_angle)
    for link in mech.moving_links:
        angle = motion.angle[:, link] if every else motion.angle[rows, link]
        out[f"phi_{link}_deg"] = np.rad2deg(phases[link](angle))
        out[f"omega_{link}"] = motion.omega[:, link].copy() if own else motion.omega[:, link]
        out[f"alpha_{link}"] = motion.alpha[:, link].copy() if own else motion.alpha[:, link]
    for joint in mech.joints:
        tag = _tag(joint.name)
        if isinstance(joint, Revolute):
            if not points:
                continue
            for prefix, value in zip(POINT, motion.point_motion(*joint_anchor(joint))):
                out[f"{prefix}_{tag}"] = value
        elif isinstance(joint, Prismatic):
            s, v, a = travel(joint, motion)
            out[f"s_{tag}"], out[f"v_{tag}"], out[f"a_{tag}"] = s, v, a
    for name, link, local in mech.named_points if points else ():
        for prefix, value in zip(POINT, motion.point_motion(link, local)):
            out[f"{prefix}_{name}"] = value
    for col, dyad in enumerate(mech.dyads):
        out[f"mu_{dyad.number}_deg"] = np.rad2deg(kin.transmission[:, col])
    if not every:  # (the link angles are of the reported rows already)
        out = {key: value if key.startswith("phi_") else value[rows]
               for key, value in out.items()}
    valid = block.valid if every else block.valid[rows]
    if not valid.all():  # nothing of an invalid row but its crank and transmission angles
        out = {key: value if key == "angle_deg" or key.startswith("mu_")
               else np.where(valid, value, np.nan) for key, value in out.items()}
    out["kinematics_valid"] = valid.astype(np.float64)
    return out


class Continuous:
    """A link angle [rad] over the reported positions of a sweep that comes block by
    block, continuous: unwrapped across ±π from its first value, which is brought into
    (−π, π]; positions without a value (NaN) stay empty and are bridged. Each call
    continues the unwrapping from the blocks before (exactly ``np.unwrap``'s arithmetic,
    its running sum of corrections carried on), ``commit()`` once a block is final."""

    def __init__(self) -> None:
        self.state: tuple | None = None
        """(last finite raw angle, running correction, turns) after the committed blocks"""
        self.pending: tuple | None = None

    def __call__(self, angle: FloatArray) -> FloatArray:
        finite = np.isfinite(angle)
        if not finite.any():  # (an empty block too)
            self.pending = self.state
            return angle
        whole = finite.all()
        p = angle if whole else angle[finite]
        ext = p if self.state is None else np.concatenate(([self.state[0]], p))
        dd = np.diff(ext)
        correction = None  # zero everywhere where no step jumps by π or more
        if (abs(dd) >= np.pi).any():
            ddmod = np.mod(dd + np.pi, 2 * np.pi) - np.pi  # np.unwrap with period 2π
            np.copyto(ddmod, np.pi, where=(ddmod == -np.pi) & (dd > 0))
            correction = ddmod - dd
            np.copyto(correction, 0, where=abs(dd) < np.pi)
        if self.state is None:
            values = p.copy()
            carry = 0.0
            if p.size > 1 and correction is None:
                values[1:] = p[1:] + 0.0  # the running sum of zero corrections
            elif p.size > 1:
                running = correction.cumsum()
                values[1:] = p[1:] + running
                carry = running[-1]
            first = values[0]
            turns = np.ceil((first - np.pi) / (2.0 * np.pi))
        elif correction is None:
            carry, turns = self.state[1] + 0.0, self.state[2]
            values = p + carry
        else:
            running = np.concatenate(([self.state[1]], correction)).cumsum()[1:]
            values = p + running
            carry, turns = running[-1], self.state[2]
        if turns:
            values = values - 2.0 * np.pi * turns
        self.pending = (p[-1], carry, turns)
        if whole:
            return values
        out = np.full(angle.shape, np.nan)
        out[finite] = values
        return out

    def commit(self) -> None:
        self.state = self.pending


class EachVariant:
    """The link angle's unwrapping (``Continuous``) of a run of variants whose blocks
    hold whole variants of ``count`` positions each: every variant unwrapped on its own
    from its first value, as a sweep of it alone unwraps it (the same arithmetic, row by
    row; a variant with a position without a value through ``Continuous`` itself)."""

    def __init__(self, count: int) -> None:
        self.count = count

    def __call__(self, angle: FloatArray) -> FloatArray:
        if angle.size == 0:
            return angle
        rows = angle.reshape(-1, self.count)
        out = np.empty(rows.shape)
        finite = np.isfinite(rows).all(axis=1)
        for k in np.flatnonzero(~finite):
            out[k] = Continuous()(rows[k])
        if finite.all():
            out = unwrapped(rows)
        elif finite.any():
            out[finite] = unwrapped(rows[finite])
        return out.reshape(-1)

    def commit(self) -> None:
        """(nothing carries over from one block to the next)"""


def unwrapped(rows: FloatArray) -> FloatArray:
    """Each row of finite angles [rad] unwrapped across ±π from its first value, which
    is brought into (−π, π]: ``Continuous`` of a first block, row by row."""
    values = rows.copy()
    if rows.shape[1] > 1:
        dd = np.diff(rows, axis=1)
        if (abs(dd) >= np.pi).any():
            ddmod = np.mod(dd + np.pi, 2 * np.pi) - np.pi  # np.unwrap with period 2π
            np.copyto(ddmod, np.pi, where=(ddmod == -np.pi) & (dd > 0))
            correction = ddmod - dd
            np.copyto(correction, 0, where=abs(dd) < np.pi)
            values[:, 1:] = rows[:, 1:] + correction.cumsum(axis=1)
        else:
            values[:, 1:] = rows[:, 1:] + 0.0
    turns = np.ceil((values[:, 0] - np.pi) / (2.0 * np.pi))
    if turns.any():
        values -= 2.0 * np.pi * turns[:, None]
    return values


def force_columns(mech: Mechanism, block: Block, machine: bool = True, own: bool = True
                  ) -> Columns:
    """Joint forces, drive torque and power, shaking force; empty where invalid; with
    ``machine``, the linkage reduced to the crank (J_red, dJ_red, M_load). Without
    ``own``, a column may be a view of the block's forces (for a caller that lets the
    block go)."""
    forces = block.forces
    if forces is None:
        return {}
    out: Columns = {}
    for joint in mech.joints:
        tag = _tag(joint.name)
        if isinstance(joint, Revolute):
            f = forces.revolute[joint.name]
            out[f"Fx_{tag}"], out[f"Fy_{tag}"] = f[:, 0], f[:, 1]
            out[f"F_{tag}"] = magnitude(f[:, 0], f[:, 1])
        else:
            out[f"FN_{tag}"] = forces.normal[joint.name]
            out[f"M_{tag}"] = forces.moment[joint.name]
    out["M_drive"] = forces.drive_torque
    follower = block.kinematics.follower
    if follower is None:
        out["P_drive"] = forces.drive_torque * block.kinematics.motion.omega[:, CRANK]
    else:  # a cam drives link 2: the cam shaft's torque at the cam's speed
        out["P_drive"] = forces.drive_torque * follower.speed
        out["F_cam"] = forces.contact_force
    out["Fx_shake"], out["Fy_shake"], out["M_shake"] = (forces.shaking[:, 0],
                                                        forces.shaking[:, 1],
                                                        forces.shaking[:, 2])
    rubbing = block.friction
    if rubbing is not None:
        for name, value in rubbing.moments.items():
            out[f"MR_{_tag(name)}"] = value
        for name, value in rubbing.friction_forces.items():
            out[f"FR_{_tag(name)}"] = value
        out["P_friction"] = rubbing.power
    invalid = ~(forces.valid & block.valid)
    out = {key: _blank(invalid, value, not own) for key, value in out.items()}
    # the self-locking figures stay where friction is what makes the forces invalid
    dead = invalid & ~rubbing.blocked if rubbing is not None else invalid
    for name, lock in (block.locking or {}).items():
        if lock.margin is not None:
            out[f"lock_margin_{_tag(name)}"] = _blank(dead, lock.margin)
    if rubbing is not None:
        out["friction_iterations"] = rubbing.iterations.copy()
    out["forces_valid"] = (forces.valid & block.valid).astype(np.float64)
    if rubbing is not None:
        for number, det in sorted(rubbing.determinant.items()):
            out[f"friction_det_{number}"] = _blank(dead, det)
    missing = ~block.valid  # from the kinematics: not given where it is not
    if machine:
        line = reduced(mech, block.kinematics)
        out["J_red"], out["dJ_red"], out["M_load"] = (_blank(missing, line.inertia, True),
                                                      _blank(missing, line.slope, True),
                                                      _blank(missing, line.load, True))
    if block.drive is not None:
        out["t"], out["M_motor"] = (block.drive.time.copy(),
                                    _blank(missing, block.drive.motor_torque))
    if block.rows.all():
        return out
    return {key: value[block.rows] for key, value in out.items()}


def _blank(mask: FloatArray, values: FloatArray, fresh: bool = False) -> FloatArray:
    """``values`` with NaN where ``mask``: a copy (the columns are their own, not views of
    the block's forces, friction or motion) unless ``fresh`` (nothing else holds them)."""
    if mask.any():
        return np.where(mask, np.nan, values)
    return values if fresh else values.copy()


def columns(mech: Mechanism, block: Block, phases: dict[int, Continuous],
            points: bool = True, machine: bool = True, own: bool = True) -> Columns:
    """All columns of a block, in contract order (without ``points``, not the motion of
    the revolute joints and named points: ``kinematic_columns``; without ``machine``
    and ``own``: ``force_columns``)."""
    return (kinematic_columns(mech, block, phases, points, own)
            | force_columns(mech, block, machine, own))


PLAUSIBLE = 1e12  # [SI] no machine has a value beyond this: a row with one is not given
FORCE_PREFIXES = ("Fx_", "Fy_", "F_", "FN_", "M_", "P_", "MR_", "FR_", "lock_margin_",
                  "friction_iterations", "forces_valid", "friction_det_")
"""names of the force block; the rest (and ``KINEMATIC_EXEMPT``) are kinematic"""
KINEMATIC_EXEMPT = ("kinematics_valid",)


def bound(mech: Mechanism, block: Block, machine: bool, count: int = 1) -> float:
    """A bound [SI] on the magnitude of every value of the columns ``columns`` gives
    only with ``points`` (x, y, vx, vy, ax, ay of the joints and named points) and,
    with ``machine``, only with ``machine`` (J_red, dJ_red; not M_load: a caller
    computes those where the mechanism has gravity, loads or springs), at the block's
    positions. For a point at distance r ≤ R from its link's origin O,
    |x| ≤ |O| + R, |v| ≤ |v_O| + |ω|·R, |a| ≤ |a_O| + (|α| + ω²)·R, each
    magnitude the largest of any component of any link (NaN left aside: a NaN is no
    value beyond the limit); J ≤ Σ m·v_S² + J_S·ω² and |J′| ≤ 2·Σ m·|v_S|·|a_S| +
    J_S·|ω|·|α| over the least crank speed Ω² and Ω³. Infinite where a value is.
    ``count``: the positions per variant of a run of variants (a number that differs
    between them is read once per variant)."""
    motion = block.kinematics.motion

    def largest(values: FloatArray) -> float:  # whole arrays: one fast reduction each
        values = values[:, FRAME:]  # (index 0 is no link)
        if values.size == 0:
            return 0.0
        top = max(float(np.fmax.reduce(values, axis=None)),
                  -float(np.fmin.reduce(values, axis=None)))
        return 0.0 if math.isnan(top) else top  # (none given)

    origin, velocity, acceleration = (largest(motion.origin), largest(motion.velocity),
                                      largest(motion.acceleration))
    w, a = largest(motion.omega), largest(motion.alpha)
    radius = max((_radius(mech, link, count) for link in mech.links), default=0.0)
    out = max(origin + radius, velocity + w * radius, acceleration + (a + w * w) * radius)
    if machine and motion.omega.shape[0]:
        energy = rate = 0.0
        for link, body in mech.links.items():
            if link == FRAME or not body.has_mass:
                continue
            mass, inertia = _largest(body.mass, count), _largest(body.inertia, count)
            centre = _largest(np.hypot(*(_each(x, count) for x in body.centre)))
            speed = velocity + w * centre
            energy += mass * speed * speed + inertia * w * w
            rate += mass * speed * (acceleration + (a + w * w) * centre) + inertia * w * a
        crank = float(np.fmin.reduce(np.abs(motion.omega[:, CRANK])))
        if crank == 0.0:
            return math.inf
        if not math.isnan(crank):  # (NaN: no position given)
            out = max(out, energy / crank ** 2, 2.0 * rate / crank ** 3)
    return math.inf if math.isnan(out) else float(out)


def _each(value, count: int = 1):
    """A number of a mechanism: as it is, or (one per position, the same at the
    ``count`` positions of a variant) one per variant."""
    return value if np.ndim(value) == 0 else np.asarray(value)[::count]


def _largest(value, count: int = 1) -> float:
    """The largest magnitude of a number of a mechanism (one, or one per position)."""
    return float(np.max(np.abs(_each(value, count))))


def _radius(mech: Mechanism, link: int, count: int = 1) -> float:
    """The largest distance of a point of ``link`` (a joint's or a named one) from its
    origin [m] (of every variant, where they differ)."""
    points = [local for joint in mech.joints
              for number, local in zip(joint.links, joint.points if isinstance(joint, Revolute)
                                       else (joint.guide_point, joint.slider_point))
              if number == link]
    points += [local for _, number, local in mech.named_points if number == link]
    return max((_largest(np.hypot(_each(x, count), _each(y, count))) for x, y in points),
               default=0.0)


def implausible(cols: Columns, names) -> FloatArray:
    """(rows,) bool: a value of the named columns beyond ``PLAUSIBLE`` in magnitude."""
    out = None
    for name in names:
        values = cols[name]
        # the extremes first (NaN left aside): a mask only for a column that has one
        # (a column that is a view across a wider array, as a joint's Fx of its (n, 2)
        # forces, copied first: numpy reduces a strided array several times slower)
        whole = values if values.flags.c_contiguous else np.ascontiguousarray(values)
        if values.size and (np.fmax.reduce(whole) > PLAUSIBLE
                            or np.fmin.reduce(whole) < -PLAUSIBLE):
            big = np.abs(values) > PLAUSIBLE  # NaN compares False
            out = big if out is None else out | big
    if out is None:
        out = np.zeros(next(iter(cols.values())).shape, dtype=bool)
    return out


def unit_of(column: str) -> str:
    """Unit of a column, for table headers."""
    if column.endswith("_deg"):
        return "°"
    return UNITS.get(column.split("_", 1)[0], "")
