"""``tactcad verify``: every requirement of the design against its prediction at a ladder level."""

from __future__ import annotations

import argparse

from tactcad.mechanics.ladder import levels_help, models
from tactcad.commands import add_design_arg, add_output_args, plan_from_args, progress_from_args
from tactcad.commands.finite_json import dumps



def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "verify", help="verification matrix: each requirement, its prediction, margin and pass",
        description="Evaluates every requirement of the design's [requirements] section (keys "
                    "the file leaves out are derived from the geometry, with the reason) at a "
                    "ladder level: full-scale force against every limit (yield / safety "
                    "factor, fatigue strength, gauge fatigue and maximum strain, notch travel) "
                    "with the one that binds, K_r/K_m, the K band over the web tolerance, the "
                    "K_obj resolution and the readable K_obj range. Exit 1 when a requirement "
                    "fails. Units: N, N/mm.")
    add_design_arg(p)
    p.add_argument("--model", choices=models(), default="closed-form",
                   help=f"ladder level ({levels_help()} per distinct element; default "
                        "%(default)s)")
    add_output_args(p, "print one JSON object: requirements and the matrix")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.studies.verification import matrix_passed, requirements_of, verification_matrix

    plan = plan_from_args(args)
    progress = progress_from_args(args)
    req = requirements_of(plan)
    from tactcad.studies.strength_studies import element_stress

    records = verification_matrix(plan, args.model, progress, req, stress=element_stress)
    ok = matrix_passed(records)
    if args.json:
        print(dumps({"design": plan.name, "model": args.model, "requirements": req.as_json(),
                     "matrix": records, "passed": ok}, indent=1))
    else:
        print(f"design {plan.name}, model {args.model}")
        print(matrix_table(records))
        for key, why in req.reasons.items():
            print(f"  {key}: {why}")
        print("all requirements met" if ok else "a requirement is not met")
    return 0 if ok else 1


def _value(v) -> str:
    if v is None:
        return "none"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(f"{x:.4g}" for x in v) + "]"
    return f"{v:.4g}"


def _pct(v) -> str:
    return "n/a" if v is None else f"{100 * v:+.1f} %"


def matrix_table(records: list[dict]) -> str:
    """The matrix as a Markdown table (one row per requirement; the limits
    of the full-scale force below it)."""
    rows = ["| requirement | target | predicted | error est. | margin | model | pass |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in records:
        err = "n/a" if r["error_estimate_rel"] is None else f"{100 * r['error_estimate_rel']:.2f} %"
        rows.append(f"| {r['requirement']} | {_value(r['target'])} | {_value(r['predicted'])} | "
                    f"{err} | {_pct(r['margin_rel'])} | {r['model']} | "
                    f"{'PASS' if r['pass'] else 'FAIL'} |")
    for r in records:
        for lim in r.get("limits", ()):
            rows.append(f"|   limit: {lim['words']} (element {lim['element']}) | | "
                        f"{lim['force_N']:.4g} N | {100 * lim['error_estimate_rel']:.2f} % | | | "
                        f"{'binds' if lim['binding'] else ''} |")
    return "\n".join(rows)
