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
    consumed = {p: s.key for s in steps for p, _ in s.parts}
    for r in rows:
        assert r.step in step_keys, r.part
        assert consumed[r.part] == r.step
    assert set(consumed) == {r.part for r in rows}
    fitted = {r.part: r.quantity - r.spares for r in rows}  # the spares stay in the kit
    assert all(fitted[p] == q for s in steps for p, q in s.parts)
    assert len(consumed) == sum(len(s.parts) for s in steps)  # one step per item


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
