"""``tactcad crosstalk``: an array's sensitivity matrix, crosstalk and decoupling matrix (the
stacked array's clamped stack, a monolithic comb's row sheets), or a silicon die's."""

from __future__ import annotations

import argparse

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import keep_option_defaults
from tactcad.commands.tolerance import add_cluster_args
from tactcad.errors import DesignError
from tactcad.mechanics.crosstalk_ladder import (CROSSTALK_LEVELS, construction_levels,
                                                crosstalk_models, default_level)
from tactcad.products.silicon_die.mechanics.die_crosstalk import CROSSTALK_COST as DIE_COST
from tactcad.products.silicon_die.mechanics.die_crosstalk import CROSSTALK_LEVEL as DIE_LEVEL

#: The level of a stacked array's crosstalk when ``--model`` is left out.
ARRAY_DEFAULT = "stack-beam"
#: A monolithic comb's levels and the one when ``--model`` is left out.
COMB_LEVELS = construction_levels("monolithic-comb")
COMB_DEFAULT = default_level("monolithic-comb")


def register(sub: argparse._SubParsersAction) -> None:
    stack_levels = construction_levels("stacked")
    p = sub.add_parser(
        "crosstalk", help="crosstalk of an array (clamped stack or comb): n x n gauge "
                          "sensitivity, tip displacements, crosstalk_rel, decoupling matrix",
        description="A unit force on each tip: each gauge's grid-averaged strain (1/N), each "
                    "tip's displacement (mm/N; Maxwell-Betti symmetric), crosstalk_rel "
                    "(largest off-diagonal over its diagonal) and the decoupling matrix. A "
                    "stacked array: the stack of element bases and spacers (bonded by the bolt "
                    "preload) bending between the clamp plates; levels " + ", ".join(
                        f"{n} {CROSSTALK_LEVELS[n].cost}" for n in stack_levels)
                    + ". --sweep adds how plate thickness, bolt spacing and spacer grade change "
                    "crosstalk_rel (on Dask). A monolithic comb: each row's sheet, its spine "
                    "held at its dowel pins and under its screws' heads, carrying every "
                    "element; levels " + ", ".join(
                        f"{n} {CROSSTALK_LEVELS[n].cost}" for n in COMB_LEVELS)
                    + f" (default {COMB_DEFAULT}, a screen that errs high; comb-fem2d the "
                    "row's sheet as a plane-stress solid). A silicon die's design file: the "
                    f"die's crosstalk through its handle and die attach ({DIE_LEVEL}, 3D FE, "
                    f"{DIE_COST}).")
    add_design_arg(p)
    add_cache_args(p)
    # no default: a die's view tells a level asked from one left out
    p.add_argument("--model", choices=(*crosstalk_models(), DIE_LEVEL), default=None,
                   help=f"crosstalk level: for a stacked array's design one of "
                        f"{', '.join(stack_levels)} (default {ARRAY_DEFAULT}); for a "
                        f"monolithic comb's one of {', '.join(COMB_LEVELS)} (default "
                        f"{COMB_DEFAULT}); for a silicon die's design {DIE_LEVEL}, its only one "
                        f"({DIE_COST})")
    p.add_argument("--sweep", action="store_true",
                   help="also sweep plate thickness, bolt spacing and spacer grade (a stacked "
                        "array's)")
    add_cluster_args(p, local_default=False)
    add_output_args(p, "print one JSON object: the matrices, crosstalk_rel, cost and the sweep")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def run(args: argparse.Namespace) -> int:
    from tactcad.studies.project_reports import crosstalk_record

    shown = product_view("crosstalk", args)  # a silicon die's design: through its handle
    if shown is not None:
        return shown
    model = array_level(args.model)
    plan = plan_from_args(args)
    if args.sweep:
        check_sweep(plan)
    record, result = crosstalk_record(plan, model)
    rows = _sweep(plan, result.model, args) if args.sweep else None
    if args.json:
        print(dumps({**record, **({} if rows is None else {"sweep": rows})}, indent=1))
        return 0
    print(render(plan.name, result, rows, record["in_force"]))
    return 0


def array_level(model: str | None) -> str | None:
    """The crosstalk level of an array's design: ``--model`` as given, None when left out
    (the design's construction's cheapest level: :data:`ARRAY_DEFAULT` for the stacked
    array, :data:`COMB_DEFAULT` for a comb). A level of the other construction is refused
    once the plan is known (:func:`tactcad.mechanics.crosstalk_ladder.level_for`), before
    anything is solved.

    Args:
        model: ``--model``, or None.

    Returns:
        A level of the ladder, or None.

    Raises:
        DesignError: ``--model`` a silicon die's level, which an array has not.
    """
    if model is None:
        return None
    if model not in crosstalk_models():
        raise DesignError("--model", model, f"one of {', '.join(crosstalk_models())} for an "
                          f"array's design", f"{model} is a silicon die's crosstalk, through "
                          "its handle and die attach; an array's is its clamped stack's or its "
                          "comb sheets'")
    return model


def check_sweep(plan) -> None:
    """Refuse ``--sweep`` on an array other than the stacked one, before anything is solved.

    Raises:
        DesignError: ``--sweep`` on a comb (its sweep's inputs are a clamped stack's).
    """
    if plan.construction == "stacked":
        return
    raise DesignError("--sweep", True, f"left out for a {plan.construction} design",
                      "the sweep changes a clamped stack's plate thickness, bolt spacing and "
                      f"spacer grade, which a {plan.construction} design has not; change the "
                      "design with --set and run again, or leave --sweep out")


def _sweep(plan, model: str, args) -> list[dict]:
    from tactcad.studies.crosstalk_sweep import crosstalk_sweep, sweep_points

    points = sweep_points(plan, model)
    if args.scheduler is None and args.workers is None:
        return crosstalk_sweep(points)
    from tactcad.studies.sweeps import LOCAL_WORKERS, dask_client, dask_mapper

    with dask_client(args.scheduler, args.workers or LOCAL_WORKERS) as client:
        return crosstalk_sweep(points, dask_mapper(client, progress=False))


def render(design: str, r, rows, in_force: dict | None = None) -> str:
    """The result as text: the figures, the crosstalk in newtons against the force
    resolution, the sensitivity matrix in microstrain per newton, the sweep."""
    lines = [f"crosstalk of {design} ({r.model}, {r.seconds:.3g} s): crosstalk_rel "
             f"{r.crosstalk_rel:.3g} (gauge {r.worst[0]} under a force on element {r.worst[1]}), "
             f"error estimate {100 * r.error_estimate_rel:.2g} %"]
    if in_force is not None:
        q = in_force
        lines.append(f"  in force: element {q['loaded_element']} at the full-scale "
                     f"{q['full_scale_force_N']:.3g} N reads {q['crosstalk_force_N']:.3g} N on gauge "
                     f"{q['gauge']} ({q['force_per_N_of_neighbour_load']:.3g} N per N), "
                     f"{q['force_resolution_steps']:.3g} of its force-resolution step "
                     f"{q['force_resolution_N']:.3g} N")
    lines += [f"  tip-displacement matrix asymmetry {r.asymmetry_rel:.2g} (Maxwell-Betti)",
              f"  model: {r.basis}",
              "gauge strain per newton on each tip (microstrain/N):",
              "| gauge | " + " | ".join(str(e) for e in r.elements) + " |",
              "| --- |" + " --- |" * len(r.elements)]
    for e, row in zip(r.elements, r.sensitivity):
        lines.append(f"| {e} | " + " | ".join(f"{1e6 * v:.4g}" for v in row) + " |")
    if rows:
        lines += ["sweep (one input changed from the design's):",
                  "| parameter | value | crosstalk_rel | error |", "| --- | --- | --- | --- |"]
        lines += [f"| {q['parameter']} | {q['value']} | {q['crosstalk_rel']:.4g} | "
                  f"{100 * q['error_estimate_rel']:.2g} % |" for q in rows]
    return "\n".join(lines)
