"""Columns -> CSV text: header line, one row per crank position, 15 significant digits.

The numbers are written exactly as ``"%.15g" % value`` writes them (with ``-0`` written
``0`` and NaN an empty field), but formatted a block of values at a time in numpy instead
of one Python string per value (5–8× the throughput of the row-by-row writer it
replaces, depending on the data; ``tests/benchmarks`` measure the two side by side):

1. **Digits.** The 15 significant digits of ``|x|`` are the integer
   ``q = round(|x| · 10^(14−e))``, ``e`` the decimal exponent (``floor(log10|x|)``). The
   product is computed exactly enough in plain doubles: ``10^(14−e)`` is tabulated as the
   sum of two doubles (``hi + lo``, correctly rounded), and the rounding error of
   ``|x|·hi`` is recovered exactly by Dekker's product (both factors split into 26-bit
   halves, Veltkamp), plus ``|x|·lo``. The fraction of the product is then known to
   better than 10⁻¹⁵ of a unit of ``q``; a value within ``_TIE`` (10⁻⁹) of a rounding
   midpoint, ±inf and magnitudes outside [``_SMALLEST``, ``_LARGEST``) (where a split
   could overflow) are formatted by Python's ``"%.15g"`` itself. Where ``log10`` is one
   off (next to a power of ten) the product's floor leaves [10^14, 10^15), and those few
   values are computed again with the next exponent;
2. **Text.** ``10·q`` gives 16 digit bytes (two 64-bit words, from a table of the
   10 000 four-digit groups); the count of significant digits is the position of the last
   nonzero digit byte, read from the exponent of the words converted to a float. One table
   row per (notation and exponent, significant digits, sign) then gives everything else
   as 64-bit masks: the digits before the decimal point, the digits after it (taken from
   the words shifted by one byte, which leaves the point's place free), the ASCII offsets
   with the point, the prefix (sign, or sign and "0.000") and how far the digits are
   shifted behind it (1 or 6 bytes). Each value becomes a 24-byte row (three words):
   prefix and digits, exponent ("e-05", bytes 17..21), separator (byte 23); what a value
   does not show is a NUL byte. The few values Python formats overwrite their rows;
3. the block's rows with the NULs dropped (``bytearray.translate``) are its CSV text.

The arrays of a block are allocated once per ``Writer`` and reused (glibc would map and
unmap every array of 128 kB or more on each use). ``Writer`` streams: ``header()`` once,
then ``rows(block)`` for every block of rows as soon as it is computed; ``write`` is the
whole table at once.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import TextIO

import numpy as np

from dyade.linkage.columns import Columns

FIELDS_PER_BLOCK = 16384
"""values formatted at once (measured on dyade-16: 8192..32768 alike, 4096 and 65536 slower);
the work arrays take about 170 B per value"""
ROW = 24
"""bytes of a value's row: prefix and digits (0..20 at most), exponent (17..21), separator (23)"""
_SEPARATOR = 7 * 8
"""bit offset of the separator in a row's last word"""
_SMALLEST, _LARGEST = 1e-290, 1e300
"""magnitudes formatted in numpy: there 10^(14−e), its rest, the products and the splits
are normal doubles (no overflow, no underflow)"""
_E_MIN, _E_MAX = -292, 301
"""decimal exponents in the tables (those of [_SMALLEST, _LARGEST) and one more each way)"""
_ZERO, _EMPTY = _E_MAX - _E_MIN + 1, _E_MAX - _E_MIN + 2
"""table entries of the zero and of the empty field (NaN, and values Python formats)"""
_TIE = 1e-9
"""how near a rounding midpoint (in units of the 15th digit) a value is left to Python"""
_SPLIT = 2.0 ** 27 + 1
"""Veltkamp's constant: splits a double into two halves of 26 bits"""
_LITTLE_ENDIAN = sys.byteorder == "little"
"""the rows are built as little-endian words; elsewhere Python formats every value"""


def _word(text: str) -> int:
    """Up to 8 bytes of text as a little-endian 64-bit word (the text in memory order)."""
    return int.from_bytes(text.encode().ljust(8, b"\0"), "little")


def _exponent_tables() -> tuple[np.ndarray, ...]:
    """Per decimal exponent e (entry e − _E_MIN; then _ZERO, _EMPTY): 10^(14−e) as
    hi + lo (hi correctly rounded, lo the rest correctly rounded: Python's integer
    arithmetic), hi's upper 26 bits, the first key of e's notation class, and the exponent
    text (bytes 1..5 of a row's last word)."""
    hi, lo = [], []
    power = 1
    for _ in range(14 - _E_MIN + 1):  # 10^0, 10^1, … (e = 14, 13, …)
        hi.append(float(power))
        lo.append(float(power - int(hi[-1])))
        power *= 10
    hi.reverse()
    lo.reverse()
    divisor = 10
    for _ in range(_E_MAX - 14):  # 10^−1, 10^−2, … (e = 15, 16, …)
        hi.append(1 / divisor)  # int / int: correctly rounded
        numerator, denominator = hi[-1].as_integer_ratio()
        lo.append((denominator - numerator * divisor) / (denominator * divisor))
        divisor *= 10
    hi, lo = np.array(hi + [5e14, 5e14]), np.array(lo + [0.0, 0.0])  # _ZERO, _EMPTY: |x| = 1
    mantissa, exponent = np.frexp(hi)
    bits = (mantissa * 2.0 ** 53).astype(np.int64)
    top = np.ldexp(((bits + 2 ** 26) >> 27 << 27).astype(np.float64), exponent - 53)
    e = np.arange(_E_MIN, _E_MAX + 1)
    fixed = (e >= -4) & (e < 15)
    key = np.r_[32 * np.where(fixed, e + 7, 2), 32, 0]
    digit = [(np.abs(e) // 10 ** k % 10 + 0x30).astype(np.uint64) for k in range(3)]
    text = np.where(e < 0, 0x2D, 0x2B).astype(np.uint64) << np.uint64(16)  # e±dd(d)
    text += np.uint64(ord("e") << 8)
    text += np.where(np.abs(e) < 100, digit[1] << np.uint64(24) | digit[0] << np.uint64(32),
                     digit[2] << np.uint64(24) | digit[1] << np.uint64(32)
                     | digit[0] << np.uint64(40))
    text = np.r_[np.where(fixed, np.uint64(0), text), np.zeros(2, np.uint64)]
    return hi, top, lo, key, text


_POWER, _POWER_TOP, _POWER_LOW, _CLASS_KEY, _EXPONENT = _exponent_tables()


def _row_tables() -> tuple[np.ndarray, ...]:
    """Per key = 32·class + 16·sign + significant digits: the masks of the digit words
    (before the point, after it, ASCII offsets with the point), the prefix word and the
    shift of the digits behind it [bits]. Classes: 0 empty, 1 zero, 2 exponent notation,
    3 + e + 4 fixed notation with exponent e = −4..14."""
    key = np.arange(22 * 32)[:, None]
    kind, digits, place = key // 32, key % 16, np.arange(16)
    small = (kind >= 3) & (kind < 7)  # 0.000ddd: the digits, no point
    point = np.where(kind == 2, 1, kind - 6)  # d.ddde+XX or ddd.ddd: after `point` digits
    dotted = (kind >= 2) & ~small
    before = (small & (place < digits)) | (dotted & (place < point))
    after = dotted & (place > point) & (place <= digits)
    offset = 0x30 * (before | after) + 0x2E * (dotted & (place == point) & (digits > point))
    bytes_ = [np.where(before, 0xFF, 0), np.where(after, 0xFF, 0), offset]
    words = [np.ascontiguousarray(table.astype(np.uint8).view(np.uint64)[:, half])
             for table in bytes_ for half in (0, 1)]
    signs = ("", "-")
    prefix = np.array([[0, 0], [_word("0")] * 2, [_word(sign) for sign in signs]]
                      + [[_word(sign + "0." + "0" * (6 - kind)) for sign in signs]
                         for kind in range(3, 7)]
                      + [[_word(sign) for sign in signs]] * 15, dtype=np.uint64)
    return (*words, np.repeat(prefix, 16, axis=1).reshape(-1),
            np.where(small, 48, 8).astype(np.uint64).reshape(-1))


_BEFORE0, _BEFORE1, _AFTER0, _AFTER1, _OFFSET0, _OFFSET1, _PREFIX, _SHIFT = _row_tables()
_GROUP = np.arange(10_000)
_DIGITS = sum((_GROUP // 10 ** (3 - k) % 10) << (8 * k) for k in range(4)).astype(np.uint64)
"""the four digit values (0..9) of 0..9999 as bytes 0..3, most significant first"""


class _Work:
    """The arrays of one block of ``size`` values, reused from block to block."""

    def __init__(self, size: int) -> None:
        self.size = size
        (self.magnitude, self.product, self.high, self.low, self.power, self.top, self.error,
         self.floor) = (np.empty(size) for _ in range(8))
        self.entry, self.q, self.group, self.rest, self.key = (
            np.empty(size, np.int64) for _ in range(5))
        self.text0, self.text1, self.shifted, self.back, self.mask = (
            np.empty(size, np.uint64) for _ in range(5))
        self.slow, self.flag = np.empty(size, bool), np.empty(size, bool)
        self.buffer = bytearray(size * ROW)
        self.rows = np.frombuffer(self.buffer, np.uint64).reshape(size, ROW // 8)


def _scaled(work: _Work, n: int) -> None:
    """``|x|·10^(14−e)`` of the first ``n`` values (``magnitude``, exponent table
    ``entry``) as its floor (``q``) and the rest (``product``, error below 10⁻¹⁵)."""
    a, entry = work.magnitude[:n], work.entry[:n]
    product, high, low, power, top, error, scratch = (
        work.product[:n], work.high[:n], work.low[:n], work.power[:n], work.top[:n],
        work.error[:n], work.floor[:n])
    _POWER.take(entry, out=power, mode="clip")
    _POWER_TOP.take(entry, out=top, mode="clip")
    np.multiply(a, power, out=product)
    power -= top  # its lower half
    np.multiply(a, _SPLIT, out=high)  # Veltkamp: a = high + low, 26 bits each
    np.subtract(high, a, out=low)
    high -= low
    np.subtract(a, high, out=low)
    np.multiply(high, top, out=error)  # Dekker: a·hi − product, exactly
    error -= product
    np.multiply(high, power, out=scratch)
    error += scratch
    np.multiply(low, top, out=scratch)
    error += scratch
    np.multiply(low, power, out=scratch)
    error += scratch
    _POWER_LOW.take(entry, out=scratch, mode="clip")
    scratch *= a
    error += scratch  # + a·lo
    np.floor(product, out=scratch)
    product -= scratch
    product += error
    np.copyto(work.q[:n], scratch, casting="unsafe")


def _rounded(work: _Work, n: int, python: list[np.ndarray]) -> None:
    """``q = round(|x|·10^(14−e))`` in [10^14, 10^15) and the exponent table entry of
    ``e`` (``entry``) of the first ``n`` values; the indices of values too near a
    rounding midpoint are added to ``python``.

    Where log10 was one off (next to a power of ten) the floor of the scaled value lies
    outside [10^14, 10^15), and the value is scaled again with the next exponent. The
    floor is enough: the scaled value can be just below 10^14 with a floor of 10^14 (the
    product rounded up), or at least 10^15 with a floor of 10^15 − 1 (``hi`` of an inexact
    power is below it), but then it rounds to 10^14, or to 10^15 which carries, and 15
    digits of the right exponent round to the same power of ten."""
    _scaled(work, n)
    q, rest, entry, flag = work.q[:n], work.product[:n], work.entry[:n], work.flag[:n]
    if q.min() < 10 ** 14 or q.max() >= 10 ** 15:
        wrong = np.flatnonzero((q < 10 ** 14) | (q >= 10 ** 15))
        again = _Work(wrong.size)
        again.magnitude[:] = work.magnitude[wrong]
        again.entry[:] = entry[wrong]
        for _ in range(3):
            _scaled(again, wrong.size)
            small, large = again.q < 10 ** 14, again.q >= 10 ** 15
            if not (small | large).any():
                break
            again.entry += large
            again.entry -= small
        else:
            python.append(wrong[small | large])
        q[wrong], rest[wrong], entry[wrong] = again.q, again.product, again.entry
    rest -= 0.5
    np.greater(rest, 0.0, out=flag)
    q += flag
    np.abs(rest, out=rest)
    np.less(rest, _TIE, out=flag)
    if flag.any():
        python.append(np.flatnonzero(flag))
    if q.max() == 10 ** 15:  # 9.99…95 rounds up to the next power of ten
        carry = np.flatnonzero(q == 10 ** 15)
        q[carry] = 10 ** 14
        entry[carry] += 1


def _eight_digits(number: np.ndarray, group: np.ndarray, text: np.ndarray,
                  scratch: np.ndarray) -> None:
    """The 8 digits of ``number`` (< 10^8, uint64, overwritten) as the bytes of ``text``."""
    np.floor_divide(number, np.uint64(10 ** 4), out=group)  # unsigned: faster
    _DIGITS.take(group.view(np.int64), out=text, mode="clip")
    group *= np.uint64(10 ** 4)
    number -= group
    _DIGITS.take(number.view(np.int64), out=scratch, mode="clip")
    scratch <<= np.uint64(32)
    text |= scratch


def _digit_words(work: _Work, n: int) -> None:
    """The digits of ``q`` and a 0 as 16 bytes of values 0..9 (``text0``, ``text1``,
    most significant first), and the count of significant digits (``rest``)."""
    text0, text1, mask = work.text0[:n], work.text1[:n], work.mask[:n]
    q, group, rest = (work.q[:n].view(np.uint64), work.group[:n].view(np.uint64),
                      work.rest[:n].view(np.uint64))
    q *= np.uint64(10)
    np.floor_divide(q, np.uint64(10 ** 8), out=rest)
    np.multiply(rest, np.uint64(10 ** 8), out=group)
    q -= group
    _eight_digits(rest, group, text0, mask)
    _eight_digits(q, group, text1, mask)
    rest = work.rest[:n]
    # the last nonzero digit is the byte of the highest set bit of text1·2^64 + text0:
    # the float's exponent (the digit bytes are at most 9, so it never rounds up to 2^k)
    number, low = work.high[:n], work.low[:n]
    np.copyto(number, text1.view(np.int64), casting="unsafe")  # < 2^60: as int64, faster
    number *= 2.0 ** 64
    np.copyto(low, text0.view(np.int64), casting="unsafe")
    number += low
    np.right_shift(number.view(np.int64), 52, out=rest)
    rest -= 1023 - 8
    rest >>= 3


def _exponents(values: np.ndarray, work: _Work) -> list[np.ndarray]:
    """``magnitude`` (|x|, 1 where not formatted in numpy) and the exponent table
    ``entry`` of ``floor(log10|x|)`` (or of the zero, or of the empty field); returns the
    indices of the values Python formats: ±inf, the huge and the tiny."""
    n = values.size
    a, entry, slow, flag = work.magnitude[:n], work.entry[:n], work.slow[:n], work.flag[:n]
    log = work.product[:n]
    np.abs(values, out=a)
    np.greater_equal(a, _SMALLEST, out=slow)
    np.less(a, _LARGEST, out=flag)
    slow &= flag
    np.logical_not(slow, out=slow)  # zero, NaN, ±inf, huge or tiny
    np.greater(a, 0.0, out=flag)  # not zero, not NaN
    flag &= slow
    python = [np.flatnonzero(flag)] if flag.any() else []
    np.copyto(a, 1.0, where=slow)
    np.log10(a, out=log)
    log -= _E_MIN  # positive: truncation is floor
    np.copyto(entry, log, casting="unsafe")
    np.copyto(entry, _EMPTY, where=slow)
    np.equal(values, 0.0, out=flag)
    np.copyto(entry, _ZERO, where=flag)
    return python


def _with_point(text: np.ndarray, shifted: np.ndarray, key: np.ndarray,
                tables: tuple[np.ndarray, ...], scratch: np.ndarray) -> None:
    """One word of digits as shown (ASCII, with the point): the bytes before the point
    from ``text``, those after it from ``shifted`` (the text one byte on)."""
    before, after, offset = tables
    after.take(key, out=scratch, mode="clip")
    shifted &= scratch
    before.take(key, out=scratch, mode="clip")
    text &= scratch
    text |= shifted
    offset.take(key, out=scratch, mode="clip")
    text += scratch


def _rows(values: np.ndarray, separators: np.ndarray, work: _Work) -> None:
    """The rows of ``values`` from their digit words, significant digits and exponents."""
    n = values.size
    key, mask, shifted, back = work.key[:n], work.mask[:n], work.shifted[:n], work.back[:n]
    text0, text1, entry = work.text0[:n], work.text1[:n], work.entry[:n]
    _CLASS_KEY.take(entry, out=key, mode="clip")
    key += work.rest[:n]
    np.right_shift(values.view(np.uint64), np.uint64(59), out=mask)
    mask &= np.uint64(16)  # the sign bit
    key += mask.view(np.int64)
    # the digits with the point: the bytes before it from text, after it from text << 8
    np.right_shift(text0, np.uint64(56), out=back)  # the byte text0 << 8 loses
    np.left_shift(text0, np.uint64(8), out=shifted)
    _with_point(text0, shifted, key, (_BEFORE0, _AFTER0, _OFFSET0), mask)
    np.left_shift(text1, np.uint64(8), out=shifted)
    shifted |= back
    _with_point(text1, shifted, key, (_BEFORE1, _AFTER1, _OFFSET1), mask)
    # the row: prefix, the digits shifted behind it, exponent, separator
    rows, shift, word = work.rows[:n], shifted, work.group[:n].view(np.uint64)
    _SHIFT.take(key, out=shift, mode="clip")
    np.subtract(np.uint64(64), shift, out=back)
    np.left_shift(text0, shift, out=word)
    _PREFIX.take(key, out=mask, mode="clip")
    np.bitwise_or(word, mask, out=rows[:, 0])
    text0 >>= back
    np.left_shift(text1, shift, out=word)
    np.bitwise_or(word, text0, out=rows[:, 1])
    text1 >>= back
    _EXPONENT.take(entry, out=mask, mode="clip")
    text1 |= mask
    np.bitwise_or(text1, separators, out=rows[:, 2])


def _format(values: np.ndarray, separators: np.ndarray, work: _Work) -> bytes | bytearray:
    """The "%.15g" texts of ``values`` (flat, at most ``work.size``), each followed by its
    separator (a word with the byte at bit ``_SEPARATOR``)."""
    if not _LITTLE_ENDIAN:  # the rows are built as little-endian words
        ends = (separators >> np.uint64(_SEPARATOR)).astype(np.uint8).tobytes().decode()
        return "".join(("%.15g" % x if x == x else "") + end
                       for x, end in zip((values + 0.0).tolist(), ends)).encode()
    n = values.size
    python = _exponents(values, work)
    _rounded(work, n, python)
    _digit_words(work, n)
    _rows(values, separators, work)
    text = work.rows[:n].view(np.uint8)
    for k in np.concatenate(python) if python else ():
        python_text = ("%.15g" % values[k]).encode()
        text[k, :ROW - 1] = 0
        text[k, :len(python_text)] = np.frombuffer(python_text, np.uint8)
    if n == work.size:
        return work.buffer.translate(None, b"\0")
    return work.buffer[:n * ROW].translate(None, b"\0")


class Writer:
    """CSV to ``out`` block by block: the header, then ``rows(block)`` as they come."""

    def __init__(self, names: list[str], out: TextIO) -> None:
        self.names = list(names)
        self.out = out
        self.written = 0
        """rows written"""
        self.step = max(1, FIELDS_PER_BLOCK // max(1, len(self.names)))
        """rows formatted at once"""
        separators = np.full(len(self.names), ord(","), dtype=np.uint64)
        if self.names:
            separators[-1] = ord("\n")
        self.separators = np.tile(separators << np.uint64(_SEPARATOR), self.step)
        """the separator words of ``step`` rows"""
        self.work: _Work | None = None

    def header(self) -> None:
        self.out.write(",".join(self.names) + "\n")

    def rows(self, block: Columns | np.ndarray) -> None:
        """Write a block of rows: the columns by name (any mapping, read in ``names``
        order), or a (rows, columns) array."""
        if isinstance(block, Mapping):
            block = np.column_stack([np.asarray(block[name], dtype=np.float64)
                                     for name in self.names]) if self.names else np.zeros((0, 0))
        table = np.ascontiguousarray(block, dtype=np.float64)
        if not self.names or table.shape[0] == 0:
            return
        if self.work is None:
            self.work = _Work(self.separators.size)
        for first in range(0, table.shape[0], self.step):
            part = table[first:first + self.step].reshape(-1)
            self._emit(_format(part, self.separators[:part.size], self.work))
        self.written += table.shape[0]

    def _emit(self, data: bytearray) -> None:
        self.out.write(data.decode("ascii"))

    def close(self) -> None:
        """End the table (an empty table is one empty line after the header, as always)."""
        if self.names and self.written == 0:
            self.out.write("\n")


def write(cols: Columns, out: TextIO) -> None:
    """Write the columns as CSV; NaN (no value at that position) becomes an empty field.

    Examples
    --------
    >>> import io
    >>> out = io.StringIO()
    >>> write({"angle_deg": np.array([0.0, 90.0]), "x": np.array([0.1 + 0.2, np.nan])}, out)
    >>> print(out.getvalue(), end="")
    angle_deg,x
    0,0.3
    90,
    """
    writer = Writer(list(cols), out)
    writer.header()
    if writer.names:
        writer.rows(cols)
    writer.close()
