"""``synthesis``: which mechanism moves like this (``dyade.synthesis``).

The input is a synthesis file (TOML, ``dyade.files.synthesis``) or its model. The
Outcome's columns are the designs, best first: the match error, its dimensions in the
canonical frame, and with masses the sweep's figures (peak and RMS drive torque, the
largest joint force, the least transmission angle, the peak shaking force, self-locking)
and whether it is on the Pareto front. Its summary gives the best design's error and
figures, the candidates traced, assembled and their rate; its ``result`` keeps the
``dyade.synthesis.Result`` (the designs' mechanism data, for files, tables and figures).
"""

from __future__ import annotations

import os
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome

OPTIONS = (
    Option("jobs", int, default=1, metavar="N", study=False,
           help="Trace the candidates' blocks on N processes (0: all cores); the same "
                "candidates and result as one process"),
    Option("scheduler", str, metavar="ADDRESS", study=False,
           help="Trace the blocks on a Dask distributed cluster instead (tcp://host:8786; "
                "needs pip install \"dyade[dask]\")"),
    Option("seed", int, metavar="N", study=False,
           help="The search's seed  [default: the file's search.seed, else 0]"),
    Option("candidates", int, positive=True, metavar="N", study=False,
           help="Candidates per round of the search  [default: the file's "
                "search.candidates, else 20000]"),
)

FIGURE_UNITS = {"M_drive_max": ("N·m", "peak |drive torque| at the operating speed"),
                "M_drive_rms": ("N·m", "RMS drive torque at the operating speed"),
                "F_joint_peak": ("N", "the largest joint force"),
                "mu_min_deg": ("°", "the least transmission angle"),
                "F_shake_max": ("N", "the peak shaking force"),
                "locks": ("-", "a joint self-locks (1) or not (0)"),
                "structural_error_deg": ("°", "the largest structural error"),
                "mu_motion_deg": ("°", "the least transmission angle between the poses")}
"""a design's figure -> (unit, description)"""


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import dataclasses

    import numpy as np

    from dyade.errors import InputError
    from dyade.files.synthesis import read_synthesis
    from dyade.model.synthesis import Synthesis
    from dyade.synthesis import error_unit, synthesise

    if source is None:
        raise InputError.parameter("source", "give a synthesis file (dyade init synthesis "
                                             "FILE writes one).")
    problem = source if isinstance(source, Synthesis) else read_synthesis(source)
    changes = {key: options[key] for key in ("seed", "candidates") if options.get(key) is not None}
    if changes:
        problem = dataclasses.replace(problem, **changes)
    jobs = options["jobs"]
    if jobs < 0:
        raise InputError.parameter("jobs", f"must be 0 (every core) or more, got {jobs}.",
                                   value=jobs)
    client = None
    if options.get("scheduler"):
        from dyade.parallel import connect

        client = connect(options["scheduler"])
    import time

    started = time.perf_counter()

    def progress(done, total, best):
        rate = done / max(time.perf_counter() - started, 1e-9)
        budget.step(done, total, f"{rate:,.0f} candidates/s, best error {best:.3g}")

    try:
        result = synthesise(problem, jobs=jobs if jobs > 0 else (os.cpu_count() or 1),
                            executor=None if client is None else client.get_executor(),
                            progress=progress, check_time=budget.time)
    finally:
        if client is not None:
            client.close()
    kind = problem.target.kind
    outcome = Outcome("synthesis", figures=("synthesis",),
                      meta={"name": problem.name, "source": problem.source,
                            "topology": problem.topology, "target": kind},
                      result=result)
    designs = result.designs
    unit, words = error_unit(problem)
    columns: dict[str, Any] = {"design": np.arange(1, len(designs) + 1, dtype=float),
                               "error": np.array([d.error for d in designs])}
    units = {"design": "-", "error": unit}
    descriptions = {"design": "the design's rank (its file: design-N.toml)",
                    "error": words}
    names = sorted({name for d in designs for name in d.figures},
                   key=list(FIGURE_UNITS).index)
    for name in names:
        columns[name] = np.array([np.nan if d.figures.get(name) is None else
                                  float(d.figures[name]) for d in designs])
        units[name], descriptions[name] = FIGURE_UNITS[name]
    if result.pareto is not None:
        columns["pareto"] = result.pareto.astype(float)
        units["pareto"] = "-"
        descriptions["pareto"] = f"on the Pareto front of error and {problem.figure}"
    made = getattr(result, "function", None)
    if made is not None and problem.topology == "slider-crank":  # the slider's position
        columns = {"crank_deg": np.rad2deg(made.crank), "output_m": made.target,
                   "traced_m": made.traced, "error_m": made.error}
        units = {"crank_deg": "°", "output_m": "m", "traced_m": "m", "error_m": "m"}
        descriptions = {"crank_deg": "the table's crank angle φ (from the guide)",
                        "output_m": "the target's slider position s (along the guide, "
                                    "from the crank pivot's foot)",
                        "traced_m": "the position the slider-crank gives (through dyade)",
                        "error_m": "the structural error s_traced − s_target"}
        if made.method != "fit" and made.precision.size:
            for k, at in enumerate(np.rad2deg(made.precision), start=1):
                outcome.add(f"precision_{k}_deg", float(at), "°",
                            description=f"precision point {k}: crank angle")
        if getattr(problem.target, "profile", None) is not None:
            outcome.add("output_zero", made.start, "m",
                        description="the slider's position where the law's lift is zero")
    elif made is not None:  # function generation: the structural error at every row
        columns = {"crank_deg": np.rad2deg(made.crank), "output_deg": np.rad2deg(made.target),
                   "traced_deg": np.rad2deg(made.target + made.error),
                   "error_deg": np.rad2deg(made.error)}
        units = {name: "°" for name in columns}
        descriptions = {"crank_deg": "the table's crank angle φ",
                        "output_deg": "the target's output angle ψ",
                        "traced_deg": "the output angle the mechanism gives (through dyade; "
                                      "a six-bar's link 6)",
                        "error_deg": "the structural error ψ_traced − ψ_target"}
        offsets = getattr(result, "offsets", None)
        if offsets is not None:  # a motion profile: its own master beside the crank angle
            columns = {"master_deg": np.rad2deg(made.crank - offsets.crank), **columns}
            units["master_deg"] = "°"
            descriptions["master_deg"] = "the profile's master angle"
            descriptions["output_deg"] = "the target's output angle ψ (the profile's s + ψ0)"
            outcome.add("crank_zero", float(np.rad2deg(offsets.crank)), "°",
                        description="the crank angle at the profile's master zero")
            outcome.add("output_zero", float(np.rad2deg(offsets.output)), "°",
                        description="the output angle where the profile's s = 0")
        for k, at in enumerate(np.rad2deg(made.precision), start=1):
            outcome.add(f"precision_{k}_deg", float(at), "°",
                        description=f"precision point {k}: crank angle")
    outcome.columns, outcome.units, outcome.descriptions = columns, units, descriptions
    best = designs[0]
    outcome.add("error", best.error, unit, description=f"best design: {words}")
    outcome.add("converged", bool(best.converged), "-",
                description="the best design's local fit converged")
    for name in names:
        outcome.add(name, best.figures.get(name), FIGURE_UNITS[name][0],
                    description=f"best design: {FIGURE_UNITS[name][1]}")
    if result.evaluated:
        outcome.add("candidates", result.evaluated, "-", description="candidates traced")
        outcome.add("assembled", result.assembled, "-",
                    description="of these, assembled over the turn and passed the filters")
        outcome.add("rate", result.rate, "1/s", description="candidates per second")
    outcome.add("designs", len(designs), "-", description="designs found")
    outcome.notes = [f"design {k}: {note}" for k, d in enumerate(designs, start=1)
                     for note in d.notes] + list(result.notes)
    return outcome


ENTRIES = {"synthesis": Analysis("synthesis", "Dimensional synthesis: which mechanism moves "
                                 "like this", run, OPTIONS, source="synthesis",
                                 figures=("synthesis",), command="dyade synthesise")}
