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
    """What the validity policy reads of the kinematics of a whole sweep (of every
    variant of a run of variants: ``variants`` sweeps of equal length, variant-major)."""

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
    variants: int = 1
    """the variants the positions belong to, each its own sweep of n / variants"""

    @classmethod
    def empty(cls, crank_angle: FloatArray, dyads: int, variants: int = 1) -> Policy:
        n = crank_angle.shape[0]
        return cls(crank_angle, np.empty((n, dyads), dtype=bool), np.empty((n, dyads)),
                   np.empty((n, dyads)), np.empty(n, dtype=bool),
                   decimals(crank_angle[:n // max(variants, 1)]), variants)

    def keep(self, first: int, last: int, kin: Kinematics) -> None:
        """Take over a block's kinematics at positions first..last−1."""
        for name in ("closes", "transmission", "conditioning", "valid"):
            getattr(self, name)[first:last] = getattr(kin, name)

    def each(self, mask: FloatArray):
        """``each`` of this sweep's variants."""
        return each(mask, self.variants)


def each(mask: FloatArray, variants: int):
    """(variant, its positions as a slice) of every variant with a True in the (n,)
    ``mask`` of ``variants`` sweeps of equal length, variant-major (the one variant of
    a single sweep: all its positions)."""
    if variants == 1:
        yield 0, slice(None)
        return
    count = mask.shape[0] // variants
    for variant in np.flatnonzero(mask.reshape(variants, count).any(axis=1)):
        yield int(variant), slice(variant * count, (variant + 1) * count)


def of_variant(value, where: slice):
    """A number of a mechanism as one variant has it: as it is, or (an array of one
    value per position of a run of variants, ``stack``) that variant's (a float)."""
    return value if np.ndim(value) == 0 else float(np.asarray(value)[where][0])


def assembly(mechanism: Mechanism, policy: Policy, allow_partial: bool,
             notes: list[list[Note]]) -> tuple[FloatArray, dict[int, AssemblyError]]:
    """((n,) bool: the positions where every dyad closes (the rows reported), the
    variants that do not close -> their ``AssemblyError``) naming the dyads and ranges
    where some does not. A single sweep raises its error unless ``allow_partial`` (then
    a note in ``notes[0]``); a run of variants reports none of the positions of a
    variant with an error."""
    rows = np.ones(policy.crank_angle.shape[0], dtype=bool)
    failed: dict[int, AssemblyError] = {}
    everywhere = policy.closes.all(axis=1)
    if everywhere.all():
        return rows, failed
    for variant, where in policy.each(~everywhere):
        try:
            rows[where] = _assembly(mechanism, policy.crank_angle[where],
                                    policy.closes[where], policy.digits, allow_partial,
                                    notes[variant])
        except AssemblyError as err:
            if policy.variants == 1:
                raise
            failed[variant] = err
            rows[where] = False
    return rows, failed


def _assembly(mechanism: Mechanism, angle: FloatArray, closes: FloatArray, digits: int,
              allow_partial: bool, notes: list[Note]) -> FloatArray:
    """``assembly`` of one sweep."""
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
          notes: list[list[Note]]) -> FloatArray:
    """(n,) bool, the positions whose kinematics is given.

    Each dyad's quality at each position comes from its own geometry (the sine of its
    transmission angle; an RPR dyad's also from its pivot distance): within the hard
    band (``dead_centre_angle`` of 0° or 180°) the rigid model is invalid and nothing is
    given; in the soft band (transmission angle below ``transmission_warning``, the
    designers' rule) results are given with a note naming the dyad, the ranges and the
    smallest transmission angle (``notes[v]``: variant v's; the bands may differ between
    variants, one value per position)."""
    angle, digits = policy.crank_angle, policy.digits
    hard = np.sin(mechanism.dead_centre_angle)
    soft = np.sin(mechanism.transmission_warning)
    well = rows & policy.valid
    for col, dyad in enumerate(mechanism.dyads):
        quality = policy.conditioning[:, col]
        near = rows & (quality <= hard)
        if near.any():
            for variant, where in policy.each(near):
                notes[variant].append(Note(
                    NoteKind.DEAD_CENTRE, f"dyad {dyad.number}",
                    tuple(ranges(angle[where], near[where])),
                    {"dyad": dyad.number,
                     "band": of_variant(mechanism.dead_centre_angle, where),
                     "digits": digits}))
            well &= ~near
        poor = rows & (quality > hard) & (quality < soft)
        if poor.any():
            for variant, where in policy.each(poor):
                mu = np.rad2deg(policy.transmission[where, col])
                off = np.where(poor[where], np.minimum(mu, 180.0 - mu), np.inf)
                k = int(np.argmin(off))
                notes[variant].append(Note(
                    NoteKind.POOR_TRANSMISSION, f"dyad {dyad.number}",
                    tuple(ranges(angle[where], poor[where])),
                    {"dyad": dyad.number,
                     "warning": of_variant(mechanism.transmission_warning, where),
                     "least_deg": float(off[k]), "at": float(angle[where][k]),
                     "digits": digits}))
    return well
