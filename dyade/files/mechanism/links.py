"""Links and joints: the frame's and the links' named points, the crank, link masses,
and the outer joints A and C of a dyad (a revolute joint, or a prismatic one with its
guide on either link); joints between the same links twice and repeated point names
are refused."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from dyade.arrays import Variants, Vec
from dyade.files.mechanism.friction import FrictionReader
from dyade.files.schema import is_number, show, suggest
from dyade.model.mechanism import CRANK, FRAME, Crank, Dyad, Link, Prismatic, Revolute
from dyade.units import rpm_to_rad_per_s

FRAME_KEYS = {"points"}
CRANK_KEYS = {"link", "pivot", "length", "speed_rpm", "direction", "points", "pin_radius",
              "friction", "clearance"}
NUMERIC_RPM = 1e12
"""[rpm] the highest crank speed read at all (1e300 rpm overflowed into a traceback)"""
LINK_KEYS = {"points", "mass", "centre", "inertia", "radius_of_gyration"}
REVOLUTE_KEYS = {"link", "point", "pin_radius", "friction", "clearance"}
PRISMATIC_KEYS = {"link", "point", "angle", "offset", "guide", "slider_point", "slider_length",
                  "slider_height", "friction", "edge_friction"}


class LinkReader(FrictionReader):
    """Reads links, points, the crank and the joints that attach a dyad to placed links."""

    unbounded = frozenset({"crank.speed_rpm"})  # above 1e6 rpm: analysed, its rows withheld

    points: dict[int, dict[str, Vec]]
    """link -> its named points (ξ, η) [m], the frame's included"""
    placed: list[int]
    """the links placed so far, in order: the frame, the crank, then two per dyad"""

    def pair(self, value: Any, key: str) -> Vec:
        if (not isinstance(value, list) or len(value) != 2
                or not all(is_number(v) for v in value)):
            raise self.fail(key, f"must be a pair of numbers [ξ, η] [{self.length_unit}], "
                                 f"got {show(value)}.", value, self.length_unit)
        if isinstance(value[0], Variants) or isinstance(value[1], Variants):
            finite = all(np.isfinite(v).all() for v in value)
        else:  # the common case, a file's point: plain floats (a file may have 100 000)
            finite = math.isfinite(value[0]) and math.isfinite(value[1])
        if not finite:
            raise self.fail(key, f"must be a pair of finite numbers [ξ, η] "
                                 f"[{self.length_unit}], got {show(value)}.", value,
                            self.length_unit)
        for v in value:
            self.below_top(_real(v), key, "length", self.length_unit, self.length)
        return (_real(value[0]) * self.length, _real(value[1]) * self.length)

    def named_points(self, table: Any, key: str) -> dict[str, Vec]:
        if not isinstance(table, dict):
            raise self.fail(key, f"must be a table of name = [ξ, η], got {show(table)}.")
        return {name: self.pair(value, f"{key}.{name}") for name, value in table.items()}

    def crank(self, table: Any) -> Crank:
        self.keys(table, "crank", CRANK_KEYS)
        link = self.integer(table.get("link", CRANK), "crank.link")
        if link != CRANK:
            raise self.fail("crank.link", f"must be 2 (link 1 is the frame, 2 the crank), "
                                          f"got {link}.")
        length = self.length_of(self.required(table, "length", "crank"), "crank.length",
                                positive=True)
        pivot = self.point_on(FRAME, table.get("pivot", [0.0, 0.0]), "crank.pivot")
        rpm = self.number(self.required(table, "speed_rpm", "crank"), "crank.speed_rpm", "rpm",
                          positive=True)
        if np.max(rpm) > NUMERIC_RPM:  # beyond the plausible 1e6 rpm: analysed, not given
            raise self.fail("crank.speed_rpm", f"must be at most {NUMERIC_RPM:g} rpm (beyond "
                                               f"it the squares overflow; 0.01…1e+06 rpm is "
                                               f"what a machine has), got {rpm:g}.", rpm, "rpm")
        direction = table.get("direction", "ccw")
        if direction not in ("ccw", "cw"):
            raise self.fail("crank.direction", f"must be \"ccw\" (counter-clockwise) or \"cw\", "
                                               f"got {show(direction)}.")
        points = {"tip": (length, 0.0)}
        points.update(self.named_points(table.get("points", {}), "crank.points"))
        self.points[CRANK] = points
        speed = rpm_to_rad_per_s(rpm) * (1.0 if direction == "ccw" else -1.0)
        joint = Revolute((FRAME, CRANK), (pivot, (0.0, 0.0)), **self.revolute_friction(
            table, "crank"))
        return Crank(pivot, length, speed, joint)

    def link_tables(self, table: dict[str, Any]) -> dict[int, dict[str, Any]]:
        out: dict[int, dict[str, Any]] = {}
        for key, sub in table.items():
            path = f"links.{key}"
            if not key.isdigit() or int(key) < 2:
                raise self.fail(path, "must name a moving link by its number (2, 3, ...); "
                                      "frame points go in [frame.points].")
            number = int(key)
            self.keys(sub, path, LINK_KEYS)
            self.points.setdefault(number, {}).update(
                self.named_points(sub.get("points", {}), f"{path}.points"))
            extra: dict[str, Any] = {}
            if "mass" in sub:
                extra["mass"] = self.within(self.number(sub["mass"], f"{path}.mass", "kg",
                                                           non_negative=True),
                                               f"{path}.mass", "mass", "kg", floor=False)
            if "centre" in sub:
                extra["centre"] = self.pair(sub["centre"], f"{path}.centre")
            if "inertia" in sub and "radius_of_gyration" in sub:
                raise self.fail(f"{path}.inertia", "and `radius_of_gyration` are two ways to say "
                                                   "the same thing: give one of them.")
            if "inertia" in sub:
                extra["inertia"] = self.within(self.number(
                    sub["inertia"], f"{path}.inertia", "kg·m²", non_negative=True),
                    f"{path}.inertia", "inertia", "kg·m²", floor=False)
            if "radius_of_gyration" in sub:
                radius = self.length_of(sub["radius_of_gyration"], f"{path}.radius_of_gyration",
                                        non_negative=True)
                if "mass" not in sub:
                    raise self.fail(f"{path}.radius_of_gyration", "needs `mass` of the same link.")
                extra["inertia"] = extra["mass"] * radius ** 2
            out[number] = extra
        return out

    # -- points and joints -------------------------------------------------------------
    def point_on(self, link: int, value: Any, key: str) -> Vec:
        if isinstance(value, str):
            names = self.points.get(link, {})
            if value not in names:
                where = {FRAME: "[frame.points]", CRANK: "[crank.points] (or \"tip\")"}.get(
                    link, f"[links.{link}.points]")
                hint = suggest(value, set(names)) if names else ""
                raise self.fail(key, f"names point \"{value}\", which link {link} does not have;"
                                     f" define it in {where} or give [ξ, η].{hint}")
            return names[value]
        return self.pair(value, key)

    def attached(self, table: dict[str, Any], key: str, allowed: set[str]) -> tuple[int, Vec]:
        self.keys(table, key, allowed)
        link = self.integer(self.required(table, "link", key), f"{key}.link")
        if link not in self.placed:
            raise self.fail(f"{key}.link", f"is link {link}, which is not placed yet: a dyad may "
                                           f"only attach to the frame (1), the crank (2) or "
                                           f"links of earlier dyads "
                                           f"({', '.join(map(str, self.placed))}).")
        return link, self.point_on(link, table.get("point", [0.0, 0.0]), f"{key}.point")

    def revolute(self, table: Any, key: str, new: int) -> tuple[int, Revolute]:
        link, point = self.attached(table, key, REVOLUTE_KEYS)
        return link, Revolute((link, new), (point, (0.0, 0.0)), **self.revolute_friction(table, key))

    def outer_prismatic(self, table: Any, key: str, new: int) -> tuple[int, Prismatic]:
        link, point = self.attached(table, key, PRISMATIC_KEYS)
        theta = self.angle_of(table.get("angle", 0.0), f"{key}.angle")
        offset = self.length_of(table.get("offset", 0.0), f"{key}.offset")
        guide = self.guide(table, key, (link, new), link)
        extra = self.prismatic_friction(table, key)
        if guide == link:
            centre = self.pair(table.get("slider_point", [0.0, 0.0]), f"{key}.slider_point")
            return link, Prismatic.through(link, point, theta, offset, new, centre, theta, **extra)
        if "slider_point" in table:
            raise self.fail(f"{key}.slider_point", "applies when the dyad's link is the slider; "
                                                   "with the guide on it, `point` is the slider point.")
        return link, Prismatic.through(new, (0.0, 0.0), 0.0, offset, link, point, -theta,
                                       **extra)

    def guide(self, table: dict[str, Any], key: str, pair: tuple[int, int], default: int) -> int:
        guide = self.integer(table.get("guide", default), f"{key}.guide")
        if guide not in pair:
            raise self.fail(f"{key}.guide", f"must be one of the joint's links {pair[0]} or "
                                            f"{pair[1]} (the link carrying the guide), got {guide}.")
        return guide

    # -- whole-mechanism checks ------------------------------------------------------
    def check_names(self, links: dict[int, Link]) -> None:
        seen: dict[str, int] = {}
        for link in links.values():
            if link.number == FRAME:
                continue
            for name in link.points:
                if name == "tip" and link.number == CRANK:
                    continue
                if name in seen:
                    raise self.fail(f"links.{link.number}.points.{name}",
                                    f"repeats the point name \"{name}\" of link {seen[name]}; "
                                    f"point names must be unique (they name CSV columns).")
                seen[name] = link.number

    def check_joints(self, crank: Crank, dyads: tuple[Dyad, ...]) -> None:
        seen: dict[tuple[int, int], str] = {(FRAME, CRANK): "the crank"}
        for dyad in dyads:
            for letter, joint in zip("ABC", dyad.joints):
                name = joint.name
                if name in seen:
                    raise self.fail(f"dyad.{dyad.number}.{letter}",
                                    f"joins links {name[0]} and {name[1]}, which {seen[name]} "
                                    f"already joins; two joints between the same links are "
                                    f"not a dyad chain.")
                seen[name] = f"joint {letter} of dyad {dyad.number}"


def _real(value: Any) -> float | Variants:
    """A number of the file as a float (``Variants`` as they are)."""
    return value if isinstance(value, Variants) else float(value)
