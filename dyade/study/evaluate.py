"""The study's variants: each one's mechanism file with the study's overrides, swept by
``dyade.analyse`` and its summary flattened to named key results (``key_results``), or
a block of them read at once and run together through the same sweep pipeline as
variants × positions (``Evaluator``, ``dyade.linkage.pipeline.prepare_variants``), their
key results by the same functions
(``dyade.linkage.summary.key_figures``): a study's outputs are the summary's figures,
of the same names and values.

A variant that cannot be built (the reader refuses a value), does not close over the
sweep (``AssemblyError``) or fails otherwise is a row with its status and reason and no
outputs; a variant that self-locks is a row with its outputs and the status "locks".
"""

from __future__ import annotations

import copy
import math
import re
from typing import Any

import numpy as np

from dyade.analyses.cam import STUDY_OUTPUTS as CAM_OUTPUTS
from dyade.analyses.servo import STUDY_OUTPUTS as SERVO_OUTPUTS
from dyade.analyses.servo import study_outputs as servo_outputs
from dyade.units import RAD_PER_S_TO_RPM

EXTRA_UNITS = {"flywheel_inertia": "kg·m²", "omega_bar": "rad/s",
               "resonance_speed_rpm": "rpm", "speed_ratio": "-"}
"""units of the outputs ``[outputs] extra`` adds; the others are summary figures
(``dyade.linkage.summary.unit``)"""
EXTRA_UNITS.update(SERVO_OUTPUTS)  # [outputs] extra = ["servo"] (dyade.analyses.servo)
EXTRA_UNITS.update(CAM_OUTPUTS)  # a cam file's study (dyade.study.cam)

OK, LOCKS, OPEN, REFUSED, FAILED = "ok", "locks", "does not close", "refused", "failed"
WITHHELD = "withheld"
"""a variant whose every position is withheld (values beyond what a machine has): no
outputs, never a row of zeros"""
STATUSES = (OK, LOCKS, OPEN, REFUSED, FAILED, WITHHELD)

RENAMED = {"M_shake_max": "M_shake_abs_max"}
"""outputs of a study that were renamed when they became summary figures (issue 36):
old -> new (``dyade.study.spec`` refuses the old, naming the new)"""


def unit(name: str) -> str:
    """The unit of an output column (SI; angles in degrees, speeds in rpm where the name
    says so): a summary figure's (``dyade.linkage.summary.unit``), or an extra's."""
    from dyade.linkage.summary import unit as figure_unit

    return EXTRA_UNITS.get(name) or figure_unit(name)


STUDIED = re.compile(r"mu_\d+_min_deg|stroke_\d+_\d+|time_ratio_\d+(_\d+)?|swing_\d+_deg"
                     r"|M_drive_(max|min|rms|abs_max)|P_drive_mean|FN?_\d+_\d+_peak|F_shake_(max|rms)"
                     r"|M_shake_abs_max|F_cam_(min|max)|P_friction_mean|locks_\d+_\d+"
                     r"|lock_(start|stop)_\d+_\d+_deg|lock_margin_\d+_\d+_min"
                     r"|speed_mean_rpm|fluctuation")
"""the summary figures a study's row gives (``dyade.linkage.summary``): the key figures
of the kinematics and forces, friction's power, self-locking, the crank's mean speed and
fluctuation; with ``[outputs] extra = ["clearance"]`` also ``CLEARANCE``"""
CLEARANCE = re.compile(r"(F_clearance|amplification)_\d+_\d+_max")


def outputs(figures: dict, extras: tuple[str, ...] = ()) -> dict[str, float]:
    """A study's outputs of one variant from its summary (name -> value, as
    ``dyade.linkage.summary.summary`` gives it): the figures a study gives
    (``STUDIED``; ``CLEARANCE`` with that extra), as floats (a flag 1.0 or 0.0, NaN
    where a figure is not given). The names and values are the summary's."""
    clearance = "clearance" in extras
    return {name: math.nan if value is None else float(value)
            for name, value in figures.items()
            if STUDIED.fullmatch(name) or clearance and CLEARANCE.fullmatch(name)}


def key_results(result, extras: tuple[str, ...] = (), fluctuation: float = 0.02
                ) -> dict[str, float]:
    """The key results of a sweep (a ``dyade.Result``) as named numbers: its summary's
    figures (``dyade.linkage.summary.summary``, without the columns' extremes) that a
    study gives (``outputs``: drive torque and power, joint peaks, smallest
    transmission angles, strokes, swings and time ratios, the shaking force and moment,
    friction power, self-locking; with a [drive] the mean speed and its fluctuation;
    with the extra ``clearance`` the largest peak force and amplification per
    clearance joint), and ``extras`` (``flywheel``: the inertia for ``fluctuation``;
    ``coupling``: the elastic drive line's lowest natural frequency ω̄ with the
    linkage's mean reduced inertia, the crank speed of its first-order resonance
    Ω = ω̄ and the operating speed's ratio Ω/ω̄ of VDI 2149). NaN where the summary
    gives no value (a time ratio of an output that does not swing once)."""
    from dyade.linkage.summary import summary

    out = outputs(summary(result, result.columns(), extremes=False), extras)
    if "flywheel" in extras and result.forces_valid is not None:
        from dyade.linkage.machine_curve import torque_curve
        from dyade.machine.flywheel import size_flywheel

        out["flywheel_inertia"] = size_flywheel(torque_curve(result.mechanism),
                                                fluctuation).flywheel
    if "coupling" in extras:  # the elastic drive line's resonance (``[drive_line]``)
        from dyade.linkage.drive import natural_frequency

        line = natural_frequency(result.mechanism)
        out.update(omega_bar=line.omega_bar, resonance_speed_rpm=line.omega_bar * RAD_PER_S_TO_RPM,
                   speed_ratio=line.ratio)
    if "servo" in extras:  # the servo motor's sizing over the cycle (``[servo]``)
        out.update(servo_outputs(result.mechanism))
    return {name: math.nan if value is None else float(value) for name, value in out.items()}


def status_of(values: dict[str, float]) -> str:
    """"locks" where any joint self-locks, else "ok"."""
    return LOCKS if any(v == 1.0 for k, v in values.items() if k.startswith("locks_")) else OK


STACK = 120
"""variants run together through the pipeline (``pipeline.prepare_variants``): 43 320
positions of a four-bar"""


class Evaluator:
    """The study's variants: ``evaluator(block)`` for a block of (variant number,
    values) gives one row per variant (a class, not a closure: it pickles for the
    processes of any executor).

    A block is read at once and run through the sweep pipeline ``STACK`` variants at a
    time, where the plan allows (``pipeline.stackable``: no friction, [drive] or
    [drive_line]; no extra outputs; parameters that are numbers of the file): the file
    read once with ``Variants`` at the parameters' key paths (checked against its own
    reading of the first and the last variant, of the last once a block has passed),
    the variants × positions one run of the pipeline, whose validity policy, bands and
    plausibility check decide per variant as in a sweep of each alone (a variant that
    does not close: its row says why), the key results by the summary's own functions
    over (variants, positions) (``dyade.linkage.summary.key_figures``). A variant the
    reader refuses, and every block that cannot be stacked, is evaluated alone
    (``one``: ``dyade.analyse``, the same pipeline for one variant)."""

    def __init__(self, path: str, data: dict[str, Any], keys: tuple[str, ...],
                 extras: tuple[str, ...] = (), fluctuation: float = 0.02,
                 choices: dict[str, tuple[str, ...]] | None = None) -> None:
        self.path, self.data, self.keys = path, data, keys
        self.choices = choices or {}
        """key -> the names of a categorical parameter, whose values are their indices"""
        self.label = path.rsplit("/", 1)[-1]
        """the file's name, in messages"""
        self.extras, self.fluctuation = extras, fluctuation
        self.calls = 0
        """variants evaluated by this object (in this process)"""
        self.together = 0
        """of these, variants evaluated in a stacked sweep"""
        self.stacks = not extras and not self.choices and not any(_whole(key) for key in keys)
        """whether blocks are worth stacking (cleared on the first that cannot be)"""
        self.stages: bool | None = None
        """whether the file's stages can be stacked (None: not known yet)"""
        self.verified = False
        """a block read at once has been each of its variants' own reading"""

    def mechanism(self, values) -> Any:
        """The variant's mechanism: the file's data (with the study's fixed overrides)
        and ``values`` at the parameters' key paths, read as ``--set`` would."""
        from dyade.files.mechanism import NUMBERING, build, set_dotted

        data = copy.deepcopy(self.data)
        for key, value in zip(self.keys, values):
            value = float(value)
            if key in self.choices:  # a categorical parameter: the name of its index
                value = self.choices[key][int(round(value))]
                set_dotted(data, key, value, self.label, "parameter", NUMBERING)
                continue
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
        if not np.any(result.valid[result.rows]):  # (issue 42) never a row of blanks as "ok"
            from dyade.analyses.machine import withholding

            why = withholding(result.notes)
            return WITHHELD, f"every position is withheld{f': {why}' if why else ''}", {}
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
        with their own reading; once a block has passed, the last only), or the
        variants' plans differ."""
        from dyade.arrays import Variants
        from dyade.errors import InputError
        from dyade.files.mechanism import NUMBERING, build, set_dotted
        from dyade.linkage.plan import plan
        from dyade.linkage.stack import same

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
            for index in (len(values) - 1,) if self.verified else (0, len(values) - 1):
                alone = self.mechanism(values[index])
                if same(together, alone, index=index) or plan(alone) != plan(together):
                    return None
        except (InputError, ValueError, TypeError):  # read variant by variant instead
            return None
        self.verified = True
        return together

    def stages_stack(self, values: np.ndarray) -> bool:
        """Whether the file's stages let variants be swept together (decided on the
        first variant that reads; ``pipeline.stackable``)."""
        from dyade.errors import InputError
        from dyade.linkage.pipeline import stackable
        from dyade.linkage.plan import plan

        if self.stages is None:
            for row in values:
                try:
                    self.stages = stackable(plan(self.mechanism(row)))
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

    def swept_together(self, values: np.ndarray, together=None, first: int = 0
                       ) -> dict[int, tuple[str, str, dict]]:
        """Variant (row of ``values``) -> its row, for every variant of one run of them
        all through the sweep pipeline (``pipeline.prepare_variants``: its validity
        policy, bands and plausibility decide per variant, as in a sweep of each alone);
        empty where the block is not stacked. The variants are read at once
        (``read_together``; ``together``: so read already, ``values`` its variants from
        ``first`` on), else one by one; a variant
        that does not close has the status "does not close" and the pipeline's
        reason."""
        from dyade.errors import DyadeError
        from dyade.linkage.pipeline import Run, prepare_variants
        from dyade.linkage.stack import spread
        from dyade.linkage.summary import key_figures

        if not self.stacks or len(values) < 2 or not self.stages_stack(values):
            return {}
        if together is None:
            together, first = self.read_together(values), 0
        if together is not None:
            read = list(range(len(values)))
            stacked = spread(together, together.sweep.count, first, first + len(values))
        else:
            read, stacked = self.read_each(values)
            if stacked is None:
                return {}
        try:
            setup = prepare_variants(stacked, len(read))
            run = Run(setup, setup.positions, points=False, machine=False)
            blocks = list(run)
        except (ValueError, TypeError):  # NotStackable, or a number the engine takes
            self.stacks = False          # as one: every block variant by variant
            return {}
        except DyadeError:  # (each variant alone says what)
            return {}
        count = setup.each
        rows: dict[int, tuple[str, str, dict]] = {
            read[variant]: (OPEN, str(err), {}) for variant, err in run.failed.items()}
        given = [variant for variant in range(len(read)) if variant not in run.failed]
        if given:
            cols = blocks[0].columns if len(blocks) == 1 else {
                name: np.concatenate([block.columns[name] for block in blocks])
                for name in blocks[0].columns}
            shaped = {name: values.reshape(len(given), count) for name, values in cols.items()
                      if name != "angle_deg"}
            presence: dict[str, str] = {}
            out = key_figures(stacked, np.rad2deg(setup.crank_angle[:count]), shaped,
                              setup.plan.kinetostatics, presence)
            names = list(out)
            table = np.column_stack([out[name] for name in names]).tolist() if names else \
                [[] for _ in given]
            # the figures a variant has only where it has a value (as alone): those rows
            # that lack one are filtered, the others taken whole
            lacks = np.zeros(len(given), dtype=bool)
            for name in presence:
                lacks |= np.isnan(out[presence[name]])
            locking = any(name.startswith("locks_") for name in names)
            valid = np.concatenate([block.valid[block.rows] for block in blocks])
            none_given = ~valid.reshape(len(given), count).any(axis=1)
            for variant, numbers, filtered, withheld in zip(given, table, lacks.tolist(),
                                                            none_given.tolist()):
                if withheld:  # (issue 42) never a row of blanks as "ok": as alone
                    from dyade.analyses.machine import withholding

                    why = withholding(run.notes[variant]) if run.notes else ""
                    rows[read[variant]] = (WITHHELD, "every position is withheld"
                                           f"{f': {why}' if why else ''}", {})
                    continue
                row = dict(zip(names, numbers))
                if filtered:
                    row = {name: value for name, value in row.items()
                           if name not in presence or not math.isnan(row[presence[name]])}
                rows[read[variant]] = (status_of(row) if locking else OK, "", row)
        self.calls += len(read)
        self.together += len(read)
        return rows

    def __call__(self, block: tuple[int, np.ndarray]) -> list[tuple[int, str, str, dict]]:
        first, values = block
        rows = []
        parts = -(-len(values) // STACK)  # as many sweeps as needed, of equal size
        together = None  # the whole block read at once (checked once)
        if parts > 1 and self.stacks and self.stages_stack(values):
            together = self.read_together(values)
        for indices in np.array_split(np.arange(len(values)), max(parts, 1)):
            start, part = int(indices[0]) if indices.size else 0, values[indices]
            done = self.swept_together(part, None if not indices.size else together, start)
            rows += [(first + start + i, *(done[i] if i in done else self.one(row)))
                     for i, row in enumerate(part)]
        return rows


def _whole(key: str) -> bool:
    """Keys that take whole numbers (a variant, a link number)."""
    return key.rsplit(".", 1)[-1] in ("variant", "link")
