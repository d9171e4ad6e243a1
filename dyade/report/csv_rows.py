"""Columns -> CSV text: header line, one row per crank position, 15 significant digits.

The numbers are written exactly as ``"%.15g" % value`` writes them (with ``-0`` written
``0`` and NaN an empty field), but formatted a block of rows at a time in numpy instead
of one Python string per value (about 10x faster; ``tests/benchmarks`` measure it
against the row-by-row writer it replaces):

1. the 15 significant digits of ``|x|`` are the integer ``q = round(|x| · 10^(14−e))``
   with ``e`` the decimal exponent, computed in extended precision (``np.longdouble``,
   64-bit mantissa on x86: its error is below 10⁻⁴ of a unit of ``q``). A value whose
   product lies within ``_TIE`` of a rounding midpoint (about 1 in 500), and ±inf, are
   formatted by Python's ``"%.15g"`` itself, so the result never depends on that error.
   Where ``np.longdouble`` is no wider than a double, every value takes that path
   (correct, only slower);
2. every value gets a scratch row of 48 bytes at fixed places, written as 64-bit words
   from small tables: sign and "0.000" prefix, the digits (from a table of the 10 000
   four-digit groups) each followed by a place for the decimal point, the exponent
   ("e-05"), the separator. What a value does not show (trailing zeros, the decimal
   point's unused places, the exponent in fixed notation) is a NUL byte;
3. the block's bytes with the NULs dropped (``bytes.translate``) are its CSV text.

``Writer`` streams: ``header()`` once, then ``rows(block)`` for every block of rows as
soon as it is computed; ``write`` is the whole table at once.
"""

from __future__ import annotations

from typing import TextIO

import numpy as np

from dyade.linkage.columns import Columns

FIELDS_PER_BLOCK = 16384
"""values formatted at once: the scratch arrays (about 120 B per value) stay in the L2 cache"""
ROW = 48
"""bytes of a value's scratch row: sign and "0.000" prefix (0..7), the 16 digit places
each followed by a place for the decimal point (8..39), exponent (40..44), separator (47)"""
_SEP = 47


def _words(texts) -> np.ndarray:
    """8-byte texts (NUL-padded) as uint64 words, in memory order."""
    raw = b"".join(t.encode("ascii").ljust(8, b"\0") for t in texts)
    return np.frombuffer(raw, dtype=np.uint64).copy()


_GROUP = np.arange(10_000)
_DIGIT_BYTES = np.zeros((10_000, 8), dtype=np.uint8)
_DIGIT_BYTES[:, 0::2] = (_GROUP[:, None] // np.array([1000, 100, 10, 1]) % 10) + ord("0")
_DIGITS = _DIGIT_BYTES.view(np.uint64).reshape(-1)
"""four digits of 0..9999, each followed by an empty decimal-point place (as 8 bytes)"""
_DIGIT_BYTES = _DIGIT_BYTES.copy()
_DIGIT_BYTES[:, 0] = 0
_FIRST = _DIGIT_BYTES.view(np.uint64).reshape(-1)
"""the same with the first digit left out (the leading group holds 3 digits)"""
_PREFIX = _words([sign + lead for sign in ("", "-")
                  for lead in ("", "0.", "0.0", "0.00", "0.000")])
"""sign and, for decimal exponents −1..−4, "0." and the zeros after it"""
_EXPONENT = _words([""] + [f"e{e:+03d}" for e in range(-399, 401)])
"""exponent text of 10^e at e + 400 (entry 0: fixed notation, no exponent)"""
_KEEP = np.zeros((4, 17), dtype=np.uint64)
"""per count c of digits shown: the bytes of the digit places to keep (the first c
digits and every decimal-point place)"""
for _c in range(17):
    _mask = bytearray(32)
    for _place in range(16):
        _mask[2 * _place + 1] = 0xFF
        if 1 <= _place <= _c:
            _mask[2 * _place] = 0xFF
    _KEEP[:, _c] = np.frombuffer(bytes(_mask), dtype=np.uint64)
_TRAILING = sum((_GROUP % 10 ** k == 0).astype(np.int64) for k in range(1, 5))
"""trailing zeros of the four-digit groups (4 for 0)"""
_POWERS = np.array([np.longdouble(f"1e{k}") for k in range(-310, 350)])
"""10^k for k = −310..349, correctly rounded to np.longdouble (strtold)"""
_TIE = 1e-3
"""how near a rounding midpoint (in units of the 15th digit) a value is left to Python"""
_EXACT = float(np.finfo(np.longdouble).eps) * 1e15 * 8 < _TIE
"""np.longdouble is wide enough for the vectorised digits (x86: 80-bit)"""


def _digits(magnitude: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """15-digit integer q in [10^14, 10^15), decimal exponent and "near a midpoint" of
    finite positive values."""
    exponent = np.floor(np.log10(magnitude)).astype(np.int64)
    scaled = magnitude.astype(np.longdouble)
    scaled *= _POWERS[324 - exponent]
    q = scaled.astype(np.int64)  # positive: truncation is floor (np.floor of longdouble is slow)
    fraction = (scaled - q.astype(np.longdouble)).astype(np.float64)
    wrong = (q >= 10 ** 15) | (q < 10 ** 14)  # log10 is off by one next to a power of ten
    if wrong.any():
        exponent[wrong] += np.where(q[wrong] >= 10 ** 15, 1, -1)
        again = magnitude[wrong].astype(np.longdouble) * _POWERS[324 - exponent[wrong]]
        q[wrong] = again.astype(np.int64)
        fraction[wrong] = (again - q[wrong].astype(np.longdouble)).astype(np.float64)
    tie = np.abs(fraction - 0.5) < _TIE
    q += fraction > 0.5
    carry = q == 10 ** 15  # 9.999…95 rounds up to the next power of ten
    if carry.any():
        q[carry] = 10 ** 14
        exponent[carry] += 1
    return q, exponent, tie


def _format(values: np.ndarray, separators: np.ndarray) -> bytes:
    """The "%.15g" texts of ``values`` (flat), each followed by its separator byte."""
    count = values.size
    values = values + 0.0  # no "-0"
    finite = np.isfinite(values)
    nonzero = finite & (values != 0.0)
    magnitude = np.abs(np.where(nonzero, values, 1.0))
    if _EXACT:
        q, exponent, python = _digits(magnitude)
        python |= ~finite
        python &= ~np.isnan(values)
    else:
        q, exponent = np.zeros(count, np.int64), np.zeros(count, np.int64)
        python = ~np.isnan(values)
    q[~nonzero] = 0
    exponent[~nonzero] = 0
    scratch = np.empty((count, ROW), dtype=np.uint8)
    words = scratch.view(np.uint64)
    groups = (q // 10 ** 12, q // 10 ** 8 % 10_000, q // 10 ** 4 % 10_000, q % 10_000)
    trailing = _TRAILING[groups[3]]
    run = groups[3] == 0
    for group in groups[2::-1]:  # a whole group of zeros: count on in the next one
        trailing += run * _TRAILING[group]
        run &= group == 0
    significant = np.maximum(15 - trailing, 1)
    fixed = (exponent >= -4) & (exponent < 15)
    whole = fixed & (exponent >= 0)
    shown = np.where(whole, np.maximum(significant, exponent + 1), significant)
    words[:, 0] = _PREFIX[(values < 0) * 5 + np.where(fixed & ~whole, -exponent, 0)]
    for k, group in enumerate(groups):
        words[:, k + 1] = np.bitwise_and((_DIGITS if k else _FIRST)[group], _KEEP[k][shown])
    words[:, 5] = _EXPONENT[np.where(fixed, 0, exponent + 400)]
    scratch[:, _SEP] = separators
    point = np.where(fixed, exponent, 0)
    dotted = np.flatnonzero(np.where(fixed, whole & (significant > exponent + 1), significant > 1))
    scratch.reshape(-1)[dotted * ROW + 11 + 2 * point[dotted]] = 46  # "."
    words[np.isnan(values), :5] = 0  # the empty field
    for k in np.flatnonzero(python):
        text = ("%.15g" % float(values[k])).encode()
        scratch[k, :_SEP] = 0
        scratch[k, :len(text)] = np.frombuffer(text, dtype=np.uint8)
    return scratch.tobytes().translate(None, b"\0")


class Writer:
    """CSV to ``out`` block by block: the header, then ``rows(block)`` as they come."""

    def __init__(self, names: list[str], out: TextIO) -> None:
        self.names = list(names)
        self.out = out
        self.written = 0
        """rows written"""
        separators = np.full(len(self.names), ord(","), dtype=np.uint8)
        if self.names:
            separators[-1] = ord("\n")
        self.separators = separators

    def header(self) -> None:
        self.out.write(",".join(self.names) + "\n")

    def rows(self, block: Columns | np.ndarray) -> None:
        """Write a block of rows: the columns by name (in ``names`` order), or a
        (rows, columns) array."""
        if isinstance(block, dict):
            block = np.column_stack([np.asarray(block[name], dtype=np.float64)
                                     for name in self.names]) if self.names else np.zeros((0, 0))
        table = np.asarray(block, dtype=np.float64)
        if not self.names or table.shape[0] == 0:
            return
        step = max(1, FIELDS_PER_BLOCK // len(self.names))
        for first in range(0, table.shape[0], step):
            part = table[first:first + step]
            separators = np.broadcast_to(self.separators, part.shape).reshape(-1)
            self._emit(_format(part.reshape(-1), separators))
        self.written += table.shape[0]

    def _emit(self, data: bytes) -> None:
        self.out.write(data.decode("ascii"))

    def close(self) -> None:
        """End the table (an empty table is one empty line after the header, as always)."""
        if self.names and self.written == 0:
            self.out.write("\n")


def write(cols: Columns, out: TextIO) -> None:
    """Write the columns as CSV; NaN (no value at that position) becomes an empty field."""
    writer = Writer(list(cols), out)
    writer.header()
    if writer.names:
        writer.rows(cols)
    writer.close()
