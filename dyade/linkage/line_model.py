"""The linkage as the crank shaft of an elastic drive line: the line of a mechanism's
``[drive_line]`` table, the crank shaft's tables J(φ), dJ/du, M_L on the integration
grid, and the natural frequency with the VDI 2149 check (what ``dyade analyse`` notes;
``dyade.linkage.drive_line`` builds the rest on it)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from dyade.errors import InputError
from dyade.linkage.drive import machine_tables
from dyade.linkage.model import FloatArray, Mechanism
from dyade.machine import drive_line as engine

VDI_2149_RATIO = 0.1  # [-] largest Ω/ω̄ for which the rigid model holds (VDI 2149 Part 1)


def line_data(mechanism: Mechanism):
    if mechanism.drive_line is None:
        raise InputError(f"{mechanism.name}: no [drive_line] table: give the elastic element "
                         f"between motor and crank (`drive_line.stiffness` [N·m/rad], or "
                         f"`drive_line.coupling` = a coupling file), see docs/guide/drive-line.md.",
                         key="drive_line")
    return mechanism.drive_line


def line_of(mechanism: Mechanism, *, ideal: bool = False) -> engine.Line:
    """The drive line of ``mechanism``: its ``[drive]`` motor (or an ideal motor when the
    file has none, or with ``ideal``)."""
    data = line_data(mechanism)
    motor = None if ideal or mechanism.drive is None else mechanism.drive.motor
    return engine.line_from(data, motor)


def crank_tables(mechanism: Mechanism, steps: int) -> engine.Tables:
    """J, dJ/du, s·M_L at the half steps of ``steps`` steps per revolution from the
    sweep's start in the running direction (no friction: not part of this model)."""
    sense = sense_of(mechanism)
    grid = mechanism.sweep.start + sense * math.pi / steps * np.arange(2 * steps)
    machine = machine_tables(mechanism, grid)
    tables = engine.Tables(machine.inertia, sense * machine.slope, sense * machine.load,
                           np.zeros(2 * steps))
    engine.check_tables(tables)
    return tables


def sense_of(mechanism: Mechanism) -> float:
    return 1.0 if mechanism.crank.speed > 0 else -1.0


@dataclass(eq=False)  # holds arrays: no meaningful ==
class CrankShaft:
    """The linkage as the crank shaft of its drive line, built once per analysis and
    passed on (``crank_shaft``): the file's line, the tables J(φ), dJ/du, s·M_L on the
    coarsest grid (``MIN_STEPS``), and, found on first use, whether joint friction
    enters, the line with an ideal motor and the natural frequency."""

    mechanism: Mechanism
    line: engine.Line
    """the line of the file: its ``[drive]`` motor, or an ideal motor without one"""
    tables: engine.Tables
    """the crank shaft on ``MIN_STEPS`` steps per revolution, friction zero (never
    changed: ``tables_at`` hands out tables to integrate with)"""

    def tables_at(self, steps: int) -> engine.Tables:
        """The crank shaft on ``steps`` steps per revolution, with a friction torque of
        its own (zero; the friction passes replace it): the coarse tables' values when
        ``steps`` is theirs, else computed."""
        if steps == self.tables.steps:
            coarse = self.tables
            return engine.Tables(coarse.inertia, coarse.slope, coarse.load,
                                 np.zeros(2 * steps))
        return crank_tables(self.mechanism, steps)

    @cached_property
    def friction(self) -> bool:
        """True when the sweep of the mechanism runs the friction solution (its plan)."""
        from dyade.linkage.plan import plan

        return bool(plan(self.mechanism).friction)

    @cached_property
    def ideal_line(self) -> engine.Line:
        """The line with an ideal motor (what the scans over speed drive)."""
        return self.line if self.line.ideal else line_of(self.mechanism, ideal=True)

    @cached_property
    def frequency(self) -> NaturalFrequency:
        """ω̄, its range over the cycle and Ω/ω̄ (``natural_frequency``), once."""
        return natural_frequency(self.mechanism, shaft=self)


def crank_shaft(mechanism: Mechanism) -> CrankShaft:
    """The crank shaft of ``mechanism``'s drive line (``CrankShaft``): its line and its
    tables on ``MIN_STEPS`` steps per revolution."""
    line = line_of(mechanism)
    return CrankShaft(mechanism, line, crank_tables(mechanism, engine.MIN_STEPS))


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class NaturalFrequency:
    """The natural frequencies of the drive line and the VDI 2149 check."""

    omega_bar: float
    """ω̄ [rad/s]: the lowest natural frequency with the linkage's mean reduced inertia J̄"""
    omega_min: float
    """the lowest natural frequency's smallest value over the cycle (J(φ) largest) [rad/s]"""
    omega_max: float
    """… and its largest (J(φ) smallest) [rad/s]"""
    inertia_mean: float
    """J̄ [kg·m²]"""
    speed: float
    """the crank's operating speed |Ω| [rad/s]"""
    crank_angle: FloatArray
    """(n,) [rad]"""
    frequency: FloatArray
    """(n,) the lowest natural frequency with J frozen at J(φ) [rad/s]"""

    @property
    def ratio(self) -> float:
        """η = Ω/ω̄ [-]"""
        return self.speed / self.omega_bar

    @property
    def vdi_2149(self) -> bool:
        """True when Ω/ω̄ ≤ 0.1: the rigid model of the drive holds (VDI 2149 Part 1)."""
        return self.ratio <= VDI_2149_RATIO


def natural_frequency(mechanism: Mechanism, *, shaft: CrankShaft | None = None
                      ) -> NaturalFrequency:
    """ω̄, the range of the lowest natural frequency over the cycle, and Ω/ω̄.

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` table (else ``InputError``).
    shaft : CrankShaft, optional
        Its crank shaft, when the caller has it already (``crank_shaft``).

    Returns
    -------
    NaturalFrequency
        ω̄ [rad/s], its range with J(φ) frozen over the cycle, Ω/ω̄ and the VDI 2149
        verdict (``vdi_2149``: Ω/ω̄ ≤ 0.1).

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/slider-crank.toml",
    ...                          {"drive_line.stiffness": 1000.0, "links.2.inertia": 0.01})
    >>> f = natural_frequency(m)
    >>> round(f.omega_bar, 2), round(f.ratio, 4), f.vdi_2149     # [rad/s], [-]
    (300.8, 0.5222, False)
    """
    shaft = shaft or crank_shaft(mechanism)
    line, tables = shaft.line, shaft.tables
    inertia = tables.inertia[0::2]
    mean = float(np.mean(tables.inertia))
    every = engine.natural_frequencies(line, np.concatenate(([mean], inertia)))[:, 0]
    angle = mechanism.sweep.start + sense_of(mechanism) * 2.0 * math.pi / engine.MIN_STEPS * \
        np.arange(engine.MIN_STEPS)
    return NaturalFrequency(float(every[0]), float(np.min(every[1:])), float(np.max(every[1:])),
                            mean, abs(mechanism.crank.speed), angle, every[1:])
