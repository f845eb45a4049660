"""The K_obj error budget in the manifest and on the review page: one row per K_obj, each
source with its unit, the columns in the page's order."""

from __future__ import annotations

import json
from pathlib import Path

from tactcad.commands.finite_json import dumps
from tactcad.export.review_page import kobj_budget_view

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _plan():
    from tactcad.api import load

    return load(str(EXAMPLE)).plan


def test_the_manifest_carries_the_budget_and_the_page_shows_its_table():
    from tactcad.export.manifest import design_facts
    from tactcad.in_use.kobj_budget import SOURCES

    facts = json.loads(dumps(design_facts(_plan())))  # as the manifest file holds it
    budget = facts["kobj_budget"]
    assert budget["force_N"] == facts["requirements"]["values"]["full_scale_force_N"]
    view = kobj_budget_view(budget)
    assert view["columns"][:2] == ["K_obj", "unit"]
    # the record's words: the crosstalk term named for the stacked array's own level
    assert view["columns"][2:-3] == [s["words"] for s in budget["sources"]]
    assert view["columns"][2:-3] == [s.words if s.key != "crosstalk"
                                     else "crosstalk (stack-timoshenko)" for s in SOURCES]
    assert len(view["rows"]) == len(budget["K_obj_N_per_mm"])
    first = view["rows"][0]
    assert first["K_obj"].endswith(" N/mm") and first["RSS"].endswith(" %")
    assert first["RSS"] == f"{100 * budget['array']['rss_rel'][0]:.3g} %"
    assert "N on the reference" in view["title"] and "K step" in view["title"]


def test_no_budget_or_no_unit_shows_no_table():
    assert kobj_budget_view(None) is None
    assert kobj_budget_view({"units": []}) is None


def test_the_pages_script_lays_the_table_out_in_the_datas_columns():
    js = (Path(__file__).resolve().parents[2] / "src" / "tactcad" / "data"
          / "review_page.js").read_text(encoding="utf-8")
    html = (Path(__file__).resolve().parents[2] / "src" / "tactcad" / "data"
            / "review_page.html").read_text(encoding="utf-8")
    assert "table(t.columns, t.rows)" in js and "showBudget();" in js
    for section, key in (("budget", "kobj_budget"), ("tissue", "tissue_coupling"),
                         ("grasp", "grasp")):
        assert f"showTableSection(DATA.{key}, '{section}')" in js
        assert f'id="{section}-body"' in html and f'id="nav-{section}"' in html


def test_the_exported_page_shows_the_budget_table(exported, browser):
    from tactcad.checks.review_browser import wait_first_frame
    from tactcad.export.review_page import REVIEW_PAGE

    out, _ = exported
    with browser() as page:
        page.goto((out / REVIEW_PAGE).resolve().as_uri())
        wait_first_frame(page)
        rows = page.locator("#budget-body tr").all_inner_texts()
        head = rows[0].split("\t")
        assert head[:2] == ["K_obj", "unit"] and head[-3:] == ["RSS", "worst case", "dominant"]
        assert len(rows) == 1 + 7 and all(" N/mm" in r and " %" in r for r in rows[1:])
        assert page.locator("#nav-budget").is_visible()
