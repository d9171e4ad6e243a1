"""Periodic orbits of a periodically forced system and their continuation in a parameter.

The system is ``dx/ds = f(s, x, p)`` with ``f`` periodic in the independent variable ``s``
(period ``Problem.period``; the drive line's crank angle, a forced oscillator's phase),
``x`` a state of ``d`` components and ``p`` a row of parameters, the first of which
(``p[0]``) is the one continued (the drive line's speed Ω, the oscillator's forcing
frequency). Everything is vectorised over lanes: ``x`` is (L, d), ``p`` is (L, q).

- ``flow``: the classical Runge–Kutta method on a uniform grid of ``steps`` steps per
  period (the field is asked at the half steps, index ``k`` = 0 … 2·steps, so that tables
  sampled on the grid serve as the field).
- ``shoot``: the periodic solutions (fixed points of the period map x(0) → x(T), over
  ``periods`` periods for a subharmonic orbit) of all lanes by Newton's method, the
  monodromy matrix ∂x(T)/∂x(0) by central differences of the map (all 2d + 1 runs of
  every lane in one integration), and the step count **by accuracy**: the solution is
  solved again with twice the steps until the state at s = 0 (relative to the problem's
  scale) and the Floquet multipliers change by less than ``tol``; a lane is reported
  ``converged`` only then, else with the reason (Newton did not converge, or the solution
  still changed at the most steps). The change is the lane's ``accuracy`` (RK4: the
  finer solution's own error is about a fifteenth of it).
- ``continuation``: the branch of periodic solutions followed in ``p[0]`` by
  pseudo-arclength continuation (secant-free: the tangent is the null vector of
  [M − I, ∂Φ/∂p], oriented by the previous one) with step control by the corrector's
  iterations and the tangent's turn, through folds; folds located where the tangent's
  ``p`` component changes sign (cubic Hermite through the two points and their tangents),
  each point's multipliers kept and the loss of stability classified: a real multiplier
  through +1 (fold, saddle-node), through −1 (period doubling), a complex pair through the
  unit circle (Neimark–Sacker).
- ``boundary``: a stability boundary in a plane of two parameters (p[0] solved, p[1]
  given): where a multiplier is +1 (fold) or −1 (period doubling), det(M − σI) = 0 by
  the secant method in p[0] at fixed p[1], many p[1] at once (lanes, in blocks), each
  converged to ``BOUNDARY_TOL`` and by accuracy with twice the steps; block to block
  the curve is predicted from its last points.

References: Seydel, *Practical Bifurcation and Stability Analysis* (shooting, the
monodromy matrix, pseudo-arclength continuation, test functions of the bifurcations);
Nayfeh & Balachandran, *Applied Nonlinear Dynamics* (Floquet multipliers).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray

Field = Callable[[int, FloatArray, FloatArray], FloatArray]
"""f(k, x, p): dx/ds at the half step k (s = k·h/2, k taken modulo 2·steps), x (L, d),
p (L, q) -> (L, d)"""

NEWTON_TOL = 1e-10  # [-] scaled residual of the period map that counts as periodic
NEWTON_MAX_ITER = 15  # most Newton iterations of a shooting
DIFFERENCE = 1e-6  # [-] central-difference step of the monodromy matrix, per scale
ACCURACY = 1e-6  # [-] the change of the solution and multipliers with twice the steps
MOST_DOUBLINGS = 4  # [-] the steps are doubled at most this often (720 -> 11520)
UNSTABLE_MARGIN = 1e-6  # [-] |μ| above 1 + this: unstable
REAL = 1e-7  # [-] a multiplier with |Im μ| below this share of |μ| counts as real

STABLE, FOLD, FLIP, TORUS = "", "fold", "period doubling", "Neimark–Sacker"
"""the kinds of a periodic solution's loss of stability (the multiplier that leaves the
unit circle: +1, −1, a complex pair); STABLE: none leaves"""


@dataclass(frozen=True, slots=True, eq=False)  # holds callables: no meaningful ==
class Problem:
    """A periodically forced system ``dx/ds = f(s, x, p)`` (module docstring).

    Parameters
    ----------
    dimension : int
        d, the size of the state.
    field : callable
        ``field(steps)`` -> ``f(k, x, p)`` on the grid of ``steps`` steps per period
        (``Field``); it may build tables once per ``steps``.
    scale : callable
        ``scale(p)`` (B, q) -> (B, d): the size of each state component (residuals,
        differences and accuracies are measured against it), positive.
    period : float
        T: the period of the independent variable.
    steps : int
        The first step count per period of ``shoot`` (doubled by accuracy).
    """

    dimension: int
    field: Callable[[int], Field]
    scale: Callable[[FloatArray], FloatArray]
    period: float = 2.0 * math.pi
    steps: int = 720
    span: Callable[[FloatArray], FloatArray] | None = None
    """``span(p)`` (B, q) -> (B, d): how far each component may range along a branch
    (the continuation measures its steps against it; default ``scale``)"""
    field_at: Callable[[FloatArray, FloatArray, FloatArray], FloatArray] | None = None
    """``field_at(s, x, p)``: dx/ds at any s (L,) per lane (for a ``mesh`` of its own per
    lane, ``flow``); None: the problem has only its uniform grids"""
    pace: Callable[[FloatArray, FloatArray], FloatArray] | None = None
    """``pace(x, p)`` (…, L, d), (L, q) -> (…, L): how fast the motion goes per unit s
    against its pace on a uniform grid (the drive line: Ω over the crank's speed); a
    ``mesh`` puts its nodes by ``max(1, pace)`` (``mesh_of``)"""
    _fields: dict = field(default_factory=dict, repr=False)

    def at(self, steps: int) -> Field:
        """The field on ``steps`` steps per period (built once per step count)."""
        if steps not in self._fields:
            self._fields[steps] = self.field(steps)
        return self._fields[steps]


def flow(problem: Problem, steps: int, x0: FloatArray, p: FloatArray, periods: int = 1,
         mesh: FloatArray | None = None) -> FloatArray:
    """x(periods·T) from x(0) = ``x0`` (L, d) with the parameters ``p`` (L, q), by RK4
    on ``steps`` steps per period, or on each lane's ``mesh`` (L, N + 1): the nodes
    0 = s_0 < … < s_N = T of its steps (``problem.field_at``)."""
    if mesh is not None:
        return _on_mesh(problem, mesh, x0, p, periods, False)
    return _uniform(problem, steps, x0, p, periods, False)


def trajectory(problem: Problem, steps: int, x0: FloatArray, p: FloatArray, periods: int = 1,
               mesh: FloatArray | None = None) -> FloatArray:
    """The states at the grid nodes s = n·h, n = 0 … steps·periods (or at the nodes of
    each lane's ``mesh``): (K + 1, L, d)."""
    if mesh is not None:
        return _on_mesh(problem, mesh, x0, p, periods, True)
    return _uniform(problem, steps, x0, p, periods, True)


def _uniform(problem: Problem, steps: int, x0: FloatArray, p: FloatArray, periods: int,
             keep: bool) -> FloatArray:
    """RK4 on ``steps`` equal steps per period, the field tabulated at the half steps;
    the last state, or (``keep``) every node's."""
    f = problem.at(steps)
    h = problem.period / steps
    x = np.array(x0, dtype=np.float64)
    out = np.empty((steps * periods + 1,) + x.shape) if keep else None
    if keep:
        out[0] = x
    for n in range(steps * periods):
        k = 2 * (n % steps)
        k1 = f(k, x, p)
        k2 = f(k + 1, x + 0.5 * h * k1, p)
        k3 = f(k + 1, x + 0.5 * h * k2, p)
        k4 = f(k + 2, x + h * k3, p)
        x = x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        if keep:
            out[n + 1] = x
    return out if keep else x


def _on_mesh(problem: Problem, mesh: FloatArray, x0: FloatArray, p: FloatArray, periods: int,
             keep: bool) -> FloatArray:
    """RK4 over each lane's own nodes ``mesh`` (L, N + 1), the field at any s."""
    f = problem.field_at
    if f is None:
        raise ValueError("a mesh of its own per lane needs the problem's field_at")
    mesh = np.asarray(mesh, dtype=np.float64)
    steps = mesh.shape[1] - 1
    widths = np.diff(mesh, axis=1)
    x = np.array(x0, dtype=np.float64)
    out = np.empty((steps * periods + 1,) + x.shape) if keep else None
    if keep:
        out[0] = x
    for n in range(steps * periods):
        j = n % steps
        s0 = mesh[:, j] + (n // steps) * problem.period
        h = widths[:, j]
        hh = h[:, None]
        k1 = f(s0, x, p)
        k2 = f(s0 + 0.5 * h, x + 0.5 * hh * k1, p)
        k3 = f(s0 + 0.5 * h, x + 0.5 * hh * k2, p)
        k4 = f(s0 + h, x + hh * k3, p)
        x = x + hh / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        if keep:
            out[n + 1] = x
    return out if keep else x


def mesh_of(problem: Problem, steps: int, x0: FloatArray, p: FloatArray, nodes: int,
            mesh: FloatArray | None = None) -> FloatArray:
    """Each lane's own mesh (L, nodes + 1) over one period: the nodes spread by the
    density max(1, ``problem.pace``) along the motion from ``x0`` (L, d) (integrated on
    ``steps`` uniform steps, or on ``mesh``), so that where the motion goes slowly in s
    (a crank that nearly stops: its steps in crank angle are then steps in time) the
    nodes gather. A lane whose motion is lost (not finite) gets the uniform mesh."""
    p = np.atleast_2d(np.asarray(p, dtype=np.float64))
    path = trajectory(problem, steps, x0, p, 1, mesh)  # (K + 1, L, d)
    s = (np.broadcast_to(np.linspace(0.0, problem.period, steps + 1)[:, None],
                         path.shape[:2]) if mesh is None else np.asarray(mesh).T)
    density = np.maximum(1.0, problem.pace(path, p))  # (K + 1, L)
    cumulative = np.concatenate((np.zeros((1, density.shape[1])), np.cumsum(
        0.5 * (density[1:] + density[:-1]) * np.diff(s, axis=0), axis=0)))
    lanes = density.shape[1]
    out = np.empty((lanes, nodes + 1))
    fine = np.isfinite(cumulative[-1]) & (cumulative[-1] > 0.0)
    target = np.linspace(0.0, 1.0, nodes + 1)
    out[~fine] = np.linspace(0.0, problem.period, nodes + 1)
    if fine.any():
        c = cumulative[:, fine] / cumulative[-1, fine]  # (K + 1, F) from 0 to 1
        # inverse of each lane's monotone c(s) at the targets, all lanes at once: the
        # lanes side by side on one axis (lane f's values shifted by 2f)
        shift = 2.0 * np.arange(c.shape[1])
        flat = (c + shift).T.ravel()
        want = (target[None, :] + shift[:, None]).ravel()
        i = np.clip(np.searchsorted(flat, want, side="right") - 1, 0, flat.size - 2)
        k = c.shape[0]
        i = np.minimum(i, (i // k) * k + k - 2)  # stay within the lane
        low, high = flat[i], flat[i + 1]
        frac = np.where(high > low, (want - low) / np.where(high > low, high - low, 1.0), 0.0)
        sf = s[:, fine].T.ravel()
        found = (sf[i] + frac * (sf[i + 1] - sf[i])).reshape(-1, nodes + 1)
        found[:, 0], found[:, -1] = 0.0, problem.period
        out[fine] = found
    return out


def refined(mesh: FloatArray) -> FloatArray:
    """Every step of each lane's ``mesh`` (L, N + 1) halved: (L, 2N + 1)."""
    mesh = np.asarray(mesh, dtype=np.float64)
    out = np.empty((mesh.shape[0], 2 * mesh.shape[1] - 1))
    out[:, 0::2] = mesh
    out[:, 1::2] = 0.5 * (mesh[:, 1:] + mesh[:, :-1])
    return out


def period_map(problem: Problem, steps: int, x0: FloatArray, p: FloatArray, scale: FloatArray,
               periods: int = 1, parameter: bool = False, mesh: FloatArray | None = None
               ) -> tuple[FloatArray, FloatArray, FloatArray | None]:
    """Φ(x0) (B, d), the monodromy matrix ∂Φ/∂x0 (B, d, d) by central differences, and
    with ``parameter`` ∂Φ/∂p[0] (B, d): every run of every lane in one integration."""
    b, d = x0.shape
    runs = 2 * d + 1 + (2 if parameter else 0)
    delta = DIFFERENCE * scale
    xs = np.repeat(x0[:, None, :], runs, axis=1)
    ps = np.repeat(np.asarray(p, dtype=np.float64)[:, None, :], runs, axis=1)
    for i in range(d):
        xs[:, 1 + 2 * i, i] += delta[:, i]
        xs[:, 2 + 2 * i, i] -= delta[:, i]
    dp = DIFFERENCE * np.maximum(np.abs(ps[:, 0, 0]), 1e-300)
    if parameter:
        ps[:, -2, 0] += dp
        ps[:, -1, 0] -= dp
    if mesh is not None:
        mesh = np.repeat(np.asarray(mesh, dtype=np.float64), runs, axis=0)
    end = flow(problem, steps, xs.reshape(-1, d), ps.reshape(b * runs, -1), periods, mesh)
    end = end.reshape(b, runs, d)
    jac = (end[:, 1:2 * d + 1:2, :] - end[:, 2:2 * d + 1:2, :]) / (2.0 * delta[:, :, None])
    by_p = (end[:, -2, :] - end[:, -1, :]) / (2.0 * dp[:, None]) if parameter else None
    return end[:, 0, :], np.swapaxes(jac, 1, 2), by_p


def ordered(multipliers: FloatArray) -> FloatArray:
    """Multipliers (B, d) sorted by modulus, largest first (complex)."""
    multipliers = np.asarray(multipliers, dtype=complex)
    order = np.argsort(-np.abs(multipliers), axis=-1, kind="stable")
    return np.take_along_axis(multipliers, order, axis=-1)


def newton(problem: Problem, steps: int, p: FloatArray, guess: FloatArray, scale: FloatArray,
           periods: int = 1, progress: Callable[[], None] | None = None,
           mesh: FloatArray | None = None
           ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, int]:
    """Shooting on one step count for all lanes: the state (B, d), converged (B,), the
    scaled residual (B,), the monodromy matrix at the last evaluation (B, d, d) and the
    iterations. A lane is converged when its residual, evaluated at the state returned,
    is at most ``NEWTON_TOL`` (the matrix is then the solution's)."""
    x = np.array(guess, dtype=np.float64)
    b, d = x.shape
    done = np.zeros(b, dtype=bool)
    residual = np.full(b, np.inf)
    jac = np.full((b, d, d), np.nan)
    active = np.ones(b, dtype=bool)
    iteration = 0
    for iteration in range(1, NEWTON_MAX_ITER + 1):
        idx = np.flatnonzero(active)
        end, j, _ = period_map(problem, steps, x[idx], p[idx], scale[idx], periods,
                               mesh=None if mesh is None else mesh[idx])
        if progress is not None:
            progress()
        jac[idx] = j
        miss = end - x[idx]
        res = np.max(np.abs(miss) / scale[idx], axis=1)
        res = np.where(np.isfinite(res), res, np.inf)
        residual[idx] = res
        ok = res <= NEWTON_TOL
        done[idx] = ok
        lost = ~np.isfinite(res)
        active[idx[ok | lost]] = False
        if not active.any():
            break
        go = ~ok & ~lost
        system = j[go] - np.eye(d)
        step = np.zeros((int(go.sum()), d))
        fine = np.isfinite(system).all(axis=(1, 2))
        if fine.any():
            try:
                step[fine] = np.linalg.solve(system[fine], -miss[go][fine][:, :, None])[:, :, 0]
            except np.linalg.LinAlgError:  # a singular lane: solve one by one
                for n in np.flatnonzero(fine):
                    try:
                        step[n] = np.linalg.solve(system[n], -miss[go][n])
                    except np.linalg.LinAlgError:
                        step[n] = 0.0
        # damp large steps: at most half the state's scale per iteration
        size = np.max(np.abs(step) / scale[idx[go]], axis=1, keepdims=True)
        step *= np.minimum(1.0, 0.5 / np.maximum(size, 1e-300))
        x[idx[go]] += step
    return x, done, residual, jac, iteration


def multiplier_change(a: FloatArray, b: FloatArray) -> FloatArray:
    """(B,) the largest change between two sets of multipliers (B, d): their moduli and
    their real parts each sorted (invariant to the order of a conjugate pair)."""
    return np.maximum(np.max(np.abs(np.sort(np.abs(a), axis=1) - np.sort(np.abs(b), axis=1)),
                             axis=1),
                      np.max(np.abs(np.sort(a.real, axis=1) - np.sort(b.real, axis=1)), axis=1))


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Solutions:
    """Periodic solutions of B lanes (``shoot``)."""

    parameter: FloatArray
    """(B, q) the parameters"""
    start: FloatArray
    """(B, d) the state at s = 0 (NaN where none was found)"""
    converged: FloatArray
    """(B,) bool: periodic to ``NEWTON_TOL`` and changed by less than the tolerance with
    twice the steps"""
    steps: FloatArray
    """(B,) int: the steps per period of the solution (the finer of the last two)"""
    accuracy: FloatArray
    """(B,) the change of the state (scaled) and the multipliers with twice the steps
    [-]; NaN where no two step counts were compared"""
    residual: FloatArray
    """(B,) the scaled residual of the period map [-]"""
    monodromy: FloatArray
    """(B, d, d) ∂Φ/∂x0 at the solution"""
    multipliers: FloatArray
    """(B, d) complex Floquet multipliers, largest modulus first (NaN where not
    converged)"""
    reason: list = field(default_factory=list)
    """(B,) str: why a lane is not converged ("" where it is)"""
    periods: int = 1
    """the periods of the map (2: a period-2 orbit)"""
    mesh: list | None = None
    """(B,) each lane's own nodes (N + 1,) of its solution, when shot on meshes (else
    None: ``steps`` uniform steps)"""

    @property
    def stability(self) -> FloatArray:
        """(B,) the largest |μ| (NaN where not converged)."""
        return np.where(self.converged, np.abs(self.multipliers[:, 0]), np.nan)

    @property
    def unstable(self) -> FloatArray:
        """(B,) bool: a multiplier outside the unit circle (False where not converged:
        no verdict, see ``converged``)."""
        return self.converged & (np.nan_to_num(self.stability) > 1.0 + UNSTABLE_MARGIN)

    @property
    def kind(self) -> list[str]:
        """(B,) how each lane is unstable (``kind_of``); "" stable or not converged."""
        return [kind_of(mu) if ok else STABLE for mu, ok in zip(self.multipliers,
                                                                self.converged)]


def kind_of(multipliers: FloatArray) -> str:
    """The kind of instability of one solution from its multipliers (largest first):
    STABLE, FOLD (a real one beyond +1), FLIP (beyond −1) or TORUS (a complex pair)."""
    mu = complex(multipliers[0])
    if not abs(mu) > 1.0 + UNSTABLE_MARGIN:
        return STABLE
    if abs(mu.imag) > REAL * abs(mu):
        return TORUS
    return FOLD if mu.real > 0.0 else FLIP


def shoot(problem: Problem, p: FloatArray, guess: FloatArray, *, steps: int | None = None,
          tol: float = ACCURACY, doublings: int = MOST_DOUBLINGS, periods: int = 1,
          progress: Callable[[], None] | None = None, mesh: FloatArray | None = None,
          retry: bool = True) -> Solutions:
    """The periodic solutions of all lanes with the steps chosen by accuracy (module
    docstring).

    Parameters
    ----------
    problem : Problem
    p : array_like, shape (B, q)
        The parameters of each lane.
    guess : array_like, shape (B, d)
        The starting states.
    steps : int, optional
        The first step count (default ``problem.steps``).
    tol : float
        The largest change of the solution (scaled) and its multipliers with twice the
        steps that counts as converged [-].
    doublings : int
        How often the steps may be doubled (then a lane that still changes is not
        converged).
    periods : int
        Periods of the map (2: a period-2 orbit).
    progress : callable, optional
        ``progress()`` hears each Newton iteration (all lanes at once).
    mesh : array_like, shape (B, N + 1), optional
        Each lane's own nodes over one period (``mesh_of``; instead of ``steps``
        uniform steps): its steps are halved by accuracy (``refined``), the solution's
        mesh is ``Solutions.mesh``.
    retry : bool
        A lane whose shooting fails is tried once more with twice the steps (False: it
        is given up, e.g. one of several seeds of one solution).

    Returns
    -------
    Solutions
    """
    p = np.atleast_2d(np.asarray(p, dtype=np.float64))
    guess = np.atleast_2d(np.asarray(guess, dtype=np.float64))
    b, d = guess.shape
    scale = problem.scale(p)
    if mesh is not None:
        mesh = np.array(mesh, dtype=np.float64)
        n = mesh.shape[1] - 1
    else:
        n = steps or problem.steps
    x, ok, residual, jac, _ = newton(problem, n, p, guess, scale, periods, progress, mesh)
    meshes = list(mesh) if mesh is not None else None
    mult = ordered(np.linalg.eigvals(np.where(np.isfinite(jac), jac, 0.0)))
    lane_steps = np.full(b, n)
    accuracy = np.full(b, np.nan)
    settled = np.zeros(b, dtype=bool)
    retry = ~ok & retry  # a lane whose shooting failed: once more with twice the steps
    for _ in range(doublings):
        todo = np.flatnonzero(~settled & (ok | retry))
        if not todo.size:
            break
        n *= 2
        fine = None
        if mesh is not None:  # the lanes still to do share their count of halvings
            fine = refined(np.array([meshes[j] for j in todo]))
            for j, row in zip(todo, fine):
                meshes[j] = row
        start = np.where(ok[todo, None], x[todo], guess[todo])
        x2, ok2, res2, jac2, _ = newton(problem, n, p[todo], start, scale[todo], periods,
                                        progress, fine)
        mult2 = ordered(np.linalg.eigvals(np.where(np.isfinite(jac2), jac2, 0.0)))
        change = np.maximum(np.max(np.abs(x2 - x[todo]) / scale[todo], axis=1),
                            multiplier_change(mult2, mult[todo]))
        both = ok[todo] & ok2
        accuracy[todo] = np.where(both, change, np.nan)
        settled[todo] = both & (change <= tol)
        retry[todo] = False
        x[todo], ok[todo], residual[todo], jac[todo] = x2, ok2, res2, jac2
        mult[todo] = mult2
        lane_steps[todo] = n
    reason = []
    for j in range(b):
        if settled[j]:
            reason.append("")
        elif not ok[j]:
            reason.append(f"no periodic solution found: the shooting did not converge with up "
                          f"to {lane_steps[j]:,} steps per period (scaled residual "
                          f"{residual[j]:.2g})")
        else:
            reason.append(f"the periodic solution still changes by {accuracy[j]:.2g} with "
                          f"{lane_steps[j]:,} steps per period (tolerance {tol:.2g})")
    mult = np.where(settled[:, None], mult, np.nan)
    x = np.where(ok[:, None], x, np.nan)
    return Solutions(p, x, settled, lane_steps, accuracy, residual, jac, mult, reason, periods,
                     meshes)


# -- continuation -----------------------------------------------------------------------
@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Fold:
    """A fold (turning point) of a branch: there the branch turns back in p[0]."""

    parameter: float
    """p[0] at the fold"""
    start: FloatArray
    """(d,) the state at s = 0 there (Hermite interpolation)"""
    index: int
    """the branch's points ``index`` and ``index + 1`` bracket it"""
    upper: bool
    """True where p[0] is largest (the branch came up in p[0] and turns back: a sweep
    upwards jumps here); False where smallest (a sweep downwards jumps here)"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Branch:
    """A branch of periodic solutions in p[0] (``continuation``)."""

    parameter: FloatArray
    """(n, q) the parameters of the points"""
    start: FloatArray
    """(n, d) the states at s = 0"""
    multipliers: FloatArray
    """(n, d) complex, largest modulus first"""
    tangent: FloatArray
    """(n, d + 1) the unit tangents in scaled variables (state, p[0])"""
    steps: FloatArray
    """(n,) int: steps per period of each point's integration"""
    folds: list
    """``Fold``s, along the branch"""
    stopped: str = ""
    """why the continuation stopped ("" when it left the parameter range)"""

    @property
    def unstable(self) -> FloatArray:
        return np.abs(self.multipliers[:, 0]) > 1.0 + UNSTABLE_MARGIN

    @property
    def kind(self) -> list[str]:
        return [kind_of(mu) for mu in self.multipliers]

    def crossings(self, value: float) -> list[tuple[int, float]]:
        """Where the branch passes p[0] = ``value``: (segment i, fraction along i -> i + 1)."""
        p = self.parameter[:, 0]
        out = []
        for i in range(p.size - 1):
            a, b = p[i] - value, p[i + 1] - value
            if a == 0.0:
                out.append((i, 0.0))
            elif a * b < 0.0 or (b == 0.0 and i == p.size - 2):
                out.append((i, a / (a - b)))
        return out


def _tangent(a: FloatArray, previous: FloatArray | None, direction: float) -> FloatArray:
    """The unit null vector of the d × (d + 1) matrix ``a``, oriented along ``previous``
    (or with its last component of the sign of ``direction``)."""
    d = a.shape[0]
    if previous is not None:
        system = np.vstack((a, previous))
        rhs = np.zeros(d + 1)
        rhs[-1] = 1.0
        try:
            t = np.linalg.solve(system, rhs)
            return t / np.linalg.norm(t)
        except np.linalg.LinAlgError:
            pass
    t = np.linalg.svd(a)[2][-1]
    if previous is not None:
        return t if np.dot(t, previous) >= 0.0 else -t
    return t if t[-1] * direction >= 0.0 else -t


def continuation(problem: Problem, x0: FloatArray, p0: FloatArray, bounds: tuple[float, float],
                 *, steps: int, direction: float = 1.0, ds: float = 0.05, ds_max: float = 1.0,
                 ds_min: float = 1e-7, most: int = 400, turn: float = 0.4,
                 finest: int | None = None, refine: float = 1e-3,
                 integrations: int | None = None, width: float | None = None,
                 progress: Callable[[], None] | None = None) -> Branch:
    """Follow the periodic solution through ``x0`` at ``p0`` (q,) in p[0] until it leaves
    ``bounds`` (the last point lies just beyond), by pseudo-arclength continuation
    (module docstring) on ``steps`` steps per period.

    Parameters
    ----------
    problem : Problem
    x0 : array_like, shape (d,)
        A state near the periodic solution at ``p0`` (corrected first).
    p0 : array_like, shape (q,)
        The parameters; p[0] is continued.
    bounds : (float, float)
        The range of p[0].
    steps : int
        Steps per period (use one that ``shoot`` found accurate).
    direction : float
        +1: start towards larger p[0], −1: smaller.
    ds, ds_max, ds_min : float
        First, largest and smallest step along the branch in scaled variables (the state
        over ``problem.scale``, p[0] over the width of ``bounds``).
    most : int
        The most points.
    turn : float
        The largest angle between neighbouring tangents [rad]: a step that turns more
        is halved (resolves the folds).
    finest : int, optional
        The most steps per period: where the step along the branch falls below
        ``refine`` (the branch bends sharply, or the corrector fails: the integration
        is too coarse there, e.g. where a crank nearly stops), the steps are doubled up
        to this and the point corrected again.
    refine : float
        The step along the branch below which the steps are doubled.
    integrations : int, optional
        The most integrations (each one period of the 2d + 3 runs of a point): the
        continuation stops there, saying so in ``stopped``.
    width : float, optional
        The measure of p[0] in the scaled variables (default the width of ``bounds``):
        a narrow ``bounds`` (a fold sought between two speeds) keeps the steps of a
        whole range.
    progress : callable, optional
        ``progress()`` hears each integration.

    Returns
    -------
    Branch
    """
    p0 = np.asarray(p0, dtype=np.float64).ravel()
    low, high = bounds
    width = width or (high - low) or abs(p0[0]) or 1.0
    d = problem.dimension
    # the state measured against its own size at the start (at least the problem's scale):
    # steps along the branch follow the parameter unless the state changes by its size
    s_x = np.maximum((problem.span or problem.scale)(p0[None, :])[0],
                     np.abs(np.asarray(x0, dtype=np.float64)))

    spent = 0

    def exhausted() -> bool:
        return integrations is not None and spent >= integrations

    def evaluate(y):
        nonlocal spent
        spent += 1
        x = y[:d] * s_x
        p = p0.copy()
        p[0] = y[d] * width
        end, jac, by_p = period_map(problem, steps, x[None], p[None], s_x[None], 1, True)
        if progress is not None:
            progress()
        g = (end[0] - x) / s_x
        a = np.empty((d, d + 1))
        a[:, :d] = (jac[0] - np.eye(d)) * s_x[None, :] / s_x[:, None]
        a[:, d] = by_p[0] * width / s_x
        return g, a, jac[0]

    def correct(y, t=None, y_pred=None):
        """Newton on the periodicity (and the arclength condition): y, a, M, iterations
        or None."""
        for iteration in range(1, 9):
            if exhausted():
                return None
            g, a, jac = evaluate(y)
            if not np.all(np.isfinite(g)) or not np.all(np.isfinite(a)):
                return None
            if np.max(np.abs(g)) <= NEWTON_TOL:
                return y, a, jac, iteration
            if t is None:  # p[0] held
                try:
                    dy = np.linalg.solve(a[:, :d], -g)
                except np.linalg.LinAlgError:
                    return None
                y = y.copy()
                y[:d] += dy
            else:
                system = np.vstack((a, t))
                rhs = -np.append(g, np.dot(t, y - y_pred))
                try:
                    y = y + np.linalg.solve(system, rhs)
                except np.linalg.LinAlgError:
                    return None
        return None

    y = np.append(np.asarray(x0, dtype=np.float64) / s_x, p0[0] / width)
    first = correct(y)
    if first is None:
        return Branch(np.empty((0, p0.size)), np.empty((0, d)), np.empty((0, d), complex),
                      np.empty((0, d + 1)), np.empty(0, dtype=int), [],
                      "the first point did not converge")
    y, a, jac, _ = first
    t = _tangent(a, None, direction)
    points, tangents, mults = [y], [t], [ordered(np.linalg.eigvals(jac)[None])[0]]
    used = [steps]
    finest = finest or steps
    stopped = ""
    while len(points) < most:
        if not (low <= y[d] * width <= high):
            break
        done = None
        while done is None:
            y_pred = y + ds * t
            done = correct(y_pred, t, y_pred)
            if done is not None:
                t_new = _tangent(done[1], t, direction)
                if np.dot(t_new, t) < math.cos(turn) and ds > ds_min:
                    done = None
            if done is None:
                if exhausted():
                    break
                ds *= 0.5
                if ds < refine and 2 * steps <= finest:
                    steps *= 2  # finer, and the last point again on the finer grid
                    again = correct(y, t, y)
                    if again is None:
                        steps //= 2
                    else:
                        y, t = again[0], _tangent(again[1], t, direction)
                        points[-1], tangents[-1] = y, t
                        mults[-1] = ordered(np.linalg.eigvals(again[2])[None])[0]
                        used[-1] = steps
                        ds = 4.0 * refine
                if ds < ds_min:
                    break
        if done is None:
            stopped = (f"the continuation ran out of its {integrations} integrations"
                       if exhausted() else
                       f"the continuation could not step on at p = {y[d] * width:.6g} "
                       f"(the step fell below {ds_min:g})")
            break
        y, _, jac, iterations = done
        t = t_new
        points.append(y)
        tangents.append(t)
        mults.append(ordered(np.linalg.eigvals(jac)[None])[0])
        used.append(steps)
        if iterations <= 4:
            ds = min(ds * 1.6, ds_max)
    else:
        stopped = f"the continuation stopped after {most} points"
    ys, ts = np.array(points), np.array(tangents)
    params = np.repeat(p0[None, :], len(points), axis=0)
    params[:, 0] = ys[:, d] * width
    folds = []
    for i in range(len(points) - 1):
        if ts[i, d] * ts[i + 1, d] < 0.0:
            # confirmed with twice the steps: both points again, their tangents' p[0]
            # components still of opposite sign (else an artefact of a coarse grid)
            steps = 2 * max(used[i], used[i + 1])
            if steps <= 2 * finest:
                again = [correct(ys[j], ts[j], ys[j]) for j in (i, i + 1)]
                if all(a is not None for a in again):
                    signs = [_tangent(a[1], ts[j], direction)[d]
                             for a, j in zip(again, (i, i + 1))]
                    if signs[0] * signs[1] >= 0.0:
                        continue
            folds.append(_fold(ys[i], ys[i + 1], ts[i], ts[i + 1], d, s_x, width, i))
    return Branch(params, ys[:, :d] * s_x, np.array(mults), ts, np.array(used), folds, stopped)


def _fold(y0, y1, t0, t1, d, s_x, width, index) -> Fold:
    """The turning point between two points of a branch from the cubic Hermite
    interpolation in arclength of the points and their unit tangents."""
    length = float(np.linalg.norm(y1 - y0))
    # p(σ) on σ ∈ [0, 1]: p0, p1, slopes length·t0[d], length·t1[d]; p'(σ) = 0
    p0, p1, m0, m1 = y0[d], y1[d], length * t0[d], length * t1[d]
    # derivative of the Hermite cubic: a·σ² + b·σ + c
    a = 6 * p0 + 3 * m0 - 6 * p1 + 3 * m1
    b = -6 * p0 - 4 * m0 + 6 * p1 - 2 * m1
    c = m0
    roots = np.roots([a, b, c]) if abs(a) > 1e-300 else np.array([-c / b])
    roots = roots[np.isreal(roots)].real
    roots = roots[(roots >= -1e-9) & (roots <= 1 + 1e-9)]
    sigma = float(roots[0]) if roots.size else -m0 / (m1 - m0)

    def hermite(v0, v1, w0, w1, s):
        return ((2 * s ** 3 - 3 * s ** 2 + 1) * v0 + (s ** 3 - 2 * s ** 2 + s) * w0
                + (-2 * s ** 3 + 3 * s ** 2) * v1 + (s ** 3 - s ** 2) * w1)

    y = hermite(y0, y1, length * t0, length * t1, sigma)
    return Fold(float(y[d] * width), y[:d] * s_x, index, bool(t0[d] > 0.0))


def branch_guesses(branch: Branch, value: float) -> list[FloatArray]:
    """Starting states on ``branch`` at p[0] = ``value``: one per crossing, by linear
    interpolation between the points (a Newton start)."""
    return [branch.start[i] + frac * (branch.start[i + 1] - branch.start[i])
            for i, frac in branch.crossings(value)]


# -- stability boundaries in a plane of two parameters ----------------------------------
BOUNDARY_TOL = 1e-9  # [-] the secant's last step in p[0], per max(|p[0]|, 1), that counts
SECANT_MAX_ITER = 30  # most secant iterations of a boundary point on one step count


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Boundary:
    """A stability boundary traced in the plane (p[0], p[1]) (``boundary``): at each of
    its points a Floquet multiplier of the periodic solution is ``crossing`` (+1: a fold,
    −1: period doubling)."""

    parameter: FloatArray
    """(n, q) the parameters of the points: p[0] solved (NaN where not converged), the
    others as given"""
    start: FloatArray
    """(n, d) the periodic solution's state at s = 0 there"""
    multipliers: FloatArray
    """(n, d) complex, largest modulus first (NaN where not converged)"""
    converged: FloatArray
    """(n,) bool: the secant converged to ``BOUNDARY_TOL`` and p[0] changed by at most the
    tolerance with twice the steps"""
    steps: FloatArray
    """(n,) int: steps per period of each point (the finer of the last two)"""
    accuracy: FloatArray
    """(n,) the change of p[0] with twice the steps, per max(|p[0]|, 1) [-]"""
    crossing: float
    """+1.0 (FOLD) or −1.0 (FLIP)"""
    reason: list = field(default_factory=list)
    """(n,) str: why a point is not converged ("" where it is)"""

    @property
    def kind(self) -> str:
        return FOLD if self.crossing > 0.0 else FLIP


def crossing_measure(monodromy: FloatArray, crossing: float) -> FloatArray:
    """(B,) det(M − σI) = Π(μᵢ − σ) of monodromy matrices (B, d, d): zero where a
    multiplier is σ = ``crossing`` (+1 or −1), of one sign on each side of it."""
    d = monodromy.shape[-1]
    return np.linalg.det(monodromy - crossing * np.eye(d))


def _secant(problem: Problem, steps: int, p: FloatArray, guess: FloatArray, scale: FloatArray,
            crossing: float, reach: FloatArray, periods: int,
            progress: Callable[[], None] | None) -> tuple:
    """p[0] of all lanes where ``crossing_measure`` vanishes, by the secant method in
    p[0] (each evaluation: the periodic solution shot at that p[0], its monodromy
    matrix), each step at most ``reach`` (L,). Returns p[0] (L,), the states, the
    monodromy matrices, converged (L,) and the reason of each lane that is not."""
    p = np.array(p, dtype=np.float64)
    lanes = p.shape[0]
    x = np.array(guess, dtype=np.float64)

    def measure(values, idx):
        q = p[idx].copy()
        q[:, 0] = values
        state, ok, _, jac, _ = newton(problem, steps, q, x[idx], scale[idx], periods, progress)
        g = np.where(ok, crossing_measure(np.where(np.isfinite(jac), jac, 0.0), crossing),
                     np.nan)
        return g, state, jac, ok

    a = p[:, 0].copy()
    ga, state, jac, ok = measure(a, np.arange(lanes))
    x = np.where(ok[:, None], state, x)
    b = a + 1e-4 * np.maximum(np.abs(a), 1e-3)  # the secant's first second point
    monodromy = jac.copy()
    done = np.zeros(lanes, dtype=bool)
    reason = ["" for _ in range(lanes)]
    lost = ~np.isfinite(ga)
    for j in np.flatnonzero(lost):
        reason[j] = f"no periodic solution found at p[0] = {a[j]:.9g}"
    active = ~lost
    for _ in range(SECANT_MAX_ITER):
        idx = np.flatnonzero(active)
        if not idx.size:
            break
        gb, state, jac, ok = measure(b[idx], idx)
        bad = ~np.isfinite(gb)
        for n in np.flatnonzero(bad):
            reason[idx[n]] = f"no periodic solution found at p[0] = {b[idx[n]]:.9g}"
        x[idx[~bad]] = state[~bad]
        monodromy[idx] = jac
        slope = (gb - ga[idx]) / (b[idx] - a[idx])
        step = np.where(slope != 0.0, -gb / np.where(slope != 0.0, slope, 1.0), np.nan)
        step = np.clip(step, -reach[idx], reach[idx])
        flat = ~np.isfinite(step) & ~bad
        for n in np.flatnonzero(flat):
            reason[idx[n]] = "the measure det(M − σI) does not change with p[0] there"
        tol = BOUNDARY_TOL * np.maximum(np.abs(b[idx]), 1.0)
        finished = ~bad & ~flat & ((np.abs(b[idx] - a[idx]) <= tol) | (gb == 0.0))
        done[idx[finished]] = True
        active[idx[finished | bad | flat]] = False
        go = ~finished & ~bad & ~flat
        a[idx[go]], ga[idx[go]] = b[idx[go]], gb[go]
        b[idx[go]] = b[idx[go]] + step[go]
    for j in np.flatnonzero(active):
        reason[j] = f"the secant did not converge in {SECANT_MAX_ITER} iterations"
    return b, x, monodromy, done, reason


def boundary(problem: Problem, p: FloatArray, guess: FloatArray, *, crossing: float = -1.0,
             block: int = 8, steps: int | None = None, tol: float = ACCURACY,
             doublings: int = MOST_DOUBLINGS, reach: float | FloatArray | None = None,
             periods: int = 1, along: int = 1, follow: bool = True,
             progress: Callable[[], None] | None = None) -> Boundary:
    """Trace a stability boundary in the plane of p[0] (solved) and p[1] (given; or
    p[``along``]): the
    p[0] at each row of ``p`` where a Floquet multiplier of the periodic solution is
    ``crossing`` (+1: a fold, −1: period doubling, e.g. the edges of a Mathieu tongue).

    Each point is solved by the secant method in p[0] at its fixed p[1] on the
    condition det(M − σI) = 0 (``crossing_measure``; M the monodromy matrix of the
    solution shot at that p[0]) to ``BOUNDARY_TOL``, then again with twice the steps
    until p[0] changes by at most ``tol`` (per max(|p[0]|, 1)); a point is ``converged``
    only then. The rows are solved ``block`` at a time, all lanes of a block in one
    integration; the curve is followed block to block: each block's first guesses of
    p[0] (and of the state) are extrapolated from the last (up to three) converged
    points in p[1] (a polynomial through them), so the rows should go along the curve
    (p[1] monotone). The first block starts from the rows' own p[0].

    Parameters
    ----------
    problem : Problem
    p : array_like, shape (n, q)
        The rows: p[1] the given second parameter (monotone along the rows), p[0] the
        first guesses (used for the first block, and where too few points converged).
    guess : array_like, shape (n, d) or (d,)
        Starting states of the periodic solutions.
    crossing : float
        +1.0 (fold) or −1.0 (period doubling).
    block : int
        Rows solved together.
    steps : int, optional
        The first step count (default ``problem.steps``).
    tol : float
        The largest change of p[0] with twice the steps, per max(|p[0]|, 1) [-].
    doublings : int
        How often the steps may be doubled.
    reach : float or array_like (n,), optional
        The largest secant step in p[0] (default a tenth of max(|p[0]|, 1e-3) of the
        first row), per row: keeps a point on its own edge when two edges are near.
    periods : int
        Periods of the map.
    along : int
        The column of ``p`` that is the second parameter (default 1).
    follow : bool
        False: every row starts from its own p[0] and ``guess`` (e.g. crossings
        bracketed on a sampled grid, several curves at once), no extrapolation.
    progress : callable, optional
        ``progress()`` hears each Newton iteration of the shootings.

    Returns
    -------
    Boundary
    """
    p = np.atleast_2d(np.asarray(p, dtype=np.float64)).copy()
    n, q = p.shape
    if q < 2:
        raise ValueError("a boundary in a plane needs two parameters per row")
    if not 0 < along < q:
        raise ValueError("the second parameter is a column of p other than p[0]")
    if crossing not in (1.0, -1.0):
        raise ValueError("crossing is +1 (fold) or -1 (period doubling)")
    guess = np.broadcast_to(np.asarray(guess, dtype=np.float64),
                            (n, problem.dimension)).copy()
    first = steps or problem.steps
    limit = np.broadcast_to(np.asarray(reach if reach is not None
                                       else 0.1 * max(abs(p[0, 0]), 1e-3), dtype=np.float64),
                            (n,))
    out_p = np.full(n, np.nan)
    start = np.full((n, problem.dimension), np.nan)
    monodromy = np.full((n, problem.dimension, problem.dimension), np.nan)
    converged = np.zeros(n, dtype=bool)
    used = np.full(n, first)
    accuracy = np.full(n, np.nan)
    reason = ["" for _ in range(n)]
    for low in range(0, n, block):
        rows = np.arange(low, min(low + block, n))
        known = np.flatnonzero(converged[:low])[-3:] if follow else np.empty(0, int)
        trial = p[rows].copy()
        x0 = guess[rows].copy()
        if known.size:
            degree = min(known.size - 1, 2)
            if degree:
                fit = np.polyfit(p[known, along], out_p[known], degree)
                trial[:, 0] = np.polyval(fit, trial[:, along])
            else:
                trial[:, 0] = out_p[known[-1]]
            x0[:] = start[known[-1]]
        scale = problem.scale(trial)
        width = limit[rows].copy()
        count = first
        value, x, jac, ok, why = _secant(problem, count, trial, x0, scale, crossing, width,
                                         periods, progress)
        settled = np.zeros(rows.size, dtype=bool)
        change = np.full(rows.size, np.nan)
        for _ in range(doublings):
            todo = np.flatnonzero(ok & ~settled)
            if not todo.size:
                break
            count *= 2
            again = trial[todo].copy()
            again[:, 0] = value[todo]
            v2, x2, j2, ok2, why2 = _secant(problem, count, again, x[todo], scale[todo],
                                            crossing, width[todo], periods, progress)
            moved = np.abs(v2 - value[todo]) / np.maximum(np.abs(v2), 1.0)
            change[todo] = np.where(ok2, moved, np.nan)
            settled[todo] = ok2 & (moved <= tol)
            value[todo], x[todo], jac[todo], ok[todo] = v2, x2, j2, ok2
            for m, j in enumerate(todo):
                why[j] = why2[m]
                used[rows[j]] = count
        for m, j in enumerate(rows):
            if settled[m]:
                continue
            reason[j] = why[m] or (f"the boundary still moves by {change[m]:.2g} with "
                                   f"{used[j]:,} steps per period (tolerance {tol:.2g})")
        converged[rows] = settled
        out_p[rows] = np.where(settled, value, np.nan)
        start[rows] = np.where(settled[:, None], x, np.nan)
        monodromy[rows] = jac
        accuracy[rows] = change
    params = p.copy()
    params[:, 0] = out_p
    mult = ordered(np.linalg.eigvals(np.where(np.isfinite(monodromy), monodromy, 0.0)))
    mult = np.where(converged[:, None], mult, np.nan)
    return Boundary(params, start, mult, converged, used, accuracy, crossing, reason)
