"""Bill of materials: quantities are the assemblies' instance counts, every
file it names exists, CSV and Markdown agree, scene assemblies are counted."""

from __future__ import annotations

import csv
import io
import json
import re
import types
from collections import Counter

import pytest

from tactcad.assembly.inventory import design_assemblies, part_quantities
from tactcad.export.bom import BOM_COLUMNS, bom_csv, bom_rows
from tactcad.catalogue.array_catalogue import Instance, Method, Process, array_instances, array_parts
from tactcad.design.array_plan import Placement, default_design_data, plan_from_dict, with_overrides


def read_csv(path):
    with open(path, newline="", encoding="utf-8-sig") as fh:
        return list(csv.DictReader(fh))


def _largest_counts(assemblies) -> dict[str, int]:
    out: dict[str, int] = {}
    for inst in assemblies.values():
        for part, n in Counter(i.part for i in inst).items():
            out[part] = max(out.get(part, 0), n)
    return out


def test_bom_quantities_are_the_assemblies_instance_counts(exported, plan, project):
    out, _ = exported
    rows = read_csv(out / "bom.csv")
    # placed parts: their instance counts (spares on top); the read-out's other bought items
    # (wire, resistors, adhesive) are not placed
    q = {r["part"]: int(r["quantity"]) - int(r["spares"]) for r in rows}
    _, assemblies = design_assemblies(project)
    placed = _largest_counts(assemblies)
    assert {k: v for k, v in q.items() if k in placed} == placed
    # the array's own parts: exactly its instance counts, which follow the design
    array = Counter(i.part for i in array_instances(plan))
    for part, n in array.items():
        assert q[part] >= n
    assert sum(q[n] for n in plan.distinct_elements) == plan.rows * plan.columns
    assert q["spacer"] == plan.rows * (plan.columns - 1) == array["spacer"]
    assert q["clamp_plate"] == 2


def test_bom_agrees_with_manifest_for_array_parts(exported):
    out, _ = exported
    man = json.loads((out / "manifest.json").read_text())
    q = {r["part"]: int(r["quantity"]) for r in read_csv(out / "bom.csv")}
    for name, p in man["parts"].items():
        if p["kind"] == "fabricated":
            assert q[name] == p["quantity"], name


def test_every_file_the_bom_names_exists(exported, plan):
    out, _ = exported
    rows = read_csv(out / "bom.csv")
    assert list(rows[0]) == list(BOM_COLUMNS)
    named = [f for r in rows for f in r["files"].split()]
    assert named
    for f in named:
        assert (out / f).is_file(), f
    md = (out / "bom.md").read_text()
    links = re.findall(r"\]\(([^)]+)\)", md)
    assert sorted(set(links)) == sorted(set(named))
    # each fabricated part points to its drawing, each element to its DXF files
    by_part = {r["part"]: r["files"].split() for r in rows}
    for r in rows:
        if r["type"] == "fabricated":  # the kit's samples too, shown in a scene or not
            assert f"drawings/{r['part']}.svg" in by_part[r["part"]] and r["stock"]
    for part in plan.distinct_elements:
        assert f"dxf/{part}_qty2.dxf" in by_part[part]
        assert "dxf/sheet_aluminium_3mm.dxf" in by_part[part]
    assert {"dxf/spacer_qty8.dxf", "dxf/sheet_aluminium_1mm.dxf"} <= set(by_part["spacer"])


def test_markdown_table_matches_csv(exported):
    out, _ = exported
    rows = read_csv(out / "bom.csv")
    md_rows = [line for line in (out / "bom.md").read_text().splitlines()
               if re.match(r"\| \d+ \|", line)]
    assert len(md_rows) == len(rows)
    for line, r in zip(md_rows, rows):
        cells = [c.strip() for c in line.strip("|").split(" | ")]
        assert cells[1] == r["part"] and cells[2] == r["quantity"] and cells[3] == r["unit"]
        assert cells[4] == r["spares"] and cells[5] == r["type"]


def test_fabricated_rows_carry_process_and_purchased_a_catalogue_reference(exported):
    out, _ = exported
    rows = read_csv(out / "bom.csv")
    kinds = [r["type"] for r in rows]
    assert kinds == sorted(kinds, key=lambda k: k != "fabricated")  # fabricated first
    for r in rows:
        assert r["material"] and r["process_or_reference"] and r["key_dimensions_mm"]
        if r["part"].startswith(("bolt_", "nut_")):
            assert re.match(r"ISO \d+ ", r["process_or_reference"])
    el = next(r for r in rows if r["part"] == "element_a4mm")
    assert el["key_dimensions_mm"].startswith("22 x 11.5 x 3")
    assert "2x Ø2.4" in el["key_dimensions_mm"]


@pytest.mark.parametrize("columns", [1, 3, 5])
def test_quantities_follow_the_design(columns):
    data = default_design_data()
    arms = data["arms"]["lengths_mm"]
    lengths = arms[:columns] + arms[5:5 + columns]
    plan = plan_from_dict(with_overrides(data, {"array.columns": columns,
                                                "arms.lengths_mm": lengths}))
    rows = bom_rows(array_instances(plan), array_parts(plan))
    q = {r.part: r.quantity for r in rows}
    assert sum(q[n] for n in plan.distinct_elements) == 2 * columns
    assert q.get("spacer", 0) == 2 * (columns - 1)
    assert q["clamp_plate"] == 2


def test_bom_rows_count_instances_per_assembly():
    plan = plan_from_dict(default_design_data())
    specs = array_parts(plan)
    p = Placement(0.0, 0.0, 0.0)
    rig = [Instance(f"s{k}", "spacer", p) for k in range(2)] + \
        [Instance(f"n{k}", "nut_M2", p) for k in range(6)]
    asm = {"array": array_instances(plan), "rig": rig}
    rows = {r.part: r for r in bom_rows(asm, specs)}
    # one set of hardware serves every assembly: the largest count of any one
    assert rows["spacer"].quantity == 8
    assert rows["nut_M2"].quantity == 6
    assert dict(rows["spacer"].per_assembly) == {"array": 8, "rig": 2}
    assert dict(rows["nut_M2"].per_assembly) == {"array": 4, "rig": 6}
    assert part_quantities(asm)["spacer"] == 8
    with pytest.raises(KeyError, match="no PartSpec"):
        bom_rows([Instance("x", "no_such_part", p)], specs)
    text = bom_csv(list(rows.values()))
    assert next(csv.DictReader(io.StringIO(text)))["part"] == "element_a4mm"


def test_scene_assemblies_are_counted_and_drawn(plan, project):
    """A scene's shown instances add their parts to the BOM and, for
    fabricated ones, to the drawings, with quantities from their instances."""
    import dataclasses

    from tactcad.assembly.inventory import fabricated_parts

    base = array_parts(plan)["spacer"]
    plate = dataclasses.replace(base, name="rig_base_plate", builder="spacer", process=Process("milling", Method.PLATE))
    shown = [("base", "rig_base_plate", "base"), ("base2", "rig_base_plate", "base")]
    shown += [(f"n{k}", "nut_M2", "nuts") for k in range(7)] + [("hidden", "nut_M2", "hidden")]
    model = types.SimpleNamespace(
        specs={"rig_base_plate": plate, "nut_M2": array_parts(plan)["nut_M2"]},
        instances=lambda: shown)
    spec = types.SimpleNamespace(groups=("base", "nuts"))
    specs, assemblies = design_assemblies(project, {"test-rig": (spec, model)})
    assert list(assemblies) == ["array", "test-rig"]
    rows = {r.part: r for r in bom_rows(assemblies, specs)}
    assert rows["rig_base_plate"].quantity == 2 and rows["rig_base_plate"].kind == "fabricated"
    assert rows["nut_M2"].quantity == 7  # the hidden group is not counted
    parts, qty = fabricated_parts(project, (specs, assemblies))
    assert "rig_base_plate" in [s.name for s in parts] and qty["rig_base_plate"] == 2


def test_real_scenes_quantities(project):
    """With the project's scenes: every scene's count is at most the BOM's
    quantity, and equal to it in at least one scene."""
    pytest.importorskip("tactcad.assembly.scene_solver")
    specs, assemblies = design_assemblies(project)
    rows = bom_rows(assemblies, specs)
    for r in rows:
        counts = [n for _, n in r.per_assembly]
        assert r.quantity == max(counts) and r.quantity > 0
    q = {r.part: r.quantity for r in rows}
    assert q["spacer"] == 8 and q["clamp_plate"] == 2


def test_bom_csv_opens_as_utf8_sig_with_alloy_temper_and_stock(tmp_path):
    """bom.csv starts with the UTF-8 byte order mark, reads back through the
    csv module with utf-8-sig (header intact, "Ø" intact), and names alloy,
    temper and the raw blank of every fabricated part."""
    from tactcad.export.bom import write_bom_files

    plan = plan_from_dict(default_design_data())
    specs = array_parts(plan)
    write_bom_files(plan, tmp_path, lambda m: None, (specs, {"array": array_instances(plan)}))
    raw = (tmp_path / "bom.csv").read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf")
    rows = read_csv(tmp_path / "bom.csv")
    assert list(rows[0]) == list(BOM_COLUMNS)
    by_part = {r["part"]: r for r in rows}
    for name, spec in specs.items():
        r = by_part[name]
        if spec.kind == "fabricated":
            assert r["material"] == f"{plan.material.name} EN AW-{plan.material.grade}"
            if "sheet" in spec.process:
                assert r["stock"].startswith(f"sheet {spec.thickness_mm:g} mm, blank ")
            else:  # milled: faced on both sides
                assert r["stock"].startswith(f"plate {spec.thickness_mm + 2:g} x ")
        else:
            assert r["stock"] == ""
    assert any("Ø" in r["key_dimensions_mm"] for r in rows)


def test_bom_stock_follows_the_design_grade():
    data = default_design_data()
    data["material"]["grade"] = "7075-T6"
    plan = plan_from_dict(data)
    rows = {r.part: r for r in bom_rows(array_instances(plan), array_parts(plan), plan=plan)}
    assert rows["element_a4mm"].material.endswith("EN AW-7075-T6")
    # spacers and clamp plates have their own grade (clamp.spacer_material, clamp.material)
    assert rows["spacer"].material.endswith("EN AW-6061-T6")
    data["clamp"]["spacer_material"] = "7075-T6"
    plan = plan_from_dict(data)
    rows = {r.part: r for r in bom_rows(array_instances(plan), array_parts(plan), plan=plan)}
    assert rows["spacer"].material.endswith("EN AW-7075-T6")
