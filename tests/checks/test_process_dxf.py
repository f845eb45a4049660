"""What each cut process writes into its shop DXF, read back with ezdxf:
wire EDM's holding tabs (count and width by the part's size, on the outer
contour) and its cut order; the etch artwork's outline offset by the stated
compensation; and the checks failing on a file that lacks them."""

from __future__ import annotations

import math
import warnings

import ezdxf
import pytest
from process_variants import cut_by
import shapely.geometry as sg

from tactcad.checks.check_result import failures
from tactcad.checks.dxf_readback import (check_etch_artwork, cut_order_checks, read_dxf,
                                         tab_checks)
from tactcad.checks.dxf_shop import check_shop_dxf_files
from tactcad.design.array_plan import EXAMPLES, load_design, plan_from_dict, with_overrides
from tactcad.export.dxf_sheet import shop_profiles, write_shop_dxf_files
from tactcad.geometry.profile import contour_points
from tactcad.vocabulary.process import EDM_TABS
from tactcad.vocabulary.schema import read_toml

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
ETCHED = cut_by("photochemical-etching", 0.3)


def _plan(**overrides):
    with warnings.catch_warnings():  # the correction's range notice at a 0.3 mm sheet
        warnings.simplefilter("ignore")
        return plan_from_dict(with_overrides(read_toml(TI, "design file"), overrides))


@pytest.fixture(scope="module")
def wire(tmp_path_factory):
    plan = load_design(TI)
    out = tmp_path_factory.mktemp("wire")
    write_shop_dxf_files(plan, out, lambda s: None)
    return plan, out


@pytest.fixture(scope="module")
def etched(tmp_path_factory):
    plan = _plan(**ETCHED)
    out = tmp_path_factory.mktemp("etched")
    write_shop_dxf_files(plan, out, lambda s: None)
    return plan, out


def _side(sp) -> float:
    x0, y0, x1, y1 = sp.profile.bbox_mm
    return max(x1 - x0, y1 - y0)


def test_wire_edm_tabs_are_on_the_outer_contour_by_the_size_rule(wire):
    plan, out = wire
    for sp in shop_profiles(plan):
        doc = ezdxf.readfile(out / sp.file_name)
        tabs = doc.modelspace().query('LINE[layer=="TAB"]')
        count, width = EDM_TABS.tabs_for(_side(sp))
        assert count > 0 and len(tabs) == count, sp.part
        ring = sg.Polygon(contour_points(sp.profile.outer)).exterior
        for t in tabs:
            a, b = tuple(t.dxf.start)[:2], tuple(t.dxf.end)[:2]
            assert math.dist(a, b) == pytest.approx(width)
            assert ring.distance(sg.Point(a)) < 1e-6 and ring.distance(sg.Point(b)) < 1e-6
            # off the web and the contact face
            assert all(math.dist(a, k) >= 1.0 for k in sp.keep_out)


def test_wire_edm_states_its_cut_order_inner_first_outer_then_tabs(wire):
    plan, out = wire
    sp = shop_profiles(plan)[0]
    doc = ezdxf.readfile(out / sp.file_name)
    order = doc.header.custom_vars.get("CUT_ORDER")
    assert order.index("inner") < order.index("outer") < order.index("tabs last")
    labels = {e.dxf.text: tuple(e.dxf.insert)[:2]
              for e in doc.modelspace().query('TEXT[layer=="CUT_ORDER"]')}
    n = len(sp.profile.holes)
    assert sorted(labels) == [str(k) for k in range(1, n + 2)]
    outer = sg.Polygon(contour_points(sp.profile.outer))
    assert not outer.contains(sg.Point(labels[str(n + 1)]))  # the outer contour last
    assert all(outer.contains(sg.Point(labels[str(k)])) for k in range(1, n + 1))


def test_etch_artwork_offsets_the_outline_by_the_stated_compensation(etched):
    plan, out = etched
    element = next(sp for sp in shop_profiles(plan) if sp.part.startswith("element_"))
    d = element.limits.compensation_per_side_mm.value_mm
    assert d == pytest.approx(0.3 / 2 / 2.5)
    doc = ezdxf.readfile(out / element.file_name)
    assert float(doc.header.custom_vars.get("COMPENSATION_PER_SIDE_MM")) == pytest.approx(d)
    msp = doc.modelspace()
    outline = msp.query('LWPOLYLINE[layer=="CUT"]')[0]
    nominal = sg.Polygon(contour_points(element.profile.outer))
    pts = [(x, y) for x, y, *_ in outline.get_points("xy")]
    dist = [nominal.exterior.distance(sg.Point(p)) for p in pts]
    assert min(dist) == pytest.approx(d, abs=1e-6) and max(dist) == pytest.approx(d, abs=1e-6)
    assert sg.Polygon(pts).contains(nominal)
    radii = sorted(c.dxf.radius for c in msp.query('CIRCLE[layer=="CUT"]'))
    assert radii == pytest.approx(sorted(h.radius - d for h in element.profile.holes))
    assert not msp.query('*[layer=="LEAD_IN"]') and not msp.query('*[layer=="TAB"]')


def test_the_etched_design_passes_its_dxf_checks(etched):
    plan, out = etched
    results = check_shop_dxf_files(plan, out)
    assert not failures(results), "\n".join(r.line() for r in failures(results))
    assert {"etch_compensation", "etch_holes", "dxf_tabs", "dxf_cut_order"} <= {r.check for r in results}


def test_tab_check_fails_on_a_missing_or_wrong_tab(wire, tmp_path):
    plan, out = wire
    sp = shop_profiles(plan)[0]
    doc = ezdxf.readfile(out / sp.file_name)
    tabs = doc.modelspace().query('LINE[layer=="TAB"]')
    doc.modelspace().delete_entity(tabs[0])
    broken = tmp_path / "broken.dxf"
    doc.saveas(broken)
    expected = [EDM_TABS.tabs_for(_side(sp))]
    assert tab_checks("x", read_dxf(out / sp.file_name), expected)[0].passed
    assert not tab_checks("x", read_dxf(broken), expected)[0].passed
    assert not tab_checks("x", read_dxf(out / sp.file_name), [(expected[0][0], 0.9)])[0].passed


def test_cut_order_check_fails_when_the_outer_contour_is_not_last(wire, tmp_path):
    plan, out = wire
    sp = shop_profiles(plan)[0]
    doc = ezdxf.readfile(out / sp.file_name)
    labels = doc.modelspace().query('TEXT[layer=="CUT_ORDER"]')
    first, last = labels[0], labels[len(labels) - 1]
    first.dxf.text, last.dxf.text = last.dxf.text, first.dxf.text
    broken = tmp_path / "order.dxf"
    doc.saveas(broken)
    assert cut_order_checks("x", read_dxf(out / sp.file_name), True)[0].passed
    assert not cut_order_checks("x", read_dxf(broken), True)[0].passed


def test_etch_check_fails_on_an_uncompensated_outline(wire, etched):
    plan, out = etched
    element = next(sp for sp in shop_profiles(plan) if sp.part.startswith("element_"))
    holes = [(h.centre, h.radius) for h in element.profile.holes]
    d = element.limits.compensation_per_side_mm.value_mm
    good = check_etch_artwork(out / element.file_name, "x", element.profile.outer, holes, d)
    assert not failures(good)
    wplan, wout = wire  # a nominal contour where artwork was expected
    wsp = shop_profiles(wplan)[0]
    bad = check_etch_artwork(wout / wsp.file_name, "x", wsp.profile.outer,
                             [(h.centre, h.radius) for h in wsp.profile.holes], d)
    assert {r.check for r in failures(bad)} >= {"etch_compensation", "etch_holes", "etch_no_lead_ins"}


def test_laser_files_pierce_instead_of_start_holes_and_pass_their_checks(tmp_path):
    plan = _plan(**cut_by("laser-cutting", 0.5))
    write_shop_dxf_files(plan, tmp_path, lambda s: None)
    element = next(sp for sp in shop_profiles(plan) if sp.part.startswith("element_"))
    doc = ezdxf.readfile(tmp_path / element.file_name)
    assert not doc.modelspace().query('CIRCLE[layer=="START_HOLE"]')
    assert doc.modelspace().query('LINE[layer=="TAB"]')
    assert "pierce point" in doc.header.custom_vars.get("CUT_ORDER")
    results = check_shop_dxf_files(plan, tmp_path)
    assert not failures(results), "\n".join(r.line() for r in failures(results))


def test_one_sheet_cut_by_two_processes_becomes_two_shop_files(tmp_path):
    """Etched elements and wire-cut spacers of one grade and thickness: a sheet per process."""
    plan = _plan(**cut_by("photochemical-etching", 0.6, **{
                    "array.pitch_mm": 1.2, "element.tip_width_mm": 1.0,
                    "clamp.spacer_material": "Ti-6Al-4V-annealed"}))
    records = write_shop_dxf_files(plan, tmp_path, lambda s: None)
    sheets = {r["path"]: r["process"] for r in records if r["kind"] == "dxf-sheet"}
    assert sorted(sheets.values()) == ["photochemical-etching", "wire-edm"], sheets
    assert len(sheets) == 2
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.drawings.part_sets import sheet_dxf_of

    on = {sheet_dxf_of(plan, spec) for spec in array_parts(plan, ("element", "spacer")).values()}
    assert on == set(sheets)  # the drawings name the sheet each part is on
    results = check_shop_dxf_files(plan, tmp_path)
    assert not failures(results), "\n".join(r.line() for r in failures(results))
