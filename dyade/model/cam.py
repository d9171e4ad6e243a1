"""A disc cam and its follower (a cam file, ``[cam]``), SI: the data, checked on their
own. The cam's curves, checks and forces are computed by ``dyade.cam``; the follower's
motion is a motion profile (``dyade.model.profile``) over the cam angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from dyade.errors import InputError

FOLLOWERS = ("translating-roller", "oscillating-roller", "translating-flat")
"""the follower kinds (``dyade.cam.geometry.FOLLOWERS``)"""
CLOSURES = ("spring", "groove")
"""force closure by a spring; form closure by a grooved cam (or a conjugate pair)"""
PRESSURE_ANGLE_MAX = {"translating-roller": math.radians(30.0),
                      "oscillating-roller": math.radians(45.0),
                      "translating-flat": math.radians(30.0)}
"""the designers' limits of |α| [rad] by follower kind (VDI 2142: 30° for a translating
follower, 45° for an oscillating one), used where the file gives none"""
CHORD_TOLERANCE_MIN = 1e-7  # [m] a finer exported profile is not made (and would be huge)
STEEL = (210e9, 0.3)  # [Pa], [-] Young's modulus and Poisson's ratio of steel


@dataclass(frozen=True)
class Cam:
    """A disc cam on a shaft turning at a constant speed, with its follower (SI).

    Frame and senses: ``dyade.cam.geometry``; the follower's coordinate is its lift [m]
    (translating) or its swing [rad] (oscillating), given by ``profile`` over the cam
    angle (one period: a whole turn).
    """

    follower: str
    """one of ``FOLLOWERS``"""
    base_radius: float
    """base circle radius r_b [m] (of the working curve)"""
    profile: Any
    """the follower's motion: a ``dyade.model.profile.Profile`` over the cam angle
    [rad] (its output [m] or [rad])"""
    speed: float
    """cam speed ω [rad/s], constant (magnitude; ``clockwise`` gives the sense)"""
    roller_radius: float = 0.0
    """r_r [m] (0 for a flat face)"""
    offset: float = 0.0
    """e [m]: the translating follower's line of motion x = e"""
    pivot_distance: float = 0.0
    """a = |OA| [m] (oscillating)"""
    arm_length: float = 0.0
    """l = |AC| [m] (oscillating)"""
    clockwise: bool = False
    """the cam turns clockwise (the mirror image of the counter-clockwise cam)"""
    closure: str = "spring"
    """one of ``CLOSURES``"""
    mass: float = 0.0
    """the follower's mass [kg] (oscillating: moment of inertia about the pivot [kg·m²])"""
    stiffness: float = 0.0
    """spring stiffness [N/m] (oscillating: [N·m/rad])"""
    preload: float = 0.0
    """the spring's compression at zero lift [m] (oscillating: [rad]); its force
    k·(s + s0)"""
    load: float = 0.0
    """a constant force pressing the follower onto the cam [N] (oscillating: moment
    [N·m]); gravity belongs here"""
    guide_friction: float = 0.0
    """μ [-] of a translating follower's guide (0: none; ``dyade.cam.guide``)"""
    guide_length: float | None = None
    """L [m], the guide's length between its two bearing points"""
    guide_overhang: float = 0.0
    """b [m], from the roller centre (flat face: the face) to the guide's near end at
    zero lift"""
    pressure_angle_max: float | None = None
    """the limit of |α| [rad]; None: ``PRESSURE_ANGLE_MAX`` of the kind"""
    width: float | None = None
    """contact length [m] for the Hertz stress (None: not computed)"""
    cam_material: tuple[float, float] = STEEL
    """(E [Pa], ν [-]) of the cam"""
    follower_material: tuple[float, float] = STEEL
    """(E [Pa], ν [-]) of the roller or face"""
    chord_tolerance: float = 1e-5
    """chord tolerance of the exported profile [m]"""
    cutter_radius: float | None = None
    """radius of the cutter [m] whose path is exported too (None: none)"""
    chain: Any = None
    """a ``dyade.model.mechanism.Mechanism`` whose crank (link 2) is the follower's lever
    (oscillating follower) or, with its own ``cam`` (a mechanism file's ``[cam]``), whose
    link 2 is this follower: the linkage the cam drives (None: the follower alone)"""
    chain_centre: tuple[float, float] | None = None
    """the cam centre O [m] in the chain's frame"""
    name: str = "cam"
    length_unit: str = "mm"
    """the file's length unit (tables and the exported profile)"""
    angle_unit: str = "deg"
    source: str | None = None
    """the file it was read from"""
    keys: dict[str, str] = field(default_factory=dict)
    """parameter -> the file's key, for messages"""

    def __post_init__(self) -> None:
        def fail(name: str, reason: str, value: Any = None) -> InputError:
            err = InputError.parameter(name, reason, value=value)
            return err.naming(self.keys) if self.keys else err

        if self.follower not in FOLLOWERS:
            raise fail("follower", f"must be one of {', '.join(FOLLOWERS)}, got "
                                   f"{self.follower!r}.", self.follower)
        if self.closure not in CLOSURES:
            raise fail("closure", f"must be one of {', '.join(CLOSURES)}, got "
                                  f"{self.closure!r}.", self.closure)
        if self.closure == "groove" and self.follower == "translating-flat":
            raise fail("closure", "= \"groove\" needs a roller follower: a roller runs in "
                                  "a groove, a flat face does not (hold it on by a spring, "
                                  "closure = \"spring\").", self.closure)
        if not self.base_radius > 0.0:
            raise fail("base_radius", f"must be positive [m], got {self.base_radius:g}.")
        if self.follower == "translating-flat":
            if self.roller_radius:
                raise fail("roller_radius", "is not a key of a flat-faced follower: a flat "
                                            "face has no roller (leave it out).")
        elif not self.roller_radius > 0.0:
            raise fail("roller_radius", f"must be positive [m] for a {self.follower} "
                                        f"follower, got {self.roller_radius:g}.")
        pitch = self.base_radius + self.roller_radius
        if self.follower == "translating-roller" and not abs(self.offset) < pitch:
            raise fail("offset", f"must be less than the pitch radius r_b + r_r = {pitch:g} m "
                                 f"in size, got {self.offset:g} m.")
        if self.follower == "oscillating-roller":
            a, length = self.pivot_distance, self.arm_length
            if not (a > 0.0 and length > 0.0):
                raise fail("pivot_distance", "and the arm length must be given and positive "
                                             "for an oscillating follower.")
            if not abs(a - length) < pitch < a + length:
                raise fail("arm_length", f"cannot put the roller on the pitch circle r_b + r_r "
                                         f"= {pitch:g} m from the pivot {a:g} m away: |a − l| "
                                         f"< r_b + r_r < a + l is needed (l = {length:g} m).")
        if self.mass < 0.0 or self.stiffness < 0.0:
            raise fail("mass", "and the spring stiffness must not be negative.")
        if not self.speed >= 0.0:
            raise fail("speed", f"must not be negative [rad/s], got {self.speed:g}.")
        if not self.chord_tolerance >= CHORD_TOLERANCE_MIN:
            raise fail("chord_tolerance", f"must be at least {CHORD_TOLERANCE_MIN:g} m (0.1 µm, "
                                          f"finer than any machine tool cuts), got "
                                          f"{self.chord_tolerance:g} m.")
        if self.pressure_angle_max is not None and not (
                0.0 < self.pressure_angle_max < math.pi / 2):
            raise fail("pressure_angle_max", f"must lie between 0° and 90° (a limit of |α|; "
                                             f"30° for a translating follower, 45° for an "
                                             f"oscillating one are usual), got "
                                             f"{math.degrees(self.pressure_angle_max):g}°.",
                       math.degrees(self.pressure_angle_max))
        if self.width is not None and not self.width > 0.0:
            raise fail("width", f"must be positive [m], got {self.width:g}.")
        if not self.guide_friction >= 0.0:
            raise fail("guide_friction", f"must not be negative [-], got "
                                         f"{self.guide_friction:g}.", self.guide_friction)
        if self.guide_friction > 0.0:
            if self.follower == "oscillating-roller":
                raise fail("guide_friction", "belongs to a translating follower's guide: an "
                                             "oscillating follower turns about its pivot.")
            if self.guide_length is None or not self.guide_length > 0.0:
                raise fail("guide_length", "is needed with guide friction: the guide's "
                                           "length L [length] between its bearing points.")
            if not self.guide_overhang >= 0.0:
                raise fail("guide_overhang", f"must not be negative [m] (the roller centre "
                                             f"below the guide's near end at zero lift), got "
                                             f"{self.guide_overhang:g}.")
        self.check_profile(fail)
        if self.chain is not None and self.chain.cam is None:  # a cam file's [chain]
            if self.follower != "oscillating-roller":
                raise fail("chain", f"needs an oscillating roller follower (its lever is the "
                                    f"chain's crank), got a {self.follower} follower.")
            if self.chain_centre is None:
                raise fail("chain_centre", "is missing: the cam centre in the chain's frame.")
            crank = self.chain.crank
            distance = math.dist(crank.pivot, self.chain_centre)
            if abs(distance - self.pivot_distance) > 1e-9 * self.pivot_distance:
                raise fail("chain_centre", f"puts the cam centre {distance:.6g} m from the "
                                           f"chain's crank pivot, which is the follower's "
                                           f"pivot: `follower.pivot_distance` says "
                                           f"{self.pivot_distance:.6g} m. Move one or the "
                                           f"other.")
            if abs(crank.length - self.arm_length) > 1e-9 * self.arm_length:
                raise fail("arm_length", f"= {self.arm_length:.6g} m differs from the chain's "
                                         f"crank length {crank.length:.6g} m (the crank is "
                                         f"the lever).")

    def check_profile(self, fail) -> None:
        """A cam's profile runs over the cam angle, one whole turn, and comes back to where
        it started (a cam cannot advance per turn); its output is a length for a
        translating follower, an angle for an oscillating one."""
        profile = self.profile
        if profile is None:
            raise fail("profile", "is missing: a cam needs its follower's motion (a "
                                  "[profile] table).")
        if profile.master != "angle":
            raise fail("profile.master", f"must be \"angle\" for a cam (the cam angle), got "
                                         f"{profile.master!r}.", profile.master)
        if abs(profile.period - 2.0 * math.pi) > 1e-9:
            raise fail("profile.period", f"must be one turn (360°) for a disc cam, got "
                                         f"{math.degrees(profile.period):g}°.",
                       math.degrees(profile.period))
        wanted = "angle" if self.follower == "oscillating-roller" else "length"
        if profile.output != wanted:
            raise fail("profile.unit", f"must be {'an angle (deg, rad)' if wanted == 'angle' else 'a length (m, cm, mm, um)'} "
                                       f"for a {self.follower} follower, got "
                                       f"{profile.unit!r}.", profile.unit)
        scale = max(max(abs(s.lift_from), abs(s.lift_to)) for s in profile.segments) or 1.0
        if abs(profile.advance) > 1e-9 * scale:
            from dyade.units import ANGLE_FACTORS, LENGTH_FACTORS

            size = LENGTH_FACTORS.get(profile.unit) or ANGLE_FACTORS[profile.unit]
            last = len(profile.segments)
            raise fail(f"profile.segment.{last}.to",
                       f"= {profile.segments[-1].lift_to / size:g} {profile.unit} does not come "
                       f"back to where the turn starts ({profile.segments[0].lift_from / size:g} "
                       f"{profile.unit}): the law does not close over the cycle, and a disc "
                       f"cam repeats every turn. End the last segment where the first starts.")
        if min(s.lift_from for s in profile.segments) < -1e-12 * scale:
            raise fail("profile", "goes below 0: a cam's lift is measured from the base "
                                  "circle (s ≥ 0); shift the profile up.")

    @property
    def pitch_radius(self) -> float:
        """r_p = r_b + r_r [m]"""
        return self.base_radius + self.roller_radius

    @property
    def limit(self) -> float:
        """The pressure-angle limit [rad] in force."""
        return (PRESSURE_ANGLE_MAX[self.follower] if self.pressure_angle_max is None
                else self.pressure_angle_max)

    @property
    def lever(self) -> float:
        """The follower's lever h [m]: 1 translating, the arm length oscillating."""
        return self.arm_length if self.follower == "oscillating-roller" else 1.0


@dataclass(frozen=True)
class CamDrive:
    """A disc cam that drives link 2 of a mechanism (a mechanism file's ``[cam]``): the
    follower is link 2, the chain's input (``dyade.model.mechanism.Crank``).

    The cam's fixed frame (``dyade.cam.geometry``: a translating follower moving along
    +y on the line x = e, an oscillating one's pivot at (a, 0), (−a, 0) for a clockwise
    cam) is turned by ``angle`` β about the cam centre ``centre`` into the mechanism's
    frame. A translating follower slides (link 2's origin is the roller centre, the flat
    face's point on its line of motion; its ξ axis along the motion); an oscillating one
    turns about its pivot (link 2 the lever, its ``tip`` the roller centre). The sweep
    runs over the cam angle θ, the cam turning at ``cam.speed`` in its own sense.
    """

    cam: Cam
    """the cam and its follower (``follower.mass`` is link 2's, in its ``[links.2]``)"""
    centre: tuple[float, float]
    """the cam centre O [m] in the mechanism's frame"""
    angle: float = 0.0
    """β [rad]: the cam's fixed frame in the mechanism's frame"""

    @property
    def sliding(self) -> bool:
        """The follower translates: link 2 slides along a frame guide."""
        return self.cam.follower != "oscillating-roller"

    def turn(self, v) -> tuple[float, float]:
        """A vector (x, y) of the cam's fixed frame in the mechanism's frame: R(β)·v."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        return (c * v[0] - s * v[1], s * v[0] + c * v[1])

    def place(self, v) -> tuple[float, float]:
        """A point of the cam's fixed frame in the mechanism's frame: O + R(β)·v [m]."""
        x, y = self.turn(v)
        return (self.centre[0] + x, self.centre[1] + y)

    @property
    def pivot(self) -> tuple[float, float]:
        """Link 2's pivot [m] in the mechanism's frame: the lever's pivot A, or the
        follower's origin (roller centre, face point) at zero lift."""
        cam, sense = self.cam, -1.0 if self.cam.clockwise else 1.0
        if cam.follower == "oscillating-roller":
            return self.place((sense * cam.pivot_distance, 0.0))
        # the line of motion is x = e for either sense (a clockwise cam mirrors the cam,
        # e -> −e, and then every curve, x -> −x)
        if cam.follower == "translating-roller":
            pitch = cam.pitch_radius
            return self.place((cam.offset, math.sqrt(pitch ** 2 - cam.offset ** 2)))
        return self.place((cam.offset, cam.base_radius))

    @property
    def guide(self) -> float | None:
        """The follower's guide angle γ [rad] in the mechanism's frame (translating), or
        None (oscillating)."""
        return self.angle + 0.5 * math.pi if self.sliding else None
