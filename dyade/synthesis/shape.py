"""Shape distances between a target path and many traced curves, vectorised over the
candidates: independent of where a closed curve starts (and which way it runs), of its
placement, and optionally of its scale; the similarity that matches them is recovered.

Both curves are resampled at ``K`` points equally spaced in arc length, centred, and
compared over every cyclic shift at once in the Fourier domain: with Z and W the
discrete Fourier transforms of the target z and the candidate w, the correlation
c_m = Σ_k conj(w_{k+m})·z_k of every shift m is one inverse transform of conj(W)·Z
(the Fourier descriptors of both curves, each harmonic's phase turning with the
shift). The best similarity z ≈ α·w_{·+m} is α = c_m/‖w‖² (scale free) or
α = c_m/|c_m| (rigid), leaving the residual ‖z‖² − |c_m|²/‖w‖² or
‖z‖² + ‖w‖² − 2|c_m|.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray

SAMPLES = 64
"""points of the arc-length resampling"""


def resample(curves: np.ndarray, count: int = SAMPLES, closed: bool = True) -> np.ndarray:
    """(candidates, count) complex: each row's polyline resampled at ``count`` points
    equally spaced in arc length (closed: around the loop back to its start); rows
    with a NaN or of no length are NaN."""
    z = np.atleast_2d(curves)
    rows, n = z.shape
    ring = np.concatenate([z, z[:, :1]], axis=1) if closed else z
    steps = np.abs(np.diff(ring, axis=1))
    total = steps.sum(axis=1)
    bad = ~(total > 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        cumulative = np.concatenate([np.zeros((rows, 1)), np.cumsum(steps, axis=1)], axis=1)
        cumulative /= total[:, None]
    cumulative[bad] = np.linspace(0.0, 1.0, ring.shape[1])
    # one sorted axis for every row: row r's arc positions shifted by 2r
    offset = 2.0 * np.arange(rows)[:, None]
    flat = (cumulative + offset).ravel()
    where = np.arange(count) / count if closed else np.linspace(0.0, 1.0, count)
    wanted = (where[None, :] + offset).ravel()
    index = np.clip(np.searchsorted(flat, wanted, side="right") - 1, 0, flat.size - 2)
    row_end = (np.arange(rows) + 1) * ring.shape[1] - 2  # the last segment's start per row
    index = np.minimum(index, np.repeat(row_end, count))
    lo, hi = flat[index], flat[index + 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(hi > lo, (wanted - lo) / (hi - lo), 0.0)
    values = ring.ravel()
    out = (values[index] * (1.0 - t) + values[index + 1] * t).reshape(rows, count)
    out[bad] = np.nan
    return out


@dataclass(slots=True, eq=False)
class Match:
    """The best similarity of each candidate onto the target."""

    error: FloatArray
    """(candidates,) RMS distance after the best similarity, over the target's RMS
    radius about its centroid [-]; inf where the candidate is not a curve"""
    factor: np.ndarray
    """(candidates,) complex α: scale·e^{iθ} applied to the candidate"""
    shift: np.ndarray
    """(candidates,) int: the cyclic shift of the candidate's samples"""
    reversed: np.ndarray
    """(candidates,) bool: the candidate runs the other way round"""
    centre: np.ndarray
    """(candidates,) complex: the candidate's centroid, before the similarity"""


def closed_match(target: np.ndarray, curves: np.ndarray, scale: bool = True,
                 either_way: bool = True) -> Match:
    """The start-point-free shape distance of every candidate curve to a closed target.

    Parameters
    ----------
    target : ndarray, shape (K,)
        The target resampled (``resample``), complex [m].
    curves : ndarray, shape (candidates, K)
        The candidates resampled likewise.
    scale : bool
        Free scale (else only rotation and translation).
    either_way : bool
        A candidate may run either way round the curve.
    """
    z = target - target.mean()
    norm_z = float(np.vdot(z, z).real)
    w = curves - curves.mean(axis=1, keepdims=True)
    centre = curves.mean(axis=1)
    spectra = np.fft.fft(z)
    best = _shifts(spectra, w, norm_z, scale)
    if either_way:
        back = _shifts(spectra, w[:, ::-1], norm_z, scale)
        flip = back[0] < best[0]
        best = tuple(np.where(flip, b, a) for a, b in zip(best, back))
    else:
        flip = np.zeros(len(w), dtype=bool)
    residual, factor, shift = best
    with np.errstate(invalid="ignore"):
        error = np.sqrt(np.maximum(residual, 0.0) / norm_z)
    error = np.where(np.isfinite(error), error, np.inf)
    return Match(error, factor, shift.astype(int), flip, centre)


def _shifts(spectra: np.ndarray, w: np.ndarray, norm_z: float, scale: bool):
    """(residual, α, shift) of the best cyclic shift of each row of w onto z."""
    count = w.shape[1]
    # c_m = Σ_k conj(w_{k+m})·z_k = (1/K)·Σ_f conj(W_f)·Z_f·e^{−2πi·fm/K}
    corr = np.fft.fft(np.conj(np.fft.fft(w, axis=1)) * spectra[None, :], axis=1) / count
    norm_w = np.einsum("ij,ij->i", w.conj(), w).real
    size = np.abs(corr)
    with np.errstate(invalid="ignore", divide="ignore"):
        if scale:
            residual = norm_z - size ** 2 / norm_w[:, None]
        else:
            residual = norm_z + norm_w[:, None] - 2.0 * size
    residual = np.where(np.isnan(residual), np.inf, residual)
    shift = np.argmin(residual, axis=1)
    rows = np.arange(w.shape[0])
    c = corr[rows, shift]
    with np.errstate(invalid="ignore", divide="ignore"):
        factor = c / norm_w if scale else c / np.abs(c)
    return residual[rows, shift], factor, shift


def timed_match(target: np.ndarray, crank: FloatArray, curves: np.ndarray,
                scale: bool = True) -> Match:
    """The distance of every candidate to a target whose points come at known crank
    angles (relative to an unknown zero): each candidate (C, M) sampled at M equal steps
    of a turn is read at the target's angles from every one of its M samples as the
    zero (linearly between samples), and the best similarity z ≈ α·w + β of each start
    kept.

    Returns a ``Match`` whose ``shift`` is the sample of the best zero.
    """
    z = np.asarray(target)
    count, m = curves.shape
    steps = (np.asarray(crank) - crank[0]) / (2.0 * np.pi / m)
    base = np.floor(steps).astype(int)
    t = steps - base
    index = (np.arange(m)[:, None] + base[None, :]) % m  # (M, N)
    w = curves[:, index] * (1.0 - t) + curves[:, (index + 1) % m] * t  # (C, M, N)
    zc = z - z.mean()
    norm_z = float(np.vdot(zc, zc).real)
    wc = w - w.mean(axis=2, keepdims=True)
    corr = np.einsum("cmn,n->cm", wc.conj(), zc)
    norm_w = np.einsum("cmn,cmn->cm", wc.conj(), wc).real
    with np.errstate(invalid="ignore", divide="ignore"):
        if scale:
            residual = norm_z - np.abs(corr) ** 2 / norm_w
        else:
            residual = norm_z + norm_w - 2.0 * np.abs(corr)
    residual = np.where(np.isnan(residual), np.inf, residual)
    shift = np.argmin(residual, axis=1)
    rows = np.arange(count)
    c = corr[rows, shift]
    with np.errstate(invalid="ignore", divide="ignore"):
        factor = c / norm_w[rows, shift] if scale else c / np.abs(c)
        error = np.sqrt(np.maximum(residual[rows, shift], 0.0) / norm_z)
    centre = w[rows, shift].mean(axis=1)
    return Match(np.where(np.isfinite(error), error, np.inf), factor, shift,
                 np.zeros(count, dtype=bool), centre)


FRACTIONS = np.geomspace(0.08, 0.92, 12)
"""the parts of a candidate's closed curve (by arc length) an open target is matched
against in a search's first pass, each from every start (22 % apart)"""
FINE_FRACTIONS = np.geomspace(0.04, 0.96, 40)
"""... and when a kept candidate's placement is recovered (8 % apart)"""
OPEN_SAMPLES = 16
"""points of an open target's arc-length resampling in the first pass"""
FINE_SAMPLES = 32
"""... and for the placement of a kept candidate"""


def open_match(target: np.ndarray, curves: np.ndarray, scale: bool = True,
               either_way: bool = True, fractions: FloatArray = FRACTIONS) -> Match:
    """The distance of an open target (a part of a curve: where it starts on the
    candidate's closed curve, how much of it it covers and the timing all unknown) to
    every window of each candidate's closed curve.

    For each fraction f of the candidate's arc length, the candidate is resampled at
    n = (K − 1)/f points equally spaced in arc length around its loop, so that K
    consecutive samples cover the part f; the correlation of the target with the
    window starting at every sample m is one transform, c_m = Σ_k conj(w_{m+k})·z_k
    (z centred), and each window's sum and sum of squares (its centroid and norm about
    it) come from cumulative sums. The best similarity of every window is that of
    ``closed_match``; the best window over the fractions, starts and directions kept.

    Parameters
    ----------
    target : ndarray, shape (K,)
        The target resampled as an open curve (``resample(..., closed=False)``),
        complex [m].
    curves : ndarray, shape (candidates, M)
        The candidates' closed curves, in order (any sampling), complex [m].

    Returns
    -------
    Match
        ``shift``: the window's first sample at the best fraction; ``centre``: the
        window's centroid (the similarity is z ≈ mean(z) + α·(w − centre)).
    """
    z = np.asarray(target)
    count = z.size
    zc = z - z.mean()
    norm_z = float(np.vdot(zc, zc).real)
    rows = np.arange(len(curves))
    best = np.full(len(curves), np.inf)
    factor = np.full(len(curves), np.nan + 0j)
    centre = np.full(len(curves), np.nan + 0j)
    shift = np.zeros(len(curves), dtype=int)
    flip = np.zeros(len(curves), dtype=bool)
    for fraction in fractions:
        n = max(count, int(round((count - 1) / fraction)))
        w = resample(curves, n, closed=True)
        padded = np.zeros(n, dtype=complex)
        padded[:count] = zc
        spectrum = np.conj(np.fft.fft(padded))
        for back in ((False, True) if either_way else (False,)):
            v = w[:, ::-1] if back else w
            # conj(c_m) = Σ_k w_{m+k}·conj(z_k): one cyclic correlation
            corr = np.conj(np.fft.ifft(np.fft.fft(v, axis=1) * spectrum[None, :], axis=1))
            ring = np.concatenate([v, v[:, :count - 1]], axis=1)
            first = np.concatenate([np.zeros((len(v), 1)), np.cumsum(ring, axis=1)], axis=1)
            second = np.concatenate([np.zeros((len(v), 1)),
                                     np.cumsum(np.abs(ring) ** 2, axis=1)], axis=1)
            sums = first[:, count:count + n] - first[:, :n]
            squares = second[:, count:count + n] - second[:, :n]
            norm_w = squares - np.abs(sums) ** 2 / count
            size = np.abs(corr)
            with np.errstate(invalid="ignore", divide="ignore"):
                residual = (norm_z - size ** 2 / norm_w if scale
                            else norm_z + norm_w - 2.0 * size)
            residual = np.where(np.isnan(residual) | ~(norm_w > 0), np.inf, residual)
            at = np.argmin(residual, axis=1)
            value = residual[rows, at]
            better = value < best
            if not better.any():
                continue
            c = corr[rows, at]
            with np.errstate(invalid="ignore", divide="ignore"):
                alpha = c / norm_w[rows, at] if scale else c / np.abs(c)
            best = np.where(better, value, best)
            factor = np.where(better, alpha, factor)
            centre = np.where(better, sums[rows, at] / count, centre)
            shift = np.where(better, at, shift)
            flip = np.where(better, back, flip)
    with np.errstate(invalid="ignore"):
        error = np.sqrt(np.maximum(best, 0.0) / norm_z)
    return Match(np.where(np.isfinite(error), error, np.inf), factor, shift, flip, centre)
