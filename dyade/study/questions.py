"""The questions on top of a study's table: sensitivity (central differences),
tolerance (Monte Carlo statistics and failure probabilities), the Pareto front of
several objectives, and the optimum of one (differential evolution)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from dyade.study.evaluate import LOCKS, OK, OPEN, REFUSED, WITHHELD, Evaluator
from dyade.study.spec import Spec

PERCENTILES = (1, 5, 50, 95, 99)
ZERO = 1e-9
"""an output below this in its unit (SI, degrees) is numerically zero (the mean drive
power of a machine without losses comes out at 1e-16 W): no normalised sensitivity"""


def sensitivity(columns: dict, spec: Spec, outputs: list[str],
                layout: tuple[int, list[tuple[int, int, float, float]]]) -> list[dict]:
    """d output / d parameter by central differences — of the rows −h and +h of each
    parameter about the nominal row, where ``layout`` (``plans.differences``) finds them
    in the table: a sensitivity plan's, or a grid's neighbours of its middle point —
    and normalised: (dy/y)/(dx/x) [% per %]; NaN where the output is numerically zero
    (below ``ZERO``)."""
    rows = []
    centre, pairs = layout
    y0 = {name: columns[name][centre] for name in outputs}
    for p, (minus, plus, h, nominal) in zip(spec.free, pairs):
        for name in outputs:
            derivative = (columns[name][plus] - columns[name][minus]) / (2.0 * h)
            normalised = (derivative * nominal / y0[name]
                          if abs(y0[name]) > ZERO and np.isfinite(y0[name]) else math.nan)
            rows.append({"parameter": p.key, "output": name, "nominal": float(nominal),
                         "step": float(h), "value": float(y0[name]),
                         "below": float(columns[name][minus]),
                         "above": float(columns[name][plus]),
                         "derivative": float(derivative), "normalised": float(normalised)})
    return rows


CONSTANT = 1e-9
"""[-] an output whose values spread less than this share of their magnitude is constant
over the variants (round-off: 0.16 m give or take 1e-17)"""


def constant(values) -> bool:
    """Whether the finite ``values`` (two or more) are one value to rounding: their spread within
    ``CONSTANT`` of their magnitude, or all numerically zero (``ZERO``)."""
    values = np.asarray(values, dtype=float)
    values = values[np.isfinite(values)]
    if values.size < 2:  # one variant's value is no evidence of a constant
        return False
    spread, size = float(np.ptp(values)), float(np.abs(values).max())
    return spread <= CONSTANT * size or size <= ZERO


def coherent(unit: str) -> tuple[str, float]:
    """The unit a derivative takes a parameter in, and how many of it one of ``unit``
    is: lengths in metres as the outputs are (``mm`` -> ``("m", 1e-3)``), angles in
    degrees as the outputs are (``rad`` -> ``("°", 57.3)``), the others as they are."""
    from dyade.units import DEG, LENGTH_FACTORS

    if unit in LENGTH_FACTORS:
        return "m", LENGTH_FACTORS[unit]
    if unit in ("deg", "°"):
        return "°", 1.0
    if unit == "rad":
        return "°", 1.0 / DEG
    return unit, 1.0


RESOLVED = 0.01
"""[-] the one-sided slopes of an extreme that crosses a grid point agree within this share
of its derivative at the crank step ``crossings`` names"""


def crossings(rows: list[dict], evaluator: Evaluator, matrix: np.ndarray,
              layout: tuple[int, list[tuple[int, int, float, float]]], spec: Spec,
              units: dict[str, str] | None = None) -> list[str]:
    """Notes on the sensitivities of sampled extremes (a peak, the least transmission
    angle: figures of one crank position of the sweep's grid) whose crank angle moves to
    another grid point between the rows −h and +h: the central difference then mixes the
    slopes of two crank angles (its one-sided slopes, backward and forward, differ by
    more than ``RESOLVED`` of the derivative). Each note names the crank step
    (``sweep.step``) at which the grid's part of that difference, which shrinks in
    proportion to the step, is within ``RESOLVED`` (at least ten times finer); what
    stays at that step is the curvature over ±h (a smaller ``plan.rel_step``). The rows
    −h and +h of a parameter whose one-sided slopes differ for some output are swept
    again (``dyade.analyse``) for the crank angles of their extremes."""
    from dyade.errors import DyadeError
    from dyade.linkage.summary import figures
    from dyade.linkage.sweep import analyse
    from dyade.units import DEG

    _, pairs = layout
    seen: dict[int, tuple[dict[str, float], float]] = {}

    def places(index: int) -> tuple[dict[str, float], float]:
        if index not in seen:
            try:
                result = analyse(evaluator.mechanism(matrix[index]))
                stats = figures(result, result.columns(), False)
                seen[index] = ({name: stat.where["angle_deg"] for name, stat in stats.items()
                                if stat.where and "angle_deg" in stat.where},
                               result.mechanism.sweep.step / DEG)
            except (DyadeError, ValueError):
                seen[index] = ({}, math.nan)
        return seen[index]

    def slopes(row: dict, h: float) -> tuple[float, float, float, float]:
        backward = (row["value"] - row["below"]) / h
        forward = (row["above"] - row["value"]) / h
        return backward, forward, 0.5 * (backward + forward), abs(forward - backward)

    notes = []
    by = {(row["parameter"], row["output"]): row for row in rows}
    for p, (minus, plus, h, nominal) in zip(spec.free, pairs):
        apart = {row["output"] for row in rows if row["parameter"] == p.key
                 and slopes(row, h)[3] > RESOLVED * abs(slopes(row, h)[2])}
        if not apart:  # every output's one-sided slopes agree: nothing to sweep again
            continue
        low, step = places(minus)
        high, _ = places(plus)
        for name in [name for name in low if name in high and name in apart]:
            row = by[(p.key, name)]
            if low[name] == high[name] or not math.isfinite(step):
                continue
            backward, forward, central, gap = slopes(row, h)
            finer = nice_below(step * max(min(0.1, RESOLVED * abs(central) / gap), 1e-3))
            scale = coherent((units or {}).get(p.key, ""))[1]  # the derivatives' unit
            notes.append(f"d {name}/d {p.key}: the extreme moves from crank angle "
                         f"{low[name]:g}° to {high[name]:g}° between the variants at −h and +h "
                         f"(h = {h:g} {(units or {}).get(p.key, '')}".rstrip() +
                         f"), across a grid point of the sweep's {step:g}° step: the central "
                         f"difference mixes the slopes at two crank angles (one-sided: "
                         f"{backward / scale:.4g} and {forward / scale:.4g} {row['unit']}, "
                         f"{100 * gap / abs(central) if central else math.inf:.0f} % apart). "
                         f"A crank step of {finer:g}° resolves the grid's part, which shrinks "
                         f"with the step (set = {{ \"sweep.step\" = {finer:g} }} in the study "
                         f"file, or --set sweep.step={finer:g}); a difference that stays is the "
                         f"curvature over ±h: a smaller plan.rel_step.")
    return notes


def nice_below(value: float) -> float:
    """The largest of 1, 2, 5 × 10^k not above ``value`` (a crank step to name)."""
    if not value > 0:
        return value
    power = 10.0 ** math.floor(math.log10(value))
    for factor in (5.0, 2.0, 1.0):
        if factor * power <= value * (1 + 1e-12):
            return float(f"{factor * power:.12g}")
    return float(f"{power:.12g}")


def tolerance(columns: dict, outputs: list[str], limits: dict[str, float]) -> dict[str, Any]:
    """Statistics of every output over the variants that give it (mean, sd, percentiles
    1, 5, 50, 95, 99, min, max; an output ``constant`` over them has its one value as
    each, sd 0, and ``constant`` True) and the probability (share of all variants) of each
    failure: no closure, refused, self-locking, a joint force above ``joint_force`` [N],
    a transmission angle below ``transmission_deg`` [°]."""
    status = columns["status"]
    n = len(status)
    stats = {}
    for name in outputs:
        values = columns[name][np.isfinite(columns[name])]
        if not values.size:
            continue
        if constant(values):  # one value to rounding (sd 2.8e-17): said so, not scattered
            value = float(np.median(values))
            stats[name] = {"count": int(values.size), "constant": True, "mean": value,
                           "sd": 0.0, "min": value, "max": value,
                           **{f"p{q}": value for q in PERCENTILES}}
            continue
        stats[name] = {"count": int(values.size), "constant": False,
                       "mean": float(values.mean()),
                       "sd": float(values.std(ddof=1)) if values.size > 1 else 0.0,
                       "min": float(values.min()), "max": float(values.max()),
                       **{f"p{q}": float(np.percentile(values, q)) for q in PERCENTILES}}
    failures = {"no_closure": float(np.mean(status == OPEN)) if n else math.nan,
                "refused": float(np.mean(status == REFUSED)) if n else math.nan,
                "self_locks": float(np.mean(status == LOCKS)) if n else math.nan}
    if np.any(status == WITHHELD):  # (only where some are: the model breaks down there)
        failures["withheld"] = float(np.mean(status == WITHHELD))
    if "joint_force" in limits:
        forces = [columns[k] for k in outputs if k.endswith("_peak")]
        above = np.zeros(n, dtype=bool)
        for values in forces:
            above |= np.abs(values) > limits["joint_force"]
        failures["joint_force_above"] = float(np.mean(above)) if n else math.nan
    if "transmission_deg" in limits:
        below = np.zeros(n, dtype=bool)
        for k in outputs:
            if k.startswith("mu_") and k.endswith("_min_deg"):
                below |= columns[k] < limits["transmission_deg"]
        failures["transmission_below"] = float(np.mean(below)) if n else math.nan
    return {"variants": n, "limits": dict(limits), "outputs": stats, "probability": failures}


def pareto(columns: dict, objectives: list[tuple[str, float]],
           bounds: dict[str, tuple[float, float]] | None = None) -> np.ndarray:
    """(n,) bool: the variants that give every objective, keep within ``bounds``, and
    that no other such variant beats in one objective without losing in another."""
    status = columns["status"]
    feasible = (status == OK) | (status == LOCKS)
    for name, (low, high) in (bounds or {}).items():
        feasible &= (columns[name] >= low) & (columns[name] <= high)
    values = np.column_stack([sense * columns[name] for name, sense in objectives])
    feasible &= np.isfinite(values).all(axis=1)
    index = np.flatnonzero(feasible)
    front = np.zeros(len(status), dtype=bool)
    points = values[index]
    for k, i in enumerate(index):
        dominated = (np.all(points <= points[k], axis=1) & np.any(points < points[k], axis=1))
        front[i] = not dominated.any()
    return front


class Objective:
    """One objective of the optimiser: ``sense`` × output of the variant at ``x``, +inf
    where the variant gives no value or leaves the bounds on other outputs (a class: it
    pickles for the executor's processes)."""

    def __init__(self, evaluator: Evaluator, name: str, sense: float,
                 bounds: dict[str, tuple[float, float]], spec: Spec | None = None) -> None:
        self.evaluator, self.name, self.sense, self.bounds = evaluator, name, sense, bounds
        self.spec = spec
        """completes the free parameters ``x`` with the linked ones (None: none linked)"""

    def __call__(self, x) -> float:
        if self.spec is not None:
            x = self.spec.complete(x)[0]
        status, _, out = self.evaluator.one(x)
        value = out.get(self.name, math.nan)
        for name, (low, high) in self.bounds.items():
            if not low <= out.get(name, math.nan) <= high:
                return math.inf
        return self.sense * value if np.isfinite(value) else math.inf


def optimise(spec: Spec, evaluator: Evaluator, workers=1) -> dict[str, Any]:
    """Minimise (or maximise) one output over the parameters' ranges with
    ``scipy.optimize.differential_evolution`` (seeded; ``workers``: a map-like callable
    or 1), polished locally by L-BFGS-B when ``polish``.

    Categorical parameters (choices among names) are not searched by the optimiser:
    every combination of their choices is taken in turn, the numeric parameters
    optimised within each (each choice evaluated once where there are none), and the
    best of them is the optimum; ``"choices"`` lists each combination's own best (its
    names, its value, its numbers). ``"x"`` gives the choices by their names."""
    import itertools

    from dyade.study.spec import needs

    settings = spec.optimise
    (name, sense), = settings["objectives"]
    linked = len(spec.free) < len(spec.parameters)
    objective = Objective(evaluator, name, sense, settings["bounds"], spec if linked else None)
    free = spec.free
    names = [j for j, p in enumerate(free) if p.categorical]
    numbers = [j for j, p in enumerate(free) if not p.categorical]
    if numbers:
        needs("scipy", "optimise")
        from scipy.optimize import differential_evolution
    combos = list(itertools.product(*(range(len(free[j].choices)) for j in names)))
    best, each, evaluations, success, message = None, [], 0, True, ""
    for combo in combos:
        fixed = Fixed(objective, len(free), dict(zip(names, map(float, combo))), numbers)
        if numbers:
            result = differential_evolution(
                fixed, [(free[j].low, free[j].high) for j in numbers], seed=spec.seed,
                maxiter=settings["maxiter"], popsize=settings["popsize"],
                tol=settings["tol"], polish=settings["polish"], workers=workers,
                updating="immediate" if workers == 1 else "deferred")
            x, fun, nfev = result.x, float(result.fun), int(result.nfev)
            success, message = success and bool(result.success), str(result.message)
        else:
            x, fun, nfev = np.empty(0), float(fixed(np.empty(0))), 1
        evaluations += nfev
        row = spec.complete(fixed.full(x))[0]
        each.append({"choice": {free[j].key: free[j].choices[c] for j, c in zip(names, combo)},
                     "x": spec.shown(row), "value": float(sense * fun)})
        if best is None or fun < best[1]:
            best = (row, fun)
    out = {"objective": name, "sense": "minimise" if sense > 0 else "maximise",
           "x": spec.shown(best[0]),  # linked ones included; the choices by name
           "value": float(sense * best[1]), "evaluations": evaluations, "success": success,
           "message": message or "every choice evaluated"}
    if names:
        out["choices"] = each
    return out


class Fixed:
    """The objective of the numeric parameters ``numbers`` (their positions in the free
    ones) with the categorical ones fixed at ``fixed`` (position -> the choice's index);
    a class: it pickles for the executor's processes."""

    def __init__(self, objective: Objective, size: int, fixed: dict[int, float],
                 numbers: list[int]) -> None:
        self.objective, self.size, self.fixed, self.numbers = objective, size, fixed, numbers

    def full(self, x) -> np.ndarray:
        """Every free parameter's value: ``x`` at ``numbers``, the choices at theirs."""
        row = np.empty(self.size)
        row[self.numbers] = x
        for j, value in self.fixed.items():
            row[j] = value
        return row

    def __call__(self, x) -> float:
        return self.objective(self.full(x))
