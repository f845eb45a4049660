"""copy_tables: a design's tables copied with nothing mutable shared, as deepcopy does."""

import copy

from tactcad.design.array_plan import EXAMPLES, read_toml
from tactcad.vocabulary.schema import copy_tables


def test_a_copy_of_a_designs_tables_equals_deepcopy_and_shares_no_table_or_array():
    tables = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")
    tables["extra"] = {"pair": ([1.0], {"a": 2}), "kinds": {"x"}}
    copied = copy_tables(tables)
    assert copied == copy.deepcopy(tables)

    def containers(value, path=()):
        if isinstance(value, (dict, list, set)):
            yield path, value
        items = value.items() if isinstance(value, dict) else \
            enumerate(value) if isinstance(value, (list, tuple)) else ()
        for k, v in items:
            yield from containers(v, path + (k,))

    mine = dict(containers(copied))
    for path, original in containers(tables):
        assert mine[path] is not original, path


def test_a_copy_calls_itself_for_tables_and_arrays_alone(monkeypatch):
    """A scalar entry is taken as it is, not copied by a call of its own (most of a design's
    entries are scalars: a call each was half a copy's time, and a design search copies
    the tables for every candidate it tries)."""
    from tactcad.vocabulary import schema

    tables = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")
    tables["extra"] = {"pair": ([1.0, None, "a"], {"a": 2}), "kinds": {"x"}, "flag": True}
    copied_by = schema.copy_tables
    calls = []

    def counted(value):
        calls.append(type(value))
        return copied_by(value)

    monkeypatch.setattr(schema, "copy_tables", counted)
    assert counted(tables) == copy.deepcopy(tables)
    assert calls and set(calls) <= {dict, list, tuple, set}
