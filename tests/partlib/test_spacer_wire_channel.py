"""The spacer with a wire channel, an array part variant in one module: a
design without its table keeps the plain spacer; one with the table
(tests/data/spacer_wire_channel.toml) gets the channeled spacer under the
spacer's part name, a valid solid of the volume its outline gives, its own
drawing note, and refusals naming the table's fields."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.design.array_plan import load_design, plan_from_dict
from tactcad.errors import DesignError

TABLE = Path(__file__).parents[1] / "data" / "spacer_wire_channel.toml"


def with_channel(design_data: dict, **values) -> dict:
    """The design's tables with the example's ``[spacer_wire_channel]``, ``values`` replaced."""
    table = tomllib.loads(TABLE.read_text(encoding="utf-8"))["spacer_wire_channel"]
    return {**design_data, "spacer_wire_channel": {**table, **values}}


@pytest.fixture
def channeled(design_data, tmp_path):
    """The default design with the example table, read from a design file."""
    import tomli_w

    path = tmp_path / "channeled.toml"
    path.write_bytes(tomli_w.dumps(with_channel(design_data)).encode())
    return load_design(path)


def test_without_the_table_the_spacer_is_the_plain_one(plan):
    spacer = array_parts(plan)["spacer"]
    assert spacer.builder == "spacer" and spacer.geometry is plan.spacer


def test_the_table_chooses_the_channeled_spacer_under_the_spacers_name(channeled):
    specs = array_parts(channeled)
    spacer = specs["spacer"]
    assert spacer.builder == "spacer_wire_channel"
    assert [n for n in specs if n.startswith("spacer")] == ["spacer"]
    table = tomllib.loads(TABLE.read_text(encoding="utf-8"))["spacer_wire_channel"]
    g = spacer.geometry
    assert (g.channel_width_mm, g.channel_depth_mm, g.channel_corner_radius_mm) == (
        table["width_mm"], table["depth_mm"], table["corner_radius_mm"])
    plain = channeled.spacer
    assert (g.length_mm, g.height_mm, g.thickness_mm, g.holes) == (
        plain.length_mm, plain.height_mm, plain.thickness_mm, plain.holes)


def test_its_volume_is_the_plain_spacers_less_the_channel(channeled):
    from tactcad.checks.solids import check_solid
    from tactcad.solids.build import build_part

    spacer = array_parts(channeled)["spacer"]
    g, s = spacer.geometry, channeled.spacer
    plate = s.length_mm * s.height_mm - sum(math.pi * (h.diameter_mm / 2) ** 2 for h in s.holes)
    channel = (g.channel_width_mm * g.channel_depth_mm
               - 2 * (1 - math.pi / 4) * g.channel_corner_radius_mm ** 2)
    assert spacer.expected_volume_mm3 == pytest.approx((plate - channel) * s.thickness_mm, rel=1e-9)
    solid = build_part(spacer)
    failed = [r.line() for r in check_solid(spacer, solid) if not r.passed]
    assert not failed, failed


def test_its_drawing_notes_the_channel_after_the_spacers_note(channeled):
    from tactcad.drawings.part_sets import drawing_of

    spacer = array_parts(channeled)["spacer"]
    drawing = type("D", (), {"spec": spacer, "plan": channeled})()
    notes = drawing_of(spacer).notes(drawing)
    assert "sets the array pitch" in notes[0] and "Wire channel" in notes[-1]


def _too_large(plan, table: dict) -> dict[str, float]:
    """Per field, a value inside the field's own range that the plain spacer
    of ``plan`` has no room for (1 mm past the limit the module derives)."""
    s = plan.spacer
    hole_top = max(h.y_mm + h.diameter_mm / 2 for h in s.holes)
    return {"width_mm": s.length_mm - 1.0, "depth_mm": s.height_mm - hole_top,
            "corner_radius_mm": min(table["width_mm"] / 2, table["depth_mm"]) + 0.5}


@pytest.mark.parametrize("field", ["width_mm", "depth_mm", "corner_radius_mm"])
def test_a_channel_that_does_not_fit_is_refused_naming_its_field(plan, design_data, field):
    table = with_channel(design_data)["spacer_wire_channel"]
    value = _too_large(plan, table)[field]
    channeled = plan_from_dict(with_channel(design_data, **{field: value}))  # in the field's range
    with pytest.raises(DesignError, match=f"spacer_wire_channel.{field}"):
        array_parts(channeled)


def test_an_unknown_field_of_the_table_is_refused(design_data):
    with pytest.raises(DesignError, match="spacer_wire_channel"):
        plan_from_dict(with_channel(design_data, slot_mm=1.0))
