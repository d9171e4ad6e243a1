"""Positions in blocks: the spans a sweep is computed in, and what couples the blocks of
a friction solution.

A block's kinematics and forces depend on its own positions only, with one exception:
the friction solution takes two figures from the whole sweep (``friction.Coupling``:
the largest crank speed, and each dyad's force floor from the positions ``friction.
sample`` picks). ``friction_coupling`` computes them once from those sample positions,
so that every block is solved as within the whole sweep, for any block size.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage import kinematics
from dyade.model.mechanism import Mechanism

if TYPE_CHECKING:  # imported where used: a sweep without friction never loads it
    from dyade.linkage import friction

BLOCK_SIZE = 2048
"""positions per block of a sweep in blocks (``--block-size``): a block's arrays
(kinematics, forces, its columns: a few kB per position for dyade-16's 270 columns) stay
within a few MB, near the cache; larger blocks gain nothing measurable when every block
is written out at once (tests/benchmarks)"""


def spans(positions: int, size: int) -> Iterator[tuple[int, int]]:
    """(first, last) of the blocks of ``size`` positions that cover ``positions`` (one
    empty block for an empty sweep: its columns are there, with no rows)."""
    if positions == 0:
        yield 0, 0
        return
    for first in range(0, positions, size):
        yield first, min(positions, first + size)


def friction_coupling(mechanism: Mechanism, crank_angle: FloatArray,
                      speed: FloatArray | float | None, acceleration: FloatArray | float | None,
                      size: int) -> friction.Coupling | None:
    """The ``Coupling`` of a sweep of ``crank_angle`` [rad] at the crank's ``speed``
    [rad/s] and ``acceleration`` [rad/s²] (one value, one per position, or None: the
    file's constant speed), computed in blocks of ``size`` positions.

    None when one block holds every position: ``friction.solve`` then takes the very same
    figures from that block's sample positions as it goes, without solving them twice
    (tests/test_pipeline.py checks the bits)."""
    n = crank_angle.shape[0]
    if n <= size:
        return None
    from dyade.linkage import friction

    given = mechanism.crank.speed if speed is None else speed
    top = float(np.nanmax(np.abs(np.broadcast_to(given, (n,))), initial=0.0))
    index = np.arange(n)[friction.sample(n)]
    kin = kinematics.sweep(mechanism, crank_angle[index], *(
        value[index] if isinstance(value, np.ndarray) else value
        for value in (speed, acceleration)))
    return friction.coupling(mechanism, kin, top)
