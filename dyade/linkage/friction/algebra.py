"""Small-matrix algebra of the friction solution, at every position at once: the
wrench W_B = W_B⁰ + Σ τ_l·R_l, gradients times wrenches, and (I + K)⁻¹ and det(I + K)
for one to three unknowns, K (m, m, n) (cofactors; ``solver``)."""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray


def combine(w0: FloatArray, rows: list[FloatArray], taus: list[FloatArray]) -> FloatArray:
    """W_B = W_B⁰ + Σ τ_l·R_l."""
    out = w0.copy()
    term = np.empty_like(out)
    for tau, row in zip(taus, rows):
        np.multiply(row, tau, out=term)
        out += term
    return out


def dot(a, r, out: FloatArray | None = None) -> FloatArray:
    """a·R for a gradient (gx, gy, gm) and a wrench (three (n,) arrays; gm may be 0.0)."""
    out = np.multiply(a[0], r[0], out=out)
    out += a[1] * r[1]
    if not (isinstance(a[2], float) and a[2] == 0.0):
        out += a[2] * r[2]
    return out


def determinant(matrix: FloatArray) -> FloatArray:
    """det(I + K) (n,) for K (m, m, n), m ≤ 3."""
    m = matrix.shape[0]
    a = [[matrix[k, l] + 1.0 if k == l else matrix[k, l] for l in range(m)] for k in range(m)]
    if m == 1:
        return a[0][0]
    if m == 2:
        return a[0][0] * a[1][1] - a[0][1] * a[1][0]
    return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            + a[0][1] * (a[1][2] * a[2][0] - a[1][0] * a[2][2])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))


def invert_small(matrix: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(I + K)⁻¹ (m, m, n) and det(I + K) (n,) at every position, for one to three
    unknowns (cofactors); ``matrix`` holds K (m, m, n) and is turned into I + K. Where
    det = 0 the inverse is set to 0 (a friction dead centre: reported, never stepped
    over)."""
    m, n = matrix.shape[0], matrix.shape[2]
    a = matrix
    for k in range(m):
        a[k, k] += 1.0
    if m == 1:
        det = a[0, 0].copy()
        out = np.empty_like(a)
    elif m == 2:
        det = a[0, 0] * a[1, 1]
        det -= a[0, 1] * a[1, 0]
        out = np.empty_like(a)
        out[0, 0], out[1, 1] = a[1, 1], a[0, 0]
        np.negative(a[0, 1], out=out[0, 1])
        np.negative(a[1, 0], out=out[1, 0])
    else:
        out = np.empty_like(a)
        term = np.empty(n)
        for k, l, (p, q), (r, t) in _COFACTORS:  # out[k, l] = cofactor (l, k) = p·q − r·t
            np.multiply(a[p], a[q], out=out[k, l])
            np.multiply(a[r], a[t], out=term)
            out[k, l] -= term
        det = a[0, 0] * out[0, 0]
        det += a[0, 1] * out[1, 0]
        det += a[0, 2] * out[2, 0]
    scale = np.divide(1.0, det, out=np.zeros(n), where=det != 0.0)
    if m == 1:
        out[0, 0] = scale
    else:
        out *= scale
    return out, det


# (k, l, (p, q), (r, t)): entry (k, l) of the adjugate, a[p]·a[q] − a[r]·a[t]
_COFACTORS = [(0, 0, ((1, 1), (2, 2)), ((1, 2), (2, 1))),
              (1, 0, ((1, 2), (2, 0)), ((1, 0), (2, 2))),
              (2, 0, ((1, 0), (2, 1)), ((1, 1), (2, 0))),
              (0, 1, ((0, 2), (2, 1)), ((0, 1), (2, 2))),
              (1, 1, ((0, 0), (2, 2)), ((0, 2), (2, 0))),
              (2, 1, ((0, 1), (2, 0)), ((0, 0), (2, 1))),
              (0, 2, ((0, 1), (1, 2)), ((0, 2), (1, 1))),
              (1, 2, ((0, 2), (1, 0)), ((0, 0), (1, 2))),
              (2, 2, ((0, 0), (1, 1)), ((0, 1), (1, 0)))]


def apply(inverse: FloatArray, vector: list[FloatArray]) -> list[FloatArray]:
    """(I + K)⁻¹·vector."""
    out = []
    term = np.empty_like(vector[0])
    for row in inverse:
        total = row[0] * vector[0]
        for entry, value in zip(row[1:], vector[1:]):
            np.multiply(entry, value, out=term)
            total += term
        out.append(total)
    return out

