"""The whole mechanism file: its top-level keys, [units], [sweep], and the order in
which the parts are read (links and joints, dyads, loads and springs, friction, drive)
and checked together."""

from __future__ import annotations

import math
import os
from typing import Any

from dyade.files.mechanism.cam import CamDriveReader
from dyade.files.mechanism.drive import DriveReader
from dyade.files.mechanism.drive_line import DriveLineReader
from dyade.files.mechanism.dyads import DyadReader
from dyade.files.mechanism.keys import TOP_KEYS
from dyade.files.mechanism.links import FRAME_KEYS
from dyade.files.mechanism.loads import LoadReader
from dyade.files.mechanism.servo import ServoReader
from dyade.files.schema import fmt, show
from dyade.model.mechanism import CRANK, FRAME, Link, Mechanism, Sweep, sweep_problem

SWEEP_KEYS = {"start", "stop", "step", "dead_centre", "transmission_warning"}


class Reader(DyadReader, LoadReader, DriveReader, DriveLineReader, ServoReader, CamDriveReader):
    """Walks the parsed TOML of a mechanism file with key paths for the error messages."""

    top_keys = TOP_KEYS

    # -- whole file ----------------------------------------------------------------
    def mechanism(self, data: dict[str, Any]) -> Mechanism:
        self.keys(data, "", TOP_KEYS)
        self.units(data.get("units", {}))
        name = data.get("name", os.path.splitext(os.path.basename(self.source))[0]
                        if self.source else "mechanism")
        if not isinstance(name, str):
            raise self.fail("name", f"must be a string, got {show(name)}.")
        sweep, dead_centre, warning = self.sweep(data.get("sweep", {}))
        friction_tol, friction_max_iter = self.friction_table(data.get("friction", {}))
        frame_table = self.keys(data.get("frame", {}), "frame", FRAME_KEYS)
        links_table = data.get("links", {})
        if not isinstance(links_table, dict):
            raise self.fail("links", f"must be a table of [links.N] tables, got {show(links_table)}.")
        self.points = {FRAME: self.named_points(
            frame_table.get("points", {}), "frame.points")}
        cam = None
        if "cam" in data:  # the cam's follower is link 2
            crank, cam = self.cam_drive(data)
        else:
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
                      for k, t in enumerate(self.tables(data.get("load", []), "load"), 1))
        springs = tuple(self.spring(t, f"spring.{k}", links)
                        for k, t in enumerate(self.tables(data.get("spring", []), "spring"), 1))
        drive = self.drive(data["drive"]) if "drive" in data else None
        if drive is not None and drive.flywheel_inertia and cam is None:
            crank_link = links[CRANK]  # the flywheel turns with the crank, about its pivot
            links[CRANK] = Link(CRANK, crank_link.points, crank_link.mass, crank_link.centre,
                                crank_link.inertia + drive.flywheel_inertia)
        if drive is not None and not any(link.has_mass for link in links.values()) and not (
                cam is not None and drive.flywheel_inertia):  # (a cam's is on its shaft)
            raise self.fail("drive", "needs the machine's inertia for its equation of motion: "
                                     "give the links masses (`links.N.mass`) or a flywheel "
                                     "(`drive.flywheel_inertia`).")
        line = self.drive_line(data["drive_line"]) if "drive_line" in data else None
        if line is not None and drive is not None and line.rotor_inertia is None:
            raise self.fail("drive_line.rotor_inertia", "is missing: with a [drive] motor the "
                                                        "drive line needs the rotor's moment of "
                                                        "inertia [kg·m²] on the motor shaft.")
        servo = None
        if "servo" in data:
            if drive is not None:
                raise self.fail("servo", "and [drive] both drive the crank: a servo follows "
                                         "its motion profile, a [drive] motor turns it by its "
                                         "characteristic. Keep one of the two tables.")
            if line is not None:  # the shaft between the servo's gear and the crank
                for key, bad in (("coupling", line.coupling is not None),
                                 ("ratio", line.ratio != 1.0),
                                 ("rotor_inertia", line.rotor_inertia is not None)):
                    if bad:
                        raise self.fail(f"drive_line.{key}", "is not taken with a [servo]: "
                                        "under a servo the drive line is a shaft (stiffness, "
                                        "damping) between the gear and the crank; the gear "
                                        "ratio and the rotor are the servo's "
                                        "(`servo.ratio`, `servo.rotor_inertia`).")
            sliders = {joint.name for joint in (j for dyad in dyads for j in dyad.joints)
                       if joint.kind == "P"}
            servo = self.servo(data["servo"], data, sliders, [n for n in self.placed if n > 1])
        return Mechanism(name, self.source, crank, dyads, links, sweep, gravity, loads, springs,
                         dead_centre, friction_tol, friction_max_iter, warning,
                         (self.length_unit, self.angle_unit), drive, line, servo=servo,
                         cam=cam)

    def sweep(self, table: Any) -> tuple[Sweep, float, float]:
        self.keys(table, "sweep", SWEEP_KEYS)
        full = 2.0 * math.pi / self.angle
        start = self.number(table.get("start", 0.0), "sweep.start", self.angle_unit)
        stop = self.number(table.get("stop", start + full), "sweep.stop", self.angle_unit)
        step = self.number(table.get("step", math.pi / 180.0 / self.angle), "sweep.step",
                           self.angle_unit, positive=True)
        if stop < start:
            raise self.fail("sweep.stop", f"must not be below sweep.start ({fmt(start)}), "
                                          f"got {fmt(stop)}.")
        dead = self.number(table.get("dead_centre", 2.0 * math.pi / 180.0 / self.angle),
                           "sweep.dead_centre", self.angle_unit, non_negative=True)
        warn = self.number(table.get("transmission_warning", 40.0 * math.pi / 180.0 / self.angle),
                           "sweep.transmission_warning", self.angle_unit, non_negative=True)
        if not dead * self.angle < warn * self.angle <= math.pi / 2:
            raise self.fail("sweep.transmission_warning", f"must lie above sweep.dead_centre "
                                                          f"({fmt(dead)}) and at most 90°, got "
                                                          f"{fmt(warn)}.", warn)
        problem = sweep_problem(start * self.angle, stop * self.angle, step * self.angle)
        if problem:
            raise self.fail("sweep", f"{problem}.")
        return (Sweep(start * self.angle, stop * self.angle, step * self.angle), dead * self.angle,
                warn * self.angle)
