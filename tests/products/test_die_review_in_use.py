"""A die's review page fills the grasp, tissue coupling and build sections as an array's page
does (the page's own tables and build book), from the die's grasp, its tissue coupling and
its traveller; a section without a result says why on one line instead of being hidden."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import tactcad
from conftest import DIE_EXAMPLE as EXAMPLE


def _page_data(html_path: Path) -> dict:
    text = html_path.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="review-data">(.*?)</script>',
                      text, re.S)
    return json.loads(found.group(1))


@pytest.fixture(scope="module")
def die_page(tmp_path_factory) -> tuple[dict, object]:
    """The review page the die's export writes (its grasp, tissue coupling and traveller
    computed as the export computes them), on stand-in drawing, scene and BOM files."""
    from tactcad.commands.die import _write_review_and_manifest
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.in_use.die_budget import die_budget
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    folder = tmp_path_factory.mktemp("die_export")
    planned = tactcad.load(EXAMPLE).planned
    plan = planned.plan
    made = {"drawing": folder / "die.svg", "glb": folder / "scene.glb",
            "bom": folder / "bom.csv", "review": folder / "review" / "index.html",
            "manifest": folder / "manifest.json"}
    made["drawing"].write_text("<svg xmlns='http://www.w3.org/2000/svg'/>", encoding="utf-8")
    made["glb"].write_bytes(b"glTF")
    made["bom"].write_text("part,quantity\ndie,1\n", encoding="utf-8")
    made["review"].parent.mkdir()
    readout = die_readout(plan)
    _write_review_and_manifest(plan, None, made, {"drawing": Path("die.svg")},
                               die_budget(plan, readout), folder, die_mount(plan, planned.jaw_stated),
                               str(EXAMPLE), readout)
    return _page_data(made["review"]), plan


@pytest.mark.xdist_group("die-review-page")  # die_page: made once, on one worker
@pytest.mark.slow  # the die's grasp and tissue coupling solved
def test_the_die_page_carries_its_grasp_as_the_grasp_table(die_page):
    data, plan = die_page
    grasp = data["grasp"]
    assert grasp is not None and grasp["rows"], "the grasp section is empty"
    assert grasp["columns"] == ["element", "force on its spring", "on the stop", "rating",
                                "margin", "verdict"]
    # one row per beam, each named by its number, forces in N
    assert [r["element"] for r in grasp["rows"]] == [str(b.number) for b in plan.beams]
    assert all(r["force on its spring"].endswith(" N") and r["verdict"] in
               {"PASS", "FAIL", "OVER RATING"} for r in grasp["rows"])
    assert grasp["title"].startswith("grasp force ")


@pytest.mark.xdist_group("die-review-page")  # die_page: made once, on one worker
@pytest.mark.slow  # the die's grasp and tissue coupling solved
def test_the_die_page_carries_its_tissue_coupling_as_the_tissue_table(die_page):
    data, plan = die_page
    tissue = data["tissue_coupling"]
    assert tissue is not None and tissue["rows"], "the tissue section is empty"
    assert tissue["columns"][0] == "unit" and "eq. 3" in tissue["columns"]
    assert f"{100 * plan.kobj_resolution_rel:.3g} % K_obj resolution" in tissue["title"]


@pytest.mark.xdist_group("die-review-page")  # die_page: made once, on one worker
@pytest.mark.slow  # the die's grasp and tissue coupling solved
def test_the_die_page_carries_its_traveller_as_the_build_book(die_page):
    from tactcad.products.silicon_die.export.traveller import traveller_steps
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    data, plan = die_page
    steps = traveller_steps(plan, die_readout(plan)["sheet_resistance_ohm_per_sq"])
    assert [s["title"] for s in data["book"]] == [s.name for s in steps]
    assert all(s["scene"] in data["scenes"] for s in data["book"])


def test_a_die_section_without_a_result_is_one_line_not_hidden():
    from tactcad.products.silicon_die.export.die_review import (design_head,
                                                                review_contents_of_die)

    plan = tactcad.load(EXAMPLE).plan
    data = review_contents_of_die(
        design_head(plan.name, None), [], ("drawings/die.svg", "<svg xmlns='"
                                           "http://www.w3.org/2000/svg'/>"),
        b"", "part,quantity\ndie,1\n", [], {}).data
    for key in ("grasp", "tissue_coupling"):
        assert data[key] is not None and data[key]["rows"] == []
        assert "tactcad " in data[key]["title"]  # says where the figures come from
    # the page shows such a section's line and no table, never hides it
    js = (Path(tactcad.__file__).parent / "data" / "review_page.js").read_text(encoding="utf-8")
    body = js[js.index("function showTableSection"):js.index("function showBudget")]
    assert "t.rows.length" in body


def test_the_pages_grasp_is_asked_as_the_grasp_command_asks_by_default():
    from tactcad.cli import build_parser
    from tactcad.products.silicon_die.studies.die_grasp_report import default_grasp_options

    cli_defaults = vars(build_parser(["grasp"]).parse_args(["grasp"]))
    ours = vars(default_grasp_options())
    assert ours == {k: cli_defaults[k] for k in ours}
