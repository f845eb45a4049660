"""The grasp's contact solves are kept in the result store (``--cache``): a later run reads
them back, the same bits, instead of converging them afresh; and they are the solves the
tissue-coupling model (verify, the budget) keeps, under one kind. The layer's correction
table is kept too: a grasp on another tissue thickness reads it back."""

from __future__ import annotations

import numpy as np

from tactcad.in_use.grasp_experiment import tissue_compliance
from tactcad.mechanics import contact
from tactcad.mechanics.contact import CONVERGED_KIND, CORRECTION_KIND, Punch
from tactcad.store import Store, counting_results, keeping_results

#: Two small tip faces a pitch apart (mm): a solve of a second or so.
FACES = [Punch(0.0, 0.0, 0.5, 0.5), Punch(1.0, 0.0, 0.5, 0.5)]


def grasp_tissue(store: Store, coupling: str = "halfspace", slab_mm: float = 3.0
                 ) -> tuple[np.ndarray, dict[str, int], dict[str, int]]:
    """The grasp's tissue compliance in a fresh run on ``store`` (``slab_mm`` the layer's
    thickness, mm): (C in mm/N, what was computed, what was read back)."""
    contact._converged_unit.cache_clear()  # a new process: nothing kept in memory
    contact._correction_spline.cache_clear()
    with keeping_results(store), counting_results() as counts:
        c = tissue_compliance(FACES, 5.0, slab_mm, coupling=coupling)
    return c, dict(counts.computed), dict(counts.reused)


def test_a_later_run_reads_the_converged_solves_back_from_the_store(tmp_path):
    store = Store(tmp_path / "store")
    first, computed, reused = grasp_tissue(store)
    assert computed.get(CONVERGED_KIND, 0) >= 1 and CONVERGED_KIND not in reused
    again, computed, reused = grasp_tissue(store)
    assert CONVERGED_KIND not in computed and reused.get(CONVERGED_KIND, 0) >= 1
    assert np.array_equal(first, again)
    assert first[0, 1] > 0 and np.allclose(first, first.T)


def test_without_a_store_every_run_solves_again(tmp_path):
    _, computed, _ = grasp_tissue(Store(None))
    _, again, reused = grasp_tissue(Store(None))
    assert computed.get(CONVERGED_KIND, 0) >= 1 and again == computed
    assert CONVERGED_KIND not in reused


def test_a_grasp_on_another_thickness_reads_the_layers_correction_table_back(tmp_path):
    store = Store(tmp_path / "store")
    _, computed, _ = grasp_tissue(store, "layer", 3.0)
    assert computed.get(CORRECTION_KIND) == 1
    table = contact._correction_spline("bonded", 0.5)
    thinner, computed, reused = grasp_tissue(store, "layer", 2.0)
    assert CORRECTION_KIND not in computed and reused.get(CORRECTION_KIND) == 1
    assert computed.get(CONVERGED_KIND, 0) >= 1  # a new thickness: its solves are new
    assert np.array_equal(contact._correction_spline("bonded", 0.5), table)
    assert np.all(np.isfinite(thinner)) and thinner[0, 0] > thinner[0, 1] > 0
