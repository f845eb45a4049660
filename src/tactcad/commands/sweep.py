"""``tactcad sweep``: design grids, the correction refit and Monte Carlo on Dask."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import add_design_arg
from .tolerance import add_cluster_args

MODELS = ("closed-form", "beam", "fem2d", "fem3d")
DEFAULT_WEBS_MM = (0.15, 0.2, 0.25, 0.3, 0.4)
DEFAULT_ARMS_MM = (4.0, 5.0, 6.0, 7.0, 8.0)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sweep", help="design grids, correction refit and Monte Carlo on Dask",
                       description="Sweeps on a Dask cluster: a new LocalCluster (2 worker "
                                   "processes x 1 thread) by default, or an existing one with "
                                   "--scheduler tcp://HOST:PORT. Same numbers either way.")
    ssub = p.add_subparsers(dest="sweep", metavar="WHAT")
    g = ssub.add_parser("grid", help="K over web x arm (x notch radius): CSV and design chart PNG")
    add_design_arg(g)
    g.add_argument("--model", choices=MODELS, default="closed-form")
    g.add_argument("--webs", type=float, nargs="+", default=list(DEFAULT_WEBS_MM), metavar="MM")
    g.add_argument("--arms", type=float, nargs="+", default=list(DEFAULT_ARMS_MM), metavar="MM")
    g.add_argument("--radii", type=float, nargs="+", default=None, metavar="MM",
                   help="notch radii (default: the design's, raised to the web where thinner)")
    g.add_argument("--out", metavar="DIR", default="exports/sweeps",
                   help="folder for design_grid.csv and design_chart.png")
    g.add_argument("--json", action="store_true", help="print the rows as JSON")
    add_cluster_args(g, local_default=True)
    g.set_defaults(func=run_grid_cmd)

    r = ssub.add_parser("refit", help="FEM points of the closed-form correction and the fit "
                                      "(fem3d: minutes)")
    r.add_argument("--reference", choices=("fem3d", "fem2d-plane-stress"), default="fem3d")
    r.add_argument("--out", metavar="FILE", default="exports/sweeps/correction_refit.json",
                   help="JSON of the points and the fit (the stored correction is not touched)")
    add_cluster_args(r, local_default=True)
    r.set_defaults(func=run_refit_cmd)

    m = ssub.add_parser("montecarlo", help="tolerance Monte Carlo on Dask, CSV of the bands")
    add_design_arg(m)
    m.add_argument("--samples", type=int, default=100_000)
    m.add_argument("--seed", type=int, default=0)
    m.add_argument("--out", metavar="DIR", default="exports/sweeps",
                   help="folder for tolerance_elements.csv and tolerance_units.csv")
    add_cluster_args(m, local_default=True)
    m.set_defaults(func=run_montecarlo_cmd)
    p.set_defaults(func=lambda args: (p.print_help(), 2)[1])


def _workers(args) -> int:
    from ..sweeps import LOCAL_WORKERS

    return args.workers or LOCAL_WORKERS


def run_grid_cmd(args: argparse.Namespace) -> int:
    from ..design import load_design
    from ..sweeps import (dask_client, dask_mapper, design_grid, plot_design_chart,
                          rows_as_json, write_grid_csv)

    plan = load_design(args.design)
    with dask_client(args.scheduler, _workers(args)) as client:
        rows = design_grid(plan, args.webs, args.arms, args.model, args.radii,
                           mapper=dask_mapper(client))
        if args.model != "closed-form":  # the chart's lines: closed form on the same grid
            rows = design_grid(plan, args.webs, args.arms, "closed-form", args.radii) + rows
    out = Path(args.out)
    csv_path = write_grid_csv(out / "design_grid.csv", rows)
    png_path = plot_design_chart(out / "design_chart.png", rows, plan)
    if args.json:
        print(json.dumps(rows_as_json(rows), indent=2, allow_nan=False))
        return 0
    print(f"{'model':<12} {'web mm':>7} {'arm mm':>7} {'R mm':>6} {'K N/mm':>10} "
          f"{'ustrain/N':>10} {'est. err':>9} {'time s':>8}")
    for row in rows:
        print(f"{row.model:<12} {row.web_mm:>7g} {row.arm_mm:>7g} {row.notch_radius_mm:>6g} "
              f"{row.K_N_per_mm:>10.4g} {1e6 * row.gauge_strain_per_N:>10.1f} "
              f"{100 * row.error_estimate_rel:>8.2f}% {row.wall_time_s:>8.3g}")
    print(f"wrote {csv_path} and {png_path}")
    return 0


def run_refit_cmd(args: argparse.Namespace) -> int:
    from ..export.atomic import write_bytes_atomic
    from ..sweeps import correction_refit, dask_client, dask_mapper

    with dask_client(args.scheduler, _workers(args)) as client:
        doc = correction_refit(dask_mapper(client), reference=args.reference)
    fit = doc["fit"]
    text = json.dumps(doc, indent=2, allow_nan=False, default=float) + "\n"
    write_bytes_atomic(args.out, text.encode())
    print(f"{len(doc['points'])} points in {doc['wall_time_s']:.1f} s; c1 {fit['c1']:.4f} "
          f"c2 {fit['c2']:.4f} c3 {fit['c3']:.4f} c4 {fit['c4']:.4f}; residual max "
          f"{100 * fit['residual_rel_max']:.2f} %, rms {100 * fit['residual_rel_rms']:.2f} %")
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


def run_montecarlo_cmd(args: argparse.Namespace) -> int:
    import csv
    import time

    from ..design import load_design
    from ..export.atomic import write_atomic
    from ..mechanics.tolerance import run_tolerance
    from ..sweeps import dask_client, dask_mapper

    plan = load_design(args.design)
    t0 = time.perf_counter()
    with dask_client(args.scheduler, _workers(args)) as client:
        report = run_tolerance(plan, args.samples, args.seed, mapper=dask_mapper(client))
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
