"""The element drawing's full-scale force note judges the rating as verify does: met,
NOT met, or undecided where the margin lies inside the closed form's error (it said met
wherever the limit reached the rating, verify's UNDECIDED included)."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import default_design_data, plan_from_dict
from tactcad.drawings.design_notes import full_scale_note, rating_verdict_words
from tactcad.mechanics.verdicts import verdict


@pytest.mark.parametrize("limit, rated, error, expected", [
    (0.40, 0.30, 0.10, "met"),
    (0.20, 0.30, 0.10, "NOT met"),
    (0.301, 0.30, 0.10, "undecided"),
    (0.29, 0.30, 0.10, "undecided"),  # short of the rating, but inside the error too
])
def test_the_rating_is_judged_by_verifys_rule(limit, rated, error, expected):
    words = rating_verdict_words(limit, rated, error)
    assert words.split()[0] == expected.split()[0], words
    if expected == "undecided":
        assert "tactcad verify" in words and f"{error:.1%}" in words


def test_the_notes_verdict_is_verifys_on_each_element():
    from tactcad.mechanics.limits import plan_limits

    plan = plan_from_dict(default_design_data())
    rated = None
    for lim in plan_limits(plan, "closed-form"):
        note = full_scale_note(plan, lim.part_name, plan.material.yield_strength_MPa, "x")
        rated = float(note.split()[3])
        lowest = min((x for x in plan_limits(plan, "closed-form")
                      if x.part_name == lim.part_name), key=lambda x: x.force_N)
        said = verdict(lowest.force_N / rated - 1, lowest.error_estimate_rel, 0.0,
                       lowest.force_N >= rated)
        expected = {"pass": "(the design's, met)", "fail": "(the design's, NOT met)",
                    "undecided": "(the design's, undecided at the closed form"}[said]
        assert expected in note, (said, note)
    assert rated is not None
