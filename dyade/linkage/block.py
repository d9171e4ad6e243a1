"""A block of positions of a sweep, through every stage its plan calls for
(``dyade.linkage.pipeline``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from dyade.arrays import FloatArray
from dyade.linkage import kinematics, kinetostatics

if TYPE_CHECKING:
    from dyade.linkage import friction
    from dyade.linkage.drive import CrankMotion

Columns = dict[str, FloatArray]


@dataclass(slots=True, eq=False)
class Block:
    """One block of positions through every stage the plan calls for (SI units)."""

    first: int
    """its first position in the sweep"""
    last: int
    """one past its last position"""
    kinematics: kinematics.Kinematics
    forces: kinetostatics.Forces | None
    """joint forces and drive torque (``forces.valid``: given); None without
    kinetostatics"""
    friction: friction.FrictionResult | None
    """friction loads, determinants and verdicts; None without friction"""
    locking: dict | None
    """joint -> ``self_locking.Locking``: every slider with friction and every joint
    that self-locks in the block; None without"""
    rows: FloatArray
    """(m,) bool: the positions reported"""
    valid: FloatArray
    """(m,) bool: the kinematics is given (closes, outside the dead-centre band,
    plausible)"""
    drive: CrankMotion | None = None
    """the crank's motion at the block's positions; None at constant speed"""
    columns: Columns = field(default_factory=dict)
    """the reported positions as named columns (``columns.columns``)"""
    implausible: dict[str, FloatArray] = field(default_factory=dict)
    """"kinematics"/"forces" -> (m,) bool: the positions taken out for a value beyond
    ``columns.PLAUSIBLE``"""
    implausible_columns: dict[str, tuple[str, ...]] = field(default_factory=dict)
    """"kinematics"/"forces" -> the columns that held such a value"""
    implausible_variants: dict[str, dict[int, tuple[str, ...]]] = field(default_factory=dict)
    """a block of a run of variants: "kinematics"/"forces" -> variant -> the columns of
    that variant that held such a value"""
