"""The ``flywheel`` and ``balance`` Outcomes (``dyade.analyses.machine``) as rich tables."""

from __future__ import annotations

from rich.table import Table

from dyade.analyses.machine import BEFORE_AFTER
from dyade.report.format import number
from dyade.roundoff import clean


def flywheel_table(outcome) -> Table:
    """One row per figure: what, key, unit, value; the given quantity marked."""
    source = outcome.meta.get("name") or outcome.meta.get("source") or ""
    table = Table(title=f"Flywheel for {source} (δ ≈ ΔE/(J·Ω²))", title_justify="left")
    table.add_column("quantity")
    table.add_column("key")
    table.add_column("unit")
    table.add_column("value", justify="right")
    for key, figure in outcome.summary.items():
        table.add_row(figure.description, key, figure.unit, number(figure.value, spec=".7g"))
    return table


def balance_tables(outcome) -> list[Table]:
    """The counterweights, and what they change (before, after, their ratio)."""
    cols = outcome.columns
    weights = Table(title=f"Counterweights for {outcome.meta['name']} (least-squares "
                          f"shaking-force balance)", title_justify="left")
    for head in ("link", "m·r [kg·m]", "angle in link frame [°]", "radius [m]", "mass [kg]"):
        weights.add_column(head, justify="right")
    for k in range(len(cols["link"])):
        weights.add_row(str(int(cols["link"][k])), number(cols["first_moment"][k]),
                        number(cols["angle_deg"][k], spec=".2f"), number(cols["radius"][k]),
                        number(cols["mass"][k]))
    effect = Table(title="Before and after (constant crank speed)", title_justify="left")
    for head in ("quantity", "unit", "before", "after", "after/before"):
        effect.add_column(head, justify="left" if head in ("quantity", "unit") else "right")
    summary = outcome.summary

    def add(label: str, unit: str, before, after, scale: float | None = None) -> None:
        """A row; round-off of ``scale`` (default: the larger of before and after) is 0."""
        if before is None or after is None:
            effect.add_row(label, unit, number(before), number(after), "")
            return
        scale = max(abs(before), abs(after)) if scale is None else scale
        before, after = clean(before, scale), clean(after, scale)
        ratio = number(after / before, spec=".3g") if before else ""
        effect.add_row(label, unit, number(before), number(after), ratio)

    for name, unit, text in BEFORE_AFTER:
        add(text, unit, summary[f"{name}_before"].value, summary[f"{name}_after"].value)
    joints = [name[:-len("_peak_before")] for name in summary if name.endswith("_peak_before")
              and not name.startswith("M_")]
    largest = max((abs(summary[f"{j}_peak_{when}"].value) for j in joints
                   for when in ("before", "after")
                   if summary[f"{j}_peak_{when}"].value is not None), default=0.0)
    for joint in joints:  # round-off of the machine's joint-force scale is 0
        add(f"{joint} largest", "N", summary[f"{joint}_peak_before"].value,
            summary[f"{joint}_peak_after"].value, largest)
    return [weights, effect]
