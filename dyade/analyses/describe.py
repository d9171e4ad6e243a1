"""``describe``: a mechanism as dyade will compute with it (``dyade describe``).

The Outcome's summary holds the plan (which stages a sweep runs: ``kinetostatics``,
``friction``, ``self_locking``, ``clearance``, ``equation_of_motion``, ``drive_line``,
each a flag) and the mechanism's figures (links, joints, mobility, the crank's speed,
the sweep and its bands); for a four-bar or slider-crank loop closed on the crank and
the frame its type (Grashof), its lengths, and its output's stroke or swing and time
ratio over one revolution at 0.5° (``loop_*``). ``result`` is the mechanism and its
plan, which the tree of ``dyade describe`` lists in assembly order
(``dyade.report.describe``). No column.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from dyade.analyses import inputs
from dyade.analyses.base import Analysis, Budget, Outcome
from dyade.analyses.sweep import STAGES, stages
from dyade.units import RAD_PER_S_TO_RPM

LOOP_STEP_DEG = 0.5  # [°] the loop's stroke, swing and time ratio: one revolution at this step


class Described(NamedTuple):
    """What ``describe`` read: the mechanism and its plan."""

    mechanism: Any
    plan: Any


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import numpy as np

    from dyade.model.mechanism import Revolute
    from dyade.linkage.plan import plan

    mechanism = inputs.load(source, options).mechanism
    the_plan = plan(mechanism)
    outcome = Outcome("describe", figures=("mechanism",),
                      meta={"name": mechanism.name, "source": mechanism.source or None,
                            "stages": stages(the_plan)},
                      result=Described(mechanism, the_plan))
    add = outcome.add
    for name in STAGES:
        value = getattr(the_plan, name)
        joints = (", ".join(f"({a},{b})" for a, b in value) if isinstance(value, tuple)
                  else value if isinstance(value, str) else "")
        add(name, bool(value), "-", description=f"stage {name.replace('_', ' ')}"
                                                + (f": {joints}" if joints else ""))
    if the_plan.equation_of_motion:
        add("motor", the_plan.equation_of_motion, "-", description="the motor of [drive]")
    links = 1 + len(mechanism.moving_links)
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    add("links", links, "-", description="links, the frame included")
    add("dyads", 1 + len(mechanism.dyads), "-", description="dyads, the crank included")
    add("revolute_joints", revolute, "-", description="revolute joints")
    add("prismatic_joints", len(mechanism.joints) - revolute, "-",
        description="prismatic joints")
    add("mobility", 3 * (links - 1) - 2 * len(mechanism.joints), "-",
        description="mobility (Grübler) F = 3·(n−1) − 2·g")
    crank = mechanism.crank
    drive = mechanism.cam
    if drive is not None:  # a cam drives link 2: the sweep runs over the cam angle
        cam = drive.cam
        add("input", f"cam-driven: a {cam.follower} follower is link 2 "
                     f"({'sliding along its guide' if crank.sliding else 'the lever'})", "-",
            description="the chain's input")
        add("cam_base_radius", float(cam.base_radius), "m", description="cam base radius")
        add("speed_rpm", float(crank.speed) * RAD_PER_S_TO_RPM, "rpm",
            description=f"cam speed ({'clockwise' if cam.clockwise else 'counter-clockwise'}"
                        f"); the sweep's angles are the cam angle θ")
    else:
        add("crank_length", float(crank.length), "m", description="crank length")
        add("speed_rpm", float(crank.speed) * RAD_PER_S_TO_RPM, "rpm",
            description="crank speed (positive: counter-clockwise)")
    sweep = mechanism.sweep
    add("start_deg", float(np.rad2deg(sweep.start)), "°", description="sweep: first crank angle")
    add("stop_deg", float(np.rad2deg(sweep.stop)), "°", description="sweep: last crank angle")
    add("step_deg", float(np.rad2deg(sweep.step)), "°", description="sweep: step")
    add("positions", int(sweep.angles().size), "-", description="sweep: crank positions")
    add("dead_centre_deg", float(np.rad2deg(mechanism.dead_centre_angle)), "°",
        description="hard band: nothing given within this of a dead centre")
    add("transmission_warning_deg", float(np.rad2deg(mechanism.transmission_warning)), "°",
        description="soft band: a note below this transmission angle")
    if the_plan.friction:
        add("friction_tol", float(mechanism.friction_tol), "-",
            description="friction iteration: tolerance")
        add("friction_max_iter", int(mechanism.friction_max_iter), "-",
            description="friction iteration: most steps")
    for name, (value, unit, text) in loop_figures(mechanism).items():
        add(name, value, unit, description=text)
    return outcome


def loop_figures(mechanism) -> dict[str, tuple[Any, str, str]]:
    """The four-bar (RRR) or slider-crank (RRP) loop closed by the first dyad on the
    crank and the frame, if there is one: its kind, Grashof type and lengths [m], and
    over one revolution at ``LOOP_STEP_DEG`` its output's stroke [m] or swing [°] and
    time ratio; name -> (value, unit, description)."""
    from dyade.model.mechanism import CRANK, FRAME

    if mechanism.cam is not None or mechanism.crank.sliding:
        return {}  # link 2 is no crank: no four-bar or slider-crank loop on it
    dyad = next((d for d in mechanism.dyads if d.known == (CRANK, FRAME)
                 and d.kind.name in ("RRR", "RRP")), None)
    if dyad is None:
        return {}
    crank = mechanism.crank.length
    a_joint, b_joint, c_joint = dyad.joints
    i, j = dyad.links
    coupler = arm(a_joint, b_joint, i)
    out: dict[str, tuple[Any, str, str]] = {}
    if dyad.kind.name == "RRR":
        rocker = arm(b_joint, c_joint, j)
        c = c_joint.points[c_joint.links.index(FRAME)]
        pivot = mechanism.crank.pivot
        ground = math.hypot(c[0] - pivot[0], c[1] - pivot[1])
        out["loop"] = ("four-bar", "-", "the loop on the crank and the frame")
        out["loop_grashof"] = (grashof(crank, coupler, rocker, ground), "-",
                               "its Grashof type")
        out["loop_crank"] = (crank, "m", "crank")
        out["loop_coupler"] = (coupler, "m", "coupler")
        out["loop_rocker"] = (rocker, "m", "rocker")
        out["loop_ground"] = (ground, "m", "ground")
    else:
        out["loop"] = ("slider-crank", "-", "the loop on the crank and the frame")
        out["loop_crank"] = (crank, "m", "crank")
        out["loop_coupler"] = (coupler, "m", "connecting rod")
    figures = loop_motion(mechanism)
    out["loop_closes"] = (figures is not None, "-", "it closes over the whole revolution")
    if figures is None:
        return out
    slider = "{}_{}".format(*c_joint.name)
    if f"stroke_{slider}" in figures:
        out["loop_stroke"] = (figures[f"stroke_{slider}"], "m", "slider stroke")
        out["loop_time_ratio"] = (figures[f"time_ratio_{slider}"], "-", "time ratio")
    elif f"swing_{j}_deg" in figures:
        out["loop_swing_deg"] = (figures[f"swing_{j}_deg"], "°", "rocker swing")
        out["loop_time_ratio"] = (figures[f"time_ratio_{j}"], "-", "time ratio")
    return out


def arm(first, second, link: int) -> float | None:
    """The distance between two revolute joints' points on ``link`` (its length)."""
    from dyade.model.mechanism import Revolute

    if not (isinstance(first, Revolute) and isinstance(second, Revolute)):
        return None
    p = first.points[first.links.index(link)]
    q = second.points[second.links.index(link)]
    return math.hypot(q[0] - p[0], q[1] - p[1])


GRASHOF = ("change point", "non-Grashof", "crank-rocker", "double crank", "double rocker",
           "rocker-crank")
"""the Grashof types of a four-bar (``grashof``)"""


def grashof(crank: float, coupler: float, rocker: float, ground: float) -> str:
    """The Grashof type of a four-bar from its four lengths (``GRASHOF``)."""
    bars = {"crank": crank, "coupler": coupler, "rocker": rocker, "ground": ground}
    s, *middle, l = sorted(bars.values())
    shortest = min(bars, key=bars.get)
    total, rest = s + l, sum(middle)
    if math.isclose(total, rest, rel_tol=1e-12):
        return "change point"
    if total > rest:
        return "non-Grashof"
    return {"crank": "crank-rocker", "ground": "double crank", "coupler": "double rocker",
            "rocker": "rocker-crank"}[shortest]


def loop_motion(mechanism) -> dict[str, Any] | None:
    """The key figures of the kinematics (``dyade.linkage.summary.key_figures``: swings,
    strokes, time ratios) over one revolution at ``LOOP_STEP_DEG``, or None when the
    mechanism does not close everywhere."""
    from dataclasses import replace

    import numpy as np

    from dyade.errors import AssemblyError
    from dyade.linkage.plan import Plan
    from dyade.linkage.summary import key_figures
    from dyade.linkage.sweep import analyse

    # the figures need the links' angles and the sliders' travel, not the named points
    # (a file may have thousands: they would cost columns at every position)
    bare = {number: replace(link, points={k: v for k, v in link.points.items() if k == "tip"})
            for number, link in mechanism.links.items()}
    one = replace(mechanism, links=bare,
                  sweep=type(mechanism.sweep)(0.0, 2 * math.pi, math.radians(LOOP_STEP_DEG)))
    try:
        result = analyse(one, plan=Plan())
    except AssemblyError:
        return None
    cols = result.columns()
    rows = {name: values[None, :] for name, values in cols.items()}
    return {name: None if np.isnan(value[0]) else float(value[0])
            for name, value in key_figures(one, cols["angle_deg"], rows, False).items()}


ENTRIES = {"describe": Analysis("describe", "A mechanism file in assembly order: its plan "
                                "and figures", run, (inputs.SET,), figures=("mechanism",),
                                command="dyade describe")}
