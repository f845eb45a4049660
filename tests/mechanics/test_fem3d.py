"""3D FEM (fem3d, the reference): half model, solver, P2 convergence,
ordering against plane stress / plane strain, extremes.

Expected convergence as for fem2d (see tests/mechanics/test_fem2d.py): observed order
of K in [1.5, 4.5] for P2 tetrahedra, Richardson error below 0.5 %.
"""

from __future__ import annotations

import math

import pytest

from tactcad.studies.correction_sweep import grid_geometry
from tactcad.mechanics.fem.fem2d import estimate_fem2d, lame, skfem_mesh, solve_elasticity
from tactcad.mechanics.fem.fem3d import fem3d_convergence, solve_fem3d
from tactcad.mechanics.fem.fem_mesh import fem_region, graded_layers, mesh_region
from tactcad.mechanics.richardson import richardson

# one worker for the module: the convergence fixture (three fem3d meshes) is solved once
pytestmark = pytest.mark.xdist_group("fem3d-convergence")

ORDER_BAND = (1.5, 4.5)
ERROR_GOAL = 0.005  # 0.5 %


def _elem(plan, arm):
    return next(g for g in plan.distinct_elements.values() if g.arm_length_mm == arm)


def _coarse_3d(g, mat, *, depth, n_layers, sym, solver="pcg"):
    """One coarse 3D solve with uniform layers (for model checks)."""
    region = fem_region(g)
    rm = mesh_region(g, region, dim=3, size_factor=2.0, web_divisions=4.0, depth_mm=depth,
                     z_layers=graded_layers(depth, n_layers, 1.0))
    mesh = skfem_mesh(rm)
    lam, mu = lame(mat, None)
    L, w, b = g.overall_length_mm, g.tip_width_mm, g.sheet_thickness_mm
    C, F, eps, n, _ = solve_elasticity(
        mesh, lam, mu, thickness=1.0, x_clamp=region.x_clamp,
        contact=(L - w, L, g.tip_top_y_mm), traction_MPa=1.0 / (w * b),
        gauge_vertex=None, sym_plane_z=b / 2 if sym else None, solver=solver, rtol=1e-11)
    return C, F, n


def test_graded_layers():
    hs = graded_layers(1.5, 6, 6.0)
    assert sum(hs) == pytest.approx(1.5)
    assert hs[-1] / hs[0] == pytest.approx(6.0 ** (5 / 6))
    assert all(a < b for a, b in zip(hs, hs[1:]))
    with pytest.raises(ValueError):
        graded_layers(0.0, 3, 2.0)


@pytest.mark.slow
def test_half_model_equals_full_thickness(plan):
    """u_z = 0 on the mid-plane of the half model reproduces the full sheet."""
    g = _elem(plan, 6.0)
    b = g.sheet_thickness_mm
    Ch, Fh, nh = _coarse_3d(g, plan.material, depth=b / 2, n_layers=2, sym=True)
    Cf, Ff, nf = _coarse_3d(g, plan.material, depth=b, n_layers=4, sym=False)
    assert Ff == pytest.approx(2 * Fh, rel=1e-9)
    assert nf > 1.5 * nh  # 5 vs 3 vertex layers
    K_half = 2 * Fh**2 / Ch
    K_full = Ff**2 / Cf
    assert K_half == pytest.approx(K_full, rel=2e-3)


@pytest.mark.slow
def test_pcg_matches_direct_solver(plan):
    g = _elem(plan, 8.0)
    b = g.sheet_thickness_mm
    Cp, Fp, _ = _coarse_3d(g, plan.material, depth=b / 2, n_layers=2, sym=True, solver="pcg")
    Cd, Fd, _ = _coarse_3d(g, plan.material, depth=b / 2, n_layers=2, sym=True, solver="direct")
    assert Fp == pytest.approx(Fd, rel=1e-12)
    assert Cp == pytest.approx(Cd, rel=1e-8)


@pytest.fixture(scope="module")
def conv_4mm(plan):
    """fem3d's three meshes of the 4 mm arm, solved once for the module's tests
    (which share a worker: ``pytestmark``)."""
    return fem3d_convergence(_elem(plan, 4.0), plan.material, verbose=True)


@pytest.mark.slow
def test_fem3d_converges_at_the_p2_rate(conv_4mm):
    ks = [s.stiffness_N_per_mm for s in conv_4mm.solutions]
    assert all(a > b for a, b in zip(ks, ks[1:]))  # converges from above
    p = richardson(ks, conv_4mm.stiffness.ratio).order
    assert ORDER_BAND[0] <= p <= ORDER_BAND[1], (ks, p)
    assert 0 < conv_4mm.stiffness.error_rel < ERROR_GOAL
    assert conv_4mm.finest.n_dofs > 2 * conv_4mm.solutions[0].n_dofs
    assert conv_4mm.peak_rss_mib > 0


@pytest.mark.slow
def test_fem3d_between_plane_stress_and_plane_strain(plan, conv_4mm):
    g = _elem(plan, 4.0)
    k3 = conv_4mm.finest.stiffness_N_per_mm
    ps = estimate_fem2d(g, plan.material, plane="stress").stiffness_N_per_mm
    pe = estimate_fem2d(g, plan.material, plane="strain").stiffness_N_per_mm
    assert ps < k3 < pe
    # the gap to either bound is far larger than the discretisation error
    assert (k3 - ps) / k3 > 10 * conv_4mm.stiffness.error_rel
    assert (pe - k3) / k3 > 10 * conv_4mm.stiffness.error_rel


@pytest.mark.slow
def test_fem3d_gauge_strain(plan, conv_4mm):
    g = _elem(plan, 4.0)
    eps3 = conv_4mm.finest.gauge_strain / conv_4mm.finest.force_N
    eps2 = estimate_fem2d(g, plan.material, plane="stress").face_strain_per_N
    eps_pe = estimate_fem2d(g, plan.material, plane="strain").face_strain_per_N
    assert eps3 < 0  # upward tip force compresses the top face over the web
    # per newton, the stiffer 3D web strains less than plane stress, more than plane strain
    assert eps_pe < abs(eps3) < eps2


@pytest.mark.slow
def test_fem3d_extremes_are_finite_and_monotonic():
    K = {}
    for t in (0.15, 0.40):
        for a in (4.0, 8.0):
            for R in (t, 2.0):
                g, mat = grid_geometry(t, a, R)
                s = solve_fem3d(g, mat, size_factor=2.0)
                assert math.isfinite(s.stiffness_N_per_mm) and s.stiffness_N_per_mm > 0
                assert math.isfinite(s.gauge_strain)
                K[(t, a, R)] = s.stiffness_N_per_mm
    for a in (4.0, 8.0):
        assert K[(0.15, a, 0.15)] < K[(0.40, a, 0.40)]
        assert K[(0.15, a, 2.0)] < K[(0.40, a, 2.0)]
    for t in (0.15, 0.40):
        for R in (t, 2.0):
            assert K[(t, 8.0, R)] < K[(t, 4.0, R)]
