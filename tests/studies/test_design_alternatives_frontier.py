"""The largest feasible force a refusal names is the frontier of the search, whatever force
was asked: a bracket grown from the web search's estimate, then bisection in it."""

from __future__ import annotations

import pytest

import tactcad.studies.design_alternatives as alternatives
from tactcad.studies.inverse_design import Targets


@pytest.mark.parametrize("asked", [50.0, 0.3, 0.2, 0.19])
def test_the_largest_feasible_force_does_not_move_with_the_force_asked(monkeypatch, asked):
    # a layout whose whole designs carry up to 0.187 N, its web search estimating 0.148 N
    # (the 7075-T6 2 x 3 case: 50 N asked gave "at most 0.155", 0.3 N "at most 0.183")
    frontier = 0.1873
    monkeypatch.setattr(alternatives, "_largest_force", lambda data, targets, correction: 0.148)
    monkeypatch.setattr(alternatives, "_feasible",
                        lambda data, targets, correction: targets.full_scale_force_N <= frontier)
    found = alternatives.largest_feasible_force({}, Targets(10.0, (1.0, 5.0), asked))
    assert found <= frontier and found == pytest.approx(frontier, rel=0.01)


def test_an_offered_range_is_never_the_asked_one(monkeypatch):
    # on the one layout the scans design on, the asked targets held: the 17-4PH refusal
    # offered "--kobj-range 1 20 (moved to the nearest feasible)", the range asked
    monkeypatch.setattr(alternatives, "_largest_force", lambda data, targets, correction: 0.0)
    monkeypatch.setattr(alternatives, "_feasible", lambda data, targets, correction: True)
    asked = Targets(8.0, (1.0, 20.0), 0.3)
    near = {a.field: a.value for a in alternatives.nearest_targets({}, asked)}
    assert near.get("--kobj-range") != (1.0, 20.0)
    assert near.get("--kr-over-km") != 8.0


def test_an_offer_refused_when_pasted_is_replaced_by_one_that_designs(monkeypatch):
    # the scan's layout met K_r/K_m 8.22 (rounded up from 8.2105) but the pasted command's
    # search refused it, and every ratio above 8; it designs at 7.4 and below
    monkeypatch.setattr(alternatives, "_largest_force", lambda data, targets, correction: 0.0)
    monkeypatch.setattr(alternatives, "_feasible",
                        lambda data, targets, correction: targets.kr_over_km >= 8.2105)
    judged: dict[float, bool] = {}

    def designs(targets, change=None):
        judged[targets.kr_over_km] = targets.kr_over_km <= 7.4
        return judged[targets.kr_over_km]

    asked = Targets(8.0, (1.0, 20.0), 0.3)
    near = {a.field: a.value for a in alternatives.nearest_targets({}, asked, designs=designs)}
    ratio = near["--kr-over-km"]
    assert judged[ratio] and ratio <= 7.4 and ratio > 6.5  # judged as pasted, and near
    assert "--full-scale-force" not in near  # the search's own frontier offers the force


def test_a_change_the_pasted_search_refuses_does_not_meet_every_target(monkeypatch):
    # the CuBe refusal's "--material 17-4PH-H900: meets every target", judged on one
    # layout, was refused when pasted: the change now carries the force it designs at
    monkeypatch.setattr(alternatives, "_largest_force", lambda data, targets, correction: 0.31)
    monkeypatch.setattr(alternatives, "_feasible",
                        lambda data, targets, correction: targets.full_scale_force_N <= 0.3)
    monkeypatch.setattr(alternatives, "largest_feasible_force",
                        lambda data, targets, correction=None: 0.3)
    monkeypatch.setattr("tactcad.vocabulary.material_library.material_grades",
                        lambda: ("CuBe-C17200-TF00", "17-4PH-H900"))
    monkeypatch.setattr("tactcad.vocabulary.material_library.strain_gauges", lambda: ())

    def designs(targets, change=None):
        return targets.full_scale_force_N <= 0.288

    data = {"material": {"name": "CuBe-C17200-TF00", "grade": "CuBe-C17200-TF00"},
            "sheet": {"thickness_mm": 6.0}, "strength": {}}
    asked = Targets(8.0, (1.0, 20.0), 0.3)
    (change,) = alternatives.relaxing_changes(data, asked, designs=designs)
    assert change.value == "17-4PH-H900" and not change.meets_targets
    assert change.largest_force_N == pytest.approx(0.281)  # 0.299, 0.29 refused; 0.281 designs
