"""The solder-terminal board, a made part written as one module: one pair of
terminal holes per element, refusals naming its fields, a shop drawing, and
its place on the bracket's foot in every scene that shows the bracket."""

from __future__ import annotations

import copy

import pytest

from tactcad.assembly.rig_models import scene_model, shown_instances
from tactcad.catalogue.rig_catalogue import rig_parts
from tactcad.catalogue.shop import stock_size
from tactcad.design.rig_plan import default_rigs_data, rigs_from_dict
from tactcad.drawings.part_sets import drawing_of
from tactcad.errors import DesignError
from tactcad.vocabulary.process import Method


@pytest.fixture(scope="module")
def rigs(plan):
    return rigs_from_dict(default_rigs_data(), plan)


@pytest.fixture(scope="module")
def spec(plan, rigs):
    return rig_parts(plan, rigs)["terminal_board"]


def test_one_pair_of_terminal_holes_per_element(plan, spec):
    g = spec.geometry
    assert len(g.hole_xs_mm) == len(plan.slots) and len(g.hole_ys_mm) == 2
    pitch = g.hole_xs_mm[1] - g.hole_xs_mm[0]
    assert pitch == pytest.approx(g.hole_ys_mm[1] - g.hole_ys_mm[0])
    assert g.length_mm == pytest.approx(g.hole_xs_mm[-1] - g.hole_xs_mm[0] + 2 * 2.0)
    assert spec.attributes["terminal_pairs"] == len(plan.slots)


def test_a_rigs_file_without_the_table_gets_the_default_board(plan, rigs):
    data = default_rigs_data()
    del data["terminal_board"]
    data["assumptions"] = {k: v for k, v in data["assumptions"].items()
                           if not k.startswith("terminal_board.")}
    assert rigs_from_dict(data, plan).library["terminal_board"] == rigs.library["terminal_board"]


@pytest.mark.parametrize("key, value, words", [
    ("pitch_mm", 1.3, ["terminal_board.pitch_mm", "1.3", "copper ring"]),
    ("edge_margin_mm", 0.6, ["terminal_board.edge_margin_mm", "edge"]),
    ("rear_margin_mm", 10.0, ["terminal_board.rear_margin_mm", "bracket.foot_length_mm"]),
    ("thickness_mm", 5.0, ["terminal_board.thickness_mm", "3.2"]),
    ("pads", 3, ["terminal_board.pads", "unknown key"]),
])
def test_bad_board_values_name_the_field(plan, key, value, words):
    data = copy.deepcopy(default_rigs_data())
    data["terminal_board"][key] = value
    with pytest.raises(DesignError) as info:
        rigs_from_dict(data, plan)
    for w in words:
        assert w in str(info.value), str(info.value)


def test_board_is_made_from_sheet_with_its_own_drawing(spec):
    assert spec.kind == "fabricated" and spec.process.method is Method.SHEET
    assert stock_size(spec).startswith("sheet 1.6 mm")
    notes = drawing_of(spec).notes
    assert any("soldered" in n for n in notes(type("D", (), {"spec": spec})()))


def test_board_solid_matches_its_estimate(plan, spec):
    from tactcad.solids.build import build_part

    solid = build_part(spec)
    assert solid.volume == pytest.approx(spec.expected_volume_mm3, rel=1e-6)
    bb = solid.bounding_box()
    assert tuple(bb.min) + tuple(bb.max) == pytest.approx(spec.expected_bbox_mm, abs=1e-6)


def test_board_sits_on_the_bracket_in_every_scene_that_shows_the_bracket(project):
    assert any("bracket" in s.groups for s in project.scenes.values())
    for scene in project.scenes.values():
        model = scene_model(project.plan, scene, project.rigs)
        shown = {name: (part, group) for name, part, group in shown_instances(model, scene)}
        assert ("terminal_board" in shown) == ("bracket" in scene.groups), scene.name
        if "bracket" in scene.groups:
            assert shown["terminal_board"] == ("terminal_board", "bracket")
            assert frozenset({"array_bracket", "terminal_board"}) in model.contacts()
