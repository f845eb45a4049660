"""The push-in vacuum fitting, a part written as one module: optional table,
refusals naming its fields, a bought envelope with its catalogue reference,
placed on the cart's hose port in every scene that shows the cart."""

from __future__ import annotations

import copy
import math

import pytest

from tactcad.assembly.rig_models import scene_model, shown_instances
from tactcad.catalogue.rig_catalogue import rig_parts
from tactcad.design.rig_plan import default_rigs_data, rigs_from_dict
from tactcad.errors import DesignError
from tactcad.vocabulary.process import Method


@pytest.fixture(scope="module")
def rigs(plan):
    return rigs_from_dict(default_rigs_data(), plan)


def test_a_rigs_file_without_the_table_gets_the_default_fitting(plan, rigs):
    data = default_rigs_data()
    del data["push_in_fitting"]
    data["assumptions"] = {k: v for k, v in data["assumptions"].items()
                           if not k.startswith("push_in_fitting.")}
    bare = rigs_from_dict(data, plan)
    assert bare.library["push_in_fitting"] == rigs.library["push_in_fitting"]


@pytest.mark.parametrize("key, value, words", [
    ("thread_diameter_mm", 6.0, ["push_in_fitting.thread_diameter_mm", "6", "cart.port_diameter_mm"]),
    ("thread_length_mm", 7.0, ["push_in_fitting.thread_length_mm", "cart.port_depth_mm"]),
    ("hex_across_flats_mm", 13.0, ["push_in_fitting.hex_across_flats_mm", "cart.thickness_mm"]),
    ("body_diameter_mm", 3.5, ["push_in_fitting.body_diameter_mm", "tube"]),
    ("colour", "blue", ["push_in_fitting.colour", "unknown key"]),
    ("hex_height_mm", "4", ["push_in_fitting.hex_height_mm"]),
])
def test_bad_fitting_values_name_the_field(plan, key, value, words):
    data = copy.deepcopy(default_rigs_data())
    data["push_in_fitting"][key] = value
    with pytest.raises(DesignError) as info:
        rigs_from_dict(data, plan)
    for w in words:
        assert w in str(info.value), str(info.value)


def test_fitting_is_a_bought_envelope_with_its_catalogue_reference(plan, rigs):
    spec = rig_parts(plan, rigs)["push_in_fitting_M5"]
    assert spec.kind == "purchased" and spec.process.method is Method.BOUGHT
    assert "SMC KQ2H04-M5A" in spec.process
    g = spec.geometry
    hexagon = math.sqrt(3) / 2 * g.hex_across_flats_mm ** 2 * g.hex_height_mm
    assert spec.expected_volume_mm3 > hexagon
    reach = next(d for d in rigs.derived if d.name == "push_in_fitting_reach")
    assert reach.value == pytest.approx(g.hex_height_mm + g.body_length_mm)


def test_fitting_envelope_matches_its_estimate(plan, rigs):
    from tactcad.solids.build import build_part

    spec = rig_parts(plan, rigs)["push_in_fitting_M5"]
    solid = build_part(spec)
    assert solid.volume == pytest.approx(spec.expected_volume_mm3, rel=1e-6)
    bb = solid.bounding_box()
    assert tuple(bb.min) + tuple(bb.max) == pytest.approx(spec.expected_bbox_mm, abs=1e-6)


def test_fitting_sits_on_the_cart_in_every_scene_that_shows_the_cart(project):
    assert any("cart" in s.groups for s in project.scenes.values())
    for scene in project.scenes.values():
        model = scene_model(project.plan, scene, project.rigs)
        shown = {name: (part, group) for name, part, group in shown_instances(model, scene)}
        assert ("push_in_fitting" in shown) == ("cart" in scene.groups), scene.name
        if "cart" in scene.groups:
            assert shown["push_in_fitting"] == ("push_in_fitting_M5", "cart")
            assert frozenset({"cart", "push_in_fitting"}) in model.contacts()
