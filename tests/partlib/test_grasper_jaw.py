"""The grasper jaw that carries the comb insert: its solid against the
volume its derivation expects, and refusals naming field, value and range."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.design.array_plan import load_design
from tactcad.errors import DesignError
from tactcad.partlib.grasper_jaw import build, insert_envelope_mm, jaw_part

GRASPER = Path(__file__).parents[2] / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def comb_plan():
    return load_design(GRASPER)


def test_pocket_holds_the_insert_envelope_with_its_clearance(comb_plan):
    g = jaw_part(comb_plan, {"pocket_clearance_mm": 0.15}).geometry
    across, along, _ = insert_envelope_mm(comb_plan)
    assert g.pocket_length_mm == pytest.approx(along + 0.3)
    assert g.pocket_width_mm == pytest.approx(across + 0.3)
    assert g.window_length_mm <= g.pocket_length_mm and g.window_width_mm <= g.pocket_width_mm


@pytest.mark.slow
def test_jaw_builds_one_valid_solid_of_the_expected_volume_and_box(comb_plan):
    data = jaw_part(comb_plan)
    solid = build(data.geometry)
    assert solid.is_valid
    assert solid.volume == pytest.approx(data.expected_volume_mm3, rel=1e-6)
    bb = solid.bounding_box()
    assert (bb.min.X, bb.min.Y, bb.min.Z, bb.max.X, bb.max.Y, bb.max.Z) == pytest.approx(
        data.expected_bbox_mm, abs=1e-6)


def test_the_default_closed_jaws_pass_the_trocar(comb_plan):
    from tactcad.partlib.grasper_jaw import closed_thickness_limit_mm

    data = jaw_part(comb_plan)
    g = data.geometry
    closed = next(d for d in data.derived if d.name == "grasper_jaw_closed_diagonal")
    assert closed.value <= 10.0
    assert g.thickness_mm + 1.5 <= closed_thickness_limit_mm(10.0, g.width_mm)


@pytest.mark.parametrize("table, words", [
    # the 5 mm class's 3.3 mm jaw cannot hold the pocket: its width is the key named
    ({"shaft_class_mm": "5"}, ["grasper_jaw.width_mm", "3.3", ">= 6.4 mm"]),
    # sqrt(10^2 - 9^2) - 1.5 = 2.858899 mm, floored so that the bound itself passes
    ({"width_clearance_mm": 1.0, "thickness_mm": 6.0},
     ["grasper_jaw.thickness_mm", "6", "<= 2.8588 mm", "1.5 mm opposing jaw", "10 mm shaft"]),
    ({"shaft_class_mm": "7"}, ["grasper_jaw.shaft_class_mm", "5, 10"]),
    # a class written as a number is named, with how to write it
    ({"shaft_class_mm": 10}, ["grasper_jaw.shaft_class_mm = 10", "5, 10 as text",
                              'shaft_class_mm = "10"']),
    ({"face_wall_mm": 0.6}, ["grasper_jaw.face_wall_mm", "0.6", "< 0.5 mm"]),
    ({"pocket_length_mm": 20.0}, ["grasper_jaw.pocket_length_mm", "20", ">= 29 mm", "envelope"]),
    ({"length_mm": 200}, ["grasper_jaw.length_mm", "200", "5 <= value <= 80 mm"]),
    ({"length_mm": 30}, ["grasper_jaw.length_mm", "30"]),
    ({"thickness_mm": 4.0}, ["grasper_jaw.thickness_mm", "4", ">= 5.4941 mm"]),
])
def test_bad_jaw_values_name_field_value_and_range(comb_plan, table, words):
    with pytest.raises(DesignError) as info:
        jaw_part(comb_plan, table)
    for w in words:
        assert w in str(info.value), str(info.value)


@pytest.mark.slow
def test_shaft_builds_a_tube_of_the_expected_volume():
    from tactcad.partlib.grasper_shaft import build as build_shaft, shaft_part

    data = shaft_part({"shaft_class_mm": "5", "length_mm": 270.0})
    solid = build_shaft(data.geometry)
    assert solid.is_valid
    assert solid.volume == pytest.approx(data.expected_volume_mm3, rel=1e-6)
    assert data.attributes["lead_channel_diameter_mm"] == pytest.approx(4.0)


@pytest.mark.parametrize("table, words", [
    ({"wall_mm": 2.4, "shaft_class_mm": "5"}, ["grasper_shaft.wall_mm", "2.4", "<= 2.25 mm"]),
    ({"length_mm": 50.0}, ["grasper_shaft.length_mm", "50", "100 <= value <= 500 mm"]),
])
def test_bad_shaft_values_name_field_value_and_range(table, words):
    from tactcad.partlib.grasper_shaft import shaft_part

    with pytest.raises(DesignError) as info:
        shaft_part(table)
    for w in words:
        assert w in str(info.value), str(info.value)


def test_the_slab_covers_the_jaw_face_unless_sized(comb_plan):
    from tactcad.partlib.tissue_slab import slab_part

    jaw = jaw_part(comb_plan).geometry
    g = slab_part(jaw, {"thickness_mm": 4.0}).geometry
    assert (g.length_mm, g.width_mm, g.thickness_mm) == (jaw.length_mm, jaw.width_mm, 4.0)
    assert slab_part(jaw, {"length_mm": 50.0}).geometry.length_mm == 50.0
    with pytest.raises(DesignError) as info:
        slab_part(jaw, {"thickness_mm": 0.0})
    assert "tissue_slab.thickness_mm" in str(info.value) and "0 < value <= 100 mm" in str(info.value)


@pytest.mark.slow
def test_the_slab_builds_its_box(comb_plan):
    from tactcad.partlib.tissue_slab import build as build_slab, slab_part

    data = slab_part(jaw_part(comb_plan).geometry)
    solid = build_slab(data.geometry)
    assert solid.is_valid and solid.volume == pytest.approx(data.expected_volume_mm3, rel=1e-9)


def test_the_window_lies_over_the_tip_field_not_the_pocket_centre(comb_plan):
    from tactcad.partlib.grasper_jaw import tip_field_offset_mm

    g = jaw_part(comb_plan).geometry
    along, across = tip_field_offset_mm(comb_plan)
    assert abs(along) > 0.5  # the comb's tips lie off its envelope's centre along the row
    assert g.window_centre_mm == pytest.approx((g.pocket_centre_x_mm + along, across))
    # the window stays within the pocket's outline
    cx, cy = g.window_centre_mm
    assert g.pocket_x0_mm <= cx - g.window_length_mm / 2
    assert cx + g.window_length_mm / 2 <= g.pocket_x0_mm + g.pocket_length_mm
    assert abs(cy) + g.window_width_mm / 2 <= g.pocket_width_mm / 2


def test_the_smallest_comb_is_screened_against_the_jaw_naming_the_size_that_binds():
    """Before a search: the comb's rows stand on edge 5.8 mm high, so a 2.6 mm robotic jaw
    holds none, said as height against the jaw's keys; the 10 mm class's jaw passes."""
    from tactcad.design.array_plan import EXAMPLES, read_toml
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.studies.comb_design import comb_misfit
    from tactcad.studies.inverse_design import Targets

    base = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")
    targets = Targets(10.0, (0.5, 5.0), 0.05)
    assert comb_misfit(jaw_room("10"), 6, base, targets) == []
    thin = {"shaft_diameter_mm": 8.0, "width_mm": 4.2, "length_mm": 16.0, "thickness_mm": 2.6,
            "opposing_jaw_mm": 2.6, "pin_inset_mm": 1.1, "opening_angle_deg": 45.0}
    missed = comb_misfit(jaw_room(thin, "robot.toml"), 6, base, targets)
    assert missed[0]["words"].startswith("height 5.79 mm") and "2.9 mm" in missed[0]["words"]
    assert "thickness_mm" in missed[0]["words"]
    # a jaw thick enough passes the 8 mm shaft beside the 2.6 mm opposing jaw at no width:
    # nothing to paste in robot.toml, the shaft it needs said instead
    assert missed[0]["option"] == "" and "a shaft of at least" in missed[0]["words"]
    seven = comb_misfit(jaw_room("10"), 7, base, targets)  # 7 x 4.3 mm > the 29.3 mm pocket
    assert [m["option"] for m in seven] == ["--columns 6"]


#: Lab jaw files (a ``[grasper_jaw]`` each) too low or too narrow for the 10 mm comb: an
#: 8 mm shaft whose thicker jaw passes it at no width, one that passes narrowed, a stated
#: pocket too narrow, a width stated as a clearance, a tiny stated pocket depth
PASTE_JAWS = {
    "palp8": {"shaft_diameter_mm": 8.0, "width_mm": 4.8, "length_mm": 40.0,
              "thickness_mm": 3.0, "opposing_jaw_mm": 3.0, "pin_diameter_mm": 1.5,
              "pin_inset_mm": 1.3, "opening_angle_deg": 40.0, "pocket_depth_mm": 1.0},
    "lab12": {"shaft_diameter_mm": 12.0, "width_mm": 11.0, "length_mm": 40.0,
              "thickness_mm": 3.2, "pin_inset_mm": -6.0, "opening_angle_deg": 45.0,
              "pocket_width_mm": 7.0},
    "narrow_pocket": {"shaft_class_mm": "10", "width_clearance_mm": 3.5, "length_mm": 40.0,
                      "thickness_mm": 5.6, "pin_inset_mm": 2.5, "opening_angle_deg": 30.0,
                      "pocket_width_mm": 0.5},
    "clearance_low": {"shaft_diameter_mm": 11.0, "width_clearance_mm": 1.5, "length_mm": 40.0,
                      "thickness_mm": 3.0, "pin_inset_mm": 2.5, "opening_angle_deg": 30.0},
    "tiny_depth": {"shaft_diameter_mm": 12.0, "width_mm": 8.0, "length_mm": 40.0,
                   "thickness_mm": 3.0, "pin_inset_mm": 2.5, "opening_angle_deg": 30.0,
                   "pocket_depth_mm": 0.05},
    "tiny_depth_tight": {"shaft_diameter_mm": 10.0, "width_mm": 8.0, "length_mm": 40.0,
                         "thickness_mm": 2.0, "opposing_jaw_mm": 1.0, "pin_inset_mm": 2.5,
                         "opening_angle_deg": 30.0, "pocket_depth_mm": 0.05},
}


def _pasted(table: dict, keys: list) -> dict:
    """The jaw file's table with each ``grasper_jaw.key = value`` of ``keys`` written in."""
    out = dict(table)
    for key, _ in keys:
        name, value = key.removeprefix("grasper_jaw.").split(" = ")
        out[name] = float(value)
    return out


@pytest.mark.parametrize("name", sorted(PASTE_JAWS))
def test_every_jaw_file_paste_is_a_jaw_the_load_accepts_and_that_holds_the_insert(
        comb_plan, name):
    """A paste is the file with its keys written in, read back through the jaw's own rules
    (the --jaw FILE read: each key's range, the pivot, the depth, the closed jaws in the
    shaft) and through the load's (the jaw for the insert); where none would pass, no key
    is offered and the reason says why."""
    from tactcad.partlib.grasper_jaw import jaw_room

    table = PASTE_JAWS[name]
    env = insert_envelope_mm(comb_plan)
    room = jaw_room(table, f"{name}.toml")
    assert env[2] > room.height_mm or env[0] > room.across_mm  # the file does not hold it
    keys = room.file_keys_to_hold(env)
    if not keys:
        why_not = room.file_paste(env)[1]
        assert "a shaft of at least" in why_not or "refused" in why_not, why_not
        return
    pasted = _pasted(table, keys)
    again = jaw_room(pasted, f"{name}.toml")  # raises on any key the jaw's rules refuse
    assert again.height_mm >= env[2] - 1e-9 and again.across_mm >= env[0] - 1e-9
    jaw_part(comb_plan, pasted)  # the load's rules for the insert in this jaw
    assert again.file_keys_to_hold(env) == []  # nothing more to paste


def test_a_shaft_no_jaw_width_passes_gets_no_paste_but_the_shaft_it_needs(comb_plan):
    """The 8 mm shaft with a 3 mm opposing jaw: a jaw thick enough for the comb passes it at
    no width (it once pasted width_mm = 0, outside the key's 1 ... 20 mm)."""
    import math

    from tactcad.partlib.grasper_jaw import jaw_room

    env = insert_envelope_mm(comb_plan)
    room = jaw_room(PASTE_JAWS["palp8"], "palp8_jaw.toml")
    keys, why_not = room.file_paste(env)
    assert keys == []
    shaft = float(why_not.split("shaft of at least ")[1].split(" mm")[0])
    thick = 3.0 + env[2] - room.height_mm
    assert shaft >= math.hypot(env[0] + 2 * (0.1 + 0.5), thick + 3.0) - 0.01
    assert "8 mm shaft" in why_not and "opposing_jaw_mm" in why_not


THIN_JAW = {"width_mm": 4.0, "length_mm": 20.0, "thickness_mm": 1.8, "pin_inset_mm": 2.0,
            "opening_angle_deg": 40.0}


def test_a_refused_shaft_reports_no_pin_the_file_never_states():
    """A jaw file whose shaft is refused: no second refusal of the pin its fallback class
    would fill in (the 10 mm class's 1.5 mm pin in a 1.8 mm jaw), only the shaft's."""
    from tactcad.errors import DesignErrors
    from tactcad.partlib.grasper_jaw import jaw_room

    with pytest.raises(DesignErrors) as err:
        jaw_room({"shaft_diameter_mm": "six", **THIN_JAW}, "six.toml")
    assert [e.field for e in err.value.errors] == ["grasper_jaw.shaft_diameter_mm"]


def test_a_pin_the_file_states_is_still_judged_with_a_refused_shaft():
    from tactcad.errors import DesignErrors
    from tactcad.partlib.grasper_jaw import jaw_room

    with pytest.raises(DesignErrors) as err:
        jaw_room({"shaft_diameter_mm": "six", **THIN_JAW, "pin_diameter_mm": 1.5}, "six.toml")
    assert [e.field for e in err.value.errors] == ["grasper_jaw.shaft_diameter_mm",
                                                   "grasper_jaw.pin_diameter_mm"]
