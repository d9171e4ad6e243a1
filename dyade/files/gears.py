"""Read a gear-drive file (TOML), validate it and convert it to the SI model of
``dyade.model.gears``.

The file lists rigid bodies, shafts, bearings, spring-damper elements, gears, meshes,
excitations and the input speed (``docs/reference/gear-file.md`` documents every key).
Lengths are in ``units.length`` and angles in ``units.angle`` as in mechanism files;
masses, inertias, stiffnesses, moduli and densities are SI. Every error names the file
and the key; the checks that need the assembled matrices (meshes that constrain the
same motion twice) are made by ``dyade.vibration.gears.assembly``, with the key too.

>>> drive = read_gears("mechanisms/gears/friswell-geared.toml")
>>> drive.model, [b.name for b in drive.bodies]
('torsional', ['motor', 'gear1', 'gear2', 'rotor3', 'rotor4'])
"""

from __future__ import annotations

import math
import os
from typing import Any

from dyade.files.schema import UnitReader, is_number, load_data, suggest
from dyade.limits import PLAUSIBLE
from dyade.files.schema import fmt as _fmt
from dyade.files.schema import show as _show
from dyade.model.gears import (
    DOFS,
    FRAME,
    PARALLEL_TOL,
    RIGID,
    Body,
    Element,
    Excitation,
    Gear,
    GearDrive,
    Material,
    Mesh,
    Shaft,
    Speed,
    Vector,
    add,
    cross,
    disk,
    dot,
    mesh_step,
    unit,
)

TOP_KEYS = {"name", "description", "model", "units", "material", "body", "shaft", "bearing",
            "element", "gear", "mesh", "excitation", "speed"}
MODELS = {"rfe": "six coordinates per body (the paper's rigid finite elements)",
          "torsional": "one rotation per body"}
MATERIAL_KEYS = {"E", "G", "density"}
BODY_KEYS = {"name", "mass", "J_x", "J_y", "J_z", "diameter", "width", "bore", "material",
             "position", "axis"}
SHAFT_KEYS = {"name", "bodies", "length", "diameter", "bore", "material", "segments",
              "shear_factor", "damping", "torsional_stiffness"}
BEARING_STIFFNESS = {"axial": 0, "radial": (1, 2), "torsion": 3, "tilt": (4, 5)}
BEARING_KEYS = ({"name", "body", "offset"} | set(BEARING_STIFFNESS)
                | {f"{key}_damping" for key in BEARING_STIFFNESS})
ELEMENT_KEYS = {"name", "bodies", "at", "axis", "stiffness", "damping"}
GEAR_KEYS = {"name", "body", "teeth", "module", "pressure_angle", "helix_angle", "hand", "width",
             "offset"}
MESH_KEYS = {"name", "driving", "driven", "rotation", "angle", "stiffness", "damping",
             "c_gamma_alpha", "face_width"}
EXCITATION_KEYS = {"name", "kind", "body", "mesh", "amplitude", "phase", "order", "harmonic",
                   "frequency"}
SPEED_KEYS = {"body", "rpm", "rotation"}
SENSES = {"right": 1, "left": -1}
PLACE_RTOL = 1e-6  # [-] positions that disagree by more than this share of the drive's size


def read_gears(path: str | os.PathLike, overrides: dict[str, Any] | None = None) -> GearDrive:
    """Read and validate a gear-drive file.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (``docs/reference/gear-file.md`` documents every key).
    overrides : dict, optional
        Dotted key path -> value, replacing keys of the file as ``--set`` does
        (``{"shaft.1.segments": 8}``; array entries by 1-based index).

    Returns
    -------
    GearDrive
        In SI units, validated; bodies placed by their shafts and meshes.

    Raises
    ------
    InputError
        Naming the file and the key path, what was expected and what was found.

    Examples
    --------
    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> [round(g.pitch_radius * 1000, 1) for g in drive.gears]      # [mm]
    [40.0, 120.0, 50.0, 175.0]
    """
    return build_gears(load_data(path, overrides), path)


def build_gears(data: dict[str, Any], path: str | os.PathLike | None = None, *,
                plausible: bool = True) -> GearDrive:
    """Validate gear-drive data and build the drive.

    Parameters
    ----------
    data : dict
        The parsed TOML of a gear-drive file, or the same structure written in Python
        (the gear-drive file reference documents every key).
    path : str or os.PathLike, optional
        The file the data came from, named in errors.
    plausible : bool
        False lifts the bounds of what a machine has (``dyade.limits``), for studies of
        limits such as a rigid bearing.

    Returns
    -------
    GearDrive
        In SI units, validated, its bodies placed.

    Examples
    --------

    >>> drive = build_gears({"model": "torsional",
    ...     "body": [{"name": "a", "J_x": 1.0}, {"name": "b", "J_x": 1.0}],
    ...     "shaft": [{"bodies": ["a", "b"], "torsional_stiffness": 100.0}]})
    >>> drive.shafts[0].torsional_stiffness
    100.0
    """
    path = os.fspath(path) if path else None
    reader = Reader(os.path.basename(path) if path else "gear drive", path)
    reader.plausible = plausible
    return reader.drive(data)


PLAUSIBLE_UNITS = {"kg": "mass", "kg·m²": "inertia", "N/m": "stiffness",
                   "N/m or N·m/rad": "stiffness", "N·m/rad": "stiffness", "N·s/m": "damping",
                   "N·m·s/rad": "damping", "rpm": "speed_rpm", "Hz": "frequency",
                   "N·m": "torque", "Pa": "modulus", "kg/m³": "density", "s": "time_constant"}
"""unit of a key -> its quantity in ``dyade.limits.PLAUSIBLE``"""


class Reader(UnitReader):
    """Walks the parsed TOML of a gear-drive file with key paths for the error messages."""

    top_keys = TOP_KEYS
    plausible = True
    ceiling = False  # its own check below: the whole range, floors included

    # -- plausibility: every number within what a machine has (dyade.limits) ----------
    def number(self, value: Any, key: str, unit: str, positive: bool = False,
               non_negative: bool = False) -> float:
        number = super().number(value, key, unit, positive, non_negative)
        quantity = PLAUSIBLE_UNITS.get(unit) if self.plausible else None
        if quantity and number != 0.0 and not PLAUSIBLE[quantity][0] <= number <= PLAUSIBLE[
                quantity][1]:
            low, high, _ = PLAUSIBLE[quantity]
            rigid = (" A support or joint that does not give is written \"rigid\" (an exact "
                     "constraint, the limit of ever stiffer springs) instead of a huge number, "
                     "which would only spoil the eigenproblem's conditioning."
                     if quantity == "stiffness" and number > high else "")
            raise self.fail(key, f"must lie in {_fmt(low)}…{_fmt(high)} {unit} (what a machine "
                                 f"has), got {_fmt(number)}.{rigid}", number, unit)
        return number

    def stiffness(self, value: Any, key: str, unit: str) -> float:
        """A stiffness coefficient [unit], or "rigid" (``RIGID``: an exact constraint)."""
        if isinstance(value, str) and value.strip().lower() == "rigid":
            return RIGID
        if isinstance(value, str):
            raise self.fail(key, f"must be a stiffness [{unit}] or \"rigid\", got {_show(value)}.",
                            value, unit)
        return self.number(value, key, unit, non_negative=True)

    def length_of(self, value: Any, key: str, positive: bool = False,
                  non_negative: bool = False) -> float:
        length = super().length_of(value, key, positive, non_negative)
        low, high, _ = PLAUSIBLE["length"]
        if self.plausible and (abs(length) > high or positive and length < low):  # offsets ~0
            raise self.fail(key, f"must lie within {_fmt(low / self.length)}…"
                                 f"{_fmt(high / self.length)} {self.length_unit} (what a "
                                 f"machine has), got {_fmt(length / self.length)}.", value,
                            self.length_unit)
        return length

    def integer(self, value: Any, key: str) -> int:
        number = super().integer(value, key)
        if self.plausible and key.endswith(".teeth") and number > PLAUSIBLE["teeth"][1]:
            raise self.fail(key, f"must be at most {PLAUSIBLE['teeth'][1]:,} (what a machine "
                                 f"has), got {number}.", number)
        return number

    # -- primitives --------------------------------------------------------------------
    def vector(self, value: Any, key: str, unit_name: str, scale: float = 1.0) -> Vector:
        if (not isinstance(value, list) or len(value) != 3
                or not all(is_number(v) and math.isfinite(v) for v in value)):
            raise self.fail(key, f"must be three numbers [x, y, z] [{unit_name}], got "
                                 f"{_show(value)}.", value, unit_name)
        return (float(value[0]) * scale, float(value[1]) * scale, float(value[2]) * scale)

    def direction(self, value: Any, key: str) -> Vector:
        vec = self.vector(value, key, "-")
        if math.sqrt(dot(vec, vec)) < 1e-12:
            raise self.fail(key, "must be a direction, got the zero vector.", value)
        return unit(vec)

    def coefficients(self, value: Any, key: str, what: str) -> tuple[float, ...]:
        rigid = what == "stiffness"
        hint = '; "rigid" where a direction does not give' if rigid else ""
        if (not isinstance(value, list) or len(value) != 6
                or not all(is_number(v) or rigid and isinstance(v, str) for v in value)):
            raise self.fail(key, f"must be six {what} coefficients [x, y, z, rx, ry, rz] "
                                 f"(N/m for x, y, z; N·m/rad for rx, ry, rz; ·s for damping"
                                 f"{hint}), got {_show(value)}.", value)
        if rigid:
            return tuple(self.stiffness(v, key, "N/m or N·m/rad") for v in value)
        return tuple(self.number(v, key, "N/m or N·m/rad", non_negative=True) for v in value)

    def rigid_damping(self, stiffness: tuple[float, ...], damping: tuple[float, ...], key: str
                      ) -> None:
        """A rigid direction takes no damping (it does not move)."""
        for name, k, c in zip(DOFS, stiffness, damping):
            if k == RIGID and c != 0.0:
                raise self.fail(key, f"gives damping in {name}, where the stiffness is "
                                     f"\"rigid\": a direction that does not move dissipates "
                                     f"nothing. Remove that damping, or give a stiffness.")

    def name_of(self, table: dict[str, Any], key: str, default: str, taken: dict[str, str]
                ) -> str:
        name = table.get("name", default)
        if not isinstance(name, str) or not name:
            raise self.fail(f"{key}.name", f"must be a non-empty string, got {_show(name)}.")
        if name == FRAME:
            raise self.fail(f"{key}.name", f"may not be \"{FRAME}\": that name stands for the "
                                           f"housing.")
        if name in taken:
            raise self.fail(f"{key}.name", f"\"{name}\" is already the name of {taken[name]}.")
        taken[name] = key
        return name

    def body_ref(self, value: Any, key: str, frame_allowed: bool = False) -> str:
        names = set(self.bodies) | ({FRAME} if frame_allowed else set())
        if not isinstance(value, str) or value not in names:
            where = ", ".join(self.bodies)
            hint = suggest(value, names) if isinstance(value, str) else f" Bodies: {where}."
            raise self.fail(key, f"names no body: {_show(value)}.{hint}", value)
        return value

    def ends(self, table: dict[str, Any], key: str) -> tuple[str, str]:
        value = self.required(table, "bodies", key)
        if not isinstance(value, list) or len(value) != 2:
            raise self.fail(f"{key}.bodies", f"must be two body names [\"a\", \"b\"] (the second "
                                             f"may be \"{FRAME}\"), got {_show(value)}.", value)
        first = self.body_ref(value[0], f"{key}.bodies")
        second = self.body_ref(value[1], f"{key}.bodies", frame_allowed=True)
        if first == second:
            raise self.fail(f"{key}.bodies", f"joins body \"{first}\" to itself.")
        return first, second

    def sense(self, value: Any, key: str) -> int:
        if value not in SENSES:
            raise self.fail(key, f"must be \"right\" or \"left\" (the sense of rotation about "
                                 f"the body's axis by the right-hand rule), got {_show(value)}.",
                            value)
        return SENSES[value]

    def material(self, value: Any, key: str, default: Material) -> Material:
        table = self.keys(value, key, MATERIAL_KEYS)
        out = {name: self.number(table[name], f"{key}.{name}",
                                 "kg/m³" if name == "density" else "Pa", positive=True)
               for name in MATERIAL_KEYS if name in table}
        return Material(**{name: out.get(name, getattr(default, name)) for name in MATERIAL_KEYS})

    def array(self, data: dict[str, Any], key: str) -> list[dict[str, Any]]:
        value = data.get(key, [])
        if not isinstance(value, list):
            raise self.fail(key, f"must be an array of tables [[{key}]], got {_show(value)}.")
        return value

    # -- the whole file ----------------------------------------------------------------
    def drive(self, data: dict[str, Any]) -> GearDrive:
        self.keys(data, "", TOP_KEYS)
        self.units(data.get("units", {}))
        model = data.get("model", "rfe")
        if model not in MODELS:
            raise self.fail("model", f"must be \"rfe\" ({MODELS['rfe']}) or \"torsional\" "
                                     f"({MODELS['torsional']}), got {_show(model)}.", model)
        self.torsional = model == "torsional"
        name = data.get("name", os.path.splitext(self.label)[0])
        if not isinstance(name, str):
            raise self.fail("name", f"must be a string, got {_show(name)}.")
        self.default_material = self.material(data.get("material", {}), "material", Material())
        taken: dict[str, str] = {}
        self.bodies: dict[str, dict[str, Any]] = {}
        body_tables = self.array(data, "body")
        if not body_tables:
            raise self.fail("body", "must list the drive's rigid bodies as [[body]] tables.")
        for k, table in enumerate(body_tables, 1):
            self.body(table, f"body.{k}", taken)
        shafts = tuple(self.shaft(t, f"shaft.{k}", taken)
                       for k, t in enumerate(self.array(data, "shaft"), 1))
        self.gears: dict[str, Gear] = {}
        self.gear_keys: dict[str, str] = {}  # gear name -> its table's key path
        gear_names: dict[str, str] = {}  # gears have names of their own: meshes refer to them
        for k, table in enumerate(self.array(data, "gear"), 1):
            self.gear(table, f"gear.{k}", gear_names)
        meshes = [self.mesh(t, f"mesh.{k}", taken)
                  for k, t in enumerate(self.array(data, "mesh"), 1)]
        positions = self.place(shafts, meshes)
        bodies = tuple(Body(n, b["mass"], b["inertia"], positions[n], b["axis"])
                       for n, b in self.bodies.items())
        shafts = tuple(self.shaft_length(s, f"shaft.{k}", positions)
                       for k, s in enumerate(shafts, 1))
        located = {b.name: b for b in bodies}
        elements = tuple(self.bearing(t, f"bearing.{k}", taken, located)
                         for k, t in enumerate(self.array(data, "bearing"), 1))
        elements += tuple(self.element(t, f"element.{k}", taken, located)
                          for k, t in enumerate(self.array(data, "element"), 1))
        self.check_train(shafts, elements, meshes)
        speed = self.speed(data["speed"]) if "speed" in data else None
        drive = GearDrive(name, bodies, shafts, elements, tuple(self.gears.values()),
                          tuple(meshes), (), speed, model, self.source)
        meshes = self.rotations(drive, meshes)
        excitations = tuple(self.excitation(t, f"excitation.{k}", taken, meshes)
                            for k, t in enumerate(self.array(data, "excitation"), 1))
        return GearDrive(name, bodies, shafts, elements, tuple(self.gears.values()),
                         tuple(meshes), excitations, speed, model, self.source)

    # -- bodies ------------------------------------------------------------------------
    def body(self, table: Any, key: str, taken: dict[str, str]) -> None:
        self.keys(table, key, BODY_KEYS)
        if "name" not in table:
            raise self.fail(f"{key}.name", "is missing: shafts, bearings and gears refer to "
                                           "bodies by name.")
        name = self.name_of(table, key, "", taken)
        shape = [k for k in ("diameter", "width", "bore", "material") if k in table]
        given = [k for k in ("mass", "J_x", "J_y", "J_z") if k in table]
        if shape and given:
            raise self.fail(f"{key}.{given[0]}", f"and `{shape[0]}` are two ways to give the "
                                                 f"mass: either mass and J_x, J_y, J_z, or a "
                                                 f"cylinder's diameter, width (and bore).")
        if shape:
            material = self.material(table.get("material", {}), f"{key}.material",
                                     self.default_material)
            diameter = self.length_of(self.required(table, "diameter", key),
                                      f"{key}.diameter", positive=True)
            width = self.length_of(self.required(table, "width", key), f"{key}.width",
                                   positive=True)
            bore = self.length_of(table.get("bore", 0.0), f"{key}.bore", non_negative=True)
            if bore >= diameter:
                raise self.fail(f"{key}.bore", f"must be smaller than the diameter "
                                               f"({_fmt(diameter / self.length)} "
                                               f"{self.length_unit}), got {_fmt(bore / self.length)}.")
            mass, inertia = disk(material.density, diameter, width, bore)
        else:
            need = ("J_x",) if self.torsional else ("mass", "J_x", "J_y", "J_z")
            for k in need:
                if k not in table:
                    why = ("the torsional model needs J_x" if self.torsional else
                           "six coordinates need the mass and all three principal inertias")
                    raise self.fail(f"{key}.{k}", f"is missing: {why} (or give a cylinder's "
                                                  f"diameter and width).")
            mass = (self.number(table["mass"], f"{key}.mass", "kg", positive=True)
                    if "mass" in table else 0.0)
            inertia = tuple(self.number(table[k], f"{key}.{k}", "kg·m²", positive=True)
                            if k in table else 0.0 for k in ("J_x", "J_y", "J_z"))
        axis = self.direction(table["axis"], f"{key}.axis") if "axis" in table else (1.0, 0.0, 0.0)
        position = (self.vector(table["position"], f"{key}.position", self.length_unit,
                                self.length) if "position" in table else None)
        self.bodies[name] = {"mass": mass, "inertia": inertia, "axis": axis,
                             "position": position, "key": key}

    # -- shafts ------------------------------------------------------------------------
    def shaft(self, table: Any, key: str, taken: dict[str, str]) -> Shaft:
        self.keys(table, key, SHAFT_KEYS)
        number = key.split(".")[1]
        name = self.name_of(table, key, f"shaft{number}", taken)
        ends = self.ends(table, key)
        if FRAME not in ends:
            a, b = (self.bodies[e]["axis"] for e in ends)
            if 1.0 - abs(dot(a, b)) > PARALLEL_TOL:
                raise self.fail(f"{key}.bodies", f"joins \"{ends[0]}\" and \"{ends[1]}\", whose "
                                                 f"axes are not parallel: a shaft is straight.")
        length = (self.length_of(table["length"], f"{key}.length", positive=True)
                  if "length" in table else 0.0)
        segments = self.integer(table.get("segments", 1), f"{key}.segments")
        if segments < 0:
            raise self.fail(f"{key}.segments", f"must be 0 (massless) or more, got {segments}.")
        damping = self.number(table.get("damping", 0.0), f"{key}.damping", "s",
                              non_negative=True)
        if "torsional_stiffness" in table:
            if not self.torsional:
                raise self.fail(f"{key}.torsional_stiffness", "is for the torsional model only: "
                                                              "six coordinates need the shaft's "
                                                              "length and diameter (or an "
                                                              "[[element]] with six coefficients).")
            for k in ("diameter", "bore", "material", "shear_factor"):
                if k in table:
                    raise self.fail(f"{key}.{k}", "and `torsional_stiffness` are two ways to give "
                                                  "the stiffness: give one of them.")
            stiffness = self.number(table["torsional_stiffness"], f"{key}.torsional_stiffness",
                                    "N·m/rad", positive=True)
            if "segments" in table and segments != 0:
                raise self.fail(f"{key}.segments", "needs a diameter: a shaft given only by its "
                                                   "torsional stiffness is massless (segments = 0).")
            return Shaft(name, ends, length, segments=0, damping=damping,
                         torsional_stiffness=stiffness)
        diameter = self.length_of(self.required(table, "diameter", key), f"{key}.diameter",
                                  positive=True)
        bore = self.length_of(table.get("bore", 0.0), f"{key}.bore", non_negative=True)
        if bore >= diameter:
            raise self.fail(f"{key}.bore", f"must be smaller than the diameter, got "
                                           f"{_fmt(bore / self.length)} {self.length_unit}.")
        material = self.material(table.get("material", {}), f"{key}.material",
                                 self.default_material)
        kappa = self.number(table.get("shear_factor", 0.9), f"{key}.shear_factor", "-",
                            positive=True)
        return Shaft(name, ends, length, diameter, bore, material, segments, kappa, damping)

    def shaft_length(self, shaft: Shaft, key: str, positions: dict[str, Vector]) -> Shaft:
        """The shaft's length from the file, else from its ends' positions."""
        if shaft.length > 0.0 or shaft.torsional_stiffness is not None:
            return shaft
        a, b = shaft.ends
        if b != FRAME and self.bodies[a]["position"] and self.bodies[b]["position"]:
            length = dot(add(positions[b], positions[a], -1.0), self.bodies[a]["axis"])
            if length > 0.0:
                from dataclasses import replace

                return replace(shaft, length=length)
        raise self.fail(f"{key}.length", "is missing: give the shaft's length (or the positions "
                                         "of both its bodies, the second further along the "
                                         "first one's axis).")

    # -- gears and meshes --------------------------------------------------------------
    def mesh_stiffness(self, table: dict[str, Any], key: str, p: Gear, r: Gear) -> float | None:
        """An elastic mesh's spring along the tooth normal [N/m]: `stiffness`, or ISO 6336's
        transverse mesh stiffness per face width `c_gamma_alpha` [N/m²] times the face width
        b, over cos²β_b (sin β_b = sin β·cos α_n); None for an ideal mesh. Either needs the
        gears' size (`module`): the spring acts at their base radii."""
        given = [k for k in ("stiffness", "c_gamma_alpha") if k in table]
        if not given:
            if "face_width" in table:
                raise self.fail(f"{key}.face_width", "is for `c_gamma_alpha` (ISO 6336's mesh "
                                                     "stiffness per face width): give it too.")
            return None
        if len(given) == 2:
            raise self.fail(f"{key}.c_gamma_alpha", "and `stiffness` are two ways to give the "
                                                    "mesh spring: give one of them.")
        if p.module is None:
            raise self.fail(f"{self.gear_keys[p.name]}.module",
                            f"is missing: mesh `{key}.{given[0]}` is elastic, and its spring "
                            f"acts at the base radii r_b = z·m_n·cos α_t/(2·cos β) of gears "
                            f"\"{p.name}\" and \"{r.name}\": give `module` on both (without it "
                            f"only the ratio is known, enough for ideal meshes).")
        if given[0] == "stiffness":
            return self.number(table["stiffness"], f"{key}.stiffness", "N/m", positive=True)
        per_width = self.number(table["c_gamma_alpha"], f"{key}.c_gamma_alpha", "N/m²",
                                positive=True)
        widths = [g.width for g in (p, r) if g.width > 0.0]
        if "face_width" in table:
            width = self.length_of(table["face_width"], f"{key}.face_width", positive=True)
        elif widths:
            width = min(widths)
        else:
            raise self.fail(f"{key}.face_width", "is missing: `c_gamma_alpha` is a stiffness per "
                                                 "face width b (or give `width` on the gears).")
        base_helix = math.asin(math.sin(p.helix_angle) * math.cos(p.pressure_angle))
        return per_width * width / math.cos(base_helix) ** 2

    def gear(self, table: Any, key: str, taken: dict[str, str]) -> None:
        self.keys(table, key, GEAR_KEYS)
        if "name" not in table:
            raise self.fail(f"{key}.name", "is missing: meshes refer to gears by name.")
        name = self.name_of(table, key, "", taken)
        if "body" not in table:
            raise self.fail(f"{key}.body", "is missing: a gear sits on a body (give its name).")
        body = self.body_ref(table["body"], f"{key}.body")
        teeth = self.integer(self.required(table, "teeth", key), f"{key}.teeth")
        if teeth < 1:
            raise self.fail(f"{key}.teeth", f"must be at least 1, got {teeth}.")
        if "module" in table:
            module = self.length_of(table["module"], f"{key}.module", positive=True)
        elif self.torsional:
            module = None
        else:
            raise self.fail(f"{key}.module", "is missing: the normal module m_n sets the pitch "
                                             "radius r = z·m_n/(2·cos β).")
        alpha = self.angle_of(table.get("pressure_angle", 20.0 * math.pi / 180.0 / self.angle),
                              f"{key}.pressure_angle")
        if not 0.0 < alpha < math.pi / 4.0:
            raise self.fail(f"{key}.pressure_angle", f"must lie between 0° and 45°, got "
                                                     f"{_fmt(math.degrees(alpha))}°.")
        beta = self.angle_of(table.get("helix_angle", 0.0), f"{key}.helix_angle")
        if not 0.0 <= beta < math.pi / 4.0:
            raise self.fail(f"{key}.helix_angle", f"must lie between 0° (spur) and 45°; the hand "
                                                  f"goes in `hand`; got "
                                                  f"{_fmt(math.degrees(beta))}°.")
        if beta > 0.0 and "hand" not in table:
            raise self.fail(f"{key}.hand", "is missing: a helical gear (helix_angle > 0) is "
                                           "\"right\" or \"left\" handed.")
        hand = 0
        if "hand" in table:
            hand = self.sense(table["hand"], f"{key}.hand") if beta > 0.0 else 0
        width = self.length_of(table.get("width", 0.0), f"{key}.width", non_negative=True)
        offset = self.length_of(table.get("offset", 0.0), f"{key}.offset")
        self.gears[name] = Gear(name, body, teeth, module, alpha, beta, hand, width, offset)
        self.gear_keys[name] = key

    def gear_ref(self, table: dict[str, Any], key: str, role: str) -> Gear:
        if role not in table:
            raise self.fail(f"{key}.{role}", f"is missing: the {role} gear's name.")
        value = table[role]
        if not isinstance(value, str) or value not in self.gears:
            hint = (suggest(value, set(self.gears)) if isinstance(value, str) and self.gears
                    else " Define it in a [[gear]] table.")
            raise self.fail(f"{key}.{role}", f"names no gear: {_show(value)}.{hint}", value)
        return self.gears[value]

    def mesh(self, table: Any, key: str, taken: dict[str, str]) -> Mesh:
        self.keys(table, key, MESH_KEYS)
        number = key.split(".")[1]
        name = self.name_of(table, key, f"mesh{number}", taken)
        p, r = self.gear_ref(table, key, "driving"), self.gear_ref(table, key, "driven")
        if p.body == r.body:
            raise self.fail(key, f"joins gears \"{p.name}\" and \"{r.name}\", which are both on "
                                 f"body \"{p.body}\": a mesh joins two bodies.")
        unit_name = self.length_unit
        if p.module is not None and r.module is not None and not math.isclose(
                p.module, r.module, rel_tol=1e-9):
            raise self.fail(key, f"joins \"{p.name}\" (module {_fmt(p.module / self.length)} "
                                 f"{unit_name}) and \"{r.name}\" (module "
                                 f"{_fmt(r.module / self.length)} {unit_name}): meshing gears "
                                 f"need the same normal module.")
        if (p.module is None) != (r.module is None):
            raise self.fail(key, f"joins \"{p.name}\" and \"{r.name}\": give `module` on both "
                                 f"gears or on neither.")
        if not math.isclose(p.pressure_angle, r.pressure_angle, rel_tol=1e-9):
            raise self.fail(key, f"joins \"{p.name}\" and \"{r.name}\" with different pressure "
                                 f"angles: meshing gears need the same α_n.")
        if not math.isclose(p.helix_angle, r.helix_angle, rel_tol=1e-9, abs_tol=1e-12):
            raise self.fail(key, f"joins \"{p.name}\" and \"{r.name}\" with different helix "
                                 f"angles: meshing gears need the same β.")
        if p.helix_angle > 0.0 and p.hand == r.hand:
            raise self.fail(key, f"joins two {'right' if p.hand > 0 else 'left'}-hand gears "
                                 f"\"{p.name}\" and \"{r.name}\": external helical gears in mesh "
                                 f"have opposite hands.")
        if not self.torsional:
            a, b = self.bodies[p.body]["axis"], self.bodies[r.body]["axis"]
            if 1.0 - abs(dot(a, b)) > PARALLEL_TOL:
                raise self.fail(key, f"joins gears on bodies \"{p.body}\" and \"{r.body}\" whose "
                                     f"axes are not parallel: dyade models cylindrical gears on "
                                     f"parallel shafts (no bevel or crossed gears).")
        rotation = (self.sense(table["rotation"], f"{key}.rotation") if "rotation" in table
                    else 0)
        angle = self.angle_of(table.get("angle", 0.0), f"{key}.angle")
        stiffness = self.mesh_stiffness(table, key, p, r)
        damping = self.number(table.get("damping", 0.0), f"{key}.damping", "N·s/m",
                              non_negative=True)
        if damping > 0.0 and stiffness is None:
            raise self.fail(f"{key}.damping", "needs `stiffness`: an ideal mesh (the "
                                              "constraint) has no relative motion to damp.")
        return Mesh(name, p.name, r.name, rotation, angle, stiffness, damping)

    # -- where the bodies are --------------------------------------------------------
    def place(self, shafts: tuple[Shaft, ...], meshes: list[Mesh]) -> dict[str, Vector]:
        """Every body's position: as given, or carried from a placed body along a shaft
        (its length along the axis) or across a mesh (the centre distance r_p + r_r along
        the line of centres). Positions reached twice must agree."""
        links: dict[str, list[tuple[str, Vector, str]]] = {n: [] for n in self.bodies}
        for k, shaft in enumerate(shafts, 1):
            a, b = shaft.ends
            if b != FRAME and shaft.length > 0.0:
                step = tuple(shaft.length * c for c in self.bodies[a]["axis"])
                links[a].append((b, step, f"shaft.{k}"))
                links[b].append((a, tuple(-c for c in step), f"shaft.{k}"))
        for k, mesh in enumerate(meshes, 1):
            p, r = self.gears[mesh.driving], self.gears[mesh.driven]
            if p.module is None or self.torsional:
                continue
            step = mesh_step(p, r, mesh, self.bodies[p.body]["axis"], self.bodies[r.body]["axis"])
            links[p.body].append((r.body, step, f"mesh.{k}"))
            links[r.body].append((p.body, tuple(-c for c in step), f"mesh.{k}"))
        given = {n: b["position"] for n, b in self.bodies.items() if b["position"] is not None}
        scale = max([1.0] + [abs(c) for v in given.values() for c in v])
        positions: dict[str, Vector] = {}
        roots = list(given) + [n for n in self.bodies if n not in given]
        for root in roots:
            if root in positions:
                continue
            positions[root] = given.get(root, (0.0, 0.0, 0.0))
            todo = [root]
            while todo:
                name = todo.pop()
                for other, step, via in links[name]:
                    there = add(positions[name], step)
                    known = positions.get(other, given.get(other))
                    if known is None:
                        positions[other] = there
                        todo.append(other)
                        continue
                    if max(abs(c) for c in add(known, there, -1.0)) > PLACE_RTOL * scale:
                        shown = ", ".join(_fmt(round(c / self.length, 9)) for c in there)
                        raise self.fail(via, f"places body \"{other}\" at [{shown}] "
                                             f"{self.length_unit}, which disagrees with its "
                                             f"position from `{self.bodies[other]['key']}` or "
                                             f"another shaft or mesh: check lengths, radii and "
                                             f"`angle`.")
                    if other not in positions:
                        positions[other] = known
                        todo.append(other)
        return positions

    # -- bearings and elements ---------------------------------------------------------
    def bearing(self, table: Any, key: str, taken: dict[str, str], bodies: dict[str, Body]
                ) -> Element:
        self.keys(table, key, BEARING_KEYS)
        number = key.split(".")[1]
        name = self.name_of(table, key, f"bearing{number}", taken)
        if "body" not in table:
            raise self.fail(f"{key}.body", "is missing: the body it carries.")
        body = bodies[self.body_ref(table["body"], f"{key}.body")]
        stiffness, damping = [0.0] * 6, [0.0] * 6
        for word, where in BEARING_STIFFNESS.items():
            unit_name = "N/m" if word in ("axial", "radial") else "N·m/rad"
            k = self.stiffness(table.get(word, 0.0), f"{key}.{word}", unit_name)
            c = self.number(table.get(f"{word}_damping", 0.0), f"{key}.{word}_damping",
                            f"{unit_name}·s", non_negative=True)
            if k == RIGID and c != 0.0:
                raise self.fail(f"{key}.{word}_damping", f"is given, but `{word}` is \"rigid\": "
                                                         f"a direction that does not move "
                                                         f"dissipates nothing. Remove it, or "
                                                         f"give `{word}` a stiffness.")
            for index in (where if isinstance(where, tuple) else (where,)):
                stiffness[index], damping[index] = k, c
        if not any(stiffness) and not any(damping):
            raise self.fail(key, "has no stiffness and no damping: give `radial`, `axial`, "
                                 "`tilt` or `torsion`.")
        offset = self.length_of(table.get("offset", 0.0), f"{key}.offset")
        point = add(body.position, body.axis, offset)
        return Element(name, (body.name, FRAME), point, body.axis, tuple(stiffness),
                       tuple(damping), "bearing", name)

    def element(self, table: Any, key: str, taken: dict[str, str], bodies: dict[str, Body]
                ) -> Element:
        self.keys(table, key, ELEMENT_KEYS)
        number = key.split(".")[1]
        name = self.name_of(table, key, f"element{number}", taken)
        a, b = self.ends(table, key)
        stiffness = self.coefficients(self.required(table, "stiffness", key),
                                      f"{key}.stiffness", "stiffness")
        damping = (self.coefficients(table["damping"], f"{key}.damping", "damping")
                   if "damping" in table else (0.0,) * 6)
        if not any(stiffness) and not any(damping):
            raise self.fail(f"{key}.stiffness", "is all zero and so is the damping: the element "
                                                "would do nothing.")
        self.rigid_damping(stiffness, damping, f"{key}.damping")
        if "at" in table:
            point = self.vector(table["at"], f"{key}.at", self.length_unit, self.length)
        elif b == FRAME:
            point = bodies[a].position
        else:
            point = add(bodies[a].position, add(bodies[b].position, bodies[a].position, -1.0), 0.5)
        axis = self.direction(table["axis"], f"{key}.axis") if "axis" in table else bodies[a].axis
        return Element(name, (a, b), point, axis, stiffness, damping, "element", name)

    # -- speed, rotation senses, excitations -------------------------------------------
    def speed(self, table: Any) -> Speed:
        self.keys(table, "speed", SPEED_KEYS)
        if "body" not in table:
            raise self.fail("speed.body", "is missing: the input body whose speed the "
                                          "Campbell diagram's axis gives.")
        body = self.body_ref(table["body"], "speed.body")
        rotation = self.sense(table["rotation"], "speed.rotation") if "rotation" in table else 0
        rpm = (self.number(table["rpm"], "speed.rpm", "rpm", positive=True)
               if "rpm" in table else None)
        return Speed(body, rotation, rpm)

    def rotations(self, drive: GearDrive, meshes: list[Mesh]) -> list[Mesh]:
        """Each mesh's driving-gear sense of rotation, from [speed] through the shafts and
        meshes; a mesh's own `rotation` must agree. Six coordinates need it (the loaded
        flank sets the sign of the plane-of-action normal's radial part)."""
        from dataclasses import replace

        omega = drive.speed_ratios() if drive.speed and drive.speed.rotation else {}
        self.check_speed_loops(drive, omega)
        out = []
        for k, mesh in enumerate(meshes, 1):
            p = self.gears[mesh.driving]
            if p.body in omega:
                sense = 1 if dot(omega[p.body], self.bodies[p.body]["axis"]) > 0 else -1
                if mesh.rotation and mesh.rotation != sense:
                    word = "right" if mesh.rotation > 0 else "left"
                    raise self.fail(f"mesh.{k}.rotation", f"is \"{word}\", but [speed] makes gear "
                                                          f"\"{p.name}\" turn "
                                                          f"{'right' if sense > 0 else 'left'}"
                                                          f"-handed about its body's axis.")
                mesh = replace(mesh, rotation=sense)
            elif not mesh.rotation and not self.torsional:
                raise self.fail(f"mesh.{k}.rotation", "is missing: the loaded flank (the sign of "
                                                      "the plane of action's radial part) follows "
                                                      "the driving gear's sense of rotation; give "
                                                      "\"right\" or \"left\" here, or [speed] body "
                                                      "and rotation.")
            out.append(mesh)
        return out

    def check_train(self, shafts: tuple[Shaft, ...], elements: tuple, meshes: list[Mesh]
                    ) -> None:
        """The train can turn: every closed loop of shafts, elements and meshes gives each
        body one speed (ratios multiply to 1 around it), whatever else the file holds.
        A mesh between two bodies that shafts already join, or a loop of meshes whose
        ratios disagree, locks the drive: refused naming the element that closes the
        loop (in the file's order: shafts, elements, meshes). Speeds are signed along
        each body's axis (a weighted union-find: body -> (parent, ratio to it))."""
        parent: dict[str, tuple[str, float]] = {}

        def root(body: str) -> tuple[str, float]:
            ratio = 1.0
            while body in parent:
                body, step = parent[body]
                ratio *= step
            return body, ratio

        def axis(body: str) -> Vector:
            return self.bodies[body]["axis"]

        joins = [(f"shaft.{k}", s.ends, "shaft", dot(axis(s.ends[0]), axis(s.ends[1])))
                 for k, s in enumerate(shafts, 1) if FRAME not in s.ends]
        joins += [(f"element.{k}", e.ends, "element", dot(axis(e.ends[0]), axis(e.ends[1])))
                  for k, e in enumerate(elements, 1) if FRAME not in e.ends]
        for k, mesh in enumerate(meshes, 1):
            p, r = self.gears[mesh.driving], self.gears[mesh.driven]
            joins.append((f"mesh.{k}", (p.body, r.body), "mesh",
                          -p.teeth / r.teeth * dot(axis(p.body), axis(r.body))))
        for key, (a, b), kind, ratio in joins:  # speed of b = ratio * speed of a
            (ra, sa), (rb, sb) = root(a), root(b)
            if ra != rb:
                parent[rb] = (ra, ratio * sa / sb)
                continue
            if math.isclose(ratio * sa, sb, rel_tol=1e-9):
                continue
            if kind == "mesh" and math.isclose(sb / sa, 1.0, rel_tol=1e-9):
                raise self.fail(key, f"joins bodies \"{a}\" and \"{b}\", which the drive's "
                                     f"other connections already make turn together (one shaft "
                                     f"line): the mesh locks the "
                                     f"drive (a gear pair turns its bodies in opposite senses). "
                                     f"Remove the mesh or the connection between them.")
            raise self.fail(key, f"closes a loop whose gear ratios disagree: around it body "
                                 f"\"{b}\" would turn at two speeds (the ratios multiply to "
                                 f"{_fmt(ratio * sa / sb)}, not 1), so the drive is locked. "
                                 f"Check the teeth of the loop's gears.")

    def check_speed_loops(self, drive: GearDrive, omega: dict[str, Vector]) -> None:
        """Around a closed loop of shafts and meshes the speeds must agree."""
        for k, mesh in enumerate(drive.meshes, 1):
            p, r = self.gears[mesh.driving], self.gears[mesh.driven]
            if p.body in omega and r.body in omega:
                want = tuple(-p.teeth / r.teeth * c for c in omega[p.body])
                if max(abs(a - b) for a, b in zip(want, omega[r.body])) > 1e-9 * max(
                        1.0, *[abs(c) for c in want]):
                    raise self.fail(f"mesh.{k}", f"closes a loop whose gear ratios disagree: "
                                                 f"body \"{r.body}\" would turn at two speeds.")

    def excitation(self, table: Any, key: str, taken: dict[str, str], meshes: list[Mesh]
                   ) -> Excitation:
        self.keys(table, key, EXCITATION_KEYS)
        number = key.split(".")[1]
        name = self.name_of(table, key, f"excitation{number}", taken)
        kind = self.required(table, "kind", key)
        if kind not in ("torque", "transmission_error"):
            raise self.fail(f"{key}.kind", f"must be \"torque\" (on a body) or "
                                           f"\"transmission_error\" (at a mesh), got "
                                           f"{_show(kind)}.", kind)
        wanted, other = ("body", "mesh") if kind == "torque" else ("mesh", "body")
        if other in table:
            raise self.fail(f"{key}.{other}", f"does not go with kind = \"{kind}\": give "
                                              f"`{wanted}`.")
        if wanted not in table:
            raise self.fail(f"{key}.{wanted}", f"is missing: the {wanted} the {kind.replace('_', ' ')} "
                                               f"acts on.")
        names = {m.name: m for m in meshes}
        if kind == "torque":
            target = self.body_ref(table["body"], f"{key}.body")
            amplitude = self.number(self.required(table, "amplitude", key), f"{key}.amplitude",
                                    "N·m", positive=True)
            teeth = None
        else:
            target = table["mesh"]
            if not isinstance(target, str) or target not in names:
                hint = suggest(target, set(names)) if isinstance(target, str) and names else ""
                raise self.fail(f"{key}.mesh", f"names no mesh: {_show(target)}.{hint}", target)
            driving = self.gears[names[target].driving]
            if driving.module is None:
                raise self.fail(f"{key}.mesh", "is a mesh without `module`: a transmission error "
                                               "[length] needs the gears' radii.")
            amplitude = self.length_of(self.required(table, "amplitude", key),
                                       f"{key}.amplitude", positive=True)
            teeth = driving.teeth
        phase = self.angle_of(table.get("phase", 0.0), f"{key}.phase")
        given = [k for k in ("order", "harmonic", "frequency") if k in table]
        if len(given) > 1:
            raise self.fail(f"{key}.{given[1]}", f"and `{given[0]}` both say where the excitation "
                                                 f"sits: give one of them.")
        order = frequency = None
        if "order" in table:
            order = self.number(table["order"], f"{key}.order", "-", positive=True)
        if "harmonic" in table:
            if teeth is None:
                raise self.fail(f"{key}.harmonic", "is for a transmission error (a harmonic of "
                                                   "the tooth-mesh frequency); a torque takes "
                                                   "`order`.")
            order = teeth * self.number(table["harmonic"], f"{key}.harmonic", "-", positive=True)
        if "frequency" in table:
            frequency = self.number(table["frequency"], f"{key}.frequency", "Hz", positive=True)
        return Excitation(name, kind, target, amplitude, phase, order, frequency)

