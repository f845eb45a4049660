"""The grasper rig: the comb insert seated in the jaw's pocket, the jaw turned about its pin
above the tissue slab; scenes placed without building a part."""

from __future__ import annotations

import math

import pytest

from tactcad.assembly.grasper_rig import pin_height_mm
from tactcad.assembly.rig_models import rig_model
from tactcad.assembly.scene_solver import assemble
from tactcad.design.array_plan import EXAMPLES
from tactcad.design.project import load_project
from tactcad.design.scene_specs import validate_scenes
from tactcad.errors import SceneError

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def project():  # the grasper example (the session's project is the paper's)
    return load_project(GRASPER)


def tip_heights(scene, plan) -> dict[int, tuple[float, float]]:
    """Element number -> (x along the jaw, height) of its contact face centre (mm)."""
    out = {}
    for s in plan.slots:
        p = scene.world_point("array", f"tip_{s.number}")
        out[s.number] = (p.X, p.Y)
    return out


def test_closed_every_contact_face_rests_on_the_slab(project):
    scene = assemble(project, "grasper-closed")
    slab = scene.specs["tissue_slab"].geometry.thickness_mm
    heights = tip_heights(scene, project.plan)
    assert [y for _, y in heights.values()] == pytest.approx([slab] * len(heights), abs=1e-9)
    # the slab's contacts are declared: the tips touch it, nothing interferes by design
    assert frozenset({"comb_row1", "tissue_slab"}) in scene.contacts


def test_open_each_tip_stands_above_the_slab_by_the_jaws_turn_about_its_pin(project):
    scene = assemble(project, "grasper-open")
    jaw = scene.specs["grasper_jaw"].geometry
    slab = scene.specs["tissue_slab"].geometry.thickness_mm
    theta = math.radians(jaw.opening_angle_deg)
    below_pin = pin_height_mm(jaw, slab) - slab  # the tip plane under the pin, closed
    for x, y in tip_heights(scene, project.plan).values():
        # a tip r from the pin along the jaw, the tip plane below_pin under it
        r = x * math.cos(theta) + (y - pin_height_mm(jaw, slab)) * math.sin(theta)
        assert y - slab == pytest.approx(below_pin * (1 - math.cos(theta)) + r * math.sin(theta),
                                         abs=1e-9)


def test_the_first_column_lies_nearest_the_pin_and_a_units_tips_at_one_radius(project):
    heights = tip_heights(assemble(project, "grasper-open"), project.plan)
    plan = project.plan
    for reference, measuring in plan.unit_pairs:
        assert heights[reference][0] == pytest.approx(heights[measuring][0], abs=1e-9)
    firsts = [heights[s.number][0] for s in plan.row_slots(0)]
    assert firsts == sorted(firsts) and firsts[0] > 0


def test_the_insert_sits_centred_in_the_pocket_with_its_tips_proud_of_the_face(project):
    scene = assemble(project, "grasper-closed")
    jaw = scene.specs["grasper_jaw"].geometry
    seat = scene.world_point("array", "jaw_seat")
    pocket = scene.world_point("grasper_jaw", "insert")
    assert (seat - pocket).length == pytest.approx(0.0, abs=1e-9)
    face = scene.world_point("grasper_jaw", "face")
    assert face.Y - seat.Y == pytest.approx(jaw.tip_proud_mm, abs=1e-9)


def test_a_stacked_array_has_no_seat_for_a_jaw():
    plan = load_project(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml").plan
    spec = validate_scenes({"scene": {"g": {"rig": "grasper", "description": "d",
                                            "groups": ["jaw"]}}})[0]["g"]
    with pytest.raises(SceneError, match="stacked construction gives the array no seat"):
        rig_model(plan, "grasper", None, spec)


@pytest.mark.parametrize("table, field", [
    ({"rig": "array", "description": "d", "groups": ["array"], "jaw_angle_deg": 10},
     "scene.s.jaw_angle_deg"),
    ({"rig": "grasper", "description": "d", "groups": ["jaw"], "jaw_angle_deg": 120},
     "scene.s.jaw_angle_deg"),
])
def test_a_jaw_angle_is_refused_off_the_grasper_or_out_of_range(table, field):
    _, problems = validate_scenes({"scene": {"s": table}})
    assert field in [e.field for e in problems.errors]


def test_the_grasper_scenes_build_no_part_to_place(project):
    from collections import Counter

    from tactcad.solids.build import BUILD_COUNTS

    before = Counter(BUILD_COUNTS)
    assemble(project, "grasper-open")
    assert Counter(BUILD_COUNTS) == before


def jaw_face_corners_in_scene(g, angle_deg: float, pin_world) -> list[tuple[float, float]]:
    """(x, height) of the jaw's face-side edge corners and 50 points along it, turned
    ``angle_deg`` about the pin (the jaw's face is its lowest side as it opens)."""
    from tactcad.assembly.grasper_rig import jaw_root

    f = jaw_root(g, angle_deg, pin_world)
    pts = []
    for i in range(51):
        x = g.length_mm * i / 50
        p = [f.origin[k] + x * f.x_dir[k] + g.thickness_mm * f.z_dir[k] for k in range(3)]
        pts.append((p[0], p[1]))
    return pts


@pytest.mark.parametrize("pin_inset, thickness, angle", [
    (2.5, 5.6, 45.0), (2.5, 5.6, 90.0), (6.0, 8.0, 60.0), (-6.0, 5.5, 45.0), (2.5, 5.6, 10.0)])
def test_the_slab_lies_clear_of_the_jaws_heel_at_every_angle_it_opens_to(pin_inset, thickness,
                                                                         angle):
    from dataclasses import replace

    from tactcad.assembly.grasper_rig import SHAFT_CLEARANCE_MM, slab_start_mm
    from tactcad.partlib.grasper_jaw import jaw_part

    plan = load_project(GRASPER).plan
    g = replace(jaw_part(plan).geometry, pin_x_mm=pin_inset, thickness_mm=thickness,
                opening_angle_deg=angle)
    slab_top = 3.0
    pin = (0.0, pin_height_mm(g, slab_top), 0.0)
    start = slab_start_mm(g, angle)
    assert start >= SHAFT_CLEARANCE_MM
    for a in (angle * k / 12 for k in range(13)):
        under = [(x, y) for x, y in jaw_face_corners_in_scene(g, a, pin)
                 if x >= start - 1e-9]
        assert all(y >= slab_top - 1e-9 for _, y in under), (a, min(under, key=lambda q: q[1]))
    # the heel of a jaw pinned inside it dips at a wide angle: the slab moves off the pin
    if pin_inset > 0 and angle >= 45:
        assert start > SHAFT_CLEARANCE_MM


def test_the_lab_jaws_open_scene_puts_the_slab_past_the_heel_it_swings_down():
    """The 10 mm class's jaw opened to 45 degrees (a lab's file): the slab moves forward so
    the heel behind the pin clears it (the open scene's interference check, kernel-free)."""
    from tactcad.assembly.grasper_rig import grasper_layout

    import tomllib

    from tactcad.design.array_plan import plan_from_dict

    data = tomllib.loads(GRASPER.read_text(encoding="utf-8"))
    data["grasper_jaw"]["opening_angle_deg"] = 60.0
    layout = grasper_layout(plan_from_dict(data))
    g = layout.specs["grasper_jaw"].geometry
    slab = layout.specs["tissue_slab"].geometry
    x0 = layout.roots["tissue_slab"].origin[0] - slab.length_mm / 2
    pin = (0.0, pin_height_mm(g, slab.thickness_mm), 0.0)
    assert all(y >= slab.thickness_mm - 1e-9
               for x, y in jaw_face_corners_in_scene(g, 60.0, pin) if x >= x0)
