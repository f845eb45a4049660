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


def test_the_comb_plan_makes_one_sheet_per_row_and_no_stacked_part(plan):
    # the strain gauges are any construction's; nothing of the stack's
    assert sorted(array_parts(plan)) == ["comb_row1", "comb_row2", "strain_gauge"]


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
