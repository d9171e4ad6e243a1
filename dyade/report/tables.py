"""Result -> rich renderables: the sweep summary and the mechanism description."""

from __future__ import annotations

import numpy as np
from rich.table import Table
from rich.tree import Tree

from dyade.linkage.sweep import Plan, Result
from dyade.linkage.model import FRAME, Mechanism, Prismatic, Revolute
from dyade.linkage.columns import Columns, unit_of
from dyade.linkage.summary import cycle_mean


def sweep_summary(result: Result, cols: Columns) -> Table:
    """Per column: min and max over the sweep and the crank angle of each."""
    angle = cols["angle_deg"]
    table = Table(title=f"{result.mechanism.name}: {angle.size} crank positions "
                        f"{angle[0]:.1f}°–{angle[-1]:.1f}°", title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    for head in ("min", "at φ21 [°]", "max", "at φ21 [°]"):
        table.add_column(head, justify="right")
    for name, values in cols.items():
        if name == "angle_deg":
            continue
        finite = np.isfinite(values)
        if not finite.any():
            table.add_row(name, unit_of(name), "—", "", "—", "")
            continue
        masked = np.where(finite, values, np.nan)
        lo, hi = int(np.nanargmin(masked)), int(np.nanargmax(masked))
        table.add_row(name, unit_of(name), f"{values[lo] + 0.0:.6g}", f"{angle[lo]:.1f}",
                      f"{values[hi] + 0.0:.6g}", f"{angle[hi]:.1f}")
    return table


def _joint_label(joint: Revolute | Prismatic) -> str:
    a, b = joint.name
    if isinstance(joint, Revolute):
        return f"({a},{b}) revolute"
    return (f"({a},{b}) prismatic, guide on link {joint.carrier}, slider link {joint.slider}, "
            f"guide angle {np.rad2deg(joint.guide_angle):g}°")


def describe(mechanism: Mechanism, the_plan: Plan) -> Tree:
    """The mechanism in assembly order, its mobility and the effects to simulate."""
    tree = Tree(f"[bold]{mechanism.name}[/bold]"
                + (f"  ({mechanism.source})" if mechanism.source else ""))
    frame_points = mechanism.links[FRAME].points
    frame = tree.add("link 1: frame")
    for name, (x, y) in frame_points.items():
        frame.add(f"point {name} = ({x * 1e3:g}, {y * 1e3:g}) mm")
    crank = mechanism.crank
    rpm = abs(crank.speed) * 60.0 / (2.0 * np.pi)
    sense = "counter-clockwise" if crank.speed > 0 else "clockwise"
    node = tree.add(f"dyad 1: link 2 crank, length {crank.length * 1e3:g} mm, {rpm:g} rpm {sense}")
    node.add(f"joint {_joint_label(crank.joint)} at ({crank.pivot[0] * 1e3:g}, "
             f"{crank.pivot[1] * 1e3:g}) mm")
    _points(node, mechanism, 2)
    for dyad in mechanism.dyads:
        i, j = dyad.links
        g, h = dyad.known
        variant = f", assembly variant {dyad.variant:+d}" if dyad.variant else ""
        node = tree.add(f"dyad {dyad.number}: kind {dyad.kind.number} {dyad.kind.name}, "
                        f"links i={i}, j={j}, attached to links {g} and {h}{variant}")
        for letter, joint in zip("ABC", dyad.joints):
            node.add(f"{letter}: joint {_joint_label(joint)}")
        for link in dyad.links:
            _points(node, mechanism, link)
    links = 1 + len(mechanism.moving_links)
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    prismatic = len(mechanism.joints) - revolute
    mobility = 3 * (links - 1) - 2 * len(mechanism.joints)
    tree.add(f"mobility (Grübler) F = 3·({links}−1) − 2·{len(mechanism.joints)} = {mobility}"
             f"  [{links} links, {revolute} revolute, {prismatic} prismatic joints]")
    effects = tree.add("effects simulated")
    for line in the_plan.effects():
        effects.add(line)
    for line in skipped(the_plan):
        effects.add(f"[dim]not simulated — {line}[/dim]")
    sweep = mechanism.sweep
    tree.add(f"sweep: crank angle {np.rad2deg(sweep.start):g}° to {np.rad2deg(sweep.stop):g}° "
             f"in steps of {np.rad2deg(sweep.step):g}° ({sweep.angles().size} positions)")
    return tree


def skipped(the_plan: Plan) -> list[str]:
    """Effects the file does not call for, and what would turn them on."""
    out = []
    if not the_plan.kinetostatics:
        out.append("kinetostatics: no masses, loads or springs in the file")
    if not the_plan.friction:
        out.append("friction: no joint has a friction coefficient μ > 0")
    if not the_plan.self_locking:
        out.append("self-locking: no slider (prismatic joint) with friction")
    if not the_plan.clearance:
        out.append("clearance peaks: no joint has clearance data "
                   "(or run `dyade clearance FILE --stiffness … --clearance …`)")
    return out


def _points(node: Tree, mechanism: Mechanism, link: int) -> None:
    for name, (xi, eta) in mechanism.links[link].points.items():
        node.add(f"link {link} point {name} = ({xi * 1e3:g}, {eta * 1e3:g}) mm (ξ, η)")


def force_summary(result: Result, cols: Columns) -> Table | None:
    """Per joint: the largest force and where; the drive: max/min/RMS torque, mean power."""
    if result.forces is None:
        return None
    angle = cols["angle_deg"]
    rubbing = result.friction
    kind = "with Coulomb friction" if rubbing is not None else "frictionless"
    table = Table(title=f"Joint forces and drive (rigid, {kind})", title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    table.add_column("largest |value|", justify="right")
    table.add_column("at φ21 [°]", justify="right")
    for joint in result.mechanism.joints:
        a, b = joint.name
        names = ([f"F_{a}_{b}"] if isinstance(joint, Revolute) else [f"FN_{a}_{b}", f"M_{a}_{b}"])
        for name in names:
            values = np.abs(cols[name])
            if not np.isfinite(values).any():
                table.add_row(name, unit_of(name), "—", "")
                continue
            k = int(np.nanargmax(values))
            table.add_row(name, unit_of(name), f"{cols[name][k] + 0.0:.6g}", f"{angle[k]:.1f}")
    torque = cols["M_drive"]
    finite = np.isfinite(torque)
    if finite.any():
        lo, hi = int(np.nanargmin(torque)), int(np.nanargmax(torque))
        table.add_row("M_drive max", "N·m", f"{torque[hi]:.6g}", f"{angle[hi]:.1f}")
        table.add_row("M_drive min", "N·m", f"{torque[lo]:.6g}", f"{angle[lo]:.1f}")
        rms = np.sqrt(cycle_mean(angle, torque ** 2))
        table.add_row("M_drive RMS", "N·m", f"{rms:.6g}", "")
        table.add_row("P_drive mean", "W", f"{cycle_mean(angle, cols['P_drive']):.6g}", "")
    if rubbing is not None:
        table.add_row("P_friction mean", "W", f"{cycle_mean(angle, cols['P_friction']):.6g}", "")
        its = cols["friction_iterations"]
        rows = result.rows & result.forces.valid
        worst = float(np.max(rubbing.residual[rows], initial=0.0))
        table.add_row("friction passes", "-", f"{its.min():.0f}–{its.max():.0f}", "")
        table.add_row("worst final residual", "-", f"{worst:.2g}", "")
    for name, lock in (result.locking or {}).items():
        a, b = name
        locks = lock.locks[result.rows]
        verdict = f"locks over {int(locks.sum())} positions" if locks.any() else "no lock"
        if lock.margin is None:
            table.add_row(f"joint ({a},{b}) ({verdict})", "", "", "")
            continue
        margin = cols[f"lock_margin_{a}_{b}"]
        if np.isfinite(margin).any():
            k = int(np.nanargmin(margin))
            table.add_row(f"lock_margin_{a}_{b} min ({verdict})", "-", f"{margin[k]:.6g}",
                          f"{angle[k]:.1f}")
    return table


def clearance_summary(result: Result) -> Table | None:
    """One row per reversal of each checked joint: angle, τ, peak, amplification."""
    if not result.clearance:
        return None
    table = Table(title="Clearance peaks (Dresig & Thümmel)", title_justify="left")
    for head in ("joint", "impacts/rev", "φ21 [°]", "τ", "F12max [N]", "rigid [N]", "×"):
        table.add_column(head, justify="right")
    for check in result.clearance:
        a, b = check.joint
        if not check.applies:
            table.add_row(f"({a},{b})", "—", "model does not apply", "", "", "", "")
            continue
        if not check.reversals:
            table.add_row(f"({a},{b})", "0", "no reversal", "", "", "", "")
        for rev in check.reversals:
            table.add_row(f"({a},{b})", str(len(check.reversals)),
                          f"{np.rad2deg(rev.crank_angle):.1f}", f"{rev.peak.tau:.4g}",
                          f"{rev.peak.force:.5g}", f"{rev.rigid_force:.5g}",
                          f"{rev.amplification:.3g}")
    return table
