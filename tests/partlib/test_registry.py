"""The form of a part written as one module: a part module's table is
optional when every field has a default, its key clashes with no rig section
or other builder (one registry answers for every builder), the parts are derived after the parts they need (a circle
or an unknown need refused) and read only those, companions and screws
become specs of their own, and the layers above find it through the
registry alone."""

from __future__ import annotations

import dataclasses

import pytest

from tactcad.design.rig_plan import OWN_TABLES, RigsFile
from tactcad.partlib.base import RigPart
from tactcad.partlib.registry import builders, derivation_order, rig_parts_lib, topological


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


def test_every_part_module_answers_in_the_one_registry_of_builders():
    from tactcad.partlib.registry import in_use_parts, part_modules

    keys = [key for part in (*part_modules(), *in_use_parts().values()) for key in part.builders()]
    assert len(keys) == len(set(keys)) and set(keys) == set(builders())
    assert {"element", "spacer", "clamp_plate", "gauge", "bolt", "nut"} <= set(keys)


def test_the_parts_in_use_give_builders_but_no_rigs_file_table():
    from tactcad.partlib.registry import in_use_parts, rig_parts_lib

    assert set(in_use_parts()) == {"grasper_jaw", "grasper_shaft", "tissue_slab"}
    assert not set(in_use_parts()) & set(rig_parts_lib())
    assert {"grasper_jaw", "grasper_shaft", "tissue_slab"} <= set(builders())


def _refused_while_patched(monkeypatch, name: str, value, cached, match: str) -> None:
    """The registry's cached function ``cached`` refuses (ValueError matching
    ``match``) while the registry's ``name`` returns ``value``; its cache is
    cleared before and after."""
    import tactcad.partlib.registry as registry

    monkeypatch.setattr(registry, name, lambda: value)
    cached.cache_clear()
    try:
        with pytest.raises(ValueError, match=match):
            cached()
    finally:
        cached.cache_clear()


def test_a_builder_key_declared_twice_is_refused(monkeypatch):
    import tactcad.partlib.registry as registry

    twice = registry.part_modules() + (rig_parts_lib()["weights"],)
    _refused_while_patched(monkeypatch, "part_modules", twice, registry.builders,
                           "builder key 'weight' is declared twice")


def test_parts_derive_after_the_parts_they_need():
    order = derivation_order()
    assert sorted(order) == sorted(rig_parts_lib())
    for key, part in rig_parts_lib().items():
        assert all(order.index(n) < order.index(key) for n in part.needs), key


def test_needs_in_a_circle_are_refused_naming_the_circle():
    assert topological(["a", "b", "c"], {"a": ["c"], "b": [], "c": ["b"]}) == ["b", "c", "a"]
    with pytest.raises(ValueError, match="circle: a -> c -> a"):
        topological(["a", "b", "c"], {"a": ["c"], "b": [], "c": ["a"]})


def test_a_part_reads_only_the_parts_it_needs():
    from tactcad.design.rig_plan import PartContext

    context = PartContext(plan=None, parts={"cart": "cart data"}, tables={"cart": "cart table"})
    assert context.part("cart") == "cart data" and context.table("cart") == "cart table"
    with pytest.raises(KeyError, match="'sample' is read but not declared in needs"):
        context.part("sample")


def test_unknown_needs_are_refused(monkeypatch):
    import tactcad.partlib.registry as registry

    lib = dict(rig_parts_lib())
    lib["weights"] = dataclasses.replace(lib["weights"], needs=("trolley",))
    _refused_while_patched(monkeypatch, "rig_parts_lib", lib, registry.derivation_order,
                           "'weights' needs 'trolley', which no part module")


def test_table_values_copy_the_table_field_for_field():
    from tactcad.partlib.base import table_values, values_from
    from tactcad.partlib.carrier import CarrierGeometry, CarrierSection
    from tactcad.vocabulary.schema import Section, number

    table = CarrierSection(width_mm=20, height_mm=60, thickness_mm=5, shelf_depth_mm=30)
    g = values_from(CarrierGeometry, table)
    assert [f.name for f in dataclasses.fields(g)] == list(CarrierSection.model_fields)
    assert (g.width_mm, g.shelf_depth_mm) == (20, 30)
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.width_mm = 1.0

    class T(Section):
        size_mm: number(1.0, 9.0)

    extended = table_values(T, height_mm=float)
    assert values_from(extended, T(size_mm=2), height_mm=3.0).height_mm == 3.0
    assert values_from(extended, T(size_mm=2), size_mm=4.0, height_mm=3.0).size_mm == 4.0


def test_companions_and_fasteners_become_specs_with_their_builders(project):
    from tactcad.catalogue.rig_catalogue import rig_parts

    specs = rig_parts(project.plan, project.rigs)
    for key, part in rig_parts_lib().items():
        data = project.rigs.library[key]
        for one in (data, *data.companions):
            builder = specs[one.name].builder
            assert builder == (one.builder or part.builder_key) and builder in builders()
    assert {"z_stage_body", "z_stage_carriage", "rail_MGNR12R", "block_MGN12H", "wheel_spacer",
            "bearing_624ZZ"} <= set(specs)
    screws = [n for n in specs if n.startswith("bolt_")]
    fastened = {f"bolt_{f.bolt.safe_name}x{f.length_mm:g}" for d in project.rigs.library.values()
                for f in d.fasteners}
    assert set(screws) == fastened  # each screw once


def test_a_screw_of_the_arrays_size_and_length_is_still_a_rig_part(project):
    """A wheel or holder screw that happens to be the array's bolt keeps its
    own spec with its joint frame (the rig mates it by that frame); only the
    bracket's through bolts, when they are the array's own bolt, are not
    listed again."""
    import dataclasses as dc

    from tactcad.catalogue.array_catalogue import bolt_name
    from tactcad.catalogue.rig_catalogue import rig_parts
    from tactcad.partlib.base import Fastener

    plan, rigs = project.plan, project.rigs
    holder = rigs.library["sample_holder"]
    same = dc.replace(holder, fasteners=(Fastener(plan.bolt, plan.bolt_length_mm, (0.1, 0.1, 0.1)),))
    specs = rig_parts(plan, dc.replace(rigs, library={**rigs.library, "sample_holder": same}))
    assert "seat" in specs[bolt_name(plan.bolt, plan.bolt_length_mm)].frames
    bracket = rigs.library["bracket"]
    assert not bracket.fasteners or bracket.fasteners[0].length_mm != plan.bolt_length_mm


def test_a_variant_stands_in_for_its_family_only_when_its_table_is_given(monkeypatch):
    import tactcad.partlib.registry as registry

    lib = dict(registry.array_parts_lib())
    lib["spacer_x"] = dataclasses.replace(lib["spacer"], key="spacer_x", replaces="spacer")
    monkeypatch.setattr(registry, "array_parts_lib", lambda: lib)
    assert "spacer_x" not in [p.key for p in registry.array_parts_for(["design"])]
    chosen = [p.key for p in registry.array_parts_for(["design", "spacer_x"])]
    assert "spacer_x" in chosen and "spacer" not in chosen
    lib["spacer_y"] = dataclasses.replace(lib["spacer_x"], key="spacer_y")
    with pytest.raises(ValueError, match="two variants of one family"):
        registry.array_parts_for(["spacer_x", "spacer_y"])
    lib["spacer_y"] = dataclasses.replace(lib["spacer_x"], key="spacer_y", replaces="washer")
    with pytest.raises(ValueError, match="replaces 'washer', which no array part module"):
        registry.array_parts_for([])
