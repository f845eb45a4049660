"""The strain gauge as a part: one foil gauge body bonded over each element's web."""

from __future__ import annotations

import pytest

from tactcad.catalogue.array_catalogue import GAUGE_PART, array_contacts, array_instances, array_parts
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides


def _plan(**overrides):
    return plan_from_dict(with_overrides(default_design_data(), overrides))


def test_one_gauge_per_element_centred_over_its_web_on_the_top_face():
    plan = _plan()
    gauges = {i.name: i for i in array_instances(plan) if i.part == GAUGE_PART}
    assert len(gauges) == len(plan.slots)
    spec = array_parts(plan)[GAUGE_PART]
    assert spec.kind == "purchased" and "grid 0.6 x 1 mm" in str(spec.process)
    for s in plan.slots:
        g, p = s.geometry, gauges[f"gauge_{s.number}"].placement
        # the web's top-face point (element frame) lands on the gauge's origin
        assert p.apply(0.0, 0.0, 0.0) == pytest.approx(
            s.placement.apply(g.hinge_x_mm, g.base_height_mm, g.sheet_thickness_mm / 2))
        assert frozenset({f"element_{s.number}", f"gauge_{s.number}"}) in array_contacts(plan)


def test_gauge_body_follows_the_readout_grid_and_stays_on_the_sheet():
    spec = array_parts(_plan(**{"readout.grid_length_mm": 1.5, "readout.grid_width_mm": 2.8}))[
        GAUGE_PART]
    body = spec.geometry
    assert body.grid_length_mm == 1.5 and body.length_mm == pytest.approx(1.5 + 1.6)
    assert body.width_mm == 3.0  # the carrier is cut to the sheet
    x0, y0, z0, x1, y1, z1 = spec.expected_bbox_mm
    # as thick as the catalogue gauge's glue line + carrier
    gauge = _plan().strength.gauge
    assert (x1 - x0, y1 - y0, z1 - z0) == pytest.approx(
        (3.1, gauge.backing_thickness_mm + gauge.adhesive_thickness_mm, 3.0))


def test_gauge_body_thickness_follows_the_readout_layer():
    spec = array_parts(_plan(**{"readout.gauge_backing_thickness_mm": 0.025,
                                "readout.adhesive_thickness_mm": 0.01}))[GAUGE_PART]
    x0, y0, z0, x1, y1, z1 = spec.expected_bbox_mm
    assert y1 - y0 == pytest.approx(0.035)


def test_gauge_solid_matches_its_spec():
    from tactcad.solids.build import build_part

    plan = _plan()
    spec = array_parts(plan)[GAUGE_PART]
    solid = build_part(spec)
    bb = solid.bounding_box()
    assert solid.volume == pytest.approx(spec.expected_volume_mm3)
    assert (bb.min.X, bb.min.Y, bb.min.Z, bb.max.X, bb.max.Y, bb.max.Z) == pytest.approx(
        spec.expected_bbox_mm)
    assert solid.wrapped.Location().IsIdentity()  # one STEP product, not a located copy
