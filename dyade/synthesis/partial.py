"""The exact fit of a part of a curve (an open path without crank angles): variable
projection. The local fit of ``dyade.synthesis.search.fit`` carries every point's crank
angle as an unknown beside the dimensions; over a third of a coupler curve the
dimensions lie in a long flat valley (a few per cent in the lengths move the curve by
1e-7 of its size) that its damped steps crawl along. Here each point's crank angle is
solved for inside the residual (the foot of the point on the curve, by Newton's method
on the distance), leaving the dimensions and the placement alone: the residual is each
point's signed distance from the curve along its normal, whose derivative with respect
to the dimensions, at the foot, is the normal part of the point's motion with its crank
angle held (the foot's own motion is along the curve).
"""

from __future__ import annotations

import math

import numpy as np

from dyade.synthesis.topology import Placement

NEWTON = 12
"""Newton steps of a foot at most"""
STEP = 1e-5
"""the crank angle step of the curve's tangent and curvature by differences [rad]"""


def polish(topology, fitted, target: np.ndarray, tolerance: float = 1e-12,
           steps: int = 400):
    """A ``search.Fitted`` refined by variable projection until the RMS distance of the
    target points from its curve, over the target's size, is at most ``tolerance``
    (converged) or ``steps`` outer steps have run; the better of it and ``fitted``."""
    from dyade.synthesis.search import Fitted, scipy_least_squares

    least_squares = scipy_least_squares()
    target = np.asarray(target, dtype=complex)
    dims = fitted.values.size
    variant = fitted.variant
    size = float(np.sqrt(np.mean(np.abs(target - target.mean()) ** 2)))
    state = {"phi": np.asarray(fitted.crank, dtype=float).copy()}

    def curve(x, phi):
        z = topology.path(x[:dims], variant, phi)[0]
        return complex(x[dims], x[dims + 1]) + np.exp(1j * x[dims + 2]) * z

    def feet(x):
        phi = state["phi"].copy()
        for _ in range(NEWTON):
            here = curve(x, phi)
            up, down = curve(x, phi + STEP), curve(x, phi - STEP)
            tangent = (up - down) / (2.0 * STEP)
            bend = (up - 2.0 * here + down) / STEP ** 2
            miss = here - target
            slope = (np.conj(miss) * tangent).real  # half the distance² 's derivative
            curvature = np.abs(tangent) ** 2 + (np.conj(miss) * bend).real
            with np.errstate(invalid="ignore", divide="ignore"):
                change = np.where(curvature > 0, -slope / curvature, 0.0)
            change = np.clip(np.nan_to_num(change), -0.2, 0.2)
            phi = phi + change
            if np.max(np.abs(change)) < 1e-15:
                break
        return phi

    def normal(x, phi):
        tangent = curve(x, phi + STEP) - curve(x, phi - STEP)
        with np.errstate(invalid="ignore", divide="ignore"):
            return 1j * tangent / np.abs(tangent)

    def residual(x):
        phi = feet(x)
        if np.all(np.isfinite(phi)):
            state["phi"] = phi
        out = ((curve(x, phi) - target) * np.conj(normal(x, phi))).real / size
        return np.where(np.isfinite(out), out, 10.0)

    def jacobian(x):
        phi = feet(x)
        n = normal(x, phi)
        columns = np.empty((target.size, x.size))
        for k in range(x.size):
            h = 1e-7 * max(1.0, abs(x[k]))
            up, down = x.copy(), x.copy()
            up[k] += h
            down[k] -= h
            columns[:, k] = ((curve(up, phi) - curve(down, phi)) * np.conj(n)).real / (
                2.0 * h * size)
        return np.where(np.isfinite(columns), columns, 0.0)

    x0 = np.concatenate([fitted.values, [fitted.placement.origin.real,
                                         fitted.placement.origin.imag,
                                         fitted.placement.angle]])
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        solution = least_squares(residual, x0, jac=jacobian, method="lm", xtol=1e-15,
                                 ftol=1e-15, gtol=1e-15, max_nfev=steps)
    x = solution.x
    with np.errstate(invalid="ignore", over="ignore"):
        phi = feet(x)
        miss = np.abs(curve(x, phi) - target)
    rms = float(np.sqrt(np.mean(miss ** 2))) if np.all(np.isfinite(miss)) else math.inf
    if not rms / size < fitted.error:
        return fitted
    placement = Placement(complex(x[dims], x[dims + 1]), 1.0, float(x[dims + 2]))
    return Fitted(x[:dims].copy(), variant, placement, phi, rms / size, rms,
                  bool(rms / size <= tolerance), list(fitted.notes))

