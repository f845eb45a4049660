"""Fit of the closed-form stiffness correction against the FEM reference.

The closed-form estimator is Euler–Bernoulli (EB): the tip compliance of a
beam whose height follows the real profile. Against converged FEM it is too
stiff, mostly through the flexure hinge (the notch region is short and deep,
so plane sections do not stay plane), by an amount that grows with t/R
(t = web thickness, R = notch radius); and the 3D element of a b = 3 mm
sheet is stiffer than plane stress (the thick arm and base restrain the
web's anticlastic bending). The correction model is

    K = K_EB / (1 + c1 (t/R) + c2 (t/R)^2) * (1 + c3)

fitted in two physically separate steps over a grid of designs:

1. c1, c2: least squares of the relative residual of K_EB / (1 + c1 x +
   c2 x^2) against fem2d plane stress (x = t/R);
2. c3: the 3D factor, least squares of the relative residual of the full
   model against fem3d (the reference), with c1, c2 fixed.

Every grid point is a complete, validated design (the default design with
the web, notch radius and all arm lengths replaced); the arm height is
raised to ``t + R + 0.5 mm`` where the default 2 mm would leave no material
under the notch. fem3d (three meshes, Richardson estimate) runs on every
grid point: 5–60 s each, the 3 x 3 x 3 grid takes about 6 minutes with two
worker processes on two cores. The result is written to
``src/tactcad/data/stiffness_correction.json``, which the closed-form
estimator reads; the per-point K values and residuals are kept in it.

The form's one constant 3D factor is its main limit: fem3d / plane stress
varies with the web thickness and the notch radius (a wider web relative to
its thickness and a shorter notch are closer to plane strain), and that
variation is most of the fit residual.

K_EB here is a private minimal version, so that the fit stands alone: the
deflection at the load point (centre of the contact face, x_tip) of a beam
clamped at the notch's back wall x_h - R,

    1/K_EB = int (x_tip - x)^2 / (E I(x)) dx + int alpha / (G A(x)) dx,

from x_h - R to x_tip, with I = b h^3 / 12, A = b h, alpha = 6/5
(rectangular section), G = E / (2 (1 + nu)) and h(x) = the material height:
t + R - sqrt(R^2 - (x - x_h)^2) over the notch, the arm height on the arm,
arm + tip height under the tip (the tip-root fillet is ignored). The
integrals are evaluated by adaptive Gauss–Kronrod quadrature
(``scipy.integrate.quad``).

Sources: S. T. Smith, "Flexures: Elements of Elastic Mechanisms" (notch
hinge compliance by integration of the beam equation); N. Lobontiu,
"Compliant Mechanisms: Design of Flexure Hinges"; Timoshenko shear
coefficient 6/5 for a rectangle.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np

from tactcad.design.array import (ElementGeometry, Material, default_design_data, plan_from_dict,
                      with_overrides)

#: Where the fitted correction is written (read by the closed-form estimator).
CORRECTION_PATH = Path(__file__).resolve().parents[1] / "data" / "stiffness_correction.json"

MODEL = "K = K_EB * (1 + c3 + c4*w) / (1 + c1*s + c2*s^2), s = t/R, w = sqrt(t*R)/b"

K_EB_DEFINITION = (
    "1/K_EB = int (x_tip - x)^2 / (E I(x)) dx + int 1.2 / (G A(x)) dx over x from the notch's "
    "back wall (hinge_x - R, rigid clamp) to the load point x_tip (centre of the contact face); "
    "I = b h^3/12, A = b h, G = E/(2(1+nu)), E = Young's modulus (no plane-strain factor); "
    "h(x) = t + R - sqrt(R^2 - (x - hinge_x)^2) over the notch, arm height on the arm, arm + "
    "tip height under the tip; tip-root fillet ignored")


# ---------------------------------------------------------------------------
# Euler–Bernoulli tip stiffness (private minimal version)
# ---------------------------------------------------------------------------
def _k_euler_bernoulli(g: ElementGeometry, material: Material) -> float:
    """EB + shear tip stiffness (N/mm) of the real profile; see module doc."""
    from scipy.integrate import quad

    E, nu = material.youngs_modulus_MPa, material.poisson_ratio
    G = E / (2.0 * (1.0 + nu))
    b, t, R = g.sheet_thickness_mm, g.web_thickness_mm, g.notch_radius_mm
    xh, x_tip = g.hinge_x_mm, g.tip_centre_x_mm
    x_tip_l = g.overall_length_mm - g.tip_width_mm
    ha, ht = g.arm_height_mm, g.arm_height_mm + g.tip_height_mm

    def h_notch(x):
        d = x - xh
        return t + R - math.sqrt(max(R * R - d * d, 0.0))

    def bend(h):
        return lambda x: (x_tip - x) ** 2 * 12.0 / (E * b * h(x) ** 3)

    def shear(h):
        return lambda x: 1.2 / (G * b * h(x))

    pieces = [(xh - R, xh + R, h_notch), (xh + R, x_tip_l, lambda x: ha),
              (x_tip_l, x_tip, lambda x: ht)]
    c = 0.0
    for x0, x1, h in pieces:
        if x1 <= x0:
            continue
        pts = [xh] if x0 < xh < x1 else None
        c += quad(bend(h), x0, x1, points=pts, limit=200, epsabs=0, epsrel=1e-10)[0]
        c += quad(shear(h), x0, x1, points=pts, limit=200, epsabs=0, epsrel=1e-10)[0]
    return 1.0 / c


# ---------------------------------------------------------------------------
# Grid
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class FitGrid:
    """Designs of the fit: every web x arm x notch radius.

    Attributes:
        web_mm: web thicknesses t (mm).
        arm_mm: arm lengths (mm).
        radius_steps: notch radii per web, geometric from R = t to
            ``notch_radius_max_mm`` (t/R from 1 down to t / R_max).
        notch_radius_max_mm: largest notch radius (mm).
        arm_height_clearance_mm: arm height is at least t + R + this.
    """

    web_mm: tuple[float, ...] = (0.15, 0.25, 0.40)
    arm_mm: tuple[float, ...] = (4.0, 6.0, 8.0)
    radius_steps: int = 3
    notch_radius_max_mm: float = 2.0
    arm_height_clearance_mm: float = 0.5

    def radii(self, t: float) -> list[float]:
        n = self.radius_steps
        if n == 1:
            return [t]
        return [float(t * (self.notch_radius_max_mm / t) ** (k / (n - 1))) for k in range(n)]

    def points(self) -> list[tuple[float, float, float]]:
        """(web t, arm length, notch radius R) of every grid point (mm)."""
        return [(t, a, R) for t in self.web_mm for R in self.radii(t) for a in self.arm_mm]


def grid_geometry(t: float, arm: float, R: float,
                  clearance_mm: float = 0.5) -> tuple[ElementGeometry, Material]:
    """A validated element of the default design with web t, notch radius R
    and arm length ``arm`` (mm); the arm height is raised to t + R +
    ``clearance_mm`` if the default is lower.

    Raises:
        DesignError: the combination is outside the design rules.
    """
    data = default_design_data()
    arm_h = max(float(data["element"]["arm_height_mm"]), t + R + clearance_mm)
    n = len(data["arms"]["lengths_mm"])
    over = {"element.web_thickness_mm": t, "element.notch_radius_mm": R,
            "element.arm_height_mm": round(arm_h, 6), "arms.lengths_mm": [arm] * n}
    plan = plan_from_dict(with_overrides(data, over), source="<correction fit grid>")
    return plan.element(1).geometry, plan.material


def _evaluate_point(args) -> dict:
    from tactcad.mechanics.fem.fem2d import fem2d_convergence
    from tactcad.mechanics.fem.fem3d import fem3d_convergence

    t, arm, R, clearance, with_3d = args
    g, mat = grid_geometry(t, arm, R, clearance)
    t0 = time.perf_counter()
    c2 = fem2d_convergence(g, mat, plane="stress")
    row = {"web_mm": t, "arm_mm": arm, "notch_radius_mm": R, "arm_height_mm": g.arm_height_mm,
           "t_over_R": t / R, "K_EB": _k_euler_bernoulli(g, mat),
           "K_fem2d_plane_stress": c2.finest.stiffness_N_per_mm,
           "err_fem2d": c2.stiffness.error_rel}
    if with_3d:
        c3 = fem3d_convergence(g, mat)
        row["K_fem3d"] = c3.finest.stiffness_N_per_mm
        row["err_fem3d"] = c3.stiffness.error_rel
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def _model(x: np.ndarray, w: np.ndarray, c1: float, c2: float, c3: float,
           c4: float = 0.0) -> np.ndarray:
    """K / K_EB: (1 + c3 + c4 w) / (1 + c1 s + c2 s^2), s = t/R, w = sqrt(t R)/b."""
    return (1.0 + c3 + c4 * w) / (1.0 + c1 * x + c2 * x * x)


def fit_coefficients(rows: Sequence[dict], reference: str = "fem3d",
                     sheet_thickness_mm: float = 3.0) -> dict:
    """Fit c1, c2 (against plane stress), then c3, c4 (against ``reference``).

    c3 + c4 w is the plane-stress -> 3D gain, w = sqrt(t R) / b: the hinge's
    bending length over the sheet width (one constant left 3.3 % residuals).

    Args:
        rows: per-point dicts with t_over_R, K_EB, K_fem2d_plane_stress and
            (for reference "fem3d") K_fem3d.
        reference: "fem3d" or "fem2d-plane-stress" (then c3 = 0).

    Returns:
        dict with c1, c2, c3 and the relative residuals of the model against
        the reference (and against plane stress with c3 = 0).

    Raises:
        ValueError: fewer than three points or an unknown reference.
    """
    from scipy.optimize import least_squares

    if len(rows) < 3:
        raise ValueError("the fit needs at least three grid points")
    if reference not in ("fem3d", "fem2d-plane-stress"):
        raise ValueError(f"reference must be 'fem3d' or 'fem2d-plane-stress', got {reference!r}")
    x = np.array([r["t_over_R"] for r in rows])
    w = np.sqrt([r["web_mm"] * r["notch_radius_mm"] for r in rows]) / sheet_thickness_mm
    keb = np.array([r["K_EB"] for r in rows])
    k2 = np.array([r["K_fem2d_plane_stress"] for r in rows])

    def res2(c):
        return keb * _model(x, w, c[0], c[1], 0.0) / k2 - 1.0

    s2 = least_squares(res2, x0=[0.4, 0.0])
    c1, c2 = (float(v) for v in s2.x)
    c3 = c4 = 0.0
    kref = k2
    if reference == "fem3d":
        kref = np.array([r["K_fem3d"] for r in rows])

        def res3(c):
            return keb * _model(x, w, c1, c2, c[0], c[1]) / kref - 1.0

        c3, c4 = (float(v) for v in least_squares(res3, x0=[0.08, 0.0]).x)
    r_ref = keb * _model(x, w, c1, c2, c3, c4) / kref - 1.0
    r_ps = res2([c1, c2])
    return {"c1": c1, "c2": c2, "c3": c3, "c4": c4, "residual_rel": r_ref.tolist(),
            "residual_rel_max": float(np.max(np.abs(r_ref))),
            "residual_rel_rms": float(np.sqrt(np.mean(r_ref**2))),
            "plane_stress_residual_rel_max": float(np.max(np.abs(r_ps))),
            "plane_stress_residual_rel_rms": float(np.sqrt(np.mean(r_ps**2)))}


def fit_correction(grid: FitGrid | None = None, *, reference: str = "fem3d",
                   path: str | Path | None = CORRECTION_PATH, processes: int = 1,
                   verbose: bool = False) -> dict:
    """Run the FEM over ``grid``, fit the correction and write the JSON.

    Args:
        grid: designs (default :class:`FitGrid`: 3 webs x 3 arms x 3 radii).
        reference: "fem3d" (3D FEM on every point) or "fem2d-plane-stress"
            (c3 = 0; fast).
        path: JSON file to write; ``None`` writes nothing.
        processes: worker processes (each grid point is independent).
        verbose: print each point as it finishes.

    Returns:
        The JSON document as a dict: model, coefficients, fit_range,
        residual_rel_max, residual_rel_rms, reference, n_points, plus the
        per-point data and the wall time of the fit.

    Raises:
        ValueError: unknown reference; DesignError: a grid point breaks the
            design rules.
    """
    if reference not in ("fem3d", "fem2d-plane-stress"):
        raise ValueError(f"reference must be 'fem3d' or 'fem2d-plane-stress', got {reference!r}")
    grid = FitGrid() if grid is None else grid
    t0 = time.perf_counter()
    jobs = [(t, a, R, grid.arm_height_clearance_mm, reference == "fem3d")
            for t, a, R in grid.points()]
    for t, a, R, c, _ in jobs:  # validate every design before the long run
        g0, mat0 = grid_geometry(t, a, R, c)
    sheet = g0.sheet_thickness_mm
    material_name = (f"{mat0.name}, E = {mat0.youngs_modulus_MPa:g} MPa, "
                     f"nu = {mat0.poisson_ratio:g}")
    rows: list[dict] = []
    if processes > 1:
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(processes, mp_context=mp.get_context("spawn")) as ex:
            for row in ex.map(_evaluate_point, jobs):
                rows.append(row)
                if verbose:
                    _print_row(row)
    else:
        for job in jobs:
            rows.append(_evaluate_point(job))
            if verbose:
                _print_row(rows[-1])
    fit = fit_coefficients(rows, reference, sheet)
    for row, r in zip(rows, fit["residual_rel"]):
        row["residual_rel"] = r
    xs = [r["t_over_R"] for r in rows]
    doc = {
        "model": MODEL,
        "coefficients": {"c1": fit["c1"], "c2": fit["c2"], "c3": fit["c3"], "c4": fit["c4"]},
        "k_eb_definition": K_EB_DEFINITION,
        "fit_range": {
            "t_over_R": [min(xs), max(xs)],
            "web_mm": [min(grid.web_mm), max(grid.web_mm)],
            "arm_mm": [min(grid.arm_mm), max(grid.arm_mm)],
            "notch_radius_mm": [min(r["notch_radius_mm"] for r in rows),
                                max(r["notch_radius_mm"] for r in rows)],
            "sheet_thickness_mm": sheet,
            "material": material_name,
        },
        "residual_rel_max": fit["residual_rel_max"],
        "residual_rel_rms": fit["residual_rel_rms"],
        "plane_stress_fit": {"c1": fit["c1"], "c2": fit["c2"], "c3": 0.0,
                             "residual_rel_max": fit["plane_stress_residual_rel_max"],
                             "residual_rel_rms": fit["plane_stress_residual_rel_rms"]},
        "reference": reference,
        "n_points": len(rows),
        "fem_error_rel_max": max(r.get("err_fem3d", r["err_fem2d"]) for r in rows),
        "wall_time_s": time.perf_counter() - t0,
        "generated_by": "tactcad.mechanics.correction_fit.fit_correction",
        "points": rows,
    }
    if path is not None:
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        Path(path).write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    return doc


def refit(path: str | Path = CORRECTION_PATH) -> dict:
    """Fit the coefficients again to the FEM points stored in ``path`` (no FEM
    run) and rewrite the file; for a change of the correction model."""
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    rows = doc["points"]
    fit = fit_coefficients(rows, doc["reference"], doc["fit_range"]["sheet_thickness_mm"])
    for row, r in zip(rows, fit["residual_rel"]):
        row["residual_rel"] = r
    doc.update(model=MODEL, residual_rel_max=fit["residual_rel_max"],
               residual_rel_rms=fit["residual_rel_rms"],
               coefficients={k: fit[k] for k in ("c1", "c2", "c3", "c4")})
    Path(path).write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    return doc


def _print_row(row: dict) -> None:
    k3 = row.get("K_fem3d", math.nan)
    print(f"t={row['web_mm']:.3g} R={row['notch_radius_mm']:.3g} a={row['arm_mm']:.3g}: "
          f"K_EB={row['K_EB']:.4g} K_2D={row['K_fem2d_plane_stress']:.4g} K_3D={k3:.4g} N/mm "
          f"({row['wall_time_s']:.1f} s)", flush=True)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m tactcad.mechanics.correction_fit [--reference R] [--processes N]``."""
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reference", default="fem3d", choices=["fem3d", "fem2d-plane-stress"])
    ap.add_argument("--processes", type=int, default=1)
    ap.add_argument("--out", default=str(CORRECTION_PATH))
    ap.add_argument("--refit", action="store_true",
                    help="refit the stored FEM points of --out, without running the FEM")
    args = ap.parse_args(argv)
    if args.refit:
        doc = refit(args.out)
        print(json.dumps({k: doc[k] for k in ("model", "coefficients", "residual_rel_max",
                                              "residual_rel_rms")}, indent=2))
        return 0
    doc = fit_correction(reference=args.reference, path=args.out, processes=args.processes,
                         verbose=True)
    print(json.dumps({k: doc[k] for k in ("model", "coefficients", "fit_range",
                                          "residual_rel_max", "residual_rel_rms", "reference",
                                          "n_points", "wall_time_s")}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
