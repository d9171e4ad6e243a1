"""The tables of a cam (``[cam]``, ``[follower]``, ``[manufacture]``, ``[profile]``) as
a cam file and a mechanism file have them (``dyade.files.cam``,
``dyade.files.mechanism``): read into ``dyade.model.cam.Cam``, every key checked with
the file and key named. A reader computes nothing.
"""

from __future__ import annotations

from typing import Any

from dyade.files.schema import UnitReader, show

TOP_KEYS = {"name", "description", "units", "cam", "follower", "manufacture", "profile",
            "chain"}
CHAIN_KEYS = {"mechanism", "centre"}
CAM_KEYS = {"follower", "base_radius", "speed_rpm", "rotation", "closure",
            "pressure_angle_max", "width", "material"}
FOLLOWER_KEYS = {"roller_radius", "offset", "pivot_distance", "arm_length", "mass",
                 "stiffness", "preload", "load", "material", "guide_friction",
                 "guide_length", "guide_overhang"}
MANUFACTURE_KEYS = {"chord_tolerance", "cutter_radius"}
MATERIAL_KEYS = {"young", "poisson"}
CHORD_TOLERANCE = 1e-5  # [m] the exported profile's chord tolerance where the file gives none
KEYS = {"follower": "cam.follower", "base_radius": "cam.base_radius", "speed": "cam.speed_rpm",
        "closure": "cam.closure", "pressure_angle_max": "cam.pressure_angle_max",
        "width": "cam.width", "roller_radius": "follower.roller_radius",
        "offset": "follower.offset", "pivot_distance": "follower.pivot_distance",
        "arm_length": "follower.arm_length", "mass": "follower.mass",
        "stiffness": "follower.stiffness", "preload": "follower.preload",
        "load": "follower.load", "guide_friction": "follower.guide_friction",
        "guide_length": "follower.guide_length",
        "guide_overhang": "follower.guide_overhang", "chord_tolerance": "manufacture.chord_tolerance",
        "cutter_radius": "manufacture.cutter_radius", "profile": "profile",
        "profile.master": "profile.master", "profile.period": "profile.period",
        "profile.unit": "profile.unit", "chain": "chain", "chain_centre": "chain.centre"}
"""the Cam's parameter -> the file's key"""


class CamReader(UnitReader):
    top_keys = TOP_KEYS


PLACE_KEYS = {"centre", "direction"}
"""a mechanism file's [cam] places the cam: its centre and the follower's direction"""
MECHANISM_ONLY = {
    "mass": "is link 2's in a mechanism file (the follower is link 2): give `links.2.mass` "
            "(and its `centre`, `inertia`) instead.",
    "guide_friction": "is not taken in a mechanism file yet: the follower's guide is joint "
                      "(1,2) of the chain; check its jamming with `dyade cam` on a cam file.",
    "guide_length": "belongs to `follower.guide_friction`, which a mechanism file does not "
                    "take yet.",
    "guide_overhang": "belongs to `follower.guide_friction`, which a mechanism file does not "
                      "take yet.",
}


def material(reader: UnitReader, table: Any, key: str) -> tuple[float, float]:
    """(E [Pa], ν [-]) of a ``material`` table (default: steel)."""
    from dyade.model.cam import STEEL

    if table is None:
        return STEEL
    reader.keys(table, key, MATERIAL_KEYS)
    young = reader.number(table.get("young", STEEL[0]), f"{key}.young", "Pa", positive=True)
    poisson = reader.number(table.get("poisson", STEEL[1]), f"{key}.poisson", "-",
                            non_negative=True)
    if not poisson < 0.5:
        raise reader.fail(f"{key}.poisson", f"must be below 0.5, got {poisson:g}.", poisson)
    return young, poisson


def build_cam(reader: UnitReader, data: dict[str, Any], label: str, path: str | None,
              chain: Any = None, centre: tuple[float, float] | None = None,
              in_mechanism: bool = False):
    """The ``Cam`` of a file's parsed ``data`` (its units already read by ``reader``).

    ``in_mechanism``: the tables of a mechanism file, whose ``[cam]`` also places the
    cam (``PLACE_KEYS``, read by the mechanism reader) and whose link 2 is the follower
    (its mass in ``[links.2]``).
    """
    import os

    from dyade.errors import InputError
    from dyade.files.profile import ProfileReader
    from dyade.model.cam import FOLLOWERS, Cam
    from dyade.units import RPM

    cam = reader.keys(data["cam"], "cam", CAM_KEYS | (PLACE_KEYS if in_mechanism else set()))
    follower = reader.keys(data.get("follower", {}), "follower", FOLLOWER_KEYS)
    made = reader.keys(data.get("manufacture", {}), "manufacture", MANUFACTURE_KEYS)
    kind = cam.get("follower")
    if kind not in FOLLOWERS:
        import difflib

        close = difflib.get_close_matches(str(kind), FOLLOWERS, n=1, cutoff=0.5)
        hint = f" Did you mean `{close[0]}`?" if close else f" Kinds: {', '.join(FOLLOWERS)}."
        raise reader.fail("cam.follower", "is missing." if kind is None else
                          f"must be a follower kind, got {show(kind)}.{hint}", kind)
    angular = kind == "oscillating-roller"
    for key, table, allowed in (("offset", follower, kind != "oscillating-roller"),
                                ("roller_radius", follower, kind != "translating-flat"),
                                ("pivot_distance", follower, angular),
                                ("arm_length", follower, angular)):
        if key in table and not allowed:
            raise reader.fail(f"follower.{key}", f"is not a key of a {kind} follower "
                                                 f"(leave it out).", table[key])
    rotation = cam.get("rotation", "ccw")
    if rotation not in ("ccw", "cw"):
        raise reader.fail("cam.rotation", f"must be \"ccw\" or \"cw\", got {show(rotation)}.",
                          rotation)
    closure = cam.get("closure", "spring")
    if closure not in ("spring", "groove"):
        raise reader.fail("cam.closure", f"must be \"spring\" or \"groove\", got "
                                         f"{show(closure)}.", closure)
    if "speed_rpm" not in cam:
        raise reader.fail("cam.speed_rpm", "is missing: the cam's speed [rpm].")
    speed = reader.number(cam["speed_rpm"], "cam.speed_rpm", "rpm", non_negative=True) * RPM

    def length(table, key, path, **check):
        return reader.length_of(table[key], path, **check) if key in table else None

    def coordinate(table, key, path):  # the follower's coordinate: a length or an angle
        if key not in table:
            return 0.0
        return reader.angle_of(table[key], path) if angular else reader.length_of(
            table[key], path)

    if "profile" not in data:
        raise reader.fail("profile", "is missing: the follower's motion over the cam angle "
                                     "(a [profile] table; dyade init cam writes one).")
    profile = ProfileReader(label, path).profile(data["profile"], data.get("name", label))
    if in_mechanism:
        for key in ("mass", "guide_friction", "guide_length", "guide_overhang"):
            if key in follower:
                raise reader.fail(f"follower.{key}", MECHANISM_ONLY[key], follower[key])
    limit = cam.get("pressure_angle_max")
    name = data.get("name", os.path.splitext(label)[0])
    try:
        return Cam(
            follower=kind,
            base_radius=reader.length_of(reader.required(cam, "base_radius", "cam"),
                                         "cam.base_radius", positive=True),
            profile=profile, speed=speed,
            roller_radius=length(follower, "roller_radius", "follower.roller_radius",
                                 positive=True) or 0.0,
            offset=length(follower, "offset", "follower.offset") or 0.0,
            pivot_distance=length(follower, "pivot_distance", "follower.pivot_distance",
                                  positive=True) or 0.0,
            arm_length=length(follower, "arm_length", "follower.arm_length",
                              positive=True) or 0.0,
            clockwise=rotation == "cw", closure=closure,
            mass=reader.number(follower.get("mass", 0.0), "follower.mass",
                               "kg·m²" if angular else "kg", non_negative=True),
            stiffness=reader.number(follower.get("stiffness", 0.0), "follower.stiffness",
                                    "N·m/rad" if angular else "N/m", non_negative=True),
            preload=coordinate(follower, "preload", "follower.preload"),
            load=reader.number(follower.get("load", 0.0), "follower.load",
                               "N·m" if angular else "N"),
            guide_friction=reader.number(follower.get("guide_friction", 0.0),
                                         "follower.guide_friction", "-", non_negative=True),
            guide_length=length(follower, "guide_length", "follower.guide_length",
                                positive=True),
            guide_overhang=length(follower, "guide_overhang", "follower.guide_overhang") or 0.0,
            pressure_angle_max=None if limit is None else reader.angle_of(
                limit, "cam.pressure_angle_max"),
            width=length(cam, "width", "cam.width", positive=True),
            cam_material=material(reader, cam.get("material"), "cam.material"),
            follower_material=material(reader, follower.get("material"), "follower.material"),
            chord_tolerance=length(made, "chord_tolerance", "manufacture.chord_tolerance",
                                   positive=True) or CHORD_TOLERANCE,
            cutter_radius=length(made, "cutter_radius", "manufacture.cutter_radius",
                                 positive=True),
            chain=chain, chain_centre=centre,
            name=name if isinstance(name, str) else label,
            length_unit=reader.length_unit, angle_unit=reader.angle_unit, source=path,
            keys={k: f"{label}: `{v}`" for k, v in KEYS.items()} | {
                f"profile.segment.{len(profile.segments)}.to":
                    f"{label}: `profile.segment.{len(profile.segments)}.to`"})
    except InputError as err:
        if str(err).startswith(label):
            raise
        raise InputError(f"{label}: {err}", source=path, key=err.key, value=err.value,
                         reason=err.reason) from None
