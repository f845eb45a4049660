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
from dataclasses import dataclass
from typing import Iterator

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found
from tactcad.errors import DesignError
from tactcad.export.dxf_sheet import COMB_SPACER_PART, ShopProfile, shop_profiles
from tactcad.geometry.profile import Arc, contour_points, inside_corners
from tactcad.vocabulary.process import Figure

#: Rounding slack at a rule's bound (mm).
SLACK_MM = 1e-9


def _rule(fig: Figure) -> str:
    return f"{fig.rule} = {fig.value_mm:.4g} mm ({fig.source})"


@dataclass(frozen=True)
class MinimumRule:
    """One "at least" rule of a process applied to a part's feature (mm), and the
    design-file field that sets the feature (for a refusal before anything is written)."""

    check: str
    feature: str
    value_mm: float
    figure: Figure
    field: str

    @property
    def holds(self) -> bool:
        return self.value_mm >= self.figure.value_mm - SLACK_MM

    def result(self, sp: ShopProfile) -> CheckResult:
        # the failing figure names its limit before the rule's source, so a line cut at
        # "; rule:" (design's process report) still says what the process needs
        verdict = "" if self.holds else f" is below the {self.figure.value_mm:.4g} mm the process needs"
        return CheckResult(self.check, sp.part, self.holds,
                           f"{sp.process}: {self.feature} {self.value_mm:.4g} mm{verdict}; "
                           f"rule: {_rule(self.figure)}")

    def error(self, sp: ShopProfile) -> DesignError:
        return DesignError(self.field, round(self.value_mm, 6),
                           f">= {self.figure.value_mm:.4g} mm: {sp.process} on {sp.part}'s "
                           f"{sp.thickness_mm:g} mm sheet ({self.figure.rule}; {self.feature})",
                           self.figure.source)


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


def _is_flexure(sp: ShopProfile) -> bool:
    return sp.web_thickness_mm is not None


def sheet_range(sp: ShopProfile) -> tuple[float, float, str, str]:
    """(thinnest, thickest, what, source) of the sheet ``sp``'s process takes for it (mm):
    a plain plate (a spacer) the process's cutting range; a flexure the range its
    stiffness model holds over (:meth:`~tactcad.vocabulary.process.CutProcess.flexure_sheet`)."""
    if not _is_flexure(sp):
        lo, hi = sp.cut.sheet_range_mm
        return lo, hi, "the process cuts", sp.cut.sheet_source
    lo, hi, source = sp.cut.flexure_sheet()
    return lo, hi, "a flexure it cuts takes", source


def _sheet_field(sp: ShopProfile) -> str:
    if _is_flexure(sp):
        return "sheet.thickness_mm"
    return "comb.spacer_process" if sp.part == COMB_SPACER_PART else "spacer.process"


def minimum_rules(sp: ShopProfile) -> list[MinimumRule]:
    """Every "at least" rule of ``sp``'s process on its nominal profile and sheet."""
    lim = sp.limits
    out = []
    holes = sp.profile.holes
    if holes:
        out.append(MinimumRule("process_min_hole", "smallest hole Ø",
                               min(2 * h.radius for h in holes), lim.min_hole_mm,
                               "clamp.bolt_size"))
        out.append(MinimumRule("process_min_web", "thinnest ligament at a hole",
                               narrowest_ligament_mm(sp), lim.min_web_mm, "clamp.bolt_size"))
    if _is_flexure(sp):
        out.append(MinimumRule("process_min_web", "flexure web", sp.web_thickness_mm,
                               lim.min_web_mm, "element.web_thickness_mm"))
    corners = inside_corners(sp.profile.outer)
    if corners:
        out.append(MinimumRule("process_inside_radius", "smallest inside radius",
                               min(r for _, r in corners), lim.min_inside_radius_mm,
                               "element.inside_corner_radius_mm"))
    slots = [2 * s.radius for s in sp.profile.outer
             if isinstance(s, Arc) and not s.ccw and abs(s.sweep) >= math.pi - 1e-9]
    if slots:
        out.append(MinimumRule("process_min_slot", "narrowest slot", min(slots),
                               lim.min_slot_mm, "element.notch_radius_mm"))
    return out


def tolerance_rule(sp: ShopProfile) -> MinimumRule | None:
    """The web's drawn tolerance against what the process holds (None: no web or no
    tolerance drawn)."""
    if not _is_flexure(sp) or sp.web_tolerance_mm is None:
        return None
    return MinimumRule("process_tolerance", "web's drawn tolerance +/-", sp.web_tolerance_mm,
                       sp.limits.tolerance_mm, "element.web_tolerance_mm")


def part_rule_checks(sp: ShopProfile) -> list[CheckResult]:
    """Every rule of ``sp``'s process on its nominal profile and sheet."""
    lo, hi, what, source = sheet_range(sp)
    t = sp.thickness_mm
    out = [CheckResult("process_sheet", sp.part, lo - SLACK_MM <= t <= hi + SLACK_MM,
                       f"{sp.process}: sheet {t:g} mm, {what} {lo:g}-{hi:g} mm ({source})")]
    out += [rule.result(sp) for rule in minimum_rules(sp)]
    tol = tolerance_rule(sp)
    if tol is not None:
        fig = tol.figure
        out.append(CheckResult(
            "process_tolerance", sp.part, tol.holds,
            f"{sp.process}: web drawn +/-{tol.value_mm:.3g} mm, the process holds "
            f"+/-{fig.value_mm:.3g} mm"
            + ("" if tol.holds else " (widen [tolerances] web_thickness_mm or choose a finer "
               "process)") + f"; rule: {fig.rule} ({fig.source})"))
    return out


def part_rule_errors(sp: ShopProfile) -> list[DesignError]:
    """The rules of ``sp``'s process it breaks, as refusals naming the design-file field
    that sets each feature, its value and the process's figure (empty: every rule holds)."""
    lo, hi, what, source = sheet_range(sp)
    t = sp.thickness_mm
    out = []
    if not lo - SLACK_MM <= t <= hi + SLACK_MM:
        out.append(DesignError(_sheet_field(sp), sp.process if not _is_flexure(sp) else t,
                               f"a sheet of {t:g} mm ({sp.part}) within what {sp.process} "
                               f"takes: {what} {lo:g}-{hi:g} mm", source))
    rules = minimum_rules(sp) + [r for r in (tolerance_rule(sp),) if r is not None]
    return out + [rule.error(sp) for rule in rules if not rule.holds]


def process_rule_errors(plan) -> list[DesignError]:
    """:func:`part_rule_errors` of every distinct part ``plan`` cuts from sheet: what a
    design must not be written with."""
    return [e for sp in shop_profiles(plan) for e in part_rule_errors(sp)]


def process_rule_checks(plan) -> list[CheckResult]:
    """:func:`part_rule_checks` of every distinct part ``plan`` cuts from sheet."""
    return [r for sp in shop_profiles(plan) for r in part_rule_checks(sp)]


def process_group(context: CheckContext) -> Iterator[Found]:
    """``process``: every cut part against its process's rules."""
    yield "process", process_rule_checks(context.plan)
