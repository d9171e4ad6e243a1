"""Accuracy studies -> records and rich tables."""

from __future__ import annotations

import math

COLUMNS = ["study", "setting", "time_ms", "quantity", "value", "rel_error", "note"]
UNITS = {"time_ms": "ms", "rel_error": "-", "value": "N or N·m (see quantity)"}


def records(rows) -> list[dict]:
    """One record per (study, setting, quantity); times in ms."""
    return [{"study": r.study, "setting": r.setting, "time_ms": r.time * 1e3,
             "quantity": r.quantity, "value": r.value, "rel_error": r.error, "note": r.extra}
            for r in rows]


def tables(name: str, records: list[dict]):
    """Per study two narrow tables: what each setting costs (time, note), and the
    relative error of each peak per setting, quantities down and settings across (the
    reference setting shows its values)."""
    from rich.table import Table

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
            cost.add_row(setting, f"{row['time_ms']:.3g}", row["note"])
        errors = Table(title=f"{name}: {study} — relative error [-] of each peak against "
                             f"{reference} (its own column: the value)", title_justify="left")
        errors.add_column("quantity")
        for setting in settings:
            errors.add_column(setting, justify="right")
        cells = {(r["setting"], r["quantity"]): r for r in mine}
        for quantity in quantities:
            values = []
            for setting in settings:
                r = cells.get((setting, quantity))
                if r is None:
                    values.append("")
                elif isinstance(r["rel_error"], float) and not math.isnan(r["rel_error"]):
                    values.append(f"{r['rel_error']:.1e}")
                else:
                    values.append(f"{r['value']:.5g}")
            errors.add_row(quantity, *values)
        parts += [cost, errors]
    return parts
