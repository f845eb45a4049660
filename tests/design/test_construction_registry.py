"""The constructions registry: the design file chooses one, a wrong name is
refused with the allowed ones, and the default is the stacked array."""

from __future__ import annotations

import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
from tactcad.design.construction_registry import (DEFAULT_CONSTRUCTION, Construction,
                                                  construction, construction_names,
                                                  construction_of, register_construction)
from tactcad.errors import DesignError, DesignErrors


def test_a_design_that_names_no_construction_is_stacked():
    plan = plan_from_dict(default_design_data())
    assert plan.construction == DEFAULT_CONSTRUCTION == "stacked"
    assert construction_of(plan).name == "stacked"


def test_naming_stacked_gives_the_same_plan_as_leaving_it_out():
    data = default_design_data()
    named = plan_from_dict(with_overrides(data, {"array.construction": "stacked"}))
    plain = plan_from_dict(data)
    assert named.slots == plain.slots and named.derived == plain.derived
    assert named.clamp == plain.clamp and named.spacer == plain.spacer


@pytest.mark.parametrize("bad", ["welded", "Stacked", 3])
def test_an_unknown_construction_is_refused_naming_the_allowed_ones(bad):
    with pytest.raises(DesignErrors) as caught:
        plan_from_dict(with_overrides(default_design_data(), {"array.construction": bad}))
    error = caught.value
    assert error.field == "array.construction"
    for name in construction_names():
        assert name in error.allowed


def test_looking_up_an_unknown_construction_raises_a_design_error():
    with pytest.raises(DesignError, match="array.construction"):
        construction("welded")


def test_a_name_registers_once():
    with pytest.raises(ValueError, match="registered already"):
        register_construction(Construction("stacked", "again", "tactcad.design.array_plan", ()))


def test_the_stacked_parts_come_from_its_part_modules():
    plan = plan_from_dict(default_design_data())
    names = set(array_parts(plan))
    assert any(n.startswith("element_") for n in names)
    assert "clamp_plate" in " ".join(names)
