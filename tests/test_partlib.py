"""The form of a part written as one module: every part module's table is
optional, its key clashes with no rig section or other builder, and the
layers above find it through the registry alone."""

from __future__ import annotations

from tactcad.design.rigs import _RigsFileBase, RigsFile
from tactcad.parts import registry as builders
from tactcad.partlib.base import RigPart
from tactcad.partlib.registry import rig_parts_lib


def test_the_registry_finds_the_part_modules():
    lib = rig_parts_lib()
    assert {"push_in_fitting", "terminal_board"} <= set(lib)
    assert all(isinstance(p, RigPart) and p.key == k for k, p in lib.items())


def test_every_part_table_is_optional_and_clashes_with_nothing():
    legacy_sections = set(_RigsFileBase.model_fields)
    for key, part in rig_parts_lib().items():
        assert key not in legacy_sections
        assert not RigsFile.model_fields[key].is_required()
        assert all(not f.is_required() for f in part.section.model_fields.values()), key
        part.section()  # the defaults make a valid table


def test_part_keys_do_not_shadow_other_builders():
    for key in rig_parts_lib():
        assert key not in builders.FAMILY_BUILDERS and key in builders.BUILDERS
