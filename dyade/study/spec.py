"""The study file (TOML): the mechanism, fixed overrides, the parameters and their
values, ranges or distributions, the plan, the outputs and the question.

Every error names the study file and the key, what was expected and what was found
(``docs/reference/study-file.md`` documents every key).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

from dyade.errors import InputError

PLANS = ("grid", "latin-hypercube", "monte-carlo", "sensitivity", "optimise")
QUESTIONS = ("table", "sensitivity", "tolerance", "optimise")
EXTRAS = ("flywheel", "clearance", "coupling", "servo")
TOP = {"mechanism", "set", "parameters", "plan", "outputs", "sensitivity", "tolerance",
       "optimise"}
POSITIVE = ("length", "lengths", "mass", "inertia", "slider_length", "slider_height",
            "pin_radius", "speed_rpm")
"""last parts of key paths (before an index) whose values must stay positive"""
MAX_VARIANTS = 10_000_000


@dataclass(frozen=True)
class Parameter:
    """One varied key: its values (a list), a range, or a distribution, in the units
    of the mechanism file (as ``--set`` takes them)."""

    key: str
    kind: str
    """values, range, uniform, normal, linked, choices"""
    values: tuple[float, ...] = ()
    """values: the list; range: the grid points"""
    low: float = math.nan
    """range, uniform: lower bound; normal: lower truncation (−inf: none)"""
    high: float = math.nan
    nominal: float = math.nan
    """normal: the mean; uniform ±tol: the middle; values and ranges: the middle value"""
    sd: float = 0.0
    step: float | None = None
    """sensitivity: the step of the central differences (default: rel_step·|nominal|)"""
    equals: str = ""
    """linked: the expression of other parameters it equals (``dyade.study.expression``)"""
    choices: tuple[str, ...] = ()
    """choices: the names it takes (a motion law, ...); ``values`` are their indices 0, 1,
    ... (the plans' matrix stays numeric), ``shown`` gives the name of an index"""

    @property
    def linked(self) -> bool:
        """Whether the parameter follows others (``{ equals = "..." }``), not varied itself."""
        return self.kind == "linked"

    @property
    def categorical(self) -> bool:
        """Whether the parameter is a choice among names (``{ choices = [...] }`` or a
        list of names), not a number."""
        return self.kind == "choices"

    def shown(self, value):
        """A value of the plans' matrix as the table shows it: a choice's name (from its
        index), else the number."""
        return self.choices[int(round(float(value)))] if self.categorical else float(value)

    def quantile(self, u):
        """Values at probabilities ``u`` (an array in [0, 1)) of this parameter's
        distribution (discrete for lists, uniform for ranges)."""
        import numpy as np

        u = np.asarray(u, dtype=float)
        if self.kind in ("values", "choices"):  # a choice: each equally likely
            picks = np.minimum((u * len(self.values)).astype(int), len(self.values) - 1)
            return np.asarray(self.values)[picks]
        if self.kind in ("range", "uniform"):
            return self.low + u * (self.high - self.low)
        if self.sd == 0.0:
            return np.full(u.shape, self.nominal)
        from statistics import NormalDist

        unit = NormalDist()
        lo = unit.cdf((self.low - self.nominal) / self.sd) if math.isfinite(self.low) else 0.0
        hi = unit.cdf((self.high - self.nominal) / self.sd) if math.isfinite(self.high) else 1.0
        p = np.clip(lo + u * (hi - lo), 1e-300, 1 - 1e-16)
        return self.nominal + self.sd * np.array([unit.inv_cdf(float(q)) for q in p.ravel()]
                                                 ).reshape(p.shape)


@dataclass(frozen=True)
class Spec:
    """A study as its file describes it."""

    mechanism: str
    """the mechanism file's path"""
    label: str
    """the study file's name, for messages"""
    fixed: dict[str, Any] = field(default_factory=dict)
    """key -> value applied to every variant before the parameters"""
    parameters: tuple[Parameter, ...] = ()
    plan: str = "grid"
    samples: int = 0
    seed: int | None = None
    rel_step: float = 1e-3
    extras: tuple[str, ...] = ()
    fluctuation: float = 0.02
    question: str = "table"
    tolerance: dict[str, float] = field(default_factory=dict)
    """limits: joint_force [N], transmission_deg [°]"""
    optimise: dict[str, Any] = field(default_factory=dict)

    @property
    def free(self) -> tuple[Parameter, ...]:
        """The parameters the plan varies (the linked ones follow them)."""
        return tuple(p for p in self.parameters if not p.linked)

    def shown(self, row) -> list:
        """A row of the matrix (every parameter, the study's order) as the table shows
        it: the names of the choices, the numbers as floats."""
        return [p.shown(v) for p, v in zip(self.parameters, row)]

    def shown_rows(self, rows) -> list[list]:
        """``shown`` of each row of ``rows`` (a (variants, parameters) float array): the
        numbers all at once where no parameter is a choice."""
        if any(p.categorical for p in self.parameters):
            return [self.shown(row) for row in rows]
        return rows.tolist()  # (float64 -> the same floats as float(value))

    def numeric(self, row) -> list[float]:
        """``shown``'s inverse: a row with the choices' names as the matrix's numbers."""
        return [float(p.choices.index(v)) if p.categorical and isinstance(v, str) else
                float(v) for p, v in zip(self.parameters, row)]

    def complete(self, free):
        """(n, p) values of every parameter, in the study's order, from (n, f) values of
        the free ones (``free``'s order): each linked parameter computed from them."""
        import numpy as np

        from dyade.study import expression

        free = np.asarray(free, dtype=float).reshape(-1, len(self.free))
        given = {p.key: free[:, j] for j, p in enumerate(self.free)}
        columns = []
        for p in self.parameters:
            if p.linked:
                value = expression.evaluate(expression.parse(p.equals), given)
                columns.append(np.broadcast_to(np.asarray(value, dtype=float),
                                               (len(free),)))
            else:
                columns.append(given[p.key])
        return np.column_stack(columns) if columns else free


def override(spec: Spec, assignments=(), samples: int | None = None,
             seed: int | None = None) -> Spec:
    """The study with a run's overrides (``dyade study --set/--samples/--seed``, the
    API's ``set``, ``samples``, ``seed``): ``set`` (``KEY=VALUE`` texts, or (key, value)
    pairs) joins the study file's `set`; an ``InputError`` on ``set`` for a key the
    study varies or the mechanism file does not have, on ``samples`` for a plan that
    does not sample, on ``seed`` below 0."""
    from dataclasses import replace

    from dyade.errors import InputError
    from dyade.files.schema import parse_assignment

    if assignments:
        pairs = [parse_assignment(a) if isinstance(a, str) else tuple(a) for a in assignments]
        varied = {p.key for p in spec.parameters}
        for key, _ in pairs:
            if key in varied:
                raise InputError.parameter("set", f"{key} is a parameter of {spec.label}: the "
                                                  f"study varies it; --set fixes the others "
                                                  f"(or change [parameters]).", value=key)
        from dyade.files.mechanism import build, load_data

        try:  # a key the file has not: named here, not as a parameter's
            build(load_data(spec.mechanism, dict(pairs), "--set"), spec.mechanism)
        except InputError as err:
            if any(words in str(err) for words in ("unknown key", "are numbered",
                                                   "is a value, not a table")):
                raise InputError.parameter("set", str(err), value=dict(pairs)) from None
        spec = replace(spec, fixed={**spec.fixed, **dict(pairs)})
    if samples is not None:
        if spec.plan not in SAMPLED:
            raise InputError.parameter("samples", f"counts the variants of a monte-carlo or "
                                                  f"latin-hypercube plan; {spec.label}'s "
                                                  f"plan.kind is \"{spec.plan}\".",
                                       value=samples)
        spec = replace(spec, samples=int(samples))  # (sized by plans.variants before any)
    if seed is not None:
        if seed < 0:
            raise InputError.parameter("seed", f"must be a whole number ≥ 0, got {seed}.",
                                       value=seed)
        spec = replace(spec, seed=int(seed))
    return spec


def needs(module: str, what: str, extra: str = "study") -> None:
    """Refuse, with the extra to install, when an optional module is missing."""
    import importlib.util

    if importlib.util.find_spec(module) is None:
        from dyade.errors import MissingExtra

        raise MissingExtra(f"{what} needs {module}, which is not installed: "
                           f"pip install \"dyade[{extra}]\".")


def fail(label: str, key: str, message: str) -> InputError:
    return InputError(f"{label}: `{key}` {message}", source=label, key=key)


def _number(label: str, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise fail(label, key, f"must be a finite number, got {value!r}.")
    return float(value)


def _pair(label: str, key: str, value: Any) -> tuple[float, float]:
    if not (isinstance(value, list) and len(value) == 2):
        raise fail(label, key, f"must be [low, high], got {value!r}.")
    low, high = (_number(label, key, v) for v in value)
    if not low < high:
        raise fail(label, key, f"must have low < high, got [{low:g}, {high:g}]: no variant.")
    return low, high


def _keys(label: str, table: dict, key: str, allowed: set[str]) -> None:
    from dyade.files.schema import other_kind, suggest

    if not isinstance(table, dict):
        raise fail(label, key, f"must be a table, got {table!r}.")
    for name in table:
        if name not in allowed:
            where = f"{key}.{name}" if key else name
            hint = "" if key else other_kind(table, allowed)
            raise fail(label, where, f"is not a study key.{hint or suggest(name, allowed)}")


def parameter(label: str, key: str, value: Any, rel_step: float) -> Parameter:
    """A parameter from its entry in ``[parameters]``."""
    where = f"parameters.{key}"
    step = None
    if isinstance(value, dict) and "equals" in value:
        _keys(label, value, where, {"equals"})
        if not isinstance(value["equals"], str):
            raise fail(label, f"{where}.equals", f"must be an expression in quotes, e.g. "
                                                 f"\"dyad.2.lengths.1 / 2\", got "
                                                 f"{value['equals']!r}.")
        return Parameter(key, "linked", equals=value["equals"])
    if isinstance(value, dict) and "step" in value and "range" not in value:
        step = _number(label, f"{where}.step", value["step"])
        if step <= 0:
            raise fail(label, f"{where}.step", f"must be positive, got {step:g}.")
        value = {k: v for k, v in value.items() if k != "step"}
    if isinstance(value, dict) and "choices" in value:
        _keys(label, value, where, {"choices"})
        return choices(label, f"{where}.choices", key, value["choices"])
    if isinstance(value, list) and value and any(isinstance(v, str) for v in value):
        return choices(label, where, key, value)
    if isinstance(value, str):
        raise fail(label, where, f"= {value!r} is one name: give the choices as a list, "
                                 f"[\"{value}\", ...], or fix it with `set`.")
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        out = Parameter(key, "values", (_number(label, where, value),),
                        nominal=float(value))
    elif isinstance(value, list):
        if not value:
            raise fail(label, where, "is an empty list: no variant.")
        values = tuple(_number(label, where, v) for v in value)
        out = Parameter(key, "values", values, min(values), max(values),
                        nominal=values[len(values) // 2] if len(values) % 2 else
                        0.5 * (values[len(values) // 2 - 1] + values[len(values) // 2]))
    elif isinstance(value, dict) and "range" in value:
        _keys(label, value, where, {"range", "count", "step"})
        low, high = _pair(label, f"{where}.range", value["range"])
        if "count" in value and "step" in value:
            raise fail(label, where, "takes count (values from low to high) or step, not both.")
        if "count" not in value and "step" not in value:  # bounds only (sampled, optimised)
            out = Parameter(key, "range", (), low, high, 0.5 * (low + high))
        elif "count" in value:
            count = value["count"]
            if isinstance(count, bool) or not isinstance(count, int) or count < 2:
                raise fail(label, f"{where}.count", f"must be a whole number ≥ 2, got {count!r}.")
        else:
            grid_step = _number(label, f"{where}.step", value["step"])
            if grid_step <= 0:
                raise fail(label, f"{where}.step", f"must be positive, got {grid_step:g}.")
            count = int(math.floor((high - low) / grid_step + 1e-9)) + 1
            if count < 2:
                raise fail(label, f"{where}.step", f"{grid_step:g} is larger than the range "
                                                   f"[{low:g}, {high:g}]: one value only.")
            high = low + (count - 1) * grid_step
        if "count" in value or "step" in value:
            import numpy as np

            values = tuple(np.linspace(low, high, count).tolist())
            out = Parameter(key, "range", values, low, high, 0.5 * (low + high))
    elif isinstance(value, dict) and "uniform" in value:
        _keys(label, value, where, {"uniform"})
        low, high = _pair(label, f"{where}.uniform", value["uniform"])
        out = Parameter(key, "uniform", (), low, high, 0.5 * (low + high))
    elif isinstance(value, dict) and "tol" in value:
        _keys(label, value, where, {"nominal", "tol"})
        nominal = _number(label, f"{where}.nominal", value.get("nominal"))
        tol = _number(label, f"{where}.tol", value["tol"])
        if tol < 0:
            raise fail(label, f"{where}.tol", f"must not be negative, got {tol:g}.")
        out = Parameter(key, "uniform", (), nominal - tol, nominal + tol, nominal)
        if tol == 0:
            out = Parameter(key, "values", (nominal,), nominal=nominal)
    elif isinstance(value, dict) and "sd" in value:
        _keys(label, value, where, {"nominal", "sd", "truncate"})
        nominal = _number(label, f"{where}.nominal", value.get("nominal"))
        sd = _number(label, f"{where}.sd", value["sd"])
        if sd < 0:
            raise fail(label, f"{where}.sd", f"must not be negative, got {sd:g}.")
        low, high = (_pair(label, f"{where}.truncate", value["truncate"])
                     if "truncate" in value else (-math.inf, math.inf))
        if not low <= nominal <= high:
            raise fail(label, f"{where}.truncate", f"[{low:g}, {high:g}] must contain the "
                                                   f"nominal {nominal:g}.")
        out = Parameter(key, "normal", (), low, high, nominal, sd)
    elif isinstance(value, dict) and "nominal" in value:
        _keys(label, value, where, {"nominal"})
        nominal = _number(label, f"{where}.nominal", value["nominal"])
        out = Parameter(key, "values", (nominal,), nominal=nominal)
    else:
        raise fail(label, where, f"must be a number, a list of values (or of names: a "
                                 f"choice), {{ range = [low, high], "
                                 f"count = n }}, {{ uniform = [low, high] }}, {{ nominal = x, "
                                 f"tol = t }} or {{ nominal = x, sd = s, truncate = [low, high] "
                                 f"}}; got {value!r}.")
    if step is not None:
        from dataclasses import replace

        out = replace(out, step=step)
    _positive(label, out)
    return out


def choices(label: str, where: str, key: str, names: Any) -> Parameter:
    """A categorical parameter: a list of names (a segment's motion law, ...), each
    taken as the mechanism file would take it; a motion law's name checked here, with a
    did-you-mean (``dyade.motion.laws.canonical``)."""
    if not isinstance(names, list) or not names:
        raise fail(label, where, f"must be a list of names, got {names!r}.")
    if not all(isinstance(n, str) and n.strip() for n in names):
        odd = next(n for n in names if not (isinstance(n, str) and n.strip()))
        raise fail(label, where, f"mixes names and {odd!r}: a parameter is a list of numbers "
                                 f"or a list of names (a choice), not both.")
    if len(set(names)) < len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise fail(label, where, f"names {twice!r} twice: give each choice once.")
    if key.rsplit(".", 1)[-1] == "law":  # a motion law: its name known before any run
        from dyade.motion.laws import canonical

        for name in names:
            try:
                canonical(name)
            except InputError as err:
                text = str(err).split("is not a motion law.", 1)[-1].strip()
                raise fail(label, where, f"names {name!r}, which is not a motion law. "
                                         f"{text}") from None
    return Parameter(key, "choices", tuple(float(i) for i in range(len(names))), 0.0,
                     float(len(names) - 1), nominal=0.0, choices=tuple(names))


QUANTITY = {"length": "a length", "lengths": "a length", "slider_length": "a length",
            "slider_height": "a length", "pin_radius": "a length", "mass": "a mass",
            "inertia": "a moment of inertia", "speed_rpm": "a crank speed"}
"""what a key of ``POSITIVE`` is, for the messages"""


def _positive(label: str, p: Parameter) -> None:
    """Refuse a parameter of a positive quantity whose values may reach zero or below
    (a normal distribution: within 6 sd, unless truncated above 0); a mass or an
    inertia may be 0 (a massless link), not below."""
    parts = [part for part in p.key.split(".") if not part.isdigit()]
    if not parts or parts[-1] not in POSITIVE:
        return
    what = QUANTITY[parts[-1]]
    zero = parts[-1] in ("mass", "inertia")  # 0 allowed, as in the mechanism file
    bound = "must not be negative" if zero else "must stay positive"
    where = f"parameters.{p.key}"
    if p.kind == "normal":
        low = max(p.low, p.nominal - 6.0 * p.sd)
        if low < 0 or (low == 0 and not zero):
            raise fail(label, where, f"is {what} and {bound}: a normal distribution "
                                     f"(nominal {p.nominal:g}, sd {p.sd:g}) reaches "
                                     f"{p.nominal - 6 * p.sd:g} within 6 sd. Refused: give "
                                     f"truncate = [low, high] with low > 0, or a smaller sd.")
    else:
        low = min(p.values) if p.values else p.low
        if low < 0 or (low == 0 and not zero):
            raise fail(label, where, f"is {what} and {bound}; its values reach {low:g}. "
                                     f"Refused.")


def read(path: str | os.PathLike) -> Spec:
    """Read and check a study file.

    Parameters
    ----------
    path : str or os.PathLike
        The study file (TOML; docs/reference/study-file.md lists every key).

    Returns
    -------
    Spec
        The study as its file describes it, checked; ``dyade.study(spec)`` runs it.

    Raises
    ------
    InputError
        Naming the file and the key, what was expected and what was found.

    Examples
    --------
    >>> import dyade
    >>> spec = dyade.study.read("mechanisms/studies/press-slide-tolerance.toml")
    >>> spec.plan, spec.samples, [p.key for p in spec.parameters]
    ('monte-carlo', 100, ['friction.coefficient', 'dyad.2.C.slider_length'])
    """
    from dyade.files.schema import read_toml

    path = os.fspath(path)
    label = os.path.basename(path)
    data = read_toml(path)
    return parse(data, label, os.path.dirname(os.path.abspath(path)))


def parse(data: dict[str, Any], label: str = "study", directory: str = ".") -> Spec:
    """A study from its TOML data (the same structure written in Python).

    Parameters
    ----------
    data : dict
        The keys of a study file.
    label : str
        Names the study in messages.
    directory : str
        Where a relative mechanism path starts (a study file's directory).

    Returns
    -------
    Spec

    Examples
    --------
    >>> import dyade
    >>> spec = dyade.study.parse({"mechanism": "mechanisms/fourbar.toml",
    ...                           "parameters": {"links.3.mass": {"nominal": 1.25, "tol": 0.25}},
    ...                           "plan": {"kind": "monte-carlo", "samples": 3, "seed": 1}})
    >>> spec.parameters[0].kind, spec.parameters[0].low, spec.parameters[0].high
    ('uniform', 1.0, 1.5)
    """
    _keys(label, data, "", TOP)
    mechanism = data.get("mechanism")
    if not isinstance(mechanism, str):
        raise fail(label, "mechanism", f"must name the mechanism file (a path relative to the "
                                       f"study file), got {mechanism!r}.")
    path = mechanism if os.path.isabs(mechanism) else os.path.join(directory, mechanism)
    if not os.path.isfile(path):
        raise fail(label, "mechanism", f"names {mechanism}, which is not a file ({path}).")
    fixed = data.get("set", {})
    if not isinstance(fixed, dict):
        raise fail(label, "set", f"must be a table of dotted keys, got {fixed!r}.")
    fixed = _flatten(fixed)
    plan = data.get("plan", {})
    _keys(label, plan, "plan", {"kind", "samples", "seed", "rel_step"})
    kind = plan.get("kind", "grid")
    if kind not in PLANS:
        from dyade.files.schema import suggest

        raise fail(label, "plan.kind", f"is {kind!r}, not a plan.{suggest(str(kind), set(PLANS))}")
    samples = plan.get("samples", 0)
    if kind in ("latin-hypercube", "monte-carlo") and (
            isinstance(samples, bool) or not isinstance(samples, int) or samples < 1):
        raise fail(label, "plan.samples", f"must be a whole number ≥ 1 for {kind}, got {samples!r}.")
    seed = plan.get("seed")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise fail(label, "plan.seed", f"must be a whole number ≥ 0, got {seed!r}.")
    rel_step = _number(label, "plan.rel_step", plan.get("rel_step", 1e-3))
    if not 0 < rel_step < 0.5:
        raise fail(label, "plan.rel_step", f"must lie in (0, 0.5), got {rel_step:g}.")
    raw = data.get("parameters", {})
    if not isinstance(raw, dict) or not raw:
        raise fail(label, "parameters", "must be a table with at least one key path.")
    params = linked(label, tuple(parameter(label, key, value, rel_step)
                                 for key, value in _flatten(raw).items()))
    free = tuple(p for p in params if not p.linked)
    if kind == "grid":
        for p in free:
            if p.kind not in ("values", "range", "choices"):
                raise fail(label, f"parameters.{p.key}", f"is a distribution ({p.kind}); a grid "
                                                         f"needs a list or a range (or plan.kind = "
                                                         f"\"monte-carlo\").")
            if not p.values:
                raise fail(label, f"parameters.{p.key}", "is a range without count or step: a "
                                                         "grid needs its values.")
        count = math.prod(len(p.values) for p in free)
        if count > MAX_VARIANTS:
            raise fail(label, "parameters", f"make a grid of {count:,} variants; at most "
                                            f"{MAX_VARIANTS:,}.")
    outputs = data.get("outputs", {})
    _keys(label, outputs, "outputs", {"extra", "fluctuation"})
    extras = outputs.get("extra", [])
    if not isinstance(extras, list) or any(e not in EXTRAS for e in extras):
        raise fail(label, "outputs.extra", f"must be a list of {', '.join(EXTRAS)}, got {extras!r}.")
    fluctuation = _number(label, "outputs.fluctuation", outputs.get("fluctuation", 0.02))
    if not 0 < fluctuation < 1:
        raise fail(label, "outputs.fluctuation", f"must lie in (0, 1), got {fluctuation:g}.")
    belong(label, data, plan, kind)
    question = "table"
    tolerance: dict[str, float] = {}
    optimise: dict[str, Any] = {}
    if kind == "sensitivity" or "sensitivity" in data:
        question = "sensitivity"
        for p in free:
            if p.categorical:
                raise fail(label, f"parameters.{p.key}", f"is a choice among names "
                                                         f"({', '.join(p.choices)}): a "
                                                         f"sensitivity's central differences "
                                                         f"need numbers. Fix it with `set` (one "
                                                         f"study per choice), or ask a grid's "
                                                         f"table instead.")
        _keys(label, data.get("sensitivity", {}), "sensitivity", set())
        if kind == "grid" and "kind" in plan:  # the differences of the grid's neighbours
            for p in free:
                if len(p.values) < 3 or len(p.values) % 2 == 0:
                    raise fail(label, f"parameters.{p.key}", f"has {len(p.values)} values: a "
                                                             f"grid's sensitivity takes the "
                                                             f"differences about its middle "
                                                             f"value, so give an odd number, "
                                                             f"at least 3 (or plan.kind = "
                                                             f"\"sensitivity\").")
        else:
            kind = "sensitivity"
    if "tolerance" in data:
        question = "tolerance"
        table = data["tolerance"]
        _keys(label, table, "tolerance", {"joint_force", "transmission_deg"})
        tolerance = {k: _number(label, f"tolerance.{k}", v) for k, v in table.items()}
    if kind == "optimise" or "optimise" in data:
        question = "optimise"
        optimise = _optimise(label, data.get("optimise", {}), params)
        if kind == "optimise" and optimise.get("objectives") and len(optimise["objectives"]) > 1:
            raise fail(label, "plan.kind", "\"optimise\" (differential evolution) takes one "
                                           "objective; for a Pareto front give a "
                                           "latin-hypercube or monte-carlo plan.")
        if kind == "optimise":
            for p in free:
                if p.kind != "range" and not p.categorical:
                    raise fail(label, f"parameters.{p.key}", "needs { range = [low, high], "
                                                             "count = n } (its bounds) to be "
                                                             "optimised.")
    return Spec(path, label, fixed, params, kind, int(samples), seed, rel_step, tuple(extras),
                fluctuation, question, tolerance, optimise)


SAMPLED = ("latin-hypercube", "monte-carlo")
QUESTION_PLANS = {"tolerance": SAMPLED, "sensitivity": ("sensitivity", "grid"),
                  "optimise": ("optimise", "grid", *SAMPLED)}
"""a question's table -> the plans that can answer it"""


def belong(label: str, data: dict, plan: dict, kind: str) -> None:
    """Refuse a plan and a table that do not belong together, naming both: a question's
    table that the plan cannot answer (``[tolerance]``'s statistics need sampled
    variants, not the ±h rows of a sensitivity plan), two questions at once, and the
    plan keys another plan would use (``plan.samples`` of a grid or a sensitivity plan,
    ``plan.rel_step`` without a sensitivity plan), instead of ignoring them."""
    asked = [name for name in QUESTION_PLANS if name in data]
    if len(asked) > 1:
        raise fail(label, f"[{asked[0]}]", f"and `[{asked[1]}]` ask two questions of one "
                                           f"study: give one table (one study per "
                                           f"question).")
    given = "kind" in plan
    shown = f'plan.kind = "{kind}"' if given else 'plan.kind (not given: "grid")'
    why = {"tolerance": "its statistics and failure probabilities need sampled variants "
                        "(plan.samples of them)",
           "sensitivity": "its central differences need the nominal and ±h of each "
                          "parameter (or a grid's neighbours about its middle)",
           "optimise": "its objectives need the variants of a search, a sample or a grid"}
    for name in asked:
        if name == "sensitivity" and not given:
            continue  # [sensitivity] alone: the sensitivity plan
        if kind not in QUESTION_PLANS[name]:
            plans = " or ".join(f'"{k}"' for k in QUESTION_PLANS[name])
            raise fail(label, f"[{name}]", f"does not belong with {shown}: {why[name]}. Give "
                                           f"plan.kind = {plans}, or remove [{name}].")
    effective = "sensitivity" if "sensitivity" in data and not given else kind
    if effective != kind:
        shown = 'plan.kind "sensitivity" (of the [sensitivity] table)'
    if "samples" in plan and effective not in SAMPLED:
        what = {"grid": "a grid's variants are every combination of its lists and ranges",
                "sensitivity": "a sensitivity plan's variants are the nominal and ±h of each "
                               "parameter",
                "optimise": "the optimiser's evaluations are bounded by optimise.maxiter and "
                            "optimise.popsize"}[effective]
        raise fail(label, "plan.samples", f"= {plan['samples']!r} does not belong with "
                                          f"{shown}: {what}. Remove plan.samples, or give "
                                          f'plan.kind = "monte-carlo" or "latin-hypercube".')
    if "rel_step" in plan and effective != "sensitivity":
        grid = " (a grid's sensitivity takes its neighbours)" if "sensitivity" in data else ""
        raise fail(label, "plan.rel_step", f"does not belong with {shown}: it sets the step "
                                           f"of a sensitivity plan's central differences"
                                           f"{grid}. Remove plan.rel_step, or give plan.kind "
                                           f'= "sensitivity".')


def _optimise(label: str, table: dict, params) -> dict[str, Any]:
    _keys(label, table, "optimise", {"minimise", "maximise", "bounds", "maxiter", "popsize",
                                     "tol", "polish"})
    objectives = []
    for sense in ("minimise", "maximise"):
        names = table.get(sense, [])
        names = [names] if isinstance(names, str) else names
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise fail(label, f"optimise.{sense}", f"must name outputs, got {names!r}.")
        for name in names:
            _current(label, f"optimise.{sense}", name)
        objectives += [(n, 1.0 if sense == "minimise" else -1.0) for n in names]
    if not objectives:
        raise fail(label, "optimise", "needs minimise or maximise (one output, or several "
                                      "for a Pareto front).")
    bounds = table.get("bounds", {})
    _keys(label, bounds, "optimise.bounds", set(bounds) if isinstance(bounds, dict) else set())
    limits = {}
    for name, pair in bounds.items():
        _current(label, f"optimise.bounds.{name}", name)
        if not (isinstance(pair, list) and len(pair) == 2):
            raise fail(label, f"optimise.bounds.{name}", f"must be [low, high] (\"\" for none), "
                                                         f"got {pair!r}.")
        low = -math.inf if pair[0] == "" else _number(label, f"optimise.bounds.{name}", pair[0])
        high = math.inf if pair[1] == "" else _number(label, f"optimise.bounds.{name}", pair[1])
        limits[name] = (low, high)
    out = {"objectives": objectives, "bounds": limits,
           "maxiter": int(table.get("maxiter", 200)), "popsize": int(table.get("popsize", 15)),
           "tol": float(table.get("tol", 1e-10)), "polish": bool(table.get("polish", True))}
    return out


def _current(label: str, key: str, name: str) -> None:
    """Refuse an output named as before issue 36 (an old study output, or a key of the
    former nested JSON summary such as ``drive.M_max``), naming its name now."""
    from dyade.linkage.summary import renamed
    from dyade.study.evaluate import RENAMED

    new = RENAMED.get(name) or renamed(name)
    if new is not None and new != name:
        raise fail(label, key, f"names the output {name!r}, which is now {new!r} (a study's "
                               f"outputs are the summary's figures, `dyade help json` "
                               f"lists the old names and the new).")


def linked(label: str, params: tuple[Parameter, ...]) -> tuple[Parameter, ...]:
    """The parameters with each linked one's expression read and checked (it names
    only free parameters of the study) and its nominal computed from theirs; an
    ``InputError`` on ``parameters.KEY.equals`` naming what is wrong."""
    from dataclasses import replace

    from dyade.files.schema import suggest
    from dyade.study import expression

    free = {p.key: p for p in params if not p.linked}
    if not free:
        raise fail(label, "parameters", "has only linked parameters ({ equals = ... }): give "
                                        "at least one that the plan varies.")
    out = []
    for p in params:
        if not p.linked:
            out.append(p)
            continue
        where = f"parameters.{p.key}.equals"
        try:
            tree = expression.parse(p.equals)
        except expression.ExpressionError as err:
            raise fail(label, where, f"= {p.equals!r}: {err} (an arithmetic expression of "
                                     f"the study's parameters and numbers: + - * / ** and "
                                     f"parentheses).") from None
        for name in expression.names(tree):
            if name in free and free[name].categorical:
                raise fail(label, where, f"= {p.equals!r} names {name}, a choice among names: "
                                         f"an expression takes numbers only.")
            if name in free:
                continue
            if name == p.key or name in {q.key for q in params}:
                raise fail(label, where, f"= {p.equals!r} names {name}, itself linked: write "
                                         f"it with the parameters the plan varies "
                                         f"({', '.join(free)}).")
            hint = suggest(name, set(free))
            raise fail(label, where, f"= {p.equals!r} names {name}, which is not a parameter "
                                     f"of this study (they are {', '.join(free)})."
                                     f"{hint if 'Did you mean' in hint else ''}")
        nominal = float(expression.evaluate(tree, {k: q.nominal for k, q in free.items()}))
        if not math.isfinite(nominal):
            raise fail(label, where, f"= {p.equals!r} is {nominal} at the nominal variant "
                                     f"(a division by zero?).")
        out.append(replace(p, nominal=nominal))
    return tuple(out)


def _flatten(table: dict, prefix: str = "") -> dict[str, Any]:
    """Nested TOML tables to dotted keys (``[parameters.dyad.2]`` as well as
    ``"dyad.2.length" = ...``); parameter entries (tables with value keys) stay."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and not (set(value) & {"range", "uniform", "tol", "sd",
                                                          "nominal", "step", "equals",
                                                          "choices"}):
            out.update(_flatten(value, f"{name}."))
        else:
            out[name] = value
    return out
