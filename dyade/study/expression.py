"""Linked parameters: a small arithmetic expression over a study's parameters
(``"links.3.centre.1" = { equals = "dyad.2.lengths.1 / 2" }``), read by a parser of its
own — numbers, the parameters' dotted key paths, ``+ - * /``, ``**``, unary signs and
parentheses, nothing else (no Python is evaluated) — and computed over every variant at
once (numpy arrays).

Grammar::

    sum     := product (("+" | "-") product)*
    product := unary (("*" | "/") unary)*
    unary   := ("+" | "-") unary | power
    power   := atom ("**" unary)?
    atom    := NUMBER | NAME | "(" sum ")"

``NAME`` is a dotted key path (``dyad.2.lengths.1``, ``links.3.mass``).
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import Any

TOKEN = re.compile(r"\s*(?:(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
                   r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z0-9_]+)*)"
                   r"|(?P<op>\*\*|[-+*/()]))")


class ExpressionError(ValueError):
    """An expression that cannot be read: ``position`` is the character where reading
    stopped (0-based)."""

    def __init__(self, message: str, position: int) -> None:
        super().__init__(message)
        self.position = position


def tokens(text: str) -> list[tuple[str, str, int]]:
    """(kind, text, position) of every token of ``text``; kind number, name or op."""
    out, at = [], 0
    while at < len(text):
        if text[at:].strip() == "":
            break
        match = TOKEN.match(text, at)
        if match is None or match.end() == at:
            raise ExpressionError(f"cannot read {text[at:].strip()[:12]!r}", at)
        kind = match.lastgroup
        out.append((kind, match.group(kind), match.start(kind)))
        at = match.end()
    return out


@lru_cache(maxsize=256)
def parse(text: str) -> tuple:
    """The expression ``text`` as a tree of tuples: ``("number", x)``, ``("name", key)``,
    ``("neg", a)``, ``(op, a, b)`` for op in + - * / **. Raises ``ExpressionError``."""
    items = tokens(text)
    if not items:
        raise ExpressionError("is empty", 0)
    at = 0

    def peek() -> tuple[str, str, int] | None:
        return items[at] if at < len(items) else None

    def take() -> tuple[str, str, int]:
        nonlocal at
        at += 1
        return items[at - 1]

    def expected(what: str):
        item = peek()
        where = item[2] if item else len(text)
        found = repr(item[1]) if item else "the end"
        return ExpressionError(f"expected {what} at character {where + 1}, found {found}",
                               where)

    def binary(next_level, ops):
        def level():
            left = next_level()
            while (item := peek()) is not None and item[0] == "op" and item[1] in ops:
                take()
                left = (item[1], left, next_level())
            return left
        return level

    def unary():
        item = peek()
        if item is not None and item[0] == "op" and item[1] in "+-" and item[1] != "**":
            take()
            inner = unary()
            return ("neg", inner) if item[1] == "-" else inner
        return power()

    def power():
        base = atom()
        item = peek()
        if item is not None and item == ("op", "**", item[2]):
            take()
            return ("**", base, unary())
        return base

    def atom():
        item = peek()
        if item is None:
            raise expected("a number, a parameter or (")
        if item[0] == "number":
            take()
            return ("number", float(item[1]))
        if item[0] == "name":
            take()
            return ("name", item[1])
        if item[1] == "(":
            take()
            inner = total()
            if (close := peek()) is None or close[1] != ")":
                raise expected(")")
            take()
            return inner
        raise expected("a number, a parameter or (")

    product = binary(unary, ("*", "/"))
    total = binary(product, ("+", "-"))
    tree = total()
    if at < len(items):
        raise expected("an operator (+ - * / **)")
    return tree


def names(tree: tuple) -> list[str]:
    """The key paths an expression reads, in order of first appearance."""
    if tree[0] == "name":
        return [tree[1]]
    if tree[0] == "number":
        return []
    out: list[str] = []
    for child in tree[1:]:
        out += [name for name in names(child) if name not in out]
    return out


def evaluate(tree: tuple, values: dict[str, Any]):
    """The expression's value with ``values`` (key path -> number or array): arrays
    broadcast, so every variant is computed at once. A division by zero gives inf or
    NaN (the mechanism reader refuses that variant)."""
    import numpy as np

    kind = tree[0]
    if kind == "number":
        return tree[1]
    if kind == "name":
        return values[tree[1]]
    if kind == "neg":
        return -evaluate(tree[1], values)
    a, b = evaluate(tree[1], values), evaluate(tree[2], values)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # refused per row
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        if kind == "+":
            return a + b
        if kind == "-":
            return a - b
        if kind == "*":
            return a * b
        if kind == "/":
            return a / b
        return np.power(a, b)
