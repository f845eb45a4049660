"""The pivoting jaw's kinematics: radii, indentation and the bias of unequal travels on R."""
import math

import pytest

from tactcad.errors import DesignError
from tactcad.in_use.jaw_kinematics import (JawGeometry, corrected_ratio, indentation_mm,
                                           ratio_bias_rel, ratio_read, tip_radius_mm)


def jaw(**kw):
    base = dict(pivot_u_mm=-5.0, pivot_v_mm=0.0, pin_to_tip_mm=40.0, opening_angle_deg=30.0,
                slab_thickness_mm=3.0)
    return JawGeometry(**{**base, **kw})


def test_tips_side_by_side_across_the_jaw_are_at_one_radius():
    j = jaw()
    assert tip_radius_mm(j, 8.0, -0.7) == pytest.approx(tip_radius_mm(j, 8.0, 0.7))
    assert tip_radius_mm(j, 8.0, 0.0) == pytest.approx(13.0)


def test_a_turned_axis_changes_the_radius_by_its_cosine():
    j = jaw(axis_angle_deg=30.0)
    assert tip_radius_mm(j, 5.0, 0.0) == pytest.approx(10.0 * math.cos(math.radians(30)))


def test_a_tip_behind_the_pin_is_refused_with_the_field():
    with pytest.raises(DesignError) as e:
        tip_radius_mm(jaw(pivot_u_mm=5.0), 0.0, 0.0)
    assert e.value.field == "jaw.pivot_u_mm"


@pytest.mark.parametrize("field,value", [("pin_to_tip_mm", 0.0), ("opening_angle_deg", 0.0),
                                         ("opening_angle_deg", 120.0), ("slab_thickness_mm", -1.0),
                                         ("pivot_u_mm", float("nan")), ("axis_angle_deg", 95.0)])
def test_bad_jaw_fields_name_field_value_and_range(field, value):
    with pytest.raises(DesignError) as e:
        jaw(**{field: value})
    assert e.value.field == f"jaw.{field}" and "..." in e.value.allowed


def test_indentation_falls_with_radius_and_vanishes_past_contact():
    near, far = indentation_mm(3.0, 10.0, 10.0), indentation_mm(3.0, 14.0, 10.0)
    assert near > far > 0
    assert near == pytest.approx(3.0 - 10.0 * math.sin(math.radians(10.0)))
    assert indentation_mm(3.0, 30.0, 10.0) == 0.0


def test_unequal_travels_scale_R_by_their_ratio_and_the_correction_undoes_it():
    k_m, k_r, k_obj = 2.0, 20.0, 1.0
    true_r = (k_r + k_obj) / (k_m + k_obj)
    read = ratio_read(k_m, k_r, k_obj, travel_m_mm=1.4, travel_r_mm=1.0)
    assert read / true_r - 1 == pytest.approx(ratio_bias_rel(1.4, 1.0)) == pytest.approx(0.4)
    assert corrected_ratio(read, 1.4, 1.0) == pytest.approx(true_r)


def test_an_unpressed_reference_is_refused():
    with pytest.raises(DesignError):
        ratio_bias_rel(1.0, 0.0)
