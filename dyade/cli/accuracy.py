"""``dyade accuracy``: what each accuracy knob buys and costs, for the user's mechanism."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.cli import main
from dyade.cli.analyse import MECHANISM_FILE, load, set_option
from dyade.cli.output import show, write_json, write_rows

COLUMNS = ["study", "setting", "time_ms", "quantity", "value", "rel_error", "note"]


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@set_option
@click.option("--repeats", type=click.IntRange(min=1), default=3, show_default=True,
              help="Runs per setting; the best time counts.")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def accuracy(mechanism_file: Path, assignments, repeats: int, fmt: str, output) -> None:
    """What accuracy costs in time, for MECHANISM_FILE.

    Crank step (5° … 0.05°): engine time and the error of the peak drive torque, the
    peak force of every joint and the clearance peaks against the finest step — where
    the peaks stop moving, and how coarse steps miss narrow peaks near dead centres.
    With friction: iterations, time and change of the peaks per friction tolerance.
    With clearance data: the closed form against the direct simulation.
    """
    from dyade.linkage import accuracy as studies

    mechanism, _ = load(mechanism_file, assignments)
    rows = studies.studies(mechanism, repeats=repeats)
    records = [{"study": r.study, "setting": r.setting, "time_ms": r.time * 1e3,
                "quantity": r.quantity, "value": r.value, "rel_error": r.error, "note": r.extra}
               for r in rows]
    if fmt == "csv":
        write_rows(records, COLUMNS, output)
    elif fmt == "json":
        write_json({name: [r[name] for r in records] for name in COLUMNS}
                   | {"summary": {"mechanism": mechanism.name}, "warnings": []}, output)
    else:
        show(_tables(mechanism.name, records), output)


def _tables(name, records):
    import math

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
