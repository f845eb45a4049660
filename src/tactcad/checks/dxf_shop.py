"""Round-trip checks of the shop DXF files (:mod:`tactcad.export.dxf_sheet`):
each per-profile file and each nested sheet, read back and compared with the
CAD face of its profile (area and box from OpenCascade, not from the writer)."""

from __future__ import annotations

from pathlib import Path

from tactcad.design.array_plan import Plan
from tactcad.export.dxf_sheet import ShopProfile, sheet_dxf_name, sheet_gap_mm, sheets
from tactcad.checks.dxf_readback import SheetPart, check_profile_dxf, check_sheet_dxf
from tactcad.checks.check_result import CheckResult


def _face(sp: ShopProfile) -> tuple[float, tuple[float, float, float, float]]:
    from tactcad.kernel.inspect import area, bounding_box
    from tactcad.kernel.shapes import profile_face

    f = profile_face(sp.profile)
    box = bounding_box(f, optimal=True)
    return area(f), (box.min[0], box.min[1], box.max[0], box.max[1])


def check_shop_dxf_files(plan: Plan, out_dir: str | Path) -> list[CheckResult]:
    """Every check of ``out_dir/dxf``: per-profile files (contours, area, box,
    wire-EDM rules, web, lead-ins, marks, extents) and nested sheets (the same
    per copy, plus copies, gaps and marks)."""
    out_dir = Path(out_dir)
    results: list[CheckResult] = []
    for (material, t), group in sheets(plan).items():
        expected = []
        for sp in group:
            area, bbox = _face(sp)
            results += check_profile_dxf(out_dir / sp.file_name, Path(sp.file_name).name, area, bbox,
                                         plan.edm, sp.web_thickness_mm, lead_ins=True,
                                         marks=(sp.file_mark,))
            expected.append(SheetPart(sp.part, area, (bbox[2] - bbox[0], bbox[3] - bbox[1]),
                                      sp.web_thickness_mm, sp.copy_marks))
        rel = sheet_dxf_name(material, t)
        results += check_sheet_dxf(out_dir / rel, Path(rel).name, expected, plan.edm, sheet_gap_mm(plan))
    return results
