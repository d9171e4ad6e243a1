"""Make the figures of the gallery (docs/*.png, docs/*.gif) with `dyade.plot`.

Run from the repository (needs the plot extra: pip install -e ".[plot]"):

    python docs/make_figures.py

Each function below builds one figure from the shipped examples and returns it (the
animation: its ``Animation``); the gallery page (docs/gallery.md) shows each function's
code and runs it at build time. The output is deterministic (the same data and
matplotlib give the same bytes), so rerunning changes nothing unless dyade or
matplotlib changed. Prints each figure's size and the time to compute and draw it.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import dyade  # noqa: E402
from dyade import clearance  # noqa: E402
from dyade.plot import animate, canvas, clearance as clearance_plot  # noqa: E402
from dyade.plot import campbell, coupling, curves, drive_line, mechanism, modes, polar  # noqa: E402
from dyade.plot import profile, servo  # noqa: E402

DOCS = ROOT / "docs"
MECHANISMS = ROOT / "mechanisms"
DPI = 80  # [dots per inch] of the gallery's PNGs


def fourbar_polar():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "fourbar.toml"))
    return polar.figure(result)


def dyade16_polar_reversals():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "dyade-16.toml"))
    return polar.figure(result, [(5, 6), (2, 7), (4, 15)])


def dyade16_torque():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "dyade-16.toml"))
    return curves.figure(result)


def slotted_lever_motion():
    mechanism = dyade.read_mechanism(MECHANISMS / "slotted-lever.toml")
    return animate.animation(dyade.analyse(mechanism, step_deg=5.0))


def coupling_resonance():
    model = dyade.read_coupling(MECHANISMS / "coupling" / "stiff-coupling.toml")
    response = dyade.coupling_response(model, np.arange(0.0, 3.0 + 1e-9, 0.01))
    points = dyade.operating_points(model, [1450, 2900], order=2)
    return coupling.figure(model, response, points)


def clearance_paper():
    args = {"mass": 3.6, "stiffness": 1e7, "clearance": 1e-4, "slope": 3.6e5}
    case = clearance_plot.Case("paper, section 4", clearance.peak_force(**args))
    speeds = clearance_plot.standalone_speeds(clearance.peaks_over_speed(
        **args, speed_rpm=300, speeds_rpm=np.arange(100, 601, 50)))
    history = clearance_plot.History(case, clearance.simulate(**args, history=True))
    return clearance_plot.figure([case], speeds=speeds, history=history,
                                 operating=clearance_plot.operating_points([case], 300))


def two_stage_campbell():
    drive = dyade.read_gears(MECHANISMS / "gears" / "two-stage.toml")
    from dyade.vibration.gears.campbell import default_speeds

    diagram = dyade.campbell(drive, default_speeds(drive.speed.rpm))
    return campbell.figure(diagram)


def two_stage_modes():
    drive = dyade.read_gears(MECHANISMS / "gears" / "two-stage.toml")
    return modes.figure(dyade.gear_modes(drive), 4)


def dyade16_drive_line():
    mechanism = dyade.read_mechanism(MECHANISMS / "dyade-16.toml", {
        "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    return drive_line.steady(dyade.drive_line_steady_state(mechanism))


def dyade16_mechanism():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "dyade-16.toml"))
    return mechanism.figure(result, at_deg=[0.0, 90.0])


def self_locking_curves():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "self-locking.toml"))
    return curves.figure(result)


def indexing_profile():
    return profile.figure(dyade.run("profile", MECHANISMS / "profiles" / "indexing.toml"))


def servo_press():
    return servo.figure(dyade.run("servo", MECHANISMS / "servo" / "press.toml"))


LAW_PARAMETERS = {"inclined-sine": {"velocity": 0.5},
                  "quintic-spline": {"points": [[0.3, 0.2], [0.6, 0.7]]},
                  "polynomial": {"v0": 0.5, "a0": 0.0, "v1": 0.0, "a1": -2.0}}
"""the parameters of a law's figure on docs/guide/motion-laws.md (others: its defaults)"""


def law_figure(name: str):
    """One motion law over its normalised time (docs/motion-laws/NAME.png)."""
    from dyade.motion.laws import law

    return profile.law_figure(law(name, **LAW_PARAMETERS.get(name, {})))


def fourbar_report(path: Path) -> None:
    """The top of `dyade report mechanisms/fourbar.toml` as headless Chromium shows it
    (skipped without a Chromium)."""
    import shutil
    import subprocess
    import tempfile

    from dyade.report.html import report

    chromium = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                     if shutil.which(n)), None)
    if chromium is None:
        print(f"{path.name}: no Chromium here, left as it is")
        return
    with tempfile.TemporaryDirectory() as folder:
        page = Path(folder) / "report.html"
        page.write_text(report(str(MECHANISMS / "fourbar.toml")), encoding="utf-8")
        subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                        "--disable-quic", "--no-first-run", "--disable-background-networking",
                        "--disable-component-update", "--disable-sync", "--hide-scrollbars",
                        f"--user-data-dir={folder}/profile", f"--screenshot={path}",
                        "--window-size=1000,2100", page.as_uri()],
                       check=True, capture_output=True, timeout=120)


FIGURES = {
    "fourbar-polar.png": fourbar_polar,
    "dyade-16-reversals.png": dyade16_polar_reversals,
    "dyade-16-torque.png": dyade16_torque,
    "slotted-lever-motion.gif": slotted_lever_motion,
    "coupling-resonance.png": coupling_resonance,
    "clearance-paper.png": clearance_paper,
    "two-stage-campbell.png": two_stage_campbell,
    "two-stage-modes.png": two_stage_modes,
    "dyade-16-driveline.png": dyade16_drive_line,
    "dyade-16-mechanism.png": dyade16_mechanism,
    "self-locking-curves.png": self_locking_curves,
    "indexing-profile.png": indexing_profile,
    "servo-press.png": servo_press,
}
"""file in docs/ -> the function that makes it"""

SCREENSHOTS = {"fourbar-report.png": fourbar_report}
"""file in docs/ -> the function that writes it (a browser's picture, not a figure)"""


def png(name: str) -> bytes:
    """The PNG bytes of the gallery figure ``name`` (a key of ``FIGURES``), as written."""
    return canvas.render(FIGURES[name](), "png", dpi=DPI)


def save(name: str, path: Path) -> None:
    """Write the gallery figure ``name`` to ``path``."""
    made = FIGURES[name]()
    if isinstance(made, animate.Animation):
        animate.save(made, str(path), fps=20, dpi=animate.DPI)
    else:
        canvas.save(made, str(path), dpi=DPI)


def main() -> None:
    os.chdir(ROOT)
    for name in FIGURES:
        path = DOCS / name
        started = time.perf_counter()
        save(name, path)
        elapsed = time.perf_counter() - started
        print(f"{name:28s} {path.stat().st_size / 1024:7.1f} KiB  {elapsed:6.2f} s")
    from dyade.motion.laws import LAWS

    (DOCS / "motion-laws").mkdir(exist_ok=True)
    for name in LAWS:
        path = DOCS / "motion-laws" / f"{name}.png"
        canvas.save(law_figure(name), str(path), dpi=DPI)
        print(f"motion-laws/{name + '.png':17s} {path.stat().st_size / 1024:7.1f} KiB")
    for name, make in SCREENSHOTS.items():
        make(DOCS / name)


if __name__ == "__main__":
    main()
