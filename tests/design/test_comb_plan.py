"""The monolithic comb's derivation: it fits the grasper's jaw, every cut
is at least the wire's slot, the fasteners come from the ISO tables, and its
elements are profiles the mechanics read as the stacked array's."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import EXAMPLES, plan_from_dict, with_overrides
from tactcad.design.comb_plan import MIN_SET_GAP_MM
from tactcad.errors import DesignErrors
from tactcad.geometry.profile import Arc
from tactcad.mechanics.closed_form import estimate_closed_form
from tactcad.partlib.array.comb_sheet import comb_profile
from tactcad.vocabulary.schema import read_toml
from tactcad.vocabulary.standards import DOWEL_PINS, MINIATURE_SCREWS

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def data():
    return read_toml(GRASPER, "design file")


@pytest.fixture(scope="module")
def plan(data):
    return plan_from_dict(data)


def test_the_comb_fits_the_stated_footprint(plan, data):
    across, along, _ = plan.comb.envelope_mm
    x, y = data["requirements"]["footprint_mm"]
    assert plan.construction == "monolithic-comb"
    assert across <= x and along <= y


def test_every_cut_is_at_least_the_wire_slot(plan):
    slot = plan.edm.min_slot_width_mm
    for sheet in plan.comb.sheets:
        for e, x0, ledge in zip(sheet.elements, sheet.offsets_mm, sheet.ledges_mm):
            assert plan.pitch_mm - e.overall_length_mm >= slot - 1e-9  # slot after the tip
            assert 2 * e.notch_radius_mm >= slot                        # the notch
            assert e.arm_underside_y_mm - ledge >= slot - 1e-9          # the stop gap as cut


def test_the_fasteners_come_from_the_iso_tables(plan):
    c = plan.comb
    assert c.screw is MINIATURE_SCREWS[c.screw.size]
    assert c.screw_length_mm in c.screw.catalogue_lengths_mm
    assert c.dowel_length_mm in DOWEL_PINS[c.dowel_diameter_mm]
    sheet = plan.comb.sheets[0]
    head = max(c.screw.head_diameter_mm, c.screw.nut_across_corners_mm)
    assert head < sheet.spine_height_mm  # head and nut stay below the arms
    for hole in sheet.holes:  # a ligament to the row's ends
        assert hole.diameter_mm / 2 < hole.x_mm < sheet.length_mm - hole.diameter_mm / 2


def test_a_pitch_too_short_for_the_longest_element_is_refused(data):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"array.pitch_mm": 4.3}))
    fields = [e.field for e in caught.value.errors]
    arms = data["arms"]["lengths_mm"]
    longest = arms.index(max(arms)) + 1
    assert f"arms.lengths_mm[{longest}]" in fields


def test_a_footprint_the_comb_does_not_fit_is_refused(data):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"requirements.footprint_mm": [8.0, 25.0]}))
    assert caught.value.field == "requirements.footprint_mm[2]"


def test_a_stop_gap_below_the_thinnest_shim_is_refused(data):
    gaps = list(data["comb"]["stop_gaps_mm"])
    gaps[0] = MIN_SET_GAP_MM / 2
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"comb.stop_gaps_mm": gaps}))
    assert caught.value.field == "comb.stop_gaps_mm[1]"


def test_a_combs_web_list_refused_names_a_webs_range_in_mm(data):
    """A word where the webs go is refused naming what one web takes (it said "(mm)")."""
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"comb.web_thicknesses_mm": "thin"}))
    assert caught.value.field == "comb.web_thicknesses_mm"
    assert "one web per element, each 0.05 ... 1 mm" in str(caught.value)
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"comb.stop_gaps_mm": "wide"}))
    assert "one gap per element, each > 0 ... 1 mm" in str(caught.value)


def test_a_comb_gives_its_webs_one_way_not_both(data):
    """A shared web beside each element's would be read by nothing: refused, naming it; each
    element's alone, or one web for all alone, is a comb."""
    import copy

    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"element.web_thickness_mm": 0.3}))
    assert caught.value.field == "element.web_thickness_mm"
    assert "comb.web_thicknesses_mm" in str(caught.value)
    shared = copy.deepcopy(data)
    del shared["comb"]["web_thicknesses_mm"]
    shared["element"]["web_thickness_mm"] = 0.12
    assert {g.web_thickness_mm for g in plan_from_dict(shared).distinct_elements.values()} \
        == {0.12}
    neither = copy.deepcopy(shared)
    del neither["element"]["web_thickness_mm"]
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(neither)
    assert caught.value.field == "comb.web_thicknesses_mm"


def test_the_stacked_tables_are_refused_under_the_comb(data):
    stacked = read_toml(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml", "design file")
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(stacked, {"array.construction": "monolithic-comb"}))
    assert "comb" in {e.field.split(".")[0] for e in caught.value.errors}


def test_the_two_rows_tips_of_a_column_share_their_distance_along_the_row(plan):
    for c in range(plan.columns):
        a, b = plan.slots[c], plan.slots[plan.columns + c]
        assert a.tip_centre_world_mm[2] == pytest.approx(b.tip_centre_world_mm[2])
        assert a.tip_centre_world_mm[1] == pytest.approx(b.tip_centre_world_mm[1])
        assert a.tip_centre_world_mm[0] < 0 < b.tip_centre_world_mm[0]


def test_the_mechanics_read_the_comb_elements_and_reach_the_ratio(plan, data):
    k = {s.number: estimate_closed_form(s.geometry, plan.material).stiffness_N_per_mm
         for s in plan.slots}
    reference, measuring = plan.unit_pairs[0]
    ratio = k[reference] / k[measuring]
    assert ratio == pytest.approx(data["requirements"]["kr_over_km"], rel=0.05)


def test_the_comb_outline_is_one_closed_contour_over_the_row(plan):
    sheet = plan.comb.sheets[0]
    prof = comb_profile(sheet)
    x0, y0, x1, y1 = prof.bbox_mm
    assert (x0, y0) == pytest.approx((0.0, 0.0))
    assert x1 == pytest.approx(sheet.length_mm)
    assert y1 == pytest.approx(sheet.elements[0].tip_top_y_mm)
    notches = [s for s in prof.outer if isinstance(s, Arc) and s.radius == pytest.approx(
        sheet.elements[0].notch_radius_mm)]
    assert len(notches) == len(sheet.elements)
    for a, b in zip(prof.outer, prof.outer[1:] + prof.outer[:1]):
        assert a.end == pytest.approx(b.start)
    assert len(prof.holes) == len(sheet.holes)


def test_the_comb_sheets_dxf_reads_back_and_meets_the_wire_rules(plan, tmp_path):
    from tactcad.checks.dxf_readback import check_profile_dxf
    from tactcad.export.dxf import write_profile_dxf

    for sheet in plan.comb.sheets:
        prof = comb_profile(sheet)
        path = write_profile_dxf(tmp_path / f"{sheet.part_name}.dxf", prof, sheet.part_name)
        thinnest = min(e.web_thickness_mm for e in sheet.elements)
        results = check_profile_dxf(path, sheet.part_name, prof.area_mm2, prof.bbox_mm, plan.edm,
                                    web_thickness_mm=thinnest, lead_ins=False)
        assert [r.line() for r in results if not r.passed] == []
        assert any(r.check == "edm_inside_radius" for r in results)


def test_a_pitch_without_room_for_the_fillet_at_the_next_post_is_refused(data):
    # the slot after the longest element (0.2 mm) is wider than the wire's; a
    # fillet of 0.25 mm at the next post would reach under the arm's end
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"element.inside_corner_radius_mm": 0.25,
                                             "element.tip_height_mm": 0.8}))
    arms = data["arms"]["lengths_mm"]
    assert f"arms.lengths_mm[{arms.index(max(arms)) + 1}]" in [e.field for e in caught.value.errors]


def test_column_pairing_reads_each_measuring_element_against_the_reference_beside_it(plan):
    assert plan.pairing == "column"
    for reference, measuring in plan.unit_pairs:
        r, m = plan.element(reference), plan.element(measuring)
        assert r.column == m.column and r.row != m.row
        assert r.tip_centre_world_mm[2] == pytest.approx(m.tip_centre_world_mm[2])


def test_every_comb_tip_lies_at_one_place_in_its_cell_whatever_its_arm(data):
    p = plan_from_dict(with_overrides(data, {"arms.lengths_mm": [2.0, 2.5, 3.0, 2.0, 2.5, 3.0] * 2,
                                             "comb.web_thicknesses_mm": [0.15] * 12}))
    z = [s.tip_centre_world_mm[2] for s in p.row_slots(0)]
    steps = [b - a for a, b in zip(z, z[1:])]
    assert steps == pytest.approx([p.pitch_mm] * (p.columns - 1))


@pytest.mark.parametrize("refs, field", [
    ([1, 7], "arms.reference_elements"),              # one per row is the row pairing's form
    ([1, 2, 3, 4, 5, 12], "arms.reference_elements"),  # not one row's elements
])
def test_column_pairing_refuses_references_that_are_not_one_row(data, refs, field):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"arms.reference_elements": refs}))
    assert caught.value.errors[0].field == field
    assert "[1, 2, 3, 4, 5, 6] or [7, 8, 9, 10, 11, 12]" in caught.value.errors[0].allowed


def test_column_pairing_left_unnamed_takes_the_row_of_shorter_arms(data):
    d = with_overrides(data, {"arms.lengths_mm": [3.0] * 6 + [2.0] * 6,
                              "comb.web_thicknesses_mm": [0.08] * 6 + [0.15] * 6})
    d["arms"].pop("reference_elements")
    p = plan_from_dict(d)
    assert p.references == (7, 8, 9, 10, 11, 12) and "row 2" in p.references_reason


def test_an_unknown_pairing_is_refused_naming_the_choices(data):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"array.pairing": "diagonal"}))
    assert caught.value.errors[0].field == "array.pairing"
    assert "row" in caught.value.errors[0].allowed and "column" in caught.value.errors[0].allowed


@pytest.mark.parametrize("process, field, words", [
    ("photochemical-etching", "comb.web_thicknesses_mm", "photochemical-etching on a 1 mm sheet"),
    ("laser-cutting", "element.web_tolerance_mm", "what laser-cutting holds"),
])
def test_rows_a_process_cannot_cut_are_refused_when_read_naming_its_limit(data, process, field,
                                                                          words):
    """The rows' ``[element] process`` shapes and judges the comb as the ``process`` check
    does: the shipped 1 mm wire-cut comb, asked etched or laser cut, is refused."""
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(data, {"element.process": process}))
    hit = [e for e in caught.value.errors if e.field == field]
    assert hit and words in hit[0].allowed, [str(e) for e in caught.value.errors]


def _etched(data):
    """The shipped comb etched from 0.15 mm foil: webs 0.2 mm (no thinner than the foil),
    the measuring arms 0.1 mm shorter for the etch's wider slot."""
    n = len(data["comb"]["web_thicknesses_mm"])
    arms = [min(a, 2.9) for a in data["arms"]["lengths_mm"]]
    return with_overrides(data, {"element.process": "photochemical-etching",
                                 "sheet.thickness_mm": 0.15, "element.web_tolerance_mm": 0.03,
                                 "readout.grid_width_mm": 0.15,  # the grid fits the foil's face
                                 "comb.web_thicknesses_mm": [0.2] * n, "arms.lengths_mm": arms})


def test_the_rows_process_gives_the_slot_and_the_sheet_part_its_process(data):
    """Etched from 0.15 mm foil (webs as thick as the foil, holes 1.5 x the thickness), the
    comb's slots follow the etch's narrowest slot, not the wire's, and the row sheets are
    etched parts (their DXF is etch artwork)."""
    from tactcad.export.dxf_sheet import shop_profiles

    plan = plan_from_dict(_etched(data))
    slot = 1.5 * 0.15  # Ti is not among the alloys the etch guides list: 1.5 x thickness
    for sheet in plan.comb.sheets:
        for e in sheet.elements:
            assert plan.pitch_mm - e.overall_length_mm >= slot - 1e-9
            assert e.process == "photochemical-etching"
    rows = [sp for sp in shop_profiles(plan) if sp.part.startswith("comb_row")]
    assert rows and {sp.process for sp in rows} == {"photochemical-etching"}


def test_the_envelope_reaches_a_dowel_pin_longer_than_the_screws_reach(data):
    """Thin rows take a stock pin longer than the stack: the envelope across the rows
    holds the pin's ends, centred on the stack (it was the screw's head to its end)."""
    thin = plan_from_dict(_etched(data))
    c = thin.comb
    assert c.dowel_length_mm > 2 * 0.15 + c.spacer_thickness_mm
    lo = c.envelope_from_x_mm
    assert lo <= -c.dowel_length_mm / 2 + 1e-9
    assert lo + c.envelope_mm[0] >= c.dowel_length_mm / 2 - 1e-9
    assert c.envelope_centre_mm[0] == pytest.approx(lo + c.envelope_mm[0] / 2)
