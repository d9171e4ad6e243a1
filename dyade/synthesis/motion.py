"""Motion generation: a four-bar whose coupler passes through three poses (closed form,
its moving pivots given or chosen) or four (a pair of dyads from the Burmester curves),
chosen free of branch and order defects and with the largest least transmission angle,
each pose checked through dyade's positions-only stage."""

from __future__ import annotations

import numpy as np

from dyade.errors import DyadeError
from dyade.synthesis import closed

TOLERANCE = 1e-9
"""[-] a pose counts as reached within this times the poses' size"""


def _candidates(poses: np.ndarray):
    """Pairs (fixed, moving) of the two dyads for the poses: every pair of points of a
    grid about the poses (three poses) or of the Burmester curves (four)."""
    z = poses[:, 0] + 1j * poses[:, 1]
    size = max(float(np.ptp(z.real)), float(np.ptp(z.imag)), 1e-9)
    if len(poses) == 3:
        grid = np.linspace(-1.0, 1.0, 7) * size
        moving = (z.mean() + grid[:, None] + 1j * grid[None, :]).ravel()
        fixed = []
        for m in moving:
            try:
                fixed.append(closed.circumcentre(closed.pose_points(poses, m)))
            except DyadeError:
                fixed.append(complex(np.nan, np.nan))
        fixed = np.array(fixed)
    elif len(poses) == 5:
        fixed, moving = closed.ball_burmester(poses)
    else:
        curves = closed.burmester(poses, samples=720)
        step = max(1, curves.centre.size // 160)
        fixed, moving = curves.centre[::step], curves.circle[::step]
    ok = np.isfinite(fixed) & (np.abs(fixed - z.mean()) < 20 * size)
    return fixed[ok], moving[ok], size


def choose(poses: np.ndarray, moving: tuple[complex, complex] | None = None):
    """(A0, A, B0, B, least transmission [rad]) of the best four-bar through the poses:
    the crank's rotations from pose to pose in one sense (order), B reached on one
    assembly (branch), the largest least transmission angle between the first and last
    pose."""
    z = poses[:, 0] + 1j * poses[:, 1]
    if moving is not None:
        a0, a, b0, b = closed.three_poses(poses, moving)
        fixed_pairs = [(a0, a, b0, b)]
    else:
        fixed, moving_, _ = _candidates(poses)
        i, j = np.triu_indices(fixed.size, 1)
        fixed_pairs = list(zip(fixed[i], moving_[i], fixed[j], moving_[j]))
        fixed_pairs += [(c, d, a, b) for a, b, c, d in fixed_pairs]
    if not fixed_pairs:
        raise DyadeError("the poses give no dyads (the Burmester curves are empty): choose "
                         "other poses.")
    a0, a, b0, b = (np.array(v, dtype=complex) for v in zip(*fixed_pairs))
    at_a = closed.pose_points(poses, a)  # (pairs, poses)
    at_b = closed.pose_points(poses, b)
    turn = np.unwrap(np.angle(at_a - a0[:, None]), axis=1)
    steps = np.diff(turn, axis=1)
    ordered = np.all(steps > 1e-6, axis=1) & (turn[:, -1] - turn[:, 0] < 2 * np.pi)
    side = ((b0[:, None] - at_a).conj() * (at_b - at_a)).imag  # (B0 − A) × (B − A)
    branch = np.all(side > 0, axis=1) | np.all(side < 0, axis=1)
    sweep = turn[:, :1] + np.linspace(0.0, 1.0, 60)[None, :] * (turn[:, -1:] - turn[:, :1])
    la, lb = np.abs(a - a0), np.abs(b - a)
    lc, ld = np.abs(b - b0), np.abs(b0 - a0)
    theta = np.angle(b0 - a0)
    ax, ay = la[:, None] * np.cos(sweep - theta[:, None]), la[:, None] * np.sin(
        sweep - theta[:, None])
    variant = np.where(side[:, 0] > 0, 1, -1)
    least = np.zeros(len(a))
    for sign in (1, -1):
        rows = variant == sign
        bx, by = closed.rrr(ax[rows], ay[rows], ld[rows, None], 0.0, lb[rows, None],
                            lc[rows, None], sign)
        sin = np.abs((bx - ax[rows]) * by - (by - ay[rows]) * (bx - ld[rows, None])) / (
            lb[rows, None] * lc[rows, None])
        least[rows] = np.arcsin(np.clip(np.min(np.where(np.isfinite(sin), sin, 0.0), axis=1),
                                        0.0, 1.0))
    usable = ordered & branch & (least > 0.0)
    if not usable.any():
        raise DyadeError(f"no four-bar of the {len(a)} dyad pairs tried passes through the "
                         f"poses in order on one assembly branch (every one has an order or "
                         f"branch defect): choose other poses" + (" or moving pivots."
                                                                  if moving else "."))
    best = int(np.argmax(np.where(usable, least, -1.0)))
    del z
    return a0[best], a[best], b0[best], b[best], float(least[best])


def poses(problem):
    """The ``poses`` target of a synthesis problem as its result (``dyade.synthesis``)."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions
    from dyade.synthesis.designs import Design, Result, speed_rpm
    from dyade.synthesis.topology import FourBar, fourbar_from_points

    target = problem.target
    given = target.poses
    a0, a, b0, b, least = choose(given, target.moving)
    point = complex(given[0, 0], given[0, 1])
    values, variant, placement, _ = fourbar_from_points(a0, a, b, b0, point)
    crank = np.unwrap(np.angle(closed.pose_points(given, a) - a0))
    sweep = (float(np.rad2deg(crank[0])), float(np.rad2deg(crank[-1])), 1.0)
    if sweep[1] - sweep[0] < 1.0:
        sweep = (sweep[0], sweep[0] + 360.0, 1.0)
    data = FourBar().data(values, variant, placement, speed_rpm(problem), problem.masses,
                          sweep=(sweep[0], sweep[1], (sweep[1] - sweep[0]) / max(
                              1, round(sweep[1] - sweep[0]))), name=problem.name)
    mechanism = build(data)
    found = positions(mechanism, crank, [(3, (values[4], values[5]))])
    traced = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    z = given[:, 0] + 1j * given[:, 1]
    miss = float(np.max(np.abs(traced - z)))
    turned = np.angle(np.exp(1j * ((found.angles[:, 3] - found.angles[0, 3])
                                   - (given[:, 2] - given[0, 2]))))
    size = max(float(np.ptp(z.real)), float(np.ptp(z.imag)), 1e-9)
    if not (miss <= TOLERANCE * size and np.abs(turned).max() <= TOLERANCE):
        raise DyadeError(f"the four-bar through the poses misses them by {miss:.3g} m in "
                         f"dyade's engine (a branch defect): choose other poses or pivots.")
    dense = np.linspace(crank[0], crank[-1], 121)  # the path between the poses
    between = positions(mechanism, dense, [(3, (values[4], values[5]))]).points[:, 0]
    design = Design(problem.name, data, miss, True, dense, between[:, 0] + 1j * between[:, 1],
                    notes=[f"least transmission angle between the first and last pose "
                           f"{np.rad2deg(least):.1f}°"])
    design.figures["mu_motion_deg"] = float(np.rad2deg(least))
    return Result(problem, [design])
