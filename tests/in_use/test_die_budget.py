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
    summed = [v for k, v in budget.terms.items() if k != db.UNCOUPLED]
    assert np.allclose(budget.total_rel, np.sqrt(sum(np.asarray(v) ** 2 for v in summed)))
    # the unit's two posts stand a fraction of a millimetre apart: eq. 3 alone is far off
    assert np.all(budget.terms[db.UNCOUPLED] > 0.1)
    assert np.all(budget.terms[db.COUPLED] < 0.1 * budget.terms[db.UNCOUPLED])
    assert set(budget.as_json()["terms_rel"]) == set(budget.terms)
