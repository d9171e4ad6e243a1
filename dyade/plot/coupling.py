"""The stiff coupling's transfer functions and phases against the tuning ratio η
(Strümpfel, eqs. (4), (7)–(10)).

The upper panel shows V_φ, V_ψ, V_q and V_r (linear or logarithmic axis), the lower one
their phases α, β, γ, δ (lead over the exciting moment, −180° … 180°, broken where they
jump). η0 (eq. (5)) and operating points are marked. An undamped resonance is drawn as a
gap, never as a spike: where a transfer function is unbounded, and on the steep flanks
around it above ``FLANK`` times the largest value away from the resonance, the curve is
left out and the gap is labelled ∞.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas

CURVES = (("V_phi", "V_φ (coupling)", "alpha", "α"),
          ("V_psi", "V_ψ (exciting side)", "beta", "β"),
          ("V_q", "V_q (counter-moment)", "gamma", "γ"),
          ("V_r", "V_r (relative)", "delta", "δ"))
"""transfer function, its label, its phase and the phase's symbol"""
FLANK = 4.0  # [-] an unbounded curve is cut above this multiple of its far-off maximum
NEAR = 0.2  # [-] "near the resonance": within this share of η_res
JUMP = 90.0  # [°] a phase step larger than this is a jump: the line breaks


def undamped_resonance(coupling) -> float | None:
    """η where the undamped coupling's response is unbounded (b2 = 0, c2 > 0): c2 = J·Ω²;
    None when damped or without such a resonance."""
    if coupling.b2 > 0.0 or coupling.c2 <= 0.0:
        return None
    return float(np.sqrt(coupling.c2 / (coupling.c1 + coupling.c2)))


def drawn(values: np.ndarray, eta: np.ndarray, resonance: float | None) -> tuple[np.ndarray, float]:
    """The values as drawn: NaN where unbounded or undefined, and near an undamped
    resonance wherever they exceed ``FLANK`` × their maximum away from it; and that cut
    (inf when nothing is cut)."""
    out = np.where(np.isfinite(values), values, np.nan)
    if resonance is None:
        return out, np.inf
    near = np.abs(eta - resonance) < NEAR * resonance
    far = out[~near & np.isfinite(out)]
    cut = FLANK * float(far.max()) if far.size else FLANK
    return np.where(near & (out > cut), np.nan, out), cut


def figure(coupling, response, operating=None, *, log: bool = False,
           fig: Figure | None = None) -> Figure:
    """Transfer functions and phases of a stiff coupling against η.

    Parameters
    ----------
    coupling : Coupling
    response : Response
        ``dyade.coupling_response(coupling, eta)``.
    operating : OperatingPoints, optional
        ``dyade.operating_points(...)``: marked on the curves.
    log : bool
        A logarithmic axis for the transfer functions.
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import numpy as np, dyade
    >>> from dyade.plot import coupling as plot
    >>> model = dyade.Coupling(1.0, 3.0, 1.0, 0.0, 0.0)          # undamped: η_res = 0.5
    >>> fig = plot.figure(model, dyade.coupling_response(model, np.arange(0, 3, 0.01)))
    >>> phi = fig.axes[0].get_lines()[0].get_ydata()
    >>> bool(np.isnan(phi[50])), bool(np.nanmax(phi) <= fig.axes[0].get_ylim()[1])
    (True, True)
    """
    eta = response.eta
    resonance = undamped_resonance(coupling)
    with canvas.style():
        fig = canvas.new(7.0, 5.6, fig)
        top, bottom = fig.subplots(2, 1, sharex=True, height_ratios=(3, 2))
        highest = 0.0
        for k, (name, label, phase, symbol) in enumerate(CURVES):
            values, cut = drawn(response.transfer[name], eta, resonance)
            if np.all(np.isnan(values)) and np.all(np.isnan(response.transfer[name])):
                continue  # not defined for this coupling (its stiffness is zero)
            top.plot(eta, values, label=label, gid=name, **canvas.line(k, True))
            if np.isfinite(values).any():
                highest = max(highest, float(np.nanmax(values)))
            bottom.plot(*_broken(eta, np.rad2deg(response.phase[phase])), label=symbol,
                        gid=phase, **canvas.line(k, True))
        if log:
            top.set_yscale("log", nonpositive="mask")
        else:
            top.set_ylim(0.0, 1.08 * highest if highest > 0 else 1.0)
        if resonance is not None and eta.min() <= resonance <= eta.max():
            top.axvspan(resonance * (1 - 0.004), resonance * (1 + 0.004), color="0.9", zorder=0)
            top.annotate(f"∞ at η = {resonance:.4g}\n(undamped)", (resonance, 1.0),
                         xycoords=("data", "axes fraction"), xytext=(4, -4),
                         textcoords="offset points", va="top", fontsize=7, gid="unbounded")
        eta0 = coupling.resonance()
        for ax in (top, bottom):
            if eta0 is not None and eta.min() <= eta0 <= eta.max():
                ax.axvline(eta0, color=canvas.GREY, linestyle=canvas.DASHES[1], linewidth=0.9,
                           gid="eta0", label=f"η0 = {eta0:.4g} (eq. 5)" if ax is top else None)
        if operating is not None:
            _operating(top, operating)
        top.set_ylabel("transfer function V [-]")
        top.legend(loc="upper right")
        bottom.set_ylabel("phase (lead over M_E) [°]")
        bottom.set_ylim(-190, 190)
        bottom.set_yticks([-180, -90, 0, 90, 180])
        bottom.set_xlabel("tuning ratio η = Ω/ω_t [-]")
        bottom.set_xlim(eta.min(), eta.max())
        bottom.legend(loc="lower left", ncols=4)
        fig.suptitle(f"Stiff coupling (Strümpfel): ω_t = {coupling.natural_frequency:.5g} rad/s, "
                     f"D = {coupling.damping_ratio:.3g}")
    return fig


def _broken(eta: np.ndarray, degrees: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """η and the phase with a NaN point inserted where it jumps by more than ``JUMP``, so
    that no vertical line crosses the panel (the values stay in (−180°, 180°])."""
    jumps = np.flatnonzero(np.abs(np.diff(degrees)) > JUMP) + 1
    return np.insert(eta.astype(float), jumps, np.nan), np.insert(degrees, jumps, np.nan)


def _operating(ax, operating) -> None:
    """Markers at the operating points on every curve, each speed named."""
    for k, (name, _, _, _) in enumerate(CURVES):
        values = np.where(np.isfinite(operating.response.transfer[name]),
                          operating.response.transfer[name], np.nan)
        ax.plot(operating.eta, values, linestyle="none", marker=canvas.MARKERS[k], markersize=6,
                markerfacecolor=canvas.COLOURS[k], markeredgecolor="black", zorder=6,
                gid=f"operating-{name}")
    for rpm, eta in zip(operating.speeds_rpm, operating.eta):
        ax.axvline(eta, color="0.3", linestyle=canvas.DASHES[2], linewidth=0.8, zorder=1,
                   gid="operating")
        ax.annotate(f"{rpm:g} rpm", (eta, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(2, -2), textcoords="offset points", rotation=90, va="top",
                    fontsize=6.5)
