"""The comb sheet as a part: the comb's plan makes one part per row, the
stacked plan none, and each builds into one valid solid of its outline's
area times the sheet."""

from __future__ import annotations

import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.design.array_plan import EXAMPLES, load_design
from tactcad.partlib.array.comb_sheet import build, comb_profile

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def plan():
    return load_design(GRASPER)


def test_the_comb_plan_makes_one_sheet_per_row_its_hardware_and_no_stacked_part(plan):
    # the strain gauges are any construction's; nothing of the stack's (its spacer,
    # clamp plates, M2+ bolts)
    names = sorted(array_parts(plan))
    assert [n for n in names if n.startswith("comb_row")] == ["comb_row1", "comb_row2"]
    assert {"comb_spacer", "strain_gauge"} <= set(names)
    assert any(n.startswith("dowel_pin_") for n in names)
    assert not {"spacer", "clamp_plate"} & set(names)


def test_the_comb_hardware_sits_in_the_sheets_holes(plan):
    from tactcad.catalogue.array_catalogue import array_instances

    placed = {i.name: i for i in array_instances(plan)}
    c = plan.comb
    for k, z in enumerate(c.screw_x_mm, start=1):
        for name in (f"screw_{k}", f"nut_{k}"):
            x, y, zz = placed[name].placement.apply(0.0, 0.0, 0.0)
            assert (y, zz) == pytest.approx((c.fastener_y_mm, z))
        # the head under row 1's outer face, the nut on row 2's
        assert placed[f"screw_{k}"].placement.apply(0, 0, 0)[0] == pytest.approx(
            -(c.spacer_thickness_mm / 2 + plan.sheet_thickness_mm))
        assert placed[f"screw_{k}"].placement.apply(0, 0, 1)[0] > \
            placed[f"screw_{k}"].placement.apply(0, 0, 0)[0]  # the shank runs to row 2
    for k, z in enumerate(c.dowel_x_mm, start=1):
        ends = [placed[f"dowel_{k}"].placement.apply(0, 0, t)[0] for t in (0.0, c.dowel_length_mm)]
        assert ends[0] == pytest.approx(-ends[1])  # centred on the stack
        holes = {round(h.x_mm, 9) for h in c.sheets[0].holes}
        assert round(z, 9) in holes


def test_the_stacked_plan_makes_no_comb_sheet():
    names = array_parts(load_design(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"))
    assert not any(n.startswith("comb_") for n in names)


def test_each_sheet_builds_one_valid_solid_of_its_outline(plan):
    from tactcad.kernel.inspect import bbox_tuple, is_valid, solid_count, volume

    sheet = plan.comb.sheets[0]
    solid = build(sheet)
    prof = comb_profile(sheet)
    assert is_valid(solid) and solid_count(solid) == 1
    assert volume(solid) == pytest.approx(prof.area_mm2 * sheet.thickness_mm, rel=1e-6)
    x0, y0, z0, x1, y1, z1 = bbox_tuple(solid)
    assert (x1 - x0, z1 - z0) == pytest.approx((sheet.length_mm, sheet.thickness_mm), abs=1e-6)


def test_each_stop_cut_wider_than_its_gap_gets_a_shim_that_leaves_the_gap(plan):
    from tactcad.design.comb_plan import placed_parts, touching
    from tactcad.partlib.array.comb_hardware import stop_shims

    placed = {name: (part, where) for name, part, where in placed_parts(plan)}
    stops = {s.element: s for s in plan.hard_stops}
    shims = stop_shims(plan.comb)
    assert len(shims) == sum(s.kind == "set" for s in stops.values()) > 0
    for row, column, shim, _ in shims:
        number = row * plan.columns + column + 1
        stop, sheet = stops[number], plan.comb.sheets[row]
        assert shim.thickness_mm == pytest.approx(stop.cut_mm - stop.gap_mm, abs=1e-9)
        part, where = placed[f"shim_{number}"]
        assert "." not in part and part in array_parts(plan)
        # the shim's top, in the array frame, lies the stop gap under the arm's underside
        arm = sheet.elements[column].arm_underside_y_mm + placed[sheet.part_name][1].dy_mm
        assert arm - (where.dy_mm + shim.thickness_mm) == pytest.approx(stop.gap_mm, abs=1e-9)
        assert frozenset({f"shim_{number}", sheet.part_name}) in touching(plan)


def test_the_sheets_drawing_and_the_build_book_name_each_shim(plan):
    from types import SimpleNamespace

    from tactcad.drawings.part_sets import PEN
    from tactcad.partlib.array.comb_sheet import notes, stacking_notes

    sheet = plan.comb.sheets[0]
    spec = SimpleNamespace(geometry=sheet, process="wire EDM", material="Ti")
    text = " ".join(notes(SimpleNamespace(spec=spec, plan=plan, tip_height=None), PEN))
    assert f"shim {sheet.shims_mm[0]:g}" in text and f"cut {sheet.cut_gaps_mm[0]:g}" in text
    assert "feeler" in " ".join(stacking_notes(None))
    # each run of like columns with its arm, web and tip, each with its tolerance
    e, tol = sheet.elements[0], PEN.tolerances(plan)
    assert f"arm {PEN.plus_minus(e.arm_length_mm, tol.arm_length_mm)}" in text
    assert f"web {PEN.web_text(e)}" in text and "±" in PEN.web_text(e)
    assert f"tip {PEN.plus_minus(e.tip_width_mm, tol.contact_face_mm)} wide" in text
    assert f"columns 1-{len(sheet.elements)}" in text.lower() and "pitch" in text
    # the stop gap with the tolerance the rows' process holds (wire EDM: +/-0.01 mm)
    gap = (sheet.stop_gaps_mm or sheet.cut_gaps_mm)[0]
    assert f"stop gap {PEN.plus_minus(gap, 0.01)} at the arm's end" in text


def test_the_spacer_has_its_own_process_and_its_shop_file(plan):
    import tomllib

    from tactcad.design.array_plan import plan_from_dict
    from tactcad.errors import DesignErrors
    from tactcad.export.dxf_sheet import shop_profiles
    from tactcad.vocabulary.process import CUT_PROCESSES

    t = plan.comb.spacer_thickness_mm
    lo, hi = CUT_PROCESSES[plan.comb.spacer_process].sheet_range_mm
    # a plain plate is judged by the process's cutting range, not the flexure model's:
    # wire EDM cuts the 0.4 mm spacer though no wire-cut flexure may be that thin
    assert lo <= t <= hi and plan.comb.spacer_process == "wire-edm"
    assert t < CUT_PROCESSES["wire-edm"].flexure_sheet()[0]
    spacer = next(sp for sp in shop_profiles(plan) if sp.part == "comb_spacer")
    assert spacer.process == plan.comb.spacer_process and spacer.thickness_mm == t
    data = tomllib.loads(GRASPER.read_text(encoding="utf-8"))
    data["comb"]["spacer_process"] = "laser-cutting"
    assert plan_from_dict(data).comb.spacer_process == "laser-cutting"
    data["comb"]["spacer_process"] = "photochemical-etching"
    data["comb"]["spacer_thickness_mm"] = 2.0  # thicker than foil is etched
    with pytest.raises(DesignErrors) as err:
        plan_from_dict(data)
    assert "comb.spacer_process" in str(err.value) and "etching" in str(err.value)


def test_each_rows_drawing_carries_the_rated_full_scale_force_as_a_stacked_element_does(plan):
    """The stacked element's drawing judges the rating against its element force limit;
    a comb's row drawings carried no such note. Each row's judges it against the row's
    lowest element force limit, by verify's rule (:func:`rating_verdict_words`)."""
    from types import SimpleNamespace

    from tactcad.drawings.design_notes import rating_verdict_words
    from tactcad.drawings.part_sets import PEN
    from tactcad.mechanics.limits import plan_limits
    from tactcad.partlib.array.comb_sheet import notes
    from tactcad.studies.verification import requirements_of

    rated = requirements_of(plan).full_scale_force_N
    limits = plan_limits(plan, "closed-form")
    for sheet in plan.comb.sheets:
        spec = SimpleNamespace(geometry=sheet, process="wire EDM", material="Ti")
        said = [n for n in notes(SimpleNamespace(spec=spec, plan=plan, tip_height=None), PEN)
                if n.startswith("Rated full-scale force")]
        assert len(said) == 1, sheet.row
        numbers = {s.number for s in plan.slots if s.row == sheet.row}
        lowest = min((lim for lim in limits if lim.element in numbers),
                     key=lambda lim: (lim.force_N, lim.element))
        words = rating_verdict_words(lowest.force_N, rated, lowest.error_estimate_rel)
        assert said[0].startswith(f"Rated full-scale force {rated:.3g} N on every tip "
                                  f"(the design's, {words}): element force limit "
                                  f"{lowest.force_N:.3g} N, the row's lowest (element "
                                  f"{lowest.element})")
        assert f"Do not load a tip beyond {rated:.3g} N." in said[0]
