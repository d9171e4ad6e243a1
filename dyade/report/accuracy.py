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
    """One table per study: settings down, the relative error of each quantity across
    (the reference setting shows its values)."""
    from rich.table import Table

    parts = []
    for study in dict.fromkeys(r["study"] for r in records):
        mine = [r for r in records if r["study"] == study]
        settings = list(dict.fromkeys(r["setting"] for r in mine))
        quantities = list(dict.fromkeys(r["quantity"] for r in mine))
        table = Table(title=f"{name}: {study} (errors relative to {settings[-1] if study != 'clearance' else 'the closed form'})",
                      title_justify="left")
        table.add_column("setting")
        table.add_column("time [ms]", justify="right")
        table.add_column("note")
        for quantity in quantities[:8]:
            table.add_column(quantity, justify="right")
        for setting in settings:
            row = [r for r in mine if r["setting"] == setting]
            cells = {r["quantity"]: r for r in row}
            values = []
            for quantity in quantities[:8]:
                r = cells.get(quantity)
                if r is None:
                    values.append("")
                elif isinstance(r["rel_error"], float) and not math.isnan(r["rel_error"]):
                    values.append(f"{r['rel_error']:.1e}")
                else:
                    values.append(f"{r['value']:.5g}")
            table.add_row(setting, f"{row[0]['time_ms']:.3g}", row[0]["note"], *values)
        if len(quantities) > 8:
            table.caption = f"{len(quantities) - 8} more quantities: --format csv"
        parts.append(table)
    return parts
