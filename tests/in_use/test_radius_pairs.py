"""Units in a pivoting jaw: radii from the plan's tips, the equal-radius rule, the correction."""
import pytest

from tactcad.design.array_plan import load_design
from tactcad.in_use.jaw_kinematics import JawGeometry
from tactcad.in_use.radius_pairs import (EQUAL_RADIUS_TOLERANCE_REL, insert_frame, paired_layout,
                                         unit_radii)
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.mechanics.readout_chain import row_units
from comb_variants import row_paired_comb

DESIGNS = ["hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml",
           "hardware/ti_array_2x3/ti_array_2x3.toml"]


def units_of(plan):
    k = ladder_stiffness_by_element(plan)
    by_part = {s.geometry.part_name: k[s.number] for s in plan.slots}
    return [(r.number, m.number) for r, m in row_units(plan, by_part)]


def jaw_for(plan, behind=5.0):
    length = max(u for u, _ in insert_frame(plan).values()) + behind + 1.0
    return JawGeometry(-behind, 0.0, length, 30.0, 3.0)


@pytest.mark.parametrize("path", DESIGNS)
def test_insert_frame_runs_along_the_first_row(path):
    plan = load_design(path)
    frame = insert_frame(plan)
    first = plan.row_slots(0)
    assert frame[first[0].number] == pytest.approx((0.0, 0.0))
    assert frame[first[-1].number][1] == pytest.approx(0.0, abs=1e-9)
    assert frame[first[-1].number][0] > 0


@pytest.mark.parametrize("path", DESIGNS)
def test_the_rule_puts_every_laid_unit_at_one_radius(path):
    plan = load_design(path)
    units = units_of(plan)
    jaw = jaw_for(plan)
    layout = paired_layout(plan, units)
    assert layout.sites
    positions = {}
    pairs = []
    for i, s in enumerate(layout.sites):
        positions[2 * i], positions[2 * i + 1] = s.reference_uv_mm, s.measuring_uv_mm
        pairs.append((2 * i, 2 * i + 1))
    for u in unit_radii(jaw, positions, pairs):
        assert u.equal and abs(u.ratio - 1) <= EQUAL_RADIUS_TOLERANCE_REL


def test_the_comb_paired_along_its_rows_fails_equal_radius_and_corrects_by_the_radii():
    plan = row_paired_comb()
    radii = unit_radii(jaw_for(plan), insert_frame(plan), units_of(plan))
    assert radii and not any(u.equal for u in radii)
    for u in radii:
        assert u.r_correction == pytest.approx(u.r_reference_mm / u.r_measuring_mm)


def test_the_shipped_comb_pairs_every_unit_at_one_radius():
    plan = load_design(DESIGNS[0])
    radii = unit_radii(jaw_for(plan), insert_frame(plan), units_of(plan))
    assert plan.pairing == "column" and len(radii) == plan.columns
    assert all(u.equal for u in radii)


def test_more_units_than_sites_are_listed_with_the_reason():
    plan = row_paired_comb()
    units = units_of(plan)
    layout = paired_layout(plan, units)
    assert len(layout.sites) == plan.columns * (plan.rows // 2)
    assert len(layout.sites) + len(layout.unplaced) == len(units)
    assert "pair sites" in layout.reason


def test_along_the_rows_each_unit_spans_one_pitch_of_radius():
    from tactcad.in_use.radius_pairs import along_row_layout

    plan = load_design(DESIGNS[0])  # the comb, paired by column
    units = units_of(plan)
    layout = along_row_layout(plan, units)
    assert layout.sites and not layout.unplaced
    rows = {s.number: s.row for s in plan.slots}
    jaw = jaw_for(plan)
    frame = insert_frame(plan)
    for s in layout.sites:
        assert rows[s.reference_site] == rows[s.measuring_site]  # side by side on one row
        (radii,) = unit_radii(jaw, frame, [(s.reference_site, s.measuring_site)])
        assert radii.r_measuring_mm - radii.r_reference_mm == pytest.approx(plan.pitch_mm)
        assert not radii.equal
    # a row's reference shared by two measuring elements: fewer disjoint sites than units
    plan = load_design(DESIGNS[1])
    layout = along_row_layout(plan, units_of(plan))
    assert len(layout.sites) == 2 and len(layout.unplaced) == 2 and "2 pair sites" in layout.reason


def test_a_single_column_has_nothing_to_lay_along_its_rows():
    from tactcad.design.array_plan import plan_from_dict, read_toml
    from tactcad.in_use.radius_pairs import along_row_layout

    d = read_toml(DESIGNS[0], "design file")  # a comb: a stacked array has two columns or more
    columns = d["array"]["columns"]
    d["array"]["columns"], d["array"]["pitch_mm"] = 1, 16.0  # a row long enough to clamp
    for table, key in (("arms", "lengths_mm"), ("comb", "web_thicknesses_mm"),
                       ("comb", "stop_gaps_mm")):
        d[table][key] = d[table][key][:1] + d[table][key][columns:columns + 1]
    d["arms"]["reference_elements"] = [1]
    plan = plan_from_dict(d)
    layout = along_row_layout(plan, [(1, 2)])
    assert layout.sites == () and layout.unplaced == ((1, 2),)
    assert "single column" in layout.reason


def test_a_unit_with_no_site_along_the_rows_is_named_with_why_not_dropped():
    # a 2 x 5 comb: each row's fifth tip has no neighbour, so unit 5/10 is not laid
    from tactcad.design.array_plan import plan_from_dict, with_overrides
    from tactcad.in_use.radius_pairs import along_row_layout
    from comb_variants import COMB, comb_data

    data = comb_data()
    arms, webs = data["arms"]["lengths_mm"], data["comb"]["web_thicknesses_mm"]
    gaps = data["comb"]["stop_gaps_mm"]
    five = {"array.columns": 5, "arms.lengths_mm": arms[:5] + arms[6:11],
            "arms.reference_elements": [1, 2, 3, 4, 5],
            "comb.web_thicknesses_mm": webs[:5] + webs[6:11],
            "comb.stop_gaps_mm": gaps[:5] + gaps[6:11]}
    plan = plan_from_dict(with_overrides(data, five), source=COMB, file=COMB)
    units = units_of(plan)
    layout = along_row_layout(plan, units)
    assert len(layout.sites) == 4 and len(layout.unplaced) == 1
    assert "no neighbour" in layout.reason and "5 columns" in layout.reason
