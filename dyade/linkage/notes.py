"""The findings of a sweep a user must know about, as data: what kind, what it concerns,
where (crank-angle ranges) and the figures that tell how much. Their wording is the
report's (``dyade.report.notes``); the engine writes no sentences.
"""

from __future__ import annotations

import enum
from typing import Any, NamedTuple

import numpy as np

from dyade.arrays import FloatArray


class NoteKind(enum.StrEnum):
    """What a note is about (a ``str``: ``note.kind == "dead_centre"`` holds).

    >>> import dyade
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/self-locking.toml"))
    >>> sorted({note.kind for note in result.notes})
    ['at_rest', 'near_self_locking', 'self_locking']
    >>> dyade.NoteKind.SELF_LOCKING == "self_locking"
    True
    """

    PARTIAL = "partial"
    """some dyad does not close over part of the sweep; those positions are left out"""
    DEAD_CENTRE = "dead_centre"
    """a dyad within the dead-centre band: nothing is given there"""
    POOR_TRANSMISSION = "poor_transmission"
    """a transmission angle below the designers' rule: results given, with care"""
    IMPLAUSIBLE = "implausible"
    """values beyond ``PLAUSIBLE`` (kinematics or forces): those rows are not given"""
    FORCES_INVALID = "forces_invalid"
    """forces not given where the kinematics is"""
    NEAR_SELF_LOCKING = "near_self_locking"
    """a dyad's friction-augmented determinant small or friction's gain large"""
    FRICTION_NOT_CONVERGED = "friction_not_converged"
    """no consistent friction solution (per position), or the equation of motion's
    friction torque did not settle (figures["where"] == "drive")"""
    AT_REST = "at_rest"
    """a joint with friction at rest relative to its partner: no friction applied"""
    NEVER_MOVES = "never_moves"
    """a joint with friction that never moves over the sweep: no friction loss"""
    SELF_LOCKING = "self_locking"
    """a joint whose friction makes its dyad lock (a friction dead centre)"""
    RUN_UP_NOT_SETTLED = "run_up_not_settled"
    """a run-up that did not become periodic within its revolutions"""
    CLEARANCE_NOT_APPLICABLE = "clearance_not_applicable"
    """the clearance check does not apply to a joint, or not on a run-up"""
    DRIVE_LINE_SOFT = "drive_line_soft"
    """the drive line's ratio Ω/ω̄ exceeds VDI 2149's 0.1: the rigid model does not hold"""
    LIFT_OFF = "lift_off"
    """a spring-closed cam follower would need a pull (contact force below 0): it lifts
    off, and the chain's forces are not given there"""

    def __repr__(self) -> str:
        return repr(self.value)  # as the plain string it equals


Span = tuple[float, float]


class Note(NamedTuple):
    """A finding of the sweep: its ``kind``, its ``subject`` ("dyad 3", "joint (3,4)",
    "slider (1,4)", or ""), the crank-angle ``ranges`` (first, last) [rad] where it holds
    (() where it is not positional) and the ``figures`` that size it (plain numbers and
    names: the dyad's number, the bands [rad], counts, the decimals [°] that tell the
    sweep's positions apart). ``dyade.report.notes.say`` words it.

    >>> import dyade
    >>> from dyade.report.notes import say
    >>> mechanism = dyade.read_mechanism("mechanisms/dyade-16.toml")
    >>> note, = dyade.analyse(mechanism).notes
    >>> note.kind, note.subject
    ('poor_transmission', 'dyad 7')
    >>> print(say(note, mechanism))
    dyad 7 (kind 1 RRR, links 13-14) has a transmission angle below 40° (the designers'
    rule) at crank angles 119.0°–204.0°, 29.5° at the least (crank angle 162.0°):
    results are given, but the drive is sensitive to friction, clearance and elasticity
    there.
    """

    kind: NoteKind
    subject: str
    ranges: tuple[Span, ...]
    figures: dict[str, Any]


def ranges(crank_angle: FloatArray, mask: FloatArray) -> list[Span]:
    """Crank-angle ranges [rad] (first, last) of runs of True in ``mask``."""
    if not mask.any():
        return []
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(float(crank_angle[a]), float(crank_angle[b - 1]))
            for a, b in zip(edges[::2], edges[1::2])]


def format_ranges(spans, limit: int = 6, digits: int = 1) -> str:
    """'212.0°–247.5°, 300.0°' for crank-angle ranges [rad], with ``digits`` decimals
    (the words of an error message, and of the report's notes)."""
    parts = []
    for first, last in spans:
        a, b = np.rad2deg(first), np.rad2deg(last)
        parts.append(f"{a:.{digits}f}°" if first == last else f"{a:.{digits}f}°–{b:.{digits}f}°")
    if len(parts) > limit:
        parts = parts[:limit] + [f"and {len(parts) - limit} more"]
    return ", ".join(parts)


def decimals(crank_angle: FloatArray) -> int:
    """Decimals [°] that tell the positions of a sweep apart: 1 for 1°, 2 for 0.01°."""
    if crank_angle.size < 2:
        return 1
    step = float(np.rad2deg(np.min(np.abs(np.diff(crank_angle)))))
    return int(min(6, max(1, np.ceil(-np.log10(step) - 1e-9)))) if step > 0 else 1
