"""The [drive_line] table: the elastic element between the motor and the crank shaft
(``dyade.machine.drive_line``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from dyade.files.schema import UnitReader, show

if TYPE_CHECKING:  # the drive line loads only with a [drive_line] table
    from dyade.model.drive_line import DriveLineData

DRIVE_LINE_KEYS = {"stiffness", "damping", "ratio", "rotor_inertia", "coupling", "steps"}


class DriveLineReader(UnitReader):
    """Reads the [drive_line] table."""

    def drive_line(self, table: Any) -> DriveLineData:
        """The [drive_line] table: a shaft (stiffness, damping) or a coupling file, the
        gear ratio and the motor's rotor inertia."""
        from dyade.errors import InputError
        from dyade.model.drive_line import DriveLineData

        self.keys(table, "drive_line", DRIVE_LINE_KEYS)
        coupling = path = None
        if "coupling" in table:
            name = table["coupling"]
            if not isinstance(name, str) or not name:
                raise self.fail("drive_line.coupling", f"must name a coupling file (TOML, as "
                                                       f"for `dyade coupling`), got {show(name)}.")
            if "stiffness" in table or "damping" in table:
                raise self.fail("drive_line.coupling", "replaces the shaft: give either "
                                                       "`coupling` or `stiffness` and "
                                                       "`damping`, not both.")
            from dyade.files.coupling import read_coupling

            base = os.path.dirname(self.source) if self.source else ""
            path = os.path.join(base, name)
            if not os.path.isfile(path):
                raise self.fail("drive_line.coupling", f"names {show(name)}, which is not a "
                                                       f"file (relative to the mechanism "
                                                       f"file's folder).", name)
            try:
                coupling = read_coupling(path)
            except InputError as err:
                raise self.fail("drive_line.coupling", f"names a coupling file that cannot be "
                                                       f"read: {err}", name) from None
            stiffness, damping = None, 0.0
        else:
            stiffness = self.number(self.required(table, "stiffness", "drive_line"),
                                    "drive_line.stiffness", "N·m/rad", positive=True)
            damping = self.number(table.get("damping", 0.0), "drive_line.damping", "N·m·s/rad",
                                  non_negative=True)
            self.within(stiffness, "drive_line.stiffness", "stiffness", "N·m/rad")
            if damping:
                self.within(damping, "drive_line.damping", "damping", "N·m·s/rad")
        ratio = self.within(self.number(table.get("ratio", 1.0), "drive_line.ratio", "-",
                                           positive=True), "drive_line.ratio", "ratio", "-")
        rotor = (self.within(self.number(table["rotor_inertia"], "drive_line.rotor_inertia",
                                            "kg·m²", positive=True),
                                "drive_line.rotor_inertia", "inertia", "kg·m²")
                 if "rotor_inertia" in table else None)
        steps = None
        if "steps" in table:
            steps = self.integer(table["steps"], "drive_line.steps")
            from dyade.limits import MAX_STEPS

            if not 36 <= steps <= MAX_STEPS:
                raise self.fail("drive_line.steps", f"must be 36…{MAX_STEPS:,} steps per "
                                                    f"revolution, got {steps:,}.", steps)
        return DriveLineData(stiffness, damping, ratio, rotor, coupling, name if path else None,
                             steps)
