"""A motion profile evaluated over the machine cycle: position, velocity, acceleration
and jerk of the output at any master angle or time, its continuity checked at every
boundary of its segments, and its characteristic values and peaks.

Each segment k runs its law S(z) over z = (x − x_k)/T_k with the lift h_k:
s = s_k + h_k·S, v = h_k/T_k·S′, a = h_k/T_k²·S″, j = h_k/T_k³·S‴ (derivatives with
respect to the master: per rad or per s; SI: m or rad). A segment with the law
``"polynomial"`` takes its end conditions as given, or else from its neighbours: the
velocity and acceleration the neighbour has at the shared boundary (rest where the
neighbour is itself such a polynomial without them).

>>> import math
>>> import numpy as np
>>> from dyade.model.profile import Profile, Segment
>>> from dyade.motion.profile import evaluate, check
>>> profile = Profile((Segment("rise", 0.0, math.pi, 0.0, 0.05, law="cycloid"),
...                    Segment("return", math.pi, 2 * math.pi, 0.05, 0.0, law="cycloid")),
...                   period=2 * math.pi)
>>> motion = evaluate(profile, np.array([0.0, math.pi / 2, 3 * math.pi]))
>>> np.round(motion.s, 6).tolist(), round(float(motion.v[1]), 6)   # [m], [m/rad]
([0.0, 0.025, 0.05], 0.031831)
>>> check(profile)
()
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.errors import InputError
from dyade.model.profile import Profile, Segment, segment_error
from dyade.motion.laws import END_ATOL, Law, end_class, law

FloatArray = np.ndarray
JUMP_RTOL = 1e-9  # [-] a jump smaller than this share of the profile's scale is none


@dataclass(frozen=True)
class Motion:
    """The output's motion at the master values ``x`` (one entry per value).

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> moved = motion.evaluate(indexing, [1.833])        # 105° [rad]: mid-rise
    >>> round(float(moved.s[0]), 4), int(moved.segment[0])
    (0.02, 1)
    """

    x: FloatArray
    """master [rad or s], as asked"""
    s: FloatArray
    """position [m or rad]"""
    v: FloatArray
    """velocity ds/dx [m or rad per rad or s]"""
    a: FloatArray
    """acceleration d²s/dx² [per rad² or s²]"""
    j: FloatArray
    """jerk d³s/dx³ [per rad³ or s³]"""
    segment: FloatArray
    """index (from 0) of the segment each x falls in"""


@dataclass(frozen=True)
class Boundary:
    """Where segment ``number − 1`` (the last one for the first) hands over to segment
    ``number``: the master there and the jumps right minus left."""

    number: int
    """the segment that starts here (from 1)"""
    x: float
    """master at the boundary [rad or s]"""
    jumps: tuple[float, float, float, float]
    """jump of s, v, a, j [m or rad; per rad (s), per rad² (s²), per rad³ (s³)]"""
    left: tuple[float, float, float, float]
    """s, v, a, j at the end of the segment before"""
    right: tuple[float, float, float, float]
    """s, v, a, j at the start of this segment"""


@dataclass(frozen=True)
class SegmentPeaks:
    """A segment's law, its characteristic values and its peaks in SI."""

    number: int
    """the segment (from 1)"""
    kind: str
    """dwell, rise, return, constant-velocity"""
    law: str
    """its law's name ("" for a dwell)"""
    boundary: str
    """the classes of its ends as run, start-end ("R-R", "G-U", …; "R-R" for a dwell)"""
    C_v: float
    """characteristic velocity of its law [-] (0 for a dwell)"""
    C_a: float
    """characteristic acceleration [-]"""
    C_j: float
    """characteristic jerk [-]"""
    C_M: float
    """characteristic torque factor: the largest magnitude of S′·S″ [-]"""
    velocity: float
    """peak velocity (magnitude) h·C_v/T [m or rad per rad or s]"""
    acceleration: float
    """peak acceleration (magnitude) h·C_a/T² [per rad² or s²]"""
    jerk: float
    """peak jerk (magnitude) h·C_j/T³ inside the segment [per rad³ or s³]"""


def normalised(value: float | None, segment: Segment, order: int) -> float | None:
    """A physical end velocity (order 1) or acceleration (order 2) of ``segment`` as the
    law's normalised one: v·T/h, a·T²/h."""
    return None if value is None else value * segment.duration**order / segment.lift


def physical(law_: Law, segment: Segment, z: FloatArray
             ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """s, v, a, j of ``segment`` running ``law_`` at the normalised z (SI)."""
    s, v, a, j = law_(z)
    h, t = segment.lift, segment.duration
    return segment.lift_from + h * s, h / t * v, h / t**2 * a, h / t**3 * j


def fixed_law(number: int, segment: Segment) -> Law | None:
    """The law of a segment whose law does not depend on its neighbours (None for a
    dwell); the errors name the segment and the key."""
    name = segment.law_name
    if name is None:
        return None
    try:
        return law(name, **segment.params)
    except InputError as err:
        key = "law" if err.key == "law" else f"params.{err.key}"
        raise segment_error(number, segment, key, err.reason or str(err), err.value) from None


def end_values(profile: Profile, laws: list[Law | None], index: int, at_end: bool
               ) -> tuple[float, float] | None:
    """(v, a) of segment ``index`` at its end (or start) when known without solving a
    polynomial's ends: a dwell rests, a fixed law gives its own, a polynomial what is
    given there (None when not given)."""
    segment = profile.segments[index]
    if segment.kind == "dwell":
        return 0.0, 0.0
    if segment.law_name == "polynomial":
        v, a = (segment.end_velocity, segment.end_acceleration) if at_end else (
            segment.start_velocity, segment.start_acceleration)
        return None if v is None and a is None else (v or 0.0, a or 0.0)
    _, v, a, _ = physical(laws[index], segment, np.array(1.0 if at_end else 0.0))
    return float(v), float(a)


def segment_laws(profile: Profile) -> tuple[Law | None, ...]:
    """The law each segment runs (None for a dwell), a polynomial's end conditions
    resolved: given ones, else its neighbour's at the shared boundary (the cycle wraps:
    the last segment is the first one's neighbour).

    Parameters
    ----------
    profile : Profile

    Returns
    -------
    tuple of Law or None
        One per segment.

    Raises
    ------
    InputError
        A misspelt law (did-you-mean) or a bad parameter, naming the segment and key.

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> [law.name if law else None for law in motion.segment_laws(indexing)]
    [None, 'modified-sine', None, 'polynomial-4567', None]
    """
    segments = profile.segments
    count = len(segments)
    laws: list[Law | None] = [None if s.law_name == "polynomial" else fixed_law(k, s)
                              for k, s in enumerate(segments, start=1)]
    for index, segment in enumerate(segments):
        if segment.law_name != "polynomial":
            continue
        given = list(segment.given)
        before = end_values(profile, laws, (index - 1) % count, at_end=True)
        after = end_values(profile, laws, (index + 1) % count, at_end=False)
        before = before or (0.0, 0.0)
        after = after or (0.0, 0.0)
        physical_ends = [given[0] if given[0] is not None else before[0],
                         given[1] if given[1] is not None else before[1],
                         given[2] if given[2] is not None else after[0],
                         given[3] if given[3] is not None else after[1]]
        v0, a0, v1, a1 = (normalised(value, segment, order)
                          for value, order in zip(physical_ends, (1, 2, 1, 2)))
        laws[index] = law("polynomial", v0=v0, a0=a0, v1=v1, a1=a1)
    return tuple(laws)


def evaluate(profile: Profile, x: FloatArray, laws: tuple[Law | None, ...] | None = None
             ) -> Motion:
    """The output's motion at the master values ``x`` (periodic over the cycle).

    Parameters
    ----------
    profile : Profile
    x : array_like
        Master values [rad or s], any shape, any cycle (a motion that advances per cycle
        adds its advance per cycle).
    laws : tuple, optional
        ``segment_laws(profile)`` when already built.

    Returns
    -------
    Motion
        s [m or rad] and its derivatives with respect to the master (per rad or per s).

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> import numpy as np
    >>> cycle = motion.evaluate(indexing, np.radians([105.0, 105.0 + 360.0]))
    >>> cycle.s.round(12).tolist()                        # [m], periodic
    [0.02, 0.02]
    """
    x = np.asarray(x, dtype=float)
    laws = segment_laws(profile) if laws is None else laws
    cycles = np.floor((x - profile.start) / profile.period)
    within = x - profile.start - cycles * profile.period + profile.start
    starts = np.array([s.start for s in profile.segments[1:]])
    which = np.searchsorted(starts, within, side="right")
    out = [np.zeros(x.shape) for _ in range(4)]
    for index, (segment, law_) in enumerate(zip(profile.segments, laws)):  # per segment
        mask = which == index
        if not mask.any():
            continue
        if law_ is None:
            out[0][mask] = segment.lift_from
            continue
        z = (within[mask] - segment.start) / segment.duration
        for target, values in zip(out, physical(law_, segment, z)):
            target[mask] = values
    out[0] = out[0] + cycles * profile.advance
    return Motion(x, out[0], out[1], out[2], out[3], which)


def ends(profile: Profile, laws: tuple[Law | None, ...]
         ) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
    """(s, v, a, j) at the start and at the end of every segment (SI)."""
    out = []
    for segment, law_ in zip(profile.segments, laws):
        if law_ is None:
            rest = (segment.lift_from, 0.0, 0.0, 0.0)
            out.append((rest, rest))
            continue
        values = physical(law_, segment, np.array([0.0, 1.0]))
        out.append((tuple(float(v[0]) for v in values), tuple(float(v[1]) for v in values)))
    return out


def boundaries(profile: Profile, laws: tuple[Law | None, ...] | None = None
               ) -> tuple[Boundary, ...]:
    """Every boundary of the cycle (the first segment's start included: the cycle
    wraps) with the jumps of s, v, a, j there.

    Parameters
    ----------
    profile : Profile
    laws : tuple, optional
        ``segment_laws(profile)`` when already built.

    Returns
    -------
    tuple of Boundary

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> [max(abs(jump) for jump in b.jumps[:3]) < 1e-12
    ...  for b in motion.boundaries(indexing)]            # s, v, a continuous
    [True, True, True, True, True]
    """
    laws = segment_laws(profile) if laws is None else laws
    values = ends(profile, laws)
    out = []
    for index, segment in enumerate(profile.segments):
        left = list(values[index - 1][1])
        if index == 0:
            left[0] -= profile.advance       # the cycle before ends one advance lower
        right = values[index][0]
        out.append(Boundary(index + 1, segment.start,
                            tuple(r - l for r, l in zip(right, left)),  # type: ignore[arg-type]
                            tuple(left), right))  # type: ignore[arg-type]
    return tuple(out)


def scales(profile: Profile) -> tuple[float, float, float]:
    """Typical s, v, a of the profile [SI] for the tolerances of its checks."""
    lifts = [abs(s.lift) for s in profile.segments] or [0.0]
    level = max(max(abs(s.lift_from), abs(s.lift_to)) for s in profile.segments)
    scale_s = max(max(lifts), level) or 1.0
    scale_v = max((abs(s.lift) / s.duration for s in profile.segments), default=0.0) or 1.0
    scale_a = max((abs(s.lift) / s.duration**2 for s in profile.segments), default=0.0) or 1.0
    return scale_s, scale_v, scale_a


def classes(profile: Profile, laws: tuple[Law | None, ...]) -> tuple[str, ...]:
    """The VDI 2143 classes of every segment's ends as run: ``"R-G"``…"""
    out = []
    _, scale_v, scale_a = scales(profile)
    for (start, end) in ends(profile, laws):
        first = end_class(start[1] / scale_v * END_ATOL / JUMP_RTOL, start[2] / scale_a
                          * END_ATOL / JUMP_RTOL)
        last = end_class(end[1] / scale_v * END_ATOL / JUMP_RTOL, end[2] / scale_a
                         * END_ATOL / JUMP_RTOL)
        out.append(f"{first}-{last}")
    return tuple(out)


def check(profile: Profile, laws: tuple[Law | None, ...] | None = None,
          units: tuple[str, float, str, float] | None = None) -> tuple[str, ...]:
    """Check the profile continuous in position, velocity and acceleration at every
    boundary and each segment's declared ``boundary`` classes.

    A jump in position or velocity is refused; a jump in acceleration is allowed where
    the law of the segment whose acceleration does not vanish there has that end of
    class U or B by its nature (the simple harmonic at a dwell, a parabola): said as a
    note (the jerk is infinite there). A given acceleration (law ``polynomial``) that
    does not meet its neighbour's is refused.

    Parameters
    ----------
    units : (str, float, str, float), optional
        The units the messages show: (master unit, its size in SI, output unit, its
        size in SI), e.g. ``("°", pi/180, "mm", 1e-3)``; SI when not given.

    Returns
    -------
    tuple of str
        The notes (allowed jumps).

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> motion.check(indexing)
    ()

    Raises
    ------
    InputError
        A refused jump or a declared class the law does not have, naming the segment
        and the key.
    """
    laws = segment_laws(profile) if laws is None else laws
    scale_s, scale_v, scale_a = scales(profile)
    if units is None:
        units = ("rad" if profile.master == "angle" else "s", 1.0,
                 "m" if profile.output == "length" else "rad", 1.0)
    x_unit, x_size, s_unit, s_size = units

    def at(x: float) -> str:
        return f"{x / x_size:g} {x_unit}".replace(" °", "°")

    def rate(value: float, order: int) -> str:
        power = "" if order == 1 else "²"
        return f"{value * x_size**order / s_size:.6g} {s_unit}/{x_unit}{power}"

    notes: list[str] = []
    count = len(profile.segments)
    runs = classes(profile, laws)
    for number, (segment, law_, run) in enumerate(zip(profile.segments, laws, runs), start=1):
        if segment.boundary is not None and law_ is not None:
            declared = segment.boundary.upper()
            if declared != run:
                raise segment_error(number, segment, "boundary", f"= \"{declared}\" but the "
                                    f"law {law_.name} runs {run} here (R rest, G constant "
                                    f"velocity, U reversal, B motion): choose a law of class "
                                    f"{declared} or the law \"polynomial\" with the end "
                                    f"conditions of {declared}.", segment.boundary)
    for boundary in boundaries(profile, laws):
        number = boundary.number
        before = (number - 2) % count + 1
        segment, other = profile.segments[number - 1], profile.segments[before - 1]
        ds, dv, da, _ = boundary.jumps
        where = f"at its start (master {at(boundary.x)})"
        if abs(ds) > JUMP_RTOL * scale_s:
            raise segment_error(number, segment, "from", f"= {boundary.right[0]:g} but segment "
                                f"{before} ends at {boundary.left[0]:g}: a jump in position "
                                f"{where}.", boundary.right[0])
        if abs(dv) > JUMP_RTOL * scale_v:
            key = ("start_velocity" if segment.start_velocity is not None else "law")
            raise segment_error(number, segment, key, f"makes the velocity jump from "
                                f"{rate(boundary.left[1], 1)} to {rate(boundary.right[1], 1)} "
                                f"{where}, after segment {before} "
                                f"({other.kind}{', ' + other.law_name if other.law_name else ''}): "
                                f"an infinite acceleration (a shock). Choose laws whose "
                                f"classes meet there (R with R or U, G with G), or the law "
                                f"\"polynomial\", which takes its neighbours' velocity and "
                                f"acceleration.", segment.law_name)
        if abs(da) > JUMP_RTOL * scale_a:
            given_here = segment.law_name == "polynomial" and segment.start_acceleration is not None
            given_there = other.law_name == "polynomial" and other.end_acceleration is not None
            if given_here or given_there:
                culprit, seg, key = ((number, segment, "start_acceleration") if given_here
                                     else (before, other, "end_acceleration"))
                raise segment_error(culprit, seg, key, f"does not meet the acceleration of "
                                    f"the neighbouring segment (a jump of {rate(da, 2)} at "
                                    f"master {at(boundary.x)}): give "
                                    f"the same value, or leave it out to take the "
                                    f"neighbour's.", seg.start_acceleration
                                    if culprit == number else seg.end_acceleration)
            causes = []
            if abs(boundary.right[2]) > JUMP_RTOL * scale_a and laws[number - 1] is not None:
                causes.append(f"segment {number} ({laws[number - 1].title}, class "
                              f"{laws[number - 1].boundary})")
            if abs(boundary.left[2]) > JUMP_RTOL * scale_a and laws[before - 1] is not None:
                causes.append(f"segment {before} ({laws[before - 1].title}, class "
                              f"{laws[before - 1].boundary})")
            notes.append(f"The acceleration jumps by {rate(da, 2)} at master "
                         f"{at(boundary.x)} (start of segment {number}): "
                         f"{' and '.join(causes)} does not bring it to zero there, as its "
                         f"class allows; the jerk is infinite at that instant.")
    return tuple(notes)


def peaks(profile: Profile, laws: tuple[Law | None, ...] | None = None
          ) -> tuple[SegmentPeaks, ...]:
    """Each segment's characteristic values and its peak velocity, acceleration and jerk
    (magnitudes; SI, exact: the law's characteristic values scaled by the lift and the
    duration).

    Parameters
    ----------
    profile : Profile
    laws : tuple, optional
        ``segment_laws(profile)`` when already built.

    Returns
    -------
    tuple of SegmentPeaks
        One per segment.

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> rise = motion.peaks(indexing)[1]
    >>> rise.law, round(rise.C_a, 4), round(rise.acceleration, 6)   # [m/rad²]
    ('modified-sine', 5.528, 0.089616)
    """
    laws = segment_laws(profile) if laws is None else laws
    runs = classes(profile, laws)
    out = []
    for number, (segment, law_, run) in enumerate(zip(profile.segments, laws, runs), start=1):
        if law_ is None:
            out.append(SegmentPeaks(number, segment.kind, "", "R-R", 0.0, 0.0, 0.0, 0.0,
                                    0.0, 0.0, 0.0))
            continue
        h, t = abs(segment.lift), segment.duration
        out.append(SegmentPeaks(number, segment.kind, law_.name, run, law_.C_v, law_.C_a,
                                law_.C_j, law_.C_M, h * law_.C_v / t, h * law_.C_a / t**2,
                                h * law_.C_j / t**3))
    return tuple(out)


def at_speed(motion: Motion, speed: float, start: float = 0.0) -> Motion:
    """The motion in time at a constant master speed: x becomes the time from
    ``start`` [s], and v, a, j derivatives with respect to time (v·ω, a·ω², j·ω³).

    Parameters
    ----------
    motion : Motion
        Of an angle master (``evaluate``).
    speed : float
        The master's speed ω [rad/s].
    start : float
        The master angle at time 0 [rad].

    Returns
    -------
    Motion

    Examples
    --------
    >>> from dyade.files.profile import read_profile
    >>> from dyade.motion import profile as motion
    >>> indexing = read_profile("mechanisms/profiles/indexing.toml")
    >>> import math
    >>> timed = motion.at_speed(motion.evaluate(indexing, [1.833]), 2 * math.pi)  # 60 rpm
    >>> round(float(timed.v[0]), 4)                       # [m/s]
    0.2815
    """
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError.parameter("speed", f"must be positive [rad/s], got {speed:g}.",
                                   value=speed, unit="rad/s")
    return Motion((motion.x - start) / speed, motion.s, motion.v * speed,
                  motion.a * speed**2, motion.j * speed**3, motion.segment)
