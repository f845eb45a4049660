"""``[requirements] kobj_accuracy_rel``: judged against the K_obj error budget in verify."""
from pathlib import Path

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
