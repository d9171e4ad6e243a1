"""A cam cycle for the tests, in closed form: cycloidal rise of h over β, dwell, cycloidal
return over β, dwell (written here, independent of dyade.motion)."""

from __future__ import annotations

import numpy as np


def cycle(theta, lift, rise_deg=120.0, dwell_deg=60.0):
    """s, s′, s″ [m, m/rad, m/rad²] of rise (β), dwell, return (β), dwell over θ [rad]."""
    beta, dwell = np.radians(rise_deg), np.radians(dwell_deg)
    theta = np.mod(theta, 2 * np.pi)
    s, ds, dds = (np.zeros_like(theta) for _ in range(3))
    rise = theta < beta
    z = theta[rise] / beta
    s[rise] = lift * (z - np.sin(2 * np.pi * z) / (2 * np.pi))
    ds[rise] = lift / beta * (1 - np.cos(2 * np.pi * z))
    dds[rise] = 2 * np.pi * lift / beta ** 2 * np.sin(2 * np.pi * z)
    top = (theta >= beta) & (theta < beta + dwell)
    s[top] = lift
    back = (theta >= beta + dwell) & (theta < 2 * beta + dwell)
    z = (theta[back] - beta - dwell) / beta
    s[back] = lift * (1 - (z - np.sin(2 * np.pi * z) / (2 * np.pi)))
    ds[back] = -lift / beta * (1 - np.cos(2 * np.pi * z))
    dds[back] = -2 * np.pi * lift / beta ** 2 * np.sin(2 * np.pi * z)
    return s, ds, dds


def polar_radius_of_curvature(theta, x, y, dx, dy, ddx, ddy):
    """The radius of curvature of a curve given in polar form, r(φ), from the cam-fixed
    point (x, y)(θ) in the FIXED frame and its θ-derivatives: seen from the cam the
    point lies at r = |(x, y)|, φ = atan2(y, x) − θ; ρ = (r² + r_φ²)^{3/2} /
    (r² + 2·r_φ² − r·r_φφ) (convex positive)."""
    r = np.hypot(x, y)
    r_t = (x * dx + y * dy) / r
    r_tt = (dx ** 2 + dy ** 2 + x * ddx + y * ddy) / r - r_t ** 2 / r
    phi_t = (x * dy - y * dx) / r ** 2 - 1.0
    phi_tt = ((x * ddy - y * ddx) * r ** 2 - (x * dy - y * dx) * 2 * r * r_t) / r ** 4
    r_p = r_t / phi_t
    r_pp = (r_tt * phi_t - r_t * phi_tt) / phi_t ** 3
    return (r ** 2 + r_p ** 2) ** 1.5 / (r ** 2 + 2 * r_p ** 2 - r * r_pp)
