"""The five dyad kinds of the DYADE paper (Thümmel & Bartke 1987) as data: number, name
(the joint pattern A-B-C), assembly variants, link frames and what their transmission
angle means.

A mechanism file names a kind by number or name (``named``); the reader
(``dyade.files.mechanism.dyads``) reads each kind's keys and builds its middle joint B in
the link frames given here; the engine closes each kind by its own closure
(``dyade.linkage.dyads``, one module per kind, named as the kind in lower case).

>>> named("rrp").number, kind(5).name, kind(4).has_variant
(2, 'PPR', False)
"""

from __future__ import annotations

from typing import NamedTuple


class DyadKind(NamedTuple):
    """What dyade knows of a dyad kind besides its closure: the static data of the kind."""

    number: int
    """the paper's kind number ("Art") 1-5"""
    name: str
    """the joint pattern A-B-C: RRR, RRP, RPR, PRP, PPR"""
    has_variant: bool
    """two closures, chosen by the assembly variant ±1 (else one, variant 0)"""
    variant_rules: tuple[str, str]
    """what variant +1 and what variant −1 mean (empty without a variant)"""
    frames: tuple[str, str]
    """the link frames of links i and j (origin, ξ axis)"""
    transmission: str
    """the two directions whose angle is the transmission angle μ"""
    singular: str
    """what μ = 0° or 180° is called: "dead centre" or "blocked position" """

    def variant_rule(self, variant: int) -> str:
        """What assembly variant ``variant`` (±1) means ("" without a variant)."""
        return self.variant_rules[0 if variant > 0 else 1] if variant else ""

    @property
    def cannot_close(self) -> str:
        """How a failed closure is said."""
        return "is blocked" if self.singular == "blocked position" else "cannot close"


RRR = DyadKind(
    1, "RRR", True, ("B left of the directed line A→C", "B right of the directed line A→C"),
    ("origin A, ξ towards B", "origin C, ξ towards B"),
    "B−A and B−C (link i and link j at B)", "dead centre")
RRP = DyadKind(
    2, "RRP", True, ("B ahead of the foot point of A in the guide direction",
                     "B behind the foot point of A in the guide direction"),
    ("origin A, ξ towards B", "origin B, ξ along the guide at C"),
    "B−A and the normal of guide C", "dead centre")
RPR = DyadKind(
    3, "RPR", True, ("the guide direction points from the guide link's pivot towards the other "
                     "link's pivot", "the guide direction points from the other link's pivot "
                                     "towards the guide link's pivot"),
    ("origin A, ξ along the guide at B", "origin C, ξ along the guide at B"),
    "the normal of guide B and the line between the pivots", "dead centre")
PRP = DyadKind(
    4, "PRP", False, ("", ""), ("origin B, ξ along the guide at A", "origin B, ξ along the guide at C"),
    "guide A and guide C", "blocked position")
PPR = DyadKind(
    5, "PPR", False, ("", ""), ("origin on guide A, ξ along the guide at A",
                                "origin C, ξ along the guide at B"),
    "guide A and guide B", "blocked position")

KINDS = (RRR, RRP, RPR, PRP, PPR)
"""every kind; kind number k is entry k (1-based), as in the paper"""
REGISTRY = tuple(k.name.lower() for k in KINDS)
"""the kinds' names in lower case, in number order (the engine's closure modules)"""


def kind(number: int) -> DyadKind:
    """The kind with this number (1-5)."""
    return KINDS[number - 1]


def named(value: object) -> DyadKind | None:
    """The kind a file names by number (1-5) or joint pattern ("RRP"); None if none."""
    if isinstance(value, str) and value.lower() in REGISTRY:
        return KINDS[REGISTRY.index(value.lower())]
    if isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= len(KINDS):
        return KINDS[value - 1]
    return None
