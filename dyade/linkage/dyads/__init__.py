"""The closures of the dyad kinds: one module each, and ``close``, which closes a dyad.

Each kind module (named as the kind in lower case: ``rrr``, ``rrp``, ``rpr``, ``prp``,
``ppr``) exports its closed-form position closure ``close(dyad, motion) -> Closure``
(``dyade.linkage.dyads.closure``), which writes the poses of links i and j into
``motion`` (NaN where the dyad does not close) and returns where it closes and its
transmission angle. What a kind is (its number and name, the joint pattern A-B-C as in
the DYADE paper, Thümmel & Bartke 1987, whether it has an assembly variant, its link
frames) is data, ``dyade.model.dyad_kinds``; the keys a mechanism file gives for each
kind, and the construction of its middle joint B from them, are read by
``dyade.files.mechanism.dyads``. Velocities, accelerations and forces do not depend on
the kind: they come from the joints' twists (``dyade.linkage.motion``). No other module
of the engine tests a kind's number: adding a kind touches its data, its module here and
its reader.

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
from typing import TYPE_CHECKING, Callable

if TYPE_CHECKING:
    from dyade.linkage.dyads.closure import Closure
    from dyade.linkage.motion import Motion
    from dyade.model.dyad_kinds import DyadKind
    from dyade.model.mechanism import Dyad


def closure_of(kind: DyadKind) -> Callable[[Dyad, Motion], Closure]:
    """The closure ``close(dyad, motion)`` of a kind, its module imported when a mechanism
    first needs it (a four-bar run need not load the four other kinds)."""
    return importlib.import_module(f"dyade.linkage.dyads.{kind.name.lower()}").close


def close(dyad: Dyad, motion: Motion) -> Closure:
    """Place links i and j of ``dyad`` in ``motion`` by the closure of its kind."""
    return closure_of(dyad.kind)(dyad, motion)
