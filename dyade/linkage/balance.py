"""Counterweights against the shaking force (Berkof & Lowen 1969; Dresig & Holzweißig,
*Maschinendynamik*).

The shaking force is the resultant of the inertia forces, F = −Σ_k m_k·a_Sk: the mass
of the moving links times the acceleration of their common centre. A counterweight of
first moment b = m·d (d from the pivot, in the link's frame) on a link turning about a
frame pivot adds −(α·E − ω²)·R(φ_k)·b, linear in b: so the counterweights that make F
smallest over the cycle (in the least-squares sense over the sweep's positions) solve

    min over b of Σ_positions |F₀ + A·b|²,

one linear least-squares problem for all chosen links at once. For a four-bar with
counterweights on crank and rocker it has an exact solution, F = 0 at every position
(full force balance, Berkof & Lowen): the common centre of mass stands still.

A counterweight is realised as a point mass b/r at the radius r from the pivot; its
mass adds inertia, so the shaking moment, the drive torque and the joint forces change:
``balance`` reports them before and after, at the crank's constant speed.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from dyade import cycle
from dyade.arrays import FloatArray, Vec
from dyade.errors import DyadeError, InputError
from dyade.limits import PLAUSIBLE, check_plausible, implausible, plausible_range
from dyade.linkage import kinematics
from dyade.linkage.components import magnitude
from dyade.linkage.options import check_size
from dyade.model.mechanism import CRANK, FRAME, Link, Mechanism, Revolute


@dataclass(frozen=True, slots=True)
class Counterweight:
    """A counterweight on a link turning about a frame pivot."""

    link: int
    pivot: Vec
    """the frame pivot in the link's frame (ξ, η) [m]"""
    first_moment: float
    """|m·d| [kg·m] about the pivot"""
    angle: float
    """direction of d in the link's frame [rad], from its ξ axis"""
    radius: float
    """|d| [m], where the point mass sits"""

    @property
    def mass(self) -> float:
        """m = first_moment/radius [kg]"""
        return self.first_moment / self.radius

    @property
    def point(self) -> Vec:
        """where the point mass sits, in the link's frame (ξ, η) [m]"""
        return (self.pivot[0] + self.radius * math.cos(self.angle),
                self.pivot[1] + self.radius * math.sin(self.angle))


@dataclass(slots=True, eq=False)  # holds arrays and results: no meaningful ==
class Balance:
    """The counterweights and what they change."""

    counterweights: list[Counterweight]
    mechanism: Mechanism
    """the balanced mechanism (counterweights merged into the links' mass data)"""
    crank_angle: FloatArray
    """(n,) the positions of the fit [rad]"""
    shaking_before: FloatArray
    """(n, 2) inertia shaking force −Σ m·a_S of the original mechanism [N]"""
    shaking_after: FloatArray
    """(n, 2) the same with the counterweights [N]"""
    before: Any
    """``Result`` of the original mechanism (constant crank speed)"""
    after: Any
    """``Result`` of the balanced mechanism"""

    def changes(self) -> dict[str, Any]:
        """Before and after, SI: the shaking force (the inertia forces' resultant: largest
        magnitude and RMS over the sweep), the shaking moment M_shake and the drive torque
        M_drive (largest magnitude and RMS), and each joint's largest force."""
        shaking = {}
        angle, valid = self.crank_angle, self.before.kinematics.valid
        for when, force in (("before", self.shaking_before), ("after", self.shaking_after)):
            size = np.where(valid, magnitude(force[:, 0], force[:, 1]), np.nan)
            shaking[f"{when}_max"] = float(np.nanmax(size))
            shaking[f"{when}_rms"] = cycle.rms(angle, size)
        shaking["residual"] = (shaking["after_rms"] / shaking["before_rms"]
                               if shaking["before_rms"] > 0.0 else 0.0)
        out: dict[str, Any] = {"shaking_force": shaking}
        columns = {"before": self.before.columns(), "after": self.after.columns()}
        for key, name in (("shaking_moment", "M_shake"), ("drive_torque", "M_drive")):
            entry = {}
            for when, cols in columns.items():
                values = cols[name][np.isfinite(cols[name])]
                entry[f"{when}_max"] = float(np.max(np.abs(values))) if values.size else None
                entry[f"{when}_rms"] = cycle.rms(angle, cols[name]) if values.size else None
            out[key] = entry
        joints = {}
        for joint in self.mechanism.joints:
            a, b = joint.name
            name = f"F_{a}_{b}" if isinstance(joint, Revolute) else f"FN_{a}_{b}"
            joints[name] = {when: (float(np.nanmax(np.abs(cols[name])))
                                   if np.isfinite(cols[name]).any() else None)
                            for when, cols in columns.items()}
        out["joint_forces"] = joints
        return out

    def file_changes(self, data: dict[str, Any]) -> tuple[dict[str, Any], list[str]]:
        """What ``--save-as`` changes in the mechanism file: dotted key -> new value, and
        the keys to remove (a radius of gyration that the inertia replaces)."""
        changed = self.file_data(data)
        overrides, removals = {}, []
        for weight in self.counterweights:
            key = str(weight.link)
            for name, value in changed["links"][key].items():
                if name in ("mass", "centre", "inertia"):
                    overrides[f"links.{key}.{name}"] = value
            if "radius_of_gyration" in data.get("links", {}).get(key, {}):
                removals.append(f"links.{key}.radius_of_gyration")
        return overrides, removals

    def file_data(self, data: dict[str, Any]) -> dict[str, Any]:
        """The mechanism file's data (parsed TOML) with the counterweighted links' mass
        data replaced (mass, centre, inertia), in the file's units: for ``--save-as``."""
        from dyade.units import LENGTH_FACTORS

        out = copy.deepcopy(data)
        length = LENGTH_FACTORS[out.get("units", {}).get("length", "m")]
        links = out.setdefault("links", {})
        flywheel = self.mechanism.drive.flywheel_inertia if self.mechanism.drive else 0.0
        for weight in self.counterweights:
            link = self.mechanism.links[weight.link]
            table = links.setdefault(str(weight.link), {})
            table.pop("radius_of_gyration", None)
            table["mass"] = link.mass
            table["centre"] = [link.centre[0] / length, link.centre[1] / length]
            table["inertia"] = link.inertia - (flywheel if weight.link == CRANK else 0.0)
        return out


def pivoted_links(mechanism: Mechanism) -> dict[int, Vec]:
    """Links that turn about a frame pivot -> the pivot in the link's frame."""
    out = {}
    for joint in mechanism.joints:
        if isinstance(joint, Revolute) and FRAME in joint.links:
            other = 1 - joint.links.index(FRAME)
            out[joint.links[other]] = joint.points[other]
    return out


def _reach(mechanism: Mechanism, link: int, pivot: Vec) -> float:
    """The largest distance from the pivot to the link's joints, named points and
    centre of mass [m]: the default radius of its counterweight."""
    points = [mechanism.links[link].centre, *mechanism.links[link].points.values()]
    for joint in mechanism.joints:
        if link not in joint.links:
            continue
        if isinstance(joint, Revolute):
            points.append(joint.points[joint.links.index(link)])
        else:
            points.append(joint.guide_point if link == joint.carrier else joint.slider_point)
    return max(math.hypot(x - pivot[0], y - pivot[1]) for x, y in points)


def inertia_shaking(mechanism: Mechanism, kin: kinematics.Kinematics) -> FloatArray:
    """(n, 2) the inertia shaking force −Σ m_k·a_Sk [N]."""
    force = np.zeros((kin.crank_angle.shape[0], 2))
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        if link.mass:
            force -= link.mass * kin.motion.point_acceleration(number, link.centre)
    return force


def balance(mechanism: Mechanism, *, links=None, radius: float | None = None) -> Balance:
    """Counterweights on ``links`` that minimise the shaking force over the sweep.

    Parameters
    ----------
    mechanism : Mechanism
        With masses; its sweep gives the positions of the fit (at constant speed).
    links : iterable of int, optional
        Links to carry a counterweight; each must turn about a frame pivot. Default:
        every such link.
    radius : float, optional
        Radius [m] of every counterweight's point mass from its pivot; default: each
        link's reach (the largest distance from its pivot to its joints, named points
        and centre of mass).

    Returns
    -------
    Balance

    Examples
    --------
    The four-bar is fully force-balanced by counterweights on crank and rocker (the
    coupler's 1.2 kg, centred on A–B, counts half at each pin: 0.6 kg·0.05 m on the
    crank, and 0.6 kg·0.15 m plus the rocker's own 0.9 kg·0.075 m on the rocker):

    >>> import dyade
    >>> result = dyade.balance(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> [(w.link, round(w.first_moment, 5), round(math.degrees(w.angle), 2))
    ...  for w in result.counterweights]
    [(2, 0.03, 180.0), (4, 0.1575, 180.0)]
    >>> float(abs(result.shaking_after).max() / abs(result.shaking_before).max()) < 1e-12
    True
    """
    from dyade.linkage.sweep import analyse

    pivots = pivoted_links(mechanism)
    if links is None:
        chosen = sorted(pivots)
    else:
        chosen = [int(link) for link in links]
        for link in chosen:
            if link not in mechanism.links:
                raise InputError.parameter(
                    "links", f"{link}: there is no link {link} (the links are "
                             f"{', '.join(map(str, sorted(mechanism.links)))}).", value=link)
            if link not in pivots:
                raise InputError.parameter(
                    "links", f"{link}: link {link} does not turn about a frame pivot (those "
                             f"that do: {', '.join(map(str, sorted(pivots)))}); a counterweight "
                             f"elsewhere would shake the frame with its own mass.", value=link)
        if len(set(chosen)) != len(chosen) or not chosen:
            raise InputError.parameter("links", "must name each link once, at least one.",
                                       value=links)
    if radius is not None and not (math.isfinite(radius) and radius > 0.0):
        raise InputError.parameter("radius", f"must be a positive length [m], got {radius}.",
                                   value=radius, unit="m")
    if radius is not None:
        check_plausible("radius", radius, "length")
    check_size(mechanism, 3 * mechanism.sweep.count, None)  # the fit and two sweeps
    if not any(link.mass > 0.0 for link in mechanism.links.values()):
        raise InputError(f"{mechanism.name}: no link has a mass, so there is no shaking force "
                         f"to balance (add mass data, see `dyade help mechanism-file`).")
    kin = kinematics.sweep(mechanism)
    usable = kin.valid
    if usable.sum() < 2:
        raise DyadeError(f"{mechanism.name}: too few positions of the sweep close to fit "
                         f"counterweights.")
    motion = kin.motion
    unbalanced = inertia_shaking(mechanism, kin)
    columns = []
    for link in chosen:
        pivot = pivots[link]
        base = motion.point_acceleration(link, pivot)
        for axis in ((1.0, 0.0), (0.0, 1.0)):  # unit first moment along ξ, then η
            shifted = (pivot[0] + axis[0], pivot[1] + axis[1])
            columns.append(-(motion.point_acceleration(link, shifted) - base))
    matrix = np.stack([column[usable].ravel() for column in columns], axis=1)
    moments, *_ = np.linalg.lstsq(matrix, -unbalanced[usable].ravel(), rcond=None)
    after = unbalanced + sum(moment * column for moment, column in zip(moments, columns))
    weights = []
    for k, link in enumerate(chosen):
        b_xi, b_eta = moments[2 * k], moments[2 * k + 1]
        reach = radius if radius is not None else _reach(mechanism, link, pivots[link])
        if reach <= 0.0:
            raise InputError.parameter("radius", f"is needed for link {link}: it has no joint "
                                                 f"or point away from its pivot.", unit="m")
        weight = Counterweight(link, pivots[link], float(math.hypot(b_xi, b_eta)),
                               float(math.atan2(b_eta, b_xi)), float(reach))
        if implausible("mass", max(weight.first_moment / reach, PLAUSIBLE["mass"][0])):
            raise InputError.parameter(
                "radius", f"{reach:g} m gives link {link} a counterweight of "
                          f"{weight.first_moment / reach:.3g} kg, beyond what a machine has "
                          f"({plausible_range('mass')}): give a larger radius.",
                value=reach, unit="m")
        weights.append(weight)
    balanced = with_counterweights(mechanism, weights)
    before_result = analyse(mechanism, constant_speed=True, allow_partial=True)
    after_result = analyse(balanced, constant_speed=True, allow_partial=True)
    return Balance(weights, balanced, kin.crank_angle, unbalanced, after, before_result,
                   after_result)


def with_counterweights(mechanism: Mechanism, weights: list[Counterweight]) -> Mechanism:
    """The mechanism with each counterweight's point mass merged into its link: mass,
    centre of mass and moment of inertia about it (parallel axes)."""
    links = dict(mechanism.links)
    for weight in weights:
        if weight.first_moment == 0.0:
            continue
        old = links[weight.link]
        extra, point = weight.mass, np.asarray(weight.point)
        mass = old.mass + extra
        centre = (old.mass * np.asarray(old.centre) + extra * point) / mass
        inertia = (old.inertia + old.mass * float(np.sum((np.asarray(old.centre) - centre) ** 2))
                   + extra * float(np.sum((point - centre) ** 2)))
        links[weight.link] = Link(old.number, old.points, float(mass),
                                  (float(centre[0]), float(centre[1])), float(inertia))
    return replace(mechanism, links=links)
