"""``dyade describe``: the mechanism as dyade will compute with it, in the file's units.

Assembly order (the crank is dyad 1, the first [[dyad]] table dyad 2), every joint with
its geometry, friction and clearance data, every link's lengths, mass, centre, inertia
and points, the loads, springs and gravity, the mobility, the effects the analysis will
simulate and the sweep; for a four-bar or slider-crank loop on the crank its Grashof
type, stroke or swing and time ratio.
"""

from __future__ import annotations

import math

import numpy as np
from rich.markup import escape
from rich.tree import Tree

from dyade.linkage.plan import Plan
from dyade.model.mechanism import CRANK, FRAME, Mechanism, Prismatic, Revolute
from dyade.report.effects import effects
from dyade.units import LENGTH_FACTORS, RAD_PER_S_TO_RPM


class Lengths:
    """Lengths shown in the file's unit."""

    def __init__(self, unit: str) -> None:
        self.unit, self.factor = unit, LENGTH_FACTORS[unit]

    def __call__(self, value: float) -> str:
        return f"{value / self.factor:g} {self.unit}"

    def point(self, p) -> str:
        return f"({p[0] / self.factor:g}, {p[1] / self.factor:g}) {self.unit}"


def describe(mechanism: Mechanism, the_plan: Plan, skipped: list[str]) -> Tree:
    """The mechanism in assembly order, its mobility and the effects to simulate."""
    length = Lengths(mechanism.units[0])
    tree = Tree(f"[bold]{mechanism.name}[/bold]"
                + (f"  ({mechanism.source})" if mechanism.source else "")
                + f"  — lengths in {length.unit}")
    frame = tree.add("link 1: frame")
    for name, point in mechanism.links[FRAME].points.items():
        frame.add(f"point {name} = {length.point(point)}")
    crank = mechanism.crank
    rpm = abs(crank.speed) * RAD_PER_S_TO_RPM
    sense = "counter-clockwise" if crank.speed > 0 else "clockwise"
    node = tree.add(f"dyad 1: link 2 crank, length {length(crank.length)}, {rpm:g} rpm {sense}")
    node.add(f"joint (1,2) revolute at {length.point(crank.pivot)}{_joint_data(crank.joint, length)}")
    _link(node, mechanism, CRANK, length)
    for k, dyad in enumerate(mechanism.dyads, 1):
        i, j = dyad.links
        g, h = dyad.known
        rule = dyad.kind.variant_rule(dyad.variant)
        variant = (f", assembly variant {dyad.variant:+d} ({rule})"
                   if dyad.variant else "")
        node = tree.add(f"dyad {dyad.number} ({escape('[[dyad]]')} table {k}): kind {dyad.kind.number} "
                        f"{dyad.kind.name}, links i={i}, j={j}, attached to links {g} and "
                        f"{h}{variant}")
        for letter, joint in zip("ABC", dyad.joints):
            node.add(f"{letter}: joint {_joint(joint, length)}")
        for link, (first, second) in zip(dyad.links, ((0, 1), (1, 2))):
            arm = _arm(dyad.joints[first], dyad.joints[second], link)
            _link(node, mechanism, link, length, arm)
    _loads(tree, mechanism, length)
    links = 1 + len(mechanism.moving_links)
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    prismatic = len(mechanism.joints) - revolute
    mobility = 3 * (links - 1) - 2 * len(mechanism.joints)
    tree.add(f"mobility (Grübler) F = 3·({links}−1) − 2·{len(mechanism.joints)} = {mobility}"
             f"  [{links} links, {revolute} revolute, {prismatic} prismatic joints]")
    for line in loop_type(mechanism, length):
        tree.add(line)
    simulated = tree.add("effects simulated")
    for line in effects(the_plan):
        simulated.add(line)
    if the_plan.friction:
        simulated.add(f"friction iteration: tolerance {mechanism.friction_tol:g}, at most "
                    f"{mechanism.friction_max_iter} steps")
    for line in skipped:
        simulated.add(f"[dim]not simulated — {line}[/dim]")
    sweep = mechanism.sweep
    tree.add(f"sweep: crank angle {np.rad2deg(sweep.start):g}° to {np.rad2deg(sweep.stop):g}° "
             f"in steps of {np.rad2deg(sweep.step):g}° ({sweep.angles().size} positions); "
             f"nothing given within {np.rad2deg(mechanism.dead_centre_angle):g}° of a dead "
             f"centre, a warning below a transmission angle of "
             f"{np.rad2deg(mechanism.transmission_warning):g}°")
    return tree


def _joint(joint, length: Lengths) -> str:
    a, b = joint.name
    if isinstance(joint, Revolute):
        return f"({a},{b}) revolute{_joint_data(joint, length)}"
    return (f"({a},{b}) prismatic: guide on link {joint.carrier} through "
            f"{length.point(joint.guide_point)} at {np.rad2deg(joint.guide_angle):g}°, slider "
            f"link {joint.slider} at {length.point(joint.slider_point)}"
            f"{_joint_data(joint, length)}")


def _joint_data(joint, length: Lengths) -> str:
    """Friction and clearance data of a joint, when it has them."""
    parts = []
    if joint.friction > 0.0:
        if isinstance(joint, Revolute):
            parts.append(f"μ = {joint.friction:g}, pin radius r_z = {length(joint.pin_radius)}")
        else:
            parts.append(f"μ = {joint.friction:g}, slider L = {length(joint.slider_length)}, "
                         f"H = {length(joint.slider_height)}")
    clearance = getattr(joint, "clearance", None)
    if clearance is not None:
        mass = f", m = {clearance.mass:g} kg" if clearance.mass is not None else ""
        parts.append(f"clearance 2s = {length(clearance.clearance)}, contact stiffness "
                     f"{clearance.stiffness:g} N/m{mass}")
    return "; " + "; ".join(parts) if parts else ""


def _arm(first, second, link: int) -> float | None:
    """The distance between two revolute joints' points on ``link`` (its length)."""
    if not (isinstance(first, Revolute) and isinstance(second, Revolute)):
        return None
    p = first.points[first.links.index(link)]
    q = second.points[second.links.index(link)]
    return math.hypot(q[0] - p[0], q[1] - p[1])


def _link(node: Tree, mechanism: Mechanism, number: int, length: Lengths,
          arm: float | None = None) -> None:
    link = mechanism.links[number]
    parts = [f"joint distance {length(arm)}"] if arm is not None else []
    if link.has_mass:
        parts.append(f"mass {link.mass:g} kg, centre {length.point(link.centre)} (ξ, η), "
                     f"J_s {link.inertia:g} kg·m²")
    if parts:
        node.add(f"link {number}: " + "; ".join(parts))
    named = [(name, point) for name, point in link.points.items()
             if not (number == CRANK and name == "tip")]
    for name, point in named[:SHOWN_POINTS]:
        node.add(f"link {number} point {name} = {length.point(point)} (ξ, η)")
    if len(named) > SHOWN_POINTS:
        node.add(f"link {number}: {len(named) - SHOWN_POINTS:,} more named points "
                 f"({named[SHOWN_POINTS][0]} … {named[-1][0]}; dyade analyse gives their paths)")


SHOWN_POINTS = 50  # named points listed per link; a file may have thousands


def _loads(tree: Tree, mechanism: Mechanism, length: Lengths) -> None:
    gx, gy = mechanism.gravity
    if gx or gy:
        tree.add(f"gravity ({gx:g}, {gy:g}) m/s²")
    for k, load in enumerate(mechanism.loads, 1):
        frame = "link frame (ξ, η)" if load.local else "world (x, y)"
        where = f"load {k} on link {load.link} at {length.point(load.point)}, {frame}"
        if load.angles is None:
            tree.add(f"{where}: force ({load.fx[0]:g}, {load.fy[0]:g}) N, moment "
                     f"{load.moment[0]:g} N·m")
        else:
            span = np.rad2deg(load.angles[[0, -1]])
            tree.add(f"{where}: table of {load.angles.size} rows over φ21 {span[0]:g}°–"
                     f"{span[1]:g}° (periodic), |F| up to "
                     f"{np.max(np.hypot(load.fx, load.fy)):g} N, |M| up to "
                     f"{np.max(np.abs(load.moment)):g} N·m")
    for spring in mechanism.springs:
        (a, b), (p, q) = spring.links, spring.points
        tree.add(f"spring {spring.name}: link {a} at {length.point(p)} to link {b} at "
                 f"{length.point(q)}, {spring.stiffness:g} N/m, free length "
                 f"{length(spring.free_length)}")


def loop_type(mechanism: Mechanism, length: Lengths) -> list[str]:
    """Grashof type, swing or stroke and time ratio of a four-bar (RRR) or slider-crank
    (RRP) loop closed by the first dyad on the crank and the frame."""
    dyad = next((d for d in mechanism.dyads if d.known == (CRANK, FRAME)
                 and d.kind.name in ("RRR", "RRP")), None)
    if dyad is None:
        return []
    crank = mechanism.crank.length
    a_joint, b_joint, c_joint = dyad.joints
    i, j = dyad.links
    coupler = _arm(a_joint, b_joint, i)
    out = []
    if dyad.kind.name == "RRR":
        rocker = _arm(b_joint, c_joint, j)
        c = c_joint.points[c_joint.links.index(FRAME)]
        pivot = mechanism.crank.pivot
        ground = math.hypot(c[0] - pivot[0], c[1] - pivot[1])
        out.append(f"four-bar {_grashof(crank, coupler, rocker, ground)}: crank "
                   f"{length(crank)}, coupler {length(coupler)}, rocker {length(rocker)}, "
                   f"ground {length(ground)}")
    else:
        out.append(f"slider-crank: crank {length(crank)}, connecting rod {length(coupler)}")
    figures = _motion(mechanism)
    if figures is None:
        out.append("it does not close over the whole revolution (see dyade analyse)")
        return out
    for name, figure in figures["strokes"].items():
        if name == "_".join(map(str, c_joint.name)):
            out.append(f"  slider stroke {length(figure['stroke'])}, time ratio "
                       f"{_ratio(figure['time_ratio'])}")
    for link, figure in figures["swings"].items():
        if int(link) == j:
            out.append(f"  rocker swing {figure['swing_deg']:.4g}°, time ratio "
                       f"{_ratio(figure['time_ratio'])}")
    return out


def _grashof(crank: float, coupler: float, rocker: float, ground: float) -> str:
    """The Grashof type of a four-bar from its four lengths."""
    bars = {"crank": crank, "coupler": coupler, "rocker": rocker, "ground": ground}
    s, *middle, l = sorted(bars.values())
    shortest = min(bars, key=bars.get)
    total, rest = s + l, sum(middle)
    if math.isclose(total, rest, rel_tol=1e-12):
        return "(Grashof change point: s + l = p + q, it can fold flat)"
    if total > rest:
        return "(non-Grashof, s + l > p + q: a triple rocker, no link turns round)"
    return {"crank": "(Grashof crank-rocker: s + l < p + q, the crank is the shortest link)",
            "ground": "(Grashof double crank: the ground link is the shortest)",
            "coupler": "(Grashof double rocker: the coupler is the shortest link)",
            "rocker": "(Grashof rocker-crank: the rocker is the shortest link and turns round, "
                      "the crank rocks)"}[shortest]


def _ratio(value: float | None) -> str:
    return f"{value:.4g}" if value is not None else "— (no single forward and return stroke)"


def _motion(mechanism: Mechanism):
    """Swings, strokes and time ratios over one revolution at 0.5°, or None when the
    mechanism does not close everywhere."""
    from dataclasses import replace

    from dyade.errors import AssemblyError
    from dyade.linkage.summary import motion_figures
    from dyade.linkage.sweep import analyse

    # the figures need the links' angles and the sliders' travel, not the named points
    # (a file may have thousands: they would cost columns at every position)
    bare = {number: replace(link, points={k: v for k, v in link.points.items() if k == "tip"})
            for number, link in mechanism.links.items()}
    one = replace(mechanism, links=bare,
                  sweep=type(mechanism.sweep)(0.0, 2 * math.pi, math.radians(0.5)))
    try:
        result = analyse(one, plan=Plan())
    except AssemblyError:
        return None
    return motion_figures(result, result.columns())
