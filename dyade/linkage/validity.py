"""The validity policy of a sweep, decided over all its positions before any result is
given: where the mechanism closes (the assembly check) and where the rigid model holds
(the dead-centre and transmission bands).

``Policy`` keeps, per position, what the policy needs of the kinematics (17 B per dyad
and position), filled block by block by the pipeline's first pass.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import AssemblyError
from dyade.linkage.kinematics import Kinematics
from dyade.linkage.notes import Note, NoteKind, decimals, format_ranges, ranges
from dyade.model.mechanism import Mechanism


@dataclass(slots=True, eq=False)
class Policy:
    """What the validity policy reads of the kinematics of a whole sweep."""

    crank_angle: FloatArray
    """(n,) [rad]"""
    closes: FloatArray
    """(n, dyads) bool: the dyad closes"""
    transmission: FloatArray
    """(n, dyads) transmission angle μ [rad]"""
    conditioning: FloatArray
    """(n, dyads) distance from a dead centre in [0, 1]"""
    valid: FloatArray
    """(n,) bool: every dyad closes and none is singular"""
    digits: int
    """the decimals [°] that tell the sweep's positions apart (``notes.decimals``)"""

    @classmethod
    def empty(cls, crank_angle: FloatArray, dyads: int) -> Policy:
        n = crank_angle.shape[0]
        return cls(crank_angle, np.empty((n, dyads), dtype=bool), np.empty((n, dyads)),
                   np.empty((n, dyads)), np.empty(n, dtype=bool), decimals(crank_angle))

    def keep(self, first: int, last: int, kin: Kinematics) -> None:
        """Take over a block's kinematics at positions first..last−1."""
        for name in ("closes", "transmission", "conditioning", "valid"):
            getattr(self, name)[first:last] = getattr(kin, name)


def assembly(mechanism: Mechanism, policy: Policy, allow_partial: bool,
             notes: list[Note]) -> FloatArray:
    """(n,) bool: the positions where every dyad closes (the rows reported); an
    ``AssemblyError`` naming the dyads and ranges where some does not, unless
    ``allow_partial`` (then a note)."""
    angle, closes, digits = policy.crank_angle, policy.closes, policy.digits
    upstream = np.ones(angle.shape[0], dtype=bool)
    problems, failing = [], []
    for col, dyad in enumerate(mechanism.dyads):
        fails = upstream & ~closes[:, col]
        if fails.any():
            spans = ranges(angle, fails)
            failing.append((dyad.number, tuple(spans)))
            problems.append(f"{dyad.label} {dyad.kind.cannot_close} for crank angles "
                            f"{format_ranges(spans, digits=digits)}")
        upstream = upstream & closes[:, col]
    if not problems:
        return np.ones(angle.shape[0], dtype=bool)
    kept = int(upstream.sum())
    if kept == 0:
        raise AssemblyError("the mechanism closes at no crank angle of the sweep: "
                            + "; ".join(problems) + ".", tuple(problems))
    if not allow_partial:
        raise AssemblyError("; ".join(problems) + ". Change the dimensions or the sweep, or "
                            "analyse only where it closes (allow_partial=True).",
                            tuple(problems), partial=True)
    notes.append(Note(NoteKind.PARTIAL, "", tuple(ranges(angle, ~upstream)),
                      {"failing": tuple(failing), "kept": kept, "positions": upstream.size,
                       "digits": digits}))
    return upstream


def bands(mechanism: Mechanism, policy: Policy, rows: FloatArray,
          notes: list[Note]) -> FloatArray:
    """(n,) bool, the positions whose kinematics is given.

    Each dyad's quality at each position comes from its own geometry (the sine of its
    transmission angle; an RPR dyad's also from its pivot distance): within the hard
    band (``dead_centre_angle`` of 0° or 180°) the rigid model is invalid and nothing is
    given; in the soft band (transmission angle below ``transmission_warning``, the
    designers' rule) results are given with a note naming the dyad, the ranges and the
    smallest transmission angle."""
    angle, digits = policy.crank_angle, policy.digits
    hard = np.sin(mechanism.dead_centre_angle)
    soft = np.sin(mechanism.transmission_warning)
    well = rows & policy.valid
    for col, dyad in enumerate(mechanism.dyads):
        quality = policy.conditioning[:, col]
        near = rows & (quality <= hard)
        if near.any():
            notes.append(Note(NoteKind.DEAD_CENTRE, f"dyad {dyad.number}",
                              tuple(ranges(angle, near)),
                              {"dyad": dyad.number, "band": mechanism.dead_centre_angle,
                               "digits": digits}))
            well &= ~near
        poor = rows & (quality > hard) & (quality < soft)
        if poor.any():
            mu = np.rad2deg(policy.transmission[:, col])
            off = np.where(poor, np.minimum(mu, 180.0 - mu), np.inf)
            k = int(np.argmin(off))
            notes.append(Note(NoteKind.POOR_TRANSMISSION, f"dyad {dyad.number}",
                              tuple(ranges(angle, poor)),
                              {"dyad": dyad.number, "warning": mechanism.transmission_warning,
                               "least_deg": float(off[k]), "at": float(angle[k]),
                               "digits": digits}))
    return well
