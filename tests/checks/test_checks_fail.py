"""Each check can fail: feed it a broken file or shape and it says so."""

from __future__ import annotations

import build123d as bd
import ezdxf
import pytest

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.checks.dxf_readback import check_profile_dxf
from tactcad.checks.interference import Placed, check_interference
from tactcad.checks.solids import check_solid
from tactcad.checks.step_readback import check_step
from tactcad.export.dxf import write_profile_dxf
from tactcad.kernel.shapes import profile_face
from tactcad.partlib.array.element import build as build_element
from tactcad.geometry.profile import element_profile


@pytest.fixture(scope="module")
def element(plan):
    g = plan.element(1).geometry
    prof = element_profile(g)
    face = profile_face(prof)
    bb = face.bounding_box()
    return g, prof, face.area, (bb.min.X, bb.min.Y, bb.max.X, bb.max.Y)


def _failed(results):
    return {r.check for r in results if not r.passed}


def test_spline_and_open_contour_fail(tmp_path, plan, element):
    g, prof, area, bbox = element
    path = tmp_path / "bad.dxf"
    write_profile_dxf(path, prof)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    outer = next(e for e in msp if e.dxftype() == "LWPOLYLINE")
    outer.closed = False
    pts = list(outer.get_points("xyb"))
    outer.set_points(pts[:-1], format="xyb")  # drop a vertex: the chain no longer closes
    msp.add_spline([(0, 0), (1, 1), (2, 0)], dxfattribs={"layer": "CUT"})
    doc.saveas(path)
    failed = _failed(check_profile_dxf(path, "bad", area, bbox, plan.edm, g.web_thickness_mm))
    assert {"dxf_entity_types", "dxf_closed_contours", "dxf_area"} <= failed


def test_missing_start_hole_and_wrong_web_fail(tmp_path, plan, element):
    g, prof, area, bbox = element
    path = tmp_path / "nostart.dxf"
    write_profile_dxf(path, prof)
    doc = ezdxf.readfile(path)
    for e in [e for e in doc.modelspace() if e.dxf.layer == "START_HOLE"][:1]:
        doc.modelspace().delete_entity(e)
    doc.saveas(path)
    failed = _failed(check_profile_dxf(path, "x", area, bbox, plan.edm, g.web_thickness_mm + 0.01))
    assert {"edm_start_holes", "dxf_web_thickness"} <= failed


def test_too_small_inside_radius_fails(tmp_path, plan, element):
    from dataclasses import replace

    g, prof, area, bbox = element
    path = tmp_path / "sharp.dxf"
    sharp = replace(g, inside_corner_radius_mm=0.05)
    sp = element_profile(sharp)
    write_profile_dxf(path, sp)
    f = profile_face(sp)
    b = f.bounding_box()
    failed = _failed(check_profile_dxf(path, "sharp", f.area, (b.min.X, b.min.Y, b.max.X, b.max.Y),
                                       plan.edm, g.web_thickness_mm, lead_ins=False))
    assert failed == {"edm_inside_radius"}


def test_open_shell_and_wrong_volume_fail(plan):
    spec = array_parts(plan)["spacer"]
    box = bd.Solid.make_box(12, 10, 1)
    shell = bd.Shell(box.faces()[:-1])
    failed = _failed(check_solid(spec, shell))
    assert {"no_free_boundaries", "solid_count", "watertight_mesh", "volume"} <= failed
    two = bd.Compound([box, box.moved(bd.Location((20, 0, 0)))])
    assert "solid_count" in _failed(check_solid(spec, two))


def test_overlap_is_reported_with_names_and_volume(plan, element):
    g = element[0]
    solid = build_element(g)
    placed = [Placed("a", solid), Placed("b", solid.moved(bd.Location((0, 0, 2.0))))]
    results = check_interference(placed, set())
    bad = [r for r in results if not r.passed and r.subject == "a / b"]
    assert bad and "overlap" in bad[0].detail
    expected = solid.volume / 3.0  # 1 of 3 mm of sheet thickness shared
    vol = float(bad[0].detail.split()[1])
    assert vol == pytest.approx(expected, rel=1e-6)


def test_declared_contact_must_touch(plan, element):
    solid = build_element(element[0])
    placed = [Placed("a", solid), Placed("b", solid.moved(bd.Location((0, 0, 3.5))))]
    results = check_interference(placed, {frozenset({"a", "b"})})
    assert any(r.check == "contact_touching" and not r.passed for r in results)


def test_step_reimport_detects_a_wrong_file(tmp_path, plan, element):
    from tactcad.kernel.step_writer import StepPart, write_step

    solid = build_element(element[0])
    path = tmp_path / "x.step"
    write_step(path, [StepPart("element_a4mm", solid, (0.5, 0.5, 0.5))])
    good = check_step(path, "x", 1, solid.volume, tuple(_bb(solid)), {"element_a4mm"})
    assert not _failed(good)
    bad = check_step(path, "x", 2, solid.volume * 1.01, tuple(_bb(solid)), {"other"})
    assert {"step_solid_count", "step_volume", "step_labels"} <= _failed(bad)
    (tmp_path / "junk.step").write_text("not a step file")
    assert "step_reimport" in _failed(check_step(tmp_path / "junk.step", "j", 1, 1.0, (0,) * 6, set()))


def _bb(s):
    b = s.bounding_box()
    return (b.min.X, b.min.Y, b.min.Z, b.max.X, b.max.Y, b.max.Z)
