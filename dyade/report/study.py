"""A design study as tables: the variants' status counts and the outputs' ranges, the
sensitivity (normalised), the tolerance statistics and failure probabilities, the
optimum and the Pareto front."""

from __future__ import annotations

from collections import Counter

import numpy as np
from rich.table import Table


def _g(value: float) -> str:
    return "—" if value is None or not np.isfinite(value) else f"{value:.6g}"


def tables(result) -> list:
    """The tables of a ``Study`` for the terminal."""
    cols, out = result.columns(), []
    counts = Counter(cols["status"].tolist())
    title = (f"Study {result.spec.label}: {len(cols['variant'])} variants of "
             f"{result.spec.mechanism.rsplit('/', 1)[-1]} ({result.spec.plan})")
    summary = Table(title=title, title_justify="left", min_width=len(title))
    summary.add_column("status")
    summary.add_column("variants", justify="right")
    summary.add_column("first reason")
    for status, count in counts.most_common():
        first = int(np.flatnonzero(cols["status"] == status)[0])
        summary.add_row(status, str(count),
                        f"variant {cols['variant'][first]}: {cols['reason'][first]}"
                        if cols["reason"][first] else "")
    out.append(summary)
    if result.sensitivity is not None:
        table = Table(title="Sensitivity (central differences; normalised: % output per % "
                            "parameter)", title_justify="left")
        for name in ("output", "parameter", "step", "d output/d parameter", "normalised"):
            table.add_column(name, justify="left" if name in ("output", "parameter") else "right")
        for row in result.sensitivity:
            table.add_row(row["output"], row["parameter"], _g(row["step"]),
                          _g(row["derivative"]), _g(row["normalised"]))
        out.append(table)
    elif result.tolerance is not None:
        tol = result.tolerance
        table = Table(title=f"Tolerance: {tol['variants']} variants", title_justify="left")
        for name in ("output", "unit", "mean", "sd", "p1", "p5", "p50", "p95", "p99"):
            table.add_column(name, justify="left" if name in ("output", "unit") else "right")
        for name, stats in tol["outputs"].items():
            table.add_row(name, result.units.get(name, ""),
                          *(_g(stats[k]) for k in ("mean", "sd", "p1", "p5", "p50", "p95", "p99")))
        out.append(table)
        failures = Table(title="Probability of failure (share of all variants)",
                         title_justify="left", min_width=48)
        failures.add_column("failure")
        failures.add_column("probability", justify="right")
        for name, p in tol["probability"].items():
            failures.add_row(name.replace("_", " "), _g(p))
        out.append(failures)
    elif result.optimum is not None:
        best = result.optimum
        table = Table(title=f"Optimum: {best['sense']} {best['objective']} = {_g(best['value'])} "
                            f"({best['evaluations']} evaluations; {best['message']})",
                      title_justify="left")
        table.add_column("parameter")
        table.add_column("value", justify="right")
        for key, value in zip(result.parameters, best["x"]):
            table.add_row(key, _g(value))
        out.append(table)
    else:
        table = Table(title="Outputs over the variants that give them", title_justify="left")
        for name in ("output", "unit", "min", "max"):
            table.add_column(name, justify="left" if name in ("output", "unit") else "right")
        for name in result.outputs:
            values = cols[name][np.isfinite(cols[name])]
            table.add_row(name, result.units.get(name, ""),
                          _g(values.min() if values.size else np.nan),
                          _g(values.max() if values.size else np.nan))
        out.append(table)
    if result.pareto is not None:
        table = Table(title="Pareto front (non-dominated variants)", title_justify="left")
        names = ["variant", *result.parameters,
                 *(n for n, _ in result.spec.optimise["objectives"])]
        for name in names:
            table.add_column(name, justify="right")
        for i in np.flatnonzero(result.pareto):
            table.add_row(*(_g(cols[n][i]) if n != "variant" else str(cols[n][i]) for n in names))
        out.append(table)
    return out
