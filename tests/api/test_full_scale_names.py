"""One rated full-scale force, under one name, in every command, page, drawing
and the API; each element's own limit under another (``yield_limited_force_N``,
"element force limit"). Tried on designs that are not the paper's: the
titanium 2 x 3 example and a 2 x 6 variant of it rated 0.077 N (the grasper
jaw's insert)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import tactcad
from tactcad.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: The 2 x 6 titanium variant: 2 mm sheet, 3 mm pitch (the M2 bolt's grip), 0.077 N rating.
TWO_BY_SIX = {"array.columns": 6, "sheet.thickness_mm": 2.0, "array.pitch_mm": 3.0,
              "arms.lengths_mm": [19.6, 6.196, 19.6, 19.6, 19.6, 19.6,
                                  19.6, 19.6, 19.6, 6.196, 19.6, 19.6],
              "requirements.full_scale_force_N": 0.077}


def _sets(values: dict) -> list[str]:
    return [arg for k, v in values.items() for arg in ("--set", f"{k}={json.dumps(v)}")]


def _json(capsys, argv: list[str]) -> dict:
    main(argv)
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("values", [{}, TWO_BY_SIX], ids=["ti_2x3", "ti_2x6"])
@pytest.mark.slow  # a whole chain through the command line or an export
def test_every_command_page_drawing_and_the_api_give_one_rated_force(capsys, values):
    from tactcad.drawings.design_notes import full_scale_note
    from tactcad.mechanics.limits import plan_limits
    from tactcad.paper.paper_load import strength_summary

    args = ["--design", str(EXAMPLE), *_sets(values)]
    strength = _json(capsys, ["strength", "--json", *args])
    verify = _json(capsys, ["verify", "--model", "closed-form", "--json", *args])
    rated = verify["requirements"]["full_scale_force_N"]
    assert rated == (values or {}).get("requirements.full_scale_force_N", 0.1)
    assert next(r["target"] for r in verify["matrix"]
                if r["requirement"] == "full_scale_force_N") == rated
    assert strength["requirement"]["full_scale_force_N"] == rated
    project = tactcad.load(EXAMPLE, set=values or None)
    plan = project.plan
    manifest = strength_summary(plan)  # the manifest's, the review page's and diff's records
    yield_limits = {lim.element: lim.force_N for lim in plan_limits(plan) if lim.limit == "yield"}
    for rec, man in zip(strength["elements"], manifest):
        assert rec["full_scale_force_N"] == man["full_scale_force_N"] == rated
        api = project.element(rec["element"]).strength()
        assert api.full_scale_force_N == rated
        assert api.yield_limited_force_N == pytest.approx(rec["yield_limited_force_N"])
        assert rec["yield_limited_force_N"] == pytest.approx(yield_limits[rec["element"]])
        assert rec["yield_limited_force_N"] != pytest.approx(rated)
        note = full_scale_note(plan, rec["part_name"], plan.material.yield_strength_MPa, "Ti")
        assert note.startswith(f"Rated full-scale force {rated:.3g} N")
        assert "element force limit" in note
    # the figures "at full scale" are at the rating
    for rec in strength["elements"]:
        assert rec["tip_deflection_mm_at_full_scale"] == pytest.approx(
            rated / rec["stiffness_N_per_mm"])


def test_the_page_and_diff_name_the_element_limit_apart_from_the_rating():
    from tactcad.export.manifest_diff import ELEMENT_FIELDS

    js = (Path(tactcad.__file__).parent / "data" / "review_page.js").read_text(encoding="utf-8")
    table = js[js.index("function showTables"):js.index("function showData")]
    assert "yield_limited_force_N: 'yield-limited force (N)'" in table
    assert "rated full-scale force" in table
    # no per-element column calls an element's own limit "full scale"
    assert not re.search(r"full_scale_force_N: '[^']*'", table)
    assert {"full_scale_force_N", "yield_limited_force_N"} <= set(ELEMENT_FIELDS)


def test_strength_met_at_the_rating_warns_of_no_limit_it_does_not_reach(capsys):
    """The symptom: "required full-scale force: met" followed by a warning that
    cycling to full scale exceeds the fatigue strength (judged at each
    element's yield-bound force, not the rating)."""
    assert main(["strength", "--design", str(EXAMPLE), *_sets(TWO_BY_SIX)]) == 0
    out = capsys.readouterr().out
    assert "rated full-scale force 0.077 N (stated in the design file): met" in out
    lowest = re.search(r"the lowest element force limit is ([\d.]+) N, bound by gauge fatigue "
                       r"strain", out)
    assert lowest and float(lowest.group(1)) > 0.077  # above the rating: met, no warning
    assert "warning" not in out
    assert "F_yield N" in out and "F_fs N" not in out
