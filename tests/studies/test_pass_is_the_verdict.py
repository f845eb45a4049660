"""``pass`` and ``met`` are True only for a PASS verdict: a rating met nominally inside the
level's error (verdict ``undecided``) once read ``"verdict": "undecided"`` beside
``"met": true`` (``strength --json``) and ``"pass": true`` (the manifest's
``requirements.closed_form_matrix``), so a script reading the flag took it for a pass."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
from tactcad.studies.project_reports import strength_record
from tactcad.studies.verification import passed_flag, requirements_record, verification_matrix

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: a rating whose closed-form margin (+3.9 %) lies inside its limit's error (4.4 %)
INSIDE_THE_ERROR_N = 0.1152


def _plan(**overrides):
    return plan_from_dict(with_overrides(read_toml(EXAMPLE, "design"), overrides), str(EXAMPLE))


@pytest.mark.parametrize("said, flag", [("pass", True), ("fail", False),
                                        ("undecided", False), ("info", None)])
def test_the_flag_is_the_verdicts(said, flag):
    assert passed_flag(said) is flag


def test_an_undecided_rating_is_not_met_in_any_output():
    plan = _plan(**{"requirements.full_scale_force_N": INSIDE_THE_ERROR_N})
    said = strength_record(plan)[0]["requirement"]
    assert said["verdict"] == "undecided" and said["margin_rel"] > 0
    assert said["met"] is False
    row = next(r for r in verification_matrix(plan, "closed-form")
               if r["requirement"] == "full_scale_force_N")
    assert row["verdict"] == "undecided" and row["pass"] is False
    record = requirements_record(plan, (100.0, 100.0, 100.0))
    force = next(r for r in record["closed_form_matrix"]
                 if r["requirement"] == "full_scale_force_N")
    assert force["verdict"] == "undecided" and force["pass"] is False
    assert record["full_scale_force"]["met"] is False
    # and it says why: undecided at the closed form, not failed
    assert record["full_scale_force"]["verdict"] == "undecided"
    assert record["full_scale_force"]["model"] == "closed-form"


def test_every_judged_row_says_its_verdict_in_its_flag():
    for r in verification_matrix(_plan(), "closed-form"):
        assert r["pass"] is passed_flag(r["verdict"]), r["requirement"]
    assert strength_record(_plan())[0]["requirement"]["met"] is True
