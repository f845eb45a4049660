"""Material grades, strain gauges and their use in the design file."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import plan_from_dict
from tactcad.errors import DesignError
from tactcad.vocabulary.material_library import (DEFAULT_GAUGE, DEFAULT_GRADE, material_grade, material_grades,
                                          strain_gauge, strain_gauges)

REQUIRED_GRADES = ("6061-T6", "7075-T6", "17-4PH-H900", "Ti-6Al-4V-annealed", "CuBe-C17200-TF00")


def test_library_has_the_grades_with_a_source_for_every_value():
    grades = material_grades()
    for name in REQUIRED_GRADES:
        g = grades[name]
        for field in ("youngs_modulus_MPa", "poisson_ratio", "yield_strength_MPa",
                      "fatigue_strength_MPa", "density_g_per_cm3"):
            assert g.source(field).strip(), (name, field)
        assert 0 < g.fatigue_strength_MPa < g.yield_strength_MPa < g.youngs_modulus_MPa / 50
        assert 0.2 < g.poisson_ratio < 0.4
        assert 1.0 < g.density_g_per_cm3 < 10.0
        assert g.fatigue_cycles >= 1e6 and -1.0 <= g.fatigue_R_ratio < 1.0


def test_stiffer_grades_rank_as_expected():
    g = material_grades()
    assert g["6061-T6"].yield_strength_MPa < g["7075-T6"].yield_strength_MPa \
        < g["Ti-6Al-4V-annealed"].yield_strength_MPa < g["17-4PH-H900"].yield_strength_MPa
    assert g["6061-T6"].youngs_modulus_MPa < g["Ti-6Al-4V-annealed"].youngs_modulus_MPa \
        < g["CuBe-C17200-TF00"].youngs_modulus_MPa < g["17-4PH-H900"].youngs_modulus_MPa


def test_gauge_limits_and_sources():
    gauge = strain_gauge(DEFAULT_GAUGE)
    assert gauge.resistance_ohm == 120.0 and gauge.bridge == "quarter"
    assert gauge.fatigue_strain == pytest.approx(1.5e-3)
    for g in strain_gauges().values():
        assert 0 < g.fatigue_strain < g.max_strain <= 0.05
        assert dict(g.sources)["fatigue_strain"].strip()


def test_unknown_grade_and_gauge_name_the_allowed_values():
    with pytest.raises(DesignError) as exc:
        material_grade("6082-T6")
    assert "material.grade" in str(exc.value) and "7075-T6" in str(exc.value)
    with pytest.raises(DesignError) as exc:
        strain_gauge("karma")
    assert "strength.gauge" in str(exc.value) and DEFAULT_GAUGE in str(exc.value)


def test_default_design_is_the_papers_aluminium_as_6061_t6(plan):
    m = plan.material
    assert m.grade == DEFAULT_GRADE
    assert (m.youngs_modulus_MPa, m.poisson_ratio) == (69000.0, 0.33)  # paper, not the grade's 68900
    assert m.yield_strength_MPa == material_grade("6061-T6").yield_strength_MPa
    assert dict(m.sources)["youngs_modulus_MPa"] == "design file"
    assert any(k == "material.grade" for k, _ in plan.assumptions)
    assert plan.strength.safety_factor == 1.5 and plan.strength.gauge.name == DEFAULT_GAUGE


def test_grade_supplies_e_and_nu_and_design_values_override(design_data):
    mat = design_data["material"]
    del mat["youngs_modulus_MPa"], mat["poisson_ratio"]
    mat["grade"] = "Ti-6Al-4V-annealed"
    mat["yield_strength_MPa"] = 830.0
    m = plan_from_dict(design_data).material
    ti = material_grade("Ti-6Al-4V-annealed")
    assert m.youngs_modulus_MPa == ti.youngs_modulus_MPa and m.poisson_ratio == ti.poisson_ratio
    assert m.yield_strength_MPa == 830.0
    assert m.fatigue_strength_MPa == ti.fatigue_strength_MPa
    assert dict(m.sources)["yield_strength_MPa"] == "design file"


def test_design_without_grade_has_only_its_own_values(design_data):
    del design_data["material"]["grade"]
    design_data["material"]["yield_strength_MPa"] = 240.0
    del design_data["assumptions"]["material.grade"]
    m = plan_from_dict(design_data).material
    assert m.grade is None and m.yield_strength_MPa == 240.0 and m.fatigue_strength_MPa is None


@pytest.mark.parametrize("section,key,value,words", [
    ("material", "grade", "unobtainium", ["material.grade", "6061-T6", "CuBe-C17200-TF00"]),
    ("material", "yield_strength_MPa", -5.0, ["material.yield_strength_MPa", "5000"]),
    ("material", "density_g_per_cm3", float("nan"), ["material.density_g_per_cm3"]),
    ("strength", "safety_factor", 0.8, ["strength.safety_factor", "1 <= value <= 10"]),
    ("strength", "gauge", "karma", ["strength.gauge", "constantan-foil"]),
    ("strength", "margin", 2.0, ["strength.margin", "safety_factor"]),
])
def test_bad_material_and_strength_values_are_refused(design_data, section, key, value, words):
    design_data[section][key] = value
    with pytest.raises(DesignError) as exc:
        plan_from_dict(design_data)
    for w in words:
        assert w in str(exc.value)


def test_strength_table_is_optional(design_data):
    del design_data["strength"]
    for k in [k for k in design_data["assumptions"] if k.startswith("strength.")]:
        del design_data["assumptions"][k]
    s = plan_from_dict(design_data).strength
    assert s.safety_factor == 1.5 and s.gauge.name == DEFAULT_GAUGE


def test_every_grade_has_a_modulus_coefficient_sourced_or_named_unsourced():
    for g in material_grades().values():
        assert -1e-3 < g.youngs_modulus_tc_per_K < 0.0, g.name
        sourced, note = g.is_sourced("youngs_modulus_tc_per_K"), dict(g.unsourced).get(
            "youngs_modulus_tc_per_K")
        assert sourced != bool(note), g.name  # a document, or the stand-in's origin: one of them
        prov = g.provenance("youngs_modulus_tc_per_K")
        assert prov.strip() and (sourced or prov.startswith("unsourced:")), g.name
    assert material_grade("6061-T6").is_sourced("youngs_modulus_tc_per_K")


#: Grades whose modulus coefficient no document was read for (a stand-in, named unsourced).
STAND_IN_MODULUS_TC = {"7075-T6"}


def test_every_sourced_modulus_coefficient_lies_within_what_its_own_points_give():
    """Recomputed from the points (or fit, or stated figure) the data file records with the
    source: a coefficient edited without its basis, or a basis misread, fails here. The
    library rounds to 3 digits, hence the 0.5 % allowance."""
    from tactcad.vocabulary.material_library import modulus_tc_bounds_per_K

    for g in material_grades().values():
        if g.name in STAND_IN_MODULUS_TC:
            assert not g.is_sourced("youngs_modulus_tc_per_K"), g.name
            continue
        assert g.is_sourced("youngs_modulus_tc_per_K"), g.name
        assert "stand-in" not in g.source("youngs_modulus_tc_per_K"), g.name
        lo, hi = modulus_tc_bounds_per_K(g.name)
        tc = g.youngs_modulus_tc_per_K
        assert lo * 1.005 <= tc <= hi * 0.995, (g.name, tc, lo, hi)


def test_the_range_of_use_sets_titanium_and_17_4ph_coefficients():
    """Ti-6Al-4V over 296-381 K (not the 296-501 K line, -3.9e-4 /K); 17-4 PH from the
    straight chromium steels row between 70 and 200 F (not the carbon-steel stand-in)."""
    ti, ph = material_grade("Ti-6Al-4V-annealed"), material_grade("17-4PH-H900")
    assert ti.youngs_modulus_tc_per_K == pytest.approx(-1.72e-4, rel=0.01)
    assert "296.3 and 381.12 K" in ti.source("youngs_modulus_tc_per_K")
    assert "Chromium steels, Cr 12%, 17%, 27%" in ph.source("youngs_modulus_tc_per_K")
    assert ph.youngs_modulus_tc_per_K == pytest.approx((28.5 - 29.2) / 29.2 / (130 * 5 / 9),
                                                       rel=0.01)


@pytest.mark.parametrize("points, moduli", [((300.0, 300.0), (1.0, 0.9)),
                                            ((300.0, 400.0), (0.0, 1.0))])
def test_modulus_points_that_give_no_slope_are_refused(points, moduli):
    from tactcad.vocabulary.material_library import modulus_tc_from_points

    with pytest.raises(ValueError, match="two temperatures and E > 0"):
        modulus_tc_from_points(points, moduli)


def test_a_grade_without_a_recorded_basis_is_named():
    from tactcad.vocabulary.material_library import modulus_tc_bounds_per_K

    with pytest.raises(DesignError, match="grades.7075-T6.youngs_modulus_tc_basis"):
        modulus_tc_bounds_per_K("7075-T6")


@pytest.mark.parametrize("table, words", [
    ({"youngs_modulus_tc_per_K": 0.01}, "-0.002 ... 0.0001 1/K"),
    ({"youngs_modulus_tc_per_K": "soft"}, "youngs_modulus_tc_per_K"),
    ({"youngs_modulus_tc_per_K": -4e-4, "sources": {}}, "one of the two"),
    ({"youngs_modulus_tc_per_K": -4e-4, "unsourced": {"youngs_modulus_tc_per_K": "x"}},
     "one of the two"),
])
def test_a_library_grade_without_a_valid_modulus_coefficient_is_refused(table, words):
    from tactcad.vocabulary.material_library import _grade_from_table, _library

    base = dict(_library()["grades"]["6061-T6"])
    base["sources"] = {k: v for k, v in base["sources"].items() if k != "youngs_modulus_tc_per_K"}
    if "sources" not in table:
        base["sources"]["youngs_modulus_tc_per_K"] = "a document"
    base.update({k: v for k, v in table.items() if k != "sources"})
    with pytest.raises(DesignError) as e:
        _grade_from_table("X", base)
    assert "grades.X." in str(e.value) and words in str(e.value)


def test_every_grade_states_its_fatigue_datum_one_way():
    """The data file itself: each grade names which stress its datum is, R, cycles,
    specimen, the ultimate strength the conversion needs, and their sources."""
    import tomllib
    from importlib import resources

    from tactcad.vocabulary.material_library import FATIGUE_DATUM_KEYS, FATIGUE_DATUM_STRESSES

    text = resources.files("tactcad").joinpath("data", "materials.toml").read_text("utf-8")
    grades = tomllib.loads(text)["grades"]
    assert set(REQUIRED_GRADES) <= set(grades)
    for name, t in grades.items():
        assert "fatigue_strength_MPa" not in t, name  # the datum has one name, not two
        for key in FATIGUE_DATUM_KEYS + ("ultimate_strength_MPa",):
            assert key in t, (name, key)
        assert t["fatigue_datum_stress"] in FATIGUE_DATUM_STRESSES, name
        assert t["fatigue_specimen"].strip(), name
        for key in ("fatigue_datum_MPa", "ultimate_strength_MPa"):
            assert t["sources"][key].strip(), (name, key)
        # an amplitude datum cannot put the cycle's maximum above the ultimate strength
        r = t["fatigue_R_ratio"]
        peak = (t["fatigue_datum_MPa"] if t["fatigue_datum_stress"] == "maximum"
                else 2 * t["fatigue_datum_MPa"] / (1 - r))
        assert peak < t["ultimate_strength_MPa"], name


def test_fully_reversed_amplitude_from_a_maximum_at_R():
    """sigma_a = sigma_max (1 - R)/2, sigma_m = sigma_max (1 + R)/2, then Goodman."""
    from tactcad.vocabulary.material_library import fully_reversed_amplitude

    s_max, r, s_u = 510.0, 0.1, 950.0
    s_a, s_m = s_max * (1 - r) / 2, s_max * (1 + r) / 2
    got = fully_reversed_amplitude(s_max, "maximum", r, s_u)
    assert got == pytest.approx(s_a / (1 - s_m / s_u))
    # the same cycle stated as its amplitude converts to the same value
    assert fully_reversed_amplitude(s_a, "amplitude", r, s_u) == pytest.approx(got)
    # a fully reversed amplitude is its own value; R = 0 maximum: half of it is mean
    assert fully_reversed_amplitude(100.0, "amplitude", -1.0, 300.0) == 100.0
    assert fully_reversed_amplitude(200.0, "maximum", 0.0, 300.0) == pytest.approx(100 / (1 - 1 / 3))
    with pytest.raises(ValueError, match="mean stress"):
        fully_reversed_amplitude(600.0, "maximum", 0.5, 400.0)
    with pytest.raises(ValueError, match="amplitude or maximum|one of"):
        fully_reversed_amplitude(100.0, "peak", -1.0, 300.0)


def test_ti_datum_is_a_maximum_stress_converted():
    """The Ti-6Al-4V datum (510 MPa at R = 0.1) is a maximum stress: the model's
    fully reversed amplitude is below the datum, not the datum itself."""
    from tactcad.vocabulary.material_library import fully_reversed_amplitude

    ti = material_grade("Ti-6Al-4V-annealed")
    assert ti.fatigue_datum_stress == "maximum" and ti.fatigue_R_ratio == pytest.approx(0.1)
    assert ti.fatigue_strength_MPa == pytest.approx(fully_reversed_amplitude(
        ti.fatigue_datum_MPa, "maximum", ti.fatigue_R_ratio, ti.ultimate_strength_MPa))
    assert ti.fatigue_strength_MPa < ti.fatigue_datum_MPa


@pytest.mark.parametrize("example", ["macro_array", "grasper_jaw_10mm"])
def test_an_unknown_grade_is_the_one_refusal_not_the_e_and_nu_it_would_supply(example):
    # a stacked array's file and a comb's, neither stating E nor nu: the grade gives them, so
    # an unknown grade is refused for itself, not also as a missing E and nu
    import tomllib
    from pathlib import Path

    from tactcad.design.array_plan import validate_design

    file = Path(__file__).resolve().parents[2] / "hardware" / example / f"{example}.toml"
    data = tomllib.loads(file.read_text())
    for key in ("youngs_modulus_MPa", "poisson_ratio"):
        data["material"].pop(key, None)
    assert not validate_design(data, file.name)[1].errors  # the grade supplies them
    data["material"]["grade"] = "unobtainium"
    errors = validate_design(data, file.name)[1].errors
    assert [(e.field, e.value) for e in errors] == [("material.grade", "unobtainium")]
    assert all(g in errors[0].allowed for g in REQUIRED_GRADES)
