"""The ``accuracy`` Outcome (``dyade.analyses.accuracy``) as rich tables."""

from __future__ import annotations

import math

from dyade.report.format import number


def tables(outcome):
    """Per study two narrow tables: what each setting costs (time, note), and the
    relative error of each peak per setting, quantities down and settings across (the
    reference setting shows its values, with the quantity's unit); then the summary."""
    from rich.table import Table

    from dyade.report.outcome import summary_table

    name, records = outcome.meta["name"], outcome.result
    parts = []
    for study in dict.fromkeys(r["study"] for r in records):
        mine = [r for r in records if r["study"] == study]
        settings = list(dict.fromkeys(r["setting"] for r in mine))
        quantities = list(dict.fromkeys(r["quantity"] for r in mine))
        reference = "the closed form" if study == "clearance" else settings[-1]
        cost = Table(title=f"{name}: {study} — cost of each setting", title_justify="left")
        for head, justify in (("setting", "left"), ("time [ms]", "right"), ("note", "left")):
            cost.add_column(head, justify=justify)
        for setting in settings:
            row = next(r for r in mine if r["setting"] == setting)
            cost.add_row(setting, number(row["time_ms"], spec=".3g"), row["note"])
        errors = Table(title=f"{name}: {study} — relative error [-] of each peak against "
                             f"{reference} (its own column: the value)", title_justify="left")
        errors.add_column("quantity")
        errors.add_column("unit")
        for setting in settings:
            errors.add_column(setting, justify="right")
        cells = {(r["setting"], r["quantity"]): r for r in mine}
        for quantity in quantities:
            values, unit = [], ""
            for setting in settings:
                r = cells.get((setting, quantity))
                if r is None:
                    values.append(number(None))
                    continue
                unit = r["unit"]
                if not math.isnan(r["rel_error"]):
                    values.append(number(r["rel_error"], spec=".1e") if r["rel_error"] else "0")
                else:
                    values.append(number(r["value"], spec=".5g"))
            errors.add_row(quantity, unit, *values)
        parts += [cost, errors]
    parts.append(summary_table(outcome, f"{name}: where the peaks stop moving"))
    return parts
