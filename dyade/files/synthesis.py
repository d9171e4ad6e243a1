"""Read a synthesis file (TOML): the topology, the target, the bounds, the search and
the scores (``docs/guide/synthesis.md``), every key checked with the file and key
named in the error; lengths in ``units.length``, angles in ``units.angle``.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from dyade.files.schema import UnitReader, read_toml, suggest
from dyade.model.synthesis import TARGETS, Synthesis, Target
from dyade.units import RPM

TOP = {"name", "topology", "units", "target", "bounds", "regions", "search", "scores",
       "output"}
SIXBAR = ("a", "b", "c", "d", "ex", "ey", "gx", "gy", "f", "g", "p", "q")
TOPOLOGIES = {"fourbar": ("a", "b", "c", "d", "p", "q"),
              "slider-crank": ("a", "b", "e", "p", "q"),
              "watt-sixbar": SIXBAR, "stephenson-sixbar": SIXBAR, "watt1-sixbar": SIXBAR,
              "stephenson1-sixbar": SIXBAR}
"""topology -> its canonical dimensions (``dyade.synthesis.topology``)"""
SIXBAR_FUNCTION = 9
"""a six-bar's function unknowns: a, b, c, ex, ey, gx, gy, f, g (d is the frame)"""
SIXBAR_POSES = 7
"""the most poses a six-bar passes through: 3N equations for 15 + N unknowns"""
TARGET_KEYS = {"kind", "points", "closed", "crank", "output", "method", "poses", "stretch",
               "moving", "profile", "range", "rows", "crank_zero", "output_zero", "radius"}
SEARCH_KEYS = {"candidates", "block", "method", "seed", "positions", "rounds",
               "min_transmission", "scale"}
SCORE_KEYS = {"speed_rpm", "mass_per_length", "mass_each", "figure", "frame"}
OUTPUT_KEYS = {"keep"}
METHODS = ("precision", "chebyshev", "fit")


def read_synthesis(path: str | os.PathLike) -> Synthesis:
    """The synthesis problem of a synthesis file.

    Raises
    ------
    InputError
        Naming the file and the key.
    """
    path = os.fspath(path)
    return parse(read_toml(path), os.path.basename(path), path)


def parse(data: dict[str, Any], label: str = "synthesis", source: str | None = None
          ) -> Synthesis:
    """The synthesis problem of a synthesis file's data (a dict with its keys)."""
    reader = UnitReader(label, source)
    reader.top_keys = TOP
    reader.keys(data, "", TOP)
    reader.units(data.get("units", {}))
    topology = data.get("topology", "fourbar")
    if topology not in TOPOLOGIES:
        raise reader.fail("topology", f"must be one of {', '.join(TOPOLOGIES)}, got "
                                      f"{topology!r}.{suggest(str(topology), TOPOLOGIES)}")
    target = _target(reader, reader.required(data, "target", ""), topology)
    names = TOPOLOGIES[topology]
    bounds = {}
    for key, value in reader.keys(data.get("bounds", {}), "bounds", set(names)).items():
        where = f"bounds.{key}"
        if not (isinstance(value, list) and len(value) == 2):
            raise reader.fail(where, f"must be [least, largest] [{reader.length_unit}], got "
                                     f"{value!r}.", value, reader.length_unit)
        low, high = (reader.length_of(v, where) for v in value)
        if high < low:
            raise reader.fail(where, f"must be [least, largest]: {value[0]} > {value[1]}.")
        bounds[key] = (low, high)
    regions = {}
    pivots = {"A0", "B0"} if topology == "fourbar" else {"A0"}
    for key, value in reader.keys(data.get("regions", {}), "regions", pivots).items():
        where = f"regions.{key}"
        if not (isinstance(value, list) and len(value) == 2
                and all(isinstance(v, list) and len(v) == 2 for v in value)):
            raise reader.fail(where, f"must be [[x least, x largest], [y least, y largest]] "
                                     f"[{reader.length_unit}], got {value!r}.", value)
        (x0, x1), (y0, y1) = ((reader.length_of(v, where) for v in pair) for pair in value)
        if x1 < x0 or y1 < y0:
            raise reader.fail(where, "must give each range as [least, largest].")
        regions[key] = (x0, x1, y0, y1)
    if regions and target.kind not in ("path",):
        raise reader.fail("regions", "apply to path targets (where the design's placement "
                                     "is found); the other targets fix the frame pivots.")
    search = reader.keys(data.get("search", {}), "search", SEARCH_KEYS)
    scores = reader.keys(data.get("scores", {}), "scores", SCORE_KEYS)
    output = reader.keys(data.get("output", {}), "output", OUTPUT_KEYS)

    def whole(table, key, default, least=1):
        if key not in table:
            return default
        value = reader.integer(table[key], key)
        if value < least:
            raise reader.fail(key, f"must be at least {least}, got {value}.", value)
        return value

    method = search.get("method", "lhs")
    if method not in ("lhs", "random"):
        raise reader.fail("search.method", f'must be "lhs" or "random", got {method!r}.')
    masses = {k: reader.number(scores[k], f"scores.{k}", u, positive=True)
              for k, u in (("mass_per_length", "kg/m"), ("mass_each", "kg")) if k in scores}
    if len(masses) == 2:
        raise reader.fail("scores.mass_each", "give mass_per_length or mass_each, not both.")
    if target.radius is not None and not bool(search.get("scale", True)):
        raise reader.fail("target.radius", "scales the design to the arc's radius, which "
                                           "search.scale = false forbids (the bounds then "
                                           "fix the size): remove one of the two.")
    least = search.get("min_transmission", 0.0)
    return Synthesis(
        name=str(data.get("name", label)), source=source, topology=topology, target=target,
        bounds=bounds,
        candidates=whole(search, "candidates", 20_000),
        block=whole(search, "block", 2_000, least=10),
        method=method, seed=whole(search, "seed", 0, least=0),
        positions=whole(search, "positions", 100, least=8),
        rounds=whole(search, "rounds", 2),
        min_transmission=reader.angle_of(least, "search.min_transmission"), regions=regions,
        scale=bool(search.get("scale", True)),
        keep=whole(output, "keep", 3),
        speed=reader.number(scores.get("speed_rpm", 60.0), "scores.speed_rpm", "rpm",
                            positive=True) * RPM,
        mass_per_length=masses.get("mass_per_length"), mass_each=masses.get("mass_each"),
        figure=str(scores.get("figure", "M_drive_rms")),
        frame=reader.length_of(scores.get("frame", 1.0 / reader.length), "scores.frame",
                               positive=True),
        length_unit=reader.length_unit)


def _target(reader: UnitReader, table: Any, topology: str) -> Target:
    reader.keys(table, "target", TARGET_KEYS)
    kind = reader.required(table, "kind", "target")
    if kind not in TARGETS:
        raise reader.fail("target.kind", f"must be one of {', '.join(TARGETS)}, got "
                                         f"{kind!r}.{suggest(str(kind), TARGETS)}")

    def angles(key):
        if key not in table:
            return None
        values = table[key]
        if not isinstance(values, list) or not values:
            raise reader.fail(f"target.{key}", f"must be a list of angles [{reader.angle_unit}].")
        return np.array([reader.angle_of(v, f"target.{key}") for v in values])

    crank = angles("crank")
    if kind == "function":
        slider = topology == "slider-crank"
        six = topology.endswith("sixbar")
        if six and table.get("method", "fit") != "fit":
            raise reader.fail("target.method", "a six-bar's function has no closed form: it "
                                               "is found by a search and least squares "
                                               "(method = \"fit\", the default); remove the "
                                               "key or use topology = \"fourbar\".")
        if "profile" in table:
            made = _profile_target(reader, table, crank, slider)
            unknowns = SIXBAR_FUNCTION + (made.zeros[1] is None)
            if six and made.rows < unknowns:
                raise reader.fail("target.rows", f"a six-bar's function has {unknowns} "
                                                 f"unknowns: give at least {unknowns} rows, "
                                                 f"got {made.rows}.", made.rows)
            return made
        if slider:
            values = table.get("output")
            if values is not None and not (isinstance(values, list) and values):
                raise reader.fail("target.output", f"must be a list of the slider's "
                                                   f"positions [{reader.length_unit}].")
            output = None if values is None else np.array(
                [reader.length_of(v, "target.output") for v in values])
        else:
            output = angles("output")
        if crank is None or output is None:
            raise reader.fail("target.crank" if crank is None else "target.output",
                              "is missing: a function target is a table of crank angles and "
                              "output angles (or a motion profile: target.profile).")
        if crank.size != output.size:
            raise reader.fail("target.output", f"has {output.size} angles for {crank.size} "
                                               "crank angles.")
        if six and crank.size < SIXBAR_FUNCTION:
            raise reader.fail("target.crank", f"a six-bar's function has {SIXBAR_FUNCTION} "
                                              f"unknowns (a, b, c, E, G, f, g; d is the "
                                              f"frame): give at least {SIXBAR_FUNCTION} rows, "
                                              f"got {crank.size}.")
        method = table.get("method", "fit" if six else
                           "precision" if crank.size == 3 else "chebyshev")
        if method not in METHODS:
            raise reader.fail("target.method", f"must be one of {', '.join(METHODS)}, got "
                                               f"{method!r}.")
        return Target(kind, crank=crank, output=output, method=method)
    if kind == "poses":
        raw = reader.required(table, "poses", "target")
        if not isinstance(raw, list) or not all(isinstance(p, list) and len(p) == 3
                                                for p in raw):
            raise reader.fail("target.poses", f"must be a list of [x, y, angle] "
                                              f"[{reader.length_unit}, {reader.angle_unit}].")
        poses = np.array([[reader.length_of(p[0], "target.poses"),
                           reader.length_of(p[1], "target.poses"),
                           reader.angle_of(p[2], "target.poses")] for p in raw])
        if topology.endswith("sixbar"):
            if not 3 <= len(poses) <= SIXBAR_POSES:
                raise reader.fail("target.poses", f"a six-bar's link 5 passes through 3 to "
                                                  f"{SIXBAR_POSES} poses (each adds three "
                                                  f"equations and one crank angle to its 15 "
                                                  f"free numbers), got {len(poses)}.")
            if "moving" in table:
                raise reader.fail("target.moving", "gives a four-bar's moving pivots: a "
                                                   "six-bar's are found by the search; remove "
                                                   "the key.")
            return Target(kind, poses=poses)
        if len(poses) not in (3, 4, 5):
            raise reader.fail("target.poses", f"motion generation takes three poses (the "
                                              f"fixed pivots in closed form), four (the "
                                              f"Burmester curves) or five (the "
                                              f"Ball–Burmester points), got {len(poses)}.")
        moving = None
        if "moving" in table:
            pair = table["moving"]
            if not (isinstance(pair, list) and len(pair) == 2):
                raise reader.fail("target.moving", "must be two points [[x, y], [x, y]].")
            moving = tuple(complex(reader.length_of(p[0], "target.moving"),
                                   reader.length_of(p[1], "target.moving")) for p in pair)
        return Target(kind, poses=poses, moving=moving)
    if kind in ("line", "arc"):
        stretch = reader.angle_of(reader.required(table, "stretch", "target"), "target.stretch")
        if not 0.0 < stretch < 2.0 * np.pi:
            raise reader.fail("target.stretch", "must lie between 0° and 360° of crank.")
        radius = None
        if "radius" in table:
            if kind != "arc":
                raise reader.fail("target.radius", "applies to an arc (kind = \"arc\"); a "
                                                   "straight line has none.")
            radius = reader.length_of(table["radius"], "target.radius", positive=True)
        return Target(kind, stretch=stretch, closed=False, radius=radius)
    raw = reader.required(table, "points", "target")
    if not isinstance(raw, list) or not all(isinstance(p, list) and len(p) == 2 for p in raw):
        raise reader.fail("target.points", f"must be a list of [x, y] [{reader.length_unit}].")
    points = np.array([complex(reader.length_of(p[0], "target.points"),
                               reader.length_of(p[1], "target.points")) for p in raw])
    closed = bool(table.get("closed", kind == "path"))
    least = 8 if crank is None else 4
    why = f"({'with' if crank is not None else 'without'} crank angles)"
    if not closed and crank is None:  # each point adds two equations and its crank angle
        least = len(TOPOLOGIES[topology]) + 4  # the dimensions and the placement (3)
        why = (f"(a part of a curve without crank angles: each point adds one equation "
               f"beyond its own crank angle, and the {len(TOPOLOGIES[topology])} dimensions "
               f"and the placement need more than {least - 1})")
    if points.size < least:
        raise reader.fail("target.points", f"a path needs at least {least} points {why}, "
                                           f"got {points.size}.")
    if crank is not None and crank.size != points.size:
        raise reader.fail("target.crank", f"has {crank.size} angles for {points.size} points.")
    return Target(kind, crank=crank, points=points, closed=closed)



def _profile_target(reader: UnitReader, table: dict, crank, slider: bool = False) -> Target:
    """A function target given as a motion profile: a profile file's path (from the
    synthesis file's folder) or an inline ``[target.profile]`` table."""
    from dyade.files.profile import ProfileReader, read_profile

    for key in ("crank", "output"):
        if key in table:
            raise reader.fail(f"target.{key}", "is given beside target.profile: a function "
                                               "target is a table or a profile, not both.")
    given = table["profile"]
    if isinstance(given, str):
        folder = os.path.dirname(reader.source) if reader.source else ""
        path = os.path.join(folder, given)
        if not os.path.isfile(path):
            raise reader.fail("target.profile", f"names {given!r}, which is not a file "
                                                f"(looked for {path}).", given)
        profile = read_profile(path)
    elif isinstance(given, dict):
        profile = ProfileReader(reader.label, reader.source).profile(given, "target profile")
    else:
        raise reader.fail("target.profile", "must be a profile file's path or a "
                                            "[target.profile] table.", given)
    if profile.master != "angle":
        raise reader.fail("target.profile", "must run over a master angle (the crank "
                                            "angle), got a profile over time.")
    if slider and profile.output == "angle":
        raise reader.fail("target.profile", f"gives an angle ({profile.unit}): a "
                                            "slider-crank's function is the slider's "
                                            "position; give the profile's unit in a length "
                                            "(mm, m), or topology = \"fourbar\".")
    if not slider and profile.output != "angle":
        raise reader.fail("target.profile", f"gives a length ({profile.unit}): function "
                                            "generation sizes a four-bar's output angle; "
                                            "give the profile's unit in deg or rad (or "
                                            "topology = \"slider-crank\" for a slider).")
    span = (profile.start, profile.start + profile.period)
    if "range" in table:
        value = table["range"]
        if not (isinstance(value, list) and len(value) == 2):
            raise reader.fail("target.range", f"must be [start, stop] of the profile's master "
                                              f"[{reader.angle_unit}], got {value!r}.", value)
        span = tuple(reader.angle_of(v, "target.range") for v in value)
        if not span[1] > span[0]:
            raise reader.fail("target.range", "must be [start, stop] with stop after start.")
        if span[1] - span[0] > 2.0 * np.pi + 1e-12:
            raise reader.fail("target.range", "must span at most one turn of the crank.")
    elif abs(profile.advance) > 0.0:
        raise reader.fail("target.range", "is missing: the profile does not come back to "
                                          "where it started, which a rocker over a whole "
                                          "turn must; give the range of the crank to follow.")
    rows = 61
    if "rows" in table:
        rows = reader.integer(table["rows"], "target.rows")
        if rows < 3:
            raise reader.fail("target.rows", f"must be at least 3, got {rows}.", rows)
    method = table.get("method", "fit")
    if method not in METHODS:
        raise reader.fail("target.method", f"must be one of {', '.join(METHODS)}, got "
                                           f"{method!r}.")
    if slider and "output_zero" in table:
        raise reader.fail("target.output_zero", "applies to a four-bar's output angle; a "
                                                "slider's start (its position where the "
                                                "law's lift is zero) is found by the "
                                                "synthesis: remove the key.")
    zeros = tuple(reader.angle_of(table[k], f"target.{k}") if k in table else None
                  for k in ("crank_zero", "output_zero"))
    return Target("function", crank=np.array(span), method=method, profile=profile,
                  rows=rows, zeros=zeros)
