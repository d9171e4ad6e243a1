"""A sweep's summary: the figures a designer sizes parts by, one name each (issue 36).

One set of names for every writer and for a study: ``figures`` gives the summary of a
sweep (``dyade analyse``, ``Result.summary()``, the ``sweep`` entry's Outcome), and a
study's outputs are the same figures of each variant, computed by the same functions
over (variants, positions) at once (``key_figures``). The names (docs/reference/json.md):

- kinematics: ``mu_<dyad>_min_deg`` (the smallest transmission angle, as its distance
  from a dead centre), ``stroke_<a>_<b>`` and ``time_ratio_<a>_<b>`` of a slider,
  ``swing_<link>_deg`` and ``time_ratio_<link>`` of a rocker;
- forces: ``M_drive_max``, ``M_drive_min``, ``M_drive_rms``, ``P_drive_mean``,
  ``F_<a>_<b>_peak`` / ``FN_<a>_<b>_peak`` (the signed value of largest magnitude),
  ``F_shake_max``, ``F_shake_rms``, ``M_shake_abs_max``;
- friction, self-locking, the equation of motion, the clearance check (``STAGES``);
- the extremes of every column, ``<column>_min`` and ``<column>_max`` (so
  ``mu_2_deg_min`` is the least value of the column ``mu_2_deg``, ``mu_2_min_deg`` its
  least distance from a dead centre).

Numbers only, SI (angles in degrees where the name says ``_deg``, speeds in rpm where
it says ``_rpm``); the report words them.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from typing import Any, NamedTuple

import numpy as np

from dyade import cycle
from dyade.units import RAD_PER_S_TO_RPM
from dyade.arrays import resolution
from dyade.linkage.columns import Columns, unit_of
from dyade.linkage.components import magnitude
from dyade.model.mechanism import Revolute
from dyade.linkage.verdicts import Outcome


def full_cycle(angle_deg: np.ndarray) -> bool:
    """The positions cover one whole crank revolution (to within a step)."""
    if angle_deg.size < 3:
        return False
    step = float(np.min(np.diff(angle_deg)))
    return float(angle_deg[-1] - angle_deg[0]) >= 360.0 - 1.5 * step


def time_ratio(angle_deg: np.ndarray, output: np.ndarray) -> float | None:
    """Time ratio of a quick-return output over one crank revolution at constant speed:
    the longer of the two crank-angle spans between its extreme positions over the
    shorter (1 for a symmetric drive). None unless the positions cover a revolution and
    the output has exactly one maximum and one minimum per revolution. One curve of
    ``time_ratios``."""
    ratio = float(time_ratios(angle_deg, np.asarray(output, dtype=np.float64)[None, :])[0])
    return None if np.isnan(ratio) else ratio


def time_ratios(angle_deg: np.ndarray, output: np.ndarray) -> np.ndarray:
    """``time_ratio`` of every row of ``output`` (variants, positions), all at the crank
    angles ``angle_deg``; NaN where there is none."""
    ratio = np.full(output.shape[0], np.nan)
    keep = np.isfinite(output).all(axis=1)
    if not keep.any() or not full_cycle(angle_deg):
        return ratio
    cycle = output[:, :-1] if angle_deg[-1] - angle_deg[0] >= 360.0 - 1e-9 else output
    rises = np.diff(np.concatenate((cycle, cycle[:, :1]), axis=1), axis=1) > 0
    keep &= np.count_nonzero(rises != np.roll(rises, 1, axis=1), axis=1) == 2  # one rise, one fall
    step = float(angle_deg[1] - angle_deg[0])
    top, bottom = _vertices(angle_deg, cycle, step, 1.0), _vertices(angle_deg, cycle, step, -1.0)
    forward = (top - bottom) % 360.0
    short, long = np.minimum(forward, 360.0 - forward), np.maximum(forward, 360.0 - forward)
    keep &= short > 0
    np.divide(long, short, out=ratio, where=keep)
    return ratio


def _vertices(angle_deg: np.ndarray, cycle: np.ndarray, step: float, sign: float
              ) -> np.ndarray:
    """Crank angle [°] of the maximum (sign +1) or minimum (−1) of each row of periodic
    sampled outputs, refined by the parabola through it and its two neighbours (error ∝
    step³ instead of half a step)."""
    rows = np.arange(cycle.shape[0])
    k = np.argmax(sign * np.where(np.isnan(cycle), -sign * np.inf, cycle), axis=1)
    before, here, after = (cycle[rows, k - 1], cycle[rows, k],
                           cycle[rows, (k + 1) % cycle.shape[1]])
    curvature = before - 2.0 * here + after
    shift = np.zeros(rows.size)
    np.divide(0.5 * (before - after), curvature, out=shift, where=curvature != 0.0)
    return angle_deg[k] + shift * step


def least_transmission(mu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest distance [°] of transmission angles ``mu`` (variants, positions)
    [°] from a dead centre (0° or 180°) per row, and the position where it lies (NaN,
    0 where a row has none)."""
    off = np.minimum(mu, 180.0 - mu)  # the angle to the nearer dead centre
    if np.isnan(np.add.reduce(off, axis=None)):  # (NaN only where one is: off ≥ 0 or NaN)
        k = np.argmin(np.where(np.isnan(off), np.inf, off), axis=1)
    else:
        k = np.argmin(off, axis=1)
    return np.take_along_axis(off, k[:, None], axis=1)[:, 0], k


def strokes(travel: np.ndarray) -> np.ndarray:
    """The stroke [m] of each row of slider travels (variants, positions): its range,
    NaN where it does not move (or has no value)."""
    high, low = np.fmax.reduce(travel, axis=1), np.fmin.reduce(travel, axis=1)
    stroke = high - low
    reach = np.maximum(np.fmax.reduce(np.abs(travel), axis=1), 1e-300)
    return np.where(stroke > 1e-12 * reach, stroke, np.nan)


def swings(phi_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The swing [°] of each row of link angles (variants, positions) [°] and the angles
    turned (unwrapped); NaN where the link turns round, does not move or a value is
    missing."""
    turned = _unwrap(np.deg2rad(phi_deg))
    np.rad2deg(turned, out=turned)
    swing = turned.max(axis=1) - turned.min(axis=1)
    moves = np.isfinite(phi_deg).all(axis=1) & (swing > 1e-9) & (swing < 359.0)
    return np.where(moves, swing, np.nan), turned


def _unwrap(rows: np.ndarray) -> np.ndarray:
    """``np.unwrap(rows, axis=1)`` to the bit, in place (``rows``: the caller's own):
    where no step between neighbours reaches π, its corrections are all 0 and only its
    ``+ 0`` is left to do."""
    if rows.ndim != 2 or rows.shape[1] < 2:
        return np.unwrap(rows, axis=-1)
    step = np.diff(rows, axis=1)
    np.abs(step, out=step)
    if not (step < np.pi).all():  # (a NaN too: numpy's carries it on)
        return np.unwrap(rows, axis=1)
    rows[:, 1:] += 0.0
    return rows


def peaks(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The value of largest magnitude of each row (variants, positions), signed, and its
    position (NaN, 0 where a row has none)."""
    magnitude = np.abs(values)
    if np.isnan(np.add.reduce(magnitude, axis=None)):  # (a sum of magnitudes is NaN only
        magnitude[np.isnan(magnitude)] = -np.inf       # where one of them is)
    k = np.argmax(magnitude, axis=1)
    return np.take_along_axis(values, k[:, None], axis=1)[:, 0], k


def pivoted(mechanism, link: int) -> bool:
    """The link turns about a frame pivot (a rocker, or a crank that turns round)."""
    return any(isinstance(j, Revolute) and 1 in j.links and link in j.links
               for j in mechanism.joints)




class Stat(NamedTuple):
    """One figure of a sweep's summary."""

    value: Any
    """a plain number (SI; degrees or rpm where the name says so), a flag, a text, or
    None where it is not given"""
    unit: str
    where: dict[str, float] | None
    """where it occurs (``{"angle_deg": 37.0}``), None for a figure of the whole sweep"""
    description: str


FIXED = {
    "positions": ("-", "crank positions reported"),
    "M_drive_max": ("N·m", "drive torque max"),
    "M_drive_min": ("N·m", "drive torque min"),
    "M_drive_rms": ("N·m", "drive torque RMS"),
    "M_drive_abs_max": ("N·m", "drive torque max |M_drive|"),
    "P_drive_mean": ("W", "mean drive power"),
    "F_shake_max": ("N", "shaking force max |F_S|"),
    "F_cam_min": ("N", "cam contact force min (below 0: lifts off)"),
    "F_cam_max": ("N", "cam contact force max"),
    "F_shake_rms": ("N", "shaking force RMS"),
    "M_shake_abs_max": ("N·m", "shaking moment max |M_S|"),
    "P_friction_mean": ("W", "mean friction power"),
    "friction_residual_max": ("-", "worst final residual of the friction solution"),
    "motion_state": ("-", "crank motion from the equation of motion"),
    "motor": ("-", "motor"),
    "J_F": ("kg·m²", "flywheel J_F"),
    "J_red_mean": ("kg·m²", "mean reduced inertia"),
    "speed_mean_rpm": ("rpm", "mean speed 2π/T"),
    "speed_min_rpm": ("rpm", "lowest speed"),
    "speed_max_rpm": ("rpm", "highest speed"),
    "fluctuation": ("-", "speed fluctuation δ"),
    "period": ("s", "period T"),
    "M_motor_mean": ("N·m", "mean motor torque"),
    "M_motor": ("N·m", "constant motor torque"),
    "steps_per_revolution": ("-", "integration steps per revolution"),
    "friction_passes": ("-", "passes of the friction torque"),
    "shooting_iterations": ("-", "shooting iterations"),
    "revolutions": ("-", "revolutions of the run-up"),
    "settled": ("-", "the run-up repeats (periodic)"),
    "duration": ("s", "run-up time"),
    "W_motor": ("J", "motor work"),
    "W_load": ("J", "work on the loads"),
    "W_friction": ("J", "friction work"),
    "E_kinetic": ("J", "kinetic energy"),
}
"""figures of fixed name -> (unit, description)"""

PATTERNS = (
    (r"mu_(\d+)_min_deg", "°", "smallest transmission angle, dyad {0}"),
    (r"stroke_(\d+)_(\d+)", "m", "stroke of slider ({0},{1})"),
    (r"time_ratio_(\d+)_(\d+)", "-", "  time ratio ({0},{1})"),
    (r"swing_(\d+)_deg", "°", "swing of link {0}"),
    (r"time_ratio_(\d+)", "-", "  time ratio (link {0})"),
    (r"(FN?)_(\d+)_(\d+)_peak", "N", "peak force {0}_{1}_{2}"),
    (r"locks_(\d+)_(\d+)", "-", "self-locking, joint ({0},{1})"),
    (r"lock_positions_(\d+)_(\d+)", "-", "self-locking positions, joint ({0},{1})"),
    (r"lock_start_(\d+)_(\d+)_deg", "°", "first self-locking angle, joint ({0},{1})"),
    (r"lock_stop_(\d+)_(\d+)_deg", "°", "last self-locking angle, joint ({0},{1})"),
    (r"impacts_(\d+)_(\d+)", "1/rev", "clearance impacts, joint ({0},{1})"),
    (r"F_clearance_(\d+)_(\d+)_max", "N", "largest clearance peak, joint ({0},{1})"),
    (r"amplification_(\d+)_(\d+)_max", "-", "largest clearance amplification, joint ({0},{1})"),
    (r"F_clearance_(\d+)_(\d+)_r(\d+)", "N", "clearance peak {2}, joint ({0},{1})"),
    (r"F_rigid_(\d+)_(\d+)_r(\d+)", "N", "rigid force at clearance peak {2}, joint ({0},{1})"),
    (r"tau_(\d+)_(\d+)_r(\d+)", "-", "τ of clearance peak {2}, joint ({0},{1})"),
    (r"amplification_(\d+)_(\d+)_r(\d+)", "-", "amplification of clearance peak {2}, "
                                               "joint ({0},{1})"),
)
"""figures named by joint, dyad or link -> (unit, description)"""

CYCLE = ("M_drive_rms", "P_drive_mean", "F_shake_rms", "P_friction_mean")
"""figures over the crank cycle (means, RMS): not of single positions (``sweep=False``)"""


def unit(name: str, columns: Mapping | None = None) -> str:
    """The unit of a summary figure by its name; the extremes ``<column>_min`` and
    ``<column>_max`` have their column's unit (``columns``: the names of the columns,
    else any name not known otherwise is taken for an extreme)."""
    return _known(name, columns)[0]


def description(name: str, columns: Mapping | None = None) -> str:
    """What a summary figure is, in a few words (a table's "quantity")."""
    return _known(name, columns)[1]


def _known(name: str, columns: Mapping | None) -> tuple[str, str]:
    if name in FIXED:
        return FIXED[name]
    for pattern, unit_, text in PATTERNS:
        match = re.fullmatch(pattern, name)
        if match:
            return unit_, text.format(*match.groups())
    column, _, which = name.rpartition("_")
    if which in ("min", "max") and (columns is None or column in columns):
        return unit_of(column) or "-", f"{'least' if which == 'min' else 'largest'} {column}"
    return "-", name


def key_figures(mechanism, angle_deg: np.ndarray, cols: Mapping[str, np.ndarray],
                forces: bool, presence: dict[str, str] | None = None,
                at: dict[str, np.ndarray] | None = None) -> dict[str, np.ndarray]:
    """The key figures of the kinematics and the forces of variants of ``mechanism``
    (columns of (variants, positions), all at the crank angles ``angle_deg``), each a
    (variants,) array: the smallest transmission angle per dyad, stroke and time ratio
    per slider, swing and time ratio per rocker; with ``forces`` the drive torque's
    peak, trough and RMS, the mean drive power, each joint's peak force, the shaking
    force's peak and RMS and the shaking moment's largest magnitude. One sweep is one
    variant (``figures``); a study's variants are many (a run of variants of the pipeline,
    ``dyade.linkage.pipeline.prepare_variants``).

    A figure no variant has (a slider that never moves) is left out; NaN for a variant
    without it. ``presence`` (filled if given): the figures a variant has only where it
    has a value, each -> the figure whose value decides (a time ratio goes with its
    stroke or swing). ``at`` (filled if given): figure -> (variants,) the position
    where it occurs, for the figures of one position."""
    out: dict[str, np.ndarray] = {}

    def each(rows: list[np.ndarray], function) -> list:
        """``function`` of the rows of each of several (variants, positions) arrays (it
        works row by row: one call per array, without copying them into one)."""
        out = []
        for array in rows:
            results = function(array)
            out.append(results if isinstance(results, tuple) else (results,))
        return out

    presence = {} if presence is None else presence

    def given(name: str, values: np.ndarray, where: np.ndarray | None = None) -> bool:
        if np.isnan(values).all():
            return False
        out[name] = values
        presence[name] = name
        if at is not None and where is not None:
            at[name] = where
        return True

    for dyad, (least, where) in zip(mechanism.dyads, each(
            [cols[f"mu_{dyad.number}_deg"] for dyad in mechanism.dyads], least_transmission)):
        given(f"mu_{dyad.number}_min_deg", least, where)
    sliders = ["{}_{}".format(*joint.name) for joint in mechanism.joints
               if not isinstance(joint, Revolute)]
    rockers = [link for link in mechanism.moving_links[1:] if pivoted(mechanism, link)]
    stroke_rows = each([cols[f"s_{tag}"] for tag in sliders], strokes)
    swing_rows = each([cols[f"phi_{link}_deg"] for link in rockers], swings)
    outputs = [cols[f"s_{tag}"] for tag in sliders] + [turned for _, turned in swing_rows]
    ratios = each(outputs, lambda rows: time_ratios(angle_deg, rows))
    for tag, (stroke,), (ratio,) in zip(sliders, stroke_rows, ratios):
        if given(f"stroke_{tag}", stroke):
            out[f"time_ratio_{tag}"] = np.where(np.isnan(stroke), np.nan, ratio)
            presence[f"time_ratio_{tag}"] = f"stroke_{tag}"
    for link, (swing, _), (ratio,) in zip(rockers, swing_rows, ratios[len(sliders):]):
        if given(f"swing_{link}_deg", swing):
            out[f"time_ratio_{link}"] = np.where(np.isnan(swing), np.nan, ratio)
            presence[f"time_ratio_{link}"] = f"swing_{link}_deg"
    if not forces:
        return out
    radians = np.deg2rad(angle_deg)
    torque = cols["M_drive"]
    force = magnitude(cols["Fx_shake"], cols["Fy_shake"])
    moment = np.abs(cols["M_shake"])
    (rms,), (shake_rms,) = each([torque, force], lambda rows: cycle.rmss(radians, rows))
    out.update(M_drive_max=np.fmax.reduce(torque, axis=1),
               M_drive_min=np.fmin.reduce(torque, axis=1), M_drive_rms=rms,
               M_drive_abs_max=np.fmax.reduce(np.abs(torque), axis=1),  # peak |M_drive|
               P_drive_mean=cycle.means(radians, cols["P_drive"]))
    names = joint_force_names(mechanism)
    for name, (peak, where) in zip(names, each([cols[name] for name in names], peaks)):
        given(f"{name}_peak", peak, where)
    out.update(F_shake_max=np.fmax.reduce(force, axis=1), F_shake_rms=shake_rms,
               M_shake_abs_max=np.fmax.reduce(moment, axis=1))
    if "F_cam" in cols:  # a cam drives link 2: its contact force's least (lift-off) and peak
        contact = cols["F_cam"]
        given("F_cam_min", np.fmin.reduce(contact, axis=1),
              np.argmin(np.where(np.isnan(contact), np.inf, contact), axis=1))
        given("F_cam_max", np.fmax.reduce(contact, axis=1), _largest(contact))
    if at is not None:
        low = np.where(np.isnan(torque), np.inf, torque)
        at.update(M_drive_max=_largest(torque), M_drive_min=np.argmin(low, axis=1),
                  M_drive_abs_max=_largest(np.abs(torque)),
                  F_shake_max=_largest(force), M_shake_abs_max=_largest(moment))
    return out


def _largest(values: np.ndarray) -> np.ndarray:
    """The first position of each row's largest value (NaN left aside)."""
    return np.argmax(np.where(np.isnan(values), -np.inf, values), axis=1)


class Rows(Mapping):
    """The columns of one sweep as (1, positions) rows, each read when asked (a
    ``Spool`` reads a column from disk)."""

    def __init__(self, cols: Mapping[str, np.ndarray]) -> None:
        self.cols = cols

    def __getitem__(self, name: str) -> np.ndarray:
        return np.asarray(self.cols[name])[None, :]

    def __iter__(self):
        return iter(self.cols)

    def __len__(self) -> int:
        return len(self.cols)


def figures(result: Outcome, cols: Mapping[str, np.ndarray],
            extremes: bool | Iterable[str] = True, sweep: bool = True) -> dict[str, Stat]:
    """The summary of a sweep: name -> ``Stat`` (value, unit, where, description).

    ``result`` is the sweep's outcome (its verdicts: forces given, friction,
    self-locking, the crank's motion, the clearance check), ``cols`` its columns (any
    mapping: a ``Spool`` reads each from disk once). The key figures (``key_figures``),
    then those of the stages the sweep ran (``stage_figures``), then with
    ``extremes`` the least and largest value of every column (or of the columns it
    names) and where (``<column>_min``, ``<column>_max``). ``sweep``: the positions are a sweep; single
    positions (``crank_angle_deg``) have no means over the cycle (``CYCLE``) and no
    time ratios. Where a figure occurs is the crank angle of a position of the sweep,
    rounded to its resolution (``arrays.resolution``: 359.5, not
    359.50000000000006)."""
    angle = np.asarray(cols["angle_deg"])
    places = np.round(angle, resolution(angle))
    names = frozenset(cols)
    out: dict[str, Stat] = {}

    def add(name: str, value: Any, where: dict | None = None) -> None:
        out[name] = stat(name, value, where, names)

    add("positions", int(angle.size))
    at: dict[str, np.ndarray] = {}
    values = key_figures(result.mechanism, angle, Rows(cols), result.forces_valid is not None,
                         at=at)
    for name, value in values.items():
        if not sweep and (name in CYCLE or name.startswith("time_ratio_")):
            continue
        add(name, float(value[0]), {"angle_deg": float(places[at[name][0]])} if name in at
            else None)
    out.update(stage_figures(result, cols, places, sweep))
    if extremes:
        for name in cols if extremes is True else extremes:
            if name == "angle_deg":
                continue
            low, high = extreme(places, cols[name])
            for which, (value, where) in (("min", low), ("max", high)):
                if f"{name}_{which}" not in out:
                    add(f"{name}_{which}", value, where)
    return out


def stat(name: str, value: Any, where: dict | None = None,
         columns: frozenset[str] | None = None) -> Stat:
    """A figure with its unit and description (``unit``, ``description``); a NaN value
    is not given (None, and nowhere)."""
    if isinstance(value, float) and math.isnan(value):
        value, where = None, None
    unit_, text = _known(name, columns)
    return Stat(value, unit_, where, text)


def extreme(places: np.ndarray, values: np.ndarray) -> tuple[tuple, tuple]:
    """((least, where), (largest, where)) of a column, NaN left aside: ``where`` the
    first crank angle (of ``places``) where it lies; (None, None) each where no value is
    given."""
    values = np.asarray(values)
    finite = np.isfinite(values)
    if not finite.any():
        return (None, None), (None, None)
    masked = np.where(finite, values, np.nan)
    lo, hi = int(np.nanargmin(masked)), int(np.nanargmax(masked))
    return ((float(values[lo]), {"angle_deg": float(places[lo])}),
            (float(values[hi]), {"angle_deg": float(places[hi])}))


def summary(result: Outcome, cols: Columns, extremes: bool = True) -> dict[str, Any]:
    """The summary's values by name (``figures`` without units and places): plain
    Python numbers, flags and texts, None where a figure is not given."""
    return {name: stat.value for name, stat in figures(result, cols, extremes).items()}


def stage_figures(result: Outcome, cols: Mapping[str, np.ndarray], places: np.ndarray,
                  sweep: bool = True) -> dict[str, Stat]:
    """The figures of the stages beyond the kinematics and the forces, where the sweep
    ran them: friction (its mean power, passes, worst residual), self-locking (per
    joint: whether, at how many positions, from where to where, the least margin of a
    slider), the crank's motion from the equation of motion, the clearance check (per
    joint: impacts, the largest peak and amplification, each peak)."""
    names = frozenset(cols)
    out: dict[str, Stat] = {}

    def add(name: str, value: Any, where: dict | None = None) -> None:
        out[name] = stat(name, value, where, names)

    radians = np.deg2rad(np.asarray(cols["angle_deg"]))
    if result.rubbing is not None:
        rows = result.rows & result.forces_valid
        if sweep:
            add("P_friction_mean", cycle.mean(radians, cols["P_friction"]))
        low, high = extreme(places, cols["friction_iterations"])
        add("friction_iterations_min", *low)
        add("friction_iterations_max", *high)
        add("friction_residual_max", float(np.max(result.rubbing.residual[rows], initial=0.0)))
    for (a, b), lock in (result.locking or {}).items():
        tag = f"{a}_{b}"
        angles = np.round(np.rad2deg(result.crank_angle[lock.locks & result.rows]),
                          resolution(np.asarray(cols["angle_deg"])))
        add(f"locks_{tag}", bool(lock.locks[result.rows].any()))
        add(f"lock_positions_{tag}", int(angles.size))
        add(f"lock_start_{tag}_deg", float(angles[0]) if angles.size else None)
        add(f"lock_stop_{tag}_deg", float(angles[-1]) if angles.size else None)
        if f"lock_margin_{tag}" in names:
            add(f"lock_margin_{tag}_min", *extreme(places, cols[f"lock_margin_{tag}"])[0])
    if result.drive is not None:
        for name, value in motion_figures(result).items():
            if isinstance(value, tuple):
                add(name, *value)
            else:
                add(name, value)
    for check in result.clearance or ():
        tag = "{}_{}".format(*check.joint)
        if not check.applies:  # (a note says why)
            for name in (f"F_clearance_{tag}_max", f"amplification_{tag}_max"):
                unit_, text = _known(name, None)
                out[name] = Stat(None, unit_, None, f"{text}: the model does not apply")
            continue
        add(f"impacts_{tag}", len(check.reversals))
        reversals = [(float(np.rad2deg(r.crank_angle)), r) for r in check.reversals]
        for name, value in ((f"F_clearance_{tag}_max", lambda r: r.peak.force),
                            (f"amplification_{tag}_max", lambda r: r.amplification)):
            if reversals:
                where, top = max(reversals, key=lambda pair: value(pair[1]))
                add(name, float(value(top)), {"angle_deg": where})
            else:
                add(name, None)
        for k, (where, r) in enumerate(reversals, start=1):
            place = {"angle_deg": where}
            add(f"F_clearance_{tag}_r{k}", float(r.peak.force), place)
            add(f"tau_{tag}_r{k}", float(r.peak.tau), place)
            add(f"F_rigid_{tag}_r{k}", float(r.rigid_force), place)
            add(f"amplification_{tag}_r{k}", float(r.amplification), place)
    return out


def motion_figures(result: Outcome) -> dict[str, Any]:
    """The crank's speed from the equation of motion (over the last revolution of a
    run-up): name -> value, or (value, where)."""
    motion = result.drive
    figures_ = motion.figures
    drive = result.mechanism.drive
    rpm = RAD_PER_S_TO_RPM
    out: dict[str, Any] = {
        "motion_state": motion.state, "motor": drive.motor.describe(),
        "J_F": float(drive.flywheel_inertia), "J_red_mean": float(figures_["inertia_mean"]),
        "speed_mean_rpm": float(figures_["speed_mean"]) * rpm,
        "speed_min_rpm": (float(figures_["speed_min"]) * rpm,
                          {"angle_deg": float(np.rad2deg(figures_["angle_min"]))}),
        "speed_max_rpm": (float(figures_["speed_max"]) * rpm,
                          {"angle_deg": float(np.rad2deg(figures_["angle_max"]))}),
        "fluctuation": float(figures_["fluctuation"]), "period": float(figures_["period"]),
        "M_motor_mean": float(figures_["motor_torque_mean"]),
        "steps_per_revolution": int(figures_["steps_per_revolution"]),
        "friction_passes": int(figures_["passes"])}
    if "motor_torque" in figures_:
        out["M_motor"] = float(figures_["motor_torque"])
    if motion.state == "run-up":
        out.update(revolutions=int(figures_["revolutions"]), settled=bool(figures_["settled"]),
                   duration=float(figures_["duration"]), W_motor=float(figures_["work_motor"]),
                   W_load=float(figures_["work_load"]),
                   W_friction=float(figures_["work_friction"]),
                   E_kinetic=float(figures_["kinetic_energy"]))
    else:
        out["shooting_iterations"] = int(figures_["iterations"])
    return out


MOTION_RENAMED = {"state": "motion_state", "motor": "motor", "flywheel_inertia": "J_F",
                  "inertia_mean": "J_red_mean", "speed_mean": "speed_mean_rpm",
                  "speed_mean_rpm": "speed_mean_rpm", "speed_min": "speed_min_rpm",
                  "speed_max": "speed_max_rpm", "speed_min_at_deg": "speed_min_rpm",
                  "speed_max_at_deg": "speed_max_rpm", "fluctuation": "fluctuation",
                  "period": "period", "motor_torque_mean": "M_motor_mean",
                  "motor_torque": "M_motor", "steps_per_revolution": "steps_per_revolution",
                  "friction_passes": "friction_passes",
                  "shooting_iterations": "shooting_iterations", "revolutions": "revolutions",
                  "settled": "settled", "duration": "duration", "work_motor": "W_motor",
                  "work_load": "W_load", "work_friction": "W_friction",
                  "kinetic_energy": "E_kinetic"}
"""the keys of the summary's former ``motion`` table -> the figures (speeds now in rpm;
an ``_at_deg`` key is the figure's ``where``)"""

RENAMED = (
    (r"drive\.M_max", "M_drive_max"), (r"drive\.M_min", "M_drive_min"),
    (r"drive\.M_rms", "M_drive_rms"), (r"drive\.P_mean", "P_drive_mean"),
    (r"joint_peaks\.(FN?_\d+_\d+)(\.value|\.at_deg)?", "{0}_peak"),
    (r"transmission\.(\d+)(\.min_deg|\.at_deg)?", "mu_{0}_min_deg"),
    (r"strokes\.(\d+_\d+)(\.stroke)?", "stroke_{0}"),
    (r"strokes\.(\d+_\d+)\.time_ratio", "time_ratio_{0}"),
    (r"swings\.(\d+)(\.swing_deg)?", "swing_{0}_deg"),
    (r"swings\.(\d+)\.time_ratio", "time_ratio_{0}"),
    (r"friction\.P_mean", "P_friction_mean"),
    (r"friction\.iterations_(min|max)", "friction_iterations_{0}"),
    (r"friction\.worst_residual", "friction_residual_max"),
    (r"self_locking\.(\d+_\d+)(\.locks)?", "locks_{0}"),
    (r"self_locking\.(\d+_\d+)\.locking_angles_deg", "lock_start_{0}_deg"),
    (r"columns\.(\w+)\.(min|max)(_at_deg)?", "{0}_{1}"),
)
"""a key of the former nested summary (``drive.M_max``, ``joint_peaks[F_1_2].value``,
``transmission[2].min_deg``) -> the figure's name now (``renamed``; the table of
docs/reference/json.md)"""


def renamed(name: str) -> str | None:
    """The figure's name now of a key path of the summary before issue 36 (the former
    nested summary, written with dots or brackets), None for any other name.

    >>> renamed("drive.M_max"), renamed("joint_peaks[F_1_2].value"), renamed("mu_2_min_deg")
    ('M_drive_max', 'F_1_2_peak', None)
    """
    path = re.sub(r"\[(\w+)\]", r".\1", name.strip()).strip(".")
    if path.startswith("motion."):
        return MOTION_RENAMED.get(path[len("motion."):])
    for pattern, new in RENAMED:
        match = re.fullmatch(pattern, path)
        if match:
            return new.format(*match.groups())
    return None


def joint_force_names(mechanism) -> list[str]:
    """The column of each joint's force: F_a_b of a revolute joint, FN_a_b (the normal
    force) of a prismatic one."""
    return [f"F_{a}_{b}" if isinstance(j, Revolute) else f"FN_{a}_{b}"
            for j in mechanism.joints for a, b in (j.name,)]


