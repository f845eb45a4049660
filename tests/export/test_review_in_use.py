"""The tissue coupling and the grasp at the maximum grasp force in the manifest and on the
review page: one table each, the figures with their units."""

from __future__ import annotations

import pytest

import json
from pathlib import Path

from tactcad.commands.finite_json import dumps
from tactcad.export.review_page import grasp_view, tissue_coupling_view

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _facts(sets=None):
    from tactcad.api import load
    from tactcad.export.manifest import design_facts

    return json.loads(dumps(design_facts(load(str(EXAMPLE), set=sets or {}).plan)))


def test_the_manifest_carries_the_tissue_coupling_and_the_page_its_table():
    facts = _facts()
    record = facts["tissue_coupling"]
    assert record["units"] and record["target_rel"] == \
        facts["requirements"]["values"]["kobj_resolution_rel"]
    view = tissue_coupling_view(record)
    assert view["columns"][0] == "unit" and len(view["rows"]) == len(record["units"])
    first, item = view["rows"][0], record["eq3"]["items"][0]
    # reference/measuring, as its title says and as the K_obj budget's table beside it names
    # each unit (it printed measuring/reference: 1/2 for the budget's 2/1)
    unit = record["units"][0]
    assert unit["unit"] == item["unit"] == [unit["measuring_element"], unit["reference_element"]]
    assert first["unit"] == unit["unit_label"] == \
        f"{unit['reference_element']}/{unit['measuring_element']}"
    assert {r["unit"] for r in view["rows"]} == \
        {f"{u['reference_element']}/{u['measuring_element']}" for u in facts["kobj_budget"]["units"]}
    assert "(reference/measuring element)" in view["title"]
    assert first["K_obj bias, eq. 3"] == f"{100 * item['bias_rel']:+.3g} %"
    assert first["eq. 3"] == item["verdict"].upper()
    assert "half-space" in view["title"] and " % K_obj resolution" in view["title"]


def test_without_a_maximum_grasp_force_no_grasp_section_and_no_table():
    assert _facts().get("grasp") is None  # a section with nothing to say is left out
    assert grasp_view(None) is None
    assert tissue_coupling_view(None) is None and tissue_coupling_view({"units": []}) is None


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_stated_maximum_grasp_force_gives_the_grasp_and_its_table():
    facts = _facts({"requirements.max_grasp_force_N": 1.0})
    grasp = facts["grasp"]
    matrix = {r["requirement"]: r for r in facts["requirements"]["closed_form_matrix"]}
    assert grasp["verdict"] == matrix["max_grasp_force_N"]["verdict"]
    assert grasp["grasp"]["as_laid_out"]["grasp_force_N"] > 0
    view = grasp_view(grasp)
    assert len(view["rows"]) == len(grasp["elements"])
    for row, it in zip(view["rows"], grasp["elements"]):
        assert row["force on its spring"] == f"{it['element_force_N']:.4g} N"
        assert row["rating"].endswith(" N") and row["verdict"] == it["verdict"].upper()
    assert view["title"].startswith(f"grasp force 1 N: {grasp['verdict'].upper()}")
    assert "degrees" in view["title"] and "slab" in view["title"]


def test_the_review_data_holds_both_tables():
    from tactcad.export.review_page import review_contents

    facts = _facts({"requirements.max_grasp_force_N": 1.0})
    data = review_contents(facts, [], {}, "", [], "A", "2026-01-01", "0").data
    assert data["tissue_coupling"]["rows"] and data["grasp"]["rows"]
    assert data["tissue_coupling"] == tissue_coupling_view(facts["tissue_coupling"])
