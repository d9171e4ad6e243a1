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

from dyade.files.cam_tables import (CAM_KEYS, CHAIN_KEYS, CHORD_TOLERANCE,  # noqa: F401
                                    FOLLOWER_KEYS, KEYS, MANUFACTURE_KEYS, MATERIAL_KEYS,
                                    TOP_KEYS, CamReader, build_cam)
from dyade.files.schema import read_toml, show


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

    path = os.fspath(path)
    label = os.path.basename(path)
    data = read_toml(path, text) if data is None else data
    if "dyad" in data:  # a mechanism file: its [cam] drives link 2, the chain
        return _in_mechanism(path, label, data)
    reader = CamReader(label, path)
    reader.keys(data, "", TOP_KEYS)
    if "cam" not in data:
        raise InputError(f"{label}: has no [cam] table: a cam file has [cam], [follower] and "
                         f"[profile] tables (dyade init cam writes one).", source=path, key="cam")
    if "units" in data:
        reader.units(data["units"])
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
    return build_cam(reader, data, label, path, chain, centre)


def _in_mechanism(path: str, label: str, data: dict):
    """The cam of a mechanism file's ``[cam]`` (``dyade.files.mechanism.cam``), its
    ``chain`` the whole mechanism."""
    import dataclasses

    from dyade.errors import InputError
    from dyade.files.mechanism import build

    if "cam" not in data:
        raise InputError(f"{label}: is a mechanism file without a [cam] table: `dyade cam` "
                         f"checks a disc cam (a cam file, or a mechanism file whose [cam] "
                         f"drives link 2; `dyade help cams`).", source=path, key="cam")
    mechanism = build(data, path)
    drive = mechanism.cam
    return dataclasses.replace(drive.cam, chain=mechanism, chain_centre=drive.centre)
