"""Property-based designs: every in-domain draw builds valid parts and DXF;
every out-of-domain draw is refused with the offending field named."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tactcad.catalogue import array_parts
from tactcad.checks.dxf import check_profile_dxf
from tactcad.checks.solids import check_solid
from tactcad.design import ARM_RANGE_MM, WEB_RANGE_MM, default_design_data, plan_from_dict, with_overrides
from tactcad.errors import DesignError
from tactcad.export.dxf import write_profile_dxf
from tactcad.parts.element import build_element, profile_face

SETTINGS = settings(max_examples=12, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])


@st.composite
def in_domain(draw):
    web = draw(st.floats(*WEB_RANGE_MM))
    notch = draw(st.floats(max(web, 0.15), 1.0))
    # The default element's 22 mm length leaves room for the bolt pattern up to
    # 8 mm arms (longer arms need a longer element); 4 mm clears the widest tip.
    arms = draw(st.lists(st.floats(4.0, min(8.0, ARM_RANGE_MM[1])), min_size=10, max_size=10))
    return {"element.web_thickness_mm": web, "element.notch_radius_mm": notch,
            "arms.lengths_mm": arms,
            "element.arm_height_mm": draw(st.floats(web + notch + 0.3, 3.0)),
            "element.tip_width_mm": draw(st.floats(1.0, 3.0))}


@SETTINGS
@given(overrides=in_domain())
def test_in_domain_designs_build_valid_parts_and_dxf(overrides, tmp_path_factory):
    plan = plan_from_dict(with_overrides(default_design_data(), overrides))
    specs = array_parts(plan)
    tmp = tmp_path_factory.mktemp("prop")
    slot = max(plan.slots, key=lambda s: s.geometry.arm_length_mm)  # the shortest base
    g = slot.geometry
    spec = specs[g.part_name]
    solid = build_element(g)
    bad = [r.line() for r in check_solid(spec, solid) if not r.passed]
    assert not bad, bad
    path = tmp / "e.dxf"
    write_profile_dxf(path, spec.profile)
    face = profile_face(spec.profile)
    bb = face.bounding_box()
    res = check_profile_dxf(path, "e", face.area, (bb.min.X, bb.min.Y, bb.max.X, bb.max.Y),
                            plan.edm, g.web_thickness_mm)
    bad = [r.line() for r in res if not r.passed]
    assert not bad, bad


@st.composite
def out_of_domain(draw):
    which = draw(st.sampled_from(["web_low", "web_high", "arm_low", "arm_high", "negative",
                                  "pitch", "nan"]))
    if which == "web_low":
        return "element.web_thickness_mm", draw(st.floats(0.0, WEB_RANGE_MM[0], exclude_max=True))
    if which == "web_high":
        return "element.web_thickness_mm", draw(st.floats(WEB_RANGE_MM[1], 5.0, exclude_min=True))
    if which == "arm_low":
        return "arms.lengths_mm[3]", draw(st.floats(-10.0, ARM_RANGE_MM[0], exclude_max=True))
    if which == "arm_high":
        return "arms.lengths_mm[3]", draw(st.floats(ARM_RANGE_MM[1], 100.0, exclude_min=True))
    if which == "negative":
        return "element.tip_height_mm", draw(st.floats(-100.0, 0.0))
    if which == "pitch":
        return "array.pitch_mm", draw(st.floats(0.0, 3.0))
    return "element.base_height_mm", math.nan


@settings(max_examples=60, deadline=None)
@given(case=out_of_domain())
def test_out_of_domain_draws_are_refused(case):
    field, value = case
    data = default_design_data()
    if field.startswith("arms.lengths_mm["):
        data["arms"]["lengths_mm"][2] = value
    else:
        data = with_overrides(data, {field: value})
    with pytest.raises(DesignError) as info:
        plan_from_dict(data)
    assert info.value.field == field
    assert "allowed" in str(info.value)
