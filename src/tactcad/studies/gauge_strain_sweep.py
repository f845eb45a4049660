"""The fem3d sweep and fit behind the gauge-strain correction of the closed form.

For each design of a scrambled Sobol set, fem3d (three meshes) gives its own
eps_xx on the flat top face; per grid (length L_g, width W, centred over the
notch at mid-width) its average (:func:`tactcad.mechanics.fem.fields.face_rectangle_average`,
Richardson error over the three meshes) is set against the Euler-Bernoulli
grid average of :func:`tactcad.mechanics.readout_chain.beam_face_mean_strain_per_N`,
and fem3d's point strain at the notch centre against EB's. The model of
:mod:`tactcad.mechanics.gauge_strain` is fitted to these ratios
(scipy.optimize.least_squares, relative residuals) and written with its
range, residuals, a hold-out set (another Sobol seed) and the points to
``src/tactcad/data/gauge_strain_correction.json``.

Domain (the gauge designs of the element domain of
:mod:`tactcad.studies.correction_sweep`, with its grid rule for the other
dimensions): web t 0.1-0.5 mm, notch radius R from t to 8 t (at most 2 mm),
arm 4-20 mm, sheet b 1.5-6 mm (b/t about 3-60), nu 0.27-0.342, and a second
Sobol set on the thin sheets a design searches, b 0.5-1.5 mm (:data:`THIN_SHEET_MM`,
b/t down to 1, the width ratio sqrt(t R) / b up to about 1); grids
L_g 0.3, 0.6, 1.0, 1.5 mm (<= arm), W 0.5, 1.0, 2.0 mm (<= b), fitted where
the grid stays over the notch, L_g / (2 R) <= :data:`XI_MAX` (the notch's
diameter: the grid of a notch as long as the gauge is inside).

The fit set adds two designs at each end of the Poisson range
(:func:`poisson_edge_designs`).

Run: ``python -m tactcad.studies.gauge_strain_sweep [n_fit n_holdout]``
(about 10 s of fem3d per design on one core).

Units: mm, N, MPa, s.
"""

from __future__ import annotations

import json
import math
import sys
import time
from typing import Sequence

import numpy as np

from tactcad.mechanics.gauge_strain import (COEFFICIENT_NAMES, GAUGE_STRAIN_FILE, MODEL,
                                            RANGE_KEYS, StrainCorrection)

WEB_MM = (0.1, 0.5)
R_OVER_T = (1.0, 8.0)
NOTCH_RADIUS_MAX_MM = 2.0
ARM_MM = (4.0, 20.0)
SHEET_MM = (1.5, 6.0)
#: The thin sheets of the second set: stock sheets a wire-cut design takes (0.5 mm the process's least).
THIN_SHEET_MM = (0.5, 1.5)
POISSON = (0.27, 0.342)
GRID_LENGTHS_MM = (0.3, 0.6, 1.0, 1.5)
GRID_WIDTHS_MM = (0.5, 1.0, 2.0)
#: Largest grid length over notch diameter fitted.
XI_MAX = 1.0
FIT_SEED, HOLDOUT_SEED = 1, 2
THIN_FIT_SEED, THIN_HOLDOUT_SEED = 3, 4


def _log_between(lo: float, hi: float, u: float) -> float:
    return float(lo * (hi / lo) ** u)


def sobol_designs(n: int, seed: int, sheet_mm: tuple[float, float] = SHEET_MM
                  ) -> list[tuple[float, float, float, float, float]]:
    """``n`` designs (t, R, a, b, nu) of the domain (module doc) with sheets in
    ``sheet_mm``, scrambled Sobol."""
    from scipy.stats import qmc

    u = qmc.Sobol(d=5, scramble=True, seed=seed).random_base2(max(1, math.ceil(math.log2(n))))
    out = []
    for row in u[:n]:
        t = _log_between(*WEB_MM, row[0])
        R = min(NOTCH_RADIUS_MAX_MM, t * _log_between(*R_OVER_T, row[1]))
        out.append((t, R, _log_between(*ARM_MM, row[2]), _log_between(*sheet_mm, row[3]),
                    POISSON[0] + (POISSON[1] - POISSON[0]) * float(row[4])))
    return out


def poisson_edge_designs() -> list[tuple[float, float, float, float, float]]:
    """Two designs at each end of the Poisson range (the library's 0.27 and Ti-6Al-4V's
    0.342), so the fitted range holds both: webs 0.15 and 0.25 mm at R = 2 t, arms
    6 and 12 mm, sheets 2 and 3 mm."""
    return [(t, 2 * t, a, b, nu) for nu in POISSON
            for t, a, b in ((0.15, 6.0, 2.0), (0.25, 12.0, 3.0))]


def evaluate_point(design: Sequence[float], label: str) -> dict:
    """fem3d's point and grid strains at one design (t, R, a, b, nu) against EB's.

    Raises:
        DesignError: the design breaks a design rule.
    """
    from tactcad.mechanics.fem.fem2d import REFINEMENT_RATIO
    from tactcad.mechanics.fem.fem3d import fem3d_convergence
    from tactcad.mechanics.fem.fields import face_rectangle_average
    from tactcad.mechanics.readout_chain import (beam_face_mean_strain_per_N,
                                                 beam_surface_strain_per_N, grid_span_mm)
    from tactcad.mechanics.richardson import richardson
    from tactcad.studies.correction_sweep import grid_geometry

    t, R, a, b, nu = (float(v) for v in design)
    g, m = grid_geometry(t, a, R, sheet_mm=b, poisson_ratio=nu)
    t0 = time.perf_counter()
    conv = fem3d_convergence(g, m)
    fin = conv.finest
    rec = {"set": label, "web_mm": t, "notch_radius_mm": R, "arm_mm": a, "sheet_mm": b,
           "poisson_ratio": nu, "point_fem3d": fin.gauge_strain / fin.force_N,
           "point_err": conv.gauge_strain.error_rel,
           "point_eb": float(beam_surface_strain_per_N(g, m, g.hinge_x_mm)), "grids": []}
    for L in GRID_LENGTHS_MM:
        for W in GRID_WIDTHS_MM:
            if W > b or L > a:
                continue
            span = grid_span_mm(g, L)
            vals = [face_rectangle_average(f, span, (b / 2 - W / 2, b / 2 + W / 2))
                    for f in conv.top_face_strains]
            rec["grids"].append({"L": L, "W": W, "fem3d": vals[-1],
                                 "err": richardson(vals, REFINEMENT_RATIO).error_rel,
                                 "eb": beam_face_mean_strain_per_N(g, m, L)})
    rec["wall_time_s"] = time.perf_counter() - t0
    return rec


def samples(points: list[dict], xi_max: float = XI_MAX) -> tuple[list[dict], np.ndarray]:
    """(coordinates, fem3d / EB) of every point's centre strain and of its grids with
    L_g / (2 R) <= ``xi_max``."""
    coords, ratio = [], []
    for p in points:
        t, R, b, nu = p["web_mm"], p["notch_radius_mm"], p["sheet_mm"], p["poisson_ratio"]
        base = {"t_over_R": t / R, "width_ratio": math.sqrt(t * R) / b, "poisson_ratio": nu,
                "sheet_over_web": b / t}
        coords.append({**base, "grid_over_notch": 0.0, "grid_width_over_sheet": 0.0})
        ratio.append(p["point_fem3d"] / p["point_eb"])
        for gr in p["grids"]:
            if gr["L"] / (2 * R) <= xi_max + 1e-12:
                coords.append({**base, "grid_over_notch": gr["L"] / (2 * R),
                               "grid_width_over_sheet": min(gr["W"], b) / b})
                ratio.append(gr["fem3d"] / gr["eb"])
    return coords, np.array(ratio)


def _residuals(corr: StrainCorrection, coords: list[dict], ratio: np.ndarray) -> np.ndarray:
    model = np.array([corr.factor(**{k: v for k, v in c.items() if k != "sheet_over_web"})
                      for c in coords])
    return model / ratio - 1.0


def _stats(r: np.ndarray) -> dict:
    return {"n": int(r.size), "max": float(np.abs(r).max()),
            "rms": float(np.sqrt(np.mean(r * r)))}


def fit(points: list[dict]) -> dict:
    """The JSON document: coefficients fitted to the ``fit`` points, range, residuals
    of fit and hold-out, and the points."""
    from scipy.optimize import least_squares

    fit_pts = [p for p in points if p["set"] == "fit"]
    coords, ratio = samples(fit_pts)
    rng = {k: [min(c[k] for c in coords), max(c[k] for c in coords)] for k in RANGE_KEYS}
    rng["grid_over_notch"] = [0.0, XI_MAX]

    def corr_of(c):
        return StrainCorrection(tuple(c), rng, 0.0, "")

    sol = least_squares(lambda c: _residuals(corr_of(c), coords, ratio),
                        np.zeros(len(COEFFICIENT_NAMES)))
    corr = corr_of(sol.x)
    hold = [p for p in points if p["set"] == "holdout"]
    doc = {"model": MODEL, "coefficients": dict(zip(COEFFICIENT_NAMES, map(float, sol.x))),
           "fit_range": rng, "fit": _stats(_residuals(corr, coords, ratio)),
           "source": (f"fem3d (P2 tetrahedra, half model, finest of three meshes) grid and "
                      f"centre strains on the top face against Euler-Bernoulli: {len(fit_pts)} "
                      f"designs of tactcad.studies.gauge_strain_sweep (Sobol seed {FIT_SEED} "
                      f"on sheets {SHEET_MM[0]:g}-{SHEET_MM[1]:g} mm, seed {THIN_FIT_SEED} on "
                      f"sheets {THIN_SHEET_MM[0]:g}-{THIN_SHEET_MM[1]:g} mm, and the Poisson "
                      f"range's ends), grids L_g/(2R) <= {XI_MAX}; hold-out: Sobol seeds "
                      f"{HOLDOUT_SEED} and {THIN_HOLDOUT_SEED}"),
           "fem3d_error_rel_max": max([p["point_err"] for p in points]
                                      + [g["err"] for p in points for g in p["grids"]]),
           "points": points}
    if hold:
        doc["holdout"] = _stats(_residuals(corr, *samples(hold)))
    return doc


def _design_key(label: str, design: Sequence[float]) -> tuple:
    return (label,) + tuple(round(float(v), 9) for v in design)


def _point_key(p: dict) -> tuple:
    return _design_key(p["set"], (p["web_mm"], p["notch_radius_mm"], p["arm_mm"], p["sheet_mm"],
                                  p["poisson_ratio"]))


def sweep_designs(n_fit: int, n_hold: int) -> list[tuple[str, list]]:
    """(set, designs) of the sweep: each Sobol set of the thick and of the thin sheets
    (the thin ones half as many) and the Poisson range's ends."""
    n_thin, n_thin_hold = max(1, (2 * n_fit) // 3), max(1, (3 * n_hold) // 4)
    return [("fit", sobol_designs(n_fit, FIT_SEED) + poisson_edge_designs()
             + sobol_designs(n_thin, THIN_FIT_SEED, THIN_SHEET_MM)),
            ("holdout", sobol_designs(n_hold, HOLDOUT_SEED)
             + sobol_designs(n_thin_hold, THIN_HOLDOUT_SEED, THIN_SHEET_MM))]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the sweep (``n_fit`` and ``n_holdout`` designs of the thick sheets, default 24
    and 8, and :func:`sweep_designs`'s thin ones), fit, write. A design whose point the
    file already holds is read from it, not solved again."""
    from tactcad.errors import DesignError

    args = list(sys.argv[1:] if argv is None else argv)
    n_fit, n_hold = (int(args[0]), int(args[1])) if len(args) == 2 else (24, 8)
    known = {}
    if GAUGE_STRAIN_FILE.is_file():
        known = {_point_key(p): p
                 for p in json.loads(GAUGE_STRAIN_FILE.read_text(encoding="utf-8"))["points"]}
    points = []
    for label, designs in sweep_designs(n_fit, n_hold):
        for design in designs:
            key = _design_key(label, design)
            if key in known:
                points.append(known[key])
                continue
            try:
                points.append(evaluate_point(design, label))
                print(f"solved {label} {tuple(round(v, 4) for v in design)}", file=sys.stderr)
            except DesignError as exc:  # a design rule the grid rule cannot meet
                print(f"skipped {design}: {exc}", file=sys.stderr)
    GAUGE_STRAIN_FILE.write_text(json.dumps(fit(points), indent=1) + "\n", encoding="utf-8")
    print(f"wrote {GAUGE_STRAIN_FILE}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
