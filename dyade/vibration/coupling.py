"""Torsional resonance of a stiff coupling (Strümpfel), as complex phasors.

Model: the exciting moment M_E = M̂_E·sin Ωt acts at the primary node ψ (massless),
which drives the coupling inertia J_K through c1t ∥ b1; the secondary side is held
still through c2t ∥ b2:

    M_E = c1t·(ψ − φ) + b1·(ψ' − φ'),    J_K·φ'' + b2·φ' + c2t·φ = M_E,
    M_Q = c2t·φ + b2·φ',                 φ_r = φ − ψ (the paper's relative angle).

With M_E = Im(M̂_E·e^{iΩt}) every response is Im(X·M̂_E·e^{iΩt}) with the phasors

    Φ = 1/(c2t − J_K·Ω² + i·b2·Ω),   Φ_r = −1/(c1t + i·b1·Ω),
    Ψ = Φ − Φ_r,                      Q = (c2t + i·b2·Ω)·Φ,

so the amplitudes are |X|·M̂_E and the phase (lead over M_E) is arg X in (−180°, 180°],
the true quadrant that the paper's arctan forms (10) lose. The transfer functions are
normalised as in the paper: V_φ = |Φ|·(c1t + c2t), V_ψ = |Ψ|·c1t,
V_q = |Q|·(c1t + c2t)/c2t, V_r = |Φ_r|·c1t; they equal eqs. (4), (7), (8), (9).
The phasor form also keeps full accuracy near a lightly damped resonance, where the
paper's Z = sqrt(W² − 2κN + κ²(1 + R²)) cancels. The coupling itself (its data and the
figures that follow from them: ω_t, D, κ, η0) is ``dyade.model.coupling.Coupling``.

>>> from dyade.model.coupling import Coupling
>>> float(response(Coupling(1.0, 1.0, 1.0, 0.05, 0.05), [0.0]).transfer["V_phi"][0])
2.0
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.model.coupling import Coupling
from dyade.units import RPM

UNBOUNDED_RTOL = 1e-14  # [-] |denominator| below this share of its terms: exactly singular


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Response:
    """Transfer functions and phases over the tuning ratio."""

    eta: FloatArray
    phasors: dict[str, np.ndarray]
    """'phi', 'psi', 'q', 'r' -> complex phasor per unit M̂_E (rad/(N·m) or -)"""
    transfer: dict[str, FloatArray]
    """'V_phi', 'V_psi', 'V_q', 'V_r' -> normalised amplitude; inf where unbounded,
    NaN where undefined (its normalising stiffness is zero)"""
    phase: dict[str, FloatArray]
    """'alpha', 'beta', 'gamma', 'delta' -> lead over M_E [rad] in (−π, π]; NaN where
    the response is zero or unbounded (phase undefined)"""
    unbounded: FloatArray
    """(n,) bool: undamped resonance, amplitudes of φ, ψ, M_Q infinite"""


def response(coupling: Coupling, eta: FloatArray) -> Response:
    """Phasor solution at the tuning ratios ``eta`` = Ω/ω_t [-] (vectorised): transfer
    functions V_φ, V_ψ, V_q, V_r (eqs. (4), (7)-(9)), phases α, β, γ, δ (true quadrant)
    and the phasors per unit exciting moment; unbounded where undamped at resonance.

    Parameters
    ----------
    coupling : Coupling
        From ``Coupling(...)`` or ``read_coupling``.
    eta : array_like
        Tuning ratios η = Ω/ω_t [-], ≥ 0.

    Returns
    -------
    Response
        ``transfer`` (V_phi, V_psi, V_q, V_r) and ``phase`` per η.

    Examples
    --------
    >>> import dyade
    >>> coupling = dyade.Coupling(1.0, 1.0, 1.0, 0.05, 0.05)
    >>> response = dyade.coupling_response(coupling, [0.0, 0.7071, 2.0])
    >>> [round(float(v), 3) for v in response.transfer["V_phi"]]   # peak near η0 = √(1 − κ)
    [2.0, 40.0, 0.286]"""
    eta = np.asarray(eta, dtype=np.float64)
    if np.any(eta < 0.0) or not np.all(np.isfinite(eta)):
        raise InputError.parameter("eta", "(tuning ratios η) must be finite and not negative.")
    j, c1, c2, b1, b2 = coupling.inertia, coupling.c1, coupling.c2, coupling.b1, coupling.b2
    omega = eta * coupling.natural_frequency
    den_phi = (c2 - j * omega ** 2) + 1j * b2 * omega
    scale = np.maximum(c2 + j * omega ** 2 + b2 * omega, np.finfo(float).tiny)
    unbounded = np.abs(den_phi) <= UNBOUNDED_RTOL * scale
    den_r = c1 + 1j * b1 * omega
    r_zero = np.abs(den_r) == 0.0  # c1 = 0, b1 > 0 at Ω = 0: relative angle unbounded
    with np.errstate(divide="ignore", invalid="ignore"):  # unbounded rows are masked below
        phi = np.where(unbounded, np.nan, 1.0 / np.where(unbounded, 1.0, den_phi))
        rel = np.where(r_zero, np.nan, -1.0 / np.where(r_zero, 1.0, den_r))
    psi = phi - rel
    # ψ̂ = 0 at an undamped anti-resonance: a round-off remainder is zero (phase undefined)
    psi = np.where(np.abs(psi) <= 1e-13 * (np.abs(phi) + np.abs(rel)), 0.0, psi)
    q = (c2 + 1j * b2 * omega) * phi
    phasors = {"phi": phi, "psi": psi, "q": q, "r": rel}
    inf = np.inf
    transfer = {
        "V_phi": np.where(unbounded, inf, np.abs(phi) * (c1 + c2)),
        "V_psi": (np.where(unbounded | r_zero, inf, np.abs(psi) * c1) if c1 > 0
                  else np.full(eta.shape, np.nan)),
        "V_q": (np.where(unbounded, inf, np.abs(q) * (c1 + c2) / c2) if c2 > 0
                else np.full(eta.shape, np.nan)),
        "V_r": (np.where(r_zero, inf, np.abs(rel) * c1) if c1 > 0
                else np.full(eta.shape, np.nan)),
    }
    phase = {name: _phase(phasors[key])
             for name, key in (("alpha", "phi"), ("beta", "psi"), ("gamma", "q"), ("delta", "r"))}
    return Response(eta, phasors, transfer, phase, unbounded)


def _phase(x: np.ndarray) -> FloatArray:
    """arg x in (−π, π]; NaN where x is zero or undefined."""
    angle = np.angle(x)
    angle = np.where(angle <= -np.pi, np.pi, angle)
    return np.where((np.abs(x) == 0.0) | ~np.isfinite(x), np.nan, angle)


def amplitudes(coupling: Coupling, resp: Response, *, moment: float) -> dict[str, FloatArray]:
    """Physical amplitudes for M̂_E = ``moment`` [N·m]: φ̂, ψ̂, φ̂_r [rad], M̂_Q [N·m]."""
    if not np.isfinite(moment) or moment <= 0.0:
        raise InputError.parameter("moment", f"must be a positive amplitude [N·m], got "
                                             f"{moment:g}.", value=moment, unit="N·m")
    out = {}
    for name, key in (("phi_hat", "phi"), ("psi_hat", "psi"), ("MQ_hat", "q"), ("phir_hat", "r")):
        value = np.abs(resp.phasors[key]) * moment
        unbounded = resp.unbounded if key != "r" else np.zeros_like(resp.unbounded)
        out[name] = np.where(unbounded | np.isnan(value), np.inf, value)
    return out


def paper_transfer(coupling: Coupling, eta: FloatArray) -> dict[str, FloatArray]:
    """The paper's closed forms (4), (7), (8), (9) — for cross-checks (needs b1 + b2 > 0,
    c1 > 0, c2 > 0)."""
    c1, c2, b1, b2 = coupling.c1, coupling.c2, coupling.b1, coupling.b2
    d, kappa = coupling.damping_ratio, coupling.kappa
    r = b1 / (b1 + b2) * (c1 + c2) / c1 * 2 * d * eta
    m = b2 / (b1 + b2) * (c1 + c2) / c2 * 2 * d * eta
    n = 1 - eta ** 2 + 2 * d * eta * r
    w = np.sqrt((1 - eta ** 2) ** 2 + (2 * d * eta) ** 2)
    z = np.sqrt(w ** 2 - 2 * kappa * n + kappa ** 2 * (1 + r ** 2))
    return {"V_phi": 1 / z, "V_psi": w / (z * np.sqrt(1 + r ** 2)),
            "V_q": np.sqrt(1 + m ** 2) / z, "V_r": 1 / np.sqrt(1 + r ** 2)}


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class OperatingPoints:
    """Operating speeds placed on the η axis."""

    speeds_rpm: FloatArray
    """(k,) shaft speeds [rpm]"""
    order: float
    """excitation order: Ω = order · 2π·speed/60"""
    eta: FloatArray
    """(k,) tuning ratios η = Ω/ω_t"""
    response: Response
    """the responses at those η"""


def operating_points(coupling: Coupling, speeds_rpm, *, order: float = 1.0) -> OperatingPoints:
    """The coupling's response at operating speeds for an excitation ``order``.

    Parameters
    ----------
    coupling : Coupling
        From ``Coupling(...)`` or ``read_coupling``.
    speeds_rpm : iterable of float
        Shaft speeds [rpm], positive.
    order : float
        Excitation order: pulses per revolution (Ω = order · 2π·speed/60).

    Returns
    -------
    OperatingPoints
        The speeds' tuning ratios η and the responses there.

    Examples
    --------

    >>> from dyade.vibration.coupling import Coupling, operating_points
    >>> points = operating_points(Coupling(1.0, 1.0, 1.0, 0.05, 0.05), [6.0], order=2)
    >>> round(float(points.eta[0]), 4), round(float(points.response.transfer["V_phi"][0]), 3)
    (0.8886, 3.433)
    """
    if not np.isfinite(order) or order <= 0:
        raise InputError.parameter("order", f"must be positive, got {order:g}.", value=order)
    speeds = np.atleast_1d(np.asarray(speeds_rpm, dtype=float))
    if np.any(~np.isfinite(speeds) | (speeds <= 0)):
        raise InputError.parameter("speeds_rpm", "(operating speeds) must be positive [rpm].",
                                   unit="rpm")
    omega = order * speeds * RPM
    eta = omega / coupling.natural_frequency
    return OperatingPoints(speeds, float(order), eta, response(coupling, eta))


def undamped_resonance(coupling: Coupling) -> float | None:
    """The tuning ratio η where the response is unbounded: without damping on the
    secondary side (b2 = 0) at η = sqrt(1 − κ) = sqrt(c2/(c1 + c2)), eq. (6); None when
    b2 > 0 (every response finite)."""
    if coupling.b2 > 0.0:
        return None
    return float(np.sqrt(1.0 - coupling.kappa))


def peaks(resp: Response, coupling: Coupling | None = None
          ) -> dict[str, tuple[float, float] | None]:
    """The largest value of each transfer function over the computed η and where:
    name -> (value, η), None where it is not defined. With ``coupling``, an undamped
    resonance inside the range is the peak of V_φ, V_ψ and V_q: (inf, η0) whether or
    not a computed η falls on it.

    >>> from dyade.vibration.coupling import Coupling, peaks, response
    >>> undamped = Coupling(1.0, 1.0, 1.0, 0.0, 0.0)
    >>> peaks(response(undamped, np.linspace(0, 3, 301)), undamped)["V_phi"]
    (inf, 0.7071067811865476)
    """
    out: dict[str, tuple[float, float] | None] = {}
    eta_u = None if coupling is None else undamped_resonance(coupling)
    inside = eta_u is not None and resp.eta.min() <= eta_u <= resp.eta.max()
    for name, values in resp.transfer.items():
        if np.all(np.isnan(values)):
            out[name] = None
        elif inside and name != "V_r":
            out[name] = (float("inf"), eta_u)
        else:
            k = int(np.nanargmax(np.where(np.isnan(values), -np.inf, values)))
            out[name] = (float(values[k]), float(resp.eta[k]))
    return out
