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
    :func:`tactcad.mechanics.requirements.verification_matrix`)."""
    from tactcad.mechanics.requirements import verification_matrix

    out = []
    for r in verification_matrix(plan, model):
        detail = f"target {r['target']}, predicted {_short(r['predicted'])} ({r['model']})"
        if "binding_limit" in r:
            detail += f", bound by {r['binding_words']} (element {r['binding_element']})"
        out.append(CheckResult("requirement", r["requirement"], r["pass"], detail))
    return out


def _short(v):
    if isinstance(v, list):
        return "[" + ", ".join(f"{x:.4g}" for x in v) + "]"
    return "none" if v is None else f"{v:.4g}"
