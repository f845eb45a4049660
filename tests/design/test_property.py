"""Property-based designs: every in-domain draw builds valid parts and DXF, and
whole designs drawn over every field of the domain validate with their rigs
and scenes, build every distinct part and assemble every scene; every
out-of-domain draw is refused with the offending field named."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from depth import draws

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.checks.dxf_readback import check_profile_dxf
from tactcad.checks.solids import check_solid
from tactcad.design.array_plan import ARM_RANGE_MM, WEB_RANGE_MM, default_design_data, plan_from_dict, with_overrides
from tactcad.design.domain import draw_design, draw_out_of_domain
from tactcad.design.project import project_from_data
from tactcad.design.rig_plan import default_rigs_data
from tactcad.design.scene_specs import DEFAULT_SCENES
from tactcad.vocabulary.schema import Problems, read_toml
from tactcad.errors import DesignError
from tactcad.export.dxf_sheet import shop_profiles, write_shop_profile
from tactcad.kernel.shapes import profile_face
from tactcad.partlib.array.element import build as build_element

SETTINGS = settings(max_examples=12, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])


@st.composite
def in_domain(draw):
    web = draw(st.floats(*WEB_RANGE_MM))
    notch = draw(st.floats(max(web, 0.15), 1.0))
    # distinct arms differ by MIN_ARM_STEP_MM (0.01 mm) at least: draw on that grid.
    # The default element's 22 mm length leaves room for the bolt pattern up to
    # 8 mm arms (longer arms need a longer element), and 4 mm clears the tip-root
    # fillet of the widest notch drawn here; the whole domain, derived limits
    # included, is drawn by tactcad.design.domain (test_validation, make fuzz).
    lo, hi = max(4.0, ARM_RANGE_MM[0]), min(8.0, ARM_RANGE_MM[1])
    grid = st.integers(round(lo * 100), round(hi * 100)).map(lambda n: n / 100)
    arms = draw(st.lists(grid, min_size=10, max_size=10))
    return {"element.web_thickness_mm": web, "element.notch_radius_mm": notch,
            "arms.lengths_mm": arms,
            "element.arm_height_mm": draw(st.floats(web + notch + 0.3, 3.0)),
            "element.tip_width_mm": draw(st.floats(1.0, 3.0))}


@pytest.mark.slow
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
    shop = next(sp for sp in shop_profiles(plan) if sp.part == g.part_name)
    write_shop_profile(path, plan, shop)
    face = profile_face(spec.profile)
    bb = face.bounding_box()
    res = check_profile_dxf(path, "e", face.area, (bb.min.X, bb.min.Y, bb.max.X, bb.max.Y),
                            plan.edm, g.web_thickness_mm, marks=(shop.file_mark,))
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


# ---------------------------------------------------------------------------
# Whole designs over every field of the domain (tactcad.design.domain)
# ---------------------------------------------------------------------------
#: Rig parts whose spec does not change with the design are built once for all
#: examples (rig builders read only their spec).
_RIG_SOLIDS: dict[str, object] = {}


def _draw_whole_design(case):
    def pick(lo, hi):
        return case.draw(st.floats(min(lo, hi), max(lo, hi)))

    def choose(options):
        return case.draw(st.sampled_from(list(options)))

    return draw_design(pick, choose), pick, choose


def _project(data):
    p = Problems("drawn.toml")
    out = project_from_data(data, default_rigs_data(), read_toml(DEFAULT_SCENES, "scenes file"), p,
                            source="drawn.toml")
    return out, p.errors


#: Whole designs built per run of the suite: the suite's share of the domain's
#: draws (10 in ``make test``, 30 in ``make test-deep``); ``make fuzz`` (scripts/fuzz.py) builds 1000 with the same draw and also
#: checks each scene's interference.
WHOLE_DESIGNS = draws(10, 30)


@pytest.mark.slow
@settings(max_examples=WHOLE_DESIGNS, deadline=None, suppress_health_check=list(HealthCheck),
          phases=[Phase.explicit, Phase.reuse, Phase.generate])  # no slow shrinking of solids
@given(case=st.data())
def test_whole_designs_validate_build_and_assemble(case):
    from tactcad.assembly.scene_solver import assemble
    from tactcad.design.project import project_of
    from tactcad.catalogue.rig_catalogue import RigPartSpec, rig_parts
    from tactcad.solids.cache import PartCache
    from tactcad.store import stable_repr

    data, _, _ = _draw_whole_design(case)
    (plan, rigs, scenes), errors = _project(data)
    assert not errors, [e.line() for e in errors]
    cache = PartCache(plan)
    bad = []
    for spec in {**array_parts(plan), **rig_parts(plan, rigs)}.values():
        if isinstance(spec, RigPartSpec):
            key = stable_repr(spec)
            if key in _RIG_SOLIDS:
                continue  # built and checked in an earlier example
            _RIG_SOLIDS[key] = cache.solid(spec)
        bad += [r.line() for r in check_solid(spec, cache.solid(spec)) if not r.passed]
    assert not bad, bad
    for name in scenes:
        scene = assemble(project_of(plan, rigs, scenes), name)
        assert scene.instances


@settings(max_examples=100, deadline=None)
@given(case=st.data())
def test_out_of_domain_whole_designs_are_refused_naming_the_field(case):
    data, pick, choose = _draw_whole_design(case)
    field, value = draw_out_of_domain(pick, choose)
    if field.startswith("arms.lengths_mm["):
        data["arms"]["lengths_mm"][1] = value
    else:
        section, key = field.split(".")
        data[section][key] = value
    _, errors = _project(data)
    assert field in [e.field for e in errors], [e.line() for e in errors]
