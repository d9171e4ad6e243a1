"""The elastic drive line (``dyade.machine.drive_line``, ``dyade.linkage.drive_line``):
closed forms, the Mathieu equation, the energy balance, the files and the command."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import drive_line as engine
from dyade.model.drive import Asynchronous
from dyade.units import RAD_PER_S_TO_RPM


def disc(steps: int, inertia: float, load: np.ndarray | None = None,
         epsilon: float = 0.0) -> engine.Tables:
    """A crank shaft of inertia J0·(1 + ε·cos 2u) with a load torque table."""
    u = math.pi / steps * np.arange(2 * steps)
    return engine.Tables(inertia * (1.0 + epsilon * np.cos(2 * u)),
                         -2.0 * epsilon * inertia * np.sin(2 * u),
                         np.zeros(2 * steps) if load is None else load, np.zeros(2 * steps))


def test_two_mass_forced_response_is_the_closed_form():
    """A disc (constant inertia) behind a shaft, an asynchronous motor with its rotor, a
    harmonic load torque M̂·sin(2φ): the steady state is the closed-form forced response
    of the two-mass system J_M·ÿ = −c·ẏ − k(y − x) − b(ẏ − ẋ), J·ẍ = k(y − x) + b(ẏ − ẋ)
    + M̂·sin(2Ωt) (c the motor's slope), to 1e-9. M̂ is small enough that the load's
    dependence on the vibrating angle (φ = Ωt + x) stays below that."""
    steps, crank, rotor, k, b, n = 1200, 0.5, 0.3, 5000.0, 3.0, 2
    ws, slope, amplitude = 100.0, 2.0, 1e-12
    u = math.pi / steps * np.arange(2 * steps)
    tables = disc(steps, crank, amplitude * np.sin(n * u))
    line = engine.Line((rotor,), (k,), (b,), Asynchronous(slope * 5.0, ws - 5.0, ws))
    lanes = engine.Lanes.of(line, [ws])
    solution = engine.periodic(line, tables, lanes, engine.rest_guess(line, tables, lanes))
    assert solution.converged.all()
    orbit = engine.integrate(line, tables, lanes, solution.start)
    w = n * ws
    kc = k + 1j * w * b
    system = np.array([[kc - w * w * rotor + 1j * w * slope, -kc], [-kc, kc - w * w * crank]])
    y, x = np.linalg.solve(system, np.array([0.0, -1j * amplitude]))  # sin: phasor −i
    t = orbit.step * np.arange(steps + 1) / ws
    twist = ((y - x) * np.exp(1j * w * t)).real
    speed = (1j * w * x * np.exp(1j * w * t)).real
    assert np.max(np.abs(orbit.state[:, 0, 1] - twist)) <= 1e-9 * np.max(np.abs(twist))
    assert np.max(np.abs(orbit.state[:, 0, 0] - speed)) <= 1e-9 * np.max(np.abs(speed))


def edges(epsilon: float, damping_ratio: float = 0.0) -> np.ndarray:
    """η = Ω/ω0 where the principal parametric region of J0·(1 + ε·cos 2φ) on a shaft
    (ideal motor, no load) starts and ends: where the largest |μ| crosses 1 (linear
    interpolation between 81 speeds)."""
    inertia, k = 2.0, 800.0
    omega0 = math.sqrt(k / inertia)
    eta = np.linspace(1.0 - epsilon, 1.0 + epsilon, 81)
    tables = disc(720, inertia, epsilon=epsilon)
    line = engine.Line((0.0,), (k,), (2.0 * damping_ratio * inertia * omega0,))
    lanes = engine.Lanes.of(line, eta * omega0)
    solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
    assert solution.converged.all()
    if damping_ratio == 0.0:  # det M = 1: unstable where |tr M| > 2
        measure = np.abs(np.sum(solution.multipliers, axis=1).real) - 2.0
    else:
        measure = np.abs(solution.multipliers[:, 0]) - 1.0
    cross = np.flatnonzero(np.diff(np.sign(measure)) != 0)
    return np.array([eta[i] - measure[i] * (eta[i + 1] - eta[i]) / (measure[i + 1] - measure[i])
                     for i in cross])


@pytest.mark.parametrize("epsilon", [pytest.param(0.02, marks=pytest.mark.slow), 0.04])
def test_first_parametric_region_is_mathieus(epsilon):
    """Linearised about the periodic motion, J = J0·(1 + ε·cos 2φ) on a shaft k gives
    d/dt(J·δẋ) + (k + ½·J″·Ω²)·δx = 0; with τ = Ωt and y = √J·δx (Liouville) it is,
    to first order in ε, Mathieu's y″ + (a − 2q·cos 2τ)·y = 0 with a = (ω0/Ω)², q = a·ε/2.
    Its first region of instability lies between a = 1 − q and a = 1 + q (Abramowitz &
    Stegun 20.2.25, b₁ and a₁ to first order in q; also Nayfeh & Mook, *Nonlinear
    Oscillations*, §5.2), so at η = Ω/ω0 = √(1 − ε/2) … √(1 + ε/2), to O(ε²)."""
    found = edges(epsilon)
    expected = np.sqrt([1.0 - epsilon / 2.0, 1.0 + epsilon / 2.0])
    assert found.size == 2
    assert np.all(np.abs(found - expected) <= 0.05 * epsilon ** 2)  # found: 0.016·ε²


@pytest.mark.slow
def test_damping_shrinks_the_region_and_removes_it_above_the_theory():
    """With viscous damping b (D = b/(2·J0·ω0)) the region is (a − 1)² = q² − 4β² with
    2β = b/(J0·Ω) (the same harmonic balance as A&S's first order): it shrinks, and it
    vanishes for D > ε/4."""
    epsilon = 0.04
    undamped = np.diff(edges(epsilon))[0]
    damped = edges(epsilon, damping_ratio=epsilon / 8.0)
    assert damped.size == 2 and np.diff(damped)[0] < 0.9 * undamped
    width = math.sqrt(1.0 + math.sqrt((epsilon / 2) ** 2 - (epsilon / 4) ** 2)) - math.sqrt(
        1.0 - math.sqrt((epsilon / 2) ** 2 - (epsilon / 4) ** 2))
    assert abs(np.diff(damped)[0] - width) <= epsilon ** 2
    assert edges(epsilon, damping_ratio=epsilon / 4.0 * 1.2).size == 0


# -- the linkage on the line ----------------------------------------------------------

from click.testing import CliRunner  # noqa: E402

import dyade  # noqa: E402
from dyade.cli import main  # noqa: E402
from dyade.linkage import drive_line as api  # noqa: E402
from tests.helpers import shipped  # noqa: E402

SLIDER = {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.05, "links.2.inertia": 0.01}
"""the shipped slider-crank with a flywheel on the crank (J̄ = 0.011 kg·m²) on a shaft:
ω̄ = 300.8 rad/s (2872 rpm), Ω/ω̄ = 0.52 at its 1500 rpm"""
MOTOR = {"drive_line.rotor_inertia": 0.005, "drive.motor": "asynchronous",
         "drive.rated_torque": 5.0, "drive.rated_speed_rpm": 1450.0,
         "drive.synchronous_speed_rpm": 1500.0}


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


@pytest.mark.slow
def test_figures_of_the_drive_line(tmp_path):
    """The plot kinds draw from the API's results: the resonance curve's peak torque
    line holds the curve's values, the unstable speeds are shaded."""
    pytest.importorskip("matplotlib")
    from dyade.plot import drive_line as figures

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"), {
        "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    curve = api.resonance_curve(mechanism, np.array([3450.0, 3575.0, 3700.0]))
    assert curve.unstable.any() and not curve.unstable.all()
    fig = figures.resonance(curve)
    np.testing.assert_array_equal(fig.axes[0].get_lines()[0].get_ydata(), curve.peak_torque)
    assert any(p.get_label() == "unstable (|μ| > 1)" for p in fig.axes[0].patches)
    figures.stability(curve).savefig(tmp_path / "stability.png")
    assert (tmp_path / "stability.png").stat().st_size > 0


def test_energy_balance_over_one_period():
    """Over one period of the steady state the motor's work equals the work of the load,
    friction and damping (the kinetic and spring energies repeat), 1e-8 relative."""
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER | MOTOR)
    state = api.steady_state(mechanism, steps=1080, accuracy=False)
    f = state.figures
    spent = f["work_load"] + f["work_friction"] + f["work_damping"]
    assert f["work_damping"] > 0.0
    assert abs(f["work_motor"] - spent) <= 1e-8 * f["work_motor"]


def test_natural_frequency_and_the_vdi_note():
    """ω̄ = √(k/J̄) for an ideal motor; the range over the cycle from J(φ); analyse
    notes Ω/ω̄ > 0.1 only when the file has a drive line."""
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER)
    freq = api.natural_frequency(mechanism)
    assert freq.omega_bar == pytest.approx(math.sqrt(1000.0 / freq.inertia_mean), rel=1e-12)
    assert freq.omega_min < freq.omega_bar < freq.omega_max
    assert freq.ratio == pytest.approx(1500 * math.pi / 30 / freq.omega_bar)
    notes = dyade.analyse(mechanism).notes
    assert [n.kind for n in notes] == ["drive_line_soft"]
    stiff = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER | {
        "drive_line.stiffness": 1e6})
    assert dyade.analyse(stiff).notes == []


def test_no_drive_line_no_stage(monkeypatch):
    """Without [drive_line] neither describe nor analyse touches the drive line."""
    def boom(*args, **kwargs):
        raise AssertionError("the drive line ran")

    from dyade.linkage import drive as line_model

    monkeypatch.setattr(line_model, "natural_frequency", boom)
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"))
    assert dyade.plan(mechanism).drive_line == ""
    dyade.analyse(mechanism)
    assert "drive line" not in run("describe", shipped("slider-crank.toml")).output


@pytest.mark.parametrize("assignment, key", [
    ("drive_line.stiffness=0", "drive_line.stiffness"),
    ("drive_line.stiffness=-5", "drive_line.stiffness"),
    ("drive_line.damping=-1", "drive_line.damping"),
    ("drive.motor=\"asynchronous\"", "drive_line.rotor_inertia"),
])
def test_bad_line_exits_2_naming_the_key(assignment, key):
    extra = ["--set", "drive.rated_torque=5", "--set", "drive.rated_speed_rpm=1450",
             "--set", "drive.synchronous_speed_rpm=1500"] if "motor" in assignment else []
    result = run("driveline", shipped("slider-crank.toml"), "--set", "drive_line.stiffness=1000",
                 "--set", assignment, *extra)
    assert result.exit_code == 2
    assert key in result.output


def test_speed_range_through_zero_and_a_bad_coupling_file(tmp_path):
    result = run("driveline", shipped("slider-crank.toml"), "--set",
                 "drive_line.stiffness=1000", "--analysis", "resonance",
                 "--speed-range", "-100:100:50")
    assert result.exit_code == 2 and "--speed-range" in result.output
    bad = tmp_path / "coupling.toml"
    bad.write_text("J = 0.01\nc1 = \n")
    text = shipped("slider-crank.toml").read_text() + f'\n[drive_line]\ncoupling = "{bad}"\n'
    mech = tmp_path / "m.toml"
    mech.write_text(text)
    result = run("driveline", mech)
    assert result.exit_code == 2 and "drive_line.coupling" in result.output


def test_run_up_that_never_reaches_speed_exits_1():
    """A weak motor (rated 0.05 N·m) that is still far from its speed after
    ``drive.max_revolutions`` = 3 revolutions: exit 1, saying so."""
    result = run("driveline", shipped("slider-crank.toml"), *sum(
        (["--set", f'{k}="{v}"' if isinstance(v, str) else f"{k}={v}"] for k, v in (
            SLIDER | MOTOR | {"drive.rated_torque": 0.05, "drive.max_revolutions": 3}).items()),
        []), "--analysis", "run-up")
    assert result.exit_code == 1
    assert "does not reach speed" in result.output


@pytest.mark.slow
@pytest.mark.parametrize("name, settings, inside, outside", [
    ("dyade-16.toml", {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.04},
     3575.0, 3450.0),
    ("slider-crank.toml", {"drive_line.stiffness": 1000.0, "drive_line.damping": 0.005,
                           "links.2.inertia": 0.004}, 8500.0, 8300.0),
])
def test_floquet_multipliers_against_long_integration(name, settings, inside, outside):
    """Near Ω = 2ω̄ (the first harmonic of J(φ)'s region) on an ideal motor: dyade-16 on a
    shaft of 1000 N·m/rad and 0.04 N·m·s/rad (ω̄ = 187.0 rad/s, D = 0.0037: unstable
    3525–3625 rpm); the shipped slider-crank with a flywheel of 0.004 kg·m² on its crank
    on 1000 N·m/rad and 0.005 N·m·s/rad (ω̄ = 444.9 rad/s: unstable 8450–8550 rpm). A
    small disturbance of the periodic motion, integrated over 70 revolutions, grows inside
    the region and dies out outside, at the rate per revolution of the largest Floquet
    multiplier from the linearisation about the periodic solution."""
    mechanism = dyade.read_mechanism(shipped(name), settings)
    line = api.line_of(mechanism)
    tables = api.crank_tables(mechanism, 720)
    lanes = engine.Lanes.of(line, np.array([inside, outside]) / RAD_PER_S_TO_RPM)
    solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
    assert solution.converged.all()
    mu = np.abs(solution.multipliers[:, 0])
    assert mu[0] > 1.01 and mu[1] < 1.0
    scale = engine.scales(line, tables, lanes)
    x = solution.start + 1e-7 * scale * np.array([1.0, -0.5])
    deviations = [x - solution.start]
    for _ in range(40):  # revolution by revolution, the disturbance at each u = 0
        x = engine.integrate(line, tables, lanes, x, keep=False)
        deviations.append(x - solution.start)
    d = np.array(deviations) / scale  # (41, lanes, dim)
    size = np.max(np.abs(d), axis=2)
    assert size[-1, 0] > 1.5 * size[0, 0]  # inside: it grows
    assert size[-10:, 1].max() < 0.9 * size[:10, 1].max()  # outside: it dies out
    for lane in range(2):  # the revolution map the long run shows: d_{n+1} = A·d_n
        a = np.linalg.lstsq(d[:-1, lane], d[1:, lane], rcond=None)[0].T
        seen = np.sort(np.abs(np.linalg.eigvals(a)))[::-1]
        assert seen == pytest.approx(np.abs(solution.multipliers[lane]), abs=1e-4)


@pytest.mark.slow
def test_stiff_line_tends_to_the_rigid_drive():
    """Stiffness → ∞: the crank speed, acceleration and shaft torque tend to the rigid
    [drive] solution (the rotor's inertia on the crank shaft), the error ∝ 1/stiffness."""
    errors = []
    for k in (1e5, 4e5):
        mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER | MOTOR | {
            "drive_line.stiffness": k, "drive_line.damping": 2.0})
        state = api.steady_state(mechanism, accuracy=False)
        errors.append([np.max(np.abs(state.crank_speed - state.rigid_speed)),
                       np.max(np.abs(state.shaft_torque - state.rigid_torque))])
    ratio = np.array(errors[0]) / np.array(errors[1])
    assert ratio == pytest.approx([4.0, 4.0], rel=0.15)


def _phasor(t: np.ndarray, y: np.ndarray, omega: float) -> complex:
    """Y with y(t) ≈ a + Im(Y·e^{iΩt}) (least squares over one period)."""
    basis = np.column_stack((np.ones_like(t), np.cos(omega * t), np.sin(omega * t)))
    _, b, c = np.linalg.lstsq(basis, y, rcond=None)[0]
    return complex(c, b)


@pytest.mark.slow
def test_coupling_in_the_line_is_strumpfels_in_the_limit():
    """The shipped stiff coupling in the line of an ideal motor (its secondary side c2, b2
    held by the motor's uniform rotation, as Strümpfel's is held still), its primary side
    c1, b1 on a disc of inertia j loaded by M̂·sin φ (the exciting moment at the primary
    node): as j → 0 the steady state's phasors of the coupling angle φ, the exciting-side
    angle ψ and the counter-moment M_Q equal ``dyade coupling``'s at the same tuning ratio
    η = Ω/ω_t, the error ∝ j."""
    coupling = dyade.read_coupling(shipped("coupling/stiff-coupling.toml"))
    eta = np.array([0.6, 1.4])
    omega = eta * coupling.natural_frequency
    expected = dyade.coupling_response(coupling, eta).phasors
    amplitude = 1e-6  # [N·m]: the load's dependence on the vibrating angle stays below 1e-9
    errors = []
    for share in (1e-2, 1e-3, 1e-4):
        disc_inertia = share * coupling.inertia
        line = engine.Line((0.0, coupling.inertia), (coupling.c2, coupling.c1),
                           (coupling.b2, coupling.b1))
        steps = engine.steps_for(line, disc_inertia, float(omega.min()))
        u = math.pi / steps * np.arange(2 * steps)
        tables = disc(steps, disc_inertia, amplitude * np.sin(u))
        lanes = engine.Lanes.of(line, omega)
        solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
        assert solution.converged.all()
        orbit = engine.integrate(line, tables, lanes, solution.start)
        worst = 0.0
        for lane in range(2):
            t = orbit.quadratures[:-1, lane, 0]
            state = orbit.state[:-1, lane]
            found = {"phi": _phasor(t, state[:, 2] - state[:, 1], omega[lane]),
                     "psi": _phasor(t, -state[:, 1], omega[lane]),
                     "q": _phasor(t, -orbit.torque[:-1, lane, 0], omega[lane])}
            for name, value in found.items():
                want = expected[name][lane] * amplitude
                worst = max(worst, abs(value - want) / abs(want))
        errors.append(worst)
    assert errors[2] <= 5e-4  # found: 3.5e-2, 3.4e-3, 3.4e-4
    assert errors[0] / errors[1] == pytest.approx(10.0, rel=0.3)
    assert errors[1] / errors[2] == pytest.approx(10.0, rel=0.3)


@pytest.mark.parametrize("direction, sense", [("ccw", 1.0),
                                              pytest.param("cw", -1.0, marks=pytest.mark.slow)])
def test_joint_forces_at_the_real_crank_motion(direction, sense):
    """The kinetostatics at the vibrating crank's speed and acceleration gives a drive
    torque equal to the shaft torque of the drive line (two independent paths: the
    dyads' forces against the reduced equation of motion), 1e-8 of its largest value;
    the line's torques are in the running direction, M_drive counter-clockwise."""
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER | {
        "crank.direction": direction})
    state = api.steady_state(mechanism, accuracy=False)
    result = api.forces(mechanism, state)
    drive = result.columns()["M_drive"]
    torque = sense * state.shaft_torque[:-1]
    assert np.max(np.abs(drive - torque)) <= 1e-8 * np.max(np.abs(torque))


@pytest.mark.slow
def test_accuracy_studies_the_drive_line_only_when_the_file_has_one():
    from dyade.linkage import accuracy

    plain = dyade.read_mechanism(shipped("slider-crank.toml"))
    assert "drive line steps" not in {r.study for r in accuracy.studies(plain, repeats=1)}
    rows = accuracy.drive_line_steps(dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER),
                                     factors=(0.5, 1.0, 2.0))
    errors = {r.setting: r.error for r in rows if r.quantity == "largest |mu|"}
    assert errors["360 steps"] < 1e-6 and np.isnan(errors["1440 steps"])


def test_driveline_json_and_describe():
    """`dyade driveline --format json`: the natural frequency, the steady state next to the
    rigid drive, the VDI note; `describe` lists the stage."""
    import json

    sets = sum((["--set", f"{k}={v}"] for k, v in SLIDER.items()), [])
    result = run("driveline", shipped("slider-crank.toml"), *sets, "--format", "json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    summary = doc["summary"]
    assert summary["vdi_2149"]["value"] is False
    assert summary["speed_ratio"]["value"] == pytest.approx(0.5222, abs=1e-4)
    assert summary["accuracy"]["value"] < 1e-5
    assert len(doc["columns"]["shaft_torque"]) == len(doc["columns"]["rigid_torque"])
    assert any("VDI 2149" in w for w in doc["notes"])
    described = run("describe", shipped("slider-crank.toml"), *sets).output
    assert "elastic drive line (shaft 1000 N·m/rad" in described
    missing = run("driveline", shipped("slider-crank.toml"))
    assert missing.exit_code == 2 and "[drive_line]" in missing.output


@pytest.mark.slow
def test_joint_friction_in_the_steady_state():
    """With joint friction (μ = 0.1 in every joint of the slider-crank) the friction torque
    comes from the kinetostatics with friction at the vibrating motion, by passes: the
    energy balance holds with its work (1e-8), and the sweep at that motion gives a drive
    torque equal to the shaft torque (to the friction tolerance)."""
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), SLIDER | {
        "friction.coefficient": 0.1, "friction.pin_radius": 5.0,
        "friction.slider_length": 30.0, "friction.slider_height": 20.0})
    state = api.steady_state(mechanism, steps=1080, accuracy=False)
    f = state.figures
    assert f["work_friction"] > 0.5 * f["work_motor"] and f["friction_passes"] > 1
    spent = f["work_load"] + f["work_friction"] + f["work_damping"]
    assert abs(f["work_motor"] - spent) <= 1e-8 * f["work_motor"]
    drive = api.forces(mechanism, state).columns()["M_drive"]
    torque = state.shaft_torque[:-1]
    assert np.max(np.abs(drive - torque)) <= 1e-8 * np.max(np.abs(torque))


def test_a_coupling_file_in_the_line():
    """`drive_line.coupling`: the shipped stiff coupling between an ideal motor (c2, b2)
    and the slider-crank (c1, b1): ω̄ is the lower root of the two-mass system J_K, J̄ on
    c2 to the held motor and c1 between them, det(K − ω²M) = 0."""
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"), {
        "drive_line.coupling": "coupling/stiff-coupling.toml"})
    coupling = dyade.read_coupling(shipped("coupling/stiff-coupling.toml"))
    freq = api.natural_frequency(mechanism)
    j1, j2, c1, c2 = coupling.inertia, freq.inertia_mean, coupling.c1, coupling.c2
    # (c1 + c2 − ω²J1)(c1 − ω²J2) − c1² = 0, a quadratic in ω²
    a, b, c = j1 * j2, -((c1 + c2) * j2 + c1 * j1), c1 * c2
    low = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
    assert freq.omega_bar == pytest.approx(math.sqrt(low), rel=1e-12)
    assert api.line_of(mechanism).elements == 2


@pytest.mark.slow
def test_the_maps_traced_boundary_separates_its_cells(tmp_path):
    """dyade-16 on a shaft of 1000 N·m/rad (unstable near 2ω̄ = 3571 rpm, the principal
    parametric region): between the cells the boundary is traced in speed at each
    damping; just below and just above each traced point (±1e-4 of Ω) the shooting of
    the same line gives opposite verdicts, and the multiplier there is −1 (period
    doubling). The region narrows with damping; the figure marks the points."""
    from dyade.analyses.drive_line import edge_notes
    from dyade.linkage.drive import crank_shaft

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"), {
        "drive_line.stiffness": 1000.0, "drive_line.steps": 360})
    damping = np.array([0.02, 0.1])
    chart = api.stability_map(mechanism, [3480.0, 3560.0, 3660.0], damping=damping)
    edges = chart.edges
    assert chart.unstable[:, 1].all() and not chart.unstable[:, [0, 2]].any()
    assert edges.missed == [] and edges.kind == ["period doubling"] * 4
    np.testing.assert_array_equal(edges.values, np.repeat(damping, 2))
    width = np.diff(edges.speed.reshape(2, 2), axis=1)[:, 0]
    assert width[1] < 0.9 * width[0]
    shaft = crank_shaft(mechanism)
    line = shaft.ideal_line
    tables = shaft.tables_at(360)
    for speed, b in zip(edges.speed, edges.values):
        near = speed * np.array([1.0 - 1e-4, 1.0, 1.0 + 1e-4])
        lanes = engine.Lanes.of(line, near, None, np.full((3, 1), b))
        solution = engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))
        assert solution.converged.all()
        assert solution.unstable[0] != solution.unstable[2]
        mu = solution.multipliers[1]
        assert np.min(np.abs(mu + 1.0)) < 1e-4, mu
    notes = edge_notes(edges, "damping", "N·m·s/rad")
    assert notes[0].startswith("stability boundary traced (a multiplier at −1")
    pytest.importorskip("matplotlib")
    from dyade.plot import drive_line as figures

    fig = figures.stability_map(chart)
    marks = [line for line in fig.axes[0].get_lines() if "traced" in line.get_label()]
    assert len(marks) == 1
    np.testing.assert_allclose(marks[0].get_xdata(), edges.speed * RAD_PER_S_TO_RPM)
