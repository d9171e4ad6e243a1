"""A mechanism file's ``[cam]``: a disc cam whose follower is link 2, the chain's input.

The cam's tables are those of a cam file (``[cam]``, ``[follower]``, ``[profile]``,
``[manufacture]``, read by ``dyade.files.cam_tables``) and ``[cam]`` places the cam:

```toml
[cam]
follower = "translating-roller"
base_radius = 30
speed_rpm = 120
centre = [0, 0]       # the cam centre in the mechanism's frame [length]
direction = 90        # translating: the follower's direction of motion [angle]
                      # (default 90, up); oscillating: from the cam centre to the
                      # lever's pivot (default 0)
```

Link 2 is then the follower: a translating one slides along its line of motion (its
origin the roller centre, or the flat face's point on that line; ξ along the motion),
an oscillating one is the lever about its pivot; its point ``tip`` is the roller centre
(the face point). ``[crank]`` is left out (link 2's points and mass go in ``[links.2]``).
"""

from __future__ import annotations

import math
from typing import Any

from dyade.files.schema import show
from dyade.model.mechanism import CRANK, FRAME, Crank, Prismatic, Revolute

CAM_TABLES = ("cam", "follower", "profile", "manufacture")


class CamDriveReader:
    """Reads a mechanism file's ``[cam]`` into link 2 (``Crank``) and its ``CamDrive``."""

    def cam_drive(self, data: dict[str, Any]) -> tuple[Crank, Any]:
        from dyade.files.cam_tables import build_cam
        from dyade.model.cam import CamDrive

        table = data["cam"]
        if not isinstance(table, dict):
            raise self.fail("cam", f"must be a table of the cam's keys, got {show(table)}.")
        for key, why in (("crank", "the cam's follower is link 2: [cam] places it (its "
                                   "centre, direction and the follower's geometry); leave "
                                   "out [crank] and give link 2's points and mass in "
                                   "[links.2]."),
                         ("servo", "and [cam] both drive link 2: keep one of the two.")):
            if key in data:
                raise self.fail(key, why)
        where = table.get("centre", [0.0, 0.0])
        if not (isinstance(where, list) and len(where) == 2):
            raise self.fail("cam.centre", f"must be the cam centre [x, y] in the mechanism's "
                                          f"frame [{self.length_unit}], got {show(where)}.",
                            where)
        centre = tuple(self.length_of(value, "cam.centre") for value in where)
        cam = build_cam(self, {key: data[key] for key in CAM_TABLES if key in data} | {
            "name": data.get("name", self.label)}, self.label, self.source,
            centre=centre, in_mechanism=True)
        sliding = cam.follower != "oscillating-roller"
        default = 90.0 if sliding else 0.0
        direction = (self.angle_of(table["direction"], "cam.direction") if "direction" in table
                     else math.radians(default))
        if sliding:
            beta = direction - 0.5 * math.pi
        else:
            beta = direction - math.pi if cam.clockwise else direction
        drive = CamDrive(cam, centre, beta)
        pivot = drive.pivot
        if sliding:
            stroke = max(max(abs(s.lift_from), abs(s.lift_to)) for s in cam.profile.segments)
            joint = Prismatic(FRAME, CRANK, pivot, drive.guide, (0.0, 0.0), 0.0)
            self.points[CRANK] = {"tip": (0.0, 0.0)}
            crank = Crank(pivot, stroke or cam.base_radius, cam.speed, joint, drive.guide)
        else:
            joint = Revolute((FRAME, CRANK), (pivot, (0.0, 0.0)))
            self.points[CRANK] = {"tip": (cam.arm_length, 0.0)}
            crank = Crank(pivot, cam.arm_length, cam.speed, joint)
        return crank, drive
