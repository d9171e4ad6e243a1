"""Stiff coupling (SPEC §3): phasors, the paper's closed forms, time domain, edge cases."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from dyade.vibration import coupling
from dyade.cli import main

DONE_WHEN = ["coupling", "--J", "1", "--c1", "1", "--c2", "1", "--b1", "0.05", "--b2", "0.05",
             "--eta-range", "0:3:0.01", "--format", "csv"]


def _rows(text):
    return list(csv.DictReader(io.StringIO(text)))


def _independent(j, c1, c2, b1, b2, eta):
    """Solve the model's two complex equations for (φ, ψ) per unit M̂_E directly:
    node ψ:  (c1 + iΩb1)(ψ − φ) = 1;  J_K:  (c2 − JΩ² + iΩb2)φ − (c1 + iΩb1)(ψ − φ) = 0."""
    omega = eta * np.sqrt((c1 + c2) / j)
    out = []
    for w in omega:
        k1 = c1 + 1j * w * b1
        a = np.array([[-k1, k1], [c2 - j * w ** 2 + 1j * w * b2 + k1, -k1]])
        phi, psi = np.linalg.solve(a, np.array([1.0, 0.0]))
        out.append((phi, psi, (c2 + 1j * w * b2) * phi, phi - psi))
    return np.array(out)


def test_done_when_agrees_with_the_phasor_solution():
    out = CliRunner().invoke(main, DONE_WHEN, catch_exceptions=False)
    assert out.exit_code == 0
    rows = _rows(out.stdout)
    assert list(rows[0]) == ["eta", "V_phi", "V_psi", "V_q", "V_r", "alpha_deg", "beta_deg",
                             "gamma_deg", "delta_deg"]
    assert len(rows) == 301
    eta = np.array([float(r["eta"]) for r in rows])
    ref = _independent(1.0, 1.0, 1.0, 0.05, 0.05, eta)
    norms = (2.0, 1.0, 2.0, 1.0)  # c1 + c2, c1, (c1 + c2)/c2, c1
    for k, (name, phase) in enumerate((("V_phi", "alpha_deg"), ("V_psi", "beta_deg"),
                                       ("V_q", "gamma_deg"), ("V_r", "delta_deg"))):
        got = np.array([float(r[name]) for r in rows])
        assert np.allclose(got, np.abs(ref[:, k]) * norms[k], rtol=1e-9, atol=0)
        angle = np.array([float(r[phase]) for r in rows])
        diff = (angle - np.degrees(np.angle(ref[:, k])) + 180) % 360 - 180
        assert np.max(np.abs(diff)) < 1e-6
        assert np.all((angle > -180) & (angle <= 180))


def test_done_when_reports_eta0():
    out = CliRunner().invoke(main, DONE_WHEN[:-2], catch_exceptions=False)
    model = coupling.Coupling(1, 1, 1, 0.05, 0.05)
    assert f"{model.resonance():.5g}" in out.stdout


@pytest.mark.parametrize("params", [(1, 1, 1, 0.05, 0.05), (0.3, 2e4, 5e4, 3.0, 0.5),
                                    (2.0, 10.0, 1.0, 0.0, 0.4), (1.0, 3.0, 7.0, 0.2, 0.0)])
def test_amplitudes_equal_the_papers_closed_forms(params):
    model = coupling.Coupling(*params)
    eta = np.linspace(0.0, 3.0, 601)
    eta = eta[np.abs(eta - (model.resonance() or -1)) > 0.02]  # away from resonance
    resp = coupling.response(model, eta)
    paper = coupling.paper_transfer(model, eta)
    for name in ("V_phi", "V_psi", "V_q", "V_r"):
        assert np.allclose(resp.transfer[name], paper[name], rtol=1e-12), name


def test_paper_phases_agree_modulo_180_degrees():
    model = coupling.Coupling(1, 1, 1, 0.05, 0.05)
    eta = np.linspace(0.05, 3, 60)
    resp = coupling.response(model, eta)
    d, c1, c2, b1, b2 = model.damping_ratio, 1.0, 1.0, 0.05, 0.05
    r = b1 / (b1 + b2) * (c1 + c2) / c1 * 2 * d * eta
    m = b2 / (b1 + b2) * (c1 + c2) / c2 * 2 * d * eta
    ll = (1 - eta ** 2) * r - 2 * d * eta
    n = 1 - eta ** 2 + 2 * d * eta * r
    w2 = (1 - eta ** 2) ** 2 + (2 * d * eta) ** 2
    kap = model.kappa
    with np.errstate(divide="ignore", invalid="ignore"):  # arctan(±inf) is ±90°: fine
        p = (w2 * r - kap * (ll + r * n)) / (kap * (n - r * ll) - w2)
        paper = {"alpha": np.arctan((ll / n + p) / (1 - ll / n * p)), "beta": np.arctan(p),
                 "gamma": np.arctan((ll + m * n + (n - m * ll) * p) / (n - m * ll - (ll + m * n) * p)),
                 "delta": np.arctan((ll + n * p - (c1 + c2) / c1 * w2 * p)
                                    / (n - ll * p - (c1 + c2) / c1 * w2))}
    for name, value in paper.items():
        defined = np.isfinite(value)  # the paper's form is 0/0 where (L/N)·P = 1
        assert defined.sum() >= 58
        diff = (resp.phase[name][defined] - value[defined] + np.pi / 2) % np.pi - np.pi / 2
        assert np.max(np.abs(diff)) < 1e-9, name


@pytest.mark.parametrize("eta", [0.4, 0.7, 1.0, 1.6])
def test_phases_against_time_domain_integration(eta):
    j, c1, c2, b1, b2 = 1.0, 1.0, 1.0, 0.3, 0.2
    model = coupling.Coupling(j, c1, c2, b1, b2)
    omega = eta * model.natural_frequency

    def rhs(t, y):
        phi, dphi, psi = y
        moment = np.sin(omega * t)
        return [dphi, (moment - b2 * dphi - c2 * phi) / j, dphi + (moment - c1 * (psi - phi)) / b1]

    period = 2 * np.pi / omega
    # the transient decays as exp(−D·ω_t·t): e^-30 ≈ 1e-13 is gone
    t_end = 5 * period + 30 / (model.damping_ratio * model.natural_frequency)
    t = np.linspace(t_end - 5 * period, t_end, 2001)
    sol = solve_ivp(rhs, (0, t_end), [0, 0, 0], method="DOP853", t_eval=t, rtol=1e-12, atol=1e-14)
    phi, dphi, psi = sol.y
    series = {"alpha": phi, "beta": psi, "gamma": c2 * phi + b2 * dphi, "delta": phi - psi}
    basis = np.column_stack((np.sin(omega * t), np.cos(omega * t)))
    resp = coupling.response(model, np.array([eta]))
    for name, y in series.items():
        (a, b), *_ = np.linalg.lstsq(basis, y, rcond=None)
        lead = np.arctan2(b, a)  # a sin + b cos = A sin(Ωt + lead)
        diff = (resp.phase[name][0] - lead + np.pi) % (2 * np.pi) - np.pi
        assert abs(np.degrees(diff)) < 1e-3, name


@pytest.mark.parametrize("params", [(1, 1, 1, 0.05, 0.05), (1, 2, 1, 0.0, 0.3), (1, 1, 3, 0.4, 0.1)])
def test_eta0_is_the_numerical_peak_of_v_phi(params):
    model = coupling.Coupling(*params)
    found = minimize_scalar(lambda e: -coupling.response(model, np.array([e])).transfer["V_phi"][0],
                            bounds=(0.0, 2.0), method="bounded", options={"xatol": 1e-12})
    assert model.resonance() == pytest.approx(found.x, abs=1e-6)


def test_b2_zero_resonance_is_independent_of_b1():
    for b1 in (0.0, 0.1, 1.0):
        assert coupling.Coupling(1, 1, 3, b1, 0.0).resonance() == pytest.approx(np.sqrt(1 - 0.25))


def test_zero_damping_resonance_is_reported_unbounded():
    out = CliRunner().invoke(main, ["coupling", "--J", "1", "--c1", "1", "--c2", "1",
                                    "--eta-range", "0:2:0.70710678118654752", "--format", "csv"],
                             catch_exceptions=False)
    assert out.exit_code == 0
    rows = _rows(out.stdout)
    assert rows[1]["V_phi"] == rows[1]["V_psi"] == rows[1]["V_q"] == "" and rows[1]["alpha_deg"] == ""
    assert "undamped resonance" in out.stderr and "unbounded" in out.stderr
    table = CliRunner().invoke(main, ["coupling", "--J", "1", "--c1", "1", "--c2", "1",
                                      "--eta-range", "0:2:0.70710678118654752"],
                               catch_exceptions=False)
    assert "∞" in table.stdout


def test_undamped_eta_one_is_the_antiresonance_of_psi():
    resp = coupling.response(coupling.Coupling(1, 1, 1, 0, 0), np.array([1.0]))
    assert resp.transfer["V_psi"][0] == pytest.approx(0.0, abs=1e-15)
    assert np.isnan(resp.phase["beta"][0])


def test_c2_zero_and_c1_zero():
    out = CliRunner().invoke(main, ["coupling", "--J", "1", "--c1", "1", "--c2", "0", "--b1", "0.1",
                                    "--b2", "0.1", "--eta-range", "0.5:1.5:0.5", "--format", "csv",
                                    "--moment", "2"], catch_exceptions=False)
    assert out.exit_code == 0 and "c2 = 0" in out.stderr
    rows = _rows(out.stdout)
    assert all(r["V_q"] == "" and float(r["MQ_hat"]) > 0 for r in rows)
    out = CliRunner().invoke(main, ["coupling", "--J", "1", "--c1", "0", "--c2", "1", "--b1", "0.1",
                                    "--b2", "0.1", "--eta-range", "0.5:1.5:0.5", "--format", "csv",
                                    "--moment", "2"], catch_exceptions=False)
    assert out.exit_code == 0 and "c1 = 0" in out.stderr
    rows = _rows(out.stdout)
    assert all(r["V_psi"] == "" and r["V_r"] == "" and float(r["psi_hat"]) > 0 for r in rows)


@pytest.mark.parametrize("args, message", [
    (["--J", "-1", "--c1", "1", "--c2", "1"], "--J must be"),
    (["--J", "1", "--c1", "-1", "--c2", "1"], "--c1 must be a non-negative number"),
    (["--J", "1", "--c1", "1", "--c2", "1", "--b2", "-0.1"], "--b2 must be a non-negative number"),
    (["--J", "1", "--c1", "0", "--c2", "0"], "c1 + c2 > 0"),
    (["--J", "1", "--c1", "1"], "--c2 must be given"),
    (["--J", "1", "--c1", "1", "--c2", "1", "--moment", "0"], "--moment must be a positive"),
    (["--J", "1", "--c1", "1", "--c2", "1", "--eta-range", "3:1:0.1"], "--eta-range"),
])
def test_bad_values_are_errors(args, message):
    out = CliRunner().invoke(main, ["coupling", *args], catch_exceptions=False)
    assert out.exit_code == 2, out.output
    assert message in out.output


def test_coupling_file_and_operating_speed(tmp_path):
    path = tmp_path / "coupling.toml"
    path.write_text('J = 1.0\nc1 = 1.0\nc2 = 1.0\nb1 = 0.05\nb2 = 0.05\neta_range = "0:1:0.5"\n'
                    'speed_rpm = 5\norder = 2\n')
    out = CliRunner().invoke(main, ["coupling", str(path)], catch_exceptions=False)
    assert out.exit_code == 0 and "Operating points" in out.stdout
    eta = 2 * 5 * 2 * np.pi / 60 / np.sqrt(2)
    assert f"{eta:.4g}" in out.stdout
    path.write_text("J = 1.0\nc1 = 1.0\nc2 = 1.0\nb3 = 0.1\n")
    bad = CliRunner().invoke(main, ["coupling", str(path)], catch_exceptions=False)
    assert bad.exit_code == 2 and "unknown key `b3`" in bad.output
