"""``dyade describe``: the mechanism of a ``describe`` Outcome as dyade will compute
with it, in the file's units.

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

from dyade.analyses.base import MISSING
from dyade.model.mechanism import CRANK, FRAME, Mechanism, Revolute
from dyade.report.effects import effects
from dyade.report.format import number
from dyade.units import LENGTH_FACTORS, RAD_PER_S_TO_RPM


class Lengths:
    """Lengths shown in the file's unit."""

    def __init__(self, unit: str) -> None:
        self.unit, self.factor = unit, LENGTH_FACTORS[unit]

    def __call__(self, value: float) -> str:
        return f"{number(value / self.factor, spec='g')} {self.unit}"

    def point(self, p) -> str:
        return (f"({number(p[0] / self.factor, spec='g')}, "
                f"{number(p[1] / self.factor, spec='g')}) {self.unit}")


def describe(outcome) -> Tree:
    """The mechanism of a ``describe`` Outcome (``dyade.analyses.describe``) in assembly
    order, its mobility, its loop's figures and the effects a sweep simulates."""
    from dyade.report.tables import skipped as not_simulated

    mechanism, the_plan = outcome.result
    skipped = not_simulated(the_plan)
    length = Lengths(mechanism.units[0])
    tree = Tree(f"[bold]{mechanism.name}[/bold]"
                + (f"  ({mechanism.source})" if mechanism.source else "")
                + f"  — lengths in {length.unit}")
    frame = tree.add("link 1: frame")
    _points(frame, FRAME, list(mechanism.links[FRAME].points.items()), length)
    crank = mechanism.crank
    rpm = abs(crank.speed) * RAD_PER_S_TO_RPM
    sense = "counter-clockwise" if crank.speed > 0 else "clockwise"
    drive = mechanism.cam
    if drive is not None:  # a cam drives link 2, its follower: the sweep is over the cam angle
        cam = drive.cam
        turning = "clockwise" if cam.clockwise else "counter-clockwise"
        node = tree.add(f"cam-driven: a disc cam (base radius {length(cam.base_radius)}) at "
                        f"{length.point(drive.centre)}, {rpm:g} rpm {turning}, drives link 2, "
                        f"its {cam.follower} follower; the sweep runs over the cam angle θ "
                        f"(the φ21 of every table)")
        if crank.sliding:
            node.add(f"joint (1,2) prismatic: link 2 slides along its guide at "
                     f"{np.rad2deg(crank.guide):g}° through {length.point(crank.pivot)} (the "
                     f"roller centre at zero lift), driven by the cam's contact force")
        else:
            node.add(f"joint (1,2) revolute at {length.point(crank.pivot)}: link 2 is the "
                     f"lever, length {length(crank.length)}, swung by the cam")
    else:
        node = tree.add(f"dyad 1: link 2 crank, length {length(crank.length)}, {rpm:g} rpm "
                        f"{sense}")
        node.add(f"joint (1,2) revolute at {length.point(crank.pivot)}"
                 f"{_joint_data(crank.joint, length)}")
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
    for line in loop_type(outcome.summary, length):
        tree.add(line)
    simulated = tree.add("effects simulated")
    for line in effects(the_plan):
        simulated.add(line)
    if the_plan.friction:
        simulated.add(f"friction iteration: tolerance {mechanism.friction_tol:g}, at most "
                    f"{mechanism.friction_max_iter} steps")
    for line in skipped:
        simulated.add(f"[dim]not simulated — {line}[/dim]")
    if mechanism.servo is not None:  # [servo]: dyade servo's, not the sweep's
        servo = mechanism.servo
        tree.add(f"servo: the crank driven by a servo along its profile "
                 f"({len(servo.profile.segments)} segments, on {servo.output}), gear "
                 f"i = {servo.gear.ratio:g}, η = {servo.gear.efficiency:g}: "
                 f"`dyade servo` sizes its motor; `dyade analyse` sweeps at the constant "
                 f"crank speed")
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
    _points(node, number, named, length)


def _points(node: Tree, number: int, named: list, length: Lengths) -> None:
    """The first ``SHOWN_POINTS`` named points of link ``number`` (the frame's too) and
    how many more there are: the tree stays small whatever the file holds."""
    frame = number == FRAME
    for name, point in named[:SHOWN_POINTS]:
        node.add(f"point {name} = {length.point(point)}" if frame
                 else f"link {number} point {name} = {length.point(point)} (ξ, η)")
    if len(named) > SHOWN_POINTS:
        node.add(f"link {number}: {len(named) - SHOWN_POINTS:,} more named points "
                 f"({named[SHOWN_POINTS][0]} … {named[-1][0]}"
                 f"{'' if frame else '; dyade analyse gives their paths'})")


SHOWN_POINTS = 50  # named points listed per link and the frame; a file may have thousands


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


def loop_type(summary, length: Lengths) -> list[str]:
    """Grashof type, swing or stroke and time ratio of a four-bar (RRR) or slider-crank
    (RRP) loop closed by the first dyad on the crank and the frame (the ``loop_*``
    figures of a ``describe`` Outcome)."""
    value = {name: figure.value for name, figure in summary.items()}
    if "loop" not in value:
        return []
    out = []
    if value["loop"] == "four-bar":
        out.append(f"four-bar {GRASHOF[value['loop_grashof']]}: crank "
                   f"{length(value['loop_crank'])}, coupler {length(value['loop_coupler'])}, "
                   f"rocker {length(value['loop_rocker'])}, ground "
                   f"{length(value['loop_ground'])}")
    else:
        out.append(f"slider-crank: crank {length(value['loop_crank'])}, connecting rod "
                   f"{length(value['loop_coupler'])}")
    if not value["loop_closes"]:
        out.append("it does not close over the whole revolution (see dyade analyse)")
        return out
    if "loop_stroke" in value:
        out.append(f"  slider stroke {length(value['loop_stroke'])}, time ratio "
                   f"{_ratio(value['loop_time_ratio'])}")
    if "loop_swing_deg" in value:
        out.append(f"  rocker swing {number(value['loop_swing_deg'], spec='.4g')}°, time ratio "
                   f"{_ratio(value['loop_time_ratio'])}")
    return out


GRASHOF = {"change point": "(Grashof change point: s + l = p + q, it can fold flat)",
           "non-Grashof": "(non-Grashof, s + l > p + q: a triple rocker, no link turns round)",
           "crank-rocker": "(Grashof crank-rocker: s + l < p + q, the crank is the shortest "
                           "link)",
           "double crank": "(Grashof double crank: the ground link is the shortest)",
           "double rocker": "(Grashof double rocker: the coupler is the shortest link)",
           "rocker-crank": "(Grashof rocker-crank: the rocker is the shortest link and turns "
                           "round, the crank rocks)"}
"""the Grashof types of ``dyade.analyses.describe.grashof``, in words"""


def _ratio(value: float | None) -> str:
    return number(value, spec=".4g") if value is not None else \
        f"{MISSING} (no single forward and return stroke)"
