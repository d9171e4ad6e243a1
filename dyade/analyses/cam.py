"""``cam``: a disc cam and its follower over one turn (issue 40): the pressure angle
against its limit, the curvature and undercut, the smallest base circle, the contact
force, the speed at which the follower lifts off, the Hertz stress, the drive torque,
and the profile to manufacture (the working curve and the cutter's path at the chord
tolerance).

The input is a cam file (``[cam]``, ``[follower]``, ``[profile]``; docs/guide/cams.md)
or a ``dyade.model.cam.Cam``.
"""

from __future__ import annotations

import os
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome

OPTIONS = (
    Option("speed", float, "rpm", positive=True, metavar="RPM",
           help="Cam speed (default: the file's cam.speed_rpm)"),
    Option("step", float, "°", 1.0, positive=True, metavar="DEG",
           help="Cam-angle step of the checks"),
)

STUDY_OUTPUTS = {
    "pressure_angle_max_deg": "°", "rho_pitch_convex_min": "m", "rho_working_min": "m",
    "undercut": "-", "base_radius_min": "m", "lift_off_speed_rpm": "rpm",
    "contact_speed_min_rpm": "rpm", "contact_force_min": "N", "contact_force_max": "N",
    "drive_torque_max": "N·m", "hertz_stress_max": "Pa", "guide_margin_min": "-",
    "outer_flank_share": "-", "face_width": "m", "face_contact_min": "m",
    "face_contact_max": "m"}
"""the summary figures a study of a cam file gives (``dyade.study.cam``), SI, angles in
degrees; a flag 1 or 0"""


def units(follower: str) -> dict[str, tuple[str, str]]:
    """column -> (unit, description) for a follower kind (an oscillating follower's
    coordinate is an angle)."""
    angle = follower == "oscillating-roller"
    q = "rad" if angle else "m"
    return {
        "angle_deg": ("°", "cam angle θ (counter-clockwise; clockwise cams: the mirror image)"),
        "s": (q, "follower swing ψ − ψ0" if angle else "follower lift s"),
        "v": ("-" if angle else "m/rad", "s′ = ds/dθ"),
        "a": ("1/rad" if angle else "m/rad²", "s″ = d²s/dθ²"),
        "j": ("1/rad²" if angle else "m/rad³", "s‴ = d³s/dθ³"),
        "pressure_angle_deg": ("°", "pressure angle α: from the follower's motion to the "
                                    "common normal, counter-clockwise positive"),
        "rho_pitch": ("m", "radius of curvature of the pitch curve (convex positive)"),
        "rho_working": ("m", "radius of curvature of the working curve (convex positive)"),
        "undercut": ("flag", "the working curve folds (undercut) here"),
        "contact_force": ("N", "contact force along the common normal (empty: lifted off)"),
        "hertz_stress": ("Pa", "Hertz contact pressure p0 (empty: no width given, or no "
                               "contact)"),
        "drive_torque": ("N·m", "torque turning the cam against the follower, in its sense "
                                "of rotation"),
        "guide_margin": ("-", "the guide's lock margin 1 − μ·p/n_y for a push along the "
                              "guide (≤ 0: a push cannot move the follower)"),
        "jammed": ("flag", "the cam pushes the follower and it jams in its guide here"),
        "outer_flank": ("flag", "a groove's outer flank carries the load here (the contact "
                                "force is negative: the outer wall pushes the roller towards "
                                "the cam centre)"),
    }


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import dataclasses

    from dyade.errors import InputError
    from dyade.model.cam import Cam
    from dyade.units import RPM

    if isinstance(source, Cam):
        cam = source
    elif source is None:
        raise InputError.parameter("source", "is missing: give a cam file (or a Cam).")
    else:
        from dyade.files.cam import read_cam

        cam = read_cam(source)
    if options.get("speed_rpm") is not None:
        cam = dataclasses.replace(cam, speed=options["speed_rpm"] * RPM)
    return checked(cam, options["step_deg"], budget)


def checked(cam, step_deg: float = 1.0, budget: Budget | None = None,
            make: bool = True) -> Outcome:
    """The Outcome of a ``dyade.model.cam.Cam``'s checks at the cam-angle step
    ``step_deg`` [°] (``make``: with the profile to manufacture; a study's variants go
    without); what ``dyade.run("cam", cam, step_deg=...)`` gives.

    Raises
    ------
    InputError
        A step above 30°.
    DyadeError
        The follower can never keep contact with the cam.
    """
    import math

    import numpy as np

    from dyade.cam import checks, geometry
    from dyade.errors import DyadeError, InputError
    from dyade.units import DEG, RPM

    step = step_deg * DEG
    if not step <= math.radians(30.0):
        raise InputError.parameter("step_deg", f"must be at most 30 [°] (a cam's checks need "
                                               f"the angles between), got "
                                               f"{step_deg:g}.",
                                   value=step_deg, unit="°")
    count = int(math.ceil(2 * math.pi / step))
    if budget is not None:
        budget.time(count * 2e-6 + 0.05, f"the cam's checks at {count:,} angles")
    result = checks.check(cam, step, make=make)
    geo = result.geometry
    theta = geo.theta
    described = units(cam.follower)
    columns: dict[str, Any] = {
        "angle_deg": np.degrees(theta), "s": result.s, "v": result.v, "a": result.a,
        "j": result.j, "pressure_angle_deg": np.degrees(geo.pressure_angle),
        "rho_pitch": geo.pitch_curvature_radius, "rho_working": geo.working_curvature_radius,
        "undercut": geo.undercut, "contact_force": result.contact_force,
        "hertz_stress": result.hertz_stress, "drive_torque": result.drive_torque}
    if cam.follower == "translating-flat":
        del columns["rho_pitch"]
    if cam.width is None:
        del columns["hertz_stress"]
    if result.guide is not None:
        columns["guide_margin"] = result.guide.margin
        columns["jammed"] = result.jammed
    if result.outer_flank is not None:
        columns["outer_flank"] = result.outer_flank
    outcome = Outcome("cam", figures=("cam",),
                      meta={"name": cam.name, "source": None if cam.source is None
                            else os.fspath(cam.source), "follower": cam.follower,
                            "length_unit": cam.length_unit,
                            "rotation": "cw" if cam.clockwise else "ccw",
                            "closure": cam.closure},
                      result=result)
    outcome.columns = {name: np.asarray(values) + 0.0 if np.asarray(values).dtype.kind == "f"
                       else np.asarray(values) for name, values in columns.items()}  # no -0
    outcome.units = {name: described[name][0] for name in columns}
    outcome.descriptions = {name: described[name][1] for name in columns}

    def at(k: int) -> dict[str, float]:
        return {"angle_deg": float(np.round(np.degrees(theta[k]), 9))}

    add = outcome.add
    alpha = np.abs(geo.pressure_angle)
    k = int(np.nanargmax(alpha))
    add("pressure_angle_max_deg", float(np.degrees(alpha[k])), "°", at(k),
        "largest |pressure angle| α", limit=round(math.degrees(cam.limit), 9))
    notes: list[str] = list(result.profile_notes)
    spans = geometry.spans(theta, alpha > cam.limit)
    if spans:
        notes.append(f"warning: the pressure angle exceeds its limit "
                     f"{math.degrees(cam.limit):g}° at cam angles {_ranges(spans)} "
                     f"({np.degrees(alpha[k]):.1f}° at most): the follower may jam in its "
                     f"guide; a base circle of at least "
                     f"{_length(result.smallest_base_radius, cam)} keeps it within."
                     if result.smallest_base_radius is not None else
                     f"warning: the pressure angle exceeds its limit "
                     f"{math.degrees(cam.limit):g}° at cam angles {_ranges(spans)} "
                     f"({np.degrees(alpha[k]):.1f}° at most), and no base circle the arm reaches "
                     f"meets it: a longer arm or another pivot is needed.")
    if cam.follower != "translating-flat":
        rho = geo.pitch_curvature_radius
        convex = np.where(rho > 0, rho, np.inf)
        kc = int(np.argmin(convex))
        add("rho_pitch_convex_min", float(convex[kc]) if np.isfinite(convex[kc]) else None,
            "m", at(kc), "smallest convex radius of the pitch curve",
            limit=cam.roller_radius)
    rho_w = geo.working_curvature_radius
    convex_part = (geo.pitch_curvature_radius > 0 if cam.follower != "translating-flat"
                   else np.isfinite(rho_w))  # where the cam bulges (a fold: ρ < 0 there)
    if convex_part.any():
        kw = int(np.nanargmin(np.where(convex_part, rho_w, np.inf)))
        add("rho_working_min", float(rho_w[kw]), "m", at(kw),
            "smallest radius of curvature of the working curve where it bulges (negative: "
            "it folds, undercut)")
    add("undercut", bool(geo.undercut.any()), "flag", None, "the working curve undercuts")
    if cam.follower == "translating-flat":  # the face's contact travels across it: x = s′
        across = (geo.contact[:, 0] - geo.centre[:, 0])  # from the stem's line, as drawn
        low, high = int(np.argmin(across)), int(np.argmax(across))
        add("face_contact_min", float(across[low]), "m", at(low),
            "the contact's least distance from the stem's line across the face (x, "
            "negative: left of the stem)")
        add("face_contact_max", float(across[high]), "m", at(high),
            "the contact's largest distance from the stem's line across the face")
        add("face_width", float(across[high] - across[low]), "m", None,
            "face width the contact's travel needs (the range of s′)")
    if result.smallest_base_radius is not None:
        what = ("smallest base circle for the pressure-angle limit"
                if cam.follower != "translating-flat" else
                "smallest base circle without a cusp (r_b + s + s″ > 0)")
        add("base_radius_min", result.smallest_base_radius, "m", None, what)
    if cam.roller_radius > cam.base_radius:
        notes.append(f"warning: the roller (r_r = {_length(cam.roller_radius, cam)}) is larger "
                     f"than the base circle (r_b = {_length(cam.base_radius, cam)}): a cam so "
                     f"small beside its roller undercuts easily"
                     f"{'' if geo.undercut.any() else ' (this one does not)'}.")
    cut = geometry.spans(theta, geo.undercut)
    if cut:
        if cam.follower == "translating-flat":
            notes.append(f"warning: undercut at cam angles {_ranges(cut)}: the working "
                         f"curve's radius r_b + s + s″ is not positive there, so the flat "
                         f"face cannot follow the motion (cusp). A base circle of at least "
                         f"{_length(result.smallest_base_radius, cam)} avoids it.")
        else:
            notes.append(f"warning: undercut at cam angles {_ranges(cut)}: the roller radius "
                         f"{_length(cam.roller_radius, cam)} exceeds the pitch curve's convex "
                         f"radius there (down to {_length(float(convex[kc]), cam)}), so the "
                         f"working curve folds over itself and the follower will not run "
                         f"the motion. Take a smaller roller or a bigger base circle.")
    if result.chain is not None:
        outcome.meta["chain"] = getattr(cam.chain, "name", None)
        bad = ~np.asarray(result.chain.valid, dtype=bool)
        if bad.any():
            notes.append(f"warning: the linkage the lever drives does not close, or sits at a "
                         f"dead centre, at cam angles {_ranges(geometry.spans(theta, bad))}: "
                         f"its forces, the contact force and the drive torque are not given "
                         f"there.")
    if result.guide is not None:
        margin = result.guide.margin
        km = int(np.nanargmin(margin))
        add("guide_margin_min", float(margin[km]), "-", at(km),
            f"least lock margin of the guide (μ = {cam.guide_friction:g})", limit=0.0)
        jams = geometry.spans(theta, result.jammed)
        if jams:
            notes.append(f"warning: the follower jams in its guide at cam angles "
                         f"{_ranges(jams)}: the cam pushes it at a pressure angle the guide's "
                         f"friction μ = {cam.guide_friction:g} locks (lock margin down to "
                         f"{float(margin[km]):.3g}); the contact force and the drive torque "
                         f"are not given there. A longer guide, less overhang or a smaller "
                         f"pressure angle frees it.")
        elif float(margin[km]) <= 0.0:
            notes.append(f"note: the guide would lock a push at cam angle "
                         f"{math.degrees(theta[km]):.1f}° (margin {float(margin[km]):.3g}), "
                         f"but the cam does not push the follower along its motion there.")
    # forces
    force = result.contact_force
    given = np.isfinite(force)
    lowest, highest = result.contact_speeds
    speed_rpm = cam.speed / RPM
    if cam.closure == "spring":
        if highest == 0.0 or lowest > highest:
            where_ = result.contact_speed_angles[1 if highest == 0.0 else 0]
            why = "no speed keeps it on"
            if highest == 0.0 and where_ is not None:
                k = int(np.argmin(np.abs(theta - where_)))
                pressing = cam.stiffness * (result.s[k] + cam.preload) + cam.load
                why = ("nothing presses it on (no spring force or load: k·(s + s0) + F = 0)"
                       if pressing == 0.0 else
                       f"the spring and the load pull it off (k·(s + s0) + F = "
                       f"{pressing:.4g} {'N·m' if cam.follower == 'oscillating-roller' else 'N'})")
            raise DyadeError(
                f"{_label(cam)}: the follower can never keep contact with the cam: {why}"
                f"{'' if where_ is None else f' at cam angle {math.degrees(where_):.1f}°'}. "
                f"The spring force "
                f"k·(s + s0) + F must press it on: check `follower.preload`, "
                f"`follower.stiffness` and `follower.load`, or groove the cam "
                f"(`cam.closure` = \"groove\").")
        lift_rpm = highest / RPM if math.isfinite(highest) else None
        where_high = result.contact_speed_angles[1]
        add("lift_off_speed_rpm", lift_rpm, "rpm",
            None if where_high is None else {"angle_deg": round(math.degrees(where_high), 9)},
            "speed at which the follower lifts off (spring too weak)")
        if lowest > 0.0:
            add("contact_speed_min_rpm", lowest / RPM, "rpm", None,
                "speed below which the load pulls the follower off")
        if lift_rpm is None:
            notes.append("note: the follower never lifts off: it never decelerates away "
                         "from the cam against its spring.")
        elif result.lifted.any():
            notes.append(f"warning: at {speed_rpm:g} rpm the follower lifts off the cam at cam "
                         f"angles {_ranges(geometry.spans(theta, result.lifted))}: the spring "
                         f"holds it on only up to {lift_rpm:.4g} rpm. The contact force is not "
                         f"given there. A stiffer spring, more preload or a lighter follower "
                         f"raise that speed.")
        else:
            times = (f", {lift_rpm / speed_rpm:.3g} times the running speed of "
                     f"{speed_rpm:g} rpm" if speed_rpm else "")
            notes.append(f"note: the spring keeps the follower on the cam up to {lift_rpm:.4g} "
                         f"rpm{times}.")
    if given.any():
        kmin = int(np.nanargmin(force))
        kmax = int(np.nanargmax(np.abs(force)))
        add("contact_force_min", float(force[kmin]), "N", at(kmin),
            "least contact force" + (" (negative: the other flank)" if cam.closure == "groove"
                                     else ""))
        add("contact_force_max", float(np.abs(force[kmax])), "N", at(kmax),
            "largest contact force")
        torque = result.drive_torque
        kt = int(np.nanargmax(np.abs(torque)))
        add("drive_torque_max", float(torque[kt]), "N·m", at(kt), "drive torque of largest size")
        if cam.width is not None and np.isfinite(result.hertz_stress).any():
            kh = int(np.nanargmax(result.hertz_stress))
            add("hertz_stress_max", float(result.hertz_stress[kh]), "Pa", at(kh),
                "largest Hertz contact pressure p0")
    else:
        from dyade.analyses.base import withheld

        notes.append("note: the follower is off the cam at every angle.")
        outcome.notes = notes
        withheld(outcome, given, "no cam angle has its contact force given")
    if result.outer_flank is not None:
        flanks(outcome, result, theta, notes)
    for made in result.manufacture:
        add(f"{made.name}_points", int(made.points.shape[0]), "-", None,
            f"points of the {CURVES[made.name]} within the chord tolerance "
            f"{_length(made.tolerance, cam)}")
    outcome.notes = notes
    return outcome


CURVES = {"working": "working curve", "outer": "groove's outer flank",
          "cutter": "cutter path"}
"""a curve to manufacture -> its words"""


def flanks(outcome, result, theta, notes: list[str]) -> None:
    """A grooved cam's flanks: which one carries the load over the turn (a share and
    the cam angles where the contact switches flanks, N changing sign)."""
    import math

    import numpy as np

    from dyade.cam import geometry

    given = np.isfinite(result.contact_force)
    outer = np.asarray(result.outer_flank, dtype=bool) & given
    share = float(np.sum(outer) / max(int(np.sum(given)), 1))
    outcome.add("outer_flank_share", share, "-", None,
                "share of the turn over which the groove's outer flank carries the load")
    if not outer.any():
        notes.append("note: the groove's inner flank (the working curve) carries the load "
                     "over the whole turn: a spring would hold this follower on as well.")
        return
    inner = ~outer & given
    words = ", ".join(f"{math.degrees(theta[k]):.1f}°" for k in np.flatnonzero(
        given & np.roll(given, 1) & (outer != np.roll(outer, 1)))[:8])
    notes.append(f"note: the contact switches flanks of the groove at cam angles {words}: the "
                 f"outer flank carries the load at {_ranges(geometry.spans(theta, outer))}, "
                 f"the inner flank (the working curve) at "
                 f"{_ranges(geometry.spans(theta, inner)) or 'no angle'}. The roller's spin "
                 f"reverses at each switch: the groove's clearance is crossed there, with an "
                 f"impact.")


def _label(cam) -> str:
    return os.path.basename(os.fspath(cam.source)) if cam.source else cam.name


def _length(value: float | None, cam) -> str:
    """A length [m] in the file's unit: ``"40 mm"``."""
    from dyade.units import LENGTH_FACTORS

    if value is None:
        return "—"
    return f"{value / LENGTH_FACTORS[cam.length_unit]:.4g} {cam.length_unit}"


def _ranges(spans) -> str:
    import math

    parts = [f"{math.degrees(a):.1f}°" if a == b else f"{math.degrees(a):.1f}°–"
             f"{math.degrees(b):.1f}°" for a, b in spans[:6]]
    return ", ".join(parts) + (f" and {len(spans) - 6} more" if len(spans) > 6 else "")


ENTRIES = {"cam": Analysis("cam", "A disc cam and its follower over one turn", run, OPTIONS,
                           source="cam", figures=("cam",), command="dyade cam")}
"""``dyade cam``: a disc cam's checks and its profile to manufacture; the registry's
``cam`` entry (``dyade.analyses.cam``)."""
