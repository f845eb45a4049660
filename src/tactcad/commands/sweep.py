"""``tactcad sweep``: design grids, the correction refit and Monte Carlo on Dask."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from tactcad.mechanics.ladder import models
from tactcad.commands import add_cache_args, add_design_arg, add_output_args, plan_from_args
from tactcad.commands.options import count, number, output_file, output_folder
from tactcad.commands.finite_json import dumps
from tactcad.commands.tolerance import add_cluster_args



def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sweep", help="design grids, correction refit and Monte Carlo on Dask",
                       description="Sweeps on a Dask cluster: a new LocalCluster (2 worker "
                                   "processes x 1 thread) by default, or an existing one with "
                                   "--scheduler tcp://HOST:PORT. Same numbers either way.")
    ssub = p.add_subparsers(dest="sweep", metavar="WHAT")
    g = ssub.add_parser("grid", help="K over web x arm (x notch radius): CSV and design chart PNG")
    add_design_arg(g)
    add_cache_args(g)
    g.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level of every point (default %(default)s)")
    g.add_argument("--webs", type=number(0, 100, "mm", lo_open=True), nargs="+", default=None,
                   metavar="MM", help="web thicknesses (mm; default: five from half to 1.5 "
                                      "times the design's web, no thinner than its cut "
                                      "process leaves on its sheet)")
    g.add_argument("--arms", type=number(0, 1000, "mm", lo_open=True), nargs="+", default=None,
                   metavar="MM", help="arm lengths (mm; default: five from the design's "
                                      "shortest arm to its longest; one arm length: half "
                                      "to 1.5 times it)")
    g.add_argument("--radii", type=number(0, 100, "mm", lo_open=True), nargs="+", default=None, metavar="MM",
                   help="notch radii (default: the design's, raised to the web where thinner)")
    g.add_argument("--out", metavar="DIR", type=output_folder, default="exports/sweeps",
                   help="folder for design_grid.csv and design_chart.png (default %(default)s)")
    add_output_args(g, "print the rows as JSON")
    add_cluster_args(g, local_default=True)
    g.set_defaults(func=run_grid_cmd)

    r = ssub.add_parser("refit", help="fem3d sweep of the closed-form correction and its fit "
                                      "(about 20 s per design per worker)")
    r.add_argument("--fit", type=count(0, 100_000, "designs"), default=64, help="Sobol designs in the fit set (default %(default)s)")
    r.add_argument("--holdout", type=count(0, 100_000, "designs"), default=16, help="Sobol designs held out (default %(default)s)")
    r.add_argument("--points", metavar="FILE", default=None,
                   help="JSON lines of the fem3d points (resumable; default: the sweep's own)")
    r.add_argument("--out", metavar="FILE", type=output_file(),
                   default="exports/sweeps/stiffness_correction.json",
                   help="fitted correction (the stored one is not touched; default %(default)s)")
    add_output_args(r, "print one JSON object: new points, seconds, residuals, the file written")
    add_cluster_args(r, local_default=True)
    r.set_defaults(func=run_refit_cmd)

    m = ssub.add_parser("montecarlo", help="tolerance Monte Carlo on Dask, CSV of the bands")
    add_design_arg(m)
    add_cache_args(m)
    m.add_argument("--samples", type=count(1, 10**8, "samples"), default=100_000,
                   help="Monte Carlo samples (default %(default)s)")
    m.add_argument("--seed", type=count(0, 2**32 - 1, "a seed"), default=0,
                   help="random seed of the draws (default %(default)s)")
    m.add_argument("--out", metavar="DIR", type=output_folder, default="exports/sweeps",
                   help="folder for tolerance_elements.csv and tolerance_units.csv (default %(default)s)")
    add_output_args(m, "print one JSON object: samples, seconds, the files written")
    add_cluster_args(m, local_default=True)
    m.set_defaults(func=run_montecarlo_cmd)
    p.set_defaults(func=lambda args: (p.print_help(), 2)[1])


def _bar(args) -> bool:
    """Dask's progress bar on stderr, unless --json or --quiet."""
    return not (args.json or args.quiet)


def _workers(args) -> int:
    from tactcad.studies.sweeps import LOCAL_WORKERS

    return args.workers or LOCAL_WORKERS


def check_out_folder(out: str | Path) -> None:
    """Refuse ``--out`` before a sweep's work when its folder is a system one or cannot be
    made.

    Args:
        out: the folder the sweep writes into.

    Raises:
        DesignError: naming ``--out``, the path and the system folder rule
            (:func:`tactcad.atomic.refuse_output_path`) or why it cannot be made
            (:func:`tactcad.atomic.unmakeable_folder`).
    """
    from tactcad.atomic import refuse_output_path, unmakeable_folder
    from tactcad.errors import DesignError

    refuse_output_path("--out", out, "a folder")  # its default too: the rule of every output
    reason = None if Path(out).is_dir() else unmakeable_folder(out)
    if reason is not None:
        raise DesignError("--out", str(out), "a folder that can be made", reason)


def _measured(plan) -> dict:
    """The chart's measured crosses: the paper's Table 1 for a design that cites the
    paper, none for another (the paper's samples are not a new design's)."""
    from tactcad.design.requirements_section import cites_paper
    from tactcad.paper.data import table1

    if not cites_paper(plan.raw):
        return {}
    return {"measured": [(m.element, m.flexing_arm_length_mm, m.stiffness_N_per_mm)
                         for m in table1()], "measured_label": "Table 1 (measured)"}


def run_grid_cmd(args: argparse.Namespace) -> int:
    from tactcad.studies.sweeps import (dask_client, dask_mapper, default_grid_axes, design_grid,
                                        evaluated_grid, grid_points, plot_design_chart,
                                        rows_as_json, write_grid_csv)

    check_out_folder(args.out)
    plan = plan_from_args(args)
    own_webs, own_arms = default_grid_axes(plan)
    webs, arms = args.webs or own_webs, args.arms or own_arms
    # the grid's values judged before a cluster starts (seconds): a refusal is said at once
    points = grid_points(plan, webs, arms, args.model, args.radii)
    with dask_client(args.scheduler, _workers(args)) as client:
        rows = evaluated_grid(points, mapper=dask_mapper(client, progress=_bar(args)))
        if args.model != "closed-form":  # the chart's lines: closed form, finer in arm
            lo, hi = min(arms), max(arms)
            fine = [lo + (hi - lo) * k / 16 for k in range(17)]
            rows = design_grid(plan, webs, fine, "closed-form", args.radii) + rows
    out = Path(args.out)
    csv_path = write_grid_csv(out / "design_grid.csv", rows)
    png_path = plot_design_chart(out / "design_chart.png", rows, plan, **_measured(plan))
    if args.json:
        print(json.dumps(rows_as_json(rows), indent=2, allow_nan=False))
        return 0
    print(f"{'model':<12} {'web mm':>7} {'arm mm':>7} {'R mm':>6} {'K N/mm':>10} "
          f"{'ustrain/N':>10} {'est. err':>9} {'time s':>8}")
    for row in rows:
        print(f"{row.model:<12} {row.web_mm:>7g} {row.arm_mm:>7g} {row.notch_radius_mm:>6g} "
              f"{row.K_N_per_mm:>10.4g} {1e6 * row.face_strain_per_N:>10.1f} "
              f"{100 * row.error_estimate_rel:>8.2f}% {row.wall_time_s:>8.3g}")
    print(f"wrote {csv_path} and {png_path}")
    return 0


def run_refit_cmd(args: argparse.Namespace) -> int:
    from tactcad.atomic import write_bytes_atomic
    from tactcad.studies.sweeps import correction_refit, dask_client, dask_mapper

    check_out_folder(Path(args.out).parent)
    with dask_client(args.scheduler, _workers(args)) as client:
        res = correction_refit(dask_mapper(client, progress=_bar(args)), args.fit, args.holdout, args.points)
    doc = res["document"]
    write_bytes_atomic(args.out, (json.dumps(doc, indent=2, allow_nan=False) + "\n").encode())
    hold = doc.get("holdout", {})
    if args.json:
        print(dumps({"new_points": res["new_points"], "wall_time_s": res["wall_time_s"],
                     "points": len(doc["points"]), "residual_rel_max": doc["residual_rel_max"],
                     "holdout_rel_max": hold.get("max"), "out": args.out}))
        return 0
    print(f"{res['new_points']} new fem3d points in {res['wall_time_s']:.1f} s; "
          f"{len(doc['points'])} in the fit; residual max {100 * doc['residual_rel_max']:.2f} %"
          + (f", hold-out max {100 * hold.get('max', float('nan')):.2f} %" if hold else "")
          + f"; wrote {args.out}")
    return 0


def run_montecarlo_cmd(args: argparse.Namespace) -> int:
    import csv
    import time

    from tactcad.atomic import write_atomic
    from tactcad.studies.tolerance_montecarlo import run_tolerance
    from tactcad.studies.sweeps import dask_client, dask_mapper

    check_out_folder(args.out)
    plan = plan_from_args(args)
    t0 = time.perf_counter()
    with dask_client(args.scheduler, _workers(args)) as client:
        report = run_tolerance(plan, args.samples, args.seed,
                               mapper=dask_mapper(client, progress=_bar(args)))
    wall = time.perf_counter() - t0
    out = Path(args.out)

    def table(path: Path, records: list[dict]) -> None:
        flat = [_flatten(r) for r in records]

        def w(tmp: Path) -> None:
            with open(tmp, "w", newline="") as fh:
                wr = csv.DictWriter(fh, fieldnames=list(flat[0]))
                wr.writeheader()
                wr.writerows(flat)

        write_atomic(path, w)

    table(out / "tolerance_elements.csv", report.elements)
    table(out / "tolerance_units.csv", report.units)
    if args.json:
        print(dumps({"samples": report.samples, "wall_time_s": wall,
                     "files": [str(out / "tolerance_elements.csv"),
                               str(out / "tolerance_units.csv")]}))
        return 0
    print(f"{report.samples} samples in {wall:.2f} s (cluster start included); wrote "
          f"{out / 'tolerance_elements.csv'} and {out / 'tolerance_units.csv'}")
    return 0


def _flatten(record: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in record.items():
        if isinstance(v, dict):
            out.update(_flatten(v, f"{prefix}{k}_"))
        else:
            out[f"{prefix}{k}"] = v
    return out
