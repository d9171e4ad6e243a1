"""Variants of one mechanism swept together (issue 26, "Fast by design"): the variants ×
positions of a stacked mechanism (``dyade.linkage.stack``) through the same engine as
one sweep — kinematics, then kinetostatics where the plan calls for it — and their
columns as (variants, positions) arrays.

Only what a sweep of each variant alone would give without a note is taken from here:
a variant is *clean* when it closes at every position, stays out of every dyad's
dead-centre band, has its forces everywhere, and no column can hold a value beyond
``columns.PLAUSIBLE`` (the motion of the points is bounded from its links' motion
instead of computed, and without gravity, loads or springs, the linkage
reduced to the crank: ``reach``). A caller sweeps every other variant alone, which
gives it its notes, its reason or its gaps exactly as ``analyse`` does.

Stages that couple the positions of a variant (friction's Newton solve with its
coupling between blocks, the equation of motion) and the drive line's check are not
stacked: ``sweep`` raises ``NotStackable`` for a plan that calls for them. The clearance check reads the joint
forces after the sweep and changes none of its columns: it is not run here (a caller
that wants its peaks evaluates each variant alone).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage import columns as columns_, kinematics, kinetostatics
from dyade.linkage.block import Block
from dyade.linkage.plan import Plan, plan
from dyade.linkage.stack import NotStackable
from dyade.model.mechanism import CRANK, FRAME, Joint, Mechanism, Revolute


@dataclass(slots=True, eq=False)
class Swept:
    """The columns of ``count`` variants over ``angle_deg``, and which are clean."""

    angle_deg: FloatArray
    """(positions,) the crank angles of every variant [°]"""
    columns: dict[str, FloatArray]
    """name -> (variants, positions), as a sweep of each variant gives them (the motion
    of the points left out; the link angles unwrapped across the variants)"""
    clean: FloatArray
    """(variants,) bool: the sweep of the variant alone gives these values and no note"""
    forces: bool
    """the plan has kinetostatics (the force columns are there)"""


def sweep(stacked: Mechanism, count: int) -> Swept:
    """The sweep of ``count`` variants stacked into ``stacked`` (``stack.stack`` or
    ``stack.spread``: numbers that differ are one value per (variant, position)), each
    over the sweep of its file; ``NotStackable`` where its plan calls for a stage that
    is not stacked (friction, a [drive])."""
    the_plan = plan(stacked)
    if not stackable(the_plan):
        raise NotStackable("friction, a [drive] or a [drive_line]: swept variant by variant")
    angle = stacked.sweep.angles()
    positions = angle.shape[0]
    kin = kinematics.sweep(stacked, np.tile(angle, count))
    hard = np.sin(stacked.dead_centre_angle)  # one, or one per position (a parameter)
    hard = hard[:, None] if np.ndim(hard) else hard
    well = kin.closes.all(axis=1) & kin.valid & (kin.conditioning > hard).all(axis=1)
    forces = kinetostatics.solve(stacked, kin) if the_plan.kinetostatics else None
    if forces is not None:
        well &= forces.valid
    everywhere = np.ones(well.shape, dtype=bool)
    block = Block(0, well.size, kin, forces, None, None, everywhere, everywhere)
    phases = {link: columns_.Continuous() for link in stacked.moving_links}
    # the reduced machine is bounded instead where nothing but inertia loads it
    machine = bool(np.any(stacked.gravity) or stacked.loads or stacked.springs)
    cols = columns_.columns(stacked, block, phases, points=False, machine=machine, own=False)
    clean = well.reshape(count, positions).all(axis=1)
    names = [name for name in cols if name != "angle_deg"]
    clean &= ~columns_.implausible(cols, names).reshape(count, positions).any(axis=1)
    bound = reach(stacked, kin.motion, count, forces is not None and not machine)
    clean &= bound <= columns_.PLAUSIBLE
    shaped = {name: values.reshape(count, positions) for name, values in cols.items()
              if name != "angle_deg"}
    return Swept(np.rad2deg(angle), shaped, clean, forces is not None)


def stackable(the_plan: Plan) -> bool:
    """Whether variants with this plan are swept together: not with friction, an
    equation of motion or an elastic drive line (whose check a single sweep makes, and
    may refuse, per variant)."""
    return not (the_plan.friction or the_plan.equation_of_motion or the_plan.drive_line)


def reach(mechanism: Mechanism, motion, count: int, machine: bool) -> FloatArray:
    """(variants,) a bound on the magnitude of every column a sweep of each variant gives
    that ``sweep`` leaves out: the point columns (x, y, vx, vy, ax, ay of the joints and
    named points) and, with ``machine``, the linkage reduced to the crank (J_red, dJ_red;
    M_load is 0 without gravity, loads or springs). For a point at distance r from its
    link's origin O, |x| ≤ |O| + r, |v| ≤ |v_O| + |ω|·r, |a| ≤ |a_O| + (|α| + ω²)·r,
    each magnitude bounded by the sum of its components' largest; J ≤ Σ m·v_S² + J_S·ω²
    and |J′| ≤ 2·Σ m·|v_S|·|a_S| + J_S·|ω|·|α| over the least crank speed Ω² and Ω³."""
    def largest(values):  # (n, links[, 2]) -> (variants, links): the largest magnitude
        shaped = values.reshape(count, -1, *values.shape[1:])
        top = np.maximum(shaped.max(axis=1), -shaped.min(axis=1))
        return top.sum(axis=-1) if top.ndim == 3 else top

    origin, velocity, acceleration = (largest(motion.origin), largest(motion.velocity),
                                      largest(motion.acceleration))
    omega, alpha = largest(motion.omega), largest(motion.alpha)
    out = np.zeros(count)
    energy, rate = np.zeros(count), np.zeros(count)
    for link in mechanism.links:
        radius = _radius(mechanism, link, count)
        w, a = omega[:, link], alpha[:, link]
        out = np.maximum.reduce([out, origin[:, link] + radius,
                                 velocity[:, link] + w * radius,
                                 acceleration[:, link] + (a + w * w) * radius])
        body = mechanism.links[link]
        if machine and link != FRAME and body.has_mass:
            mass, inertia = each(body.mass, count), each(body.inertia, count)
            centre = each(np.hypot(*body.centre), count)
            speed = velocity[:, link] + w * centre
            energy = energy + mass * speed * speed + inertia * w * w
            rate = rate + mass * speed * (acceleration[:, link] + (a + w * w) * centre) \
                + inertia * w * a
    if machine:
        crank = np.abs(motion.omega[:, CRANK]).reshape(count, -1).min(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.maximum.reduce([out, energy / crank ** 2, 2.0 * rate / crank ** 3])
    return np.where(np.isnan(out), np.inf, out)


def _radius(mechanism: Mechanism, link: int, count: int) -> float | FloatArray:
    """The largest distance of a point of ``link`` (a joint's or a named one) from its
    origin [m]: one, or one per variant where the points differ between variants."""
    points = [local for joint in mechanism.joints
              for number, local in zip(joint.links, _joint_points(joint))
              if number == link]
    points += [local for _, number, local in mechanism.named_points if number == link]
    radius = 0.0
    for x, y in points:
        radius = np.maximum(radius, each(np.hypot(x, y), count))
    return radius


def each(value, count: int) -> float | FloatArray:
    """A number of a stacked mechanism: as it is, or (one per variant and position,
    the same at every position of a variant) one per variant."""
    return value if np.ndim(value) == 0 else np.asarray(value).reshape(count, -1)[:, 0]


def _joint_points(joint: Joint) -> tuple:
    """A joint's link-fixed points, in the order of ``joint.links``: a revolute joint's
    two, a prismatic joint's guide point on the carrier and slider point on the slider."""
    return joint.points if isinstance(joint, Revolute) else (joint.guide_point,
                                                              joint.slider_point)
