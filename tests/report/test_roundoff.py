"""Round-off is zero (issue 28, ``dyade.roundoff``): no command prints a figure below the
round-off of its own scale as a non-zero number, and a flag is yes or no.

The outputs are scanned for printed numbers: every shipped example's quantities in SI
lie far above 1e-10 (the smallest, a clearance of 1e-5 m or an inertia of 1e-4 kg·m²),
so a non-zero figure below ``TINY`` is round-off printed as a result. Lines that report
differences, errors, residuals or tolerances (which measure round-off themselves) are
not scanned."""

from __future__ import annotations

import re

import pytest
from click.testing import CliRunner

from dyade.cli import main
from dyade.roundoff import clean, is_roundoff
from tests.conftest import MECHANISMS, SHIPPED

TINY = 1e-10
NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")
MEASURES = ("residual", "differ", "error", "tol", "accuracy", "1e-")


def tiny_figures(text: str) -> list[str]:
    """The lines of ``text`` that print a non-zero number below TINY."""
    out = []
    for line in text.splitlines():
        if any(word in line.lower() for word in MEASURES):
            continue
        for token in NUMBER.findall(line):
            value = float(token)
            if value != 0.0 and abs(value) < TINY:
                out.append(line.strip())
                break
    return out


def run(*args: str) -> str:
    result = CliRunner(env={"COLUMNS": "200"}).invoke(main, list(args), catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return result.stdout + result.stderr


def test_the_rule():
    assert is_roundoff(1.1e-16, 1.9) and not is_roundoff(1e-11, 1.9)
    assert clean(-5.6e-16, 22.0) == 0.0 and str(clean(-5.6e-16, 22.0)) == "0.0"  # no −0
    assert clean(3.0, 22.0) == 3.0 and not is_roundoff(float("nan"), 1.0)


def test_the_scanner_sees_round_off():
    assert tiny_figures("M_1_4   N·m   7.10543e-15   34.0\nF_1_2   N   1286.01")
    assert not tiny_figures("M_1_4   N·m   0\nworst final residual  1.8e-14")


@pytest.mark.parametrize("args", [
    ("analyse", "slider-crank.toml", "--all"),
    ("flywheel", "fourbar.toml", "--fluctuation", "0.02"),
    ("balance", "fourbar.toml"),
    ("balance", "dyade-16.toml"),
    ("analyse", "dyade-16.toml", "--all")], ids=lambda a: "-".join(a[:2]))
def test_the_outputs_issue_28_found_print_round_off_as_zero(args):
    command, name, *rest = args
    text = run(command, str(MECHANISMS / name), *rest)
    assert tiny_figures(text) == []
    assert "1/0" not in text  # a flag is yes or no in a table


def test_the_curves_legend_says_a_round_off_mean_is_zero():
    pytest.importorskip("matplotlib")
    import dyade
    from dyade.plot import curves

    figure = curves.figure(dyade.analyse(dyade.read_mechanism(MECHANISMS / "slider-crank.toml")))
    labels = [line.get_label() for line in figure.axes[0].get_lines()]
    assert "mean 0 N·m" in labels


def commands():
    """Every command that reads a mechanism, on every shipped example."""
    for path in SHIPPED:
        yield ("analyse", str(path), "--all")
        yield ("analyse", str(path), "--all", "--set", "friction.coefficient=0.1",
               "--set", "friction.pin_radius=5", "--set", "friction.slider_length=40",
               "--set", "friction.slider_height=20")
        yield ("describe", str(path))
        yield ("flywheel", str(path), "--fluctuation", "0.02")
        yield ("balance", str(path))
    for path in sorted((MECHANISMS / "gears").glob("*.toml")):
        yield ("gears", str(path), "--modes", "3")
        yield ("gears", str(path), "--campbell", "0:3000:100")
    for path in sorted((MECHANISMS / "coupling").glob("*.toml")):
        yield ("coupling", str(path))
    yield ("flywheel", str(MECHANISMS / "torque" / "engine.csv"), "--fluctuation", "0.02",
           "--speed-rpm", "3000")


@pytest.mark.slow
@pytest.mark.parametrize("args", list(commands()), ids=lambda a: "-".join(
    [a[0], a[1].split("/")[-1]] + (["mu"] if "--set" in a else [])))
def test_no_command_prints_round_off(args):
    text = CliRunner(env={"COLUMNS": "200"}).invoke(main, list(args)).output
    assert tiny_figures(text) == []
    assert "1/0" not in text
