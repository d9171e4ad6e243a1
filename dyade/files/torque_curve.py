"""Read a torque curve (CSV): columns ``angle_deg`` and ``M_drive`` [N·m], optionally
``M_load`` [N·m] — or a whole CSV of ``dyade analyse``, which has them (and ``J_red``).

Every error names the file, the column and the row. ``read_table`` gives the file's
columns in SI as a ``dyade.model.torque_table.TorqueTable``; the flywheel
(``dyade.machine.flywheel``) computes on it.
"""

from __future__ import annotations

import os

import numpy as np

from dyade.errors import InputError
from dyade.limits import PLAUSIBLE
from dyade.units import rpm_to_rad_per_s
from dyade.model.torque_table import TorqueTable

REQUIRED = ("angle_deg", "M_drive")
OPTIONAL = ("M_load", "J_red", "dJ_red", "omega_2")


CHECKED = ("angle_deg", "M_drive", "M_load")
"""columns whose every cell must be a finite, plausible number (the others of dyade's
CSV are empty where a sweep gives no value)"""
RADIANS_SPAN = 2.0 * np.pi + 5e-3  # [-] a span up to 2π written with few digits (6.28319, 6.283)
TORQUE_LIMIT = 1e9  # [N·m] no machine's crank shaft carries more (dyade.limits "torque")
BOUNDED = {"J_red": (PLAUSIBLE["inertia"][1], "kg·m²"),
           "omega_2": (rpm_to_rad_per_s(PLAUSIBLE["speed_rpm"][1]), "rad/s")}
"""the optional columns of dyade's CSV -> the largest magnitude a machine has, and its unit
(they may be empty where a sweep gives no value)"""


def load_columns(path: str | os.PathLike, text: str | None = None) -> dict[str, np.ndarray]:
    """The torque curve's columns of a CSV file (empty fields are NaN); ``text``: its
    content when already read (standard input), ``path`` naming it. Every message names
    the file, the column as the header spells it and the line; a byte-order mark (Excel's
    "CSV UTF-8") is dropped; headers match whatever their case or surrounding spaces."""
    path = os.fspath(path)
    label = os.path.basename(path)
    if text is None:
        try:
            with open(path, encoding="utf-8-sig") as handle:
                text = handle.read()
        except OSError as err:
            raise InputError(f"{path}: cannot read the file ({err.strerror}).",
                             source=path) from None
        except UnicodeDecodeError:
            raise InputError(f"{label}: not a UTF-8 text file; save it as CSV UTF-8.",
                             source=path) from None
    text = text.removeprefix("\ufeff")
    lines = [(number, line.strip()) for number, line in enumerate(text.splitlines(), start=1)
             if line.strip()]
    if not lines:
        raise InputError(f"{label}: the file is empty; it needs a header line with "
                         f"{', '.join(REQUIRED)}.", source=path)
    header_line, header = lines[0]
    written = [name.strip().strip('"') for name in header.split(",")]
    known = {name.lower(): name for name in REQUIRED + OPTIONAL}
    names = [known.get(name.lower(), name) for name in written]
    missing = [name for name in REQUIRED if name not in names]
    if missing:
        raise InputError(f"{label}: no column {', '.join(missing)} in the header (line "
                         f"{header_line}: {', '.join(written[:8])}"
                         f"{' …' if len(written) > 8 else ''}); the columns are angle_deg "
                         f"[°] and M_drive [N·m], optionally M_load [N·m].",
                         source=path, key=missing[0])
    wanted = [name for name in REQUIRED + OPTIONAL if name in names]
    twice = [name for name in wanted if names.count(name) > 1]
    if twice:
        raise InputError(f"{label}: line {header_line}: the column {twice[0]} appears twice "
                         f"in the header.", source=path, key=twice[0])
    index = {name: names.index(name) for name in wanted}
    rows, numbers = [], []
    for number, line in lines[1:]:
        fields = line.split(",")
        if len(fields) != len(names):
            raise InputError(f"{label}: line {number} has {len(fields)} fields, the header "
                             f"(line {header_line}) {len(names)}.", source=path)
        row = []
        for name in wanted:
            cell = fields[index[name]].strip()
            column = written[index[name]]
            try:
                value = float(cell) if cell else np.nan
            except ValueError:
                raise InputError(f"{label}: line {number}, column {column}: not a number: "
                                 f"{cell!r}.", source=path, key=name) from None
            if name in CHECKED and not np.isfinite(value):
                got = "empty" if not cell else f"not a finite number: {cell!r}"
                raise InputError(f"{label}: line {number}, column {column}: {got}; the curve "
                                 f"needs a value at every angle of the revolution.",
                                 source=path, key=name)
            if name in ("M_drive", "M_load") and abs(value) > TORQUE_LIMIT:
                raise InputError(f"{label}: line {number}, column {column}: {cell} N·m is "
                                 f"beyond what a machine has (|M| ≤ {TORQUE_LIMIT:g} N·m).",
                                 source=path, key=name)
            if name in BOUNDED and abs(value) > BOUNDED[name][0]:  # NaN (empty) passes
                top, unit = BOUNDED[name]
                raise InputError(f"{label}: line {number}, column {column}: {cell} {unit} is "
                                 f"beyond what a machine has (at most {top:g} {unit}).",
                                 source=path, key=name)
            row.append(value)
        rows.append(row)
        numbers.append(number)
    if len(rows) < 4:
        raise InputError(f"{label}: needs at least 4 rows over one revolution, got {len(rows)}.",
                         source=path)
    table = np.array(rows)
    angle, column = table[:, 0], written[index["angle_deg"]]
    steps = np.diff(angle)
    if np.any(steps <= 0.0):
        k = int(np.flatnonzero(steps <= 0.0)[0])
        what = "repeats" if steps[k] == 0.0 else "is below"
        raise InputError(f"{label}: line {numbers[k + 1]}, column {column}: {angle[k + 1]:g} "
                         f"{what} line {numbers[k]}'s {angle[k]:g}; the angles must rise "
                         f"strictly over one revolution.", source=path, key="angle_deg")
    if angle[-1] - angle[0] <= RADIANS_SPAN and angle[-1] - angle[0] > 3.0:
        raise InputError(f"{label}: column {column} runs from {angle[0]:g} to {angle[-1]:g} "
                         f"(lines {numbers[0]} to {numbers[-1]}): these look like radians; "
                         f"the column is in degrees (0 to 360): multiply by 180/π.",
                         source=path, key="angle_deg")
    return {name: table[:, k] for k, name in enumerate(wanted)}


def read_table(path: str | os.PathLike, text: str | None = None) -> TorqueTable:
    """The torque curve of a CSV file in SI (``load_columns`` checks it); ``text``: its
    content when already read (standard input), ``path`` naming it.

    >>> table = read_table("mechanisms/torque/engine.csv")
    >>> table.angle.size, table.load is None, table.machine, table.source   # 0°…360°
    (361, True, False, 'engine.csv')
    """
    path = os.fspath(path)
    columns = load_columns(path, text)
    return TorqueTable(np.deg2rad(columns["angle_deg"]), columns["M_drive"],
                       columns.get("M_load"), columns.get("J_red"), columns.get("omega_2"),
                       "dJ_red" in columns, os.path.basename(path))
