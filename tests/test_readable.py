"""Figures a designer can read at a glance (issue 29): on every plot kind and shipped
example no two drawn text labels overlap and none leaves the figure, while every label
that carries information is drawn (every reversal number, the 0°/90°/180°/270° marks of a
polar diagram, every link number and named point of a mechanism drawing).

The figures are the ones the command line writes: `dyade plot KIND` runs with the writer
replaced by one that keeps the figure. The sweep over every example is slow; a few of
the figures that were unreadable before issue 29 run by default.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.cli import main  # noqa: E402
from dyade.linkage.notes import NoteKind  # noqa: E402
from dyade.plot import canvas  # noqa: E402
from tests.conftest import SHIPPED  # noqa: E402
from tests.helpers import shipped  # noqa: E402
from tests.readable import clashes, drawn_labels  # noqa: E402

GEARS = [shipped("gears/two-stage.toml"), shipped("gears/friswell-geared.toml")]
OTHERS = {
    "coupling": [[shipped("coupling/stiff-coupling.toml")]],
    "campbell": [[GEARS[0]]],
    "modes": [[path] for path in GEARS],
    "clearance": [["--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
                   "360000", "--speed-rpm", "300", "--speed-range", "100:600:100",
                   "--simulate"],
                  [shipped("dyade-16.toml"), "--speed-range", "100:600:50", "--simulate"]],
}


def drawn(kind: str, args: list, monkeypatch) -> list:
    """The figures `dyade plot KIND ARGS` draws (each animation at its first, middle and
    last frame), kept instead of written."""
    kept = []
    monkeypatch.setattr(canvas, "render", lambda fig, fmt, dpi=100: kept.append(fig) or b"")

    def frames(fig, update, count, path, fps=20.0, dpi=80):
        for k in sorted({0, count // 2, count - 1}):
            update(k)
            kept.append(_Frozen(fig, k))

    monkeypatch.setattr(canvas, "save_frames", frames)
    suffix = "gif" if kind == "animate" else "png"
    out = CliRunner().invoke(main, ["plot", kind, *map(str, args), "-o", f"/tmp/unused.{suffix}"],
                             catch_exceptions=False)
    assert out.exit_code == 0, out.output
    return kept


class _Frozen:
    """An animation's figure at frame k (checked at once, before the next frame)."""

    def __init__(self, fig, k: int) -> None:
        self.fig, self.k, self.problems = fig, k, clashes(fig)


def problems_of(kept) -> list[str]:
    out = []
    for item in kept:
        if isinstance(item, _Frozen):
            out += [f"frame {item.k}: {p}" for p in item.problems]
        else:
            out += clashes(item)
    return out


def linkage_jobs(paths) -> list:
    jobs = []
    for path in paths:
        kinds = ["curves", "mechanism", "animate"]
        if dyade.read_mechanism(path).has_dynamics:
            kinds.insert(0, "polar")
        jobs += [pytest.param(kind, [path], id=f"{kind}-{path.stem}") for kind in kinds]
    return jobs


QUICK = [pytest.param("polar", [shipped("dyade-16.toml")], id="polar-dyade-16"),
         pytest.param("mechanism", [shipped("dyade-16.toml")], id="mechanism-dyade-16"),
         pytest.param("polar", [shipped("slider-crank.toml")], id="polar-slider-crank")]
EVERY = linkage_jobs(SHIPPED) + [pytest.param(kind, args, id=f"{kind}-{k}")
                                 for kind, cases in OTHERS.items()
                                 for k, args in enumerate(cases)]


@pytest.mark.parametrize("kind, args", QUICK)
def test_labels_neither_overlap_nor_leave_the_figure(kind, args, monkeypatch):
    assert problems_of(drawn(kind, args, monkeypatch)) == []


@pytest.mark.slow
@pytest.mark.parametrize("kind, args", EVERY)
def test_every_kind_and_example_is_readable(kind, args, monkeypatch):
    assert problems_of(drawn(kind, args, monkeypatch)) == []
