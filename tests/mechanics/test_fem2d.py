"""Plane FEM (fem2d): FEM region, P2 convergence, extremes, plane stress/strain,
clamp-line sensitivity, gauge strain.

Expected convergence: for P2 elements the energy (compliance) error is
O(h^(2k)) = O(h^4) for a smooth solution; the clamp-line corners (fixed edge
meeting a free edge) and the edges of the loaded contact face are mild
singularities that lower it, and measurements on this notch flexure show
about h^2 ... h^3.5. The tests accept an observed order in [1.5, 4.5].
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely.geometry as sg

from tactcad.studies.correction_sweep import grid_geometry
from tactcad.mechanics.fem.fem2d import (estimate_fem2d, fem2d_convergence, plane_model_error,
                                        solve_fem2d)
from tactcad.mechanics.fem.fem_mesh import (clip_chain, default_clamp_margin_mm, fem_region,
                                        mesh_region)
from tactcad.mechanics.richardson import richardson
from tactcad.geometry.profile import Arc, Line, contour_area, element_profile

ORDER_BAND = (1.5, 4.5)
ERROR_GOAL = 0.005  # 0.5 %


def _elem(plan, arm):
    return next(g for g in plan.distinct_elements.values() if g.arm_length_mm == arm)


@pytest.fixture(scope="module")
def plane_stress_estimate(plan):
    """estimate_fem2d's default (plane stress, three meshes) of the default plan's element
    with a given arm (mm), solved once a module: three tests read the same two estimates."""
    kept = {}

    def estimate(arm):
        if arm not in kept:
            kept[arm] = estimate_fem2d(_elem(plan, arm), plan.material)
        return kept[arm]
    return estimate


def _polygon(segments, n_arc=400):
    """Dense polygon of a chain of lines and arcs (independent of the code's
    own area formula)."""
    pts = []
    for s in segments:
        if isinstance(s, Arc):
            a0 = math.atan2(s.start[1] - s.centre[1], s.start[0] - s.centre[0])
            for k in range(n_arc):
                a = a0 + s.sweep * k / n_arc
                pts.append((s.centre[0] + s.radius * math.cos(a),
                            s.centre[1] + s.radius * math.sin(a)))
        else:
            pts.append(s.start)
    return sg.Polygon(pts)


# ---------------------------------------------------------------------------
# FEM region
# ---------------------------------------------------------------------------
def test_fem_region_is_the_cropped_profile(plan):
    g = _elem(plan, 4.0)
    region = fem_region(g)
    outline, x_clamp, reason = region  # unpacks as a 3-tuple
    margin = default_clamp_margin_mm(g)
    assert x_clamp == pytest.approx(g.hinge_x_mm - g.notch_radius_mm - margin)
    assert "clamp line" in reason
    # closed chain, last segment on the clamp line
    for a, b in zip(outline, outline[1:] + outline[:1]):
        assert a.end == pytest.approx(b.start)
    last = outline[-1]
    assert isinstance(last, Line)
    assert last.start[0] == pytest.approx(x_clamp) and last.end[0] == pytest.approx(x_clamp)
    # the profile's arcs (notch, fillet) are kept as the very same arcs
    prof_arcs = [s for s in element_profile(g).outer if isinstance(s, Arc)]
    assert [s for s in outline if isinstance(s, Arc)] == prof_arcs
    # area: the profile's outer contour clipped by a half plane (shapely, dense polygon)
    full = _polygon(element_profile(g).outer)
    half = sg.box(x_clamp, -1.0, 100.0, 100.0)
    assert contour_area(outline) > 0
    assert contour_area(outline) == pytest.approx(full.intersection(half).area, rel=1e-4)


def test_clip_chain_splits_an_arc(plan):
    g = _elem(plan, 4.0)
    outline = fem_region(g).outline
    x = g.hinge_x_mm + 0.2  # through the notch arc
    clipped = clip_chain(outline, x)
    first = clipped[0]
    assert isinstance(first, Arc)
    assert first.centre == (g.hinge_x_mm, g.notch_centre_y_mm)
    assert first.start[0] == pytest.approx(x)
    assert math.dist(first.start, first.centre) == pytest.approx(g.notch_radius_mm)
    expect = _polygon(outline).intersection(sg.box(x, -1.0, 100.0, 100.0)).area
    assert contour_area(clipped) == pytest.approx(expect, rel=1e-4)


def test_fem_region_rejects_bad_margins(plan):
    g = _elem(plan, 8.0)
    with pytest.raises(ValueError):
        fem_region(g, 0.0)
    with pytest.raises(ValueError):
        fem_region(g, -1.0)
    with pytest.raises(ValueError, match="bolt holes"):
        fem_region(g, 5.0)  # would reach the bolt holes of the 8 mm element


def test_mesh_has_gauge_vertex_and_refines(plan):
    g = _elem(plan, 6.0)
    coarse = mesh_region(g, size_factor=2.0)
    fine = mesh_region(g, size_factor=1.0)
    assert fine.t.shape[1] > 2 * coarse.t.shape[1]
    assert fine.p[:, fine.gauge_vertex] == pytest.approx([g.hinge_x_mm, g.base_height_mm])
    assert fine.neck_size == pytest.approx(coarse.neck_size / 2)


# ---------------------------------------------------------------------------
# Richardson extrapolation
# ---------------------------------------------------------------------------
def test_richardson_recovers_a_known_expansion():
    r = math.sqrt(2.0)
    hs = [1.0, 1 / r, 0.5]
    vals = [3.0 + 0.7 * h**2.5 for h in hs]
    est = richardson(vals, r)
    assert est.order == pytest.approx(2.5, rel=1e-9)
    assert est.extrapolated == pytest.approx(3.0, rel=1e-12)
    assert est.error_rel == pytest.approx(0.7 * 0.5**2.5 / 3.0, rel=1e-9)
    with pytest.raises(ValueError):
        richardson([1.0, 2.0], r)
    oscillating = richardson([1.0, 1.1, 1.05], r)
    assert math.isnan(oscillating.order) and oscillating.error_rel > 0


# ---------------------------------------------------------------------------
# Convergence at the P2 rate
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("arm", [4.0, 8.0])
def test_p2_convergence_rate_and_error(plan, arm, plane_stress_estimate):
    g = _elem(plan, arm)
    conv = fem2d_convergence(g, plan.material, levels=4)
    ks = [s.stiffness_N_per_mm for s in conv.solutions]
    # conforming displacement FEM is too stiff and converges from above
    assert all(a > b for a, b in zip(ks, ks[1:]))
    for i in range(len(ks) - 2):
        p = richardson(ks[i:i + 3], conv.stiffness.ratio).order
        assert ORDER_BAND[0] <= p <= ORDER_BAND[1], (ks, p)
    # default settings: three meshes, estimated error within the goal
    res = plane_stress_estimate(arm)
    assert res.model == "fem2d"
    assert 0 < res.error_estimate_rel - plane_model_error(g, plan.material) < ERROR_GOAL
    assert res.stiffness_N_per_mm == pytest.approx(ks[-1], rel=1e-9)


def test_isoparametric_and_straight_cells_converge_to_one_limit(plan):
    g = _elem(plan, 4.0)
    curved = fem2d_convergence(g, plan.material, curved=True)
    straight = fem2d_convergence(g, plan.material, curved=False)
    assert straight.stiffness.extrapolated == pytest.approx(curved.stiffness.extrapolated,
                                                            rel=3e-3)
    # straight cells cut the notch's chords: larger error on the same mesh
    assert straight.stiffness.error_rel > curved.stiffness.error_rel


def test_stiffness_is_independent_of_the_load(plan):
    g = _elem(plan, 5.0)
    s1 = solve_fem2d(g, plan.material, force_N=1.0, size_factor=2.0)
    s2 = solve_fem2d(g, plan.material, force_N=2.0, size_factor=2.0)
    assert s1.stiffness_N_per_mm == pytest.approx(s2.stiffness_N_per_mm, rel=1e-9)
    assert s2.gauge_strain == pytest.approx(2 * s1.gauge_strain, rel=1e-9)
    assert s2.tip_deflection_mm == pytest.approx(2 * s1.tip_deflection_mm, rel=1e-9)
    with pytest.raises(ValueError):
        solve_fem2d(g, plan.material, plane="membrane")


# ---------------------------------------------------------------------------
# Extremes of the design domain
# ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def extremes():
    """K (plane stress) over web {0.15, 0.4} x arm {4, 8} x {t/R = 1, R = 2 mm}."""
    out = {}
    for t in (0.15, 0.40):
        for a in (4.0, 8.0):
            for R in (t, 2.0):
                g, mat = grid_geometry(t, a, R)
                out[(t, a, R)] = estimate_fem2d(g, mat)
    return out


@pytest.mark.xdist_group("fem2d-extremes")  # extremes: made once, on one worker
@pytest.mark.slow
def test_extremes_are_finite_positive_and_converged(extremes):
    for key, res in extremes.items():
        assert math.isfinite(res.stiffness_N_per_mm) and res.stiffness_N_per_mm > 0, key
        assert math.isfinite(res.face_strain_per_N), key
        g, mat = grid_geometry(*key)
        discretisation = res.error_estimate_rel - plane_model_error(g, mat)
        assert discretisation < ERROR_GOAL, (key, discretisation)


@pytest.mark.xdist_group("fem2d-extremes")  # extremes: made once, on one worker
@pytest.mark.slow  # eight mesh-convergence studies (the module's fixture)
def test_extremes_are_monotonic(extremes):
    K = {k: r.stiffness_N_per_mm for k, r in extremes.items()}
    for a in (4.0, 8.0):
        # thinner web -> softer (same notch shape t/R = 1, and same R = 2 mm)
        assert K[(0.15, a, 0.15)] < K[(0.40, a, 0.40)]
        assert K[(0.15, a, 2.0)] < K[(0.40, a, 2.0)]
        for t in (0.15, 0.40):
            # larger notch radius at the same web -> longer hinge -> softer
            assert K[(t, a, 2.0)] < K[(t, a, t)]
    for t in (0.15, 0.40):
        for R in (t, 2.0):
            # longer arm -> softer
            assert K[(t, 8.0, R)] < K[(t, 4.0, R)]


# ---------------------------------------------------------------------------
# Plane stress vs plane strain
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("arm", [4.0, 8.0])
def test_plane_strain_is_stiffer_than_plane_stress(plan, arm, plane_stress_estimate):
    g = _elem(plan, arm)
    ps = plane_stress_estimate(arm)
    pe = estimate_fem2d(g, plan.material, plane="strain")
    assert pe.model == "fem2d-plane-strain"
    assert pe.stiffness_N_per_mm > ps.stiffness_N_per_mm
    nu = plan.material.poisson_ratio
    # bending-dominated: the ratio approaches the plate factor 1/(1 - nu^2)
    assert pe.stiffness_N_per_mm / ps.stiffness_N_per_mm < 1.0 / (1.0 - nu * nu) + 0.02


# ---------------------------------------------------------------------------
# Clamp line
# ---------------------------------------------------------------------------
CLAMP_SENSITIVITY = 0.003  # measured: 0.13 % for 2 -> 4 mm on the 4 mm arm


def test_moving_the_clamp_line_into_the_base_changes_K_little(plan):
    g = _elem(plan, 4.0)  # the 4 mm arm has the longest free base in front of the bolts
    m0 = default_clamp_margin_mm(g)
    K0 = solve_fem2d(g, plan.material, region=fem_region(g)).stiffness_N_per_mm
    K2 = solve_fem2d(g, plan.material, region=fem_region(g, 2 * m0)).stiffness_N_per_mm
    # more elastic base in the model -> softer, but only slightly
    assert K2 < K0
    assert abs(K2 - K0) / K0 < CLAMP_SENSITIVITY


# ---------------------------------------------------------------------------
# Gauge strain
# ---------------------------------------------------------------------------
def test_gauge_strain_against_beam_theory(plan):
    mat = plan.material
    strains = {}
    for arm in (4.0, 8.0):
        g = _elem(plan, arm)
        res = estimate_fem2d(g, mat, force_N=2.0)
        # bending stress at the neck: eps = M (t/2) / (E I) = 6 F a / (E b t^2),
        # compressive on the top face for an upward tip force
        eb = 6.0 * arm / (mat.youngs_modulus_MPa * g.sheet_thickness_mm
                          * g.web_thickness_mm**2)
        assert solve_fem2d(g, mat, size_factor=2.0).gauge_strain < 0
        assert res.face_strain_per_N > 0  # the result carries the magnitude
        assert 0.8 < res.face_strain_per_N / eb < 1.2
        strains[arm] = res.face_strain_per_N
    # the moment at the hinge grows with the lever: about twice for twice the arm
    assert strains[8.0] / strains[4.0] == pytest.approx(2.0, rel=0.05)


def test_estimate_carries_element_number_and_rejects_bad_input(plan):
    g = plan.element(3).geometry
    res = estimate_fem2d(g, plan.material, element=3)
    assert res.element == 3 and res.wall_time_s > 0
    assert np.isfinite(res.as_json()["stiffness_N_per_mm"])
    with pytest.raises(ValueError):
        estimate_fem2d(g, plan.material, plane="plate")
    with pytest.raises(ValueError):
        estimate_fem2d(g, plan.material, margin_mm=-0.5)


# ---------------------------------------------------------------------------
# The correction sweep's grid rule
# ---------------------------------------------------------------------------
def test_grid_rule_reproduces_the_default_element(plan):
    """At the default's t, R, a, b, nu the grid rule gives the default element."""
    g0 = plan.element(4).geometry  # 8 mm arm
    g, mat = grid_geometry(g0.web_thickness_mm, g0.arm_length_mm, g0.notch_radius_mm)
    for name in ("arm_height_mm", "tip_width_mm", "tip_height_mm", "base_height_mm",
                 "overall_length_mm", "sheet_thickness_mm"):
        assert getattr(g, name) == pytest.approx(getattr(g0, name)), name
    assert mat.poisson_ratio == plan.material.poisson_ratio


@pytest.mark.parametrize("t,a,R,b", [(0.05, 20.0, 0.05, 10.0), (1.0, 3.6, 2.0, 0.5),
                                     (0.05, 2.0, 0.05, 0.5), (1.0, 20.0, 2.0, 10.0)])
def test_grid_rule_corners_are_valid_designs(t, a, R, b):
    from tactcad.studies.correction_sweep import arm_height_mm, arm_min_mm

    g, _ = grid_geometry(t, a, R, sheet_mm=b, poisson_ratio=0.27)
    assert g.arm_height_mm == pytest.approx(arm_height_mm(t, R, a))
    assert g.arm_height_mm > t + R and g.arm_height_mm <= 5.0
    assert a >= arm_min_mm(R) - 1e-9
    region = fem_region(g)  # the FEM region exists: clamp line in front of the bolts
    assert region.x_clamp < g.hinge_x_mm - g.notch_radius_mm


@pytest.mark.parametrize("arm", [4.0, 8.0])
def test_error_estimate_covers_the_plane_stress_model_error_against_3d(plan, arm,
                                                                      plane_stress_estimate):
    """The closed form is fitted to fem3d within 1.6 %: fem2d's estimate must
    reach its distance to that 3D stand-in, less the fit's error."""
    from tactcad.mechanics.closed_form import estimate_closed_form

    g = _elem(plan, arm)
    res = plane_stress_estimate(arm)
    k3d = estimate_closed_form(g, plan.material).stiffness_N_per_mm
    assert res.stiffness_N_per_mm < k3d  # plane stress is softer than the wide 3D element
    assert res.error_estimate_rel >= abs(res.stiffness_N_per_mm / k3d - 1.0) - 0.016
    assert 0.01 < plane_model_error(g, plan.material) < 0.12


def _layered_moduli(z):
    """Two materials in layers along z: (lam, mu) in MPa."""
    E = np.where(z < 0.5, 200e3, 70e3)
    nu = np.where(z < 0.5, 0.30, 0.33)
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


@pytest.mark.parametrize("element", ["tet-p2", "hex2-layered"])
def test_assembly_is_the_elasticity_form_of_scikit_fem(element):
    """The contraction assembly equals scikit-fem's ``asm`` of
    2 mu eps(u):eps(v) + lam div u div v on the vector element, dof for dof
    (the interleaved numbering), for one material and for layers of two."""
    from skfem import (Basis, BilinearForm, ElementHex2, ElementTetP2, ElementVector, MeshHex,
                       MeshTet, asm)
    from skfem.helpers import ddot, sym_grad, trace

    from tactcad.mechanics.fem.fem2d import assemble_elasticity

    axis = np.array([0.0, 0.3, 0.5, 1.2])
    if element == "tet-p2":
        scalar_element, mesh, order = ElementTetP2(), MeshTet.init_tensor(axis, axis, axis), 2
        moduli = lambda z: (np.full_like(z, 1.3e5), np.full_like(z, 0.8e5))  # noqa: E731
    else:
        scalar_element, mesh, order = ElementHex2(), MeshHex.init_tensor(axis, axis, axis), 4
        moduli = _layered_moduli

    @BilinearForm
    def elasticity(u, v, p):
        lam, mu = moduli(p.x[2])
        eu, ev = sym_grad(u), sym_grad(v)
        return 2 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev)

    expected = asm(elasticity, Basis(mesh, ElementVector(scalar_element), intorder=order))
    scalar = Basis(mesh, scalar_element, intorder=order)
    lam, mu = moduli(np.asarray(scalar.global_coordinates())[2])
    got = assemble_elasticity(scalar, lam, mu, chunk=7)  # several chunks
    scale = abs(expected).max()
    assert abs(got - expected).max() < 1e-12 * scale
    if element == "tet-p2":  # numbers, not fields: the same matrix
        assert abs(assemble_elasticity(scalar, 1.3e5, 0.8e5) - expected).max() < 1e-12 * scale


@pytest.mark.parametrize("fixed", ["none", "some", "all-but-one"])
def test_the_free_block_is_scikit_fems_condensed_matrix(fixed):
    """``free_block`` keeps the rows and columns scikit-fem's ``condense`` keeps, in
    order and to the bit, whichever unknowns are fixed."""
    import scipy.sparse as sp
    from skfem import condense

    from tactcad.mechanics.fem.fem2d import free_block

    rng = np.random.default_rng(3)
    n = 40
    A = sp.random(n, n, density=0.2, random_state=4, format="csr")
    A = (A + A.T + sp.eye(n)).tocsr()
    D = {"none": np.array([], dtype=int), "some": np.sort(rng.choice(n, 9, replace=False)),
         "all-but-one": np.delete(np.arange(n), 17)}[fixed]
    free = np.setdiff1d(np.arange(n), D)
    expected = condense(A, np.zeros(n), D=D)[0] if len(D) else A
    got = free_block(A, free)
    assert got.shape == (len(free), len(free))
    assert (got != expected).nnz == 0
    assert np.array_equal(got.toarray(), A.toarray()[np.ix_(free, free)])


def test_the_two_level_cycle_is_one_symmetric_operator():
    """The p-multigrid cycle that carries its residuals is the textbook cycle
    (smooth, correct on P1, smooth again, each residual formed anew), and
    symmetric and positive, as conjugate gradients needs."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve
    from skfem import Basis, ElementTetP2, MeshTet

    from tactcad.mechanics.fem.fem2d import (_two_level_preconditioner, assemble_elasticity,
                                            chebyshev_smoother, p1_embedding)

    axis = np.linspace(0.0, 1.0, 4)
    mesh = MeshTet.init_tensor(axis, axis, axis)
    sb = Basis(mesh, ElementTetP2(), intorder=2)
    A = assemble_elasticity(sb, 1.3e5, 0.8e5)
    clamped = np.flatnonzero(sb.doflocs[0] < 1e-9)
    free = np.setdiff1d(np.arange(A.shape[0]), (3 * clamped[:, None] + np.arange(3)).ravel())
    A = A[free][:, free].tocsr()
    P = sp.kron(p1_embedding(mesh, sb.N), sp.eye(3), format="csr")[free]
    P = P[:, np.flatnonzero(P.getnnz(axis=0))].tocsr()
    cycle = _two_level_preconditioner(A, P)
    smooth, Ac = chebyshev_smoother(A), (P.T @ A @ P).tocsc()

    def textbook(r):
        x = smooth(r, True)[0]
        x += P @ spsolve(Ac, P.T @ (r - A @ x))
        return x + smooth(r - A @ x, True)[0]

    rng = np.random.default_rng(1)
    v, w = rng.standard_normal(A.shape[0]), rng.standard_normal(A.shape[0])
    Mv, Mw = cycle(v), cycle(w)
    assert np.abs(Mv - textbook(v)).max() < 1e-9 * np.abs(Mv).max()
    assert abs(w @ Mv - v @ Mw) < 1e-9 * abs(w @ Mv)
    assert v @ Mv > 0 and w @ Mw > 0


#: Meshes with gmsh, then writes to a closed pipe and signals itself SIGTERM:
#: run in a fresh interpreter, as a process that signals itself must not be
#: the test's own.
GMSH_THEN_SIGNALS = """
import os, signal
from tactcad.mechanics.fem.fem_mesh import gmsh_session

caught = []
signal.signal(signal.SIGTERM, lambda number, frame: caught.append(number))
with gmsh_session("signals"):
    pass
read_end, write_end = os.pipe()
os.close(read_end)
try:
    os.write(write_end, b"x")
except BrokenPipeError:
    print("broken pipe raised")
os.kill(os.getpid(), signal.SIGTERM)
print("SIGTERM handled", caught == [signal.SIGTERM])
"""


def test_meshing_leaves_the_host_process_its_signal_handlers():
    """gmsh's initialisation sets SIGPIPE, SIGTERM and the fault signals to
    their defaults: a host process (the API, a watch session, a pytest
    worker) that meshed once was then ended by SIGPIPE on a write to a killed
    worker's pipe, and by SIGTERM without its clean-up. Its own dispositions
    are kept: the write raises, the handler runs."""
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", GMSH_THEN_SIGNALS],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, f"ended by signal {-proc.returncode}: {proc.stderr[-2000:]}"
    assert proc.stdout.split("\n")[:2] == ["broken pipe raised", "SIGTERM handled True"]
