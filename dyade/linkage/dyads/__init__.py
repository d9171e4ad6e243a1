"""The dyad kinds: one module each, and the registry that finds them.

Each kind module exports one description, ``KIND`` (a ``DyadKind``,
``dyade.linkage.model``): its number and name (the joint pattern A-B-C, as in the DYADE
paper, Thümmel & Bartke 1987), whether it has an assembly variant, its link frames, and
its closed-form position closure ``close(dyad, motion) -> Closure``
(``dyade.linkage.dyads.closure``), which writes the poses of links i and j into
``motion`` (NaN where the dyad does not close) and returns where it closes and its
transmission angle. Velocities, accelerations and forces do not depend on the kind:
they come from the joints' twists (``dyade.linkage.motion``). The kinds know geometry
and mechanics only: the keys a mechanism file gives for each kind, and the construction
of its middle joint B from them, are read by ``dyade.files.mechanism.dyads``. No other
module of the engine tests a kind's number: adding a kind touches its module,
``REGISTRY`` and its reader.

The transmission angle μ of a dyad is the angle between the two columns of its
2×2 closure Jacobian, so sin μ = 0 exactly at a dead centre or blocked position:

====  =====================================  ==========================
kind  μ is the angle between                 μ = 0° or 180° means
====  =====================================  ==========================
RRR   B−A and B−C (link i and link j at B)   stretched / folded dyad
RRP   B−A and the normal of guide C          link i normal to the guide
RPR   normal of guide B and (pivot − pivot)  slider at the foot point
PRP   guide A and guide C                    parallel guides: blocked
PPR   guide A and guide B                    parallel guides: blocked
====  =====================================  ==========================
"""

from __future__ import annotations

import importlib

from dyade.linkage.model import DyadKind

REGISTRY = ("rrr", "rrp", "rpr", "prp", "ppr")
"""Modules of the dyad kinds; kind number k is entry k (1-based), as in the paper."""


def kind(number: int) -> DyadKind:
    """The kind with this number, its module imported when a mechanism first needs it
    (a four-bar run need not load the four other kinds)."""
    return importlib.import_module(f"dyade.linkage.dyads.{REGISTRY[number - 1]}").KIND


def named(value: object) -> DyadKind | None:
    """The kind a file names by number (1-5) or joint pattern ("RRP"); None if none."""
    if isinstance(value, str) and value.lower() in REGISTRY:
        return kind(REGISTRY.index(value.lower()) + 1)
    if isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= len(REGISTRY):
        return kind(value)
    return None
