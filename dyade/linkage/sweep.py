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
from dyade.linkage.model import FloatArray, Mechanism, Sweep

if TYPE_CHECKING:  # imported where used: a kinematics-only run never loads them
    from dyade.linkage import friction


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
    return Plan(kinematics=True, kinetostatics=dynamics, friction=rubbing, self_locking=locking,
                clearance=gaps)


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

    @property
    def crank_angle(self) -> FloatArray:
        """(n,) crank angle φ21 of every computed position [rad]."""
        return self.kinematics.crank_angle

    def columns(self) -> dict[str, FloatArray]:
        """The reported positions as named columns, in the CSV's order and units (SI,
        angles in degrees: names ending in ``_deg``); NaN where a value is not given."""
        from dyade.linkage import columns

        return columns.columns(self)

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


def format_ranges(spans: list[tuple[float, float]], limit: int = 6) -> str:
    """'212.0°–247.5°, 300.0°' for crank-angle ranges [rad]."""
    parts = []
    for first, last in spans:
        a, b = np.rad2deg(first), np.rad2deg(last)
        parts.append(f"{a:.1f}°" if first == last else f"{a:.1f}°–{b:.1f}°")
    if len(parts) > limit:
        parts = parts[:limit] + [f"and {len(parts) - limit} more"]
    return ", ".join(parts)


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
    return replace(mechanism, sweep=Sweep(start, stop, step))


def analyse(mechanism: Mechanism, *, start: float | None = None, stop: float | None = None,
            step: float | None = None, crank_angle: FloatArray | None = None,
            allow_partial: bool = False, friction_tol: float | None = None,
            friction_max_iter: int | None = None, plan: Plan | None = None) -> Result:
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
    """
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
    return run(mechanism, plan, allow_partial, crank_angle)


def run(mechanism: Mechanism, the_plan: Plan | None = None, allow_partial: bool = False,
        crank_angle: FloatArray | None = None) -> Result:
    """Run the planned stages over the crank sweep (``analyse`` without the overrides)."""
    the_plan = the_plan or plan(mechanism)
    kin = kinematics.sweep(mechanism, crank_angle)
    notes: list[Note] = []
    rows = _check_assembly(mechanism, kin, allow_partial, notes)
    _dead_centres(mechanism, kin, rows, notes)
    forces = rubbing = locking = None
    angle = kin.crank_angle
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
    if forces is not None:
        invalid = rows & ~forces.valid
        if rubbing is not None:  # those get their own notes
            invalid &= ~(rubbing.locked | rubbing.unsolved)
            for mask in rubbing.near.values():
                invalid &= ~mask
        if invalid.any():
            spans = ranges(angle, invalid)
            notes.append(Note("forces_invalid", "", tuple(spans),
                              f"forces are not given at crank angles {format_ranges(spans)}: a "
                              f"dyad is at or near a dead centre or blocked position, where the "
                              f"rigid model is invalid (forces_valid = 0, force fields empty)."))
    result = Result(mechanism, the_plan, kin, forces, rows, notes, rubbing, locking)
    if the_plan.clearance:
        from dyade.linkage import joint_clearance

        result.clearance = joint_clearance.check_mechanism(mechanism, result, the_plan.clearance)
        for check in result.clearance:
            if not check.applies:
                a, b = check.joint
                notes.append(Note("clearance_not_applicable", f"joint ({a},{b})", (),
                                  f"clearance check of joint ({a},{b}) does not apply: "
                                  f"{check.reason}."))
    return result


def _check_assembly(mechanism: Mechanism, kin: kinematics.Kinematics, allow_partial: bool,
                    notes: list[Note]) -> FloatArray:
    """Rows that close; an AssemblyError naming dyads and ranges unless allowed."""
    upstream = np.ones(kin.crank_angle.shape[0], dtype=bool)
    problems = []
    for col, dyad in enumerate(mechanism.dyads):
        fails = upstream & ~kin.closes[:, col]
        if fails.any():
            problems.append(f"{dyad.label} {dyad.kind.cannot_close} for crank angles "
                            f"{format_ranges(ranges(kin.crank_angle, fails))}")
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


def _dead_centres(mechanism: Mechanism, kin: kinematics.Kinematics, rows: FloatArray,
                  notes: list[Note]) -> None:
    band = np.sin(mechanism.dead_centre_angle)
    for col, dyad in enumerate(mechanism.dyads):
        near = rows & (kin.conditioning[:, col] <= band)
        if near.any():
            spans = ranges(kin.crank_angle, near)
            notes.append(Note("dead_centre", f"dyad {dyad.number}", tuple(spans),
                              f"{dyad.label} is within "
                              f"{np.rad2deg(mechanism.dead_centre_angle):g}° of a "
                              f"{dyad.kind.singular} (transmission angle near 0° or 180°) at "
                              f"crank angles {format_ranges(spans)}."))


def _friction_notes(mechanism: Mechanism, kin: kinematics.Kinematics,
                    rubbing: "friction.FrictionResult", rows: FloatArray, notes: list[Note]
                    ) -> None:
    angle = kin.crank_angle
    band = np.sin(mechanism.dead_centre_angle)
    for dyad in mechanism.dyads:
        near = rows & rubbing.near.get(dyad.number, np.zeros_like(rows))
        if near.any():
            spans = ranges(angle, near)
            notes.append(Note("near_self_locking", f"dyad {dyad.number}", tuple(spans),
                              f"{dyad.label} is near self-locking at crank angles "
                              f"{format_ranges(spans)}: its friction-augmented determinant is "
                              f"below {band:.3g} or friction multiplies its joint forces more "
                              f"than {1 / band:.0f}-fold (the sin of, and one over, the "
                              f"{np.rad2deg(mechanism.dead_centre_angle):g}° dead-centre band); "
                              f"the rigid model is invalid there (forces_valid = 0, force "
                              f"fields empty)."))
    failed = rows & rubbing.unsolved
    if failed.any():
        spans = ranges(angle, failed)
        notes.append(Note("friction_not_converged", "", tuple(spans),
                          f"no consistent friction solution was found in "
                          f"{mechanism.friction_max_iter} passes (tolerance "
                          f"{mechanism.friction_tol:g}) at {int(failed.sum())} positions: crank "
                          f"angles {format_ranges(spans)}; forces are not given there "
                          f"(forces_valid = 0)."))
    for name, mask in rubbing.at_rest.items():
        if (mask & rows).any():
            spans = ranges(angle, mask & rows)
            notes.append(Note("at_rest", f"joint ({name[0]},{name[1]})", tuple(spans),
                              f"joint ({name[0]},{name[1]}) is at rest relative to its partner at "
                              f"crank angles {format_ranges(spans)}: the friction direction is "
                              f"undefined there and no friction is applied."))
    for name in rubbing.never_moves:
        notes.append(Note("never_moves", f"joint ({name[0]},{name[1]})", (),
                          f"joint ({name[0]},{name[1]}) never moves relative to its partner over "
                          f"the sweep: it has no friction loss."))


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
                          f"{format_ranges(spans)}: {labels[lock.dyad]} has no friction "
                          f"equilibrium there (its friction-augmented determinant changes "
                          f"sign: a friction dead centre, caused by the friction in ({a},{b})); "
                          f"forces are not given there (forces_valid = 0)."))
