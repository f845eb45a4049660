"""``tactcad diff`` as a lab reads it: the design values edited, elements paired by their
place, the bill of materials, and an ``--out`` folder holding one comparison's pictures.
Manifests are built small (no export is run)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import tactcad
from tactcad import cli
from tactcad.export.manifest import stated_section, strength_section
from tactcad.errors import DesignError
from tactcad.export.manifest_diff import DIFF_RECORD, compare

HARDWARE = Path(__file__).resolve().parents[2] / "hardware"
COMB = HARDWARE / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
TI = HARDWARE / "ti_array_2x3" / "ti_array_2x3.toml"


def write_export(folder: Path, manifest: dict, files: dict[str, str] | None = None) -> Path:
    """A small export folder: ``manifest.json`` and the named files' texts."""
    folder.mkdir(parents=True)
    for rel, text in (files or {}).items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        (folder / rel).write_text(text, encoding="utf-8")
    (folder / "manifest.json").write_text(json.dumps({"files": [], **manifest}),
                                          encoding="utf-8")
    return folder


def with_digests(folder: Path) -> Path:
    """``folder`` with its manifest's sha256 of each listed file the file's own."""
    from tactcad.atomic import file_sha256

    path = folder / "manifest.json"
    manifest = json.loads(path.read_text(encoding="utf-8"))
    for f in manifest["files"]:
        if (folder / f["path"]).is_file():
            f["sha256"] = file_sha256(folder / f["path"])
    path.write_text(json.dumps(manifest), encoding="utf-8")
    return folder


def test_a_comb_designs_edited_values_are_named_by_their_dotted_keys(tmp_path):
    # material and web 0.164 -> 0.18 showed a part's material and volume, never the web;
    # the jaw's length only a changed sheet
    webs = [0.18] * 6 + [0.08] * 6
    old = tactcad.load(COMB).plan
    new = tactcad.load(COMB, set={"comb.web_thicknesses_mm": webs,
                                  "grasper_jaw.length_mm": 35.0}).plan
    assert stated_section(old)["comb.web_thicknesses_mm"] == [0.164] * 6 + [0.08] * 6
    assert not any(k.startswith(("assumptions.", "files.")) for k in stated_section(old))
    d = compare(write_export(tmp_path / "old", {"stated": stated_section(old)}),
                write_export(tmp_path / "new", {"stated": stated_section(new)}))
    assert {s["name"]: (s["before"], s["after"]) for s in d.stated} == {
        "comb.web_thicknesses_mm": ([0.164] * 6 + [0.08] * 6, webs),
        "grasper_jaw.length_mm": (34.0, 35.0)}
    lines = d.lines()
    assert "stated        comb.web_thicknesses_mm: [0.164 x6, 0.08 x6] -> [0.18 x6, 0.08 x6] " \
           "mm" in lines
    assert "stated        grasper_jaw.length_mm: 34 -> 35 mm" in lines
    assert d.changed


def test_a_grades_modulus_is_not_stated_where_the_file_leaves_it_out(tmp_path):
    old = tactcad.load(TI).plan
    new = tactcad.load(TI, set={"material.grade": "17-4PH-H900",
                                "material.name": "17-4PH"}).plan
    assert "material.youngs_modulus_MPa" not in stated_section(old)
    d = compare(write_export(tmp_path / "old", {"stated": stated_section(old)}),
                write_export(tmp_path / "new", {"stated": stated_section(new)}))
    assert {s["name"] for s in d.stated} == {"material.grade", "material.name"}
    edited = tactcad.load(TI, set={"material.youngs_modulus_MPa": 110000.0}).plan
    assert stated_section(edited)["material.youngs_modulus_MPa"] == 110000.0  # the file's


def test_a_record_only_one_export_has_reads_added_or_removed(tmp_path):
    old = write_export(tmp_path / "old", {"requirements": {"closed_form_matrix": [
        {"requirement": "gone"}]}})
    new = write_export(tmp_path / "new", {"rows": [{"row": 1, "role": "reference"}]})
    lines = compare(old, new).lines()
    assert "row 1 (reference)  added" in lines
    assert "requirement   gone: removed" in lines
    assert not any("True" in line or "False" in line for line in lines)


def test_exports_of_different_products_say_so_once_and_compare_what_both_have(tmp_path):
    old = write_export(tmp_path / "old", {"product": "metal-array", "stated": {"a.b": 1}})
    new = write_export(tmp_path / "new", {"product": "silicon-die", "stated": {"die.x": 2},
                                          "rows": [{"row": 1, "role": "reference"}]})
    lines = compare(old, new).lines()
    assert lines[0].startswith("products      the two exports are of different products "
                               "(metal-array -> silicon-die)")
    assert not any(line.startswith(("row ", "stated")) for line in lines)


def test_a_manifest_without_stated_values_names_none(tmp_path):
    d = compare(write_export(tmp_path / "old", {}),
                write_export(tmp_path / "new", {"stated": {"sheet.thickness_mm": 1.0}}))
    assert d.stated == [] and not d.changed


def _records(rows: int, columns: int, stiffness: dict[int, float]) -> list[dict]:
    """Element records of a rows x columns array numbered row by row (row 1 the references:
    2 mm arms, then 3 mm arms)."""
    return [{"element": r * columns + c + 1, "row": r + 1, "column": c + 1,
             "part_name": f"element_a{r + 2}mm", "stiffness_N_per_mm": stiffness[r]}
            for r in range(rows) for c in range(columns)]


def test_a_removed_column_is_named_by_its_row_and_column_not_by_renumbered_elements(
        tmp_path):
    # comb columns 6 -> 5: "element 6 part_name element_a2mm -> element_a3mm" and
    # "element 11/12 present True -> False"; column 6 (elements 6 and 12) was removed
    k = {0: 57.5, 1: 4.4}
    d = compare(write_export(tmp_path / "old", {"strength": _records(2, 6, k)}),
                write_export(tmp_path / "new", {"strength": _records(2, 5, k)}))
    removed = [(e["row"], e["column"], e["element"]) for e in d.elements
               if "present" in e["changes"]]
    assert removed == [(1, 6, 6), (2, 6, 12)]
    others = [e for e in d.elements if "present" not in e["changes"]]
    # row 2 is numbered one lower; nothing else of it changed
    assert [(e["row"], e["column"], e["changes"]) for e in others] == [
        (2, c, {"element": {"before": 6 + c, "after": 5 + c}}) for c in range(1, 6)]
    lines = d.lines()
    # the removed column first, then the numbering it moved: one line a row
    assert lines[:3] == ["row 1 column 6 removed (element 6)",
                         "row 2 column 6 removed (element 12)",
                         "row 2: elements 7-11 renumbered 6-10"]
    assert not any("part_name" in line or "-> 6" in line for line in lines)


def test_renumbered_elements_are_grouped_in_runs_and_a_changed_one_keeps_its_line(tmp_path):
    # rows 2 and 3 numbered one lower; element 8 -> 7 (row 2 column 3) also stiffer
    new = _records(3, 4, {0: 1.0, 1: 2.0, 2: 3.0})
    old = [dict(r, element=r["element"] + (r["row"] > 1)) for r in new]
    new[6]["stiffness_N_per_mm"] = 2.5
    d = compare(write_export(tmp_path / "old", {"strength": old}),
                write_export(tmp_path / "new", {"strength": new}))
    assert d.lines()[:3] == [
        "element 7 (row 2 column 3)  element 8 -> 7, stiffness_N_per_mm 2 -> 2.5 N/mm",
        "row 2: elements 6-7 renumbered 5-6, element 9 renumbered 8",
        "row 3: elements 10-13 renumbered 9-12"]
    assert len(d.elements) == 8  # the record keeps every element's own finding


def test_the_manifest_records_each_elements_row_and_column():
    plan = tactcad.load(TI).plan
    records = strength_section(plan)
    assert [(r["element"], r["row"], r["column"]) for r in records] == [
        (s.number, s.row + 1, s.column + 1) for s in plan.slots]


def test_elements_without_a_recorded_place_are_paired_by_number(tmp_path):
    old = [{"element": 1, "stiffness_N_per_mm": 2.0}]
    new = [{"element": 1, "row": 1, "column": 1, "stiffness_N_per_mm": 3.0}]
    d = compare(write_export(tmp_path / "old", {"strength": old}),
                write_export(tmp_path / "new", {"strength": new}))
    assert d.elements == [{"element": 1, "changes": {
        "stiffness_N_per_mm": {"before": 2.0, "after": 3.0}}}]


BOM_HEAD = "item,part,quantity,unit\n"


def test_the_bill_of_materials_items_added_removed_and_recounted(tmp_path):
    # stacked columns 4 -> 3: the parts' bolts were listed, the BOM's were not
    listed = {"files": [{"path": "bom.csv", "kind": "bom-csv", "sha256": "x"}]}
    old = write_export(tmp_path / "old", listed, {"bom.csv": "\ufeff" + BOM_HEAD + (
        "1,element_a6mm,4,pcs\n2,bolt_M3x35,2,pcs\n3,bolt_M3x40,2,pcs\n")})
    new = write_export(tmp_path / "new", listed, {"bom.csv": "\ufeff" + BOM_HEAD + (
        "1,element_a6mm,3,pcs\n2,bolt_M3x30,2,pcs\n3,bolt_M3x35,2,pcs\n")})
    d = compare(with_digests(old), with_digests(new))
    assert d.bom == {"added": [{"item": "bolt_M3x30", "quantity": 2}],
                     "removed": [{"item": "bolt_M3x40", "quantity": 2}],
                     "changed": [{"item": "element_a6mm", "before": 4, "after": 3}]}
    assert {"bom added     bolt_M3x30 x2", "bom removed   bolt_M3x40 x2",
            "bom quantity  element_a6mm: 4 -> 3"} <= set(d.lines())
    assert d.as_json()["bom"] == d.bom


def test_a_dies_bill_of_materials_is_read_by_its_own_columns(tmp_path):
    listed = {"files": [{"path": "bom.csv", "kind": "bom-csv", "sha256": "x"}]}
    old = write_export(tmp_path / "old", listed, {"bom.csv": "item,qty\ndie,1\nresistor,4\n"})
    new = write_export(tmp_path / "new", listed, {"bom.csv": "item,qty\ndie,1\nresistor,2\n"})
    assert compare(with_digests(old), with_digests(new)).bom["changed"] == [
        {"item": "resistor", "before": 4, "after": 2}]


def test_a_bill_of_materials_other_than_the_exports_is_refused(tmp_path):
    listed = {"files": [{"path": "bom.csv", "kind": "bom-csv", "sha256": "x"}]}
    old = with_digests(write_export(tmp_path / "old", listed, {"bom.csv": "item,qty\ndie,1\n"}))
    new = with_digests(write_export(tmp_path / "new", listed, {"bom.csv": "item,qty\ndie,2\n"}))
    (new / "bom.csv").write_bytes(b"\x00\xff garbage")  # after the export
    with pytest.raises(DesignError, match="bom.csv is not the file the export wrote"):
        compare(old, new)


SVG = ('<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="20mm" '
       'viewBox="0 0 40 20"><line x1="{x}" y1="2" x2="{x}" y2="18" stroke="black" '
       'stroke-width="1"/></svg>')


def _sheet_export(folder: Path, xs: dict[str, int]) -> Path:
    """An export with one drawing sheet per name, each a line at x (its sha256 the x)."""
    files = [{"path": f"drawings/{n}.svg", "kind": "drawing-svg", "sha256": str(x)}
             for n, x in xs.items()]
    return write_export(folder, {"files": files}, {f"drawings/{n}.svg": SVG.format(x=x)
                                                   for n, x in xs.items()})


def test_a_second_diff_into_a_folder_replaces_the_first_ones_pictures(tmp_path, capsys):
    base = _sheet_export(tmp_path / "base", {"a": 5, "b": 5})
    a_moved = _sheet_export(tmp_path / "a_moved", {"a": 30, "b": 5})
    b_moved = _sheet_export(tmp_path / "b_moved", {"a": 5, "b": 30})
    out = tmp_path / "pictures"
    assert cli.main(["diff", str(base), str(a_moved), "--out", str(out), "--quiet"]) == 1
    assert sorted(p.name for p in out.iterdir()) == sorted([
        DIFF_RECORD, "a_overlay.png", "a_side_by_side.png"])
    assert cli.main(["diff", str(base), str(b_moved), "--out", str(out), "--quiet"]) == 1
    assert sorted(p.name for p in out.iterdir()) == sorted([
        DIFF_RECORD, "b_overlay.png", "b_side_by_side.png"])
    record = json.loads((out / DIFF_RECORD).read_text(encoding="utf-8"))
    assert record["files"] == ["b_overlay.png", "b_side_by_side.png"]
    assert record["new"] == str(b_moved)
    # no change: no picture, and the record (listing none) so the folder is known next time
    assert cli.main(["diff", str(base), str(base), "--out", str(out), "--quiet"]) == 0
    assert [p.name for p in out.iterdir()] == [DIFF_RECORD]
    assert json.loads((out / DIFF_RECORD).read_text(encoding="utf-8"))["files"] == []
    assert cli.main(["diff", str(base), str(a_moved), "--out", str(out), "--quiet"]) == 1
    capsys.readouterr()


def test_a_folder_without_a_record_is_refused_saying_so(tmp_path, capsys):
    base = _sheet_export(tmp_path / "base", {"a": 5})
    moved = _sheet_export(tmp_path / "moved", {"a": 30})
    out = tmp_path / "pictures"
    out.mkdir()
    (out / "assembly_overlay.png").write_bytes(b"an older diff's")
    code = cli.main(["diff", str(base), str(moved), "--out", str(out), "--json"])
    message = json.loads(capsys.readouterr().out)["error"]["message"]
    assert code == 2 and "no diff wrote" not in message
    assert f"holds no {DIFF_RECORD}" in message and "assembly_overlay.png" in message
    assert "empty it, or name another folder" in message
    assert [p.name for p in out.iterdir()] == ["assembly_overlay.png"]


def test_a_folder_holding_files_no_diff_wrote_is_refused_and_kept(tmp_path, capsys):
    base = _sheet_export(tmp_path / "base", {"a": 5})
    moved = _sheet_export(tmp_path / "moved", {"a": 30})
    out = tmp_path / "pictures"
    out.mkdir()
    (out / "notes.png").write_bytes(b"the lab's")
    code = cli.main(["diff", str(base), str(moved), "--out", str(out), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "--out" and "notes.png" in error["message"]
    assert [p.name for p in out.iterdir()] == ["notes.png"]
    # beside an earlier diff's pictures too: neither is deleted
    (out / "notes.png").unlink()
    assert cli.main(["diff", str(base), str(moved), "--out", str(out), "--quiet"]) == 1
    (out / "notes.png").write_bytes(b"the lab's")
    assert cli.main(["diff", str(base), str(moved), "--out", str(out), "--quiet"]) == 2
    assert sorted(p.name for p in out.iterdir()) == sorted([
        DIFF_RECORD, "a_overlay.png", "a_side_by_side.png", "notes.png"])
    capsys.readouterr()


@pytest.mark.parametrize("record", ['{"written_by": "other", "files": ["x.png"]}',
                                    '{"written_by": "tactcad diff", "files": ["../x.png"]}',
                                    "{not json"])
def test_a_record_no_diff_wrote_protects_the_folder(tmp_path, capsys, record):
    base = _sheet_export(tmp_path / "base", {"a": 5})
    moved = _sheet_export(tmp_path / "moved", {"a": 30})
    out = tmp_path / "pictures"
    out.mkdir()
    (out / DIFF_RECORD).write_text(record, encoding="utf-8")
    (out / "x.png").write_bytes(b"the lab's")
    assert cli.main(["diff", str(base), str(moved), "--out", str(out), "--quiet"]) == 2
    assert sorted(p.name for p in out.iterdir()) == sorted([DIFF_RECORD, "x.png"])
    capsys.readouterr()
