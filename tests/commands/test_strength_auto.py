"""``tactcad strength`` decides the rated full-scale force as ``verify`` does: by default
(``--model auto``) the closed form, and for a rating it leaves undecided the level verify's
own climb (:func:`tactcad.studies.verification.verification_auto`) decides it at, so a
CuBe 2 x 4 rated within the closed form's 10 % no longer read UNDECIDED in ``strength``
and PASS at fem3d in ``verify``. ``--model closed-form`` keeps its output."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
from tactcad.studies import project_reports

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: a rating whose closed-form margin (+3.9 %) lies inside its limit's error (4.4 %)
INSIDE_THE_ERROR_N = 0.1152
#: an envelope for verify's footprint row (the example states no footprint)
ENVELOPE_MM = (100.0, 100.0, 100.0)
SETS = ["--set", f"requirements.full_scale_force_N={INSIDE_THE_ERROR_N}"]


def _plan(**overrides):
    return plan_from_dict(with_overrides(read_toml(EXAMPLE, "design"), overrides), str(EXAMPLE))


def _climbed_to(level, monkeypatch, asked):
    """verify's climb stood in for by one that names ``level`` (no FEM solved here)."""
    import tactcad.studies.verification as verification

    def climb(plan, progress=None, requirements=None, stress=None, levels=None,
              envelope_mm=None):
        asked.append(stress)
        return [{"requirement": "full_scale_force_N", "model": level, "verdict": "pass",
                 "decided_by": level, "levels_tried": ["closed-form", level]}], []

    monkeypatch.setattr(verification, "verification_auto", climb)


def test_an_undecided_rating_is_judged_at_the_level_verifys_climb_decides_it(monkeypatch):
    asked = []
    _climbed_to("beam", monkeypatch, asked)
    plan = _plan(**{"requirements.full_scale_force_N": INSIDE_THE_ERROR_N})
    record, _ = project_reports.strength_auto(plan, ENVELOPE_MM)
    said = record["requirement"]
    assert len(asked) == 1 and asked[0] is not None  # verify's climb, with the stresses
    assert said["model"] == "beam" and said["levels_tried"] == ["closed-form", "beam"]
    assert said == {**project_reports.strength_record(plan, "beam")[0]["requirement"],
                    "decided_by": None if said["verdict"] == "undecided" else "beam",
                    "levels_tried": ["closed-form", "beam"]}
    assert {e["model"] for e in record["elements"]} == {"beam"}


def test_a_rating_the_closed_form_decides_climbs_nowhere(monkeypatch):
    asked = []
    _climbed_to("beam", monkeypatch, asked)
    record, _ = project_reports.strength_auto(_plan(), ENVELOPE_MM)
    assert asked == [] and record["requirement"]["model"] == "closed-form"
    assert record["requirement"]["decided_by"] == "closed-form"
    assert record == {**project_reports.strength_record(_plan())[0],
                      "requirement": record["requirement"]}


def test_the_command_decides_under_auto_and_closed_form_stays_the_default(monkeypatch, capsys):
    asked = []
    _climbed_to("beam", monkeypatch, asked)
    assert main(["strength", "--design", str(EXAMPLE), *SETS]) == 0
    closed = capsys.readouterr().out
    assert asked == [] and closed.startswith("Strength, model closed-form:")
    assert "UNDECIDED" in closed and "tactcad strength --model auto" in closed
    assert main(["strength", "--design", str(EXAMPLE), *SETS, "--model", "auto"]) == 0
    said = capsys.readouterr()
    auto = said.out
    assert len(asked) == 1
    # the climb is announced before it starts, on stderr, with its cost and the way out
    assert "leaves the rated force undecided" in said.err and "--model closed-form" in said.err
    assert auto.startswith("Strength, model beam (auto: the closed form left the rated force "
                           "undecided):")
    rating = next(line for line in auto.splitlines() if line.startswith("rated full-scale "
                                                                         "force 0.1152 N ("))
    assert ", beam)" in rating and "closed-form" not in rating


@pytest.mark.parametrize("tried, words", [(["closed-form", "beam", "fem2d", "fem3d"],
                                           "fem3d is the ladder's top level"),
                                          (None, "tactcad strength --model auto")])
def test_an_undecided_hint_names_the_highest_level_tried(tried, words):
    from tactcad.commands.strength import rating_text

    judged = {"full_scale_force_N": 0.8, "reason": "stated", "verdict": "undecided",
              "element_force_limit_N": 0.81, "binding_limit": "yield", "binding_element": 1,
              "margin_rel": 0.0125, "element_force_limit_error_rel": 0.1,
              "model": "closed-form", **({"levels_tried": tried} if tried else {})}
    assert words in rating_text(judged)
