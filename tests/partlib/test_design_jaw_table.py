"""A design states the grasper its insert is for: ``[grasper_jaw]``, ``[grasper_shaft]``
and ``[tissue_slab]`` in the design file, validated at load and read by the jaw scene,
the ``grasper`` checks and ``design --jaw``'s room."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import pytest

from tactcad.design.array_plan import plan_from_dict
from tactcad.errors import DesignError, DesignErrors
from tactcad.partlib.grasper_jaw import class_jaw_file_table, design_table, jaw_part, jaw_room
from tactcad.partlib.grasper_shaft import shaft_part

HARDWARE = Path(__file__).parents[2] / "hardware"
GRASPER = HARDWARE / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
STACKED = HARDWARE / "ti_array_2x3" / "ti_array_2x3.toml"


@pytest.fixture(scope="module")
def comb_data():
    return tomllib.loads(GRASPER.read_text(encoding="utf-8"))


#: a jaw file stating the 10 mm class's default jaw
JAW_10 = class_jaw_file_table("10")


def with_tables(data: dict, **tables) -> dict:
    out = copy.deepcopy(data)
    out.update(tables)
    return out


def test_the_jaw_the_design_states_is_the_jaw_of_its_scene_and_checks(comb_data):
    plain = jaw_part(plan_from_dict(comb_data)).geometry
    plan = plan_from_dict(with_tables(comb_data, grasper_jaw={"opening_angle_deg": 45.0,
                                                              "length_mm": 40.0}))
    g = jaw_part(plan).geometry
    assert (g.opening_angle_deg, g.length_mm) == (45.0, 40.0)
    assert (plain.opening_angle_deg, plain.length_mm) != (45.0, 40.0)
    # the pocket keeps its place from the distal end: a longer jaw moves it by the difference
    assert g.pocket_x0_mm - plain.pocket_x0_mm == pytest.approx(40.0 - plain.length_mm)


def test_the_shaft_takes_the_jaws_class_unless_it_states_one(comb_data):
    plan = plan_from_dict(with_tables(comb_data, grasper_jaw={"shaft_class_mm": "10"}))
    assert design_table(plan, "grasper_shaft") == {"shaft_class_mm": "10"}
    assert shaft_part(design_table(plan, "grasper_shaft")).geometry.outer_diameter_mm == 10.0
    with pytest.raises(DesignErrors) as err:
        plan_from_dict(with_tables(comb_data, grasper_jaw={"shaft_class_mm": "10"},
                                   grasper_shaft={"shaft_class_mm": "5"}))
    assert "grasper_shaft.shaft_class_mm" in str(err.value) and "allowed 10 mm" in str(err.value)


@pytest.mark.parametrize("tables, field", [
    ({"grasper_jaw": {"length_mm": 500.0}}, "grasper_jaw.length_mm"),
    ({"grasper_jaw": {"shaft_class_mm": 10}}, "grasper_jaw.shaft_class_mm"),
    ({"grasper_jaw": {"pocket_width": 5.0}}, "grasper_jaw.pocket_width"),
    ({"tissue_slab": {"thickness_mm": -1.0}}, "tissue_slab.thickness_mm"),
    ({"tissue_slab": {"base": "glued"}}, "tissue_slab.base"),
    ({"grasper_shaft": "10"}, "grasper_shaft"),
])
def test_a_bad_in_use_table_is_refused_at_load_naming_its_field(comb_data, tables, field):
    with pytest.raises(DesignErrors) as err:
        plan_from_dict(with_tables(comb_data, **tables))
    assert field in str(err.value)


def test_a_stacked_design_may_state_its_grasper_too():
    data = tomllib.loads(STACKED.read_text(encoding="utf-8"))
    plan = plan_from_dict(with_tables(data, grasper_jaw={"shaft_class_mm": "5"}))
    assert design_table(plan, "grasper_jaw") == {"shaft_class_mm": "5"}


def test_a_jaw_files_stated_pocket_is_the_room_less_its_clearances():
    room = jaw_room({**JAW_10, "pocket_width_mm": 5.0, "pocket_length_mm": 20.0,
                     "pocket_clearance_mm": 0.2}, "my_jaw.toml")
    assert (room.across_mm, room.along_mm) == pytest.approx((4.6, 19.6))
    assert room.label == "10 mm-shaft jaw of my_jaw.toml" and room.option == "my_jaw.toml"
    whole = jaw_room("10")
    assert whole.across_mm > room.across_mm and whole.along_mm > room.along_mm
    assert whole.label == "10 mm jaw" and whole.table == {"shaft_class_mm": "10"}


@pytest.mark.parametrize("table, field", [
    ({"pocket_width_mm": 6.0}, "grasper_jaw.pocket_width_mm"),  # the 6.5 mm jaw's walls
    ({"pocket_length_mm": 33.0}, "grasper_jaw.pocket_length_mm"),  # past the pin's steel
    ({"shaft_class_mm": "7"}, "grasper_jaw.shaft_class_mm"),
])
def test_a_pocket_the_jaw_cannot_hold_is_refused_naming_its_field(table, field):
    with pytest.raises(DesignErrors) as err:
        jaw_room({**JAW_10, **table}, "j.toml")
    assert field in str(err.value)


#: the lab's own 12 mm grasper: jaw 36 x 11 mm, pocket 26 x 7 mm, pivot 6 mm behind the
#: heel, 45 degrees open (its height is the lab's to state)
LAB_JAW = {"shaft_diameter_mm": 12.0, "width_mm": 11.0, "length_mm": 36.0,
           "thickness_mm": 3.2, "pin_inset_mm": -6.0, "opening_angle_deg": 45.0,
           "pocket_width_mm": 7.0, "pocket_length_mm": 26.0}


@pytest.mark.parametrize("key", ["width_mm", "length_mm", "thickness_mm", "pin_inset_mm",
                                 "opening_angle_deg", "shaft_diameter_mm"])
def test_a_jaw_file_that_leaves_a_key_out_is_refused_by_its_name(key):
    table = {k: v for k, v in LAB_JAW.items() if k != key}
    with pytest.raises(DesignErrors) as err:
        jaw_room(table, "lab_jaw.toml")
    assert len(err.value.errors) == 1 and f"grasper_jaw.{key}" in str(err.value)
    assert "not given" in str(err.value)


def test_a_labs_12_mm_jaw_with_its_7_mm_pocket_is_the_room_it_states():
    room = jaw_room(LAB_JAW, "lab_jaw.toml")
    assert (room.across_mm, room.along_mm) == pytest.approx((6.8, 25.8))
    assert room.height_mm == pytest.approx(3.2 + 0.3)
    assert room.label == "12 mm-shaft jaw of lab_jaw.toml"


@pytest.mark.parametrize("change, field", [
    ({"width_clearance_mm": 1.0}, "grasper_jaw.width_clearance_mm"),  # width stated twice
    ({"width_mm": 12.5}, "grasper_jaw.width_mm"),  # wider than the shaft
    ({"pin_inset_mm": 0.2}, "grasper_jaw.pin_inset_mm"),  # the pin cuts the heel
    ({"shaft_class_mm": "10"}, "grasper_jaw.shaft_diameter_mm"),  # two shafts
    ({"pocket_width_mm": 10.5}, "grasper_jaw.pocket_width_mm"),  # through the side walls
])
def test_a_jaw_stated_two_ways_or_past_its_steel_is_refused_naming_the_key(change, field):
    with pytest.raises(DesignErrors) as err:
        jaw_room({**LAB_JAW, **change}, "lab_jaw.toml")
    assert field in str(err.value)


def test_an_unknown_class_names_the_option():
    with pytest.raises(DesignError) as err:
        jaw_room("7")
    assert err.value.field == "--jaw"


def test_the_grasp_runs_on_the_jaw_the_design_states(comb_data):
    from tactcad.design.grasper_in_use import stated_grasper
    from tactcad.in_use.grasp_experiment import DEFAULT_OPENING_DEG, default_jaw

    plain = plan_from_dict(comb_data | {"grasper_jaw": {}})
    base = stated_grasper(plain)
    jaw = default_jaw(plain)
    assert (jaw.pivot_u_mm, jaw.pin_to_tip_mm) == (base.pivot_u_mm, base.pin_to_tip_mm)
    # the pin 0.5 mm nearer the jaw's heel is 0.5 mm further from the tips; a 2 mm longer
    # jaw moves the pocket (held at the distal wall) and the tips 2 mm away from the pin
    moved = stated_grasper(plan_from_dict(comb_data | {"grasper_jaw": {"pin_inset_mm": 2.0}}))
    assert moved.pivot_u_mm - base.pivot_u_mm == pytest.approx(-0.5)
    assert moved.pin_to_tip_mm - base.pin_to_tip_mm == pytest.approx(0.5)
    longer = stated_grasper(plan_from_dict(comb_data | {"grasper_jaw": {"length_mm": 36.0}}))
    assert longer.pivot_u_mm - base.pivot_u_mm == pytest.approx(-(36.0 - 34.0))
    wide = default_jaw(plan_from_dict(comb_data | {"grasper_jaw": {"opening_angle_deg": 45.0},
                                                   "tissue_slab": {"thickness_mm": 4.0}}))
    assert (wide.opening_angle_deg, wide.slab_thickness_mm) == (45.0, 4.0)
    # given values win over the stated ones
    assert default_jaw(plain, opening_deg=20.0).opening_angle_deg == 20.0
    # a design that states no grasper keeps the defaults
    bare = {k: v for k, v in comb_data.items() if k not in ("grasper_jaw", "assumptions")}
    assert stated_grasper(plan_from_dict(bare)) is None
    assert default_jaw(plan_from_dict(bare)).opening_angle_deg == DEFAULT_OPENING_DEG


@pytest.mark.parametrize("shaft_class", ["5", "10"])
def test_each_classs_default_jaw_passes_its_trocar_closed(shaft_class):
    import math

    from tactcad.partlib.grasper_jaw import (MIN_WALL_MM, SHAFT_CLASSES_MM, GrasperJawSection,
                                             with_class_defaults)

    j = with_class_defaults(GrasperJawSection(shaft_class_mm=shaft_class))
    width = SHAFT_CLASSES_MM[shaft_class] - j.width_clearance_mm
    assert math.hypot(width, j.thickness_mm + j.opposing_jaw_mm) <= SHAFT_CLASSES_MM[shaft_class]
    assert j.pin_diameter_mm <= j.thickness_mm - 2 * MIN_WALL_MM  # steel round the pin
    assert jaw_room(shaft_class).across_mm > 0
    # a stated size wins over the class's
    assert with_class_defaults(GrasperJawSection(shaft_class_mm=shaft_class,
                                                 thickness_mm=2.0)).thickness_mm == 2.0


@pytest.mark.parametrize("table, field", [
    ({"tip_proud_mm": 2.0}, "grasper_jaw.tip_proud_mm"),  # no face wall would do: the proud height
    ({"face_wall_mm": 0.6}, "grasper_jaw.face_wall_mm"),
    ({"pocket_width_mm": 3.0}, "grasper_jaw.pocket_width_mm"),  # narrower than the insert
])
def test_a_stated_jaw_that_cannot_take_the_insert_names_the_field_to_change(comb_data, table,
                                                                            field):
    plan = plan_from_dict(with_tables(comb_data, grasper_jaw=table))
    with pytest.raises(DesignErrors) as err:
        jaw_part(plan)
    assert [e.field for e in err.value.errors] == [field]


TAPER = [[4.0, -2.75], [33.0, -2.25], [33.0, 2.25], [4.0, 2.75]]  # a jaw narrowing to its tip


def test_an_outlines_stretch_for_a_band_is_exact():
    from tactcad.partlib.grasper_jaw import outline_stretch_mm

    assert outline_stretch_mm(TAPER, 4.5) == pytest.approx((4.0, 33.0))
    # half width 2.75 - 0.5 (x - 4) / 29 >= 2.5 up to x = 18.5
    assert outline_stretch_mm(TAPER, 5.0) == pytest.approx((4.0, 18.5))
    assert outline_stretch_mm(TAPER, 5.6) is None
    # two lobes joined by a neck: the longer lobe wins
    lobes = [[4, -2], [10, -2], [10, -0.5], [12, -0.5], [12, -2], [30, -2], [30, 2], [12, 2],
             [12, 0.5], [10, 0.5], [10, 2], [4, 2]]
    assert outline_stretch_mm(lobes, 3.0) == pytest.approx((12.0, 30.0))
    assert outline_stretch_mm(lobes, 0.8) == pytest.approx((4.0, 30.0))


def test_the_pocket_is_placed_inside_a_stated_outline(comb_data):
    from tactcad.checks.grasper_fit import pocket_inside_outline_mm

    plan = plan_from_dict(with_tables(comb_data, grasper_jaw={"pocket_outline_mm": [
        [4.0, -2.75], [33.0, -2.75], [33.0, 2.75], [4.0, 2.75]]}))
    g = jaw_part(plan).geometry
    assert g.pocket_outline_mm is not None and pocket_inside_outline_mm(g) >= 0
    # the 5.4 mm pocket fits the band only where the taper is wide enough: refused, named
    with pytest.raises(DesignErrors) as err:
        jaw_part(plan_from_dict(with_tables(comb_data, grasper_jaw={"pocket_outline_mm": TAPER})))
    assert [e.field for e in err.value.errors] == ["grasper_jaw.pocket_outline_mm"]


@pytest.mark.parametrize("outline, words", [
    ([[5, -1], [20, 1], [20, -1], [5, 1]], "simple polygon"),  # a bow tie
    ([[2, -2], [20, -2], [20, 2], [2, 2]], "<= x <="),  # over the pin's steel
    ([[5, -3], [20, -3], [20, 3], [5, 3]], "|y| <="),  # through the side walls
])
def test_a_bad_outline_is_refused_naming_it(outline, words):
    with pytest.raises(DesignErrors) as err:
        jaw_room({**JAW_10, "pocket_outline_mm": outline}, "j.toml")
    assert "grasper_jaw.pocket_outline_mm" in str(err.value) and words in str(err.value)


def test_a_jaw_outline_sets_the_room_each_sheet_gets():
    room = jaw_room({**JAW_10, "pocket_outline_mm": TAPER}, "taper.toml")
    assert room.outline is not None
    assert room.along_for(4.2) == pytest.approx(29.0 - 2 * room.clearance_mm)
    assert room.along_for(4.8) < room.along_for(4.2)  # a wider comb gets a shorter stretch
    assert room.along_for(6.0) == 0.0


#: a wristed robotic instrument's thin jaw in an 8 mm shaft (its pin 1.5 mm, 1.1 mm from
#: the heel: the jaw's 2.6 mm thickness leaves 0.26 mm of steel round it)
ROBOT_JAW = {"shaft_diameter_mm": 8.0, "width_mm": 4.2, "length_mm": 16.0,
             "thickness_mm": 2.6, "opposing_jaw_mm": 2.6, "pin_diameter_mm": 1.5,
             "pin_inset_mm": 1.1, "opening_angle_deg": 45.0}


def test_a_jaw_files_errors_are_refused_all_at_once_each_with_its_range():
    """An opening of 180 degrees no longer hides the pin's and the pocket's errors: one
    refusal lists every key, its value and the range the jaw allows."""
    bad = {**ROBOT_JAW, "opening_angle_deg": 180.0, "pin_diameter_mm": 2.2,
           "pin_inset_mm": 0.5, "pocket_depth_mm": 3.0}
    with pytest.raises(DesignErrors) as err:
        jaw_room(bad, "robot.toml")
    lines = {e.field: e.line() for e in err.value.errors}
    assert set(lines) == {"grasper_jaw.opening_angle_deg", "grasper_jaw.pin_diameter_mm",
                          "grasper_jaw.pin_inset_mm", "grasper_jaw.pocket_depth_mm"}
    assert "0 < value <= 90 degrees" in lines["grasper_jaw.opening_angle_deg"]
    assert "<= 2.08 mm" in lines["grasper_jaw.pin_diameter_mm"]  # 2.6 less 2 x 0.26 mm
    assert ">= 1.36 mm" in lines["grasper_jaw.pin_inset_mm"]  # 1.1 mm radius + 0.26 mm
    assert "0 < value < 2.6 mm" in lines["grasper_jaw.pocket_depth_mm"]


def test_a_key_left_out_does_not_raise_errors_of_the_keys_read_with_it():
    table = {k: v for k, v in ROBOT_JAW.items() if k != "thickness_mm"} | {"pin_diameter_mm": 3.9}
    with pytest.raises(DesignErrors) as err:
        jaw_room(table, "robot.toml")
    # the pin is judged against a thickness the file does not state: not judged
    assert [e.field for e in err.value.errors] == ["grasper_jaw.thickness_mm"]


@pytest.mark.parametrize("change, ok", [
    ({}, True),  # a 1.5 mm pin 1.1 mm from the heel of a 2.6 mm jaw (was: <= 1.6 mm, >= 1.25)
    ({"thickness_mm": 2.4, "opposing_jaw_mm": 2.4, "pin_inset_mm": 1.0}, True),
    ({"pin_diameter_mm": 2.08, "pin_inset_mm": 1.3}, True),
    ({"pin_diameter_mm": 2.1}, False),   # 0.25 mm above and below: < a tenth of 2.6 mm
    ({"pin_inset_mm": 1.0}, False),      # 0.25 mm behind it
    ({"pin_inset_mm": -0.75}, True),     # behind the heel, clear of it
])
def test_any_pin_the_jaws_own_body_allows_is_accepted(change, ok):
    table = {**ROBOT_JAW, **change}
    if ok:
        assert jaw_room(table, "robot.toml").across_mm > 0
    else:
        with pytest.raises(DesignErrors) as err:
            jaw_room(table, "robot.toml")
        assert next(iter(change)) in str(err.value) and "allowed" in str(err.value)


def test_a_jaw_the_shaft_cannot_pass_closed_is_refused_before_any_search():
    with pytest.raises(DesignErrors) as err:
        jaw_room({**JAW_10, "width_clearance_mm": None, "width_mm": 6.5, "thickness_mm": 6.5},
                 "thick.toml")
    e = err.value.errors[0]
    assert len(err.value.errors) == 1 and e.field == "grasper_jaw.thickness_mm"
    assert "<= 6.0993 mm" in e.allowed and "opposing_jaw_mm" in e.allowed


#: a lab's 12 mm jaw too thick closed beside its 3.2 mm opposing jaw at its 11 mm width
THICK12_JAW = {"shaft_diameter_mm": 12.0, "width_mm": 11.0, "length_mm": 26.0,
               "thickness_mm": 3.2, "opposing_jaw_mm": 3.2, "pin_diameter_mm": 1.5,
               "pin_inset_mm": 1.6, "opening_angle_deg": 40.0}


def test_a_jaw_too_thick_closed_names_the_width_and_opposing_jaw_that_let_it_pass():
    """The refusal of thickness_mm gives the widest width_mm and the thickest
    opposing_jaw_mm that let the stated thickness pass the shaft closed (the other keys
    kept), each a value a lab pastes into its file and the jaw's rules then accept."""
    import re

    with pytest.raises(DesignErrors) as err:
        jaw_room(THICK12_JAW, "jaw12.toml")
    e = err.value.errors[0]
    assert e.field == "grasper_jaw.thickness_mm" and "<= 1.5958 mm" in e.allowed
    width = float(re.search(r"width_mm <= ([0-9.]+) mm", e.why).group(1))
    opposing = float(re.search(r"opposing_jaw_mm <= ([0-9.]+) mm", e.why).group(1))
    assert (width, opposing) == (10.1508, 1.5958), e.why  # sqrt(12² - 6.4²), sqrt(12² - 11²) - 3.2
    for key, value in (("width_mm", width), ("opposing_jaw_mm", opposing)):
        assert jaw_room({**THICK12_JAW, key: value}, "jaw12.toml").across_mm > 0
    # the width left to a clearance: the least clearance that lets it pass
    by_clearance = {k: v for k, v in THICK12_JAW.items() if k != "width_mm"}
    with pytest.raises(DesignErrors) as err:
        jaw_room({**by_clearance, "width_clearance_mm": 1.0}, "jaw12.toml")
    why = err.value.errors[0].why
    least = float(re.search(r"width_clearance_mm >= ([0-9.]+) mm", why).group(1))
    assert least == 1.8492, why
    assert jaw_room({**by_clearance, "width_clearance_mm": least}, "jaw12.toml").across_mm > 0


def test_a_stated_pocket_depth_sets_the_combs_face_wall(comb_data):
    plan = plan_from_dict(with_tables(comb_data, grasper_jaw={"pocket_depth_mm": 5.2}))
    g = jaw_part(plan).geometry
    assert g.pocket_depth_mm == 5.2 and g.thickness_mm - g.pocket_depth_mm == pytest.approx(0.4)
    for depth, words in ((5.55, "<= 5.5 mm"), (4.0, "5.1 < value")):  # too thin; arms hit it
        with pytest.raises(DesignErrors) as err:
            jaw_part(plan_from_dict(with_tables(comb_data,
                                                grasper_jaw={"pocket_depth_mm": depth})))
        assert [e.field for e in err.value.errors] == ["grasper_jaw.pocket_depth_mm"]
        assert words in err.value.errors[0].allowed


@pytest.mark.parametrize("change, field, words", [
    # wider than the shaft: the width's refusal alone, no negative thickness offered
    ({"width_mm": 9.0}, "grasper_jaw.width_mm", "<= 8 mm"),
    # the opposing jaw alone leaves no thickness for this one beside a 7.9 mm width
    ({"width_mm": 7.9, "opposing_jaw_mm": 1.3}, "grasper_jaw.opposing_jaw_mm", "< 1.261 mm"),
])
def test_a_jaw_no_thickness_can_pass_names_the_size_that_binds(change, field, words):
    with pytest.raises(DesignErrors) as err:
        jaw_room({**ROBOT_JAW, **change}, "robot.toml")
    assert [e.field for e in err.value.errors] == [field]
    assert words in err.value.errors[0].allowed
    assert "-" not in err.value.errors[0].allowed.split("mm")[0]


#: a lab's jaw as wide as its 12 mm shaft (the opposing jaw left at its 1.5 mm default)
EQUAL_JAW = {"shaft_diameter_mm": 12.0, "width_mm": 12.0, "length_mm": 30.0,
             "thickness_mm": 6.0, "pin_inset_mm": -6.0, "opening_angle_deg": 45.0}


def test_a_jaw_as_wide_as_its_shaft_names_its_width_with_a_width_that_passes():
    """Width equal to the bore leaves no thickness: the width is named (not the opposing jaw
    the file leaves out, with "< 0 mm"), and the widest it offers passes the shaft closed."""
    with pytest.raises(DesignErrors) as err:
        jaw_room(EQUAL_JAW, "jaw_eq.toml")
    assert [e.field for e in err.value.errors] == ["grasper_jaw.width_mm"]
    allowed = err.value.errors[0].allowed
    assert allowed.startswith("<= ") and allowed.endswith(" mm")
    widest = float(allowed.split()[1])
    assert 0 < widest < 12.0
    assert jaw_room({**EQUAL_JAW, "width_mm": widest}, "jaw_eq.toml").across_mm > 0
    # the width stated as a clearance: the clearance is named, with one that passes
    by_clearance = {k: v for k, v in EQUAL_JAW.items() if k != "width_mm"}
    with pytest.raises(DesignErrors) as err:
        jaw_room({**by_clearance, "width_clearance_mm": 0.0}, "jaw_eq.toml")
    assert [e.field for e in err.value.errors] == ["grasper_jaw.width_clearance_mm"]
    least = float(err.value.errors[0].allowed.split()[1])
    assert jaw_room({**by_clearance, "width_clearance_mm": least}, "jaw_eq.toml").across_mm > 0


@pytest.mark.parametrize("point, words", [
    ([4.0, float("nan")], "a finite number, -100 <= value <= 100 mm"),
    ([4.0, 200.0], "-100 <= value <= 100 mm"),
])
def test_a_bad_coordinate_of_an_outline_names_the_point_and_a_coordinates_range(point, words):
    """A coordinate is refused by the coordinate's range, not the outline's count of points."""
    outline = [point, [33.0, -2.25], [33.0, 2.25], [4.0, 2.75]]
    with pytest.raises(DesignErrors) as err:
        jaw_room({**JAW_10, "pocket_outline_mm": outline}, "j.toml")
    e = next(e for e in err.value.errors if e.field.startswith("grasper_jaw.pocket_outline_mm"))
    assert e.field == "grasper_jaw.pocket_outline_mm[1][2]"
    assert e.allowed == words and "points" not in e.allowed
    assert "y across" in e.why


def test_an_outline_point_that_is_no_pair_is_refused_as_a_point():
    outline = [[4.0], [33.0, -2.25], [33.0, 2.25], [4.0, 2.75]]
    with pytest.raises(DesignErrors) as err:
        jaw_room({**JAW_10, "pocket_outline_mm": outline}, "j.toml")
    e = next(e for e in err.value.errors if e.field.startswith("grasper_jaw.pocket_outline_mm"))
    assert (e.field, e.allowed) == ("grasper_jaw.pocket_outline_mm[1]", "an [x, y] point (mm)")
