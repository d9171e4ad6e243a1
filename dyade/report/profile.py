"""A ``profile`` Outcome (``dyade.analyses.profile``) -> rich tables: the segments with
their laws, classes, characteristic values and peaks, and the motion over the cycle."""

from __future__ import annotations

import numpy as np

from dyade.report.format import number, ordinal

ROWS = 40
"""about this many rows of the motion in a table (every k-th; CSV has all)"""


def tables(outcome) -> list:
    """The segments' table, the profile's peaks and the motion (every k-th row)."""
    from rich.table import Table

    from dyade.analyses.profile import MASTER_WORDS, OUTPUT_WORDS
    from dyade.files.profile import MASTER_UNITS, output_factor

    profile, _, _, _ = outcome.result
    x_word = MASTER_WORDS[MASTER_UNITS[profile.master][0]]
    x_size = MASTER_UNITS[profile.master][1]
    s_word = OUTPUT_WORDS[profile.unit]
    s_size = output_factor(profile.unit)
    units = outcome.units
    period = f"{number(profile.period / x_size)}{'' if x_word == '°' else ' '}{x_word}"
    segments = Table(title=f"Motion profile: {profile.name} (one cycle of {period})",
                     title_justify="left")
    for head in ("#", "kind", "law", f"master [{x_word}]", f"lift [{s_word}]", "classes",
                 "C_v", "C_a", "C_j", "C_M", f"|v| max [{units['v']}]",
                 f"|a| max [{units['a']}]", f"|j| max [{units['j']}]"):
        segments.add_column(head, justify="left" if head in ("kind", "law", "classes")
                            else "right")
    value = outcome.value
    for k, segment in enumerate(profile.segments, start=1):
        law = value(f"segment{k}_law")
        row = [str(k), segment.kind, law or "—",
               f"{number(segment.start / x_size)}–{number(segment.end / x_size)}",
               f"{number(segment.lift_from / s_size)}–{number(segment.lift_to / s_size)}"
               if law else number(segment.lift_from / s_size),
               value(f"segment{k}_boundary") or "R-R"]
        row += [number(value(f"segment{k}_{n}"), spec=".5g") if law else "—"
                for n in ("C_v", "C_a", "C_j", "C_M")]
        row += [number(value(f"segment{k}_{s}_max"), spec=".5g") if law else "0"
                for s in ("v", "a", "j")]
        segments.add_row(*row)
    peaks = Table(title="Peaks of the profile", title_justify="left")
    for head in ("quantity", "value", "unit", "where"):
        peaks.add_column(head, justify="right" if head == "value" else "left")
    master = next(n for n in outcome.columns if n in ("time_s", "angle_deg")
                  and (n == "time_s" or "time_s" not in outcome.columns))
    for symbol, words in (("v", "velocity"), ("a", "acceleration"), ("j", "jerk (inside)")):
        figure = outcome.summary[f"{symbol}_max"]
        where = figure.where or {}
        peaks.add_row(f"peak |{symbol}|, {words}", number(figure.value, spec=".5g"),
                      figure.unit, f"segment {where.get('segment')}, near "
                      f"{number(where.get(master), spec='.6g')}"
                      f"{'' if units[master] == '°' else ' '}{units[master]}")
    cols = outcome.columns
    rows = len(cols["s"])
    stride = max(1, int(np.ceil(rows / ROWS)))
    note = (f" ({rows} rows, every {ordinal(stride)} shown; --format csv for all)"
            if stride > 1 else "")
    motion = Table(title="Motion over the cycle" + note, title_justify="left")
    names = [n for n in cols if n != "segment"] + ["segment"]
    heads = {"angle_deg": "angle [°]", "time_s": "time [s]", "segment": "segment"}
    scale = {n: float(np.max(np.abs(cols[n]))) if rows else 0.0 for n in names}
    for name in names:
        motion.add_column(heads.get(name, f"{name} [{units[name]}]"), justify="right")
    for k in list(range(0, rows, stride)) + ([rows - 1] if (rows - 1) % stride else []):
        motion.add_row(*[str(int(cols[n][k])) if n == "segment"
                         else number(float(cols[n][k]), scale[n], ".6g") for n in names])
    return [segments, peaks, motion]
