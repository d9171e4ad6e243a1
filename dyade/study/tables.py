"""A study's table on disk: the CSV journal it streams to block by block (and reads
back to resume), by the one cell rule of every CSV dyade writes
(``dyade.analyses.base.cell``: 15 significant digits, an empty cell for a value not
given, flags 1/0), and Parquet with the units in the schema's metadata. Also
``write_parquet`` for any named columns (``dyade analyse -o sweep.parquet``)."""

from __future__ import annotations

import csv
import json
import os

import numpy as np

from dyade.analyses.base import cell
from dyade.errors import InputError

TEXT = ("status", "reason")
"""the columns that hold words; ``variant`` holds whole numbers, the others numbers"""


def header(parameters: list[str], outputs: list[str]) -> list[str]:
    return ["variant", *parameters, "status", "reason", *outputs]


class Journal:
    """The CSV a study streams to: a header, then one line per variant, a block at a
    time, flushed, each value by the one cell rule (``cell``); ``done``: the rows
    already there (``--resume``), as ``typed`` gives them. Without a path, nothing is
    written (the rows are the caller's)."""

    def __init__(self, path: str | None, names: list[str], resume: bool,
                 label: str = "study", words: tuple[str, ...] = ()) -> None:
        self.path, self.names = path, names
        self.done: dict[int, list] = {}
        self.handle = None
        if path is None:
            return
        if resume and os.path.exists(path) and os.path.getsize(path) > 0:
            self.done = {index: typed(names, row, words)
                         for index, row in _read_rows(path, names, label).items()}
            self._trim()
            self.handle = open(path, "a", newline="", encoding="utf-8")
        else:
            self.handle = open(path, "w", newline="", encoding="utf-8")
            self.handle.write(line(names))
            self.handle.flush()

    def _trim(self) -> None:
        """Cut a last line that an interruption left without its end."""
        with open(self.path, "rb+") as handle:
            data = handle.read()
            if data and not data.endswith(b"\n"):
                handle.truncate(data.rfind(b"\n") + 1)

    def write(self, rows: list[list]) -> None:
        """Rows of typed values (the variant, the parameters, status and reason, the
        outputs), each value by the one cell rule (``cell``)."""
        if self.handle is None:
            return
        self.handle.write("".join(line(row) for row in rows))
        self.handle.flush()

    def close(self) -> None:
        if self.handle is not None:
            self.handle.close()


def line(values) -> str:
    """One CSV line of values by the one cell rule (``cell``)."""
    return ",".join(cell(value) for value in values) + "\n"


def same(written, value) -> bool:
    """Whether a number read back from a CSV (15 significant digits) is ``value``'s (a
    name: the same name)."""
    return cell(written) == cell(value)


def typed(names: list[str], row: list[str], words: tuple[str, ...] = ()) -> list:
    """A row of the CSV as values: the variant an int, the words (``TEXT`` and the
    categorical parameters ``words``) as they are, the rest floats (an empty cell NaN)."""
    return [int(v) if name == "variant" else v if name in TEXT or name in words
            else _number(v) for name, v in zip(names, row)]


def _number(text: str):
    """A cell as a float (empty: NaN); a name (a categorical parameter's) as it is."""
    if text == "":
        return np.nan
    try:
        return float(text)
    except ValueError:
        return text


def _read_rows(path: str, names: list[str], label: str) -> dict[int, list[str]]:
    with open(path, newline="", encoding="utf-8") as handle:
        lines = handle.read().split("\n")
    if lines and lines[-1] != "":  # a line cut short by an interruption
        lines = lines[:-1]
    reader = csv.reader(lines)
    try:
        first = next(reader)
    except StopIteration:
        return {}
    if first != names:
        raise InputError(f"{label}: resuming: {path} holds other columns than this study "
                         f"gives (another study, or the study file changed); remove it or "
                         f"write elsewhere.", source=path)
    done = {}
    for row in reader:
        if len(row) == len(names):
            done[int(row[0])] = row
    return done


def read_csv(path: str) -> dict[str, np.ndarray]:
    """A study's CSV as named columns (numbers as floats, ``variant`` as integers)."""
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    values = [typed(rows[0], row) for row in rows[1:]]
    words = tuple(name for k, name in enumerate(rows[0])
                  if any(isinstance(row[k], str) for row in values))
    return columns_of(rows[0], values, words)


def columns_of(names: list[str], rows: list[list], words: tuple[str, ...] = ()
               ) -> dict[str, np.ndarray]:
    """Typed rows (``typed``) as named columns, in the order of their variants (the
    words of ``TEXT`` and ``words``, a categorical parameter's names, as objects)."""
    rows = sorted(rows, key=lambda r: r[0])
    out: dict[str, np.ndarray] = {}
    for k, name in enumerate(names):
        values = [r[k] for r in rows]
        if name == "variant":
            out[name] = np.array(values, dtype=np.int64)
        elif name in TEXT or name in words:
            out[name] = np.array(values, dtype=object)
        else:
            out[name] = np.array(values, dtype=float)
    return out


def write_parquet(columns, units: dict[str, str], path: str,
                  metadata: dict[str, str] | None = None) -> None:
    """Named columns as a Parquet file (the ``parquet`` extra, pyarrow): each column's
    unit in its field's metadata (``unit``) and all of them, as JSON, in the schema's
    (``dyade.units``)."""
    from dyade.study.spec import needs

    needs("pyarrow", "Parquet tables", extra="parquet")
    import pyarrow as pa
    import pyarrow.parquet as pq

    fields, arrays = [], []
    for name in columns:
        values = np.asarray(columns[name])
        array = pa.array(values.tolist() if values.dtype == object else values)
        fields.append(pa.field(name, array.type, metadata={"unit": units.get(name, "")}))
        arrays.append(array)
    meta = {"dyade.units": json.dumps({n: units.get(n, "") for n in columns})}
    meta.update(metadata or {})
    table = pa.Table.from_arrays(arrays, schema=pa.schema(fields, metadata=meta))
    partial = f"{path}.partial"
    try:
        pq.write_table(table, partial)
        os.replace(partial, path)
    finally:
        if os.path.exists(partial):
            os.unlink(partial)
