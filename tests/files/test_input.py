"""Bad input of every kind: clear message naming file and key, exit code 2 (or 1)."""

from __future__ import annotations

import textwrap

import pytest
from click.testing import CliRunner

from dyade.cli import main

FOURBAR = textwrap.dedent("""\
    name = "t"
    units = { length = "mm" }
    [frame.points]
    B0 = [250, 0]
    [crank]
    length = 50
    speed_rpm = 300
    [[dyad]]
    kind = "RRR"
    links = [3, 4]
    A = { link = 2, point = "tip" }
    C = { link = 1, point = "B0" }
    lengths = [200, 150]
    variant = 1
    """)


def run(tmp_path, text, *args):
    path = tmp_path / "mech.toml"
    path.write_text(text)
    result = CliRunner().invoke(main, ["analyse", str(path), *args], catch_exceptions=False)
    return result


def test_good_file_exits_zero(tmp_path):
    assert run(tmp_path, FOURBAR, "--format", "csv").exit_code == 0


@pytest.mark.parametrize("change, message", [
    (("variant = 1", "varient = 1"), "unknown key `dyad.2.varient`. Did you mean `variant`?"),
    (("speed_rpm = 300", "speed_rmp = 300"), "unknown key `crank.speed_rmp`. Did you mean `speed_rpm`?"),
    (("lengths = [200, 150]", "lengths = [200, \"150\"]"),
     "`dyad.2.lengths.2` must be a number [mm], got \"150\"."),
    (("lengths = [200, 150]", "lengths = [200, -150]"), "`dyad.2.lengths.2` must be positive [mm], got -150."),
    (("lengths = [200, 150]", "lengths = [200, 0]"), "`dyad.2.lengths.2` must be positive [mm], got 0."),
    (("length = 50", "length = 0"), "`crank.length` must be positive [mm], got 0."),
    (("speed_rpm = 300", ""), "`crank.speed_rpm` is missing."),
    (("links = [3, 4]", "links = [3, 3]"), "`dyad.2.links` must be two different new link numbers"),
    (("A = { link = 2", "A = { link = 5"), "`dyad.2.A.link` is link 5, which is not placed yet"),
    (("point = \"B0\"", "point = \"B1\""), "`dyad.2.C.point` names point \"B1\", which link 1 does not have"),
    (("kind = \"RRR\"", "kind = \"RRX\""), "`dyad.2.kind` must be 1-5 or one of RRR, RRP, RPR, PRP, PPR, got \"RRX\"."),
    (("variant = 1", "variant = 2"), "`dyad.2.variant` must be +1 or -1 (assembly variant), got 2."),
    (("units = { length = \"mm\" }", "units = { length = \"inch\" }"), "`units.length` must be one of m, cm, mm, um"),
    (("[crank]", "[crank]\ndirection = \"left\""), "`crank.direction` must be \"ccw\""),
])
def test_bad_values_name_the_key(tmp_path, change, message):
    result = run(tmp_path, FOURBAR.replace(*change))
    assert result.exit_code == 2, result.output
    assert "mech.toml" in result.output
    assert message in " ".join(result.output.split()), result.output
    assert "Traceback" not in result.output


def test_toml_syntax_error_gives_line_and_column(tmp_path):
    result = run(tmp_path, FOURBAR.replace("lengths = [200, 150]", "lengths = [200, 150"))
    assert result.exit_code == 2
    assert "mech.toml: not valid TOML" in result.output
    assert "line" in result.output and "column" in result.output


def test_duplicate_links_across_dyads(tmp_path):
    text = FOURBAR + textwrap.dedent("""\
        [[dyad]]
        kind = "RRR"
        links = [4, 5]
        A = { link = 3, point = [100, 0] }
        C = { link = 1, point = [0, 200] }
        lengths = [100, 100]
        """)
    result = run(tmp_path, text)
    assert result.exit_code == 2
    assert "`dyad.3.links` uses link 4 again" in result.output


def test_links_table_for_a_link_nobody_places(tmp_path):
    result = run(tmp_path, FOURBAR + "[links.7]\npoints = { P = [1, 2] }\n")
    assert result.exit_code == 2
    assert "`links.7` describes link 7, which no dyad places" in " ".join(result.output.split())


def test_dyad_that_cannot_close_names_dyad_and_ranges(tmp_path):
    # rocker too short: |A B0| ranges 200..300 mm, l_i + l_j = 260 mm
    result = run(tmp_path, FOURBAR.replace("lengths = [200, 150]", "lengths = [200, 60]"))
    assert result.exit_code == 1
    text = " ".join(result.output.split())
    assert "dyad 2 (kind 1 RRR, links 3-4) cannot close for crank angles" in text
    assert "--allow-partial" in text


def test_allow_partial_leaves_out_the_open_positions(tmp_path):
    text = FOURBAR.replace("lengths = [200, 150]", "lengths = [200, 60]")
    result = run(tmp_path, text, "--format", "csv", "--allow-partial")
    assert result.exit_code == 0
    rows = result.stdout.strip().splitlines()[1:]
    angles = [float(r.split(",")[0]) for r in rows]
    assert 0 < len(angles) < 361
    assert "left out" in result.stderr
    assert all("nan" not in r and ",," not in r for r in rows)


def test_sweep_options_and_bad_step(tmp_path):
    ok = run(tmp_path, FOURBAR, "--format", "csv", "--start", "10", "--stop", "20", "--step", "5")
    assert [r.split(",")[0] for r in ok.stdout.strip().splitlines()[1:]] == ["10", "15", "20"]
    bad = run(tmp_path, FOURBAR, "--step", "0")
    assert bad.exit_code == 2 and "--step" in bad.output


def test_missing_file_is_a_usage_error(tmp_path):
    result = CliRunner().invoke(main, ["analyse", str(tmp_path / "nope.toml")],
                                catch_exceptions=False)
    assert result.exit_code == 2 and "nope.toml" in result.output


def test_csv_has_the_contract_columns(tmp_path, mechanisms_dir):
    result = CliRunner().invoke(main, ["analyse", str(mechanisms_dir / "slider-crank.toml"),
                                       "--format", "csv"], catch_exceptions=False)
    header = result.stdout.splitlines()[0].split(",")
    assert header[:4] == ["angle_deg", "phi_2_deg", "omega_2", "alpha_2"]
    for name in ("x_1_2", "vx_2_3", "ay_3_4", "s_1_4", "v_1_4", "a_1_4", "mu_2_deg"):
        assert name in header
    assert "x_1_4" not in header  # (1,4) is prismatic: travel columns only


def test_piped_table_is_plain(mechanisms_dir):
    result = CliRunner().invoke(main, ["analyse", str(mechanisms_dir / "fourbar.toml"), "--all"],
                                catch_exceptions=False)
    assert result.exit_code == 0
    assert "\x1b[" not in result.stdout
    assert "omega_3" in result.stdout


def test_describe_lists_the_dyads_and_effects(mechanisms_dir):
    result = CliRunner().invoke(main, ["describe", str(mechanisms_dir / "dyade-16.toml")],
                                catch_exceptions=False)
    text = " ".join(result.stdout.split())
    assert result.exit_code == 0
    assert "dyad 8 ([[dyad]] table 7): kind 1 RRR" in text
    assert "(1,6) prismatic" in text
    assert "F = 3·(16−1) − 2·22 = 1" in text
    assert "kinematics" in text


def test_top_level_key_after_a_table_gets_a_hint(tmp_path):
    result = run(tmp_path, FOURBAR + "gravity = true\n")
    text = " ".join(result.output.split())
    assert result.exit_code == 2
    assert "unknown key `dyad.2.gravity`" in text and "is a top-level key" in text
