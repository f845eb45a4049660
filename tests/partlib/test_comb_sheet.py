"""The comb sheet as a part: the comb's plan makes one part per row, the
stacked plan none, and each builds into one valid solid of its outline's
area times the sheet."""

from __future__ import annotations

import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.design.array_plan import EXAMPLES, load_design
from tactcad.partlib.array.comb_sheet import build, comb_profile

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def plan():
    return load_design(GRASPER)


def test_the_comb_plan_makes_one_sheet_per_row_its_hardware_and_no_stacked_part(plan):
    # the strain gauges are any construction's; nothing of the stack's (its spacer,
    # clamp plates, M2+ bolts)
    names = sorted(array_parts(plan))
    assert [n for n in names if n.startswith("comb_row")] == ["comb_row1", "comb_row2"]
    assert {"comb_spacer", "strain_gauge"} <= set(names)
    assert any(n.startswith("dowel_pin_") for n in names)
    assert not {"spacer", "clamp_plate"} & set(names)


def test_the_comb_hardware_sits_in_the_sheets_holes(plan):
    from tactcad.catalogue.array_catalogue import array_instances

    placed = {i.name: i for i in array_instances(plan)}
    c = plan.comb
    for k, z in enumerate(c.screw_x_mm, start=1):
        for name in (f"screw_{k}", f"nut_{k}"):
            x, y, zz = placed[name].placement.apply(0.0, 0.0, 0.0)
            assert (y, zz) == pytest.approx((c.fastener_y_mm, z))
        # the head under row 1's outer face, the nut on row 2's
        assert placed[f"screw_{k}"].placement.apply(0, 0, 0)[0] == pytest.approx(
            -(c.spacer_thickness_mm / 2 + plan.sheet_thickness_mm))
        assert placed[f"screw_{k}"].placement.apply(0, 0, 1)[0] > \
            placed[f"screw_{k}"].placement.apply(0, 0, 0)[0]  # the shank runs to row 2
    for k, z in enumerate(c.dowel_x_mm, start=1):
        ends = [placed[f"dowel_{k}"].placement.apply(0, 0, t)[0] for t in (0.0, c.dowel_length_mm)]
        assert ends[0] == pytest.approx(-ends[1])  # centred on the stack
        holes = {round(h.x_mm, 9) for h in c.sheets[0].holes}
        assert round(z, 9) in holes


def test_the_stacked_plan_makes_no_comb_sheet():
    names = array_parts(load_design(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"))
    assert not any(n.startswith("comb_") for n in names)


def test_each_sheet_builds_one_valid_solid_of_its_outline(plan):
    from tactcad.kernel.inspect import bbox_tuple, is_valid, solid_count, volume

    sheet = plan.comb.sheets[0]
    solid = build(sheet)
    prof = comb_profile(sheet)
    assert is_valid(solid) and solid_count(solid) == 1
    assert volume(solid) == pytest.approx(prof.area_mm2 * sheet.thickness_mm, rel=1e-6)
    x0, y0, z0, x1, y1, z1 = bbox_tuple(solid)
    assert (x1 - x0, z1 - z0) == pytest.approx((sheet.length_mm, sheet.thickness_mm), abs=1e-6)
