"""The design report (``dyade report``): one self-contained HTML file to review a
mechanism or a gear drive with colleagues.

For a mechanism file: the key results of ``dyade analyse``, the notes (validity,
friction, self-locking, clearance), the figures of ``dyade.plot``
(the linkage at four positions, drive torque and power with the energy fluctuation and
the transmission angles, the joints' polar diagrams, the clearance check where the file
has clearance data, the crank's speed and the motor where it has a ``[drive]``) and the
motion, one frame per swept position, scrubbed with a crank-angle slider, and last, for
reference, the file in assembly order as ``dyade describe`` says it. For a gear
file: the natural frequencies and energy shares, the Campbell diagram and the mode
shapes; for a study file its tables and the figure of its question; for a cam file the
cam's checks, their notes, the cam with its follower and its curves over the turn
(``dyade cam`` and ``dyade plot cam``).

Self-contained: figures inline as SVG (text as paths: no font is needed), the motion's
script and data inline, no request leaves the file; printable (a print stylesheet keeps
each figure on one page). Deterministic: the same input gives the same bytes (fixed
SVG hash salt, no dates, element ids prefixed per figure).
"""

from __future__ import annotations

import html
import io
import json
import os
import re
from typing import Any

import numpy as np

from dyade.errors import InputError

STYLE = """
:root { --ink: #1a1a1a; --rule: #c8c8c8; --muted: #5a5a5a; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: var(--ink);
       max-width: 1100px; margin: 1.5em auto; padding: 0 1em; line-height: 1.4; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; } h2 { font-size: 1.2em; border-bottom: 1px solid
var(--rule); padding-bottom: 0.2em; margin-top: 1.6em; }
.source { color: var(--muted); margin-top: 0; }
pre { background: #f6f6f6; padding: 0.8em; overflow-x: auto; font-size: 0.82em; line-height: 1.25; }
table { border-collapse: collapse; font-size: 0.88em; margin: 0.6em 0; }
caption { text-align: left; font-weight: 600; padding: 0.3em 0; white-space: pre-line; }
th, td { border-bottom: 1px solid var(--rule); padding: 0.2em 0.7em; }
th { text-align: left; background: #f0f0f0; } td.number { text-align: right;
font-variant-numeric: tabular-nums; }
ul.notes li { margin: 0.3em 0; } .none { color: var(--muted); }
figure { margin: 1em 0; break-inside: avoid; page-break-inside: avoid; }
figure svg { max-width: 100%; height: auto; display: block; }
figcaption { color: var(--muted); font-size: 0.9em; }
.motion-controls { display: flex; gap: 1em; align-items: center; }
.motion-controls input { flex: 1; }
nav ul { columns: 2; }
@media print {
  body { max-width: none; margin: 0; font-size: 10pt; }
  nav, .motion-controls { display: none; }
  h2 { break-after: avoid; page-break-after: avoid; }
  figure svg { max-height: 24cm; width: auto; max-width: 100%; }
  pre { white-space: pre-wrap; }
}
"""

SCRIPT = """
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("motion-data").textContent);
  var svg = document.getElementById("motion");
  var slider = document.getElementById("motion-slider");
  var readout = document.getElementById("motion-angle");
  var NS = "http://www.w3.org/2000/svg";
  function add(tag, attrs) {
    var node = document.createElementNS(NS, tag);
    for (var key in attrs) { node.setAttribute(key, attrs[key]); }
    svg.appendChild(node);
    return node;
  }
  function pairs(flat) {
    var out = [];
    for (var i = 0; i < flat.length; i += 2) { out.push(flat[i] + "," + flat[i + 1]); }
    return out.join(" ");
  }
  data.paths.forEach(function (p) {
    add("polyline", {points: pairs(p), fill: "none", stroke: "#8c8c8c",
                     "stroke-width": 1, "stroke-dasharray": "2 3"});
  });
  data.fixed.forEach(function (p) {
    add("polygon", {points: pairs(p), fill: "#ffffff", stroke: "#000", "stroke-width": 1});
  });
  var bodies = data.bodies.map(function (b) {
    var shape = b.plate ?
      add("polygon", {fill: b.colour, "fill-opacity": 0.25, stroke: b.colour, "stroke-width": 1.6}) :
      add("polyline", {fill: "none", stroke: b.colour, "stroke-width": 4, "stroke-linecap": "round"});
    return {b: b, shape: shape};
  });
  var rails = data.rails.map(function (r) {
    return {r: r, shape: add("path", {fill: "none", stroke: r.colour, "stroke-width": 1.2})};
  });
  var blocks = data.blocks.map(function (b) {
    return {b: b, shape: add("polygon", {fill: "#ffffff", "fill-opacity": 0.55, stroke: "#000",
                                         "stroke-width": 1.2})};
  });
  var pins = data.pins.map(function (p) {
    return {p: p, shape: add("circle", {r: 3.5, fill: "#fff", stroke: "#000", "stroke-width": 1.1})};
  });
  var points = data.points.map(function (p) {
    var mark = add("rect", {width: 5, height: 5, fill: "#000"});
    var text = add("text", {"font-size": 11, "font-family": "sans-serif"});
    text.textContent = p.name;
    return {p: p, mark: mark, text: text};
  });
  var labels = bodies.map(function (item) {
    var text = add("text", {"font-size": 10, "font-family": "sans-serif", "text-anchor": "middle",
                            "dominant-baseline": "central", fill: "#111"});
    text.textContent = String(item.b.link);
    return {item: item, text: text};
  });
  function at(flat, k, size) { return flat.slice(k * size, (k + 1) * size); }
  function show(k) {
    bodies.forEach(function (item) {
      item.shape.setAttribute("points", pairs(at(item.b.xy, k, item.b.size)));
    });
    labels.forEach(function (label) {
      var xy = at(label.item.b.xy, k, label.item.b.size), x = 0, y = 0, n = xy.length / 2;
      for (var i = 0; i < xy.length; i += 2) { x += xy[i] / n; y += xy[i + 1] / n; }
      label.text.setAttribute("x", x.toFixed(1));
      label.text.setAttribute("y", (y - 9).toFixed(1));
    });
    rails.forEach(function (item) {
      var xy = at(item.r.xy, k, 8);
      item.shape.setAttribute("d", "M" + xy[0] + "," + xy[1] + "L" + xy[2] + "," + xy[3] +
                              "M" + xy[4] + "," + xy[5] + "L" + xy[6] + "," + xy[7]);
    });
    blocks.forEach(function (item) {
      item.shape.setAttribute("points", pairs(at(item.b.xy, k, 8)));
    });
    pins.forEach(function (item) {
      var xy = at(item.p.xy, k, 2);
      item.shape.setAttribute("cx", xy[0]);
      item.shape.setAttribute("cy", xy[1]);
    });
    points.forEach(function (item) {
      var xy = at(item.p.xy, k, 2);
      item.mark.setAttribute("x", xy[0] - 2.5);
      item.mark.setAttribute("y", xy[1] - 2.5);
      item.text.setAttribute("x", xy[0] + 5);
      item.text.setAttribute("y", xy[1] - 5);
    });
    svg.setAttribute("data-frame", String(k));
    readout.textContent = "φ21 = " + data.angles[k].toFixed(1) + "°";
  }
  slider.addEventListener("input", function () { show(Number(slider.value)); });
  show(Number(slider.value));
})();
"""

MOTION_WIDTH = 640.0  # [px] the motion's drawing
DECIMALS = 1  # [px] coordinates of the motion's data


def report(path: str, overrides: dict[str, Any] | None = None, **options: Any) -> str:
    """The design report of a mechanism, gear, study or coupling file as one
    self-contained HTML page.

    Parameters
    ----------
    path : str
        A mechanism file (with a ``[crank]`` table), a gear file (``[[shaft]]``,
        ``[[gear]]`` … tables), a study file (``[plan]`` and ``[parameters]``), a
        coupling file (``J``, ``c1``, ``c2``) or a cam file (``[cam]`` and
        ``[follower]``).
    overrides : dict, optional
        Dotted keys and values that replace the file's (as ``--set``).
    **options
        The options of the analyses the report composes, by their API names, as the
        commands take them: for a mechanism ``start_deg``, ``stop_deg``, ``step_deg``
        and ``allow_partial`` (a mechanism that closes over part of the turn is
        reported over that part, the gaps shaded in the figures and said in the notes),
        ``units`` (``"file"``: the tables' lengths in the file's length unit, as
        ``dyade analyse``'s; ``"si"``: in metres).

    Returns
    -------
    str
        The HTML page (UTF-8 text; the same file gives the same text).

    Raises
    ------
    InputError
        The file is none of these kinds, or is not valid, or an option does not apply
        to its kind.
    """
    import os

    import dyade
    from dyade.files.schema import read_toml

    data = read_toml(path)  # names the file; a CSV is recognised as one
    source = os.path.basename(os.fspath(path))
    if "crank" in data:
        mechanism = dyade.read_mechanism(path, overrides)
        page = mechanism_report(mechanism, source=source, **options)
        # the page names the file, not where it lies: the same file gives the same bytes
        for where in sorted({os.fspath(path), os.path.abspath(path)}, key=len, reverse=True):
            page = page.replace(html.escape(where), html.escape(source))
        return page
    if "cam" in data and "follower" in data:
        return cam_report(path, overrides, source=source, **options)
    given = sorted(name for name, value in options.items() if value not in (None, False))
    if given:
        raise InputError.parameter(tuple(given), f"apply to a mechanism file; {source} is "
                                                 f"not one.")
    if any(key in data for key in ("shaft", "gear", "body")):
        return gear_report(dyade.read_gears(path, overrides), source=source)
    if "plan" in data and "parameters" in data and not overrides:
        return study_report(path, source=source)
    if any(key in data for key in ("J", "c1", "c2")) and not overrides:
        return coupling_report(path, source=source)
    from dyade.files.schema import other_kind

    raise InputError(f"{path}: neither a mechanism file (no [crank] table), a gear file "
                     f"(no [[shaft]], [[gear]] or [[body]] tables), a study file ([plan] "
                     f"and [parameters]) nor a coupling file (J, c1, c2), the last two "
                     f"without --set: a report is made of one of these (see "
                     f"`dyade help mechanism-file`).{other_kind(data, set())}")


# -- a mechanism -------------------------------------------------------------------------
def mechanism_report(mechanism, *, source: str = "", start_deg: float | None = None,
                     stop_deg: float | None = None, step_deg: float | None = None,
                     allow_partial: bool = False, units: str = "file") -> str:
    """The design report of a mechanism (see ``report``), over the sweep the options
    give (``dyade.analyse``'s)."""
    import dyade
    from dyade.registry import REGISTRY
    from dyade.analyses.sweep import outcome_of
    from dyade.plot import curves, mechanism as drawing, polar
    from dyade.report import describe, tables

    result = dyade.analyse(mechanism, start_deg=start_deg, stop_deg=stop_deg,
                           step_deg=step_deg, allow_partial=allow_partial)
    mechanism = result.mechanism  # with the sweep asked for
    cols = result.columns()
    outcome = outcome_of(result, cols)  # the sweep's Outcome, as dyade analyse gives it
    page = Page(f"{mechanism.name}: design report", source)
    length = mechanism.units[0] if units == "file" else "m"  # tables: the file's lengths
    parts = [table_html(tables.key_results(outcome, length), caption=False)]
    if result.drive is not None:
        parts.append(table_html(tables.motion_table(outcome)))
    page.section("Key results", "".join(parts))
    notes = outcome.notes
    page.section("Notes: where the model holds, friction, self-locking, clearance",
                 notes_html(notes))
    page.section("The linkage", figure(drawing.figure(result), "mechanism",
                                       "The linkage at four crank positions, the paths of "
                                       "its named points dotted."))
    page.section("The motion", motion_html(result))
    quantities = curves.default_quantities(result)
    if result.forces_valid is not None:
        quantities.insert(1, "P_drive")
    page.section("Drive torque, power and transmission angles", figure(
        curves.figure(result, quantities), "curves",
        "Drive torque with its cycle mean and the energy a flywheel must store (ΔE), the "
        "drive power, and each dyad's transmission angle; warned ranges shaded."))
    if result.drive is not None:
        page.section("The drive: crank speed and motor", figure(
            curves.figure(result, [name for name in ("omega_2", "M_motor", "M_drive")
                                   if name in cols]), "drive",
            "The crank's speed from the equation of motion and the motor's torque."))
    if mechanism.drive_line is not None:
        page.section("The elastic drive line (dyade driveline)", drive_line_html(mechanism))
    if result.forces is not None:
        page.section("Joint forces: polar diagrams", figure(
            polar.figure(result), "polar",
            "The force on the higher-numbered link over the crank cycle; crank angle every "
            "30°, reversals of the line of action numbered."))
    if any(getattr(joint, "clearance", None) is not None for joint in mechanism.joints):
        page.section("Clearance check", clearance_html(mechanism, result))
    page.section("The file in assembly order (dyade describe)",  # reference: last
                 pre(text_of(describe.describe(REGISTRY["describe"](mechanism)))))
    return page.html()


def drive_line_html(mechanism) -> str:
    """The file's [drive_line]: its natural frequency and range over the cycle, the VDI
    2149 ratio Ω/ω̄ with its verdict, and the periodic steady state next to the rigid
    drive's: the Outcome of the entry ``driveline-steady`` (run once), its notes, its
    tables as ``dyade driveline`` prints them and its figure."""
    from dyade.registry import REGISTRY
    from dyade.plot import drive_line as plot
    from dyade.report import drive_line as words

    outcome = REGISTRY["driveline-steady"](mechanism)
    notes = outcome.notes
    return (notes_html(notes) if notes else "") + table_html_many(
        words.tables(outcome, columns=False)) + figure(
        plot.steady(outcome.result), "driveline",
        "Shaft torque, crank speed and twist of the elastic drive line over one revolution, "
        "next to the rigid drive's torque and speed.")


def clearance_html(mechanism, result) -> str:
    """f(τ) of every reversal of the joints with clearance data, the peak force over
    0.5–1.5 times the crank speed (5 speeds), and the worst reversal simulated: the
    Outcomes of the ``clearance-check`` and ``clearance-speeds`` entries, each run once,
    over the positions where the mechanism closes (those of the report's sweep
    ``result``, which has succeeded: ``allow_partial`` changes nothing where it closes
    everywhere)."""
    from dyade.registry import REGISTRY
    from dyade.plot import clearance as plot

    partial = not bool(np.all(result.rows))
    check = REGISTRY["clearance-check"](mechanism, simulate=True, allow_partial=partial)
    checked = check.result
    rpm = checked.speed_rpm
    speeds = REGISTRY["clearance-speeds"](
        mechanism, speed_range_rpm=f"{0.5 * rpm:.6g}:{1.5 * rpm:.6g}:{0.25 * rpm:.6g}",
        allow_partial=partial)
    cases = plot.cases(checked.study[0][1])
    worst = checked.history
    history = (None if worst is None else
               plot.History(plot.Case(worst.label, worst.peak), worst.simulation))
    fig = plot.figure(cases, speeds=plot.speed_lines(speeds.result.study), history=history,
                      title=mechanism.name, operating=plot.operating_points(cases, rpm))
    return figure(fig, "clearance", "The clearance peak force of each reversal on f(τ), the "
                  "peak against crank speed with the operating point, and the worst reversal "
                  "simulated next to the closed form.")


def motion_html(result) -> str:
    """The linkage drawn by an inline script, one frame per swept position, and a
    crank-angle slider."""
    from dyade.plot.mechanism import geometry, link_colour

    geo = geometry(result)
    x0, x1, y0, y1 = geo.limits
    scale = MOTION_WIDTH / (x1 - x0)
    height = (y1 - y0) * scale

    def flat(xy: np.ndarray) -> list:
        """(…, 2) world points -> flat list of SVG coordinates, frames first."""
        xy = np.asarray(xy, dtype=float)
        screen = np.stack([(xy[..., 0] - x0) * scale, (y1 - xy[..., 1]) * scale], axis=-1)
        return np.round(np.nan_to_num(screen), DECIMALS).reshape(-1).tolist()

    data = {
        "angles": np.round(np.rad2deg(geo.crank_angle), 6).tolist(),
        "paths": [flat(path) for path in geo.paths.values()],
        "fixed": [flat(np.array([at, at + [-0.6 * h, -h], at + [0.6 * h, -h]]))
                  for at in geo.pivots.values() for h in [0.045 * geo.size]],
        "bodies": [{"link": body.link, "plate": bool(body.plate),
                    "colour": link_colour(body.link), "size": int(body.outline.shape[1] * 2),
                    "xy": flat(body.outline)} for body in geo.bodies],
        "rails": [{"colour": "#262626" if s.fixed_guide else link_colour(s.carrier),
                   "xy": flat(s.rails)} for s in geo.sliders],
        "blocks": [{"xy": flat(s.block)} for s in geo.sliders],
        "pins": [{"xy": flat(xy)} for xy in geo.pins.values()],
        "points": [{"name": name, "xy": flat(xy)} for name, xy in geo.points.items()],
    }
    count = len(data["angles"])
    text = json.dumps(data, separators=(",", ":"), ensure_ascii=False).replace("</", "<\\/")
    return (f'<figure class="motion"><svg id="motion" xmlns="http://www.w3.org/2000/svg" '
            f'viewBox="0 0 {MOTION_WIDTH:.0f} {height:.0f}" width="{MOTION_WIDTH:.0f}" '
            f'height="{height:.0f}" role="img" aria-label="the linkage in motion"></svg>'
            f'<div class="motion-controls"><label for="motion-slider">crank angle</label>'
            f'<input type="range" id="motion-slider" min="0" max="{count - 1}" value="0" '
            f'step="1"><output id="motion-angle"></output></div>'
            f'<figcaption>{count} frames, one per swept position: move the slider to turn '
            f'the crank.</figcaption></figure>'
            f'<script type="application/json" id="motion-data">{text}</script>'
            f'<script>{SCRIPT}</script>')


# -- a disc cam ---------------------------------------------------------------------------
CAM_ANGLES = (0.0, 180.0)
"""[°] the cam angles the report draws the cam and its follower at (the first solid)"""


def cam_report(path, overrides=None, *, source: str = "", step_deg: float | None = None,
               **options: Any) -> str:
    """The design report of a cam file (see ``report``): the checks of the ``cam`` entry
    (pressure angle, curvature and undercut, smallest base circle, contact force,
    lift-off speed, Hertz stress, drive torque, the profile to manufacture), its notes,
    the cam figure of ``dyade plot cam`` and the table over the turn (as ``dyade cam``
    gives them). ``step_deg``: the cam-angle step of the checks (the entry's)."""
    from dyade.plot import cam as plot
    from dyade.registry import REGISTRY
    from dyade.report import cam as words

    given = sorted(name for name, value in options.items()
                   if value not in (None, False) and name != "units")
    if given or overrides:
        raise InputError.parameter(tuple(given) or ("set",),
                                   f"apply to a mechanism file; {source} is a cam file (its "
                                   f"report takes --step, the cam-angle step).")
    outcome = REGISTRY["cam"](path, **({} if step_deg is None else {"step_deg": step_deg}))
    summary, *rest = words.tables(outcome, words.REPORT_COLUMNS)
    page = Page(f"{outcome.meta.get('name') or 'Cam'}: design report", source)
    page.section("The cam's checks", table_html(summary, caption=False))
    notes = outcome.notes
    page.section("Notes: pressure angle, undercut, lift-off, the profile",
                 notes_html(notes) if notes else
                 '<p class="none">None: the cam passes every check over the turn.</p>')
    angles = ", ".join(f"{a:g}°" for a in CAM_ANGLES)
    page.section("The cam and its follower", figure(
        plot.figure(outcome, CAM_ANGLES), "cam",
        f"The cam turned to {angles} with its follower (the first solid, the common "
        f"normal dashed), the follower's motion s, s′, s″, s‴, the pressure angle against "
        f"its limit, the radii of curvature with the roller's radius (undercut shaded), "
        f"the contact force and the drive torque over the turn."))
    page.section("Over the turn", table_html_many(rest))
    return page.html()


# -- a gear drive ------------------------------------------------------------------------
def gear_report(drive, *, source: str = "") -> str:
    """The design report of a gear drive (see ``report``): its modes, Campbell diagram
    and mode shapes, from the Outcomes of the ``gear-modes`` and ``gear-campbell``
    entries (each run once; the Campbell diagram reuses the modes)."""
    from dyade.registry import REGISTRY
    from dyade.plot import campbell as campbell_plot, modes as modes_plot
    from dyade.report import gears

    outcome = REGISTRY["gear-modes"](drive)
    modes = outcome.result.modes
    page = Page(f"{drive.name}: design report", source)
    page.section("Natural frequencies and energy shares",
                 table_html_many(gears.mode_tables(outcome)))
    page.section("Notes", notes_html(outcome.notes))
    if drive.speed is not None and drive.speed.rpm:
        campbell = REGISTRY["gear-campbell"](modes)  # 0 to 1.5 × the file's speed
        page.section("Campbell diagram", figure(
            campbell_plot.figure(campbell.result), "campbell",
            "Natural frequencies against the input speed, the excitation lines and their "
            "crossings, sized by the modal mesh stiffness.") + table_html_many(
            gears.campbell_tables(campbell)))
    page.section("Mode shapes", figure(modes_plot.figure(modes, 4), "modes",
                                       "The first elastic mode shapes along each shaft line."))
    return page.html()


# -- a design study ---------------------------------------------------------------------
def study_report(path, *, source: str = "") -> str:
    """The design report of a study file (see ``report``): its tables and the figure of
    its question."""
    from dyade.plot import study as plot
    from dyade.registry import REGISTRY
    from dyade.report.study import tables

    outcome = REGISTRY["study"](path)
    result = outcome.result
    page = Page(f"Study {result.spec.label}: design report", source)
    page.section("Results", table_html_many(tables(outcome)))
    page.section("The question", figure(plot.question_figure(result), "study",
                                        "The figure of the study's question (as dyade plot "
                                        "study draws it)."))
    return page.html()


# -- a stiff coupling -------------------------------------------------------------------
def coupling_report(path, *, source: str = "") -> str:
    """The design report of a coupling file (see ``report``): the torsional resonance
    (Strümpfel), its notes, the transfer functions and phases against η with the
    operating points, and their tables (as ``dyade coupling`` gives them)."""
    from dyade.registry import REGISTRY
    from dyade.plot import coupling as plot
    from dyade.report import coupling as report_

    outcome = REGISTRY["coupling"](path)
    model, response, operating = outcome.result
    tables = report_.tables(outcome)
    first = 2 if operating is not None else 1  # the summary and the operating points
    page = Page(f"{outcome.meta.get('name') or 'Stiff coupling'}: design report", source)
    page.section("Torsional resonance", table_html_many(tables[:first]))
    notes = outcome.notes
    page.section("Notes", notes_html(notes) if notes else
                 '<p class="none">None: the coupling is damped on both sides.</p>')
    page.section("Transfer functions and phases", figure(
        plot.figure(model, response, operating), "coupling",
        "The transfer functions V against the tuning ratio η = Ω/ω_t and their phases "
        "(lead over the exciting moment), the resonance and the operating points marked."))
    page.section("Tables", table_html_many(tables[first:]))
    return page.html()


# -- the page ----------------------------------------------------------------------------
class Page:
    """Sections of a report, written as one HTML page."""

    def __init__(self, title: str, source: str) -> None:
        self.title, self.source = title, source
        self.sections: list[tuple[str, str]] = []

    def section(self, heading: str, body: str) -> None:
        self.sections.append((heading, body))

    def html(self) -> str:
        from dyade import __version__

        ids = [f"s{k + 1}" for k in range(len(self.sections))]
        contents = "".join(f'<li><a href="#{i}">{html.escape(h)}</a></li>'
                           for i, (h, _) in zip(ids, self.sections))
        body = "".join(f'<section id="{i}"><h2>{html.escape(h)}</h2>{b}</section>'
                       for i, (h, b) in zip(ids, self.sections))
        source = (f"from {html.escape(self.source)}, " if self.source else "")
        return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
                f'<meta name="viewport" content="width=device-width, initial-scale=1">'
                f'<meta name="generator" content="dyade {__version__}">'
                f"<title>{html.escape(self.title)}</title><style>{STYLE}</style></head>"
                f"<body><h1>{html.escape(self.title)}</h1>"
                f'<p class="source">{source}made by dyade {__version__}</p>'
                f"<nav><ul>{contents}</ul></nav>{body}</body></html>\n")


def figure(fig, key: str, caption: str) -> str:
    """A matplotlib figure as inline SVG, its ids prefixed with ``key`` (unique on the
    page), with its caption."""
    from dyade.plot import canvas

    svg = canvas.render(fig, "svg").decode("utf-8")
    svg = svg[svg.index("<svg"):]
    ids = set(re.findall(r'\bid="([^"]+)"', svg))
    if ids:
        pattern = "|".join(re.escape(i) for i in sorted(ids, key=len, reverse=True))
        seen: dict[str, int] = {}

        def unique(match) -> str:  # a gid given to an artist in every panel: numbered
            name = match.group(1)
            seen[name] = seen.get(name, 0) + 1
            return f'id="{key}-{name}"' if seen[name] == 1 else f'id="{key}-{name}-{seen[name]}"'

        svg = re.sub(rf'#({pattern})\b', lambda m: f"#{key}-{m.group(1)}", svg)
        svg = re.sub(rf'\bid="({pattern})"', unique, svg)
    svg = re.sub(r'<svg([^>]*?) width="([\d.]+)pt" height="([\d.]+)pt"',
                 r'<svg\1 width="\2pt" height="\3pt" role="img"', svg, count=1)
    return (f'<figure id="figure-{key}">{svg}<figcaption>{html.escape(caption)}'
            f"</figcaption></figure>")


def text_of(renderable) -> str:
    """A rich renderable as plain text (no colour), 100 columns wide."""
    from rich.console import Console

    console = Console(file=io.StringIO(), width=100, color_system=None, record=True,
                      force_terminal=False, legacy_windows=False)
    console.print(renderable)
    return console.export_text().rstrip() + "\n"


def pre(text: str) -> str:
    return f"<pre>{html.escape(text)}</pre>"


def table_html(table, caption: bool = True) -> str:
    """A rich Table as an HTML table: its title as caption, its columns and cells as
    text (markup removed); right-justified columns as numbers. ``caption``: also its
    caption (the terminal's hints about flags are left out with False)."""
    from rich.text import Text

    def plain(value) -> str:
        # texts as written, as the terminal shows them (dyade.cli.output.literal): "[mm]"
        # in a header is a unit, not markup
        return value.plain if isinstance(value, Text) else str(value)

    columns = table.columns
    head = "".join(f"<th>{html.escape(plain(c.header))}</th>" for c in columns)
    cells = [list(c.cells) for c in columns]
    kinds = [' class="number"' if c.justify == "right" else "" for c in columns]
    rows = []
    for k in range(max((len(c) for c in cells), default=0)):
        rows.append("<tr>" + "".join(f"<td{kind}>{html.escape(plain(cell[k]))}</td>"
                                     for kind, cell in zip(kinds, cells)) + "</tr>")
    title = f"<caption>{html.escape(plain(table.title))}</caption>" if table.title else ""
    note = (f'<p class="none">{html.escape(plain(table.caption))}</p>'
            if caption and table.caption else "")
    return f"<table>{title}<thead><tr>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>{note}"


def table_html_many(parts) -> str:
    """Rich tables and lines of text as HTML."""
    out = []
    for part in parts:
        if part is None:
            continue
        out.append(f"<p>{html.escape(str(part))}</p>" if isinstance(part, str) else
                   table_html(part))
    return "".join(out)


def notes_html(notes: list[str]) -> str:
    if not notes:
        return '<p class="none">None: the model holds over the whole sweep.</p>'
    return '<ul class="notes">' + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>"
