"""The JSON writer's parts: the columns of a document written a column and a block of
values at a time (``write_columns``, for columns kept on disk), numbers as the CSV
writes them (``json_numbers``).

The document itself is ``Outcome.to_document()`` (docs/reference/json.md); numbers are
written as in the CSV (15 significant digits), NaN and infinities as null
(``dyade.analyses.base.jsonable``).
"""

from __future__ import annotations

import math


CHUNK = 1 << 16
"""values formatted and written at a time"""


def json_numbers(values, writer: JsonNumbers | None = None) -> list[str]:
    """float64 values as JSON numbers, exactly as ``json.dumps`` writes
    ``float(f"{v + 0.0:.15g}")`` (and null for NaN and ±inf), a block at a time.

    The 15-digit text of the CSV writer (``report.csv_rows``) is that number's shortest
    text already (two decimals of at most 15 digits are never the same normal double),
    but for: a whole number, which gets ".0" (``90`` → ``90.0``); 10¹⁵ ≤ |v| < 10¹⁶,
    written without an exponent (``1.5e+15`` → ``1500000000000000.0``); subnormals
    (below 10⁻³⁰⁸ a double holds fewer digits: Python's shortest text); and
    ±1.79769313486232e+308, which reads back as infinity: null, as NaN and ±inf.

    >>> import numpy as np
    >>> json_numbers(np.array([90.0, -0.0, 0.1 + 0.2, 1.5e15, 2e-7, np.nan, -np.inf]))
    ['90.0', '0.0', '0.3', '1500000000000000.0', '2e-07', 'null', 'null']

    ``writer``: a ``JsonNumbers`` to reuse (the columns of one document): its work
    arrays (about 2 MB) are then allocated once, not once per column.
    """
    lines = (writer or JsonNumbers()).lines(values)
    return [text if ("." in text or "e" in text) and "e+15" not in text
            and "e+308" not in text and "e-3" not in text else _number(text)
            for text in lines]


class JsonNumbers:
    """The CSV writer of ``json_numbers``, one value a line, its work arrays kept from one
    call to the next."""

    def __init__(self) -> None:
        import io

        from dyade.report import csv_rows

        self.buffer = io.StringIO()
        self.writer = csv_rows.Writer(["value"], self.buffer)

    def lines(self, values) -> list[str]:
        """The CSV writer's text of each value (NaN: empty)."""
        import numpy as np

        self.buffer.seek(0)
        self.buffer.truncate()
        self.writer.rows(np.asarray(values, dtype=np.float64).reshape(-1, 1))
        lines = self.buffer.getvalue().split("\n")
        lines.pop()
        return lines


def _number(text: str) -> str:
    """The rare cases: whole numbers, 10¹⁵..10¹⁶, exponents −30..−39 and −300.. (below
    10⁻³⁰⁸ a double has fewer than 15 digits: Python writes fewer), and what is not a
    finite number (NaN, ±inf, and 1.79769313486232e+308, which reads back as inf):
    null."""
    if not text or text.endswith("inf"):
        return "null"
    if "e" not in text:
        return text + ".0"
    value = float(text)
    return repr(value) if math.isfinite(value) else "null"


def write_columns(columns, handle) -> None:
    """``"columns": {...}`` of a document as ``json.dumps(..., indent=1)`` writes it
    there (one value a line), a column and a block of values at a time: the columns may
    be a ``Spool`` that reads each back from disk."""
    import json

    import numpy as np

    names = list(columns)
    if not names:
        handle.write(' "columns": {}')
        return
    handle.write(' "columns": {\n')
    numbers = JsonNumbers()
    for k, name in enumerate(names):
        values = np.asarray(columns[name], dtype=np.float64)
        handle.write(f"  {json.dumps(name, ensure_ascii=False)}: ")
        if values.size == 0:
            handle.write("[]")
        else:
            handle.write("[\n   ")
            for first in range(0, values.size, CHUNK):
                if first:
                    handle.write(",\n   ")
                handle.write(",\n   ".join(json_numbers(values[first:first + CHUNK], numbers)))
            handle.write("\n  ]")
        handle.write(",\n" if k < len(names) - 1 else "\n")
    handle.write(" }")
