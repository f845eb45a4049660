"""A BOM that builds the sensor: gauges with spares, terminals, lead wire, bridge completion,
adhesive; clamp plates and spacers of their own material."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest

from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
from tactcad.design.project import load_project
from tactcad.errors import DesignError
from tactcad.drawings.sheet import fmt_mm
from tactcad.export.bom import CSV_ENCODING, write_bom_files

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _bom(plan, tmp_path) -> dict[str, dict]:
    from tactcad.assembly.inventory import design_assemblies
    from tactcad.design.project import project_for_plan

    write_bom_files(plan, tmp_path, lambda line: None, design_assemblies(project_for_plan(plan)))
    text = (tmp_path / "bom.csv").read_bytes().decode(CSV_ENCODING)
    return {r["part"]: r for r in csv.DictReader(io.StringIO(text))}


def test_example_bom_has_gauges_for_every_element_plus_spares_and_its_own_plate_material(
        tmp_path):
    plan = load_project(EXAMPLE).plan
    rows = _bom(plan, tmp_path)
    n = plan.rows * plan.columns
    gauge = rows["strain_gauge"]
    assert int(gauge["quantity"]) == n + 2 and gauge["spares"] == "2"
    assert "grid 0.6 x 1 mm" in gauge["process_or_reference"]
    # the modelled body: carrier outline, as thick as the catalogue's glue line + carrier
    layer = plan.strength.gauge.grid_height_mm
    assert gauge["key_dimensions_mm"] == f"2.2 x {fmt_mm(layer, 2)} x 2"
    assert int(rows["solder_terminal_pair"]["quantity"]) == n + 2
    assert int(rows["bridge_completion_resistor"]["quantity"]) == 3 * n
    assert rows["lead_wire"]["unit"] == "m" and float(rows["lead_wire"]["quantity"]) >= 1.5 * n
    assert rows["gauge_adhesive"]["quantity"] == "1"
    # the titanium elements' clamp plates and spacers are aluminium, not titanium
    assert rows["clamp_plate"]["material"] == "aluminium EN AW-6061-T6"
    assert rows["spacer"]["material"] == "aluminium EN AW-6061-T6"
    assert rows[plan.element(1).geometry.part_name]["material"] == "Ti-6Al-4V-annealed"
    md = (tmp_path / "bom.md").read_text(encoding="utf-8")
    assert "Ti-6Al-4V-annealed Ti-6Al-4V-annealed" not in md


def test_spares_clamp_and_spacer_material_are_set_on_their_own(tmp_path):
    data = with_overrides(default_design_data(), {
        "bom.spares": 5, "clamp.material": "7075", "clamp.spacer_material": "17-4ph-h900",
        "bom.lead_wire_m_per_element": 0.25})
    rows = _bom(plan_from_dict(data), tmp_path)
    assert rows["strain_gauge"]["quantity"] == "15" and rows["strain_gauge"]["spares"] == "5"
    assert rows["clamp_plate"]["material"] == "aluminium EN AW-7075-T6"
    assert rows["spacer"]["material"] == "stainless steel 17-4PH-H900"
    assert rows["lead_wire"]["quantity"] == "3"  # 10 x 0.25 m, whole metres up
    assert rows["element_a4mm"]["material"] == "aluminium EN AW-6061-T6"


@pytest.mark.parametrize("key, value, field", [
    ("clamp.material", "wood", "clamp.material"),
    ("clamp.spacer_material", "aluminium", "clamp.spacer_material"),  # two grades fit
    ("bom.spares", -1, "bom.spares"),
    ("bom.spares", 1.5, "bom.spares"),
    ("bom.lead_wire_m_per_element", 0, "bom.lead_wire_m_per_element"),
])
def test_bad_bom_values_are_refused_naming_the_field(key, value, field):
    with pytest.raises(DesignError) as exc:
        plan_from_dict(with_overrides(default_design_data(), {key: value}))
    assert field in str(exc.value)
