"""``dyade driveline``: a linkage driven through an elastic shaft or coupling."""

from __future__ import annotations

import click

from dyade.cli import main
from dyade.cli.common import infer_format, load
from dyade.cli.options import MECHANISM_FILE, POSITIVE, Renamed, set_option
from dyade.cli.output import console, flags, show, write_json, write_rows

ANALYSES = click.Choice(["steady", "resonance", "stability", "map", "run-up"])
FLAGS = {"speeds_rpm": "--speed-range", "speed_rpm": "--speed-rpm", "stiffness": "--map",
         "damping": "--map"}
"""API parameter -> the flag it comes from"""


def speed_range(text: str, hint: str, quantity: str = "speed_rpm") -> list[float]:
    """START:STOP:STEP [rpm], STOP included (``dyade.files.schema.range_parts``,
    ``range_values``); both ends of one sign (the crank's sense); ``quantity``
    (``dyade.limits.PLAUSIBLE``) bounds the ends: a --map's stiffness or damping."""
    from dyade.files.schema import range_parts, range_values
    from dyade.limits import implausible, plausible_range

    try:
        start, stop, step = range_parts(text, " [rpm]")
        if not (step > 0 and stop >= start):
            raise ValueError(f"needs START <= STOP and STEP > 0, got {text!r}.")
        if any(implausible(quantity, abs(end)) for end in (start, stop)
               if end or quantity != "damping"):
            raise ValueError(f"values must lie in {plausible_range(quantity)} (what a "
                             f"machine has), got {text!r}.")
        return range_values(start, stop, step, 2000, "speeds")
    except ValueError as err:
        raise click.BadParameter(str(err), param_hint=hint) from None


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--analysis", "what", type=ANALYSES, default="steady", show_default=True,
              help="steady: the periodic state at the operating speed next to the rigid "
                   "drive's; resonance: peak shaft torque, twist and speed fluctuation over "
                   "--speed-range; stability: the Floquet multipliers over --speed-range; map: "
                   "the largest multiplier over --speed-range × --map; run-up: from rest "
                   "under the [drive] motor.")
@click.option("--speed-range", "speeds_rpm", cls=Renamed, old=("--speeds-rpm",),
              metavar="START:STOP:STEP",
              help="Crank speeds of an ideal motor [rpm] for resonance, stability and map.")
@click.option("--speed-rpm", type=POSITIVE, metavar="RPM",
              help="The ideal motor's speed for steady [rpm] [default: the crank's].")
@click.option("--map", "map_range", metavar="stiffness|damping=START:STOP:STEP",
              help="The line's parameter and values for --analysis map [N·m/rad or "
                   "N·m·s/rad].")
@set_option
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="table, csv or json. [default: table on stdout; with -o: from its suffix]")
@click.option("-o", "--output", type=click.Path(writable=True, dir_okay=False),
              help="Write to this file instead of standard output.")
def driveline(mechanism_file: str, what: str, speeds_rpm: str | None, speed_rpm: float | None,
              map_range: str | None, assignments: tuple[str, ...], fmt: str | None,
              output: str | None) -> None:
    """The elastic drive line of MECHANISM_FILE ([drive_line] table): motor → shaft or
    coupling → the linkage's crank shaft with its reduced inertia J(φ).

    Always: ω̄, the lowest natural frequency with the mean inertia J̄, its range over the
    cycle, η = Ω/ω̄ and the VDI 2149 check (the rigid model holds for η ≤ 0.1). Then
    the analysis asked for:

    \b
        dyade driveline mech.toml                       # steady state vs rigid
        dyade driveline mech.toml --analysis resonance --speed-range 300:6000:50
        dyade driveline mech.toml --analysis map --speed-range 300:6000:50 \\
            --map stiffness=500:2000:100
        dyade driveline mech.toml --analysis run-up

    Resonance curves, stability charts and maps scan an ideal motor's speed (a [drive]
    motor is replaced by one); steady state and run-up use the [drive] motor if the file
    has one. Forced resonances lie near Ω = ω̄/k, parametric instability near
    Ω = 2ω̄/k, k a harmonic of J(φ) or M_L(φ). A run-up that never reaches speed exits 1.
    """
    import numpy as np

    from dyade.linkage import drive_line as api
    from dyade.report import drive_line as report

    from dyade.limits import implausible, plausible_range

    if speed_rpm is not None and implausible("speed_rpm", speed_rpm):
        raise click.BadParameter(f"must lie in {plausible_range('speed_rpm')} (what a machine "
                                 f"has), got {speed_rpm:g}.", param_hint="--speed-rpm")
    fmt = fmt or infer_format(output)
    mechanism = load(mechanism_file, assignments).mechanism
    notes: list[str] = []
    with flags(FLAGS):
        freq = api.natural_frequency(mechanism)
        summary = {"natural_frequency": report.frequency_summary(freq)}
        if not freq.vdi_2149:
            notes.append(f"Ω/ω̄ = {freq.ratio:.3g} exceeds 0.1 (VDI 2149 Part 1): the rigid "
                         f"drive's model does not hold for this line.")
        if what != "steady" and api.has_friction(mechanism):
            notes.append(f"joint friction is left out of the {what} (the steady state takes "
                         f"it, by passes at the vibrating crank's motion).")
        speeds = None
        if what in ("resonance", "stability", "map"):
            if not speeds_rpm:
                raise click.UsageError(f"--analysis {what} needs --speed-range START:STOP:STEP.")
            speeds = speed_range(speeds_rpm, "--speed-range")
        elif speeds_rpm:
            raise click.UsageError(f"--speed-range is for resonance, stability and map, not "
                                   f"{what}.")
        if map_range and what != "map":
            raise click.UsageError("--map is for --analysis map.")
        if speed_rpm is not None and what != "steady":
            raise click.UsageError("--speed-rpm is for --analysis steady.")
        if what == "steady":
            state = api.steady_state(mechanism, speed_rpm=speed_rpm)
            columns = report.steady_columns(state)
            summary["steady"] = report.steady_summary(state)
            title = "Periodic steady state of the drive line, next to the rigid drive"
        elif what in ("resonance", "stability"):
            curve = api.resonance_curve(mechanism, speeds)
            columns = report.resonance_columns(curve)
            summary["resonances"] = report.resonance_labels(curve)
            summary["unstable_rpm"] = report.unstable_ranges(columns["speed_rpm"],
                                                             curve.unstable)
            summary["steps_per_revolution"] = curve.steps
            if not curve.converged.all():
                notes.append(f"no periodic state at {int((~curve.converged).sum())} speeds "
                             f"(the crank would stop or turn back, or the shooting did not "
                             f"converge): left empty.")
            title = "Resonance curve and Floquet multipliers (ideal motor)"
        elif what == "map":
            if not map_range or "=" not in map_range:
                raise click.UsageError("--analysis map needs --map stiffness=START:STOP:STEP "
                                       "or damping=START:STOP:STEP.")
            name, text = map_range.split("=", 1)
            if name not in ("stiffness", "damping"):
                raise click.BadParameter(f"maps stiffness or damping, got {name!r}.",
                                         param_hint="--map")
            values = speed_range(text, "--map", name)
            result = api.stability_map(mechanism, speeds, **{name: values})
            grid_speed, grid_value = np.meshgrid(result.speed * report.RPM, result.values)
            columns = {"speed_rpm": grid_speed.ravel(), name: grid_value.ravel(),
                       "floquet": result.stability.ravel(),
                       "unstable": result.unstable.ravel().astype(float)}
            title = f"Largest Floquet multiplier over speed × {name}"
        else:
            run = api.run_up(mechanism)
            columns = {"time": run.time, "angle_deg": np.degrees(run.crank_angle),
                       "crank_speed_rpm": run.crank_speed * report.RPM,
                       "motor_speed_rpm": run.motor_speed * report.RPM,
                       "shaft_torque": run.shaft_torque, "twist_deg": np.degrees(run.twist)}
            summary["run_up"] = dict(run.figures)
            title = "Run-up from rest"
    names = list(columns)
    if fmt == "csv":
        table = np.column_stack([np.asarray(columns[n], dtype=float) for n in names]) + 0.0
        write_rows([dict(zip(names, row)) for row in table.tolist()], names, output)
    elif fmt == "json":
        from dyade.report.document import document

        write_json(document("driveline", columns, report.UNITS, summary, notes,
                            mechanism=mechanism.name, analysis=what), output)
    else:
        parts = [report.summary_table("Natural frequency, VDI 2149",
                                      summary["natural_frequency"])]
        for key in ("steady", "run_up"):
            if key in summary:
                parts.append(report.summary_table(key.replace("_", "-"), summary[key]))
        if "resonances" in summary:
            parts.append(report.summary_table("Resonances expected in the range (rpm)", {
                f"{row['kind']} k={row['harmonic']}": row["speed_rpm"]
                for row in summary["resonances"]} | {"unstable [rpm]": str(
                    [(round(a, 4), round(b, 4)) for a, b in summary["unstable_rpm"]])}))
        count = len(columns[names[0]])
        parts.append(report.table(title, columns, every=max(1, count // 60)))
        show(parts, output)
    err = console(stderr=True)
    for note in notes:
        err.print(f"note: {note}", markup=False)
