"""Hypothesis strategies: random closable-ish dyads of every kind on a crank.

Every dyad hangs on the crank (link 2, pivot at the origin, length = ``scale``) and the
frame; lengths, offsets and guide angles are drawn relative to ``scale``, which ranges
from micrometres to metres.
"""

from __future__ import annotations

from typing import Any

from hypothesis import strategies as st

KINDS = ["RRR", "RRP", "RPR", "PRP", "PPR"]


def _size(lo: float, hi: float):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def dyad_files(draw, kind: str | None = None) -> dict[str, Any]:
    """A mechanism file (as a dict, SI units) with one dyad of ``kind`` on a crank."""
    kind = kind or draw(st.sampled_from(KINDS))
    scale = 10 ** draw(_size(-6, 0))
    def length(lo, hi):
        return draw(_size(lo, hi)) * scale
    def angle():
        return draw(_size(-180, 180))
    def frame_point():
        return [draw(_size(-4, 4)) * scale, draw(_size(-4, 4)) * scale]
    dyad: dict[str, Any] = {"kind": kind, "links": [3, 4]}
    tip = {"link": 2, "point": "tip"}
    if kind == "RRR":
        dyad.update(A=tip, C={"link": 1, "point": frame_point()},
                    lengths=[length(0.3, 5), length(0.3, 5)])
    elif kind == "RRP":
        dyad.update(A=tip, C={"link": 1, "point": frame_point(), "angle": angle(),
                              "offset": length(-1, 1), "guide": draw(st.sampled_from([1, 4]))},
                    length=length(0.5, 5))
    elif kind == "RPR":
        dyad.update(A=tip, C={"link": 1, "point": frame_point()},
                    B={"guide": draw(st.sampled_from([3, 4])), "offset": length(-1, 1)})
    elif kind == "PRP":
        dyad.update(A={"link": 2, "point": [length(-1, 1), length(-1, 1)], "angle": angle(),
                       "offset": length(-1, 1), "guide": draw(st.sampled_from([2, 3]))},
                    C={"link": 1, "point": frame_point(), "angle": angle(),
                       "offset": length(-1, 1), "guide": draw(st.sampled_from([1, 4]))})
    else:
        b_angle = draw(_size(20, 160)) * draw(st.sampled_from([1, -1]))
        dyad.update(A={"link": 1, "point": frame_point(), "angle": angle(),
                       "offset": length(-1, 1), "guide": draw(st.sampled_from([1, 3]))},
                    B={"angle": b_angle, "point": [length(-1, 1), length(-1, 1)],
                       "offset": length(-1, 1), "guide": draw(st.sampled_from([3, 4]))},
                    C=tip)
    if kind in ("RRR", "RRP", "RPR"):
        dyad["variant"] = draw(st.sampled_from([1, -1]))
    return {"units": {"length": "m", "angle": "deg"},
            "crank": {"pivot": [0.0, 0.0], "length": scale,
                      "speed_rpm": draw(_size(1, 3000)),
                      "direction": draw(st.sampled_from(["ccw", "cw"]))},
            "dyad": [dyad], "links": {"3": {"points": {"P": [length(-2, 2), length(-2, 2)]}}}}
