"""The form of a part written as one module: a part module's table is
optional when every field has a default, its key clashes with no rig section
or other builder, the parts are derived after the parts they need (a circle
refused), and the layers above find it through the registry alone."""

from __future__ import annotations

from tactcad.design.rigs import OWN_TABLES, RigsFile
from tactcad.parts import registry as builders
from tactcad.partlib.base import RigPart
import pytest

from tactcad.partlib.registry import derivation_order, rig_parts_lib, topological


def test_the_registry_finds_the_part_modules():
    lib = rig_parts_lib()
    assert {"push_in_fitting", "terminal_board"} <= set(lib)
    assert all(isinstance(p, RigPart) and p.key == k for k, p in lib.items())


def test_a_part_table_is_optional_exactly_when_every_field_has_a_default():
    for key, part in rig_parts_lib().items():
        assert key not in OWN_TABLES
        required = any(f.is_required() for f in part.section.model_fields.values())
        assert RigsFile.model_fields[key].is_required() == required == part.table_required, key
        if not required:
            part.section()  # the defaults make a valid table


def test_part_keys_do_not_shadow_other_builders():
    for part in rig_parts_lib().values():
        assert part.builder_key not in builders.FAMILY_BUILDERS
        assert part.builder_key in builders.BUILDERS


def test_parts_derive_after_the_parts_they_need():
    order = derivation_order()
    assert sorted(order) == sorted(rig_parts_lib())
    for key, part in rig_parts_lib().items():
        assert all(order.index(n) < order.index(key) for n in part.needs), key


def test_needs_in_a_circle_are_refused_naming_the_circle():
    assert topological(["a", "b", "c"], {"a": ["c"], "b": [], "c": ["b"]}) == ["b", "c", "a"]
    with pytest.raises(ValueError, match="circle: a -> c -> a"):
        topological(["a", "b", "c"], {"a": ["c"], "b": [], "c": ["a"]})
