"""Shop DXF sheets are grouped by grade and thickness: two grades of one
family at one thickness get a sheet each (tactcad.export.dxf_sheet)."""

from __future__ import annotations

import copy

from tactcad.catalogue.files import sheet_dxf_name, sheet_material_names
from tactcad.design.array_plan import plan_from_dict
from tactcad.export.dxf_sheet import sheets, write_shop_dxf_files


def test_one_grade_per_family_and_thickness_keeps_the_family_name():
    cuts = [("aluminium", "aluminium EN AW-6061-T6", 3.0), ("aluminium", "aluminium EN AW-6061-T6", 1.0),
            ("aluminium", "aluminium EN AW-7075-T6", 1.0), ("titanium", "", 3.0)]
    assert sheet_material_names(cuts) == ["aluminium", "aluminium EN AW-6061-T6",
                                          "aluminium EN AW-7075-T6", "titanium"]


def test_two_grades_of_one_family_at_one_thickness_get_two_sheets(design_data, tmp_path):
    data = copy.deepcopy(design_data)
    data["array"]["pitch_mm"] = 6.0                 # spacer 6 - 3 = 3 mm, as thick as the elements
    data["array"]["columns"] = 3                    # so the M2 bolts still reach
    data["arms"]["lengths_mm"] = [4.0, 6.0, 8.0, 4.0, 6.0, 8.0]
    data["arms"].pop("reference_elements", None)
    data["clamp"]["spacer_material"] = "7075-T6"    # elements are 6061-T6
    plan = plan_from_dict(data)
    groups = sheets(plan)
    assert sorted(groups) == [("aluminium EN AW-6061-T6", 3.0), ("aluminium EN AW-7075-T6", 3.0)]
    assert [sp.part for sp in groups[("aluminium EN AW-7075-T6", 3.0)]] == ["spacer"]
    (tmp_path / "dxf").mkdir()
    records = write_shop_dxf_files(plan, tmp_path, log=lambda s: None)
    sheet_files = sorted(r["path"] for r in records if r["kind"] == "dxf-sheet")
    assert sheet_files == sorted(sheet_dxf_name(m, t) for m, t in groups)
    assert all((tmp_path / f).is_file() for f in sheet_files)
    # the element drawing's note names the element's own sheet
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.drawings.part_sets import sheet_dxf_of

    specs = array_parts(plan)
    assert sheet_dxf_of(plan, specs["spacer"]) == sheet_dxf_name("aluminium EN AW-7075-T6", 3.0)
    element = next(s for n, s in specs.items() if n.startswith("element_"))
    assert sheet_dxf_of(plan, element) == sheet_dxf_name("aluminium EN AW-6061-T6", 3.0)


def test_the_shipped_example_keeps_its_family_named_sheets(plan):
    assert sorted(sheets(plan)) == [("aluminium", 1.0), ("aluminium", 3.0)]
