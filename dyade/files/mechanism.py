"""Read a mechanism file (TOML), validate it, and convert it to SI model objects.

Every error names the file, the key path, what was expected (with its unit) and what
was found; unknown keys get a "Did you mean" (``mechanisms/README.md`` documents every
key). The keys of each dyad kind and its middle joint B are read here (``MIDDLE``): the
kinds themselves (``dyade.linkage.dyads``) know geometry and mechanics only. The
primitives are the shared schema (``dyade.files.schema``).
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from dyade.errors import InputError
from dyade.files.schema import UnitReader, set_dotted, suggest
from dyade.files.schema import load_data as schema_load_data
from dyade.files.schema import fmt as _fmt
from dyade.files.schema import show as _show
from dyade.linkage import dyads as dyad_kinds
from dyade.linkage.model import (
    CRANK,
    FRAME,
    ClearanceData,
    Crank,
    Dyad,
    DyadKind,
    Link,
    Load,
    Mechanism,
    Prismatic,
    Revolute,
    Spring,
    Sweep,
    Vec,
    sweep_problem,
)
from dyade.units import rpm_to_rad_per_s

if TYPE_CHECKING:  # the motor models load only with a [drive] table
    from dyade.machine.motor import Drive

TOP_KEYS = {"name", "description", "units", "sweep", "frame", "crank", "dyad", "links",
            "gravity", "load", "spring", "friction", "drive"}
SWEEP_KEYS = {"start", "stop", "step", "dead_centre", "transmission_warning"}
FRAME_KEYS = {"points"}
CRANK_KEYS = {"link", "pivot", "length", "speed_rpm", "direction", "points", "pin_radius",
              "friction", "clearance"}
LINK_KEYS = {"points", "mass", "centre", "inertia", "radius_of_gyration"}
REVOLUTE_KEYS = {"link", "point", "pin_radius", "friction", "clearance"}
PRISMATIC_KEYS = {"link", "point", "angle", "offset", "guide", "slider_point", "slider_length",
                  "slider_height", "friction", "edge_friction"}
FRICTION_KEYS = {"coefficient", "tol", "max_iter", "pin_radius", "slider_length", "slider_height",
                 "edge_friction"}
MIDDLE_R_KEYS = {"pin_radius", "friction", "clearance"}
MIDDLE_P_KEYS = {"guide", "offset", "angle", "point", "slider_length", "slider_height",
                 "friction", "edge_friction"}
DYAD_KEYS_COMMON = {"kind", "links", "A", "B", "C", "variant", "name"}
GRAVITY_KEYS = {"x", "y"}
MOTOR_KEYS = {"constant": {"torque"},
              "asynchronous": {"rated_torque", "rated_speed_rpm", "synchronous_speed_rpm"},
              "table": {"table"}}
"""[drive] motor kind -> the keys of its characteristic"""
DRIVE_KEYS = {"motor", "flywheel_inertia", "steps", "tol", "max_revolutions"}.union(
    *MOTOR_KEYS.values())
STANDARD_GRAVITY = 9.80665  # [m/s²]
NUMBERING = {"dyad": (2, "dyads are numbered as in DYADE: the crank is dyad 1, the first "
                         "[[dyad]] table dyad 2")}
"""arrays of tables whose entries are not numbered from 1, for keys and overrides"""


def read_mechanism(path: str | os.PathLike, overrides: dict[str, Any] | None = None
                   ) -> Mechanism:
    """Read and validate a mechanism file.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (``mechanisms/README.md`` documents every key).
    overrides : dict, optional
        Dotted key path -> value, replacing keys of the file as ``--set`` does
        (``{"crank.speed_rpm": 600}``; array entries by 1-based index).

    Returns
    -------
    Mechanism
        In SI units, validated.

    Raises
    ------
    InputError
        Naming the file and the key path, what was expected and what was found.
    """
    return build(load_data(path, overrides), path)


def load_data(path: str | os.PathLike, overrides: dict[str, Any] | None = None,
              what: str = "override", text: str | None = None) -> dict[str, Any]:
    """The file's TOML data with ``overrides`` (dotted key -> value, dyads numbered as in
    DYADE) applied; ``what`` names them in messages; ``text``: the file's content when
    already read (stdin)."""
    return schema_load_data(path, overrides, what, text, NUMBERING)


def edited(text: str, overrides: dict[str, Any], label: str = "mechanism",
           what: str = "override", removals: tuple[str, ...] | list[str] = ()) -> str:
    """The file's text with ``overrides`` applied (and the dotted keys of ``removals``
    removed), everything else kept: comments, key order, inline tables, short arrays on
    one line (``--save-as``; tomlkit edits the parsed document in place)."""
    import tomlkit

    document = tomlkit.parse(text)
    for key in removals:
        *path, last = key.split(".")
        table = document
        for part in path:
            table = table[part]
        del table[last]
    for key, value in overrides.items():
        set_dotted(document, key, value, label, what, NUMBERING)
    return tomlkit.dumps(document)


def build(data: dict[str, Any], path: str | os.PathLike | None = None) -> Mechanism:
    """Validate mechanism data (the parsed TOML of a mechanism file, or the same
    structure written in Python) and build the mechanism; errors name ``path``."""
    path = os.fspath(path) if path else None
    return Reader(os.path.basename(path) if path else "mechanism", path).mechanism(data)


def dumps(data: dict[str, Any]) -> str:
    """Mechanism data (a dict with the keys of a mechanism file) as TOML text."""
    import tomlkit

    return tomlkit.dumps(data)


class Reader(UnitReader):
    """Walks the parsed TOML of a mechanism file with key paths for the error messages."""

    top_keys = TOP_KEYS

    def pair(self, value: Any, key: str) -> Vec:
        if (not isinstance(value, list) or len(value) != 2
                or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)):
            raise self.fail(key, f"must be a pair of numbers [ξ, η] [{self.length_unit}], "
                                 f"got {_show(value)}.", value, self.length_unit)
        if not all(math.isfinite(v) for v in value):
            raise self.fail(key, f"must be a pair of finite numbers [ξ, η] "
                                 f"[{self.length_unit}], got {_show(value)}.", value,
                            self.length_unit)
        return (float(value[0]) * self.length, float(value[1]) * self.length)

    # -- whole file ----------------------------------------------------------------
    def mechanism(self, data: dict[str, Any]) -> Mechanism:
        self.keys(data, "", TOP_KEYS)
        self.units(data.get("units", {}))
        name = data.get("name", os.path.splitext(os.path.basename(self.source))[0]
                        if self.source else "mechanism")
        if not isinstance(name, str):
            raise self.fail("name", f"must be a string, got {_show(name)}.")
        sweep, dead_centre, warning = self.sweep(data.get("sweep", {}))
        friction = data.get("friction", {})
        self.keys(friction, "friction", FRICTION_KEYS)
        self.friction_defaults = {
            name: self.length_of(friction[name], f"friction.{name}", positive=True)
            for name in ("pin_radius", "slider_length", "slider_height") if name in friction}
        self.default_mu = self.number(friction.get("coefficient", 0.0), "friction.coefficient",
                                      "-", non_negative=True)
        self.default_edges = self.boolean(friction.get("edge_friction", True),
                                          "friction.edge_friction")
        friction_tol = self.number(friction.get("tol", 1e-9), "friction.tol", "-", positive=True)
        friction_max_iter = self.integer(friction.get("max_iter", 50), "friction.max_iter")
        if friction_max_iter < 1:
            raise self.fail("friction.max_iter", f"must be at least 1, got {friction_max_iter}.")
        frame_table = self.keys(data.get("frame", {}), "frame", FRAME_KEYS)
        links_table = data.get("links", {})
        if not isinstance(links_table, dict):
            raise self.fail("links", f"must be a table of [links.N] tables, got {_show(links_table)}.")
        self.points: dict[int, dict[str, Vec]] = {FRAME: self.named_points(
            frame_table.get("points", {}), "frame.points")}
        crank = self.crank(self.required(data, "crank", ""))
        dyad_tables = data.get("dyad", [])
        if not isinstance(dyad_tables, list) or not dyad_tables:
            raise self.fail("dyad", "must list at least one dyad as [[dyad]] tables "
                                    "(the crank alone is no linkage).")
        self.placed = [FRAME, CRANK]
        link_data = self.link_tables(links_table)
        dyads = tuple(self.dyad(table, number) for number, table in enumerate(dyad_tables, start=2))
        for number in link_data:
            if number not in self.placed:
                raise self.fail(f"links.{number}", f"describes link {number}, which no dyad "
                                f"places (placed links: {', '.join(map(str, self.placed))}).")
        links = {}
        for number in self.placed:
            extra = link_data.get(number, {})
            points = dict(self.points.get(number, {}))
            links[number] = Link(number, points, **extra)
        self.check_names(links)
        self.check_joints(crank, dyads)
        gravity = self.gravity(data.get("gravity", None))
        loads = tuple(self.load(t, f"load.{k}", links)
                      for k, t in enumerate(_list(data.get("load", []), "load", self), 1))
        springs = tuple(self.spring(t, f"spring.{k}", links)
                        for k, t in enumerate(_list(data.get("spring", []), "spring", self), 1))
        drive = self.drive(data["drive"]) if "drive" in data else None
        if drive is not None and drive.flywheel_inertia:
            crank_link = links[CRANK]  # the flywheel turns with the crank, about its pivot
            links[CRANK] = Link(CRANK, crank_link.points, crank_link.mass, crank_link.centre,
                                crank_link.inertia + drive.flywheel_inertia)
        if drive is not None and not any(link.has_mass for link in links.values()):
            raise self.fail("drive", "needs the machine's inertia for its equation of motion: "
                                     "give the links masses (`links.N.mass`) or a flywheel "
                                     "(`drive.flywheel_inertia`).")
        return Mechanism(name, self.source, crank, dyads, links, sweep, gravity, loads, springs,
                         dead_centre, friction_tol, friction_max_iter, warning,
                         (self.length_unit, self.angle_unit), drive)

    def sweep(self, table: Any) -> tuple[Sweep, float, float]:
        self.keys(table, "sweep", SWEEP_KEYS)
        full = 2.0 * math.pi / self.angle
        start = self.number(table.get("start", 0.0), "sweep.start", self.angle_unit)
        stop = self.number(table.get("stop", start + full), "sweep.stop", self.angle_unit)
        step = self.number(table.get("step", math.pi / 180.0 / self.angle), "sweep.step",
                           self.angle_unit, positive=True)
        if stop < start:
            raise self.fail("sweep.stop", f"must not be below sweep.start ({_fmt(start)}), "
                                          f"got {_fmt(stop)}.")
        dead = self.number(table.get("dead_centre", 2.0 * math.pi / 180.0 / self.angle),
                           "sweep.dead_centre", self.angle_unit, non_negative=True)
        warn = self.number(table.get("transmission_warning", 40.0 * math.pi / 180.0 / self.angle),
                           "sweep.transmission_warning", self.angle_unit, non_negative=True)
        if not dead * self.angle < warn * self.angle <= math.pi / 2:
            raise self.fail("sweep.transmission_warning", f"must lie above sweep.dead_centre "
                                                          f"({_fmt(dead)}) and at most 90°, got "
                                                          f"{_fmt(warn)}.", warn)
        problem = sweep_problem(start * self.angle, stop * self.angle, step * self.angle)
        if problem:
            raise self.fail("sweep", f"{problem}.")
        return (Sweep(start * self.angle, stop * self.angle, step * self.angle), dead * self.angle,
                warn * self.angle)

    def named_points(self, table: Any, key: str) -> dict[str, Vec]:
        if not isinstance(table, dict):
            raise self.fail(key, f"must be a table of name = [ξ, η], got {_show(table)}.")
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
        direction = table.get("direction", "ccw")
        if direction not in ("ccw", "cw"):
            raise self.fail("crank.direction", f"must be \"ccw\" (counter-clockwise) or \"cw\", "
                                               f"got {_show(direction)}.")
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
                extra["mass"] = self.number(sub["mass"], f"{path}.mass", "kg", non_negative=True)
            if "centre" in sub:
                extra["centre"] = self.pair(sub["centre"], f"{path}.centre")
            if "inertia" in sub and "radius_of_gyration" in sub:
                raise self.fail(f"{path}.inertia", "and `radius_of_gyration` are two ways to say "
                                                   "the same thing: give one of them.")
            if "inertia" in sub:
                extra["inertia"] = self.number(sub["inertia"], f"{path}.inertia", "kg·m²",
                                               non_negative=True)
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

    def revolute_friction(self, table: dict[str, Any], key: str) -> dict[str, Any]:
        out = self.friction_data(table, key, ("pin_radius",))
        if "clearance" in table:
            sub = self.keys(table["clearance"], f"{key}.clearance", {"gap", "stiffness", "mass"})
            path = f"{key}.clearance"
            gap = self.length_of(self.required(sub, "gap", path), f"{path}.gap", positive=True)
            stiffness = self.number(self.required(sub, "stiffness", path), f"{path}.stiffness",
                                    "N/m", positive=True)
            mass = (self.number(sub["mass"], f"{path}.mass", "kg", positive=True)
                    if "mass" in sub else None)
            out["clearance"] = ClearanceData(gap, stiffness, mass)
        return out

    def prismatic_friction(self, table: dict[str, Any], key: str) -> dict[str, Any]:
        out = self.friction_data(table, key, ("slider_length", "slider_height"))
        out["edge_friction"] = self.boolean(table.get("edge_friction", self.default_edges),
                                            f"{key}.edge_friction")
        return out

    def boolean(self, value: Any, key: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(key, f"must be true or false, got {_show(value)}.", value)
        return value

    def friction_data(self, table: dict[str, Any], key: str, needs: tuple[str, ...]
                      ) -> dict[str, Any]:
        """μ of a joint (or the file default) and the sizes friction needs: r_z for a
        revolute joint, slider length L and height H for a prismatic one."""
        mu = self.number(table.get("friction", self.default_mu), f"{key}.friction", "-",
                         non_negative=True)
        out: dict[str, Any] = {"friction": mu}
        for name in needs:
            if name in table:
                out[name] = self.length_of(table[name], f"{key}.{name}", positive=True)
            elif name in self.friction_defaults:
                out[name] = self.friction_defaults[name]
            elif mu > 0.0:
                what = {"pin_radius": "the pin radius r_z", "slider_length": "the slider length L",
                        "slider_height": "the slider height H"}[name]
                raise self.fail(f"{key}.{name}", f"is missing: the joint has friction "
                                                 f"(μ = {mu:g}) and needs {what} "
                                                 f"[{self.length_unit}] (or give a default in "
                                                 f"[friction] {name}).")
        return out

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

    def dyad(self, table: Any, number: int) -> Dyad:
        key = f"dyad.{number}"
        if not isinstance(table, dict):
            raise self.fail(key, f"must be a table, got {_show(table)}.")
        kind = self.kind(self.required(table, "kind", key), f"{key}.kind")
        keys, middle = MIDDLE[kind.name]
        self.keys(table, key, DYAD_KEYS_COMMON | keys)
        links = self.required(table, "links", key)
        if (not isinstance(links, list) or len(links) != 2
                or any(isinstance(v, bool) or not isinstance(v, int) for v in links)):
            raise self.fail(f"{key}.links", f"must be two link numbers [i, j], got {_show(links)}.")
        i, j = links
        for link in (i, j):
            if link in self.placed:
                raise self.fail(f"{key}.links", f"uses link {link} again; every dyad places two "
                                                f"new links (placed: "
                                                f"{', '.join(map(str, self.placed))}).")
        if i == j or i < 3 or j < 3:
            raise self.fail(f"{key}.links", f"must be two different new link numbers above 2, "
                                            f"got {_show(links)}.")
        if kind.has_variant:
            variant = self.integer(table.get("variant", 1), f"{key}.variant")
            if variant not in (1, -1):
                raise self.fail(f"{key}.variant", f"must be +1 or -1 (assembly variant), "
                                                  f"got {variant}.")
        else:
            if "variant" in table:
                raise self.fail(f"{key}.variant", f"is not used by kind {kind.number} "
                                                  f"({kind.name}): it has one closure only.")
            variant = 0
        pattern = kind.name
        for letter, joint_kind in zip("ABC", pattern):
            if letter == "B":
                continue
            if letter not in table:
                raise self.fail(f"{key}.{letter}", "is missing: say which placed link and point "
                                                   f"joint {letter} attaches to.")
        g = h = 0
        if pattern[0] == "R":
            g, joint_a = self.revolute(table["A"], f"{key}.A", i)
        else:
            g, joint_a = self.outer_prismatic(table["A"], f"{key}.A", i)
        if pattern[2] == "R":
            h, joint_c = self.revolute(table["C"], f"{key}.C", j)
        else:
            h, joint_c = self.outer_prismatic(table["C"], f"{key}.C", j)
        b_table = table.get("B", {})
        joint_b = middle(self, b_table, f"{key}.B", i, j, table, key)
        self.placed.extend((i, j))
        return Dyad(number, kind, (i, j), (g, h), (joint_a, joint_b, joint_c), variant)

    def kind(self, value: Any, key: str) -> DyadKind:
        kind = dyad_kinds.named(value)
        if kind is None:
            names = ", ".join(name.upper() for name in dyad_kinds.REGISTRY)
            raise self.fail(key, f"must be 1-{len(dyad_kinds.REGISTRY)} or one of {names}, "
                                 f"got {_show(value)}.", value)
        return kind

    def middle_revolute(self, table: Any, key: str) -> dict[str, Any]:
        """The keys of a revolute joint B: its friction and clearance data."""
        self.keys(table, key, MIDDLE_R_KEYS)
        return self.revolute_friction(table, key)

    def middle_prismatic(self, table: Any, key: str, point: bool) -> tuple[float, dict[str, Any]]:
        """The common keys of a prismatic joint B: its offset [m] and friction data;
        ``point``: the kind also takes the guide's `point` and `angle`."""
        self.keys(table, key, MIDDLE_P_KEYS if point else MIDDLE_P_KEYS - {"angle", "point"})
        return self.length_of(table.get("offset", 0.0), f"{key}.offset"), \
            self.prismatic_friction(table, key)

    # -- loads (used by the force analysis) -----------------------------------------
    def gravity(self, value: Any) -> Vec:
        if value is None or value is False:
            return (0.0, 0.0)
        if value is True:
            return (0.0, -STANDARD_GRAVITY)
        self.keys(value, "gravity", GRAVITY_KEYS)
        return (self.number(value.get("x", 0.0), "gravity.x", "m/s²"),
                self.number(value.get("y", 0.0), "gravity.y", "m/s²"))

    def drive(self, table: Any) -> Drive:
        """The [drive] table: motor characteristic, flywheel and integration settings."""
        from dyade.machine.motor import (Asynchronous, ConstantTorque, Drive, Motor,
                                         TorqueSpeedTable)

        self.keys(table, "drive", DRIVE_KEYS)
        kind = self.required(table, "motor", "drive")
        if not isinstance(kind, str) or kind not in MOTOR_KEYS:
            raise self.fail("drive.motor", f"must be one of {', '.join(map(_show, MOTOR_KEYS))}"
                                           f", got {_show(kind)}.", kind)
        for key in table:
            if key in DRIVE_KEYS - {"motor", "flywheel_inertia", "steps", "tol",
                                    "max_revolutions"} - MOTOR_KEYS[kind]:
                raise self.fail(f"drive.{key}", f"does not belong to a {_show(kind)} motor "
                                                f"(its keys: {', '.join(sorted(MOTOR_KEYS[kind]))}"
                                                f").")
        motor: Motor
        if kind == "constant":
            torque = (self.number(table["torque"], "drive.torque", "N·m", positive=True)
                      if "torque" in table else None)
            motor = ConstantTorque(torque)
        elif kind == "asynchronous":
            rated = self.number(self.required(table, "rated_torque", "drive"),
                                "drive.rated_torque", "N·m", positive=True)
            speed = self.number(self.required(table, "rated_speed_rpm", "drive"),
                                "drive.rated_speed_rpm", "rpm", positive=True)
            synchronous = self.number(self.required(table, "synchronous_speed_rpm", "drive"),
                                      "drive.synchronous_speed_rpm", "rpm", positive=True)
            if synchronous <= speed:
                raise self.fail("drive.synchronous_speed_rpm", f"must be above the rated speed "
                                                               f"({_fmt(speed)} rpm: an "
                                                               f"asynchronous motor slips), got "
                                                               f"{_fmt(synchronous)}.",
                                synchronous, "rpm")
            motor = Asynchronous(rated, rpm_to_rad_per_s(speed), rpm_to_rad_per_s(synchronous))
        else:
            rows = self.required(table, "table", "drive")
            if not isinstance(rows, list) or len(rows) < 2:
                raise self.fail("drive.table", f"must list at least two rows [speed [rpm], "
                                               f"torque [N·m]], got {_show(rows)}.")
            parsed = []
            for r, row in enumerate(rows, 1):
                if (not isinstance(row, list) or len(row) != 2
                        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in row)
                        or not all(math.isfinite(v) for v in row)):
                    raise self.fail(f"drive.table.{r}", f"must be [speed [rpm], torque [N·m]], "
                                                        f"got {_show(row)}.")
                parsed.append([float(v) for v in row])
            arr = np.array(parsed)
            if arr[0, 0] < 0 or np.any(np.diff(arr[:, 0]) <= 0):
                raise self.fail("drive.table", "speeds must rise strictly from 0 rpm or more.")
            motor = TorqueSpeedTable(rpm_to_rad_per_s(arr[:, 0]), arr[:, 1])
        flywheel = self.number(table.get("flywheel_inertia", 0.0), "drive.flywheel_inertia",
                               "kg·m²", non_negative=True)
        steps = None
        if "steps" in table:
            steps = self.integer(table["steps"], "drive.steps")
            if steps < 36:
                raise self.fail("drive.steps", f"must be at least 36 steps per revolution, got "
                                               f"{steps}.", steps)
        tol = self.number(table.get("tol", 1e-10), "drive.tol", "-", positive=True)
        revolutions = self.integer(table.get("max_revolutions", 500), "drive.max_revolutions")
        if revolutions < 2:
            raise self.fail("drive.max_revolutions", f"must be at least 2, got {revolutions}.")
        return Drive(motor, flywheel, steps, tol, revolutions)

    def link_ref(self, value: Any, key: str, links: dict[int, Link]) -> int:
        link = self.integer(value, key)
        if link not in links:
            raise self.fail(key, f"is link {link}, which the mechanism does not have "
                                 f"(links: {', '.join(map(str, links))}).")
        return link

    def load(self, table: Any, key: str, links: dict[int, Link]) -> Load:
        self.keys(table, key, {"link", "point", "force", "moment", "table", "frame"})
        link = self.link_ref(self.required(table, "link", key), f"{key}.link", links)
        point = self.point_on(link, table.get("point", [0.0, 0.0]), f"{key}.point")
        frame = table.get("frame", "world")
        if frame not in ("world", "link"):
            raise self.fail(f"{key}.frame", f"must be \"world\" (x, y) or \"link\" (ξ, η), "
                                            f"got {_show(frame)}.")
        if "table" in table:
            if "force" in table or "moment" in table:
                raise self.fail(f"{key}.table", "replaces `force` and `moment`: give either "
                                                "a table or constant values.")
            rows = table["table"]
            if not isinstance(rows, list) or len(rows) < 2:
                raise self.fail(f"{key}.table", "must list at least two rows "
                                                f"[angle, Fx, Fy, M], got {_show(rows)}.")
            parsed = []
            for r, row in enumerate(rows, 1):
                if (not isinstance(row, list) or len(row) != 4
                        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in row)
                        or not all(math.isfinite(v) for v in row)):
                    raise self.fail(f"{key}.table.{r}", f"must be four finite numbers [angle "
                                                        f"[{self.angle_unit}], Fx [N], Fy [N], "
                                                        f"M [N·m]], got {_show(row)}.", row)
                parsed.append([float(v) for v in row])
            arr = np.array(parsed)
            angles = arr[:, 0] * self.angle
            if np.any(np.diff(angles) <= 0) or angles[-1] - angles[0] >= 2 * math.pi:
                raise self.fail(f"{key}.table", "angles must rise strictly and span less than "
                                                "one revolution (the table repeats every 360°).")
            return Load(link, point, angles, arr[:, 1], arr[:, 2], arr[:, 3], frame == "link")
        force = table.get("force", [0.0, 0.0])
        if (not isinstance(force, list) or len(force) != 2
                or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in force)
                or not all(math.isfinite(v) for v in force)):
            raise self.fail(f"{key}.force", f"must be two finite numbers [Fx, Fy] [N], got "
                                            f"{_show(force)}.", force, "N")
        moment = self.number(table.get("moment", 0.0), f"{key}.moment", "N·m")
        return Load(link, point, None, np.array([float(force[0])]), np.array([float(force[1])]),
                    np.array([moment]), frame == "link")

    def spring(self, table: Any, key: str, links: dict[int, Link]) -> Spring:
        self.keys(table, key, {"name", "from", "to", "stiffness", "free_length"})
        ends = []
        for end in ("from", "to"):
            sub = self.required(table, end, key)
            self.keys(sub, f"{key}.{end}", {"link", "point"})
            link = self.link_ref(self.required(sub, "link", f"{key}.{end}"),
                                 f"{key}.{end}.link", links)
            ends.append((link, self.point_on(link, sub.get("point", [0.0, 0.0]),
                                             f"{key}.{end}.point")))
        stiffness = self.number(self.required(table, "stiffness", key), f"{key}.stiffness",
                                "N/m", non_negative=True)
        free = self.length_of(self.required(table, "free_length", key), f"{key}.free_length",
                              non_negative=True)
        name = table.get("name", key.replace(".", ""))
        return Spring((ends[0][0], ends[1][0]), (ends[0][1], ends[1][1]), stiffness, free, str(name))

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


def _list(value: Any, key: str, reader: Reader) -> list[Any]:
    if not isinstance(value, list):
        raise reader.fail(key, f"must be an array of tables [[{key}]], got {_show(value)}.")
    return value


# -- the kinds' own keys and joint B ----------------------------------------------------
# middle(reader, table, key, i, j, dyad_table, dyad_key) -> Joint: joint B of a dyad of
# links i and j from its table ``B`` (key path ``key``) and the dyad's table (``dyad_key``),
# in the link frames of the kind (``DyadKind.frames``, ``mechanisms/README.md``)
def rrr_middle(reader: Reader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B from ``lengths = [|AB|, |CB|]``: at (|AB|, 0) on link i, (|CB|, 0) on j."""
    friction = reader.middle_revolute(table, key)
    lengths = reader.required(dyad_table, "lengths", dyad_key)
    if not isinstance(lengths, list) or len(lengths) != 2:
        raise reader.fail(f"{dyad_key}.lengths", f"must be [|AB|, |CB|] [{reader.length_unit}], "
                                                 f"got {_show(lengths)}.", lengths)
    l_i = reader.length_of(lengths[0], f"{dyad_key}.lengths.1", positive=True)
    l_j = reader.length_of(lengths[1], f"{dyad_key}.lengths.2", positive=True)
    return Revolute((i, j), ((l_i, 0.0), (l_j, 0.0)), **friction)


def rrp_middle(reader: Reader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B from ``length = |AB|``: at (|AB|, 0) on link i, the origin of link j."""
    friction = reader.middle_revolute(table, key)
    l_i = reader.length_of(reader.required(dyad_table, "length", dyad_key), f"{dyad_key}.length",
                           positive=True)
    return Revolute((i, j), ((l_i, 0.0), (0.0, 0.0)), **friction)


def rpr_middle(reader: Reader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Prismatic:
    """Joint B: the guide along the ξ axis of its carrier (link j unless ``guide`` says
    otherwise), the slider point at the other link's origin, ``offset`` to its left."""
    offset, extra = reader.middle_prismatic(table, key, point=False)
    guide = reader.guide(table, key, (i, j), j)
    slider = i if guide == j else j
    return Prismatic.through(guide, (0.0, 0.0), 0.0, offset, slider, (0.0, 0.0), 0.0, **extra)


def prp_middle(reader: Reader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B: the pin at the origins of both links."""
    return Revolute((i, j), ((0.0, 0.0), (0.0, 0.0)), **reader.middle_revolute(table, key))


def ppr_middle(reader: Reader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Prismatic:
    """Joint B: a guide through ``point`` of link i at ``angle`` to guide A (90° unless
    given; not parallel to it), or on link j with ``guide = j``."""
    offset, extra = reader.middle_prismatic(table, key, point=True)
    theta = reader.angle_of(table.get("angle", 90.0 * math.pi / 180.0 / reader.angle),
                            f"{key}.angle")
    point = reader.point_on(i, table.get("point", [0.0, 0.0]), f"{key}.point")
    if abs(math.sin(theta)) < 1e-9:
        raise reader.fail(f"{key}.angle", "makes guide B parallel to guide A: a PPR dyad is "
                                          "then blocked in every position. Use an angle that "
                                          "is not 0° or 180°.", theta)
    if reader.guide(table, key, (i, j), i) == i:
        return Prismatic.through(i, point, theta, offset, j, (0.0, 0.0), theta, **extra)
    return Prismatic.through(j, (0.0, 0.0), 0.0, offset, i, point, -theta, **extra)


MIDDLE: dict[str, tuple[frozenset, Callable[..., Revolute | Prismatic]]] = {
    "RRR": (frozenset({"lengths"}), rrr_middle),
    "RRP": (frozenset({"length"}), rrp_middle),
    "RPR": (frozenset(), rpr_middle),
    "PRP": (frozenset(), prp_middle),
    "PPR": (frozenset(), ppr_middle),
}
"""kind name -> (keys of its [[dyad]] table beyond the common ones, the reader of its
joint B); one entry per kind of ``dyade.linkage.dyads.REGISTRY``"""
