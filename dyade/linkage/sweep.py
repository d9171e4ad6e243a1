"""The sweep of a mechanism, whole (``analyse``) or in blocks (``analyse_in_blocks``):
its options checked and applied (``configure``), then run by the one pipeline
(``dyade.linkage.pipeline``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from dyade.errors import InputError
from dyade.linkage.blocks import BLOCK_SIZE
from dyade.linkage.columns import Columns
from dyade.linkage.model import FloatArray, Mechanism, Revolute, Sweep, sweep_problem
from dyade.linkage.block import Block
from dyade.linkage.pipeline import Run, prepare, stages
from dyade.linkage.pipeline import Setup
from dyade.linkage.plan import Plan
from dyade.linkage.plan import plan as infer_plan
from dyade.linkage.verdicts import Outcome

if TYPE_CHECKING:
    from dyade.linkage import friction, kinematics, kinetostatics

COLLECT_BLOCK = 1 << 16
"""positions per block of ``analyse`` (its columns are kept in memory anyway): one block
for every common sweep (no friction coupling to compute), and one block's arrays
(kinematics, forces: a few kB per position) well below the columns at millions of
positions"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Result(Outcome):
    """Everything a sweep computed, in SI units.

    ``columns()`` gives the sweep as named columns (the CSV contract, documented in
    ``mechanisms/README.md``), ``summary()`` the extremes and the figures a designer
    sizes parts by, ``notes`` the findings (dead centres, partial sweeps, friction,
    self-locking; ``dyade.report.notes.say`` words them), ``to_pandas()`` a DataFrame
    indexed by the crank angle [°]. ``kinematics``, ``forces`` and ``friction`` are the
    whole sweep's arrays (computed again, as one block, where it ran in several).
    """

    setup: Setup | None = None
    """the sweep that was run (its crank angles, speeds and accelerations)"""
    table: Columns = field(default_factory=dict)
    """the reported positions as named columns"""
    block: Block | None = None
    """the whole sweep as one block (kept where it ran as one; else made when asked)"""

    def columns(self) -> Columns:
        """The reported positions as named columns, in the CSV's order and units (SI,
        angles in degrees: names ending in ``_deg``); NaN where a value is not given."""
        return self.table

    def summary(self, cols: Columns | None = None) -> dict[str, Any]:
        """Extremes of every column and where, drive torque and power, joint peaks,
        friction, self-locking and clearance figures, as plain numbers."""
        from dyade.linkage import summary as summary_

        return summary_.summary(self, self.table if cols is None else cols)

    def to_pandas(self):
        """The columns as a ``pandas.DataFrame`` indexed by ``angle_deg`` (needs pandas)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Result.to_pandas() needs pandas, which dyade does not install: "
                              "pip install pandas") from None
        return pandas.DataFrame(self.columns()).set_index("angle_deg")

    def whole(self) -> Block:
        """The whole sweep as one block: kinematics, forces, friction (the same numbers
        as its blocks had; ``forces.valid`` is ``forces_valid``)."""
        if self.block is None:
            setup, n = self.setup, self.setup.positions
            block = stages(setup, setup.kinematics(0, n), 0, n, None, self.rows, self.valid)
            if block.forces is not None:
                block.forces.valid = self.forces_valid.copy()
            self.block = block
        return self.block

    @property
    def kinematics(self) -> kinematics.Kinematics:
        """Positions, velocities and accelerations of every link at every position."""
        return self.whole().kinematics

    @property
    def forces(self) -> kinetostatics.Forces | None:
        """Joint forces and drive torque; None when the plan has no kinetostatics."""
        return self.whole().forces

    @property
    def friction(self) -> friction.FrictionResult | None:
        """Friction loads, determinants and verdicts; None without friction."""
        return self.whole().friction


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


def column_count(mechanism: Mechanism) -> int:
    """How many columns a sweep of ``mechanism`` gives (about: the friction determinants
    and lock margins are not counted)."""
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    prismatic = len(mechanism.joints) - revolute
    columns = (1 + 3 * len(mechanism.moving_links) + 6 * revolute + 3 * prismatic
               + 6 * len(mechanism.named_points) + len(mechanism.dyads))
    if mechanism.has_dynamics:
        rubbing = sum(j.friction > 0.0 for j in mechanism.joints)
        columns += 3 * revolute + 2 * prismatic + 6 + 2 * rubbing + (2 if rubbing else 0)
    return columns


def memory_estimate(mechanism: Mechanism, positions: int) -> int:
    """What a sweep of ``positions`` in one block will take [B], from its column count."""
    return BYTES_PER_VALUE * column_count(mechanism) * positions + (50 << 20)


def collect_estimate(block_size: int):
    """What ``analyse`` needs [B] in blocks of ``block_size`` positions, as
    ``configure``'s ``estimate``: its columns (8 B per value) and one block."""
    def estimate(mechanism: Mechanism, positions: int) -> int:
        if positions <= block_size:
            return memory_estimate(mechanism, positions)
        return 8 * column_count(mechanism) * positions + memory_estimate(mechanism, block_size)

    return estimate


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


def stream_estimate(block_size: int):
    """What a sweep in blocks of ``block_size`` positions needs [B] besides its output,
    as ``configure``'s ``estimate``: one block's columns and arrays, and the
    per-position arrays kept for the whole sweep."""
    def estimate(mechanism: Mechanism, positions: int) -> int:
        if positions <= block_size:  # one block: the whole sweep in memory
            return memory_estimate(mechanism, positions)
        per_position = 17 * len(mechanism.dyads) + KEPT_PER_POSITION + 16 * sum(
            isinstance(j, Revolute) for j in mechanism.joints)
        if mechanism.has_dynamics and any(j.friction > 0.0 for j in mechanism.joints):
            # the residual; not solved, locked; near per dyad; at rest and locks per joint
            per_position += 10 + len(mechanism.dyads) + 2 * len(mechanism.joints)
        block = memory_estimate(mechanism, min(positions, block_size)) - (50 << 20)
        return 2 * block + per_position * positions + (60 << 20)

    return estimate


KEPT_PER_POSITION = 64
"""[B] what a sweep in blocks keeps per position besides the per-dyad arrays: crank
angle, speed and acceleration, masks, the clearance joints' forces"""


def analyse(mechanism: Mechanism, *, start: float | None = None, stop: float | None = None,
            step: float | None = None, crank_angle: FloatArray | None = None,
            allow_partial: bool = False, friction_tol: float | None = None,
            friction_max_iter: int | None = None, plan: Plan | None = None,
            max_memory: float | None = None, dead_centre: float | None = None,
            transmission_warning: float | None = None,
            crank_speed: FloatArray | float | None = None,
            crank_acceleration: FloatArray | float | None = None,
            constant_speed: bool = False, run_up: bool = False,
            block_size: int | None = None) -> Result:
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
        (default ``MAX_MEMORY``, 4 GiB): its columns, 8 B per value, and one block.
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
    block_size : int, optional
        Positions computed at a time (default ``COLLECT_BLOCK``): the results are the
        same to the bit for any block size; larger blocks take more memory besides the
        columns, smaller ones more time per position.

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
    size = _block_size(block_size, COLLECT_BLOCK)
    mechanism, the_plan = configure(
        mechanism, start=start, stop=stop, step=step, positions=None if crank_angle is None
        else np.size(crank_angle), friction_tol=friction_tol,
        friction_max_iter=friction_max_iter, plan=plan, max_memory=max_memory,
        dead_centre=dead_centre, transmission_warning=transmission_warning,
        given_speed=crank_speed is not None or crank_acceleration is not None,
        constant_speed=constant_speed, run_up=run_up, estimate=collect_estimate(size))
    for name, value in (("crank_speed", crank_speed), ("crank_acceleration", crank_acceleration)):
        if value is not None and not np.all(np.isfinite(value)):
            raise InputError.parameter(name, "must be finite.", value=value)
    setup = prepare(mechanism, the_plan, allow_partial=allow_partial, crank_angle=crank_angle,
                    crank_speed=crank_speed, crank_acceleration=crank_acceleration,
                    run_up=run_up)
    return collect(Run(setup, size))


def collect(run: Run) -> Result:
    """A run's blocks gathered into one ``Result``: its columns in memory (a run of one
    block keeps that block's)."""
    setup = run.setup
    whole = setup.positions <= run.block_size
    table: Columns = {}
    kept = None
    row = 0
    for block in run:
        if whole:
            kept, table = block, block.columns
            continue
        if not table:
            total = int(run.rows.sum())
            table = {name: np.empty(total) for name in block.columns}
        count = block.columns["angle_deg"].size
        for name, values in block.columns.items():
            table[name][row:row + count] = values
        row += count
    outcome = run.outcome
    return Result(*(getattr(outcome, f.name) for f in fields(Outcome)), setup=setup,
                  table=table, block=kept)


def analyse_in_blocks(mechanism: Mechanism, *, block_size: int | None = None,
                      start: float | None = None, stop: float | None = None,
                      step: float | None = None, allow_partial: bool = False,
                      friction_tol: float | None = None, friction_max_iter: int | None = None,
                      max_memory: float | None = None, dead_centre: float | None = None,
                      transmission_warning: float | None = None, constant_speed: bool = False,
                      run_up: bool = False) -> Run:
    """``analyse`` block by block, in memory that does not grow with the number of
    positions: a ``Run`` to iterate for its ``Block``s of ``block_size`` positions
    (default ``BLOCK_SIZE``), each with its ``columns``; once they are exhausted,
    ``run.outcome`` holds the notes and verdicts. The options as for ``analyse``
    (``max_memory`` bounds what the run needs besides what the caller keeps).

    >>> import dyade
    >>> run = dyade.analyse_in_blocks(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...                               block_size=100)
    >>> [block.columns["angle_deg"].size for block in run], run.positions
    ([100, 100, 100, 61], 361)
    """
    size = _block_size(block_size, BLOCK_SIZE)
    mechanism, the_plan = configure(
        mechanism, start=start, stop=stop, step=step, friction_tol=friction_tol,
        friction_max_iter=friction_max_iter, max_memory=max_memory, dead_centre=dead_centre,
        transmission_warning=transmission_warning, constant_speed=constant_speed,
        run_up=run_up, estimate=stream_estimate(size))
    return Run(prepare(mechanism, the_plan, allow_partial=allow_partial, run_up=run_up), size)


def _block_size(size, default: int) -> int:
    size = default if size is None else size
    if not (isinstance(size, (int, np.integer)) and size >= 1):
        raise InputError.parameter("block_size", f"must be a whole number of positions ≥ 1, "
                                                 f"got {size}.", value=size)
    return int(size)


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
    the_plan = plan if plan is not None else infer_plan(mechanism)
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
