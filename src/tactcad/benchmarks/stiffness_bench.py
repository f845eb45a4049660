"""``tactcad bench stiffness``: the speed/accuracy trade of the stiffness ladder.

Grid: the hold-out designs of the closed-form correction (stored with their
fem3d stiffness in ``src/tactcad/data/stiffness_correction.json``; not used
in the fit) and the design file's own elements. They span the design domain:
web 0.05-1 mm, notch radius t-2 mm, arm 2-20 mm, sheet 0.5-10 mm, Poisson
ratio 0.27-0.34 (other dimensions by the grid rule of
:mod:`tactcad.studies.correction_sweep`).

closed-form, beam and fem2d run on every design and are compared with the
stored fem3d stiffness. fem3d itself (the costly level, 10-120 s per design)
runs on a subset: the design file's shortest- and longest-arm elements and
the first ``FEM3D_HOLDOUT_SUBSET`` hold-out designs (about 4 minutes on one
core); its time per evaluation and its agreement with the stored values are
printed. Printed: time per evaluation
and the error against fem3d (max and mean) per level, plus the vectorised
closed form's evaluations per second. Written:
``<out>/stiffness_tradeoff.csv`` and ``.png`` (error vs time, log-log).

Units: mm, N/mm, s.
"""

from __future__ import annotations

import csv
import json
import math
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.mechanics.correction import CORRECTION_FILE, range_warnings_unsaid
from tactcad.studies.correction_sweep import grid_geometry
from tactcad.mechanics.ladder import estimate, models

#: Hold-out designs on which fem3d is run live (the others use the stored value).
FEM3D_HOLDOUT_SUBSET = 2
GOALS = {"closed-form": "≥ 1e7 evals/s, ≤ 2 % from fem3d",
         "fem2d": "≤ 0.5 % estimated error in ≤ 2 s",
         "fem3d": "≤ 0.5 % estimated error, ≤ 4 GiB"}


@dataclass(frozen=True)
class Design:
    """One benchmark design: geometry, material and the stored fem3d K (N/mm; NaN if none)."""

    label: str
    geometry: ElementGeometry
    material: Material
    k_fem3d_stored: float = float("nan")
    fem3d_live: bool = False


@dataclass(frozen=True)
class Point:
    model: str
    label: str
    web_mm: float
    arm_mm: float
    notch_radius_mm: float
    sheet_mm: float
    poisson_ratio: float
    k_N_per_mm: float
    error_estimate_rel: float
    wall_time_s: float
    error_vs_fem3d_rel: float = float("nan")


def design_grid(plan: Plan, correction_path: str | Path = CORRECTION_FILE) -> list[Design]:
    """The design's distinct elements (``plan``), then the stored hold-out designs."""
    own = {s.geometry.part_name: s.geometry for s in plan.slots}
    arms = sorted(own.values(), key=lambda g: g.arm_length_mm)
    extremes = {arms[0].part_name, arms[-1].part_name}
    out = [Design(name, g, plan.material, fem3d_live=name in extremes)
           for name, g in sorted(own.items(), key=lambda kv: kv[1].arm_length_mm)]
    doc = json.loads(Path(correction_path).read_text(encoding="utf-8"))
    for i, p in enumerate(q for q in doc["points"] if q["set"] == "holdout"):
        g, mat = grid_geometry(p["web_mm"], p["arm_mm"], p["notch_radius_mm"],
                               sheet_mm=p["sheet_mm"], poisson_ratio=p["poisson_ratio"],
                               youngs_modulus_MPa=p["youngs_modulus_MPa"])
        out.append(Design(f"holdout_{i + 1}", g, mat, float(p["K_fem3d"]),
                          fem3d_live=i < FEM3D_HOLDOUT_SUBSET))
    return out


def closed_form_throughput(n: int = 1_000_000) -> float:
    """Vectorised closed-form evaluations per second over ``n`` random designs of the domain."""
    from tactcad.mechanics.closed_form import closed_form_stiffness

    rng = np.random.default_rng(0)
    t = np.exp(rng.uniform(np.log(0.05), np.log(1.0), n))
    R = rng.uniform(t, 2.0)
    a = rng.uniform(R + 1.7, 20.0)
    b = rng.uniform(0.5, 10.0, n)
    kw = dict(arm_height_mm=np.maximum(2.0, t + R + 0.5), tip_width_mm=2.0, tip_height_mm=1.5,
              E=69000.0, nu=0.33, b=b)
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        closed_form_stiffness(t, R, a, **kw)
        best = min(best, time.perf_counter() - t0)
    return n / best


def run(plan: Plan, levels=None, out_dir="exports/reports", progress=print) -> list[Point]:
    """Run the ladder's ``levels`` (None: every level) over the grid of
    ``plan``, write CSV + PNG, return the points."""
    grid = design_grid(plan)
    points: list[Point] = []
    for model in levels or models():
        for i, d in enumerate(grid, start=1):
            if model == "fem3d" and not d.fem3d_live:
                continue
            g = d.geometry
            progress(f"  {model:<12} design {i}/{len(grid)} {d.label}: t={g.web_thickness_mm:.4g} "
                     f"a={g.arm_length_mm:.4g} R={g.notch_radius_mm:.4g} "
                     f"b={g.sheet_thickness_mm:.4g} nu={d.material.poisson_ratio:.3g}")
            with range_warnings_unsaid():
                r = estimate(model, g, d.material)
            points.append(Point(model, d.label, g.web_thickness_mm, g.arm_length_mm,
                                g.notch_radius_mm, g.sheet_thickness_mm,
                                d.material.poisson_ratio, r.stiffness_N_per_mm,
                                r.error_estimate_rel, r.wall_time_s))
    stored = {d.label: d.k_fem3d_stored for d in grid}
    live = {p.label: p.k_N_per_mm for p in points if p.model == "fem3d"}

    def error_vs_fem3d(p: Point) -> float:
        # fem3d itself: live against stored (NaN where nothing is stored)
        ref = stored[p.label] if p.model == "fem3d" else live.get(p.label, stored[p.label])
        return abs(p.k_N_per_mm / ref - 1.0)

    points = [replace(p, error_vs_fem3d_rel=error_vs_fem3d(p)) for p in points]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    _write_csv(out / "stiffness_tradeoff.csv", points)
    _plot(out / "stiffness_tradeoff.png", points)
    return points


def summary(points: list[Point]) -> list[dict]:
    rows = []
    for model in dict.fromkeys(p.model for p in points):
        ps = [p for p in points if p.model == model]
        errs = np.array([p.error_vs_fem3d_rel for p in ps])
        rows.append({"model": model, "n": len(ps),
                     "time_per_eval_s": float(np.median([p.wall_time_s for p in ps])),
                     "max_time_s": float(max(p.wall_time_s for p in ps)),
                     "err_vs_fem3d_max": float(np.nanmax(errs)) if np.isfinite(errs).any() else float("nan"),
                     "err_vs_fem3d_mean": float(np.nanmean(errs)) if np.isfinite(errs).any() else float("nan"),
                     "est_err_max": float(max(p.error_estimate_rel for p in ps))})
    return rows


def _write_csv(path: Path, points: list[Point]) -> None:
    from tactcad.atomic import write_atomic

    def w(tmp: Path) -> None:
        with open(tmp, "w", newline="") as fh:
            wr = csv.writer(fh)
            wr.writerow(["model", "design", "web_mm", "arm_mm", "notch_radius_mm", "sheet_mm",
                         "poisson_ratio", "K_N_per_mm", "error_estimate_rel", "wall_time_s",
                         "error_vs_fem3d_rel"])
            for p in points:
                wr.writerow([p.model, p.label, f"{p.web_mm:.6g}", f"{p.arm_mm:.6g}",
                             f"{p.notch_radius_mm:.6g}", f"{p.sheet_mm:.6g}",
                             f"{p.poisson_ratio:.4g}", f"{p.k_N_per_mm:.6g}",
                             f"{p.error_estimate_rel:.3g}", f"{p.wall_time_s:.4g}",
                             f"{p.error_vs_fem3d_rel:.4g}"])
    write_atomic(path, w)


def _plot(path: Path, points: list[Point]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tactcad.atomic import write_atomic

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for model in dict.fromkeys(p.model for p in points):
        ps = [p for p in points if p.model == model and np.isfinite(p.error_vs_fem3d_rel)]
        if not ps:
            continue
        err = [max(p.error_vs_fem3d_rel, 1e-6) for p in ps]  # fem3d itself sits at the floor
        ax.scatter([p.wall_time_s for p in ps], err, label=model, s=18)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per evaluation (s)")
    ax.set_ylabel("|K - K_fem3d| / K_fem3d")
    ax.set_title("Stiffness ladder: error vs cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    write_atomic(path, lambda tmp: fig.savefig(tmp, format="png", metadata={"Software": None}))
    plt.close(fig)


def main(args, plan: Plan) -> int:
    """Entry point of ``tactcad bench stiffness`` (``plan``: the validated
    design with the command line's overrides)."""
    models_run = tuple(getattr(args, "models", None) or models())
    out_dir = getattr(args, "out", None) or "exports/reports"
    as_json = getattr(args, "json", False)
    quiet = as_json or getattr(args, "quiet", False)
    progress = (lambda s: None) if quiet else (lambda s: print(s, file=sys.stderr, flush=True))
    grid = design_grid(plan)
    n_hold = sum(d.label.startswith("holdout_") for d in grid)
    live = ", ".join(d.label for d in grid if d.fem3d_live)
    progress(f"tactcad bench stiffness: {len(grid) - n_hold} design elements + {n_hold} hold-out "
             f"designs of the correction (web 0.05-1 mm, arm 2-20 mm, sheet 0.5-10 mm); fem3d "
             f"live on {live}, stored fem3d elsewhere")
    thr = closed_form_throughput()
    points = run(plan, models_run, out_dir, progress=progress)
    if as_json:
        def clean(v):
            return None if isinstance(v, float) and not math.isfinite(v) else v

        print(json.dumps({"closed_form_evaluations_per_s": thr,
                          "levels": [{k: clean(v) for k, v in r.items()} for r in summary(points)],
                          "files": [f"{out_dir}/stiffness_tradeoff.csv",
                                    f"{out_dir}/stiffness_tradeoff.png"]},
                         indent=2, allow_nan=False))
        return 0
    print(f"\nclosed form, vectorised: {thr:,.0f} element evaluations/s (goal ≥ 1e7)")
    print(f"{'level':<12} {'n':>3} {'time/eval s':>12} {'max time s':>11} {'err vs fem3d max':>17} "
          f"{'mean':>8} {'est. err max':>13}  goal")
    for r in summary(points):
        print(f"{r['model']:<12} {r['n']:>3} {r['time_per_eval_s']:>12.4g} {r['max_time_s']:>11.3g} "
              f"{100 * r['err_vs_fem3d_max']:>16.2f}% {100 * r['err_vs_fem3d_mean']:>7.2f}% "
              f"{100 * r['est_err_max']:>12.3f}%  {GOALS.get(r['model'], '')}")
    print("(fem3d row: live fem3d against the stored fem3d of the hold-out designs)")
    print(f"wrote {out_dir}/stiffness_tradeoff.csv and .png")
    return 0
