"""The paper's elimination of the multipliers (eqs. (27)–(33)) against the null-space
reduction: the same natural frequencies, and exactly one extra zero eigenvalue per mesh."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given

import dyade
from dyade.vibration.gears.elimination import check, eliminated
from dyade.vibration.gears.assembly import assemble
from dyade.vibration.gears.modes import gear_modes
from tests.vibration.gears.drives import build, random_drives
from tests.helpers import shipped


def _agrees(result, meshes: int) -> None:
    assert result.difference < 1e-9, result.difference
    assert result.extra_zeros == meshes
    assert result.meshes == meshes
    assert result.largest_imaginary < 1e-9


@pytest.mark.parametrize("name, meshes, rigid", [("gears/friswell-geared.toml", 1, 1),
                                                 ("gears/two-stage.toml", 2, 1)])
def test_shipped_drives(name, meshes, rigid):
    result = check(dyade.read_gears(shipped(name)))
    _agrees(result, meshes)
    assert result.rigid_zeros == rigid


@given(data=random_drives())
def test_generated_drives(data):
    """1e-9 wherever double precision allows it. Both solutions carry a round-off of about
    eps·ω²_max/ω² in ω² (the symmetric eigh and the paper's non-symmetric form alike; the
    measured differences stay below 5·eps·ω²_max/ω²_min): so 1e-9 on drives whose
    eigenvalues spread over up to 10⁵, and 50·eps·spread on stiffer ones (tiny pinions in
    stiff bearings, finely divided short shafts)."""
    drive = build(data)
    modes = gear_modes(drive)
    result = check(drive, modes)
    spread = modes.eigenvalues.max() / modes.eigenvalues.min()
    tolerance = 1e-9 if spread <= 1e5 else 50 * np.finfo(float).eps * spread
    assert result.difference < tolerance, (result.difference, spread)
    assert result.extra_zeros == result.meshes == len(assemble(drive).ideal)


def test_the_eliminated_form_is_the_papers_formula():
    """K_f = −g(gᵀM⁻¹g)⁻¹gᵀM⁻¹K (eq. 30) makes the constraint forces vanish from the
    accelerations: gᵀM⁻¹(K + K_f) = 0, so gᵀq'' = 0 for every q."""
    system = assemble(dyade.read_gears(shipped("gears/two-stage.toml")))
    k_f, l_f, f = eliminated(system)
    g, inverse = system.constraints, 1.0 / system.mass
    k = system.stiffness
    assert np.max(np.abs(g.T @ (inverse[:, None] * (k + k_f)))) < 1e-9 * np.max(
        np.abs(g.T @ (inverse[:, None] * k)))
    assert np.allclose(f @ f, f, atol=1e-12)  # a projector
    assert np.allclose(l_f, -f @ system.damping)
