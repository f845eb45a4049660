"""The ``process`` check group: every part cut from sheet against its cut
process's rules (:mod:`tactcad.vocabulary.process`), on the design alone
(no export needed): the sheet in the process's range, the smallest hole, the
thinnest web and ligament, the smallest inside radius, the narrowest slot,
and the web's drawn tolerance against what the process holds. Each result
names the feature, its value, the rule with its figure and the rule's source.

Units: mm.
"""

from __future__ import annotations

import math
from typing import Iterator

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found
from tactcad.export.dxf_sheet import ShopProfile, shop_profiles
from tactcad.geometry.profile import Arc, contour_points, inside_corners
from tactcad.vocabulary.process import Figure

#: Rounding slack at a rule's bound (mm).
SLACK_MM = 1e-9


def _rule(fig: Figure) -> str:
    return f"{fig.rule} = {fig.value_mm:.4g} mm ({fig.source})"


def _at_least(check: str, sp: ShopProfile, feature: str, value: float, fig: Figure) -> CheckResult:
    ok = value >= fig.value_mm - SLACK_MM
    verdict = "" if ok else " is below it"
    return CheckResult(check, sp.part, ok,
                       f"{sp.process}: {feature} {value:.4g} mm{verdict}; rule: {_rule(fig)}")


def narrowest_ligament_mm(sp: ShopProfile) -> float:
    """The thinnest material around the holes (mm): hole to outer contour and
    hole to hole, edge to edge; inf without holes."""
    import shapely.geometry as sg

    ring = sg.Polygon(contour_points(sp.profile.outer)).exterior
    holes = sp.profile.holes
    gaps = [ring.distance(sg.Point(h.centre)) - h.radius for h in holes]
    gaps += [math.dist(a.centre, b.centre) - a.radius - b.radius
             for i, a in enumerate(holes) for b in holes[:i]]
    return min(gaps, default=math.inf)


def part_rule_checks(sp: ShopProfile) -> list[CheckResult]:
    """Every rule of ``sp``'s process on its nominal profile and sheet."""
    cut, lim = sp.cut, sp.limits
    lo, hi = cut.sheet_range_mm
    t = sp.thickness_mm
    out = [CheckResult("process_sheet", sp.part, lo - SLACK_MM <= t <= hi + SLACK_MM,
                       f"{sp.process}: sheet {t:g} mm, the process takes {lo:g}-{hi:g} mm "
                       f"({cut.sheet_source})")]
    holes = sp.profile.holes
    if holes:
        smallest = min(2 * h.radius for h in holes)
        out.append(_at_least("process_min_hole", sp, "smallest hole Ø", smallest, lim.min_hole_mm))
        out.append(_at_least("process_min_web", sp, "thinnest ligament at a hole",
                             narrowest_ligament_mm(sp), lim.min_web_mm))
    if sp.web_thickness_mm is not None:
        out.append(_at_least("process_min_web", sp, "flexure web", sp.web_thickness_mm,
                             lim.min_web_mm))
    corners = inside_corners(sp.profile.outer)
    if corners:
        out.append(_at_least("process_inside_radius", sp, "smallest inside radius",
                             min(r for _, r in corners), lim.min_inside_radius_mm))
    slots = [2 * s.radius for s in sp.profile.outer
             if isinstance(s, Arc) and not s.ccw and abs(s.sweep) >= math.pi - 1e-9]
    if slots:
        out.append(_at_least("process_min_slot", sp, "narrowest slot", min(slots), lim.min_slot_mm))
    tol = sp.web_tolerance_mm
    if sp.web_thickness_mm is not None and tol is not None:
        fig = lim.tolerance_mm
        ok = tol >= fig.value_mm - SLACK_MM
        out.append(CheckResult(
            "process_tolerance", sp.part, ok,
            f"{sp.process}: web drawn +/-{tol:.3g} mm, the process holds +/-{fig.value_mm:.3g} mm"
            + ("" if ok else " (widen [tolerances] web_thickness_mm or choose a finer process)")
            + f"; rule: {fig.rule} ({fig.source})"))
    return out


def process_rule_checks(plan) -> list[CheckResult]:
    """:func:`part_rule_checks` of every distinct part ``plan`` cuts from sheet."""
    return [r for sp in shop_profiles(plan) for r in part_rule_checks(sp)]


def process_group(context: CheckContext) -> Iterator[Found]:
    """``process``: every cut part against its process's rules."""
    yield "process", process_rule_checks(context.plan)
