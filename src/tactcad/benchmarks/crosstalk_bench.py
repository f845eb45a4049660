"""``tactcad bench crosstalk``: cost and error of each crosstalk level on a design.

Per level of :data:`tactcad.mechanics.crosstalk_ladder.CROSSTALK_LEVELS` that describes the
design's construction (the stacked array's ``stack-*``, a monolithic comb's ``comb-*``):
the wall time of the plan's inputs (the elements' own K and gauge strain, once), the best
of ``REPEATS`` solves (s; a meshed level once), crosstalk_rel, the level's own error
estimate, its distance to the last level and the tip matrix's asymmetry. Prints figures;
sets no goal. Units: s.
"""

from __future__ import annotations

import json
import time

from tactcad.design.array_plan import Plan
from tactcad.mechanics.crosstalk_ladder import (CROSSTALK_LADDER, CROSSTALK_LEVELS,
                                                construction_levels, level_for)

REPEATS = 5


def measure(plan: Plan) -> dict:
    """``{"inputs_s", "levels": [{model, solve_s, crosstalk_rel, error_estimate_rel,
    vs_last_level_rel, asymmetry_rel}]}`` for ``plan``."""
    levels = construction_levels(plan.construction)
    t0 = time.perf_counter()
    inputs = level_for(plan).read_inputs(plan)  # refuses a construction no level describes
    inputs_s = time.perf_counter() - t0
    rows = []
    for model in levels:
        best, result = float("inf"), None
        for _ in range(1 if CROSSTALK_LEVELS[model].meshed else REPEATS):
            # never from the result store: the bench times the solve
            result = CROSSTALK_LADDER.run(model, (inputs,), {}, label=plan.construction,
                                          keep=False)
            best = min(best, result.seconds)
        rows.append({"model": model, "solve_s": best, "crosstalk_rel": result.crosstalk_rel,
                     "error_estimate_rel": result.error_estimate_rel,
                     "asymmetry_rel": result.asymmetry_rel,
                     "elements": len(result.elements)})
    last = rows[-1]["crosstalk_rel"]
    for r in rows:
        r["vs_last_level_rel"] = abs(r["crosstalk_rel"] / last - 1.0) if last else 0.0
    return {"design": plan.name, "inputs_s": inputs_s, "levels": rows}


def main(args, plan: Plan) -> int:
    """Entry point of ``tactcad bench crosstalk``."""
    figures = measure(plan)
    if getattr(args, "json", False):
        print(json.dumps(figures, indent=1, allow_nan=False))
        return 0
    print(f"crosstalk levels on {figures['design']} ({figures['levels'][0]['elements']} elements); "
          f"inputs (own K and gauge strain) {figures['inputs_s']:.3g} s, once")
    print(f"| level | solve s (best of {REPEATS}; a meshed level once) | crosstalk_rel | "
          "error estimate | vs last level | asymmetry |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in figures["levels"]:
        print(f"| {r['model']} | {r['solve_s']:.3g} | {r['crosstalk_rel']:.4g} | "
              f"{100 * r['error_estimate_rel']:.3g} % | {100 * r['vs_last_level_rel']:.2g} % | "
              f"{r['asymmetry_rel']:.2g} |")
    return 0
