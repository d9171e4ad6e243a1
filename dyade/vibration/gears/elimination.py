"""The paper's own solution: the multipliers eliminated (Berczyński, Maćkowiak and
Marchelek 1978, eqs. (27)-(33)), as a check of the null-space reduction.

Differentiating the constraints twice and eliminating the multipliers gives

    λ = (gᵀM⁻¹g)⁻¹·gᵀM⁻¹·(L·q' + K·q − P)                                  (27)
    M·q'' + (L + L_f)·q' + (K + K_f)·q = P + P_f                            (32)
    L_f = −g(gᵀM⁻¹g)⁻¹gᵀM⁻¹L,  K_f = −g(gᵀM⁻¹g)⁻¹gᵀM⁻¹K,  P_f = −g(gᵀM⁻¹g)⁻¹gᵀM⁻¹P

with all n coordinates kept. K + K_f is not symmetric, and the constraints hold only at
the acceleration level (gᵀq'' = 0): the eigenproblem M⁻¹(K + K_f)·q = ω²·q has the
constrained drive's n − l − r elastic eigenvalues, its r rigid-body zeros, and one extra
zero per mesh, whose eigenvectors violate the constraint (they are the motions the
eliminated form no longer resists). ``check`` solves it with ``numpy.linalg.eig`` and
reports these zeros separately from the rigid-body modes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError
from dyade.model.gears import GearDrive
from dyade.vibration.gears.assembly import System, assemble
from dyade.vibration.gears.modes import Modes, gear_modes

SEPARATION = 1e3  # [-] the smallest elastic |ω²| must exceed the largest "zero" this often
RANK_RTOL = 1e-8  # [-] singular values of gᵀ·(zero eigenvectors) that count as violations


def eliminated(system: System) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(K_f, L_f, F) of eqs. (29)-(31): K_f = −F·K, L_f = −F·L, P_f = −F·P with
    F = g(gᵀM⁻¹g)⁻¹gᵀM⁻¹."""
    g, inverse_mass = system.constraints, 1.0 / system.mass
    gram = g.T @ (inverse_mass[:, None] * g)
    f = g @ np.linalg.solve(gram, g.T * inverse_mass[None, :])
    return -f @ system.stiffness, -f @ system.damping, f


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Elimination:
    """The eliminated form's eigenvalues against the null-space modes."""

    frequencies: FloatArray
    """(k,) elastic natural frequencies of eq. (33) [Hz], ascending"""
    reference: FloatArray
    """(k,) the null-space frequencies [Hz]"""
    difference: float
    """largest relative difference between the two"""
    extra_zeros: int
    """zero eigenvalues whose eigenvectors violate the constraints (one per constraint:
    ideal mesh or rigid direction)"""
    rigid_zeros: int
    """zero eigenvalues of rigid-body modes (they satisfy the constraints)"""
    zeros: FloatArray
    """the eigenvalues counted as zero [1/s²] (their size shows the round-off)"""
    largest_imaginary: float
    """largest |Im ω²| / |ω²| among the elastic eigenvalues (0 in exact arithmetic)"""
    meshes: int
    """ideal meshes"""
    constraints: int
    """constraints (ideal meshes and rigid directions): the extra zeros there should be"""


def check(drive: GearDrive | System, modes: Modes | None = None) -> Elimination:
    """Solve the paper's eliminated form (32)-(33) and compare it with ``gear_modes``.

    Parameters
    ----------
    drive : GearDrive or System
    modes : Modes, optional
        The null-space solution, if already computed.

    Returns
    -------
    Elimination
        Frequencies of both, their largest relative difference, and the zero eigenvalues
        split into the extra ones (one per ideal mesh) and the rigid-body ones.

    Raises
    ------
    DyadeError
        When the zero eigenvalues cannot be told from the elastic ones.

    Examples
    --------
    >>> import dyade
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> result = dyade.check_elimination(drive)
    >>> result.extra_zeros, result.rigid_zeros, result.difference < 1e-9
    (2, 1, True)
    """
    system = drive if isinstance(drive, System) else assemble(drive)
    modes = modes if modes is not None else gear_modes(system)
    k_f, _, _ = eliminated(system)
    scale = 1.0 / np.sqrt(system.mass)
    # M⁻¹(K + K_f) is similar to M^-½·(K + K_f)·M^-½, which is better scaled
    a = scale[:, None] * (system.stiffness + k_f) * scale[None, :]
    values = np.linalg.eigvals(a)
    values = values[np.argsort(np.abs(values))]
    zero_count = system.constraints.shape[1] + modes.rigid.shape[1]
    elastic = values[zero_count:]
    zeros = values[:zero_count]
    biggest_zero = float(np.max(np.abs(zeros), initial=0.0))
    if elastic.size and np.min(np.abs(elastic)) < SEPARATION * biggest_zero:
        raise DyadeError(f"the eliminated form's {zero_count} zero eigenvalues cannot be told "
                         f"from its elastic ones (|ω²| {biggest_zero:.3g} against "
                         f"{np.min(np.abs(elastic)):.3g} 1/s²): the drive is too stiff for "
                         f"this check in double precision.")
    # the zero eigenvalues' eigenvectors: the null space of the eliminated matrix (by SVD;
    # eig's vectors for a repeated eigenvalue may come out parallel), and how many
    # independent directions of it violate the constraints
    _, sigma, vt = np.linalg.svd(a)
    if zero_count and sigma[a.shape[0] - zero_count] > 1e-6 * sigma[0]:
        raise DyadeError("the eliminated form's zero eigenvalues have fewer independent "
                         "eigenvectors than their count: their split into extra and rigid-body "
                         "zeros is not defined.")
    kernel = scale[:, None] * vt[a.shape[0] - zero_count:].T
    violating = system.constraints.T @ (kernel / np.linalg.norm(kernel, axis=0))
    sigma_g = np.linalg.svd(violating, compute_uv=False) if violating.size else np.zeros(0)
    norm = np.linalg.norm(system.constraints, axis=0).max(initial=1.0)
    extra = int(np.sum(sigma_g > RANK_RTOL * norm))
    elastic = elastic[np.argsort(elastic.real)]
    frequencies = np.sqrt(np.abs(elastic.real)) / (2.0 * np.pi)
    reference = modes.frequencies
    if frequencies.size != reference.size:
        raise DyadeError(f"the eliminated form has {frequencies.size} elastic frequencies, the "
                         f"null-space solution {reference.size}.")
    difference = float(np.max(np.abs(frequencies - reference) / reference, initial=0.0))
    imaginary = float(np.max(np.abs(elastic.imag) / np.abs(elastic), initial=0.0))
    return Elimination(frequencies, reference, difference, extra, zero_count - extra,
                       zeros.real.copy(), imaginary, len(system.ideal),
                       system.constraints.shape[1])
