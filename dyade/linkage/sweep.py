"""What a mechanism file calls for (``plan``) and the sweep that does it (``run``).

The plan is decided from the data before anything runs, and printed by ``describe``:
masses, loads or springs → kinetostatics; a friction coefficient → friction
iteration; a slider with friction → self-locking test. Stages the scene does not call
for are not run.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from typing import TYPE_CHECKING

from dyade.linkage import kinematics, kinetostatics
from dyade.errors import AssemblyError

if TYPE_CHECKING:  # imported where used: a kinematics-only run never loads them
    from dyade.linkage import friction
from dyade.linkage.model import FloatArray, Mechanism


@dataclass(frozen=True, slots=True)
class Plan:
    """The stages a sweep will run."""

    kinematics: bool = True
    kinetostatics: bool = False
    """masses, loads or springs present"""
    friction: tuple[tuple[int, int], ...] = ()
    """joints with μ > 0 (friction iteration runs only with kinetostatics)"""
    self_locking: tuple[tuple[int, int], ...] = ()
    """sliders with μ > 0"""
    clearance: tuple[tuple[int, int], ...] = ()
    """revolute joints with clearance data in the file (peak-force check, SPEC §2)"""

    def effects(self) -> list[str]:
        """One line per simulated effect, for ``describe``."""
        out = ["kinematics: positions, velocities, accelerations of every link, joint and point"]
        if self.kinetostatics:
            out.append("kinetostatics: joint forces, driving torque, shaking force (d'Alembert, "
                       "backward dyad by dyad)")
        if self.friction:
            out.append("Coulomb friction (iterated per dyad) in joints "
                       + ", ".join(f"({a},{b})" for a, b in self.friction))
        if self.self_locking:
            out.append("self-locking test for sliders "
                       + ", ".join(f"({a},{b})" for a, b in self.self_locking))
        if self.clearance:
            out.append("clearance peak check (Dresig–Thümmel) in joints "
                       + ", ".join(f"({a},{b})" for a, b in self.clearance))
        return out

    def skipped(self) -> list[str]:
        """Effects the file does not call for, and what would turn them on."""
        out = []
        if not self.kinetostatics:
            out.append("kinetostatics: no masses, loads or springs in the file")
        if not self.friction:
            out.append("friction: no joint has a friction coefficient μ > 0")
        if not self.self_locking:
            out.append("self-locking: no slider (prismatic joint) with friction")
        if not self.clearance:
            out.append("clearance peaks: no joint has clearance data "
                       "(or run `dyade clearance FILE --stiffness … --clearance …`)")
        return out


def plan(mechanism: Mechanism) -> Plan:
    """Decide the stages from the data (SPEC §1: only what the scene calls for)."""
    dynamics = mechanism.has_dynamics
    rubbing = tuple(j.name for j in mechanism.joints if j.friction > 0.0) if dynamics else ()
    locking = tuple(j.name for j in mechanism.friction_sliders) if dynamics else ()
    gaps = tuple(j.name for j in mechanism.joints
                 if getattr(j, "clearance", None) is not None) if dynamics else ()
    return Plan(kinematics=True, kinetostatics=dynamics, friction=rubbing, self_locking=locking,
                clearance=gaps)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Result:
    """Everything a sweep computed, in SI units."""

    mechanism: Mechanism
    plan: Plan
    kinematics: kinematics.Kinematics
    forces: kinetostatics.Forces | None
    """joint forces and drive torque; None when the plan has no kinetostatics"""
    rows: FloatArray
    """(n,) bool: positions that are reported (all, or with --allow-partial the closing ones)"""
    notes: list[str] = field(default_factory=list)
    """warnings for stderr: dead centres, partial sweeps, skipped stages"""
    friction: friction.FrictionResult | None = None
    """friction loads and iteration record; None without friction"""
    locking: dict | None = None
    """slider -> self_locking.Locking; None without sliders with friction"""
    clearance: list | None = None
    """clearance.JointCheck per joint with clearance data; None without such data"""

    @property
    def crank_angle(self) -> FloatArray:
        return self.kinematics.crank_angle


def ranges(crank_angle: FloatArray, mask: FloatArray) -> list[tuple[float, float]]:
    """Crank-angle ranges [rad] (first, last) of runs of True in ``mask``."""
    if not mask.any():
        return []
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(float(crank_angle[a]), float(crank_angle[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def format_ranges(crank_angle: FloatArray, mask: FloatArray, limit: int = 6) -> str:
    """'212.0°–247.5°, 300.0°' for the runs of True in ``mask``."""
    parts = []
    for first, last in ranges(crank_angle, mask):
        a, b = np.rad2deg(first), np.rad2deg(last)
        parts.append(f"{a:.1f}°" if first == last else f"{a:.1f}°–{b:.1f}°")
    if len(parts) > limit:
        parts = parts[:limit] + [f"and {len(parts) - limit} more"]
    return ", ".join(parts)


def run(mechanism: Mechanism, the_plan: Plan | None = None, allow_partial: bool = False,
        crank_angle: FloatArray | None = None) -> Result:
    """Run the planned stages over the crank sweep."""
    the_plan = the_plan or plan(mechanism)
    kin = kinematics.sweep(mechanism, crank_angle)
    notes: list[str] = []
    rows = _check_assembly(mechanism, kin, allow_partial, notes)
    _dead_centres(mechanism, kin, rows, notes)
    forces = rubbing = locking = None
    if the_plan.friction:
        from dyade.linkage import friction, self_locking

        rubbing = friction.iterate(mechanism, kin)
        forces = rubbing.forces
        _friction_notes(mechanism, kin, rubbing, rows, notes)
        if the_plan.self_locking:
            locking = self_locking.test(mechanism, kin.motion, rubbing, forces.valid)
            for name, lock in locking.items():
                if (lock.locks & rows).any():
                    notes.append(f"slider ({name[0]},{name[1]}) locks (self-locking) at crank "
                                 f"angles {format_ranges(kin.crank_angle, lock.locks & rows)}.")
    elif the_plan.kinetostatics:
        forces = kinetostatics.solve(mechanism, kin)
    if forces is not None:
        invalid = rows & ~forces.valid
        if invalid.any():
            notes.append(f"forces are not given at crank angles "
                         f"{format_ranges(kin.crank_angle, invalid)}: a dyad is at or near a "
                         f"dead centre or blocked position, where the rigid model is invalid "
                         f"(forces_valid = 0, force fields empty).")
    result = Result(mechanism, the_plan, kin, forces, rows, notes, rubbing, locking)
    if the_plan.clearance:
        from dyade import clearance

        result.clearance = clearance.check_mechanism(mechanism, result, the_plan.clearance)
        for check in result.clearance:
            if not check.applies:
                notes.append(f"clearance check of joint ({check.joint[0]},{check.joint[1]}) "
                             f"does not apply: {check.reason}.")
    return result


def _check_assembly(mechanism: Mechanism, kin: kinematics.Kinematics, allow_partial: bool,
                    notes: list[str]) -> FloatArray:
    """Rows that close; an AssemblyError naming dyads and ranges unless allowed."""
    upstream = np.ones(kin.crank_angle.shape[0], dtype=bool)
    problems = []
    for col, dyad in enumerate(mechanism.dyads):
        fails = upstream & ~kin.closes[:, col]
        if fails.any():
            what = dyad.kind.cannot_close
            problems.append(f"{dyad.label} {what} for crank angles "
                            f"{format_ranges(kin.crank_angle, fails)}")
        upstream = upstream & kin.closes[:, col]
    if not problems:
        return np.ones(kin.crank_angle.shape[0], dtype=bool)
    if not allow_partial:
        raise AssemblyError("; ".join(problems) + ". Change the dimensions or the sweep, or "
                            "use --allow-partial to analyse only where it closes.")
    kept = int(upstream.sum())
    notes.append("; ".join(problems) + f". Those positions are left out ({kept} of "
                 f"{upstream.size} kept).")
    if kept == 0:
        raise AssemblyError("the mechanism closes at no crank angle of the sweep: "
                            + "; ".join(problems) + ".")
    return upstream


def _dead_centres(mechanism: Mechanism, kin: kinematics.Kinematics, rows: FloatArray,
                  notes: list[str]) -> None:
    band = np.sin(mechanism.dead_centre_angle)
    for col, dyad in enumerate(mechanism.dyads):
        near = rows & (kin.conditioning[:, col] <= band)
        if near.any():
            word = dyad.kind.singular
            notes.append(f"{dyad.label} is within {np.rad2deg(mechanism.dead_centre_angle):g}° of "
                         f"a {word} (transmission angle near 0° or 180°) at crank angles "
                         f"{format_ranges(kin.crank_angle, near)}.")


def _friction_notes(mechanism: Mechanism, kin: kinematics.Kinematics,
                    rubbing: "friction.FrictionResult", rows: FloatArray, notes: list[str]) -> None:
    failed = rows & kin.valid & ~rubbing.converged
    if failed.any():
        notes.append(f"the friction iteration did not converge to {mechanism.friction_tol:g} in "
                     f"{mechanism.friction_max_iter} steps at {int(failed.sum())} positions: crank "
                     f"angles {format_ranges(kin.crank_angle, failed)} (worst relative change "
                     f"{np.max(rubbing.residual[failed]):.3g}).")
    for name, mask in rubbing.at_rest.items():
        if (mask & rows).any():
            notes.append(f"joint ({name[0]},{name[1]}) is at rest relative to its partner at crank "
                         f"angles {format_ranges(kin.crank_angle, mask & rows)}: the friction "
                         f"direction is undefined there and no friction is applied.")
    for name in rubbing.never_moves:
        notes.append(f"joint ({name[0]},{name[1]}) never moves relative to its partner over the "
                     f"sweep: it has no friction loss.")
