"""A catalogue of servo motors (CSV), read into ``dyade.model.servo.Catalogue``.

One motor per row, a header naming the columns (any order; other columns are ignored):

``name``              the motor's name
``rated_torque``      M_N [N·m], the continuous (thermal) torque
``peak_torque``       M_max [N·m]
``rated_speed_rpm``   n_N [rpm]
``top_speed_rpm``     n_max [rpm]
``rotor_inertia``     J_M [kg·m²]
``envelope``          optional: the peak-torque envelope as points ``rpm:N·m`` separated
                      by spaces (``"0:9.5 3000:9.5 6000:4"``), speeds rising; empty: the
                      peak torque holds up to the top speed

Lines starting with ``#`` are comments. Every error names the file, the row (and its
motor) and the column.
"""

from __future__ import annotations

import csv
import io
import math
import os
from dyade.errors import InputError

COLUMNS = {"name": "", "rated_torque": "N·m", "peak_torque": "N·m", "rated_speed_rpm": "rpm",
           "top_speed_rpm": "rpm", "rotor_inertia": "kg·m²"}
"""required column -> its unit"""
OPTIONAL = ("envelope",)
LARGEST = 1e9  # [N·m, rpm, kg·m²] beyond any motor: refused before its squares overflow


def read_catalogue(path: str | os.PathLike, label: str | None = None):
    """Read a motor catalogue (module docstring): a ``Catalogue`` in SI units.

    Raises
    ------
    InputError
        The file is missing or unreadable, a column is missing, a value is not a positive
        number (naming the row, the motor and the column), or no motor is listed.
    """
    label = label or os.fspath(path)
    try:
        with open(path, encoding="utf-8-sig", newline="") as handle:  # -sig: Excel's BOM
            text = handle.read()
    except OSError as err:
        raise InputError(f"{label}: cannot read the motor catalogue ({err.strerror}).",
                         source=label) from None
    except UnicodeDecodeError:
        raise InputError(f"{label}: the motor catalogue is not a text file in UTF-8: save "
                         f"it as CSV (UTF-8).", source=label) from None
    return parse_catalogue(text, label)


def parse_catalogue(text: str, label: str = "catalogue"):
    """The catalogue of a CSV text (``read_catalogue``)."""
    import numpy as np

    from dyade.model.servo import Catalogue, ServoMotor
    from dyade.units import RPM

    text = text.removeprefix("\ufeff")  # a byte-order mark (Excel's "CSV UTF-8")
    lines = [line for line in text.splitlines()
             if line.strip() and not line.lstrip().startswith("#")]
    reader = csv.DictReader(io.StringIO("\n".join(lines)))
    header = [name.strip() for name in (reader.fieldnames or [])]
    missing = [name for name in COLUMNS if name not in header]
    if missing:
        raise InputError.in_file(label, missing[0], f"is missing: a motor catalogue needs the "
                                 f"columns {', '.join(COLUMNS)} (and optionally envelope); "
                                 f"the file has {', '.join(header) or 'none'}.",
                                 source=label)
    motors = []
    seen: dict[str, int] = {}
    for row_number, raw in enumerate(reader, start=1):
        if None in raw:  # csv.DictReader's key of the fields beyond the header's
            raise InputError(f"{label}: row {row_number} ({raw.get('name') or 'no name'}) "
                             f"has {len(header) + len(raw[None])} fields, the header "
                             f"{len(header)}: a comma inside a value? Quote the value, or "
                             f"name the extra column in the header.", source=label)
        row = {(k or "").strip(): (v or "").strip() for k, v in raw.items()}
        name = row["name"] or f"row {row_number}"
        where = f"row {row_number} ({name})"
        if name in seen:
            raise InputError.in_file(label, "name", f"{name!r} of row {row_number} is also "
                                     f"the name of row {seen[name]}: the results name motors "
                                     f"by it, so give each motor its own name.", source=label)
        seen[name] = row_number
        values: dict[str, float] = {}
        for column, unit in COLUMNS.items():
            if column == "name":
                continue
            values[column] = _positive(row[column], label, where, column, unit)
        if values["peak_torque"] < values["rated_torque"]:
            raise InputError.in_file(label, "peak_torque", f"of {where} is below its rated "
                                     f"torque ({values['rated_torque']:g} N·m).", source=label,
                                     value=values["peak_torque"], unit="N·m")
        if values["top_speed_rpm"] < values["rated_speed_rpm"]:
            raise InputError.in_file(label, "top_speed_rpm", f"of {where} is below its rated "
                                     f"speed ({values['rated_speed_rpm']:g} rpm).",
                                     source=label, value=values["top_speed_rpm"], unit="rpm")
        speeds = torques = None
        if row.get("envelope"):
            speeds, torques = _envelope(row["envelope"], label, where)
            speeds, torques = np.array(speeds) * RPM, np.array(torques)
        motors.append(ServoMotor(name, values["rated_torque"], values["peak_torque"],
                                 values["rated_speed_rpm"] * RPM, values["top_speed_rpm"] * RPM,
                                 values["rotor_inertia"], speeds, torques))
    if not motors:
        raise InputError(f"{label}: the motor catalogue lists no motor (one row per motor "
                         f"under the header).", source=label)
    return Catalogue(tuple(motors), label)


def _positive(text: str, label: str, where: str, column: str, unit: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and 0.0 < value <= LARGEST):
        raise InputError.in_file(label, column, f"of {where} must be a positive number "
                                 f"[{unit}]{' up to %g' % LARGEST if value > 0.0 else ''}, "
                                 f"got {text!r}.", source=label, value=text, unit=unit)
    return value


def _envelope(text: str, label: str, where: str) -> tuple[list[float], list[float]]:
    speeds, torques = [], []
    for point in text.replace(";", " ").split():
        parts = point.split(":")
        try:
            speed, torque = (float(p) for p in parts)
        except ValueError:
            speed = torque = math.nan
        if len(parts) != 2 or not (math.isfinite(speed) and math.isfinite(torque)) \
                or speed < 0.0 or torque < 0.0:
            raise InputError.in_file(label, "envelope", f"of {where} must list points "
                                     f"rpm:N·m separated by spaces (\"0:9.5 3000:9.5 "
                                     f"6000:4\"), got {point!r}.", source=label, value=text)
        speeds.append(speed)
        torques.append(torque)
    if len(speeds) < 2 or any(b <= a for a, b in zip(speeds, speeds[1:])):
        raise InputError.in_file(label, "envelope", f"of {where} needs at least two points "
                                 f"with rising speeds, got {text!r}.", source=label, value=text)
    return speeds, torques

