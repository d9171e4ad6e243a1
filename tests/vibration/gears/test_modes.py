"""Natural frequencies and modes of gear drives (Berczyński, Maćkowiak, Marchelek 1978):
a published example, and the invariants every mode must keep."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

import dyade
from dyade.vibration.gears.assembly import assemble
from dyade.vibration.gears.modes import NullSpace, gear_modes, multipliers, sizeless
from tests.helpers import shipped

SHIPPED = ["gears/friswell-geared.toml", "gears/two-stage.toml"]


def test_friswell_geared_system():
    # Friswell, Penny, Garvey, Lees, Dynamics of Rotating Machines (2010), geared motor
    # with two rotors: the book prints 425.4, 634.1 and 3247.2 Hz (one decimal)
    modes = gear_modes(dyade.read_gears(shipped("gears/friswell-geared.toml")))
    assert [round(float(f), 1) for f in modes.frequencies] == [425.4, 634.1, 3247.2]
    # an independent solve (gear 2 folded onto gear 1 by the ratio 1, scipy.linalg.eigh):
    j = np.diag([400e-6, 25e-6 + 25e-6, 700e-6, 700e-6])  # motor, gears, rotor 3, rotor 4
    k = np.zeros((4, 4))
    for a, b, stiffness in ((0, 1, 1e4), (1, 2, 5e3), (1, 3, 5e3)):
        k[np.ix_([a, b], [a, b])] += stiffness * np.array([[1, -1], [-1, 1]])
    reference = np.sqrt(np.abs(scipy.linalg.eigh(k, j, eigvals_only=True)[1:])) / (2 * np.pi)
    assert np.allclose(reference, [425.3595, 634.0728, 3247.1924], rtol=0, atol=5e-5)
    assert np.allclose(modes.frequencies, reference, rtol=1e-10)
    # the free drive turns as a whole: one rigid-body mode, not a 0 Hz resonance
    assert modes.rigid.shape[1] == 1 and modes.frequencies.size == 3


@pytest.mark.parametrize("name", SHIPPED)
def test_modes_are_m_orthonormal_and_satisfy_the_constrained_equations(name):
    modes = gear_modes(dyade.read_gears(shipped(name)))
    system = modes.system
    m, k, g = np.diag(system.mass), system.stiffness, system.constraints
    phi = np.hstack([modes.rigid, modes.shapes])
    assert np.allclose(phi.T @ m @ phi, np.eye(phi.shape[1]), atol=1e-10)
    assert np.max(np.abs(g.T @ phi)) < 1e-12 * np.max(np.abs(g)) * np.max(np.abs(phi))
    # K·φ − ω²·M·φ = g·λ with λ from the paper's multiplier formula (eq. 27)
    lam = multipliers(system, k @ modes.shapes)
    residual = k @ modes.shapes - m @ modes.shapes * modes.eigenvalues - g @ lam
    assert np.max(np.abs(residual)) < 1e-9 * np.max(np.abs(k @ modes.shapes))
    expected = -system.senses[:, None] * lam
    sized = [k for k in system.ideal if k not in sizeless(system)]  # no module: NaN (issue 28)
    rows = [list(system.ideal).index(k) for k in sized]
    assert np.allclose(modes.mesh_forces[sized], expected[rows], rtol=1e-9,
                       atol=1e-9 * np.max(np.abs(expected), initial=0.0))
    assert np.isnan(modes.mesh_forces[sizeless(system)]).all()
    # rigid-body modes store no strain energy
    assert np.max(np.abs(k @ modes.rigid)) < 1e-9 * np.max(np.abs(k))


@pytest.mark.parametrize("name", SHIPPED)
def test_energy_shares_sum_to_one_and_to_the_modal_energy(name):
    modes = gear_modes(dyade.read_gears(shipped(name)))
    kinetic = sum(modes.kinetic.values())
    strain = sum(modes.strain.values())
    assert np.allclose(kinetic, 1.0, rtol=1e-12) and np.allclose(strain, 1.0, rtol=1e-12)
    # the elements' energies add up to ½·φᵀKφ = ½·ω² (M-orthonormal modes): the element
    # maps and the assembled K agree
    system = modes.system
    parts = np.zeros(modes.frequencies.size)
    for e in range(len(system.elements)):
        deform = system.element_maps[e] @ modes.shapes[system.element_dofs[e]]
        parts += 0.5 * system.element_stiffness[e] @ deform ** 2
    assert np.allclose(parts, 0.5 * modes.eigenvalues, rtol=1e-9)


def test_null_space_is_orthonormal_and_annihilates_the_constraints():
    system = assemble(dyade.read_gears(shipped("gears/two-stage.toml")))
    null = NullSpace.of(system.constraints)
    n = null.matrix()
    assert n.shape == (system.size, system.size - 2)
    assert np.allclose(n.T @ n, np.eye(n.shape[1]), atol=1e-14)
    assert np.max(np.abs(system.constraints.T @ n)) < 1e-14
    assert np.allclose(null.reduce(system.stiffness), n.T @ system.stiffness @ n, rtol=1e-12,
                       atol=1e-6)


def test_modes_agree_with_a_dense_reduction():
    """The structured reduction against the textbook one: dense N, scipy's generalized
    eigh of NᵀKN and NᵀMN."""
    modes = gear_modes(dyade.read_gears(shipped("gears/two-stage.toml")))
    system = modes.system
    n = NullSpace.of(system.constraints).matrix()
    values = scipy.linalg.eigh(n.T @ system.stiffness @ n, n.T @ np.diag(system.mass) @ n,
                               eigvals_only=True)
    assert np.allclose(np.sort(values)[1:], modes.eigenvalues, rtol=1e-9)
