"""What a mechanism calls for (``plan``) and the sweep that does it (``analyse``).

The plan is decided from the data before anything runs, and shown by ``describe``:
masses, loads or springs → kinetostatics; a friction coefficient → friction
solution and self-locking verdict; a slider with friction → its self-locking margin; clearance data → the clearance
check. Stages the scene does not call for are not run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from dyade.errors import AssemblyError, InputError
from dyade.linkage import kinematics, kinetostatics
from dyade.linkage.model import FloatArray, Mechanism, Revolute, Sweep, sweep_problem

if TYPE_CHECKING:  # imported where used: a kinematics-only run never loads them
    from dyade.linkage import drive, friction


@dataclass(frozen=True, slots=True)
class Plan:
    """The stages a sweep will run, decided from the data before anything runs
    (``plan``): each is a tuple of the joints it concerns, or a flag."""

    kinematics: bool = True
    kinetostatics: bool = False
    """masses, loads or springs present"""
    friction: tuple[tuple[int, int], ...] = ()
    """joints with μ > 0 (friction runs only with kinetostatics)"""
    self_locking: tuple[tuple[int, int], ...] = ()
    """sliders with μ > 0"""
    clearance: tuple[tuple[int, int], ...] = ()
    """revolute joints with clearance data in the file (peak-force check)"""
    equation_of_motion: str = ""
    """the motor of a [drive] table ('' without one): the crank's speed comes from the
    equation of motion"""

    def effects(self) -> list[str]:
        """One line per simulated effect."""
        out = ["kinematics: positions, velocities, accelerations of every link, joint and point"]
        if self.kinetostatics:
            out.append("kinetostatics: joint forces, driving torque, shaking force (d'Alembert, "
                       "backward dyad by dyad)")
        if self.friction:
            out.append("Coulomb friction (solved per dyad) in joints "
                       + ", ".join(f"({a},{b})" for a, b in self.friction)
                       + "; self-locking (friction dead centres) of their dyads")
        if self.self_locking:
            out.append("self-locking margin of sliders "
                       + ", ".join(f"({a},{b})" for a, b in self.self_locking))
        if self.clearance:
            out.append("clearance peak check (Dresig–Thümmel) in joints "
                       + ", ".join(f"({a},{b})" for a, b in self.clearance))
        if self.equation_of_motion:
            out.append(f"equation of motion J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_M(φ̇) + M_L(φ) − M_F with "
                       f"the motor: {self.equation_of_motion}; its periodic steady state "
                       f"(shooting over one revolution), or the run-up from rest when asked; "
                       f"then kinematics and forces at the real crank speed and acceleration")
        return out


def plan(mechanism: Mechanism) -> Plan:
    """Decide the stages from the data: only what the mechanism calls for.

    >>> import dyade
    >>> dyade.plan(dyade.read_mechanism("mechanisms/fourbar.toml")).kinetostatics
    True
    """
    dynamics = mechanism.has_dynamics
    rubbing = tuple(j.name for j in mechanism.joints if j.friction > 0.0) if dynamics else ()
    locking = tuple(j.name for j in mechanism.friction_sliders) if dynamics else ()
    gaps = tuple(j.name for j in mechanism.joints
                 if getattr(j, "clearance", None) is not None) if dynamics else ()
    motion = ""
    if mechanism.drive is not None:
        motion = mechanism.drive.motor.describe()
        if mechanism.drive.flywheel_inertia:
            motion += f", flywheel {mechanism.drive.flywheel_inertia:g} kg·m²"
    return Plan(kinematics=True, kinetostatics=dynamics, friction=rubbing, self_locking=locking,
                clearance=gaps, equation_of_motion=motion)


_infer_plan = plan  # ``analyse`` has a parameter named plan


class Note(NamedTuple):
    """A finding of the sweep a user must know about (``str(note)`` is its text)."""

    kind: str
    """"partial", "dead_centre", "forces_invalid", "friction_not_converged", "at_rest",
    "never_moves", "self_locking", "near_self_locking" or "clearance_not_applicable" """
    subject: str
    """what it concerns: "dyad 3", "joint (3,4)", "slider (1,4)", or "" """
    ranges: tuple[tuple[float, float], ...]
    """crank-angle ranges (first, last) [rad] where it holds; () where not positional"""
    text: str
    """the sentence, as the command line prints it"""

    def __str__(self) -> str:
        return self.text


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Result:
    """Everything a sweep computed, in SI units.

    ``columns()`` gives the sweep as named columns (the CSV contract, documented in
    ``mechanisms/README.md``), ``summary()`` the extremes and the figures a designer
    sizes parts by, ``notes`` the findings (dead centres, partial sweeps, friction,
    self-locking), ``to_pandas()`` a DataFrame indexed by the crank angle [°].
    """

    mechanism: Mechanism
    plan: Plan
    kinematics: kinematics.Kinematics
    forces: kinetostatics.Forces | None
    """joint forces and drive torque; None when the plan has no kinetostatics"""
    rows: FloatArray
    """(n,) bool: positions that are reported (all, or with allow_partial the closing ones)"""
    notes: list[Note] = field(default_factory=list)
    """findings: dead centres, partial sweeps, friction, self-locking, clearance"""
    friction: friction.FrictionResult | None = None
    """friction loads, determinants and verdicts; None without friction"""
    locking: dict | None = None
    """joint -> self_locking.Locking for every slider with friction and every joint that
    self-locks; None without friction"""
    clearance: list | None = None
    """joint_clearance.JointCheck per joint with clearance data; None without such data"""
    valid: FloatArray | None = None
    """(n,) bool: the kinematics is given (closes, outside the dead-centre band,
    plausible); forces additionally need ``forces.valid``"""
    cached: dict | None = None
    """the columns, computed once by ``run``"""
    drive: drive.CrankMotion | None = None
    """the crank's motion from the equation of motion; None at constant speed"""
    phases: dict | None = None
    """a block of a streamed sweep: link -> ``columns.Continuous``, its link angles'
    unwrapping carried on from the blocks before; None for a whole sweep"""

    @property
    def crank_angle(self) -> FloatArray:
        """(n,) crank angle φ21 of every computed position [rad]."""
        return self.kinematics.crank_angle

    def columns(self) -> dict[str, FloatArray]:
        """The reported positions as named columns, in the CSV's order and units (SI,
        angles in degrees: names ending in ``_deg``); NaN where a value is not given."""
        if self.cached is None:
            from dyade.linkage import columns

            self.cached = columns.columns(self)
        return self.cached

    def summary(self, cols: dict[str, FloatArray] | None = None) -> dict[str, Any]:
        """Extremes of every column and where, drive torque and power, joint peaks,
        friction, self-locking and clearance figures, as plain numbers."""
        from dyade.linkage import summary

        return summary.summary(self, self.columns() if cols is None else cols)

    def to_pandas(self):
        """The columns as a ``pandas.DataFrame`` indexed by ``angle_deg`` (needs pandas)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Result.to_pandas() needs pandas, which dyade does not install: "
                              "pip install pandas") from None
        return pandas.DataFrame(self.columns()).set_index("angle_deg")


def ranges(crank_angle: FloatArray, mask: FloatArray) -> list[tuple[float, float]]:
    """Crank-angle ranges [rad] (first, last) of runs of True in ``mask``."""
    if not mask.any():
        return []
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(float(crank_angle[a]), float(crank_angle[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def format_ranges(spans: list[tuple[float, float]], limit: int = 6, digits: int = 1) -> str:
    """'212.0°–247.5°, 300.0°' for crank-angle ranges [rad], with ``digits`` decimals."""
    parts = []
    for first, last in spans:
        a, b = np.rad2deg(first), np.rad2deg(last)
        parts.append(f"{a:.{digits}f}°" if first == last else f"{a:.{digits}f}°–{b:.{digits}f}°")
    if len(parts) > limit:
        parts = parts[:limit] + [f"and {len(parts) - limit} more"]
    return ", ".join(parts)


def decimals(crank_angle: FloatArray) -> int:
    """Decimals [°] that tell the positions of a sweep apart: 1 for 1°, 2 for 0.01°."""
    if crank_angle.size < 2:
        return 1
    step = float(np.rad2deg(np.min(np.abs(np.diff(crank_angle)))))
    return int(min(6, max(1, np.ceil(-np.log10(step) - 1e-9)))) if step > 0 else 1


def with_sweep(mechanism: Mechanism, start: float | None = None, stop: float | None = None,
               step: float | None = None) -> Mechanism:
    """The mechanism with its sweep changed [rad]; ``stop`` defaults to one revolution
    after a given ``start`` (else the mechanism's own)."""
    if start is None and stop is None and step is None:
        return mechanism
    current = mechanism.sweep
    for name, value in (("start", start), ("stop", stop), ("step", step)):
        if value is not None and not math.isfinite(value):
            raise InputError.parameter(name, f"must be a finite angle [rad], got {value}.",
                                       value=value, unit="rad")
    if stop is None:
        stop = current.stop if start is None else start + 2 * math.pi
    start = current.start if start is None else start
    step = current.step if step is None else step
    if step <= 0:
        raise InputError.parameter("step", f"must be positive [rad], got {step:g}.", value=step,
                                   unit="rad")
    if stop < start:
        raise InputError.parameter("stop", f"must not be below the start angle [rad], got "
                                           f"{stop:g}.", value=stop, unit="rad")
    problem = sweep_problem(start, stop, step)
    if problem:
        raise InputError.parameter("sweep", f"{problem}.", unit="rad")
    return replace(mechanism, sweep=Sweep(start, stop, step))


MAX_MEMORY = 4 << 30  # [B] default bound on what a sweep may take (overridable)
BYTES_PER_VALUE = 90  # [B] per column and position: arrays, the table and its CSV text
"""measured: dyade-16 (269 columns) and the four-bar (59) at 3 600 and 36 000 positions
peak at 84-86 B per column and position in `dyade analyse --format csv`"""


def memory_estimate(mechanism: Mechanism, positions: int) -> int:
    """What a sweep of ``positions`` will take [B], from its column count."""
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    prismatic = len(mechanism.joints) - revolute
    columns = (1 + 3 * len(mechanism.moving_links) + 6 * revolute + 3 * prismatic
               + 6 * len(mechanism.named_points) + len(mechanism.dyads))
    if mechanism.has_dynamics:
        rubbing = sum(j.friction > 0.0 for j in mechanism.joints)
        columns += 3 * revolute + 2 * prismatic + 6 + 2 * rubbing + (2 if rubbing else 0)
    return BYTES_PER_VALUE * columns * positions + (50 << 20)


def check_size(mechanism: Mechanism, positions: int, max_memory: float | None,
               estimate=None) -> None:
    """Refuse a sweep that would take more than ``max_memory`` [B], before allocating;
    ``estimate(mechanism, positions)`` [B] (default ``memory_estimate``)."""
    bound = MAX_MEMORY if max_memory is None else max_memory
    need = (estimate or memory_estimate)(mechanism, positions)
    if need > bound:
        raise InputError.parameter(
            "max_memory", f"is {_size(bound)}, and this sweep of {positions:,} positions would "
                          f"take about {_size(need)}. Use a coarser step or a shorter range, or "
                          f"raise the bound.", value=bound, unit="B")


def _size(nbytes: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if nbytes < 1000 or unit == "PB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1000


def analyse(mechanism: Mechanism, *, start: float | None = None, stop: float | None = None,
            step: float | None = None, crank_angle: FloatArray | None = None,
            allow_partial: bool = False, friction_tol: float | None = None,
            friction_max_iter: int | None = None, plan: Plan | None = None,
            max_memory: float | None = None, dead_centre: float | None = None,
            transmission_warning: float | None = None,
            crank_speed: FloatArray | float | None = None,
            crank_acceleration: FloatArray | float | None = None,
            constant_speed: bool = False, run_up: bool = False) -> Result:
    """Sweep the crank: kinematics, and what the mechanism calls for (``plan``).

    Parameters
    ----------
    mechanism : Mechanism
        From ``read_mechanism`` or ``build_mechanism``.
    start, stop, step : float, optional
        The crank-angle sweep [rad], overriding the mechanism's; ``stop`` defaults to one
        revolution after ``start``.
    crank_angle : array_like, optional
        Crank angles φ21 [rad] to compute instead of a regular sweep.
    allow_partial : bool
        Report only the positions where every dyad closes, with a note, instead of
        raising ``AssemblyError``.
    friction_tol : float, optional
        A position's friction solution is accepted when a fixed-point step would change
        its joint forces or friction loads by less than this share [-].
    friction_max_iter : int, optional
        Most passes of the friction solution per dyad and position.
    plan : Plan, optional
        The stages to run (default: ``plan(mechanism)``).
    max_memory : float, optional
        Refuse, before allocating anything, a sweep estimated to take more memory [B]
        (default ``MAX_MEMORY``, 4 GiB).
    dead_centre, transmission_warning : float, optional
        The validity policy's hard and soft bands [rad] (defaults: the mechanism's,
        2° and 40°): within ``dead_centre`` of a dead centre nothing is given; below
        ``transmission_warning`` results come with a note.
    crank_speed, crank_acceleration : float or array_like, optional
        The crank's speed φ̇21 [rad/s] and angular acceleration φ̈21 [rad/s²], one value
        or one per position, instead of the constant speed of the file: the kinematics
        and forces of a crank that speeds up or slows down.
    constant_speed : bool
        Ignore the ``[drive]`` table: the crank at its constant ``speed_rpm``.
    run_up : bool
        With a ``[drive]`` table: the run-up from rest at the start angle instead of the
        periodic steady state; the positions are the whole run-up at the sweep's step.

    Returns
    -------
    Result

    Raises
    ------
    AssemblyError
        A dyad cannot close over part of the sweep (naming the dyad and the ranges).

    Examples
    --------
    >>> import dyade
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> cols = result.columns()
    >>> cols["angle_deg"].size, round(float(cols["M_drive"].max()), 3)
    (361, 1.466)

    One position of a crank that speeds up (φ̇21 = 20 rad/s, φ̈21 = 150 rad/s²):

    >>> torque = dyade.analyse(result.mechanism, crank_angle=[0.5], crank_speed=20.0,
    ...                        crank_acceleration=150.0).columns()["M_drive"]
    >>> round(float(torque[0]), 4)
    0.0378
    """
    mechanism, the_plan = configure(
        mechanism, start=start, stop=stop, step=step, positions=None if crank_angle is None
        else np.size(crank_angle), friction_tol=friction_tol,
        friction_max_iter=friction_max_iter, plan=plan, max_memory=max_memory,
        dead_centre=dead_centre, transmission_warning=transmission_warning,
        given_speed=crank_speed is not None or crank_acceleration is not None,
        constant_speed=constant_speed, run_up=run_up)
    for name, value in (("crank_speed", crank_speed), ("crank_acceleration", crank_acceleration)):
        if value is not None and not np.all(np.isfinite(value)):
            raise InputError.parameter(name, "must be finite.", value=value)
    return run(mechanism, the_plan, allow_partial, crank_angle, crank_speed, crank_acceleration,
               run_up)


def configure(mechanism: Mechanism, *, start: float | None = None, stop: float | None = None,
              step: float | None = None, positions: int | None = None,
              friction_tol: float | None = None, friction_max_iter: int | None = None,
              plan: Plan | None = None, max_memory: float | None = None,
              dead_centre: float | None = None, transmission_warning: float | None = None,
              given_speed: bool = False, constant_speed: bool = False, run_up: bool = False,
              estimate=None) -> tuple[Mechanism, Plan]:
    """``analyse``'s options checked and applied: the mechanism to sweep and its plan.
    ``positions``: how many crank angles are given (default: the sweep's); ``estimate``:
    the memory the sweep needs [B] as a function of (mechanism, positions) (default
    ``memory_estimate``)."""
    mechanism = with_sweep(mechanism, start, stop, step)
    if friction_tol is not None:
        if not (math.isfinite(friction_tol) and friction_tol > 0):
            raise InputError.parameter("friction_tol", f"must be a positive number [-], got "
                                                       f"{friction_tol}.", value=friction_tol)
        mechanism = replace(mechanism, friction_tol=friction_tol)
    if friction_max_iter is not None:
        if friction_max_iter < 1:
            raise InputError.parameter("friction_max_iter", f"must be at least 1, got "
                                                            f"{friction_max_iter}.",
                                       value=friction_max_iter)
        mechanism = replace(mechanism, friction_max_iter=friction_max_iter)
    if dead_centre is not None or transmission_warning is not None:
        hard = mechanism.dead_centre_angle if dead_centre is None else dead_centre
        soft = mechanism.transmission_warning if transmission_warning is None else transmission_warning
        if not (math.isfinite(hard) and math.isfinite(soft) and 0.0 <= hard < soft <= np.pi / 2):
            raise InputError.parameter(("dead_centre", "transmission_warning"),
                                       f"must satisfy 0 ≤ the dead-centre band < the warning angle ≤ "
                                       f"90°, got {np.rad2deg(hard):g}° and {np.rad2deg(soft):g}°.")
        mechanism = replace(mechanism, dead_centre_angle=hard, transmission_warning=soft)
    positions = mechanism.sweep.count if positions is None else positions
    check_size(mechanism, positions, max_memory, estimate)
    the_plan = plan if plan is not None else _infer_plan(mechanism)
    if constant_speed and the_plan.equation_of_motion:
        the_plan = replace(the_plan, equation_of_motion="")
    if run_up and not the_plan.equation_of_motion:
        raise InputError.parameter("run_up", "needs a [drive] table in the mechanism (a motor "
                                             "to run it up with).", value=run_up)
    if the_plan.equation_of_motion and given_speed:
        raise InputError.parameter(("crank_speed", "crank_acceleration"),
                                   "cannot be given with a [drive] table: its equation of "
                                   "motion sets the crank's speed (analyse at constant speed "
                                   "to give them).")
    return mechanism, the_plan


def run(mechanism: Mechanism, the_plan: Plan | None = None, allow_partial: bool = False,
        crank_angle: FloatArray | None = None, crank_speed: FloatArray | float | None = None,
        crank_acceleration: FloatArray | float | None = None, run_up: bool = False) -> Result:
    """Run the planned stages over the crank sweep (``analyse`` without the overrides)."""
    the_plan = the_plan or plan(mechanism)
    motion = None
    if the_plan.equation_of_motion:
        from dyade.linkage import drive

        motion = drive.solve(mechanism, crank_angle, run_up=run_up,
                             friction=bool(the_plan.friction))
        crank_angle, crank_speed = motion.crank_angle, motion.speed
        crank_acceleration = motion.acceleration
    kin = kinematics.sweep(mechanism, crank_angle, crank_speed, crank_acceleration)
    notes: list[Note] = []
    rows = _check_assembly(mechanism, kin, allow_partial, notes)
    well = _bands(mechanism, kin, rows, notes)
    forces = rubbing = locking = None
    angle = kin.crank_angle
    digits = decimals(angle)
    if the_plan.friction:
        from dyade.linkage import friction, self_locking

        rubbing = friction.solve(mechanism, kin)
        forces = rubbing.forces
        _friction_notes(mechanism, kin, rubbing, rows, notes)
        if the_plan.self_locking or rubbing.locks:  # slider margins, or a lock to name
            locking = self_locking.test(mechanism, kin, rubbing)
            _locking_notes(mechanism, kin, locking, rows, notes)
    elif the_plan.kinetostatics:
        forces = kinetostatics.solve(mechanism, kin)
    result = Result(mechanism, the_plan, kin, forces, rows, notes, rubbing, locking, valid=well,
                    drive=motion)
    result.cached = _plausible(result, digits)
    if forces is not None:
        invalid = result.valid & ~forces.valid
        if rubbing is not None:  # those get their own notes
            invalid &= ~(rubbing.locked | rubbing.unsolved)
            for mask in rubbing.near.values():
                invalid &= ~mask
        if invalid.any():
            notes.append(_forces_invalid_note(angle, invalid, digits))
    if motion is not None:
        _motion_notes(motion, notes)
    if the_plan.clearance and run_up:
        notes.append(Note("clearance_not_applicable", "", (),
                          "the clearance check is not made on a run-up: it needs the periodic "
                          "cycle."))
    elif the_plan.clearance:
        result.clearance = _clearance(mechanism, result, the_plan, notes)
    return result


def _clearance(mechanism: Mechanism, result, the_plan: Plan, notes: list[Note]) -> list:
    """The clearance check of the plan's joints, and a note for each it does not apply to."""
    from dyade.linkage import joint_clearance

    checks = joint_clearance.check_mechanism(mechanism, result, the_plan.clearance)
    for check in checks:
        if not check.applies:
            a, b = check.joint
            notes.append(Note("clearance_not_applicable", f"joint ({a},{b})", (),
                              f"clearance check of joint ({a},{b}) does not apply: "
                              f"{check.reason}."))
    return checks


def _check_assembly(mechanism: Mechanism, kin: kinematics.Kinematics, allow_partial: bool,
                    notes: list[Note]) -> FloatArray:
    """Rows that close; an AssemblyError naming dyads and ranges unless allowed."""
    upstream = np.ones(kin.crank_angle.shape[0], dtype=bool)
    problems = []
    for col, dyad in enumerate(mechanism.dyads):
        fails = upstream & ~kin.closes[:, col]
        if fails.any():
            problems.append(f"{dyad.label} {dyad.kind.cannot_close} for crank angles "
                            f"{format_ranges(ranges(kin.crank_angle, fails), digits=decimals(kin.crank_angle))}")
        upstream = upstream & kin.closes[:, col]
    if not problems:
        return np.ones(kin.crank_angle.shape[0], dtype=bool)
    kept = int(upstream.sum())
    if kept == 0:
        raise AssemblyError("the mechanism closes at no crank angle of the sweep: "
                            + "; ".join(problems) + ".", tuple(problems))
    if not allow_partial:
        raise AssemblyError("; ".join(problems) + ". Change the dimensions or the sweep, or "
                            "analyse only where it closes (allow_partial=True).",
                            tuple(problems), partial=True)
    notes.append(Note("partial", "", tuple(ranges(kin.crank_angle, ~upstream)),
                      "; ".join(problems) + f". Those positions are left out ({kept} of "
                      f"{upstream.size} kept)."))
    return upstream


def _bands(mechanism: Mechanism, kin: kinematics.Kinematics, rows: FloatArray,
           notes: list[Note]) -> FloatArray:
    """The validity policy: (n,) bool, the positions whose kinematics is given.

    Each dyad's quality at each position comes from its own geometry (the sine of its
    transmission angle; an RPR dyad's also from its pivot distance): within the hard
    band (``dead_centre_angle`` of 0° or 180°) the rigid model is invalid and nothing is
    given; in the soft band (transmission angle below ``transmission_warning``, the
    designers' rule) results are given with a note naming the dyad, the ranges and the
    smallest transmission angle."""
    hard = np.sin(mechanism.dead_centre_angle)
    soft = np.sin(mechanism.transmission_warning)
    digits = decimals(kin.crank_angle)
    well = rows & kin.valid
    for col, dyad in enumerate(mechanism.dyads):
        quality = kin.conditioning[:, col]
        near = rows & (quality <= hard)
        if near.any():
            spans = ranges(kin.crank_angle, near)
            notes.append(Note("dead_centre", f"dyad {dyad.number}", tuple(spans),
                              f"{dyad.label} is within "
                              f"{np.rad2deg(mechanism.dead_centre_angle):g}° of a "
                              f"{dyad.kind.singular} (transmission angle near 0° or 180°) at "
                              f"crank angles {format_ranges(spans, digits=digits)}: the rigid "
                              f"model is invalid there, and nothing is given (empty in CSV, "
                              f"null in JSON)."))
            well &= ~near
        poor = rows & (quality > hard) & (quality < soft)
        if poor.any():
            mu = np.rad2deg(kin.transmission[:, col])
            off = np.where(poor, np.minimum(mu, 180.0 - mu), np.inf)
            k = int(np.argmin(off))
            spans = ranges(kin.crank_angle, poor)
            notes.append(Note("poor_transmission", f"dyad {dyad.number}", tuple(spans),
                              f"{dyad.label} has a transmission angle below "
                              f"{np.rad2deg(mechanism.transmission_warning):g}° (the designers' "
                              f"rule) at crank angles {format_ranges(spans, digits=digits)}, "
                              f"{off[k]:.{digits}f}° at the least (crank angle "
                              f"{np.rad2deg(kin.crank_angle[k]):.{digits}f}°): results are "
                              f"given, but the drive is sensitive to friction, clearance and "
                              f"elasticity there."))
    return well


def _plausible(result: Result, digits: int, masks: dict | None = None
               ) -> dict[str, FloatArray]:
    """The columns, with the rows that hold a value beyond ``PLAUSIBLE`` taken out
    (``result.valid``, ``forces.valid`` updated) and a note; returns the columns.
    With ``masks`` (a block of a streamed sweep), the positions taken out go there
    ("kinematics", "forces" -> (n,) bool) instead of a note."""
    from dyade.linkage import columns

    cols = columns.columns(result)
    kinematic = [name for name in cols if name in columns.KINEMATIC_EXEMPT
                 or not name.startswith(columns.FORCE_PREFIXES)]
    for block, names in (("kinematics", [n for n in kinematic if n != "angle_deg"]),
                         ("forces", [n for n in cols if n not in kinematic])):
        if not names:
            continue
        bad = columns.implausible(cols, names)
        if not bad.any():
            continue
        where = np.flatnonzero(result.rows)[bad]
        mask = np.zeros_like(result.rows)
        mask[where] = True
        if block == "kinematics":
            result.valid &= ~mask
        if result.forces is not None:
            result.forces.valid &= ~mask
        if masks is None:
            result.notes.append(_implausible_note(block, result.crank_angle, mask, digits))
        else:
            masks[block] = mask
        cols = columns.columns(result)
    return cols


def _implausible_note(block: str, angle: FloatArray, mask: FloatArray, digits: int) -> Note:
    from dyade.linkage.columns import PLAUSIBLE

    spans = ranges(angle, mask)
    return Note("implausible", "", tuple(spans),
                f"{block} beyond {PLAUSIBLE:.0e} (SI units) at crank angles "
                f"{format_ranges(spans, digits=digits)}: no machine moves or loads so; those "
                f"rows are not given.")


def _forces_invalid_note(angle: FloatArray, invalid: FloatArray, digits: int) -> Note:
    spans = ranges(angle, invalid)
    return Note("forces_invalid", "", tuple(spans),
                f"forces are not given at crank angles {format_ranges(spans, digits=digits)}, "
                f"where the kinematics is: the rigid model's forces are not valid there "
                f"(forces_valid = 0, force fields empty).")


def _friction_notes(mechanism: Mechanism, kin: kinematics.Kinematics,
                    rubbing: "friction.FrictionResult", rows: FloatArray, notes: list[Note]
                    ) -> None:
    angle = kin.crank_angle
    digits = decimals(angle)
    band = np.sin(mechanism.dead_centre_angle)
    for dyad in mechanism.dyads:
        near = rows & rubbing.near.get(dyad.number, np.zeros_like(rows))
        if near.any():
            spans = ranges(angle, near)
            notes.append(Note("near_self_locking", f"dyad {dyad.number}", tuple(spans),
                              f"{dyad.label} is near self-locking at crank angles "
                              f"{format_ranges(spans, digits=digits)}: its friction-augmented determinant is "
                              f"below {band:.3g} or friction multiplies its joint forces more "
                              f"than {1 / band:.0f}-fold (the sin of, and one over, the "
                              f"{np.rad2deg(mechanism.dead_centre_angle):g}° dead-centre band); "
                              f"the rigid model is invalid there (forces_valid = 0, force "
                              f"fields empty)."))
    failed = rows & rubbing.unsolved
    if failed.any():
        spans = ranges(angle, failed)
        from dyade.linkage.friction import RESTART_PASSES

        few = mechanism.friction_max_iter < RESTART_PASSES
        notes.append(Note("friction_not_converged", "", tuple(spans),
                          f"no consistent friction solution was found in "
                          f"{mechanism.friction_max_iter} passes (tolerance "
                          f"{mechanism.friction_tol:g}) at {int(failed.sum())} positions: crank "
                          f"angles {format_ranges(spans, digits=digits)}; forces are not given there "
                          f"(forces_valid = 0)"
                          + (f"; fewer than {RESTART_PASSES} passes (friction.max_iter) "
                             f"give no self-locking verdict." if few else ".")))
    for name, mask in rubbing.at_rest.items():
        if (mask & rows).any():
            spans = ranges(angle, mask & rows)
            notes.append(Note("at_rest", f"joint ({name[0]},{name[1]})", tuple(spans),
                              f"joint ({name[0]},{name[1]}) is at rest relative to its partner at "
                              f"crank angles {format_ranges(spans, digits=digits)}: the friction direction is "
                              f"undefined there and no friction is applied."))
    for name in rubbing.never_moves:
        notes.append(Note("never_moves", f"joint ({name[0]},{name[1]})", (),
                          f"joint ({name[0]},{name[1]}) never moves relative to its partner over "
                          f"the sweep: it has no friction loss."))


def _motion_notes(motion: "drive.CrankMotion", notes: list[Note]) -> None:
    figures = motion.figures
    if motion.state == "run-up" and not figures["settled"]:
        notes.append(Note("run_up_not_settled", "", (),
                          f"the run-up did not become periodic within {figures['revolutions']} "
                          f"revolutions (raise [drive] max_revolutions)."))
    if not figures["friction_converged"]:
        notes.append(Note("friction_not_converged", "", (),
                          f"the friction torque of the equation of motion did not settle in "
                          f"{figures['passes']} passes (largest change "
                          f"{figures['friction_change']:.3g} N·m)."))


def _locking_notes(mechanism: Mechanism, kin: kinematics.Kinematics, locking: dict,
                   rows: FloatArray, notes: list[Note]) -> None:
    labels = {dyad.number: dyad.label for dyad in mechanism.dyads}
    for joint in mechanism.joints:
        lock = locking.get(joint.name)
        if lock is None or not (lock.locks & rows).any():
            continue
        a, b = joint.name
        what = "slider" if joint.kind == "P" else "joint"
        spans = ranges(kin.crank_angle, lock.locks & rows)
        notes.append(Note("self_locking", f"{what} ({a},{b})", tuple(spans),
                          f"{what} ({a},{b}) locks (self-locking) at crank angles "
                          f"{format_ranges(spans, digits=decimals(kin.crank_angle))}: {labels[lock.dyad]} has no friction "
                          f"equilibrium there (its friction-augmented determinant changes "
                          f"sign: a friction dead centre, caused by the friction in ({a},{b})); "
                          f"forces are not given there (forces_valid = 0)."))
