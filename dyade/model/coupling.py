"""The stiff coupling of Strümpfel (a coupling file, or ``[drive_line] coupling``), SI:
its data, checked, and the figures that follow from them alone (ω_t, D, κ, η0 of eq. (5)).
Its response to an exciting moment is computed by ``dyade.vibration.coupling``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.errors import InputError

UNITS = {"inertia": "kg·m²", "c1": "N·m/rad", "c2": "N·m/rad", "b1": "N·m·s/rad",
         "b2": "N·m·s/rad"}


@dataclass(frozen=True, slots=True)
class Coupling:
    """The stiff coupling model (SI): J_K between c1t ∥ b1 (primary, excited) and
    c2t ∥ b2 (secondary, held).

    Examples
    --------
    >>> from dyade.model.coupling import Coupling
    >>> coupling = Coupling(inertia=1.0, c1=1.0, c2=1.0, b1=0.05, b2=0.05)
    >>> round(coupling.resonance(), 4)      # η0, eq. (5)
    0.7067
    >>> round(coupling.natural_frequency, 4), round(coupling.kappa, 4)   # ω_t [rad/s], κ [-]
    (1.4142, 0.5)
    """

    inertia: float
    """J_K [kg·m²]"""
    c1: float
    """primary-side torsional stiffness c1t [N·m/rad]"""
    c2: float
    """secondary-side torsional stiffness c2t [N·m/rad]"""
    b1: float
    """primary-side damping b1 [N·m·s/rad]"""
    b2: float
    """secondary-side damping b2 [N·m·s/rad]"""

    def __post_init__(self) -> None:
        for name in ("inertia", "c1", "c2", "b1", "b2"):
            value = getattr(self, name)
            if not np.isfinite(value) or value < 0.0:
                raise InputError.parameter(name, f"must be a non-negative number, got "
                                                 f"{value:g}.", value=value, unit=UNITS[name])
        if self.inertia <= 0.0:
            raise InputError.parameter("inertia", f"must be positive [kg·m²], got "
                                                  f"{self.inertia:g}.", value=self.inertia,
                                       unit="kg·m²")
        if self.c1 + self.c2 <= 0.0:
            raise InputError.parameter(("c1", "c2"), "are both zero: the coupling has no "
                                                     "stiffness, so no natural frequency ω_t and "
                                                     "no tuning ratio η. Give c1 + c2 > 0.")
        if self.c1 == 0.0 and self.b1 == 0.0:
            raise InputError.parameter(("c1", "b1"), "are both zero: nothing carries the exciting "
                                                     "moment to the coupling (the primary node "
                                                     "would run away).")

    @property
    def natural_frequency(self) -> float:
        """ω_t = sqrt((c1t + c2t)/J_K) [rad/s]"""
        return float(np.sqrt((self.c1 + self.c2) / self.inertia))

    @property
    def damping_ratio(self) -> float:
        """D = (b1 + b2)/(2·J_K·ω_t) [-] (the paper prints a square root here, a slip: D
        is dimensionless only in this form)"""
        return (self.b1 + self.b2) / (2.0 * self.inertia * self.natural_frequency)

    @property
    def kappa(self) -> float:
        """κ = c1t/(c1t + c2t) [-]"""
        return self.c1 / (self.c1 + self.c2)

    def resonance(self) -> float | None:
        """η0 of eq. (5) (the peak of V_φ); None when V_φ has no peak (η0² ≤ 0)."""
        share2 = self.b2 / (self.b1 + self.b2) if self.b1 + self.b2 > 0 else 0.0
        square = 1.0 - self.kappa - 2.0 * self.damping_ratio ** 2 * share2 ** 2
        return float(np.sqrt(square)) if square > 0.0 else None
