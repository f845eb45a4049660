"""Round-trip checks of the shop DXF files (:mod:`tactcad.export.dxf_sheet`):
each per-profile file and each nested sheet, read back and compared with the
CAD face of its profile (area and box from OpenCascade, not from the writer),
and with what its cut process says the file holds
(:attr:`tactcad.vocabulary.process.CutProcess.shop`): a cutting tool's file
its lead-ins, holding tabs by the tab rule and the cut order; etch artwork its
outline offset by the compensation."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tactcad.checks.check_result import CheckResult
from tactcad.checks.dxf_readback import (SheetPart, check_etch_artwork, check_profile_dxf,
                                         check_sheet_dxf, cut_order_checks, read_dxf, tab_checks)
from tactcad.design.array_plan import Plan
from tactcad.export.dxf_sheet import ShopProfile, sheet_dxf_name, sheet_gap_mm, sheets


@dataclass(frozen=True)
class CutRules:
    """The two figures the read-back checks of a cut contour hold it to (mm)."""

    min_inside_radius_mm: float
    min_slot_width_mm: float


def cut_rules(sp: ShopProfile) -> CutRules:
    """``sp``'s process's smallest inside radius and slot (mm) for its file's
    contours; none for etch artwork, whose outline is the phototool's, not the
    part's (the etch's rules are checked on the part: :mod:`tactcad.checks.process_rules`)."""
    if sp.cut.shop.offset_outline:
        return CutRules(0.0, 0.0)
    lim = sp.limits
    return CutRules(lim.min_inside_radius_mm.value_mm, lim.min_slot_mm.value_mm)


def _face(sp: ShopProfile) -> tuple[float, tuple[float, float, float, float]]:
    from tactcad.kernel.inspect import area, bounding_box
    from tactcad.kernel.shapes import profile_face

    f = profile_face(sp.profile)
    box = bounding_box(f, optimal=True)
    return area(f), (box.min[0], box.min[1], box.max[0], box.max[1])


def _tabs_expected(sp: ShopProfile) -> tuple[int, float]:
    rule = sp.cut.shop.tabs
    x0, y0, x1, y1 = sp.profile.bbox_mm
    return rule.tabs_for(max(x1 - x0, y1 - y0)) if rule else (0, 0.0)


def _process_checks(path: Path, name: str, group: list[ShopProfile],
                    copies: list[ShopProfile]) -> list[CheckResult]:
    """Tabs and cut order of a cutting tool's file (``copies``: the profile of
    each part in the file, in the order its outer contours are read)."""
    shop = group[0].cut.shop
    if not shop.lead_ins:
        return []
    r = read_dxf(path)
    return (tab_checks(name, r, [_tabs_expected(sp) for sp in copies])
            + cut_order_checks(name, r, bool(shop.cut_order)))


def _sheet_order(path: Path, group: list[ShopProfile]) -> list[ShopProfile]:
    """The profile of each part on a nested sheet, in the order its outer
    contours are read back (matched by the box size)."""
    from tactcad.checks.dxf_readback import outer_contours
    from tactcad.geometry.profile import contour_bbox

    out = []
    for c in outer_contours(read_dxf(path)):
        x0, y0, x1, y1 = contour_bbox(c.segments)
        out.append(min(group, key=lambda sp: abs((sp.drawn.bbox_mm[2] - sp.drawn.bbox_mm[0]) - (x1 - x0))
                       + abs((sp.drawn.bbox_mm[3] - sp.drawn.bbox_mm[1]) - (y1 - y0))))
    return out


def _profile_checks(out_dir: Path, sp: ShopProfile, plan: Plan) -> tuple[list[CheckResult], SheetPart]:
    path, name = out_dir / sp.file_name, Path(sp.file_name).name
    if sp.cut.shop.offset_outline:
        d = sp.limits.compensation_per_side_mm.value_mm
        results = check_etch_artwork(path, name, sp.profile.outer,
                                     [(h.centre, h.radius) for h in sp.profile.holes], d,
                                     marks=(sp.file_mark,))
        drawn = sp.drawn
        x0, y0, x1, y1 = drawn.bbox_mm
        return results, SheetPart(sp.part, drawn.area_mm2, (x1 - x0, y1 - y0), None, sp.copy_marks)
    area, bbox = _face(sp)
    results = check_profile_dxf(path, name, area, bbox, cut_rules(sp), sp.web_thickness_mm,
                                lead_ins=True, marks=(sp.file_mark,),
                                start_holes=sp.cut.shop.start_holes)
    results += _process_checks(path, name, [sp], [sp])
    return results, SheetPart(sp.part, area, (bbox[2] - bbox[0], bbox[3] - bbox[1]),
                              sp.web_thickness_mm, sp.copy_marks)


def check_shop_dxf_files(plan: Plan, out_dir: str | Path) -> list[CheckResult]:
    """Every check of ``out_dir/dxf``: per-profile files (contours, area, box,
    the process's cutting rules, web, lead-ins, tabs, cut order, marks,
    extents; for etch artwork the compensation) and nested sheets (the same
    per copy, plus copies, gaps and marks)."""
    out_dir = Path(out_dir)
    results: list[CheckResult] = []
    for (material, t), group in sheets(plan).items():
        expected = []
        for sp in group:
            found, part = _profile_checks(out_dir, sp, plan)
            results += found
            expected.append(part)
        rel = sheet_dxf_name(material, t)
        cutting = group[0].cut.shop.lead_ins
        results += check_sheet_dxf(out_dir / rel, Path(rel).name, expected, cut_rules(group[0]),
                                   sheet_gap_mm(plan), lead_ins=cutting,
                                   start_holes=group[0].cut.shop.start_holes)
        if cutting:
            results += _process_checks(out_dir / rel, Path(rel).name, group,
                                       _sheet_order(out_dir / rel, group))
    return results
