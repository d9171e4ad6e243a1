"""The Outcomes of the drive line's entries (``dyade.analyses.drive_line``) as rich
tables: the natural frequency and VDI 2149, the analysis's own figures, and its columns
(every k-th row to about 60), every number through ``report.format``."""

from __future__ import annotations

from rich.table import Table

from dyade.analyses.base import MISSING
from dyade.analyses.drive_line import FREQUENCY
from dyade.report.format import FLAG, number, where
from dyade.report.outcome import columns_table

TITLES = {"driveline-frequency": "The lowest natural frequency over the cycle (J frozen at J(φ))",
          "driveline-steady": "Periodic steady state of the drive line, next to the rigid drive",
          "driveline-resonance": "Resonance curve and Floquet multipliers (ideal motor)",
          "driveline-stability": "Resonance curve and Floquet multipliers (ideal motor)",
          "driveline-map": "Largest Floquet multiplier over speed × {parameter}",
          "driveline-run-up": "Run-up from rest"}
"""entry -> the title of its columns' table"""

SUMMARIES = {"driveline-steady": "Steady state", "driveline-resonance": "Resonances",
             "driveline-stability": "Stability and resonances",
             "driveline-map": "Stability map", "driveline-run-up": "Run-up"}
"""entry -> the title of its own figures' table"""


def ranges(pairs, unit: str) -> str:
    """``[[3525, 3625], [3800, 3800]]`` -> ``"3525–3625 rpm, 3800–3800 rpm"``; none:
    "none"."""
    if not pairs:
        return "none"
    return ", ".join(f"{number(a)}–{number(b)} {unit}" for a, b in pairs)


def value_text(figure) -> str:
    """A summary figure's value for a table: a number (``format.number``), a flag yes/no,
    the unstable speed ranges as text, a list of numbers."""
    value = figure.value
    if figure.name == "unstable_rpm":
        return ranges(value, figure.unit)
    if isinstance(value, (list, tuple)):
        return ", ".join(number(v) for v in value) or MISSING
    text = number(value)
    if figure.limit is not None:
        text += f" (limit {number(figure.limit)})"
    return text


def summary_table(title: str, figures) -> Table:
    """figure | value | unit | where | meaning of ``figures`` (``Figure``s): the name as
    the JSON document has it; a flag's yes/no and the speed ranges without a unit of
    their own."""
    out = Table(title=title, title_justify="left")
    out.add_column("figure")
    out.add_column("value", justify="right")
    out.add_column("unit")
    out.add_column("where")
    out.add_column("meaning")
    for figure in figures:
        unit = "" if figure.name == "unstable_rpm" or figure.unit == FLAG else figure.unit
        out.add_row(figure.name, value_text(figure), unit, where(figure.where),
                    figure.description.strip())
    return out


def frequency_table(outcome) -> Table:
    """ω̄, its range, J̄, Ω, η and the VDI 2149 verdict of any drive-line Outcome."""
    return summary_table("Natural frequency, VDI 2149",
                         [outcome.summary[name] for name in FREQUENCY if name in outcome.summary])


def own_table(outcome) -> Table | None:
    """The entry's own figures (all but the natural frequency's)."""
    figures = [figure for name, figure in outcome.summary.items() if name not in FREQUENCY]
    return summary_table(SUMMARIES[outcome.analysis], figures) if figures else None


def tables(outcome, columns: bool = True) -> list:
    """The tables of a drive-line Outcome: the natural frequency, its own figures, and
    (with ``columns``) its columns."""
    parts = [frequency_table(outcome), own_table(outcome)]
    if columns:
        parameter = next((n for n in ("stiffness", "damping") if n in outcome.columns), "")
        parts.append(columns_table(outcome, TITLES[outcome.analysis].format(parameter=parameter),
                                   most=61))  # a revolution of 720 steps: every 12th (6°)
    return [part for part in parts if part is not None]
