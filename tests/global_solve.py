"""An independent check of the kinetostatics: one global linear system per position.

The constraint residual of the whole mechanism is written here again, from the joint
definitions, and differentiated by the complex-step method (exact to round-off); the
loads (inertia, gravity, constant forces) are reduced here too. Then Jᵀ·λ = Q is solved
for all joints and the drive at once, without the dyad-by-dyad decomposition.
"""

from __future__ import annotations

import numpy as np

from dyade.model.mechanism import CRANK, FRAME, Mechanism, Revolute


def _rot(phi, u):
    return np.array([np.cos(phi) * u[0] - np.sin(phi) * u[1],
                     np.sin(phi) * u[0] + np.cos(phi) * u[1]])


def _residual(mechanism: Mechanism, q: np.ndarray, index: dict[int, int]) -> np.ndarray:
    def pose(link):
        if link == FRAME:
            return np.zeros(2, dtype=q.dtype), 0.0 * q[0]
        k = index[link]
        return q[3 * k:3 * k + 2], q[3 * k + 2]

    out = []
    for joint in mechanism.joints:
        if isinstance(joint, Revolute):
            (p, r), (u_p, u_r) = joint.links, joint.points
            (o_p, f_p), (o_r, f_r) = pose(p), pose(r)
            out.extend(o_p + _rot(f_p, u_p) - o_r - _rot(f_r, u_r))
        else:
            (o_c, f_c), (o_s, f_s) = pose(joint.carrier), pose(joint.slider)
            out.append(f_s - f_c - joint.relative_angle)
            normal = np.array([-np.sin(f_c + joint.guide_angle), np.cos(f_c + joint.guide_angle)])
            w = o_s + _rot(f_s, joint.slider_point) - o_c - _rot(f_c, joint.guide_point)
            out.append(normal @ w)
    out.append(pose(CRANK)[1])  # drive constraint
    return np.array(out)


def _jacobian(mechanism: Mechanism, q: np.ndarray, index: dict[int, int]) -> np.ndarray:
    """∂Φ/∂q by the complex step (exact to round-off)."""
    h = 1e-30
    jac = np.empty((q.size, q.size))
    for col in range(q.size):
        dq = q.astype(complex)
        dq[col] += 1j * h
        jac[:, col] = _residual(mechanism, dq, index).imag / h
    return jac


def _own_motion(mechanism, q, index, jac, speed, acceleration):
    """q̇ and q̈ of the whole mechanism from its constraints: Φ_q·q̇ = (0, …, φ̇) and
    Φ_q·q̈ = (0, …, φ̈) − (Φ_q·q̇)_q·q̇, the last term by a central difference of the
    complex-step directional derivative along q̇."""
    rhs = np.zeros(q.size)
    rhs[-1] = speed
    qdot = np.linalg.solve(jac, rhs)
    h, step = 1e-30, 1e-5 / max(np.max(np.abs(qdot)), 1e-300)

    def directional(shift):  # Φ_q(q + shift·q̇)·q̇
        return _residual(mechanism, q + shift * qdot + 1j * h * qdot, index).imag / h

    bias = (directional(step) - directional(-step)) / (2.0 * step)
    rhs = -bias
    rhs[-1] += acceleration
    return qdot, np.linalg.solve(jac, rhs)


def global_forces(mechanism: Mechanism, kin, constant_loads=(), crank_speed=None,
                  crank_acceleration=None) -> dict:
    """Per position: joint forces on the higher link (revolute: Fx, Fy; prismatic: FN, M)
    and the drive torque, from one global solve. ``constant_loads``: (link, local point,
    (Fx, Fy)) world forces. With ``crank_speed`` and ``crank_acceleration`` (one value per
    position) the velocities and accelerations are found here too, from the constraints
    (only the positions of ``kin`` are used); else those of ``kin`` are."""
    links = mechanism.moving_links
    index = {link: k for k, link in enumerate(links)}
    motion = kin.motion
    g = np.asarray(mechanism.gravity)
    n = kin.crank_angle.shape[0]
    out: dict = {"drive": np.full(n, np.nan)}
    for joint in mechanism.joints:
        out[joint.name] = np.full((n, 2), np.nan)
    for row in range(n):
        q = np.concatenate([np.r_[motion.origin[row, link], motion.angle[row, link]]
                            for link in links])
        jac = _jacobian(mechanism, q, index)
        if crank_speed is None:
            omega = {link: motion.omega[row, link] for link in links}
            alpha = {link: motion.alpha[row, link] for link in links}
            origin_acc = {link: motion.acceleration[row, link] for link in links}
        else:
            qdot, qddot = _own_motion(mechanism, q, index, jac, crank_speed[row],
                                      crank_acceleration[row])
            omega = {link: qdot[3 * index[link] + 2] for link in links}
            alpha = {link: qddot[3 * index[link] + 2] for link in links}
            origin_acc = {link: qddot[3 * index[link]:3 * index[link] + 2] for link in links}
        load = np.zeros(q.size)
        for link in links:
            data = mechanism.links[link]
            k = index[link]
            if data.mass or data.inertia:
                arm = _rot(motion.angle[row, link], data.centre)
                acc = (origin_acc[link] + alpha[link] * np.array([-arm[1], arm[0]])
                       - omega[link] ** 2 * arm)
                force = data.mass * (g - acc)
                load[3 * k:3 * k + 2] += force
                load[3 * k + 2] += arm[0] * force[1] - arm[1] * force[0]
                load[3 * k + 2] -= data.inertia * alpha[link]
        for link, local, force in constant_loads:
            k = index[link]
            arm = _rot(motion.angle[row, link], local)
            load[3 * k:3 * k + 2] += force
            load[3 * k + 2] += arm[0] * force[1] - arm[1] * force[0]
        lam = np.linalg.solve(jac.T, load)
        r = 0
        for joint in mechanism.joints:
            pair = lam[r:r + 2]
            r += 2
            if isinstance(joint, Revolute):
                # Φ = r_p + R u_p − r_q − R u_q: the force on link q is +λ, on p it is −λ
                higher_is_second = joint.links[1] > joint.links[0]
                out[joint.name][row] = pair if higher_is_second else -pair
            else:
                # force on the slider: −λ_normal·n at S and moment −λ_angle
                sign = -1.0 if joint.slider > joint.carrier else 1.0
                out[joint.name][row] = sign * pair[::-1]  # (FN, M)
        out["drive"][row] = -lam[r]
    return out
