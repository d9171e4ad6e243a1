"""``dyade driveline``: a linkage driven through an elastic shaft or coupling
(``[drive_line]``), one registry entry per question (``dyade.linkage.drive_line``).

- ``driveline-frequency``: ω̄, its range over the cycle, Ω/ω̄ and the VDI 2149 verdict;
- ``driveline-steady``: the periodic steady state next to the rigid drive's;
- ``driveline-resonance``, ``driveline-stability``: peak shaft torque, twist, speed
  fluctuation and the largest Floquet multiplier over the speeds of an ideal motor (one
  integration gives both; they differ in the figure they draw);
- ``driveline-map``: the largest Floquet multiplier over speed × stiffness or damping;
- ``driveline-run-up``: from rest under the ``[drive]`` motor, in time.

Every entry reads the mechanism once (``inputs.load``), builds its crank shaft once
(``linkage.drive.crank_shaft``: the line, the tables, ω̄) and passes it on, and puts the
natural frequency's figures and the VDI 2149 note in its Outcome.

Options and their API names: ``--speed-range START:STOP:STEP`` [rpm] is
``speed_range_rpm`` (the same text, or a sequence of speeds [rpm] at the API),
``--speed`` ``speed_rpm``, ``--map stiffness=START:STOP:STEP`` ``map``, ``--set``
``set``.
"""

from __future__ import annotations

from typing import Any

from dyade.analyses.base import MAX_MEMORY, Analysis, Budget, Option, Outcome, withheld
from dyade.analyses.inputs import SET, load

SPEED_RANGE = Option("speed-range", str, "rpm", metavar="START:STOP:STEP",
                     help="Crank speeds of an ideal motor, STOP included (a [drive] motor is "
                          "replaced by one; at the API also a sequence of speeds)")
ETA_RANGE = Option("eta-range", str, metavar="START:STOP:STEP",
                   help="Crank speeds as η = Ω/ω̄ instead of --speed-range (ω̄: the line's "
                        "lowest natural frequency with the mean inertia), e.g. 0.2:1.6:0.01")
SPEED_RPM = Option("speed", float, "rpm", positive=True, metavar="RPM", old=("--speed-rpm",),
                   help="The ideal motor's speed for the steady state (default: the crank's; "
                        "not with a [drive] motor)")
MAP = Option("map", str, metavar="stiffness|damping=START:STOP:STEP",
             help="The shaft's parameter to map against speed and its values [N·m/rad or "
                  "N·m·s/rad]")
PERIOD_TWO = Option("period-two", bool,
                    help="Where a speed's only periodic motions are unstable by period "
                         "doubling (a multiplier below −1), shoot the period-2 motion over two "
                         "revolutions and list it as a row with period 2 (about 10–20 s per "
                         "such speed; counted in the time estimate and --max-time)")
OPTIONS = (SET, SPEED_RANGE, ETA_RANGE, SPEED_RPM, MAP, PERIOD_TWO)
"""every option of the drive line's entries (``dyade driveline`` declares them all)"""

MOST_SPEEDS = 2000  # the most speeds (or map values) one run takes
VDI_2149_WORDS = ("Ω/ω̄ = {ratio:.3g} exceeds {limit:g} (VDI 2149 Part 1): the rigid drive's "
                  "model does not hold for this line.")
"""the VDI 2149 note, worded here only"""
NO_STATE = ("the crank would stop or turn back within the cycle, the shooting did not "
            "converge, or the solution was not periodic to the tolerance (or its energy "
            "balance did not close)")
"""why a speed has no periodic state"""

PERIOD_TWO_SECONDS = 15.0  # [s] the period-2 motion of one speed on 720 steps per
# revolution (measured on a 2-core machine under load: 10 s for one speed, 49 s for three)
# the time estimate of a run (measured on a 2-core machine, issue 36): the shooting's
# RK4 step costs about SECONDS_PER_STEP, plus SECONDS_PER_LANE_STEP for each lane (a
# speed or map cell, times 2d + 1 for the monodromy matrix); a run takes ITERATIONS
# Newton iterations and a last integration that keeps the orbit (two iterations' worth)
SECONDS_PER_STEP = 1.5e-4  # [s]
SECONDS_PER_LANE_STEP = 1.5e-7  # [s]
ITERATIONS = 6  # [-] Newton iterations of a typical run (at most NEWTON_MAX_ITER)
FRICTION_FACTOR = 8.0  # [-] a steady state with joint friction: passes and kinetostatics
SECONDS_PER_TIME_STEP = 6e-4  # [s] one RK4 step in time of the run-up
RUN_UP_REVOLUTIONS = 10  # [-] revolutions a typical run-up takes to settle

FREQUENCY = {
    "omega_bar": ("rad/s", "ω̄: the lowest natural frequency with the mean reduced "
                           "inertia J̄"),
    "resonance_speed_rpm": ("rpm", "ω̄ as a crank speed (Ω = ω̄)"),
    "omega_min": ("rad/s", "the lowest natural frequency's smallest value over the cycle "
                           "(J(φ) largest)"),
    "omega_max": ("rad/s", "… and its largest (J(φ) smallest)"),
    "inertia_mean": ("kg·m²", "J̄: the crank shaft's mean reduced moment of inertia"),
    "speed_rpm": ("rpm", "the crank's operating speed Ω (--speed, else the file's)"),
    "speed_ratio": ("-", "η = Ω/ω̄"),
    "vdi_2149": ("1/0", "the rigid drive's model holds (VDI 2149 Part 1: Ω/ω̄ ≤ 0.1)"),
}
"""the natural frequency's figures, in every entry's summary: name -> (unit,
description)"""

COLUMNS = {
    "angle_deg": ("°", "crank angle φ21"),
    "natural_frequency": ("rad/s", "the lowest natural frequency with J frozen at J(φ)"),
    "shaft_torque": ("N·m", "torque of the elastic element into the crank shaft"),
    "rigid_torque": ("N·m", "drive torque of the rigid drive at the same mean speed"),
    "speed_rpm": ("rpm", "crank speed"),
    "rigid_speed_rpm": ("rpm", "crank speed of the rigid drive"),
    "acceleration": ("rad/s²", "crank acceleration in the running direction"),
    "rigid_acceleration": ("rad/s²", "crank acceleration of the rigid drive"),
    "twist_deg": ("°", "twist of the line, motor side against crank"),
    "eta": ("-", "η = Ω/ω̄"),
    "peak_torque": ("N·m", "largest |shaft torque| over the cycle (empty: no periodic "
                           "state)"),
    "rigid_peak_torque": ("N·m", "largest |drive torque| of the rigid drive"),
    "twist_amplitude_deg": ("°", "(max − min)/2 of the twist"),
    "fluctuation": ("-", "(max − min)/mean of the crank speed"),
    "floquet": ("-", "largest |Floquet multiplier| (empty: no periodic state)"),
    "unstable": ("1/0", "a Floquet multiplier outside the unit circle (|μ| > 1); empty: "
                        "not converged, no verdict"),
    "period": ("-", "revolutions of the periodic motion: 1, or 2 where the period-1 motion "
                    "flips (a multiplier below −1; --period-two)"),
    "solution": ("-", "the periodic solution's number at its speed (several where a "
                      "resonance folds over), by twist amplitude"),
    "twist_max_deg": ("°", "largest |twist| over the period"),
    "instability": ("-", "how it is unstable: fold (μ = +1), period doubling (μ = −1), "
                         "Neimark–Sacker (a complex pair); empty: stable or no verdict"),
    "converged": ("1/0", "periodic to the tolerance, unchanged with twice the steps and its "
                         "energy balance closed"),
    "steps": ("-", "RK4 steps per revolution of the solution"),
    "accuracy": ("-", "change of the solution (scaled) and its multipliers with twice the "
                      "steps"),
    "balance": ("-", "energy balance over the period: |motor − loads − friction − damping| "
                     "of the largest work"),
    "slowest": ("-", "the crank's slowest speed over the cycle over Ω (negative: it turns "
                     "back for a moment)"),
    "in_time": ("1/0", "solved in time, not in crank angle (the crank nearly stops or turns "
                       "back; its angle is then no variable): steps per motor revolution"),
    "stiffness": ("N·m/rad", "the shaft's torsional stiffness"),
    "damping": ("N·m·s/rad", "the shaft's damping"),
    "time": ("s", "time from rest"),
    "crank_speed_rpm": ("rpm", "crank speed"),
    "motor_speed_rpm": ("rpm", "motor speed reduced to the crank shaft"),
}
"""column -> (unit, description) of every drive-line entry"""


# -- what every entry shares -----------------------------------------------------------
def rpm(speed):
    """[rad/s] -> [rpm] (``dyade.units.RAD_PER_S_TO_RPM``)."""
    from dyade.units import RAD_PER_S_TO_RPM

    return speed * RAD_PER_S_TO_RPM


def start(source: Any, options: dict[str, Any], name: str, figures: tuple[str, ...] = ()):
    """The mechanism of ``source`` with ``set``, its crank shaft (built once), and the
    Outcome with the natural frequency's figures and the VDI 2149 note (at ``--speed``
    where the entry has it and it is given, else the file's speed)."""
    from dyade.linkage.drive import crank_shaft

    loaded = load(source, options)
    mechanism = loaded.mechanism
    shaft = crank_shaft(mechanism)
    outcome = Outcome(name, figures=figures,
                      meta={"mechanism": mechanism.name,
                            "source": None if loaded.text is None else loaded.label})
    speed_rpm = options.get(SPEED_RPM.api)
    frequency_figures(outcome, shaft.frequency, None if speed_rpm is None else abs(speed_rpm))
    return shaft, outcome


def frequency_figures(outcome: Outcome, freq, speed_rpm: float | None = None) -> None:
    """ω̄ and its range, J̄, Ω, η and the VDI 2149 verdict in the summary; the note when
    the rigid model does not hold. ``speed_rpm``: the run's speed (``--speed``), in
    place of the file's."""
    import dataclasses

    import numpy as np

    from dyade.linkage.drive import VDI_2149_RATIO
    from dyade.units import RPM

    if speed_rpm is not None:
        freq = dataclasses.replace(freq, speed=speed_rpm * RPM)

    angle = np.degrees(freq.crank_angle)
    values = {"omega_bar": (freq.omega_bar, None),
              "resonance_speed_rpm": (rpm(freq.omega_bar), None),
              "omega_min": (freq.omega_min, {"angle_deg": angle[np.argmin(freq.frequency)]}),
              "omega_max": (freq.omega_max, {"angle_deg": angle[np.argmax(freq.frequency)]}),
              "inertia_mean": (freq.inertia_mean, None),
              "speed_rpm": (rpm(freq.speed), None),
              "speed_ratio": (freq.ratio, None),
              "vdi_2149": (bool(freq.vdi_2149), None)}
    for name, (value, where) in values.items():
        unit, description = FREQUENCY[name]
        outcome.add(name, value, unit, where, description,
                    VDI_2149_RATIO if name == "speed_ratio" else None)
    if not freq.vdi_2149:
        outcome.notes.append(vdi_note(freq.ratio))


def vdi_note(ratio: float) -> str:
    """The note of a line too soft for the rigid model (VDI 2149 Part 1)."""
    from dyade.linkage.drive import VDI_2149_RATIO

    return VDI_2149_WORDS.format(ratio=ratio, limit=VDI_2149_RATIO)


def set_columns(outcome: Outcome, columns: dict[str, Any]) -> None:
    """The Outcome's columns (arrays; floats with -0.0 as 0.0), units and descriptions."""
    import numpy as np

    arrays = {name: np.asarray(values) for name, values in columns.items()}
    outcome.columns = {name: values + 0.0 if values.dtype.kind == "f" else values
                       for name, values in arrays.items()}
    outcome.units = {name: COLUMNS[name][0] for name in columns}
    outcome.descriptions = {name: COLUMNS[name][1] for name in columns}


def friction_note(shaft, what: str) -> list[str]:
    return ([f"joint friction is left out of the {what} (the steady state takes it, by "
             f"passes at the vibrating crank's motion)."] if shaft.friction else [])


def ticker(budget: Budget, expected: int):
    """The engine's ``progress(...)`` (a Newton iteration, a revolution done) as
    ``budget.progress(done, total)``, counting the calls: the total is ``expected``
    until the work goes beyond it."""
    count = 0

    def tick(*_: Any) -> None:
        nonlocal count
        count += 1
        budget.progress(count, max(expected, count + 1))

    return tick


def shooting_seconds(steps: int, lanes: int, dimension: int, iterations: int = ITERATIONS
                     ) -> float:
    """The time estimate of the shooting of ``lanes`` lanes on ``steps`` steps [s]."""
    return (iterations + 2) * steps * (SECONDS_PER_STEP
                                       + SECONDS_PER_LANE_STEP * lanes * (2 * dimension + 1))


def orbit_values(line) -> int:
    """float64 values per lane and step of a kept orbit (``engine.Orbit``: the state,
    the quadratures, the element torques, the acceleration), twice for the arrays made
    from them."""
    from dyade.machine import drive_line as engine

    return 2 * (line.dimension + engine.QUADRATURES + line.elements + 1)


def steps_of(shaft, line, speed: float, stiffness_max=None) -> int:
    """RK4 steps per revolution of a run at the lowest ``speed`` [rad/s] (as the engine
    chooses them; a line too stiff to integrate is refused here, before any step)."""
    import numpy as np

    from dyade.machine import drive_line as engine

    return shaft.mechanism.drive_line.steps or engine.steps_for(
        line, float(np.min(shaft.tables.inertia)), speed, stiffness_max)


def speeds_of(value: Any, name: str = SPEED_RANGE.api, quantity: str = "speed_rpm",
              unit: str = "rpm") -> list[float]:
    """The values of a START:STOP:STEP text (STOP included; ``dyade.files.schema``), or a
    sequence of them, each end within the plausible range of ``quantity``
    (``dyade.limits``); an ``InputError`` on ``name`` saying what is wrong."""
    from dyade.errors import InputError
    from dyade.files.schema import range_parts, range_values
    from dyade.limits import implausible, plausible_range

    if value is None:
        raise InputError.parameter(name, f"must be given: START:STOP:STEP [{unit}].")
    try:
        if isinstance(value, str):
            first, last, step = range_parts(value, f" [{unit}]")
            if not (step > 0 and last >= first):
                raise ValueError(f"needs START <= STOP and STEP > 0, got {value!r}.")
            values = range_values(first, last, step, MOST_SPEEDS,
                                  "speeds" if unit == "rpm" else "values")
        else:
            values = [float(v) for v in (value if hasattr(value, "__len__") else [value])]
            if not values:
                raise ValueError("must list at least one value.")
            if len(values) > MOST_SPEEDS:
                raise ValueError(f"asks for {len(values)} values; at most {MOST_SPEEDS}.")
            first, last = min(values), max(values)
        if quantity == "eta" and not 0.0 < first <= last <= 100.0:
            raise ValueError(f"η = Ω/ω̄ must lie in (0, 100], got {value!r}.")
        if quantity != "eta" and any(implausible(quantity, abs(end)) for end in (first, last)
                                     if end or quantity != "damping"):
            raise ValueError(f"values must lie in {plausible_range(quantity)} (what a machine "
                             f"has), got {value!r}.")
    except (TypeError, ValueError) as err:
        raise InputError.parameter(name, str(err), value=value, unit=unit) from None
    return values


def naming(err):
    """An engine's error on its parameters named by the entry's options."""
    return err.naming({"speeds_rpm": SPEED_RANGE.api, "stiffness": MAP.api,
                       "damping": MAP.api})


# -- the entries --------------------------------------------------------------------------
def frequency(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """ω̄, its range over the cycle with J frozen at J(φ), Ω/ω̄, VDI 2149."""
    import numpy as np

    shaft, outcome = start(source, options, "driveline-frequency")
    freq = shaft.frequency
    set_columns(outcome, {"angle_deg": np.degrees(freq.crank_angle),
                          "natural_frequency": freq.frequency})
    outcome.result = freq
    return outcome


def steady(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """The periodic steady state at the operating speed next to the rigid drive's."""
    import numpy as np

    from dyade.errors import InputError
    from dyade.limits import implausible, plausible_range
    from dyade.linkage import drive_line as api
    from dyade.units import RPM

    speed_rpm = options.get(SPEED_RPM.api)
    if speed_rpm is not None and implausible("speed_rpm", speed_rpm):
        raise InputError.parameter(SPEED_RPM.api, f"must lie in {plausible_range('speed_rpm')} "
                                                  f"(what a machine has), got {speed_rpm:g}.",
                                   value=speed_rpm, unit="rpm")
    shaft, outcome = start(source, options, "driveline-steady", ("driveline",))
    line = shaft.line
    if speed_rpm is not None and not line.ideal:
        raise InputError.parameter(SPEED_RPM.api, "is for an ideal motor; a [drive] motor "
                                                  "finds its own speed.")
    speed = abs(shaft.mechanism.crank.speed) if speed_rpm is None else speed_rpm * RPM
    steps = steps_of(shaft, line, speed)
    seconds = 1.5 * shooting_seconds(steps, 1, line.dimension)
    budget.time(seconds * (FRICTION_FACTOR if shaft.friction else 1.0),
                f"the drive line's steady state ({steps:,} steps per revolution)")
    state = api.steady_state(shaft.mechanism, speed_rpm=speed_rpm, shaft=shaft,
                             progress=ticker(budget, ITERATIONS))
    set_columns(outcome, {"angle_deg": np.degrees(state.crank_angle),
                          "shaft_torque": state.shaft_torque,
                          "rigid_torque": state.rigid_torque,
                          "speed_rpm": rpm(state.crank_speed),
                          "rigid_speed_rpm": rpm(state.rigid_speed),
                          "acceleration": state.crank_acceleration,
                          "rigid_acceleration": state.rigid_acceleration,
                          "twist_deg": np.degrees(state.twist)})
    angle = outcome.columns["angle_deg"]
    f = state.figures
    add = outcome.add
    add("speed_mean_rpm", rpm(f["speed_mean"]), "rpm", description="mean crank speed Ω̄")
    add("eta", f["eta"], "-", description="η = Ω̄/ω̄ at the mean speed")
    add("period", f["period"], "s", description="period of one revolution")
    add("fluctuation", f["fluctuation"], "-",
        description="speed fluctuation (max − min)/mean of the crank")
    add("rigid_fluctuation", f["rigid_fluctuation"], "-",
        description="speed fluctuation of the rigid drive")
    k = int(np.argmax(np.abs(state.shaft_torque)))
    add("peak_torque", float(np.abs(state.shaft_torque[k])), "N·m",
        {"angle_deg": angle[k]}, "largest |shaft torque| over the cycle")
    k = int(np.argmax(np.abs(state.rigid_torque)))
    add("rigid_peak_torque", float(np.abs(state.rigid_torque[k])), "N·m",
        {"angle_deg": angle[k]}, "largest |drive torque| of the rigid drive")
    add("twist_amplitude_deg", float(np.degrees(np.ptp(state.twist) / 2.0)), "°",
        description="twist amplitude (max − min)/2")
    for name, words in (("work_motor", "work of the motor over the period"),
                        ("work_load", "work of the loads over the period"),
                        ("work_friction", "work of friction over the period"),
                        ("work_damping", "work of damping over the period")):
        add(name, f[name], "J", description=words)
    add("stability", f["stability"], "-", description="largest |Floquet multiplier|")
    add("floquet", [abs(complex(m)) for m in state.multipliers], "-",
        description="|Floquet multipliers|")
    add("stable", state.stable, "1/0", description="the periodic motion is stable (|μ| ≤ 1)")
    add("iterations", f["iterations"], "-", description="Newton iterations of the shooting")
    add("steps_per_revolution", f["steps_per_revolution"], "-",
        description="RK4 steps per revolution")
    if "accuracy" in f:
        add("accuracy", f["accuracy"], "-",
            description="change of the shaft torque with half the steps, of its largest")
    if "friction_passes" in f:
        add("friction_passes", f["friction_passes"], "-",
            description="passes of the joint friction torque")
        add("friction_change", f["friction_change"], "N·m",
            description="change of the friction torque in the last pass")
    if "reached_from_rpm" in f:
        add("reached_from_rpm", f["reached_from_rpm"], "rpm",
            description="the shooting missed the state: followed up in speed from here")
        outcome.notes.append(f"The shooting from the line's linear response missed this "
                             f"steady state (the crank nearly stops): it was followed up in "
                             f"speed from {f['reached_from_rpm']:.5g} rpm and shot again on "
                             f"{f['steps_per_revolution']} steps per revolution.")
    outcome.result = state
    return outcome


def speeds_asked(options: dict[str, Any], shaft) -> list[float]:
    """The speeds [rpm] of ``speed_range_rpm`` or of ``eta_range`` (η = Ω/ω̄, one of the
    two)."""
    from dyade.errors import InputError

    given = options.get(SPEED_RANGE.api), options.get(ETA_RANGE.api)
    if given[0] is not None and given[1] is not None:
        raise InputError.parameter(ETA_RANGE.api, f"is given with {SPEED_RANGE.flag}: give "
                                                  f"one of the two (η = Ω/ω̄ or rpm).")
    if given[1] is None:
        return speeds_of(given[0])
    etas = speeds_of(given[1], ETA_RANGE.api, "eta", "-")
    return [rpm(eta * shaft.frequency.omega_bar) for eta in etas]


def curve(name: str):
    """The resonance curve (``driveline-resonance``) or the stability chart
    (``driveline-stability``) over ``speed_range_rpm`` or ``eta_range``: one run gives
    both."""

    def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
        import numpy as np

        from dyade.errors import InputError
        from dyade.limits import check_memory
        from dyade.linkage import drive_line as api
        from dyade.units import RPM

        if options.get(ETA_RANGE.api) is None:
            speeds_of(options.get(SPEED_RANGE.api))  # a bad range refused before the file
        shaft, outcome = start(source, options, name, ("driveline",))
        what = name.removeprefix("driveline-")
        try:
            speeds = speeds_asked(options, shaft)
            line = shaft.ideal_line
            low = min(abs(s) for s in speeds) * RPM
            steps = steps_of(shaft, line, low) if low > 0 else 0
            check_memory((2 * steps + 1) * len(speeds) * orbit_values(line) * 8.0,
                         f"the orbits of {len(speeds):,} speeds over {2 * steps:,} steps",
                         budget.max_memory, "Ask for fewer speeds", MAX_MEMORY.api)
            budget.time(scan_seconds(steps, len(speeds), line.dimension),
                        f"the {what} at {len(speeds):,} speeds ({steps:,} steps per "
                        f"revolution and more, by accuracy)")
            found = api.resonance_curve(shaft.mechanism, speeds, shaft=shaft,
                                        progress=ticker(budget, SCAN_INTEGRATIONS))
        except InputError as err:
            raise naming(err) from None
        withheld(Outcome(name, notes=[NO_STATE]), found.converged,
                 "no speed of the range has a periodic state of the drive line")
        outcome.notes += friction_note(shaft, what)
        missing = ~found.converged
        if missing.any():
            reasons = sorted(set(r for r in found.reason if r))
            outcome.notes.append(f"not converged at {int(missing.sum())} speeds, no verdict "
                                 f"there (left empty): {'; '.join(reasons[:3])}"
                                 f"{' …' if len(reasons) > 3 else ''}.")
        for words in found.stopped:
            outcome.notes.append(f"the branch was not followed over the whole range ({words}): "
                                 f"further solutions beyond may be missed.")
        speed = rpm(found.speed)
        if found.in_time.any():
            back = found.in_time & (np.nan_to_num(found.slowest, nan=1.0) < 0.0)
            outcome.notes.append(
                f"at {int(found.in_time.sum())} solutions ({number_range(speed[found.in_time])}"
                f" rpm) the crank nearly stops or turns back for a moment (at {int(back.sum())}; "
                f"slowest {np.nanmin(found.slowest[found.in_time]):.3g} of Ω): solved in time, "
                f"not in crank angle (column in_time).")
        several = np.unique(speed[found.solution > 1])
        if several.size:
            stable_many = [s for s in several
                           if np.sum((speed == s) & found.converged & ~found.unstable) > 1]
            outcome.notes.append(
                f"several periodic solutions at {several.size} speeds "
                f"({number_range(several)} rpm; two or more stable at {len(stable_many)}): "
                f"which one the machine runs in depends on how it got there (a sweep upwards "
                f"jumps at {_list(f for f, up in found.folds if up)} rpm, downwards at "
                f"{_list(f for f, up in found.folds if not up)} rpm).")
        alone = [s for s in np.unique(speed[found.converged])
                 if not np.any((speed == s) & found.converged & ~found.unstable)]
        rows = {"speed_rpm": speed, "eta": found.eta, "period": np.ones(speed.size, dtype=int),
                "solution": found.solution,
                "peak_torque": found.peak_torque,
                "rigid_peak_torque": found.rigid_peak_torque,
                "twist_amplitude_deg": np.degrees(found.twist_amplitude),
                "twist_max_deg": np.degrees(found.twist_max),
                "fluctuation": found.fluctuation, "floquet": found.stability,
                "unstable": found.verdict,
                "instability": np.array(found.kind, dtype=object),
                "converged": found.converged,
                "steps": found.steps_used, "accuracy": found.accuracy,
                "balance": found.balance, "slowest": found.slowest,
                "in_time": found.in_time}
        if options.get(PERIOD_TWO.api):
            rows = period_two_rows(shaft, found, alone, rows, outcome, budget, steps)
        if alone:
            outcome.notes.append(
                f"at {len(alone)} speeds ({number_range(alone)} rpm) every periodic solution "
                f"found is unstable: the machine does not settle on it (a perturbation grows "
                f"as |μ| per revolution); a period-2 or quasi-periodic motion, or a jump to "
                f"another branch, follows (a flip region's period-2 motion: "
                f"{PERIOD_TWO.flag}).")
        set_columns(outcome, rows)
        add = outcome.add
        for k, at, kind in found.resonances:
            add(f"{kind}_k{k}_rpm", rpm(at), "rpm", {"eta": at / found.omega_bar},
                f"{kind} resonance Ω = {'2' if kind == 'parametric' else ''}ω̄/{k} "
                f"(harmonic {k} of J(φ){'' if kind == 'parametric' else ' or M_L(φ)'})")
        first = found.solution == 1
        add("unstable_rpm", unstable_ranges(speed[first], found.unstable[first]), "rpm",
            description="speeds where the (first) periodic motion is unstable (|μ| > 1)")
        add("jump_up_rpm", [rpm(f) for f, up in found.folds if up], "rpm",
            description="folds where a sweep upwards in speed jumps (the branch turns back)")
        add("jump_down_rpm", [rpm(f) for f, up in found.folds if not up], "rpm",
            description="folds where a sweep downwards in speed jumps")
        k = int(np.nanargmax(found.stability))
        add("stability_max", float(found.stability[k]), "-", {"speed_rpm": speed[k]},
            "largest |Floquet multiplier| over the speeds")
        k = int(np.nanargmax(found.peak_torque))
        add("peak_torque_max", float(found.peak_torque[k]), "N·m", {"speed_rpm": speed[k]},
            "largest shaft torque over the speeds")
        add("accuracy_max", float(np.nanmax(found.accuracy)), "-",
            description="largest change of a solution with twice the steps", limit=None)
        add("tolerance", found.tolerance, "-",
            description="the change with twice the steps that counts as converged")
        add("not_converged", int(missing.sum()), "-",
            description="speeds without a periodic solution to the tolerance (no verdict)")
        add("steps_per_revolution", found.steps, "-",
            description="RK4 steps per revolution to start with (doubled by accuracy)")
        outcome.result = found
        return outcome

    return run


def period_two_rows(shaft, found, alone, rows: dict, outcome: Outcome, budget: Budget,
                    steps: int) -> dict:
    """The scan's ``rows`` with a row of ``period`` 2 at each speed [rpm] of ``alone``
    (every periodic solution unstable) where a solution flips (period doubling) and the
    period-2 motion is found (``linkage.drive_line.period_two``, from the scan's own
    flipping orbit), after its speed's rows;
    the speeds without one in a note. The time it takes is checked against the budget
    first: beyond it, a note instead."""
    import numpy as np

    from dyade.errors import InputError
    from dyade.linkage import drive_line as api
    from dyade.machine import periodic

    speed = rows["speed_rpm"]
    flips = [s for s in alone if any(k == "period doubling" for k, at, ok in
                                     zip(found.kind, speed, found.converged) if ok and at == s)]
    if not flips:
        outcome.notes.append(f"{PERIOD_TWO.flag}: no speed of the range has only unstable "
                             f"periodic motions with a multiplier below −1: no period-2 rows.")
        return rows
    seconds = PERIOD_TWO_SECONDS * len(flips) * max(steps, 1) / 720.0
    try:
        budget.time(seconds, f"the period-2 motions at {len(flips)} "
                             f"speed{'s' if len(flips) > 1 else ''} that flip")
    except InputError as err:
        outcome.notes.append(f"the period-2 motions were not computed: {err}")
        return rows
    two = api.period_two(shaft.mechanism, flips, shaft=shaft, curve=found)
    found.period_two = two
    missed = [f"{s:.6g}" for s, ok in zip(flips, two.found) if not ok]
    if missed:
        outcome.notes.append(f"no period-2 motion found at {len(missed)} of the {len(flips)} "
                             f"speeds that flip ({', '.join(missed[:6])}"
                             f"{' …' if len(missed) > 6 else ''} rpm): "
                             f"{sorted(set(r for r in two.reason if r))[0]}.")
    if not two.found.any():
        return rows
    kinds = [periodic.kind_of(mu) for mu in two.multipliers]
    stable = ~(two.stability > 1.0 + periodic.UNSTABLE_MARGIN)
    extra = {"speed_rpm": np.asarray(flips), "eta": two.eta,
             "period": np.full(len(flips), 2),
             "solution": np.array([int(np.sum(speed == s)) + 1 for s in flips]),
             "peak_torque": two.peak_torque,
             "rigid_peak_torque": np.array([rows["rigid_peak_torque"][speed == s][0]
                                            for s in flips]),
             "twist_amplitude_deg": np.degrees(two.twist_amplitude),
             "twist_max_deg": np.degrees(two.twist_max),
             "fluctuation": two.fluctuation, "floquet": two.stability,
             "unstable": np.array([bool(not ok) for ok in stable], dtype=object),
             "instability": np.array(["" if ok else k for ok, k in zip(stable, kinds)],
                                     dtype=object),
             "converged": np.ones(len(flips), dtype=bool), "steps": two.steps,
             "accuracy": two.accuracy, "balance": two.balance, "slowest": two.slowest,
             "in_time": np.ones(len(flips), dtype=bool)}
    keep = np.flatnonzero(two.found)
    merged = {name: np.concatenate([np.asarray(values, dtype=extra[name].dtype
                                               if extra[name].dtype == object else None),
                                    extra[name][keep]])
              for name, values in rows.items()}
    order = np.argsort(merged["speed_rpm"], kind="stable")
    outcome.notes.append(
        f"period-2 motions (rows with period 2: over two revolutions, their multipliers "
        f"over two revolutions) at {keep.size} speeds ({number_range(np.asarray(flips)[keep])}"
        f" rpm; {int(stable[keep].sum())} stable): where the period-1 motion flips, the "
        f"machine settles on its period-2 motion where that is stable.")
    return {name: values[order] for name, values in merged.items()}


def _list(values) -> str:
    """Speeds [rad/s] as words in rpm (a note's numbers, 6 digits)."""
    out = [f"{rpm(v):.6g}" for v in values]
    return ", ".join(out) if out else "none in the range"


def number_range(values) -> str:
    """``first–last`` of values (a note's numbers, 6 digits)."""
    return f"{min(values):.6g}–{max(values):.6g}"


SCAN_INTEGRATIONS = 40  # [-] integrations of a typical scan (shooting, doubling, branches)


def scan_seconds(steps: int, speeds: int, dimension: int) -> float:
    """The time estimate of a scan over ``speeds`` speeds [s]: the shooting of all speeds
    at ``steps`` and twice the steps, every speed's solution carried to both neighbours
    (``linkage.drive_line``'s carry step: 2 lanes a speed, from a neighbour's solution:
    few iterations), and the continuation (one lane's 2d + 3 runs per integration)."""
    return (shooting_seconds(steps, speeds, dimension, 4)
            + 2 * shooting_seconds(2 * steps, speeds, dimension, 1)
            + shooting_seconds(steps, 2 * speeds, dimension, 1)
            + SCAN_INTEGRATIONS * steps * (SECONDS_PER_STEP * 0.3))


def unstable_ranges(speed_rpm, unstable) -> list[list[float]]:
    """The speed ranges [rpm] of consecutive unstable points, [first, last] each."""
    out, first, last = [], None, None
    for value, bad in zip([*speed_rpm.tolist(), None], [*unstable.tolist(), False]):
        if bad and first is None:
            first = value
        if not bad and first is not None:
            out.append([first, last])
            first = None
        last = value
    return out


TRACE_ITERATIONS = 30  # [-] Newton iterations (on the map's steps) of a traced boundary point


def stability_map(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """The largest Floquet multiplier over speed × the shaft's stiffness or damping."""
    import numpy as np

    from dyade.errors import InputError
    from dyade.linkage import drive_line as api
    from dyade.units import RPM

    speeds = speeds_of(options.get(SPEED_RANGE.api))
    text = options.get(MAP.api)
    parameter, _, values_text = (text or "").partition("=")
    if parameter not in ("stiffness", "damping") or not values_text:
        raise InputError.parameter(MAP.api, f"must be stiffness=START:STOP:STEP [N·m/rad] or "
                                            f"damping=START:STOP:STEP [N·m·s/rad] (it maps "
                                            f"stiffness or damping), got {text!r}.", value=text)
    unit = COLUMNS[parameter][0]
    values = speeds_of(values_text, MAP.api, parameter, unit)
    shaft, outcome = start(source, options, "driveline-map", ("driveline",))
    try:
        line = shaft.ideal_line
        low = min(abs(s) for s in speeds) * RPM
        steps = (steps_of(shaft, line, low, np.array([max(values)]) if parameter == "stiffness"
                          else None) if low > 0 and line.elements == 1 else 0)
        lanes = len(speeds) * len(values)
        # the traced boundary: about two crossings per row, some 30 shootings each
        # (secant iterations, on the steps and twice the steps)
        trace = shooting_seconds(steps, 2 * len(values), line.dimension, TRACE_ITERATIONS)
        budget.time(shooting_seconds(steps, lanes, line.dimension) + trace,
                    f"the stability map of {lanes:,} cells ({steps:,} steps per revolution) "
                    f"and its traced boundary")
        found = api.stability_map(shaft.mechanism, speeds, **{parameter: values}, shaft=shaft,
                                  progress=ticker(budget, ITERATIONS))
    except InputError as err:
        raise naming(err) from None
    outcome.notes += friction_note(shaft, "map")
    grid_speed, grid_value = np.meshgrid(rpm(found.speed), found.values)
    stability = found.stability.ravel()
    given = np.isfinite(stability)
    withheld(Outcome("driveline-map", notes=[NO_STATE]), given,
             "no cell of the map has a periodic state of the drive line")
    if not given.all():
        outcome.notes.append(f"no periodic state in {int((~given).sum())} cells ({NO_STATE}): "
                             f"left empty.")
    set_columns(outcome, {"speed_rpm": grid_speed.ravel(), parameter: grid_value.ravel(),
                          "floquet": stability, "unstable": found.unstable.ravel()})
    k = int(np.nanargmax(stability))
    outcome.add("stability_max", float(stability[k]), "-",
                {"speed_rpm": grid_speed.ravel()[k], parameter: grid_value.ravel()[k]},
                "largest |Floquet multiplier| over the map")
    outcome.add("unstable_cells", int(found.unstable.sum()), "-",
                description="cells where the periodic motion is unstable (|μ| > 1)")
    edges = found.edges
    if edges is not None:
        outcome.add("boundary_points", int(edges.speed.size), "-",
                    description="points of the stability boundary traced between the cells "
                                "(a multiplier at −1 or +1, converged to 1e-6)")
        outcome.notes += edge_notes(edges, parameter, unit)
    outcome.result = found
    return outcome


def edge_notes(edges: Any, parameter: str, unit: str) -> list[str]:
    """The traced boundary of a map in words: per value of the parameter, the speeds
    [rpm] where a multiplier is −1 (period doubling) or +1 (fold); the crossings not
    traced and why."""
    def number(value: float) -> str:
        return f"{value:.6g}"

    notes = []
    for kind in sorted(set(edges.kind)):
        rows = {}
        for speed, value, k in zip(rpm(edges.speed), edges.values, edges.kind):
            if k == kind:
                rows.setdefault(float(value), []).append(number(float(speed)))
        sigma = "−1" if kind == "period doubling" else "+1"
        listed = "; ".join(f"{number(value)} {unit}: {', '.join(speeds)} rpm"
                           for value, speeds in rows.items())
        notes.append(f"stability boundary traced (a multiplier at {sigma}, {kind}), "
                     f"{parameter} -> speed: {listed}.")
    for value, low, high, reason in edges.missed:
        notes.append(f"the boundary between {number(float(rpm(low)))} and "
                     f"{number(float(rpm(high)))} rpm at {parameter} {number(float(value))} "
                     f"{unit} is not traced: {reason}.")
    return notes


def run_up(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """From rest under the ``[drive]`` motor until the mean speed settles."""
    import numpy as np

    from dyade.linkage import drive_line as api
    from dyade.machine import drive_line as engine

    shaft, outcome = start(source, options, "driveline-run-up", ("driveline",))
    mechanism = shaft.mechanism
    revolutions = RUN_UP_REVOLUTIONS
    if mechanism.drive is not None:  # (without one, the engine says what is missing)
        top = float(engine.natural_frequencies(
            shaft.line, np.array([np.min(shaft.tables.inertia)]))[0, -1])
        per_revolution = api.STEPS_PER_VIBRATION_IN_TIME * top / abs(mechanism.crank.speed)
        revolutions = min(revolutions, mechanism.drive.max_revolutions)
        budget.time(per_revolution * revolutions * SECONDS_PER_TIME_STEP,
                    f"the run-up (about {per_revolution:,.0f} time steps per revolution)")
    found = api.run_up(mechanism, shaft=shaft, progress=ticker(budget, revolutions))
    outcome.notes += friction_note(shaft, "run-up")
    set_columns(outcome, {"time": found.time, "angle_deg": np.degrees(found.crank_angle),
                          "crank_speed_rpm": rpm(found.crank_speed),
                          "motor_speed_rpm": rpm(found.motor_speed),
                          "shaft_torque": found.shaft_torque,
                          "twist_deg": np.degrees(found.twist)})
    f = found.figures
    add = outcome.add
    add("peak_torque", f["peak_torque"], "N·m",
        {"time_s": f["peak_time"], "speed_rpm": rpm(f["peak_speed"])},
        "largest |shaft torque| on the way (signed)")
    add("peak_time", f["peak_time"], "s", description="when the largest shaft torque occurs")
    add("peak_speed_rpm", rpm(f["peak_speed"]), "rpm",
        description="the crank speed at the largest shaft torque")
    add("duration", f["duration"], "s", description="time to speed")
    add("revolutions", f["revolutions"], "-", description="revolutions to speed")
    add("speed_mean_rpm", rpm(f["speed_mean"]), "rpm",
        description="mean crank speed over the last revolution")
    add("time_step", f["time_step"], "s", description="RK4 time step")
    outcome.result = found
    return outcome


ENTRIES = {
    "driveline-frequency": Analysis(
        "driveline-frequency", "The drive line's natural frequency and VDI 2149", frequency,
        (SET,), command="dyade driveline --analysis frequency"),
    "driveline-steady": Analysis(
        "driveline-steady", "Periodic steady state of the drive line, next to the rigid drive",
        steady, (SET, SPEED_RPM), figures=("driveline",),
        command="dyade driveline --analysis steady"),
    "driveline-resonance": Analysis(
        "driveline-resonance", "Resonance curve of the drive line (ideal motor)",
        curve("driveline-resonance"), (SET, SPEED_RANGE, ETA_RANGE, PERIOD_TWO),
        figures=("driveline",),
        command="dyade driveline --analysis resonance"),
    "driveline-stability": Analysis(
        "driveline-stability", "Floquet multipliers of the drive line over speed (ideal motor)",
        curve("driveline-stability"), (SET, SPEED_RANGE, ETA_RANGE, PERIOD_TWO),
        figures=("driveline",),
        command="dyade driveline --analysis stability"),
    "driveline-map": Analysis(
        "driveline-map", "Largest Floquet multiplier over speed × stiffness or damping",
        stability_map, (SET, SPEED_RANGE, MAP), figures=("driveline",),
        command="dyade driveline --analysis map"),
    "driveline-run-up": Analysis(
        "driveline-run-up", "Run-up of the drive line from rest", run_up, (SET,),
        figures=("driveline",), command="dyade driveline --analysis run-up"),
}
