"""A design's elements solved side by side, one process each, into the command's store:
the command's own solve reads them back and solves nothing again; without a store on
disk nothing is prefetched."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import EXAMPLES, load_design
from tactcad.mechanics.ladder import estimate
from tactcad.store import Store, keeping_results
from tactcad.studies.parallel_solves import solve_side_by_side


@pytest.mark.slow  # processes started by spawn
def test_the_elements_solved_side_by_side_are_read_back_not_solved_again(tmp_path, monkeypatch):
    plan = load_design(EXAMPLES / "macro_array" / "macro_array.toml")
    elements = list(plan.distinct_elements.values())[:2]
    with keeping_results(Store(tmp_path / "store")):
        assert solve_side_by_side("fem2d", elements, plan.material) == 2
        import tactcad.mechanics.fem.fem2d as fem2d

        def solved_again(*args, **kwargs):
            raise AssertionError("solved again in this process")
        monkeypatch.setattr(fem2d, "estimate_fem2d", solved_again)
        for g in elements:
            assert estimate("fem2d", g, plan.material).stiffness_N_per_mm > 0


def test_nothing_is_prefetched_without_a_store_on_disk_or_with_one_element():
    plan = load_design(EXAMPLES / "macro_array" / "macro_array.toml")
    elements = list(plan.distinct_elements.values())
    with keeping_results(Store(None)):
        assert solve_side_by_side("fem3d", elements, plan.material) == 0
    assert solve_side_by_side("fem3d", elements, plan.material) == 0  # no store block
