"""The block CSV writer (issue 17) writes exactly the bytes of the row-by-row writer it
replaced ("%.15g", empty field for NaN, no "-0"): on every shipped mechanism, and on
random arrays built to hit every branch of its digit arithmetic."""

from __future__ import annotations

import io

import numpy as np
import pytest
from hypothesis import given, strategies as st

import dyade
from dyade.report import csv_rows
from tests.benchmarks import old_csv
from tests.helpers import ROOT


def _both(cols) -> tuple[str, str]:
    old, new = io.StringIO(), io.StringIO()
    old_csv.write(cols, old)
    csv_rows.write(cols, new)
    return old.getvalue(), new.getvalue()


def _assert_same(new: str, old: str) -> None:
    """new == old; a failure shows the first differing line and field (pytest's diff of
    two long texts would take minutes)."""
    if new == old:
        return
    lines = new.split("\n"), old.split("\n")
    row = next((k for k, pair in enumerate(zip(*lines)) if pair[0] != pair[1]),
               min(map(len, lines)))
    fields = [line[row].split(",") if row < len(line) else [] for line in lines]
    column = next((k for k, pair in enumerate(zip(*fields)) if pair[0] != pair[1]),
                  min(map(len, fields)))
    assert (row, column, fields[0][column:column + 1]) == (row, column,
                                                           fields[1][column:column + 1])
    assert len(lines[0]) == len(lines[1])


@pytest.mark.parametrize("path", sorted((ROOT / "mechanisms").glob("*.toml")),
                         ids=lambda p: p.name)
def test_shipped_mechanisms_byte_identical(path):
    cols = dyade.analyse(dyade.read_mechanism(path), allow_partial=True).columns()
    old, new = _both(cols)
    _assert_same(new, old)


def _awkward(rng, rows: int) -> np.ndarray:
    """Columns of every kind: wide magnitudes, integers, exact decimals, -0.0, NaN, ±inf,
    powers of ten and their neighbours, subnormals, 15-digit midpoints."""
    cols = [rng.standard_normal(rows) * 10.0 ** rng.integers(-30, 30, rows),
            rng.standard_normal(rows) * 10.0 ** rng.integers(-324, 308, rows),
            np.round(rng.standard_normal(rows) * 1e6),
            np.round(rng.standard_normal(rows) * 1e3, 3),
            np.arange(rows) * 0.1,
            rng.integers(-10 ** 17, 10 ** 17, rows).astype(np.float64),
            np.where(rng.random(rows) < 0.5, -0.0, 0.0),
            np.where(rng.random(rows) < 0.3, np.nan, rng.standard_normal(rows)),
            rng.choice([np.inf, -np.inf, 1.0, np.nan], rows),
            10.0 ** rng.integers(-20, 20, rows),
            np.nextafter(10.0 ** rng.integers(-20, 20, rows), rng.choice([0.0, np.inf], rows)),
            rng.choice([5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                        -1e-310, 123456789012345.5, 0.5, 1e15, 999999999999999.9,
                        1.000000000000005, 9.9999999999999995, 1e-4, 9.99999999999999e-5,
                        99999999999999.95, 1e16 + 2.0], rows),
            (rng.integers(10 ** 14, 10 ** 15, rows) + 0.5) * 10.0 ** rng.integers(-20, 5, rows)]
    return np.column_stack(cols)


@pytest.mark.parametrize("seed", range(4))
def test_random_arrays_byte_identical(seed):
    rng = np.random.default_rng(seed)
    table = _awkward(rng, 20_000)
    cols = {f"c{k}": table[:, k] for k in range(table.shape[1])}
    old, new = _both(cols)
    _assert_same(new, old)


@pytest.mark.parametrize("shape", [(0, 3), (1, 1), (3, 0), (7, 5000)])
def test_edge_shapes(shape):
    rng = np.random.default_rng(1)
    table = rng.standard_normal(shape) * 1e3
    cols = {f"c{k}": table[:, k] for k in range(shape[1])}
    old, new = _both(cols)
    _assert_same(new, old)


def test_blocks_stream_the_same_text():
    """Rows written block by block (any split) give the whole table's text."""
    rng = np.random.default_rng(2)
    table = _awkward(rng, 1000)
    names = [f"c{k}" for k in range(table.shape[1])]
    whole = io.StringIO()
    csv_rows.write(dict(zip(names, table.T)), whole)
    streamed = io.StringIO()
    writer = csv_rows.Writer(names, streamed)
    writer.header()
    for first, last in ((0, 1), (1, 2), (2, 500), (500, 1000)):
        writer.rows(table[first:last])
    writer.close()
    _assert_same(streamed.getvalue(), whole.getvalue())


def test_python_path(monkeypatch):
    """Values outside the numpy path's range are formatted by Python: with an empty range,
    every value but zero and NaN is."""
    monkeypatch.setattr(csv_rows, "_SMALLEST", np.inf)
    rng = np.random.default_rng(3)
    table = _awkward(rng, 300)
    old, new = _both({f"c{k}": table[:, k] for k in range(table.shape[1])})
    _assert_same(new, old)


def test_big_endian_fallback(monkeypatch):
    """Where words are not little-endian, Python formats every value."""
    monkeypatch.setattr(csv_rows, "_LITTLE_ENDIAN", False)
    table = _awkward(np.random.default_rng(4), 300)
    old, new = _both({f"c{k}": table[:, k] for k in range(table.shape[1])})
    _assert_same(new, old)


def _table(values: np.ndarray, width: int) -> dict[str, np.ndarray]:
    rows = -(-values.size // width)
    table = np.resize(values, rows * width).reshape(rows, width)
    return {f"c{k}": table[:, k] for k in range(width)}


def test_edges_of_the_numpy_path():
    """Around the bounds of the numpy range, the ends of the exponent tables, the
    fixed/exponent notation switch and the powers of ten (log10 one off, 9.99…95 carrying
    into the next power): every neighbour within 3 ulps."""
    centres = np.array([csv_rows._SMALLEST, csv_rows._LARGEST, 1e-291, 1e-289, 1e299, 1e301]
                       + [10.0 ** k for k in range(-22, 23)]
                       + [9.999999999999995 * 10.0 ** k for k in range(-20, 20)]
                       + [5 * 10.0 ** k for k in range(-20, 20)])
    values = [centres]
    for _ in range(3):
        values = [np.nextafter(values[0], 0.0), *values, np.nextafter(values[-1], np.inf)]
    values = np.concatenate(values)
    old, new = _both(_table(np.concatenate([values, -values]), 7))
    _assert_same(new, old)


FLOATS = st.integers(0, 2 ** 64 - 1).map(lambda bits: np.uint64(bits).view(np.float64))


@given(st.lists(FLOATS, min_size=1, max_size=400), st.integers(1, 9))
def test_random_bit_patterns(values, width):
    """Any float64 (every exponent, sign, NaN payload), in any number of columns."""
    old, new = _both(_table(np.array(values), width))
    _assert_same(new, old)


@given(st.lists(st.floats(width=64), min_size=1, max_size=400), st.integers(1, 9))
def test_hypothesis_floats(values, width):
    """Hypothesis' floats lean to the awkward ones: ±0, ±inf, NaN, the smallest and
    largest, integers, simple decimals."""
    old, new = _both(_table(np.array(values, dtype=np.float64), width))
    _assert_same(new, old)
