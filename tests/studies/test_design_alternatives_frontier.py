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
