"""The row-by-row CSV writer dyade had before issue 17: the yardstick of the block writer
(speed in tests/benchmarks, bytes in tests/report/test_csv.py)."""

from __future__ import annotations

from typing import TextIO

import numpy as np

from dyade.linkage.columns import Columns


def write(cols: Columns, out: TextIO) -> None:
    """Write the columns as CSV; NaN (no value at that position) becomes an empty field."""
    names = list(cols)
    out.write(",".join(names) + "\n")
    if not names:
        return
    table = np.column_stack([np.asarray(cols[name], dtype=np.float64) for name in names])
    table = table + 0.0  # no "-0" in the output
    row_format = ",".join(["%.15g"] * len(names))
    lines = [row_format % row for row in map(tuple, table.tolist())]
    text = "\n".join(lines)
    if np.isnan(table).any():
        # fields are separated by commas, so "nan" only ever stands for a whole field
        text = text.replace("nan", "")
    out.write(text)
    out.write("\n")
