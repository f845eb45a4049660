"""The hard stops' check group: one result per element of a construction
with stops, none for one without."""

from __future__ import annotations

from dataclasses import replace

from tactcad.checks.groups import CheckContext
from tactcad.checks.stop_checks import stop_group
from tactcad.design.array_plan import EXAMPLES, load_design


def test_the_group_gives_one_result_per_element_of_the_comb(tmp_path):
    plan = load_design(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    found = list(stop_group(CheckContext(plan, tmp_path, None)))
    assert [label for label, _ in found] == ["hard stops"]
    results = found[0][1]
    assert [r.subject for r in results] == [f"element {s.number}" for s in plan.slots]
    assert all(r.passed for r in results)


def test_a_stop_past_yield_fails_its_element_only(tmp_path):
    plan = load_design(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    stops = list(plan.hard_stops)
    stops[4] = replace(stops[4], gap_mm=0.5, kind="cut", cut_mm=0.5)
    results = list(stop_group(CheckContext(replace(plan, hard_stops=tuple(stops)), tmp_path, None)))[0][1]
    assert [r.subject for r in results if not r.passed] == ["element 5"]


def test_the_group_is_silent_for_a_construction_without_stops(tmp_path):
    plan = load_design(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
    assert list(stop_group(CheckContext(plan, tmp_path, None))) == []
