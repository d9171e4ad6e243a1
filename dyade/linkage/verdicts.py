"""What a sweep keeps of every position once its blocks are computed: the verdicts the
notes, the summary and the tables read (a few bytes per position, joint and dyad), and
the notes made of them at the end.

``Rubbing`` keeps the friction solution's verdicts (``friction.FrictionResult``: not
solved, self-locking, near self-locking, at rest, the final residual), ``Verdict`` a
joint's self-locking verdict (``self_locking.Locking``), ``Outcome`` all a sweep
found: the positions reported and given, the notes, the crank's motion and the
clearance check.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.notes import Note, NoteKind, ranges
from dyade.linkage.plan import Plan
from dyade.model.mechanism import Mechanism

if TYPE_CHECKING:  # imported where used: a sweep without friction never loads it
    from dyade.linkage import friction
    from dyade.linkage.drive import CrankMotion
    from dyade.linkage.joint_clearance import JointCheck


@dataclass(slots=True, eq=False)
class Verdict:
    """A joint's self-locking verdict over a sweep: what the summary, the tables and the
    notes read of a ``self_locking.Locking``."""

    locks: FloatArray
    """(n,) bool: its dyad self-locks there and this joint's friction is the cause"""
    dyad: int
    """the number of the joint's dyad"""
    margin: bool | None
    """True for a slider, whose margin is in the columns (``lock_margin_*``); None for a
    revolute joint, which has none"""


@dataclass(slots=True, eq=False)
class Rubbing:
    """The friction solution's verdicts over a sweep, position by position."""

    residual: FloatArray
    """(n,) the final relative change a fixed-point step would make [-]"""
    unsolved: FloatArray
    """(n,) bool: no consistent friction solution found"""
    locked: FloatArray
    """(n,) bool: some dyad self-locks"""
    near: dict[int, FloatArray] = field(default_factory=dict)
    """dyad number -> (n,) bool: near self-locking"""
    at_rest: dict[tuple[int, int], FloatArray] = field(default_factory=dict)
    """joint -> (n,) bool: relative velocity zero (cleared for the joints that never move)"""
    never_moves: list[tuple[int, int]] = field(default_factory=list)
    """the joints at rest over the whole sweep (decided at its end)"""
    locks: dict[tuple[int, int], Verdict] = field(default_factory=dict)
    """joint -> its verdict, for every slider with friction and every joint that locks
    somewhere"""

    @classmethod
    def empty(cls, positions: int) -> Rubbing:
        return cls(np.empty(positions), np.empty(positions, dtype=bool),
                   np.empty(positions, dtype=bool))

    def keep(self, first: int, last: int, block: friction.FrictionResult,
             locking: dict | None) -> None:
        """Take over the verdicts of a block's friction solution and its ``locking``
        (``self_locking.test``) at positions first..last−1."""
        n = self.residual.shape[0]
        self.residual[first:last] = block.residual
        self.unsolved[first:last] = block.unsolved
        self.locked[first:last] = block.locked
        for number, mask in block.near.items():
            self.near.setdefault(number, np.zeros(n, dtype=bool))[first:last] = mask
        for name, mask in block.at_rest.items():
            self.at_rest.setdefault(name, np.zeros(n, dtype=bool))[first:last] = mask
        for name, lock in (locking or {}).items():
            if name not in self.locks:
                self.locks[name] = Verdict(np.zeros(n, dtype=bool), lock.dyad,
                                           None if lock.margin is None else True)
            self.locks[name].locks[first:last] = lock.locks

    def finish(self, usable: FloatArray) -> None:
        """Decide the joints that never move (at rest at every ``usable`` position: the
        kinematics valid) and clear their at-rest masks."""
        from dyade.linkage import friction

        self.never_moves = friction.never_moves(self.at_rest, usable)
        for name in self.never_moves:
            self.at_rest[name] = np.zeros(usable.shape[0], dtype=bool)

    def locking(self, mechanism: Mechanism) -> dict[tuple[int, int], Verdict] | None:
        """The verdicts in the order of the joints (None where the sweep has none)."""
        out = {joint.name: self.locks[joint.name] for joint in mechanism.joints
               if joint.name in self.locks}
        return out or None

    def notes(self, mechanism: Mechanism, angle: FloatArray, rows: FloatArray, digits: int
              ) -> list[Note]:
        """The friction and self-locking notes of the sweep (once ``finish``ed), its
        crank-angle ranges told apart to ``digits`` decimals [°]."""
        from dyade.linkage.friction import RESTART_PASSES

        out = []
        for dyad in mechanism.dyads:
            near = rows & self.near.get(dyad.number, np.zeros_like(rows))
            if near.any():
                out.append(Note(NoteKind.NEAR_SELF_LOCKING, f"dyad {dyad.number}",
                                tuple(ranges(angle, near)),
                                {"dyad": dyad.number, "band": mechanism.dead_centre_angle,
                                 "digits": digits}))
        failed = rows & self.unsolved
        if failed.any():
            out.append(Note(NoteKind.FRICTION_NOT_CONVERGED, "", tuple(ranges(angle, failed)),
                            {"where": "positions", "passes": mechanism.friction_max_iter,
                             "tolerance": mechanism.friction_tol,
                             "positions": int(failed.sum()),
                             "verdict": mechanism.friction_max_iter >= RESTART_PASSES,
                             "restart_passes": RESTART_PASSES, "digits": digits}))
        for name, mask in self.at_rest.items():
            if (mask & rows).any():
                out.append(Note(NoteKind.AT_REST, f"joint ({name[0]},{name[1]})",
                                tuple(ranges(angle, mask & rows)),
                                {"joint": name, "digits": digits}))
        for name in self.never_moves:
            out.append(Note(NoteKind.NEVER_MOVES, f"joint ({name[0]},{name[1]})", (),
                            {"joint": name}))
        for joint in mechanism.joints:
            lock = self.locks.get(joint.name)
            if lock is None or not (lock.locks & rows).any():
                continue
            a, b = joint.name
            what = "slider" if joint.kind == "P" else "joint"
            out.append(Note(NoteKind.SELF_LOCKING, f"{what} ({a},{b})",
                            tuple(ranges(angle, lock.locks & rows)),
                            {"joint": joint.name, "slider": joint.kind == "P",
                             "dyad": lock.dyad, "digits": digits}))
        return out

    @property
    def blocked(self) -> FloatArray:
        """(n,) bool: positions where friction keeps the forces from being given
        (self-locking, not solved, near self-locking): they have notes of their own."""
        from dyade.linkage import friction

        return friction.blocked(self.locked, self.unsolved, self.near)


@dataclass(slots=True, eq=False)
class Outcome:
    """All a sweep found besides its columns, the same for any block size."""

    mechanism: Mechanism
    plan: Plan
    crank_angle: FloatArray
    """(n,) crank angle φ21 of every computed position [rad]"""
    rows: FloatArray
    """(n,) bool: positions that are reported (all, or with allow_partial the closing ones)"""
    valid: FloatArray
    """(n,) bool: the kinematics is given (closes, outside the dead-centre band,
    plausible)"""
    forces_valid: FloatArray | None
    """(n,) bool: the forces are given (``forces_valid``); None without kinetostatics"""
    notes: list[Note]
    """findings: dead centres, partial sweeps, friction, self-locking, clearance"""
    rubbing: Rubbing | None = None
    """the friction solution's verdicts; None without friction"""
    locking: dict[tuple[int, int], Verdict] | None = None
    """joint -> self-locking verdict for every slider with friction and every joint that
    self-locks; None without"""
    drive: CrankMotion | None = None
    """the crank's motion from the equation of motion (``drive.CrankMotion``); None at
    constant speed"""
    clearance: list[JointCheck] | None = None
    """the clearance check per joint with clearance data; None without"""
