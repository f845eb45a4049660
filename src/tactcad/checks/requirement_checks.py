"""The design's requirements as check results: the verification matrix with the verdicts
``tactcad verify`` gives by default (:func:`tactcad.studies.verification.verification_auto`:
the closed form, and a higher ladder level only for a requirement it leaves undecided), so
``check`` fails where ``verify`` fails. The solves are kept in the result store
(:func:`tactcad.store.kept_result`): a check after a verify (or the other way round) with
the same store solves nothing again."""

from __future__ import annotations

from typing import Iterator

from tactcad.checks.groups import CheckContext, Found
from tactcad.checks.check_result import CheckResult

#: ``model`` of :func:`requirement_checks` that climbs the ladder as ``verify`` does.
AUTO = "auto"


def requirement_group(context: CheckContext) -> Iterator[Found]:
    """``requirements``: the verification matrix of the design at ``context.requirements_model``
    (default ``auto``, verify's own verdicts)."""
    yield "requirements", requirement_checks(context.plan, context.requirements_model)


def requirement_records(plan, model: str = AUTO) -> list[dict]:
    """The verification records of ``plan`` at ``model``.

    Args:
        plan: the validated design.
        model: ``auto`` (verify's default: each requirement at the cheapest level that
            decides it, FEM levels solved only for one the closed form leaves undecided)
            or a ladder level (every requirement at that level).

    Returns:
        One record per requirement, as :func:`tactcad.studies.verification.verification_matrix`
        makes them (with ``decided_by`` and ``levels_tried`` under ``auto``).

    Raises:
        UnknownModelError: ``model`` is neither ``auto`` nor a ladder level.
        DesignError: the material has no yield strength.
    """
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.strength_studies import element_stress
    from tactcad.studies.verification import (requirements_of, verification_auto,
                                              verification_matrix)

    envelope = array_envelope_mm(plan)
    if model != AUTO:
        return verification_matrix(plan, model, envelope_mm=envelope,
                                   stress=None if model == "closed-form" else element_stress)
    records, _ = verification_auto(plan, None, requirements_of(plan), stress=element_stress,
                                   envelope_mm=envelope)
    return records


def requirement_checks(plan, model: str = AUTO) -> list[CheckResult]:
    """One :class:`CheckResult` per requirement of ``plan`` (see
    :func:`requirement_records`, each as :func:`requirement_check` makes it).

    Args:
        plan: the validated design.
        model: ``auto`` (default, the verdicts ``tactcad verify`` gives) or a ladder level.

    Returns:
        The results in the matrix's order.
    """
    return [requirement_check(r, model) for r in requirement_records(plan, model)]


def requirement_check(r: dict, model: str = AUTO) -> CheckResult:
    """One verification record (an array's or a die's) as a check result: failed when its
    verdict is ``fail``; an ``undecided`` one (margin inside the error estimate of the highest
    level that computes it) passes, marked undecided; an ``info`` one (a row reported, not
    judged: :func:`tactcad.mechanics.verdicts.reported_not_judged`) is marked info, neither
    failed nor counted as passed, without a target or a margin (``status``).

    Args:
        r: the record (``requirement``, ``verdict``, ``target``, ``predicted``, ...).
        model: the level asked (``auto`` or a ladder level), for an undecided one's words.

    Returns:
        The :class:`CheckResult` (check ``requirement``, subject the requirement's name).
    """
    from tactcad.mechanics.verdicts import INFO
    from tactcad.studies.verification import (GRID_POWER_REQUIREMENT, binding_text, margin_text,
                                              percent_text, predicted_text, value_text)

    if r["verdict"] == INFO:  # the design's own figure (a requirement the lab never stated)
        detail = (f"info: not stated, not judged: predicted {value_text(r['predicted'])} "
                  f"(error {percent_text(r['error_estimate_rel'], sign=False)}, "
                  f"{r['model']})" + (f"; {r['note']}" if r.get("note") else ""))
        return CheckResult("requirement", r["requirement"], True, detail, info=True)
    detail = (f"{r['verdict']}: target {value_text(r['target'])}, predicted "
              f"{predicted_text(r)}, margin {margin_text(r)} "
              f"(error {percent_text(r['error_estimate_rel'], sign=False)}, {r['model']})")
    if binding_text(r):
        detail += f", binds: {binding_text(r)}"
    if r["requirement"] == GRID_POWER_REQUIREMENT and r["verdict"] != "pass":
        detail += f"; {r['basis']}"
    elif r["verdict"] == "undecided":
        detail += "; " + _undecided_words(r, model)
    return CheckResult("requirement", r["requirement"], r["verdict"] != "fail", detail,
                       undecided=r["verdict"] == "undecided")


def _undecided_words(record: dict, model: str) -> str:
    """Why an undecided requirement stays so: no level computes it closer, the ladder's
    highest level tried left it inside its error, or (one level asked) verify climbs."""
    if record["level_fixed"]:
        return "no level computes it closer"
    if model == AUTO:
        return f"undecided up to the ladder's top ({record['levels_tried'][-1]})"
    return "tactcad verify --model auto decides it up the ladder"
