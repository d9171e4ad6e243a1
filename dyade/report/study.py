"""The ``study`` Outcome (``dyade.study.entry``) as tables: the variants' status
counts and the outputs' ranges, the sensitivity (normalised), the tolerance statistics
and failure probabilities, the optimum and the Pareto front."""

from __future__ import annotations

from collections import Counter

import numpy as np
from rich.table import Table

from dyade.study.entry import STATISTICS, failure, identifier
from dyade.report.format import number
from dyade.study.questions import constant


def constants(outputs: list[tuple[str, float]], units: dict[str, str]) -> Table | None:
    """The outputs constant over the variants (``questions.constant``: one value to
    rounding), each with its one value, instead of a spread of round-off."""
    if not outputs:
        return None
    table = Table(title="Constant over the variants", min_width=34,
                  title_justify="left")
    for name in ("output", "unit", "value"):
        table.add_column(name, justify="right" if name == "value" else "left")
    for name, value in outputs:
        table.add_row(name, units.get(name, ""), number(value))
    return table


def tables(outcome) -> list:
    """The tables of a ``study`` Outcome (or of a ``Study``) for the terminal."""
    if not hasattr(outcome, "summary"):  # a Study of dyade.study
        from dyade.study.entry import outcome_of

        outcome = outcome_of(outcome)
    result, cols, figures = outcome.result, outcome.columns, outcome.summary
    units, out = outcome.units, []
    counts = Counter(np.asarray(cols["status"]).tolist())
    count = len(cols["variant"])
    title = (f"Study {outcome.meta['study']}: {count} variant{'s' * (count != 1)} of "
             f"{outcome.meta['mechanism'].rsplit('/', 1)[-1]} ({outcome.meta['plan']})")
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
        for name in ("output", "parameter", "step", "d output/d parameter", "unit",
                     "normalised [-]"):
            table.add_column(name, justify="left" if name in ("output", "parameter", "unit")
                             else "right")
        for row in result.sensitivity:
            output, key = row["output"], row["parameter"]
            derivative = figures[f"d_{output}_d_{identifier(key)}"]
            table.add_row(output, key, f"{number(row['step'])} {units.get(key, '')}".rstrip(),
                          number(derivative.value), derivative.unit,
                          number(figures[f"sensitivity_{output}_{identifier(key)}"].value))
        out.append(table)
    elif result.tolerance is not None:
        table = Table(title=f"Tolerance: {figures['variants'].value} variants",
                      title_justify="left")
        shown = ("mean", "sd", "p1", "p5", "p50", "p95", "p99")
        for name in ("output", "unit", *shown):
            table.add_column(name, justify="left" if name in ("output", "unit") else "right")
        stats = result.tolerance["outputs"]
        for name in stats:
            if stats[name].get("constant"):
                continue
            scale = max(abs(figures[f"min_{name}"].value), abs(figures[f"max_{name}"].value))
            table.add_row(name, units.get(name, ""),  # round-off of the output's scale: 0
                          *(number(figures[f"{stat}_{name}"].value, scale) for stat in STATISTICS
                            if stat in shown))
        out.append(table)
        out.append(constants([(name, stats[name]["mean"]) for name in stats
                              if stats[name].get("constant")], units))
        failures = Table(title="Probability of failure (share of all variants)",
                         title_justify="left", min_width=48)
        failures.add_column("failure")
        failures.add_column("probability [-]", justify="right")
        limits = result.tolerance.get("limits", {})
        for name in result.tolerance["probability"]:
            failures.add_row(failure(name, limits), number(figures[f"probability_{name}"].value))
        out.append(failures)
    elif result.optimum is not None:
        best = result.optimum
        value = figures[f"optimum_{best['objective']}"]
        table = Table(title=f"Optimum: {best['sense']} {best['objective']} = "
                            f"{number(value.value)} {value.unit} ({best['evaluations']} "
                            f"evaluations; {best['message']})", title_justify="left")
        table.add_column("parameter")
        table.add_column("value", justify="right")
        table.add_column("unit")
        for key in result.parameters:
            figure = figures[f"optimum_{identifier(key)}"]
            table.add_row(key, number(figure.value), figure.unit)
        out.append(table)
        if best.get("choices"):  # categorical parameters: the best of each choice
            unit = f" [{value.unit}]" if value.unit and value.unit != "-" else ""
            each = Table(title=f"The best of each choice ({best['sense']} {best['objective']})",
                         title_justify="left")
            for key in result.parameters:
                each.add_column(key, justify="right")
            each.add_column(f"{best['objective']}{unit}", justify="right")
            for row in best["choices"]:
                each.add_row(*(number(v) for v in row["x"]), number(row["value"]))
            out.append(each)
    else:
        table = Table(title="Outputs over the variants that give them", title_justify="left")
        for name in ("output", "unit", "min", "max"):
            table.add_column(name, justify="left" if name in ("output", "unit") else "right")
        same = []
        for name in result.outputs:
            low, high = figures[f"min_{name}"].value, figures[f"max_{name}"].value
            if low is not None and len(cols["variant"]) > 1 and constant(cols[name]):
                same.append((name, low))
                continue
            table.add_row(name, units.get(name, ""), number(low), number(high))
        out.append(table)
        out.append(constants(same, units))
    if result.pareto is not None:
        table = Table(title="Pareto front (non-dominated variants)", title_justify="left")
        names = ["variant", *result.parameters,
                 *(n for n, _ in result.spec.optimise["objectives"])]
        for name in names:
            unit = units.get(name, "")
            table.add_column(f"{name} [{unit}]" if unit and unit != "-" else name,
                             justify="right")
        for i in np.flatnonzero(result.pareto):
            table.add_row(*(number(cols[n][i]) if n != "variant" else str(cols[n][i])
                            for n in names))
        out.append(table)
    return [table for table in out if table is not None]
