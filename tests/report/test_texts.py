"""Texts right (issue 28): what dyade says about a file matches the file and the numbers."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import shipped


@pytest.mark.parametrize("variant", [1, -1])
def test_describe_prints_the_rule_of_each_variant_and_the_geometry_obeys_it(variant):
    out = CliRunner(env={"COLUMNS": "250"}).invoke(
        main, ["describe", str(shipped("fourbar.toml")), "--set", f"dyad.2.variant={variant}"],
        catch_exceptions=False)
    assert out.exit_code == 0, out.output
    side = "left" if variant > 0 else "right"
    assert (f"assembly variant {variant:+d} (B {side} of the directed line A→C)"
            in " ".join(out.stdout.split()))
    # and B is on that side of A→C at every position
    cols = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), overrides={
        "dyad.2.variant": variant})).columns()
    a = np.array([cols["x_2_3"], cols["y_2_3"]])
    b = np.array([cols["x_3_4"], cols["y_3_4"]])
    c = np.array([cols["x_1_4"], cols["y_1_4"]])
    cross = (c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0])
    assert np.all(np.sign(cross) == variant)


# -- the figures the prose quotes, checked against the real output ------------------------
# A page carries, next to the prose, the command that makes its figures and the figures:
#
#   <!-- checked figures: dyade analyse mechanisms/self-locking.toml
#   locks at 90°–179° | locks (self-locking) at crank angles 90.0°–179.0°
#   117.1 W ≈ mean power
#   mean power P_mean W 117.1287
#   -->
#
# "PROSE | OUTPUT": PROSE is in the page, OUTPUT in the command's output; "QUOTE ≈ LABEL":
# QUOTE is in the page, and its first number is the first number after LABEL in the
# output rounded as QUOTE writes it; a line of neither kind is in both. Whitespace is
# normalised (tables wrap and align), the comment itself is not part of the page.
import re
import shlex

from tests.helpers import ROOT

CHECK = re.compile(r"<!-- checked figures: (.*?)\n(.*?)-->", re.S)
NUMBER = re.compile(r"[-−]?\d+(?:\.(\d+))?(?:[eE][-+]?\d+)?")
PAGES = ([ROOT / "README.md", ROOT / "mechanisms" / "README.md",
          ROOT / "mechanisms" / "gears" / "README.md"]
         + sorted(p for p in (ROOT / "docs").glob("**/*") if p.suffix in (".md", ".rst")
                  and "_build" not in p.parts))


def flat(text: str) -> str:
    return " ".join(text.split())


def checks() -> list[tuple[str, str, list[str], str]]:
    out = []
    for page in PAGES:
        if not page.exists():
            continue
        text = page.read_text()
        prose = flat(CHECK.sub(" ", text))
        for command, body in CHECK.findall(text):
            out.append((f"{page.relative_to(ROOT)}: {command[:60]}", command,
                        [line.strip() for line in body.splitlines() if line.strip()], prose))
    return out


CHECKS = checks()


def test_the_pages_carry_checked_figures():
    assert len(CHECKS) >= 8 and sum(len(lines) for _, _, lines, _ in CHECKS) >= 28


def _number(text: str) -> tuple[float, int | None]:
    found = NUMBER.search(text)
    assert found, text
    return float(found.group(0).replace("−", "-")), (len(found.group(1)) if found.group(1)
                                                     else 0)


@pytest.mark.parametrize("label, command, lines, prose", CHECKS, ids=[c[0] for c in CHECKS])
def test_quoted_figures_are_the_real_output(label, command, lines, prose):
    args = shlex.split(command)
    assert args[0] == "dyade"
    result = CliRunner(env={"COLUMNS": "200"}).invoke(main, args[1:], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    output = flat(result.stdout + result.stderr)
    for line in lines:
        if " ≈ " in line:
            quote, where = line.split(" ≈ ", 1)
            assert flat(quote) in prose, f"the page does not say {quote!r}"
            assert flat(where) in output, f"no {where!r} in the output of {command}"
            value, decimals = _number(quote)
            real, _ = _number(output.split(flat(where), 1)[1])
            assert round(real, decimals) == value, f"{quote!r}: the output says {real}"
        else:
            said, shown = line.split(" | ", 1) if " | " in line else (line, line)
            assert flat(said) in prose, f"the page does not say {said!r}"
            assert flat(shown) in output, f"no {shown!r} in the output of {command}"
