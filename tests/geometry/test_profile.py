"""The exact profile: area, bbox, corners and the web function, checked independently."""

from __future__ import annotations

import math

import pytest
import shapely.geometry as sg

from tactcad.geometry.profile import (Arc, contour_area, contour_bbox, element_profile, inside_corners,
                             web_thickness_at)


def _polygon(segments, n_arc=2000):
    pts = []
    for s in segments:
        pts.append(s.start)
        if isinstance(s, Arc):
            a0 = math.atan2(s.start[1] - s.centre[1], s.start[0] - s.centre[0])
            pts += [(s.centre[0] + s.radius * math.cos(a0 + s.sweep * k / n_arc),
                     s.centre[1] + s.radius * math.sin(a0 + s.sweep * k / n_arc)) for k in range(1, n_arc)]
    return sg.Polygon(pts)


@pytest.mark.parametrize("number", [1, 2, 3, 4, 7])
def test_area_and_bbox_match_a_dense_polygon(plan, number):
    g = plan.element(number).geometry
    prof = element_profile(g)
    poly = _polygon(prof.outer)
    assert poly.is_valid
    assert contour_area(prof.outer) == pytest.approx(poly.area, rel=1e-6)
    assert contour_bbox(prof.outer) == pytest.approx(poly.bounds, abs=1e-6)
    assert contour_area(prof.outer) > 0  # counter-clockwise


def test_contour_is_closed_and_continuous(plan):
    prof = element_profile(plan.element(4).geometry)
    segs = prof.outer
    for a, b in zip(segs, segs[1:] + segs[:1]):
        assert math.dist(a.end, b.start) < 1e-12


def test_inside_corners_are_the_notch_and_the_tip_fillet(plan):
    g = plan.element(1).geometry
    corners = inside_corners(element_profile(g).outer)
    radii = sorted(r for _, r in corners)
    assert radii == pytest.approx([g.inside_corner_radius_mm, g.notch_radius_mm])


def test_inside_corner_detector_finds_a_sharp_corner():
    from tactcad.geometry.profile import _chain
    l_shape = _chain([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)])
    corners = inside_corners(l_shape)
    assert corners == [((1, 1), 0.0)]


def test_web_function_minimum_is_the_web(plan):
    g = plan.element(1).geometry
    assert web_thickness_at(g, g.hinge_x_mm) == pytest.approx(g.web_thickness_mm)
    edge = web_thickness_at(g, g.hinge_x_mm + g.notch_radius_mm)
    assert edge == pytest.approx(g.web_thickness_mm + g.notch_radius_mm)
    with pytest.raises(ValueError):
        web_thickness_at(g, g.hinge_x_mm + 2 * g.notch_radius_mm)


def test_lever_arm_is_table1_flexing_arm(plan):
    for s in plan.slots:
        g = s.geometry
        assert g.tip_centre_x_mm - g.hinge_x_mm == pytest.approx(g.arm_length_mm)
