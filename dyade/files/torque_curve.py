"""Read a torque curve (CSV): columns ``angle_deg`` and ``M_drive`` [N·m], optionally
``M_load`` [N·m] — or a whole CSV of ``dyade analyse``, which has them (and ``J_red``).

Every error names the file, the column and the row.
"""

from __future__ import annotations

import os

import numpy as np

from dyade.errors import InputError

REQUIRED = ("angle_deg", "M_drive")
OPTIONAL = ("M_load", "J_red", "dJ_red", "omega_2")


def load_columns(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """The torque curve's columns of a CSV file (empty fields are NaN)."""
    path = os.fspath(path)
    label = os.path.basename(path)
    try:
        with open(path, encoding="utf-8") as handle:
            lines = [line.strip() for line in handle if line.strip()]
    except OSError as err:
        raise InputError(f"{path}: cannot read the file ({err.strerror}).", source=path) from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a UTF-8 text file.", source=path) from None
    if not lines:
        raise InputError(f"{label}: the file is empty; it needs a header line with "
                         f"{', '.join(REQUIRED)}.", source=path)
    names = [name.strip() for name in lines[0].split(",")]
    missing = [name for name in REQUIRED if name not in names]
    if missing:
        raise InputError(f"{label}: no column {', '.join(missing)} in the header (it has "
                         f"{', '.join(names[:8])}{' …' if len(names) > 8 else ''}).",
                         source=path, key=missing[0])
    wanted = [name for name in REQUIRED + OPTIONAL if name in names]
    index = {name: names.index(name) for name in wanted}
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        fields = line.split(",")
        if len(fields) != len(names):
            raise InputError(f"{label}: line {number} has {len(fields)} fields, the header "
                             f"{len(names)}.", source=path)
        row = []
        for name in wanted:
            text = fields[index[name]].strip()
            try:
                row.append(float(text) if text else np.nan)
            except ValueError:
                raise InputError(f"{label}: line {number}, column {name}: not a number: "
                                 f"{text!r}.", source=path, key=name) from None
        rows.append(row)
    if len(rows) < 4:
        raise InputError(f"{label}: needs at least 4 rows over one revolution, got {len(rows)}.",
                         source=path)
    table = np.array(rows)
    return {name: table[:, k] for k, name in enumerate(wanted)}
