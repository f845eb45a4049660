"""Modal levels "fem2d" and "fem3d": natural frequencies and mode shapes of
one element as clamped in the stiffness model.

The same P2 meshes, clamp and isoparametric geometry as the stiffness levels
(:mod:`tactcad.mechanics.fem.fem2d`, :mod:`tactcad.mechanics.fem.fem3d`): the
cropped exact profile, all displacements fixed on the clamp line
``x = x_clamp``. The generalized eigenproblem

    K phi = omega^2 M phi

uses the P2 stiffness matrix ``K`` and the consistent P2 mass matrix
``M = rho * integral(phi_i phi_j)`` (one block per displacement component),
solved for its lowest ``modes`` eigenpairs by ARPACK in shift-invert mode
about sigma = 0 (``scipy.sparse.linalg.eigsh``; SuperLU factors K once).
Units: mm, N, s, so the density enters in t/mm^3 (g/cm^3 x 1e-9) and
omega^2 comes out in 1/s^2; f = omega / (2 pi) in Hz.

fem2d: plane stress through the sheet thickness b (in-plane modes only).
fem3d: the half model of fem3d solved twice, once with ``u_z = 0`` on the
mid-plane (modes symmetric about it: bending in the sheet's plane, the
sensing direction) and once with ``u_x = u_y = 0`` there (antisymmetric:
bending out of the plane, twisting); both spectra are merged, each mode
labelled with its family.

Error estimate: the first frequency on three meshes (sizes r^2, r, 1 times
the default) Richardson-extrapolated (:mod:`tactcad.mechanics.richardson`);
fem2d adds the plane model's frequency error against 3D
(:func:`plane_frequency_error`), as its stiffness level adds the stiffness's.

Sources: K.-J. Bathe, "Finite Element Procedures" (1996), ch. 10-11
(consistent mass, generalized eigenproblem, shift); R. B. Lehoucq, D. C.
Sorensen, C. Yang, "ARPACK Users' Guide" (1998), shift-invert mode; scipy
documentation (``eigsh`` with ``sigma``); scikit-fem documentation
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
from tactcad.mechanics.fem.fem2d import (REFINEMENT_RATIO, assemble_elasticity, lame,
                                         plane_model_error, single_threaded_blas, size_factors,
                                         skfem_mesh)
from tactcad.mechanics.fem.fem_mesh import WEB_DIVISIONS, FemRegion, fem_region, graded_layers, mesh_region
from tactcad.mechanics.modal_result import ModalResult, Mode, density_t_per_mm3
from tactcad.mechanics.richardson import richardson

#: 3D modal meshes: neck size = web thickness / WEB_DIVISIONS_MODAL_3D and
#: N_LAYERS_MODAL layers over the half thickness on the finest mesh. Coarser
#: than fem3d's stiffness meshes: the eigenvalue converges at twice the
#: order of the displacement, and SuperLU's fill-in grows fast in 3D.
WEB_DIVISIONS_MODAL_3D = 4.0
N_LAYERS_MODAL = 4
Z_GRADING_MODAL = 4.0

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


def _mass_scalar(sb):
    from skfem import BilinearForm, asm

    return asm(BilinearForm(lambda u, v, w: u * v), sb)


def _vector_mass(sb, rho: float, dim: int):
    import scipy.sparse as sp

    # interleaved numbering dim * s + c, as assemble_elasticity
    return sp.kron(_mass_scalar(sb), sp.eye(dim), format="csr") * rho


def _lowest_modes(A, M, fixed: np.ndarray, modes: int) -> tuple[np.ndarray, np.ndarray]:
    """Lowest ``modes`` eigenpairs of A phi = lam M phi with ``fixed`` dofs
    removed (shift-invert about 0). Returns (lam ascending, full vectors)."""
    from scipy.sparse.linalg import eigsh

    n = A.shape[0]
    free = np.setdiff1d(np.arange(n), fixed)
    Af = A[free][:, free].tocsc()
    Mf = M[free][:, free].tocsc()
    k = min(modes, len(free) - 2)
    lam, vec = eigsh(Af, k=k, M=Mf, sigma=0.0, which="LM")
    order = np.argsort(lam)
    full = np.zeros((n, k))
    full[free] = vec[:, order]
    return lam[order], full


def _facet_dofs(mesh, sb, predicate) -> np.ndarray:
    facets = mesh.facets_satisfying(predicate, boundaries_only=True)
    return sb.get_dofs(facets).all()


def solve_modes(mesh, material: Material, *, thickness: float, x_clamp: float, modes: int,
                plane: str | None, sym_plane_z: float | None = None,
                families: tuple[str, ...] = ("in-plane",), intorder: int | None = None) -> ModalSolve:
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

    Returns:
        :class:`ModalSolve`, frequencies ascending over the families.

    Raises:
        DesignError: the material has no density.
        RuntimeError: the clamp face is not in the mesh.
    """
    import skfem
    from skfem import Basis

    t0 = time.perf_counter()
    rho = density_t_per_mm3(material)
    dim = mesh.dim()
    p2 = skfem.ElementTriP2() if dim == 2 else skfem.ElementTetP2()
    if intorder is None:
        intorder = 4
    sb = Basis(mesh, p2, intorder=intorder)
    lam_, mu = lame(material, plane)
    A = assemble_elasticity(sb, lam_, mu) * thickness
    M = _vector_mass(sb, rho, dim) * thickness
    tol = 1e-7
    cd = _facet_dofs(mesh, sb, lambda x: np.abs(x[0] - x_clamp) < tol)
    if len(cd) == 0:
        raise RuntimeError("clamp face not found in the mesh")
    clamp = (dim * cd[:, None] + np.arange(dim)[None, :]).ravel()
    found: list[tuple[float, str, np.ndarray]] = []
    with single_threaded_blas():
        for fam in (families if sym_plane_z is not None else ("in-plane",)):
            fixed = clamp
            if sym_plane_z is not None:
                sd = _facet_dofs(mesh, sb, lambda x: np.abs(x[2] - sym_plane_z) < tol)
                comps = (2,) if fam == "in-plane" else (0, 1)
                fixed = np.union1d(fixed, (dim * sd[:, None] + np.array(comps)[None, :]).ravel())
            lam, vecs = _lowest_modes(A, M, fixed, modes)
            found += [(float(l), fam, vecs[:, i]) for i, l in enumerate(lam)]
    found.sort(key=lambda f: f[0])
    found = found[:modes]
    freqs = tuple(math.sqrt(max(l, 0.0)) / (2 * math.pi) for l, _, _ in found)
    return ModalSolve(freqs, tuple(f for _, f, _ in found), A.shape[0],
                      time.perf_counter() - t0, sb, tuple(v for _, _, v in found), sym_plane_z)


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
    if dim == 2:
        rm = mesh_region(g, region, dim=2, size_factor=size_factor, web_divisions=WEB_DIVISIONS)
    else:
        b = g.sheet_thickness_mm
        nl = max(2, int(round(N_LAYERS_MODAL / size_factor)))
        rm = mesh_region(g, region, dim=3, size_factor=size_factor,
                         web_divisions=WEB_DIVISIONS_MODAL_3D, depth_mm=b / 2,
                         z_layers=graded_layers(b / 2, nl, Z_GRADING_MODAL))
    return skfem_mesh(rm, curved=True)


def solve_element_modes(g: ElementGeometry, material: Material, *, dim: int, modes: int = 3,
                        size_factor: float = 1.0, region: FemRegion | None = None) -> ModalSolve:
    """One mesh's modes of an element: plane stress (``dim`` 2) or the 3D
    half model in both families (``dim`` 3). Raises as :func:`solve_modes`."""
    region = fem_region(g) if region is None else region
    mesh = _mesh(g, region, dim, size_factor)
    if dim == 2:
        return solve_modes(mesh, material, thickness=g.sheet_thickness_mm,
                           x_clamp=region.x_clamp, modes=modes, plane="stress")
    return solve_modes(mesh, material, thickness=1.0, x_clamp=region.x_clamp, modes=modes,
                       plane=None, sym_plane_z=g.sheet_thickness_mm / 2,
                       families=tuple(FAMILIES))


def _estimate(model: str, dim: int, g: ElementGeometry, material: Material, *,
              element: int | None, modes: int, ratio: float,
              progress: Callable[[str], None] | None, keep: bool) -> ModalResult:
    if modes < 1:
        raise ValueError(f"modes = {modes!r}: allowed 1 or more")
    t0 = time.perf_counter()
    density_t_per_mm3(material)  # refuse a material without density before meshing
    region = fem_region(g)
    sols = []
    for i, s in enumerate(size_factors(3, ratio)):
        # the coarser meshes only feed the first frequency's Richardson estimate
        sols.append(solve_element_modes(g, material, dim=dim, modes=modes if i == 2 else 1,
                                        size_factor=s, region=region))
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
        basis=(f"P2 {'plane stress' if dim == 2 else '3D half model, both mid-plane families'}, "
               f"consistent mass, shift-invert about 0, Richardson over 3 meshes "
               f"(order {rich.order:.2f})"))
    return result


def estimate_modal_fem2d(g: ElementGeometry, material: Material, *, element: int | None = None,
                         modes: int = 3, ratio: float = REFINEMENT_RATIO,
                         progress: Callable[[str], None] | None = None,
                         keep_shapes: bool = False) -> ModalResult:
    """Modal level "fem2d": plane-stress P2 modes (in-plane only), three meshes.

    Returns:
        :class:`~tactcad.mechanics.modal_result.ModalResult`: the finest mesh's
        lowest ``modes`` frequencies (Hz), the Richardson error of the first
        plus the plane model's (:func:`plane_frequency_error`), wall time (s).

    Raises:
        ValueError: modes < 1. DesignError: no density.
    """
    return _estimate("fem2d", 2, g, material, element=element, modes=modes, ratio=ratio,
                     progress=progress, keep=keep_shapes)


def estimate_modal_fem3d(g: ElementGeometry, material: Material, *, element: int | None = None,
                         modes: int = 3, ratio: float = REFINEMENT_RATIO,
                         progress: Callable[[str], None] | None = None,
                         keep_shapes: bool = False) -> ModalResult:
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
                     progress=progress, keep=keep_shapes)


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
    for k, (f, fam, vec) in enumerate(zip(solve.frequencies_Hz, solve.families, solve.shapes)):
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
