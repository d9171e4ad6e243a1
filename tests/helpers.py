"""Helpers for tests: build mechanisms from dicts, run the engine at given angles."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from dyade.linkage import kinematics
from dyade.files.mechanism import Reader
from dyade.model.mechanism import Mechanism

ROOT = Path(__file__).resolve().parent.parent
"""the repository: mechanisms/, and the directory to run ``python -m dyade`` from"""
TEMPLATES = ROOT / "dyade" / "templates"
"""the files `dyade init` writes"""


def mechanism_from(data: dict[str, Any]) -> Mechanism:
    return Reader("test.toml").mechanism(data)


def kinematics_at(mechanism: Mechanism, angles) -> kinematics.Kinematics:
    return kinematics.sweep(mechanism, np.asarray(angles, dtype=np.float64))


def read_csv(text: str) -> dict[str, np.ndarray]:
    lines = text.strip().splitlines()
    names = lines[0].split(",")
    rows = [[float(v) if v else np.nan for v in line.split(",")] for line in lines[1:]]
    table = np.array(rows)
    return {name: table[:, k] for k, name in enumerate(names)}


def shipped(name: str) -> Path:
    return ROOT / "mechanisms" / name


def with_frame_points(folder: Path, count: int) -> Path:
    """The shipped four-bar with ``count`` more named frame points (P0 … P{count-1}),
    written into ``folder``."""
    points = "".join(f"P{k} = [{k % 1000}, {k % 37}]\n" for k in range(count))
    path = folder / f"frame-{count}.toml"
    path.write_text(shipped("fourbar.toml").read_text().replace("B0 = [250, 0]\n",
                                                                "B0 = [250, 0]\n" + points))
    return path
