"""The jaw's design atlas in a project's review page: read from the design's own atlas/
folder only, every judged point drawn with its hover text and design command, the front as
a table, a damaged atlas shown as such, a new atlas a new page."""

from __future__ import annotations

import json
import math
import re

import pytest

from tactcad.export.atlas_view import atlas_identity, atlas_view
from tactcad.studies.atlas_files import (PROJECT_ATLAS_FOLDER, SUMMARY_NAME, TABLE_NAME,
                                         write_table)


def _record(point: int, force: float, lo: float, hi: float, feasible: bool,
            resolution: float = math.nan, material: str = "silicon") -> dict:
    # the fields evaluate_point writes, with the figures a feasible die carries
    return {"product": "mems-die", "material": material, "point": point,
            "kr_over_km": 10.0, "kobj_lo_N_per_mm": lo, "kobj_hi_N_per_mm": hi,
            "full_scale_force_N": force, "columns": 4, "feasible": feasible,
            "binding_limit": "" if feasible else "strength",
            "binding_detail": "" if feasible else "failure probability above 0.001",
            "design_field": "" if feasible else "--full-scale-force",
            "kobj_resolution_rel": resolution if feasible else math.nan,
            "max_force_N": 2 * force if feasible else math.nan, "lowest_first_Hz": math.nan,
            "sheet_mm": math.nan, "layer_um": 40.0 if feasible else math.nan,
            "command": f"tactcad design --jaw 5 --full-scale-force {force:g} --out p{point}.toml"}


RECORDS = [_record(0, 0.01, 1.0, 20.0, True, 0.001),   # front: largest span
           _record(1, 0.02, 1.0, 5.0, True, 0.002),    # front: largest force
           _record(2, 0.005, 1.0, 4.0, True, 0.003),   # beaten by 0 in all three
           _record(3, 0.5, 1.0, 30.0, False)]


def _project(tmp_path, records=RECORDS, summary=None):
    design = tmp_path / "die.toml"
    design.write_text("# a design file; the atlas view reads only its folder\n")
    folder = tmp_path / PROJECT_ATLAS_FOLDER
    write_table(folder / TABLE_NAME, records, {"jaw": "5"})
    (folder / SUMMARY_NAME).write_text(json.dumps(summary or {
        "jaw": "5", "points": 4, "seed": 7, "complete": True}), encoding="utf-8")
    return design


def test_every_point_is_drawn_with_its_figures_and_command_and_the_front_is_its_table(tmp_path):
    view = atlas_view(_project(tmp_path))
    assert len(view["points"]) == len(RECORDS)
    assert view["groups"] == ["mems-die silicon"]
    on_front = {p["command"] for p in view["points"] if p["front"]}
    assert on_front == {RECORDS[0]["command"], RECORDS[1]["command"]}
    rows = view["front"]["rows"]
    assert sorted(r["design command"] for r in rows) == sorted(on_front)
    refused = next(p for p in view["points"] if not p["feasible"])
    assert "refused (strength)" in refused["title"] and refused["title"].endswith(
        RECORDS[3]["command"])
    first = next(p for p in view["points"] if p["command"] == RECORDS[0]["command"])
    assert first["span"] == pytest.approx(20.0) and first["force_N"] == 0.01
    assert "K_obj resolution 0.10%" in first["title"]
    assert "seed 7" in view["title"] and "3 designed" in view["title"]


def test_the_projects_own_targets_are_marked_and_nonsense_targets_are_not(tmp_path):
    design = _project(tmp_path)
    mark = atlas_view(design, (0.03, 0.5, 6.0))["design"]
    assert mark["force_N"] == 0.03 and mark["span"] == pytest.approx(12.0)
    assert "0.03 N rated" in mark["title"] and "0.5-6 N/mm" in mark["title"]
    assert atlas_view(design)["design"] is None
    assert atlas_view(design, (0.03, 0.0, 6.0))["design"] is None
    assert atlas_view(design, (math.nan, 0.5, 6.0))["design"] is None


def test_the_exports_mark_is_what_the_designs_requirements_state():
    from tactcad.export.jobs import design_targets

    facts = {"requirements": {"values": {"full_scale_force_N": 0.2,
                                         "kobj_range_N_per_mm": [1.0, 8.0]}}}
    assert design_targets(facts) == (0.2, 1.0, 8.0)
    assert design_targets({"requirements": {"values": {"full_scale_force_N": 0.2}}}) is None
    assert design_targets({}) is None


def test_a_huge_atlas_draws_its_front_and_designed_points_first_and_says_so(tmp_path):
    from tactcad.export.atlas_view import drawn_points

    records = [_record(i, 0.001 * (1 + i % 50), 1.0, 2.0 + i % 7, i % 3 == 0, 0.01)
               for i in range(900)]
    view = atlas_view(_project(tmp_path, records=records))
    assert len(view["points"]) == 900 and "drawn" not in view["title"]
    points = view["points"]
    kept = drawn_points(points, limit=400)
    assert len(kept) == 400
    assert [p for p in points if p["front"]] == [p for p in kept if p["front"]]
    assert sum(p["feasible"] for p in kept) == sum(p["feasible"] for p in points) == 300
    assert kept == [p for p in points if p in kept]  # table order kept
    assert drawn_points(points, limit=10_000) == points


def test_a_stopped_run_says_only_the_finished_points_are_shown(tmp_path):
    view = atlas_view(_project(tmp_path, summary={"jaw": "5", "points": 9, "seed": 0,
                                                  "complete": False}))
    assert "stopped" in view["note"]


@pytest.mark.parametrize("damage", ["not parquet", "no summary", "bad field"])
def test_a_damaged_atlas_is_shown_as_unreadable_never_an_error(tmp_path, damage):
    design = _project(tmp_path, records=(
        [{**RECORDS[0], "full_scale_force_N": -1.0}] if damage == "bad field" else RECORDS))
    folder = tmp_path / PROJECT_ATLAS_FOLDER
    if damage == "not parquet":
        (folder / TABLE_NAME).write_bytes(b"PAR1 this is not a table")
    elif damage == "no summary":
        (folder / SUMMARY_NAME).unlink()
    view = atlas_view(design)
    assert view["points"] == [] and view["front"] is None
    assert "could not be read" in view["note"] and "--project" in view["note"]


def test_no_atlas_no_section_and_a_design_made_in_code_never_reads_the_working_folder(
        tmp_path, monkeypatch):
    design = tmp_path / "die.toml"
    design.write_text("")
    assert atlas_view(design) is None and atlas_identity(design) == ""
    _project(tmp_path)  # an atlas in the working folder
    monkeypatch.chdir(tmp_path)
    assert atlas_view("<dict>") is None and atlas_identity("<dict>") == ""
    assert atlas_view(None) is None


def test_a_new_atlas_is_a_new_identity(tmp_path):
    design = _project(tmp_path)
    before = atlas_identity(design)
    assert re.fullmatch(r"[0-9a-f]{64}", before)
    _project(tmp_path, records=RECORDS[:2])
    assert atlas_identity(design) != before


def test_the_page_draws_the_atlas_and_a_click_shows_the_point(exported, browser, tmp_path):
    """The exported page with an atlas section in its data: one mark per point, the front's
    rows, and a click puts the point's hover text in the panel."""
    from tactcad.checks.review_browser import wait_first_frame
    from tactcad.export.review_page import REVIEW_PAGE, json_in_html

    out, _ = exported
    page_file = out / REVIEW_PAGE
    text = page_file.read_text(encoding="utf-8")
    found = re.search(r'(<script type="application/json" id="review-data">)(.*?)(</script>)',
                      text, re.S)
    data = json.loads(found.group(2))
    data["atlas"] = atlas_view(_project(tmp_path), (0.03, 0.5, 6.0))
    patched = tmp_path / "review" / "index.html"
    patched.parent.mkdir()
    patched.write_text(text[:found.start(2)] + json_in_html(data) + text[found.end(2):],
                       encoding="utf-8")
    for sibling in page_file.parent.iterdir():  # its scripts and models, as exported
        if sibling.name != "index.html" and sibling.is_file():
            (patched.parent / sibling.name).write_bytes(sibling.read_bytes())
    with browser() as page:
        page.goto(patched.resolve().as_uri())
        wait_first_frame(page)
        assert page.locator("#nav-atlas").is_visible()
        feasible = sum(r["feasible"] for r in RECORDS)
        assert page.locator("#atlas-plot circle").count() == feasible
        assert page.locator("#atlas-plot path.refused").count() == len(RECORDS) - feasible
        assert page.locator("#atlas-body tr").count() == 1 + 2
        assert page.locator("#atlas-plot polygon.this-design").count() == 1
        page.locator("#atlas-plot path.refused").first.click()
        assert RECORDS[3]["command"] in page.locator("#atlas-picked").inner_text()
        assert page.errors == []


def test_a_product_the_atlas_left_out_is_named_with_its_misfit_on_the_page(tmp_path):
    # an 8 mm jaw's atlas judged the die alone and the page said nothing of the comb
    misfit = "does not fit: height 5.79 mm vs the jaw's 3.3 mm (thickness_mm + tip_proud_mm)"
    design = _project(tmp_path, summary={
        "jaw": "lab.toml", "points": 4, "seed": 0, "complete": True,
        "left_out": [{"product": "monolithic-comb", "misfit": misfit},
                     {"product": 7, "misfit": None}]})  # an entry not in words: skipped
    note = atlas_view(design)["note"]
    assert f"Not searched: monolithic-comb: {misfit}." in note
    assert note.count("Not searched") == 1
    (tmp_path / "plain").mkdir()
    plain = atlas_view(_project(tmp_path / "plain"))["note"]
    assert "Not searched" not in plain
