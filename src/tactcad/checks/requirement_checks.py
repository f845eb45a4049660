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
    error estimate) passes with a note that ``tactcad verify`` decides it."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.verification import verification_matrix

    out = []
    for r in verification_matrix(plan, model, envelope_mm=array_envelope_mm(plan)):
        detail = (f"{r['verdict']}: target {_short(r['target'])}, predicted "
                  f"{_short(r['predicted'])}, margin {_pct(r['margin_rel'])} "
                  f"(error {_pct(r['error_estimate_rel'], sign=False)}, {r['model']})")
        if "binding_limit" in r:
            detail += f", bound by {r['binding_words']} (element {r['binding_element']})"
        if "measuring_element" in r:
            detail += (f", worst pair row {r['row']}: element {r['reference_element']} / "
                       f"{r['measuring_element']}")
        if "binding_axis" in r:
            detail += f", tightest along {r['binding_axis']}"
        if r["verdict"] == "undecided":
            detail += ("; no level computes it closer" if r["level_fixed"] else
                       "; tactcad verify --model auto decides it up the ladder")
        out.append(CheckResult("requirement", r["requirement"], r["verdict"] != "fail", detail))
    return out


def _pct(v, sign: bool = True) -> str:
    return "n/a" if v is None else (f"{100 * v:+.1f} %" if sign else f"{100 * v:.2f} %")


def _short(v):
    if isinstance(v, list):
        return "[" + ", ".join(f"{x:.4g}" for x in v) + "]"
    return "none" if v is None else f"{v:.4g}"
