"""Natural frequencies and modes of a gear drive by null-space reduction.

The mesh constraints gᵀq = 0 are solved exactly by q = N·r with N orthonormal and
gᵀN = 0; the reduced problem NᵀKN·r = ω²·NᵀMN·r is symmetric. Its mass matrix is
factored by Cholesky (NᵀMN = C·Cᵀ) and ``numpy.linalg.eigh`` solves the standard
problem C⁻¹·NᵀKN·C⁻ᵀ·y = ω²·y; the modes q = N·C⁻ᵀ·y are M-orthonormal.

N is built where the constraints act: only the coordinates of geared bodies appear in g,
so N is the identity on every other coordinate and an orthonormal null basis (from a QR
factorisation of g's rows there) on the geared ones. The reduction and the Cholesky
factor inherit that structure, and the eigensolver's cost is all that grows with the
drive (see tests/benchmarks).

Rigid-body modes (a drive that can turn, or move, without deforming anything) are found
from the structure, not from small eigenvalues: bodies joined by elements that are stiff
in all directions move as one; the motions of these clusters that no remaining element
direction and no mesh resists are the rigid-body modes. They are removed from the
eigenproblem exactly and reported as such, never as resonances at 0 Hz.

For each elastic mode: the kinetic and strain energy shares (torsion, lateral, axial; per
shaft, bearing, element and elastic mesh) and the modal mesh forces by the paper's
multiplier formula λ = (gᵀM⁻¹g)⁻¹·gᵀM⁻¹·K·φ (eq. 27 with P = 0, L = 0). There are no
gyroscopic terms in this model: the frequencies do not depend on speed.

>>> import dyade
>>> modes = dyade.gear_modes(dyade.read_gears("mechanisms/gears/friswell-geared.toml"))
>>> [round(float(f), 1) for f in modes.frequencies]   # Friswell et al. (2010): 425.4, 634.1, 3247.2
[425.4, 634.1, 3247.2]
>>> modes.rigid.shape[1]                              # the drive turns freely as a whole
1
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.limits import check_memory
from dyade.model.gears import FRAME, GearDrive
from dyade.vibration.gears.assembly import CATEGORY, System, assemble, transfer

KERNEL_RTOL = 1e-9  # [-] singular values of the cluster constraint matrix below this share
#                     of the largest: a motion nothing resists (rigid-body mode)
RESOLVED = 1e3  # [-] an eigenvalue below RESOLVED·eps·|A| cannot be told from round-off
MOTIONS = ("torsion", "lateral", "axial")
TIE_RTOL = 1e-9  # [-] strain-energy shares this close to the largest tie with it (``dominant``)
KINETIC_CATEGORY = ("axial", "lateral", "lateral", "torsion", "lateral", "lateral")
"""what each body coordinate (ux … rz) moves"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class NullSpace:
    """q = N·r, gᵀN = 0, NᵀN = I, with N the identity on the coordinates ``free`` (no
    mesh acts on them) and ``basis`` on the coordinates ``geared``. The reduced
    coordinates are r = (q[free], s)."""

    free: np.ndarray
    geared: np.ndarray
    basis: FloatArray
    """(len(geared), len(geared) − l), orthonormal columns"""

    @classmethod
    def of(cls, g: FloatArray) -> NullSpace:
        n, l = g.shape
        geared = np.flatnonzero(np.any(g != 0.0, axis=1))
        free = np.setdiff1d(np.arange(n), geared)
        q, _ = np.linalg.qr(g[geared], mode="complete")
        return cls(free, geared, q[:, l:])

    @property
    def size(self) -> int:
        return self.free.size + self.basis.shape[1]

    def reduce(self, a: FloatArray) -> FloatArray:
        """NᵀAN of a symmetric (n, n) matrix."""
        f, s, b = self.free, self.geared, self.basis
        side = a[np.ix_(f, s)] @ b
        return np.block([[a[np.ix_(f, f)], side], [side.T, b.T @ a[np.ix_(s, s)] @ b]])

    def project(self, v: np.ndarray) -> np.ndarray:
        """Nᵀv of (n,) or (n, k)."""
        return np.concatenate([v[self.free], self.basis.T @ v[self.geared]])

    def expand(self, r: np.ndarray) -> np.ndarray:
        """N·r of (m,) or (m, k)."""
        out = np.zeros((self.free.size + self.geared.size,) + r.shape[1:], dtype=r.dtype)
        nf = self.free.size
        out[self.free] = r[:nf]
        out[self.geared] = self.basis @ r[nf:]
        return out

    def matrix(self) -> FloatArray:
        """N as a dense (n, m) matrix (for checks)."""
        return self.expand(np.eye(self.size))


@dataclass(slots=True, eq=False)
class Reduced:
    """The reduced, mass-normalised problem: A = C⁻¹·NᵀKN·C⁻ᵀ with NᵀMN = C·Cᵀ, where C
    is block diagonal: diag(√m) on the free coordinates, a Cholesky factor on the rest."""

    null: NullSpace
    root: FloatArray
    """√m of the free coordinates"""
    cholesky: FloatArray
    """lower triangular Cholesky factor of Nᵀ·M·N on the geared coordinates"""
    standard: FloatArray
    """A (m, m), symmetric"""

    def up(self, r: np.ndarray) -> np.ndarray:
        """Cᵀ·r: reduced coordinates -> standard ones."""
        nf = self.root.size
        scale = self.root if r.ndim == 1 else self.root[:, None]
        return np.concatenate([scale * r[:nf], self.cholesky.T @ r[nf:]])

    def down(self, y: np.ndarray) -> np.ndarray:
        """C⁻ᵀ·y: standard coordinates -> reduced ones."""
        nf = self.root.size
        scale = self.root if y.ndim == 1 else self.root[:, None]
        return np.concatenate([y[:nf] / scale, np.linalg.solve(self.cholesky.T, y[nf:])])

    def to_coordinates(self, y: np.ndarray) -> np.ndarray:
        """q = N·C⁻ᵀ·y"""
        return self.null.expand(self.down(y))


def reduce(system: System) -> Reduced:
    """Null space, Cholesky factor and standard matrix of ``system``."""
    null = NullSpace.of(system.constraints)
    f, s, b = null.free, null.geared, null.basis
    chol = np.linalg.cholesky(b.T @ (system.mass[s][:, None] * b))
    nf = f.size
    root = np.sqrt(system.mass[f])
    k = null.reduce(system.stiffness)
    a = k  # scaled in place: A = C⁻¹·K_r·C⁻ᵀ block by block
    a[:nf, :nf] /= np.outer(root, root)
    side = np.linalg.solve(chol, (k[:nf, nf:] / root[:, None]).T)  # C_s⁻¹·K_sf·D⁻¹
    a[nf:, :nf] = side
    a[:nf, nf:] = side.T
    inner = np.linalg.solve(chol, np.linalg.solve(chol, k[nf:, nf:]).T).T
    a[nf:, nf:] = 0.5 * (inner + inner.T)
    return Reduced(null, root, chol, a)


def rigid_modes(system: System) -> FloatArray:
    """(n, k): a basis of the motions that no element and no mesh resists (K·q = 0 and
    gᵀq = 0), from the structure: clusters of bodies joined by elements that are stiff in
    every direction move rigidly; the remaining element directions and the mesh rows
    constrain the clusters' motions; what is left is the kernel."""
    per = system.per_body
    nb = len(system.bodies)
    parent = list(range(nb))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    index = {b.name: k for k, b in enumerate(system.bodies)}
    merged = np.zeros(len(system.elements), dtype=bool)
    for e, element in enumerate(system.elements):
        a, b = element.ends
        if b == FRAME:
            continue
        k = (system.element_stiffness[e] > 0.0) | system.element_rigid[e]
        stiff = bool(np.all(k)) if per == 6 else (bool(k[3]) and _parallel(system, a, b))
        if stiff:
            merged[e] = True
            parent[root(index[a])] = root(index[b])
    clusters = sorted({root(i) for i in range(nb)})
    column = {c: k for k, c in enumerate(clusters)}
    p = per * len(clusters)
    expand = np.zeros((system.size, p))  # cluster motions -> body coordinates
    scale = max(1.0, *[float(np.max(np.abs(b.position))) for b in system.bodies])
    for i, body in enumerate(system.bodies):
        c = root(i)
        cols = slice(per * column[c], per * (column[c] + 1))
        rows = slice(per * i, per * (i + 1))
        if per == 1:
            expand[rows, cols] = float(np.dot(body.axis, system.bodies[c].axis))
        else:
            to_local = system.to_global(i).T
            move = transfer(body.position, system.bodies[c].position)
            move[:, 3:] *= scale  # rotations in units of the drive's size: conditioning
            expand[rows, cols] = to_local @ move
    rows = [system.constraints.T @ expand, system.mesh_rows.T @ expand]
    for e in np.flatnonzero(~merged):
        acting = np.flatnonzero(system.element_stiffness[e] > 0.0)
        rows.append(system.element_maps[e][acting] @ expand[system.element_dofs[e]])
    stacked = np.vstack(rows)
    norms = np.linalg.norm(stacked, axis=1)
    stacked = stacked[norms > 0.0] / norms[norms > 0.0, None]
    if stacked.shape[0] == 0:
        return expand
    _, sigma, vt = np.linalg.svd(stacked)
    rank = int(np.sum(sigma > KERNEL_RTOL * sigma[0]))
    return expand @ vt[rank:].T


def _parallel(system: System, a: str, b: str) -> bool:
    ea, eb = (np.asarray(system.bodies[system.index(x)].axis) for x in (a, b))
    return abs(abs(float(ea @ eb)) - 1.0) < 1e-9


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Modes:
    """Natural frequencies, M-orthonormal modes, energy shares and modal mesh forces."""

    system: System
    frequencies: FloatArray
    """(k,) elastic natural frequencies [Hz], ascending; NaN where below round-off"""
    eigenvalues: FloatArray
    """(k,) ω² [1/s²]"""
    shapes: FloatArray
    """(n, k) M-orthonormal modes (φᵀMφ = 1) [m/√kg, rad·m/√kg … per coordinate]"""
    rigid: FloatArray
    """(n, r) M-orthonormal rigid-body modes (no strain energy, not resonances)"""
    kinetic: dict[tuple[str, str], FloatArray]
    """(body or shaft, "torsion"|"lateral"|"axial") -> (k,) share of the kinetic energy"""
    strain: dict[tuple[str, str], FloatArray]
    """(shaft, bearing, element or mesh name, "torsion"|"lateral"|"axial"|"mesh") ->
    (k,) share of the strain energy"""
    mesh_forces: FloatArray
    """(meshes, k) modal mesh force along n, compression positive, per unit modal
    coordinate [N/(m·√kg)]: −λ of the paper's multiplier formula (ideal meshes) or the
    spring force (elastic meshes), signed by ``System.senses``"""
    unresolved: np.ndarray
    """(k,) bool: eigenvalue within round-off of zero (frequency NaN)"""
    resolution: float
    """the smallest frequency the computation resolves [Hz]"""

    @property
    def mesh_stiffness(self) -> FloatArray:
        """(meshes, k) modal mesh stiffness F²/ω² [N/m]: a transmission error e at a mesh
        gives the mode a modal force F·e, and at its resonance with damping ratio ζ a
        dynamic mesh force F²·e/(2ζ·ω²); an elastic mesh of stiffness k_m holds the share
        F²/(ω²·k_m) of the mode's strain energy."""
        with np.errstate(divide="ignore", invalid="ignore"):  # unresolved modes: NaN
            return self.mesh_forces ** 2 / self.eigenvalues[None, :]

    def totals(self, energy: str = "strain") -> dict[str, FloatArray]:
        """Shares by motion ("torsion", "lateral", "axial"; strain energy adds "mesh");
        NaN for the motions the torsional model does not have."""
        table = self.strain if energy == "strain" else self.kinetic
        out = {m: np.zeros(self.frequencies.size) for m in MOTIONS + ("mesh",) * (energy == "strain")}
        for (_, motion), share in table.items():
            out[motion] = out[motion] + share
        if self.system.per_body == 1:  # the torsional model has no lateral or axial motion
            out["lateral"] = out["axial"] = np.full(self.frequencies.size, np.nan)
        return out

    def dominant(self) -> list[tuple[str, str, float]]:
        """Per mode, the (owner, motion) that holds the largest strain-energy share; where
        several hold it alike (within ``TIE_RTOL``), all of them: owners joined by " = "
        (with their motions where those differ, the motion then "")."""
        keys = list(self.strain)
        if not keys:
            return [("", "", float("nan"))] * self.frequencies.size
        values = np.array([self.strain[k] for k in keys]).reshape(len(keys), -1)
        best = np.argmax(values, axis=0)
        out = []
        for k, b in enumerate(best):
            top = float(values[b, k])
            tied = [keys[i] for i in np.flatnonzero(values[:, k] >= top * (1.0 - TIE_RTOL))]
            if len(tied) == 1 or not top > 0.0:
                out.append((keys[b][0], keys[b][1], top))
            elif len({motion for _, motion in tied}) == 1:
                out.append((" = ".join(owner for owner, _ in tied), tied[0][1], top))
            else:
                out.append((" = ".join(f"{owner} {motion}" for owner, motion in tied), "", top))
        return out


MATRICES = 10
"""dense n×n matrices alive at once in ``gear_modes`` (measured: the peak is 8-9 of them
at 1 836 and 3 636 coordinates)"""


def coordinate_count(drive: GearDrive) -> int:
    """How many coordinates the drive's model has: one or six per body and per shaft
    segment (known before anything is assembled)."""
    per_body = 1 if drive.torsional else 6
    return per_body * (len(drive.bodies) + sum(max(s.segments, 0) for s in drive.shafts))


def check_modes_size(drive: GearDrive, max_memory: float | None = None) -> None:
    """Refuse, before assembling, an eigenproblem beyond ``max_memory`` [B]
    (``dyade.limits``: one bound for every command)."""
    n = coordinate_count(drive)
    check_memory(MATRICES * 8.0 * n * n + (50 << 20), f"the eigenproblem of {n:,} coordinates",
                 max_memory, "Divide the shafts into fewer segments (`segments`)")


def gear_modes(drive: GearDrive | System, *, max_memory: float | None = None) -> Modes:
    """Natural frequencies and modes of a gear drive (null-space reduction, Cholesky,
    ``numpy.linalg.eigh``).

    Parameters
    ----------
    drive : GearDrive or System
        A drive from ``read_gears`` (or its assembled ``System``).
    max_memory : float, optional
        Bound on what the eigenproblem may take [B] (default ``dyade.limits.MAX_MEMORY``),
        checked before anything is assembled.

    Returns
    -------
    Modes
        Elastic frequencies [Hz] ascending, M-orthonormal shapes, the rigid-body modes
        separately, energy shares and modal mesh forces.

    Examples
    --------
    >>> import dyade
    >>> modes = dyade.gear_modes(dyade.read_gears("mechanisms/gears/two-stage.toml"))
    >>> round(float(modes.frequencies[0]), 1), modes.rigid.shape[1]
    (79.2, 1)
    """
    if not isinstance(drive, System):
        check_modes_size(drive, max_memory)
    system = drive if isinstance(drive, System) else assemble(drive)
    reduced = reduce(system)
    a = reduced.standard
    rigid_q = rigid_modes(system)
    nr = rigid_q.shape[1]
    u = np.zeros((a.shape[0], 0))
    if nr:
        u, _ = np.linalg.qr(reduced.up(reduced.null.project(rigid_q)))
        au = a @ u
        a = a - u @ au.T - au @ u.T + u @ (u.T @ au) @ u.T  # P·A·P, P = I − U·Uᵀ
    values, vectors = np.linalg.eigh(a)
    if nr:
        overlap = np.sum((u.T @ vectors) ** 2, axis=0)
        is_rigid = np.zeros(values.size, dtype=bool)
        is_rigid[np.argsort(-overlap)[:nr]] = True
        values, vectors = values[~is_rigid], vectors[:, ~is_rigid]
    floor = RESOLVED * np.finfo(float).eps * max(float(np.max(np.abs(values), initial=0.0)), 1e-300)
    unresolved = values <= floor
    shapes = reduced.to_coordinates(vectors)
    rigid = reduced.to_coordinates(u)
    with np.errstate(invalid="ignore"):  # unresolved: NaN
        frequencies = np.where(unresolved, np.nan, np.sqrt(np.abs(values))) / (2.0 * np.pi)
    kinetic, strain = energy_shares(system, shapes)
    forces = modal_mesh_forces(system, shapes)
    return Modes(system, frequencies, values, shapes, rigid, kinetic, strain, forces, unresolved,
                 float(np.sqrt(floor) / (2.0 * np.pi)))


def energy_shares(system: System, shapes: FloatArray
                  ) -> tuple[dict[tuple[str, str], FloatArray], dict[tuple[str, str], FloatArray]]:
    """Kinetic shares per (body or shaft, motion) and strain shares per (owner, motion) of
    every mode (columns of ``shapes``); each mode's shares sum to 1."""
    per = system.per_body
    categories = KINETIC_CATEGORY if per == 6 else ("torsion",)
    kinetic_parts = system.mass[:, None] * shapes ** 2
    kinetic: dict[tuple[str, str], FloatArray] = {}
    for i, (body, owner) in enumerate(zip(system.bodies, system.owners)):
        for d in range(per):
            key = (owner or body.name, categories[d])
            kinetic[key] = kinetic.get(key, 0.0) + kinetic_parts[i * per + d]
    strain: dict[tuple[str, str], FloatArray] = {}
    for e, element in enumerate(system.elements):
        deform = system.element_maps[e] @ shapes[system.element_dofs[e]]
        energy = 0.5 * system.element_stiffness[e][:, None] * deform ** 2
        for d in np.flatnonzero(system.element_stiffness[e] > 0.0):
            key = (element.owner, CATEGORY[d])
            strain[key] = strain.get(key, 0.0) + energy[d]
    for k, mesh in enumerate(system.drive.meshes):
        if mesh.stiffness is not None:
            strain[(mesh.name, "mesh")] = 0.5 * mesh.stiffness * (system.mesh_rows[:, k] @ shapes) ** 2
    total_t = sum(kinetic.values())
    total_u = sum(strain.values()) if strain else np.zeros(shapes.shape[1])
    with np.errstate(divide="ignore", invalid="ignore"):  # a mode without strain: NaN shares
        kinetic = {k: v / total_t for k, v in kinetic.items()}
        strain = {k: v / total_u for k, v in strain.items()}
    return kinetic, strain


def multipliers(system: System, residual: np.ndarray) -> np.ndarray:
    """λ = (gᵀM⁻¹g)⁻¹·gᵀM⁻¹·residual (the paper's eq. (27)), for a residual (n,) or
    (n, k) — K·φ for a mode, L·q' + K·q − P in general: one row per column of g (the
    ideal meshes', then the rigid supports' ``System.supports``)."""
    g = system.constraints
    inverse_mass = 1.0 / system.mass
    gram = g.T @ (inverse_mass[:, None] * g)
    return np.linalg.solve(gram, g.T @ (inverse_mass[:, None] * residual
                                        if residual.ndim > 1 else inverse_mass * residual))


def modal_mesh_forces(system: System, shapes: FloatArray) -> FloatArray:
    """(meshes, k): the mesh force of every mode, compression positive (−λ for ideal
    meshes, k·w·φ for elastic ones, times the mesh's sense: ``System.senses``); NaN for
    a mesh whose gears have no module (``sizeless``)."""
    out = np.zeros((len(system.drive.meshes), shapes.shape[1]))
    if system.ideal:
        # (gᵀM⁻¹g)⁻¹·gᵀM⁻¹·K first: l rows, so that no n×n×k product is formed
        rows = multipliers(system, system.stiffness)[:len(system.ideal)]
        out[list(system.ideal)] = -(rows @ shapes)
    for k, mesh in enumerate(system.drive.meshes):
        if mesh.stiffness is not None:
            out[k] = mesh.stiffness * (system.mesh_rows[:, k] @ shapes)
    out[sizeless(system)] = np.nan  # per unit module: not a force in newtons
    return system.senses[:, None] * out


def sizeless(system: System) -> list[int]:
    """The meshes whose gears have no `module` (a torsional model that gives only the
    ratio): their forces, and with them κ, are not given (NaN)."""
    return [k for k, mesh in enumerate(system.drive.meshes)
            if system.drive.gear(mesh.driving).module is None]
