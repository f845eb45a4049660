"""Shop DXF: one file per distinct profile, nested sheets, CIRCLE holes,
extents, lead-ins, part marks and the R12 variant, each read back from the file."""

from __future__ import annotations

import ezdxf
import pytest

from tactcad.checks.dxf_readback import read_dxf
from tactcad.checks.dxf_shop import check_shop_dxf_files
from tactcad.checks.check_result import failures
from tactcad.errors import DesignError
from tactcad.export.dxf_sheet import (DXF_VERSION_ENV, profile_dxf_name, sheet_dxf_name, shelf_layout,
                                      shop_profiles, write_shop_dxf_files)


@pytest.fixture(scope="module", params=["R2010", "R12"])
def shop(request, plan, tmp_path_factory):
    out = tmp_path_factory.mktemp(f"dxf_{request.param}")
    records = write_shop_dxf_files(plan, out, lambda s: None, request.param)
    return request.param, out, records


def test_one_file_per_distinct_profile_with_its_quantity(plan, shop):
    _, out, records = shop
    profiles = [r for r in records if r["kind"] == "dxf-profile"]
    assert [r["part"] for r in profiles] == list(plan.distinct_elements) + ["spacer"]
    for r in profiles:
        assert r["path"] == profile_dxf_name(r["part"], r["quantity"])
    assert sum(r["quantity"] for r in profiles if r["part"].startswith("element_")) == len(plan.slots)
    assert {r["part"]: r["quantity"] for r in profiles}["spacer"] == len(plan.spacer_placements)
    sheets = [r["path"] for r in records if r["kind"] == "dxf-sheet"]
    assert sheets == [sheet_dxf_name("aluminium", 3.0), sheet_dxf_name("aluminium", 1.0)]
    assert {p.relative_to(out).as_posix() for p in out.rglob("*.dxf")} == {r["path"] for r in records}


@pytest.mark.slow
def test_every_shop_check_passes_on_the_files(plan, shop):
    _, out, _ = shop
    results = check_shop_dxf_files(plan, out)
    assert not failures(results), "\n".join(r.line() for r in failures(results))
    sheet_checks = {r.check for r in results if r.subject.startswith("sheet_")}
    assert {"sheet_gap", "sheet_copies", "dxf_web_thickness", "dxf_lead_in", "dxf_part_marks"} <= sheet_checks


def test_holes_are_circles_and_extents_are_real(plan, shop):
    version, out, _ = shop
    doc = ezdxf.readfile(out / "dxf/element_a4mm_qty2.dxf")
    cut = [e for e in doc.modelspace() if e.dxf.layer == "CUT"]
    outline = "POLYLINE" if version == "R12" else "LWPOLYLINE"
    assert sorted(e.dxftype() for e in cut) == ["CIRCLE", "CIRCLE", outline]
    g = plan.element(1).geometry
    lo, hi = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
    assert hi[0] == pytest.approx(g.overall_length_mm)
    assert hi[1] == pytest.approx(g.tip_top_y_mm)
    assert lo[0] < 0  # the outer lead-in starts outside the part
    if version == "R12":
        assert doc.dxfversion == "AC1009" and "LWPOLYLINE" not in {e.dxftype() for e in doc.modelspace()}
    else:
        assert doc.header["$INSUNITS"] == 4
        assert doc.header.custom_vars.get("QUANTITY") == "2"


def test_marks_name_every_element_copy(plan, shop):
    _, out, _ = shop
    marks = read_dxf(out / sheet_dxf_name("aluminium", 3.0)).marks
    arms = {s.number: s.geometry.arm_length_mm for s in plan.slots}
    assert sorted(marks) == sorted(f"E{n} A{a:g}" for n, a in arms.items())


def test_same_plan_writes_identical_dxf_bytes(plan, shop, tmp_path):
    version, out, records = shop
    write_shop_dxf_files(plan, tmp_path, lambda s: None, version)
    for r in records:
        assert (tmp_path / r["path"]).read_bytes() == (out / r["path"]).read_bytes(), r["path"]


@pytest.mark.slow
def test_lead_in_on_the_web_fails(plan, tmp_path):
    write_shop_dxf_files(plan, tmp_path, lambda s: None, "R2010")
    path = tmp_path / "dxf/element_a4mm_qty2.dxf"
    doc = ezdxf.readfile(path)
    g = plan.element(1).geometry
    lead = next(e for e in doc.modelspace() if e.dxftype() == "LINE" and e.dxf.end[0] == 0.0)
    lead.dxf.end = (g.hinge_x_mm - g.notch_radius_mm, g.notch_centre_y_mm)  # on the notch wall
    doc.saveas(path)
    bad = {r.check for r in check_shop_dxf_files(plan, tmp_path) if not r.passed}
    assert "dxf_lead_in" in bad


@pytest.mark.slow
def test_overlapping_sheet_and_wrong_extents_fail(plan, tmp_path):
    write_shop_dxf_files(plan, tmp_path, lambda s: None, "R2010")
    path = tmp_path / sheet_dxf_name("aluminium", 1.0)
    doc = ezdxf.readfile(path)
    outlines = [e for e in doc.modelspace() if e.dxftype() == "LWPOLYLINE"]
    pts = [(x + 1.0, y, b) for x, y, b in outlines[1].get_points("xyb")]
    outlines[1].set_points(pts, format="xyb")  # 1 mm towards its neighbour: gap below the rule
    doc.modelspace().dxf.extmax = (1e20, 1e20, 0)  # ezdxf writes the layout's extents
    doc.saveas(path)
    bad = {(r.check, r.subject) for r in check_shop_dxf_files(plan, tmp_path) if not r.passed}
    assert ("sheet_gap", "sheet_aluminium_1mm.dxf") in bad
    assert ("dxf_extents", "sheet_aluminium_1mm.dxf") in bad


def test_shelf_layout_keeps_the_gap():
    import shapely.geometry as sg

    sizes = [(10.0, 5.0), (3.0, 8.0), (7.0, 7.0), (12.0, 2.0), (4.0, 4.0)]
    corners = shelf_layout(sizes, 2.5, row_width_mm=20.0)
    boxes = [sg.box(x, y, x + w, y + h) for (x, y), (w, h) in zip(corners, sizes)]
    assert min(a.distance(b) for i, a in enumerate(boxes) for b in boxes[:i]) >= 2.5 - 1e-12
    assert min(x for x, _ in corners) == 2.5 and min(y for _, y in corners) == 2.5


def test_unknown_dxf_version_is_a_design_error(plan, tmp_path, monkeypatch):
    monkeypatch.setenv(DXF_VERSION_ENV, "R14")
    with pytest.raises(DesignError, match="R2010 or R12"):
        write_shop_dxf_files(plan, tmp_path, lambda s: None)


def test_spacer_gets_start_holes_and_no_web(plan):
    spacer = next(sp for sp in shop_profiles(plan) if sp.part == "spacer")
    assert len(spacer.profile.start_holes) == len(spacer.profile.holes) > 0
    assert spacer.web_thickness_mm is None


def test_the_shop_files_name_the_material_as_the_bom_does(plan, tmp_path):
    """Every DXF header's MATERIAL is the BOM's material with alloy and temper."""
    import ezdxf

    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.catalogue.shop import material_designation
    from tactcad.export.dxf_sheet import shop_profiles, write_shop_dxf_files

    (tmp_path / "dxf").mkdir()
    write_shop_dxf_files(plan, tmp_path, lambda line: None)
    specs = array_parts(plan)
    for sp in shop_profiles(plan):
        doc = ezdxf.readfile(tmp_path / sp.file_name)
        assert doc.header.custom_vars.get("MATERIAL") == material_designation(specs[sp.part], plan)
        assert "EN AW-" in doc.header.custom_vars.get("MATERIAL")


def _slotted_block(slot_mm: float) -> "Profile":
    """A 20 x 10 mm block (CCW) with a 12 mm deep slot ``slot_mm`` wide cut in from its
    right side: the slot's long edges are the longest edges farthest from (0, 0)."""
    from tactcad.geometry.profile import Line, Profile
    y0, y1 = 5 - slot_mm / 2, 5 + slot_mm / 2
    pts = [(0, 0), (20, 0), (20, y0), (8, y0), (8, y1), (20, y1), (20, 10), (0, 10)]
    return Profile(tuple(Line(a, b) for a, b in zip(pts, pts[1:] + pts[:1])), (), ())


#: Points on the block's outside faces and one at the slot's end: the lead-in's entry keeps
#: away from them, so the slot's long edges rank first.
FACES = ([(x, 0.0) for x in range(21)] + [(x, 10.0) for x in range(21)]
         + [(0.0, y) for y in range(11)] + [(7.0, 5.0)])


@pytest.mark.parametrize("slot_mm", [0.4, 0.99, 3.0])
def test_the_outer_lead_in_starts_outside_the_part_and_runs_clear_of_it(slot_mm):
    # a slot narrower than the lead-in put the start in the part across it (a long comb row)
    import shapely.geometry as sg
    from tactcad.export.dxf_sheet import LEAD_IN_MM, outer_lead_in
    from tactcad.geometry.profile import contour_points
    profile = _slotted_block(slot_mm)
    lead = outer_lead_in(profile, keep_out=FACES)
    part = sg.Polygon(contour_points(profile.outer))
    assert part.exterior.distance(sg.Point(lead.entry)) < 1e-9
    assert part.distance(sg.Point(lead.start)) > LEAD_IN_MM * 0.1, lead
    assert abs(math_dist(lead.start, lead.entry) - LEAD_IN_MM) < 1e-9
    across_the_slot = lead.entry[0] > 8 and abs(abs(lead.entry[1] - 5) - slot_mm / 2) < 1e-9
    assert across_the_slot == (slot_mm > LEAD_IN_MM), lead  # a long edge only with room


def test_a_contour_with_no_straight_edge_is_refused():
    from tactcad.export.dxf_sheet import outer_lead_in
    from tactcad.geometry.profile import Arc, Profile
    disc = Profile((Arc((1, 0), (-1, 0), (0, 0), True), Arc((-1, 0), (1, 0), (0, 0), True)), (), ())
    with pytest.raises(ValueError, match="no straight edge"):
        outer_lead_in(disc, keep_out=[])


def math_dist(a, b) -> float:
    return ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5
