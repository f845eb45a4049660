"""The array's placed parts come from its construction (the registry): the
comb places one sheet per row and a gauge on every element, each gauge bonded
to its row's sheet; the placed solids of the comb lie where the plan's
placements put them and do not interfere."""

from __future__ import annotations

import pytest

from tactcad.assembly.plan_locations import location
from tactcad.catalogue.array_catalogue import array_contacts, array_instances, array_parts
from tactcad.checks.array_checks import interference_group
from tactcad.checks.groups import CheckContext
from tactcad.design.array_plan import EXAMPLES, Placement, load_design
from tactcad.kernel.locations import point
from tactcad.solids.cache import PartCache

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def comb():
    return load_design(GRASPER)


def test_the_comb_places_its_row_sheets_and_a_gauge_per_element(comb):
    names = [i.name for i in array_instances(comb)]
    sheets = [s.part_name for s in comb.comb.sheets]
    assert names[:len(sheets)] == sheets
    assert sorted(n for n in names if n.startswith("gauge_")) == sorted(
        f"gauge_{s.number}" for s in comb.slots)
    assert {i.part for i in array_instances(comb)} <= set(array_parts(comb))


def test_every_comb_gauge_is_bonded_to_its_rows_sheet(comb):
    contacts = array_contacts(comb)
    for s in comb.slots:
        assert frozenset({comb.comb.sheets[s.row].part_name, f"gauge_{s.number}"}) in contacts


@pytest.mark.parametrize("placement", [Placement(1.0, 2.0, 3.0, quarter_turn=True),
                                       Placement(-0.5, 0.0, 4.0, turned=True, quarter_turn=True),
                                       Placement(1.0, 2.0, 3.0, turned=True)])
def test_a_placements_cad_location_puts_a_point_where_the_plan_says(placement):
    for local in ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.3, -0.7, 2.0)):
        got = point(location(placement), local)
        assert (got.X, got.Y, got.Z) == pytest.approx(placement.apply(*local), abs=1e-9)


@pytest.mark.slow  # every solid of a comb built and checked
def test_the_placed_comb_has_no_interference_and_every_gauge_on_its_sheet(comb, tmp_path):
    found = [r for _, results in interference_group(CheckContext(comb, tmp_path, PartCache(comb),
                                                                 None, None)) for r in results]
    assert found and all(r.passed for r in found), [r for r in found if not r.passed]
