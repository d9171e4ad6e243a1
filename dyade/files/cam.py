"""Read a cam file (TOML): a disc cam, its follower and the follower's motion profile.

```toml
name = "Feeder cam"
units = { length = "mm", angle = "deg" }

[cam]
follower = "translating-roller"   # or "oscillating-roller", "translating-flat"
base_radius = 40                  # r_b [length]
speed_rpm = 300
rotation = "ccw"                  # or "cw" (the mirror image)
closure = "spring"                # or "groove" (form closure)
pressure_angle_max = 30           # [angle] (default 30°; oscillating 45°)
width = 12                        # contact length for the Hertz stress [length]

[follower]
roller_radius = 10                # [length]
offset = 5                        # translating [length]
mass = 0.8                        # [kg] (oscillating: [kg·m²] about the pivot)
stiffness = 2000                  # [N/m] (oscillating: [N·m/rad])
preload = 10                      # spring compression at s = 0 [length] (oscillating: [angle])
load = 15                         # [N] pressing it onto the cam (oscillating: [N·m])
guide_friction = 0.1              # μ of a translating follower's guide (default 0: none)
guide_length = 40                 # L between the guide's bearing points [length]
guide_overhang = 25               # roller centre to the guide's near end at s = 0 [length]

[manufacture]
chord_tolerance = 0.01            # [length]
cutter_radius = 12                # [length]

[profile]                         # the follower's motion over the cam angle (360°)
...
```

Every key is checked here, by the shared schema, with the file and key named; the
profile by ``dyade.files.profile``. A reader computes nothing.
"""

from __future__ import annotations

import os
from typing import Any

from dyade.files.schema import UnitReader, read_toml, show

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

    def material(self, table: Any, key: str) -> tuple[float, float]:
        from dyade.model.cam import STEEL

        if table is None:
            return STEEL
        self.keys(table, key, MATERIAL_KEYS)
        young = self.number(table.get("young", STEEL[0]), f"{key}.young", "Pa", positive=True)
        poisson = self.number(table.get("poisson", STEEL[1]), f"{key}.poisson", "-",
                              non_negative=True)
        if not poisson < 0.5:
            raise self.fail(f"{key}.poisson", f"must be below 0.5, got {poisson:g}.", poisson)
        return young, poisson


def is_cam(data: dict[str, Any]) -> bool:
    """Whether a file's TOML data are a cam file's (a ``[cam]`` table, no crank or dyads
    of a mechanism)."""
    return isinstance(data, dict) and "cam" in data and not ({"crank", "dyad"} & set(data))


def read_cam(path: str | os.PathLike, text: str | None = None,
             data: dict[str, Any] | None = None):
    """The cam of a cam file.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (docs/guide/cams.md describes every key).
    text : str, optional
        The file's content when already read.
    data : dict, optional
        The file's TOML data when already read (and edited: a study's variant,
        ``dyade.files.schema.load_data``).

    Returns
    -------
    dyade.model.cam.Cam

    Raises
    ------
    InputError
        Naming the file and the key (``follower.roller_radius``).

    Examples
    --------
    >>> from dyade.files.cam import read_cam
    >>> cam = read_cam("mechanisms/cams/translating-roller.toml")
    >>> cam.follower, round(cam.base_radius, 6), cam.length_unit
    ('translating-roller', 0.04, 'mm')
    """
    from dyade.errors import InputError
    from dyade.files.profile import ProfileReader
    from dyade.model.cam import FOLLOWERS, Cam
    from dyade.units import RPM

    path = os.fspath(path)
    label = os.path.basename(path)
    data = read_toml(path, text) if data is None else data
    reader = CamReader(label, path)
    reader.keys(data, "", TOP_KEYS)
    if "cam" not in data:
        raise InputError(f"{label}: has no [cam] table: a cam file has [cam], [follower] and "
                         f"[profile] tables (dyade init cam writes one).", source=path, key="cam")
    if "units" in data:
        reader.units(data["units"])
    cam = reader.keys(data["cam"], "cam", CAM_KEYS)
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
    chain, centre = None, None
    if "chain" in data:
        table = reader.keys(data["chain"], "chain", CHAIN_KEYS)
        file = reader.required(table, "mechanism", "chain")
        if not isinstance(file, str):
            raise reader.fail("chain.mechanism", f"must be the path of a mechanism file (from "
                                                 f"this file's folder), got {show(file)}.", file)
        where = reader.required(table, "centre", "chain")
        if not (isinstance(where, list) and len(where) == 2):
            raise reader.fail("chain.centre", f"must be the cam centre [x, y] in the "
                                              f"mechanism's frame [{reader.length_unit}], got "
                                              f"{show(where)}.", where)
        centre = tuple(reader.length_of(value, "chain.centre") for value in where)
        from dyade.files.mechanism import read_mechanism

        chain = read_mechanism(os.path.join(os.path.dirname(path), file))
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
            cam_material=reader.material(cam.get("material"), "cam.material"),
            follower_material=reader.material(follower.get("material"), "follower.material"),
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
