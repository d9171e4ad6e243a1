"""Columns -> CSV text: header line, one row per crank position, full precision."""

from __future__ import annotations

from typing import TextIO

import numpy as np

from dyade.report.columns import Columns


def write(cols: Columns, out: TextIO) -> None:
    """Write the columns as CSV; NaN (invalid positions) becomes an empty field."""
    names = list(cols)
    out.write(",".join(names) + "\n")
    if not names:
        return
    table = np.column_stack([np.asarray(cols[name], dtype=np.float64) for name in names])
    text = np.char.mod("%.15g", table)
    text[np.isnan(table)] = ""
    out.write("\n".join(",".join(row) for row in text.tolist()))
    out.write("\n")
