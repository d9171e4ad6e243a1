"""``profile``: a motion profile over one machine cycle (VDI 2143 laws, segment by segment).

The input is a profile file (or a mechanism file with a ``[profile]`` table), or a
``Profile``. The Outcome's table runs over the cycle: the master (``angle_deg`` or
``time_s``), the output's position ``s`` and its derivatives ``v``, ``a``, ``j`` with
respect to the master, in the file's units (``mm``, ``mm/°``, ``mm/°²``, ``mm/°³``);
with ``speed_rpm`` (an angle master) per second instead, and the time ``time_s``. The
summary gives each segment's law, its boundary classes, its characteristic values
C_v, C_a, C_j, C_M and its peaks, and the profile's peaks. The continuity of the
profile is checked first: a jump refused (exit 2, naming the segment and key), an
acceleration jump its law's class allows said as a note.
"""

from __future__ import annotations

import os
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome

OPTIONS = (
    Option("points", int, default=361, positive=True, least=2,
           help="Rows of the table over one cycle, both ends included (361: every degree "
                "of a 360° cycle)"),
    Option("speed", float, "rpm", positive=True,
           help="Master speed (an angle master): the table in time, v, a, j per second"),
)

BYTES_PER_POINT = 30 * 8.0  # [B] the arrays of one point: master, s, v, a, j, masks, columns
MASTER_WORDS = {"deg": "°", "s": "s", "rad": "rad"}
"""the master's unit in files -> as tables show it"""
OUTPUT_WORDS = {"deg": "°", "rad": "rad", "m": "m", "cm": "cm", "mm": "mm", "um": "µm"}


def load(source: Any):
    """The Profile of ``source`` (a path, or already a Profile) and a label for errors."""
    from dyade.files.profile import read_profile
    from dyade.model.profile import Profile

    if isinstance(source, Profile):
        return source, ""
    if source is None:
        from dyade.errors import InputError
        raise InputError("profile needs a profile file (or a mechanism file with a "
                         "[profile] table): dyade init profile writes one.")
    return read_profile(source), os.path.basename(os.fspath(source))


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import numpy as np

    from dyade.errors import InputError

    with np.errstate(over="ignore", invalid="ignore"):
        try:
            outcome = tabulate(source, options, budget)
            numbers = [np.asarray(v, dtype=float) for v in outcome.columns.values()]
            numbers += [np.asarray(f.value, dtype=float) for f in outcome.summary.values()
                        if isinstance(f.value, (int, float))]
            finite = all(np.isfinite(v).all() for v in numbers)
        except OverflowError:
            finite = False
    if not finite:  # lifts over durations (or a master speed) beyond floating point
        where = "" if not isinstance(source, (str, os.PathLike)) else \
            f"{os.path.basename(os.fspath(source))}: "
        raise InputError(f"{where}the profile's velocity, acceleration or jerk exceed the "
                         f"range of numbers (a lift too large for its segment's duration, "
                         f"or --speed too small): check the segments' `to` and `end` in "
                         f"[profile], and the master speed.", key="profile.segment")
    return outcome


def tabulate(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``run`` without its range check: the Outcome as computed."""
    import numpy as np

    from dyade.errors import InputError
    from dyade.files.profile import MASTER_UNITS, output_factor
    from dyade.motion import profile as engine
    from dyade.units import RPM

    profile, label = load(source)
    x_file, x_size = MASTER_UNITS[profile.master]
    s_size = output_factor(profile.unit)
    x_word, s_word = MASTER_WORDS[x_file], OUTPUT_WORDS[profile.unit]
    speed = options.get("speed_rpm")
    if speed is not None and profile.master != "angle":
        raise InputError.parameter("speed_rpm", "applies to an angle master only: this "
                                                "profile's master is the time already.",
                                   value=speed, unit="rpm")
    points = int(options.get("points") or 361)
    if points < 2:
        raise InputError.parameter("points", f"must be at least 2, got {points}.",
                                   value=points)
    from dyade.analyses.base import MAX_MEMORY
    from dyade.limits import check_memory

    check_memory(points * BYTES_PER_POINT, f"the profile at {points:,} points",
                 budget.max_memory, "Ask for fewer points", MAX_MEMORY.api)
    budget.time(points * 2e-7, f"the profile at {points:,} points")
    try:
        laws = engine.segment_laws(profile)
        notes = list(engine.check(profile, laws, (x_word, x_size, s_word, s_size)))
    except InputError as err:
        if label and err.key and err.key.startswith("profile."):
            raise InputError(f"{label}: {err}", source=os.fspath(source), key=err.key,
                             value=err.value, reason=err.reason) from None
        raise
    x = profile.start + profile.period * np.linspace(0.0, 1.0, points)
    inside = x.copy()
    inside[-1] = profile.start + profile.period * (1.0 - 1e-15)  # the cycle's end, from inside
    motion = engine.evaluate(profile, inside, laws)
    omega = None if speed is None else speed * RPM
    if omega is None:
        master_name, master_values = f"{profile.master}_{x_file}", x / x_size
        rates = (x_size, x_word)
    else:
        master_name = "time_s"
        master_values = (x - profile.start) / omega
        rates = (1.0 / omega, "s")
    rate, rate_word = rates
    units = {"s": s_word, "v": f"{s_word}/{rate_word}", "a": f"{s_word}/{rate_word}²",
             "j": f"{s_word}/{rate_word}³"}
    columns: dict[str, Any] = {}
    if omega is not None:
        columns["angle_deg"] = x / x_size
    columns[master_name] = master_values
    columns["s"] = motion.s / s_size
    columns["v"] = motion.v * rate / s_size
    columns["a"] = motion.a * rate**2 / s_size
    columns["j"] = motion.j * rate**3 / s_size
    columns["segment"] = motion.segment + 1
    names = {"angle_deg": "°", "time_s": "s"}
    outcome = Outcome("profile", figures=("profile",),
                      meta={"name": profile.name, "source": None if not label
                            else os.fspath(source), "master": profile.master,
                            "unit": profile.unit},
                      result=(profile, laws, motion, omega))
    outcome.columns = columns
    outcome.units = {**{n: names[n] for n in columns if n in names}, **units, "segment": "-"}
    outcome.descriptions = {
        "angle_deg": "master angle", "time_s": "time",
        "s": "output's position", "v": f"velocity ds/d{'t' if rate_word == 's' else 'φ'}",
        "a": "acceleration", "j": "jerk", "segment": "segment (from 1)"}
    outcome.descriptions = {n: outcome.descriptions[n] for n in columns}
    add = outcome.add
    add("period", profile.period / x_size, x_word, description="one machine cycle")
    if omega is not None:
        add("cycle_time", profile.period / omega, "s",
            description="one cycle at the master speed")
    peaks = engine.peaks(profile, laws)
    where_name = master_name
    for symbol, field, order in (("v", "velocity", 1), ("a", "acceleration", 2),
                                 ("j", "jerk", 3)):
        values = np.abs(columns[symbol])
        k = int(np.argmax(values))
        best = max(peaks, key=lambda p: getattr(p, field))
        add(f"{symbol}_max", getattr(best, field) * rate**order / s_size, units[symbol],
            where={where_name: float(master_values[k]), "segment": best.number},
            description=f"peak |{symbol}| (exact: h·C_{symbol}/T{'' if order == 1 else '^' + str(order)})"
            if symbol != "j" else "peak |j| inside the segments (not at a jump of a)")
    for peak in peaks:
        if not peak.law:
            continue
        k = peak.number
        segment = profile.segments[k - 1]
        add(f"segment{k}_law", peak.law, "-", description=f"segment {k}: {segment.kind}, "
            f"{segment.start / x_size:g}–{segment.end / x_size:g} {x_word}")
        add(f"segment{k}_boundary", peak.boundary, "-", description="  boundary classes "
            "start-end (R rest, G constant velocity, U reversal, B motion)")
        for name in ("C_v", "C_a", "C_j", "C_M"):
            add(f"segment{k}_{name}", getattr(peak, name), "-",
                description=f"  characteristic value {name}")
        for symbol, field, order in (("v", "velocity", 1), ("a", "acceleration", 2),
                                     ("j", "jerk", 3)):
            add(f"segment{k}_{symbol}_max", getattr(peak, field) * rate**order / s_size,
                units[symbol], description=f"  peak |{symbol}|")
    outcome.notes = notes
    return outcome


ENTRIES = {"profile": Analysis("profile", "Motion profile over a machine cycle (VDI 2143 "
                               "laws)", run, OPTIONS, source="profile", figures=("profile",),
                               command="dyade profile")}
"""``dyade profile``: a motion profile over the machine cycle; the registry's ``profile``
entry (``dyade.analyses.profile``)."""
