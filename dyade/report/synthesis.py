"""A ``synthesis`` Outcome (``dyade.analyses.synthesis``) -> rich tables, and each
design's mechanism file as text."""

from __future__ import annotations

from dyade.report.format import number


def tables(outcome) -> list:
    """The designs (error, dimensions, sweep figures) and the search's summary."""
    from rich.table import Table

    from dyade.report.outcome import columns_table, summary_table

    result = outcome.result
    parts = [summary_table(outcome, f"Synthesis: {outcome.meta.get('name')} "
                                    f"({outcome.meta.get('topology')}, "
                                    f"{outcome.meta.get('target')})")]
    if getattr(result, "function", None) is not None:
        parts.append(columns_table(outcome, "Structural error at every row of the table"))
    dims = Table(title="Designs (mechanism files: design-N.toml)", title_justify="left")
    error = outcome.summary.get("error")  # the function table's columns hold no "error"
    unit = error.unit if error is not None else outcome.units.get("error", "-")
    for head in ("design", f"error [{unit}]", "frame pivots [m]",
                 "lengths [m]", "coupler point P [m]", "variant"):
        dims.add_column(head, justify="right")
    for k, design in enumerate(result.designs, start=1):
        data = design.data
        frame = data["frame"]["points"]
        dyads = data["dyad"]
        lengths = [data["crank"]["length"], *(v for dyad in dyads
                                              for v in dyad.get("lengths") or [dyad.get("length")])]
        point = next((body["points"]["P"] for body in data.get("links", {}).values()
                      if "P" in body.get("points", {})), None)
        dims.add_row(str(k), number(design.error, spec=".4g"),
                     "; ".join(f"{n} ({number(v[0], spec='.6g')}, {number(v[1], spec='.6g')})"
                               for n, v in frame.items()),
                     ", ".join(number(v, spec=".6g") for v in lengths),
                     "—" if point is None else f"({number(point[0], spec='.6g')}, "
                                               f"{number(point[1], spec='.6g')})",
                     " ".join(f"{dyad['variant']:+d}" for dyad in dyads))
    parts.append(dims)
    if getattr(result, "function", None) is None and len(outcome.columns) > 2:
        parts.append(columns_table(outcome, "Designs: match error and sweep figures"))
    return [part for part in parts if part is not None]


def mechanism_text(design, source: str | None = None) -> str:
    """A design's mechanism file (TOML), with a comment saying where it came from."""
    from dyade.arrays import plain
    from dyade.files.mechanism.editing import dumps

    head = (f"# {design.name}, written by `dyade synthesise`"
            + (f" from {source}" if source else "") + f": match error {design.error:.6g}.\n"
            "# Run: dyade analyse THIS_FILE\n")
    return head + dumps(plain(design.data))
