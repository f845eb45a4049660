"""Hard stops: each engages after the rated deflection and before yield, and
the check names the element and the values when one does not."""

from __future__ import annotations

from dataclasses import replace

import pytest

from tactcad.checks.stop_checks import stop_checks
from tactcad.design.array_plan import EXAMPLES, HardStop, load_design
from tactcad.mechanics.hard_stops import engagement_travel_mm, stop_gap_for, stop_verdicts

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
FORCE_N = 0.05


@pytest.fixture(scope="module")
def plan():
    return load_design(GRASPER)


def test_every_element_of_the_comb_has_a_stop(plan):
    assert [s.element for s in plan.hard_stops] == [s.number for s in plan.slots]


def test_every_stop_engages_between_rating_and_yield(plan):
    verdicts = stop_verdicts(plan, FORCE_N)
    assert len(verdicts) == len(plan.slots)
    for v in verdicts:
        assert v.rated_tip_mm < v.engage_tip_mm < v.yield_tip_mm, v


def test_a_gap_past_yield_fails_and_the_check_names_the_element(plan):
    first = plan.hard_stops[0]
    wide = replace(first, gap_mm=1.0, kind="cut", cut_mm=1.0)
    broken = replace(plan, hard_stops=(wide, *plan.hard_stops[1:]))
    v = stop_verdicts(broken, FORCE_N)[0]
    assert v.engage_tip_mm > v.yield_tip_mm and not v.engages_between
    result = stop_checks(broken)[0]
    assert not result.passed and result.subject == f"element {first.element}"
    assert "yield-limited" in result.detail


def test_a_gap_under_the_rated_deflection_fails(plan):
    first = plan.hard_stops[1]
    narrow = replace(first, gap_mm=1e-4)
    v = stop_verdicts(replace(plan, hard_stops=(narrow,)), FORCE_N)[0]
    assert v.engage_tip_mm < v.rated_tip_mm and not v.engages_between


def test_the_gap_for_a_multiple_inverts_the_engagement_travel():
    stop = HardStop(1, 0.05, 3.5, "set", 0.13)
    gap = stop_gap_for(1.3, 0.02, stop, 3.0)
    assert engagement_travel_mm(replace(stop, gap_mm=gap), 3.0) == pytest.approx(1.3 * 0.02)


def test_a_construction_without_stops_has_no_stop_checks():
    assert stop_checks(load_design(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")) == []


def test_a_non_positive_gap_is_refused():
    with pytest.raises(ValueError, match="element 3"):
        engagement_travel_mm(HardStop(3, 0.0, 3.5, "set", 0.13), 3.0)
