"""The sweep of a mechanism, collected into one ``Result`` (``analyse``) or block by
block (``analyse_in_blocks``): its options checked and applied
(``dyade.linkage.options``), then run by the one pipeline (``dyade.linkage.pipeline``).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.linkage.blocks import BLOCK_SIZE
from dyade.linkage.columns import Columns
from dyade.linkage.options import (angles_in_degrees, collect_estimate, configure, radians,
                                   stream_estimate, sweep_in_degrees)
from dyade.linkage.block import Block
from dyade.linkage.pipeline import Run, prepare, stages
from dyade.linkage.pipeline import Setup
from dyade.linkage.plan import Plan
from dyade.linkage.verdicts import Outcome
from dyade.model.mechanism import Mechanism

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
    the columns reference, ``docs/reference/columns.md``), ``summary()`` the figures a
    designer sizes parts by and the extremes of every column, by name (plain Python
    numbers; docs/reference/json.md names them), ``notes`` the
    findings (dead centres, partial sweeps, friction, self-locking;
    ``dyade.report.notes.say`` words them), ``to_pandas()`` a DataFrame indexed by the
    crank angle [°]. ``kinematics``, ``forces`` and ``friction`` are the whole sweep's
    arrays (computed again, as one block, where it ran in several), in SI units.

    >>> import dyade
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"), step_deg=0.5)
    >>> summary = result.summary()
    >>> round(summary["M_drive_max"], 3), round(summary["F_shake_max"], 2)   # [N·m], [N]
    (1.466, 98.21)
    >>> result.kinematics.crank_angle.shape                  # every position [rad]
    (721,)
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

    def __getitem__(self, name: str) -> FloatArray:
        """The column ``name`` (``result["F_2_3"]``), as ``columns()[name]``: one value per
        reported position, NaN where not given; a name it does not have is a
        ``KeyError`` naming the closest ones."""
        try:
            return self.table[name]
        except (KeyError, TypeError):
            import difflib

            close = difflib.get_close_matches(str(name), list(self.table), n=3)
            hint = (f" Did you mean {', '.join(close)}?" if close
                    else " Its columns: result.columns().keys() (`dyade help columns`).")
            raise KeyError(f"the sweep has no column {name!r}.{hint}") from None

    def __contains__(self, name: object) -> bool:
        return name in self.table

    def at(self, angle_deg: float) -> dict[str, float]:
        """Every column's value at the crank angle ``angle_deg`` [°]: the sweep's own row
        where the angle is one of its positions, else computed exactly at that angle by
        the rule of ``analyse(..., crank_angle_deg=[angle_deg])`` (``dyade analyse --at``)
        with the sweep's own settings (plan, validity bands, crank speed). NaN where a
        value is not given, as in ``columns()``.

        Parameters
        ----------
        angle_deg : float
            The crank angle φ21 [°], within the swept range.

        Returns
        -------
        dict
            Column name -> value (units as in ``columns()``: SI, angles in degrees).

        Raises
        ------
        InputError
            The angle lies outside the swept range, or the sweep's crank motion is not
            one an angle between its positions has (a run-up, or speeds given per
            position).

        Examples
        --------
        >>> import dyade
        >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"))
        >>> round(result.at(37)["F_2_3"], 3) == round(float(result["F_2_3"][37]), 3)
        True
        >>> round(result.at(37.5)["M_drive"], 4)      # between positions: computed there
        0.3768
        """
        try:
            angle = float(angle_deg)
        except (TypeError, ValueError):
            raise InputError.parameter("angle_deg", f"must be a number [°], got "
                                                    f"{angle_deg!r}.", value=angle_deg,
                                       unit="°") from None
        angles = self.table["angle_deg"]
        given = angles[np.isfinite(angles)]
        low, high = (float(given.min()), float(given.max())) if given.size else (np.nan, np.nan)
        tol = 1e-9 * max(1.0, abs(angle))  # [°] the table's angles, converted from radians
        if not low - tol <= angle <= high + tol:
            raise InputError.parameter(
                "angle_deg", f"must lie within the swept range {low:g}°…{high:g}°, got "
                             f"{angle:g}: a result answers where it was swept (analyse at that "
                             f"angle: crank_angle_deg=[{angle:g}]).", value=angle, unit="°")
        hit = np.flatnonzero(np.abs(angles - angle) <= tol)
        if hit.size:
            return {name: float(column[hit[0]]) for name, column in self.table.items()}
        return self._computed_at(angle)

    def _computed_at(self, angle: float) -> dict[str, float]:
        """``at`` between the sweep's positions: one position computed with its settings."""
        setup = self.setup
        speed = acceleration = None
        if setup.motion is not None:
            if setup.motion.state == "run-up":
                raise InputError.parameter("angle_deg", f"must be one of the run-up's own "
                                                        f"positions, got {angle:g}: the "
                                                        f"run-up passes each angle more than "
                                                        f"once.", value=angle, unit="°")
        else:
            speed, acceleration = (_one_value(setup.speed, "crank_speed", angle),
                                   _one_value(setup.acceleration, "crank_acceleration", angle))
        one = analyse_si(setup.mechanism, crank_angle=np.array([np.deg2rad(angle)]),
                         allow_partial=setup.allow_partial, plan=setup.plan,
                         crank_speed=speed, crank_acceleration=acceleration)
        table = one.columns()
        return {name: float(table[name][0]) if name in table and table[name].size else np.nan
                for name in self.table}

    def summary(self, cols: Columns | None = None) -> dict[str, Any]:
        """The summary's figures by name (``dyade.linkage.summary``): drive torque and
        power, joint peaks, the shaking force, transmission angles, strokes, swings,
        friction, self-locking, the crank's motion and clearance figures, and the
        extremes of every column (``<column>_min``, ``<column>_max``), as plain numbers
        (None where not given). ``dyade.run("sweep", ...)`` gives each with its unit and
        where it occurs."""
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
            self.block = _decided(block, self.rubbing)
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


def _one_value(value, name: str, angle: float) -> float | None:
    """A sweep's crank speed or acceleration as one value for a position between its
    own (None: the file's); refused where it was given per position and varies."""
    if value is None or np.ndim(value) == 0:
        return value
    values = np.asarray(value, dtype=np.float64)
    if values.size and np.all(values == values[0]):
        return float(values[0])
    raise InputError.parameter("angle_deg", f"must be one of the sweep's own positions, got "
                                            f"{angle:g}: its {name} was given per position "
                                            f"(analyse at that angle with the {name} there: "
                                            f"crank_angle_deg=[{angle:g}], {name}=...).",
                               value=angle, unit="°")


def _decided(block: Block, rubbing) -> Block:
    """The whole sweep's block with what only the whole sweep decides: the joints that
    never move (``Rubbing.finish``), their at-rest masks cleared."""
    if block.friction is not None and rubbing is not None:
        block.friction.never_moves = list(rubbing.never_moves)
        for name in rubbing.never_moves:
            block.friction.at_rest[name] = rubbing.at_rest[name].copy()
    return block


RENAMED = {"start": "start_deg", "stop": "stop_deg", "step": "step_deg",
           "crank_angle": "crank_angle_deg", "dead_centre": "dead_centre_deg",
           "transmission_warning": "transmission_warning_deg"}
"""former parameter names of ``analyse`` and ``analyse_in_blocks`` (radians) -> the
names that carry the unit (degrees); the old names are refused, naming the new"""


def analyse(mechanism: Mechanism, *, start_deg: float | None = None,
            stop_deg: float | None = None, step_deg: float | None = None,
            crank_angle_deg=None, allow_partial: bool = False,
            friction_tol: float | None = None, friction_max_iter: int | None = None,
            plan: Plan | None = None, max_memory: float | None = None,
            dead_centre_deg: float | None = None, transmission_warning_deg: float | None = None,
            crank_speed: FloatArray | float | None = None,
            crank_acceleration: FloatArray | float | None = None,
            constant_speed: bool = False, run_up: bool = False,
            block_size: int | None = None, **renamed) -> Result:
    """Sweep the crank: kinematics, and what the mechanism calls for (``plan``).

    Angles are in degrees, as in the files, flags and tables: the names say so
    (``step_deg``); speeds and everything else in SI units.

    Parameters
    ----------
    mechanism : Mechanism
        From ``read_mechanism`` or ``build_mechanism``.
    start_deg, stop_deg, step_deg : float, optional
        The crank-angle sweep [°], overriding the mechanism's; ``stop_deg`` defaults to
        one revolution after ``start_deg``. A step above one revolution, or a sweep of
        one position, is refused (``InputError``): for single positions give
        ``crank_angle_deg``.
    crank_angle_deg : array_like, optional
        Crank angles φ21 [°] to compute instead of a regular sweep.
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
        (default ``dyade.limits.MAX_MEMORY``, 4 GiB): its columns, 8 B per value, and one block.
    dead_centre_deg, transmission_warning_deg : float, optional
        The validity policy's hard and soft bands [°] (defaults: the mechanism's, 2° and
        40°): within ``dead_centre_deg`` of a dead centre nothing is given; below
        ``transmission_warning_deg`` results come with a note.
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
    **renamed
        The former names in radians (``start``, ``stop``, ``step``, ``crank_angle``,
        ``dead_centre``, ``transmission_warning``) are refused with an ``InputError``
        naming the new one.

    Returns
    -------
    Result

    Raises
    ------
    AssemblyError
        A dyad cannot close over part of the sweep (naming the dyad and the ranges).
    InputError
        A bad option, naming the parameter and the fix.

    Examples
    --------
    >>> import dyade
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> cols = result.columns()
    >>> cols["angle_deg"].size, round(float(cols["M_drive"].max()), 3)
    (361, 1.466)

    Every 2° from 90° to 180°:

    >>> dyade.analyse(result.mechanism, start_deg=90, stop_deg=180, step_deg=2).summary()["positions"]
    46

    One position of a crank that speeds up (φ̇21 = 20 rad/s, φ̈21 = 150 rad/s²):

    >>> torque = dyade.analyse(result.mechanism, crank_angle_deg=[30.0], crank_speed=20.0,
    ...                        crank_acceleration=150.0).columns()["M_drive"]
    >>> round(float(torque[0]), 4)
    0.0786
    """
    InputError.refuse_renamed("analyse", renamed, RENAMED)
    mechanism = sweep_in_degrees(mechanism, start_deg, stop_deg, step_deg)
    return analyse_si(mechanism, crank_angle=angles_in_degrees(crank_angle_deg),
                      allow_partial=allow_partial, friction_tol=friction_tol,
                      friction_max_iter=friction_max_iter, plan=plan, max_memory=max_memory,
                      dead_centre=radians(dead_centre_deg, "dead_centre_deg"),
                      transmission_warning=radians(transmission_warning_deg,
                                                   "transmission_warning_deg"),
                      crank_speed=crank_speed, crank_acceleration=crank_acceleration,
                      constant_speed=constant_speed, run_up=run_up, block_size=block_size)


def analyse_si(mechanism: Mechanism, *, crank_angle: FloatArray | None = None,
               allow_partial: bool = False, friction_tol: float | None = None,
               friction_max_iter: int | None = None, plan: Plan | None = None,
               max_memory: float | None = None, dead_centre: float | None = None,
               transmission_warning: float | None = None,
               crank_speed: FloatArray | float | None = None,
               crank_acceleration: FloatArray | float | None = None,
               constant_speed: bool = False, run_up: bool = False,
               block_size: int | None = None) -> Result:
    """``analyse`` for the engine's own callers, in SI units: ``crank_angle``,
    ``dead_centre`` and ``transmission_warning`` [rad]; the sweep is the mechanism's."""
    size = _block_size(block_size, COLLECT_BLOCK)
    mechanism, the_plan = configure(
        mechanism, positions=None if crank_angle is None
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
                  table=table,
                  block=None if kept is None else _decided(kept, outcome.rubbing))


def analyse_in_blocks(mechanism: Mechanism, *, block_size: int | None = None,
                      start_deg: float | None = None, stop_deg: float | None = None,
                      step_deg: float | None = None, allow_partial: bool = False,
                      friction_tol: float | None = None, friction_max_iter: int | None = None,
                      max_memory: float | None = None, dead_centre_deg: float | None = None,
                      transmission_warning_deg: float | None = None,
                      constant_speed: bool = False, run_up: bool = False, **renamed) -> Run:
    """``analyse`` block by block, in memory that does not grow with the number of
    positions.

    Iterate over the returned ``Run`` for its ``Block``s of ``block_size`` positions,
    each with its ``columns``; once they are exhausted, ``run.outcome`` holds the notes
    and verdicts.

    Parameters
    ----------
    mechanism : Mechanism
        From ``read_mechanism`` or ``build_mechanism``.
    block_size : int, optional
        Positions per block (default ``BLOCK_SIZE``).
    start_deg, stop_deg, step_deg : float, optional
        The crank-angle sweep [°], as for ``analyse``.
    allow_partial, friction_tol, friction_max_iter, dead_centre_deg, transmission_warning_deg, constant_speed, run_up
        As for ``analyse``.
    max_memory : float, optional
        The memory [B] the run may need besides what the caller keeps.
    **renamed
        The former names in radians are refused, as by ``analyse``.

    Returns
    -------
    Run
        An iterable of ``Block``; ``run.positions`` the number of positions,
        ``run.outcome`` the notes and verdicts once every block was taken.

    Examples
    --------
    >>> import dyade
    >>> run = dyade.analyse_in_blocks(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...                               block_size=100)
    >>> [block.columns["angle_deg"].size for block in run], run.positions
    ([100, 100, 100, 61], 361)

    The largest drive torque, block by block, without keeping the sweep:

    >>> run = dyade.analyse_in_blocks(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...                               block_size=100, step_deg=0.5)
    >>> round(max(float(block.columns["M_drive"].max()) for block in run), 3)
    1.466
    """
    InputError.refuse_renamed("analyse_in_blocks", renamed, RENAMED)
    size = _block_size(block_size, BLOCK_SIZE)
    mechanism = sweep_in_degrees(mechanism, start_deg, stop_deg, step_deg)
    mechanism, the_plan = configure(
        mechanism, friction_tol=friction_tol, friction_max_iter=friction_max_iter,
        max_memory=max_memory, dead_centre=radians(dead_centre_deg, "dead_centre_deg"),
        transmission_warning=radians(transmission_warning_deg, "transmission_warning_deg"),
        constant_speed=constant_speed, run_up=run_up, estimate=stream_estimate(size))
    return Run(prepare(mechanism, the_plan, allow_partial=allow_partial, run_up=run_up), size)


def _block_size(size, default: int) -> int:
    size = default if size is None else size
    if not (isinstance(size, (int, np.integer)) and size >= 1):
        raise InputError.parameter("block_size", f"must be a whole number of positions ≥ 1, "
                                                 f"got {size}.", value=size)
    return int(size)


