"""Each element's hard stop as check results: it engages after the rated
deflection and before yield (:mod:`tactcad.mechanics.hard_stops`)."""

from __future__ import annotations

from typing import Iterator

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found


def stop_group(context: CheckContext) -> Iterator[Found]:
    """``hard stops``: one result per element of a construction that gives
    its elements stops (nothing for one that gives none)."""
    results = stop_checks(context.plan)
    if results:
        yield "hard stops", results


def stop_checks(plan) -> list[CheckResult]:
    """One :class:`CheckResult` per hard stop of ``plan``, at the design's
    rated full-scale force (``[requirements]`` or derived) and the closed form:
    failed when the stop engages at or below the rated deflection or at or
    beyond the yield-limited one; the detail names the values and whether the stop engages
    below the element's fatigue limits (past them, it says which binds)."""
    if not plan.hard_stops:
        return []
    from tactcad.mechanics.hard_stops import stop_verdicts
    from tactcad.studies.verification import requirements_of

    force = requirements_of(plan).full_scale_force_N
    out = []
    for v in stop_verdicts(plan, force):
        how = ("cut in the sheet" if v.kind == "cut" else
               f"set with a shim in the {v.cut_mm:.3f} mm slot the wire cuts (narrower than it)")
        fatigue = "" if not v.fatigue_limit else (
            f"; {v.engage_force_N:.4g} N on the element, "
            + ("below" if v.below_fatigue else "past (binds: overloads it stops cycle the "
               "element beyond)") + f" its {v.fatigue_limit} limit "
            f"{v.fatigue_tip_mm * v.stiffness_N_per_mm:.4g} N")
        detail = (f"engages at {v.engage_tip_mm:.4f} mm tip travel = {v.multiple_of_rated:.2f} x the "
                  f"rated {v.rated_tip_mm:.4f} mm ({force:g} N at K {v.stiffness_N_per_mm:.3g} N/mm), "
                  f"yield-limited {v.yield_tip_mm:.4f} mm; gap {v.gap_mm:.3f} mm {how}{fatigue}")
        out.append(CheckResult("hard stop", f"element {v.element}", v.engages_between, detail))
    return out
