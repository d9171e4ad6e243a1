"""Six-bars for function targets (link 6's angle against the crank angle) and pose targets
(link 5 through poses): search and least squares, each result checked through dyade."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.errors import InputError
from dyade.files.synthesis import parse
from dyade.synthesis.topology import TOPOLOGIES

STEPHENSON = np.array([0.3, 1.0, 0.9, 1.0, 0.5, 0.4, 0.6, 1.4, 1.2, 1.0, 0.4, -0.2])


ERROR_REACHED = 1e-6
"""[°] the structural error the function test asks of the search and fit"""


def own(variant=1, start=0.0, stop=120.0, rows=9):
    """A Stephenson III six-bar's crank angles, link 6's angle, link 5's poses [deg, m]."""
    crank = np.deg2rad(np.linspace(start, stop, rows))
    e, f, g, p = TOPOLOGIES["stephenson-sixbar"].joints(STEPHENSON, variant, crank)
    return crank, np.angle(f - g)[0], p[0], np.angle(f - e)[0]


def test_link_6_and_link_5_of_the_closed_form_are_dyades():
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    crank, psi, p, theta = own(rows=13)
    data = TOPOLOGIES["stephenson-sixbar"].data(STEPHENSON, 1)
    found = positions(build(data), crank, [(5, (0.4, -0.2))])
    assert np.abs(np.angle(np.exp(1j * (found.angles[:, 6] - psi)))).max() < 1e-12
    assert np.abs(np.angle(np.exp(1j * (found.angles[:, 5] - theta)))).max() < 1e-12
    assert np.abs(found.points[:, 0, 0] + 1j * found.points[:, 0, 1] - p).max() < 1e-12


def test_too_few_rows_or_too_many_poses_name_the_key():
    crank, psi, p, theta = own(rows=8)
    with pytest.raises(InputError) as err:
        parse({"topology": "watt-sixbar", "target": {
            "kind": "function", "crank": list(np.rad2deg(crank)), "output": list(np.rad2deg(psi))}})
    assert "target.crank" in str(err.value) and "at least 9" in str(err.value)
    with pytest.raises(InputError) as err:
        parse({"topology": "watt-sixbar", "target": {
            "kind": "function", "method": "precision", "crank": [0] * 9, "output": [0] * 9}})
    assert "target.method" in str(err.value)
    poses = [[float(z.real), float(z.imag), 10.0 * k] for k, z in enumerate(p)]
    with pytest.raises(InputError) as err:
        parse({"topology": "watt1-sixbar", "target": {"kind": "poses", "poses": poses}})
    assert "target.poses" in str(err.value) and "7" in str(err.value)
    made = parse({"topology": "watt1-sixbar", "target": {"kind": "poses", "poses": poses[:5]}})
    assert made.target.poses.shape == (5, 3)
    law = {"unit": "deg", "period": 360, "segment": [
        {"kind": "rise", "law": "cycloid", "end": 120, "to": 40},
        {"kind": "return", "law": "cycloid", "end": 360, "to": 0}]}
    for zero, least in (({"output_zero": 150}, 9), ({}, 10)):  # ψ0 found: one more unknown
        with pytest.raises(InputError) as err:
            parse({"topology": "stephenson-sixbar", "target": {
                "kind": "function", "profile": law, "range": [0, 120], "rows": least - 1,
                **zero}})
        assert "target.rows" in str(err.value) and f"at least {least}" in str(err.value)


def test_the_cli_says_too_few_rows_with_exit_2(tmp_path):
    from dyade.cli import main

    path = tmp_path / "six.toml"
    path.write_text('topology = "stephenson-sixbar"\n[target]\nkind = "function"\n'
                    'crank = [0, 10, 20]\noutput = [50, 60, 70]\n')
    out = CliRunner().invoke(main, ["synthesise", str(path)])
    assert out.exit_code == 2 and "target.crank" in out.output and "Traceback" not in out.output


@pytest.mark.slow
def test_five_poses_of_a_six_bars_own_link_are_passed_through():
    from dyade.synthesis import synthesise

    for rows in (5,):
        crank, _, p, theta = own(stop=150.0, rows=rows)
        poses = [[float(z.real), float(z.imag), float(np.rad2deg(t))] for z, t in zip(p, theta)]
        result = synthesise(parse({"topology": "stephenson-sixbar", "target": {
            "kind": "poses", "poses": poses}, "search": {"candidates": 600, "block": 600}}))
        best = result.designs[0]
        assert best.converged and best.error < 1e-9  # [m], through dyade's engine
        assert "misses by at most" in best.notes[0]


@pytest.mark.slow
def test_a_six_bars_own_function_is_recovered_and_analyse_gives_the_same_angle(tmp_path):
    import csv

    from dyade.cli import main
    from dyade.report.synthesis import mechanism_text
    from dyade.synthesis import synthesise

    crank, psi, _, _ = own()
    result = synthesise(parse({"topology": "stephenson-sixbar", "target": {
        "kind": "function", "crank": list(np.rad2deg(crank)),
        "output": list(np.rad2deg(psi))}, "search": {"candidates": 1000, "block": 1000}}))
    made, best = result.function, result.designs[0]
    assert np.abs(np.rad2deg(made.error)).max() == pytest.approx(best.error)
    assert best.converged and best.error < ERROR_REACHED  # [°]
    path = tmp_path / "design.toml"  # the written file through `dyade analyse`
    path.write_text(mechanism_text(best), encoding="utf-8")
    table = tmp_path / "design.csv"
    out = CliRunner().invoke(main, ["analyse", str(path), "--format", "csv", "-o", str(table)])
    assert out.exit_code == 0, out.output
    with table.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    angle = np.array([float(r["angle_deg"]) for r in rows])
    phi6 = np.deg2rad([float(r["phi_6_deg"]) for r in rows])
    table_rows = [int(np.argmin(np.abs(angle - v))) for v in np.rad2deg(crank)]
    assert np.abs(angle[table_rows] - np.rad2deg(crank)).max() < 1e-9  # the table's angles
    miss = np.angle(np.exp(1j * (phi6[table_rows] - made.traced)))
    assert np.abs(miss).max() < 1e-12  # [rad]
