"""The benchmark yardstick must compute the same four-bar as dyade (else the ratio is
meaningless)."""

import numpy as np

from dyade.linkage import sweep as analysis
from dyade.files import mechanism as toml_input
from tests.benchmarks.yardstick import fourbar, slider_crank
from tests.helpers import shipped


def test_yardstick_agrees_with_dyade():
    mechanism = toml_input.read_mechanism(shipped("fourbar.toml"))
    result = analysis.analyse(mechanism)
    ref = fourbar(result.crank_angle, mechanism.crank.speed)
    motion = result.kinematics.motion
    assert np.allclose(motion.omega[:, 3], ref["omega3"], rtol=1e-9)
    assert np.allclose(motion.alpha[:, 4], ref["alpha4"], rtol=1e-9)
    assert np.allclose(result.forces.revolute[(3, 4)], np.stack((ref["F34x"], ref["F34y"]), -1),
                       rtol=1e-8, atol=1e-8)
    assert np.allclose(result.forces.drive_torque, ref["M_drive"], rtol=1e-8, atol=1e-9)


def test_slider_crank_yardstick_agrees_with_dyade():
    mechanism = toml_input.read_mechanism(shipped("slider-crank.toml"))
    result = analysis.analyse(mechanism)
    ref = slider_crank(result.crank_angle, mechanism.crank.speed)
    motion = result.kinematics.motion
    cols = result.columns()
    assert np.allclose(motion.omega[:, 3], ref["omega3"], rtol=1e-9)
    assert np.allclose(motion.alpha[:, 3], ref["alpha3"], rtol=1e-9)
    assert np.allclose(cols["ax_3_4"], ref["a_B"], rtol=1e-9, atol=1e-9)
    assert np.allclose(result.forces.revolute[(3, 4)], np.stack((ref["F34x"], ref["F34y"]), -1),
                       rtol=1e-8, atol=1e-8)
    assert np.allclose(result.forces.drive_torque, ref["M_drive"], rtol=1e-8, atol=1e-9)


def test_variant_yardstick_agrees_with_a_study(tmp_path):
    """The variants' yardstick (tests/benchmarks/test_study_speed.py) gives the study's
    key results."""
    import numpy as np

    import dyade
    from tests.benchmarks.yardstick import fourbar_variants
    from tests.helpers import shipped

    study = tmp_path / "study.toml"
    study.write_text(f'mechanism = "{shipped("fourbar.toml")}"\n[parameters]\n'
                     f'"dyad.2.lengths.1" = [190, 215]\n"dyad.2.lengths.2" = [140, 160]\n')
    cols = dyade.study(str(study)).columns()
    want = fourbar_variants(cols["dyad.2.lengths.1"] / 1000, cols["dyad.2.lengths.2"] / 1000,
                            np.deg2rad(np.arange(361.0)), 10 * np.pi)
    outputs = set(cols) - {"variant", "status", "reason", "dyad.2.lengths.1",
                           "dyad.2.lengths.2"}
    assert outputs == set(want)  # the yardstick computes every output the study gives
    for name, values in want.items():
        assert np.allclose(cols[name], values, rtol=1e-9, atol=1e-12), name
