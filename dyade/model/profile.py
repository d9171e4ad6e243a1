"""A motion profile over a machine cycle (SI): segments of motion laws over the master
variable, a crank angle [rad] or the time [s]. Data and the checks of the data alone
(segments that meet, positive durations, kinds that agree with their lifts); evaluating
the profile is ``dyade.motion.profile``.

>>> from dyade.model.profile import Profile, Segment
>>> import math
>>> rise = Segment("rise", 0.0, math.pi, 0.0, 0.05, law="cycloid")
>>> back = Segment("return", math.pi, 2 * math.pi, 0.05, 0.0, law="polynomial-345")
>>> Profile((rise, back), period=2 * math.pi).output
'length'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from dyade.errors import InputError

KINDS = ("dwell", "rise", "return", "constant-velocity")
"""the kinds of a segment"""
MASTERS = {"angle": "rad", "time": "s"}
"""master variable -> its SI unit"""
LENGTH_UNITS = ("m", "cm", "mm", "um")
ANGLE_UNITS = ("deg", "rad")
CLASSES = "RGUB"
"""VDI 2143 boundary classes: R rest, G constant velocity, U reversal, B motion"""
MEET_RTOL = 1e-9  # [-] two ends meet when they differ by less than this share of the scale


@dataclass(frozen=True)
class Segment:
    """One segment of a profile: a law from ``start`` to ``end`` of the master variable
    carrying the output from ``lift_from`` to ``lift_to``.

    The end conditions ``start_velocity`` … ``end_acceleration`` are those of the law
    ``"polynomial"`` (the quintic of given end conditions), in SI per unit of the master
    (m/rad, m/rad², rad/s, …); ``None`` matches the neighbouring segment there.

    Examples
    --------
    >>> import math
    >>> from dyade.model.profile import Segment
    >>> rise = Segment("rise", 0.0, math.pi / 2, 0.0, 0.04, law="modified-sine")
    >>> round(rise.duration, 6), rise.lift, rise.law_name
    (1.570796, 0.04, 'modified-sine')
    """

    kind: str
    """"dwell", "rise", "return" or "constant-velocity" """
    start: float
    """master at the segment's start [rad or s]"""
    end: float
    """master at its end [rad or s]"""
    lift_from: float
    """output at the start [m or rad]"""
    lift_to: float
    """output at the end [m or rad]"""
    law: str | None = None
    """the motion law's name (``dyade.motion.laws.LAWS``); None for a dwell (and
    ``"constant-velocity"`` for that kind)"""
    params: dict[str, Any] = field(default_factory=dict)
    """the law's parameters (``ramp``, ``points``, ``velocity`` …)"""
    boundary: str | None = None
    """the classes its ends must have, start-end (``"R-R"``, ``"R-G"``, ``"U-U"``…); None:
    whatever its law gives"""
    start_velocity: float | None = None
    """given velocity at the start [m or rad per rad or s] (law ``polynomial``)"""
    start_acceleration: float | None = None
    """given acceleration at the start [per rad² or s²] (law ``polynomial``)"""
    end_velocity: float | None = None
    """given velocity at the end (law ``polynomial``)"""
    end_acceleration: float | None = None
    """given acceleration at the end (law ``polynomial``)"""

    @property
    def duration(self) -> float:
        """end − start [rad or s]"""
        return self.end - self.start

    @property
    def lift(self) -> float:
        """lift_to − lift_from [m or rad] (negative for a return)"""
        return self.lift_to - self.lift_from

    @property
    def law_name(self) -> str | None:
        """The law the segment runs (``"constant-velocity"`` for that kind even when
        not written; None for a dwell)."""
        if self.kind == "dwell":
            return None
        if self.kind == "constant-velocity" and self.law is None:
            return "constant-velocity"
        return self.law

    @property
    def given(self) -> tuple[float | None, float | None, float | None, float | None]:
        """(start_velocity, start_acceleration, end_velocity, end_acceleration)"""
        return (self.start_velocity, self.start_acceleration, self.end_velocity,
                self.end_acceleration)


def segment_error(number: int, segment: Segment | None, key: str, reason: str,
                  value: Any = None, unit: str | None = None) -> InputError:
    """An ``InputError`` about key ``key`` of segment ``number`` (counted from 1):
    its key path is ``profile.segment.N.key`` (the reader names the file)."""
    what = ""
    if segment is not None:
        law = segment.law_name if segment.law_name not in (None, segment.kind) else None
        what = f" ({segment.kind}{f', {law}' if law else ''})"
    err = InputError(f"segment {number}{what}: `{key}` {reason}",
                     key=f"profile.segment.{number}.{key}", value=value, unit=unit,
                     reason=reason)
    err.segment = number
    return err


@dataclass(frozen=True)
class Profile:
    """A motion profile over one machine cycle: its segments in order, end to end,
    covering one ``period`` of the master from the first segment's start.

    An output that does not come back to where it started (an indexing table that
    advances each cycle) repeats with that advance per cycle.

    Examples
    --------
    >>> import math
    >>> from dyade.model.profile import Profile, Segment
    >>> table = Profile((Segment("rise", 0.0, 1.5 * math.pi, 0.0, math.pi / 2, "cycloid"),
    ...                  Segment("dwell", 1.5 * math.pi, 2 * math.pi, math.pi / 2,
    ...                          math.pi / 2)), period=2 * math.pi, unit="deg")
    >>> table.output, round(table.advance, 6)          # a quarter turn per cycle [rad]
    ('angle', 1.570796)
    """

    segments: tuple[Segment, ...]
    """the segments in order of the master"""
    period: float
    """one machine cycle of the master [rad or s]"""
    master: str = "angle"
    """"angle" (a crank or cam angle, [rad] inside, degrees in files) or "time" [s]"""
    unit: str = "mm"
    """the output's unit in files and tables: a length (m, cm, mm, um) or an angle
    (deg, rad); inside SI (m or rad)"""
    name: str = "profile"
    """a name for titles"""
    master_unit: str = "deg"
    """the master's unit in files and tables: deg or rad for an angle, s for time"""

    def __post_init__(self) -> None:
        if self.master not in MASTERS:
            raise InputError.parameter("master", f"must be \"angle\" or \"time\", got "
                                                 f"{self.master!r}.", value=self.master)
        if self.unit not in LENGTH_UNITS + ANGLE_UNITS:
            raise InputError.parameter("unit", f"must be a length ({', '.join(LENGTH_UNITS)}) "
                                               f"or an angle ({', '.join(ANGLE_UNITS)}), got "
                                               f"{self.unit!r}.", value=self.unit)
        if not (math.isfinite(self.period) and self.period > 0.0):
            raise InputError.parameter("period", f"must be positive, got {self.period:g}.",
                                       value=self.period)
        if not self.segments:
            raise InputError.parameter("segments", "are missing: a profile needs at least "
                                                   "one segment.")
        scale_x = self.period
        scale_s = max(max(abs(s.lift_from), abs(s.lift_to)) for s in self.segments) or 1.0
        for number, segment in enumerate(self.segments, start=1):
            self.check_segment(number, segment, scale_s)
            if number > 1:
                before = self.segments[number - 2]
                if abs(segment.start - before.end) > MEET_RTOL * scale_x:
                    raise segment_error(number, segment, "start", f"= {segment.start:g} "
                                        f"does not meet the end of segment {number - 1} "
                                        f"({before.end:g}): segments run end to end.",
                                        segment.start)
                if abs(segment.lift_from - before.lift_to) > MEET_RTOL * scale_s:
                    raise segment_error(number, segment, "from", f"= {segment.lift_from:g} "
                                        f"does not meet where segment {number - 1} ends "
                                        f"(to = {before.lift_to:g}): a jump in position.",
                                        segment.lift_from)
        covered = self.segments[-1].end - self.segments[0].start
        if abs(covered - self.period) > MEET_RTOL * scale_x:
            last = len(self.segments)
            raise segment_error(last, self.segments[-1], "end", f"= {self.segments[-1].end:g}: "
                                f"the segments cover {covered:g} of the master, the period "
                                f"is {self.period:g}; the last segment must end one period "
                                f"after the first starts (add a dwell).",
                                self.segments[-1].end)

    @staticmethod
    def check_segment(number: int, segment: Segment, scale: float) -> None:
        """Refuse a segment whose data contradict each other (naming it and the key)."""
        if segment.kind not in KINDS:
            import difflib
            close = difflib.get_close_matches(str(segment.kind), KINDS, n=1, cutoff=0.6)
            hint = f" Did you mean `{close[0]}`?" if close else f" Kinds: {', '.join(KINDS)}."
            raise segment_error(number, None, "kind", f"must be a segment kind, got "
                                f"{segment.kind!r}.{hint}", segment.kind)
        for key, value in (("start", segment.start), ("end", segment.end),
                           ("from", segment.lift_from), ("to", segment.lift_to)):
            if not math.isfinite(value):
                raise segment_error(number, segment, key, f"must be a finite number, got "
                                    f"{value}.", value)
        if not segment.duration > 0.0:
            raise segment_error(number, segment, "end", f"= {segment.end:g} is not after its "
                                f"start ({segment.start:g}): a segment needs a positive "
                                f"duration, got {segment.duration:g}.", segment.end)
        moves = abs(segment.lift) > MEET_RTOL * scale
        if segment.kind == "dwell":
            if moves:
                raise segment_error(number, segment, "to", f"= {segment.lift_to:g} differs "
                                    f"from `from` = {segment.lift_from:g}: a dwell stands "
                                    f"still (make it a rise or a return).", segment.lift_to)
            if segment.law is not None:
                raise segment_error(number, segment, "law", "is given for a dwell, which "
                                    "has none: remove it, or make the segment a rise or a "
                                    "return.", segment.law)
            return
        if not moves:
            raise segment_error(number, segment, "to", f"= {segment.lift_to:g} equals `from`: "
                                f"a {segment.kind} must move (make it a dwell).",
                                segment.lift_to)
        if segment.kind == "rise" and segment.lift < 0.0:
            raise segment_error(number, segment, "to", f"= {segment.lift_to:g} is below "
                                f"`from` = {segment.lift_from:g}: a rise goes up (make it a "
                                f"return).", segment.lift_to)
        if segment.kind == "return" and segment.lift > 0.0:
            raise segment_error(number, segment, "to", f"= {segment.lift_to:g} is above "
                                f"`from` = {segment.lift_from:g}: a return goes down (make "
                                f"it a rise).", segment.lift_to)
        if segment.kind == "constant-velocity" and segment.law not in (None,
                                                                        "constant-velocity"):
            raise segment_error(number, segment, "law", f"= {segment.law!r} for a constant "
                                f"velocity, which runs its own law: leave `law` out, or make "
                                f"the segment a rise or a return.", segment.law)
        if segment.law_name is None:
            raise segment_error(number, segment, "law", f"is missing: a {segment.kind} "
                                f"needs a motion law (for example \"modified-sine\").")
        if segment.boundary is not None:
            parts = segment.boundary.upper().split("-")
            if len(parts) != 2 or any(len(p) != 1 or p not in CLASSES for p in parts):
                raise segment_error(number, segment, "boundary", f"must be two classes "
                                    f"start-end of R (rest), G (constant velocity), U "
                                    f"(reversal), B (motion), like \"R-R\"; got "
                                    f"{segment.boundary!r}.", segment.boundary)

    @property
    def output(self) -> str:
        """"length" or "angle": what the output is"""
        return "length" if self.unit in LENGTH_UNITS else "angle"

    @property
    def start(self) -> float:
        """The master at the cycle's start (the first segment's start) [rad or s]."""
        return self.segments[0].start

    @property
    def advance(self) -> float:
        """How far the output moves per cycle [m or rad] (0 for a motion that comes
        back)."""
        return self.segments[-1].lift_to - self.segments[0].lift_from
