"""The schema every input file shares: typed keys with units and range checks.

``TableReader`` walks parsed TOML with key paths, so that every error names the file,
the key, what was expected (with its unit) and what was found; unknown keys get a "Did
you mean". ``Field`` declares the keys of a flat file (key -> type, unit, default,
range), read by ``TableReader.fields``. ``read_toml``, ``parse_assignment`` and
``set_dotted`` are the file access and the ``--set`` overrides of every file kind.
"""

from __future__ import annotations

import math
import os
import tomllib
from typing import Any, NamedTuple

from dyade.arrays import Variants
from dyade.errors import InputError
from dyade.units import ANGLE_FACTORS, LENGTH_FACTORS


class Field(NamedTuple):
    """One key of a flat file."""

    kind: str
    """"number", "string" or "numbers" (a number or an array of numbers)"""
    unit: str = "-"
    """unit of a number, shown in messages"""
    check: str = ""
    """"", "positive" or "non_negative" """
    default: Any = None
    """value when the key is absent (None: absent stays absent)"""


def read_toml(path: str | os.PathLike, text: str | None = None) -> dict[str, Any]:
    """A TOML file as a dict; InputError naming the file when it cannot be read, is not
    UTF-8 text or is not valid TOML. ``text``: the content, already read (standard
    input), with ``path`` naming it."""
    path = os.fspath(path)
    return _parse(read_text(path) if text is None else text, path)


def read_text(path: str | os.PathLike) -> str:
    """A file's UTF-8 text; InputError naming the file when it cannot be read or is not
    UTF-8 text."""
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read()
    except OSError as err:
        raise InputError(f"{path}: cannot read the file ({err.strerror}).", source=path) from None
    except UnicodeDecodeError as err:
        raise InputError(f"{path}: not a UTF-8 text file (byte {err.start}: "
                         f"{err.object[err.start:err.start + 1]!r}); save it as UTF-8 TOML.",
                         source=path) from None


KINDS = (
    ("a mechanism file", {"sweep", "frame", "crank", "dyad", "links", "gravity", "load",
                          "spring", "friction", "drive"},
     "dyade describe, analyse, clearance, accuracy, flywheel, balance and plot"),
    ("a gear-drive file", {"model", "material", "body", "shaft", "bearing", "element", "gear",
                           "mesh", "excitation", "speed"},
     "dyade gears, plot campbell and plot modes"),
    ("a coupling file", {"J", "c1", "c2", "b1", "b2", "moment", "eta_range", "speed_rpm",
                         "order"},
     "dyade coupling and plot coupling"),
    ("a study file", {"mechanism", "plan", "parameters", "tolerance", "optimise",
                      "sensitivity", "outputs"},
     "dyade study and plot study"),
)
"""each kind of input file: its own top-level keys and the commands that read it"""


def other_kind(table: dict[str, Any], allowed: set[str] | dict) -> str:
    """" It is a gear-drive file: …" when the top-level keys of ``table`` that
    ``allowed`` does not know belong to another kind of dyade file (two of them, or
    every key of the file), else ""."""
    unknown = [name for name in table if name not in allowed]
    for kind, keys, commands in KINDS:
        ours = [name for name in unknown if name in keys]
        if ours and (len(ours) >= 2 or all(name in keys or name in ("name", "description",
                                                                    "units")
                                           for name in table)):
            return (f" It looks like {kind} (it has {', '.join(f'`{n}`' for n in ours[:3])}), "
                    f"which {commands} read.")
    return ""


def _parse(text: str, path: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        first = text.lstrip("\ufeff").split("\n", 1)[0]
        if path.lower().endswith(".csv") or ("," in first and "=" not in first
                                             and "[" not in first):
            raise InputError(f"{path}: not a TOML file: it looks like a CSV file (a torque "
                             f"curve or a sweep), which dyade flywheel reads.",
                             source=path) from None
        raise InputError(f"{path}: not valid TOML: {err}.", source=path) from None
    except RecursionError:
        raise InputError(f"{path}: arrays or tables nested too deeply to read; no dyade file "
                         f"needs more than three levels.", source=path) from None


def load_data(path: str | os.PathLike, overrides: dict[str, Any] | None = None,
              what: str = "override", text: str | None = None,
              first: dict[str, tuple[int, str]] | None = None) -> dict[str, Any]:
    """A file's TOML data with ``overrides`` (dotted key -> value) applied; ``what``
    names them in messages; ``text``: the file's content when already read (stdin);
    ``first``: arrays of tables not numbered from 1 (``set_dotted``)."""
    path = os.fspath(path)
    data = read_toml(path, text)
    for key, value in (overrides or {}).items():
        set_dotted(data, key, value, os.path.basename(path), what, first)
    return data


def parse_assignment(text: str) -> tuple[str, Any]:
    """``KEY=VALUE`` of ``--set``: VALUE is read as a TOML value (number, string, array,
    inline table, true/false); anything that is not TOML is taken as a string."""
    if "=" not in text:
        raise InputError(f"--set {text}: expected KEY=VALUE with a dotted key as in the file, "
                         f"e.g. --set crank.speed_rpm=600.")
    key, raw = (part.strip() for part in text.split("=", 1))
    if not key or any(not part for part in key.split(".")):
        raise InputError(f"--set {text}: the key `{key}` is not a dotted key path.")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    return key, value


def set_dotted(data: dict[str, Any], dotted: str, value: Any, label: str = "",
               what: str = "override", first: dict[str, tuple[int, str]] | None = None
               ) -> None:
    """Replace the key at a dotted path in ``data``; array entries by number, from 1 or
    from ``first[path] = (number of the first entry, what that numbering is)``.
    ``what`` names the overrides in messages (the command line says ``--set``)."""
    parts = dotted.split(".")
    target: Any = data
    for depth, part in enumerate(parts):
        path = ".".join(parts[:depth])  # the container's path
        final = depth == len(parts) - 1
        if isinstance(target, list):
            base, why = (first or {}).get(path, (1, ""))
            top = base + len(target) - 1
            if not part.isdigit() or not base <= int(part) <= top:
                numbers = f"{base}…{top}" if target else "none"
                raise InputError(f"{label}: {what} {dotted}: the entries of `{path}` are numbered "
                                 f"{numbers}, got {part}{f' ({why})' if why else ''}.",
                                 source=label, key=dotted)
            if final:
                target[int(part) - base] = value
                return
            target = target[int(part) - base]
        elif isinstance(target, dict):
            if final:
                target[part] = value
                return
            target = target.setdefault(part, {})
        else:
            raise InputError(f"{label}: {what} {dotted}: `{path}` is a value, not a table.",
                             source=label, key=dotted)


def value_range(text: str, unit: str = "", positive_start: bool = False,
                most: int = 10_000_000) -> list[float]:
    """START:STOP:STEP as the list of its values (``range_parts``, ``range_values``);
    ``ValueError`` saying what is wrong (``unit`` shown in the expected form): not three
    finite numbers, START below 0 (or 0 with ``positive_start``), STOP below START, STEP
    not positive, or more than ``most`` values."""
    start, stop, step = range_parts(text, unit)
    low = "0 < START" if positive_start else "0 <= START"
    if not (step > 0 and stop >= start and (start > 0 if positive_start else start >= 0)):
        raise ValueError(f"needs {low} <= STOP and STEP > 0, got {text!r}.")
    return range_values(start, stop, step, most)


def range_parts(text: str, unit: str = "") -> tuple[float, float, float]:
    """START:STOP:STEP as three finite numbers; ``ValueError`` saying what is wrong."""
    try:
        start, stop, step = (float(part) for part in text.split(":"))
    except ValueError:
        raise ValueError(f"must be START:STOP:STEP{unit}, got {text!r}.") from None
    if not all(math.isfinite(v) for v in (start, stop, step)):
        raise ValueError(f"needs finite numbers, got {text!r}.")
    return start, stop, step


def range_values(start: float, stop: float, step: float, most: int, what: str = "values"
                 ) -> list[float]:
    """START, START + STEP, … up to STOP (included to within 1e-9 of a step);
    ``ValueError`` for more than ``most`` of them (``what`` they are, in the message)."""
    import numpy as np

    with np.errstate(over="ignore"):
        count = np.floor((stop - start) / step + 1e-9) + 1
    if not count <= most:
        shown = f"{count:.0f}" if np.isfinite(count) else "too many"
        raise ValueError(f"asks for {shown} {what}; at most {most}.")
    return (start + step * np.arange(int(count))).tolist()


def suggest(key: str, allowed: set[str] | dict) -> str:
    """" Did you mean `x`?" for a misspelt key, else the allowed keys."""
    import difflib  # only for a misspelt key

    close = difflib.get_close_matches(key, sorted(allowed), n=1, cutoff=0.6)
    return f" Did you mean `{close[0]}`?" if close else f" Allowed: {', '.join(sorted(allowed))}."


def show(value: Any) -> str:
    """A value as the user wrote it, for messages."""
    if isinstance(value, str):
        return f"\"{value}\""
    if isinstance(value, dict):
        return "a table"
    return repr(value)


def fmt(value: float) -> str:
    return f"{value:g}"


def is_number(value: Any) -> bool:
    """A number of the file (an int or a float, not a bool), or ``Variants``: one per
    variant of a block of a study."""
    return (not isinstance(value, bool) and isinstance(value, (int, float))) or isinstance(
        value, Variants)


CEILINGS = {"kg": "mass", "kg·m²": "inertia", "N/m": "stiffness", "N·m/rad": "stiffness",
            "N·s/m": "damping", "N·m·s/rad": "damping", "rpm": "speed_rpm", "Hz": "frequency",
            "N·m": "torque", "N": "force", "m/s²": "acceleration", "Pa": "modulus",
            "kg/m³": "density"}
"""unit of a number read -> its quantity in ``dyade.limits.PLAUSIBLE``: a magnitude above
that range's top is refused wherever a file gives it (the floors are each key's own).
Seconds are not among them: a time constant and a machine's cycle time differ."""


class TableReader:
    """Walks parsed TOML with key paths for the error messages.

    ``label`` names the file in messages (its base name), ``source`` is its path.
    ``top_keys``: the file's top-level keys, for the hint that a key was written below
    a [table] header by mistake.

    Every number read with a unit of ``CEILINGS`` is refused above what a machine has
    (``ceiling``; keys in ``unbounded`` are left to their reader's own rule).
    """

    top_keys: set[str] = set()
    ceiling = True
    unbounded: frozenset[str] = frozenset()

    def __init__(self, label: str, source: str | None = None) -> None:
        self.label = label
        self.source = source

    def fail(self, key: str, message: str, value: Any = None, unit: str | None = None
             ) -> InputError:
        return InputError.in_file(self.label, key, message, source=self.source, value=value,
                                  unit=unit)

    def keys(self, table: Any, key: str, allowed: set[str] | dict) -> dict[str, Any]:
        if not isinstance(table, dict):
            raise self.fail(key, f"must be a table, got {show(table)}.", table)
        for name in table:
            if name not in allowed:
                where = f"{key}.{name}" if key else name
                if key and name in self.top_keys:
                    hint = (f" `{name}` is a top-level key: move it above the first [table] "
                            f"header (in TOML, keys after a [header] belong to that table).")
                elif not key and other_kind(table, allowed):
                    hint = other_kind(table, allowed)
                else:
                    hint = suggest(name, allowed)
                raise InputError(f"{self.label}: unknown key `{where}`.{hint}",
                                 source=self.source, key=where)
        return table

    def required(self, table: dict[str, Any], key: str, path: str) -> Any:
        if key not in table:
            raise self.fail(f"{path}.{key}" if path else key, "is missing.")
        return table[key]

    def within(self, value: float, key: str, quantity: str, unit: str,
               floor: bool = True) -> float:
        """``value`` when 0 (none) or within what a machine has (``dyade.limits.PLAUSIBLE``
        of ``quantity``, in SI = ``unit``), else refused naming ``key`` and the range;
        without ``floor`` only its top (tiny link masses are the force floor's business)."""
        from dyade.limits import PLAUSIBLE, implausible

        if isinstance(value, Variants):  # each variant's own check (all at once; one
            import numpy as np                  # by one for the message of one that fails)

            low, high, _ = PLAUSIBLE[quantity]
            v = np.asarray(value)
            if (np.isfinite(v) & (low <= v) & (v <= high) | (v == 0.0)
                    | (not floor and v <= high)).all():
                return value
            for one in value:
                self.within(float(one), key, quantity, unit, floor)
            return value
        if value != 0.0 and implausible(quantity, value) and (floor or value > PLAUSIBLE[
                quantity][1]):
            low, high, _ = PLAUSIBLE[quantity]
            raise self.fail(key, f"must lie in {low:g}…{high:g} {unit} (what a machine has), "
                                 f"got {value:g}.", value, unit)
        return value

    def number(self, value: Any, key: str, unit: str, positive: bool = False,
               non_negative: bool = False) -> float:
        if not is_number(value):
            raise self.fail(key, f"must be a number [{unit}], got {show(value)}.", value, unit)
        if isinstance(value, Variants):  # each variant's own check (all at once; one
            import numpy as np               # by one for the message of one that fails)

            v = np.asarray(value)
            if not (np.isfinite(v).all() and (not positive or (v > 0.0).all())
                    and (not non_negative or (v >= 0.0).all())):
                for one in value:
                    self.number(float(one), key, unit, positive, non_negative)
            if self.ceiling and key not in self.unbounded:
                self.below_top(value, key, CEILINGS.get(unit), unit)
            return value
        value = float(value)
        if not math.isfinite(value):
            raise self.fail(key, f"must be a finite number [{unit}], got {value}.", value, unit)
        if positive and value <= 0.0:
            raise self.fail(key, f"must be positive [{unit}], got {fmt(value)}.", value, unit)
        if non_negative and value < 0.0:
            raise self.fail(key, f"must not be negative [{unit}], got {fmt(value)}.", value, unit)
        if self.ceiling and key not in self.unbounded:
            self.below_top(value, key, CEILINGS.get(unit), unit)
        return value

    def below_top(self, value: float, key: str, quantity: str | None, unit: str,
                  scale: float = 1.0) -> None:
        """Refuse ``value`` [``unit``; ``value * scale`` in SI] whose magnitude lies above
        what a machine has (``dyade.limits.PLAUSIBLE[quantity]``), naming ``key`` and the
        range; nothing for ``quantity`` None."""
        if quantity is None:
            return
        from dyade.limits import PLAUSIBLE

        if isinstance(value, Variants):  # each variant's own check (all at once; one
            import numpy as np               # by one for the message of one that fails)

            if not (np.abs(np.asarray(value) * scale) > PLAUSIBLE[quantity][1]).any():
                return
            for one in value:
                self.below_top(float(one), key, quantity, unit, scale)
            return
        low, high, _ = PLAUSIBLE[quantity]
        if abs(value * scale) > high:
            shown = f"{low / scale:g}…{high / scale:g}{'' if unit == '-' else f' {unit}'}"
            raise self.fail(key, f"must lie in {shown} (what a machine has), got {value:g}.",
                            value, unit)  # as ``within`` words it

    def integer(self, value: Any, key: str) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(key, f"must be a whole number, got {show(value)}.", value)
        return value

    def fields(self, table: dict[str, Any], spec: dict[str, Field], path: str = ""
               ) -> dict[str, Any]:
        """Check a flat table against ``spec``: unknown keys, types, finiteness, ranges;
        defaults filled in. Numbers come back as floats, arrays of numbers as lists."""
        self.keys(table, path, spec)
        out: dict[str, Any] = {}
        for name, field in spec.items():
            key = f"{path}.{name}" if path else name
            if name not in table:
                if field.default is not None:
                    out[name] = field.default
                continue
            value = table[name]
            if field.kind == "string":
                if not isinstance(value, str):
                    raise self.fail(key, f"must be a string, got {show(value)}.", value)
                out[name] = value
                continue
            many = field.kind == "numbers" and isinstance(value, list)
            values = value if many else [value]
            if field.kind == "numbers" and not all(is_number(v) for v in values):
                raise self.fail(key, f"must be a number or a list of numbers [{field.unit}], "
                                     f"got {show(value)}.", value, field.unit)
            checked = [self.number(v, key, field.unit, positive=field.check == "positive",
                                   non_negative=field.check == "non_negative") for v in values]
            out[name] = checked if many else checked[0]
        return out


class UnitReader(TableReader):
    """A reader of a file with a ``[units]`` table: lengths in ``units.length``, angles in
    ``units.angle`` (default m and degrees), converted to SI by ``length_of``,
    ``angle_of``."""

    def __init__(self, label: str, source: str | None = None) -> None:
        super().__init__(label, source)
        self.length = 1.0
        self.angle = math.pi / 180.0
        self.length_unit = "m"
        self.angle_unit = "deg"

    def length_of(self, value: Any, key: str, positive: bool = False,
                  non_negative: bool = False) -> float:
        number = self.number(value, key, self.length_unit, positive, non_negative)
        if self.ceiling:
            self.below_top(number, key, "length", self.length_unit, self.length)
        return number * self.length

    def angle_of(self, value: Any, key: str) -> float:
        return self.number(value, key, self.angle_unit) * self.angle

    def units(self, table: Any) -> None:
        self.keys(table, "units", {"length", "angle"})
        length = table.get("length", "m")
        if length not in LENGTH_FACTORS:
            raise self.fail("units.length", f"must be one of {', '.join(LENGTH_FACTORS)}, "
                                            f"got {show(length)}.")
        angle = table.get("angle", "deg")
        if angle not in ANGLE_FACTORS:
            raise self.fail("units.angle", f"must be one of {', '.join(ANGLE_FACTORS)}, "
                                           f"got {show(angle)}.")
        self.length, self.length_unit = LENGTH_FACTORS[length], length
        self.angle, self.angle_unit = ANGLE_FACTORS[angle], angle
