"""``tactcad strength``: peak stress, yield-limited force, and the stress, gauge
strain and tip deflection at the design's rated full-scale force of every
element of a design.

Examples::

    tactcad strength
    tactcad strength --model closed-form
    tactcad strength --model fem2d --json
"""

from __future__ import annotations

import argparse
import json
import sys

from tactcad.design.requirements_section import cites_paper
from tactcad.mechanics.ladder import levels_help, models
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view, progress_from_args)
from tactcad.commands.options import keep_option_defaults
from tactcad.studies.project_reports import AUTO



def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "strength", help="every element's force limits and its stress, gauge strain and tip "
                         "deflection at the design's rated full-scale force",
        description="Peak von Mises stress per newton at the flexure hinge of every element, "
                    "its yield-limited force = yield / (stress per N x safety factor), and the "
                    "stress, gauge strain and tip deflection at the design's rated full-scale "
                    "force ([requirements] full_scale_force_N, derived when absent; the force "
                    "verify and the drawings name); judges that rating against every element "
                    "force limit as verify does (met, NOT met, or UNDECIDED when the margin "
                    "lies inside the level's error estimate) and exits 1 when it fails; "
                    "warns where the rated force exceeds an element's yield-limited force, "
                    "the fatigue strength or the gauge's fatigue or maximum strain. Units: "
                    "MPa, N, mm, microstrain.")
    p.add_argument("--model", choices=(AUTO, *models()), default="closed-form",
                   help=f"ladder level ({levels_help()} per distinct element; FEM stress "
                        "meshes are finer than the stiffness ones), or auto: the closed form, "
                        "and where it leaves the rated force undecided the level verify "
                        "--model auto decides it at, every distinct element then at that "
                        "level (fem3d: about 10 s an element; solves kept in and read back "
                        "from the result store); default %(default)s")
    add_design_arg(p)
    add_cache_args(p)
    add_output_args(p, "print one JSON object: the elements' records and the requirement's")
    p.add_argument("--table1", action="store_true",
                   help="the paper's design: compare each element's yield-limited force with "
                        "its measured max support force (design web and as-built web)")
    keep_option_defaults(p)  # a die's design: its view refuses an array's options
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    shown = product_view("strength", args)  # a silicon die's design: each row's beam root
    if shown is not None:
        return shown
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.project_reports import strength_auto, strength_record
    from tactcad.studies.reference_loads import reference_load_of

    plan = plan_from_args(args)
    if args.table1:
        if not cites_paper(plan.raw):
            from tactcad.errors import DesignError

            raise DesignError("--table1", True, "only for a design whose requirements.source "
                              "cites the measurements (the paper's design)")
        return _run_table1(plan, "closed-form" if args.model == AUTO else args.model, args.json)
    report = progress_from_args(args)
    progress = (lambda s: report(f"  ... {s}"))
    record, records = (strength_auto(plan, array_envelope_mm(plan), progress,
                                     notice=None if args.quiet else _say_climbing)
                       if args.model == AUTO else strength_record(plan, args.model, progress))
    judged = record["requirement"]
    code = 1 if judged["verdict"] == "fail" else 0  # as verify: an undecided rating exits 0
    if args.json:
        print(json.dumps(record, indent=2, allow_nan=False))
        return code
    m, s = plan.material, plan.strength
    print(f"Strength, model {model_words(args.model, judged)}: {m.grade or m.name}, yield {m.yield_strength_MPa:g} MPa, "
          f"fatigue {_fmt_opt(m.fatigue_strength_MPa)} MPa, safety factor {s.safety_factor:g}, "
          f"gauge {s.gauge.name} (max {s.gauge.max_strain * 1e6:.0f}, fatigue "
          f"{s.gauge.fatigue_strain * 1e6:.0f} microstrain)")
    load = reference_load_of(plan)  # the paper's study load: its design only
    print(f"rated full-scale force F_fs {judged['full_scale_force_N']:g} N; F_yield: the "
          f"force at yield / safety factor {s.safety_factor:g}; SF: yield over the web's "
          f"stress at F_fs (met when >= {s.safety_factor:g}); SF, ue, tip: at F_fs")
    print(f"{'el':>3} {'arm mm':>6} {'MPa/N':>7} {'K_t':>5} {'F_yield N':>9} {'SF':>5} "
          f"{'ue at F_fs':>10} {'tip um':>7}"
          + (f" {f'MPa at {load.force_N:g} N':>10}" if load else ""))
    for r in records:
        print(f"{r.element:>3} {r.arm_length_mm:>6.1f} {r.stress_MPa_per_N:>7.1f} "
              f"{r.stress_concentration_factor:>5.3f} {r.yield_limited_force_N:>9.3f} "
              f"{r.yield_safety_factor_at_full_scale:>5.2f} "
              f"{r.gauge_strain_at_full_scale * 1e6:>10.0f} "
              f"{r.tip_deflection_mm_at_full_scale * 1e3:>7.1f}"
              + (f" {r.stress_MPa_at_reference_load:>10.0f}" if load else ""))
    print(rating_text(judged))
    seen = set()
    for r in records:
        for w in r.warnings:
            key = (r.part_name, w)
            if key not in seen:
                seen.add(key)
                print(f"warning: element {r.element} ({r.part_name}): {w}")
    return code


def _say_climbing(line: str) -> None:
    """Print the line ``strength --model auto`` says before it climbs, on stderr (so
    ``--json`` stays one JSON document)."""
    print(f"tactcad: {line}", file=sys.stderr, flush=True)


def model_words(asked: str, judged: dict) -> str:
    """The level a report's figures are at: the one asked, or under ``auto`` the level that
    decided the rating (or, still undecided, the most accurate one tried).

    Args:
        asked: ``--model``. judged: the report's ``requirement`` record.

    Returns:
        A phrase: ``closed-form``, ``fem3d (auto: the closed form left the rated force
        undecided)``.
    """
    if asked != AUTO or judged["model"] == "closed-form":
        return judged["model"]
    return f"{judged['model']} (auto: the closed form left the rated force undecided)"


#: How ``strength`` words each verdict on the rated full-scale force.
RATING_WORDS = {"pass": "met", "fail": "NOT met", "undecided": "UNDECIDED"}


def rating_text(judged: dict) -> str:
    """The line judging the rated full-scale force: its verdict (verify's, with the margin and
    the binding limit's error estimate) and, when undecided, the level that can decide it.

    Args:
        judged: :func:`tactcad.studies.project_reports.full_scale_judgement`'s record (N,
            relative).

    Returns:
        One line.
    """
    line = (f"rated full-scale force {judged['full_scale_force_N']:g} N ({judged['reason']}): "
            f"{RATING_WORDS[judged['verdict']]}; the lowest element force limit is "
            f"{judged['element_force_limit_N']:.3g} N, bound by {judged['binding_limit']} "
            f"(element {judged['binding_element']}), margin {100 * judged['margin_rel']:+.1f} % "
            f"(error {100 * judged['element_force_limit_error_rel']:.2f} %, {judged['model']})")
    if judged["verdict"] != "undecided":
        return line
    # under auto, the ladder was climbed: the hint is the highest level tried's
    tried = judged.get("levels_tried") or [judged["model"]]
    return f"{line}: the margin lies inside the error; {climb_hint(tried[-1])}"


def climb_hint(model: str) -> str:
    """What decides a rating undecided at ``model``: a more accurate ladder level, or, at the
    top, a larger margin.

    Args:
        model: the ladder level that left it undecided.

    Returns:
        A phrase.
    """
    order = list(models())
    above = order[order.index(model) + 1:] if model in order else []
    if not above:
        return (f"{model} is the ladder's top level: widen the margin (a lower rating, a "
                "stronger element) or measure the element")
    if model == "closed-form":
        return ("a more accurate level decides it: tactcad strength --model auto (as verify "
                f"climbs) or --model {above[-1]}")
    return f"a more accurate level decides it: tactcad strength --model {above[-1]}"


def _run_table1(plan, model: str, as_json: bool) -> int:
    from tactcad.paper.table1 import table1_force_comparison

    rows = table1_force_comparison(plan, model)
    if as_json:
        print(json.dumps(rows, indent=2, allow_nan=False))
        return 0
    print(f"Yield-limited force ({model}, design web; closed form, as-built web) against "
          f"Table 1's max support force, safety factor {plan.strength.safety_factor:g}")
    print(f"{'el':>3} {'arm mm':>6} {'max support N':>13} {'F_yield N':>9} {'web as built':>12} "
          f"{'F_yield built N':>15} {'MPa at max':>10} {'SF at max':>9}")
    for r in rows:
        print(f"{r['element']:>3} {r['arm_length_mm']:>6.1f} {r['max_support_force_N']:>13.2f} "
              f"{r['yield_limited_force_N']:>9.3f} {r['web_as_built_mm']:>12.3f} "
              f"{r['yield_limited_force_as_built_N']:>15.3f} "
              f"{r['stress_MPa_at_max_support_force_as_built']:>10.0f} "
              f"{r['yield_safety_factor_at_max_support_force_as_built']:>9.2f}")
    return 0


def _fmt_opt(x: float | None) -> str:
    return "n/a" if x is None else f"{x:g}"
