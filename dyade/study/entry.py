"""``study``: many variants of one mechanism file, one row each (``dyade.study``).

The Outcome's columns are the study's table: one row per variant, the parameters (by
their ``--set`` key paths, in the mechanism file's units), ``status`` and ``reason``,
then the outputs (SI, angles in degrees). Its summary holds the answers of the study
file's question with their units: the counts of the variants by status; the least and
largest value of each output (a plain table), the statistics and the probabilities of
failure (tolerance), the sensitivities (d output/d parameter and normalised), the optimum
or the Pareto front. Its notes say which variants gave no outputs and why.
"""

from __future__ import annotations

import math
import os
import re
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome
from dyade.analyses.inputs import SET

OVERRIDES = (
    Option("set", str, multiple=True, metavar="KEY=VALUE", study=False,
           help="Override a key of the mechanism file for every variant, as the study "
                "file's `set` does (repeatable): --set crank.speed_rpm=600. Not a key the "
                "study varies"),
    Option("samples", int, positive=True, metavar="N", study=False,
           help="Variants of a monte-carlo or latin-hypercube plan (overrides plan.samples): "
                "--samples 20 for a quick look"),
    Option("seed", int, metavar="N", study=False,
           help="The plan's seed (overrides plan.seed): the same rows on any number of "
                "workers"),
)
"""the study file's keys a run may override (``dyade.study.spec.override``)"""
assert OVERRIDES[0].api == SET.api  # the one --set of every entry that reads a mechanism

OPTIONS = (*OVERRIDES,
    Option("jobs", int, default=1, metavar="N", study=False,
           help="Run the variants on N processes (0: all cores); the same table as one "
                "process gives"),
    Option("scheduler", str, metavar="ADDRESS", study=False,
           help="Run the blocks on a Dask distributed cluster instead (tcp://host:8786; needs "
                "pip install \"dyade[dask]\")"),
    Option("block-size", int, positive=True, metavar="N", study=False,
           help="Variants per task  [default: at least 0.1 s of work, every worker busy]"),
    Option("journal", str, metavar="FILE", study=False,
           help="A CSV the rows stream to, block by block, as they are computed"),
    Option("resume", bool, study=False,
           help="Keep the rows already in the journal (an interrupted study) and compute only "
                "the others"),
)

STATUS_WORDS = {"ok": "ok", "locks": "self-lock", "does not close": "do not close",
                "refused": "were refused", "failed": "failed",
                "withheld": "have every position withheld"}
"""a variant's status -> the words of a note on the variants with it"""
STATUS_NAMES = {"ok": "ok", "locks": "locks", "does not close": "not_closing",
                "refused": "refused", "failed": "failed", "withheld": "withheld"}
"""a variant's status -> its count's figure (``variants_NAME``)"""
STATISTICS = ("mean", "sd", "p1", "p5", "p50", "p95", "p99", "min", "max")
"""the tolerance statistics of every output, each a figure ``STAT_OUTPUT``"""


def identifier(key: str) -> str:
    """A key path as a figure's name: ``dyad.2.lengths.1`` -> ``dyad_2_lengths_1``."""
    return re.sub(r"\W", "_", key)


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    from dyade.errors import InputError
    from dyade.parallel import connect
    from dyade.study import study as run_study
    from dyade.study.spec import Spec, override, read

    jobs = options["jobs"]
    if jobs < 0:
        raise InputError.parameter("jobs", f"must be 0 (every core) or more, got {jobs}.",
                                   value=jobs)
    if options.get("resume") and not options.get("journal"):
        raise InputError.parameter("resume", "needs the journal: the CSV of the interrupted "
                                             "run.")
    spec = override(source if isinstance(source, Spec) else read(source),
                    options.get("set") or (), options.get("samples"), options.get("seed"))
    client = connect(options["scheduler"]) if options.get("scheduler") else None
    try:
        result = run_study(spec, jobs=jobs if jobs > 0 else (os.cpu_count() or 1),
                           executor=None if client is None else client.get_executor(),
                           output=options.get("journal"), resume=bool(options.get("resume")),
                           block_size=options.get("block_size"), progress=rated(budget),
                           max_memory=budget.max_memory, check_time=budget.time)
    except InputError as err:
        raise err.naming({"max_memory": "max_memory_mb"}) from None
    finally:
        if client is not None:
            client.close()
    return outcome_of(result)


def outcome_of(result) -> Outcome:
    """A ``Study`` (``dyade.study``) as an Outcome: its table as the columns, its answers
    as the summary, the variants without outputs as notes."""
    import numpy as np

    spec, cols, units = result.spec, result.columns(), result.units
    descriptions = {"variant": "the variant's number in the plan",
                    "status": "ok, locks, does not close, refused, failed or withheld",
                    "reason": "why a variant gives no outputs, or which joint self-locks"}
    descriptions.update({key: f"the parameter {key}, as --set takes it"
                         for key in result.parameters})
    outcome = Outcome("study", columns=cols, units={name: units.get(name, "") for name in cols},
                      descriptions=descriptions, result=result,
                      meta={"study": spec.label, "mechanism": spec.mechanism,
                            "plan": spec.plan, "question": spec.question,
                            "evaluations": result.evaluations})
    add = outcome.add
    status = np.asarray(cols["status"])
    count = len(status)
    add("variants", count, "-", description="variants")
    for name, figure in STATUS_NAMES.items():
        given = int(np.sum(status == name))
        if given or name == "ok":
            add(f"variants_{figure}", given, "-", description=f"variants: {name}")
    for name, words in STATUS_WORDS.items():
        where = np.flatnonzero(status == name)
        if name != "ok" and where.size:
            first = int(where[0])
            reason = str(cols["reason"][first]).rstrip(".")
            because = f": {reason}" if reason else ""
            outcome.notes.append(f"{where.size} of {count} variants {words} (the first, variant "
                                 f"{int(cols['variant'][first])}{because}).")
    outcome.notes += list(getattr(result, "notes", []))
    if result.sensitivity is not None:
        sensitivities(outcome, result)
    elif result.tolerance is not None:
        tolerance(outcome, result)
    elif result.optimum is not None:
        optimum(outcome, result)
    else:
        for name in result.outputs:
            values = np.asarray(cols[name], dtype=float)
            finite = np.flatnonzero(np.isfinite(values))
            for end, pick in (("min", np.argmin), ("max", np.argmax)):
                k = int(finite[pick(values[finite])]) if finite.size else None
                add(f"{end}_{name}", None if k is None else float(values[k]), units.get(name, ""),
                    where=None if k is None else {"variant": int(cols["variant"][k])},
                    description=f"{'least' if end == 'min' else 'largest'} {name} over the "
                                f"variants that give it")
    if result.pareto is not None:
        front = [int(v) for v in np.asarray(cols["variant"])[result.pareto]]
        add("pareto_variants", front, "-", description="the non-dominated variants")
    return outcome


def sensitivities(outcome: Outcome, result) -> None:
    """d output/d parameter and its normalised form, per output and parameter."""
    zero = False
    for row in result.sensitivity:
        output, key = row["output"], row["parameter"]
        place = {"parameter": key, "output": output, "nominal": row["nominal"],
                 "step": row["step"]}
        outcome.add(f"d_{output}_d_{identifier(key)}", row["derivative"], row["unit"],
                    where=place, description=f"d {output}/d {key} (central differences; "
                                             f"lengths in m, angles in °)")
        outcome.add(f"sensitivity_{output}_{identifier(key)}", row["normalised"], "-",
                    where=place, description=f"{output} per {key}, normalised (% per %)")
        zero = zero or math.isnan(row["normalised"])
    if zero:
        outcome.notes.append("the normalised sensitivity of an output that is numerically zero "
                             "at the nominal variant is not given.")


def tolerance(outcome: Outcome, result) -> None:
    """The statistics of every output and the probabilities of failure."""
    tol, units = result.tolerance, result.units
    for name, stats in tol["outputs"].items():
        for stat in STATISTICS:
            outcome.add(f"{stat}_{name}", stats[stat], units.get(name, ""),
                        description=f"{name}: {stat} over the {stats['count']} variants that "
                                    f"give it")
    limits = tol.get("limits", {})
    for name, share in tol["probability"].items():
        outcome.add(f"probability_{name}", share, "-",
                    description=f"share of the variants: {failure(name, limits)}")


FAILURES = {"no_closure": "does not close", "refused": "refused by the reader",
            "withheld": "every position withheld", "self_locks": "self-locks"}
"""a tolerance study's failures -> their words (the limits': ``failure``)"""


def failure(name: str, limits: dict[str, float]) -> str:
    """A failure of a tolerance study in words, a limit with its value and unit: "joint
    force above 5000 N", "transmission angle below 40°"."""
    if name == "joint_force_above":
        return f"joint force above {limits.get('joint_force', math.nan):g} N"
    if name == "transmission_below":
        return f"transmission angle below {limits.get('transmission_deg', math.nan):g}°"
    return FAILURES.get(name, name.replace("_", " "))


def optimum(outcome: Outcome, result) -> None:
    """The optimum of one objective: its value where it occurs, the parameters there."""
    best, units = result.optimum, result.units
    place = dict(zip(result.parameters, best["x"]))
    name = best["objective"]
    outcome.add(f"optimum_{name}", best["value"], units.get(name, ""), where=place,
                description=f"{best['sense']} {name} (differential evolution)")
    for key, value in place.items():
        outcome.add(f"optimum_{identifier(key)}", value, units.get(key, ""),
                    description=f"{key} at the optimum")
    for k, each in enumerate(best.get("choices", ())):  # categorical: each choice's best
        words = ", ".join(f"{key} = {value}" for key, value in each["choice"].items())
        outcome.add(f"best_{name}_{k}", each["value"], units.get(name, ""),
                    where=dict(zip(result.parameters, each["x"])),
                    description=f"{best['sense']} {name} with {words}")
    outcome.add("evaluations", best["evaluations"], "-", description="evaluations of the "
                                                                       "optimiser")
    if not best.get("success", True):
        outcome.notes.append(f"the optimiser did not converge: {best['message'].rstrip('.')}.")


ENTRIES = {"study": Analysis("study", "A design study: many variants of one mechanism file",
                             run, OPTIONS, source="study", command="dyade study")}


def rated(budget):
    """``progress(done, total)`` for the study's blocks: the budget's, with the rate
    (variants per second) as its note, as the synthesis tells its candidates'."""
    import time

    started = time.perf_counter()

    def progress(done, total):
        rate = done / max(time.perf_counter() - started, 1e-9)
        budget.step(done, total, f"{rate:,.0f} variants/s")

    return progress
