"""``tactcad crosstalk``: the clamped array's sensitivity matrix, crosstalk and decoupling matrix."""

from __future__ import annotations

import argparse

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import keep_option_defaults
from tactcad.commands.tolerance import add_cluster_args
from tactcad.errors import DesignError
from tactcad.mechanics.stack_crosstalk import CROSSTALK_LEVELS, crosstalk_models
from tactcad.products.silicon_die.mechanics.die_crosstalk import CROSSTALK_COST as DIE_COST
from tactcad.products.silicon_die.mechanics.die_crosstalk import CROSSTALK_LEVEL as DIE_LEVEL

#: The level of an array's crosstalk when ``--model`` is left out.
ARRAY_DEFAULT = "stack-beam"


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "crosstalk", help="crosstalk of the clamped array: n x n gauge sensitivity, tip "
                          "displacements, crosstalk_rel, decoupling matrix",
        description="A unit force on each tip, the stack of element bases and spacers (bonded "
                    "by the bolt preload) bending between the clamp plates: each gauge's "
                    "grid-averaged strain (1/N), each tip's displacement (mm/N; Maxwell-Betti "
                    "symmetric), crosstalk_rel (largest off-diagonal over its diagonal) and the "
                    "decoupling matrix. Levels: " + ", ".join(
                        f"{n} {lv.cost}" for n, lv in CROSSTALK_LEVELS.items())
                    + ". --sweep adds how plate thickness, bolt spacing and spacer grade change "
                    "crosstalk_rel (on Dask). A silicon die's design file: the die's crosstalk "
                    f"through its handle and die attach ({DIE_LEVEL}, 3D FE, {DIE_COST}).")
    add_design_arg(p)
    add_cache_args(p)
    # no default: a die's view tells a level asked from one left out
    p.add_argument("--model", choices=(*crosstalk_models(), DIE_LEVEL), default=None,
                   help=f"crosstalk level: for an array's design one of "
                        f"{', '.join(crosstalk_models())} (default {ARRAY_DEFAULT}); for a "
                        f"silicon die's design {DIE_LEVEL}, its only one ({DIE_COST})")
    p.add_argument("--sweep", action="store_true",
                   help="also sweep plate thickness, bolt spacing and spacer grade")
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
    record, result = crosstalk_record(plan, model)
    rows = _sweep(plan, model, args) if args.sweep else None
    if args.json:
        print(dumps({**record, **({} if rows is None else {"sweep": rows})}, indent=1))
        return 0
    print(render(plan.name, result, rows, record["in_force"]))
    return 0


def array_level(model: str | None) -> str:
    """The crosstalk level of an array's design: ``--model`` as given, :data:`ARRAY_DEFAULT`
    when left out.

    Args:
        model: ``--model``, or None.

    Returns:
        A level of the stack's ladder.

    Raises:
        DesignError: ``--model`` a silicon die's level, which an array's stack has not.
    """
    if model is None:
        return ARRAY_DEFAULT
    if model not in crosstalk_models():
        raise DesignError("--model", model, f"one of {', '.join(crosstalk_models())} for an "
                          f"array's design", f"{model} is a silicon die's crosstalk, through "
                          "its handle and die attach; an array's is its clamped stack's")
    return model


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
