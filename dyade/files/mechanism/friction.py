"""Friction and clearance data of the joints: the file-wide defaults of [friction], each
joint's coefficient μ and the sizes friction needs (pin radius r_z; slider length L and
height H), and a revolute joint's clearance for the peak-force check."""

from __future__ import annotations

from typing import Any

from dyade.files.schema import UnitReader, show
from dyade.model.mechanism import ClearanceData

FRICTION_KEYS = {"coefficient", "tol", "max_iter", "pin_radius", "slider_length", "slider_height",
                 "edge_friction"}


class FrictionReader(UnitReader):
    """Reads the friction keys of the joints, with the defaults of the [friction] table."""

    friction_defaults: dict[str, float]
    """[friction] pin_radius, slider_length, slider_height [m], where given"""
    default_mu: float
    """[friction] coefficient: μ of a joint that gives none [-]"""
    default_edges: bool
    """[friction] edge_friction: a slider's edges rub (unless the joint says otherwise)"""

    def friction_table(self, friction: Any) -> tuple[float, int]:
        """The [friction] table: the joints' defaults (kept for ``friction_data``) and
        the friction solver's tolerance and iteration cap."""
        self.keys(friction, "friction", FRICTION_KEYS)
        self.friction_defaults = {
            name: self.length_of(friction[name], f"friction.{name}", positive=True)
            for name in ("pin_radius", "slider_length", "slider_height") if name in friction}
        self.default_mu = self.number(friction.get("coefficient", 0.0), "friction.coefficient",
                                      "-", non_negative=True)
        self.below_top(self.default_mu, "friction.coefficient", "friction_coefficient", "-")
        self.default_edges = self.boolean(friction.get("edge_friction", True),
                                          "friction.edge_friction")
        friction_tol = self.number(friction.get("tol", 1e-9), "friction.tol", "-", positive=True)
        friction_max_iter = self.integer(friction.get("max_iter", 50), "friction.max_iter")
        if friction_max_iter < 1:
            raise self.fail("friction.max_iter", f"must be at least 1, got {friction_max_iter}.")
        return friction_tol, friction_max_iter

    def boolean(self, value: Any, key: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(key, f"must be true or false, got {show(value)}.", value)
        return value

    def friction_data(self, table: dict[str, Any], key: str, needs: tuple[str, ...]
                      ) -> dict[str, Any]:
        """μ of a joint (or the file default) and the sizes friction needs: r_z for a
        revolute joint, slider length L and height H for a prismatic one."""
        mu = self.number(table.get("friction", self.default_mu), f"{key}.friction", "-",
                         non_negative=True)
        self.below_top(mu, f"{key}.friction", "friction_coefficient", "-")
        out: dict[str, Any] = {"friction": mu}
        for name in needs:
            if name in table:
                out[name] = self.length_of(table[name], f"{key}.{name}", positive=True)
            elif name in self.friction_defaults:
                out[name] = self.friction_defaults[name]
            elif mu > 0.0:
                what = {"pin_radius": "the pin radius r_z", "slider_length": "the slider length L",
                        "slider_height": "the slider height H"}[name]
                raise self.fail(f"{key}.{name}", f"is missing: the joint has friction "
                                                 f"(μ = {mu:g}) and needs {what} "
                                                 f"[{self.length_unit}] (or give a default in "
                                                 f"[friction] {name}).")
        return out

    def revolute_friction(self, table: dict[str, Any], key: str) -> dict[str, Any]:
        out = self.friction_data(table, key, ("pin_radius",))
        if "clearance" in table:
            sub = self.keys(table["clearance"], f"{key}.clearance", {"gap", "stiffness", "mass"})
            path = f"{key}.clearance"
            gap = self.length_of(self.required(sub, "gap", path), f"{path}.gap", positive=True)
            stiffness = self.number(self.required(sub, "stiffness", path), f"{path}.stiffness",
                                    "N/m", positive=True)
            mass = (self.number(sub["mass"], f"{path}.mass", "kg", positive=True)
                    if "mass" in sub else None)
            out["clearance"] = ClearanceData(gap, stiffness, mass)
        return out

    def prismatic_friction(self, table: dict[str, Any], key: str) -> dict[str, Any]:
        out = self.friction_data(table, key, ("slider_length", "slider_height"))
        out["edge_friction"] = self.boolean(table.get("edge_friction", self.default_edges),
                                            f"{key}.edge_friction")
        return out
