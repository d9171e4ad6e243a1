"""The variants of a study as a matrix (variants × parameters), made once, in the
calling process, from the plan and its seed: the same rows on any number of workers."""

from __future__ import annotations

import itertools

import numpy as np

from dyade.study.spec import Spec


def variants(spec: Spec) -> np.ndarray:
    """(n, p) values of the parameters, one row per variant, in the study's order:
    a grid varies the last parameter fastest; ``sensitivity`` gives the nominal row,
    then the rows −h and +h of each parameter in turn (``steps``)."""
    params = spec.parameters
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


def steps(spec: Spec) -> np.ndarray:
    """The central differences' step h of each parameter: its own ``step``, else
    ``rel_step`` × |nominal| (``rel_step`` itself for a nominal of 0)."""
    return np.array([p.step if p.step is not None else
                     spec.rel_step * (abs(p.nominal) if p.nominal != 0 else 1.0)
                     for p in spec.parameters])
