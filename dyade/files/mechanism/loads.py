"""Loads on the links: gravity, applied forces and moments (constant, or a table over the
crank angle) and springs between link points."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from dyade.arrays import Vec
from dyade.files.mechanism.links import LinkReader
from dyade.files.schema import show
from dyade.model.mechanism import Link, Load, Spring

GRAVITY_KEYS = {"x", "y"}
STANDARD_GRAVITY = 9.80665  # [m/s²]


class LoadReader(LinkReader):
    """Reads [gravity], [[load]] and [[spring]] against the links the dyads placed."""

    def gravity(self, value: Any) -> Vec:
        if value is None or value is False:
            return (0.0, 0.0)
        if value is True:
            return (0.0, -STANDARD_GRAVITY)
        self.keys(value, "gravity", GRAVITY_KEYS)
        return (self.number(value.get("x", 0.0), "gravity.x", "m/s²"),
                self.number(value.get("y", 0.0), "gravity.y", "m/s²"))

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
                                            f"got {show(frame)}.")
        if "table" in table:
            if "force" in table or "moment" in table:
                raise self.fail(f"{key}.table", "replaces `force` and `moment`: give either "
                                                "a table or constant values.")
            rows = table["table"]
            if not isinstance(rows, list) or len(rows) < 2:
                raise self.fail(f"{key}.table", "must list at least two rows "
                                                f"[angle, Fx, Fy, M], got {show(rows)}.")
            parsed = []
            for r, row in enumerate(rows, 1):
                if (not isinstance(row, list) or len(row) != 4
                        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in row)
                        or not all(math.isfinite(v) for v in row)):
                    raise self.fail(f"{key}.table.{r}", f"must be four finite numbers [angle "
                                                        f"[{self.angle_unit}], Fx [N], Fy [N], "
                                                        f"M [N·m]], got {show(row)}.", row)
                for v, quantity, unit in zip(row[1:], ("force", "force", "torque"),
                                             ("N", "N", "N·m")):
                    self.below_top(float(v), f"{key}.table.{r}", quantity, unit)
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
                                            f"{show(force)}.", force, "N")
        for v in force:
            self.below_top(float(v), f"{key}.force", "force", "N")
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

    def tables(self, value: Any, key: str) -> list[Any]:
        """An array of tables, [[load]] or [[spring]]."""
        if not isinstance(value, list):
            raise self.fail(key, f"must be an array of tables [[{key}]], got {show(value)}.")
        return value
