"""The die's K_obj budget: each term moves with what sizes it, the summed terms leave out
the uncoupled eq. 3's bias (the coupled inversion removes it), and the record carries it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tactcad.products.silicon_die.design.mems_die import die_plan
from tactcad.products.silicon_die.in_use import die_budget as db
from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.studies.inverse_design import Targets


@pytest.fixture(scope="module")
def plan():
    return die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"))


@pytest.fixture(scope="module")
def budget(plan):
    return db.die_budget(plan)


def test_the_read_out_term_grows_with_the_bridges_noise(plan, budget):
    readout = die_readout(plan)
    noisier = {**readout, "rows": {role: {**row, "force_resolution_N": 1000 * row[
        "force_resolution_N"]} for role, row in readout["rows"].items()}}
    louder = db.die_budget(plan, noisier).terms["read-out noise"]
    assert np.all(louder > 500 * budget.terms["read-out noise"])


def test_a_layer_held_exactly_leaves_no_device_layer_term(plan, budget):
    exact = dataclasses.replace(plan, stack=dataclasses.replace(plan.stack,
                                                                device_tolerance_um=0.0))
    assert np.allclose(db.die_budget(exact).terms["device layer"], 0.0, atol=1e-12)
    assert np.all(budget.terms["device layer"] > 0.005)


def test_the_sum_leaves_out_the_uncoupled_bias_and_keeps_what_the_inversion_leaves(budget):
    summed = [v for k, v in budget.terms.items() if k not in db.SHOWN_NOT_SUMMED]
    assert db.UNCOUPLED in db.SHOWN_NOT_SUMMED
    assert np.allclose(budget.total_rel, np.sqrt(sum(np.asarray(v) ** 2 for v in summed)))
    # the unit's two posts stand a fraction of a millimetre apart: eq. 3 alone is far off
    assert np.all(budget.terms[db.UNCOUPLED] > 0.1)
    assert np.all(budget.terms[db.COUPLED] < 0.1 * budget.terms[db.UNCOUPLED])
    assert set(budget.as_json()["terms_rel"]) == set(budget.terms)


def test_the_reading_terms_are_the_coupled_inversions_of_the_perturbed_coupled_r(plan, budget):
    """The read-out noise and the resistor zero drift perturb each deflection on the coupled
    sample (every post pressing) and are read back by the coupled inversion, checked here
    against the coupled model directly; eq. 3 on eq. 2's R (the former path) differs."""
    from tactcad.in_use.tissue_coupling import Tissue, coupled_object_stiffness, coupled_ratio
    from tactcad.in_use.tissue_coupling import coupled_sample_from_punches
    from tactcad.mechanics.contact import Punch
    from tactcad.mechanics.lumped_model import deflection_ratio, object_stiffness

    side = plan.post_um * 1e-3
    sample = coupled_sample_from_punches(
        [b.number for b in plan.beams],
        [Punch(b.x_um * 1e-3, b.tip_y_um * 1e-3, side, side) for b in plan.beams], Tissue())
    k = {b.number: plan.k_r_N_per_mm if b.role == "reference" else plan.k_m_N_per_mm
         for b in plan.beams}
    pair = (plan.beams[plan.columns + plan.columns // 2].number,
            plan.beams[plan.columns // 2].number)
    ks = budget.k_obj_N_per_mm
    readout = die_readout(plan)
    rows = readout["rows"]
    e_r = plan.full_scale_force_N / plan.k_r_N_per_mm
    r = np.atleast_1d(coupled_ratio(sample, k, pair, ks))
    e_m = r * e_r
    noise = np.hypot(rows["reference"]["force_resolution_N"] / plan.k_r_N_per_mm / e_r,
                     rows["measuring"]["force_resolution_N"] / plan.k_m_N_per_mm / e_m)
    step = db.TEMPERATURE_STEP_K / np.sqrt(3)
    drifted = ((e_m + rows["measuring"]["zero_drift_N_per_K"] * step / plan.k_m_N_per_mm)
               / (e_r + rows["reference"]["zero_drift_N_per_K"] * step / plan.k_r_N_per_mm))

    def read(x):
        return np.array([coupled_object_stiffness(sample, k, pair, float(v)) for v in x]) / ks - 1

    assert budget.terms["read-out noise"] == pytest.approx(np.abs(read(r * (1 + noise))),
                                                           rel=1e-6)
    assert budget.terms["resistor zero drift"] == pytest.approx(np.abs(read(drifted)), rel=1e-6)
    # the former path: eq. 3 on eq. 2's R, the noise over eq. 2's deflections
    r2 = np.array([float(deflection_ratio(plan.k_m_N_per_mm, plan.k_r_N_per_mm, x)) for x in ks])
    noise2 = np.hypot(rows["reference"]["force_resolution_N"] / plan.k_r_N_per_mm / e_r,
                      rows["measuring"]["force_resolution_N"] / plan.k_m_N_per_mm / (r2 * e_r))
    eq3 = np.abs(np.array([float(object_stiffness(float(x), plan.k_m_N_per_mm, plan.k_r_N_per_mm))
                           for x in r2 * (1 + noise2)]) / ks - 1)
    assert not np.allclose(budget.terms["read-out noise"], eq3, rtol=0.02)


def test_the_posts_as_made_are_shown_and_what_the_zeroing_leaves_is_summed(plan, budget):
    as_made, zeroed = budget.terms[db.AS_MADE], budget.terms[db.ZEROED]
    summed = [v for k, v in budget.terms.items() if k not in (db.UNCOUPLED, db.AS_MADE)]
    assert np.allclose(budget.total_rel, np.sqrt(sum(np.asarray(v) ** 2 for v in summed)))
    assert np.all(zeroed > 0) and np.all(zeroed < as_made)
    assert db.AS_MADE in budget.as_json()["rss_leaves_out"]
    record = budget.tip_height
    assert record["tolerance_mm"] == pytest.approx(plan.post_height_um * 1e-3 * 0.02)
    assert record["tolerance_mm"] > record["mismatch_after_zeroing_mm"] > 0
    assert record["tolerance_for_accuracy_mm"] is None  # no kobj_accuracy_rel stated


def test_the_post_term_vanishes_without_a_mismatch_and_grows_linearly_while_small(plan, budget):
    unit = db._die_unit(plan)
    ks = budget.k_obj_N_per_mm
    assert np.all(db.post_mismatch_rel(plan, unit, ks, 0.0) == 0.0)
    small, double = (db.post_mismatch_rel(plan, unit, ks, d) for d in (2e-6, 4e-6))
    assert np.all(small > 0)
    assert double / small == pytest.approx(np.full(len(ks), 2.0), rel=0.05)


def test_the_post_tolerance_the_accuracy_needs_fills_what_the_other_terms_leave(plan, budget):
    others_sq = sum(np.asarray(v) ** 2 for k, v in budget.terms.items()
                    if k not in (db.UNCOUPLED, db.AS_MADE, db.ZEROED))
    accuracy = 1.5 * float(np.sqrt(np.max(others_sq)))
    stated = db.die_budget(dataclasses.replace(plan, kobj_accuracy_rel=accuracy))
    tol = stated.tip_height["tolerance_for_accuracy_mm"]
    assert tol is not None and tol > 0
    unit = db._die_unit(plan)
    ks = budget.k_obj_N_per_mm

    def worst(t):
        return float(np.sqrt(np.max(others_sq + db.post_mismatch_rel(plan, unit, ks, 2 * t) ** 2)))

    assert worst(tol) == pytest.approx(accuracy, rel=0.01)  # printed to three digits
    assert worst(1.05 * tol) > accuracy
    tight = db.die_budget(dataclasses.replace(plan, kobj_accuracy_rel=0.5 * accuracy / 1.5))
    assert tight.tip_height["tolerance_for_accuracy_mm"] is None
