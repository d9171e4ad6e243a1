"""Coulomb friction dyad by dyad over the whole sweep (Thümmel & Bartke 1987, section 4):
solved directly for a consistent pattern of directions, with the self-locking verdict.

One idea per module, imports pointing down the list:

* ``laws``: the Coulomb law of a revolute and of a prismatic joint (edge friction);
* ``algebra``: small-matrix algebra at every position at once, (I + K)⁻¹ and det(I + K);
* ``scales``: the coupling of blocks (``Coupling``): the crank speed and force floors a
  block of positions takes from the whole sweep;
* ``result``: ``FrictionResult``;
* ``passes``: the laws applied group by group inside the backward pass, one run of it;
* ``solver``: the direct (Newton) solution, ``solve``, and ``coupling``.

The paper's fixed-point iteration is the tests' independent check (``tests/fixed_point.py``).
"""

from __future__ import annotations

from dyade.linkage.friction.laws import AT_REST_RTOL, EDGE
from dyade.linkage.friction.result import FrictionResult, blocked, never_moves
from dyade.linkage.friction.scales import Coupling, sample, top_speed
from dyade.linkage.friction.solver import RESTART_PASSES, coupling, solve

__all__ = ["AT_REST_RTOL", "EDGE", "RESTART_PASSES", "Coupling", "FrictionResult", "blocked",
           "coupling", "never_moves", "sample", "solve", "top_speed"]
