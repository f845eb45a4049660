"""The gauge strain beyond plane-stress beam theory: the fitted width and profile
factor, the bonded layer, the exact face average, and the read-out that carries them."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from tactcad.mechanics.gauge_strain import (GAUGE_STRAIN_FILE, StrainCorrection,
                                            bonded_grid_factor, face_under_layer_factor,
                                            grid_strain_factor, load_strain_correction,
                                            point_strain_factor)
from tactcad.mechanics.notch_profile import notched_height_mm
from tactcad.studies.gauge_strain_sweep import _residuals, samples


# ---------------------------------------------------------------------------
# The bonded layer: transformed section
# ---------------------------------------------------------------------------
def test_a_layer_without_stiffness_lifts_the_grid_by_the_height_ratio():
    b = bonded_grid_factor(0.25, 3.0, 69000.0, 0.05, 0.0, 1.0)
    assert b.read_factor == pytest.approx((0.125 + 0.05) / 0.125)
    assert b.stiffening_rel == 0.0


def test_a_layer_of_the_web_material_across_the_sheet_is_a_thicker_web():
    t, h, E, w = 0.2, 0.05, 1.0e5, 3.0
    got = bonded_grid_factor(t, w, E, h, E, w)
    # one web t + h: top-face strain per moment 6 / (E w (t + h)^2) against 6 / (E w t^2)
    assert got.read_factor == pytest.approx((t / (t + h)) ** 2, rel=1e-12)
    assert got.stiffening_rel == pytest.approx(((t + h) / t) ** 3 - 1, rel=1e-12)
    assert got.neutral_axis_shift_mm == pytest.approx(h / 2, rel=1e-12)


def test_the_face_under_a_layer_without_stiffness_is_the_bare_face():
    assert float(face_under_layer_factor(0.25, 3.0, 69000.0, 0.05, 0.0, 1.0)) == 1.0
    assert float(face_under_layer_factor(0.25, 3.0, 69000.0, 0.0, 1e4, 1.0)) == 1.0


def test_the_face_under_a_layer_of_the_web_material_is_inside_a_thicker_web():
    t, h, E, w = 0.2, 0.05, 1.0e5, 3.0
    # one web t + h: the old face lies (t - h) / 2 above its centroid, strain per moment
    # 12 (t - h) / 2 / (E w (t + h)^3) against the bare web's 12 t / 2 / (E w t^3)
    want = (t - h) / t * (t / (t + h)) ** 3
    assert float(face_under_layer_factor(t, w, E, h, E, w)) == pytest.approx(want, rel=1e-12)


def test_the_face_under_the_default_gauge_strains_less_than_the_bare_face(plan):
    from tactcad.mechanics.bonded_layer import layer_face_factor, layer_of

    g, mat = plan.element(1).geometry, plan.material
    f = layer_face_factor(g, mat.youngs_modulus_MPa, layer_of(g))
    b = bonded_grid_factor(g.web_thickness_mm, g.sheet_thickness_mm, mat.youngs_modulus_MPa,
                           g.gauge.height_mm, g.gauge.modulus_MPa, layer_of(g).width_mm)
    # the stiffened web and its risen neutral axis: 0.89 on the paper's 0.25 mm web
    assert f == pytest.approx((1 - 2 * b.neutral_axis_shift_mm / g.web_thickness_mm)
                              / (1 + b.stiffening_rel), rel=1e-12)
    assert 0.85 < f < 0.93
    assert layer_face_factor(g.bare(), mat.youngs_modulus_MPa, None) == 1.0


def test_bonded_grid_refuses_bad_input():
    with pytest.raises(ValueError, match="web"):
        bonded_grid_factor(0.0, 3.0, 1e5, 0.05, 3e3, 1.0)


# ---------------------------------------------------------------------------
# The fitted factor and its file
# ---------------------------------------------------------------------------
def test_the_fitted_file_reproduces_its_residuals():
    doc = json.loads(GAUGE_STRAIN_FILE.read_text())
    corr = load_strain_correction()
    fit_pts = [p for p in doc["points"] if p["set"] == "fit"]
    r = _residuals(corr, *samples(fit_pts))
    assert np.abs(r).max() == pytest.approx(doc["fit"]["max"], rel=1e-9)
    hold = [p for p in doc["points"] if p["set"] == "holdout"]
    assert hold, "the file keeps a hold-out set"
    assert np.abs(_residuals(corr, *samples(hold))).max() == pytest.approx(
        doc["holdout"]["max"], rel=1e-9)
    assert corr.error_rel == max(doc["fit"]["max"], doc["holdout"]["max"])


def test_wide_sheet_point_factor_tends_to_plane_strain(plan):
    g, mat = plan.element(1).geometry, plan.material
    corr = load_strain_correction()
    # a vanishing hinge length against the width: phi -> 1, the point factor -> (1 - nu^2)(1 + c3 s)
    wide = replace(g, sheet_thickness_mm=1e6)
    c3 = corr.coefficients[2]
    s = g.web_thickness_mm / g.notch_radius_mm
    assert point_strain_factor(wide, mat).factor == pytest.approx(
        (1 - mat.poisson_ratio ** 2) * (1 + c3 * s), rel=1e-6)


def test_outside_the_fitted_range_is_flagged_with_a_larger_error(plan):
    g, mat = plan.element(1).geometry, plan.material
    inside = grid_strain_factor(g, mat, 0.6, 1.0)
    assert inside.outside == ()
    assert inside.error_rel == load_strain_correction().error_rel
    long_grid = grid_strain_factor(g, mat, 2.5 * g.notch_radius_mm, 1.0)  # xi = 1.25
    assert long_grid.outside == ("grid_over_notch",)
    assert long_grid.error_rel > inside.error_rel


def test_closed_form_stiffness_result_carries_the_point_factor_and_the_layer(plan):
    from tactcad.mechanics.bonded_layer import layer_face_factor, layer_of
    from tactcad.mechanics.closed_form import estimate_closed_form, gauge_strain_per_newton

    g, mat = plan.element(1).geometry, plan.material
    eb = float(gauge_strain_per_newton(g.web_thickness_mm, g.arm_length_mm,
                                       E=mat.youngs_modulus_MPa, b=g.sheet_thickness_mm))
    layer = layer_face_factor(g, mat.youngs_modulus_MPa, layer_of(g))
    assert layer < 1.0
    # the face at the grid's centre under the gauge's glue line and carrier
    got = estimate_closed_form(g, mat).face_strain_per_N
    assert got == pytest.approx(eb * point_strain_factor(g, mat).factor * layer, rel=1e-12)
    assert estimate_closed_form(g, mat, corrected=False).face_strain_per_N == pytest.approx(
        eb * layer, rel=1e-14)
    # the element as cut: the bare face
    bare = g.bare()
    assert estimate_closed_form(bare, mat).face_strain_per_N == pytest.approx(
        eb * point_strain_factor(bare, mat).factor, rel=1e-12)
    assert estimate_closed_form(bare, mat, corrected=False).face_strain_per_N == eb


def test_closed_form_warns_outside_the_strain_fit(plan):
    from tactcad.mechanics.closed_form import estimate_closed_form
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning

    g, mat = plan.element(1).geometry, plan.material
    with pytest.warns(GaugeStrainRangeWarning, match="gauge strain"):
        estimate_closed_form(replace(g, sheet_thickness_mm=0.4), mat)  # b/t 1.6, fitted >= 1.87


# ---------------------------------------------------------------------------
# The read-out carries them
# ---------------------------------------------------------------------------
def test_readout_grid_strain_is_the_corrected_face_times_the_bonded_layer(plan):
    from tactcad.mechanics.readout_chain import (beam_face_mean_strain_per_N, grid_strain_per_N,
                                                 readout_chain)

    chain = readout_chain(plan)
    g, mat = plan.element(1).geometry, plan.material
    got = grid_strain_per_N(g, mat, chain, "closed-form")
    c = grid_strain_factor(g, mat, chain.grid_length_mm, chain.grid_width_mm)
    assert got["surface"] == pytest.approx(
        c.factor * beam_face_mean_strain_per_N(g, mat, chain.grid_length_mm), rel=1e-12)
    layer = bonded_grid_factor(g.web_thickness_mm, g.sheet_thickness_mm, mat.youngs_modulus_MPa,
                               chain.grid_height_mm, chain.gauge_backing_modulus_MPa,
                               min(chain.grid_width_mm + 1.0, g.sheet_thickness_mm))
    # section by section along the span: below the web's factor, above the thickest section's
    ends = notched_height_mm(chain.grid_length_mm / 2, g.web_thickness_mm, g.notch_radius_mm,
                             g.base_height_mm, g.arm_height_mm)
    thick = bonded_grid_factor(float(ends), g.sheet_thickness_mm, mat.youngs_modulus_MPa,
                               chain.grid_height_mm, chain.gauge_backing_modulus_MPa,
                               min(chain.grid_width_mm + 1.0, g.sheet_thickness_mm))
    assert thick.read_factor < got["read_factor"] < layer.read_factor
    assert got["grid"] == pytest.approx(got["surface"] * got["read_factor"], rel=1e-12)
    # the weighted mean by a plain midpoint sum over the span, apart from Gauss-Legendre's
    u = (np.arange(4000) + 0.5) / 4000 * chain.grid_length_mm - chain.grid_length_mm / 2
    h = notched_height_mm(u, g.web_thickness_mm, g.notch_radius_mm, g.base_height_mm,
                          g.arm_height_mm)
    face = (g.arm_length_mm - u) / h ** 2
    read = np.array([bonded_grid_factor(float(hi), g.sheet_thickness_mm,
                                        mat.youngs_modulus_MPa, chain.grid_height_mm,
                                        chain.gauge_backing_modulus_MPa,
                                        min(chain.grid_width_mm + 1.0, g.sheet_thickness_mm)
                                        ).read_factor for hi in h])
    assert got["read_factor"] == pytest.approx((face * read).sum() / face.sum(), rel=1e-5)
    assert got["error_rel"] == c.error_rel and got["outside_fit"] == ()
    # the catalogue gauge lifts the grid 55 um: more than the surface, less than without stiffness
    assert 1.0 < got["read_factor"] < got["height_factor"]
    assert got["height_factor"] == pytest.approx(
        1 + chain.grid_height_mm / (g.web_thickness_mm / 2))


def test_readout_report_flags_a_grid_outside_the_fit(plan):
    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.studies.verification import requirements_of

    raw = json.loads(json.dumps(plan.raw))
    raw.setdefault("readout", {})["grid_length_mm"] = 1.5  # xi = 1.5 at R = 0.5
    from tactcad.design.array_plan import plan_from_dict

    long_plan = plan_from_dict(raw, source="<test>")
    rep = readout_report(long_plan, requirements_of(long_plan)).as_json()
    assert all(r["strain_outside_fit"] == ["grid_over_notch"] for r in rep["elements"])
    assert any("outside its fitted range" in n for n in rep["notes"])


def test_catalogue_gauges_state_their_layer_with_a_source():
    from tactcad.vocabulary.material_library import strain_gauges

    for gauge in strain_gauges().values():
        assert 0.02 <= gauge.grid_height_mm <= 0.08
        assert gauge.backing_modulus_MPa > 0
        for key in ("backing_thickness_mm", "adhesive_thickness_mm", "backing_modulus_MPa"):
            assert gauge.source(key) if hasattr(gauge, "source") else dict(gauge.sources)[key]


def test_model_coordinates_examples_inside_the_fit():
    from pathlib import Path

    from tactcad.api import load
    from tactcad.mechanics.readout_chain import readout_chain

    root = Path(__file__).resolve().parents[2]
    for design in ("hardware/macro_array/macro_array.toml",
                   "hardware/ti_array_2x3/ti_array_2x3.toml"):
        plan = load(root / design).plan
        chain = readout_chain(plan)
        for g in plan.distinct_elements.values():
            f = grid_strain_factor(g, plan.material, chain.grid_length_mm, chain.grid_width_mm)
            assert f.outside == (), (design, g.part_name, f.coordinates)
            assert math.isfinite(f.factor) and 0.8 < f.factor < 1.2
    assert isinstance(load_strain_correction(), StrainCorrection)


def test_a_web_tolerance_end_outside_the_strain_fit_is_named_in_words_with_its_element(plan):
    """The warning of a web at its lower tolerance limit names the element, that limit and
    its web (not the drawn web's figures as if they were its own), and its coordinate in
    words, not by the model's variable name."""
    import warnings

    from tactcad.in_use.kobj_budget import web_tolerance_k_change
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning

    g = plan.element(1).geometry
    # b/t 47.6 at the drawn web (fitted <= 49.95), 58.8 at its lower limit 0.085 mm
    g = replace(g, web_thickness_mm=0.105, web_tolerance_mm=0.02, sheet_thickness_mm=5.0,
                notch_radius_mm=0.5)
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        web_tolerance_k_change(g, plan.material)
    texts = [str(w.message) for w in said if issubclass(w.category, GaugeStrainRangeWarning)]
    assert texts, [str(w.message) for w in said]
    assert all("sheet_over_web" not in t for t in texts), texts
    low = [t for t in texts if "lower tolerance limit, 0.085 mm" in t]
    assert low and g.part_name in low[0] and "drawn 0.105 +/-0.02 mm" in low[0], texts
    assert "the sheet over the web thickness, b/t" in low[0] and "b/t 58.8" in low[0]
