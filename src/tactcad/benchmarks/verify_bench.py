"""``tactcad bench verify``: the speed-for-accuracy trade of ``verify --model
auto`` measured on a design. Each ladder level's whole matrix is timed, then
``auto``; the figures say what ``auto`` spent, which level decided each
requirement, and whether its verdicts are the top level's.

Units: s.
"""

from __future__ import annotations

import time
from typing import Sequence

from tactcad.design.array_plan import Plan


def verify_trade(plan: Plan, envelope_mm: Sequence[float] | None, stress,
                 levels: Sequence[str]) -> dict:
    """Seconds and verdicts of each level's matrix and of ``auto`` climbing ``levels``.

    Args:
        plan: the design.
        envelope_mm: the array's envelope (mm), for a stated footprint.
        stress: the FEM levels' stress (``tactcad.studies.strength_studies.element_stress``).
        levels: the ladder, cheapest first; the last is the reference.

    Returns:
        ``{"levels": [{"model", "seconds", "verdicts"}], "auto": {"seconds",
        "verdicts", "decided_by", "levels"}, "compared_with": the top level,
        "conflicting_verdicts": [requirement, ...] (pass on one side, fail on the
        other), "agree": bool}``.
    """
    from tactcad.studies.verification import (requirements_of, verification_auto,
                                              verification_matrix)

    req = requirements_of(plan)
    rows = []
    for level in levels:
        t0 = time.perf_counter()
        records = verification_matrix(plan, level, None, req, stress, envelope_mm)
        rows.append({"model": level, "seconds": time.perf_counter() - t0,
                     "verdicts": {r["requirement"]: r["verdict"] for r in records}})
    t0 = time.perf_counter()
    records, spent = verification_auto(plan, None, req, stress, tuple(levels), envelope_mm)
    auto = {"seconds": time.perf_counter() - t0,
            "verdicts": {r["requirement"]: r["verdict"] for r in records},
            "decided_by": {r["requirement"]: r["decided_by"] for r in records},
            "levels": spent}
    top = rows[-1]
    # a verdict one side decided and the other decided the other way (undecided agrees)
    conflicts = sorted(k for k, v in auto["verdicts"].items()
                       if {v, top["verdicts"].get(k)} == {"pass", "fail"})
    return {"design": plan.name, "levels": rows, "auto": auto, "compared_with": top["model"],
            "conflicting_verdicts": conflicts, "agree": not conflicts}


def trade_table(report: dict) -> str:
    """The figures as text: one line per level and one for ``auto``."""
    lines = [f"tactcad bench verify: {report['design']}"]
    for row in report["levels"]:
        verdicts = ", ".join(f"{k} {v}" for k, v in row["verdicts"].items() if v not in ("pass", "info"))
        lines.append(f"  {row['model']:<12} {row['seconds']:8.2f} s   "
                     f"{verdicts or 'every requirement pass'}")
    auto = report["auto"]
    decided = ", ".join(f"{k} at {v or 'no level'}" for k, v in auto["decided_by"].items())
    lines.append(f"  {'auto':<12} {auto['seconds']:8.2f} s   decided: {decided}")
    lines.append(f"  auto and {report['compared_with']} agree on every decided verdict: "
                 + ("yes" if report["agree"] else
                    "no (" + ", ".join(report["conflicting_verdicts"]) + ")"))
    return "\n".join(lines)
