"""Level 2 (Timoshenko stepped beam): convergence, cross-checks, agreement with level 1."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.design.array_plan import load_design
from tactcad.mechanics.beam import (
    beam_convergence, beam_mesh, estimate_beam, solve_beam, unit_load_compliance)
from tactcad.mechanics.closed_form import closed_form_compliance, estimate_closed_form
from tactcad.mechanics.stiffness_result import StiffnessResult

PLAN = load_design()
MAT = PLAN.material
G0 = PLAN.element(1).geometry.bare()  # the levels' own sections (the gauge: test_bonded_layer)
E, NU, B = MAT.youngs_modulus_MPa, MAT.poisson_ratio, G0.sheet_thickness_mm


def _geometry(t: float, R: float, a: float):
    return dataclasses.replace(G0, web_thickness_mm=t, notch_radius_mm=R, arm_length_mm=a)


def _k_closed(g) -> float:
    return estimate_closed_form(g, MAT, corrected=False).stiffness_N_per_mm


EXTREMES = [(0.25, 0.5, 4.0), (0.25, 0.5, 8.0), (0.15, 2.0, 8.0), (0.15, 2.0, 4.0),
            (0.4, 0.4, 4.0), (0.15, 0.15, 8.0)]


@pytest.mark.parametrize("t,R,a", EXTREMES)
def test_richardson_order_is_two(t, R, a):
    conv = beam_convergence(_geometry(t, R, a), MAT, 128)
    # mid-point rule in the smooth notch variable: O(n^-2)
    assert 1.9 <= conv.observed_order <= 2.1
    k1, k2, k3 = conv.stiffness_N_per_mm
    assert abs(k3 - conv.extrapolated_N_per_mm) < abs(k2 - conv.extrapolated_N_per_mm)
    assert conv.error_estimate_rel < 1e-4


@pytest.mark.parametrize("t,R,a", EXTREMES)
def test_sharp_corner_beam_converges_to_closed_form(t, R, a):
    """Without the tip-root fillet the beam has the closed form's exact sections,
    so the closed form is the exact limit: the Richardson estimate must predict
    the actual discretisation error, and the extrapolation must hit the limit."""
    g = _geometry(t, R, a)
    k_exact = _k_closed(g)
    conv = beam_convergence(g, MAT, 64, include_fillet=False)
    actual = abs(conv.stiffness_N_per_mm[-1] / k_exact - 1)
    assert 0.8 * conv.error_estimate_rel <= actual <= 1.25 * conv.error_estimate_rel
    assert conv.extrapolated_N_per_mm == pytest.approx(k_exact, rel=1e-5)
    fine = beam_convergence(g, MAT, 512, include_fillet=False)
    assert fine.extrapolated_N_per_mm == pytest.approx(k_exact, rel=1e-7)


def test_beam_agrees_with_closed_form_for_default_design():
    """Tolerance 0.1 %: both levels use the same sections and Timoshenko shear;
    the beam adds only the 0.2 mm tip-root fillet, which stiffens a piece of the
    arm whose bending is < 1 % of the tip compliance, and its discretisation
    error (< 1e-4). Anything above 0.1 % would be a bug, not physics."""
    for num, g in ((s.number, s.geometry.bare()) for s in PLAN.slots):
        r = estimate_beam(g, MAT, element=num)
        parts = closed_form_compliance(
            g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
            arm_height_mm=g.arm_height_mm, tip_width_mm=g.tip_width_mm,
            tip_height_mm=g.tip_height_mm, E=E, nu=NU, b=B)
        assert float(parts.arm_bending / parts.total) < 0.01
        k_cf = _k_closed(g)
        assert r.stiffness_N_per_mm == pytest.approx(k_cf, rel=1e-3)
        disc = beam_convergence(g, MAT).error_estimate_rel
        assert r.stiffness_N_per_mm > k_cf * (1 - disc)  # the fillet only stiffens
        assert isinstance(r, StiffnessResult) and r.model == "beam" and r.element == num
        assert 0 < disc < 1e-4
        # The reported error adds beam theory's model error at the notch (t/R = 0.5:
        # Euler-Bernoulli about 15-25 % too stiff against 3D FEM).
        assert 0.10 < r.error_estimate_rel - disc < 0.30


@pytest.mark.parametrize("n", [16, 64, 256])
def test_transfer_solution_equals_unit_load_sum(n):
    g = PLAN.element(4).geometry
    mesh = beam_mesh(g, n)
    sol = solve_beam(mesh, E, NU, B, g.web_thickness_mm)
    assert sol.compliance_mm_per_N == pytest.approx(unit_load_compliance(mesh, E, NU, B),
                                                    rel=1e-13)
    assert np.all(np.diff(sol.deflection_mm_per_N) > 0)
    assert np.all(np.diff(sol.rotation_rad_per_N) > 0)
    assert sol.hinge_moment_Nmm_per_N == pytest.approx(g.arm_length_mm, rel=1e-12)


def test_mesh_follows_profile():
    g = PLAN.element(3).geometry
    mesh = beam_mesh(g, 32)
    x, h = mesh.x_mm, mesh.height_mm
    assert x[0] == pytest.approx(g.hinge_x_mm - g.notch_radius_mm)
    assert x[-1] == pytest.approx(g.tip_centre_x_mm)
    assert x[mesh.hinge_node] == g.hinge_x_mm
    assert h.min() > g.web_thickness_mm
    in_notch = (x[:-1] >= g.hinge_x_mm - g.notch_radius_mm) & (x[1:] <= g.hinge_x_mm + g.notch_radius_mm)
    assert np.count_nonzero(in_notch) == 32
    assert h[-1] == pytest.approx(g.arm_height_mm + g.tip_height_mm)


def test_free_base_block_is_negligible():
    g = PLAN.element(1).geometry  # longest free base (shortest arm)
    k_rigid = estimate_beam(g, MAT).stiffness_N_per_mm
    k_base = estimate_beam(g, MAT, clamp_x_mm=12.0).stiffness_N_per_mm
    assert k_base < k_rigid
    assert k_base / k_rigid > 0.999


def test_gauge_strain_matches_closed_form_and_lever():
    strains = {}
    for slot in PLAN.slots:
        g = slot.geometry
        r = estimate_beam(g, MAT)
        c = estimate_closed_form(g, MAT)  # both: EB x the fitted point factor
        assert r.face_strain_per_N == pytest.approx(c.face_strain_per_N, rel=1e-12)
        strains[g.arm_length_mm] = r.face_strain_per_N
    arms = np.array(sorted(strains))
    eps = np.array([strains[a] for a in arms])
    np.testing.assert_allclose(eps / arms, eps[0] / arms[0], rtol=1e-12)


@pytest.mark.parametrize("bad", [12, 4, 0, 100])
def test_invalid_segments(bad):
    with pytest.raises(ValueError):
        beam_convergence(G0, MAT, bad)


def test_invalid_clamp():
    with pytest.raises(ValueError):
        beam_mesh(G0, 16, clamp_x_mm=G0.hinge_x_mm)
    with pytest.raises(ValueError):
        beam_mesh(G0, 15)


@settings(max_examples=60, deadline=None)
@given(t=st.floats(0.15, 0.4), a=st.floats(4.0, 8.0), frac=st.floats(0.0, 1.0))
def test_random_in_domain(t, a, frac):
    R = t + frac * (2.0 - t)
    g = _geometry(t, R, a)
    r = estimate_beam(g, MAT, n_segments=64)
    assert math.isfinite(r.stiffness_N_per_mm) and r.stiffness_N_per_mm > 0
    assert math.isfinite(r.face_strain_per_N) and r.face_strain_per_N > 0
    disc = beam_convergence(g, MAT, 64).error_estimate_rel
    assert 0 <= disc < 1e-3
    assert disc < r.error_estimate_rel < 1.0  # plus a finite model error
    assert r.stiffness_N_per_mm == pytest.approx(_k_closed(g), rel=2e-3)


#: fem3d (P2 tetrahedra, finest of three meshes, its Richardson error) of the measuring
#: element of the comb `tactcad design --jaw 10 --construction monolithic-comb --kr-over-km
#: 21.267 --kobj-range 2.87533 18.4831 --full-scale-force 0.0832511 --columns 2 --material
#: Ti-6Al-4V-annealed` writes (arm height 1 mm, its bonded gauge), by `tactcad stiffness
#: --element 3 --model fem3d --set arms.lengths_mm=... --set comb.web_thicknesses_mm=...`:
#: (arm mm, web mm, K N/mm, error), 2026-11-30.
COMB_FEM3D = ((9.0, 0.234, 3.0327839387416446, 0.00043598),
              (11.0, 0.234, 1.99719208178834, 0.00046039),
              (11.0, 0.3, 3.3105595080930104, 0.00057347),
              (12.6, 0.234, 1.502348467356717, 0.00040603))


def _comb_element(arm_mm: float, web_mm: float):
    from tactcad.design.array_plan import Material
    from tactcad.partlib.array.element import ElementGeometry, GaugeStack

    g = ElementGeometry(arm_length_mm=arm_mm, web_thickness_mm=web_mm, notch_radius_mm=0.3,
                        tip_width_mm=1.0, tip_height_mm=0.8, arm_height_mm=1.0,
                        base_height_mm=4.994101615137755, overall_length_mm=arm_mm + 1.6,
                        inside_corner_radius_mm=0.1, sheet_thickness_mm=1.0,
                        web_tolerance_mm=0.01, bolt_holes=(), start_hole_diameter_mm=0.5,
                        process="wire-edm", gauge=GaugeStack(grid_length_mm=0.6,
                                                             grid_width_mm=1.0, height_mm=0.055,
                                                             modulus_MPa=10000.0))
    return g, Material(name="Ti-6Al-4V-annealed", youngs_modulus_MPa=113800.0,
                       poisson_ratio=0.342, grade="Ti-6Al-4V-annealed")


def _stored_arm_aspect_points():
    import json

    from tactcad.design.array_plan import Material
    from tactcad.mechanics import correction
    from tactcad.partlib.array.element import ElementGeometry, GaugeStack

    for p in json.loads(correction.CORRECTION_FILE.read_text())[
            "arm_aspect_extrapolation"]["points"]:
        geom = dict(p["geometry"])
        gauge = geom.pop("gauge")
        geom["bolt_holes"] = tuple(geom["bolt_holes"])
        yield (ElementGeometry(**geom, gauge=GaugeStack(**gauge) if gauge else None),
               Material(**p["material"]), p["K_fem3d"], p["err_fem3d"])


def test_the_beams_error_estimate_bounds_fem3d_past_the_fitted_arm_aspect():
    """Past the correction's fitted arm / arm height (4) the correction itself errs more,
    and the beam's model error, read off it, with it: the stated error bounds the beam's
    distance from fem3d (plus fem3d's own error) at every stored fem3d point (a / h_a 4 to
    7.8) and on a comb's element at 9 to 12.6, where it once said 25 % for 32 % off."""
    import warnings

    points = [(*_comb_element(a, t), k, e) for a, t, k, e in COMB_FEM3D]
    points += list(_stored_arm_aspect_points())
    assert max(g.arm_length_mm / g.arm_height_mm for g, *_ in points) > 12
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for g, mat, k_fem3d, err_fem3d in points:
            r = estimate_beam(g, mat)
            off = abs(r.stiffness_N_per_mm / k_fem3d - 1.0) + err_fem3d
            assert r.error_estimate_rel >= off, (g.arm_length_mm, g.web_thickness_mm)
            assert r.error_estimate_rel < 1.5 * off + 0.02  # a bound, not a blanket
