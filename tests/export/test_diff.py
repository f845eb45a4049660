"""``tactcad diff OLD NEW``: what changed between two exports, from their manifests."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from PIL import Image

import tactcad
from conftest import warm_store_copy, with_default_companions
from tactcad import cli
from tactcad.errors import DesignError
from tactcad.export.manifest_diff import (DIFF_RECORD, NEW_RGB, OLD_RGB, compare, overlay,
                                          side_by_side)

DEFAULT = tactcad.load().source
ARM_CHANGED = {"arms.lengths_mm": [4.0, 7.0, 6.0, 8.0, 6.5, 8.0, 5.0, 4.0, 5.0, 7.0]}


def test_overlay_colours_old_new_and_common_ink():
    old = np.full((4, 5), 255, np.uint8)
    new = np.full((3, 6), 255, np.uint8)
    old[0, 0] = new[0, 0] = 0  # both
    old[1, 1] = 0  # old only
    new[2, 5] = 0  # new only (beyond the old sheet's width)
    image = overlay(old, new)
    assert image.shape == (4, 6, 3)
    assert tuple(image[0, 0]) == (0, 0, 0)
    assert tuple(image[1, 1]) == OLD_RGB and tuple(image[2, 5]) == NEW_RGB
    assert (image[3] == 255).all()
    pair = side_by_side(old, new, gap_px=2)
    assert pair.shape == (4, 5 + 2 + 6, 3)


def test_refuses_what_is_neither_an_export_nor_a_design(tmp_path, capsys):
    (tmp_path / "notes.txt").write_text("x")
    for bad in (tmp_path / "missing", tmp_path, tmp_path / "notes.txt"):
        code = cli.main(["diff", str(bad), str(bad), "--json"])
        error = json.loads(capsys.readouterr().out)["error"]
        assert code == 2 and error["field"] == "OLD", error
    (tmp_path / "broken").mkdir()
    (tmp_path / "broken" / "manifest.json").write_text("{not json")
    with pytest.raises(DesignError, match="manifest.json"):
        compare(tmp_path / "broken", tmp_path / "broken")


@pytest.fixture(scope="module")
def arm_changed_export(arm_changed_cold):
    """The default design with element 5's arm 6 -> 6.5 mm, exported."""
    return arm_changed_cold[1]


def test_one_arm_changed_names_that_element_its_k_its_sheets_and_the_assembly(
        exported, arm_changed_export, tmp_path, capsys):
    old, _ = exported
    pictures = tmp_path / "pictures"
    code = cli.main(["diff", str(old), str(arm_changed_export), "--out", str(pictures), "--json"])
    report = json.loads(capsys.readouterr().out)
    assert code == 1 and report["changed"]

    # the element: its part, arm, K and strength, before and after
    assert [e["element"] for e in report["elements"]] == [5]
    ch = report["elements"][0]["changes"]
    assert ch["part_name"] == {"before": "element_a6mm", "after": "element_a6p5mm"}
    assert ch["arm_length_mm"] == {"before": 6.0, "after": 6.5}
    before = tactcad.load().element(5).stiffness().stiffness_N_per_mm
    after = tactcad.load(set=ARM_CHANGED).element(5).stiffness().stiffness_N_per_mm
    assert ch["stiffness_N_per_mm"]["before"] == pytest.approx(before, rel=1e-12)
    assert ch["stiffness_N_per_mm"]["after"] == pytest.approx(after, rel=1e-12)
    assert after < before  # a longer arm is softer

    # the parts: the new one, and the old one now made once (element 3 keeps it)
    assert report["parts"]["added"] == ["element_a6p5mm"] and report["parts"]["removed"] == []
    assert report["parts"]["changed"] == {"element_a6mm": {"quantity": {"before": 2, "after": 1}}}
    assert report["derived"] == []  # the longest arm sets the clamp: unchanged

    # the sheets: the element's (drawn against the sheet it replaces), the old part's
    # quantity, the assembly sheet; nothing else, and only these rendered
    sheets = {s["sheet"]: s for s in report["sheets"]}
    assert set(sheets) == {"drawings/element_a6p5mm.svg", "drawings/element_a6mm.svg",
                           "drawings/assembly.svg"}
    assert sheets["drawings/element_a6p5mm.svg"]["status"] == "added"
    assert sheets["drawings/element_a6p5mm.svg"]["compared_with"] == "drawings/element_a6mm.svg"
    assert sheets["drawings/assembly.svg"]["status"] == "changed"
    assert sorted(p.name for p in pictures.iterdir()) == sorted([DIFF_RECORD, *(
        f"{stem}_{kind}.png" for stem in ("element_a6p5mm", "element_a6mm", "assembly")
        for kind in ("overlay", "side_by_side"))])  # and the record of the pictures
    image = np.asarray(Image.open(pictures / "element_a6p5mm_overlay.png").convert("RGB"))
    for rgb in (OLD_RGB, NEW_RGB, (0, 0, 0)):  # the old, the new and the unchanged lines
        assert (image == np.array(rgb, dtype=image.dtype)).all(axis=-1).any(), rgb
    # the files that follow from the parts are counted, not listed as findings
    assert "step/array.step" in report["files"]["changed"]

    text = compare(old, arm_changed_export).lines()
    assert any(line.startswith("element 5 ") and "stiffness_N_per_mm" in line for line in text)
    assert text[-1] == "changed"


def test_same_export_twice_is_no_change_and_renders_nothing(exported, tmp_path, capsys):
    old, _ = exported
    copy = tmp_path / "copy"
    shutil.copytree(old, copy)
    code = cli.main(["diff", str(old), str(copy), "--out", str(tmp_path / "pictures")])
    out = capsys.readouterr().out
    assert code == 0 and out.splitlines() == ["no change"]
    # no picture; the record, listing none, so a later diff knows the folder as a diff's
    assert [p.name for p in (tmp_path / "pictures").iterdir()] == ["diff.json"]


@pytest.mark.slow
def test_design_files_are_exported_through_the_store_then_compared(tmp_path, capsys,
                                                                 default_store):
    changed = tmp_path / "thick.toml"
    text = DEFAULT.read_text(encoding="utf-8")
    assert "web_thickness_mm = 0.25" in text
    changed.write_text(text.replace("web_thickness_mm = 0.25", "web_thickness_mm = 0.3"),
                       encoding="utf-8")
    with_default_companions(changed)
    store = str(warm_store_copy(default_store, tmp_path / "store"))  # the default's jobs in it
    code = cli.main(["diff", str(DEFAULT), str(changed), "--cache", store, "--json", "--quiet"])
    report = json.loads(capsys.readouterr().out)
    assert code == 1
    assert [e["element"] for e in report["elements"]] == list(range(1, 11))  # every element
    assert all(e["changes"]["stiffness_N_per_mm"]["after"]
               > e["changes"]["stiffness_N_per_mm"]["before"] for e in report["elements"])
    assert report["parts"]["added"] == report["parts"]["removed"] == []


@pytest.mark.parametrize("manifest", [
    '{"files": [{"nopath": 1}]}', '{"files": [], "strength": [{"x": 1}]}',
    '{"files": [], "strength": 5}', '{"files": [], "derived": [{"v": 1}]}',
    '{"files": [], "parts": []}', '[1, 2]', '{"files": 3}', '{not json'])
def test_a_manifest_tactcad_did_not_write_is_bad_input(tmp_path, capsys, manifest):
    (tmp_path / "manifest.json").write_text(manifest)
    code = cli.main(["diff", str(tmp_path), str(tmp_path), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and "manifest.json" in error["message"]


def test_a_sheet_path_leading_out_of_the_export_is_refused(tmp_path, capsys):
    for name in ("a", "b"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "manifest.json").write_text(json.dumps({"files": [
            {"path": "../../etc/hostname", "kind": "drawing-svg", "sha256": name}]}))
    code = cli.main(["diff", str(tmp_path / "a"), str(tmp_path / "b"), "--out",
                     str(tmp_path / "pictures"), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and "inside the export folder" in error["message"]


def test_two_dies_differ_in_their_beams_and_derived_values_not_only_in_bytes(tmp_path):
    # a die's manifest keeps its beams as "elements" and its derived values in "die": the
    # diff read neither and said only that 8 files changed
    def die_manifest(folder, force_N, depth_um):
        folder.mkdir()
        man = {"files": [{"path": "masks/die.gds", "sha256": str(force_N)}],
               "elements": [{"element": 1, "part_name": "reference beam",
                             "stiffness_N_per_mm": 3.58, "full_scale_force_N": force_N}],
               "die": {"full_scale_force_N": force_N, "rows": 2,
                       "cavity_depths_um": {"reference": depth_um},
                       "root_peak_stress_MPa_at_rated_force": {"reference": 27e3 * force_N},
                       "weibull": {"source": "a text the files' bytes report"}}}
        (folder / "manifest.json").write_text(json.dumps(man), encoding="utf-8")
        return folder

    d = compare(die_manifest(tmp_path / "old", 0.008, 4.0),
                die_manifest(tmp_path / "new", 0.006, 3.0))
    assert d.elements == [{"element": 1, "changes": {
        "full_scale_force_N": {"before": 0.008, "after": 0.006}}}]
    derived = {r["name"]: (r["before"], r["after"], r["unit"]) for r in d.derived}
    # the rating is the die file's own: stated, not derived
    assert d.stated == [{"name": "die.full_scale_force_N", "before": 0.008, "after": 0.006,
                         "unit": "N"}]
    assert derived == {"die.cavity_depths_um.reference": (4.0, 3.0, "um"),
                       "die.root_peak_stress_MPa_at_rated_force.reference":
                           (27e3 * 0.008, 27e3 * 0.006, "MPa")}
    assert "derived       die.cavity_depths_um.reference: 4 -> 3 um" in d.lines()


def test_a_thinner_web_shows_its_binding_fatigue_limit_and_the_ratings_flipped_verdict(
        tmp_path):
    """The Ti 2 x 3's web 0.165 -> 0.14 mm: the gauge-fatigue limit that binds falls below
    the 0.1 N rating; the diff named K and the yield-limited force but neither the binding
    fatigue limits nor the rating's margin and verdict (pass -> fail)."""
    from tactcad.export.manifest import requirements_section, strength_section
    from tactcad.export.manifest_diff import REQUIREMENT_FIELDS
    from tactcad.mechanics.limits import plan_limits

    from pathlib import Path

    example = (Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3"
               / "ti_array_2x3.toml")

    def manifest(folder, web_mm):
        plan = tactcad.load(example, set={"element.web_thickness_mm": web_mm}).plan
        folder.mkdir()
        man = {"files": [], "strength": strength_section(plan),
               "requirements": requirements_section(plan)}
        (folder / "manifest.json").write_text(json.dumps(man), encoding="utf-8")
        limits = {(lim.element, lim.limit): lim.force_N for lim in plan_limits(plan)}
        for rec in man["strength"]:  # the manifest's fatigue limits are the limits' own
            assert rec["gauge_fatigue_force_N"] == pytest.approx(
                limits[rec["element"], "gauge_fatigue"], rel=1e-9)
            assert rec["fatigue_force_N"] == pytest.approx(limits[rec["element"], "fatigue"],
                                                           rel=1e-9)
        return folder

    d = compare(manifest(tmp_path / "old", 0.165), manifest(tmp_path / "new", 0.14))
    element = {e["element"]: e["changes"] for e in d.elements}[1]
    assert {"gauge_fatigue_force_N", "fatigue_force_N"} <= set(element)
    assert element["gauge_fatigue_force_N"]["after"] < 0.1 < \
        element["gauge_fatigue_force_N"]["before"]
    rating = {r["requirement"]: r["changes"] for r in d.requirements}["full_scale_force_N"]
    assert rating["verdict"] == {"before": "pass", "after": "fail"}
    assert rating["margin_rel"]["before"] > 0 > rating["margin_rel"]["after"]
    assert rating["predicted"]["after"] == pytest.approx(
        element["gauge_fatigue_force_N"]["after"])
    assert set(rating) <= set(REQUIREMENT_FIELDS) and "target" not in rating
    line = next(x for x in d.lines() if x.startswith("requirement   full_scale_force_N"))
    before, after = (100 * rating["margin_rel"][k] for k in ("before", "after"))
    assert f"margin_rel {before:+.3g} % -> {after:+.3g} %" in line
    assert "verdict pass -> fail" in line
    assert d.as_json()["requirements"] == d.requirements and d.changed
