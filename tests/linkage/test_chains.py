"""Random mechanisms with outer joints on any placed link, through `dyade analyse
--format csv` (issue 14): no traceback; every row marked valid passes the closure, the
central differences and the power balance; no valid value beyond the plausibility
bound."""

from __future__ import annotations

import numpy as np
import pytest
import tomlkit
from click.testing import CliRunner
from hypothesis import given

from dyade.cli import main
from dyade.files.mechanism import build
from dyade.linkage import kinematics
from dyade.linkage import motion as joints
from dyade.linkage.columns import PLAUSIBLE
from tests.helpers import kinematics_at, read_csv
from tests.strategies import chained_files
from tests.linkage.test_kinetostatics import applied_power, kinetic_energy_rate

H = 1e-6  # [rad] central-difference step of the crank angle


@pytest.mark.slow  # 4 s: the default suite's budget
@given(data=chained_files())
def test_random_chains_through_the_command(data, tmp_path_factory):
    path = tmp_path_factory.mktemp("chain") / "chain.toml"
    path.write_text(tomlkit.dumps(data))
    result = CliRunner().invoke(main, ["analyse", str(path), "--format", "csv", "--allow-partial",
                                       "--step", "2"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    assert "Traceback" not in result.output
    if result.exit_code == 1:  # closes nowhere, or nothing given anywhere: said so
        assert ("closes at no crank angle" in result.output or "cannot close" in result.output
                or "no position of the sweep has its kinematics given" in result.output)
        return
    cols = read_csv(result.stdout)
    valid = cols["kinematics_valid"] == 1
    for name, values in cols.items():
        assert not np.any(np.abs(values[valid]) > PLAUSIBLE), name
    if not valid.any():
        return
    mechanism = build(data, str(path))
    angles = np.deg2rad(cols["angle_deg"][valid])
    here = kinematics_at(mechanism, angles)
    assert here.valid.all()
    places = [np.abs(values[valid]) for name, values in cols.items()
              if name.startswith(("x_", "y_"))]
    size = max(float(np.nanmax(np.concatenate(places))), mechanism.crank.length)  # [m]
    for joint in mechanism.joints:  # closure to round-off
        res = joints.residual(joint, here.motion)
        reach = max(size, float(np.nanmax(np.abs(here.motion.origin))))  # frames may lie far
        if joint.kind == "P":  # (relative angle [rad], distance from the guide [m])
            assert np.max(np.abs(res[:, 0])) < 1e-12, joint.name
            res = res[:, 1]
        assert np.max(np.abs(res)) < 1e-11 * reach, joint.name
    # central differences of positions and velocities against the velocities and
    # accelerations, where the neighbouring positions are valid too
    ahead, behind = kinematics_at(mechanism, angles + H), kinematics_at(mechanism, angles - H)
    ok = ahead.valid & behind.valid
    omega = mechanism.crank.speed
    for link in mechanism.moving_links:
        v = here.motion.velocity[ok, link]
        a = here.motion.acceleration[ok, link]
        fd_v = (ahead.motion.origin[ok, link] - behind.motion.origin[ok, link]) / (2 * H) * omega
        fd_a = (ahead.motion.velocity[ok, link] - behind.motion.velocity[ok, link]) / (2 * H) * omega
        typical_v = max(np.max(np.abs(v), initial=0.0), size * abs(omega))
        typical_a = max(np.max(np.abs(a), initial=0.0), size * omega ** 2)
        assert np.max(np.abs(fd_v - v), initial=0.0) <= 1e-4 * typical_v, link
        assert np.max(np.abs(fd_a - a), initial=0.0) <= 1e-3 * typical_a, link
    # the power balance with the masses, where forces are given: M_drive·Ω = dE/dt − P_applied
    given = cols["forces_valid"][valid] == 1
    assert np.all(np.isfinite(cols["M_drive"][valid][given]))
    assert not np.isfinite(cols["M_drive"][valid][~given]).any()
    forces = cols["M_drive"][valid][given] * omega
    rhs = (kinetic_energy_rate(mechanism, here.motion)
           - applied_power(mechanism, here.motion, angles))[given]
    if not given.any():
        return
    mass = sum(link.mass for link in mechanism.links.values())
    physical = mass * (size * omega) ** 2 * abs(omega)  # [W] a power of this machine's size
    scale = max(np.max(np.abs(rhs)), physical)
    assert np.allclose(forces, rhs, rtol=0, atol=1e-8 * scale)
