"""Statistics over one crank revolution — the mean, the RMS and the integral of a sampled
periodic curve — one function each, used by ``analyse`` (its summary), ``balance``,
``flywheel`` and the plots alike, so that every command prints the same figure.

A sweep 0°–360° holds the same position twice: these functions count it once. The
samples of a revolution are periodic (``revolution``): the last angle repeats the first
(it is dropped), or the sweep stops short of the next revolution by at most 1.5 steps
(the closing interval is the gap to the first angle plus 2π). A periodic curve is
integrated interval by interval with its cubic Hermite interpolant, the slopes by
three-point differences (``integrals``: fourth order for smooth curves, and for equal
steps exactly the periodic trapezoid rule, the plain mean of the distinct positions).
A sweep over part of a revolution is averaged over its own span by the trapezoid rule.

>>> import numpy as np
>>> phi = np.deg2rad(np.arange(0.0, 361.0, 1.0))           # 0°..360°: 360° repeats 0°
>>> torque = 1.0 + np.cos(phi)
>>> round(mean(phi, torque), 12), round(rms(phi, torque), 12)   # 1 and sqrt(1.5)
(1.0, 1.224744871392)
"""

from __future__ import annotations

import math

import numpy as np

from dyade.arrays import FloatArray
from dyade.roundoff import ROUNDOFF, clean

TURN = 2.0 * math.pi
CLOSE_RTOL = 1e-9  # [-] a last angle this close to the first plus 2π repeats it
EQUAL_RTOL = 1e-12  # [-] steps that differ by no more than this share are equal
GAP_STEPS = 1.5  # a sweep this many steps short of 2π still covers the revolution


def revolution(angle: FloatArray, values: FloatArray) -> tuple[FloatArray, FloatArray, bool]:
    """(angles, values, periodic): the distinct positions of a sweep ``angle`` [rad]
    (rising) with their ``values``, and whether they cover one revolution (the module
    docstring): a repeated last position is dropped."""
    angle = np.asarray(angle, dtype=np.float64)
    values = np.asarray(values, dtype=np.float64)
    if angle.size < 3:
        return angle, values, False
    span = float(angle[-1] - angle[0])
    if abs(span - TURN) <= CLOSE_RTOL * TURN:
        return angle[:-1], values[:-1], True
    steps = np.diff(angle)
    return angle, values, span < TURN and TURN - span <= GAP_STEPS * float(np.max(steps))


def segments(angle: FloatArray, values: FloatArray, ahead: FloatArray | None = None
             ) -> tuple[FloatArray, FloatArray]:
    """Interval lengths h_i of a periodic curve's distinct positions (the last one
    closing the revolution) and its three-point slopes (``ahead``: ``_ahead(values)``
    if the caller has it)."""
    h = np.diff(np.append(angle, angle[0] + TURN))
    left = np.roll(h, 1)
    if ahead is None:  # (each difference once: the next's is this one's)
        step = _ahead(values)
        step -= values
    else:
        step = np.subtract(ahead, values)
    # (left²·step + h²·step_behind) / (left·h·(left + h)), in place
    slope = _behind(step)
    slope *= h * h
    step *= left * left
    slope += step
    slope /= left * h * (left + h)
    return h, slope


def _ahead(values: FloatArray) -> FloatArray:
    """``np.roll(values, -1, axis=-1)``: each position's next, the last's the first."""
    out = np.empty_like(values)
    out[..., :-1] = values[..., 1:]
    out[..., -1] = values[..., 0]
    return out


def _behind(values: FloatArray) -> FloatArray:
    """``np.roll(values, 1, axis=-1)``: each position's previous, the first's the last."""
    out = np.empty_like(values)
    out[..., 1:] = values[..., :-1]
    out[..., 0] = values[..., -1]
    return out


def integrals(angle: FloatArray, values: FloatArray) -> FloatArray:
    """∫ over each interval of a periodic curve's cubic Hermite interpolant (the last
    interval closes the revolution), at its distinct positions (``values``: one curve,
    or one per row, all at ``angle``)."""
    ahead = _ahead(values)
    h, slope = segments(angle, values, ahead)
    # 0.5·h·(y_i + y_i+1) + h²/12·(s_i − s_i+1), in place (the same operations)
    ahead += values
    ahead *= 0.5 * h
    change = _ahead(slope)
    np.subtract(slope, change, out=change)
    change *= h * h / 12.0
    ahead += change
    return ahead


def mean(angle: FloatArray, values: FloatArray) -> float:
    """The mean of ``values`` over the crank angle ``angle`` [rad]: over the revolution
    if the sweep covers one (each position once), else over the sweep's span (trapezoid
    rule); finite values only (where some are not, the trapezoid rule over those given).
    NaN if none is; 0 where it is round-off of the values (``dyade.roundoff``). One
    curve of ``means``."""
    values = np.asarray(values, dtype=np.float64)
    return float(means(angle, values.reshape(1, -1))[0])


def _one(angle: FloatArray, values: FloatArray) -> float:
    """``mean`` of one curve that is not finite over a whole revolution."""
    keep = np.isfinite(values)
    if not keep.any():
        return float("nan")
    return clean(_mean(angle, values, keep), float(np.max(np.abs(values[keep]))))


def _mean(angle: FloatArray, values: FloatArray, keep: FloatArray) -> float:
    """``mean`` before the round-off rule."""
    if not keep.all():
        angle, values = angle[keep], values[keep]
    else:
        distinct, cycle, periodic = revolution(angle, values)
        if periodic:
            return float(np.sum(integrals(distinct, cycle)) / TURN)
    if angle.size < 2:
        return float(values.mean()) if values.size else float("nan")
    return float(np.sum((values[1:] + values[:-1]) * np.diff(angle))
                 / (2.0 * (angle[-1] - angle[0])))


def means(angle: FloatArray, values: FloatArray) -> FloatArray:
    """``mean`` of every row of ``values`` (variants, positions), all at the crank angle
    ``angle`` [rad]: one reduction over the rows finite over a whole revolution, ``mean``
    row by row for the others (a partial sweep, gaps)."""
    angle = np.asarray(angle, dtype=np.float64)
    values = np.asarray(values, dtype=np.float64)
    out = np.empty(values.shape[0])
    distinct, _, periodic = revolution(angle, angle)
    whole = np.zeros(len(out), dtype=bool)
    if periodic and values.size:  # a row's largest and least: finite where all its
        high, low = np.max(values, axis=1), np.min(values, axis=1)  # values are (NaN
        whole = np.isfinite(high) & np.isfinite(low)  # propagates)
    if whole.any():
        rows = values if whole.all() else values[whole]
        totals = (np.sum(rows[:, :distinct.size], axis=-1) / distinct.size
                  if equal_steps(distinct) else
                  np.sum(integrals(distinct, rows[:, :distinct.size]), axis=-1) / TURN)
        scale = np.maximum(high, -low)  # max |row|
        if not whole.all():
            scale = scale[whole]
        out[whole] = np.where(np.abs(totals) <= ROUNDOFF * scale, 0.0, totals + 0.0)
    for k in np.flatnonzero(~whole):
        out[k] = _one(angle, values[k])
    return out


def equal_steps(distinct: FloatArray) -> bool:
    """Whether the distinct positions of a revolution (``revolution``) are equally
    spaced, the closing interval included (to ``EQUAL_RTOL``): their mean is then the
    plain mean of the values (what ``integrals`` sum to, without its slopes)."""
    h = np.diff(np.append(distinct, distinct[0] + TURN))
    return bool(np.ptp(h) <= EQUAL_RTOL * np.mean(h))


def rmss(angle: FloatArray, values: FloatArray) -> FloatArray:
    """``rms`` of every row of ``values`` (variants, positions) (``means``)."""
    values = np.asarray(values, dtype=np.float64)
    return np.sqrt(means(angle, values * values))


def rms(angle: FloatArray, values: FloatArray) -> float:
    """The root mean square of ``values`` over the crank angle ``angle`` [rad]
    (``mean`` of the squares)."""
    values = np.asarray(values, dtype=np.float64)
    return float(np.sqrt(mean(angle, values * values)))
