"""The design's requirements as check results (the verification matrix at the closed form)."""

from __future__ import annotations

from typing import Iterator

from tactcad.checks.groups import CheckContext, Found
from tactcad.checks.check_result import CheckResult


def requirement_group(context: CheckContext) -> Iterator[Found]:
    """``requirements``: the verification matrix of the design at the closed form."""
    yield "requirements", requirement_checks(context.plan)


def requirement_checks(plan, model: str = "closed-form") -> list[CheckResult]:
    """One :class:`CheckResult` per requirement of ``plan`` (see
    :func:`tactcad.studies.verification.verification_matrix`): failed when
    its verdict is ``fail``; an ``undecided`` one (margin inside the level's
    error estimate) passes, marked undecided (``status``), with a note that
    ``tactcad verify`` decides it."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.verification import (GRID_POWER_REQUIREMENT, binding_text, margin_text,
                                              percent_text, value_text, verification_matrix)

    out = []
    for r in verification_matrix(plan, model, envelope_mm=array_envelope_mm(plan)):
        detail = (f"{r['verdict']}: target {value_text(r['target'])}, predicted "
                  f"{value_text(r['predicted'])}, margin {margin_text(r)} "
                  f"(error {percent_text(r['error_estimate_rel'], sign=False)}, {r['model']})")
        if binding_text(r):
            detail += f", binds: {binding_text(r)}"
        if r["requirement"] == GRID_POWER_REQUIREMENT and r["verdict"] != "pass":
            detail += f"; {r['basis']}"
        elif r["verdict"] == "undecided":
            detail += ("; no level computes it closer" if r["level_fixed"] else
                       "; tactcad verify --model auto decides it up the ladder")
        out.append(CheckResult("requirement", r["requirement"], r["verdict"] != "fail", detail,
                               undecided=r["verdict"] == "undecided"))
    return out
