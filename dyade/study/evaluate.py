"""The study's variants: each one's mechanism file with the study's overrides, swept by
``dyade.analyse`` and its summary flattened to named key results (``key_results``), or
a block of them read at once and swept together (``Evaluator``,
``dyade.linkage.variants``), their key results by the same functions (``figures``).

A variant that cannot be built (the reader refuses a value), does not close over the
sweep (``AssemblyError``) or fails otherwise is a row with its status and reason and no
outputs; a variant that self-locks is a row with its outputs and the status "locks".
"""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np

UNITS = {"M_drive_max": "N·m", "M_drive_min": "N·m", "M_drive_rms": "N·m", "P_drive_mean": "W",
         "P_friction_mean": "W", "F_shake_max": "N", "F_shake_rms": "N", "M_shake_max": "N·m",
         "flywheel_inertia": "kg·m²", "speed_mean_rpm": "rpm", "fluctuation": "-",
         "omega_bar": "rad/s", "resonance_speed_rpm": "rpm", "speed_ratio": "-"}
"""units of the outputs with fixed names; the others by their prefix (``unit``)"""

OK, LOCKS, OPEN, REFUSED, FAILED = "ok", "locks", "does not close", "refused", "failed"
STATUSES = (OK, LOCKS, OPEN, REFUSED, FAILED)


def unit(name: str) -> str:
    """The unit of an output column (SI; angles in degrees)."""
    if name in UNITS:
        return UNITS[name]
    if name.endswith("_deg"):
        return "deg"
    if name.startswith(("F_", "FN_")):
        return "N"
    if name.startswith("stroke_"):
        return "m"
    if name.startswith(("time_ratio_", "locks_", "lock_margin_", "amplification_")):
        return "-"
    return ""


def key_results(result, extras: tuple[str, ...] = (), fluctuation: float = 0.02
                ) -> dict[str, float]:
    """The key results of a sweep (a ``dyade.Result``) as named numbers: what ``analyse``'s
    summary gives (drive torque and power, joint peaks, smallest transmission angles,
    strokes, swings and time ratios, friction power, self-locking), the shaking force and
    moment (``figures`` of the one sweep), and ``extras`` (``flywheel``: the inertia for
    ``fluctuation``; ``clearance``: the peak force and amplification per clearance
    joint; ``coupling``: the elastic drive line's lowest natural frequency ω̄ with the
    linkage's mean reduced inertia, the crank speed of its first-order resonance
    Ω = ω̄ and the operating speed's ratio Ω/ω̄ of VDI 2149). NaN where the summary
    gives no value (a time ratio of an output that does not swing once)."""
    from dyade.linkage.summary import stage_figures

    cols = result.columns()
    rows = {name: values[None, :] for name, values in cols.items()}
    out = {name: float(values[0]) for name, values in figures(
        result.mechanism, cols["angle_deg"], rows, result.forces_valid is not None).items()}
    s = stage_figures(result, cols)
    if "friction" in s:
        out["P_friction_mean"] = s["friction"]["P_mean"]
    for joint, lock in s.get("self_locking", {}).items():
        out[f"locks_{joint}"] = 1.0 if lock["locks"] else 0.0
        angles = lock["locking_angles_deg"]
        out[f"lock_start_{joint}_deg"] = float(angles[0]) if len(angles) else math.nan
        out[f"lock_stop_{joint}_deg"] = float(angles[-1]) if len(angles) else math.nan
        margin = cols.get(f"lock_margin_{joint}")
        if margin is not None:
            out[f"lock_margin_{joint}_min"] = float(np.fmin.reduce(margin))
    if "motion" in s:
        out["speed_mean_rpm"] = s["motion"]["speed_mean_rpm"]
        out["fluctuation"] = s["motion"]["fluctuation"]
    if "flywheel" in extras and result.forces_valid is not None:
        from dyade.linkage.machine_curve import torque_curve
        from dyade.machine.flywheel import size_flywheel

        out["flywheel_inertia"] = size_flywheel(torque_curve(result.mechanism),
                                                fluctuation).flywheel
    if "coupling" in extras:  # the elastic drive line's resonance (``[drive_line]``)
        from dyade.linkage.drive import natural_frequency
        from dyade.units import RAD_PER_S_TO_RPM

        line = natural_frequency(result.mechanism)
        out.update(omega_bar=line.omega_bar, resonance_speed_rpm=line.omega_bar * RAD_PER_S_TO_RPM,
                   speed_ratio=line.ratio)
    if "clearance" in extras:
        for check in s.get("clearance", []):
            joint = check["joint"]
            peaks = [r["F_max"] for r in check["reversals"]]
            gains = [r["amplification"] for r in check["reversals"]]
            out[f"F_clearance_{joint}_max"] = max(peaks) if peaks else math.nan
            out[f"amplification_{joint}_max"] = max(gains) if gains else math.nan
    return {name: math.nan if value is None else float(value) for name, value in out.items()}


def figures(mechanism, angle_deg: np.ndarray, cols: dict[str, np.ndarray], forces: bool,
            presence: dict[str, str] | None = None) -> dict[str, np.ndarray]:
    """The key results of the kinematics and the forces of variants of ``mechanism``
    (columns of (variants, positions), all at the crank angles ``angle_deg``), each a
    (variants,) array, by the summary's own functions (``dyade.linkage.summary``): the
    smallest transmission angle per dyad, stroke and time ratio per slider, swing and
    time ratio per rocker; with ``forces`` the drive torque's peak, trough and RMS, the
    mean drive power, each joint's peak force, the shaking force's peak and RMS and the
    shaking moment's peak. A figure no variant has (a slider that never moves) is left
    out; NaN for a variant without it. ``presence`` (filled if given): the figures a
    variant has only where it has a value, each -> the figure whose value decides (a
    time ratio goes with its stroke or swing), as ``key_results`` of the variant alone
    gives them."""
    from dyade import cycle
    from dyade.linkage import summary as figures_
    from dyade.model.mechanism import Revolute

    out: dict[str, np.ndarray] = {}

    def each(rows: list[np.ndarray], function) -> list:
        """``function`` of the rows of several (variants, positions) arrays in one call
        (they share the crank angles): its results split again, one per array."""
        if not rows:
            return []
        count = rows[0].shape[0]
        results = function(np.concatenate(rows))
        results = results if isinstance(results, tuple) else (results,)
        return [tuple(r[k * count:(k + 1) * count] for r in results)
                for k in range(len(rows))]

    presence = {} if presence is None else presence

    def given(name: str, values: np.ndarray) -> bool:
        if np.isnan(values).all():
            return False
        out[name] = values
        presence[name] = name
        return True

    for dyad, (least, _) in zip(mechanism.dyads, each(
            [cols[f"mu_{dyad.number}_deg"] for dyad in mechanism.dyads],
            figures_.least_transmission)):
        given(f"mu_{dyad.number}_min_deg", least)
    sliders = ["{}_{}".format(*joint.name) for joint in mechanism.joints
               if not isinstance(joint, Revolute)]
    rockers = [link for link in mechanism.moving_links[1:] if figures_.pivoted(mechanism, link)]
    strokes = each([cols[f"s_{tag}"] for tag in sliders], figures_.strokes)
    swings = each([cols[f"phi_{link}_deg"] for link in rockers], figures_.swings)
    outputs = [cols[f"s_{tag}"] for tag in sliders] + [turned for _, turned in swings]
    ratios = each(outputs, lambda rows: figures_.time_ratios(angle_deg, rows))
    for tag, (stroke,), (ratio,) in zip(sliders, strokes, ratios):
        if given(f"stroke_{tag}", stroke):
            out[f"time_ratio_{tag}"] = np.where(np.isnan(stroke), np.nan, ratio)
            presence[f"time_ratio_{tag}"] = f"stroke_{tag}"
    for link, (swing, _), (ratio,) in zip(rockers, swings, ratios[len(sliders):]):
        if given(f"swing_{link}_deg", swing):
            out[f"time_ratio_{link}"] = np.where(np.isnan(swing), np.nan, ratio)
            presence[f"time_ratio_{link}"] = f"swing_{link}_deg"
    if not forces:
        return out
    radians = np.deg2rad(angle_deg)
    torque = cols["M_drive"]
    force = np.hypot(cols["Fx_shake"], cols["Fy_shake"])
    (rms,), (shake_rms,) = each([torque, force], lambda rows: cycle.rmss(radians, rows))
    out.update(M_drive_max=np.fmax.reduce(torque, axis=1),
               M_drive_min=np.fmin.reduce(torque, axis=1), M_drive_rms=rms,
               P_drive_mean=cycle.means(radians, cols["P_drive"]))
    names = figures_.joint_force_names(mechanism)
    for name, (peak, _) in zip(names, each([cols[name] for name in names], figures_.peaks)):
        given(f"{name}_peak", peak)
    out.update(F_shake_max=np.fmax.reduce(force, axis=1), F_shake_rms=shake_rms,
               M_shake_max=np.fmax.reduce(np.abs(cols["M_shake"]), axis=1))
    return out


def status_of(values: dict[str, float]) -> str:
    """"locks" where any joint self-locks, else "ok"."""
    return LOCKS if any(v == 1.0 for k, v in values.items() if k.startswith("locks_")) else OK


STACK = 120
"""variants swept together (``dyade.linkage.variants``): 43 320 positions of a four-bar,
its arrays in the cache"""


class Evaluator:
    """The study's variants: ``evaluator(block)`` for a block of (variant number,
    values) gives one row per variant (a class, not a closure: it pickles for the
    processes of any executor).

    A block is read and swept together, ``STACK`` variants at a time, where the plan
    allows (``dyade.linkage.variants``: no friction, [drive] or clearance data, no
    extra outputs, parameters that are numbers of the file): the file read once with
    ``Variants`` at the parameters' key paths (checked against the first and the last
    variant read alone), the variants × positions swept in one run, the key results
    by the summary's own functions over (variants, positions). Every variant that is
    not clean there (it does not close, comes near a dead centre, is refused, ...) and
    every block that cannot be stacked is evaluated alone (``one``)."""

    def __init__(self, path: str, data: dict[str, Any], keys: tuple[str, ...],
                 extras: tuple[str, ...] = (), fluctuation: float = 0.02) -> None:
        self.path, self.data, self.keys = path, data, keys
        self.label = path.rsplit("/", 1)[-1]
        """the file's name, in messages"""
        self.extras, self.fluctuation = extras, fluctuation
        self.calls = 0
        """variants evaluated by this object (in this process)"""
        self.together = 0
        """of these, variants evaluated in a stacked sweep"""
        self.stacks = not extras and not any(_whole(key) for key in keys)
        """whether blocks are worth stacking (cleared on the first that cannot be)"""
        self.stages: bool | None = None
        """whether the file's stages can be stacked (None: not known yet)"""

    def mechanism(self, values) -> Any:
        """The variant's mechanism: the file's data (with the study's fixed overrides)
        and ``values`` at the parameters' key paths, read as ``--set`` would."""
        from dyade.files.mechanism import NUMBERING, build, set_dotted

        data = copy.deepcopy(self.data)
        for key, value in zip(self.keys, values):
            value = float(value)
            set_dotted(data, key, int(value) if value.is_integer() and _whole(key) else value,
                       self.label, "parameter", NUMBERING)
        return build(data, self.path)

    def one(self, values) -> tuple[str, str, dict[str, float]]:
        """(status, reason, outputs) of one variant."""
        from dyade.errors import AssemblyError, DyadeError, InputError
        from dyade.linkage.sweep import analyse

        self.calls += 1
        try:
            mechanism = self.mechanism(values)
        except InputError as err:
            return REFUSED, str(err), {}
        try:
            result = analyse(mechanism)
        except AssemblyError as err:
            return OPEN, str(err), {}
        except DyadeError as err:
            return FAILED, str(err), {}
        out = key_results(result, self.extras, self.fluctuation)
        status = status_of(out)
        reason = ""
        if status == LOCKS:
            reason = "self-locks at " + ", ".join(
                f"joint ({k[6:].replace('_', ',')})" for k, v in out.items()
                if k.startswith("locks_") and v == 1.0)
        return status, reason, out

    def read_together(self, values: np.ndarray):
        """The block's variants (rows of ``values``) read at once: a mechanism with
        ``Variants`` where they differ; None where the reader cannot take them so (a
        value it checks in a way an array does not pass, a refused variant) or the
        result is not each variant's own mechanism (the first and the last compared
        with their own reading), or the variants' plans differ."""
        from dyade.arrays import Variants
        from dyade.errors import InputError
        from dyade.files.mechanism import NUMBERING, build, set_dotted
        from dyade.linkage.plan import plan
        from dyade.linkage.stack import pick, same

        data = copy.deepcopy(self.data)
        try:
            for key, column in zip(self.keys, values.T):
                set_dotted(data, key, Variants(column), self.label, "parameter", NUMBERING)
            together = build(data, self.path)
            dynamics = np.zeros(len(values), dtype=bool)  # masses that vanish in some
            for link in together.links.values():          # variants: plans that differ
                dynamics |= (np.asarray(link.mass) > 0.0) | (np.asarray(link.inertia) > 0.0)
            if dynamics.any() and not dynamics.all() and not (together.loads
                                                              or together.springs):
                return None
            for index in (0, len(values) - 1):
                alone = self.mechanism(values[index])
                if same(pick(together, index), alone) or plan(alone) != plan(together):
                    return None
        except (InputError, ValueError, TypeError):  # read variant by variant instead
            return None
        return together

    def stages_stack(self, values: np.ndarray) -> bool:
        """Whether the file's stages let variants be swept together (decided on the
        first variant that reads; ``variants.stackable``)."""
        from dyade.errors import InputError
        from dyade.linkage import variants
        from dyade.linkage.plan import plan

        if self.stages is None:
            for row in values:
                try:
                    self.stages = variants.stackable(plan(self.mechanism(row)))
                except InputError:
                    continue
                self.stacks = self.stacks and self.stages
                break
        return bool(self.stages)

    def read_each(self, values: np.ndarray) -> tuple[list[int], Any]:
        """The block's variants read one by one and stacked (``stack.stack``): (the
        variants read, their stacked mechanism), or ([], None) where fewer than two are
        read or they differ in more than numbers."""
        from dyade.errors import InputError
        from dyade.linkage.plan import plan
        from dyade.linkage.stack import NotStackable, stack

        read, mechanisms = [], []
        for index, row in enumerate(values):
            try:
                mechanisms.append(self.mechanism(row))
            except InputError:  # refused: its own evaluation says why
                continue
            read.append(index)
        if len(read) < 2 or len({plan(m) for m in mechanisms}) > 1:
            return [], None  # (variants whose stages differ are swept each alone)
        try:
            return read, stack(mechanisms, mechanisms[0].sweep.count)
        except NotStackable:
            return [], None

    def swept_together(self, values: np.ndarray) -> dict[int, tuple[str, str, dict]]:
        """Variant (row of ``values``) -> its row, for the clean variants of one sweep of
        them all (``dyade.linkage.variants``); empty where the block is not stacked.
        The variants are read at once (``read_together``), else one by one."""
        from dyade.linkage import variants
        from dyade.linkage.stack import spread

        if not self.stacks or len(values) < 2 or not self.stages_stack(values):
            return {}
        together = self.read_together(values)
        if together is not None:
            read, stacked = list(range(len(values))), spread(together, together.sweep.count)
        else:
            read, stacked = self.read_each(values)
            if stacked is None:
                return {}
        try:
            swept = variants.sweep(stacked, len(read))
        except (ValueError, TypeError):  # NotStackable, or a number the engine takes
            self.stacks = False          # as one: every block variant by variant
            return {}
        presence: dict[str, str] = {}
        out = figures(stacked, swept.angle_deg, swept.columns, swept.forces, presence)
        clean = np.flatnonzero(swept.clean)
        self.calls += clean.size
        self.together += clean.size
        names = list(out)
        table = np.column_stack([out[name][clean] for name in names]).tolist()
        rows = {}
        for i, numbers in zip(clean.tolist(), table):
            row = dict(zip(names, numbers))  # the figures this variant has, as alone
            row = {name: value for name, value in row.items()
                   if name not in presence or not math.isnan(row[presence[name]])}
            rows[read[i]] = (status_of(row), "", row)
        return rows

    def __call__(self, block: tuple[int, np.ndarray]) -> list[tuple[int, str, str, dict]]:
        first, values = block
        rows = []
        parts = -(-len(values) // STACK)  # as many sweeps as needed, of equal size
        for indices in np.array_split(np.arange(len(values)), max(parts, 1)):
            start, part = int(indices[0]) if indices.size else 0, values[indices]
            done = self.swept_together(part)
            rows += [(first + start + i, *(done[i] if i in done else self.one(row)))
                     for i, row in enumerate(part)]
        return rows


def _whole(key: str) -> bool:
    """Keys that take whole numbers (a variant, a link number)."""
    return key.rsplit(".", 1)[-1] in ("variant", "link")
