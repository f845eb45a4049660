"""Strength: peak stress at the flexure hinge, full-scale force, warnings, CLI."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from tactcad.cli import main
from tactcad.design import plan_from_dict
from tactcad.errors import DesignError
from tactcad.mechanics.strength import (KT_FIT_TOLERANCE, PAPER_LOAD_N, full_scale_force,
                                        nominal_stress_per_newton, plan_strength,
                                        stress_concentration_factor, strength_summary)

JSON_KEYS = {"element", "stress_MPa_per_N", "full_scale_force_N",
             "yield_safety_factor_at_full_scale", "gauge_strain_at_full_scale",
             "tip_deflection_mm_at_full_scale"}


def test_stress_concentration_tends_to_one_and_grows_with_t_over_r():
    s = np.array([1e-4, 0.05, 0.2, 0.5, 1.0])
    kt = stress_concentration_factor(0.25 * s, 0.25)
    assert kt[0] == pytest.approx(1.0, abs=1e-4)
    assert np.all(np.diff(kt) > 0)
    assert 1.1 < kt[3] < 1.2  # t/R = 0.5: Smith's double-notch form gives 1.106


def test_full_scale_force_formula(plan):
    rec = plan_strength(plan)[3]  # element 4, 8 mm arm
    y, sf = plan.material.yield_strength_MPa, plan.strength.safety_factor
    assert rec.full_scale_force_N == pytest.approx(y / (rec.stress_MPa_per_N * sf), rel=1e-12)
    assert rec.yield_safety_factor_at_full_scale == pytest.approx(sf)
    assert rec.gauge_strain_at_full_scale == pytest.approx(
        6 * 8.0 / (69000 * 3.0 * 0.25**2) * rec.full_scale_force_N, rel=1e-12)
    assert rec.tip_deflection_mm_at_full_scale == pytest.approx(
        rec.full_scale_force_N / rec.stiffness_N_per_mm, rel=1e-12)
    assert float(full_scale_force(y, rec.stress_MPa_per_N, 2 * sf)) == pytest.approx(
        rec.full_scale_force_N / 2)
    with pytest.raises(ValueError):
        full_scale_force(y, rec.stress_MPa_per_N, 0.5)


def test_papers_8mm_arm_at_2N_is_above_6061_yield(plan):
    rec = next(r for r in plan_strength(plan) if r.arm_length_mm == 8.0)
    nominal = float(nominal_stress_per_newton(0.25, 8.0, 3.0)) * PAPER_LOAD_N
    assert nominal == pytest.approx(512.0)  # ~500 MPa in the web
    assert rec.stress_MPa_at_paper_load > plan.material.yield_strength_MPa
    assert any("above the yield strength" in w for w in rec.warnings)
    assert any("fatigue strain" in w for w in rec.warnings)


def test_stronger_grade_raises_full_scale_and_clears_the_yield_warning(design_data):
    design_data["material"]["grade"] = "17-4PH-H900"
    del design_data["material"]["youngs_modulus_MPa"], design_data["material"]["poisson_ratio"]
    plan = plan_from_dict(design_data)
    rec = next(r for r in plan_strength(plan) if r.arm_length_mm == 4.0)
    assert rec.full_scale_force_N == pytest.approx(1170.0 / (rec.stress_MPa_per_N * 1.5))
    assert not any("above the yield strength" in w for w in rec.warnings)


def test_no_yield_strength_is_refused(design_data):
    del design_data["material"]["grade"]
    del design_data["assumptions"]["material.grade"]
    plan = plan_from_dict(design_data)
    with pytest.raises(DesignError) as exc:
        strength_summary(plan)
    assert "material.yield_strength_MPa" in str(exc.value) and "6061-T6" in str(exc.value)


def test_summary_records_are_finite_with_the_required_keys(plan):
    recs = strength_summary(plan)
    assert [r["element"] for r in recs] == list(range(1, 11))
    for r in recs:
        assert JSON_KEYS <= set(r)
        assert all(math.isfinite(v) for v in r.values() if isinstance(v, float))


def test_cli_json_and_text(capsys):
    assert main(["strength", "--json"]) == 0
    recs = json.loads(capsys.readouterr().out)
    assert len(recs) == 10 and JSON_KEYS <= set(recs[0])
    assert main(["strength"]) == 0
    out = capsys.readouterr().out
    assert "F_fs N" in out and "above the yield strength" in out


def test_cli_bad_grade_is_an_error_not_a_traceback(tmp_path, capsys):
    from tactcad.design import DEFAULT_DESIGN

    text = DEFAULT_DESIGN.read_text().replace('grade = "6061-T6"', 'grade = "6062-T6"')
    f = tmp_path / "bad.toml"
    f.write_text(text)
    assert main(["strength", "--design", str(f)]) == 2
    err = capsys.readouterr().err
    assert "material.grade" in err and "7075-T6" in err


@pytest.mark.slow
@pytest.mark.parametrize("web,radius,arm", [(0.25, 0.5, 8.0), (0.25, 0.25, 4.0), (0.1, 1.0, 6.0),
                                            (0.4, 0.4, 5.0)])
def test_closed_form_stress_matches_the_fem2d_field(plan, web, radius, arm):
    """K_t fitted form against converged plane-stress P2 FEM (Richardson):
    within KT_FIT_TOLERANCE (2 %) over t/R = 0.1 ... 1 and arms 4 ... 8 mm."""
    from tactcad.mechanics.strength import fem_peak_stress, peak_stress_per_newton

    g = dataclasses.replace(plan.element(1).geometry, web_thickness_mm=web,
                            notch_radius_mm=radius, arm_length_mm=arm)
    fem = fem_peak_stress(g, plan.material, "fem2d")
    closed = float(peak_stress_per_newton(web, radius, arm, g.sheet_thickness_mm))
    assert fem.stress_error_rel < 0.01
    assert abs(closed / fem.stress_MPa_per_N - 1) < KT_FIT_TOLERANCE
    # the peak sits at the notch root, under the gauge
    x, y = fem.peak_location_mm
    assert x == pytest.approx(g.hinge_x_mm, abs=radius / 4)
    assert y == pytest.approx(g.base_height_mm - web, abs=web / 4)
