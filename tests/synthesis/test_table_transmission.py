"""A function table has one answer (Freudenstein's three points, a slider-crank's, their
least-squares fits): ``search.min_transmission`` cannot choose among candidates there, so
a solution whose transmission angle falls below it over the table's range is refused
(exit 1) with the least angle and where it lies — the same angle ``dyade analyse`` reports
for the design — and a limit it keeps lets the design through."""

from __future__ import annotations

import json
import re

import pytest
from click.testing import CliRunner

from dyade.cli import main


def template(tmp_path, kind: str, limit: float | None):
    path = tmp_path / f"{kind}-{limit}.toml"
    assert CliRunner().invoke(main, ["init", kind, str(path)]).exit_code == 0
    if limit is not None:
        text = path.read_text().replace("[scores]", f"[search]\nmin_transmission = {limit}\n\n"
                                                    "[scores]", 1)
        path.write_text(text)
    return path


def analysed_least(tmp_path, kind: str) -> float:
    """The design's smallest transmission angle [°] by ``dyade analyse`` of its file over
    the table's range."""
    folder = tmp_path / "designs"
    out = CliRunner().invoke(main, ["synthesise", str(template(tmp_path, kind, None)),
                                    "--write", str(folder)])
    assert out.exit_code == 0, out.output
    out = CliRunner().invoke(main, ["analyse", str(folder / "design-1.toml"),
                                    "--format", "json"])
    assert out.exit_code == 0, out.output
    summary = json.loads(out.output)["summary"]
    return min(v["value"] for k, v in summary.items() if re.fullmatch(r"mu_\d+_min_deg", k))


@pytest.mark.parametrize("kind", ["synthesis-function", "synthesis-slider"])
def test_a_table_solution_below_the_transmission_limit_is_refused(tmp_path, kind):
    least = analysed_least(tmp_path, kind)
    below = CliRunner().invoke(main, ["synthesise", str(template(tmp_path, kind, least + 1.0))])
    assert below.exit_code == 1, below.output
    said = re.search(r"transmission angle of only ([\d.]+)°", below.output)
    assert said and float(said.group(1)) == pytest.approx(least, abs=0.06)
    assert "search.min_transmission" in below.output and "Traceback" not in below.output
    kept = CliRunner().invoke(main, ["synthesise", str(template(tmp_path, kind, least - 1.0))])
    assert kept.exit_code == 0, kept.output
