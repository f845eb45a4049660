"""Level 1 (closed-form) stiffness: exactness, physics, correction hook, inverse."""

from __future__ import annotations

import dataclasses
import json
import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.mechanics.gauge_strain import point_strain_factor
from tactcad.design.array_plan import load_design
from tactcad.errors import DesignError
from tactcad.mechanics import correction as corr_mod
from tactcad.mechanics.closed_form import (
    ALPHA_SHEAR, closed_form_compliance, closed_form_stiffness, estimate_closed_form,
    gauge_strain_per_newton, notch_integrals, web_for_stiffness)
from tactcad.mechanics.correction import (
    IDENTITY, Correction, CorrectionRangeWarning, FitRange, apply_correction, load_correction)
from tactcad.mechanics.stiffness_result import StiffnessResult
from tactcad.geometry.profile import web_thickness_at
from tactcad.studies.correction_fit import FitData, fit_correction

PLAN = load_design()
MAT = PLAN.material
G0 = PLAN.element(1).geometry.bare()  # the closed form's own terms (the gauge: test_bonded_layer)
E, NU, B = MAT.youngs_modulus_MPa, MAT.poisson_ratio, G0.sheet_thickness_mm
KW = dict(arm_height_mm=G0.arm_height_mm, tip_width_mm=G0.tip_width_mm,
          tip_height_mm=G0.tip_height_mm, E=E, nu=NU, b=B)


def _geometry(t: float, R: float, a: float):
    return dataclasses.replace(G0, web_thickness_mm=t, notch_radius_mm=R, arm_length_mm=a)


def _gauss_over_notch(g, fun, n_gauss: int = 40) -> float:
    """Composite Gauss-Legendre quadrature of fun(u, h(u)) du over the notch,
    with h from the exact profile (tactcad.geometry.profile.web_thickness_at), in the
    angle theta (u = R sin theta), panels graded towards the neck."""
    R, t = g.notch_radius_mm, g.web_thickness_mm
    w = math.sqrt(t / R)
    cuts = [w * 2.0**k for k in range(-4, 8) if w * 2.0**k < 0.5 * math.pi]
    bps = sorted({0.0, 0.5 * math.pi, -0.5 * math.pi, *cuts, *(-c for c in cuts)})
    xg, wg = np.polynomial.legendre.leggauss(n_gauss)
    total = 0.0
    for lo, hi in zip(bps[:-1], bps[1:]):
        th = 0.5 * (hi - lo) * xg + 0.5 * (hi + lo)
        u = R * np.sin(th)
        h = np.array([web_thickness_at(g, g.hinge_x_mm + ui) for ui in u])
        total += 0.5 * (hi - lo) * np.sum(wg * fun(u, h) * R * np.cos(th))
    return float(total)


T_OVER_R = np.geomspace(0.01, 1.0, 9)
CASES = [(s * R, R, a) for s in T_OVER_R for R, a in ((0.4, 4.0), (2.0, 8.0))]
CASES += [(0.15, 0.15, 4.0), (0.15, 2.0, 8.0), (0.4, 0.4, 8.0), (0.4, 2.0, 4.0),
          (0.25, 0.5, 6.0)]


@pytest.mark.parametrize("t,R,a", CASES)
def test_closed_form_matches_quadrature(t, R, a):
    g = _geometry(t, R, a)
    ni = notch_integrals(t, R)
    q0 = _gauss_over_notch(g, lambda u, h: 1.0 / h**3)
    q1 = _gauss_over_notch(g, lambda u, h: u / h**3)
    q2 = _gauss_over_notch(g, lambda u, h: u * u / h**3)
    qs = _gauss_over_notch(g, lambda u, h: 1.0 / h)
    assert float(ni.inv_h3) == pytest.approx(q0, rel=1e-10)
    assert abs(q1) <= 1e-12 * q0 * R  # odd moment vanishes: symmetric notch
    assert float(ni.u2_h3) == pytest.approx(q2, rel=1e-10)
    assert float(ni.inv_h) == pytest.approx(qs, rel=1e-10)
    # full notch terms of the tip compliance: 12 (a - u)^2 / (E b h^3) and alpha / (G b h)
    parts = closed_form_compliance(t, R, a, **KW)
    qb = _gauss_over_notch(g, lambda u, h: 12.0 * (a - u) ** 2 / (E * B * h**3))
    G = E / (2 * (1 + NU))
    assert float(parts.notch_bending) == pytest.approx(qb, rel=1e-10)
    assert float(parts.notch_shear) == pytest.approx(ALPHA_SHEAR / (G * B) * qs, rel=1e-10)


def test_arm_terms_match_direct_integration():
    t, R, a = 0.25, 0.5, 6.0
    parts = closed_form_compliance(t, R, a, **KW)
    ha, ht, w = G0.arm_height_mm, G0.arm_height_mm + G0.tip_height_mm, G0.tip_width_mm
    d = np.linspace(w / 2, a - R, 200001)  # lever over the arm
    f = 12 * d**2 / (E * B * ha**3)
    arm = np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(d))
    tip = 12 * (w / 2) ** 3 / 3 / (E * B * ht**3)
    assert float(parts.arm_bending) == pytest.approx(arm + tip, rel=1e-8)


def test_small_t_over_R_tends_to_classical_hinge_stiffness():
    # k_theta -> 2 E b t^2.5 / (9 pi sqrt(2 R)) (single-sided notch) as t/R -> 0
    R = 1.0
    errs = []
    for s in (1e-2, 1e-3, 1e-4):
        t = s * R
        c_rot = 12.0 / (E * B) * float(notch_integrals(t, R).inv_h3)
        k_classic = 2 * E * B * t**2.5 / (9 * math.pi * math.sqrt(2 * R))
        errs.append(abs(1.0 / c_rot / k_classic - 1))
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 1e-3


@pytest.mark.parametrize("t", [0.15, 0.25, 0.4])
@pytest.mark.parametrize("a", [4.0, 8.0])
def test_monotonic_in_web_arm_and_radius(t, a):
    webs = np.linspace(0.15, 0.4, 26)
    arms = np.linspace(4.0, 8.0, 21)
    radii = np.linspace(t, 2.0, 30)
    k_web = closed_form_stiffness(webs, 0.5, a, **KW)
    k_arm = closed_form_stiffness(t, 0.5, arms, **KW)
    k_rad = closed_form_stiffness(t, radii, a, **KW)
    for k in (k_web, k_arm, k_rad):
        assert np.all(np.isfinite(k)) and np.all(k > 0)
    assert np.all(np.diff(k_web) > 0)   # thinner web -> softer
    assert np.all(np.diff(k_arm) < 0)   # longer lever -> softer
    # larger notch radius -> longer, more compliant hinge -> softer
    assert np.all(np.diff(k_rad) < 0)


def test_extremes_finite():
    t = np.array([0.15, 0.4])[:, None, None]
    R = np.array([0.4, 2.0])[None, :, None]
    a = np.array([4.0, 8.0])
    k = closed_form_stiffness(t, R, a, **KW)
    assert k.shape == (2, 2, 2)
    k_sharp = closed_form_stiffness(0.15, 0.15, a, **KW)  # t/R = 1 at the thinnest web
    for kk in (k, k_sharp):
        assert np.all(np.isfinite(kk)) and np.all(kk > 0)


def test_broadcast_matches_scalar():
    t = np.array([0.15, 0.25, 0.4])
    a = np.array([[4.0], [8.0]])
    k = closed_form_stiffness(t, 0.5, a, **KW)
    assert k.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            ks = closed_form_stiffness(float(t[j]), 0.5, float(a[i, 0]), **KW)
            assert np.ndim(ks) == 0
            assert float(ks) == pytest.approx(k[i, j], rel=1e-15)


@pytest.mark.parametrize("bad", [dict(web_mm=-0.1), dict(web_mm=np.nan), dict(notch_radius_mm=0.0),
                                 dict(arm_length_mm=1.0), dict(nu=0.5)])
def test_invalid_input_raises(bad):
    args = dict(web_mm=0.25, notch_radius_mm=0.5, arm_length_mm=6.0, **KW)
    args.update(bad)
    with pytest.raises(ValueError):
        closed_form_stiffness(args.pop("web_mm"), args.pop("notch_radius_mm"),
                              args.pop("arm_length_mm"), **args)


def test_gauge_strain_is_euler_bernoulli_and_proportional_to_lever():
    arms = np.array([4.0, 5.0, 6.0, 7.0, 8.0])
    eps = gauge_strain_per_newton(0.25, arms, E=E, b=B)
    assert np.all(eps > 0)
    np.testing.assert_allclose(eps / arms, eps[0] / arms[0], rtol=1e-14)
    assert eps[0] == pytest.approx(6 * 4.0 / (E * B * 0.25**2), rel=1e-15)
    # 2 N at arms 4 ... 8 mm: print next to the paper's ANSYS 0.2711 ... 0.6316 %
    pct = 2.0 * eps * 100
    print(f"gauge strain at 2 N, arms 4 ... 8 mm: {pct[0]:.4f} ... {pct[-1]:.4f} %")
    # strain scales as 1/t^2
    assert float(gauge_strain_per_newton(0.125, 4.0, E=E, b=B)) == pytest.approx(4 * eps[0])


def test_estimate_closed_form_result(monkeypatch, tmp_path):
    monkeypatch.setattr(corr_mod, "CORRECTION_FILE", tmp_path / "absent.json")
    for slot in PLAN.slots:
        g = slot.geometry.bare()
        r = estimate_closed_form(g, MAT, element=slot.number)
        assert isinstance(r, StiffnessResult) and r.model == "closed-form"
        assert r.element == slot.number
        k = closed_form_stiffness(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm, **KW)
        assert r.stiffness_N_per_mm == pytest.approx(float(k), rel=1e-14)
        # EB at the notch centre x the fitted plane-strain factor (its own file)
        assert r.face_strain_per_N == pytest.approx(
            6 * g.arm_length_mm / (E * B * g.web_thickness_mm**2)
            * point_strain_factor(g, MAT).factor, rel=1e-14)
        assert r.error_estimate_rel == pytest.approx(
            0.39 * g.web_thickness_mm / g.notch_radius_mm)
        assert r.wall_time_s >= 0


# ---------------------------------------------------------------------------
# Correction hook
# ---------------------------------------------------------------------------
def test_identity_correction():
    assert IDENTITY.is_identity and Correction() == IDENTITY
    k = np.array([10.0, 20.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out, inside = apply_correction(k, np.array([0.01, 5.0]), IDENTITY, web_mm=9.0, arm_mm=99.0)
    np.testing.assert_array_equal(out, k)
    assert inside.all()


#: 3D gain of the example correction at nu = 0.33, w = 0: nu^2 / (1 - nu^2) * c3.
EXAMPLE_GAIN = 0.33**2 / (1 - 0.33**2) * 0.75


def _example_correction() -> Correction:
    return Correction(coefficients=(0.39, 0.05, 0.75),
                      fit_range=FitRange(t_over_R=(0.075, 1.0), web_mm=(0.15, 0.4),
                                         arm_mm=(4.0, 8.0)),
                      residual_rel=0.01, source="synthetic test data")


def test_correction_factor_and_range_flag():
    c = _example_correction()
    s = np.array([0.1, 0.5, 2.0])
    with pytest.warns(CorrectionRangeWarning, match="1 of 3"):
        k, inside = apply_correction(np.ones(3), s, c)
    np.testing.assert_allclose(k, (1 + EXAMPLE_GAIN) / (1 + 0.39 * s + 0.05 * s * s), rtol=1e-15)
    np.testing.assert_array_equal(inside, [True, True, False])
    with pytest.warns(CorrectionRangeWarning):
        _, inside = apply_correction(np.ones(2), np.array([0.5, 0.5]), c, web_mm=0.25,
                                     arm_mm=np.array([6.0, 9.0]))
    np.testing.assert_array_equal(inside, [True, False])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _, inside = apply_correction(np.ones(3), s, c, warn=False)
    assert not inside.all()


def test_correction_validation():
    with pytest.raises(DesignError):
        Correction(coefficients=(1.0, 2.0))
    with pytest.raises(DesignError):
        Correction(coefficients=(-2.0, 0.0, 0.0), fit_range=FitRange(t_over_R=(0.1, 1.0)))
    with pytest.raises(DesignError):
        FitRange(t_over_R=(1.0, 0.5))
    with pytest.raises(ValueError):
        Correction(coefficients=(-2.0, 0.0, 0.0)).factor(1.0)


def test_the_correction_file_is_parsed_once_and_again_when_it_changes(tmp_path, monkeypatch):
    c = _example_correction()
    path = tmp_path / "stiffness_correction.json"
    path.write_text(json.dumps(c.as_json()))
    parsed = []
    real_loads = json.loads
    monkeypatch.setattr(json, "loads", lambda text: parsed.append(1) or real_loads(text))
    assert all(load_correction(path) == c for _ in range(50))
    assert len(parsed) == 1
    other = dict(c.as_json(), residual_rel_max=0.25)
    tmp = tmp_path / "new.json"
    tmp.write_text(json.dumps(other))
    tmp.replace(path)  # as a refit writes it: a new file in its place
    assert load_correction(path).residual_rel == 0.25 and len(parsed) == 2


def test_correction_json_round_trip_and_loader(tmp_path):
    c = _example_correction()
    path = tmp_path / "stiffness_correction.json"
    path.write_text(json.dumps(c.as_json()))
    assert load_correction(path) == c
    assert load_correction(tmp_path / "missing.json") == IDENTITY
    bad = c.as_json()
    del bad["fit_range"]
    path.write_text(json.dumps(bad))
    with pytest.raises(DesignError):
        load_correction(path)
    path.write_text("{not json")
    with pytest.raises(DesignError):
        load_correction(path)


def _synthetic_fit_data(coefficients, n=60, seed=1) -> FitData:
    rng = np.random.default_rng(seed)
    t = np.exp(rng.uniform(np.log(0.05), np.log(1.0), n))
    R = t * np.exp(rng.uniform(0.0, np.log(40.0), n))
    b = np.exp(rng.uniform(np.log(0.5), np.log(10.0), n))
    nu = rng.uniform(0.27, 0.34, n)
    q = rng.uniform(0.6, 1.0, n)
    p = rng.uniform(0.0, 0.05, n)
    r = rng.uniform(0.0, 0.1, n)
    k_eb = rng.uniform(0.1, 100.0, n)
    truth = Correction(coefficients=coefficients)
    s, w, v = t / R, np.sqrt(t * R) / b, t / b
    k_ref = k_eb * truth.factor(s, w, nu, q, p, r, v)
    return FitData(t_over_R=s, width_ratio=w, poisson_ratio=nu, notch_share=q, shear_share=p,
                   arm_share=r, web_over_sheet=v, K_eb=k_eb, K_ref=k_ref)


def test_fit_correction_recovers_coefficients():
    true = (0.55, 0.02, 0.9, 1.5, 0.3, 2.5, -0.5, 1.0)
    data = _synthetic_fit_data(true)
    c = fit_correction(data, fit_range=FitRange(web_mm=(0.05, 1.0)), source="synthetic")
    np.testing.assert_allclose(c.coefficients, true, rtol=1e-6, atol=1e-8)
    assert c.residual_rel < 1e-10
    assert np.max(np.abs(data.residuals(c))) == pytest.approx(c.residual_rel, abs=1e-15)
    # a subset of free coefficients leaves the others at zero
    c3 = fit_correction(data, fit_range=FitRange(), source="synthetic", free=("c1", "c2", "c3"))
    assert c3.coefficients[3:] == (0.0,) * 5 and c3.residual_rel > 1e-3
    with pytest.raises(ValueError):
        fit_correction(data, fit_range=FitRange(), source="x", free=("c9",))


def test_estimate_closed_form_with_correction():
    c = _example_correction()
    g = G0
    r0 = estimate_closed_form(g, MAT, corrected=False)
    r1 = estimate_closed_form(g, MAT, correction=c)
    s = g.web_thickness_mm / g.notch_radius_mm
    parts = closed_form_compliance(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm, **KW)
    q = float(parts.notch_bending / parts.total)
    assert 0.9 < q < 1.0
    assert r1.stiffness_N_per_mm == pytest.approx(
        r0.stiffness_N_per_mm * (1 + EXAMPLE_GAIN) / (1 + q * (0.39 * s + 0.05 * s * s)),
        rel=1e-14)
    assert r1.error_estimate_rel == 0.01
    assert r1.face_strain_per_N == pytest.approx(
        r0.face_strain_per_N * point_strain_factor(g, MAT).factor, rel=1e-14)


# ---------------------------------------------------------------------------
# Web-thickness inverse
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("t", [0.15, 0.25, 0.4])
@pytest.mark.parametrize("element", [1, 4])
def test_web_for_stiffness_round_trip(t, element):
    g = dataclasses.replace(PLAN.element(element).geometry, web_thickness_mm=t)
    k = estimate_closed_form(g, MAT, corrected=False).stiffness_N_per_mm
    assert web_for_stiffness(k, g, MAT, corrected=False) == pytest.approx(t, abs=1e-8)
    c = _example_correction()
    k_c = estimate_closed_form(g, MAT, correction=c).stiffness_N_per_mm
    assert web_for_stiffness(k_c, g, MAT, correction=c) == pytest.approx(t, abs=1e-8)


def test_web_for_stiffness_out_of_range():
    with pytest.raises(ValueError, match="allowed"):
        web_for_stiffness(1e4, G0, MAT, corrected=False)
    with pytest.raises(ValueError):
        web_for_stiffness(-1.0, G0, MAT, corrected=False)
    with pytest.warns(CorrectionRangeWarning):
        t = web_for_stiffness(1.5, PLAN.element(4).geometry, MAT, correction=_example_correction())
    assert t < 0.15


# ---------------------------------------------------------------------------
# Property test over the design domain
# ---------------------------------------------------------------------------
@settings(max_examples=200, deadline=None)
@given(t=st.floats(0.15, 0.4), a=st.floats(4.0, 8.0), frac=st.floats(0.0, 1.0))
def test_random_in_domain_positive(t, a, frac):
    R = t + frac * (2.0 - t)
    k = float(closed_form_stiffness(t, R, a, **KW))
    eps = float(gauge_strain_per_newton(t, a, E=E, b=B))
    assert math.isfinite(k) and k > 0
    assert math.isfinite(eps) and eps > 0
    parts = closed_form_compliance(t, R, a, **KW)
    assert all(float(p) > 0 for p in parts)
    assert float(parts.notch_bending) > 0.8 * float(parts.total)  # the hinge dominates


# ---------------------------------------------------------------------------
# The stored fem3d fit: hold-out designs, range warning
# ---------------------------------------------------------------------------
def _stored_points(kind: str) -> list[dict]:
    doc = json.loads(corr_mod.CORRECTION_FILE.read_text())
    return [p for p in doc["points"] if p["set"].startswith(kind)]


def _closed_form_at(p: dict):
    from tactcad.studies.correction_sweep import grid_geometry

    g, mat = grid_geometry(p["web_mm"], p["arm_mm"], p["notch_radius_mm"], sheet_mm=p["sheet_mm"],
                           poisson_ratio=p["poisson_ratio"],
                           youngs_modulus_MPa=p["youngs_modulus_MPa"])
    with warnings.catch_warnings():
        warnings.simplefilter("error", CorrectionRangeWarning)  # hold-out lies inside the range
        return estimate_closed_form(g, mat)


def test_closed_form_within_2_percent_of_fem3d_on_holdout_designs():
    """Designs not used in the fit, across the whole domain (web 0.05-1 mm,
    arm 2-20 mm, sheet 0.5-10 mm, nu 0.27-0.34): the estimator, run through
    the plan, stays within 2 % of the stored fem3d stiffness, and its error
    estimate (the fit's largest residual) covers the hold-out error."""
    hold = _stored_points("holdout")
    assert len(hold) >= 8
    errs = []
    for p in hold:
        r = _closed_form_at(p)
        errs.append(r.stiffness_N_per_mm / p["K_fem3d"] - 1)
        assert r.stiffness_N_per_mm / p["K_fem3d"] - 1 == pytest.approx(p["residual_rel"],
                                                                         abs=1e-9)
    print(f"hold-out: max {100 * max(map(abs, errs)):.2f} %, "
          f"mean {100 * np.mean(np.abs(errs)):.2f} %")
    assert max(abs(e) for e in errs) <= 0.02
    spans = {k: (min(p[k] for p in hold), max(p[k] for p in hold))
             for k in ("web_mm", "arm_mm", "sheet_mm")}
    assert spans["web_mm"][1] / spans["web_mm"][0] > 4  # the hold-out spans the domain
    assert spans["arm_mm"][1] / spans["arm_mm"][0] > 3
    assert spans["sheet_mm"][1] / spans["sheet_mm"][0] > 4


def test_fit_residuals_and_statistics_match_the_model():
    doc = json.loads(corr_mod.CORRECTION_FILE.read_text())
    c = load_correction()
    fit = _stored_points("fit")
    r = FitData.from_points(fit).residuals(c)
    assert np.max(np.abs(r)) == pytest.approx(doc["fit"]["max"], rel=1e-9)
    assert np.max(np.abs(r)) == pytest.approx(c.residual_rel, rel=1e-9)
    assert c.residual_rel <= 0.02
    fr = doc["fit_range"]
    assert fr["web_mm"] == pytest.approx([0.05, 1.0]) and fr["arm_mm"][1] == pytest.approx(20.0)
    assert fr["sheet_mm"] == pytest.approx([0.5, 10.0])
    assert fr["poisson_ratio"][0] <= 0.27 and fr["poisson_ratio"][1] >= 0.34


def test_the_range_warning_says_the_coordinate_in_words_and_names_no_module():
    """The warning carried the fit's data record, module path and all
    (``44 designs of tactcad.mechanics.correction_sweep``): it says each coordinate in
    words and what to run instead."""
    thick = dataclasses.replace(G0, sheet_thickness_mm=40.0)
    with pytest.warns(CorrectionRangeWarning) as said:
        estimate_closed_form(thick, MAT)
    text = str(said[0].message)
    assert "sheet_mm (sheet thickness, mm)" in text and "--model fem3d" in text
    assert re.search(r"tactcad\.[a-z_]+\.", text) is None, text


def test_closed_form_warns_outside_the_fitted_range_with_an_error_estimate():
    thick = dataclasses.replace(G0, sheet_thickness_mm=40.0)  # beyond the 10 mm sheet
    with pytest.warns(CorrectionRangeWarning, match=r"sheet_mm .*estimated error up to [0-9.]+ %"):
        estimate_closed_form(thick, MAT)
    soft = dataclasses.replace(MAT, poisson_ratio=0.45)  # beyond the material library
    with pytest.warns(CorrectionRangeWarning, match=r"poisson_ratio .*estimated error"):
        r = estimate_closed_form(G0, soft)
    # outside, the estimate adds how far the correction moves beyond the range
    assert r.error_estimate_rel > load_correction().residual_rel + 0.01
    with warnings.catch_warnings():
        warnings.simplefilter("error", CorrectionRangeWarning)
        r0 = estimate_closed_form(G0, MAT)  # the default design lies inside
    assert r0.error_estimate_rel == pytest.approx(load_correction().residual_rel)


# ---------------------------------------------------------------------------
# One Richardson extrapolation for every level
# ---------------------------------------------------------------------------
def test_every_level_uses_the_one_richardson_function():
    import ast
    import pathlib

    from tactcad.mechanics import beam, richardson
    from tactcad.mechanics.fem import fem2d, fem3d

    for mod in (beam, fem2d, fem3d):
        assert mod.richardson is richardson.richardson, mod.__name__
    root = pathlib.Path(richardson.__file__).parent
    for path in root.rglob("*.py"):
        if path.name == "richardson.py":
            continue
        tree = ast.parse(path.read_text())
        defined = {n.name for n in ast.walk(tree)
                   if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        assert not defined & {"richardson", "Richardson"}, path
        src = path.read_text()
        assert "2.0**p - 1" not in src and "ratio**p - 1" not in src, path  # no private copy
    # the beam uses that function, with the formal order 2 as fallback
    from tactcad.mechanics.beam import beam_convergence

    conv = beam_convergence(G0, MAT, 64)
    rk = richardson.richardson(conv.stiffness_N_per_mm, 2.0, formal_order=2.0)
    assert conv.extrapolated_N_per_mm == rk.extrapolated
    assert conv.error_estimate_rel == rk.error_rel


def test_richardson_falls_back_to_the_formal_order():
    from tactcad.mechanics.richardson import richardson

    exact, c = 3.0, 0.5
    vals = [exact + c * h**2 for h in (1.0, 0.5, 0.25)]
    r = richardson(vals, 2.0, formal_order=2.0)
    assert r.order == pytest.approx(2.0) and r.extrapolated == pytest.approx(exact)
    flat = richardson([1.0, 1.0, 1.0], 2.0, formal_order=2.0)  # round-off: order undefined
    assert math.isnan(flat.order) and flat.extrapolated == 1.0 and flat.error_rel == 0.0
    odd = richardson([1.0, 1.1, 1.05], 2.0)  # oscillating: no order, last difference
    assert math.isnan(odd.order) and odd.error_rel == pytest.approx(0.05 / 1.05)


def test_the_corrections_range_covers_every_library_material_and_is_checked_at_fem3d():
    import json

    from tactcad.vocabulary.material_library import material_grade, material_grades
    from tactcad.mechanics.correction import CORRECTION_FILE, load_correction

    lo, hi = load_correction().fit_range.poisson_ratio
    for name in material_grades():
        assert lo <= material_grade(name).poisson_ratio <= hi, name
    doc = json.loads(CORRECTION_FILE.read_text(encoding="utf-8"))
    fit_hi = max(p["poisson_ratio"] for p in doc["points"] if p["set"].startswith("fit"))
    beyond = [p for p in doc["points"] if p["poisson_ratio"] > fit_hi]
    # the range beyond the fitted points rests on fem3d checks at its end
    assert beyond and all(p["set"].startswith("check") for p in beyond)
    assert max(p["poisson_ratio"] for p in beyond) == hi
    assert max(abs(p["residual_rel"]) for p in beyond) <= doc["holdout"]["max"]


@pytest.mark.parametrize("web, radius, arm, bare", [(0.25, 1.0, 8.0, False), (0.6, 0.6, 14.0, False),
                                                     (0.12, 2.5, 30.0, False), (0.25, 1.0, 8.0, True)])
def test_the_error_estimate_alone_is_the_closed_form_levels_to_the_bit(plan, web, radius, arm,
                                                                        bare):
    from tactcad.mechanics.closed_form import closed_form_error_estimate_rel
    from tactcad.mechanics.ladder import estimate

    g = dataclasses.replace(plan.element(1).geometry, web_thickness_mm=web,
                            notch_radius_mm=radius, arm_length_mm=arm)
    if bare:
        g = g.bare()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # some of these lie outside the fitted range
        whole = estimate("closed-form", g, plan.material).error_estimate_rel
        alone = closed_form_error_estimate_rel(g, plan.material)
    assert alone == whole and alone > 0


@pytest.mark.parametrize("web_mm", [0.02, 0.05, 0.08, 0.164, 0.4, 1.0])
def test_the_corrected_k_alone_is_the_estimators_to_the_bit(web_mm):
    """A web search reads K alone: the 10 mm jaw's comb elements (each with its bonded
    gauge) and their bare sections give the estimator's K exactly at every trial web."""
    from tactcad.design.array_plan import EXAMPLES, plan_from_dict, read_toml
    from tactcad.mechanics.closed_form import corrected_element_k

    comb = plan_from_dict(read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml",
                                    "design file"))
    geometries = {s.geometry for s in comb.slots}
    geometries |= {g.bare() for g in geometries}
    assert any(g.gauge for g in geometries) and any(not g.gauge for g in geometries)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the thinnest webs leave the fitted range
        for g in geometries:
            trial = dataclasses.replace(g, web_thickness_mm=web_mm)
            expected = estimate_closed_form(trial, comb.material).stiffness_N_per_mm
            assert corrected_element_k(trial, comb.material) == expected
