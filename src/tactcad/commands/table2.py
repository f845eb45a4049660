"""``tactcad table2``: every model of paper Table 2 scored against the 48 measured R.

Examples::

    tactcad table2
    tactcad table2 --json
    tactcad table2 --plot docs/images/table2_models.png
"""

from __future__ import annotations

import argparse

from tactcad.mechanics.ladder import models


def register(subparsers) -> None:
    """Add the ``table2`` sub-command."""
    from tactcad.commands import add_cache_args, add_design_arg, add_output_args
    from tactcad.commands.options import PLOT_SUFFIXES, output_file

    p = subparsers.add_parser(
        "table2", help="each model's error against the paper's 48 measured R (Table 2)",
        description="Eq. 2 with Table 1's K, the coupled half-space rig, and one-parameter "
                    "models (effective reference stiffness, reference gain, sample scale, layer "
                    "thickness) scored on held-out rows only: leave-one-sample-out and "
                    "leave-one-element-out. Relative error |R_pred - R_meas|/R_meas.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for element 5 (no Table 1 entry) in the coupled models "
                        "(default %(default)s)")
    p.add_argument("--plot", metavar="PNG", type=output_file(*PLOT_SUFFIXES), default=None,
                   help="write measured R with eq. 2 and the held-out fitted-K_r model here")
    add_output_args(p, "print one JSON object")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Handler of ``tactcad table2``; returns the exit code."""
    from tactcad.commands import plan_from_args
    from tactcad.paper.table2_models import table2_report
    from tactcad.commands.finite_json import dumps

    from tactcad.paper.table1 import require_table1

    plan = plan_from_args(args)
    # the paper's measurements: the paper's design, or a refusal saying why
    require_table1(plan, command="table2")
    report = table2_report(plan, args.model)
    if args.plot:
        report["plot"] = str(write_plot(report, args.plot))
    if args.json:
        print(dumps(report))
        return 0
    print(f"Table 2: {report['rows']} measured R, K_r = {report['k_r_N_per_mm']} N/mm; "
          f"{report['measured_r_below_one']} rows read R < 1")
    print(f"{'model':34s} {'scheme':24s} {'median':>7s} {'max':>7s}  held-out  fitted")
    for m in report["models"]:
        fitted = ", ".join(f"{k} = {v:.4g}" for k, v in m["fitted_parameters"].items()) or "-"
        print(f"{m['name']:34s} {m['scheme']:24s} {m['median_rel_error']:7.3f} "
              f"{m['max_rel_error']:7.3f}  {str(m['held_out']):8s}  {fitted}")
    for m in report["skipped_models"]:
        print(f"skipped {m['name']}: {m['reason']}")
    if "plot" in report:
        print(f"plot: {report['plot']}")
    return 0


def write_plot(report: dict, path: str):
    """Measured R (markers), eq. 2 (solid) and eq. 2 with K_r fitted on the other samples (dashed)."""
    from tactcad.paper.figures import plot_ratio_map

    rows = report["table2"]
    by_name = {(m["name"], m["scheme"]): m for m in report["models"]}
    eq2 = by_name[("eq2", "none")]["predicted_R"]
    fitted = by_name[("eq2-effective-K_r", "leave-one-sample-out")]["predicted_R"]
    k_r = report["k_r_N_per_mm"]
    series, measured = [], []
    for element in sorted({r["element"] for r in rows}):
        idx = [i for i, r in enumerate(rows) if r["element"] == element]
        k_m = rows[idx[0]]["K_m_N_per_mm"]
        x = [k_m / rows[i]["K_obj_N_per_mm"] for i in idx]
        ratio = k_r / k_m
        series.append({"label": f"K_r/K_m = {ratio:.3g} eq. 2", "K_r_over_K_m": ratio,
                       "K_m_over_K_obj": x, "R": [eq2[i] for i in idx]})
        series.append({"label": None, "K_r_over_K_m": ratio, "style": "--",
                       "K_m_over_K_obj": x, "R": [fitted[i] for i in idx]})
        measured.append({"K_r_over_K_m": ratio, "K_m_over_K_obj": x,
                         "R": [rows[i]["R"] for i in idx]})
    measured[0]["label"] = "measured (Table 2)"
    series[1]["label"] = "eq. 2, K_r fitted on other samples"
    return plot_ratio_map(series, path, "Table 2: measured R (markers), eq. 2 with Table 1's K "
                          "(solid), held-out fitted K_r (dashed)", measured)
