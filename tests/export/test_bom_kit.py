"""The complete kit: every sample the rigs name, consumables, and a step per row."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.assembly.inventory import design_assemblies, fabricated_parts
from tactcad.design.project import load_project
from tactcad.export.bom import bom_csv, complete_kit, kit_steps, sample_kit


HARDWARE = Path(__file__).resolve().parents[2] / "hardware"


@pytest.fixture(scope="module", params=["macro_array", "ti_array_2x3"])
def kit(request):
    project = load_project(HARDWARE / request.param / f"{request.param}.toml")
    assembled = design_assemblies(project)
    rows = complete_kit(project, assembled)
    return project, rows, kit_steps(project, rows, assembled[0])


def test_sample_kit_lists_every_stiffness_the_rigs_name(kit):
    from tactcad.partlib.sample import stiffnesses

    project, rows, _ = kit
    named = stiffnesses(project.rigs.library["sample"])
    kit_parts = sample_kit(project)
    assert sorted(k for k, _ in kit_parts.values()) == sorted(named)
    by_part = {r.part: r for r in rows}
    for part in kit_parts:
        assert by_part[part].quantity >= 1 and by_part[part].step == "samples-cast"
    assert len(named) > sum(1 for r in rows if r.part in kit_parts and any(
        n for _, n in r.per_assembly))  # more samples than the scenes show


def test_every_row_names_its_step_and_every_step_part_is_a_row(kit):
    _, rows, steps = kit
    step_keys = {s.key for s in steps}
    consumed: dict[str, list[str]] = {}
    counted: dict[str, int] = {}
    for s in steps:
        for p, q in s.parts:
            consumed.setdefault(p, []).append(s.key)
            counted[p] = counted.get(p, 0) + q
    for r in rows:
        assert r.step in step_keys, r.part
        assert consumed[r.part][0] == r.step  # a nut shared over steps: its first one's
    assert set(consumed) == {r.part for r in rows}
    fitted = {r.part: r.quantity - r.spares for r in rows}  # the spares stay in the kit
    assert counted == fitted  # every fitted unit in some step, none counted twice
    # one step per item, but a nut, fitted where the bolts of its size are
    assert all(len(keys) == 1 or p.startswith("nut_") for p, keys in consumed.items())


def test_each_steps_nuts_follow_the_bolts_it_fits_as_the_bom_counts_them(kit):
    """The build book's nuts are the BOM's, each step fitting as many of a size as the
    bolts of that size it fits (the stack's clamp bolts and a rig's through bolts alike)."""
    from tactcad.assembly.build_steps import fastener_sizes
    from tactcad.assembly.inventory import design_assemblies

    project, rows, steps = kit
    sizes = fastener_sizes(design_assemblies(project)[0])
    bom_nuts = {r.part: r.quantity - r.spares for r in rows if sizes.get(r.part, ("",))[0] == "nut"}
    assert bom_nuts
    for s in steps:
        for nut, q in s.parts:
            kind, size = sizes.get(nut, ("", ""))
            if kind == "nut":
                bolts = sum(n for p, n in s.parts if sizes.get(p) == ("bolt", size))
                assert 0 < q <= bolts, (s.key, nut, q, bolts)
    assert {n: sum(q for s in steps for p, q in s.parts if p == n) for n in bom_nuts} == bom_nuts


def test_nuts_are_shared_over_the_steps_that_fit_bolts_of_their_size():
    from tactcad.assembly.build_steps import nuts_with_their_bolts

    fasteners = {"bolt_M2x20": ("bolt", "M2"), "bolt_M2x25": ("bolt", "M2"),
                 "bolt_M4x12": ("bolt", "M4"), "nut_M2": ("nut", "M2")}
    by_step = {"array-bolts": [("bolt_M2x20", 4), ("nut_M2", 7)],
               "rig-a": [("plate", 1), ("bolt_M2x25", 2), ("bolt_M4x12", 4)]}
    out = nuts_with_their_bolts(by_step, fasteners, ["array-bolts", "rig-a"])
    assert dict(out["array-bolts"])["nut_M2"] == 5  # 4 with the bolts, the odd one left
    assert dict(out["rig-a"]) == {"plate": 1, "bolt_M2x25": 2, "bolt_M4x12": 4, "nut_M2": 2}


def test_kit_has_consumables_and_step_column(kit):
    _, rows, _ = kit
    kinds = {r.kind for r in rows}
    assert "consumable" in kinds
    assert {"solder_wire", "gauge_adhesive", "lead_wire"} <= {r.part for r in rows}
    header = bom_csv(rows).splitlines()[0]
    assert header.endswith(",step")


def test_the_ti_example_kit_carries_no_paper_sample(kit):
    project, rows, steps = kit
    if project.plan.raw.get("requirements", {}).get("source"):
        pytest.skip("the paper's design")
    text = " ".join(n for s in steps for n in s.notes)
    assert "10.01" not in text and "sample_k10p01" not in {r.part for r in rows}


def test_every_sample_is_a_part_of_its_own_with_its_drawing_and_stock(kit):
    """A sample no scene shows is cast and drawn as the shown ones are: its
    own drawing (not another stiffness's) and its stock."""
    project, _, _ = kit
    assembled = design_assemblies(project)
    rows = complete_kit(project, assembled, files=lambda spec: (f"drawings/{spec.name}.svg",))
    by_part = {r.part: r for r in rows}
    made, qty = fabricated_parts(project, assembled)
    for part, (k, spec) in sample_kit(project).items():
        row = by_part[part]
        assert row.files == (f"drawings/{part}.svg",) and row.stock, row
        assert f"measured stiffness {k:g} N/mm" in row.process
        assert spec in made and qty[part] == row.quantity
