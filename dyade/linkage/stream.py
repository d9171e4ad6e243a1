"""A sweep in blocks of positions, in memory that does not grow with the sweep.

``stream`` gives the columns of a sweep block by block (``Stream.blocks()``), each as
soon as it is computed, and afterwards the notes and the clearance check, exactly as
``analyse(...).columns()`` and ``.notes`` give them for the whole sweep:

1. a first pass computes the kinematics block by block and keeps what the validity
   policy needs per position (closure, transmission angle and conditioning of every
   dyad: 17 B per dyad and position): the assembly check (and its error, before any
   output) and the dead-centre bands are decided over the whole sweep;
2. a second pass computes each block again (kinematics and forces; a sweep of one
   block keeps its kinematics from the first) and gives its columns; link angles are
   unwrapped on from the block before (``columns.Continuous``);
   the rows with implausible values, the positions where the forces are not given, and
   the forces of the joints with clearance data are kept per position for the notes and
   the clearance check, which are made at the end.

A ``[drive]`` mechanism solves its crank's motion over the whole cycle first, then
streams: the equation of motion keeps a few arrays of its grid (J, J′, M_L, M_F and the
path at every half step, computed block by block: ``drive``) and of the positions (the
crank's speed, acceleration, time and torques).

With friction, what couples the positions of the friction solution
(``friction.Coupling``: the sweep's largest crank speed, and each dyad's force floor,
taken from about 256 sample positions) comes from the first pass: the largest speed
block by block, and the floors from the friction solution at the sample positions
alone, which is the whole sweep's there. Each block is then solved as within the whole
sweep, bit for bit; the verdicts the notes and the summary need (self-locking, not
solved and near self-locking positions, joints at rest, the final residual) are kept
per position (a few bytes per joint and dyad), and the joints that never move are
decided at the end.
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from types import SimpleNamespace
from typing import Any

import numpy as np

from dyade.linkage import kinematics, kinetostatics
from dyade.linkage.model import FloatArray, Mechanism, Revolute
from dyade.linkage.sweep import (Note, Plan, Result, _bands, _check_assembly,
                                 _clearance, _forces_invalid_note, _friction_notes,
                                 _implausible_note, _locking_notes, _motion_notes,
                                 _plausible, configure, decimals)

BLOCK_SIZE = 2048
"""positions per block (``--block-size``): a block's arrays (kinematics, forces, its
columns: a few kB per position for dyade-16's 270 columns) stay within a few MB, near
the cache; larger blocks gain nothing measurable (tests/benchmarks)"""
FIRST_PASS = 0.1
"""the first pass's share of a streamed sweep's time, for the progress bar until the
second pass has measured its own (about 0.1 for dyade-16 with friction, 0.15 without,
writing CSV)"""
KEPT_PER_POSITION = 64
"""[B] what a streamed sweep keeps per position besides the per-dyad arrays: crank
angle, speed and acceleration, masks, the clearance joints' forces"""


def stream_estimate(block_size: int):
    """What a streamed sweep needs [B], as ``configure``'s ``estimate``: one block's
    columns and arrays, and the per-position arrays kept for the whole sweep."""
    def estimate(mechanism: Mechanism, positions: int) -> int:
        from dyade.linkage.sweep import memory_estimate

        per_position = 17 * len(mechanism.dyads) + KEPT_PER_POSITION + 16 * sum(
            isinstance(j, Revolute) for j in mechanism.joints)
        if mechanism.has_dynamics and any(j.friction > 0.0 for j in mechanism.joints):
            # the residual; not solved, locked; near per dyad; at rest and locks per joint
            per_position += 10 + len(mechanism.dyads) + 2 * len(mechanism.joints)
        block = memory_estimate(mechanism, min(positions, block_size)) - (50 << 20)
        return 2 * block + per_position * positions + (60 << 20)

    return estimate


@dataclass(slots=True, eq=False)
class Verdict:
    """A joint's self-locking verdict over a streamed sweep: what the summary, the tables
    and the notes read of a ``self_locking.Locking``."""

    locks: FloatArray
    """(n,) bool: its dyad self-locks there and this joint's friction is the cause"""
    dyad: int
    """the number of the joint's dyad"""
    margin: bool | None
    """True for a slider, whose margin is in the columns (``lock_margin_*``); None for a
    revolute joint, which has none"""


@dataclass(slots=True, eq=False)
class Rubbing:
    """The friction solution of a streamed sweep, as far as the notes, the summary and
    the tables read it (``friction.FrictionResult``): its verdicts per position."""

    residual: FloatArray
    """(n,) the final relative change a fixed-point step would make [-]"""
    unsolved: FloatArray
    """(n,) bool: no consistent friction solution found"""
    locked: FloatArray
    """(n,) bool: some dyad self-locks"""
    near: dict[int, FloatArray]
    """dyad number -> (n,) bool: near self-locking"""
    at_rest: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: relative velocity zero (cleared for the joints that never move)"""
    never_moves: list[tuple[int, int]] = field(default_factory=list)
    """the joints at rest over the whole sweep (decided at its end)"""
    locks: dict[tuple[int, int], Verdict] = field(default_factory=dict)
    """joint -> its verdict, for every slider with friction and every joint that locks
    somewhere"""

    def keep(self, first: int, last: int, block, locking: dict | None) -> None:
        """Take over the verdicts of a block's ``FrictionResult`` and its ``locking``."""
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

    def locking(self, mechanism: Mechanism) -> dict | None:
        """The verdicts in the order of the joints, as ``self_locking.test`` gives them
        (None where the whole sweep has none)."""
        out = {joint.name: self.locks[joint.name] for joint in mechanism.joints
               if joint.name in self.locks}
        return out or None


@dataclass(eq=False)
class Stream:
    """A configured sweep to be computed block by block (``stream``)."""

    mechanism: Mechanism
    plan: Plan
    allow_partial: bool
    block_size: int
    crank_angle: FloatArray
    speed: FloatArray | float | None
    acceleration: FloatArray | float | None
    motion: Any = None
    """the crank's motion (``drive.CrankMotion``) of a [drive] mechanism, else None"""
    notes: list[Note] = field(default_factory=list)
    """complete once ``blocks()`` is exhausted"""
    clearance: list | None = None
    """the clearance check (``joint_clearance.JointCheck`` per joint), once streamed"""
    positions: int = 0
    """rows given"""
    progress: Any = None
    """called with (done, total) as the blocks are computed, in units of the time they
    take: the first pass (the validity policy) counts as ``FIRST_PASS`` of the whole
    until the second pass's first block says how much slower that one is (the forces,
    friction and the writer's work per block: 5 to 15 times)"""
    rows: FloatArray | None = None
    """(n,) bool: the positions reported (once the first pass is done)"""
    valid: FloatArray | None = None
    """(n,) bool: forces given (``forces_valid``), once streamed; None without forces"""
    friction: Rubbing | None = None
    """the friction solution's verdicts, once streamed; None without friction"""
    coupling: Any = None
    """what couples the positions of the friction solution (``friction.Coupling``), once
    the first pass is done; None without friction"""
    _shown: float = field(default=0.0, repr=False)
    """the share of the run the progress was last given"""

    def _slice(self, value, first: int, last: int):
        return value[first:last] if isinstance(value, np.ndarray) else value

    def _kinematics(self, first: int, last: int) -> kinematics.Kinematics:
        return kinematics.sweep(self.mechanism, self.crank_angle[first:last],
                                self._slice(self.speed, first, last),
                                self._slice(self.acceleration, first, last))

    def _tick(self, done: float, total: float) -> None:
        """Report ``done`` of ``total``, never a smaller share than before (the second
        pass's projection may grow)."""
        if self.progress is not None:
            self._shown = max(self._shown, done / total)
            self.progress(self._shown * total, total)

    def _spans(self) -> Iterator[tuple[int, int]]:
        n = self.crank_angle.shape[0]
        for first in range(0, n, self.block_size):
            yield first, min(n, first + self.block_size)

    def outcome(self) -> SimpleNamespace:
        """What the summary and the tables read of a ``Result`` (``summary.summary(
        stream.outcome(), spool)``), once ``blocks()`` is exhausted: the mechanism, plan,
        rows, notes, the crank's motion, the clearance check, ``forces.valid`` and the
        friction solution's verdicts (``Rubbing``, ``Verdict``)."""
        rubbing = self.friction
        return SimpleNamespace(mechanism=self.mechanism, plan=self.plan, notes=self.notes,
                               crank_angle=self.crank_angle, rows=self.rows,
                               forces=SimpleNamespace(valid=self.valid)
                               if self.plan.kinetostatics else None,
                               friction=rubbing, locking=None if rubbing is None
                               else rubbing.locking(self.mechanism), drive=self.motion,
                               clearance=self.clearance)

    def _coupling(self, top: float):
        """The friction solution's ``Coupling`` of the whole sweep: the largest crank
        speed ``top`` [rad/s] (from the first pass), the force floors from the sample
        positions."""
        from dyade.linkage import friction

        index = np.arange(self.crank_angle.shape[0])[friction.sample(self.crank_angle.shape[0])]
        kin = kinematics.sweep(self.mechanism, self.crank_angle[index],
                               *(value[index] if isinstance(value, np.ndarray) else value
                                 for value in (self.speed, self.acceleration)))
        return friction.coupling(self.mechanism, kin, top)

    def _forces(self, kin: kinematics.Kinematics, coupling, first: int, last: int):
        """A block's forces, and with friction its solution and self-locking verdicts
        (kept for the notes)."""
        if not self.plan.friction:
            return kinetostatics.solve(self.mechanism, kin), None, None
        from dyade.linkage import friction, self_locking

        rubbing = friction.solve(self.mechanism, kin, coupling=coupling, whole=False)
        self.coupling = rubbing.coupling
        locking = None
        if self.plan.self_locking or rubbing.locks:  # as the whole sweep (sweep.run)
            locking = self_locking.test(self.mechanism, kin, rubbing)
        self.friction.keep(first, last, rubbing, locking)
        return rubbing.forces, rubbing, locking

    def blocks(self) -> Iterator[dict[str, FloatArray]]:
        """The columns of every block of positions, in order (NaN where not given)."""
        mechanism, n = self.mechanism, self.crank_angle.shape[0]
        dyads = len(mechanism.dyads)
        policy = SimpleNamespace(crank_angle=self.crank_angle,
                                 closes=np.empty((n, dyads), dtype=bool),
                                 transmission=np.empty((n, dyads)),
                                 conditioning=np.empty((n, dyads)),
                                 valid=np.empty(n, dtype=bool))
        started = time.perf_counter()
        top = 0.0  # the largest crank speed (friction)
        for first, last in self._spans():
            kin = self._kinematics(first, last)
            for name in ("closes", "transmission", "conditioning", "valid"):
                getattr(policy, name)[first:last] = getattr(kin, name)
            if self.plan.friction:
                from dyade.linkage.friction import top_speed

                top = max(top, top_speed(kin))
            self._tick(last, n / FIRST_PASS)
        first_pass = time.perf_counter() - started
        kept_kin = kin if n <= self.block_size else None  # one block: computed once
        notes = self.notes
        rows = self.rows = _check_assembly(mechanism, policy, self.allow_partial, notes)
        well = _bands(mechanism, policy, rows, notes)
        usable = policy.valid if self.plan.friction else None  # for the joints never moving
        del policy
        coupling = None
        if self.plan.friction:
            if n > self.block_size:  # (one block is the whole sweep: its own coupling)
                coupling = self.coupling = self._coupling(top)
            self.friction = Rubbing(np.empty(n), np.empty(n, dtype=bool),
                                    np.empty(n, dtype=bool), {}, {})
        digits = decimals(self.crank_angle)
        implausible = {"kinematics": np.zeros(n, dtype=bool), "forces": np.zeros(n, dtype=bool)}
        forces_valid = self.valid = (np.zeros(n, dtype=bool) if self.plan.kinetostatics
                                     else None)
        joints = self.plan.clearance if self.plan.clearance and not (
            self.motion is not None and self.motion.state == "run-up") else ()
        kept = {name: np.empty((n, 2)) for name in joints}
        phases = None
        for first, last in self._spans():
            kin = kept_kin if kept_kin is not None else self._kinematics(first, last)
            forces = rubbing = locking = None
            if self.plan.kinetostatics:
                forces, rubbing, locking = self._forces(kin, coupling, first, last)
            motion = None
            if self.motion is not None:
                motion = replace(self.motion, **{
                    name: getattr(self.motion, name)[first:last]
                    for name in ("crank_angle", "speed", "acceleration", "time",
                                 "motor_torque", "friction_torque")})
            if phases is None:
                from dyade.linkage.columns import Continuous

                phases = {link: Continuous() for link in mechanism.moving_links}
            result = Result(mechanism, self.plan, kin, forces, rows[first:last].copy(), [],
                            rubbing, locking, valid=well[first:last].copy(), drive=motion,
                            phases=phases)
            masks: dict[str, FloatArray] = {}
            cols = _plausible(result, digits, masks)
            for phase in phases.values():
                phase.commit()
            for block, mask in masks.items():
                implausible[block][first:last] = mask
            if forces is not None:
                well[first:last] = result.valid
                forces_valid[first:last] = forces.valid
                for name in joints:
                    kept[name][first:last] = forces.revolute[name]
            self.positions += int(cols["angle_deg"].size)
            yield cols
            # the second pass's time projected from its blocks so far, against the first's
            ratio = (time.perf_counter() - started - first_pass) * n / (
                last * max(first_pass, 1e-9))
            self._tick(n + ratio * last, n * (1.0 + ratio))
        invalid = None if forces_valid is None else well & ~forces_valid
        if self.friction is not None:
            self._rubbing_notes(usable, rows, invalid)
        for block in ("kinematics", "forces"):
            if implausible[block].any():
                notes.append(_implausible_note(block, self.crank_angle, implausible[block],
                                               digits))
        if invalid is not None and invalid.any():
            notes.append(_forces_invalid_note(self.crank_angle, invalid, digits))
        if self.motion is not None:
            _motion_notes(self.motion, notes)
        if self.plan.clearance and not joints:
            notes.append(Note("clearance_not_applicable", "", (),
                              "the clearance check is not made on a run-up: it needs the "
                              "periodic cycle."))
        elif joints:
            whole = SimpleNamespace(crank_angle=self.crank_angle, rows=rows, drive=self.motion,
                                    forces=SimpleNamespace(revolute=kept, valid=forces_valid))
            self.clearance = _clearance(mechanism, whole, self.plan, notes)

    def _rubbing_notes(self, usable: FloatArray, rows: FloatArray, invalid: FloatArray
                       ) -> None:
        """The friction and self-locking notes of the whole sweep (as ``sweep.run``), once
        the joints that never move are known; the positions where friction keeps the
        forces from being given are taken out of ``invalid`` (they have their own
        notes)."""
        from dyade.linkage.friction import never_moves

        rubbing, mechanism = self.friction, self.mechanism
        rubbing.never_moves = never_moves(rubbing.at_rest, usable)
        for name in rubbing.never_moves:
            rubbing.at_rest[name] = np.zeros(rows.shape[0], dtype=bool)
        angle = SimpleNamespace(crank_angle=self.crank_angle)
        _friction_notes(mechanism, angle, rubbing, rows, self.notes)
        locking = rubbing.locking(mechanism)
        if locking is not None:
            _locking_notes(mechanism, angle, locking, rows, self.notes)
        invalid &= ~(rubbing.locked | rubbing.unsolved)  # those have their own notes
        for mask in rubbing.near.values():
            invalid &= ~mask


class Spool(Mapping):
    """The columns of a streamed sweep kept in a temporary file instead of memory: each
    block is appended as it comes (``add``), and ``spool[name]`` reads one whole column
    back (8 B per position). What needs a whole column (the JSON's arrays, the summary's
    extremes, means and time ratios) takes them one at a time, with the very functions
    the whole sweep uses, so the results are the same to the last bit.

    The file is in the temporary folder (``TMPDIR``): 8 B per value, e.g. 786 MB for
    dyade-16's 273 columns at 360 000 positions; it is deleted on ``close`` (or when
    the spool is collected).

    >>> import dyade
    >>> sweep = stream(dyade.read_mechanism("mechanisms/fourbar.toml"), block_size=100)
    >>> with Spool(sweep.blocks()) as spool:
    ...     print(len(spool), spool["angle_deg"][[0, -1]])
    63 [  0. 360.]
    """

    float_columns = True
    """every column is a 1-D float64 array"""

    def __init__(self, blocks: Iterable[Mapping[str, FloatArray]]) -> None:
        import tempfile

        self.file = tempfile.TemporaryFile(prefix="dyade-spool-")
        self.names: list[str] = []
        self.where: dict[str, int] = {}
        self.blocks: list[tuple[int, int]] = []
        """(offset [B], rows) of every block: its columns one after another"""
        self.rows = 0
        self.kept: dict[str, FloatArray] = {}
        """the column read last (a table or the summary often asks for it twice running)"""
        for block in blocks:
            self.add(block)

    def add(self, block: Mapping[str, FloatArray]) -> None:
        if not self.names:
            self.names = list(block)
            self.where = {name: k for k, name in enumerate(self.names)}
        rows = int(np.shape(block[self.names[0]])[0])
        table = np.empty((len(self.names), rows))
        for k, name in enumerate(self.names):
            table[k] = block[name]
        self.blocks.append((self.file.tell(), rows))
        self.file.write(table.data)
        self.rows += rows

    def __getitem__(self, name: str) -> FloatArray:
        if name in self.kept:
            return self.kept[name]
        k = self.where[name]
        out = np.empty(self.rows)
        row = 0
        for offset, rows in self.blocks:
            self.file.seek(offset + 8 * k * rows)
            self.file.readinto(memoryview(out[row:row + rows]).cast("B"))
            row += rows
        self.file.seek(0, 2)
        self.kept = {name: out}
        return out

    def __iter__(self) -> Iterator[str]:
        return iter(self.names)

    def __len__(self) -> int:
        return len(self.names)

    def close(self) -> None:
        self.file.close()

    def __enter__(self) -> "Spool":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def stream(mechanism: Mechanism, *, block_size: int | None = None, start: float | None = None,
           stop: float | None = None, step: float | None = None,
           allow_partial: bool = False, friction_tol: float | None = None,
           friction_max_iter: int | None = None, max_memory: float | None = None,
           dead_centre: float | None = None, transmission_warning: float | None = None,
           constant_speed: bool = False, run_up: bool = False) -> Stream:
    """``analyse`` block by block: a ``Stream`` whose ``blocks()`` give the columns of
    ``block_size`` positions at a time (default ``BLOCK_SIZE``), in memory that does
    not grow with the number of positions; the options as for ``analyse``
    (``max_memory`` bounds what the stream needs).

    >>> import dyade
    >>> sweep = stream(dyade.read_mechanism("mechanisms/fourbar.toml"), block_size=100)
    >>> [cols["angle_deg"].size for cols in sweep.blocks()], sweep.positions
    ([100, 100, 100, 61], 361)
    """
    from dyade.errors import InputError

    size = BLOCK_SIZE if block_size is None else block_size
    if not (isinstance(size, (int, np.integer)) and size >= 1):
        raise InputError.parameter("block_size", f"must be a whole number of positions ≥ 1, "
                                                 f"got {size}.", value=size)
    mechanism, the_plan = configure(
        mechanism, start=start, stop=stop, step=step, friction_tol=friction_tol,
        friction_max_iter=friction_max_iter, max_memory=max_memory, dead_centre=dead_centre,
        transmission_warning=transmission_warning, constant_speed=constant_speed,
        run_up=run_up, estimate=stream_estimate(int(size)))
    angle, speed, acceleration, motion = mechanism.sweep.angles(), None, None, None
    if the_plan.equation_of_motion:
        from dyade.linkage import drive

        motion = drive.solve(mechanism, None, run_up=run_up, friction=bool(the_plan.friction))
        angle, speed, acceleration = motion.crank_angle, motion.speed, motion.acceleration
    return Stream(mechanism, the_plan, allow_partial, int(size), np.asarray(angle, np.float64),
                  speed, acceleration, motion)
