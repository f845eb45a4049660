"""``tactcad bench stiffness``: the speed/accuracy trade of the stiffness ladder.

Every level is run over a grid of designs spanning the design domain (web
0.15-0.4 mm, arm 4-8 mm, notch radius from t/R = 1 down to t/R = 0.25) and
compared with fem3d, the reference. Printed: time per evaluation and the
error against fem3d (max and mean over the grid) per level, plus the
vectorised closed form's evaluations per second. Written:
``<out>/stiffness_tradeoff.csv`` and ``.png`` (error vs time, log-log).

Units: mm, N/mm, s.
"""

from __future__ import annotations

import csv
import itertools
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from tactcad.design.array import ElementGeometry, Material, Plan, load_design
from tactcad.mechanics.ladder import MODELS, estimate

WEBS_MM = (0.15, 0.25, 0.40)
ARMS_MM = (4.0, 8.0)
NOTCH_RADII = ("t", 0.6)  # "t": R equal to the web (t/R = 1); 0.6 mm: t/R down to 0.25
GOALS = {"closed-form": "≥ 1e6 evals/s, ≤ 2 % from fem3d",
         "fem2d": "≤ 0.5 % estimated error in ≤ 2 s",
         "fem3d": "≤ 0.5 % in ≤ 60 s, ≤ 4 GiB"}


@dataclass(frozen=True)
class Point:
    model: str
    web_mm: float
    arm_mm: float
    notch_radius_mm: float
    k_N_per_mm: float
    error_estimate_rel: float
    wall_time_s: float
    error_vs_fem3d_rel: float = float("nan")


def design_grid(base: ElementGeometry) -> list[ElementGeometry]:
    """Grid of element geometries over the design domain (mm)."""
    out = []
    for t, a, r in itertools.product(WEBS_MM, ARMS_MM, NOTCH_RADII):
        R = t if r == "t" else float(r)
        out.append(replace(base, web_thickness_mm=t, arm_length_mm=a, notch_radius_mm=R))
    return out


def closed_form_throughput(material: Material, base: ElementGeometry, n: int = 1_000_000) -> float:
    """Vectorised closed-form evaluations per second over ``n`` random in-domain designs."""
    from tactcad.mechanics.closed_form import closed_form_stiffness

    rng = np.random.default_rng(0)
    t = rng.uniform(*WEBS_MM[::2], n)
    a = rng.uniform(*ARMS_MM, n)
    R = rng.uniform(t, 2.0)
    kw = dict(arm_height_mm=base.arm_height_mm, tip_width_mm=base.tip_width_mm,
              tip_height_mm=base.tip_height_mm, E=material.youngs_modulus_MPa,
              nu=material.poisson_ratio, b=base.sheet_thickness_mm)
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        closed_form_stiffness(t, R, a, **kw)
        best = min(best, time.perf_counter() - t0)
    return n / best


def run(models=MODELS, design=None, out_dir="exports/reports", progress=print,
        plan: Plan | None = None) -> list[Point]:
    """Run the ladder over the grid around ``plan`` (default: the design file
    ``design``), write CSV + PNG, return the points."""
    plan = load_design(design) if plan is None else plan
    base = plan.element(1).geometry
    grid = design_grid(base)
    points: list[Point] = []
    for model in models:
        for i, g in enumerate(grid, start=1):
            progress(f"  {model:<12} design {i}/{len(grid)}: t={g.web_thickness_mm} a={g.arm_length_mm} "
                     f"R={g.notch_radius_mm}")
            r = estimate(model, g, plan.material)
            points.append(Point(model, g.web_thickness_mm, g.arm_length_mm, g.notch_radius_mm,
                                r.stiffness_N_per_mm, r.error_estimate_rel, r.wall_time_s))
    ref = {(p.web_mm, p.arm_mm, p.notch_radius_mm): p.k_N_per_mm for p in points if p.model == "fem3d"}
    if ref:
        points = [replace(p, error_vs_fem3d_rel=abs(p.k_N_per_mm - ref[(p.web_mm, p.arm_mm, p.notch_radius_mm)])
                          / ref[(p.web_mm, p.arm_mm, p.notch_radius_mm)]) for p in points]
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
            wr.writerow(["model", "web_mm", "arm_mm", "notch_radius_mm", "K_N_per_mm",
                         "error_estimate_rel", "wall_time_s", "error_vs_fem3d_rel"])
            for p in points:
                wr.writerow([p.model, p.web_mm, p.arm_mm, p.notch_radius_mm, f"{p.k_N_per_mm:.6g}",
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


def main(args, plan: Plan | None = None) -> int:
    """Entry point of ``tactcad bench stiffness`` (``plan``: the design with
    the command line's overrides; default: ``args.design`` as it is)."""
    models = tuple(getattr(args, "models", None) or MODELS)
    out_dir = getattr(args, "out", None) or "exports/reports"
    design = getattr(args, "design", None)
    quiet = getattr(args, "json", False) or getattr(args, "quiet", False)
    progress = (lambda s: None) if quiet else (lambda s: print(s, file=sys.stderr, flush=True))
    progress("tactcad bench stiffness: grid "
             f"{len(WEBS_MM)} webs x {len(ARMS_MM)} arms x {len(NOTCH_RADII)} notch radii")
    plan = load_design(design) if plan is None else plan
    thr = closed_form_throughput(plan.material, plan.element(1).geometry)
    points = run(models, design, out_dir, progress=progress, plan=plan)
    if getattr(args, "json", False):
        import json
        import math

        def clean(v):
            return None if isinstance(v, float) and not math.isfinite(v) else v

        print(json.dumps({"closed_form_evaluations_per_s": thr,
                          "levels": [{k: clean(v) for k, v in r.items()} for r in summary(points)],
                          "files": [f"{out_dir}/stiffness_tradeoff.csv",
                                    f"{out_dir}/stiffness_tradeoff.png"]},
                         indent=2, allow_nan=False))
        return 0
    print(f"\nclosed form, vectorised: {thr:,.0f} element evaluations/s (goal ≥ 1e6)")
    print(f"{'level':<12} {'time/eval s':>12} {'max time s':>11} {'err vs fem3d max':>17} "
          f"{'mean':>8} {'est. err max':>13}  goal")
    for r in summary(points):
        print(f"{r['model']:<12} {r['time_per_eval_s']:>12.4g} {r['max_time_s']:>11.3g} "
              f"{100 * r['err_vs_fem3d_max']:>16.2f}% {100 * r['err_vs_fem3d_mean']:>7.2f}% "
              f"{100 * r['est_err_max']:>12.3f}%  {GOALS.get(r['model'], '')}")
    print(f"wrote {out_dir}/stiffness_tradeoff.csv and .png")
    return 0
