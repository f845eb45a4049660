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


def test_elements_already_kept_are_not_handed_to_other_processes(tmp_path, monkeypatch):
    """Only the elements the store does not hold are solved side by side: with one of two
    kept, the other is left to the command (no process started); at the ladder's top
    alone is it worth a process."""
    import concurrent.futures

    from tactcad.studies.parallel_solves import top_of_the_ladder

    plan = load_design(EXAMPLES / "macro_array" / "macro_array.toml")
    elements = list(plan.distinct_elements.values())[:2]
    started = []

    def pool(*args, **kwargs):
        started.append(args)
        raise OSError("no process in this test")
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", pool)
    with keeping_results(Store(tmp_path / "store")):
        assert solve_side_by_side("fem2d", elements, plan.material) == 0
        assert started  # neither kept: both would have gone to processes
        started.clear()
        estimate("fem2d", elements[0], plan.material)
        assert solve_side_by_side("fem2d", elements, plan.material) == 0
        assert not started
    assert top_of_the_ladder("fem3d") and not top_of_the_ladder("fem2d")


def test_only_kept_answers_from_the_store_and_computes_nothing(tmp_path):
    from tactcad.store import NotKept, kept_result, only_kept

    with keeping_results(Store(tmp_path / "store")):
        with only_kept(), pytest.raises(NotKept):
            kept_result("a sum", lambda: 1 + 1, "inputs")
        assert kept_result("a sum", lambda: 1 + 1, "inputs") == 2
        with only_kept():
            assert kept_result("a sum", lambda: 3, "inputs") == 2


def test_at_fem3d_the_peak_stress_sequences_go_to_the_processes_after_every_k(
        tmp_path, monkeypatch):
    """A verification at fem3d reads each element's K and its peak stress, two sequences an
    element: the stress ones were solved in turn after the K's side by side; now all four
    share the cores (every K first), and at fem2d only the K's go (its stress is cheap)."""
    import concurrent.futures

    from tactcad.studies import parallel_solves

    plan = load_design(EXAMPLES / "macro_array" / "macro_array.toml")
    elements = list(plan.distinct_elements.values())[:2]
    submitted = []

    class Pool:
        def __init__(self, workers, **kwargs):
            self.workers = workers

        def submit(self, fn, root, model, g, material, what):
            submitted.append((model, what, g.part_name))
            done = concurrent.futures.Future()
            done.set_result(None)
            return done

        def shutdown(self, wait=True, cancel_futures=False):
            pass

    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", Pool)
    monkeypatch.setattr(parallel_solves, "_kept", lambda *args: False)
    lines = []
    with keeping_results(Store(tmp_path / "store")):
        assert solve_side_by_side("fem3d", elements, plan.material, lines.append,
                                  peak_stress=True) == 2
        names = [g.part_name for g in elements]
        assert submitted == [("fem3d", "stiffness", n) for n in names] + \
            [("fem3d", "peak stress", n) for n in names]
        assert lines == ["fem3d: 4 solves (the K and peak stress of 2 elements) side by side "
                         "in 2 processes"]
        submitted.clear()
        solve_side_by_side("fem2d", elements, plan.material, peak_stress=True)
        assert [what for _, what, _ in submitted] == ["stiffness", "stiffness"]
        # the stresses a verification keeps from below (strengths_decided_below): every K,
        # the peak stress of the other element alone
        submitted.clear(), lines.clear()
        solve_side_by_side("fem3d", elements, plan.material, lines.append, peak_stress=True,
                           stress_geometries=elements[1:])
        assert submitted == [("fem3d", "stiffness", n) for n in names] + \
            [("fem3d", "peak stress", names[1])]
        assert lines == ["fem3d: 3 solves (the K of 2 elements, the peak stress of 1) side by "
                         "side in 2 processes"]


def test_a_processs_peak_stress_sequence_is_the_one_the_strength_study_reads(monkeypatch):
    """The sequence a process solves for an element's peak stress is asked with the very
    arguments :func:`fem_peak_stress` asks it with (so it reads it back from the store)."""
    import tactcad.mechanics.fem.fem3d as fem3d
    from tactcad.studies import parallel_solves, strength_studies

    class Asked(Exception):
        pass

    calls = []

    def recorded(*args, **kwargs):
        calls.append((args, kwargs))
        raise Asked
    monkeypatch.setattr(fem3d, "fem3d_convergence", recorded)
    plan = load_design(EXAMPLES / "macro_array" / "macro_array.toml")
    g = next(iter(plan.distinct_elements.values()))
    with pytest.raises(Asked):
        parallel_solves._compute(parallel_solves.PEAK_STRESS, "fem3d", g, plan.material)
    with pytest.raises(Asked):
        strength_studies.fem_peak_stress(g, plan.material, "fem3d")
    assert len(calls) == 2 and calls[0] == calls[1]
    assert calls[0][0][0] == g.bare()
