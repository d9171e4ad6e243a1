"""Array types shared by every analysis (for annotations; numpy.typing is loaded only
by a type checker, it costs start-up time)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    FloatArray = npt.NDArray[np.float64]
else:
    FloatArray = np.ndarray
Vec = tuple[float, float]
"""A point or vector (x, y) or (ξ, η) [m]."""
