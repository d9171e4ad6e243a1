"""``dyade clearance``: the joint-clearance peak check (SPEC §2)."""

from __future__ import annotations

import math
import time
from pathlib import Path

import click

from dyade.cli import main
from dyade.cli.analyse import MECHANISM_FILE, SUFFIX, batch
from dyade.cli.options import value_range
from dyade.cli.output import console, show, write_json, write_rows

STANDALONE_COLUMNS = ["mass", "stiffness", "clearance", "slope", "t1", "v1", "tau", "f_tau",
                      "F_max"]
SIMULATION_COLUMNS = ["F_sim", "sim_rel_diff", "sim_steps", "sim_time_s", "closed_time_s",
                      "separates"]
MECHANISM_COLUMNS = ["joint", "reversal", "angle_deg", "slope", "t1", "v1", "tau", "f_tau",
                     "F_max", "F_clearance", "F_rigid", "amplification", "mass", "stiffness",
                     "clearance", "line_deg", "wander_deg"]


def _joint(text: str) -> tuple[int, int]:
    try:
        a, b = (int(part) for part in text.split(","))
    except ValueError:
        raise click.BadParameter(f"must be two link numbers like 5,6, got {text!r}.",
                                 param_hint="--joint") from None
    return (a, b) if a < b else (b, a)


def _emit(rows: list[dict], names: list[str], fmt: str, output: Path | None,
          summary: dict, warnings: list[str], parts) -> None:
    """CSV rows, JSON (columns as arrays + summary + warnings) or rich tables."""
    if fmt == "csv":
        write_rows(rows, names, output)
    elif fmt == "json":
        obj = {name: [row.get(name) for row in rows] for name in names}
        write_json(obj | {"summary": summary, "warnings": warnings}, output)
    else:
        show(parts(), output)
    err = console(stderr=True)
    for line in warnings:
        err.print(line)


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1)
@click.option("--joint", "joints", multiple=True, metavar="I,J",
              help="Revolute joint to check, e.g. --joint 5,6 (repeatable); default: every "
                   "revolute joint (with a file).")
@click.option("--mass", "masses", type=float, multiple=True, metavar="KG",
              help="Reduced mass m [kg]; give it twice (--mass m11 --mass m22) for the two "
                   "masses of SPEC §2, eq. (17). With a file: default from the joint's "
                   "`clearance.mass` or the two links' masses.")
@click.option("--stiffness", type=float, help="Contact stiffness c [N/m] (typical 1e7…1e9).")
@click.option("--clearance", "gap", type=float,
              help="Clearance (radial play) 2s [m] (typical 2e-5…2e-4).")
@click.option("--slope", type=float, help="Standalone: force slope F0/t0 at the reversal [N/s].")
@click.option("--speed-rpm", type=float,
              help="Standalone: crank speed [rpm] at which --slope holds (for --speed-range).")
@click.option("--speed-range", metavar="START:STOP:STEP",
              help="Peak force against crank speed [rpm]; the slope grows with Ω³ (eq. 30).")
@click.option("--simulate", is_flag=True,
              help="Also integrate the two-mass model directly; report its peak, the cost of "
                   "each method and whether contact holds (rebound).")
@click.option("--sim-steps", type=click.IntRange(min=10), default=400, show_default=True,
              help="RK4 steps per contact period for --simulate.")
@click.option("--max-wander", type=click.FloatRange(min=0, max=90), default=20.0,
              show_default=True,
              help="Largest angle [°] the force may leave its line of action (forces ≥ 25 % of "
                   "the peak) for the model to apply.")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: one row (record) per reversal.")
@click.option("-o", "--output", type=click.Path(writable=True, path_type=Path),
              help="Write the result to this file instead of standard output; with several "
                   "mechanism files a directory with one result per file.")
def clearance(mechanism_files: tuple[Path, ...], joints: tuple[str, ...], masses: tuple[float, ...],
              stiffness: float | None, gap: float | None, slope: float | None,
              speed_rpm: float | None, speed_range: str | None, simulate: bool,
              sim_steps: int, max_wander: float, fmt: str, output: Path | None) -> None:
    """Peak force in a revolute joint with clearance (Dresig & Thümmel, SPEC §2).

    Where a joint force reverses its sense, the pin crosses the clearance 2s and strikes
    the bearing. Standalone, from four numbers:

        dyade clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000

    gives the paper's 2182 N. Over a mechanism (the rigid forces from its kinetostatics):

        dyade clearance mechanisms/dyade-16.toml --stiffness 1e8 --clearance 1e-4

    checks every revolute joint: the dominant line of action of its force, whether the
    force keeps to it (else the model does not apply, and dyade says why), and for each
    reversal the slope F0/t0 = |dF/dφ21|·Ω, τ, f(τ), the peak and its amplification over
    the rigid force. Impacts per revolution = number of reversals.
    """
    from dyade import clearance as engine
    from dyade.errors import InputError

    if len(masses) > 2:
        raise click.BadParameter("give one reduced mass, or the two masses m11 and m22.",
                                 param_hint="--mass")
    for name, value in (("mass", masses[0] if masses else None), ("stiffness", stiffness),
                        ("clearance", gap), ("slope", slope)):
        if value is not None and not value > 0:
            raise InputError(f"--{name} must be a positive number, got {value:g}.")
    if len(masses) == 2 and not masses[1] > 0:
        raise InputError(f"--mass must be a positive number, got {masses[1]:g}.")
    mass = engine.reduced_mass(*masses) if len(masses) == 2 else (masses[0] if masses else None)
    wander = math.radians(max_wander)
    speeds = value_range(speed_range, "--speed-range", " in rpm", positive_start=True) if speed_range else None
    if not mechanism_files:
        _standalone(mass, stiffness, gap, slope, speed_rpm, speeds, simulate, sim_steps, fmt,
                    output)
    else:
        if slope is not None or speed_rpm is not None:
            raise click.UsageError("--slope and --speed-rpm are for the standalone check; over a "
                                   "mechanism the slope comes from its joint forces.")
        if (stiffness is None) != (gap is None):
            raise click.UsageError("give --stiffness and --clearance together (or neither, to use "
                                   "the clearance data of the mechanism file).")
        chosen = [_joint(j) for j in joints]

        def run_one(path: Path, target: Path | None, _: object = None) -> None:
            _over_mechanism(path, chosen, mass, stiffness, gap, speeds, simulate, sim_steps, fmt,
                            target, wander)

        if len(mechanism_files) == 1 and not (output and output.is_dir()):
            run_one(mechanism_files[0], output)
            return
        from dyade.errors import DyadeError

        if output is None:
            raise click.UsageError(f"{len(mechanism_files)} mechanism files need -o DIR.")
        output.mkdir(parents=True, exist_ok=True)
        failures = batch(mechanism_files, output, run_one, SUFFIX[fmt])
        if failures:
            lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
            raise DyadeError(f"{len(failures)} of {len(mechanism_files)} files failed:\n{lines}")


def _standalone(mass, stiffness, gap, slope, speed_rpm, speeds, simulate, sim_steps, fmt, output):
    from dyade import clearance as engine

    missing = [flag for flag, value in (("--mass", mass), ("--stiffness", stiffness),
                                        ("--clearance", gap), ("--slope", slope)) if value is None]
    if missing:
        raise click.UsageError(f"the standalone check needs {', '.join(missing)} (or give a "
                               f"mechanism file).")
    if speeds and speed_rpm is None:
        raise click.UsageError("--speed-range needs --speed-rpm: the speed at which --slope holds.")
    cases = [(None, slope)] if not speeds else [(rpm, slope * (rpm / speed_rpm) ** 3) for rpm in speeds]
    rows = []
    for rpm, k in cases:
        started = time.perf_counter()
        peak = engine.peak_force(mass, stiffness, gap, k)
        closed_time = time.perf_counter() - started
        row = {"speed_rpm": rpm, "mass": mass, "stiffness": stiffness, "clearance": gap,
               "slope": k, "t1": peak.t1, "v1": peak.v1, "tau": peak.tau, "f_tau": peak.f_tau,
               "F_max": peak.force, "F_clearance": peak.clearance_share,
               "F_rigid_share": peak.rigid_share, "soft": peak.soft,
               "closed_time_s": closed_time}
        if simulate:
            row.update(_simulated(engine, mass, stiffness, gap, k, sim_steps, peak.force))
        rows.append(row)
    names = (["speed_rpm"] if speeds else []) + STANDALONE_COLUMNS + (SIMULATION_COLUMNS if simulate else [])
    warnings = [line for row in rows for line in _notes(row)]

    def parts():
        from rich.table import Table

        table = Table(title="Clearance peak force (Dresig & Thümmel, SPEC §2)", title_justify="left")
        if not speeds:
            row = rows[0]
            for head in ("quantity", "value", "unit"):
                table.add_column(head, justify="right" if head == "value" else "left")
            lines = [("reduced mass m", "mass", "kg"), ("contact stiffness c", "stiffness", "N/m"),
                     ("clearance 2s", "clearance", "m"), ("force slope F0/t0", "slope", "N/s"),
                     ("free flight t1, eq. (15)", "t1", "s"), ("impact speed v1, eq. (16)", "v1", "m/s"),
                     ("τ = ω·t1, eq. (23)", "tau", "-"), ("f(τ), eq. (36)", "f_tau", "-"),
                     ("peak force F12max = c·s·f(τ)", "F_max", "N"),
                     ("  clearance share 6·c·s/τ", "F_clearance", "N"),
                     ("  rigid force reached by then", "F_rigid_share", "N")]
            if simulate:
                lines += [("simulated peak (RK4)", "F_sim", "N"),
                          ("  relative difference", "sim_rel_diff", "-"),
                          ("  RK4 steps", "sim_steps", ""), ("time: closed form", "closed_time_s", "s"),
                          ("time: simulation", "sim_time_s", "s")]
            for label, key, unit in lines:
                table.add_row(label, _cell_pretty(row[key]), unit)
        else:
            show_cols = [("speed_rpm", "speed [rpm]"), ("slope", "F0/t0 [N/s]"), ("tau", "τ"),
                         ("F_max", "F12max [N]"), ("F_clearance", "6cs/τ [N]")]
            if simulate:
                show_cols += [("F_sim", "simulated [N]")]
            _fill(table, show_cols, rows)
        return [table]

    _emit(rows, names, fmt, output, {"cases": len(rows)}, warnings, parts)


def _simulated(engine, mass, stiffness, gap, slope, steps, closed) -> dict:
    started = time.perf_counter()
    sim = engine.simulate(mass, stiffness, gap, slope, steps)
    elapsed = time.perf_counter() - started
    return {"F_sim": sim.force, "sim_rel_diff": (sim.force - closed) / closed,
            "sim_steps": sim.steps, "sim_time_s": elapsed, "separates": sim.separates,
            "separation_time": sim.separation_time, "rebound_speed": sim.rebound_speed,
            "contact_to_peak": sim.contact_to_peak}


def _notes(row: dict, where: str = "") -> list[str]:
    out = []
    if row.get("soft"):
        out.append(f"note: {where}τ = {row['tau']:.3g} < 2: a soft impact. The first maximum of "
                   f"eq. (26) comes after the first contact half-wave, where the paper's eq. (36) "
                   f"(principal arccos) does not apply; dyade gives that true first maximum. For "
                   f"τ ≪ 2 it is only a small ripple on the rising rigid force: there is no knock.")
    if row.get("separates"):
        out.append(f"note: {where}after the peak the masses separate at t = "
                   f"{row['separation_time']:.4g} s (rebound at {row['rebound_speed']:.3g} m/s): "
                   f"a second impact follows.")
    elif "separates" in row:
        out.append(f"note: {where}the masses stay in contact through the first contact period "
                   f"(the closed form's assumption holds).")
    return out


def _fill(table, show: list[tuple[str, str]], rows: list[dict]) -> None:
    """Right-aligned columns (key, heading) and one table row per result row."""
    for _, head in show:
        table.add_column(head, justify="right")
    for row in rows:
        table.add_row(*[_cell_pretty(row.get(key)) for key, _ in show])


def _cell_pretty(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.5g}" if abs(value) < 1e5 else f"{value:.4g}"
    return str(value)


def _over_mechanism(path, joints, mass, stiffness, gap, speeds, simulate, sim_steps, fmt, output,
                    max_wander):
    from dataclasses import replace

    import numpy as np

    from dyade.linkage import sweep as analysis
    from dyade.files import mechanism as toml_input
    from dyade import clearance as engine
    from dyade.linkage.model import ClearanceData, Revolute
    from dyade.units import RPM

    mechanism = toml_input.read_mechanism(path)
    override = ClearanceData(gap, stiffness, None) if stiffness is not None else None
    if not joints:
        joints = [j.name for j in mechanism.joints if isinstance(j, Revolute)]
    rows, skipped = [], []
    for rpm in speeds or [None]:
        mech = mechanism
        if rpm is not None:
            sign = 1.0 if mechanism.crank.speed > 0 else -1.0
            mech = replace(mechanism, crank=replace(mechanism.crank, speed=sign * rpm * RPM))
        result = analysis.run(mech)
        for check in engine.check_mechanism(mech, result, joints, override, mass, max_wander):
            if not check.applies:
                if rpm is None or rpm == speeds[0]:
                    skipped.append(check)
                continue
            for number, rev in enumerate(check.reversals, 1):
                peak = rev.peak
                row = {"speed_rpm": rpm, "joint": f"{check.joint[0]}-{check.joint[1]}",
                       "reversal": number, "angle_deg": float(np.rad2deg(rev.crank_angle)),
                       "slope": peak.slope, "t1": peak.t1, "v1": peak.v1, "tau": peak.tau,
                       "f_tau": peak.f_tau, "F_max": peak.force,
                       "F_clearance": peak.clearance_share, "F_rigid": rev.rigid_force,
                       "amplification": rev.amplification, "mass": peak.mass,
                       "stiffness": peak.stiffness, "clearance": peak.clearance,
                       "line_deg": float(np.rad2deg(check.line_angle)),
                       "wander_deg": float(np.rad2deg(check.wander)), "soft": peak.soft,
                       "impacts": len(check.reversals), "mass_source": check.mass_source}
                if simulate:
                    row.update(_simulated(engine, peak.mass, peak.stiffness, peak.clearance,
                                          peak.slope, sim_steps, peak.force))
                rows.append(row)
            if not check.reversals and (rpm is None or rpm == speeds[0]):
                skipped.append(check)
    names = (["speed_rpm"] if speeds else []) + MECHANISM_COLUMNS + (
        ["F_sim", "sim_rel_diff", "separates"] if simulate else [])
    warnings = []
    for check in skipped:
        a, b = check.joint
        if check.applies:
            warnings.append(f"joint ({a},{b}): the force keeps one sense over the cycle (line of "
                            f"action {np.rad2deg(check.line_angle):.0f}°): no reversal, no "
                            f"clearance impact.")
        else:
            warnings.append(f"joint ({a},{b}): not checked — {check.reason}.")
    if any(row.get("soft") for row in rows):
        warnings.append("note: reversals with τ < 2 are soft impacts: their peak comes after the "
                        "first contact half-wave (see `dyade clearance --help`).")
    summary = {"mechanism": mechanism.name, "reversals": len(rows),
               "joints_checked": [f"{a}-{b}" for a, b in joints]}
    _emit(rows, names, fmt, output, summary, warnings,
          lambda: [_mechanism_table(mechanism.name, rows, speeds, simulate)])


def _mechanism_table(name, rows, speeds, simulate):
    from rich.table import Table

    lines = {}
    for row in rows:
        lines.setdefault(row["joint"], (row["line_deg"], row["wander_deg"], row["mass"],
                                        row["mass_source"]))
    caption = "; ".join(f"({j.replace('-', ',')}): line {line:.0f}°, wander {wander:.0f}°, "
                        f"m = {mass:.3g} kg ({source})"
                        for j, (line, wander, mass, source) in lines.items())
    table = Table(title=f"{name}: clearance peaks per reversal (SPEC §2)", title_justify="left",
                  caption=caption or None, caption_justify="left")
    show = [("speed_rpm", "rpm")] if speeds else []
    show += [("joint", "joint"), ("impacts", "impacts/rev"), ("angle_deg", "φ21 [°]"),
             ("slope", "F0/t0 [N/s]"), ("tau", "τ"), ("F_max", "F12max [N]"),
             ("F_rigid", "rigid [N]"), ("amplification", "×")]
    if simulate:
        show += [("F_sim", "simulated [N]")]
    _fill(table, show, rows)
    return table
