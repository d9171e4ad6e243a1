"""The variants of a study as a matrix (variants × parameters), made once, in the
calling process, from the plan and its seed: the same rows on any number of workers."""

from __future__ import annotations

import itertools
import math

import numpy as np

from dyade.study.spec import Spec


def variants(spec: Spec) -> np.ndarray:
    """(n, p) values of the parameters, one row per variant, in the study's order:
    a grid varies the last parameter fastest; ``sensitivity`` gives the nominal row,
    then the rows −h and +h of each parameter in turn (``steps``). The plan varies the
    free parameters; each linked one is computed from them (``Spec.complete``)."""
    refuse_too_many(spec)
    return spec.complete(free_variants(spec))


def free_variants(spec: Spec) -> np.ndarray:
    """(n, f) values of the free parameters (``Spec.free``), one row per variant."""
    params = spec.free
    if spec.plan == "grid":
        return np.array(list(itertools.product(*(p.values for p in params))), dtype=float
                        ).reshape(-1, len(params))
    if spec.plan == "sensitivity":
        nominal = np.array([p.nominal for p in params])
        rows = [nominal]
        for j, h in enumerate(steps(spec)):
            for sign in (-1.0, 1.0):
                row = nominal.copy()
                row[j] += sign * h
                rows.append(row)
        return np.array(rows)
    if spec.plan == "optimise":
        return np.empty((0, len(params)))
    if spec.plan == "monte-carlo":
        u = np.random.default_rng(spec.seed).random((spec.samples, len(params)))
    else:  # latin-hypercube: one sample in each of n equal strata of every parameter
        from dyade.study.spec import needs

        needs("scipy", "a latin-hypercube plan")
        from scipy.stats import qmc

        try:
            sampler = qmc.LatinHypercube(d=len(params), rng=np.random.default_rng(spec.seed))
        except TypeError:  # scipy before 1.15 names it seed
            sampler = qmc.LatinHypercube(d=len(params), seed=np.random.default_rng(spec.seed))
        u = sampler.random(spec.samples)
    return np.column_stack([p.quantile(u[:, j]) for j, p in enumerate(params)])


def count(spec: Spec) -> int:
    """How many variants the plan makes, before any is made (an optimiser's are its
    evaluations, bounded by its own budget: 0 here)."""
    if spec.plan == "grid":
        return math.prod(len(p.values) for p in spec.free)
    if spec.plan == "sensitivity":
        return 1 + 2 * len(spec.free)
    if spec.plan == "optimise":
        return 0
    return spec.samples


def refuse_too_many(spec: Spec) -> None:
    """Refuse, before the matrix is allocated or a variant run, a plan whose table
    would exceed ``dyade.limits.MAX_MEMORY`` (a row of parameters and results per
    variant at ``BYTES_PER_VALUE`` each): the figure and the keys that make it."""
    from dyade.errors import InputError
    from dyade.limits import BYTES_PER_VALUE, MAX_MEMORY, size

    n = count(spec)
    need = n * (len(spec.parameters) + RESULT_COLUMNS) * BYTES_PER_VALUE
    if need > MAX_MEMORY:
        keys = ("`plan.samples`" if spec.plan in ("monte-carlo", "latin-hypercube")
                else "the lists and ranges of [parameters]")
        raise InputError(f"{spec.label}: the {spec.plan} plan makes {n:,} variants, whose table "
                         f"would take about {size(need)} (more than {size(MAX_MEMORY)}). "
                         f"Ask for fewer with {keys}, or split the study.",
                         source=spec.label)


RESULT_COLUMNS = 64
"""about how many result columns a variant's row has (analyse's summary, status)"""


def steps(spec: Spec) -> np.ndarray:
    """The central differences' step h of each free parameter: its own ``step``, else
    ``rel_step`` × |nominal| (``rel_step`` itself for a nominal of 0)."""
    return np.array([p.step if p.step is not None else
                     spec.rel_step * (abs(p.nominal) if p.nominal != 0 else 1.0)
                     for p in spec.free])


def differences(spec: Spec) -> tuple[int, list[tuple[int, int, float, float]]]:
    """Where the sensitivity's central differences read the table: (the row of the
    nominal variant, per parameter (the row at −h, the row at +h, h, the nominal
    value)). A ``sensitivity`` plan: its nominal row, then −h and +h of each free
    parameter (``steps``); a grid: its middle point (each parameter's middle value) and
    its neighbours along each parameter (h: half their distance)."""
    params = spec.free
    if spec.plan != "grid":
        h = steps(spec)
        return 0, [(1 + 2 * j, 2 + 2 * j, float(h[j]), p.nominal)
                   for j, p in enumerate(params)]
    sizes = [len(p.values) for p in params]
    strides = [math.prod(sizes[j + 1:]) for j in range(len(params))]  # the last fastest
    middle = [size // 2 for size in sizes]
    centre = sum(m * stride for m, stride in zip(middle, strides))
    out = []
    for j, p in enumerate(params):
        below, above = p.values[middle[j] - 1], p.values[middle[j] + 1]
        out.append((centre - strides[j], centre + strides[j], 0.5 * (above - below),
                    p.values[middle[j]]))
    return centre, out
