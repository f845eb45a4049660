"""Level-3 stiffness estimator "fem2d": plane stress / plane strain FEM.

Quadratic triangles (P2 displacement field: scikit-fem ``ElementTriP2`` basis
in the dof numbering of ``ElementVector``) on a gmsh mesh of the cropped exact profile
(:func:`tactcad.mechanics.fem.fem_mesh.fem_region`), refined at the web of the
flexure hinge. Geometry is isoparametric (``MeshTri2``: the midside node of
every edge on the notch or fillet arc sits on the exact circle) unless
``curved=False``. Straight-sided cells cut the notch's chords and leave a
geometry error in the thin web: on the default meshes of the 4 and 8 mm arms
they converge at order 1.9 with an estimated error of 0.5 %, the
isoparametric cells at order 3.5 with 0.02 %.

Boundary conditions: all displacements fixed on the clamp line
``x = x_clamp``; a uniform traction along +y over the contact face (top face
of the tip, width ``g.tip_width_mm``) with total force ``force_N`` through
the sheet thickness b.

Outputs:

* tip stiffness from the energy (compliance) of the discrete solution,
  ``K = F^2 / (f^T u)``, where ``f^T u`` = F x (mean deflection of the
  contact face); this is the quantity that converges fastest and does not
  depend on a single node;
* gauge strain ``eps_xx`` on the flat top face at ``x = hinge_x`` (the P2
  field's strain evaluated at that mesh vertex in each adjacent triangle
  and averaged), per newton of tip force. The field value is negative (an
  upward tip force compresses the top face over the web);
  :class:`StiffnessResult` carries its magnitude, as the closed form and
  the paper report it;
* a Richardson-extrapolation error estimate from three meshes whose element
  sizes shrink by a constant ratio r (default sqrt 2): observed order
  ``p = ln((K1 - K2) / (K2 - K3)) / ln r``, ``K_ext = K3 + (K3 - K2) / (r^p - 1)``,
  ``|K3 - K_ext| / K_ext`` for the finest mesh K3, which is the value
  reported; ``error_estimate_rel`` adds the plane model's error against 3D
  (:func:`plane_model_error`: plane stress is up to about 11 % softer than
  a wide 3D element), as the beam level adds beam theory's.

Plane stress uses ``lambda* = E nu / (1 - nu^2)``, plane strain the 3D Lamé
``lambda = E nu / ((1 + nu)(1 - 2 nu))``; both with ``mu = E / (2 (1 + nu))``
and thickness b.

Sources: scikit-fem documentation (``Basis``, ``FacetBasis``,
``ElementVector``, ``skfem.models.elasticity``, ``MeshTri2``); L. F.
Richardson, "The deferred approach to the limit" (1927) and P. J. Roache,
"Verification and Validation in Computational Science and Engineering"
(observed order, grid convergence); plane stress / plane strain constitutive
laws as in S. P. Timoshenko & J. N. Goodier, "Theory of Elasticity".

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.mechanics.fem.fem_mesh import (WEB_DIVISIONS, FemRegion, RegionMesh, curved_doflocs, fem_region,
                       mesh_region)
from tactcad.mechanics.blas_threads import single_threaded_blas  # noqa: F401 (the FEM levels' import)
from tactcad.mechanics.bonded_layer import BondedLayer
from tactcad.mechanics.stiffness_result import StiffnessResult
from tactcad.mechanics.richardson import Richardson, richardson

#: Refinement ratio between successive meshes of the Richardson sequence.
REFINEMENT_RATIO = math.sqrt(2.0)

#: Tip force (N) of the paper's FEM design study (the gauge strain is per N).
DEFAULT_FORCE_N = 2.0

PLANES = ("stress", "strain")


# ---------------------------------------------------------------------------
# One solve
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class FemSolution:
    """One FEM solve on one mesh.

    Attributes:
        stiffness_N_per_mm: K = F^2 / (f^T u) (N/mm).
        tip_deflection_mm: mean deflection of the contact face along +y (mm).
        gauge_strain: eps_xx at the gauge point under ``force_N`` (1; signed,
            negative = compression).
        force_N: total tip force (N).
        n_dofs: number of displacement unknowns (before the clamp is applied).
        n_cells: triangles (2D) or tetrahedra (3D).
        neck_size_mm: element size at the neck (mm).
        wall_time_s: mesh + assembly + solve (s).
    """

    stiffness_N_per_mm: float
    tip_deflection_mm: float
    gauge_strain: float
    force_N: float
    n_dofs: int
    n_cells: int
    neck_size_mm: float
    wall_time_s: float
    field: "DisplacementField | None" = dataclasses.field(default=None, repr=False, compare=False)
    #: the grid's mean eps_xx under ``force_N`` (signed) on its plane: the top of a bonded
    #: layer, else the face; NaN when no grid was given
    grid_strain: float = float("nan")


@dataclass(frozen=True, eq=False)
class DisplacementField:
    """The solved P2 displacement field of one solve, for stress recovery and VTU.

    Attributes:
        basis: scalar P2 ``CellBasis`` (scikit-fem) on the solve's mesh (mm).
        displacement: dof vector, interleaved ``dim * s + c`` (mm), under the
            solve's force.
        lam, mu: Lame parameters used (MPa; ``lam`` is lambda* in plane stress).
        plane: "stress", "strain" or None (3D).
        force_N: total tip force of the solve (N; the full element in 3D).
        sym_plane_z: 3D half model: z of the mid-plane (u_z = 0), else None.
    """

    basis: object
    displacement: np.ndarray
    lam: float
    mu: float
    plane: str | None
    force_N: float
    sym_plane_z: float | None = None
    #: the element's cells (bool per cell) where a bonded layer was meshed with it: the
    #: stresses are the element's, of ``lam`` and ``mu`` (None: every cell)
    body_cells: np.ndarray | None = None


def lame(material: Material, plane: str | None) -> tuple[float, float]:
    """Lamé parameters (lambda, mu) in MPa for ``plane`` = "stress",
    "strain", or ``None`` (3D).

    Raises:
        ValueError: unknown plane.
    """
    E, nu = material.youngs_modulus_MPa, material.poisson_ratio
    mu = E / (2.0 * (1.0 + nu))
    if plane is None or plane == "strain":
        return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu
    if plane == "stress":
        return E * nu / (1.0 - nu * nu), mu
    raise ValueError(f"plane must be one of {PLANES}, got {plane!r}")


def skfem_mesh(rm: RegionMesh, curved: bool = True):
    """scikit-fem mesh of a :class:`RegionMesh`: ``MeshTri2``/``MeshTet2``
    with the arcs' midside nodes on the exact circles (``curved``), else the
    linear ``MeshTri``/``MeshTet`` (straight-sided cells)."""
    return skfem_mesh_of(rm.p, rm.t, rm.arcs if curved else ())


def skfem_mesh_of(p: np.ndarray, t: np.ndarray, arcs: Sequence = ()):
    """scikit-fem mesh of the simplices ``t`` on the vertices ``p`` (shape (dim, n), mm):
    ``MeshTri2``/``MeshTet2`` whose edges on one of ``arcs``' circles (anything with a
    ``centre`` and a ``radius``) have their midside node on it, the linear
    ``MeshTri``/``MeshTet`` without arcs."""
    import skfem

    dim = p.shape[0]
    lin = (skfem.MeshTri if dim == 2 else skfem.MeshTet)(p, t)
    if not arcs:
        return lin
    quad_cls = skfem.MeshTri2 if dim == 2 else skfem.MeshTet2
    quad = quad_cls.from_mesh(lin)
    nv = lin.p.shape[1]
    edges = lin.facets if dim == 2 else lin.edges
    doflocs = curved_doflocs(quad.doflocs, lin.p, edges, nv + np.arange(edges.shape[1]), arcs)
    return quad_cls(doflocs, quad.t)


def assemble_elasticity(sb, lam, mu, chunk: int | None = None, free: np.ndarray | None = None):
    """Stiffness matrix of isotropic linear elasticity for the vector space
    built on the scalar Lagrange basis ``sb`` (P2 triangles and tetrahedra,
    triquadratic hexahedra, ...), optionally only its block on the free unknowns.

    Global numbering is interleaved, ``dim * s + c`` for scalar dof s and
    component c, which is scikit-fem's numbering for ``ElementVector``. The
    local matrices are formed from the scalar basis gradients by tensor
    contractions per chunk of cells:
    ``K[ia, jb] = sum_q w (lam g_ia g_jb + mu g_ib g_ja + mu delta_ab g_i . g_j)``,
    and summed on the scalar pattern a component pair at a time
    (:mod:`tactcad.mechanics.fem.fem_assembly`). This is scikit-fem's ``asm`` of
    the same form without a Python call per pair of basis functions.

    Args:
        sb: scikit-fem ``CellBasis`` of a scalar element.
        lam, mu: Lamé parameters (MPa): numbers, or arrays of shape
            (cells, quadrature points) of ``sb`` for a body of several materials.
        chunk: cells per contraction; ``None``: about 450 000 local entries
            (500 P2 tetrahedra), small enough to stay in the cache.
        free: the unknowns kept, ascending; the others (fixed at zero) are left
            out of rows and columns, as ``free_block(A, free)`` would. None: all.

    Returns:
        ``scipy.sparse.csr_matrix`` of shape (dim N, dim N) (N = sb.N), or
        (len(free), len(free)), N/mm per unit thickness in 2D.

    Raises:
        ValueError: ``free`` not ascending distinct unknowns, ``chunk`` below 1.

    Source: the isotropic elasticity bilinear form 2 mu eps(u):eps(v) +
    lam div u div v (e.g. Hughes, "The Finite Element Method", ch. 2), with
    the gradients of scikit-fem's basis.
    """
    from tactcad.mechanics.fem.fem_assembly import component_blocks, interleaved_csr, scalar_pattern

    pattern = scalar_pattern(sb.element_dofs, sb.N)
    blocks = component_blocks(sb, lam, mu, pattern, chunk)
    return interleaved_csr(pattern, blocks, sb.mesh.dim(), free)


def free_block(A, free: np.ndarray):
    """The block ``A[free][:, free]`` of a sparse matrix, in one pass over the rows kept.

    What scikit-fem's ``condense`` forms for homogeneous fixed values, without its
    column selection by a sparse product. The solves ask ``assemble_elasticity(...,
    free=...)`` for this block directly; this cuts it from a matrix already formed.

    Args:
        A: sparse matrix, shape (n, n).
        free: indices of the kept unknowns, ascending, shape (m,).

    Returns:
        ``scipy.sparse.csr_matrix`` of shape (m, m), the kept rows and columns in order.
    """
    import scipy.sparse as sp

    rows = sp.csr_matrix(A)[free]
    m = len(free)
    renumbered = np.full(A.shape[1], -1, dtype=np.int64)
    renumbered[free] = np.arange(m)
    cols = renumbered[rows.indices]
    kept = cols >= 0
    row_of = np.repeat(np.arange(m), np.diff(rows.indptr))
    indptr = np.concatenate([[0], np.cumsum(np.bincount(row_of[kept], minlength=m))])
    return sp.csr_matrix((rows.data[kept], cols[kept].astype(rows.indices.dtype), indptr),
                         shape=(m, m))


def basis_gradients(sb, u_scalar_fields: Sequence[np.ndarray], cells: np.ndarray,
                    points: np.ndarray) -> np.ndarray:
    """Gradients of fields on the scalar basis ``sb`` at reference points of some cells.

    The basis functions' gradients are formed for ``cells`` only, on ``sb``'s dofs and
    mapping (no new numbering of the whole mesh), and combined with each field's cell
    values directly: what scikit-fem's ``CellBasis(..., elements=cells).interpolate``
    gives, without the per-call work over the whole mesh.

    Args:
        sb: scalar basis (e.g. P2) of the solve.
        u_scalar_fields: one dof vector (length sb.N) per displacement component.
        cells: cell indices, shape (m,).
        points: reference-cell points, shape (dim, q).

    Returns:
        ``G[i, j, e, k] = d u_i / d x_j`` at point k of cell e, shape (fields, dim, m, q).

    Source: scikit-fem documentation (``CellBasis`` with a given quadrature and dofs).
    """
    from skfem import CellBasis

    cb = CellBasis(sb.mesh, sb.elem, mapping=sb.mapping, elements=np.asarray(cells),
                   quadrature=(points, np.ones(points.shape[1])), dofs=sb.dofs,
                   disable_doflocs=True)
    edofs = cb.element_dofs  # (nbf, m)
    grads = np.array([cb.basis[b][0].grad for b in range(cb.Nbfun)])  # (nbf, dim, m, q)
    return np.array([np.einsum("be,bjeq->jeq", np.asarray(u)[edofs], grads)
                     for u in u_scalar_fields])


def vertex_gradient(sb, u_scalar_fields: Sequence[np.ndarray], vertex: int) -> np.ndarray:
    """Gradient of P2 fields at a mesh vertex, averaged over the cells that
    share it (the P2 gradient is discontinuous across cells).

    Args:
        sb: scalar P2 basis.
        u_scalar_fields: one dof vector (length sb.N) per displacement
            component.
        vertex: vertex index.

    Returns:
        shape (dim, dim): G[i, j] = d u_i / d x_j.

    Raises:
        ValueError: the vertex belongs to no cell.
    """
    mesh = sb.mesh
    dim = mesh.dim()
    ref = mesh.init_refdom().p  # reference-cell vertices, shape (dim, dim + 1)
    cells, local = np.nonzero(mesh.t.T == vertex)
    if len(cells) == 0:
        raise ValueError(f"vertex {vertex} belongs to no cell")
    G = np.zeros((len(u_scalar_fields), dim))
    for k in np.unique(local):  # one basis per local position of the vertex
        at_k = basis_gradients(sb, u_scalar_fields, cells[local == k], ref[:, [k]])
        G += at_k[:, :, :, 0].sum(axis=2)
    return G / len(cells)


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    # einsum, not BLAS: a threaded BLAS level-1 call on two cores competes
    # with the single-threaded sparse products of the iteration
    return float(np.einsum("i,i->", a, b))


def pcg(A, b: np.ndarray, M, rtol: float = 1e-9, maxiter: int = 2000) -> tuple[np.ndarray, int]:
    """Preconditioned conjugate gradients for SPD ``A`` (Saad, Alg. 9.1).

    Args:
        A: SPD sparse matrix, shape (n, n).
        b: right-hand side, shape (n,).
        M: preconditioner, callable r -> M^-1 r (SPD).
        rtol: stop when ||r|| <= rtol ||b||.
        maxiter: iteration limit.

    Returns:
        (x, iterations).

    Raises:
        RuntimeError: not converged within ``maxiter`` or a breakdown
            (non-positive curvature: A or M not SPD).
    """
    x = np.zeros_like(b)
    r = b.copy()
    bb = math.sqrt(_dot(b, b))
    if bb == 0.0:
        return x, 0
    z = M(r)
    p = z.copy()
    rz = _dot(r, z)
    for it in range(1, maxiter + 1):
        Ap = A @ p
        pAp = _dot(p, Ap)
        if not pAp > 0:
            raise RuntimeError("PCG breakdown: the system or preconditioner is not SPD")
        alpha = rz / pAp
        x += alpha * p
        r -= alpha * Ap
        if math.sqrt(_dot(r, r)) <= rtol * bb:
            return x, it
        z = M(r)
        rz_new = _dot(r, z)
        p *= rz_new / rz
        p += z
        rz = rz_new
    raise RuntimeError(f"PCG did not converge in {maxiter} iterations")


def chebyshev_smoother(A, degree: int = 3):
    """Chebyshev polynomial smoother of degree ``degree`` in D^-1 A (D = diagonal)
    on [lambda_max / 30, lambda_max], lambda_max from 20 power iterations
    (fixed seed) times 1.2 (Saad, Alg. 12.1).

    Returns:
        ``smooth(r, with_residual) -> (x, res)``: x approximates A^-1 r from
        x = 0 (shape of r: one vector (n,) or a block of them (n, m), which
        shares each product with A); ``res`` is r - A x when
        ``with_residual``, else the residual before the last step (one
        product with A saved).
    """
    dinv = 1.0 / A.diagonal()
    rng = np.random.default_rng(0)
    v = rng.standard_normal(A.shape[0])
    lmax = 1.0
    v /= math.sqrt(_dot(v, v))
    for _ in range(20):
        w = dinv * (A @ v)
        nw = math.sqrt(_dot(w, w))
        lmax = nw  # ||v|| = 1
        v = w / nw
    hi, lo = 1.2 * lmax, 1.2 * lmax / 30.0  # power iteration underestimates lambda_max
    theta, delta = 0.5 * (hi + lo), 0.5 * (hi - lo)
    sigma = theta / delta

    def smooth(r, with_residual: bool):
        di = dinv if r.ndim == 1 else dinv[:, None]
        rho = 1.0 / sigma
        d = di * r / theta
        x = d.copy()
        res = r - A @ d
        for k in range(degree - 1):
            rho_new = 1.0 / (2.0 * sigma - rho)
            d = rho_new * rho * d + 2.0 * rho_new / delta * (di * res)
            rho = rho_new
            x += d
            if with_residual or k < degree - 2:
                res -= A @ d
        return x, res

    return smooth


def _two_level_preconditioner(A, P, smooth_degree: int = 3,
                              coarse_order: np.ndarray | None = None):
    """Symmetric two-level (p-multigrid) preconditioner for the P2 system.

    Coarse space: the P1 (vertex) functions of the same mesh, embedded in P2
    by ``P``; coarse operator ``P^T A P`` factorised once by SuperLU.
    Smoother: :func:`chebyshev_smoother` of degree ``smooth_degree``, applied
    before and after the coarse correction, so the cycle is symmetric (usable
    in CG). The residuals are carried through the cycle: six products with A
    per cycle at degree 3 where forming each residual anew takes eight. The
    cycle takes one residual (n,) or a block (n, m) (an eigensolver's).
    ``coarse_order``: an elimination order of the coarse unknowns (None:
    minimum degree).
    """
    from tactcad.mechanics.fem.sparse_lu import spd_lu

    restrict = P.T.tocsr()  # CSR by CSR: P^T A P of 573 000 unknowns 1.0 s, not 1.6-1.9 s
    lu = spd_lu(restrict @ A @ P, order=coarse_order)
    smooth = chebyshev_smoother(A, smooth_degree)

    def apply(r):
        x, res = smooth(r, True)
        e = P @ lu.solve(restrict @ res)
        x += e
        res -= A @ e
        x += smooth(res, False)[0]
        return x

    return apply


def p1_embedding(mesh, nscalar: int):
    """Sparse matrix (nscalar x n_vertices) taking vertex values of a P1
    function to the P2 dofs (vertex dofs copy, edge dofs average the edge's
    two vertices; exact for isoparametric P2 geometry as well)."""
    import scipy.sparse as sp

    nv = int(mesh.nvertices)
    edges = mesh.facets if mesh.dim() == 2 else mesh.edges
    ne = edges.shape[1]
    if nv + ne != nscalar:
        raise RuntimeError("unexpected P2 dof layout")
    rows = np.concatenate([np.arange(nv), nv + np.arange(ne), nv + np.arange(ne)])
    cols = np.concatenate([np.arange(nv), edges[0], edges[1]])
    vals = np.concatenate([np.ones(nv), 0.5 * np.ones(ne), 0.5 * np.ones(ne)])
    return sp.csr_matrix((vals, (rows, cols)), shape=(nscalar, nv))


def p_multigrid(mesh, nscalar: int, A_free, free: np.ndarray):
    """The two-level P2/P1 preconditioner (:func:`_two_level_preconditioner`)
    of a vector P2 system whose unknowns ``free`` are kept (the others fixed
    and removed).

    Args:
        mesh: the scikit-fem mesh (2D or 3D).
        nscalar: scalar P2 dofs (``basis.N``); the vector numbering is
            interleaved, ``dim * s + c``.
        A_free: the SPD matrix on the free unknowns (CSR), shape (len(free),) * 2.
        free: indices of the kept unknowns, ascending.

    Returns:
        ``apply(r)``: approximately ``A_free^-1 r`` for a residual (n,) or a block (n, m).
    """
    dim = mesh.dim()
    P, coarse_kept = free_p1_embedding(mesh, nscalar, free)
    order = coarse_nested_dissection(mesh, coarse_kept) if dim == 3 else None
    return _two_level_preconditioner(A_free, P, coarse_order=order)


def free_p1_embedding(mesh, nscalar: int, free: np.ndarray):
    """The vector P1-to-P2 embedding (:func:`p1_embedding` per component, interleaved
    ``dim * s + a``) on the kept unknowns only: rows ``free``, columns the vertex unknowns
    that are not fixed, formed directly instead of from the full embedding.

    Args:
        mesh: scikit-fem triangle or tetrahedron mesh (P2 dofs: vertices, then edges).
        nscalar: scalar P2 dofs (vertices + edges).
        free: kept vector unknowns, ascending, shape (m,).

    Returns:
        ``(P, coarse_kept)``: ``scipy.sparse.csr_matrix`` (m x kept vertex unknowns; 1 on a
        vertex's own unknowns, 1/2 on an edge's from each end), and the boolean mask of the
        kept vertex unknowns ``dim * v + a``.

    Raises:
        RuntimeError: the dofs are not the P2 layout (vertices, then edges).
    """
    import scipy.sparse as sp

    dim = mesh.dim()
    nv = int(mesh.nvertices)
    edges = mesh.facets if dim == 2 else mesh.edges
    ne = edges.shape[1]
    if nv + ne != nscalar:
        raise RuntimeError("unexpected P2 dof layout")
    kept = np.zeros(dim * nscalar, dtype=bool)
    kept[free] = True
    coarse_kept = kept[:dim * nv]  # vertex v's unknowns come first, dim v + a
    fine = np.full(dim * nscalar, -1, dtype=np.int64)
    fine[kept] = np.arange(kept.sum())
    coarse = np.full(dim * nv, -1, dtype=np.int64)
    coarse[coarse_kept] = np.arange(coarse_kept.sum())
    comp = np.arange(dim)
    edge_rows = (dim * (nv + np.arange(ne))[:, None] + comp).ravel()
    rows = np.concatenate([np.arange(dim * nv), edge_rows, edge_rows])
    cols = np.concatenate([np.arange(dim * nv), (dim * edges[0][:, None] + comp).ravel(),
                           (dim * edges[1][:, None] + comp).ravel()])
    vals = np.concatenate([np.ones(dim * nv), np.full(2 * dim * ne, 0.5)])
    r, c = fine[rows], coarse[cols]
    on = (r >= 0) & (c >= 0)
    P = sp.csr_matrix((vals[on], (r[on], c[on])), shape=(len(free), int(coarse_kept.sum())))
    return P, coarse_kept


def vertex_graph(mesh):
    """The mesh's vertices joined when they share a cell: the node graph of its P1 functions.

    Args:
        mesh: scikit-fem mesh (any cell type; ``mesh.t`` its cells' vertices).

    Returns:
        ``scipy.sparse.csr_matrix``, vertices x vertices, nonzero where two vertices share a
        cell (the diagonal included).
    """
    import scipy.sparse as sp

    t = mesh.t
    nv = int(mesh.nvertices)
    rows = np.repeat(t, t.shape[0], axis=0).ravel()
    cols = np.tile(t, (t.shape[0], 1)).ravel()
    return sp.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(nv, nv))


def coarse_nested_dissection(mesh, kept: np.ndarray) -> np.ndarray:
    """Elimination order of the P1 coarse system of a 3D mesh: METIS's nested dissection of
    the vertex graph, each vertex's three dofs together, the fixed dofs left out.

    On the finest mesh of a layered element (21 000 coarse unknowns) it leaves less fill
    than minimum degree, so the coarse factor is formed and applied in each cycle faster.

    Args:
        mesh: scikit-fem tetrahedron mesh.
        kept: boolean mask over the interleaved vertex dofs ``3 v + a`` (the coarse unknowns
            kept), shape (3 x vertices,).

    Returns:
        The kept coarse unknowns in elimination order (numbered among them).

    Source: METIS_NodeND (Karypis and Kumar, SIAM J. Sci. Comput. 20, 1998) through pymetis.
    """
    from tactcad.mechanics.fem.sparse_lu import graph_nested_dissection, node_dof_order

    return node_dof_order(graph_nested_dissection(vertex_graph(mesh)), mesh.dim(), kept)


def solve_elasticity(mesh, lam: float, mu: float, *, thickness: float, x_clamp: float,
                     contact: tuple[float, float, float], traction_MPa: float,
                     gauge_vertex: int | None, sym_plane_z: float | None = None,
                     solver: str = "direct", intorder: int | None = None,
                     rtol: float = 1e-10):
    """Assemble and solve linear elasticity with P2 elements (BLAS on one
    thread, see :func:`single_threaded_blas`).

    Args:
        mesh: scikit-fem triangle (2D; stiffness scaled by ``thickness``) or
            tetrahedron mesh, linear or quadratic geometry.
        lam, mu: Lamé parameters (MPa).
        thickness: out-of-plane thickness b in 2D (mm); 1 in 3D.
        x_clamp: clamp line/face, all displacements fixed (mm).
        contact: (x_min, x_max, y) of the contact face (mm).
        traction_MPa: uniform traction along +y on the contact face (MPa).
        gauge_vertex: vertex index for the gauge strain (or None).
        sym_plane_z: 3D only: z of a symmetry plane where u_z = 0.
        solver: "direct" (SuperLU, symmetric mode, minimum-degree ordering on
            A^T + A) or "pcg" (conjugate gradient with a two-level P2/P1
            p-multigrid preconditioner, relative residual ``rtol``).
        intorder: quadrature order (default 4 in 2D, 2 in 3D: exact for the
            P1 x P1 gradient products of straight P2 cells).

    Returns:
        (f^T u in N mm, total modelled force f.sum() in N, eps_xx at the
        gauge, number of dofs, CG iterations or 0). The mean contact-face
        deflection is f^T u / f.sum().

    Raises:
        RuntimeError: contact face or clamp line not found in the mesh, or
            CG did not converge.
        ValueError: unknown solver.
    """
    return solve_elasticity_field(mesh, lam, mu, thickness=thickness, x_clamp=x_clamp,
                                  contact=contact, traction_MPa=traction_MPa,
                                  gauge_vertex=gauge_vertex, sym_plane_z=sym_plane_z,
                                  solver=solver, intorder=intorder, rtol=rtol)[:5]


def solve_elasticity_field(mesh, lam: float, mu: float, **kwargs):
    """:func:`solve_elasticity` that also returns the field: a 6-tuple, the
    five values of :func:`solve_elasticity` and ``(basis, u)``, the scalar P2
    basis and the interleaved displacement vector (mm)."""
    with single_threaded_blas():
        return _solve_elasticity(mesh, lam, mu, **kwargs)


def _solve_elasticity(mesh, lam, mu, *, thickness, x_clamp, contact, traction_MPa,
                      gauge_vertex, sym_plane_z=None, solver="direct", intorder=None,
                      rtol=1e-10):
    import skfem
    from skfem import Basis, FacetBasis, LinearForm, asm

    if solver not in ("direct", "pcg"):
        raise ValueError(f"solver must be 'direct' or 'pcg', got {solver!r}")
    dim = mesh.dim()
    p2 = skfem.ElementTriP2() if dim == 2 else skfem.ElementTetP2()
    if intorder is None:
        intorder = 4 if dim == 2 else 2
    sb = Basis(mesh, p2, intorder=intorder)
    n = dim * int(sb.N)

    x0, x1, yc = contact
    tol = 1e-7
    cf = mesh.facets_satisfying(
        lambda x: (np.abs(x[1] - yc) < tol) & (x[0] > x0 - tol) & (x[0] < x1 + tol),
        boundaries_only=True)
    clamp = mesh.facets_satisfying(lambda x: np.abs(x[0] - x_clamp) < tol, boundaries_only=True)
    if len(cf) == 0 or len(clamp) == 0:
        raise RuntimeError("contact face or clamp line not found in the mesh")
    fb = FacetBasis(mesh, p2, facets=cf, intorder=intorder)
    q = float(traction_MPa)
    fy = asm(LinearForm(lambda v, w: q * v), fb) * thickness
    f = np.zeros(n)
    f[dim * np.arange(sb.N) + 1] = fy
    cdofs = sb.get_dofs(clamp).all()
    D = (dim * cdofs[:, None] + np.arange(dim)[None, :]).ravel()
    if sym_plane_z is not None:
        sym = mesh.facets_satisfying(lambda x: np.abs(x[2] - sym_plane_z) < tol,
                                     boundaries_only=True)
        D = np.union1d(D, dim * sb.get_dofs(sym).all() + 2)
    u = np.zeros(n)
    I = np.setdiff1d(np.arange(n), D)  # the fixed values are zero: f[I] is the load left
    Ac, fc = assemble_elasticity(sb, lam, mu, free=I), f[I]
    if thickness != 1.0:
        Ac = Ac * thickness
    iters = 0
    if solver == "direct":
        from tactcad.mechanics.fem.sparse_lu import spd_lu

        lu = spd_lu(Ac)
        u[I] = lu.solve(fc)
    else:
        Acsr = Ac.tocsr()
        u[I], iters = pcg(Acsr, fc, p_multigrid(mesh, sb.N, Acsr, I), rtol=rtol)
    compliance = float(f @ u)
    force = float(f.sum())
    eps_xx = float("nan")
    if gauge_vertex is not None:
        comps = [u[c::dim] for c in range(dim)]
        eps_xx = float(vertex_gradient(sb, comps, gauge_vertex)[0, 0])
    return compliance, force, eps_xx, n, iters, (sb, u)


def solve_fem2d(g: ElementGeometry, material: Material, *, plane: str = "stress",
                size_factor: float = 1.0, web_divisions: float = WEB_DIVISIONS,
                curved: bool = True, force_N: float = DEFAULT_FORCE_N,
                region: FemRegion | None = None, keep_field: bool = False,
                layer: BondedLayer | None = None) -> FemSolution:
    """One plane FEM solve (P2 triangles) of the element's tip stiffness.

    Args:
        g: element geometry (mm).
        material: E (MPa), nu.
        plane: "stress" or "strain".
        size_factor: scales every element size (< 1 refines).
        web_divisions: neck element size = web thickness / web_divisions
            (before ``size_factor``).
        curved: isoparametric P2 geometry on the arcs (else straight cells).
        force_N: total tip force (N); K does not depend on it (linear).
        region: cropped outline; ``None`` uses :func:`fem_region` (g).
        keep_field: keep the displacement field in ``FemSolution.field``.
        layer: the bonded gauge's glue line and carrier
            (:class:`~tactcad.mechanics.bonded_layer.BondedLayer`), meshed as a second
            region on the top face (plane stress, its modulus spread over the sheet);
            the grid strain is then read on its top. None: the bare element.

    Raises:
        ValueError: unknown plane, non-positive force.
    """
    if plane not in PLANES:
        raise ValueError(f"plane must be one of {PLANES}, got {plane!r}")
    if not force_N > 0:
        raise ValueError(f"force_N must be > 0, got {force_N!r}")
    t0 = time.perf_counter()
    region = fem_region(g) if region is None else region
    rm = mesh_region(g, region, dim=2, size_factor=size_factor, web_divisions=web_divisions,
                     layer_box=None if layer is None else layer.box(region.x_clamp),
                     layer_marks_x=() if layer is None else (layer.grid_x0_mm, layer.grid_x1_mm))
    mesh = skfem_mesh(rm, curved=curved)
    lam, mu = lame(material, plane)
    L, w = g.overall_length_mm, g.tip_width_mm
    b = g.sheet_thickness_mm
    lam_cells, mu_cells = layered_lame(lam, mu, rm.layer_cells, layer, b, plane)
    compliance, force, eps, n, _, (sb, u) = solve_elasticity_field(
        mesh, lam_cells, mu_cells, thickness=b, x_clamp=region.x_clamp,
        contact=(L - w, L, g.tip_top_y_mm), traction_MPa=force_N / (w * b),
        gauge_vertex=rm.gauge_vertex)
    body = None if rm.layer_cells is None else ~rm.layer_cells
    field = DisplacementField(sb, u, lam, mu, plane, force_N, body_cells=body) \
        if keep_field else None
    grid = float("nan") if layer is None else grid_plane_strain(rm.p, u, layer)
    return FemSolution(stiffness_N_per_mm=force**2 / compliance,
                       tip_deflection_mm=compliance / force,
                       gauge_strain=eps, force_N=force_N, n_dofs=n, n_cells=rm.t.shape[1],
                       neck_size_mm=rm.neck_size, wall_time_s=time.perf_counter() - t0,
                       field=field, grid_strain=grid)


def layered_lame(lam: float, mu: float, layer_cells: np.ndarray | None,
                 layer: BondedLayer | None, sheet_mm: float, plane: str | None):
    """(lambda, mu) per cell, shape (n_cells, 1), with a bonded layer's own (its modulus
    spread over the sheet, :meth:`~tactcad.mechanics.bonded_layer.BondedLayer.
    modulus_over_sheet_MPa`) on its cells; the numbers as they are without a layer (MPa)."""
    if layer is None or layer_cells is None:
        return lam, mu
    from tactcad.design.array_plan import Material

    spread = Material("bonded layer", layer.modulus_over_sheet_MPa(sheet_mm),
                      layer.poisson_ratio)
    lam_l, mu_l = lame(spread, plane)
    return (np.where(layer_cells, lam_l, lam)[:, None],
            np.where(layer_cells, mu_l, mu)[:, None])


def grid_plane_strain(vertices: np.ndarray, u: np.ndarray, layer: BondedLayer) -> float:
    """The grid's mean eps_xx on its plane (the layer's top): the difference of u_x at the
    grid's ends (mesh vertices, ``vertices`` shape (dim, n); a P2 field's first n scalar
    dofs are its vertices') over its length: the mean of du_x/dx along the line, exact for
    the field. In 3D the ends are read where the vertices lie on the mid-plane side's
    largest z (the symmetry plane of a half model).

    Raises:
        RuntimeError: a grid end is not a mesh vertex.
    """
    dim = vertices.shape[0]
    ux = u[0::dim]
    y = layer.grid_plane_y_mm
    on_line = np.abs(vertices[1] - y) < 1e-7
    if dim == 3:
        on_line &= np.abs(vertices[2] - vertices[2].max()) < 1e-7
    values = []
    for x in (layer.grid_x0_mm, layer.grid_x1_mm):
        hit = np.flatnonzero(on_line & (np.abs(vertices[0] - x) < 1e-7))
        if len(hit) == 0:
            raise RuntimeError(f"the grid's end x = {x:g} mm is not a mesh vertex")
        values.append(ux[hit[0]])
    return float((values[1] - values[0]) / layer.grid_length_mm)


@dataclass(frozen=True)
class Convergence:
    """A mesh sequence and its Richardson estimate (coarsest first)."""

    solutions: tuple[FemSolution, ...]
    stiffness: Richardson
    gauge_strain: Richardson
    wall_time_s: float

    @property
    def finest(self) -> FemSolution:
        return self.solutions[-1]


def size_factors(levels: int, ratio: float) -> list[float]:
    """Size factors r^(levels-1), ..., r, 1: the finest mesh is the default
    mesh, the others are coarser by r and r^2."""
    if levels < 3:
        raise ValueError("at least three meshes are needed for Richardson extrapolation")
    return [ratio**k for k in range(levels - 1, -1, -1)]


def fem2d_convergence(g: ElementGeometry, material: Material, *, plane: str = "stress",
                      web_divisions: float = WEB_DIVISIONS, ratio: float = REFINEMENT_RATIO,
                      levels: int = 3, curved: bool = True, force_N: float = DEFAULT_FORCE_N,
                      region: FemRegion | None = None,
                      progress: Callable[[str], None] | None = None) -> Convergence:
    """Solve on ``levels`` meshes (sizes r^(levels-1) ... 1 times the default)
    and Richardson-extrapolate K and the gauge strain; ``progress`` gets one
    line per mesh level solved. The bonded gauge ``g`` carries is meshed as its
    layer (:func:`solve_fem2d`, :func:`tactcad.mechanics.bonded_layer.layer_of`)."""
    from tactcad.mechanics.bonded_layer import layer_of

    layer = layer_of(g)
    t0 = time.perf_counter()
    region = fem_region(g) if region is None else region
    found = []
    with single_threaded_blas():
        for s in size_factors(levels, ratio):
            t_level = time.perf_counter()
            found.append(solve_fem2d(g, material, plane=plane, size_factor=s,
                                     web_divisions=web_divisions, curved=curved,
                                     force_N=force_N, region=region, layer=layer))
            if progress is not None:
                progress(f"fem2d {g.part_name}: mesh {len(found)}/{levels} (h x {s:.3f}), "
                         f"{time.perf_counter() - t_level:.1f} s")
    sols = tuple(found)
    rk = richardson([s.stiffness_N_per_mm for s in sols], ratio)
    rg = richardson([s.gauge_strain for s in sols], ratio)
    return Convergence(sols, rk, rg, time.perf_counter() - t0)


def grid_plane_strain_per_N(conv: Convergence, g: ElementGeometry, material: Material,
                            grid_width_mm: float, ratio: float = REFINEMENT_RATIO) -> dict:
    """What the gauge of ``g`` reads at fem2d, the one figure ``stiffness``, ``readout``,
    ``strength`` and ``thermal`` print as ``grid_strain_per_N``: the mean strain on the grid's
    plane (the layer's top) over the grid. The plane-stress solve gives it along the grid's
    length only; the fem3d-fitted width factor 1 - nu^2 phi of the face
    (:func:`tactcad.mechanics.gauge_strain.width_strain_factor`) carries that line to the
    grid's area in the sheet's width, as the closed form's grid factor does.

    Args:
        conv: ``g``'s mesh sequence with its layer meshed (:func:`fem2d_convergence`).
        g: the element; it carries the gauge.
        material: E (MPa), nu.
        grid_width_mm: the grid across the sheet (mm).
        ratio: the meshes' refinement ratio (``conv``'s).

    Returns:
        ``{"grid": 1/N (signed; the finest mesh's), "grid_error_rel": the Richardson error
        over the meshes plus the width factor's, "grid_source": text}``.

    Raises:
        ValueError: ``g`` carries no gauge.
    """
    from tactcad.mechanics.gauge_strain import width_strain_factor

    if g.gauge is None:
        raise ValueError(f"{g.part_name} carries no gauge: no grid's plane to read")
    per_N = [s.grid_strain / s.force_N for s in conv.solutions]
    width = width_strain_factor(g.bare(), material, grid_width_mm)
    return {"grid": width.factor * per_N[-1],
            "grid_error_rel": richardson(per_N, ratio).error_rel + width.error_rel,
            "grid_source": "fem2d with the glue line and carrier meshed: the grid's plane "
                           "along it, x the fem3d-fitted width factor"}


def estimate_fem2d(g: ElementGeometry, material: Material, *, element: int | None = None,
                   plane: str = "stress", web_divisions: float = WEB_DIVISIONS,
                   ratio: float = REFINEMENT_RATIO, curved: bool = True,
                   force_N: float = DEFAULT_FORCE_N,
                   margin_mm: float | None = None,
                   progress: Callable[[str], None] | None = None) -> StiffnessResult:
    """Level-3 estimate: plane stress (or plane strain) P2 FEM, three meshes; the bonded
    gauge ``g`` carries meshed as its layer (:func:`fem2d_convergence`).

    Args:
        g: element geometry (mm).
        material: E (MPa), nu.
        element: paper element number, carried into the result.
        plane: "stress" (the paper's FEM assumption) or "strain".
        web_divisions: finest-mesh neck size = web thickness / web_divisions.
        ratio: refinement ratio of the three meshes.
        curved: isoparametric arcs.
        force_N: tip force (N) for the gauge strain (reported per N).
        margin_mm: clamp margin behind the notch (``None``: the default of
            :func:`~tactcad.mechanics.fem.fem_mesh.fem_region`).
        progress: gets one line per mesh level solved (level, seconds).

    Returns:
        :class:`StiffnessResult` with model "fem2d" (plane stress) or
        "fem2d-plane-strain": K of the finest mesh (N/mm), ``face_strain_per_N``:
        magnitude of the face strain at the grid's centre per N (1/N; compressive), error estimate of K: the
        Richardson discretisation error plus the plane model's error against
        3D (:func:`plane_model_error`), total wall time (s).

    Raises:
        ValueError: unknown plane or bad margin.
    """
    region = fem_region(g, margin_mm)
    conv = fem2d_convergence(g, material, plane=plane, web_divisions=web_divisions, ratio=ratio,
                             curved=curved, force_N=force_N, region=region, progress=progress)
    fin = conv.finest
    return StiffnessResult(
        element=element, model="fem2d" if plane == "stress" else "fem2d-plane-strain",
        stiffness_N_per_mm=fin.stiffness_N_per_mm,
        face_strain_per_N=abs(fin.gauge_strain) / force_N,
        error_estimate_rel=conv.stiffness.error_rel + plane_model_error(g, material, plane),
        wall_time_s=conv.wall_time_s,
        grid_strain_per_N=None if g.gauge is None else float(grid_plane_strain_per_N(
            conv, g, material, g.gauge.grid_width_mm, ratio)["grid"]))


def plane_model_error(g: ElementGeometry, material: Material, plane: str = "stress") -> float:
    """Relative model error of a plane model against 3D (fem3d), from the
    width gain 1 + g of the fem3d-fitted correction
    (:func:`tactcad.mechanics.closed_form.width_gain`): plane stress is
    softer than 3D by 1 - 1/(1 + g); plane strain stiffer by (1/(1 - nu^2))/(1 + g) - 1.
    The same correction gives beam's model error (its notch term)."""
    from tactcad.mechanics.closed_form import width_gain

    gain = width_gain(g, material)
    if plane == "stress":
        return abs(1.0 - 1.0 / gain)
    nu = material.poisson_ratio
    return abs(1.0 / (1.0 - nu * nu) / gain - 1.0)
