"""The servo-driven linkage: the crank follows a motion profile over the cycle time (an
"electronic cam"), or the profile is given for an output (a slider's travel, a link's
angle) and inverted through the linkage to the crank's motion; the torque the crank
shaft needs then comes from the sweep at the real crank speed and acceleration of every
instant (inverse dynamics, the kinetostatics of ``dyade.linkage.pipeline``):

    M_c = J(φ)·φ̈ + ½·J′(φ)·φ̇² − M_L(φ) + M_F.

Inversion. Along the output's branch between two of its dead centres (where its
velocity ratio s′ = ds/dφ changes sign) the output position s(φ) is monotonic; the crank
angle of every instant solves s(φ) = s*(t) by Newton's method, all instants at once,
from a table of the branch. Then φ̇ = ṡ*/s′ and φ̈ = (s̈* − s″·φ̇²)/s′, with s′ and s″
the output's velocity and acceleration at unit crank speed. Where the profile asks for
an output beyond a dead centre the inverse is not unique (or does not exist), and the
inversion is refused naming the dead centres' crank angles.

The motor behind its gear is ``dyade.machine.servo``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError
from dyade.linkage.plan import Plan, plan
from dyade.linkage.sweep import analyse
from dyade.machine import servo as engine
from dyade.model.mechanism import Mechanism

INVERSE_STEP = math.radians(0.25)  # [rad] the table of the output over a revolution
NEWTON_MAX_ITER = 50  # most Newton iterations of the inversion
INVERSE_TOL = 1e-13  # [-] |s(φ) − s*| relative to the branch's travel that counts as solved
OUTPUT = re.compile(r"^(?:s_(\d+)_(\d+)|phi_(\d+))$")


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Target:
    """The profile's motion at the instants of the cycle, SI: the crank's angle [rad],
    or the output's position [m or rad], and their time derivatives."""

    time: FloatArray
    """(n,) t [s]"""
    position: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    jerk: FloatArray


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class ServoMotion:
    """The crank's motion over the cycle and what the crank shaft needs for it."""

    time: FloatArray
    """(n,) t [s]"""
    angle: FloatArray
    """(n,) φ [rad]"""
    speed: FloatArray
    """(n,) φ̇ [rad/s]"""
    acceleration: FloatArray
    """(n,) φ̈ [rad/s²]"""
    target: Target
    """the profile's motion (of the crank or the output)"""
    torque: FloatArray | None = None
    """(n,) M_c [N·m], the drive torque of the sweep at φ, φ̇, φ̈ (inverse dynamics)"""
    inertia: FloatArray | None = None
    """(n,) J(φ) [kg·m²]"""
    inertia_slope: FloatArray | None = None
    """(n,) J′(φ) [kg·m²/rad]"""
    load: FloatArray | None = None
    """(n,) M_L(φ) [N·m]"""
    friction: FloatArray | None = None
    """(n,) M_F = M_c − (J·φ̈ + ½·J′·φ̇² − M_L) [N·m], the friction's share"""
    branch: tuple[float, float] | None = None
    """the crank angles [rad] of the output's dead centres that bound the inversion"""
    iterations: int = 0
    """Newton iterations of the inversion"""

    def cycle(self) -> engine.Cycle:
        """The cycle as the motor's sizing takes it."""
        return engine.Cycle(self.time, self.speed, self.acceleration, self.torque,
                            self.inertia)


def output_columns(name: str) -> tuple[str, str, str, float]:
    """The sweep's columns of an output (position, velocity, acceleration) and the
    factor that takes the position column to SI: ``s_1_4`` -> (s_1_4, v_1_4, a_1_4, 1),
    ``phi_4`` -> (phi_4_deg, omega_4, alpha_4, π/180)."""
    match = OUTPUT.match(name)
    if match is None:
        raise ValueError(name)
    if match.group(3) is not None:
        link = match.group(3)
        return f"phi_{link}_deg", f"omega_{link}", f"alpha_{link}", math.pi / 180.0
    i, j = match.group(1), match.group(2)
    return f"s_{i}_{j}", f"v_{i}_{j}", f"a_{i}_{j}", 1.0


def _unit_speed(mechanism: Mechanism, angles: FloatArray, name: str
                ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """The output's position s, s′ and s″ at unit crank speed at ``angles`` [rad] (the
    angles where the linkage closes, returned first)."""
    position, velocity, acceleration, factor = output_columns(name)
    result = analyse(mechanism, crank_angle_deg=np.degrees(angles), crank_speed=1.0,
                     crank_acceleration=0.0, allow_partial=True, plan=Plan())
    columns = result.columns()
    closed = np.radians(columns["angle_deg"])
    s = columns[position] * factor
    if factor != 1.0:  # an angle: continuous along the table
        s = np.unwrap(s)
    return closed, s, columns[velocity], columns[acceleration], columns["angle_deg"]


def dead_centres(mechanism: Mechanism, name: str, start: float
                 ) -> tuple[float, float, FloatArray, FloatArray]:
    """The output's branch through the crank angle ``start``: the crank angles of the
    dead centres before and after it (s′ = 0, linear between the table's points) and the
    table of the branch (crank angles, output positions), monotonic.

    Raises
    ------
    DyadeError
        The output is at a dead centre at ``start``, or has none within a revolution
        either way (a crank-driven output: no inversion needed), or the linkage does not
        close at ``start``.
    """
    count = int(round(2.0 * math.pi / INVERSE_STEP))
    grid = start + INVERSE_STEP * np.arange(-count, count + 1)
    closed, s, ds, _, _ = _unit_speed(mechanism, grid, name)
    here = np.flatnonzero(np.isclose(closed, start, rtol=0.0, atol=1e-12))
    if here.size == 0:
        raise DyadeError(f"the linkage does not close at the servo's start crank angle "
                         f"{math.degrees(start):.6g}°.")
    k = int(here[0])
    sense = np.sign(ds[k])
    if sense == 0.0:
        raise DyadeError(f"the output {name} is at a dead centre at the start crank angle "
                         f"{math.degrees(start):.6g}° (its velocity ratio is 0 there): start "
                         f"the cycle inside a stroke.")
    # the branch: the run of positions with s′ of the start's sign, through k, where the
    # positions follow one another on the grid (the linkage closes in between)
    same = (np.sign(ds) == sense)
    steps_ok = np.isclose(np.diff(closed), INVERSE_STEP, rtol=1e-9)
    low = k
    while low > 0 and same[low - 1] and steps_ok[low - 1]:
        low -= 1
    high = k
    while high < closed.size - 1 and same[high + 1] and steps_ok[high]:
        high += 1
    if low == 0 or high == closed.size - 1:
        raise DyadeError(f"the output {name} has no dead centre within a revolution of the "
                         f"start crank angle {math.degrees(start):.6g}°: it turns with the "
                         f"crank; give the profile to the crank (`servo.output = \"crank\"`).")

    def zero(a: int, b: int) -> float:  # s′ = 0 between the table's points a and b
        if not steps_ok[min(a, b)]:  # the linkage stops closing there
            return float(closed[a])
        return float(closed[a] + (closed[b] - closed[a]) * ds[a] / (ds[a] - ds[b]))

    return (zero(low, low - 1), zero(high, high + 1), closed[low:high + 1], s[low:high + 1])


def invert(mechanism: Mechanism, name: str, start: float, target: Target
           ) -> tuple[FloatArray, FloatArray, FloatArray, tuple[float, float], int]:
    """The crank's angle, speed and acceleration [rad, rad/s, rad/s²] that move the
    output ``name`` as ``target`` does (its positions measured from the output's
    position at the crank angle ``start``), the dead centres that bound the branch and
    the Newton iterations (module docstring).

    Raises
    ------
    DyadeError
        The profile asks for the output beyond a dead centre, naming the crank angles,
        or Newton's method does not converge.
    """
    first, last, table_angle, table_s = dead_centres(mechanism, name, start)
    s0 = float(np.interp(start, table_angle, table_s))
    wanted = s0 + target.position - target.position[0]
    lowest, highest = float(np.min(table_s)), float(np.max(table_s))
    beyond = (wanted <= lowest) | (wanted >= highest)
    if beyond[0]:
        raise DyadeError(f"the output {name} is at a dead centre at the start crank angle "
                         f"{math.degrees(start):.6g}° (its dead centres: crank angles "
                         f"{math.degrees(first):.6g}° and {math.degrees(last):.6g}°): start "
                         f"the cycle inside a stroke (`servo.start`).")
    if beyond.any():
        factor = output_columns(name)[3]
        unit = "°" if factor != 1.0 else " mm"
        scale = 1.0 / factor if factor != 1.0 else 1000.0
        times = target.time[beyond]
        raise DyadeError(
            f"the profile moves the output {name} beyond a dead centre at t = "
            f"{times[0]:.6g}–{times[-1]:.6g} s: from the start crank angle "
            f"{math.degrees(start):.6g}° it reaches only {lowest * scale:.6g}{unit} to "
            f"{highest * scale:.6g}{unit}, between its dead centres at crank angles "
            f"{math.degrees(first):.6g}° and {math.degrees(last):.6g}° (the profile asks "
            f"{np.min(wanted) * scale:.6g}{unit} to {np.max(wanted) * scale:.6g}{unit}); "
            f"beyond them the crank angle of an output position is not unique. Shorten the "
            f"profile's stroke or move `servo.start`.")
    order = np.argsort(table_s)
    angle = np.interp(wanted, table_s[order], table_angle[order])
    travel = highest - lowest
    for iteration in range(1, NEWTON_MAX_ITER + 1):
        closed, s, ds, dds, _ = _unit_speed(mechanism, angle, name)
        if closed.size != angle.size:
            raise DyadeError(f"the inversion of the profile on {name} left the linkage's "
                             f"branch (it does not close at every crank angle tried).")
        miss = s - wanted
        if np.max(np.abs(miss)) <= INVERSE_TOL * travel:
            speed = target.velocity / ds
            acceleration = (target.acceleration - dds * speed * speed) / ds
            return angle, speed, acceleration, (first, last), iteration
        angle = angle - miss / ds
    raise DyadeError(f"the inversion of the profile on {name} did not converge in "
                     f"{NEWTON_MAX_ITER} Newton iterations (to {INVERSE_TOL:g} of the stroke).")


def crank_motion(mechanism: Mechanism, output: str, start: float, target: Target
                 ) -> ServoMotion:
    """The crank's motion over the cycle: the profile's own (``output == "crank"``: the
    angle from ``start``) or inverted from the output's."""
    if output == "crank":
        return ServoMotion(target.time, start + target.position - target.position[0],
                           target.velocity.copy(), target.acceleration.copy(), target)
    angle, speed, acceleration, branch, iterations = invert(mechanism, output, start, target)
    return ServoMotion(target.time, angle, speed, acceleration, target, branch=branch,
                       iterations=iterations)


def inverse_dynamics(mechanism: Mechanism, motion: ServoMotion, **options) -> ServoMotion:
    """The sweep at the crank's real angle, speed and acceleration of every instant:
    ``motion`` with its torque M_c, J, J′, M_L and M_F filled in (``options``: those of
    ``analyse``, e.g. ``friction_tol``).

    Raises
    ------
    DyadeError
        The forces are not given at some instants (a dyad at a dead centre), naming them.
    """
    # the clearance check asks for a sweep over the crank angle, which a cycle in time is
    # not (a dwell repeats its angle): left out here
    stages = replace(plan(mechanism), clearance=())
    result = analyse(mechanism, crank_angle_deg=np.degrees(motion.angle),
                     crank_speed=motion.speed, crank_acceleration=motion.acceleration,
                     plan=stages, **options)
    columns = result.columns()
    if "M_drive" not in columns:
        raise DyadeError("the linkage has no masses, loads or springs: the servo's crank "
                         "needs no torque (give the links masses, `links.N.mass`).")
    torque = columns["M_drive"]
    valid = np.asarray(columns.get("forces_valid", np.ones(torque.size)), dtype=bool)
    if torque.size != motion.time.size or not valid.all():
        bad = ~valid if valid.size == motion.time.size else np.ones(motion.time.size, bool)
        times, angles = motion.time[bad], np.degrees(motion.angle[bad])
        raise DyadeError(f"the drive torque is not given at t = {times[0]:.6g}–{times[-1]:.6g} "
                         f"s (crank angles {angles.min():.6g}°–{angles.max():.6g}°): the sweep "
                         f"withholds the forces there (a dyad at or near a dead centre, or "
                         f"a slider that self-locks; `dyade analyse` at these angles says "
                         f"which).")
    inertia, slope, load = columns["J_red"], columns["dJ_red"], columns["M_load"]
    speed, accel = motion.speed, motion.acceleration
    motion.torque = torque
    motion.inertia, motion.inertia_slope, motion.load = inertia, slope, load
    motion.friction = torque - (inertia * accel + 0.5 * slope * speed * speed - load)
    return motion


def machine_function(mechanism: Mechanism, low: float, high: float, step: float
                     ) -> Callable[[float], tuple[float, float, float]]:
    """J(φ), J′(φ) and M_L(φ) between the crank angles ``low`` and ``high`` [rad] as a
    function of one angle, from tables every ``step`` [rad] (J by the cubic Hermite with
    its slope J′, J′ and M_L linear): the reduced machine for ``machine.servo.follow``."""
    count = int(math.ceil((high - low) / step)) + 1
    grid = low + step * np.arange(count)
    columns = analyse(mechanism, crank_angle_deg=np.degrees(grid), crank_speed=1.0,
                      crank_acceleration=0.0).columns()
    inertia, slope, load = (columns[name].tolist() for name in ("J_red", "dJ_red", "M_load"))
    h = float(step)

    def at(phi: float) -> tuple[float, float, float]:
        k = min(max(int((phi - low) / h), 0), count - 2)
        x = (phi - low) / h - k
        x2, x3 = x * x, x * x * x
        j = ((2 * x3 - 3 * x2 + 1) * inertia[k] + (x3 - 2 * x2 + x) * h * slope[k]
             + (3 * x2 - 2 * x3) * inertia[k + 1] + (x3 - x2) * h * slope[k + 1])
        return (j, slope[k] + x * (slope[k + 1] - slope[k]),
                load[k] + x * (load[k + 1] - load[k]))

    return at


LINE_STEPS_PER_PERIOD = 40  # RK4 steps per period of the line's natural frequency, at least
LINE_MARGIN = math.radians(20.0)  # [rad] the machine's tables reach this beyond the profile


def line_refinement(line, inertia: FloatArray, period: float, samples: int) -> int:
    """How many times finer than the cycle's samples the elastic line is integrated: at
    least ``LINE_STEPS_PER_PERIOD`` steps per period of its highest natural frequency
    √(k/min J) [-]."""
    omega = math.sqrt(line.stiffness / float(np.min(inertia)))
    return max(1, math.ceil(LINE_STEPS_PER_PERIOD * period * omega / (2.0 * math.pi * samples)))


def elastic_line(mechanism: Mechanism, fine: ServoMotion, friction: FloatArray
                 ) -> engine.LineCycle:
    """The crank's periodic motion behind the ``[drive_line]`` shaft whose motor end
    follows the crank's profile motion ``fine`` (at the half steps of its instants; the
    friction torque M_F there, frozen at the rigid motion's): ``machine.servo.
    line_periodic`` on the linkage's J, J′ and M_L."""
    line = mechanism.drive_line
    low = float(np.min(fine.angle)) - LINE_MARGIN
    high = float(np.max(fine.angle)) + LINE_MARGIN
    machine = machine_function(mechanism, low, high, math.radians(0.05))
    advance = float(fine.angle[-1] - fine.angle[0])
    return engine.line_periodic(machine, fine.angle, fine.speed, friction, fine.time,
                                line.stiffness, line.damping, advance)
