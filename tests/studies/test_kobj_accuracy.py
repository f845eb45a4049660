"""``[requirements] kobj_accuracy_rel``: judged against the K_obj error budget in verify."""
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")


def _record(target):
    from tactcad.api import load
    from tactcad.studies.verification import element_figures, kobj_accuracy_record, requirements_of

    sets = {} if target is None else {"requirements.kobj_accuracy_rel": target}
    plan = load(TI, set=sets).plan
    fig = element_figures(plan)
    return kobj_accuracy_record(plan, fig, requirements_of(plan, fig))


@pytest.fixture(scope="module")
def worst():
    """(worst RSS over the range of the array's best unit, the budget's uncertainty there)."""
    from tactcad.api import load
    from tactcad.studies.verification import design_kobj_budget, element_figures, requirements_of

    plan = load(TI).plan
    fig = element_figures(plan)
    return design_kobj_budget(plan, fig, requirements_of(plan, fig)).worst_array_rss()


def test_not_stated_is_not_judged():
    assert _record(None) is None


def test_met_beyond_the_budgets_uncertainty_passes(worst):
    rss, unc = worst
    r = _record(rss * (1 + 3 * unc))
    assert r["verdict"] == "pass" and r["pass"] and r["predicted"] == pytest.approx(rss)
    assert r["error_estimate_rel"] == pytest.approx(unc)


def test_missed_beyond_it_fails(worst):
    rss, unc = worst
    r = _record(rss / (1 + 3 * unc))
    assert r["verdict"] == "fail" and not r["pass"]


def test_inside_the_budgets_own_uncertainty_is_undecided(worst):
    rss, unc = worst
    r = _record(rss * (1 + unc / 2))
    assert r["verdict"] == "undecided" and r["pass"]
    assert r["dominant"] in {p["dominant"] for p in r["points"]}


def test_the_matrix_carries_the_record_and_words_its_binding_point(worst):
    from tactcad.api import load
    from tactcad.studies.verification import binding_text, verification_matrix

    plan = load(TI, set={"requirements.kobj_accuracy_rel": 0.5}).plan
    rec = [r for r in verification_matrix(plan) if r["requirement"] == "kobj_accuracy_rel"]
    assert len(rec) == 1 and rec[0]["verdict"] == "pass" and rec[0]["stated"]
    assert "K_obj" in binding_text(rec[0]) and "N/mm" in binding_text(rec[0])


@pytest.mark.parametrize("value", [0, -0.1, 11, "'ten'"])
def test_a_bad_value_is_refused_naming_the_key_and_the_range(value):
    from tactcad.api import load
    from tactcad.errors import DesignError

    with pytest.raises(DesignError) as e:
        load(TI, set={"requirements.kobj_accuracy_rel": value})
    text = str(e.value)
    assert "kobj_accuracy_rel" in text and "10" in text


#: The Ti example widened to 2 x 4 (a stacked array of two soft elements beside each row's
#: reference and one past it): the far unit's other terms reach 1.7 % at the top of its range.
FOUR_COLUMNS = {"array.columns": 4, "arms.lengths_mm": [19.605, 6.196, 19.605, 19.605] * 2,
                "requirements.kobj_range_N_per_mm": [1.0, 5.0],
                "requirements.full_scale_force_N": 0.1}


def _accuracy_rows(target):
    """(the kobj_accuracy_rel row, the tip-height row, the budget) of the 2 x 4 array."""
    from tactcad.api import load
    from tactcad.studies.verification import (accuracy_budget, element_figures,
                                              kobj_accuracy_record, requirements_of,
                                              tip_height_tolerance_record)

    plan = load(TI, set={**FOUR_COLUMNS, "requirements.kobj_accuracy_rel": target}).plan
    fig = element_figures(plan)
    req = requirements_of(plan, fig)
    budget = accuracy_budget(plan, fig, req)
    return (kobj_accuracy_record(plan, fig, req, budget),
            tip_height_tolerance_record(plan, fig, budget), budget)


def test_an_accuracy_met_by_the_units_that_read_leaves_the_tips_a_tolerance():
    """One budget decides both rows: an accuracy the array meets (each K_obj read by its best
    unit) leaves the tip height a tolerance, though a unit that reads none of the range has
    other terms beyond it."""
    from tactcad.in_use.kobj_budget import _others_after_sq

    accuracy, tip, budget = _accuracy_rows(0.016)
    worst_other = max(float(np.sqrt(np.max(_others_after_sq(u)))) for u in budget.units)
    assert worst_other > 0.016, "the case no longer has a unit beyond the accuracy"
    assert accuracy["verdict"] == "pass"
    assert tip["target"] is not None and tip["pass"] and tip["margin_rel"] > 0, \
        tip["binding_words"]


def test_a_looser_accuracy_leaves_a_looser_tip_tolerance():
    allowances = [_accuracy_rows(a)[1]["target"] for a in (0.016, 0.1, 0.5)]
    assert None not in allowances and allowances[0] < allowances[1] < allowances[2]
