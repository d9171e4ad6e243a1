"""The [servo] table: the crank driven by a servo motor that follows a motion profile
(the file's [profile] table, or a profile file the table names) through a gear, read
into ``dyade.model.servo.Servo``."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from dyade.files.schema import UnitReader, show

if TYPE_CHECKING:  # the servo loads only with a [servo] table
    from dyade.model.servo import Servo

SERVO_KEYS = {"output", "start", "cycle_time", "ratio", "ratio_range", "efficiency",
              "gear_inertia", "rotor_inertia", "catalogue", "samples", "max_inertia_ratio",
              "profile"}
MAX_SAMPLES = 200_000  # time points per cycle


def output_known(output: str, sliders: set[tuple[int, int]], moving: list[int]) -> bool:
    """``output`` is "crank", a prismatic joint's travel ``s_i_j`` (i < j) or a moving
    link's angle ``phi_N`` (N > 2)."""
    if output == "crank":
        return True
    parts = output.split("_")
    if not all(p.isdigit() for p in parts[1:]) or len(parts) < 2:
        return False
    numbers = tuple(int(p) for p in parts[1:])
    if parts[0] == "s" and len(numbers) == 2:
        return numbers in sliders
    return parts[0] == "phi" and len(numbers) == 1 and numbers[0] in moving and numbers[0] > 2


class ServoReader(UnitReader):
    """Reads the [servo] table."""

    def servo(self, table: Any, data: dict[str, Any], sliders: set[tuple[int, int]],
              moving: list[int]) -> Servo:
        """The [servo] table with its profile (``data["profile"]`` or the file named by
        ``servo.profile``); ``sliders`` are the prismatic joints and ``moving`` the moving
        links, which ``servo.output`` may name."""
        from dyade.model.servo import Gear, Servo

        self.keys(table, "servo", SERVO_KEYS)
        output = table.get("output", "crank")
        if not isinstance(output, str) or not output_known(output, sliders, moving):
            raise self.fail("servo.output", f"must be \"crank\" (the profile is the crank's "
                                            f"angle), a slider's travel \"s_i_j\" (a prismatic "
                                            f"joint (i,j), e.g. \"s_1_4\") or a link's angle "
                                            f"\"phi_N\" (a moving link N > 2), got "
                                            f"{show(output)}.", output)
        start = self.number(table.get("start", 0.0), "servo.start", self.angle_unit) * self.angle
        profile = self.servo_profile(table, data)
        cycle_time = None
        if "cycle_time" in table:
            cycle_time = self.number(table["cycle_time"], "servo.cycle_time", "s")
            if not cycle_time > 0.0:
                given = show(table["cycle_time"])
                raise self.fail("servo.cycle_time", f"must be positive [s] (the time of one "
                                                    f"machine cycle), got {given}.",
                                table["cycle_time"], "s")
            if profile.master == "time":
                raise self.fail("servo.cycle_time", "is given, but the profile's master is "
                                                    "time: its period is the cycle time. "
                                                    "Remove `servo.cycle_time`, or give the "
                                                    "profile over a master angle.")
        elif profile.master != "time":
            raise self.fail("servo.cycle_time", "is missing: the profile runs over a master "
                                                "angle, and the servo needs the time of one "
                                                "cycle [s].")
        want_angle = output == "crank" or output.startswith("phi_")
        if want_angle != (profile.output == "angle"):
            raise self.fail("servo.output", f"is {show(output)}, which is "
                                            f"{'an angle' if want_angle else 'a length'}, but "
                                            f"the profile's unit is {show(profile.unit)}: give "
                                            f"the profile in "
                                            f"{'deg or rad' if want_angle else 'a length unit'}.",
                            output)
        self.periodic(profile, output)
        ratio = self.number(table.get("ratio", 1.0), "servo.ratio", "-", positive=True)
        efficiency = self.number(table.get("efficiency", 1.0), "servo.efficiency", "-",
                                 positive=True)
        if efficiency > 1.0:
            raise self.fail("servo.efficiency", f"must lie in (0, 1], got {show(efficiency)}.",
                            efficiency)
        gear_inertia = self.number(table.get("gear_inertia", 0.0), "servo.gear_inertia",
                                   "kg·m²", non_negative=True)
        rotor = (self.number(table["rotor_inertia"], "servo.rotor_inertia", "kg·m²",
                             positive=True) if "rotor_inertia" in table else None)
        ratio_range = None
        if "ratio_range" in table:
            pair = table["ratio_range"]
            if (not isinstance(pair, list) or len(pair) != 2
                    or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                               for v in pair) or not 0.0 < pair[0] < pair[1]):
                raise self.fail("servo.ratio_range", f"must be [lowest, highest] gear ratios, "
                                                     f"0 < lowest < highest, got {show(pair)}.",
                                pair)
            ratio_range = (float(pair[0]), float(pair[1]))
        samples = self.integer(table.get("samples", 720), "servo.samples")
        if not 36 <= samples <= MAX_SAMPLES or samples % 2:
            raise self.fail("servo.samples", f"must be an even number of time steps per cycle, "
                                             f"36…{MAX_SAMPLES:,}, got {samples}.", samples)
        limit = self.number(table.get("max_inertia_ratio", 10.0), "servo.max_inertia_ratio", "-",
                            positive=True)
        catalogue = None
        if "catalogue" in table:
            catalogue = self.catalogue_file(table["catalogue"])
        return Servo(profile, output, start, Gear(ratio, efficiency, gear_inertia), rotor,
                     catalogue, ratio_range, samples, limit, cycle_time)

    def periodic(self, profile, output: str) -> None:
        """Refuse a profile after which the machine does not repeat: the crank turns whole
        revolutions per cycle, an output inverted through the linkage comes back."""
        import math

        from dyade.files.profile import amount, output_factor

        size = output_factor(profile.unit)
        turns = profile.advance / (2.0 * math.pi)
        scale = max(max(abs(s.lift_from), abs(s.lift_to)) for s in profile.segments) or 1.0
        if output == "crank" and abs(turns - round(turns)) * 2.0 * math.pi <= 1e-9 * scale:
            return
        if output != "crank" and abs(profile.advance) <= 1e-9 * scale:
            return
        key = f"profile.segment.{len(profile.segments)}.to"
        moved = amount(profile.advance / size, profile.unit)
        need = ("the crank a whole number of revolutions (0, 360°, 720°, …)"
                if output == "crank" else f"the output {output} back to where it starts")
        raise self.fail(key, f"ends the cycle {moved} from where it starts: the servo's "
                             f"machine repeats its cycle only when the profile brings {need}; "
                             f"end the last segment there.", profile.segments[-1].lift_to / size)

    def relative(self, name: Any, key: str, what: str) -> str:
        if not isinstance(name, str) or not name:
            raise self.fail(key, f"must name {what} (relative to the mechanism file's "
                                 f"folder), got {show(name)}.", name)
        base = os.path.dirname(self.source) if self.source else ""
        path = os.path.join(base, name)
        if not os.path.isfile(path):
            raise self.fail(key, f"names {show(name)}, which is not a file (relative to the "
                                 f"mechanism file's folder).", name)
        return path

    def catalogue_file(self, name: Any):
        from dyade.errors import InputError
        from dyade.files.catalogue import read_catalogue

        path = self.relative(name, "servo.catalogue", "a motor catalogue (CSV)")
        try:
            return read_catalogue(path, name)
        except InputError as err:
            raise self.fail("servo.catalogue", f"names a catalogue that cannot be read: "
                                               f"{err}", name) from None

    def servo_profile(self, table: dict[str, Any], data: dict[str, Any]):
        """The profile of the servo: the file's [profile] table, or the file that
        ``servo.profile`` names (one or the other)."""
        from dyade.files.profile import ProfileReader, read_profile

        if "profile" in table:
            if "profile" in data:
                raise self.fail("servo.profile", "names a profile file, and the file has a "
                                                 "[profile] table too: keep one.")
            return read_profile(self.relative(table["profile"], "servo.profile",
                                              "a profile file (TOML)"))
        if "profile" not in data:
            raise self.fail("servo", "needs a motion profile: a [profile] table in this file "
                                     "(with [[profile.segment]] tables), or `servo.profile = "
                                     "\"FILE.toml\"` naming a profile file.")
        name = data.get("name") if isinstance(data.get("name"), str) else "profile"
        return ProfileReader(self.label, self.source).profile(data["profile"], name)
