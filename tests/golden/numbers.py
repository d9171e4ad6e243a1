#!/usr/bin/env python3
"""Compare two golden runs number by number (issue 36): no number may change, only its
form. Stdlib only.

    python3 tests/golden/numbers.py BEFORE AFTER [--names NAMES.tsv]

BEFORE and AFTER are output folders of tests/golden/run.py. For every command
(``NAME.out``, ``NAME.err``, ``NAME.rc`` and the files it wrote):

- **exit code**: must be the same; a change is listed (category ``exit``);
- **JSON** (a ``.out`` or file that parses as JSON): every number of the old document
  must stand in the new one. Columns are compared by name (old names mapped to new by
  NAMES, a tab-separated ``old<TAB>new`` list; numbers equal, null = NaN); every other
  number of the old document (its summary, whatever its shape) must be a number of the
  new document (as printed: both write 15 significant digits);
- **CSV** (a header line of names, then rows of numbers): columns by (mapped) name, each
  value equal, an empty cell = ``nan`` (the old study CSV) and ``0.0``/``1.0`` = ``0``/``1``;
- **text** (tables, messages): every number of the old text must stand in the new text
  as printed, or scaled by 1000 (lengths in the file's mm instead of m, category
  ``units``), or the new text has it to fewer digits (category ``digits``).

Categories of form that are not counted as changes: names (mapped), missing marks
(``nan``/``None``/empty -> ``—``/null/empty), flags (``True``/``False``/``0.0`` ->
``yes``/``no``/``0``). Prints each command whose numbers differ, with the numbers, and a
count per category; exit status 0 when no number changed, 1 otherwise.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
import sys
from collections import Counter
from pathlib import Path

NUMBER = re.compile(r"(?<![\w.])[-−+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w])")
"""a number in a text: not part of a word (``F_1_2``, ``v2``) or of a longer number"""


def numbers_of_text(text: str) -> list[float]:
    out = []
    for match in NUMBER.finditer(text):
        token = match.group(0).replace("−", "-")
        try:
            out.append(float(token))
        except ValueError:
            pass
    return out


def leaves(value, path: str = ""):
    """(path, number) for every number in a JSON value."""
    if isinstance(value, dict):
        for key, item in value.items():
            yield from leaves(item, f"{path}.{key}" if path else str(key))
    elif isinstance(value, list):
        for k, item in enumerate(value):
            yield from leaves(item, f"{path}[{k}]")
    elif isinstance(value, bool):
        yield path, float(value)
    elif isinstance(value, (int, float)):
        yield path, float(value)


def same(a: float, b: float) -> bool:
    if math.isnan(a) and math.isnan(b):
        return True
    if a == b:
        return True
    return abs(a - b) <= 1e-14 * max(abs(a), abs(b))


def key(x: float) -> str:
    return "nan" if math.isnan(x) else f"{x:.12g}"


def cell(text: str) -> float:
    text = text.strip()
    if text in ("", "nan", "NaN", "None", "null"):
        return math.nan
    if text in ("True", "true"):
        return 1.0
    if text in ("False", "false"):
        return 0.0
    return float(text)


def parse_csv(text: str):
    rows = list(csv.reader(io.StringIO(text)))
    if len(rows) < 2 or len(rows[0]) < 1:
        return None
    header = rows[0]
    try:
        columns = {name: [cell(row[k]) for row in rows[1:] if len(row) == len(header)]
                   for k, name in enumerate(header)}
    except ValueError:
        return None
    return columns


def compare_columns(old: dict, new: dict, names: dict, where: str, out: list) -> None:
    for name, values in old.items():
        target = names.get(name, name)
        if target not in new:
            out.append(("column missing", f"{where}: column {name} (-> {target}) is gone"))
            continue
        other = new[target]
        if len(other) != len(values):
            out.append(("rows", f"{where}: column {name}: {len(values)} -> {len(other)} rows"))
            continue
        bad = [k for k, (a, b) in enumerate(zip(values, other))
               if not same(float("nan") if a is None else a, float("nan") if b is None else b)]
        if bad:
            k = bad[0]
            out.append(("number", f"{where}: column {name}: {len(bad)} values differ, first "
                                  f"row {k}: {values[k]!r} -> {other[k]!r}"))


def as_floats(values) -> list[float]:
    return [math.nan if v is None else float(v) for v in values]


def compare_json(old, new, names: dict, where: str, out: list) -> None:
    old_columns = old.get("columns") if isinstance(old, dict) else None
    new_columns = new.get("columns") if isinstance(new, dict) else None
    if isinstance(old_columns, dict) and isinstance(new_columns, dict):
        try:
            compare_columns({k: as_floats(v) for k, v in old_columns.items()},
                            {k: as_floats(v) for k, v in new_columns.items()}, names, where, out)
        except (TypeError, ValueError):
            pass
        old = {k: v for k, v in old.items() if k not in ("columns", "units")}
    # a figure of the old summary may be a column of the new document (a list of rows)
    found = Counter(key(x) for _, x in leaves(new))
    for path, x in leaves(old):
        if found.get(key(x)):
            continue
        if found.get(key(x * 30.0 / math.pi)):  # a speed in rad/s now given in rpm
            out.append(("units (rad/s -> rpm)", f"{where}: {path} = {x!r}"))
            continue
        out.append(("number", f"{where}: {path} = {x!r} is not in the new document"))


def compare_text(old: str, new: str, where: str, out: list, categories: Counter) -> None:
    have = [x for x in numbers_of_text(new)]
    exact = Counter(key(x) for x in have)
    for x in numbers_of_text(old):
        if exact.get(key(x)):
            continue
        if any(same(x * 1000, y) or same(x / 1000, y) for y in have):
            categories["units (m -> mm in tables)"] += 1
            continue
        if any(y != 0 and abs(x - y) <= 5e-4 * abs(y) for y in have):
            categories["digits"] += 1
            continue
        out.append(("number", f"{where}: {x!r} is not in the new text"))


def load_names(path: str | None) -> dict:
    if not path:
        return {}
    out = {}
    for line in Path(path).read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            old, new = line.split("\t")[:2]
            out[old.strip()] = new.strip()
    return out


def main(argv: list[str]) -> int:
    args = [a for a in argv if not a.startswith("--")]
    names = load_names(argv[argv.index("--names") + 1] if "--names" in argv else None)
    if "--names" in argv:
        args.remove(argv[argv.index("--names") + 1])
    before, after = Path(args[0]), Path(args[1])
    problems: list[tuple[str, str]] = []
    categories: Counter = Counter()
    for old_path in sorted(before.iterdir()):
        name = old_path.name
        new_path = after / name
        if name.endswith(".timings.tsv") or name == "commands.txt":
            continue
        if not new_path.exists():
            problems.append(("file missing", name))
            continue
        old, new = old_path.read_text(errors="replace"), new_path.read_text(errors="replace")
        if old == new:
            categories["identical"] += 1
            continue
        categories["changed form"] += 1
        if name.endswith(".rc"):
            problems.append(("exit", f"{name}: {old.strip()} -> {new.strip()}"))
            continue
        try:
            compare_json(json.loads(old), json.loads(new), names, name, problems)
            continue
        except ValueError:
            pass
        old_csv, new_csv = parse_csv(old), parse_csv(new)
        if old_csv is not None and new_csv is not None and "," in old.partition("\n")[0]:
            compare_columns(old_csv, new_csv, names, name, problems)
            continue
        compare_text(old, new, name, problems, categories)
    for kind, text in problems:
        print(f"{kind}: {text}")
    print("; ".join(f"{k}: {v}" for k, v in sorted(categories.items())))
    counted = Counter(kind for kind, _ in problems)
    print("changes: " + ("; ".join(f"{k}: {v}" for k, v in sorted(counted.items())) or "none"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
