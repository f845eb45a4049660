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
