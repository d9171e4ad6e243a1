"""The topologies a synthesis sizes, each in a canonical frame (the crank's pivot at the
origin, the frame line along x): its dimensions by name, its mechanism file as data (for
the reader: numbers, or ``Variants`` for a block of candidates read at once), the
coupler point the path is traced by, and its coupler curve in closed form (for the local
least-squares fit; the search traces it through dyade's engine).

A result is placed in the world by a similarity: x_world = x0 + s·e^{iθ}·x, the crank
angle φ_world = φ + θ (``Placement``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np

from dyade.arrays import FloatArray
from dyade.synthesis.closed import rrr

COUPLER = 3
"""the coupler's link number (links: 1 frame, 2 crank, 3 coupler, 4 rocker or slider)"""


@dataclass(frozen=True, slots=True)
class Placement:
    """Where a canonical linkage stands: x_world = origin + scale·e^{iθ}·x."""

    origin: complex = 0j
    """the crank's pivot [m]"""
    scale: float = 1.0
    """[-]"""
    angle: float = 0.0
    """θ, the frame line's direction [rad]"""

    def apply(self, z):
        return self.origin + self.scale * np.exp(1j * self.angle) * z


class Topology(ABC):
    """What a topology gives a synthesis (subclasses: ``FourBar``, ``SliderCrank``)."""

    name: str
    names: tuple[str, ...]
    """the canonical dimensions [m]"""
    defaults: dict[str, tuple[float, float]]
    """default bounds of each dimension [m], for a frame of about 1"""
    coupler: int = COUPLER
    """the link that carries the coupler point P"""
    variants: tuple[int, ...] = (1, -1)
    """the assembly variants a search draws (``dyad_variants`` spells each out)"""

    def dyad_variants(self, variant: int) -> tuple[int, ...]:
        """Each dyad's assembly variant (+1/−1) of a topology's ``variant``."""
        return (int(variant),)

    @abstractmethod
    def data(self, values: dict[str, Any], variant: int, placement: Placement = Placement(),
             speed_rpm: float = 60.0, masses: dict | None = None,
             sweep: tuple[float, float, float] = (0.0, 360.0, 1.0), name: str = "") -> dict:
        """The mechanism file's data of one candidate (numbers, or ``Variants`` for a
        block) placed by ``placement``."""

    @abstractmethod
    def path(self, values: FloatArray, variant: int, crank: FloatArray) -> np.ndarray:
        """(candidates, positions) complex: the coupler point in the canonical frame at
        the crank angles ``crank`` [rad], in closed form; NaN where it does not close."""

    def named(self, values) -> dict[str, Any]:
        """Dimensions by name: a dict as it is, a sequence in ``names``' order as floats."""
        if isinstance(values, dict):
            return values
        return dict(zip(self.names, (float(v) for v in values)))

    @abstractmethod
    def turns(self, values: FloatArray) -> FloatArray:
        """(candidates,) bool: the crank can turn fully (Grashof), for each row of values."""


def bar(length, per_length: float | None, each: float | None) -> dict:
    """Mass data of a bar of ``length`` [m] from its end at the link's origin along ξ:
    mass per length [kg/m] or a mass each [kg], centre mid-way, J = m·l²/12."""
    mass = each if each is not None else per_length * abs(length)
    return {"mass": mass, "centre": [0.5 * length, 0.0], "inertia": mass * length * length / 12.0}


class FourBar(Topology):
    """The four-bar A0–A–B–B0: crank a, coupler b (A→B), rocker c (B0→B), frame d (A0→B0
    along x), the coupler point (p, q) in the coupler's frame (origin A, ξ towards B)."""

    name = "fourbar"
    names = ("a", "b", "c", "d", "p", "q")
    defaults = {"a": (0.1, 1.0), "b": (0.3, 3.0), "c": (0.3, 3.0), "d": (1.0, 1.0),
                "p": (-2.0, 2.0), "q": (-2.0, 2.0)}

    def data(self, values, variant, placement=Placement(), speed_rpm=60.0, masses=None,
             sweep=(0.0, 360.0, 1.0), name="") -> dict:
        values = self.named(values)
        s, turn = placement.scale, np.exp(1j * placement.angle)
        a, b, c, d, p, q = (values[k] for k in self.names)
        b0 = placement.origin + s * d * turn
        if isinstance(d, np.ndarray):
            b0x, b0y = b0.real, b0.imag
        else:
            b0x, b0y = float(b0.real), float(b0.imag)
        data = {"name": name or "Four-bar (synthesised)", "units": {"length": "m", "angle": "deg"},
                "sweep": {"start": sweep[0], "stop": sweep[1], "step": sweep[2]},
                "frame": {"points": {"A0": [placement.origin.real, placement.origin.imag],
                                     "B0": [b0x, b0y]}},
                "crank": {"pivot": "A0", "length": s * a, "speed_rpm": speed_rpm},
                "dyad": [{"kind": "RRR", "links": [3, 4], "A": {"link": 2, "point": "tip"},
                          "C": {"link": 1, "point": "B0"}, "lengths": [s * b, s * c],
                          "variant": int(variant)}],
                "links": {"3": {"points": {"P": [s * p, s * q]}}}}
        if masses:
            per, each = masses.get("per_length"), masses.get("each")
            data["links"]["2"] = bar(s * a, per, each)
            data["links"]["3"].update(bar(s * b, per, each))
            data["links"]["4"] = bar(s * c, per, each)
        return data

    def path(self, values, variant, crank):
        """(candidates, positions) complex: the coupler point in the canonical frame."""
        values = np.atleast_2d(values)
        a, b, c, d, p, q = (values[:, k, None] for k in range(6))
        ax, ay = a * np.cos(crank), a * np.sin(crank)
        bx, by = rrr(ax, ay, d, 0.0 * d, b, c, variant)
        ex, ey = (bx - ax) / b, (by - ay) / b
        return (ax + ex * p - ey * q) + 1j * (ay + ey * p + ex * q)

    def turns(self, values):
        a, b, c, d = (np.abs(values[:, k]) for k in range(4))
        lengths = np.sort(np.column_stack([a, b, c, d]), axis=1)
        grashof = lengths[:, 0] + lengths[:, 3] <= lengths[:, 1] + lengths[:, 2]
        return grashof & (lengths[:, 0] == np.minimum(a, d))  # crank or frame the shortest


class SliderCrank(Topology):
    """The slider-crank: crank a, conrod b (A→B), the guide along x at offset e (through
    (0, e)), the coupler point (p, q) in the conrod's frame (origin A, ξ towards B)."""

    name = "slider-crank"
    names = ("a", "b", "e", "p", "q")
    defaults = {"a": (0.1, 1.0), "b": (0.3, 3.0), "e": (-1.0, 1.0), "p": (-2.0, 2.0),
                "q": (-2.0, 2.0)}

    def data(self, values, variant, placement=Placement(), speed_rpm=60.0, masses=None,
             sweep=(0.0, 360.0, 1.0), name="") -> dict:
        values = self.named(values)
        s = placement.scale
        a, b, e, p, q = (values[k] for k in self.names)
        turn = np.exp(1j * placement.angle)
        through = placement.origin + s * 1j * turn * e
        if isinstance(e, np.ndarray):
            gx, gy = through.real, through.imag
        else:
            gx, gy = float(through.real), float(through.imag)
        data = {"name": name or "Slider-crank (synthesised)",
                "units": {"length": "m", "angle": "deg"},
                "sweep": {"start": sweep[0], "stop": sweep[1], "step": sweep[2]},
                "frame": {"points": {"A0": [placement.origin.real, placement.origin.imag]}},
                "crank": {"pivot": "A0", "length": s * a, "speed_rpm": speed_rpm},
                "dyad": [{"kind": "RRP", "links": [3, 4], "A": {"link": 2, "point": "tip"},
                          "C": {"link": 1, "point": [gx, gy],
                                "angle": float(np.rad2deg(placement.angle))},
                          "length": s * b, "variant": int(variant)}],
                "links": {"3": {"points": {"P": [s * p, s * q]}}}}
        if masses:
            per, each = masses.get("per_length"), masses.get("each")
            data["links"]["2"] = bar(s * a, per, each)
            data["links"]["3"].update(bar(s * b, per, each))
            data["links"]["4"] = {"mass": each if each is not None else per * s * b * 0.25}
        return data

    def path(self, values, variant, crank):
        values = np.atleast_2d(values)
        a, b, e, p, q = (values[:, k, None] for k in range(5))
        ax, ay = a * np.cos(crank), a * np.sin(crank)
        with np.errstate(invalid="ignore"):
            run = np.sqrt(b * b - (e - ay) ** 2)
        bx, by = ax + (run if variant > 0 else -run), e + 0.0 * ay
        ex, ey = (bx - ax) / b, (by - ay) / b
        return (ax + ex * p - ey * q) + 1j * (ay + ey * p + ex * q)

    def turns(self, values):
        a, b, e = np.abs(values[:, 0]), np.abs(values[:, 1]), values[:, 2]
        return b > a + np.abs(e)


class SixBar(Topology):
    """The six-bars made of two RRR dyads as dyade assembles them: the four-bar
    A0–A–B–B0 (a, b, c, d as ``FourBar``), then a second dyad E–F–G of lengths f
    (E–F) and g (G–F) from a point E of one of the four-bar's moving links to a point G
    of the frame or of another link, (gx, gy) in that link's frame (the frame's: the
    canonical one); the coupler point P = (p, q) on the second coupler E–F (origin E,
    ξ towards F). Links: 1 frame, 2 crank (origin A0, ξ towards A), 3 coupler (origin
    A, ξ towards B), 4 rocker (origin B0, ξ towards B), 5 second coupler, 6 the second
    dyad's other link. The chains (``CHAINS``):

    - Watt II: E on the rocker, G on the frame (the frame and the rocker ternary,
      adjacent at B0);
    - Stephenson III: E on the coupler, G on the frame (the frame and the coupler
      ternary, apart);
    - Watt I: E on the coupler, G on the rocker (the two ternaries adjacent at B, the
      frame binary);
    - Stephenson I: E on the crank, G on the rocker (the ternary crank and rocker
      apart, joined by the binary frame and coupler).

    Stephenson II (the frame a binary of the chain's two-link path between its
    ternaries) has no crank whose remaining links split into two dyads: it needs a
    triad, which dyade does not assemble.

    ``variant`` 1…4 spells the two dyads' assembly variants: (+1, +1), (+1, −1),
    (−1, +1), (−1, −1)."""

    names = ("a", "b", "c", "d", "ex", "ey", "gx", "gy", "f", "g", "p", "q")
    coupler = 5
    variants = (1, 2, 3, 4)
    SPELLED = {1: (1, 1), 2: (1, -1), 3: (-1, 1), 4: (-1, -1)}
    CHAINS = {"watt": (4, 1, "Watt II"), "stephenson": (3, 1, "Stephenson III"),
              "watt1": (3, 4, "Watt I"), "stephenson1": (2, 4, "Stephenson I")}
    """chain -> (the link that carries E, the one that carries G, its name)"""

    def __init__(self, chain: str) -> None:
        self.chain = chain
        self.name = f"{chain}-sixbar"
        self.carrier, self.anchor, self.title = self.CHAINS[chain]
        """the links that carry E and G"""
        self.defaults = {"a": (0.1, 1.0), "b": (0.3, 3.0), "c": (0.3, 3.0), "d": (1.0, 1.0),
                         "ex": (-1.5, 1.5), "ey": (-1.5, 1.5),
                         "gx": (-1.0, 2.0) if self.anchor == 1 else (-1.5, 1.5),
                         "gy": (-1.5, 1.5), "f": (0.3, 3.0), "g": (0.3, 3.0),
                         "p": (-2.0, 2.0), "q": (-2.0, 2.0)}

    def dyad_variants(self, variant):
        return self.SPELLED[int(variant)]

    def data(self, values, variant, placement=Placement(), speed_rpm=60.0, masses=None,
             sweep=(0.0, 360.0, 1.0), name="") -> dict:
        values = self.named(values)
        first, second = self.dyad_variants(variant)
        four = FourBar().data({k: values[k] for k in FourBar.names[:4]} | {"p": 0.0, "q": 0.0},
                              first, placement, speed_rpm, masses, sweep, name)
        s, turn = placement.scale, np.exp(1j * placement.angle)
        links = four["links"]
        if self.anchor == 1:  # G a frame pivot, placed in the world
            d0 = placement.origin + s * turn * (values["gx"] + 1j * values["gy"])
            if isinstance(values["gx"], np.ndarray) or isinstance(values["gy"], np.ndarray):
                four["frame"]["points"]["D0"] = [d0.real, d0.imag]
            else:
                four["frame"]["points"]["D0"] = [float(d0.real), float(d0.imag)]
            end = {"link": 1, "point": "D0"}
        else:  # G on a moving link, in its frame
            links.setdefault(str(self.anchor), {}).setdefault("points", {})["G"] = [
                s * values["gx"], s * values["gy"]]
            end = {"link": self.anchor, "point": "G"}
        four["name"] = name or f"{self.title} six-bar (synthesised)"
        four["dyad"].append({"kind": "RRR", "links": [5, 6],
                             "A": {"link": self.carrier, "point": "E"}, "C": end,
                             "lengths": [s * values["f"], s * values["g"]],
                             "variant": int(second)})
        links["3"] = {k: v for k, v in links["3"].items() if k != "points"}
        links.setdefault(str(self.carrier), {}).setdefault("points", {})["E"] = [
            s * values["ex"], s * values["ey"]]
        links["5"] = {"points": {"P": [s * values["p"], s * values["q"]]}}
        if masses:
            per, each = masses.get("per_length"), masses.get("each")
            links["5"].update(bar(s * values["f"], per, each))
            links["6"] = bar(s * values["g"], per, each)
        if not links["3"]:
            del links["3"]
        return four

    def path(self, values, variant, crank):
        return self.joints(values, variant, crank)[3]

    def joints(self, values, variant, crank):
        """(E, F, G, P), each (candidates, positions) complex [m] in the canonical frame at
        the crank angles ``crank`` [rad], in closed form (NaN where it does not close):
        the second dyad's joints (E on link 5, F joining links 5 and 6, G on link 6) and
        the coupler point P. Link 5's angle is that of F − E, link 6's that of F − G."""
        return self.loops(values, variant, crank)[2:]

    def transmission(self, values, variant, crank, loops=None):
        """(candidates, positions) the smaller of the two dyads' transmission angles μ
        [rad], each folded to [0, π/2] (dyade's ``mu_N_min_deg``): the first dyad's at B
        (between the coupler A–B and the rocker B0–B), the second's at F (between E–F and
        G–F); NaN where the six-bar does not close. ``loops``: the six-bar's ``loops``
        there, where the caller has them."""
        a, b, e, f, g, _ = self.loops(values, variant, crank) if loops is None else loops
        values = np.atleast_2d(values)
        lengths = values[:, [1, 2, 8, 9], None]
        first = np.abs(((b - a).conjugate() * (b - values[:, 3, None])).imag)
        second = np.abs(((f - e).conjugate() * (f - g)).imag)
        with np.errstate(invalid="ignore"):
            sin = np.minimum(first / (lengths[:, 0] * lengths[:, 1]),
                             second / (lengths[:, 2] * lengths[:, 3]))
            return np.arcsin(np.clip(sin, 0.0, 1.0))

    def loops(self, values, variant, crank):
        """(A, B, E, F, G, P): the joints of both loops, each (candidates, positions)
        complex [m] in the canonical frame (``joints``), in closed form."""
        values = np.atleast_2d(values)
        a, b, c, d, ex, ey, gx, gy, f, g, p, q = (values[:, k, None] for k in range(12))
        first, second = self.dyad_variants(variant)
        ax, ay = a * np.cos(crank), a * np.sin(crank)
        bx, by = rrr(ax, ay, d, 0.0 * d, b, c, first)
        frames = {2: (0.0 * ax, 0.0 * ay, ax / a, ay / a),  # origin, ξ of each moving link
                  3: (ax, ay, (bx - ax) / b, (by - ay) / b),
                  4: (d + 0.0 * bx, 0.0 * by, (bx - d) / c, by / c)}

        def at(link, x, y):
            if link == 1:
                return x + 0.0 * ax, y + 0.0 * ay
            ox, oy, ux, uy = frames[link]
            return ox + ux * x - uy * y, oy + uy * x + ux * y

        px, py = at(self.carrier, ex, ey)
        hx, hy = at(self.anchor, gx, gy)
        fx, fy = rrr(px, py, hx, hy, f, g, second)
        vx, vy = (fx - px) / f, (fy - py) / f
        return (ax + 1j * ay, bx + 1j * by, px + 1j * py, fx + 1j * fy, hx + 1j * hy,
                (px + vx * p - vy * q) + 1j * (py + vy * p + vx * q))

    def turns(self, values):
        return FourBar().turns(values[:, :4])


TOPOLOGIES = {"fourbar": FourBar(), "slider-crank": SliderCrank(),
              **{f"{chain}-sixbar": SixBar(chain) for chain in SixBar.CHAINS}}
"""name -> topology"""


def fourbar_from_points(a0: complex, a: complex, b: complex, b0: complex, p: complex
                        ) -> tuple[FloatArray, int, Placement, float]:
    """A four-bar given by its pivots and coupler point at one position (complex [m]):
    (canonical dimensions (a, b, c, d, p, q) [m], assembly variant, placement, the crank
    angle of that position in the canonical frame [rad])."""
    theta = float(np.angle(b0 - a0))
    turn = np.exp(-1j * theta)
    ca, cb, cb0 = (a - a0) * turn, (b - a0) * turn, (b0 - a0) * turn
    unit = (cb - ca) / abs(cb - ca)
    local = ((p - a0) * turn - ca) / unit
    values = np.array([abs(ca), abs(cb - ca), abs(cb - cb0), abs(cb0), local.real, local.imag])
    side = ((cb0 - ca).conjugate() * (cb - ca)).imag  # (B0 − A) × (B − A)
    return values, 1 if side > 0 else -1, Placement(complex(a0), 1.0, theta), float(np.angle(ca))
