"""CSV writer on data other than dyade-16's columns (issue 17), disabled in the normal test
run (each body runs once as a smoke test); the block writer and the row-by-row writer it
replaced, on the same table, in one run:

    pytest tests/benchmarks/test_csv_writer.py --benchmark-enable --benchmark-columns=min,median,rounds

- "wide": 100 000 values of every magnitude 1e-30..1e30 (half of them in exponent
  notation), with 5 % zeros and 5 % NaN;
- "short": 100 000 integers and decimals of 1 to 3 places (trailing zeros trimmed, the
  decimal point in every place).
(dyade-16's own columns: ``test_csv_writer_dyade16_3600`` in test_benchmarks.py.)
"""

from __future__ import annotations

import io

import numpy as np
import pytest

from dyade.report import csv_rows
from tests.benchmarks import old_csv


def _table(kind: str) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(17)
    if kind == "wide":
        values = rng.standard_normal(100_000) * 10.0 ** rng.integers(-30, 30, 100_000)
        values[rng.random(values.size) < 0.05] = 0.0
        values[rng.random(values.size) < 0.05] = np.nan
    else:
        scale = 10.0 ** rng.integers(0, 4, 100_000)
        values = np.round(rng.standard_normal(100_000) * 1e3 * scale) / scale
    table = values.reshape(-1, 20)
    return {f"c{k}": table[:, k] for k in range(table.shape[1])}


@pytest.mark.parametrize("writer", ["row by row (before issue 17)", "blocks"])
@pytest.mark.parametrize("kind", ["wide", "short"])
def test_csv_writer(benchmark, kind, writer):
    cols = _table(kind)
    write = old_csv.write if writer.startswith("row") else csv_rows.write

    def run():
        out = io.StringIO()
        write(cols, out)
        return out

    assert benchmark(run).getvalue().count("\n") == 5001
