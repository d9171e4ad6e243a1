"""A hand-written, single-purpose vectorised numpy four-bar: kinematics and forces.

The yardstick for dyade's general engine (issue 7): the same four-bar as
mechanisms/fourbar.toml (crank 50, coupler 200, rocker 150 mm, B0 = (250, 0) mm,
coupler 1.2 kg / J 0.004, rocker 0.9 kg / J 0.0017, centres at the middles, crank
massless), closed-form loop equations, Newton–Euler per link solved by hand.
"""

from __future__ import annotations

import numpy as np

R2, R3, R4, B0 = 0.05, 0.2, 0.15, 0.25  # [m]
M3, J3, M4, J4 = 1.2, 0.004, 0.9, 0.0017  # [kg], [kg m²]
G3, G4 = 0.1, 0.075  # [m] centres of coupler and rocker from A and B0, along the link


def fourbar(phi: np.ndarray, omega: float, R3: float | np.ndarray = R3,  # noqa: N803
            R4: float | np.ndarray = R4) -> dict[str, np.ndarray]:
    """Angles, rates and joint forces of the four-bar at crank angles ``phi``; coupler
    ``R3`` and rocker ``R4`` [m] may be arrays that broadcast against ``phi`` (variants ×
    positions)."""
    c2, s2 = np.cos(phi), np.sin(phi)
    ax, ay = R2 * c2, R2 * s2
    dx, dy = B0 - ax, -ay
    dist2 = dx * dx + dy * dy
    dist = np.sqrt(dist2)
    gamma = np.arccos((R3 * R3 + dist2 - R4 * R4) / (2 * R3 * dist))
    phi3 = np.arctan2(dy, dx) + gamma
    c3, s3 = np.cos(phi3), np.sin(phi3)
    bx, by = ax + R3 * c3, ay + R3 * s3
    phi4 = np.arctan2(by, bx - B0)
    c4, s4 = np.cos(phi4), np.sin(phi4)
    sin34 = np.sin(phi3 - phi4)
    w3 = omega * R2 * np.sin(phi4 - phi) / (R3 * sin34)
    w4 = omega * R2 * np.sin(phi3 - phi) / (R4 * sin34)
    rx = R2 * omega ** 2 * c2 + R3 * w3 ** 2 * c3 - R4 * w4 ** 2 * c4
    ry = R2 * omega ** 2 * s2 + R3 * w3 ** 2 * s3 - R4 * w4 ** 2 * s4
    det = R3 * R4 * (s3 * c4 - s4 * c3)
    a3 = (-R4 * c4 * rx - R4 * s4 * ry) / det
    a4 = (-R3 * c3 * rx - R3 * s3 * ry) / det
    # centre accelerations (at G3, G4 along the links: their middles in the file)
    a_ax, a_ay = -R2 * omega ** 2 * c2, -R2 * omega ** 2 * s2
    g3x = a_ax + G3 * (-a3 * s3 - w3 ** 2 * c3)
    g3y = a_ay + G3 * (a3 * c3 - w3 ** 2 * s3)
    g4x = G4 * (-a4 * s4 - w4 ** 2 * c4)
    g4y = G4 * (a4 * c4 - w4 ** 2 * s4)
    # rocker moments about B0 and coupler moments about A give F34 (force on 4 at B)
    # rocker: M_B0(F34) + M_B0(−m4 g4) − J4 a4 = 0 ; coupler: M_A(−F34) + M_A(−m3 g3) − J3 a3 = 0
    k4 = J4 * a4 + G4 * (c4 * M4 * g4y - s4 * M4 * g4x)
    k3 = J3 * a3 + G3 * (c3 * M3 * g3y - s3 * M3 * g3x)
    # R4(c4 Fy − s4 Fx) = k4 ;  −R3(c3 Fy − s3 Fx) = k3
    den = R4 * R3 * (s3 * c4 - c3 * s4)
    fx = (k4 * R3 * c3 + k3 * R4 * c4) / den
    fy = (k4 * R3 * s3 + k3 * R4 * s4) / den
    # coupler: F23 (on 3 at A) = m3 g3 + F34 ; crank torque from F23 at A
    f23x, f23y = M3 * g3x + fx, M3 * g3y + fy
    torque = ax * f23y - ay * f23x
    return {"phi3": phi3, "phi4": phi4, "omega3": w3, "omega4": w4, "alpha3": a3,
            "alpha4": a4, "a3x": g3x, "a3y": g3y, "a4x": g4x, "a4y": g4y, "F34x": fx, "F34y": fy, "F23x": f23x, "F23y": f23y, "M_drive": torque}


SR2, SL3, SE = 0.04, 0.16, 0.01  # [m] crank, conrod, guide offset (mechanisms/slider-crank.toml)
SM3, SJ3, SG3, SM4 = 0.6, 0.0013, 0.08, 0.5  # conrod mass, inertia, centre from A; slider mass


def slider_crank(phi: np.ndarray, omega: float) -> dict[str, np.ndarray]:
    """The offset slider-crank of mechanisms/slider-crank.toml (crank 40, conrod 160 mm,
    guide 10 mm above the crank pivot along x, slider ahead; conrod 0.6 kg / J 0.0013 with
    its centre 80 mm from the crank pin, slider 0.5 kg at the piston pin, crank massless):
    closed-form loop equations, Newton–Euler per link solved by hand."""
    c2, s2 = np.cos(phi), np.sin(phi)
    ax, ay = SR2 * c2, SR2 * s2
    s3 = (SE - ay) / SL3
    c3 = np.sqrt(1.0 - s3 * s3)
    phi3 = np.arctan2(s3, c3)
    bx = ax + SL3 * c3
    w3 = -SR2 * omega * c2 / (SL3 * c3)  # the slider stays on its guide: d/dt(ay + l s3) = 0
    vb = -SR2 * omega * s2 - SL3 * s3 * w3
    a_ax, a_ay = -SR2 * omega ** 2 * c2, -SR2 * omega ** 2 * s2
    a3 = (SL3 * s3 * w3 ** 2 - a_ay) / (SL3 * c3)
    ab = a_ax - SL3 * (c3 * w3 ** 2 + s3 * a3)
    gx = a_ax + SG3 * (-s3 * a3 - c3 * w3 ** 2)
    gy = a_ay + SG3 * (c3 * a3 - s3 * w3 ** 2)
    fx = SM4 * ab  # on the slider at B along the frictionless guide
    k3 = SJ3 * a3 + SG3 * (c3 * SM3 * gy - s3 * SM3 * gx)  # conrod moments about A
    fy = (s3 * fx - k3 / SL3) / c3
    f23x, f23y = SM3 * gx + fx, SM3 * gy + fy
    torque = ax * f23y - ay * f23x
    return {"phi3": phi3, "x_B": bx, "v_B": vb, "a_B": ab, "omega3": w3, "alpha3": a3,
            "F34x": fx, "F34y": fy, "F23x": f23x, "F23y": f23y, "M_drive": torque}


def fourbar_variants(r3: np.ndarray, r4: np.ndarray, phi: np.ndarray, omega: float
                     ) -> dict[str, np.ndarray]:
    """Key results of four-bar variants (coupler ``r3``, rocker ``r4`` [m], each (V,))
    over crank angles ``phi`` (P,, one revolution, 0 to 2π), every one ``dyade study``
    gives for the shipped four-bar: the drive torque's peak, trough and RMS and the mean
    drive power over the cycle (the periodic trapezoid rule), the peak force of every
    joint, the smallest transmission angle [°], the rocker's swing [°] and time ratio,
    the shaking force's peak and RMS and the shaking moment's peak; one (variants ×
    positions) broadcast."""
    out = fourbar(phi[None, :], omega, r3[:, None], r4[:, None])
    cycle = slice(0, -1)  # 360° repeats 0°: each position once
    turn = phi[-1] - phi[0]

    def mean(values):  # over the revolution: the periodic trapezoid rule
        return values[:, cycle].sum(axis=1) / (phi.size - 1) if turn else values.mean(axis=1)

    torque = out["M_drive"]
    mu = np.rad2deg(np.abs(np.remainder(out["phi3"] - out["phi4"] + np.pi, 2 * np.pi) - np.pi))
    # the frame's load: minus the rate of change of the moving links' momentum (crank
    # massless, no gravity); its moment about the crank pivot
    c3, s3, c4, s4 = (np.cos(out["phi3"]), np.sin(out["phi3"]), np.cos(out["phi4"]),
                      np.sin(out["phi4"]))
    g3x, g3y = R2 * np.cos(phi) + G3 * c3, R2 * np.sin(phi) + G3 * s3
    g4x, g4y = B0 + G4 * c4, G4 * s4
    f3x, f3y = M3 * out["a3x"], M3 * out["a3y"]
    f4x, f4y = M4 * out["a4x"], M4 * out["a4y"]
    shake = np.hypot(f3x + f4x, f3y + f4y)
    moment = (g3x * f3y - g3y * f3x + J3 * out["alpha3"] + g4x * f4y - g4y * f4x
              + J4 * out["alpha4"])
    f14 = np.hypot(f4x - out["F34x"], f4y - out["F34y"])  # the rocker: m4·a4 = F14 + F34
    rocker = np.rad2deg(np.unwrap(out["phi4"], axis=1))
    top, bottom = _vertex(rocker[:, cycle], 1.0), _vertex(rocker[:, cycle], -1.0)
    forward = np.rad2deg((top - bottom) * (phi[1] - phi[0])) % 360.0
    short = np.minimum(forward, 360.0 - forward)
    return {"M_drive_max": torque.max(axis=1), "M_drive_min": torque.min(axis=1),
            "M_drive_abs_max": np.abs(torque).max(axis=1),
            "M_drive_rms": np.sqrt(mean(torque * torque)),
            "P_drive_mean": mean(torque * omega),
            "F_1_2_peak": np.hypot(out["F23x"], out["F23y"]).max(axis=1),
            "F_2_3_peak": np.hypot(out["F23x"], out["F23y"]).max(axis=1),
            "F_3_4_peak": np.hypot(out["F34x"], out["F34y"]).max(axis=1),
            "F_1_4_peak": f14.max(axis=1),
            "mu_2_min_deg": np.minimum(mu, 180.0 - mu).min(axis=1),
            "swing_4_deg": rocker.max(axis=1) - rocker.min(axis=1),
            "time_ratio_4": (360.0 - short) / short,
            "F_shake_max": shake.max(axis=1), "F_shake_rms": np.sqrt(mean(shake * shake)),
            "M_shake_abs_max": np.abs(moment).max(axis=1)}


def _vertex(values: np.ndarray, sign: float) -> np.ndarray:
    """The position (in steps, fractional) of each row's maximum (sign +1) or minimum
    (−1) of a periodic sampled curve, by the parabola through it and its neighbours."""
    rows = np.arange(values.shape[0])
    k = np.argmax(sign * values, axis=1)
    before, here, after = (values[rows, k - 1], values[rows, k],
                           values[rows, (k + 1) % values.shape[1]])
    return k + 0.5 * (before - after) / (before - 2.0 * here + after)
