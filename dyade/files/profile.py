"""Read a motion profile: the ``[profile]`` table of a mechanism file or of its own file.

```toml
[profile]
master = "angle"          # "angle" (degrees) or "time" (s)
period = 360              # one machine cycle [° or s]
unit = "mm"               # the output: a length (m, cm, mm, um) or an angle (deg, rad)

[[profile.segment]]       # one per segment, in order; `start` defaults to the end of
kind = "dwell"            # the one before (0 for the first), `from` to where it ended
end = 60

[[profile.segment]]
kind = "rise"
law = "modified-sine"
end = 150
to = 40
```

Every key is checked here with the file and the key path named (``profile.segment.2.end``);
the numbers are compared as written (segments that meet, positive durations, one period
covered); the laws themselves are built, and the profile's continuity checked, by the
engine (``dyade.motion.profile``). A reader computes nothing.
"""

from __future__ import annotations

import math
import os
from typing import Any

from dyade.files.schema import TableReader, fmt, read_toml, show
from dyade.units import ANGLE_FACTORS, LENGTH_FACTORS

PROFILE_KEYS = {"master", "period", "unit", "name", "segment"}
SEGMENT_KEYS = {"kind", "law", "params", "start", "end", "from", "to", "boundary",
                "start_velocity", "start_acceleration", "end_velocity", "end_acceleration"}
FILE_KEYS = {"name", "description", "profile"}
"""top-level keys of a profile file of its own"""
MASTER_UNITS = {"angle": ("deg", ANGLE_FACTORS["deg"]), "time": ("s", 1.0)}
"""master -> its unit in files and the size of that unit in SI"""
MEET_RTOL = 1e-9  # [-] numbers as written that differ by less than this share meet


def amount(value: float, unit: str) -> str:
    """A number of the file with its unit, as messages write it: 190°, 0.3 s, 40 mm."""
    return f"{fmt(value)}°" if unit == "deg" else f"{fmt(value)} {unit}"


def output_factor(unit: str) -> float:
    """Size of the output's unit in SI [m or rad per unit]."""
    return LENGTH_FACTORS.get(unit) or ANGLE_FACTORS[unit]


class ProfileReader(TableReader):
    """Walks a ``[profile]`` table with key paths for the error messages."""

    def profile(self, table: Any, name: str):
        from dyade.model.profile import ANGLE_UNITS, KINDS, LENGTH_UNITS, Profile, Segment

        self.keys(table, "profile", PROFILE_KEYS)
        master = table.get("master", "angle")
        if master not in MASTER_UNITS:
            raise self.fail("profile.master", f"must be \"angle\" (degrees) or \"time\" (s), "
                                              f"got {show(master)}.", master)
        x_unit, x_size = MASTER_UNITS[master]
        unit = table.get("unit", "mm")
        if unit not in LENGTH_UNITS + ANGLE_UNITS:
            raise self.fail("profile.unit", f"must be a length ({', '.join(LENGTH_UNITS)}) or "
                                            f"an angle ({', '.join(ANGLE_UNITS)}), got "
                                            f"{show(unit)}.", unit)
        s_size = output_factor(unit)
        name = table.get("name", name)
        if not isinstance(name, str):
            raise self.fail("profile.name", f"must be a string, got {show(name)}.", name)
        period = self.number(self.required(table, "period", "profile"), "profile.period",
                             x_unit, positive=True)
        tables = table.get("segment", [])
        if not isinstance(tables, list) or not tables or not all(
                isinstance(t, dict) for t in tables):
            raise self.fail("profile.segment", "must list the segments as [[profile.segment]] "
                                               "tables (at least one), got "
                                               f"{show(tables)}.", tables)
        segments, end, lift = [], 0.0, 0.0
        first_start = None
        for number, seg in enumerate(tables, start=1):
            path = f"profile.segment.{number}"
            self.keys(seg, path, SEGMENT_KEYS)
            kind = seg.get("kind")
            if kind not in KINDS:
                import difflib
                close = difflib.get_close_matches(str(kind), KINDS, n=1, cutoff=0.6)
                hint = (f" Did you mean `{close[0]}`?" if close
                        else f" Kinds: {', '.join(KINDS)}.")
                raise self.fail(f"{path}.kind", ("is missing." if kind is None else
                                                 f"must be a segment kind, got {show(kind)}.")
                                + ("" if kind is None else hint), kind)
            start = self.number(seg.get("start", end), f"{path}.start", x_unit)
            if number > 1 and abs(start - end) > MEET_RTOL * period:
                raise self.fail(f"{path}.start", f"= {amount(start, x_unit)} does not meet the "
                                f"end of segment {number - 1} ({amount(end, x_unit)}): segments "
                                f"run end to end (leave `start` out to take it).", start, x_unit)
            first_start = start if first_start is None else first_start
            stop = self.number(self.required(seg, "end", path), f"{path}.end", x_unit)
            if not stop - start > MEET_RTOL * period:  # shorter: the segments meet there
                raise self.fail(f"{path}.end", f"= {amount(stop, x_unit)} is not after the "
                                f"segment's start ({amount(start, x_unit)}): a segment needs a "
                                f"positive duration, got {amount(stop - start, x_unit)}"
                                + ("." if stop <= start else f" (less than {MEET_RTOL:g} of "
                                   f"the period)."), stop, x_unit)
            lift_from = self.number(seg.get("from", lift), f"{path}.from", unit)
            if number > 1 and abs(lift_from - lift) > MEET_RTOL * max(abs(lift), 1.0):
                raise self.fail(f"{path}.from", f"= {amount(lift_from, unit)} does not meet where "
                                f"segment {number - 1} ends ({amount(lift, unit)}): a jump in "
                                f"position (leave `from` out to take it).", lift_from, unit)
            lift_to = self.number(seg.get("to", lift_from), f"{path}.to", unit)
            self.direction(kind, lift_from, lift_to, f"{path}.to", unit, "to" in seg)
            law = seg.get("law")
            if law is not None and not isinstance(law, str):
                raise self.fail(f"{path}.law", f"must be the name of a motion law, got "
                                               f"{show(law)}.", law)
            if kind == "dwell" and law is not None:
                raise self.fail(f"{path}.law", "is given for a dwell, which has none: remove "
                                               "it, or make the segment a rise or a return.",
                                law)
            if kind in ("rise", "return") and law is None:
                raise self.fail(f"{path}.law", f"is missing: a {kind} needs a motion law "
                                               f"(for example \"modified-sine\"; dyade profile "
                                               f"--help lists them).")
            params = self.params(seg.get("params", {}), f"{path}.params")
            boundary = seg.get("boundary")
            if boundary is not None and not isinstance(boundary, str):
                raise self.fail(f"{path}.boundary", f"must be a string like \"R-R\", got "
                                                    f"{show(boundary)}.", boundary)
            given = {}
            for key in ("start_velocity", "start_acceleration", "end_velocity",
                        "end_acceleration"):
                if key in seg:
                    order = 1 if key.endswith("velocity") else 2
                    power = "" if order == 1 else "²"
                    if law != "polynomial":
                        raise self.fail(f"{path}.{key}", "is an end condition of the law "
                                        "\"polynomial\" only; other laws have theirs.",
                                        seg[key])
                    value = self.number(seg[key], f"{path}.{key}", f"{unit}/{'°' if x_unit == 'deg' else x_unit}{power}")
                    given[key] = value * s_size / x_size**order
            segments.append(Segment(kind, start * x_size, stop * x_size, lift_from * s_size,
                                    lift_to * s_size, law, params, boundary, **given))
            end, lift = stop, lift_to
        if abs(end - first_start - period) > MEET_RTOL * period:
            last = f"profile.segment.{len(tables)}.end"
            raise self.fail(last, f"= {amount(end, x_unit)}: the segments cover "
                            f"{amount(end - first_start, x_unit)}, the period is "
                            f"{amount(period, x_unit)}; the last segment must end one period after the first "
                            f"starts (add a dwell).", end, x_unit)
        try:
            return Profile(tuple(segments), period * x_size, master, unit, name, x_unit)
        except Exception as err:  # the model's own checks: said with the file's name
            from dyade.errors import InputError
            if isinstance(err, InputError):
                raise InputError(f"{self.label}: {err}", source=self.source, key=err.key,
                                 value=err.value, reason=err.reason) from None
            raise

    def direction(self, kind: str, lift_from: float, lift_to: float, key: str, unit: str,
                  written: bool) -> None:
        """Refuse a lift that contradicts the segment's kind."""
        moves = abs(lift_to - lift_from) > MEET_RTOL * max(abs(lift_from), abs(lift_to), 1.0)
        if kind == "dwell" and moves:
            raise self.fail(key, f"= {amount(lift_to, unit)} differs from `from` = "
                                 f"{amount(lift_from, unit)}: a dwell stands still (make it a "
                                 f"rise or a return).", lift_to, unit)
        if kind != "dwell" and not moves:
            raise self.fail(key, ("is missing" if not written else
                                  f"= {amount(lift_to, unit)} equals `from`") +
                            f": a {kind} must move (give `to`, or make it a dwell).",
                            lift_to, unit)
        if kind == "rise" and lift_to < lift_from:
            raise self.fail(key, f"= {amount(lift_to, unit)} is below `from` = "
                                 f"{amount(lift_from, unit)}: a rise goes up (make it a "
                                 f"return).", lift_to, unit)
        if kind == "return" and lift_to > lift_from:
            raise self.fail(key, f"= {amount(lift_to, unit)} is above `from` = "
                                 f"{amount(lift_from, unit)}: a return goes down (make it a "
                                 f"rise).", lift_to, unit)

    def params(self, table: Any, path: str) -> dict[str, Any]:
        """A law's parameters: numbers or (nested) lists of numbers, dimensionless."""
        if not isinstance(table, dict):
            raise self.fail(path, f"must be a table of the law's parameters, like "
                                  f"{{ ramp = 0.1 }}, got {show(table)}.", table)

        def numeric(value: Any) -> bool:
            if isinstance(value, list):
                return all(numeric(v) for v in value)
            return not isinstance(value, bool) and isinstance(value, (int, float)) and \
                math.isfinite(value)

        for key, value in table.items():
            if not numeric(value):
                raise self.fail(f"{path}.{key}", f"must be a number or a list of numbers [-], "
                                                 f"got {show(value)}.", value)
        return dict(table)


def read_profile(path: str | os.PathLike, text: str | None = None):
    """The motion profile of a file: its ``[profile]`` table (a mechanism file's, or a
    profile file's own).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (docs/guide/motion-laws.md describes every key).
    text : str, optional
        The file's content when already read.

    Returns
    -------
    Profile

    Raises
    ------
    InputError
        Naming the file and the key path (``profile.segment.2.end``).

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> profile = read_profile("mechanisms/profiles/indexing.toml")
    >>> profile.master, len(profile.segments), profile.unit
    ('angle', 5, 'mm')
    """
    from dyade.errors import InputError

    path = os.fspath(path)
    label = os.path.basename(path)
    data = read_toml(path, text)
    reader = ProfileReader(label, path)
    if "profile" not in data:
        raise InputError(f"{label}: has no [profile] table: a motion profile is a "
                         f"[profile] table with [[profile.segment]] tables (dyade init "
                         f"profile writes one).", source=path, key="profile")
    from dyade.files.mechanism.keys import TOP_KEYS
    reader.keys(data, "", FILE_KEYS | TOP_KEYS)
    default = data.get("name", os.path.splitext(label)[0])
    return reader.profile(data["profile"], default if isinstance(default, str) else label)
