"""A die's beam in 3D finite elements with silicon's full anisotropic stiffness
(scikit-fem): the die's fem3d level, a model of another kind than the closed form and than
CalculiX's brick (:func:`tactcad.products.silicon_die.mechanics.die_dynamics.calculix_beam_check`).

The beam, root to the post's far edge, is meshed with triquadratic hexahedra (27 nodes,
scikit-fem's ``ElementHex2``: bending without locking through a few layers), node planes at
the post's centre and at its footprint's edges. The stiffness is assembled from the 4th-order
tensor C_ijkl of silicon turned into the beam's frame (<110> along the beam on a (100)
wafer, :meth:`tactcad.vocabulary.crystal.CubicElasticity.in_frame`), K_ia,jb =
sum_q w g_ik C_akbl g_jl, per chunk of cells (no Python call per pair of basis functions).
The beam runs into its frame block (the die as made; :func:`tactcad.products.silicon_die.mechanics.die_dynamics.
beam_on_frame`): the device layer behind and beside the root, bonded on the buried oxide
and the handle (one silicon solid), the cavity under the beam with the handle as its floor,
held at the handle's underside. The frame turns and gives under the root's moment and shear:
on the example die that makes K_r 15 % and K_m 7 % softer than the same beams clamped at the
root (``frame=False``, the textbook cantilever K = E w t^3 / (4 L^3)); the die's closed form
carries that give as extra length behind the root
(:func:`tactcad.products.silicon_die.design.mems_die.root_extension_um`, fitted to this level).
K: a uniform shear traction of total F over the cross-section at
the post's centre (an internal plane of facets), K = F^2 / (f . u), f the consistent load
vector, so f . u / F is the section's mean deflection. f1: the lowest eigenvalue of
K u = omega^2 M u, M the silicon's consistent mass plus the post's as a surface density over
its footprint on the top face (scipy ``eigsh``, shift-invert at 0). Each at two meshes,
the second twice as fine every way, Richardson-extrapolated (order 4 for the energy of
quadratic elements on the clamped beam; :data:`FRAME_ORDER` on its frame, whose re-entrant
corner at the cavity's edge is singular); the error estimate is the extrapolation's change.
The factorisation (SuperLU under a minimum-degree ordering) serves both the static solve and
the eigenvalue's shift-invert.

Units: mm, N, MPa, tonne/mm^3 (so N/mm over tonne is 1/s^2), Hz.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

#: Elements along, across, through the beam on the coarser mesh (the finer doubles each).
DIVISIONS = (12, 2, 2)
#: The convergence order of K and f1 Richardson assumes for the clamped beam (quadratic
#: elements, energy norm squared: h^4).
ORDER = 4.0
#: The order on the beam on its frame: where the beam's underside meets the cavity's edge
#: the solid has a re-entrant 270 degree corner, whose stresses grow as r^(lambda - 1) with
#: lambda = 0.5445 (Williams, "Stress singularities resulting from various boundary
#: conditions in angular corners of plates in extension", J. Appl. Mech. 19, 1952, the
#: symmetric mode of a 3 pi / 2 wedge), so the energy, and K, converge as h^(2 lambda)
#: on a mesh refined evenly (CalculiX's C3D20 on the same block halves its change per
#: halving of the edge).
FRAME_ORDER = 2 * 0.5445
#: Voigt index of each pair of tensor indices (xx, yy, zz, yz, zx, xy).
VOIGT = ((0, 5, 4), (5, 1, 3), (4, 3, 2))


@dataclass(frozen=True)
class DieBeamFem:
    """One beam at the die's fem3d level.

    Attributes:
        role: the beam's row ("reference", "measuring").
        k_N_per_mm: K, extrapolated. f1_Hz: the first resonance with its post, extrapolated.
        k_error_rel, f1_error_rel: each extrapolation's change from the finer mesh.
        dofs: the finer mesh's degrees of freedom. wall_time_s: both meshes.
    """

    role: str
    k_N_per_mm: float
    f1_Hz: float
    k_error_rel: float
    f1_error_rel: float
    dofs: int
    wall_time_s: float
    #: on its frame block (the die as made), or clamped at its root
    frame: bool = True

    def as_json(self) -> dict:
        return {"role": self.role, "K_N_per_mm": self.k_N_per_mm, "f1_Hz": self.f1_Hz,
                "K_error_rel": self.k_error_rel, "f1_error_rel": self.f1_error_rel,
                "dofs": self.dofs, "wall_time_s": self.wall_time_s,
                "root": "on its frame" if self.frame else "clamped"}


def stiffness_tensor(voigt: np.ndarray) -> np.ndarray:
    """C_ijkl (3, 3, 3, 3) of a 6 x 6 Voigt stiffness (MPa; engineering shear strains)."""
    c = np.empty((3, 3, 3, 3))
    for i in range(3):
        for j in range(3):
            for k in range(3):
                for m in range(3):
                    c[i, j, k, m] = voigt[VOIGT[i][j], VOIGT[k][m]]
    return c


def assemble_anisotropic(sb, c: np.ndarray, chunk: int = 200):
    """The stiffness matrix of linear elasticity with the tensor ``c`` (MPa) on the vector
    space over the scalar basis ``sb`` (interleaved numbering ``3 s + a``, scikit-fem's
    ``ElementVector``'s), ``scipy.sparse.csr_matrix``, N/mm."""
    import scipy.sparse as sp

    nbf = sb.Nbfun
    grads = np.array([sb.basis[i][0].grad for i in range(nbf)])  # (nbf, 3, nel, nq)
    weights = sb.dx
    edofs = sb.element_dofs
    nel, n = edofs.shape[1], 3 * sb.N
    rows, cols, vals = [], [], []
    for e0 in range(0, nel, chunk):
        sl = slice(e0, min(nel, e0 + chunk))
        g = grads[:, :, sl, :]
        # K[e, i, a, j, b] = sum_q w g_ik C_akbl g_jl
        k = np.einsum("ikeq,akbl,jleq,eq->eiajb", g, c, g, weights[sl], optimize=True)
        gd = (3 * edofs[:, sl].T[:, :, None] + np.arange(3)[None, None, :]).reshape(-1, 3 * nbf)
        rows.append(np.broadcast_to(gd[:, :, None], k.shape[:1] + (3 * nbf, 3 * nbf)).ravel())
        cols.append(np.broadcast_to(gd[:, None, :], k.shape[:1] + (3 * nbf, 3 * nbf)).ravel())
        vals.append(k.reshape(-1))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))


def _planes(lo: float, hi: float, cuts: list[float], count: int) -> np.ndarray:
    """About ``count`` divisions of [lo, hi] with node planes at every cut inside it."""
    edges = sorted({lo, hi, *[c for c in cuts if lo < c < hi]})
    out = [lo]
    for a, b in zip(edges, edges[1:]):
        parts = max(1, round(count * (b - a) / (hi - lo)))
        out += list(np.linspace(a, b, parts + 1)[1:])
    return np.array(out)


def _mesh(plan, beam, divisions: tuple[int, int, int], frame: bool):
    """The beam's hexahedra (its root clamped) or the beam on its frame block (the block
    held at the handle's underside; :func:`tactcad.products.silicon_die.mechanics.die_dynamics.beam_on_frame`),
    and a predicate of the held points."""
    from skfem import MeshHex

    from tactcad.products.silicon_die.mechanics.die_dynamics import beam_on_frame

    at = beam.length_um * 1e-3  # the post's centre: the force
    half_post = plan.post_um * 1e-3 / 2
    width, thick = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    post_y = min(half_post, width / 2)
    nx, ny, nz = divisions
    xs = _planes(0.0, at + half_post, [at - half_post, at], nx)
    ys = _planes(-width / 2, width / 2, [-post_y, post_y], ny)
    zs = np.linspace(0.0, thick, nz + 1)
    if not frame:
        return MeshHex.init_tensor(xs, ys, zs), lambda x: np.isclose(x[0], 0.0)
    block = beam_on_frame(plan, beam, xs, ys, zs)
    mesh = MeshHex.init_tensor(block.xs, block.ys, block.zs)
    centres = mesh.p[:, mesh.t].mean(axis=1)
    mesh = mesh.remove_elements(np.flatnonzero(~block.solid(*centres)))
    return mesh, lambda x: np.isclose(x[2], -block.handle_mm)


def _solve(plan, beam, divisions: tuple[int, int, int],
           frame: bool = True) -> tuple[float, float, int]:
    """(K N/mm, f1 Hz, dofs) of ``beam`` on one mesh, on its frame or clamped at its root.

    Everything is assembled on the scalar basis and carried to the displacement's three
    components by the interleaved numbering ``3 s + a`` (:func:`assemble_anisotropic`): the
    load is the z component's, the mass is the scalar mass on each component (one scalar
    basis instead of a vector one, whose mapping and mass kernel cost as much as the
    factorisation)."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import LinearOperator, eigsh
    from skfem import Basis, BilinearForm, ElementHex2, FacetBasis, LinearForm, condense

    from tactcad.products.silicon_die.mechanics.die_dynamics import (POST_DENSITY_KG_M3,
                                                                     SILICON_DENSITY_KG_M3)
    from tactcad.mechanics.fem.sparse_lu import spd_lu
    from tactcad.vocabulary.crystal import SILICON

    at = beam.length_um * 1e-3  # the post's centre: the force
    half_post = plan.post_um * 1e-3 / 2
    width, thick = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    post_y = min(half_post, width / 2)
    mesh, held = _mesh(plan, beam, divisions, frame)
    scalar = Basis(mesh, ElementHex2())
    c = stiffness_tensor(SILICON.in_frame((1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)))
    k = assemble_anisotropic(scalar, c)
    clamped = _components(scalar.get_dofs(held).all())
    section = FacetBasis(mesh, scalar.elem, facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[0], at) & (x[2] > -1e-12) & (np.abs(x[1]) < width / 2 + 1e-12)))

    @LinearForm
    def spread(v, w):  # a unit force, spread evenly over the section
        return v / (width * thick)

    f = np.zeros(3 * scalar.N)
    f[2::3] = -spread.assemble(section)  # down (-z)
    kk, ff, _, free = condense(k, f, D=clamped)
    lu = spd_lu(kk)
    u = np.zeros(3 * scalar.N)
    u[free] = lu.solve(ff)
    k_N_per_mm = 1.0 / float(f @ u)
    rho = SILICON_DENSITY_KG_M3 * 1e-12  # tonne/mm^3
    post_t = POST_DENSITY_KG_M3 * plan.post_um ** 2 * plan.post_height_um * 1e-18 * 1e-3

    @BilinearForm
    def mass(u_, v, w):
        return w.density * u_ * v

    top = FacetBasis(mesh, scalar.elem, facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[2], thick) & (np.abs(x[0] - at) <= half_post + 1e-12)
        & (np.abs(x[1]) <= post_y + 1e-12)))
    m_scalar = (mass.assemble(scalar, density=rho)
                + mass.assemble(top, density=post_t / (2 * half_post * 2 * post_y)))
    m = sp.kron(m_scalar, sp.identity(3), format="csr")  # the same on each component
    mm = condense(k, m, D=clamped, expand=False)[1]
    inverse = LinearOperator(kk.shape, matvec=lu.solve, dtype=float)  # shift-invert at 0
    lam = eigsh(kk, k=1, M=mm, sigma=0.0, which="LM", OPinv=inverse,
                return_eigenvectors=False)
    return k_N_per_mm, math.sqrt(float(lam[0])) / (2 * math.pi), 3 * scalar.N


def _components(scalar_dofs: np.ndarray) -> np.ndarray:
    """The displacement's dofs ``3 s + a`` (a = x, y, z) of scalar dofs ``s``."""
    return (3 * np.asarray(scalar_dofs)[:, None] + np.arange(3)[None, :]).ravel()


def die_beam_fem3d(plan, beam, divisions: tuple[int, int, int] = DIVISIONS,
                   frame: bool = True) -> DieBeamFem:
    """``beam`` of ``plan`` at two meshes (``divisions`` and twice as fine), extrapolated
    (module doc).

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`. beam: one of its beams.
        divisions: elements along, across and through the beam on the coarser mesh.
        frame: the beam on its frame block (the die as made); False: clamped at its root
            (the textbook cantilever, E w t^3 / (4 L^3) with shear and plate effects).

    Returns:
        :class:`DieBeamFem`.

    Raises:
        ValueError: a division below 1.
    """
    if min(divisions) < 1:
        raise ValueError(f"divisions {divisions!r}: each at least 1")
    t0 = time.perf_counter()
    coarse = _solve(plan, beam, divisions, frame)
    fine = _solve(plan, beam, tuple(2 * d for d in divisions), frame)
    r = 2.0 ** (FRAME_ORDER if frame else ORDER)

    def extrapolated(a: float, b: float) -> tuple[float, float]:
        best = b + (b - a) / (r - 1.0)
        return best, abs(best / b - 1.0)

    k, k_err = extrapolated(coarse[0], fine[0])
    f1, f_err = extrapolated(coarse[1], fine[1])
    return DieBeamFem(beam.role, k, f1, k_err, f_err, fine[2], time.perf_counter() - t0, frame)
