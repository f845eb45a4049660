"""``tactcad bench crosstalk``: cost and error of each crosstalk level on a design.

Per level of :data:`tactcad.mechanics.stack_crosstalk.CROSSTALK_LEVELS`: the
wall time of the plan's stack inputs (the elements' own K and gauge strain,
once), the best of ``REPEATS`` solves (s), crosstalk_rel, the level's own
error estimate, its distance to the last level and the tip matrix's
asymmetry. Prints figures; sets no goal. Units: s.
"""

from __future__ import annotations

import json
import time

from tactcad.design.array_plan import Plan
from tactcad.mechanics.stack_crosstalk import crosstalk_models, estimate_crosstalk, stack_inputs

REPEATS = 5


def measure(plan: Plan) -> dict:
    """``{"inputs_s", "levels": [{model, solve_s, crosstalk_rel, error_estimate_rel,
    vs_last_level_rel, asymmetry_rel}]}`` for ``plan``."""
    t0 = time.perf_counter()
    inputs = stack_inputs(plan)
    inputs_s = time.perf_counter() - t0
    rows = []
    for model in crosstalk_models():
        best, result = float("inf"), None
        for _ in range(1 if model == "stack-fem3d" else REPEATS):
            result = estimate_crosstalk(inputs, model)
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
          f"stack inputs (own K and gauge strain) {figures['inputs_s']:.3g} s, once")
    print("| level | solve s (best of 5; fem3d once) | crosstalk_rel | error estimate | vs last level | "
          "asymmetry |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in figures["levels"]:
        print(f"| {r['model']} | {r['solve_s']:.3g} | {r['crosstalk_rel']:.4g} | "
              f"{100 * r['error_estimate_rel']:.3g} % | {100 * r['vs_last_level_rel']:.2g} % | "
              f"{r['asymmetry_rel']:.2g} |")
    return 0
