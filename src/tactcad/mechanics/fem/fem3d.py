"""Level-4 stiffness estimator "fem3d" (the reference): 3D P2 elasticity.

Quadratic tetrahedra (scikit-fem ``ElementTetP2``, isoparametric
``MeshTet2`` with the notch and fillet edges on the exact circles) on the
cropped exact profile (:func:`tactcad.mechanics.fem.fem_mesh.fem_region`)
extruded through the sheet.

Half model: geometry, clamp and load are symmetric about the mid-plane
z = b/2 of the sheet, so only 0 <= z <= b/2 is meshed with ``u_z = 0`` on the
mid-plane; the full element's stiffness is ``K = 2 F_h^2 / (f_h^T u_h)``
(twice the force at the same deflection). This halves the unknowns.

Mesh: the 2D mesh of :func:`~tactcad.mechanics.fem.fem_mesh.mesh_region` (size
``t / web_divisions`` at the neck) extruded in ``n_layers`` layers that grow
geometrically from the free face z = 0 (where the through-thickness
variation of the stress is largest: plane-stress-like at the free face,
plane-strain-like inside) to the mid-plane, each prism split into three
tetrahedra. ``size_factor`` scales the in-plane sizes and divides the layer
count, so the three meshes of the Richardson sequence are refined in all
directions by the same ratio (in-plane exactly, through the thickness to
the nearest whole layer).

Boundary conditions: all displacements fixed on the clamp face
``x = x_clamp``; uniform traction along +y on the contact face (the tip's top
face, ``tip_width x b``).

Solver: conjugate gradients preconditioned by a symmetric two-level
p-multigrid cycle (Chebyshev–Jacobi smoothing on P2, exact coarse solve on
the P1 functions of the same mesh, factorised once under METIS's nested
dissection of the vertex graph: on the 19.6 mm titanium arm's finest mesh,
21 700 coarse unknowns, 0.9 s of CPU to factorise and 20 ms per cycle
against 2.1 s and 32 ms under minimum degree), see
:func:`tactcad.mechanics.fem.fem2d.solve_elasticity`. Measured on two cores:
SuperLU (symmetric mode, minimum-degree ordering) needs about 20 s and
2.5 GiB at 7.6 x 10^4 unknowns and minutes and over 5 GiB at 1.4 x 10^5, as
fill-in grows fast in 3D; PCG needs a few seconds and under 0.5 GiB at
7 x 10^4 unknowns.

Outputs as for fem2d: K from the energy, gauge strain ``eps_xx`` at the
top face over the web at x = hinge_x on the mid-plane (the centre of a gauge
bonded across the web), Richardson error estimate over three meshes; and,
per mesh, ``eps_xx`` on the whole flat top face
(:func:`~tactcad.mechanics.fem.fields.top_face_strain`), which the read-out
averages over the gauge grid's area.

Sources: scikit-fem documentation (``MeshTet2``, ``ElementTetP2``,
``Basis``, ``FacetBasis``, ``condense``); gmsh reference manual
(OpenCASCADE ``extrude`` with layers); Y. Saad, "Iterative Methods for
Sparse Linear Systems", 2nd ed. (Chebyshev acceleration, preconditioned CG);
Richardson extrapolation by :mod:`tactcad.mechanics.richardson`.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import math
import resource
import time
from dataclasses import dataclass, replace
from typing import Callable

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.mechanics.fem.fem2d import (DEFAULT_FORCE_N, REFINEMENT_RATIO, Convergence, DisplacementField,
                    FemSolution, grid_plane_strain, lame, layered_lame, single_threaded_blas,
                    size_factors, skfem_mesh, solve_elasticity_field)
from tactcad.mechanics.bonded_layer import BondedLayer, layer_of
from tactcad.mechanics.fem.fem_mesh import FemRegion, fem_region, graded_layers, mesh_region
from tactcad.mechanics.fem.fields import FaceStrain, PeakStress, peak_notch_stress, top_face_strain
from tactcad.mechanics.stiffness_result import StiffnessResult
from tactcad.mechanics.richardson import richardson
from tactcad.store import kept_result

#: Finest-mesh neck size = web thickness / WEB_DIVISIONS_3D.
WEB_DIVISIONS_3D = 6.0

#: Layers through the half thickness on the finest mesh.
N_LAYERS = 6

#: Thickness ratio of the mid-plane layer to the free-face layer.
Z_GRADING = 6.0

#: PCG stops at this relative residual. Against 1e-7 on the finest meshes of the macro
#: array's two elements and of a nearly incompressible one (nu 0.476, the slowest to
#: converge): K the same within 6e-15 (the energy is quadratic in the error), the gauge
#: strain within 1.1e-8 and the hinge's peak stress within 1.8e-8 (five orders below the
#: Richardson error), in a quarter fewer PCG iterations (the macro array's first element
#: 49 -> 35, the nu 0.476 one 80 -> 61).
PCG_RTOL = 1e-5


def peak_rss_mib() -> float:
    """Peak resident set size of this process so far (MiB; Linux ru_maxrss is kB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def solve_fem3d(g: ElementGeometry, material: Material, *, size_factor: float = 1.0,
                web_divisions: float = WEB_DIVISIONS_3D, n_layers: int = N_LAYERS,
                grading: float = Z_GRADING, curved: bool = True,
                force_N: float = DEFAULT_FORCE_N, region: FemRegion | None = None,
                solver: str = "pcg", keep_field: bool = False,
                layer: BondedLayer | None = None) -> FemSolution:
    """One 3D P2 solve (half model) of the element's tip stiffness.

    Args:
        g: element geometry (mm).
        material: E (MPa), nu.
        size_factor: scales the in-plane sizes; the layer count becomes
            ``max(2, round(n_layers / size_factor))``.
        web_divisions: neck size = web thickness / web_divisions (before
            ``size_factor``).
        n_layers: layers over the half thickness b/2 at ``size_factor`` 1.
        grading: mid-plane layer / free-face layer thickness.
        curved: isoparametric arcs (else straight-sided tetrahedra).
        force_N: total tip force on the full element (N).
        region: cropped outline; ``None`` uses :func:`fem_region` (g).
        solver: "pcg" (default) or "direct" (SuperLU; small meshes only).
        keep_field: keep the half model's displacement field in
            ``FemSolution.field`` (mid-plane at z = b/2).
        layer: the bonded gauge's glue line and carrier
            (:class:`~tactcad.mechanics.bonded_layer.BondedLayer`), meshed on the top face
            across the sheet, its modulus spread over it; the grid strain is read on its
            top at the mid-plane. None: the bare element.

    Returns:
        :class:`~tactcad.mechanics.fem.fem2d.FemSolution` for the full element
        (K, mean contact deflection, gauge strain under ``force_N``; n_dofs
        and n_cells of the half model).

    Raises:
        ValueError: non-positive force or size factor, unknown solver.
        RuntimeError: meshing failed or CG did not converge.
    """
    if not force_N > 0:
        raise ValueError(f"force_N must be > 0, got {force_N!r}")
    t0 = time.perf_counter()
    region = fem_region(g) if region is None else region
    b = g.sheet_thickness_mm
    nl = max(2, int(round(n_layers / size_factor)))
    layers = graded_layers(b / 2, nl, grading)
    rm = mesh_region(g, region, dim=3, size_factor=size_factor, web_divisions=web_divisions,
                     depth_mm=b / 2, z_layers=layers,
                     layer_box=None if layer is None else layer.box(region.x_clamp),
                     layer_marks_x=() if layer is None else (layer.grid_x0_mm,
                                                             layer.grid_x1_mm))
    mesh = skfem_mesh(rm, curved=curved)
    lam, mu = lame(material, None)
    L, w = g.overall_length_mm, g.tip_width_mm
    lam_cells, mu_cells = layered_lame(lam, mu, rm.layer_cells, layer, b, None)
    compliance, force_h, eps, n, _, (sb, u) = solve_elasticity_field(
        mesh, lam_cells, mu_cells, thickness=1.0, x_clamp=region.x_clamp,
        contact=(L - w, L, g.tip_top_y_mm), traction_MPa=force_N / (w * b),
        gauge_vertex=rm.gauge_vertex, sym_plane_z=b / 2, solver=solver, rtol=PCG_RTOL)
    deflection = compliance / force_h
    body = None if rm.layer_cells is None else ~rm.layer_cells
    field = DisplacementField(sb, u, lam, mu, None, 2.0 * force_h, b / 2, body_cells=body) \
        if keep_field else None
    grid = float("nan") if layer is None else grid_plane_strain(rm.p, u, layer)
    return FemSolution(stiffness_N_per_mm=2.0 * force_h / deflection,
                       tip_deflection_mm=deflection, gauge_strain=eps, force_N=2.0 * force_h,
                       n_dofs=n, n_cells=rm.t.shape[1], neck_size_mm=rm.neck_size,
                       wall_time_s=time.perf_counter() - t0, field=field, grid_strain=grid)


@dataclass(frozen=True)
class Convergence3D(Convergence):
    """:class:`~tactcad.mechanics.fem.fem2d.Convergence` plus the peak memory,
    each mesh's peak stress at the hinge (coarsest first, under the solves'
    force; :func:`~tactcad.mechanics.fem.fields.peak_notch_stress`) and each
    mesh's eps_xx on the flat top face (:func:`~tactcad.mechanics.fem.fields.top_face_strain`,
    per newton), so the stiffness, strength and read-out levels read one set of solves."""

    peak_rss_mib: float = math.nan
    peaks: tuple[PeakStress, ...] = ()
    top_face_strains: tuple[FaceStrain, ...] = ()
    #: with a bonded layer: each mesh's eps_xx on the grid's plane (the layer's top), per N
    grid_plane_strains: tuple[FaceStrain, ...] = ()


def fem3d_convergence(g: ElementGeometry, material: Material, *,
                      web_divisions: float = WEB_DIVISIONS_3D, n_layers: int = N_LAYERS,
                      grading: float = Z_GRADING, ratio: float = REFINEMENT_RATIO,
                      levels: int = 3, curved: bool = True, force_N: float = DEFAULT_FORCE_N,
                      region: FemRegion | None = None, solver: str = "pcg",
                      verbose: bool = False,
                      progress: Callable[[str], None] | None = None) -> Convergence3D:
    """Solve on ``levels`` meshes (sizes r^(levels-1) ... 1 times the
    default), Richardson-extrapolate K and the gauge strain, and take each
    mesh's peak stress at the hinge.

    The sequence is kept in the result store (:func:`tactcad.store.kept_result`;
    key: the geometry, material, region and every setting but ``verbose``
    and ``progress``), so the stiffness level (:func:`estimate_fem3d`) and
    the strength study's peak stress of the same element solve it once.
    The bonded gauge ``g`` carries is meshed as its layer (:func:`solve_fem3d`,
    :func:`tactcad.mechanics.bonded_layer.layer_of`).

    With ``verbose`` each solve prints its K, unknowns, wall time and the
    process's peak RSS; ``progress`` gets one line per mesh level solved.
    """
    region = fem_region(g) if region is None else region
    settings = {"web_divisions": web_divisions, "n_layers": n_layers, "grading": grading,
                "ratio": ratio, "levels": levels, "curved": curved, "force_N": force_N,
                "solver": solver}
    layer = layer_of(g)
    if layer is not None:  # the bare element's key stays as it was
        settings["layer"] = layer
    return kept_result("fem3d convergence",
                       lambda: _converge(g, material, region, settings, verbose, progress),
                       g, material, region, settings)


def _converge(g: ElementGeometry, material: Material, region: FemRegion, settings: dict,
              verbose: bool, progress: Callable[[str], None] | None) -> Convergence3D:
    t0 = time.perf_counter()
    levels, ratio = settings["levels"], settings["ratio"]
    solve = {k: v for k, v in settings.items() if k not in ("levels", "ratio")}
    sols, peaks, faces, grids = [], [], [], []
    layer = settings.get("layer")
    with single_threaded_blas():
        for s in size_factors(levels, ratio):
            sol = solve_fem3d(g, material, size_factor=s, region=region, keep_field=True,
                              **solve)
            peaks.append(peak_notch_stress(sol.field, g))
            faces.append(top_face_strain(sol.field, g.base_height_mm))
            if layer is not None:
                grids.append(top_face_strain(sol.field, layer.grid_plane_y_mm))
            sol = replace(sol, field=None)  # frees the mesh and basis before the next solve
            sols.append(sol)
            if progress is not None:
                progress(f"fem3d {g.part_name}: mesh {len(sols)}/{levels} (h x {s:.3f}), "
                         f"{sol.n_dofs} unknowns, {sol.wall_time_s:.1f} s")
            if verbose:
                print(f"fem3d {g.part_name}: h x {s:.3f}: K = {sol.stiffness_N_per_mm:.5f} "
                      f"N/mm, {sol.n_dofs} dofs, {sol.wall_time_s:.1f} s, peak RSS "
                      f"{peak_rss_mib():.0f} MiB")
    rk = richardson([s.stiffness_N_per_mm for s in sols], ratio)
    rg = richardson([s.gauge_strain for s in sols], ratio)
    conv = Convergence3D(tuple(sols), rk, rg, time.perf_counter() - t0, peak_rss_mib(),
                         tuple(peaks), tuple(faces), tuple(grids))
    if verbose:
        print(f"fem3d {g.part_name}: K = {sols[-1].stiffness_N_per_mm:.5f} N/mm, Richardson "
              f"order {rk.order:.2f}, K_ext = {rk.extrapolated:.5f}, error "
              f"{100 * rk.error_rel:.3f} %, {conv.wall_time_s:.1f} s, peak RSS "
              f"{conv.peak_rss_mib:.0f} MiB")
    return conv


def grid_area_strains_per_N(conv: Convergence3D, g: ElementGeometry,
                            grid_width_mm: float) -> list[float]:
    """Each mesh's strain on the grid's plane (the layer's top) averaged over the grid's area,
    per newton (1/N, signed; coarsest first): what the gauge of ``g`` reads at fem3d, the one
    figure ``stiffness``, ``readout`` and ``strength`` print as ``grid_strain_per_N``.

    Args:
        conv: ``g``'s sequence with its layer meshed (:func:`fem3d_convergence`).
        g: the element; its gauge's layer sets the grid's ends along it.
        grid_width_mm: the grid across the sheet (mm), centred on the mid-plane, at most the
            sheet.

    Returns:
        one value a mesh.

    Raises:
        ValueError: ``g`` carries no gauge.
    """
    from tactcad.mechanics.fem.fields import face_rectangle_average

    layer = layer_of(g)
    if layer is None:
        raise ValueError(f"{g.part_name} carries no gauge: no grid's plane to read")
    b = g.sheet_thickness_mm
    w = min(grid_width_mm, b)
    span, across = (layer.grid_x0_mm, layer.grid_x1_mm), (b / 2 - w / 2, b / 2 + w / 2)
    return [face_rectangle_average(f, span, across) for f in conv.grid_plane_strains]


def estimate_fem3d(g: ElementGeometry, material: Material, *, element: int | None = None,
                   web_divisions: float = WEB_DIVISIONS_3D, n_layers: int = N_LAYERS,
                   grading: float = Z_GRADING, ratio: float = REFINEMENT_RATIO,
                   curved: bool = True, force_N: float = DEFAULT_FORCE_N,
                   margin_mm: float | None = None, solver: str = "pcg",
                   verbose: bool = False,
                   progress: Callable[[str], None] | None = None) -> StiffnessResult:
    """Level-4 (reference) estimate: 3D P2 FEM of the half element, three meshes; the
    bonded gauge ``g`` carries meshed as its layer (:func:`fem3d_convergence`).

    Args:
        g: element geometry (mm).
        material: E (MPa), nu.
        element: paper element number, carried into the result.
        web_divisions, n_layers, grading: finest mesh (see
            :func:`solve_fem3d`).
        ratio: refinement ratio of the three meshes.
        curved: isoparametric arcs.
        force_N: tip force (N) for the gauge strain (reported per N).
        margin_mm: clamp margin behind the notch (``None``: default of
            :func:`~tactcad.mechanics.fem.fem_mesh.fem_region`).
        solver: "pcg" or "direct".
        verbose: print K, time and peak RSS of every mesh.
        progress: gets one line per mesh level solved (level, unknowns, seconds).

    Returns:
        :class:`StiffnessResult` with model "fem3d": K of the finest mesh
        (N/mm), ``face_strain_per_N``: magnitude of the face strain at the grid's
        centre per N (1/N; the top face over
        the web is compressed by an upward tip force; the signed value is
        ``FemSolution.gauge_strain``), Richardson error estimate of K, total
        wall time (s).

    Raises:
        ValueError: bad margin, force or solver.
        RuntimeError: meshing failed or CG did not converge.
    """
    region = fem_region(g, margin_mm)
    conv = fem3d_convergence(g, material, web_divisions=web_divisions, n_layers=n_layers,
                             grading=grading, ratio=ratio, curved=curved, force_N=force_N,
                             region=region, solver=solver, verbose=verbose, progress=progress)
    fin = conv.finest
    return StiffnessResult(
        element=element, model="fem3d", stiffness_N_per_mm=fin.stiffness_N_per_mm,
        face_strain_per_N=abs(fin.gauge_strain) / force_N,
        error_estimate_rel=conv.stiffness.error_rel, wall_time_s=conv.wall_time_s,
        grid_strain_per_N=None if g.gauge is None else
        float(grid_area_strains_per_N(conv, g, g.gauge.grid_width_mm)[-1]))
