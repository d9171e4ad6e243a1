"""Writers over an ``Outcome`` (``dyade.analyses.base``): the one CSV of its columns,
and the generic tables of its summary and columns. A command may show richer tables
(``dyade.report.tables`` for a sweep), built from the same Outcome and the same
formatter (``dyade.report.format``)."""

from __future__ import annotations

from typing import TextIO

import numpy as np
from rich.table import Table

from dyade.analyses.base import Outcome
from dyade.report import csv_rows
from dyade.report.format import FLAG, cell, display, number, ordinal, where


def is_numeric(values) -> bool:
    values = np.asarray(values)
    return values.dtype.kind in "fiub"


def write_csv(outcome: Outcome, handle: TextIO, names: list[str] | None = None) -> None:
    """The Outcome's columns as CSV, one rule for every command (``format.cell``): 15
    significant digits, an empty cell where a value is not given, flags 1/0."""
    names = list(outcome.columns) if names is None else names
    columns = {name: outcome.columns[name] for name in names}
    if all(is_numeric(values) for values in columns.values()):
        numbers = {name: np.asarray(values, dtype=np.float64) for name, values in columns.items()}
        csv_rows.write({name: np.where(np.isfinite(values), values, np.nan)  # ±∞: empty
                        if np.isinf(values).any() else values
                        for name, values in numbers.items()}, handle)
        return
    handle.write(",".join(names) + "\n")
    rows = len(next(iter(columns.values()), ()))
    lists = {name: np.asarray(values).tolist() for name, values in columns.items()}
    for k in range(rows):
        handle.write(",".join(cell(lists[name][k]) for name in names) + "\n")




def scale(values) -> float:
    """The largest finite magnitude of numeric ``values`` (0 if none)."""
    values = np.asarray(values)
    if values.dtype.kind not in "fiu":
        return 0.0
    finite = np.abs(values[np.isfinite(values)])
    return float(finite.max()) if finite.size else 0.0


def summary_table(outcome: Outcome, title: str, length_unit: str = "m") -> Table | None:
    """quantity | value | unit | where: the summary's figures, lengths in
    ``length_unit``; a limit beside its figure."""
    if not outcome.summary:
        return None
    table = Table(title=title, title_justify="left")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    table.add_column("where")
    for name, figure in outcome.summary.items():
        factor, unit = display(figure.unit, length_unit)
        value = figure.value
        if isinstance(value, (float, int)) and not isinstance(value, bool):
            value = value * factor
        if isinstance(value, (list, tuple)):
            text = ", ".join(number(v) for v in value) or "none"
        else:
            text = number(value)
        if figure.limit is not None:
            text += f" (limit {number(figure.limit * factor)})"
        table.add_row(figure.description or name, text, unit, where(figure.where))
    return table


def columns_table(outcome: Outcome, title: str, names: list[str] | None = None,
                  length_unit: str = "m", most: int = 40) -> Table | None:
    """The columns ``names`` (all), every k-th row to about ``most`` rows, each header
    with its unit; the title says when rows are left out."""
    names = list(outcome.columns) if names is None else names
    if not names:
        return None
    rows = len(np.asarray(outcome.columns[names[0]]))
    stride = max(1, -(-rows // most))
    every = f" ({rows} rows, every {ordinal(stride)} shown; --format csv for all)" \
        if stride > 1 else ""
    table = Table(title=title + every, title_justify="left")
    scaled = {}
    for name in names:
        factor, unit = display(outcome.units.get(name, ""), length_unit)
        values = np.asarray(outcome.columns[name])
        if values.dtype.kind == "f":
            values = values * factor
        scaled[name] = values
        shown = unit and unit != FLAG  # a flag's values say yes or no: no unit
        table.add_column(f"{name} [{unit}]" if shown else name,
                         justify="right" if values.dtype.kind in "fiu" else "left")
    scales = {name: scale(values) for name, values in scaled.items()}
    for k in range(0, rows, stride):
        table.add_row(*[number(scaled[name][k].item() if hasattr(scaled[name][k], "item")
                               else scaled[name][k], scales[name]) for name in names])
    return table
