"""`dyade plot` (issue 16): checks on the figures' data, not on pixels.

The polar line is the CSV's forces, its reversal markers are where `dyade clearance`
reports reversals, a range the analysis warns about is a break in the line and a shaded
band, an undamped coupling resonance is a gap, an animation has one frame per step with
the links ending at the CSV's joint positions, every kind writes PNG, SVG (and PDF, GIF),
the same data gives the same bytes, and without matplotlib every plot command says
what to install (exit 2).
"""

from __future__ import annotations

import csv
import io
import sys

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.cli import main  # noqa: E402
from dyade.plot import animate, canvas, clearance as clearance_plot, coupling, curves  # noqa: E402
from dyade.plot import campbell as campbell_plot, mechanism, modes as modes_plot, polar  # noqa: E402
from tests.conftest import SHIPPED  # noqa: E402
from tests.helpers import read_csv, shipped  # noqa: E402

DEAD_CENTRE = {"dyad.2.lengths": [200, 100]}
"""the four-bar stretched at φ21 = 180° (50 + 200 = 250 − ... : |AC| = 300 = 200 + 100)"""
SHORT = {"dyad.2.lengths": [120, 100]}
"""the four-bar that cannot close where |AC| > 220 mm"""


def run(*args: str, env: dict | None = None):
    return CliRunner(env=env).invoke(main, [str(a) for a in args], catch_exceptions=False)


def csv_of(*args: str) -> dict[str, np.ndarray]:
    out = run("analyse", *args, "--format", "csv")
    assert out.exit_code == 0, out.output
    return read_csv(out.stdout)


def line(ax, gid: str):
    found = [artist for artist in ax.get_lines() if artist.get_gid() == gid]
    assert len(found) == 1, (gid, [a.get_gid() for a in ax.get_lines()])
    return found[0]


def same(a, b, atol=0.0, rtol=1e-14) -> bool:
    """Equal arrays, NaN where NaN; ``rtol``: the CSV prints 15 significant digits."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.all((np.isnan(a) & np.isnan(b))
                                              | (np.abs(a - b) <= atol + rtol * np.abs(b))))


# -- polar diagrams -----------------------------------------------------------------------
@pytest.mark.parametrize("name, overrides", [("dyade-16.toml", {}), ("fourbar.toml", DEAD_CENTRE)])
def test_polar_line_vertices_are_the_csv_forces(name, overrides):
    sets = [f"--set={key}={value}".replace(" ", "") for key, value in overrides.items()]
    table = csv_of(shipped(name), *sets)
    fig = polar.figure(dyade.analyse(dyade.read_mechanism(shipped(name), overrides)))
    titles = [ax.get_title().splitlines()[0] for ax in fig.axes if ax.get_visible()]
    joints = [j.name for j in dyade.read_mechanism(shipped(name)).joints if j.kind == "R"]
    assert titles == [f"joint ({a},{b}): force on link {b}" for a, b in joints]
    for ax, (a, b) in zip(fig.axes, joints):
        data = line(ax, f"force-{a}-{b}").get_xydata()
        assert same(data[:, 0], table[f"Fx_{a}_{b}"]) and same(data[:, 1], table[f"Fy_{a}_{b}"])
        assert ax.get_xlabel() == f"Fx_{a}_{b} [N]" and ax.get_ylabel() == f"Fy_{a}_{b} [N]"


def test_polar_breaks_where_the_forces_are_not_given():
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), DEAD_CENTRE))
    fig = polar.figure(result, [(3, 4)])
    fx = line(fig.axes[0], "force-3-4").get_xdata()
    gap = np.isnan(fx)
    angle = np.rad2deg(result.crank_angle)
    assert gap.any() and np.all((angle[gap] >= 178) & (angle[gap] <= 182))
    assert np.isfinite(fx[~gap]).all()
    assert f"gaps at {int(gap.sum())} positions" in fig.axes[0].get_title()


def test_polar_crank_angle_marks_sit_on_the_curve_every_30_degrees():
    table = csv_of(shipped("fourbar.toml"))
    fig = polar.figure(dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"))), [(2, 3)])
    marks = line(fig.axes[0], "crank-angles-2-3").get_xydata()
    at = np.isin(table["angle_deg"], np.arange(0, 360, 30))
    assert same(marks, np.column_stack((table["Fx_2_3"][at], table["Fy_2_3"][at])))
    labels = [t.get_text() for t in fig.axes[0].texts if t.get_text().endswith("°")]
    assert labels == [f"{deg}°" for deg in range(0, 360, 30)]


def test_polar_reversals_are_where_dyade_clearance_reports_them():
    args = [shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance", "1e-4",
            "--max-wander", "40", "--format", "csv"]
    out = run("clearance", *args)
    assert out.exit_code == 0, out.output
    reported: dict[str, list[float]] = {}
    for row in csv.DictReader(io.StringIO(out.stdout)):
        reported.setdefault(row["joint"], []).append(float(row["angle_deg"]))
    assert sum(len(v) for v in reported.values()) >= 10  # 40° lets (13,14) and more in
    table = csv_of(shipped("dyade-16.toml"))
    result = dyade.analyse(dyade.read_mechanism(shipped("dyade-16.toml")))
    fig = polar.figure(result, max_wander_deg=40)
    angle = table["angle_deg"]
    for ax in (ax for ax in fig.axes if ax.get_visible()):
        a, b = (int(v) for v in ax.get_title().split("(")[1].split(")")[0].split(","))
        markers = [artist for artist in ax.get_lines() if artist.get_gid() == f"reversals-{a}-{b}"]
        expected = reported.get(f"{a}-{b}", [])
        if not markers:
            assert not expected
            continue
        # the markers: the CSV force interpolated linearly at each reported reversal angle
        fx = np.interp(np.mod(expected, 360), angle, table[f"Fx_{a}_{b}"])
        fy = np.interp(np.mod(expected, 360), angle, table[f"Fy_{a}_{b}"])
        scale = np.nanmax(table[f"F_{a}_{b}"])
        assert np.allclose(markers[0].get_xydata(), np.column_stack((fx, fy)), rtol=0,
                           atol=1e-9 * scale), (a, b)
        numbers = [t.get_text() for t in ax.texts if t.get_text().isdigit()]
        assert numbers == [str(k) for k in range(1, len(expected) + 1)]
        assert all(f"{k} at {deg % 360:.1f}°" in ax.get_title()
                   for k, deg in enumerate(expected, 1))


def test_polar_of_a_mechanism_without_forces_says_why():
    out = run("plot", "polar", shipped("scotch-yoke.toml"), "-o", "never.png")
    assert out.exit_code == 2 and "need joint forces" in out.output


def test_polar_joint_not_revolute_names_the_flag(tmp_path):
    out = run("plot", "polar", shipped("slider-crank.toml"), "--joint", "1,4", "-o",
              tmp_path / "p.png")
    assert out.exit_code == 2
    assert "--joint" in out.output and "no revolute joint (1,4)" in out.output


# -- curves -----------------------------------------------------------------------------
def test_energy_surplus_from_the_curve():
    # issue 18's reference: T = 10000 + 2000 sin 2θ − 1800 cos 2θ N·m against its mean:
    # ΔE = 2·sqrt(1000² + 900²) = 2690.725 J; 0° and 360° counted once
    theta = np.linspace(0.0, 2 * np.pi, 721)
    mean, delta = curves.energy_surplus(theta, 10000 + 2000 * np.sin(2 * theta)
                                        - 1800 * np.cos(2 * theta))
    assert mean == pytest.approx(10000, rel=1e-12)
    assert delta == pytest.approx(2 * np.hypot(1000, 900), rel=1e-8)  # 0.5° steps: 4th order
    assert curves.energy_surplus(theta[:300], np.sin(theta[:300]))[1] is None  # no cycle


def test_default_curves_torque_mean_and_energy_against_the_csv():
    from scipy.integrate import cumulative_trapezoid

    table = csv_of(shipped("dyade-16.toml"))
    fig = curves.figure(dyade.analyse(dyade.read_mechanism(shipped("dyade-16.toml"))))
    torque_ax, mu_ax = fig.axes
    assert same(line(torque_ax, "M_drive").get_ydata(), table["M_drive"])
    # the mean and ΔE are the flywheel's, from the torque at 0.1° (a load table's kinks
    # need the fine step): scipy's trapezoid rule on the CSV at 0.1° agrees
    fine = csv_of(shipped("dyade-16.toml"), "--step", "0.1")
    phi = np.deg2rad(fine["angle_deg"])
    mean = np.trapezoid(fine["M_drive"], phi) / (2 * np.pi)
    assert line(torque_ax, "M_mean").get_ydata()[0] == pytest.approx(mean, rel=1e-9)
    energy = cumulative_trapezoid(fine["M_drive"] - mean, phi, initial=0.0)
    title = torque_ax.get_title()
    delta = float(title.split("ΔE = ")[1].split(" J")[0])
    assert delta == pytest.approx(energy.max() - energy.min(), rel=2e-4)
    for dyad in range(2, 9):
        assert same(line(mu_ax, f"mu_{dyad}_deg").get_ydata(), table[f"mu_{dyad}_deg"])
    assert torque_ax.get_ylabel() == "M_drive [N·m]"
    assert mu_ax.get_ylabel() == "transmission angle μ [°]"


def test_warned_ranges_are_shaded_named_and_breaks_in_the_line():
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), SHORT),
                           allow_partial=True)
    fig = curves.figure(result, ["F_3_4", "x_3_4", "y_3_4"])
    force_ax, position_ax = fig.axes
    assert position_ax.get_ylabel() == "[m]" and force_ax.get_ylabel() == "F_3_4 [N]"
    (first, last), = next(n for n in result.notes if n.kind == "partial").ranges
    for ax in fig.axes:
        bands = [p for p in ax.patches if p.get_gid() == "note-partial"]
        assert len(bands) == 1 and bands[0].get_label() == "does not close"
        x = bands[0].get_patch_transform().transform(bands[0].get_path().vertices)[:, 0]
        half = 0.5 * np.rad2deg(result.mechanism.sweep.step)
        assert x.min() == pytest.approx(np.rad2deg(first) - half)
        assert x.max() == pytest.approx(np.rad2deg(last) + half)
    y = line(position_ax, "x_3_4").get_ydata()
    angle = np.rad2deg(result.crank_angle)
    inside = (angle >= np.rad2deg(first) - 1e-9) & (angle <= np.rad2deg(last) + 1e-9)
    assert np.isnan(y[inside]).all() and np.isfinite(y[~inside]).all()


def test_dead_centre_band_and_note_on_the_transmission_angle():
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), DEAD_CENTRE))
    fig = curves.figure(result)
    torque_ax, mu_ax = fig.axes
    assert "not given everywhere" in torque_ax.get_title()
    assert sum(p.get_gid() == "dead-centre-band" for p in mu_ax.patches) == 2
    names = {p.get_label() for p in mu_ax.patches if p.get_gid() == "note-dead_centre"}
    assert names == {"dyad 2: near a dead centre"}


def test_unknown_column_names_the_flag_and_a_close_match(tmp_path):
    out = run("plot", "curves", shipped("fourbar.toml"), "--columns", "M_drve", "-o", tmp_path / "c.png")
    assert out.exit_code == 2
    assert "--columns" in out.output and "Did you mean M_drive" in out.output


# -- the mechanism and its animation ----------------------------------------------------------
def _check_frame(scene, table, mech, k):
    """Pins at the CSV's joints; bars between two revolute joints end at them; blocks
    centred on their slider points."""
    pins = scene.pins.get_xydata()
    revolute = [j for j in mech.joints if j.kind == "R"]
    for (x, y), joint in zip(pins, revolute):
        a, b = joint.name
        assert same([x, y], [table[f"x_{a}_{b}"][k], table[f"y_{a}_{b}"][k]], atol=1e-12)
    checked = 0
    for body, artist, _ in scene.bodies:
        ends = artist.get_xy() if body.plate else artist.get_xydata()
        on_link = [j for j in revolute if body.link in j.links]
        if body.plate or len(on_link) != 2:
            continue
        joints = {tuple(np.round([table[f"x_{a}_{b}"][k], table[f"y_{a}_{b}"][k]], 12))
                  for a, b in (j.name for j in on_link)}
        if len(joints) == 2 and len(_unique_points(ends)) == 2:
            assert {tuple(np.round(p, 12)) for p in ends} == joints, body.link
            checked += 1
    return checked


def _unique_points(points):
    return {tuple(np.round(p, 12)) for p in points}


@pytest.mark.parametrize("name", ["fourbar.toml", "watt-sixbar.toml", "dyade-16.toml",
                                  "slider-crank.toml"])
def test_animation_one_frame_per_step_links_end_at_the_joints(name, tmp_path):
    table = csv_of(shipped(name), "--step", "30")
    mech = dyade.read_mechanism(shipped(name))
    result = dyade.analyse(mech, step_deg=30)
    motion = animate.animation(result)
    assert motion.count == table["angle_deg"].size == 13
    checked = 0
    for k in range(motion.count):
        motion.update(k)
        checked += _check_frame(motion.scene, table, mech, k)
        assert motion.title.get_text() == f"φ21 = {table['angle_deg'][k]:6.1f}°"
        for slider, _, block in motion.scene.sliders:
            joint = next(j for j in mech.joints if j.name == slider.joint)
            centre = block.get_xy()[:4].mean(axis=0)
            expected = result.kinematics.motion.point(joint.slider, joint.slider_point)[k]
            assert same(centre, expected, atol=1e-12)
    assert checked >= 13  # every frame checked at least one bar
    if name != "slider-crank.toml":
        return  # the GIF (its bars and slider blocks) once: saving costs 1 s a frame
    path = tmp_path / "motion.gif"
    animate.save(motion, str(path), dpi=30)
    from PIL import Image

    with Image.open(path) as gif:
        assert gif.n_frames == motion.count


def test_still_mechanism_at_the_angles_asked():
    mech = dyade.read_mechanism(shipped("slider-crank.toml"))
    fig = mechanism.figure(dyade.analyse(mech), at_deg=[0, 45, 200])
    assert [ax.get_title() for ax in fig.axes if ax.get_visible()] == [
        "φ21 = 0°", "φ21 = 45°", "φ21 = 200°"]
    for ax, deg in zip(fig.axes, (0, 45, 200)):
        table = csv_of(shipped("slider-crank.toml"), "--at", str(deg))
        pins = line(ax, "pins").get_xydata()
        expected = [[table[f"x_{a}_{b}"][0], table[f"y_{a}_{b}"][0]]
                    for a, b in ((1, 2), (2, 3), (3, 4))]
        assert same(pins, expected, atol=1e-12)


def test_mechanism_at_a_blocked_angle_is_an_analysis_problem(tmp_path):
    out = run("plot", "mechanism", shipped("tangent-drive.toml"), "--at", "0,90", "-o",
              tmp_path / "m.png")
    assert out.exit_code == 1 and "blocked" in out.output


# -- coupling --------------------------------------------------------------------------------
def test_undamped_resonance_is_a_gap_not_a_spike():
    model = dyade.Coupling(1.0, 3.0, 1.0, 0.0, 0.0)  # η_res = sqrt(c2/(c1 + c2)) = 0.5
    eta = np.round(np.arange(0.0, 3.0 + 1e-9, 0.01), 12)
    response = dyade.coupling_response(model, eta)
    assert response.unbounded[50] and eta[50] == 0.5
    fig = coupling.figure(model, response)
    top, bottom = fig.axes
    for name in ("V_phi", "V_psi", "V_q"):
        y = line(top, name).get_ydata()
        values = response.transfer[name]
        far = np.abs(eta - 0.5) >= coupling.NEAR * 0.5
        finite_max = np.nanmax(np.where(np.isfinite(values[far]), values[far], np.nan))
        assert np.isnan(y[50])                                   # the resonance: a gap
        assert np.nanmax(y) <= coupling.FLANK * finite_max       # no spike above the cut
        assert np.nanmax(y) <= top.get_ylim()[1]
        kept = np.isfinite(y)
        assert same(y[kept], values[kept])                       # the rest is the data
    # η_res = sqrt(1/2) falls between grid points: α jumps 0° -> 180° between two finite
    # values there, and the line must break instead of drawing a vertical stroke
    model = dyade.Coupling(1.0, 1.0, 1.0, 0.0, 0.0)
    _, bottom = coupling.figure(model, dyade.coupling_response(model, eta)).axes
    for name in ("alpha", "beta", "gamma", "delta"):
        y = line(bottom, name).get_ydata()
        steps = np.abs(np.diff(y))
        assert np.all(steps[np.isfinite(steps)] <= coupling.JUMP)  # jumps are breaks
    x, y = line(bottom, "alpha").get_xdata(), line(bottom, "alpha").get_ydata()
    gap = np.flatnonzero(np.isnan(y))
    assert gap.size == 1 and (x[gap - 1], x[gap + 1]) == pytest.approx((0.70, 0.71))


def test_damped_coupling_draws_its_peak_and_operating_points():
    model = dyade.read_coupling(shipped("coupling/stiff-coupling.toml"))
    eta = np.arange(0.0, 3.0 + 1e-9, 0.01)
    response = dyade.coupling_response(model, eta)
    points = dyade.operating_points(model, [1450, 2900], order=2)
    top, _ = coupling.figure(model, response, points).axes
    for name in ("V_phi", "V_psi", "V_q", "V_r"):
        assert same(line(top, name).get_ydata(), response.transfer[name])
        assert same(line(top, f"operating-{name}").get_xydata(),
                    np.column_stack((points.eta, points.response.transfer[name])))
    eta0 = [a for a in top.get_lines() if a.get_gid() == "eta0"][0].get_xdata()[0]
    assert eta0 == pytest.approx(model.resonance())


def test_plot_coupling_takes_the_options_of_dyade_coupling(tmp_path):
    out = run("plot", "coupling", "--J", "1", "--c1", "3", "--c2", "1", "--log", "-o",
              tmp_path / "c.svg")
    assert out.exit_code == 0, out.output
    out = run("plot", "coupling", "--J", "-1", "--c1", "3", "--c2", "1", "-o", tmp_path / "c.svg")
    assert out.exit_code == 2 and "--J" in out.output


# -- clearance ---------------------------------------------------------------------------------
def test_clearance_points_history_and_speeds_are_the_api_numbers():
    out = run("clearance", shipped("dyade-16.toml"), "--stiffness", "1e8", "--clearance",
              "1e-4", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    mech = dyade.read_mechanism(shipped("dyade-16.toml"))
    cases = clearance_plot.cases(dyade.check_clearance(mech, stiffness=1e8, clearance=1e-4))
    assert [c.label for c in cases] == [f"({r['joint'].replace('-', ',')}) #{r['reversal']}"
                                        for r in rows]
    worst = max(cases, key=lambda c: c.peak.force)
    p = worst.peak
    sim = dyade.simulate_clearance(p.mass, p.stiffness, clearance=p.clearance, slope=p.slope,
                                   history=True)
    study = dyade.clearance_speed_study(mech, [200, 300], stiffness=1e8, clearance=1e-4)
    fig = clearance_plot.figure(cases, speeds=clearance_plot.speed_lines(study),
                                history=clearance_plot.History(worst, sim))
    tau_ax, speed_ax, time_ax = fig.axes
    drawn = np.concatenate([a.get_xydata() for a in tau_ax.get_lines()
                            if (a.get_gid() or "").startswith("cases-")])
    assert np.allclose(np.sort(drawn[:, 0]), np.sort([float(r["tau"]) for r in rows]),
                       rtol=1e-12)
    simulated = line(time_ax, "simulated").get_xydata()
    assert same(simulated, np.column_stack((1e3 * sim.time, sim.contact_force)))
    closed = line(time_ax, "closed-form").get_xydata()
    assert same(closed[:, 1], dyade.clearance.contact_force(p, closed[:, 0] / 1e3),
                atol=1e-9 * p.force)  # the time axis in ms: round-off of the scaling
    at_300 = max(float(r["F_max"]) for r in rows if r["joint"] == "5-6")
    assert line(speed_ax, "speed-(5,6)").get_ydata()[1] == pytest.approx(at_300, rel=1e-12)


# -- gear drives: Campbell diagram and mode shapes ----------------------------------------
TWO_STAGE = shipped("gears/two-stage.toml")


@pytest.fixture(scope="module")
def two_stage():
    drive = dyade.read_gears(TWO_STAGE)
    diagram = dyade.campbell(drive, np.arange(0.0, 2201.0, 10.0))
    return drive, diagram, campbell_plot.figure(diagram)


def collection(ax, gid: str):
    found = [c for c in ax.collections if c.get_gid() == gid]
    assert len(found) == 1, gid
    return found[0]


def test_campbell_natural_frequencies_are_horizontal_lines_at_the_api_frequencies(two_stage):
    _, diagram, fig = two_stage
    ax = fig.axes[0]
    f = diagram.modes.frequencies
    top = ax.get_ylim()[1]
    drawn = {l.get_gid() for l in ax.get_lines() if l.get_gid().startswith("mode-")}
    assert drawn == {f"mode-{k + 1}" for k in np.flatnonzero(f <= top)}
    assert {f"mode-{c.mode}" for c in diagram.crossings} <= drawn  # every resonance's mode
    for k in np.flatnonzero(f <= top):
        mode = line(ax, f"mode-{k + 1}")
        assert list(mode.get_ydata()) == [f[k], f[k]]  # horizontal, exactly the API's value
        assert list(mode.get_xdata()) == [0.0, 2200.0]
    title = fig.get_suptitle()
    assert "no gyroscopic" in title and f"{int(np.sum(f > top))} modes above" in title


def test_campbell_order_lines_pass_through_order_times_speed(two_stage):
    _, diagram, fig = two_stage
    ax = fig.axes[0]
    # written out from the file: shafts 1 : 1/3 : 1/10.5, pinions of 20 teeth on the input
    # and the intermediate shaft, the load's torque ripple twice per revolution
    per_rpm = {"input ×1": 1.0, "intermediate ×1": 1 / 3, "output ×1": 1 / 10.5,
               **{f"stage1 ×{h}": 20.0 * h for h in (1, 2, 3)},
               **{f"stage2 ×{h}": 20.0 * h / 3 for h in (1, 2, 3)},
               "excitation1": 20.0, "excitation2": 2 / 10.5}
    assert [o.name for o in diagram.orders] == list(per_rpm)
    for k, order in enumerate(diagram.orders):
        drawn = line(ax, f"order-{order.name}")
        n, y = drawn.get_xdata(), drawn.get_ydata()
        assert np.array_equal(n, diagram.speeds_rpm) and np.array_equal(y, diagram.lines[k])
        assert np.allclose(y, per_rpm[order.name] * n / 60.0, rtol=1e-12, atol=0.0)


def test_campbell_crossing_markers_sit_at_the_api_crossings(two_stage):
    _, diagram, fig = two_stage
    ax = fig.axes[0]
    parts = {gid: collection(ax, f"crossings-{gid}") for gid in ("ranked", "weak", "unranked")}
    marked = np.vstack([c.get_offsets() for c in parts.values()])
    expected = np.array([(c.speed_rpm, c.frequency) for c in diagram.crossings])
    assert marked.shape == expected.shape
    assert np.array_equal(marked[np.lexsort(marked.T)], expected[np.lexsort(expected.T)])
    lines = {o.name: o for o in diagram.orders}
    for c in diagram.crossings:  # each on its line and its mode: f = slope·n, f = f_mode
        assert c.frequency == pytest.approx(lines[c.order].slope * c.speed_rpm, rel=1e-12)
        assert c.frequency == diagram.modes.frequencies[c.mode - 1]
    kappa = np.array([c.mesh_stiffness for c in diagram.crossings])
    largest = np.nanmax(kappa)
    ranked = np.isfinite(kappa) & (kappa >= campbell_plot.WEAK * largest)
    unranked = np.isnan(kappa)
    assert np.array_equal(parts["ranked"].get_offsets(), expected[ranked])
    assert np.array_equal(parts["unranked"].get_offsets(), expected[unranked])
    assert len(parts["weak"].get_offsets()) == np.sum(~ranked & ~unranked) > 0
    sizes = parts["ranked"].get_sizes()  # larger κ, larger marker; the largest the largest
    order = np.argsort(kappa[ranked])
    assert np.all(np.diff(sizes[order]) >= 0) and sizes.max() == campbell_plot.SIZES[1]
    assert [lines[c.order].mesh is None for c in diagram.crossings] == list(unranked)
    labels = [t.get_text() for t in ax.texts if t.get_gid() == "crossing-label"]
    strongest = diagram.crossings[int(np.nanargmax(kappa))]
    assert labels[0] == f"mode {strongest.mode}\n{strongest.speed_rpm:.0f} rpm"


def test_campbell_shaft_and_torque_crossings_are_marked_unranked():
    diagram = dyade.campbell(dyade.read_gears(TWO_STAGE), np.arange(0.0, 20001.0, 500.0))
    ax = campbell_plot.figure(diagram).axes[0]
    squares = collection(ax, "crossings-unranked").get_offsets()
    expected = [(c.speed_rpm, c.frequency) for c in diagram.crossings
                if c.kind == "shaft" or c.order == "excitation2"]
    assert len(expected) == 10 and np.array_equal(squares, expected)


def test_mode_shape_vertices_are_the_api_shapes_normalised():
    modes = dyade.gear_modes(dyade.read_gears(TWO_STAGE))
    fig = modes_plot.figure(modes, 4)
    system = modes.system
    names = [b.name for b in system.bodies]
    lines = {"input": ["motor", "input.1", "gear1"],
             "intermediate": ["gear2", "intermediate.1", "gear3"],
             "output": ["gear4", "output.1", "load"]}
    columns = {"ux": 0, "uy": 1, "uz": 2, "rx": 3}
    for k in range(4):
        shape = modes.shapes[:, k].reshape(-1, 6)
        radius = np.array([np.sqrt(b.inertia[0] / b.mass) for b in system.bodies])
        raw = {d: shape[:, c] * (radius if d == "rx" else 1.0) for d, c in columns.items()}
        every = np.concatenate(list(raw.values()))
        scale = every[np.argmax(np.abs(every))]  # the largest entry becomes +1
        axes = fig.subfigs[k].axes
        assert [ax.get_title() for ax in axes] == list(lines)
        for ax, (shaft, bodies) in zip(axes, lines.items()):
            index = [names.index(b) for b in bodies]
            for dof in columns:
                drawn = line(ax, f"shape-{k + 1}-{shaft}-{dof}")
                x = [system.bodies[i].position[0] * 1e3 for i in index]
                assert np.allclose(drawn.get_xdata(), x, rtol=0, atol=1e-9)
                assert np.allclose(drawn.get_ydata(), raw[dof][index] / scale, rtol=1e-12,
                                   atol=1e-15)
        title = fig.subfigs[k]._suptitle.get_text()
        owner, motion, share = modes.dominant()[k]
        assert title.startswith(f"mode {k + 1}: {modes.frequencies[k]:.5g} Hz")
        assert f"{owner} {motion} {share:.0%}" in title
    assert "ρ·rx" in fig.get_suptitle() and "largest entry" in fig.get_suptitle()


def test_torsional_mode_shapes_follow_the_shafts_without_positions():
    modes = dyade.gear_modes(dyade.read_gears(shipped("gears/friswell-geared.toml")))
    fig = modes_plot.figure(modes, 3)
    names = [b.name for b in modes.system.bodies]
    for k in range(3):
        rx = modes.shapes[:, k]
        scale = rx[np.argmax(np.abs(rx))]
        axes = fig.subfigs[k].axes
        for ax, bodies in zip(axes, (["motor", "gear1", "rotor4"], ["gear2", "rotor3"])):
            drawn = line(ax, f"shape-{k + 1}-{ax.get_title()}-rx")
            assert list(drawn.get_xdata()) == list(range(len(bodies)))
            assert [t.get_text() for t in ax.get_xticklabels()] == bodies
            assert np.allclose(drawn.get_ydata(), rx[[names.index(b) for b in bodies]] / scale,
                               rtol=1e-12)
        assert not [l for l in axes[0].get_lines() if str(l.get_gid()).endswith("-uy")]


@pytest.mark.slow  # 6 s: the default suite's budget (determinism, run by CI's slow set)
def test_gear_plots_same_data_same_bytes():
    drive = dyade.read_gears(TWO_STAGE)
    for fmt in ("png", "svg"):
        made = [canvas.render(campbell_plot.figure(dyade.campbell(drive, [0, 500, 1000])), fmt,
                              dpi=30) for _ in range(2)]
        assert made[0] == made[1], fmt
        made = [canvas.render(modes_plot.figure(dyade.gear_modes(drive), 2), fmt, dpi=30)
                for _ in range(2)]
        assert made[0] == made[1], fmt


def test_plot_campbell_default_speeds_and_errors(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    from dyade.vibration.gears.campbell import default_speeds

    assert np.array_equal(default_speeds(1450), np.linspace(0, 2200, 201))
    out = run("plot", "campbell", TWO_STAGE, "--dpi", "25")
    assert out.exit_code == 0 and "wrote two-stage-campbell.png" in out.stderr, out.output
    out = run("plot", "campbell", shipped("gears/friswell-geared.toml"), "-o", "x.png")
    assert out.exit_code == 2 and "`[speed]`" in out.output
    no_rpm = tmp_path / "no-rpm.toml"
    no_rpm.write_text(TWO_STAGE.read_text().replace("rpm = 1450", ""))
    out = run("plot", "campbell", no_rpm, "-o", "x.png")
    assert out.exit_code == 2 and "--speed-range" in out.output
    out = run("plot", "campbell", TWO_STAGE, "--speed-range", "0:100:0", "-o", "x.png")
    assert out.exit_code == 2 and "--speed-range" in out.output
    out = run("plot", "modes", shipped("gears/friswell-geared.toml"), "--modes", "9", "-o",
              "m.svg")
    assert out.exit_code == 0, out.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.svg", "no-rpm.toml",
                                                          "two-stage-campbell.png"]


# -- every kind, every format, same bytes ---------------------------------------------------
KINDS = [("polar", "fourbar.toml"), ("curves", "dyade-16.toml"), ("mechanism", "watt-sixbar.toml")]
SPECIAL = {
    "coupling": [shipped("coupling/stiff-coupling.toml")],
    "campbell": [shipped("gears/two-stage.toml"), "--speed-range", "0:2000:50"],
    "modes": [shipped("gears/two-stage.toml"), "--modes", "2"],
    "clearance": ["--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
                  "360000", "--speed-rpm", "300", "--speed-range", "100:600:100", "--simulate"],
}


@pytest.mark.slow  # 8 s per format: the default suite's budget (every kind, CI's slow set)
@pytest.mark.parametrize("fmt", ["png", "svg"])
def test_every_kind_writes_png_and_svg(fmt, tmp_path):
    magic = {"png": b"\x89PNG", "svg": b"<?xml"}[fmt]
    jobs = [(kind, [shipped(name)]) for kind, name in KINDS] + list(SPECIAL.items())
    for kind, args in jobs:
        path = tmp_path / f"{kind}.{fmt}"
        out = run("plot", kind, *args, "-o", path, "--dpi", "40")
        assert out.exit_code == 0, (kind, out.output)
        assert path.read_bytes().startswith(magic), kind
    out = run("plot", "animate", shipped("scotch-yoke.toml"), "--step", "45", "-o",
              tmp_path / "m.gif", "--dpi", "30")
    assert out.exit_code == 0 and (tmp_path / "m.gif").read_bytes().startswith(b"GIF89a")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        [f"{kind}.{fmt}" for kind, _ in KINDS] + [f"{k}.{fmt}" for k in SPECIAL] + ["m.gif"])


@pytest.mark.parametrize("path", [path if path.stem == "fourbar" else
                                  pytest.param(path, marks=pytest.mark.slow) for path in SHIPPED],
                         ids=lambda p: p.stem)  # one in the default run, every one with slow
def test_the_commands_run_on_every_shipped_mechanism(path, tmp_path):
    has_forces = dyade.read_mechanism(path).has_dynamics
    for kind in ("polar", "curves", "mechanism"):
        out = run("plot", kind, path, "-o", tmp_path / f"{kind}.png", "--dpi", "25")
        if kind == "polar" and not has_forces:
            assert out.exit_code == 2 and "need joint forces" in out.output
        else:
            assert out.exit_code == 0, (kind, out.output)
    out = run("plot", "animate", path, "--step", "60", "-o", tmp_path / "m.gif", "--dpi", "20")
    assert out.exit_code == 0, out.output


@pytest.mark.slow  # 8 s: the default suite's budget (determinism, run by CI's slow set)
def test_same_data_same_bytes(tmp_path):
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")))
    for fmt in ("png", "svg", "pdf"):
        first = canvas.render(polar.figure(result, [(2, 3), (3, 4)]), fmt, dpi=50)
        again = canvas.render(polar.figure(dyade.analyse(result.mechanism), [(2, 3), (3, 4)]),
                              fmt, dpi=50)
        assert first == again, fmt
    assert b"Date" not in canvas.render(curves.figure(result), "svg")
    assert b"Software" not in canvas.render(curves.figure(result), "png", dpi=20)
    pdf = canvas.render(curves.figure(result), "pdf")
    assert b"CreationDate" not in pdf and b"Producer" not in pdf
    paths = [tmp_path / "a.gif", tmp_path / "b.gif"]
    for path in paths:
        animate.save(animate.animation(dyade.analyse(result.mechanism, step_deg=45)),
                     str(path), dpi=25)
    assert paths[0].read_bytes() == paths[1].read_bytes()


def test_default_output_name_and_batch_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = run("plot", "curves", shipped("fourbar.toml"), "--dpi", "25")
    assert out.exit_code == 0 and "wrote fourbar-curves.png" in out.stderr
    assert (tmp_path / "fourbar-curves.png").exists()
    out = run("plot", "curves", shipped("fourbar.toml"), shipped("slider-crank.toml"), "-o",
              "figures", "--format", "svg", "--dpi", "25")
    assert out.exit_code == 0, out.output
    assert sorted(p.name for p in (tmp_path / "figures").iterdir()) == [
        "fourbar-curves.svg", "slider-crank-curves.svg"]
    assert not list(tmp_path.glob(".*part*")) and not list((tmp_path / "figures").glob(".*"))


@pytest.mark.parametrize("args, message", [
    (["curves", shipped("fourbar.toml"), "-o", "x.jpg"], "the format comes from the suffix"),
    (["animate", shipped("fourbar.toml"), "-o", "x.png"], ".gif"),
    (["mechanism", shipped("fourbar.toml"), "--at", "a,b", "-o", "x.png"], "--at"),
    (["curves", shipped("fourbar.toml"), "--show"], "needs a display"),
])
def test_bad_output_options_are_usage_errors(args, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    out = run("plot", *args)
    assert out.exit_code == 2 and message in out.output, out.output
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("kind", ["polar", "curves", "mechanism", "animate", "coupling",
                                  "clearance", "campbell", "modes"])
def test_without_matplotlib_every_plot_command_names_the_extra(kind, monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib fails
    args = {"coupling": ["--J", "1", "--c1", "1", "--c2", "1"],
            "clearance": SPECIAL["clearance"], "campbell": SPECIAL["campbell"],
            "modes": SPECIAL["modes"]}.get(kind, [shipped("fourbar.toml")])
    out = run("plot", kind, *args, "-o", tmp_path / "x.gif")
    assert out.exit_code == 2
    assert 'pip install "dyade[plot]"' in out.output
