"""The dyads of a mechanism file: the [[dyad]] tables, their kind, links and outer joints
A and C, and each kind's own keys and middle joint B (the file syntax of the kinds; their
data are ``dyade.model.dyad_kinds``, their closures ``dyade.linkage.dyads``)."""

from __future__ import annotations

import math
from typing import Any, Callable

from dyade.files.mechanism.links import LinkReader
from dyade.files.schema import show
from dyade.model import dyad_kinds
from dyade.model.dyad_kinds import DyadKind
from dyade.model.mechanism import Dyad, Prismatic, Revolute

DYAD_KEYS_COMMON = {"kind", "links", "A", "B", "C", "variant", "name"}
MIDDLE_R_KEYS = {"pin_radius", "friction", "clearance"}
MIDDLE_P_KEYS = {"guide", "offset", "angle", "point", "slider_length", "slider_height",
                 "friction", "edge_friction"}


class DyadReader(LinkReader):
    """Reads the [[dyad]] tables: each kind's keys and joint B by ``MIDDLE``."""

    def dyad(self, table: Any, number: int) -> Dyad:
        key = f"dyad.{number}"
        if not isinstance(table, dict):
            raise self.fail(key, f"must be a table, got {show(table)}.")
        kind = self.kind(self.required(table, "kind", key), f"{key}.kind")
        keys, middle = MIDDLE[kind.name]
        self.keys(table, key, DYAD_KEYS_COMMON | keys)
        links = self.required(table, "links", key)
        if (not isinstance(links, list) or len(links) != 2
                or any(isinstance(v, bool) or not isinstance(v, int) for v in links)):
            raise self.fail(f"{key}.links", f"must be two link numbers [i, j], got {show(links)}.")
        i, j = links
        for link in (i, j):
            if link in self.placed:
                raise self.fail(f"{key}.links", f"uses link {link} again; every dyad places two "
                                                f"new links (placed: "
                                                f"{', '.join(map(str, self.placed))}).")
        if i == j or i < 3 or j < 3:
            raise self.fail(f"{key}.links", f"must be two different new link numbers above 2, "
                                            f"got {show(links)}.")
        if kind.has_variant:
            variant = self.integer(table.get("variant", 1), f"{key}.variant")
            if variant not in (1, -1):
                raise self.fail(f"{key}.variant", f"must be +1 or -1 (assembly variant), "
                                                  f"got {variant}.")
        else:
            if "variant" in table:
                raise self.fail(f"{key}.variant", f"is not used by kind {kind.number} "
                                                  f"({kind.name}): it has one closure only.")
            variant = 0
        pattern = kind.name
        for letter, joint_kind in zip("ABC", pattern):
            if letter == "B":
                continue
            if letter not in table:
                raise self.fail(f"{key}.{letter}", "is missing: say which placed link and point "
                                                   f"joint {letter} attaches to.")
        g = h = 0
        if pattern[0] == "R":
            g, joint_a = self.revolute(table["A"], f"{key}.A", i)
        else:
            g, joint_a = self.outer_prismatic(table["A"], f"{key}.A", i)
        if pattern[2] == "R":
            h, joint_c = self.revolute(table["C"], f"{key}.C", j)
        else:
            h, joint_c = self.outer_prismatic(table["C"], f"{key}.C", j)
        b_table = table.get("B", {})
        joint_b = middle(self, b_table, f"{key}.B", i, j, table, key)
        self.placed.extend((i, j))
        return Dyad(number, kind, (i, j), (g, h), (joint_a, joint_b, joint_c), variant)

    def kind(self, value: Any, key: str) -> DyadKind:
        kind = dyad_kinds.named(value)
        if kind is None:
            names = ", ".join(name.upper() for name in dyad_kinds.REGISTRY)
            raise self.fail(key, f"must be 1-{len(dyad_kinds.REGISTRY)} or one of {names}, "
                                 f"got {show(value)}.", value)
        return kind

    def middle_revolute(self, table: Any, key: str) -> dict[str, Any]:
        """The keys of a revolute joint B: its friction and clearance data."""
        self.keys(table, key, MIDDLE_R_KEYS)
        return self.revolute_friction(table, key)

    def middle_prismatic(self, table: Any, key: str, point: bool) -> tuple[float, dict[str, Any]]:
        """The common keys of a prismatic joint B: its offset [m] and friction data;
        ``point``: the kind also takes the guide's `point` and `angle`."""
        self.keys(table, key, MIDDLE_P_KEYS if point else MIDDLE_P_KEYS - {"angle", "point"})
        return self.length_of(table.get("offset", 0.0), f"{key}.offset"), \
            self.prismatic_friction(table, key)


# -- the kinds' own keys and joint B ----------------------------------------------------
# middle(reader, table, key, i, j, dyad_table, dyad_key) -> Joint: joint B of a dyad of
# links i and j from its table ``B`` (key path ``key``) and the dyad's table (``dyad_key``),
# in the link frames of the kind (``DyadKind.frames``, ``docs/reference/mechanism-file.md``)
def rrr_middle(reader: DyadReader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B from ``lengths = [|AB|, |CB|]``: at (|AB|, 0) on link i, (|CB|, 0) on j."""
    friction = reader.middle_revolute(table, key)
    lengths = reader.required(dyad_table, "lengths", dyad_key)
    if not isinstance(lengths, list) or len(lengths) != 2:
        raise reader.fail(f"{dyad_key}.lengths", f"must be [|AB|, |CB|] [{reader.length_unit}], "
                                                 f"got {show(lengths)}.", lengths)
    l_i = reader.length_of(lengths[0], f"{dyad_key}.lengths.1", positive=True)
    l_j = reader.length_of(lengths[1], f"{dyad_key}.lengths.2", positive=True)
    return Revolute((i, j), ((l_i, 0.0), (l_j, 0.0)), **friction)


def rrp_middle(reader: DyadReader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B from ``length = |AB|``: at (|AB|, 0) on link i, the origin of link j."""
    friction = reader.middle_revolute(table, key)
    l_i = reader.length_of(reader.required(dyad_table, "length", dyad_key), f"{dyad_key}.length",
                           positive=True)
    return Revolute((i, j), ((l_i, 0.0), (0.0, 0.0)), **friction)


def rpr_middle(reader: DyadReader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Prismatic:
    """Joint B: the guide along the ξ axis of its carrier (link j unless ``guide`` says
    otherwise), the slider point at the other link's origin, ``offset`` to its left."""
    offset, extra = reader.middle_prismatic(table, key, point=False)
    guide = reader.guide(table, key, (i, j), j)
    slider = i if guide == j else j
    return Prismatic.through(guide, (0.0, 0.0), 0.0, offset, slider, (0.0, 0.0), 0.0, **extra)


def prp_middle(reader: DyadReader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Revolute:
    """Joint B: the pin at the origins of both links."""
    return Revolute((i, j), ((0.0, 0.0), (0.0, 0.0)), **reader.middle_revolute(table, key))


def ppr_middle(reader: DyadReader, table: Any, key: str, i: int, j: int,
               dyad_table: dict[str, Any], dyad_key: str) -> Prismatic:
    """Joint B: a guide through ``point`` of link i at ``angle`` to guide A (90° unless
    given; not parallel to it), or on link j with ``guide = j``."""
    offset, extra = reader.middle_prismatic(table, key, point=True)
    theta = reader.angle_of(table.get("angle", 90.0 * math.pi / 180.0 / reader.angle),
                            f"{key}.angle")
    point = reader.point_on(i, table.get("point", [0.0, 0.0]), f"{key}.point")
    if abs(math.sin(theta)) < 1e-9:
        raise reader.fail(f"{key}.angle", "makes guide B parallel to guide A: a PPR dyad is "
                                          "then blocked in every position. Use an angle that "
                                          "is not 0° or 180°.", theta)
    if reader.guide(table, key, (i, j), i) == i:
        return Prismatic.through(i, point, theta, offset, j, (0.0, 0.0), theta, **extra)
    return Prismatic.through(j, (0.0, 0.0), 0.0, offset, i, point, -theta, **extra)


MIDDLE: dict[str, tuple[frozenset, Callable[..., Revolute | Prismatic]]] = {
    "RRR": (frozenset({"lengths"}), rrr_middle),
    "RRP": (frozenset({"length"}), rrp_middle),
    "RPR": (frozenset(), rpr_middle),
    "PRP": (frozenset(), prp_middle),
    "PPR": (frozenset(), ppr_middle),
}
"""kind name -> (keys of its [[dyad]] table beyond the common ones, the reader of its
joint B); one entry per kind of ``dyade.model.dyad_kinds.KINDS``"""
