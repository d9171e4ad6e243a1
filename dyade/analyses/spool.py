"""The columns of a sweep in blocks, kept in a temporary file instead of memory: the
columns of a ``sweep`` Outcome (``dyade.analyses.sweep``), which every writer reads one
column at a time."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping

import numpy as np

from dyade.arrays import FloatArray


class Spool(Mapping):
    """The columns of a streamed sweep kept in a temporary file instead of memory: each
    block is appended as it comes (``add``), and ``spool[name]`` reads one whole column
    back (8 B per position). What needs a whole column (the JSON's arrays, the summary's
    extremes, means and time ratios) takes them one at a time, with the very functions
    the whole sweep uses, so the results are the same to the last bit.

    The file is in the temporary folder (``TMPDIR``): 8 B per value, e.g. 786 MB for
    dyade-16's 273 columns at 360 000 positions; it is deleted on ``close`` (or when
    the spool is collected).

    >>> import dyade
    >>> run = dyade.analyse_in_blocks(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...                               block_size=100)
    >>> with Spool(block.columns for block in run) as spool:
    ...     print(len(spool), spool["angle_deg"][[0, -1]])
    63 [  0. 360.]
    """

    float_columns = True
    """every column is a 1-D float64 array"""

    def __init__(self, blocks: Iterable[Mapping[str, FloatArray]]) -> None:
        import tempfile

        self.file = tempfile.TemporaryFile(prefix="dyade-spool-")
        self.names: list[str] = []
        self.where: dict[str, int] = {}
        self.blocks: list[tuple[int, int]] = []
        """(offset [B], rows) of every block: its columns one after another"""
        self.rows = 0
        self.kept: dict[str, FloatArray] = {}
        """the column read last (a table or the summary often asks for it twice running)"""
        for block in blocks:
            self.add(block)

    def add(self, block: Mapping[str, FloatArray]) -> None:
        if not self.names:
            self.names = list(block)
            self.where = {name: k for k, name in enumerate(self.names)}
        rows = int(np.shape(block[self.names[0]])[0])
        table = np.empty((len(self.names), rows))
        for k, name in enumerate(self.names):
            table[k] = block[name]
        self.blocks.append((self.file.tell(), rows))
        self.file.write(table.data)
        self.rows += rows

    def __getitem__(self, name: str) -> FloatArray:
        if name in self.kept:
            return self.kept[name]
        k = self.where[name]
        out = np.empty(self.rows)
        row = 0
        for offset, rows in self.blocks:
            self.file.seek(offset + 8 * k * rows)
            self.file.readinto(memoryview(out[row:row + rows]).cast("B"))
            row += rows
        self.file.seek(0, 2)
        self.kept = {name: out}
        return out

    def parts(self, names: list[str] | None = None) -> Iterator[dict[str, FloatArray]]:
        """The columns ``names`` (all) block by block, as they were added."""
        names = self.names if names is None else names
        for offset, rows in self.blocks:
            table = np.empty((len(self.names), rows))
            self.file.seek(offset)
            self.file.readinto(memoryview(table).cast("B"))
            yield {name: table[self.where[name]] for name in names}
        self.file.seek(0, 2)

    def __iter__(self) -> Iterator[str]:
        return iter(self.names)

    def __contains__(self, name: object) -> bool:  # (Mapping's would read the column)
        return name in self.where

    def __len__(self) -> int:
        return len(self.names)

    def close(self) -> None:
        self.file.close()

    def __del__(self) -> None:  # collected: the temporary file goes with it
        file = getattr(self, "file", None)
        if file is not None:
            file.close()

    def __enter__(self) -> "Spool":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
