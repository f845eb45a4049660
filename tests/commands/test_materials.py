"""The materials library on the command line, grade names matched where only one fits, and
a material said once in the drawings and the BOM."""

from __future__ import annotations

import json

import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.catalogue.shop import material_designation
from tactcad.cli import main
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
from tactcad.vocabulary.material_library import material_grade, material_grades
from tactcad.errors import DesignError


def test_materials_json_lists_every_grade_with_its_values_and_sources(capsys):
    assert main(["materials", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [g["grade"] for g in out["grades"]] == list(material_grades())
    for g in out["grades"]:
        lib = material_grade(g["grade"])
        assert g["youngs_modulus_MPa"] == lib.youngs_modulus_MPa
        assert g["yield_strength_MPa"] == lib.yield_strength_MPa
        assert {"youngs_modulus_MPa", "yield_strength_MPa", "fatigue_strength_MPa"} <= set(
            g["sources"])
    assert {g["gauge"] for g in out["gauges"]} >= {"constantan-foil"}


@pytest.mark.parametrize("text, grade", [
    ("Ti-6Al-4V-annealed", "Ti-6Al-4V-annealed"), ("ti-6al-4v-annealed", "Ti-6Al-4V-annealed"),
    ("ti-6al", "Ti-6Al-4V-annealed"), ("6061", "6061-T6"), ("17-4ph-h900", "17-4PH-H900")])
def test_grade_matched_without_regard_to_case_where_one_fits(text, grade):
    assert material_grade(text).name == grade


@pytest.mark.parametrize("text", ["aluminium", "Titanium", "unobtainium", ""])
def test_unknown_grade_is_refused_naming_the_grades(text):
    with pytest.raises(DesignError) as exc:
        material_grade(text)
    assert exc.value.field == "material.grade"
    assert all(g in exc.value.allowed for g in material_grades())


def test_file_grade_without_modulus_is_refused_on_the_grade_not_a_missing_key():
    data = with_overrides(default_design_data(), {})
    data["material"] = {"name": "x", "grade": "Titanum"}
    with pytest.raises(DesignError) as exc:
        plan_from_dict(data)
    fields = [e.field for e in exc.value.errors] if hasattr(exc.value, "errors") else [
        exc.value.field]
    assert fields == ["material.grade"]


def test_design_material_option_takes_a_spelling_and_refuses_an_unknown_one(tmp_path, capsys):
    argv = ["design", "--kr-over-km", "4", "--kobj-range", "2", "10", "--full-scale-force", "0.1",
            "--verify", "none",
            "--out", str(tmp_path / "d.toml"), "--json"]
    assert main([*argv, "--material", "unobtainium"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert "--material" in err["message"] and "Ti-6Al-4V-annealed" in err["message"]


def test_a_material_named_as_its_grade_is_said_once():
    data = default_design_data()
    data["material"] = {"name": "Ti-6Al-4V-annealed", "grade": "Ti-6Al-4V-annealed"}
    plan = plan_from_dict(data)
    spec = array_parts(plan)[plan.element(1).geometry.part_name]
    assert material_designation(spec, plan) == "Ti-6Al-4V-annealed"
    assert material_designation(array_parts(plan_from_dict(default_design_data()))["spacer"],
                                plan_from_dict(default_design_data())) == "aluminium EN AW-6061-T6"


def test_materials_lists_each_grades_modulus_coefficient_and_marks_a_stand_in(capsys):
    from tactcad.cli import main
    from tactcad.vocabulary.material_library import material_grades

    assert main(["materials"]) == 0
    text = capsys.readouterr().out
    assert "dE/E dT 1/K" in text
    for g in material_grades().values():
        row = next(line for line in text.splitlines() if line.startswith(f"| {g.name} |"))
        assert ("(unsourced)" in row) != g.is_sourced("youngs_modulus_tc_per_K")
    assert main(["materials", "--json"]) == 0
    grades = {g["grade"]: g for g in json.loads(capsys.readouterr().out)["grades"]}
    assert grades["6061-T6"]["youngs_modulus_tc_per_K"] < 0
    assert "youngs_modulus_tc_per_K" in grades["7075-T6"]["unsourced"]  # 6061's stands in
    assert "youngs_modulus_tc_per_K" in grades["CuBe-C17200-TF00"]["sources"]
