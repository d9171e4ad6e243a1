"""``servo``: a servo-driven crank sized over its machine cycle (the ``[servo]`` table of
a mechanism file): the crank's motion from the profile (or the output's profile inverted
through the linkage), the torque by inverse dynamics at the real speed and acceleration
of every instant, the motor's torque behind the gear, its peak and RMS torque, top
speed, inertia ratio and regenerated energy, for the gear's ratio or over a range of
ratios (the RMS optimum marked), and a motor catalogue checked row by row
(``dyade.linkage.servo``, ``dyade.machine.servo``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome
from dyade.analyses.inputs import MECHANISM, load

OPTIONS = MECHANISM + (
    Option("ratio", float, positive=True, metavar="I",
           help="Gear ratio i = motor speed / crank speed (overrides servo.ratio)"),
    Option("ratio-range", str, metavar="START:STOP:STEP",
           help="Size over the gear ratios START, START+STEP, … STOP, as every range of "
                "dyade, and mark the RMS optimum within [START, STOP] (overrides "
                "servo.ratio_range): --ratio-range 3:40:1. LOW:HIGH (two numbers) takes "
                "--ratio-count ratios log-spaced instead"),
    Option("ratio-count", int, positive=True, metavar="N",
           help="Gear ratios of a LOW:HIGH range or of servo.ratio_range, log-spaced  "
                "[default: 25]"),
    Option("catalogue", str, metavar="CSV", study=False,
           help="Motor catalogue to check row by row (overrides servo.catalogue): columns "
                "name, rated_torque, peak_torque, rated_speed_rpm, top_speed_rpm, "
                "rotor_inertia, optionally envelope"),
    Option("rotor-inertia", float, "kg·m²", positive=True, metavar="J",
           help="The motor's rotor inertia J_M (overrides servo.rotor_inertia)"),
    Option("samples", int, positive=True, least=36, metavar="N",
           help="Time steps per cycle, even (overrides servo.samples)"),
    Option("max-inertia-ratio", float, positive=True, metavar="LAMBDA",
           help="Largest load-to-motor inertia ratio a motor passes with (overrides "
                "servo.max_inertia_ratio)"),
)

COLUMNS = {
    "t": ("s", "time since the cycle's start"),
    "angle_deg": ("°", "crank angle φ"),
    "omega_2": ("rad/s", "crank speed φ̇"),
    "alpha_2": ("rad/s²", "crank acceleration φ̈"),
    "s": ("", "the profile's position (crank angle [rad] or output [m, rad]) from its start"),
    "v": ("", "its velocity (per s)"),
    "a": ("", "its acceleration (per s²)"),
    "j": ("", "its jerk (per s³)"),
    "M_crank": ("N·m", "torque the crank shaft needs M_c = J·φ̈ + ½·J′·φ̇² − M_L + M_F"),
    "J_red": ("kg·m²", "reduced moment of inertia J(φ)"),
    "M_load": ("N·m", "reduced load torque M_L(φ), positive where the loads drive"),
    "M_friction": ("N·m", "friction's share of the crank torque M_F"),
    "n_motor_rpm": ("rpm", "motor speed i·φ̇"),
    "M_motor": ("N·m", "motor torque (rotor and gear inertia, gear losses included)"),
    "P_motor": ("W", "motor power M·ω (negative: fed back)"),
    "P_gear_loss": ("W", "power the gear loses"),
    "M_line": ("N·m", "torque of the [drive_line] shaft on the crank (elastic line)"),
    "lag_deg": ("°", "the crank's angle behind the elastic line minus the profile's"),
}
"""column -> (unit, description)"""


@dataclass
class ServoRun:
    """What the servo entry found, for the report and the figures."""

    mechanism: Any
    motion: Any
    """``dyade.linkage.servo.ServoMotion``"""
    cycle: Any
    """``dyade.machine.servo.Cycle``"""
    ratio: float
    """the ratio of the columns (the gear's, the RMS optimum of a range, or the chosen
    motor's)"""
    sizing: Any
    """``dyade.machine.servo.Sizing`` over ``ratios``"""
    optimum: float | None
    """the RMS-optimal ratio within the range (None: no range or no rotor inertia)"""
    checks: list
    """``dyade.machine.servo.Check`` per catalogue motor (empty without a catalogue)"""
    chosen: Any
    """the Check of the smallest motor that passes, or None"""
    rotor_inertia: float
    load: Any
    """``dyade.machine.servo.MotorLoad`` at ``ratio``"""


RATIO_RANGE = (1e-6, 1e6)  # [-] gear ratios a servo sizing takes
INERTIA_RANGE = (1e-12, 1e6)  # [kg·m²] rotor and gear inertias a servo sizing takes


def ratio_range(text: str, count: int | None = None
                ) -> tuple[tuple[float, float], list[float] | None]:
    """``--ratio-range``: ``START:STOP:STEP`` (as every range option of dyade: START,
    START + STEP, … up to STOP) -> ((START, STOP), its ratios); ``LOW:HIGH`` (two
    numbers, as before) -> ((LOW, HIGH), None: ``count`` log-spaced ratios, the
    caller's). An ``InputError`` on ``ratio_range`` (0 < START < STOP, STEP > 0, at
    most 10 000 ratios) or on ``ratio_count`` given with a STEP."""
    from dyade.errors import InputError
    from dyade.files.schema import range_values

    parts = text.split(":")
    try:
        numbers = [float(part) for part in parts]
    except ValueError:
        numbers = []
    if len(numbers) not in (2, 3) or not 0.0 < numbers[0] < numbers[1] < float("inf") or (
            len(numbers) == 3 and not 0.0 < numbers[2] < float("inf")):
        raise InputError.parameter("ratio_range", f"must be START:STOP:STEP with 0 < START < "
                                                  f"STOP and STEP > 0 (e.g. 3:40:1), or "
                                                  f"LOW:HIGH for --ratio-count log-spaced "
                                                  f"ratios; got {text!r}.", value=text)
    bounds = (numbers[0], numbers[1])
    if len(numbers) == 2:
        return bounds, None
    if count is not None:
        raise InputError.parameter("ratio_count", f"counts the log-spaced ratios of a LOW:HIGH "
                                                  f"range; --ratio-range {text} gives its own "
                                                  f"(every {numbers[2]:g}). Give one or the "
                                                  f"other.", value=count)
    try:
        ratios = range_values(*numbers, 10_000, "gear ratios")
    except ValueError as err:
        raise InputError.parameter("ratio_range", str(err), value=text) from None
    return bounds, ratios


def target(servo, samples: int):
    """The profile's motion at ``samples`` + 1 instants of one cycle (SI)."""
    import numpy as np

    from dyade.linkage.servo import Target
    from dyade.motion.profile import evaluate

    profile = servo.profile
    period = profile.period if profile.master == "time" else servo.cycle_time
    t = np.linspace(0.0, period, samples + 1)
    rate = profile.period / period  # master per second
    motion = evaluate(profile, profile.start + t * rate)
    jerk = motion.j.copy()
    # the cycle's last instant is the next cycle's first for s, v, a (continuous), but
    # its jerk is the last segment's (a law may start with a jerk of its own)
    jerk[-1] = evaluate(profile, np.array([profile.start + profile.period * (1.0 - 1e-12)])).j[0]
    return Target(t, np.asarray(motion.s, dtype=float), motion.v * rate,
                  motion.a * rate ** 2, jerk * rate ** 3)


def checked_profile(profile, label: str) -> tuple[str, ...]:
    """The profile checked continuous (``dyade.motion.profile.check``), its errors
    naming the file: the notes of the jumps its laws allow."""
    import math

    from dyade.errors import InputError
    from dyade.files.profile import output_factor
    from dyade.motion.profile import check

    master = ("s", 1.0) if profile.master == "time" else (
        "°" if profile.master_unit == "deg" else "rad",
        math.pi / 180.0 if profile.master_unit == "deg" else 1.0)
    name = os.path.basename(label)
    try:
        return check(profile, units=(*master, profile.unit, output_factor(profile.unit)))
    except InputError as err:
        raise InputError(f"{name}: {err}", source=label, key=err.key, value=err.value,
                         unit=err.unit, reason=err.reason) from None


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import numpy as np

    from dyade.errors import InputError

    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        outcome = size(source, options, budget)  # a profile beyond any machine overflows:
    if not all(np.isfinite(np.asarray(v, dtype=float)).all()  # its forces withheld, or here
               for v in outcome.columns.values()):
        raise InputError("the servo's torques or speeds over the cycle exceed the range of "
                         "numbers: check the profile's lifts and durations ([profile]) for "
                         "values far beyond a machine's.", key="profile")
    return outcome


def size(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``run`` without its range check: the Outcome as computed."""
    import math

    import numpy as np

    from dyade.errors import DyadeError, InputError
    from dyade.files.catalogue import read_catalogue
    from dyade.files.mechanism.servo import MAX_SAMPLES
    from dyade.linkage import servo as linkage
    from dyade.machine import servo as engine
    from dyade.model.servo import Gear
    from dyade.units import RAD_PER_S_TO_RPM

    loaded = load(source, options)
    mechanism = loaded.mechanism
    servo = mechanism.servo
    label = loaded.label or "mechanism"
    if servo is None:
        raise InputError(f"{os.path.basename(label)}: has no [servo] table: `dyade servo` "
                         f"sizes the servo that drives the crank by a motion profile (dyade "
                         f"init servo writes an example).", source=label, key="servo")
    samples = options.get("samples") or servo.samples
    if samples % 2 or samples < 36:
        raise InputError.parameter("samples", f"must be an even number of at least 36, got "
                                              f"{samples}.", value=samples)
    gear = servo.gear
    if options.get("ratio") is not None:
        gear = Gear(options["ratio"], gear.efficiency, gear.inertia)
    bounds, stepped = ((ratio_range(options["ratio_range"], options.get("ratio_count"))
                        if options.get("ratio_range") else (servo.ratio_range, None)))
    rotor = options.get("rotor_inertia") or servo.rotor_inertia
    limit = options.get("max_inertia_ratio") or servo.max_inertia_ratio
    for value, flag, key, unit, (low, high) in (
            (samples, "--samples", "servo.samples", "", (36, MAX_SAMPLES)),
            (gear.ratio, "--ratio", "servo.ratio", " [-]", RATIO_RANGE),
            *((end, "--ratio-range", "servo.ratio_range", " [-]", RATIO_RANGE)
              for end in bounds or ()),
            (rotor or 1.0, "--rotor-inertia", "servo.rotor_inertia", " [kg·m²]", INERTIA_RANGE),
            (gear.inertia or 1.0, "", "servo.gear_inertia",
             " [kg·m²]", INERTIA_RANGE)):
        if not low <= value <= high:  # beyond any machine, and beyond floating point's squares
            name = f"{flag} ({key})" if flag else f"`{key}`"
            raise InputError(f"{os.path.basename(label)}: {name} must lie in {low:g}…{high:g}"
                             f"{unit}, got {value:g}.", source=label, key=key, value=value)
    catalogue = servo.catalogue
    if options.get("catalogue"):
        catalogue = read_catalogue(options["catalogue"])
    budget.time(samples * 2e-5 * max(1, len(mechanism.dyads)), f"the cycle at {samples} instants")

    notes = [f"note: {text}" for text in checked_profile(servo.profile, label)]
    try:
        motion = linkage.crank_motion(mechanism, servo.output, servo.start,
                                      target(servo, samples))
    except DyadeError as err:  # beyond a dead centre: said with the file's name
        if type(err) is not DyadeError:
            raise
        raise DyadeError(f"{os.path.basename(label)}: {err}") from None
    motion = linkage.inverse_dynamics(mechanism, motion)
    cycle = motion.cycle()
    line = None
    if mechanism.drive_line is not None:  # the crank behind an elastic shaft
        refine = linkage.line_refinement(mechanism.drive_line, motion.inertia, cycle.period,
                                         samples)
        budget.time(refine * samples * 4e-4, f"the elastic drive line at {refine * samples:,} "
                                              f"steps per cycle")
        fine = linkage.crank_motion(mechanism, servo.output, servo.start,
                                    target(servo, 2 * refine * samples))
        line = linkage.elastic_line(mechanism, fine, np.interp(fine.time, motion.time,
                                                               motion.friction))
        torque = line.torque[::refine]
        cycle = engine.Cycle(cycle.time, cycle.speed, cycle.acceleration, torque, cycle.inertia)
        shaft = mechanism.drive_line
        lag = np.degrees(np.max(np.abs(line.angle[::refine] - motion.angle)))
        notes.append(
            f"note: the crank is driven through the [drive_line] shaft ({shaft.stiffness:g} "
            f"N·m/rad, {shaft.damping:g} N·m·s/rad) whose gear end follows the profile: the "
            f"crank lags it by up to {lag:.3g}°, and the motor is sized by the shaft's torque "
            f"M_line (the periodic state; friction as at the rigid motion).")
    if bounds is not None:
        count = options.get("ratio_count") or 25
        ratios = (np.asarray(stepped) if stepped is not None
                  else np.geomspace(bounds[0], bounds[1], count))
    else:
        ratios = np.array([gear.ratio])
    optimum = None
    if bounds is not None and rotor:
        optimum = engine.optimal_ratio(cycle, gear, rotor, bounds)
        ratios = np.sort(np.append(ratios, optimum))
    elif bounds is not None:
        notes.append("note: no rotor inertia (`servo.rotor_inertia`): the RMS torque falls "
                     "with the ratio without a minimum, and no optimum is marked.")
    sizing = engine.sizing(cycle, engine.motor_load(cycle, gear, rotor or 0.0, ratios), gear)
    checks, chosen = [], None
    ratio = optimum if optimum is not None else gear.ratio if bounds is None else None
    if catalogue is not None:
        checks = engine.catalogue_checks(cycle, gear, catalogue.motors, ratios, limit, bounds)
        chosen = engine.smallest_passing(checks)
        if chosen is None:
            raise DyadeError(no_motor(checks, catalogue.source, ratios, bounds))
        rotor = chosen.motor.rotor_inertia
        ratio = float(chosen.sizing.ratio[chosen.best])
    if ratio is None:  # a range without a rotor: the gear's own ratio for the columns
        ratio = gear.ratio
    load_at = engine.motor_load(cycle, gear, rotor or 0.0, ratio)
    figures = engine.sizing(cycle, load_at, gear)
    run_result = ServoRun(mechanism, motion, cycle, ratio, sizing, optimum, checks, chosen,
                          rotor or 0.0, load_at)

    outcome = Outcome("servo", figures=("servo",),
                      meta={"name": mechanism.name, "source": loaded.label or None,
                            "output": servo.output},
                      result=run_result)
    target_motion = motion.target
    columns = {"t": motion.time, "angle_deg": np.degrees(motion.angle), "omega_2": motion.speed,
               "alpha_2": motion.acceleration,
               "s": target_motion.position - target_motion.position[0],
               "v": target_motion.velocity, "a": target_motion.acceleration,
               "j": target_motion.jerk, "M_crank": motion.torque, "J_red": motion.inertia,
               "M_load": motion.load, "M_friction": motion.friction,
               "n_motor_rpm": load_at.speed[0] * RAD_PER_S_TO_RPM, "M_motor": load_at.torque[0],
               "P_motor": load_at.torque[0] * load_at.speed[0],
               "P_gear_loss": load_at.gear_loss[0]}
    if line is not None:
        columns["M_line"] = cycle.torque
        columns["lag_deg"] = np.degrees(line.angle[::refine] - motion.angle)
    unit = "m" if servo.profile.output == "length" else "rad"
    outcome.columns = columns
    outcome.units = {name: COLUMNS[name][0] for name in columns}
    for name, suffix in (("s", ""), ("v", "/s"), ("a", "/s²"), ("j", "/s³")):
        outcome.units[name] = unit + suffix
    outcome.descriptions = {name: COLUMNS[name][1] for name in columns}
    add = outcome.add
    add("cycle_time", float(cycle.period), "s", description="cycle time T")
    add("output", servo.output, "-", description="what the profile moves")
    add("ratio", ratio, "-", description="gear ratio i of the columns"
        + (" (the chosen motor's)" if chosen is not None else
           " (the RMS optimum)" if optimum is not None else ""))
    add("efficiency", gear.efficiency, "-", description="gear efficiency η")
    add("rotor_inertia", rotor, "kg·m²", description="rotor inertia J_M"
        + (f" of {chosen.motor.name}" if chosen is not None else ""))
    peak_t = float(figures.peak_at[0])
    add("crank_torque_peak", float(np.max(np.abs(motion.torque))), "N·m",
        where={"time_s": float(motion.time[np.argmax(np.abs(motion.torque))])},
        description="peak torque the crank shaft needs")
    add("crank_speed_max_rpm", float(np.max(np.abs(motion.speed))) * RAD_PER_S_TO_RPM, "rpm",
        description="top crank speed")
    add("motor_torque_peak", float(figures.peak_torque[0]), "N·m", where={"time_s": peak_t},
        description="peak motor torque")
    add("motor_torque_rms", float(figures.rms_torque[0]), "N·m",
        description="RMS motor torque √(1/T·∫M²dt) (heating)")
    add("motor_speed_max_rpm", float(figures.top_speed[0]) * RAD_PER_S_TO_RPM, "rpm",
        description="top motor speed")
    add("inertia_ratio", None if not rotor else float(figures.inertia_ratio[0]), "-",
        limit=limit, description="inertia ratio λ = (max J/i² + J_G)/J_M")
    add("regenerated", float(figures.regenerated[0]), "J",
        description="energy fed back per cycle ∫max(−M·ω, 0)dt")
    add("gear_loss", float(engine.trapezoid(load_at.gear_loss[0], cycle.time)), "J",
        description="energy the gear loses per cycle")
    if bounds is not None:
        add("ratio_low", bounds[0], "-", description="lowest gear ratio of the range")
        add("ratio_high", bounds[1], "-", description="highest gear ratio of the range")
        add("ratio_optimum", optimum, "-", description="RMS-optimal gear ratio in the range "
                                                      "(golden section)")
        if optimum is not None and (math.isclose(optimum, bounds[0], rel_tol=1e-6)
                                    or math.isclose(optimum, bounds[1], rel_tol=1e-6)):
            notes.append(f"note: the RMS-optimal gear ratio lies at an end of the range "
                         f"({optimum:.6g}): widen the range to find the true optimum.")
    if chosen is not None:
        row = chosen.best
        add("motor", chosen.motor.name, "-", description="smallest motor of the catalogue that "
                                                        "passes")
        add("motors_passing", sum(check.best is not None for check in checks), "-",
            description=f"motors of {len(checks)} that pass at some ratio")
        add("margin_thermal", float(chosen.thermal[row]), "-",
            description="thermal margin 1 − RMS/M_N")
        add("margin_peak", float(chosen.peak[row]), "-",
            description="peak margin 1 − |M|/envelope(ω), the least over the cycle")
        add("margin_speed", float(chosen.speed[row]), "-",
            description="speed margin 1 − max|ω|/n_max")
        add("margin_inertia", float(chosen.inertia[row]), "-",
            description="inertia margin 1 − λ/λ_max")
    if line is not None:
        add("line_frequency", math.sqrt(mechanism.drive_line.stiffness / float(np.mean(
            motion.inertia))), "rad/s", description="the line's natural frequency √(k/J̄)")
        add("crank_lag_max_deg", float(np.max(np.abs(columns["lag_deg"]))), "°",
            description="largest lag of the crank behind its profile (elastic line)")
        add("line_torque_peak", float(np.max(np.abs(cycle.torque))), "N·m",
            where={"time_s": float(motion.time[np.argmax(np.abs(cycle.torque))])},
            description="peak torque of the drive line's shaft")
    if motion.branch is not None:
        add("dead_centre_first_deg", math.degrees(motion.branch[0]), "°",
            description="the output's dead centre before the start (crank angle)")
        add("dead_centre_last_deg", math.degrees(motion.branch[1]), "°",
            description="the output's dead centre after the start (crank angle)")
    if np.any(motion.friction != 0.0) and np.max(np.abs(motion.friction)) > 1e-9 * max(
            1.0, float(np.max(np.abs(motion.torque)))):
        notes.append("note: friction's share of the crank torque is in M_friction (Coulomb "
                     "friction at the joints, from the sweep's forces).")
    outcome.notes = notes
    return outcome


def no_motor(checks, source, ratios, bounds) -> str:
    """The message when no motor of the catalogue passes at any ratio: the closest
    motor (the largest least margin) and why it fails."""
    import numpy as np

    from dyade.units import RAD_PER_S_TO_RPM

    def least(check):
        margins = np.minimum(np.minimum(check.thermal, check.peak),
                             np.minimum(check.speed, check.inertia))
        row = int(np.argmax(margins))
        return float(margins[row]), row

    best = max(checks, key=lambda c: least(c)[0])
    row = least(best)[1]
    ratio = float(best.sizing.ratio[row])
    where = (f"at any gear ratio {bounds[0]:g}–{bounds[1]:g}" if bounds is not None
             else f"at the gear ratio {ratio:g}")
    name = os.path.basename(source) if source else "the catalogue"
    figures = best.sizing
    return (f"no motor of {name} passes {where}: the closest, {best.motor.name} (at i = "
            f"{ratio:.4g}), fails {', '.join(best.failed(row))} — RMS "
            f"{figures.rms_torque[row]:.4g} N·m of {best.motor.rated_torque:g}, peak "
            f"{figures.peak_torque[row]:.4g} N·m of {best.motor.peak_torque:g}, top speed "
            f"{figures.top_speed[row] * RAD_PER_S_TO_RPM:.5g} rpm of "
            f"{best.motor.top_speed * RAD_PER_S_TO_RPM:.5g}, inertia ratio "
            f"{figures.inertia_ratio[row]:.3g}. Add a larger motor, widen the ratio range or "
            f"slow the profile.")


STUDY_OUTPUTS = {"motor_torque_peak": "N·m", "motor_torque_rms": "N·m",
                 "motor_speed_max_rpm": "rpm", "inertia_ratio": "-", "regenerated": "J",
                 "crank_torque_peak": "N·m", "ratio": "-"}
"""the servo's figures a design study gives with ``[outputs] extra = ["servo"]``, and
their units: the motor's at the ratio of the columns (the servo's own, the RMS optimum of
its range, or the chosen catalogue motor's)"""


def study_outputs(mechanism) -> dict[str, float]:
    """The ``STUDY_OUTPUTS`` of a mechanism with a ``[servo]`` (its file's settings),
    for one variant of a design study."""
    from dyade.errors import InputError

    if mechanism.servo is None:
        raise InputError("the study's extra output \"servo\" needs a [servo] table in the "
                         "mechanism file.", key="outputs.extra")
    outcome = ENTRIES["servo"](mechanism)
    return {name: outcome.value(name) for name in STUDY_OUTPUTS}


ENTRIES = {"servo": Analysis("servo", "Servo-driven crank: motor torque over the cycle and "
                             "its sizing", run, OPTIONS, figures=("servo",),
                             command="dyade servo")}
"""``dyade servo``: the registry's ``servo`` entry (``dyade.analyses.servo``)."""
