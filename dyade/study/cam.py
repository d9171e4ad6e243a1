"""A study of a cam file (``mechanism`` in the study file names a cam file): each
variant is the cam file's data with the study's values at their key paths
(``cam.base_radius``, ``follower.roller_radius``, ``follower.offset``,
``follower.stiffness``, ``profile.segment.2.to``, ...), read by ``dyade.files.cam``
and checked by the ``cam`` entry (``dyade.analyses.cam.checked``, at 1° as ``dyade
cam`` by default, without the profile to manufacture); its outputs are the summary's
figures (``dyade.analyses.cam.STUDY_OUTPUTS``), of the same names and values.
"""

from __future__ import annotations

import copy
import math
from typing import Any

STEP_DEG = 1.0
"""[°] the cam-angle step of every variant's checks (``dyade cam``'s default)"""


class CamEvaluator:
    """The variants of a cam file: ``evaluator(block)`` for a block of (first variant
    number, values) gives one row per variant, (number, status, reason, outputs); the
    same interface as ``dyade.study.evaluate.Evaluator`` (a class: it pickles for the
    processes of any executor). Variants are checked one by one (the checks of one cam
    are vectorised over its angles)."""

    stacks = False
    """variants are never swept together"""
    crossings = False
    """no crank grid whose extremes' angles a sensitivity's notes would follow"""

    def __init__(self, path: str, data: dict[str, Any], keys: tuple[str, ...],
                 choices: dict[str, tuple[str, ...]] | None = None) -> None:
        self.path, self.data, self.keys = path, data, keys
        self.choices = choices or {}
        self.label = path.replace("\\", "/").rsplit("/", 1)[-1]
        self.calls = 0
        self.together = 0

    def mechanism(self, values):
        """The variant's ``dyade.model.cam.Cam`` (InputError where the reader refuses
        it)."""
        from dyade.files.cam import read_cam
        from dyade.files.schema import set_dotted

        data = copy.deepcopy(self.data)
        for key, value in zip(self.keys, values):
            value = float(value)
            if key in self.choices:
                value = self.choices[key][int(round(value))]
            set_dotted(data, key, value, self.label, "parameter")
        return read_cam(self.path, data=data)

    def stages_stack(self, values) -> bool:
        return False

    def unit(self, key: str) -> str:
        """A parameter's unit as the cam file takes it (its ``[units]``)."""
        units = self.data.get("units", {}) if isinstance(self.data.get("units"), dict) else {}
        length, angle = units.get("length", "m"), units.get("angle", "rad")
        angular = isinstance(self.data.get("cam"), dict) and self.data["cam"].get(
            "follower") == "oscillating-roller"
        last = key.rsplit(".", 1)[-1]
        if key.startswith("profile."):
            return {"end": angle, "start": angle}.get(last, self.data.get("profile", {}).get(
                "unit", "") if last in ("to", "from") else "")
        if last in ("preload",):
            return angle if angular else length
        if last in ("pressure_angle_max",):
            return angle
        return {"speed_rpm": "rpm", "mass": "kg·m²" if angular else "kg",
                "stiffness": "N·m/rad" if angular else "N/m", "load": "N·m" if angular else "N",
                "guide_friction": "-", "young": "Pa", "poisson": "-"}.get(last, length)

    def one(self, values) -> tuple[str, str, dict[str, float]]:
        """(status, reason, outputs) of one variant."""
        from dyade.analyses.cam import STUDY_OUTPUTS, checked
        from dyade.errors import DyadeError, InputError
        from dyade.study.evaluate import FAILED, OK, REFUSED

        self.calls += 1
        try:
            cam = self.mechanism(values)
        except InputError as err:
            return REFUSED, str(err), {}
        try:
            outcome = checked(cam, STEP_DEG, make=False)
        except InputError as err:
            return REFUSED, str(err), {}
        except DyadeError as err:  # the follower can never keep contact
            return FAILED, str(err), {}
        out = {}
        for name, figure in outcome.summary.items():
            if name in STUDY_OUTPUTS:
                value = figure.value
                out[name] = math.nan if value is None else float(value)
        return OK, "", out

    def __call__(self, block) -> list[tuple[int, str, str, dict]]:
        first, values = block
        return [(first + i, *self.one(row)) for i, row in enumerate(values)]
