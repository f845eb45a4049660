"""``tactcad verify``: every requirement of the design against its prediction at a ladder level."""

from __future__ import annotations

import argparse

from tactcad.mechanics.ladder import levels_help, models
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view, progress_from_args)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import keep_option_defaults



def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "verify", help="verification matrix: each requirement, its prediction, margin and pass",
        description="Evaluates every requirement of the design's [requirements] section (keys "
                    "the file leaves out are derived from the geometry, with the reason) at a "
                    "ladder level: full-scale force against every limit (yield / safety "
                    "factor, fatigue strength, gauge fatigue and maximum strain, notch travel) "
                    "with the one that binds, K_r/K_m, the K band over the web tolerance, the "
                    "K_obj resolution and the readable K_obj range. Each verdict is pass, "
                    "fail or undecided (the margin lies inside the level's error estimate); "
                    "--model auto (the default) starts at the closed form and climbs the "
                    "ladder only while a requirement is undecided, naming the level that "
                    "decided each and the seconds spent. Exit 1 when a requirement fails. "
                    "Units: N, N/mm, s.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--model", choices=("auto", *models()), default="auto",
                   help=f"ladder level ({levels_help()} per distinct element), or auto: the "
                        "cheapest level that decides each requirement (default %(default)s)")
    add_output_args(p, "print one JSON object: requirements and the matrix")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def run(args: argparse.Namespace) -> int:
    shown = product_view("verify", args)  # a silicon die's design: its own matrix
    if shown is not None:
        return shown
    from tactcad.studies.verification import (GRID_POWER_REQUIREMENT, matrix_passed, matrix_table,
                                                prefetch_top_level, requirements_of,
                                                undecided, verification_auto,
                                                verification_matrix)
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.vocabulary.schema import stale_reasons
    from tactcad.studies.strength_studies import element_stress

    plan = plan_from_args(args)
    progress = progress_from_args(args)
    req = requirements_of(plan)
    envelope = array_envelope_mm(plan)
    if args.model == "auto":
        records, levels = verification_auto(plan, progress, req, stress=element_stress,
                                            envelope_mm=envelope)
    else:
        prefetch_top_level(plan, args.model, progress, peak_stress=True)
        records, levels = verification_matrix(plan, args.model, progress, req,
                                              stress=element_stress, envelope_mm=envelope), []
    ok = matrix_passed(records)
    open_ = undecided(records)
    budget = kobj_budget_section(plan, req, args.model)
    from tactcad.studies.verification import tissue_coupling_record

    tissue = tissue_coupling_record(plan, req)
    if args.json:
        print(dumps({"design": plan.name, "model": args.model, "requirements": req.as_json(),
                     "matrix": records, "levels": levels, "undecided": open_, "passed": ok,
                     "kobj_budget": budget if isinstance(budget, str) else budget.as_json(),
                     "tissue_coupling": tissue}, indent=1))
    else:
        print(f"design {plan.name}, model {args.model}")
        print(matrix_table(records))
        for key, why in req.reasons.items():
            print(f"  {key}: {why}")
        for key, why in stale_reasons(plan.raw).items():  # edited since design wrote them
            print(f"note: [assumptions] {key}: {why}")
        for note in dict.fromkeys(r["note"] for r in records if r.get("note")):
            print(f"note: {note}")
        for level in levels:
            print(f"  {level['model']}: {level['seconds']:.2f} s")
        print(tissue_text(tissue))
        grasp = next((r for r in records if r["requirement"] == "max_grasp_force_N"), None)
        if grasp:
            print(grasp_text(grasp))
        power = next(r for r in records if r["requirement"] == GRID_POWER_REQUIREMENT)
        if power["verdict"] != "pass":
            print(f"gauge excitation: {power['verdict'].upper()}: {power['basis']}")
        by_margin = [k for k in open_ if k != GRID_POWER_REQUIREMENT]
        if by_margin:
            top = records[0].get("levels_tried", [args.model])[-1]
            print(f"undecided at {top} (margin inside its error estimate): {', '.join(by_margin)}"
                  + ("" if args.model == "auto" else "; --model auto climbs the ladder"))
        for r in records:
            if r["verdict"] == "undecided" and r.get("less_accurate_levels"):
                print(less_accurate_text(r))
        from tactcad.commands.budget import render_array

        print(f"K_obj error budget not evaluated: {budget}" if isinstance(budget, str)
              else "\n".join(render_array(budget)))
        print("no requirement fails" if ok else "a requirement is not met")
    return 0 if ok else 1


def less_accurate_text(record: dict) -> str:
    """An undecided row's levels: the one shown (the most accurate, the smallest error
    estimate) and each other level tried with its verdict, margin and error estimate.

    Args:
        record: a verification record of ``verify --model auto`` with
            ``less_accurate_levels`` (margins and errors relative).

    Returns:
        One line, e.g. ``kobj_accuracy_rel: undecided; shown at closed-form, the most
        accurate level (error 4.50 %); less accurate: fem2d FAIL (margin -100.0 %,
        error 9.70 %)``.
    """
    from tactcad.studies.verification import percent_text

    others = ", ".join(f"{b['model']} {b['verdict'].upper()} (margin "
                       f"{percent_text(b['margin_rel'])}, error "
                       f"{percent_text(b['error_estimate_rel'], sign=False)})"
                       for b in record["less_accurate_levels"])
    return (f"  {record['requirement']}: undecided; shown at {record['model']}, the most "
            f"accurate level (error {percent_text(record['error_estimate_rel'], sign=False)})"
            f"; less accurate: {others}")


def kobj_budget_section(plan, req, model: str):
    """The design's K_obj error budget for verify's output (reported; judged only through
    ``kobj_accuracy_rel``): at ``model``, the closed form for ``auto``; the refusal's text
    when a source cannot be evaluated (a material of unknown CTE)."""
    from tactcad.errors import DesignError
    from tactcad.in_use.kobj_budget import DEFAULT_DELTA_T_K, kobj_budget
    from tactcad.studies.verification import calibration_gauge

    try:
        return kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                           DEFAULT_DELTA_T_K, "closed-form" if model == "auto" else model,
                           force_gauge=calibration_gauge(plan),
                           readable_within_rel=req.kobj_resolution_rel)
    except DesignError as exc:
        return str(exc)


def grasp_text(record: dict) -> str:
    """The grasp at the maximum grasp force: the jaw and tissue assumed, the elements beyond
    their overload limit with force and limit, those past their fatigue limit (each grasp a
    cycle beyond it, not judged by the overload verdict) and those past the rated force (on
    a stop or not)."""
    over = "; ".join(record.get("over_limit") or []) or "every element within its overload limit"
    fatigue = "; ".join(record.get("fatigue_at_max_grasp") or [])
    past = "; ".join(record.get("past_rating") or [])
    return (f"grasp at {record['target']:g} N: {record['verdict'].upper()}: {over}"
            + (f"; past a fatigue limit at every such grasp: {fatigue}" if fatigue else "")
            + (f"; past the rated force: {past}" if past else "") + f" ({record['basis']})")


#: How each reading of the tissue-coupling record is named, and what its verdict means
#: (not a requirement of the matrix: how K_obj must be read).
TISSUE_READINGS = (("eq3", "eq. 3 alone", {"pass": "may be read so", "fail": "must not be read "
                                           "so", "undecided": "within its error of the limit"}),
                   ("coupled", "the coupled inversion (eq. 3 corrected)",
                    {"pass": "reads within it", "fail": "reads outside it",
                     "undecided": "within its error of the limit"}))


def tissue_text(record: dict) -> str:
    """The tissue coupling's K_obj bias, worst unit (reference/measuring), by eq. 3 and by
    the coupled inversion, each with what its verdict means for the reading."""
    from tactcad.in_use.tissue_coupling import unit_label, worst_unit

    if not record["units"]:
        return "tissue coupling: no sensing unit"
    parts = []
    for key, words, meaning in TISSUE_READINGS:
        worst = worst_unit(record[key]["items"], lambda it: it["bias_rel"])
        bias = "no answer" if worst["bias_rel"] is None else f"{100 * worst['bias_rel']:+.3g} %"
        verdict = record[key]["verdict"]
        parts.append(f"{words} worst {bias} (unit {unit_label(worst['unit'])}): "
                     f"{meaning.get(verdict, verdict)}")
    return (f"tissue coupling ({record['tissue']}), K_obj bias over the range against the "
            f"{100 * record['target_rel']:.3g} % resolution (how K_obj must be read, not a "
            f"requirement): " + "; ".join(parts)
            + (f"; the coupled inversion checked on {record['check_level']}"
               if record.get("check_level") else ""))


