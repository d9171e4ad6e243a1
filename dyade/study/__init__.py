"""Design studies: many variants of one mechanism file, one row each (``dyade study``).

A study file (TOML; ``docs/reference/study-file.md``) names a mechanism file,
the parameters by the dotted key paths of ``--set`` (each a list, a range or a
distribution), the plan (grid, Latin hypercube, Monte Carlo, sensitivity, optimise)
and what to ask of the table. ``study(...)`` runs it and gives a ``Study``: one row per
variant, the parameters first, then its status and reason ("ok", "locks", "does not
close", "refused", "failed"), then every key result of ``analyse``'s summary
(``dyade.study.evaluate.key_results``).

The variants run in blocks of at least 0.1 s of work, here, on ``jobs`` processes or on
any ``concurrent.futures.Executor`` (a Dask cluster's: ``Client(address).get_executor()``);
within a block they are read at once and swept together where the file allows
(``dyade.study.evaluate.Evaluator``, ``dyade.linkage.pipeline.prepare_variants``);
the rows stream to ``output`` block by block, and ``resume`` computes only the blocks
not yet there. The plan's rows are made here from its seed: the same table on any
number of workers.
"""

from __future__ import annotations

import os
import sys
import types
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from dyade.errors import InputError
from dyade.study.spec import Parameter, Spec, needs, parse, read

if TYPE_CHECKING:  # numpy only in annotations: `dyade --help` lists the study without it
    import numpy as np

__all__ = ["Parameter", "Spec", "Study", "needs", "parse", "read", "study"]


class _Package(types.ModuleType):
    """``dyade.study(...)`` is ``dyade.study.study(...)``: the package is the function's
    name too (importing a subpackage sets the parent's attribute to the module)."""

    def __call__(self, *args, **kwargs) -> Study:
        return study(*args, **kwargs)


sys.modules[__name__].__class__ = _Package


@dataclass(eq=False)
class Study:
    """A study's table and its answers.

    ``columns()``: named columns (``variant``, the parameters by their key paths,
    ``status``, ``reason``, the outputs); ``units``: each column's unit (parameters in
    the mechanism file's units, as ``--set`` takes them); ``sensitivity``,
    ``tolerance``, ``pareto`` and ``optimum``: the answers to the study file's
    question (None where not asked).

    Examples
    --------
    >>> import dyade
    >>> spec = dyade.study.parse({"mechanism": "mechanisms/fourbar.toml",
    ...                           "parameters": {"dyad.2.lengths.1": [190, 210]}})
    >>> result = dyade.study(spec)
    >>> list(result.columns())[:4], result.units["dyad.2.lengths.1"]
    (['variant', 'dyad.2.lengths.1', 'status', 'reason'], 'mm')
    >>> result.columns()["mu_2_min_deg"].round(2).tolist()
    [56.57, 65.03]
    """

    spec: Spec
    parameters: list[str]
    outputs: list[str]
    table: dict[str, np.ndarray]
    evaluations: int = 0
    """variants evaluated by this run (not those a resumed run found done)"""
    sensitivity: list[dict] | None = None
    tolerance: dict[str, Any] | None = None
    pareto: np.ndarray | None = None
    """(n,) bool: the non-dominated variants, for two or more objectives"""
    optimum: dict[str, Any] | None = None
    units: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    """what the answers need said (a sensitivity of an extreme that crosses a grid point
    of the sweep, ``questions.crossings``)"""

    def columns(self) -> dict[str, np.ndarray]:
        """The table as named columns, one entry per variant, in the plan's order."""
        return self.table

    def to_pandas(self):
        """The table as a ``pandas.DataFrame`` indexed by ``variant`` (needs pandas)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Study.to_pandas() needs pandas, which dyade does not install: "
                              "pip install pandas") from None
        frame = pandas.DataFrame(self.table).set_index("variant")
        frame.attrs["units"] = dict(self.units)
        return frame

    def answers(self) -> dict[str, Any]:
        """The question's answers as plain data (for JSON)."""
        out: dict[str, Any] = {}
        if self.sensitivity is not None:
            out["sensitivity"] = self.sensitivity
        if self.tolerance is not None:
            out["tolerance"] = self.tolerance
        if self.pareto is not None:
            out["pareto"] = [int(v) for v in self.table["variant"][self.pareto]]
        if self.optimum is not None:
            out["optimum"] = self.optimum
        return out


def study(file: str | os.PathLike | Spec, *, jobs: int = 1, executor=None,
          output: str | os.PathLike | None = None, resume: bool = False,
          block_size: int | None = None, progress=None, max_memory: float | None = None,
          check_time=None, set=(), samples: int | None = None,
          seed: int | None = None) -> Study:
    """Run a design study.

    Parameters
    ----------
    file : str, os.PathLike or Spec
        The study file (TOML), or a ``Spec`` from ``dyade.study.parse``.
    jobs : int
        Processes on this machine (1: here, one variant after another).
    executor : concurrent.futures.Executor, optional
        Runs the blocks instead (its ``map``): a process pool, a Dask cluster's
        ``Client(address).get_executor()``; the evaluator and the blocks must pickle.
    output : str or os.PathLike, optional
        A CSV file the rows stream to, block by block, as they are computed (for
        another format, write the table from ``columns()`` afterwards).
    resume : bool
        Keep the rows already in ``output`` and compute only the others.
    block_size : int, optional
        Variants per task (default: at least 0.1 s of work, every worker busy).
    progress : callable, optional
        ``progress(done, total)`` in variants, as the blocks come.
    max_memory : float, optional
        Bound on what the run may take [B] (default ``dyade.limits.MAX_MEMORY``): the
        table and the sweeps of the variants under way at once, estimated from the
        probe's outputs and refused (an ``InputError`` on ``max_memory``) before the
        variants run.
    check_time : callable, optional
        ``check_time(seconds, what)`` hears the estimate of the whole run [s], from the
        probe's time per variant, before the variants run; it may refuse it
        (``dyade.analyses.base.Budget.time``).
    set : sequence of str or (key, value) pairs, optional
        Overrides of the mechanism file for every variant, as the study file's ``set``
        (``"crank.speed_rpm=600"``); not a key the study varies.
    samples, seed : int, optional
        Override ``plan.samples`` (a sampled plan only) and ``plan.seed``
        (``dyade.study.spec.override``; ``dyade study --set/--samples/--seed``).

    Returns
    -------
    Study

    Raises
    ------
    InputError
        The study file or a key path is wrong (naming the file and the key).

    Examples
    --------
    A grid over the four-bar's coupler length (a study file gives the same as a dict
    to ``dyade.study.parse``; mechanism paths relative to the study file's directory):

    >>> import dyade
    >>> spec = dyade.study.parse({"mechanism": "mechanisms/fourbar.toml",
    ...                           "parameters": {"dyad.2.lengths.1": [190, 210]}})
    >>> dyade.study(spec).columns()["M_drive_rms"].round(4).tolist()
    [1.0505, 1.0051]
    """
    from dyade.study import plans, questions, run

    from dyade.study.spec import override

    spec = override(file if isinstance(file, Spec) else read(file), set, samples, seed)
    if block_size is not None and not (isinstance(block_size, int) and block_size >= 1):
        raise InputError.parameter("block_size", f"must be a whole number ≥ 1, got "
                                                 f"{block_size!r}.", value=block_size)
    evaluator = run.evaluator_for(spec)
    params = [p.key for p in spec.parameters]
    nominal = [p.nominal for p in spec.parameters]
    units = {"variant": "", "status": "", "reason": "",
             **{k: evaluator.unit(k) if hasattr(evaluator, "unit")
                else _file_unit(k, evaluator.data.get("units", {})) for k in params}}
    if spec.plan == "optimise":
        return _optimise(spec, evaluator, params, units, jobs, executor, max_memory, check_time)
    matrix = plans.variants(spec)
    if not len(matrix):
        raise InputError(f"{spec.label}: the plan gives no variant.", source=spec.label)
    outputs, cost = run.probe(evaluator, matrix, nominal,
                              precise=(jobs > 1 or executor is not None) and block_size is None)
    workers = jobs if executor is None else max(jobs, 2)
    bound(evaluator, nominal, len(matrix), len(params) + 3 + len(outputs),
          jobs if executor is None else 0, max_memory)
    if check_time is not None:
        check_time(cost * len(matrix) / max(workers, 1),
                   f"{spec.label}: {len(matrix):,} variants on {workers} "
                   f"process{'es' * (workers != 1)}")
    units.update({name: output_unit(name) for name in outputs})
    path = None if output is None else os.fspath(output)
    table, evaluated = run.execute(spec, evaluator, matrix, outputs, path, jobs=jobs,
                                   executor=executor, resume=resume, size=block_size,
                                   cost=cost, progress=progress)
    result = Study(spec, params, outputs, table, evaluated, units=units)
    if spec.question == "sensitivity":
        result.sensitivity = questions.sensitivity(table, spec, outputs,
                                                   plans.differences(spec))
        per_unit(result.sensitivity, units)
        if getattr(evaluator, "crossings", True):  # (a cam file's study: no crank grid)
            result.notes += questions.crossings(result.sensitivity, evaluator, matrix,
                                                plans.differences(spec), spec, units)
    if spec.question == "tolerance":
        result.tolerance = questions.tolerance(table, outputs, spec.tolerance)
    if spec.question == "optimise":  # several objectives over a sampled plan
        result.pareto = questions.pareto(table, spec.optimise["objectives"],
                                         spec.optimise["bounds"])
    return result


def _optimise(spec, evaluator, params, units, jobs, executor, max_memory=None,
              check_time=None) -> Study:
    import math
    import time

    from dyade.study import questions, tables

    nominal = [p.nominal for p in spec.parameters]
    started = time.perf_counter()
    evaluator.one(nominal)  # the time of one evaluation, for the estimate
    cost = time.perf_counter() - started
    evaluator.calls -= 1
    bound(evaluator, nominal, 1, len(params) + 3, jobs if executor is None else 0, max_memory)
    if check_time is not None:
        settings = spec.optimise
        combos = math.prod(len(p.choices) for p in spec.free if p.categorical)
        numeric = sum(not p.categorical for p in spec.free)
        most = combos * (settings["popsize"] * numeric * (settings["maxiter"] + 1) or 1)
        workers = jobs if executor is None else max(jobs, 2)
        check_time(cost * most / max(workers, 1),
                   f"{spec.label}: at most {most:,} evaluations of the optimiser")
    pool = None
    if executor is not None:
        workers = executor.map
    elif jobs > 1:
        import multiprocessing
        import sys
        from concurrent.futures import ProcessPoolExecutor

        context = multiprocessing.get_context("fork" if sys.platform == "linux" else None)
        pool = ProcessPoolExecutor(jobs, mp_context=context)
        workers = pool.map
    else:
        workers = 1
    try:
        optimum = questions.optimise(spec, evaluator, workers)
    finally:
        if pool is not None:
            pool.shutdown()
    status, reason, out = evaluator.one(spec.numeric(optimum["x"]))
    outputs = list(out)
    units.update({name: output_unit(name) for name in outputs})
    names = tables.header(params, outputs)
    row = [0, *optimum["x"], status, reason, *(float(out[n]) for n in outputs)]
    words = tuple(p.key for p in spec.parameters if p.categorical)
    return Study(spec, params, outputs, tables.columns_of(names, [row], words),
                 optimum["evaluations"], optimum=optimum, units=units)


def output_unit(name: str) -> str:
    """An output column's unit (``dyade.study.evaluate.unit``), degrees as °."""
    from dyade.study.evaluate import unit

    found = unit(name)
    return "°" if found == "deg" else found


TABLE_BYTES_PER_VALUE = 64
"""[B] per value of a study's table: the rows as Python lists of floats, and the columns"""
SWEEP_BYTES_PER_VALUE = 16
"""[B] per column and position of a variant's sweep (measured: about 16 B for a stack of
120 four-bars, the arrays and their intermediates)"""
BASE_BYTES = 50 << 20
"""[B] what the study takes besides its sweeps (numpy and the modules; the processes of
``-j`` are forked, and share them)"""


def bound(evaluator, nominal, variants: int, columns: int, processes: int,
          max_memory: float | None) -> None:
    """Refuse, before the variants run, a study whose table and sweeps under way would
    take more than ``max_memory`` [B]: ``variants`` rows of ``columns``, and on each of
    ``processes`` (0: on a cluster, not here) the sweep of a block of variants (a stack
    of ``STACK`` where they are swept together)."""
    from dyade.errors import InputError
    from dyade.limits import check_memory
    from dyade.linkage.options import column_count
    from dyade.study.evaluate import STACK

    need = TABLE_BYTES_PER_VALUE * variants * columns
    try:
        mechanism = evaluator.mechanism(nominal)
    except InputError:  # a nominal the reader refuses: its row says so
        mechanism = None
    if mechanism is not None and processes and hasattr(mechanism, "sweep"):
        stack = STACK if evaluator.stacks else 1
        need += processes * SWEEP_BYTES_PER_VALUE * column_count(mechanism) \
            * mechanism.sweep.count * stack + BASE_BYTES
    check_memory(need, f"this study of {variants:,} variants"
                       f"{f' ({processes} at a time)' if processes > 1 else ''}", max_memory,
                 "Use fewer variants or processes")


def ratio_unit(top: str, bottom: str) -> str:
    """The unit of a derivative: ``N·m`` per ``m`` -> ``N·m/m``; a quantity per its own
    unit (``m`` per ``m``, ``°`` per ``°``) -> ``-``."""
    top = "" if top == "-" else top
    bottom = "" if bottom == "-" else bottom
    if not bottom:
        return top or "-"
    if top == bottom:
        return "-"
    return f"{top or '1'}/{bottom}"


def per_unit(rows: list[dict], units: dict[str, str]) -> None:
    """The sensitivity's derivatives (``questions.sensitivity``, per the parameter's unit
    in the mechanism file) in one consistent unit each: the output's unit per the
    parameter's coherent unit (``coherent``: lengths in m, angles in °, as the outputs
    are), never metres per millimetre; its unit as ``unit``."""
    from dyade.study.questions import coherent

    for row in rows:
        bottom, factor = coherent(units.get(row["parameter"], ""))
        row["derivative"] = row["derivative"] / factor
        row["unit"] = ratio_unit(units.get(row["output"], ""), bottom)


LENGTHS = {"length", "lengths", "centre", "points", "slider_length", "slider_height",
           "pin_radius", "slider_point", "point", "gap", "A0", "B0"}
ANGLES = {"angle", "start", "stop", "step", "dead_centre", "transmission_warning"}
OTHER = {"mass": "kg", "inertia": "kg·m²", "speed_rpm": "rpm", "friction": "-",
         "coefficient": "-", "stiffness": "N/m", "variant": "-"}


def _file_unit(key: str, units: dict) -> str:
    """A parameter's unit, as the mechanism file takes it (its ``[units]``): lengths and
    angles in the file's units, the rest in SI (""; unknown)."""
    parts = [part for part in key.split(".") if not part.isdigit()]
    names = set(parts[-2:])
    if parts and parts[-1] in OTHER:
        return OTHER[parts[-1]]
    if names & ANGLES:
        return units.get("angle", "rad") if isinstance(units, dict) else "rad"
    if names & LENGTHS or (parts and parts[0] == "frame"):
        return units.get("length", "m") if isinstance(units, dict) else "m"
    return ""
