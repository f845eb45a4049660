"""Modal levels "fem2d" and "fem3d": natural frequencies and mode shapes of
one element as clamped in the stiffness model.

The same P2 meshes, clamp and isoparametric geometry as the stiffness levels
(:mod:`tactcad.mechanics.fem.fem2d`, :mod:`tactcad.mechanics.fem.fem3d`): the
cropped exact profile, all displacements fixed on the clamp line
``x = x_clamp``. The generalized eigenproblem

    K phi = omega^2 M phi

uses the P2 stiffness matrix ``K`` and the consistent P2 mass matrix
``M = rho * integral(phi_i phi_j)`` (one block per displacement component),
solved for its lowest ``modes`` eigenpairs: the plane meshes by ARPACK in
shift-invert mode about sigma = 0 (``scipy.sparse.linalg.eigsh``; SuperLU
factors K once), the 3D meshes by LOBPCG preconditioned with the stiffness
solves' two-level p-multigrid cycle (:func:`lobpcg_lowest`), as a factorisation
of a 3D P2 matrix fills gigabytes (on two cores, the Ti example's 19.6 mm arm:
1.8 GB and 53 s of CPU against 0.7 GB and 20 s; the frequencies agree within 3e-8).
Units: mm, N, s, so the density enters in t/mm^3 (g/cm^3 x 1e-9) and
omega^2 comes out in 1/s^2; f = omega / (2 pi) in Hz.

fem2d: plane stress through the sheet thickness b (in-plane modes only).
fem3d: the half model of fem3d solved twice, once with ``u_z = 0`` on the
mid-plane (modes symmetric about it: bending in the sheet's plane, the
sensing direction) and once with ``u_x = u_y = 0`` there (antisymmetric:
bending out of the plane, twisting); both spectra are merged, each mode
labelled with its family.

Each mode's direction is read off its modal displacement
(:func:`mode_direction`): the share of its kinetic energy in each component
names it "in-plane" (u_y: bending in the sheet's plane), "out-of-plane"
(u_z: bending out of it), "torsion" (u_y in the antisymmetric family: the
arm twisting about its length) or "axial" (u_x in the symmetric family).

Added mass (:class:`~tactcad.mechanics.modal_result.PointMass`: gauge,
adhesive, leads, pads): lumped on the mesh vertex nearest its place, on the
mid-plane (the 3D half model carries half of it), in every displacement
component.

Error estimate: the first frequency on three meshes (sizes r^2, r, 1 times
the default) Richardson-extrapolated (:mod:`tactcad.mechanics.richardson`);
fem2d adds the plane model's frequency error against 3D
(:func:`plane_frequency_error`), as its stiffness level adds the stiffness's.

Sources: K.-J. Bathe, "Finite Element Procedures" (1996), ch. 10-11
(consistent mass, generalized eigenproblem, shift); R. B. Lehoucq, D. C.
Sorensen, C. Yang, "ARPACK Users' Guide" (1998), shift-invert mode; scipy
documentation (``eigsh`` with ``sigma``, ``lobpcg``); A. V. Knyazev,
"Toward the optimal preconditioned eigensolver: LOBPCG", SIAM J. Sci.
Comput. 23 (2001) 517-541; scikit-fem documentation
(``BilinearForm``, ``asm``, ``condense``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.mechanics.fem.fem2d import (REFINEMENT_RATIO, assemble_elasticity, lame, layered_lame,
                                         p_multigrid, plane_model_error, single_threaded_blas,
                                         size_factors, skfem_mesh)
from tactcad.mechanics.fem.fem_mesh import WEB_DIVISIONS, FemRegion, fem_region, graded_layers, mesh_region
from tactcad.mechanics.modal_result import ModalResult, Mode, PointMass, density_t_per_mm3
from tactcad.mechanics.richardson import richardson

#: 3D modal meshes: neck size = web thickness / WEB_DIVISIONS_MODAL_3D and
#: N_LAYERS_MODAL layers over the half thickness on the finest mesh. Coarser
#: than fem3d's stiffness meshes: the eigenvalue converges at twice the
#: order of the displacement, and SuperLU's fill-in grows fast in 3D.
WEB_DIVISIONS_MODAL_3D = 4.0
N_LAYERS_MODAL = 4
Z_GRADING_MODAL = 4.0

#: The eigensolvers of :func:`solve_modes`: shift-invert about 0 with a
#: SuperLU factorisation (the plane meshes), LOBPCG with the p-multigrid
#: preconditioner (the 3D meshes, whose factorisation fills gigabytes).
EIGEN_SOLVERS = ("direct", "lobpcg")

#: Families of the 3D half model's modes (boundary condition on the mid-plane).
FAMILIES = {"in-plane": "u_z = 0 on the mid-plane (symmetric)",
            "out-of-plane": "u_x = u_y = 0 on the mid-plane (antisymmetric)"}


@dataclass(frozen=True, eq=False)
class ModalSolve:
    """One mesh's eigen-solution (Hz, mm) and what is needed to write its shapes."""

    frequencies_Hz: tuple[float, ...]
    families: tuple[str, ...]
    n_dofs: int
    wall_time_s: float
    basis: object = field(repr=False)
    shapes: tuple[np.ndarray, ...] = field(repr=False)  # full interleaved vectors per mode
    sym_plane_z: float | None = None
    #: each mode's mid-plane family (the half model's boundary condition, :data:`FAMILIES`)
    mid_plane_families: tuple[str, ...] = ()


def _mass_scalar(sb):
    from skfem import BilinearForm, asm

    return asm(BilinearForm(lambda u, v, w: u * v), sb)


def _vector_mass(sb, rho, dim: int):
    """The consistent mass matrix (interleaved numbering ``dim * s + c``, as
    :func:`~tactcad.mechanics.fem.fem2d.assemble_elasticity`); ``rho`` a number or one
    density per cell (t/mm^3)."""
    import scipy.sparse as sp

    if np.ndim(rho) == 0:
        return sp.kron(_mass_scalar(sb), sp.eye(dim), format="csr") * rho
    from skfem import BilinearForm, asm

    weights = np.broadcast_to(np.asarray(rho, float)[:, None], sb.dx.shape)
    scalar = asm(BilinearForm(lambda u, v, w: w.rho * u * v), sb, rho=weights)
    return sp.kron(scalar, sp.eye(dim), format="csr")


def _lowest_modes(A, M, fixed: np.ndarray, modes: int,
                  precondition: Callable | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Lowest ``modes`` eigenpairs of A phi = lam M phi with ``fixed`` dofs
    removed: shift-invert about 0 with SuperLU (``precondition`` None), or
    LOBPCG with the preconditioner ``precondition(A_free, free)`` makes
    (:func:`lobpcg_lowest`). Returns (lam ascending, full vectors)."""
    from scipy.sparse.linalg import eigsh

    n = A.shape[0]
    free = np.setdiff1d(np.arange(n), fixed)
    Af = A[free][:, free]
    Mf = M[free][:, free]
    k = min(modes, len(free) - 2)
    if precondition is None:
        lam, vec = eigsh(Af.tocsc(), k=k, M=Mf.tocsc(), sigma=0.0, which="LM")
    else:
        lam, vec = lobpcg_lowest(Af.tocsr(), Mf.tocsr(), k,
                                 lambda As: precondition(As, free))
    order = np.argsort(lam)
    full = np.zeros((n, k))
    full[free] = vec[:, order]
    return lam[order], full


#: LOBPCG stops when every wanted eigenvalue's estimated relative error is
#: below this (frequencies to half of it): five orders below the Richardson
#: error of the finest meshes, and near the rounding floor of the 3D
#: stiffness matrix (the first frequency of the Ti example's long arm differs
#: by 3e-8 between this and the shift-invert solver).
EIGEN_RTOL = 1e-9

#: Block vectors beyond the wanted modes: the k-th eigenpair converges at
#: the rate lambda_k / lambda_(block + 1), so a spare vector keeps two close
#: modes (out of the plane, say) from slowing the last wanted one.
GUARD_VECTORS = 1

#: LOBPCG iterations between two checks of the error estimate, and at most in all.
LOBPCG_CHECK_EVERY = 10
LOBPCG_MAXITER = 400


def lobpcg_lowest(A, M, k: int, precondition: Callable) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` lowest eigenpairs of the SPD pencil ``A phi = lam M phi``
    by LOBPCG (scipy's ``lobpcg``) with a preconditioner close to A^-1.

    Memory stays that of the matrices and a few blocks of vectors, where a
    shift-invert Lanczos method needs a factorisation of A (SuperLU's fill-in
    of a 3D P2 system at 8.3 x 10^4 unknowns: 1.3 x 10^8 entries, 1.6 GB,
    for each of fem3d's two mid-plane families).

    Both matrices are first scaled to a unit mean diagonal (the consistent
    mass in t/mm^3 is some 1e-9 of the stiffness), which keeps the Gram
    matrices of the Rayleigh-Ritz step well conditioned. Convergence: for an
    M-normalised Ritz vector x with residual r = A x - lam M x, the relative
    error of lam is about r^T A^-1 r / lam (the share of the higher modes
    in x); with the preconditioner T for A^-1 this is checked every
    :data:`LOBPCG_CHECK_EVERY` iterations against :data:`EIGEN_RTOL`.

    Args:
        A, M: stiffness and mass on the free unknowns (sparse, SPD).
        k: how many eigenpairs.
        precondition: ``precondition(A_scaled) -> apply``, ``apply(R)``
            approximately ``A_scaled^-1 R`` for a block R (n, m).

    Returns:
        (eigenvalues ascending (k,), eigenvectors (n, k), M-orthonormal).

    Raises:
        RuntimeError: not converged within :data:`LOBPCG_MAXITER` iterations.

    Sources: A. V. Knyazev, "Toward the optimal preconditioned eigensolver:
    LOBPCG", SIAM J. Sci. Comput. 23 (2001) 517-541; scipy documentation
    (``scipy.sparse.linalg.lobpcg``); the error estimate as in B. N. Parlett,
    "The Symmetric Eigenvalue Problem" (1998), ch. 11 (Rayleigh quotient
    error in the energy norm of the residual).
    """
    import warnings

    from scipy.sparse.linalg import LinearOperator, lobpcg

    a, b = float(A.diagonal().mean()), float(M.diagonal().mean())
    As, Ms = A / a, M / b
    apply = precondition(As)
    T = LinearOperator(As.shape, matvec=apply, matmat=apply, dtype=float)
    X = np.random.default_rng(0).standard_normal((As.shape[0], k + GUARD_VECTORS))
    for _ in range(0, LOBPCG_MAXITER, LOBPCG_CHECK_EVERY):
        with warnings.catch_warnings():
            # it always stops at maxiter (the tolerance it is given is never
            # met) and says so; the check below is the stopping rule
            warnings.simplefilter("ignore", UserWarning)
            lam, X = lobpcg(As, X, B=Ms, M=T, tol=1e-300, largest=False,
                            maxiter=LOBPCG_CHECK_EVERY)
        order = np.argsort(lam)
        lam, X = lam[order], X[:, order]
        Xk, lk = X[:, :k], lam[:k]
        MX = Ms @ Xk
        R = As @ Xk - MX * lk
        err = np.einsum("ij,ij->j", R, apply(R)) / (lk * np.einsum("ij,ij->j", Xk, MX))
        if np.all(err < EIGEN_RTOL):
            return lk * (a / b), Xk / np.sqrt(b)
    raise RuntimeError(f"LOBPCG did not converge in {LOBPCG_MAXITER} iterations "
                       f"(estimated eigenvalue errors {err.tolist()})")


def mode_direction(vector: np.ndarray, scalar_mass, dim: int, family: str) -> str:
    """A mode's direction from its displacement (module docstring): the component
    carrying most of its kinetic energy v_c^T M v_c, read with its mid-plane family.

    Args:
        vector: the mode, interleaved (dim * node + component).
        scalar_mass: the scalar P2 mass matrix (one component).
        dim: 2 or 3. family: "in-plane" (symmetric) or "out-of-plane" (antisymmetric).

    Returns:
        "in-plane", "out-of-plane", "torsion" or "axial".
    """
    energy = [float(vector[c::dim] @ (scalar_mass @ vector[c::dim])) for c in range(dim)]
    main = int(np.argmax(energy))
    if main == 2:
        return "out-of-plane"
    if family == "out-of-plane":
        return "torsion" if main == 1 else "out-of-plane"
    return "in-plane" if main == 1 else "axial"


def _add_point_masses(M, mesh, sb, masses: tuple[PointMass, ...], dim: int,
                      sym_plane_z: float | None):
    """M with each point mass lumped on the vertex nearest its place (mid-plane in 3D;
    half of it on a half model)."""
    if not masses:
        return M
    M = M.tolil()
    # the corner vertices (a curved mesh also lists its mid-side nodes in p)
    corners = np.unique(mesh.t[:dim + 1])
    p = mesh.p[:, corners]
    for m in masses:
        where = np.array([m.x_mm, m.y_mm] + ([sym_plane_z] if dim == 3 else []))
        vertex = int(corners[np.argmin(np.sum((p - where[:, None]) ** 2, axis=0))])
        node = int(sb.nodal_dofs[0, vertex])
        share = 0.5 if sym_plane_z is not None else 1.0
        for c in range(dim):
            M[dim * node + c, dim * node + c] += share * m.mass_t
    return M.tocsr()


def _facet_dofs(mesh, sb, predicate) -> np.ndarray:
    facets = mesh.facets_satisfying(predicate, boundaries_only=True)
    return sb.get_dofs(facets).all()


def solve_modes(mesh, material: Material, *, thickness: float, x_clamp: float, modes: int,
                plane: str | None, sym_plane_z: float | None = None,
                families: tuple[str, ...] = ("in-plane",), intorder: int | None = None,
                solver: str = "direct", added_masses: tuple[PointMass, ...] = (),
                layer=None, layer_cells: np.ndarray | None = None,
                sheet_mm: float | None = None) -> ModalSolve:
    """The lowest ``modes`` natural frequencies of a clamped P2 mesh.

    Args:
        mesh: scikit-fem triangle (2D, ``thickness`` b) or tetrahedron mesh (mm).
        material: E (MPa), nu, density (g/cm^3).
        thickness: b in 2D (mm); 1 in 3D.
        x_clamp: clamp line/face (mm), all displacements fixed.
        modes: how many eigenpairs per family (>= 1).
        plane: "stress"/"strain" in 2D, None in 3D.
        sym_plane_z: 3D half model: z of the mid-plane.
        families: 3D half model: which of :data:`FAMILIES` to solve.
        solver: "direct" (shift-invert about 0, SuperLU) or "lobpcg"
            (:func:`lobpcg_lowest` with the two-level p-multigrid
            preconditioner of the stiffness solves; a 3D mesh's memory).
        added_masses: point masses lumped on the nearest vertex (:func:`_add_point_masses`).
        layer, layer_cells, sheet_mm: a bonded gauge's layer
            (:class:`~tactcad.mechanics.bonded_layer.BondedLayer`), its cells and the
            sheet it is spread over (mm): its stiffness on those cells, no mass of its own
            (the gauge installation's mass is one of ``added_masses``).

    Returns:
        :class:`ModalSolve`, frequencies ascending over the families, each
        mode's direction read off its displacement (:func:`mode_direction`).

    Raises:
        DesignError: the material has no density.
        RuntimeError: the clamp face is not in the mesh; LOBPCG did not converge.
        ValueError: unknown solver.
    """
    import skfem
    from skfem import Basis

    if solver not in EIGEN_SOLVERS:
        raise ValueError(f"solver = {solver!r}: allowed {', '.join(EIGEN_SOLVERS)}")
    t0 = time.perf_counter()
    rho = density_t_per_mm3(material)
    dim = mesh.dim()
    p2 = skfem.ElementTriP2() if dim == 2 else skfem.ElementTetP2()
    if intorder is None:
        intorder = 4
    sb = Basis(mesh, p2, intorder=intorder)
    lam_, mu = layered_lame(*lame(material, plane), layer_cells, layer, sheet_mm, plane)
    A = assemble_elasticity(sb, lam_, mu) * thickness
    scalar_mass = _mass_scalar(sb)
    density = rho if layer_cells is None or layer is None else np.where(layer_cells, 0.0, rho)
    M = _add_point_masses(_vector_mass(sb, density, dim) * thickness, mesh, sb, added_masses,
                          dim, sym_plane_z)
    tol = 1e-7
    cd = _facet_dofs(mesh, sb, lambda x: np.abs(x[0] - x_clamp) < tol)
    if len(cd) == 0:
        raise RuntimeError("clamp face not found in the mesh")
    clamp = (dim * cd[:, None] + np.arange(dim)[None, :]).ravel()
    precondition = None if solver == "direct" else (
        lambda A_free, free: p_multigrid(mesh, sb.N, A_free, free))
    found: list[tuple[float, str, np.ndarray]] = []
    with single_threaded_blas():
        for fam in (families if sym_plane_z is not None else ("in-plane",)):
            fixed = clamp
            if sym_plane_z is not None:
                sd = _facet_dofs(mesh, sb, lambda x: np.abs(x[2] - sym_plane_z) < tol)
                comps = (2,) if fam == "in-plane" else (0, 1)
                fixed = np.union1d(fixed, (dim * sd[:, None] + np.array(comps)[None, :]).ravel())
            lam, vecs = _lowest_modes(A, M, fixed, modes, precondition)
            found += [(float(l), mode_direction(vecs[:, i], scalar_mass, dim, fam), vecs[:, i],
                       fam) for i, l in enumerate(lam)]
    found.sort(key=lambda f: f[0])
    found = found[:modes]
    freqs = tuple(math.sqrt(max(l, 0.0)) / (2 * math.pi) for l, _, _, _ in found)
    return ModalSolve(freqs, tuple(f[1] for f in found), A.shape[0],
                      time.perf_counter() - t0, sb, tuple(f[2] for f in found), sym_plane_z,
                      tuple(f[3] for f in found))


def plane_frequency_error(g: ElementGeometry, material: Material) -> float:
    """fem2d's model error on a frequency against 3D (relative): plane stress
    is softer by e = :func:`~tactcad.mechanics.fem.fem2d.plane_model_error`,
    so f is lower by 1 - sqrt(1 - e); plus half the error of the fitted
    correction that e comes from (f ~ sqrt K)."""
    import warnings

    from tactcad.mechanics.closed_form import estimate_closed_form

    e = plane_model_error(g, material, "stress")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its error estimate already says how far it extrapolates
        fit = estimate_closed_form(g, material).error_estimate_rel
    return 1.0 - math.sqrt(max(1.0 - e, 0.0)) + 0.5 * fit


def _mesh(g: ElementGeometry, region: FemRegion, dim: int, size_factor: float):
    # the mesh, its bonded layer's cells (None for a bare element) and the layer
    from tactcad.mechanics.bonded_layer import layer_of

    layer = layer_of(g)
    box = None if layer is None else layer.box(region.x_clamp)
    if dim == 2:
        rm = mesh_region(g, region, dim=2, size_factor=size_factor, web_divisions=WEB_DIVISIONS,
                         layer_box=box)
    else:
        b = g.sheet_thickness_mm
        nl = max(2, int(round(N_LAYERS_MODAL / size_factor)))
        rm = mesh_region(g, region, dim=3, size_factor=size_factor,
                         web_divisions=WEB_DIVISIONS_MODAL_3D, depth_mm=b / 2,
                         z_layers=graded_layers(b / 2, nl, Z_GRADING_MODAL), layer_box=box)
    return skfem_mesh(rm, curved=True), rm.layer_cells, layer


def solve_element_modes(g: ElementGeometry, material: Material, *, dim: int, modes: int = 3,
                        size_factor: float = 1.0, region: FemRegion | None = None,
                        added_masses: tuple[PointMass, ...] = ()) -> ModalSolve:
    """One mesh's modes of an element: plane stress (``dim`` 2) or the 3D
    half model in both families (``dim`` 3). Raises as :func:`solve_modes`."""
    region = fem_region(g) if region is None else region
    mesh, cells, layer = _mesh(g, region, dim, size_factor)
    bonded = {"layer": layer, "layer_cells": cells, "sheet_mm": g.sheet_thickness_mm}
    if dim == 2:
        return solve_modes(mesh, material, thickness=g.sheet_thickness_mm,
                           x_clamp=region.x_clamp, modes=modes, plane="stress",
                           added_masses=added_masses, **bonded)
    return solve_modes(mesh, material, thickness=1.0, x_clamp=region.x_clamp, modes=modes,
                       plane=None, sym_plane_z=g.sheet_thickness_mm / 2,
                       families=tuple(FAMILIES), solver="lobpcg", added_masses=added_masses,
                       **bonded)


def _estimate(model: str, dim: int, g: ElementGeometry, material: Material, *,
              element: int | None, modes: int, ratio: float,
              progress: Callable[[str], None] | None, keep: bool,
              added_masses: tuple[PointMass, ...] = ()) -> ModalResult:
    if modes < 1:
        raise ValueError(f"modes = {modes!r}: allowed 1 or more")
    t0 = time.perf_counter()
    density_t_per_mm3(material)  # refuse a material without density before meshing
    region = fem_region(g)
    sols = []
    for i, s in enumerate(size_factors(3, ratio)):
        # the coarser meshes only feed the first frequency's Richardson estimate
        sols.append(solve_element_modes(g, material, dim=dim, modes=modes if i == 2 else 1,
                                        size_factor=s, region=region,
                                        added_masses=added_masses))
        if progress is not None:
            progress(f"{model} modal {g.part_name}: mesh {i + 1}/3 (h x {s:.3f}), "
                     f"{sols[-1].n_dofs} unknowns, {sols[-1].wall_time_s:.1f} s")
    rich = richardson([s.frequencies_Hz[0] for s in sols], ratio)
    err = rich.error_rel
    if dim == 2:
        err += plane_frequency_error(g, material)
    fin = sols[-1]
    result = ModalResult(
        element=element, model=model,
        modes=tuple(Mode(i + 1, f, fam) for i, (f, fam) in enumerate(zip(fin.frequencies_Hz,
                                                                          fin.families))),
        solve=fin if keep else None,
        error_estimate_rel=err, wall_time_s=time.perf_counter() - t0,
        added_mass_g=sum(m.mass_g for m in added_masses),
        basis=(f"P2 {'plane stress' if dim == 2 else '3D half model, both mid-plane families'}, "
               f"consistent mass, shift-invert about 0, Richardson over 3 meshes "
               f"(order {rich.order:.2f})"))
    return result


def estimate_modal_fem2d(g: ElementGeometry, material: Material, *, element: int | None = None,
                         modes: int = 3, ratio: float = REFINEMENT_RATIO,
                         progress: Callable[[str], None] | None = None,
                         keep_shapes: bool = False,
                         added_masses: tuple[PointMass, ...] = ()) -> ModalResult:
    """Modal level "fem2d": plane-stress P2 modes (in-plane only), three meshes.

    Returns:
        :class:`~tactcad.mechanics.modal_result.ModalResult`: the finest mesh's
        lowest ``modes`` frequencies (Hz), the Richardson error of the first
        plus the plane model's (:func:`plane_frequency_error`), wall time (s).

    Raises:
        ValueError: modes < 1. DesignError: no density.
    """
    return _estimate("fem2d", 2, g, material, element=element, modes=modes, ratio=ratio,
                     progress=progress, keep=keep_shapes, added_masses=added_masses)


def estimate_modal_fem3d(g: ElementGeometry, material: Material, *, element: int | None = None,
                         modes: int = 3, ratio: float = REFINEMENT_RATIO,
                         progress: Callable[[str], None] | None = None,
                         keep_shapes: bool = False,
                         added_masses: tuple[PointMass, ...] = ()) -> ModalResult:
    """Modal level "fem3d" (the reference): 3D P2 half model in both
    mid-plane families (:data:`FAMILIES`), three meshes.

    Returns:
        :class:`~tactcad.mechanics.modal_result.ModalResult`: the lowest
        ``modes`` frequencies (Hz) of both families merged, the Richardson
        error of the first, wall time (s).

    Raises:
        ValueError: modes < 1. DesignError: no density.
    """
    return _estimate("fem3d", 3, g, material, element=element, modes=modes, ratio=ratio,
                     progress=progress, keep=keep_shapes, added_masses=added_masses)


def write_modes_vtu(path: str | Path, solve: ModalSolve) -> Path:
    """Write every mode shape of a solve as a VTU file for ParaView.

    Point data ``mode_K`` (K = 1, 2, ...; shape (n, 3), mass-normalised, mm
    per sqrt(t)) for each mode; its frequency is in the array's name
    (``mode_1_123.4Hz``). A 3D half model is mirrored about the mid-plane
    (u_z flips sign for an in-plane mode, u_x and u_y for an out-of-plane one).

    Returns:
        the path written (parent directories are created).
    """
    import meshio

    mesh = solve.basis.mesh
    dim = mesh.dim()
    nv = mesh.p.shape[1]
    pts = np.zeros((nv, 3))
    pts[:, :dim] = mesh.p.T
    cells = mesh.t.T.astype(np.int64)
    data = {}
    mirrored = solve.sym_plane_z is not None
    mid = solve.mid_plane_families or solve.families
    for k, (f, fam, vec) in enumerate(zip(solve.frequencies_Hz, mid, solve.shapes)):
        d = np.zeros((nv, 3))
        for c in range(dim):
            d[:, c] = vec[c::dim][:nv]  # P2 vertex dofs come first
        if mirrored:
            m = d.copy()
            flip = (2,) if fam == "in-plane" else (0, 1)
            m[:, list(flip)] *= -1.0
            d = np.vstack([d, m])
        data[f"mode_{k + 1}_{f:.4g}Hz"] = d
    if mirrored:
        zm = solve.sym_plane_z
        mp = pts.copy()
        mp[:, 2] = 2.0 * zm - mp[:, 2]
        pts = np.vstack([pts, mp])
        cells = np.vstack([cells, cells[:, [0, 2, 1, 3]] + nv])
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    meshio.Mesh(pts, [("triangle" if dim == 2 else "tetra", cells)], point_data=data).write(
        out, file_format="vtu")
    return out
