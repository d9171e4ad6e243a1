"""The one sweep pipeline: plan → blocks of positions → stages → per-block results →
what the sweep keeps.

``prepare`` turns a mechanism and its plan into a ``Setup``: the crank angles, and the
crank's speed and acceleration there (from the equation of motion when the plan has a
drive: ``drive.solve``). ``Run`` computes it in blocks of positions:

1. a first pass computes the kinematics block by block and keeps what the validity
   policy needs per position (``validity.Policy``): the assembly check (and its error,
   before any result) and the dead-centre bands are decided over the whole sweep;
2. a second pass runs every stage the plan calls for on each block (kinematics;
   kinetostatics; friction and self-locking, each block solved as within the whole
   sweep: ``blocks.friction_coupling``), makes its columns (``columns``; link angles
   unwrapped on from the block before) and takes out the rows with implausible values,
   and yields it as a ``Block``; what the notes, the summary and the clearance check
   need is kept per position (``verdicts``);
3. at the end, the notes and the clearance check (``Run.outcome``).

The block size changes nothing but memory and speed: the columns are the same to the
bit for any block size, the notes the same. A sweep of one block keeps the kinematics
of its first pass.

Variants are an axis of the same pipeline: a run of ``variants`` sweeps of one topology
stacked into one mechanism (``stack``: a number that differs is one value per variant
and position, variant-major) goes through the same passes as one block
(``prepare_variants``: the caller sizes the run; its columns may be views of the
block's arrays). The validity policy, the dead-centre bands, the plausibility
check and the notes are decided per variant by the same functions (a variant that does
not close reports no position and has its ``AssemblyError`` in ``Run.failed``; its
notes are ``Run.notes[v]``). The stages that couple a variant's positions (friction's
solution with its coupling between blocks, the equation of motion) and the drive line's
check run one variant at a time: a run of one variant, ``prepare``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import AssemblyError
from dyade.linkage import columns as columns_, kinematics, kinetostatics
from dyade.linkage.block import Block
from dyade.linkage.blocks import friction_coupling, spans
from dyade.linkage.columns import Columns, Continuous, EachVariant
from dyade.linkage.notes import Note, NoteKind, ranges
from dyade.linkage.plan import Plan
from dyade.linkage.validity import Policy, assembly, bands, each
from dyade.linkage.verdicts import Outcome, Rubbing
from dyade.model.mechanism import Mechanism

if TYPE_CHECKING:  # imported where used: a kinematics-only run never loads them
    from dyade.linkage import friction
    from dyade.linkage.drive import CrankMotion

FIRST_PASS = 0.1
"""the first pass's share of a sweep's time, for the progress until the second pass has
measured its own (about 0.1 for dyade-16 with friction, 0.15 without, writing CSV)"""


@dataclass(slots=True, eq=False)
class Setup:
    """A sweep ready to run: the mechanism, its plan and the positions."""

    mechanism: Mechanism
    plan: Plan
    crank_angle: FloatArray
    """(n,) crank angle φ21 of every position [rad]"""
    speed: FloatArray | float | None = None
    """crank speed φ̇21 [rad/s]: one per position, one value, or None (the file's)"""
    acceleration: FloatArray | float | None = None
    """crank acceleration φ̈21 [rad/s²]: one per position, one value, or None (zero)"""
    motion: CrankMotion | None = None
    """the crank's motion from the equation of motion; None at constant speed"""
    allow_partial: bool = False
    """report only the positions where every dyad closes (else an ``AssemblyError``)"""
    variants: int = 1
    """the sweeps stacked into the mechanism, each of ``positions / variants`` positions
    (variant-major): 1 for a sweep"""

    @property
    def positions(self) -> int:
        return self.crank_angle.shape[0]

    @property
    def each(self) -> int:
        """positions per variant"""
        return self.positions // self.variants

    def kinematics(self, first: int, last: int) -> kinematics.Kinematics:
        """The kinematics of positions first..last−1."""
        return kinematics.sweep(self.mechanism, self.crank_angle[first:last],
                                _part(self.speed, first, last),
                                _part(self.acceleration, first, last),
                                (last - first) // self.each if self.variants > 1 else 1)


def _part(value, first: int, last: int):
    return value[first:last] if isinstance(value, np.ndarray) else value


def _per_position(value, n: int) -> FloatArray | float | None:
    """None, one value (a float), or one per position: an (n,) array of the Setup's own
    (a copy, broadcast from one value given as a list: blocks slice it; a caller's later
    change of its array changes no result that is computed on demand)."""
    if value is None:
        return None
    array = np.asarray(value, dtype=np.float64)
    if array.ndim == 0:
        return float(array)
    return np.array(np.broadcast_to(array, (n,)))


def prepare(mechanism: Mechanism, the_plan: Plan, *, allow_partial: bool = False,
            crank_angle: FloatArray | None = None, crank_speed: FloatArray | float | None = None,
            crank_acceleration: FloatArray | float | None = None, run_up: bool = False
            ) -> Setup:
    """The sweep of ``mechanism`` at ``crank_angle`` [rad] (default: its own sweep; for a
    run-up the whole run-up), the crank at ``crank_speed`` and ``crank_acceleration``,
    or, where the plan has an equation of motion, as that gives them."""
    motion = None
    if the_plan.equation_of_motion:
        from dyade.linkage import drive

        motion = drive.solve(mechanism, crank_angle, run_up=run_up,
                             friction=bool(the_plan.friction))
        crank_angle, crank_speed = motion.crank_angle, motion.speed
        crank_acceleration = motion.acceleration
    angle = mechanism.sweep.angles() if crank_angle is None else crank_angle
    angle = np.array(angle, dtype=np.float64)  # the Setup's own: whole() reads it later
    return Setup(mechanism, the_plan, angle, _per_position(crank_speed, angle.shape[0]),
                 _per_position(crank_acceleration, angle.shape[0]), motion, allow_partial)


COUPLED = "friction, a [drive] or a [drive_line]: swept variant by variant"
"""why a plan's variants are not stacked (``prepare_variants``)"""


def stackable(the_plan: Plan) -> bool:
    """Whether variants with this plan run stacked (``prepare_variants``): not with
    friction or an equation of motion (stages that couple a variant's positions) or an
    elastic drive line (whose check a single sweep makes, per variant)."""
    return not (the_plan.friction or the_plan.equation_of_motion or the_plan.drive_line)


def prepare_variants(stacked: Mechanism, count: int, the_plan: Plan | None = None) -> Setup:
    """The run of ``count`` variants stacked into ``stacked`` (``stack.stack`` or
    ``stack.spread``), each over the sweep of its file, at the file's constant crank
    speed; ``NotStackable`` where the plan calls for a stage that couples a variant's
    positions (``stackable``: those run one variant at a time, ``prepare``).
    ``the_plan``: the stages to run (default: the mechanism's; ``Plan()``: the
    kinematics only, the first pass of a search)."""
    from dyade.linkage.plan import plan
    from dyade.linkage.stack import NotStackable

    the_plan = plan(stacked) if the_plan is None else the_plan
    if not stackable(the_plan):
        raise NotStackable(COUPLED)
    angle = np.tile(stacked.sweep.angles(), count)
    return Setup(stacked, the_plan, angle, variants=count)


def stages(setup: Setup, kin: kinematics.Kinematics, first: int, last: int,
           coupling: friction.Coupling | None, rows: FloatArray, valid: FloatArray) -> Block:
    """The stages after the kinematics (``kin``, of positions first..last−1): the
    forces, with friction its solution and the self-locking verdicts. ``coupling``: the
    sweep's friction coupling (None when the block is the whole sweep); ``rows``,
    ``valid``: (m,) bool, the block's positions reported and with their kinematics
    given (copied)."""
    mechanism, the_plan = setup.mechanism, setup.plan
    forces = rubbing = locking = None
    if the_plan.friction:
        from dyade.linkage import friction, self_locking

        rubbing = friction.solve(mechanism, kin, coupling=coupling, whole=False)
        forces = rubbing.forces
        if the_plan.self_locking or rubbing.locks:  # slider margins, or a lock to name
            locking = self_locking.test(mechanism, kin, rubbing)
    elif the_plan.kinetostatics:
        forces = kinetostatics.solve(mechanism, kin)
    motion = None
    if setup.motion is not None:
        motion = setup.motion.part(first, last)
    return Block(first, last, kin, forces, rubbing, locking, rows.copy(), valid.copy(),
                 motion)


def tabulate(mechanism: Mechanism, block: Block, phases: dict[int, Continuous],
             count: int = 0, points: bool = True, machine: bool = True) -> None:
    """The block's columns, with the rows that hold a value beyond ``PLAUSIBLE`` taken
    out (``block.valid``, ``forces.valid`` updated, ``block.implausible`` set; of a
    block of whole variants of ``count`` positions each, a run of variants,
    ``block.implausible_variants`` names the columns of each variant that held one).

    Without ``points`` (``machine``) the block's columns leave out the motion of the
    joints and named points (the linkage reduced to the crank); whether they would hold
    such a value is decided all the same: they are computed, for the check only, unless
    ``columns.bound`` shows that none can."""
    wanted = None
    if not (points and machine):
        loaded = bool(np.any(mechanism.gravity) or mechanism.loads or mechanism.springs)
        if block.forces is None:
            machine = True  # (no force columns: no machine columns)
        elif loaded:
            machine = True  # (M_load is not bounded: computed)
        if not (points and machine) and columns_.bound(  # (the machine's too if left out)
                mechanism, block, not machine, count or 1) > columns_.PLAUSIBLE:
            wanted = (points, machine)
            points = machine = True
    cols = columns_.columns(mechanism, block, phases, points=points, machine=machine,
                            own=count == 0)
    kinematic = {name for name in cols if name in columns_.KINEMATIC_EXEMPT
                 or not name.startswith(columns_.FORCE_PREFIXES)}
    for part, names in (("kinematics", [n for n in cols if n in kinematic
                                        and n != "angle_deg"]),
                        ("forces", [n for n in cols if n not in kinematic])):
        if not names:
            continue
        bad = columns_.implausible(cols, names)
        if not bad.any():
            continue
        mask = np.zeros_like(block.rows)
        mask[np.flatnonzero(block.rows)[bad]] = True
        if part == "kinematics":
            block.valid &= ~mask
        if block.forces is not None:
            block.forces.valid &= ~mask
        block.implausible[part] = mask
        block.implausible_columns[part] = tuple(
            n for n in names if np.any(np.abs(cols[n]) > columns_.PLAUSIBLE))
        if count:  # the columns of each variant (the block's rows: whole variants)
            index = np.flatnonzero(block.rows)
            per = block.implausible_variants.setdefault(part, {})
            for variant, where in each(mask, mask.shape[0] // count):
                taken = (index >= where.start) & (index < where.stop)
                per[block.first // count + variant] = tuple(
                    n for n in names if np.any(np.abs(cols[n][taken]) > columns_.PLAUSIBLE))
        cols = columns_.columns(mechanism, block, phases, points=points, machine=machine,
                                own=count == 0)
    for phase in phases.values():
        phase.commit()
    if wanted is not None:  # computed for the check only
        cols = {name: values for name, values in cols.items()
                if (wanted[0] or name.split("_", 1)[0] not in columns_.POINT)
                and (wanted[1] or name not in columns_.MACHINE)}
    block.columns = cols


@dataclass(eq=False)
class Run:
    """A sweep computed in blocks of ``block_size`` positions: iterate for the
    ``Block``s, in order; then ``outcome`` holds the notes and verdicts.

    ``progress(done, total)`` is called as the blocks are computed, in units of the time
    they take: the first pass (the validity policy) counts as ``FIRST_PASS`` of the
    whole until the second pass's first block says how much slower that one is (the
    forces, friction and what the caller does with each block: 5 to 15 times)."""

    setup: Setup
    block_size: int
    progress: Callable[[float, float], None] | None = None
    outcome: Outcome | None = None
    """all but the columns, once the blocks are exhausted"""
    rows: FloatArray | None = None
    """(n,) bool: the positions reported, once the first pass is done"""
    coupling: friction.Coupling | None = None
    """the friction coupling of the sweep (None without friction, or with one block)"""
    positions: int = 0
    """rows given so far"""
    failed: dict[int, AssemblyError] = field(default_factory=dict)
    """a run of variants: variant -> why it does not close (it reports no position)"""
    notes: list[list[Note]] = field(default_factory=list)
    """the notes of each variant, once the blocks are exhausted (a sweep's are
    ``outcome.notes``)"""
    points: bool = True
    """the blocks' columns hold the motion of the joints and named points (without:
    their plausibility is decided all the same, ``tabulate``)"""
    machine: bool = True
    """the blocks' columns hold the linkage reduced to the crank (J_red, dJ_red, M_load)
    (a run of variants that reads a few columns leaves both out: a study)"""
    _shown: float = field(default=0.0, repr=False)

    def _tick(self, done: float, total: float) -> None:
        """Report ``done`` of ``total``, never a smaller share than before (the second
        pass's projection may grow)."""
        if self.progress is not None and total > 0:
            self._shown = max(self._shown, done / total)
            self.progress(self._shown * total, total)

    def __iter__(self) -> Iterator[Block]:
        setup, size = self.setup, self.block_size
        mechanism, the_plan, n = setup.mechanism, setup.plan, setup.positions
        angle, variants = setup.crank_angle, setup.variants
        if variants > 1:  # one block: its numbers are one per (variant, position)
            size = max(n, 1)
        policy = Policy.empty(angle, len(mechanism.dyads), variants)
        started = time.perf_counter()
        kin = None
        for first, last in spans(n, size):
            kin = setup.kinematics(first, last)
            policy.keep(first, last, kin)
            self._tick(last, n / FIRST_PASS)
        first_pass = time.perf_counter() - started
        kept = kin if n <= size else None  # one block: its kinematics computed once
        notes: list[list[Note]] = [[] for _ in range(variants)]
        rows, self.failed = assembly(mechanism, policy, setup.allow_partial, notes)
        self.rows = rows
        well = bands(mechanism, policy, rows, notes)
        usable, digits = policy.valid, policy.digits  # (the rest is let go)
        del policy, kin
        if the_plan.friction:
            self.coupling = friction_coupling(mechanism, angle, setup.speed,
                                              setup.acceleration, size)
        keep = Keep(setup, rows, well)
        phases = {link: Continuous() if variants == 1 else EachVariant(setup.each)
                  for link in mechanism.moving_links}
        for first, last in spans(n, size):
            block = stages(setup, kept if kept is not None else setup.kinematics(first, last),
                           first, last, self.coupling, rows[first:last], well[first:last])
            tabulate(mechanism, block, phases, setup.each if variants > 1 else 0,
                     self.points, self.machine)
            keep.block(block)
            self.positions += int(block.columns["angle_deg"].size)
            yield block
            # the second pass's time projected from its blocks so far, against the first's
            ratio = (time.perf_counter() - started - first_pass) * n / (
                max(last, 1) * max(first_pass, 1e-9))
            self._tick(n + ratio * last, n * (1.0 + ratio))
        self.outcome = keep.outcome(notes, usable, digits)
        self.notes = notes


class Keep:
    """What a run keeps of every block for its notes, verdicts and clearance check."""

    def __init__(self, setup: Setup, rows: FloatArray, well: FloatArray) -> None:
        the_plan, n = setup.plan, setup.positions
        self.setup, self.rows, self.well = setup, rows, well
        self.implausible = {"kinematics": np.zeros(n, dtype=bool),
                            "forces": np.zeros(n, dtype=bool)}
        self.implausible_columns: dict[str, dict[str, None]] = {"kinematics": {},
                                                                "forces": {}}
        self.implausible_variants: dict[str, dict[int, tuple[str, ...]]] = {
            "kinematics": {}, "forces": {}}
        """a run of variants: the columns of each variant that held such a value"""
        self.forces_valid = np.zeros(n, dtype=bool) if the_plan.kinetostatics else None
        self.lifted = np.zeros(n, dtype=bool)
        """a cam's spring-closed follower would need a pull here (it lifts off)"""
        self.rubbing = Rubbing.empty(n) if the_plan.friction else None
        run_up = setup.motion is not None and setup.motion.state == "run-up"
        self.joints = (the_plan.clearance if the_plan.clearance and not run_up
                       and setup.variants == 1 else ())  # (a variant's own check)
        self.forces = {name: np.empty((n, 2)) for name in self.joints}
        """the clearance joints' forces [N] at every position"""

    def block(self, block: Block) -> None:
        first, last = block.first, block.last
        for part, mask in block.implausible.items():
            self.implausible[part][first:last] = mask
        for part, names in block.implausible_columns.items():
            self.implausible_columns[part].update(dict.fromkeys(names))
        for part, per in block.implausible_variants.items():
            self.implausible_variants[part].update(per)
        self.well[first:last] = block.valid
        if block.forces is not None:
            self.forces_valid[first:last] = block.forces.valid
            contact = block.forces.contact_force
            if contact is not None and self.setup.mechanism.cam.cam.closure == "spring":
                self.lifted[first:last] = block.valid & (contact < 0.0)
            for name in self.joints:
                self.forces[name][first:last] = block.forces.revolute[name]
        if block.friction is not None:
            self.rubbing.keep(first, last, block.friction, block.locking)

    def outcome(self, each_notes: list[list[Note]], usable: FloatArray, digits: int
                ) -> Outcome:
        """The notes of the whole sweep after those of its validity policy
        (``each_notes``: of every variant, added to), its verdicts and clearance check;
        ``usable``: (n,) bool, the kinematics valid (for the joints that never move);
        ``digits``: the decimals [°] of its ranges. A run of variants: the outcome of
        all its positions, its notes in ``each_notes`` only."""
        setup, rows, well = self.setup, self.rows, self.well
        mechanism, angle, variants = setup.mechanism, setup.crank_angle, setup.variants
        notes = each_notes[0] if variants == 1 else []
        forces_valid, rubbing = self.forces_valid, self.rubbing
        invalid = None if forces_valid is None else well & ~forces_valid
        locking = None
        if rubbing is not None:  # (a sweep of one variant)
            rubbing.finish(usable)
            notes += rubbing.notes(mechanism, angle, rows, digits)
            invalid &= ~rubbing.blocked  # those have notes of their own
            locking = rubbing.locking(mechanism)
        for part in ("kinematics", "forces"):
            mask = self.implausible[part]
            if mask.any():
                for variant, where in each(mask, variants):
                    each_notes[variant].append(Note(
                        NoteKind.IMPLAUSIBLE, "", tuple(ranges(angle[where], mask[where])),
                        {"part": part, "limit": columns_.PLAUSIBLE, "digits": digits,
                         "columns": tuple(self.implausible_columns[part]) if variants == 1
                         else self.implausible_variants[part][variant]}))
        if self.lifted.any():
            invalid &= ~self.lifted  # (a note of their own)
            for variant, where in each(self.lifted, variants):
                each_notes[variant].append(Note(
                    NoteKind.LIFT_OFF, "", tuple(ranges(angle[where], self.lifted[where])),
                    {"digits": digits}))
        if invalid is not None and invalid.any():
            for variant, where in each(invalid, variants):
                each_notes[variant].append(Note(
                    NoteKind.FORCES_INVALID, "", tuple(ranges(angle[where], invalid[where])),
                    {"digits": digits}))
        if setup.motion is not None:
            notes += motion_notes(setup.motion)
        if setup.plan.drive_line:
            from dyade.linkage.drive import natural_frequency

            line = natural_frequency(mechanism)
            if not line.vdi_2149:
                notes.append(Note(NoteKind.DRIVE_LINE_SOFT, "", (),
                                  {"ratio": line.ratio, "omega_bar": line.omega_bar}))
        outcome = Outcome(mechanism, setup.plan, angle, rows, well, forces_valid, notes,
                          rubbing, locking, setup.motion)
        if setup.plan.clearance and not self.joints:
            notes.append(Note(NoteKind.CLEARANCE_NOT_APPLICABLE, "", (), {"run_up": True}))
        elif self.joints:
            from dyade.linkage import joint_clearance

            outcome.clearance = joint_clearance.check_mechanism(
                mechanism, outcome, self.forces, self.joints)
            for check in outcome.clearance:
                if not check.applies:
                    a, b = check.joint
                    notes.append(Note(NoteKind.CLEARANCE_NOT_APPLICABLE, f"joint ({a},{b})",
                                      (), {"joint": check.joint, "reason": check.reason}))
        return outcome


def motion_notes(motion: CrankMotion) -> list[Note]:
    """A run-up that did not settle; a friction torque that did not settle."""
    figures, out = motion.figures, []
    if motion.state == "run-up" and not figures["settled"]:
        out.append(Note(NoteKind.RUN_UP_NOT_SETTLED, "", (),
                        {"revolutions": figures["revolutions"]}))
    if not figures["friction_converged"]:
        out.append(Note(NoteKind.FRICTION_NOT_CONVERGED, "", (),
                        {"where": "drive", "passes": figures["passes"],
                         "change": figures["friction_change"]}))
    return out
