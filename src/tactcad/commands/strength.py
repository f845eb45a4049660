"""``tactcad strength``: peak stress, full-scale force, gauge strain and tip
deflection at full scale of every element of a design.

Examples::

    tactcad strength
    tactcad strength --model fem2d --json
"""

from __future__ import annotations

import argparse
import json

from tactcad.commands import add_design_arg, add_output_args, plan_from_args, progress_from_args

MODELS = ("closed-form", "beam", "fem2d", "fem3d")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "strength", help="full-scale force of every element from yield, safety factor and the "
                         "peak stress at the flexure hinge",
        description="Peak von Mises stress per newton at the flexure hinge of every element, "
                    "the full-scale force = yield / (stress per N x safety factor), and the "
                    "gauge strain and tip deflection at full scale; warns where the paper's "
                    "2 N load exceeds yield, or full scale exceeds the fatigue strength or the "
                    "gauge's fatigue or maximum strain. Units: MPa, N, mm, microstrain.")
    p.add_argument("--model", choices=MODELS, default="closed-form",
                   help="ladder level (fem2d ~2 s, fem3d ~1 min per distinct element)")
    add_design_arg(p)
    add_output_args(p, "print a JSON list of records")
    p.add_argument("--table1", action="store_true",
                   help="compare the full-scale force with Table 1's max support force per "
                        "element (design web and as-built web)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.studies.strength import plan_strength

    plan = plan_from_args(args)
    if args.table1:
        return _run_table1(plan, args.model, args.json)
    report = progress_from_args(args)
    progress = (lambda s: report(f"  ... {s}"))
    records = plan_strength(plan, args.model, progress=progress)
    if args.json:
        print(json.dumps([r.as_json() for r in records], indent=2, allow_nan=False))
        return 0
    m, s = plan.material, plan.strength
    print(f"Strength, model {args.model}: {m.grade or m.name}, yield {m.yield_strength_MPa:g} MPa, "
          f"fatigue {_fmt_opt(m.fatigue_strength_MPa)} MPa, safety factor {s.safety_factor:g}, "
          f"gauge {s.gauge.name} (max {s.gauge.max_strain * 1e6:.0f}, fatigue "
          f"{s.gauge.fatigue_strain * 1e6:.0f} microstrain)")
    print(f"{'el':>3} {'arm mm':>6} {'MPa/N':>7} {'K_t':>5} {'F_fs N':>7} {'SF':>4} "
          f"{'ue at F_fs':>10} {'tip um':>7} {'MPa at 2 N':>10}")
    for r in records:
        print(f"{r.element:>3} {r.arm_length_mm:>6.1f} {r.stress_MPa_per_N:>7.1f} "
              f"{r.stress_concentration_factor:>5.3f} {r.full_scale_force_N:>7.3f} "
              f"{r.yield_safety_factor_at_full_scale:>4.2f} "
              f"{r.gauge_strain_at_full_scale * 1e6:>10.0f} "
              f"{r.tip_deflection_mm_at_full_scale * 1e3:>7.1f} {r.stress_MPa_at_paper_load:>10.0f}")
    seen = set()
    for r in records:
        for w in r.warnings:
            key = (r.part_name, w)
            if key not in seen:
                seen.add(key)
                print(f"warning: element {r.element} ({r.part_name}): {w}")
    return 0


def _run_table1(plan, model: str, as_json: bool) -> int:
    from tactcad.studies.strength import table1_force_comparison

    rows = table1_force_comparison(plan, model)
    if as_json:
        print(json.dumps(rows, indent=2, allow_nan=False))
        return 0
    print(f"Full-scale force ({model}, design web; closed form, as-built web) against Table 1's "
          f"max support force, safety factor {plan.strength.safety_factor:g}")
    print(f"{'el':>3} {'arm mm':>6} {'max support N':>13} {'F_fs N':>7} {'web as built':>12} "
          f"{'F_fs built N':>12} {'MPa at max':>10} {'SF at max':>9}")
    for r in rows:
        print(f"{r['element']:>3} {r['arm_length_mm']:>6.1f} {r['max_support_force_N']:>13.2f} "
              f"{r['full_scale_force_N']:>7.3f} {r['web_as_built_mm']:>12.3f} "
              f"{r['full_scale_force_as_built_N']:>12.3f} "
              f"{r['stress_MPa_at_max_support_force_as_built']:>10.0f} "
              f"{r['yield_safety_factor_at_max_support_force_as_built']:>9.2f}")
    return 0


def _fmt_opt(x: float | None) -> str:
    return "n/a" if x is None else f"{x:g}"
