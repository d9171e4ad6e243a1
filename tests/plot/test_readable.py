"""Figures a designer can read at a glance (issue 29): on every plot kind and shipped
example no two drawn text labels overlap and none leaves the figure, while every label
that carries information is drawn (every reversal number, the 0°/90°/180°/270° marks of a
polar diagram, every link number and named point of a mechanism drawing).

The figures are the ones the command line writes: `dyade plot KIND` runs with the writer
replaced by one that keeps the figure. The sweep over every example is slow; a few of
the figures that were unreadable before issue 29 run by default.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.cli import main  # noqa: E402
from dyade.linkage.notes import NoteKind  # noqa: E402
from dyade.plot import canvas  # noqa: E402
from tests.conftest import SHIPPED  # noqa: E402
from tests.helpers import TEMPLATES, shipped  # noqa: E402
from tests.readable import clashes, covered_lines, drawn_labels  # noqa: E402

GEARS = [shipped("gears/two-stage.toml"), shipped("gears/friswell-geared.toml")]
OTHERS = {
    "coupling": [[shipped("coupling/stiff-coupling.toml")]],
    "campbell": [[GEARS[0]]],
    "modes": [[path] for path in GEARS],
    "clearance": [["--mass", "3.6", "--stiffness", "1e7", "--clearance", "1e-4", "--slope",
                   "360000", "--speed-rpm", "300", "--speed-range", "100:600:100",
                   "--simulate"],
                  [shipped("dyade-16.toml"), "--speed-range", "100:600:50", "--simulate"]],
    "profile": [[shipped("profiles/indexing.toml")], [shipped("profiles/conveyor.toml")],
                [TEMPLATES / "profile.toml"]],
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
    with tempfile.TemporaryDirectory() as folder:  # a folder of its own (tests run in parallel)
        out = CliRunner().invoke(main, ["plot", kind, *map(str, args), "-o",
                                        str(Path(folder) / f"unused.{suffix}")],
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


STUDY = shipped("studies/press-slide-tolerance.toml")
DRIVE_LINE = [shipped("dyade-16.toml"), "--set", "drive_line.stiffness=1000",
              "--set", "drive_line.damping=0.04"]
SPEEDS = ["--speed-range", "3000:4200:50"]
DRIVE_LINE_CASES = {"resonance": SPEEDS, "stability": SPEEDS, "steady": [],
                    "map": ["--speed-range", "3000:4200:100", "--map", "stiffness=600:1400:200"]}
GRID = {"dyad.2.lengths.1": "[170, 180, 190, 200, 210]",
        "dyad.2.lengths.2": "[140, 145, 150, 155, 160]"}
COARSE = {"dyad.2.lengths.1": "[80, 190, 200]", "dyad.2.lengths.2": "[150, 155]"}
SENSITIVITY = {"dyad.2.lengths.1": "{ nominal = 190, tol = 1 }",
               "dyad.2.lengths.2": "{ nominal = 150, tol = 1 }",
               "links.4.mass": "{ nominal = 0.9, tol = 0.01 }"}


def study_args(case: str, tmp_path) -> list:
    """`dyade plot study` arguments: the shipped tolerance study's histograms, an output
    along one parameter of a fourbar grid or a map over two, a sensitivity study's bars."""
    from tests.study.test_study import study_file

    if case == "tolerance":
        return [STUDY]
    if case == "sensitivity":
        return [study_file(tmp_path, "fourbar.toml", SENSITIVITY,
                           "kind = \"sensitivity\"\nrel_step = 0.002")]
    grid = study_file(tmp_path, "fourbar.toml", COARSE if case == "map-coarse" else GRID)
    axes = ["--x", "dyad.2.lengths.1"]
    return [grid, *axes] + (["--y", "dyad.2.lengths.2"] if case.startswith("map") else [])


QUICK = [pytest.param("polar", [shipped("dyade-16.toml")], id="polar-dyade-16",
                      marks=pytest.mark.slow),  # 5 s: the default suite's budget
         pytest.param("mechanism", [shipped("dyade-16.toml")], id="mechanism-dyade-16",
                      marks=pytest.mark.slow),
         pytest.param("mechanism", [shipped("fourbar.toml")], id="mechanism-fourbar"),
         pytest.param("polar", [shipped("slider-crank.toml")], id="polar-slider-crank")]
EVERY = linkage_jobs(SHIPPED) + [pytest.param(kind, args, id=f"{kind}-{k}")
                                 for kind, cases in OTHERS.items()
                                 for k, args in enumerate(cases)]


@pytest.mark.parametrize("case", ["map-coarse"])
def test_a_study_map_is_readable(case, tmp_path, monkeypatch):
    readable("study", study_args(case, tmp_path), monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("case", ["tolerance", "line", "map", "sensitivity"])
def test_every_study_figure_is_readable(case, tmp_path, monkeypatch):
    readable("study", study_args(case, tmp_path), monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("analysis", list(DRIVE_LINE_CASES))
def test_every_drive_line_figure_is_readable(analysis, monkeypatch):
    readable("driveline", [*DRIVE_LINE, "--analysis", analysis, *DRIVE_LINE_CASES[analysis]],
             monkeypatch)


# the kinds whose legends are checked against the drawn lines too (issue 29, legends that
# covered curves)
LEGENDS_OFF_THE_CURVES = {"study", "driveline", "curves"}


def readable(kind: str, args: list, monkeypatch) -> None:
    """No label overlaps or leaves the figure, and every informative label is drawn."""
    kept = drawn(kind, args, monkeypatch)
    assert problems_of(kept) == []
    if kind in LEGENDS_OFF_THE_CURVES:
        assert [p for fig in kept for p in covered_lines(fig)] == []
    if kind in ("polar", "mechanism"):
        result = dyade.analyse(dyade.read_mechanism(args[0]))
        keeps = (polar_keeps_every_reversal_number_and_crank_angle_mark if kind == "polar"
                 else mechanism_keeps_every_link_number_and_point_name)
        for fig in kept:
            keeps(fig, result)


@pytest.mark.parametrize("kind, args", QUICK)
def test_labels_neither_overlap_nor_leave_the_figure(kind, args, monkeypatch):
    readable(kind, args, monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("kind, args", EVERY)
def test_every_kind_and_example_is_readable(kind, args, monkeypatch):
    readable(kind, args, monkeypatch)


def covered(text: str, step: float = 30.0) -> set[int]:
    """The crank angles [°] a mark label names: "90°", "150°/180°", "0°–150°"."""
    out: set[int] = set()
    for part in text.split("/"):
        ends = [int(v.strip().rstrip("°")) for v in part.split("–")]
        out |= set(range(ends[0], ends[-1] + 1, int(step)))
    return out


def by_axes(fig) -> dict:
    texts: dict = {}
    for text, _ in drawn_labels(fig):
        texts.setdefault(text.axes, []).append(text)
    return texts


def polar_keeps_every_reversal_number_and_crank_angle_mark(fig, result) -> None:
    texts = by_axes(fig)
    for ax in (ax for ax in fig.axes if ax.get_visible()):
        gids = {line.get_gid(): line for line in ax.get_lines()}
        drawn_texts = [t.get_text() for t in texts.get(ax, [])]
        marks = next(line for gid, line in gids.items() if gid and gid.startswith("crank-"))
        named = [covered(t.get_text()) for t in texts.get(ax, [])
                 if (t.get_gid() or "").startswith("crank-angle-")]
        # every mark has a label, no angle twice, the quarter turns among them
        assert sum(len(n) for n in named) == len(marks.get_xdata()) == len(set().union(*named))
        reversals = [line for gid, line in gids.items() if gid and gid.startswith("reversals-")]
        count = len(reversals[0].get_xdata()) if reversals else 0
        assert sorted(t for t in drawn_texts if t.isdigit()) == [str(k) for k in
                                                                   range(1, count + 1)]
        angle = np.rad2deg(result.crank_angle)
        given = canvas.on_grid(result, result.columns()["forces_valid"].astype(float)) == 1
        quarter = {q for q in (0, 90, 180, 270) if given[np.argmin(np.abs(angle - q))]}
        assert quarter and quarter <= set().union(*named)


def mechanism_keeps_every_link_number_and_point_name(fig, result) -> None:
    from dyade.plot import mechanism

    expected = sorted([str(body.link) for body in mechanism.geometry(result).bodies]
                      + [point for point, _, _ in result.mechanism.named_points])
    texts = by_axes(fig)
    panels = [ax for ax in fig.axes if ax.get_visible()]
    assert len(panels) in (3, 4)  # a full turn: 4 positions, else start, middle, end
    for ax in panels:
        assert sorted(t.get_text() for t in texts[ax]
                      if t.get_gid() and t.get_gid().startswith(("link-label", "point-label"))
                      ) == expected


def test_every_note_kind_has_a_shading_style():
    assert set(canvas.NOTE_LOOK) == {kind.value for kind in NoteKind}
    looks = [look[1:] for look in canvas.NOTE_LOOK.values()]
    assert len(set(looks)) == len(looks)  # hatch and grey tell the kinds apart


def test_press_slide_shades_its_near_self_locking_ranges():
    from dyade.plot import curves

    result = dyade.analyse(dyade.read_mechanism(shipped("self-locking.toml")))
    notes = [n for n in result.notes if n.kind == NoteKind.NEAR_SELF_LOCKING]
    assert notes and notes[0].ranges
    fig = curves.figure(result)
    half = 0.5 * np.rad2deg(result.mechanism.sweep.step)
    for ax in fig.axes:
        spans = [p for p in ax.patches if p.get_gid() == "note-near_self_locking"]
        extents = sorted((round(float(p.get_x()) + half, 6),
                          round(float(p.get_x() + p.get_width()) - half, 6)) for p in spans)
        assert extents == sorted((round(float(np.rad2deg(a)), 6), round(float(np.rad2deg(b)), 6))
                                 for n in notes for a, b in n.ranges)
        assert any("near self-locking" in t.get_text() for t in ax.get_legend().get_texts())


def test_clearance_speed_panel_marks_the_operating_point_on_its_curve(monkeypatch):
    fig, = drawn("clearance", [shipped("dyade-16.toml"), "--speed-range", "100:600:50"],
                 monkeypatch)
    speed_panel = fig.axes[1]
    lines = {line.get_gid(): line for line in speed_panel.get_lines()}
    point = lines["operating-(2,7)"].get_xydata()[0]
    curve = lines["speed-(2,7)"].get_xydata()
    rpm = dyade.read_mechanism(shipped("dyade-16.toml")).crank.speed * 60 / (2 * np.pi)
    assert point[0] == pytest.approx(rpm)
    # the check at the operating speed and the speed study there: two paths, one force
    assert point[1] == pytest.approx(np.interp(rpm, curve[:, 0], curve[:, 1]), rel=1e-9)


def test_coupling_phase_legend_is_off_the_curves(monkeypatch):
    fig, = drawn("coupling", [shipped("coupling/stiff-coupling.toml")], monkeypatch)
    drawn_labels(fig)  # lays the figure out
    phase = fig.axes[1]
    legend = next(legend for legend in fig.legends if legend.get_title().get_text() == "phase")
    box = legend.get_window_extent()
    assert box.y1 <= phase.get_window_extent().y0  # below the panel, under its axis label
    assert [t.get_text() for t in legend.get_texts()] == ["α", "β", "γ", "δ"]


def test_campbell_enlarges_the_frequencies_below_600_hz(monkeypatch):
    from dyade.plot import campbell

    fig, = drawn("campbell", [GEARS[0]], monkeypatch)
    overview, enlarged = fig.axes[:2]
    assert enlarged.get_ylim() == (0.0, campbell.ZOOM)
    modes = dyade.gear_modes(dyade.read_gears(GEARS[0])).frequencies
    shown = sorted(int(line.get_gid().split("-")[1]) for line in enlarged.get_lines()
                   if (line.get_gid() or "").startswith("mode-"))
    assert shown == [k + 1 for k, f in enumerate(modes) if f <= campbell.ZOOM]
    assert enlarged.bbox.height > overview.bbox.height
