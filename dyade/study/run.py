"""A study run: the variants in blocks, on this process, on ``-j`` processes
(``dyade.parallel``) or on any ``concurrent.futures.Executor`` (a Dask cluster's
included), each block's rows streamed to the journal as it comes, so that a rerun with
``resume`` computes only the blocks not yet there."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable

import numpy as np

from dyade.errors import InputError
from dyade.study import tables
from dyade.study.evaluate import FAILED, STACK, Evaluator
from dyade.study.spec import Spec

TASK_TIME = 0.1
"""[s] the least work per block handed to a worker (a task's overhead is ~1 ms on a
process pool, ~10 ms on a Dask cluster)"""


def evaluator_for(spec: Spec) -> Evaluator:
    """The spec's evaluator, with the mechanism file's data read once (and the study's
    fixed overrides applied); the key paths checked on the nominal variant."""
    from dyade.files.mechanism import load_data

    data = load_data(spec.mechanism, spec.fixed, f"{spec.label}: set")
    from dyade.files.cam import is_cam

    if is_cam(data):  # a cam file: its checks per variant (``dyade.study.cam``)
        from dyade.study.cam import CamEvaluator

        evaluator = CamEvaluator(spec.mechanism, data, tuple(p.key for p in spec.parameters),
                                 {p.key: p.choices for p in spec.parameters if p.categorical})
        nominal = [p.nominal for p in spec.parameters]
        check_choices(spec, evaluator, nominal)
        try:
            evaluator.mechanism(nominal)
        except InputError as err:  # a key path that is not there (a value: the rows')
            if any(words in str(err) for words in KEY_PROBLEMS):
                raise InputError(f"{spec.label}: [parameters]: {err}", source=spec.label,
                                 key=err.key) from None
        if spec.extras:
            raise InputError(f"{spec.label}: `outputs.extra` belongs to a mechanism file's "
                             f"study; a cam file's study gives the cam's checks (leave it "
                             f"out).", source=spec.label, key="outputs.extra")
        return evaluator
    evaluator = Evaluator(spec.mechanism, data, tuple(p.key for p in spec.parameters),
                          spec.extras, spec.fluctuation,
                          {p.key: p.choices for p in spec.parameters if p.categorical})
    nominal = [p.nominal for p in spec.parameters]
    check_choices(spec, evaluator, nominal)
    try:
        mechanism = evaluator.mechanism(nominal)
    except InputError as err:  # a key path that is not there; a value is the rows' to say
        text = str(err)
        if any(words in text for words in KEY_PROBLEMS):
            raise InputError(f"{spec.label}: [parameters]: {text}", source=spec.label,
                             key=err.key) from None
    else:
        if "coupling" in spec.extras and mechanism.drive_line is None:
            raise InputError(f"{spec.label}: `outputs.extra` asks for \"coupling\" (the drive "
                             f"line's resonance speed), but {os.path.basename(spec.mechanism)} "
                             f"has no [drive_line] table: give it one (`drive_line.stiffness` "
                             f"[N·m/rad] or `drive_line.coupling` = a coupling file), e.g. "
                             f"`set = {{ \"drive_line.stiffness\" = 1000 }}` in the study "
                             f"file.", source=spec.label, key="outputs.extra")
    return evaluator


def check_choices(spec: Spec, evaluator: Evaluator, nominal: list[float]) -> None:
    """Refuse, before any variant runs, a categorical parameter's choice that the
    mechanism file's reader refuses (a law given to a dwell, a key path that takes no
    name), naming the study file, the parameter and the choice, with the reader's
    words (a variant refused for another of its values is its row's to say)."""
    for j, p in enumerate(spec.parameters):
        for index, name in enumerate(p.choices):
            values = list(nominal)
            values[j] = float(index)
            try:
                evaluator.mechanism(values)
            except InputError as err:
                if name in str(err) or p.key in str(err) or err.key == p.key:
                    raise InputError(f"{spec.label}: `parameters.{p.key}`: the choice "
                                     f"{name!r} is refused: {err}", source=spec.label,
                                     key=f"parameters.{p.key}") from None


KEY_PROBLEMS = ("unknown key", "are numbered", "is a value, not a table")
"""what the reader and ``set_dotted`` say of a key path that is wrong (not of a value)"""


def probe(evaluator: Evaluator, matrix: np.ndarray, nominal, precise: bool = True
          ) -> tuple[list[str], float]:
    """The output names (of the nominal variant, else of the first that gives outputs)
    and the time one variant takes [s], for the block size: of a second evaluation
    with ``precise`` (the first loads modules); where the evaluator sweeps variants
    together, of a trial block of the first variants (their share of a block's time)."""
    started = time.perf_counter()
    status, _, out = evaluator.one(nominal)
    cost = time.perf_counter() - started
    evaluator.calls -= 1
    if precise:
        started = time.perf_counter()
        evaluator.one(nominal)
        cost = time.perf_counter() - started
        evaluator.calls -= 1
    for row in matrix[:5] if not out else ():
        _, _, out = evaluator.one(row)
        evaluator.calls -= 1
        if out:
            break
    trial = matrix[:TRIAL]
    if len(trial) > 1 and evaluator.stacks and evaluator.stages_stack(trial):
        calls, together = evaluator.calls, evaluator.together
        started = time.perf_counter()
        evaluator((0, trial))
        if evaluator.together > together:  # (else: variant by variant, as measured)
            cost = (time.perf_counter() - started) / len(trial)
        evaluator.calls, evaluator.together = calls, together
    return list(out), cost


TRIAL = 64
"""variants of the trial block that measures a stacked sweep's cost per variant"""


def block_size(count: int, cost: float, workers: int, stack: int = 1) -> int:
    """Variants per block: at least ``TASK_TIME`` of work, but every worker busy; a
    whole number of sweeps of ``stack`` variants where the evaluator sweeps them
    together (and that keeps every worker busy)."""
    size = max(1, math.ceil(TASK_TIME / max(cost, 1e-6)))
    size = stack * math.ceil(size / stack)
    if workers > 1:
        size = min(size, max(1, math.ceil(count / workers)))
    return size


def execute(spec: Spec, evaluator: Evaluator, matrix: np.ndarray, outputs: list[str],
            journal_path: str | None, *, jobs: int = 1, executor=None, resume: bool = False,
            size: int | None = None, cost: float = 0.01,
            progress: Callable[[int, int], None] | None = None) -> tuple[dict, int]:
    """Evaluate the rows of ``matrix`` not yet in the journal (a CSV at
    ``journal_path``; None: the rows are kept here only); (the whole table as named
    columns, the variants evaluated by this call)."""
    from dyade import parallel

    params = [p.key for p in spec.parameters]
    names = tables.header(params, outputs)
    words = tuple(p.key for p in spec.parameters if p.categorical)
    journal = tables.Journal(journal_path, names, resume, spec.label, words)
    rows = dict(journal.done)
    for index, row in rows.items():  # the plan still gives these values (to the CSV's digits)?
        if index >= len(matrix) or any(
                not tables.same(row[1 + j], shown) for j, shown in
                enumerate(spec.shown(matrix[index]))):
            journal.close()
            raise InputError(f"{spec.label}: resuming: variant {index} of {journal_path} has "
                             f"other parameter values than this plan gives (its seed, "
                             f"samples or parameters changed); remove the file or write "
                             f"elsewhere.", source=journal_path)
        row[1:1 + len(params)] = spec.shown(matrix[index])  # the plan's own values
    todo = [i for i in range(len(matrix)) if i not in rows]
    workers = jobs if executor is None else max(jobs, 2)
    size = size or block_size(len(todo), cost, workers, STACK if evaluator.stacks else 1)
    blocks = []
    for k in range(0, len(todo), size):  # consecutive runs of variants not done
        chunk = todo[k:k + size]
        start = 0
        for j in range(1, len(chunk) + 1):
            if j == len(chunk) or chunk[j] != chunk[j - 1] + 1:
                blocks.append((chunk[start], matrix[chunk[start]:chunk[j - 1] + 1]))
                start = j
    if executor is not None:
        results = executor.map(evaluator, blocks)
    else:
        results = parallel.ordered_map(evaluator, blocks, jobs, lost=_lost)
    done = len(rows)
    evaluated = 0
    try:
        if progress is not None:
            progress(done, len(matrix))
        for block in results:
            shown = spec.shown_rows(matrix[[index for index, *_ in block]])
            lines = [[index, *values, status, reason,
                      *[out.get(name, math.nan) for name in outputs]]
                     for (index, status, reason, out), values in zip(block, shown)]
            journal.write(lines)
            for line in lines:
                rows[line[0]] = line
            evaluated += len(lines)
            done += len(lines)
            if progress is not None:
                progress(done, len(matrix))
    finally:
        journal.close()
        close = getattr(results, "close", None)
        if close is not None:
            close()
    return tables.columns_of(names, list(rows.values()), words), evaluated


def _lost(block, reason: str):
    """Rows for a block whose worker process ended without a result."""
    first, values = block
    return [(first + i, FAILED, f"{reason} (rerun it alone)", {}) for i in range(len(values))]
