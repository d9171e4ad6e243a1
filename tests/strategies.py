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


@st.composite
def chained_files(draw) -> dict[str, Any]:
    """Two dyads: the first of any kind on the crank and the frame (``dyad_files``), the
    second of any kind with its outer joints A and C on ANY placed links (frame, crank
    or the first dyad's links, the same link twice allowed), its geometry drawn in the
    world at crank angle 0 and carried into the links' frames there, so that it closes
    at least at that position. Every moving link gets a mass (kinetostatics runs)."""
    import numpy as np

    from dyade.files.mechanism import build
    from dyade.linkage import kinematics

    data = draw(dyad_files())
    first = build(data)
    kin = kinematics.sweep(first, np.zeros(1))
    if not kin.valid[0] or kin.conditioning[0, 0] < 0.2:
        from hypothesis import reject
        reject()
    motion = kin.motion
    scale = data["crank"]["length"]

    def world(lo=-3.0, hi=3.0):
        return np.array([draw(_size(lo, hi)), draw(_size(lo, hi))]) * scale

    def local(link, point):  # a world point at crank angle 0 in the frame of ``link``
        c, s = motion.cos[0, link], motion.sin[0, link]
        d = point - motion.origin[0, link]
        return [float(c * d[0] + s * d[1]), float(-s * d[0] + c * d[1])]

    def local_angle(link, theta):  # a world direction [deg] in the frame of ``link``
        return float(theta - np.rad2deg(motion.angle[0, link]))

    kind = draw(st.sampled_from(KINDS))
    g, h = draw(st.sampled_from([1, 2, 3, 4])), draw(st.sampled_from([1, 2, 3, 4]))
    a, b, c_ = world(), world(), world()
    dyad: dict[str, Any] = {"kind": kind, "links": [5, 6]}
    cross = lambda u, v: u[0] * v[1] - u[1] * v[0]
    if kind == "RRR":
        from hypothesis import assume
        assume(abs(cross(c_ - a, b - a)) > 0.3 * np.linalg.norm(c_ - a) * np.linalg.norm(b - a))
        # links of some length (a subnormal one passed the test above and was refused)
        assume(min(np.linalg.norm(b - a), np.linalg.norm(b - c_)) > 0.05 * scale)
        dyad.update(A={"link": g, "point": local(g, a)}, C={"link": h, "point": local(h, c_)},
                    lengths=[float(np.linalg.norm(b - a)), float(np.linalg.norm(b - c_))],
                    variant=1 if cross(c_ - a, b - a) > 0 else -1)
    elif kind == "RRP":
        theta = draw(_size(-180, 180))
        d = np.array([np.cos(np.deg2rad(theta)), np.sin(np.deg2rad(theta))])
        foot = a + np.dot(b - a, d) * d
        from hypothesis import assume
        assume(np.linalg.norm(b - a) > 0.2 * scale and abs(np.dot(b - foot, d)) > 0.2 * scale)
        dyad.update(A={"link": g, "point": local(g, a)},
                    C={"link": h, "point": local(h, b), "angle": local_angle(h, theta)},
                    length=float(np.linalg.norm(b - a)),
                    variant=1 if np.dot(b - foot, d) > 0 else -1)
    elif kind == "RPR":
        rho = np.linalg.norm(c_ - a)
        from hypothesis import assume
        assume(rho > 0.3 * scale)
        dyad.update(A={"link": g, "point": local(g, a)}, C={"link": h, "point": local(h, c_)},
                    B={"guide": draw(st.sampled_from([5, 6])),
                       "offset": float(draw(_size(-0.7, 0.7)) * rho)},
                    variant=draw(st.sampled_from([1, -1])))
    elif kind == "PRP":
        ta, tc = draw(_size(-180, 180)), draw(_size(-180, 180))
        from hypothesis import assume
        assume(abs(np.sin(np.deg2rad(ta - tc))) > 0.3)
        dyad.update(A={"link": g, "point": local(g, b), "angle": local_angle(g, ta)},
                    C={"link": h, "point": local(h, b), "angle": local_angle(h, tc)})
    else:  # PPR
        dyad.update(A={"link": g, "point": local(g, a), "angle": local_angle(g, draw(_size(-180, 180)))},
                    B={"angle": draw(_size(30, 150)) * draw(st.sampled_from([1, -1]))},
                    C={"link": h, "point": local(h, c_)})
    data = dict(data)
    data["dyad"] = data["dyad"] + [dyad]
    data["links"] = {str(k): {"mass": draw(_size(0.1, 3.0)),
                              "centre": [draw(_size(-1, 1)) * scale, draw(_size(-1, 1)) * scale],
                              "radius_of_gyration": draw(_size(0.1, 1.0)) * scale}
                     for k in (3, 4, 5, 6)}
    data["links"]["3"]["points"] = {"P": [0.5 * scale, 0.2 * scale]}
    data["gravity"] = draw(st.sampled_from([False, True]))
    return data
