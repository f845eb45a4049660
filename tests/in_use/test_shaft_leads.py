"""Leads through the shaft: count, bundle diameter, the channel's verdict."""
import math

import pytest

from tactcad.errors import DesignError
from tactcad.in_use.shaft_leads import bundle_diameter_mm, leads_check


def test_twelve_three_wire_bridges_are_36_leads():
    c = leads_check(12, 3.0)
    assert c.leads == 36 and c.connection == "three-wire"


def test_the_bundle_holds_the_wires_cross_section_at_the_packing_factor():
    d = bundle_diameter_mm(36, 0.25, 0.6)
    assert 36 * 0.25 ** 2 / d ** 2 == pytest.approx(0.6)


def test_the_verdict_follows_the_channel():
    need = leads_check(12, 10.0).bundle_diameter_mm
    assert leads_check(12, need * 1.01).fits and not leads_check(12, need * 0.99).fits


def test_two_wire_bridges_need_fewer_leads():
    assert leads_check(12, 3.0, "two-wire").leads == 24


@pytest.mark.parametrize("kw,field", [(dict(bridges=0, channel_diameter_mm=3.0), "bridges"),
                                      (dict(bridges=12, channel_diameter_mm=-1.0),
                                       "channel_diameter_mm"),
                                      (dict(bridges=12, channel_diameter_mm=3.0, connection="x"),
                                       "connection"),
                                      (dict(bridges=12, channel_diameter_mm=3.0,
                                            packing_factor=0.95), "packing_factor")])
def test_bad_inputs_name_the_field(kw, field):
    with pytest.raises(DesignError) as e:
        leads_check(**kw)
    assert e.value.field == field
