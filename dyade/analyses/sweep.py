"""``sweep``: the crank sweep of a mechanism (``dyade analyse``): positions, velocities
and accelerations of every link, joint and named point, and what the file calls for
(forces, friction, self-locking, the clearance check, the equation of motion).

The sweep is computed block by block in memory that does not grow with it
(``dyade.linkage.sweep.analyse_in_blocks``); the Outcome's columns are a ``Spool`` on
disk (``dyade.analyses.spool``), read a column at a time by the summary and by every
writer. Single crank positions are asked for by their angles (``at_deg``; the command
line's ``--at``): one rule with the API's ``crank_angle_deg``, and a "sweep" of one
position is refused, naming them (``dyade.analyses.inputs.load``).

The summary's figures are ``dyade.linkage.summary.figures``: one name per figure, the
names a study's outputs have (docs/reference/json.md).
"""

from __future__ import annotations

from typing import Any

from dyade.analyses import inputs
from dyade.analyses.base import Analysis, Budget, Figure, Option, Outcome

AT = Option("at", float, "°", multiple=True, metavar="DEG",
            help="Analyse these crank angles only, instead of a sweep (repeatable, or a "
                 "comma list: --at 30,60,90)")
FRICTION_TOL = Option("friction-tol", float, positive=True,
                      help="Accept a position's friction solution when a fixed-point step "
                           "would change its joint forces or friction loads by less than "
                           "this (default: the file's [friction] tol, 1e-9)")
FRICTION_MAX_ITER = Option("friction-max-iter", int, positive=True, metavar="N",
                           help="Most passes of the friction solution per dyad and position; "
                                "positions not solved are said (default: the file's "
                                "[friction] max_iter, 50)")
DEAD_CENTRE = Option("dead-centre", float, "°", metavar="DEG",
                     help="Hard band: within this of a dead centre (transmission angle 0° or "
                          "180°) nothing is given (default: the file's [sweep] dead_centre, "
                          "2°)")
TRANSMISSION_WARNING = Option("transmission-warning", float, "°", metavar="DEG",
                              help="Soft band: transmission angles below this are said in a "
                                   "note (default: the file's [sweep] transmission_warning, "
                                   "40°, H. Alt's rule)")
RUN_UP = Option("run-up", bool,
                help="With a [drive] table: the run-up from rest at the start angle, "
                     "revolution after revolution until the speed repeats, instead of the "
                     "periodic steady state; the rows are the whole run-up at the sweep's "
                     "step (column t: time)")
CONSTANT_SPEED = Option("constant-speed", bool,
                        help="Ignore the [drive] table: the crank at its constant speed_rpm "
                             "(to compare with the real speed)")
BLOCK_SIZE = Option("block-size", int, metavar="N", study=False,
                    help="Compute the sweep N positions at a time (default 2048; 0: all at "
                         "once), in memory that does not grow with the sweep; CSV rows are "
                         "written as they come, for the other formats the columns wait in a "
                         "temporary file (8 B per value, in TMPDIR)")
FAIL_ON_LOCK = Option("fail-on-lock", bool, study=False,
                      help="Fail (exit status 1) when the mechanism self-locks; otherwise "
                           "self-locking is a finding, reported")
OPTIONS = (inputs.SET, *inputs.SWEEP, AT, inputs.ALLOW_PARTIAL, FRICTION_TOL,
           FRICTION_MAX_ITER, DEAD_CENTRE, TRANSMISSION_WARNING, RUN_UP, CONSTANT_SPEED,
           BLOCK_SIZE, FAIL_ON_LOCK)

STAGES = ("kinematics", "kinetostatics", "friction", "self_locking", "clearance",
          "equation_of_motion", "drive_line")
"""the stages of a sweep, in the order it runs them (``dyade.linkage.plan.Plan``)"""


def stages(the_plan) -> list[str]:
    """The stages a sweep of ``the_plan`` runs, by name (``STAGES``)."""
    return [name for name in STAGES if getattr(the_plan, name)]


FIGURES = ("curves", "mechanism", "polar", "animate")
"""the figures of a sweep (``dyade plot KIND``)"""

ENGINE_NAMES = {"max_memory": "max_memory_mb", "crank_angle_deg": AT.api,
                "sweep": "the sweep (start_deg, stop_deg, step_deg)"}
"""the engine's parameters (``dyade.analyse_in_blocks``) -> the entry's options, in errors"""

def named(err):
    """An error of the engine with its parameters named as the entry's options
    (``ENGINE_NAMES``), the fix it suggests too (``crank_angle_deg=[...]`` is
    ``at_deg=[...]``)."""
    from dyade.errors import InputError

    if not err.parameters:
        return err
    renamed = err.naming(ENGINE_NAMES)
    reason = (renamed.reason or "").replace("crank_angle_deg=[...]", f"{AT.api}=[...]")
    out = InputError(str(renamed).replace("crank_angle_deg=[...]", f"{AT.api}=[...]"),
                     key=renamed.key, value=renamed.value, unit=renamed.unit, reason=reason)
    out.parameters = renamed.parameters
    return out


SECOND = 8e6
"""values (positions × columns) a sweep computes and writes in about a second; a
quarter of that with friction (measured: self-locking.toml, dyade-16.toml)"""


def estimate(run) -> float:
    """The time a sweep (``pipeline.Run``) takes [s], about."""
    from dyade.linkage.options import BYTES_PER_VALUE, memory_estimate

    setup = run.setup
    values = (memory_estimate(setup.mechanism, setup.positions) - (50 << 20)) / BYTES_PER_VALUE
    return max(values, 0.0) / SECOND * (4.0 if setup.plan.friction else 1.0)


class Sweep:
    """A sweep under way: the file read with the options (``inputs.load``), its first
    block computed (the assembly check fails here, before any output); ``blocks()``
    gives every block's columns as it is computed, ``outcome(columns)`` the Outcome
    once they are all taken.

    The command line writes a CSV from ``blocks()`` row by row as they come; the
    ``sweep`` entry keeps them in a ``Spool`` and gives the Outcome with its summary.
    """

    def __init__(self, source: Any, options: dict[str, Any], budget: Budget) -> None:
        from dyade.errors import InputError

        self.options = options
        self.at = options.get(AT.api) or ()
        swept = [option.api for option in inputs.SWEEP if options.get(option.api) is not None]
        if self.at and swept:
            raise InputError.parameter((AT.api, swept[0]), "exclude each other: single crank "
                                                           "positions, or a sweep.")
        if options.get(RUN_UP.api) and options.get(CONSTANT_SPEED.api):
            raise InputError.parameter((RUN_UP.api, CONSTANT_SPEED.api),
                                       "exclude each other.")
        size = options.get(BLOCK_SIZE.api)
        if size is not None and size < 0:
            raise InputError.parameter(BLOCK_SIZE.api, f"must be a whole number of positions "
                                                       f"≥ 0 (0: all at once), got {size}.",
                                       value=size)
        try:
            self.start(source, options, budget, size)
        except InputError as err:
            raise named(err) from None

    def start(self, source: Any, options: dict[str, Any], budget: Budget, size) -> None:
        """Read the file and compute the first block (``__init__``)."""
        from dyade.linkage.sweep import analyse, analyse_in_blocks

        self.loaded = inputs.load(source, options)
        common = dict(allow_partial=bool(options.get(inputs.ALLOW_PARTIAL.api)),
                      friction_tol=options.get(FRICTION_TOL.api),
                      friction_max_iter=options.get(FRICTION_MAX_ITER.api),
                      max_memory=budget.max_memory,
                      dead_centre_deg=options.get(DEAD_CENTRE.api),
                      transmission_warning_deg=options.get(TRANSMISSION_WARNING.api),
                      constant_speed=bool(options.get(CONSTANT_SPEED.api)),
                      run_up=bool(options.get(RUN_UP.api)))
        self.run = self.result = None
        if self.at:  # a few positions: computed at once
            self.result = analyse(self.loaded.mechanism, crank_angle_deg=list(self.at),
                                  block_size=size or None, **common)
            self.first, self.rest = self.result.columns(), iter(())
            return
        import sys

        self.run = analyse_in_blocks(self.loaded.mechanism,
                                     block_size=sys.maxsize if size == 0 else size, **common)
        seconds = estimate(self.run)
        budget.time(seconds, f"the sweep of {self.run.setup.positions:,} positions")
        self.long = seconds > 1.0
        """whether the run is worth a progress bar"""
        if self.long:
            self.run.progress = budget.progress
        self.rest = (block.columns for block in self.run)
        self.first = next(self.rest)  # the assembly check fails here, before any output

    def blocks(self):
        """The columns of every block, the first included, as they are computed."""
        yield self.first
        yield from self.rest

    @property
    def verdicts(self):
        """The sweep's verdicts and notes (``linkage.verdicts.Outcome``), once every
        block was taken."""
        return self.result if self.result is not None else self.run.outcome

    def outcome(self, columns=None, extremes=True) -> Outcome:
        """The Outcome of the sweep (``outcome_of``), once every block was taken."""
        return outcome_of(self.verdicts, columns, self.options, self.loaded.label,
                          single=bool(self.at), extremes=extremes)


def outcome_of(verdicts, columns=None, options: dict[str, Any] | None = None,
               label: str = "", single: bool = False, extremes=True) -> Outcome:
    """The Outcome of a sweep from its verdicts and notes (``verdicts``: a
    ``linkage.verdicts.Outcome``, or the ``Result`` of ``dyade.analyse``), its notes
    worded; with ``columns`` (a mapping of every column: a ``Spool``, or the Result's
    own), the columns, their units and the summary (``extremes``: of every column, or of
    those it names; ``single``: the positions are single ones, not a sweep). A sweep
    that gives no position its kinematics is refused (``DyadeError``,
    ``base.withheld``). ``options``: those it ran with (API names), ``label``: its
    file as messages name it."""
    from dyade.analyses.base import withheld
    from dyade.analyses.notes import say

    mechanism = verdicts.mechanism
    out = Outcome("sweep", figures=FIGURES, result=verdicts,
                  meta={"name": mechanism.name, "source": label or None,
                        "positions": int(verdicts.rows.sum()), "stages": stages(verdicts.plan)})
    out.options = {name: value for name, value in (options or {}).items() if value is not None}
    out.notes = [say(note, mechanism) for note in verdicts.notes]
    withheld(out, verdicts.valid[verdicts.rows],
             f"{mechanism.name}: no position of the sweep has its kinematics given")
    if columns is not None:
        from dyade.linkage.columns import unit_of
        from dyade.linkage.summary import figures

        out.columns = columns
        out.units = {name: unit_of(name) for name in columns}
        out.summary = {name: Figure(name, stat.value, stat.unit, stat.where, stat.description)
                       for name, stat in figures(verdicts, columns, extremes,
                                                 sweep=not single).items()}
    return out


def locks(outcome: Outcome) -> bool:
    """Whether the mechanism of a sweep's Outcome self-locks somewhere."""
    verdicts = outcome.result
    return any(lock.locks[verdicts.rows].any() for lock in (verdicts.locking or {}).values())


def refuse_lock(outcome: Outcome, message: str = "the mechanism self-locks (see the "
                                                  "notes); fail_on_lock was asked for.") -> None:
    """``fail_on_lock``: a ``DyadeError`` (``message``) where the mechanism self-locks."""
    from dyade.errors import DyadeError

    if locks(outcome):
        raise DyadeError(message)


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    from dyade.analyses.spool import Spool

    sweep = Sweep(source, options, budget)
    spool = Spool(sweep.blocks())
    outcome = sweep.outcome(spool)
    if options.get(FAIL_ON_LOCK.api):
        refuse_lock(outcome)
    return outcome


ENTRIES = {"sweep": Analysis("sweep", "The crank sweep of a mechanism: kinematics, forces, "
                             "friction, self-locking, clearance, the equation of motion", run,
                             OPTIONS, figures=FIGURES, command="dyade analyse")}
