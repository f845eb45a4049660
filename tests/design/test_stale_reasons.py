"""A reason ``tactcad design`` writes under ``[assumptions]`` records the value it was
written for; after a hand edit of that value the outputs show the reason as no longer
applying, and a file without the record reads as it always did. A per-element list of
the wrong length is refused with the number of values it takes."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import EXAMPLES, plan_from_dict, with_overrides
from tactcad.design.requirements_section import DERIVED_BY_DESIGN, derived_requirements
from tactcad.errors import DesignErrors
from tactcad.vocabulary.schema import (read_toml, reason_as_read, value_text,
                                       with_written_values)

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def data():
    return read_toml(GRASPER, "design file")


def _reasons(plan) -> dict:
    return dict(plan.assumptions)


def test_a_reason_records_its_value_and_an_unedited_file_shows_it_as_before(data):
    written = with_written_values(data)
    assert written["assumptions"]["sheet.thickness_mm"].endswith(" [written for 1]")
    assert written["assumptions"]["array.pitch_mm"].endswith(" [written for 4.8]")
    assert with_written_values(written) == written  # a record is replaced, never doubled
    assert _reasons(plan_from_dict(written)) == _reasons(plan_from_dict(data))


def test_an_edited_value_shows_its_reason_stale_in_the_plans_provenance(data):
    grade = {"material.grade": "The comb's material: Ti-6Al-4V-annealed, E 113800 MPa"}
    written = with_written_values({**data, "assumptions": {**data["assumptions"], **grade}})
    plan = plan_from_dict(with_overrides(written, {"array.pitch_mm": 4.9,
                                                   "material.grade": "17-4PH-H900",
                                                   "material.name": "17-4PH"}))
    why = _reasons(plan)
    assert why["array.pitch_mm"].endswith(
        "(written for 4.8; the file now states 4.9: the reason no longer applies)")
    assert "written for Ti-6Al-4V-annealed; the file now states 17-4PH-H900" in \
        why["material.grade"]
    assert why["sheet.thickness_mm"] == dict(data["assumptions"].items())[
        "sheet.thickness_mm"].strip()  # unedited: as written, without the record


def test_a_file_without_the_record_reads_unchanged(data):
    plan = plan_from_dict(with_overrides(data, {"array.pitch_mm": 4.9}))
    assert _reasons(plan)["array.pitch_mm"] == data["assumptions"]["array.pitch_mm"].strip()


def test_an_indexed_key_and_a_value_left_out():
    tables = {"arms": {"lengths_mm": [2.0, 3.0]},
              "assumptions": {"arms.lengths_mm[2]": "the second", "comb.stop_gaps_mm": "x"}}
    written = with_written_values(tables)["assumptions"]
    assert written == {"arms.lengths_mm[2]": "the second [written for 3]",
                       "comb.stop_gaps_mm": "x"}  # no value in the file: no record
    edited = {**tables, "arms": {"lengths_mm": [2.0, 3.5]}}
    assert reason_as_read("arms.lengths_mm[2]", written["arms.lengths_mm[2]"], edited) == \
        ("the second (written for 3; the file now states 3.5: the reason no longer applies)",
         False)
    assert reason_as_read("comb.stop_gaps_mm", "y [written for 1]", tables)[0].endswith(
        "the file now leaves it out: the reason no longer applies)")
    assert value_text([0.5, 5]) == "[0.5, 5]" and value_text(True) == "true"


def test_a_requirement_edited_since_design_derived_it_is_no_longer_derived():
    why = f"{DERIVED_BY_DESIGN}: 2.12 %"
    raw = with_written_values({"requirements": {"kobj_resolution_rel": 0.023},
                               "assumptions": {"requirements.kobj_resolution_rel": why}})
    assert derived_requirements(raw) == {"kobj_resolution_rel": why}
    raw["requirements"] = {"kobj_resolution_rel": 0.05}
    assert derived_requirements(raw) == {}


def test_a_per_element_list_of_the_wrong_length_names_the_number(data):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"comb.web_thicknesses_mm": [0.1]}))
    rows, columns = data["array"]["rows"], data["array"]["columns"]
    assert f"{rows} x {columns} = {rows * columns} values" in str(caught.value)


def test_verify_notes_a_reason_that_no_longer_applies(tmp_path):
    import tomli_w
    from conftest import run_cli

    from tactcad.vocabulary.schema import stale_reasons

    ti = EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"
    tables = with_written_values(read_toml(ti, "design file"))
    assert stale_reasons(tables) == {}
    key = "element.notch_radius_mm"
    edited = with_overrides(tables, {key: tables["element"]["notch_radius_mm"] + 0.05})
    assert list(stale_reasons(edited)) == [key]
    design = tmp_path / "ti_array_2x3.toml"
    design.write_text(tomli_w.dumps(edited))
    for name in ("rigs.toml", "scenes.toml", "zeroing_flat.csv"):  # the files it names
        (tmp_path / name).write_bytes((ti.parent / name).read_bytes())
    r = run_cli("verify", "--design", str(design), "--model", "closed-form")
    assert f"note: [assumptions] {key}: " in r.stdout, r.stderr
    assert "the reason no longer applies)" in r.stdout


def test_a_reason_carried_from_a_base_design_is_written_once_and_stays_stale():
    from tactcad.studies.inverse_design import with_base_named

    base = with_written_values({"sheet": {"thickness_mm": 1.0},
                                "material": {"grade": "Ti-6Al-4V-annealed"},
                                "assumptions": {"sheet.thickness_mm": "one sheet",
                                                "material.grade": "Ti, E 113800 MPa"}})
    edited = {**base, "material": {"grade": "CuBe-C17200-TF00"}}  # the lab's edit
    why = with_base_named(edited, "base.toml")["assumptions"]
    assert why["sheet.thickness_mm"] == "one sheet"
    assert why["material.grade"] == ("Ti, E 113800 MPa (written for Ti-6Al-4V-annealed; the "
                                     "file now states CuBe-C17200-TF00: the reason no longer "
                                     "applies)")


def test_a_design_written_by_design_as_a_base_keeps_its_pointer_and_one_record():
    from tactcad.studies.inverse_design import start_tables, with_base_named

    raw = read_toml(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml", "design file")
    pointer = "Kept from the base design (d1.toml), where it is an assumption."
    d2 = with_written_values({**raw, "assumptions": {**raw.get("assumptions", {}),
                                                     "material.grade": pointer}})
    d5 = with_written_values(with_base_named(start_tables(d2, "d2.toml"), "d2.toml"))
    why = d5["assumptions"]["material.grade"]
    assert why == ("Kept from the base design (d2.toml), where it is an assumption. "
                   "[written for Ti-6Al-4V-annealed]")
    assert reason_as_read("material.grade", why, d5) == (
        "Kept from the base design (d2.toml), where it is an assumption.", True)
    edited = {**d2, "material": {**d2["material"], "grade": "17-4PH-H900"}}  # by hand
    why = with_base_named(start_tables(edited, "d2.toml"), "d2.toml")["assumptions"][
        "material.grade"]
    assert why == ("Kept from the base design (d2.toml), where it is an assumption. (written "
                   "for Ti-6Al-4V-annealed; the file now states 17-4PH-H900: the reason no "
                   "longer applies)")


def test_only_the_last_record_is_read():
    from tactcad.vocabulary.schema import plain_reason

    assert plain_reason("x [written for 1.5] [written for 2]") == ("x", "2")
    assert plain_reason("x [written for [0.5, 2]]") == ("x", "[0.5, 2]")
    assert plain_reason("x [written for 1") == ("x [written for 1", None)
