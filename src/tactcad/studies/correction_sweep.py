"""The fem3d sweep behind the closed-form stiffness correction.

Runs fem3d (three meshes, Richardson error) over designs that cover the
design domain and stores, per design, the fem3d stiffness and the four
Euler-Bernoulli compliance terms of the closed form; :mod:`.correction`
fits its model to these points and writes
``src/tactcad/data/stiffness_correction.json``.

Domain (mm): web t 0.05-1, notch radius R from t to 2 (t/R 0.025-1), arm
a 2-20, sheet b 0.5-10, Poisson ratio 0.27-0.34 (the material library:
17-4PH 0.27, CuBe 0.30, Al 6061-T6/7075-T6 0.33; Ti-6Al-4V's 0.342 is
covered by fem3d checks at that ratio, set "check-nu"). Young's
modulus scales out of K (linear elasticity, displacement-free loading), so
one E serves every material.

Grid rule (the dimensions the domain does not fix, chosen as a designer of
the wider domain would; the default design's values at t = 0.25, R = 0.5,
a = 8, b = 3):

* arm height h_a = max(2, t + R + 0.5, a / 4), at most 5 mm: the default
  2 mm, raised so the notch opens 0.5 mm below the arm underside and so a
  long arm stays at a / h_a <= 4 (the default's 8 mm / 2 mm; arm bending then
  stays a small share of the hinge compliance);
* tip width min(2, a / 2): the 2 mm contact face, narrowed on short arms so
  the tip-root fillet clears the notch (a >= w / 2 + r_corner + R + 0.5);
* tip height 1.5, base height 10, inside corner radius 0.2 (default);
* overall length a + R + w / 2 + 12.5: the default's 12.5 mm clamped base
  for every arm (bolt pattern and clamp plate unchanged);
* one column (two elements), pitch max(6, b + 1) so the spacer fits and the
  mounting bolts clear the bases of 2 mm arms, wire
  0.02 mm with no spark gap so R = t stays cuttable.

Designs are drawn by scrambled Sobol sampling (scipy.stats.qmc) in
(log t, log(R / t) scaled to the room up to R_max, log a scaled to the room
above a_min(R), log b, nu), where R_max = 2 and a_min keeps the tip root
clear of the notch; the fit set and the hold-out set use different seeds.
Corner designs (t, R, a, b at their bounds, nu at both ends) join the fit set.

Sources: scipy.stats.qmc.Sobol (Owen-scrambled Sobol sequence); fem3d of
:mod:`tactcad.mechanics.fem.fem3d`; closed form of
:mod:`tactcad.mechanics.closed_form`.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Iterable, Sequence


from tactcad.design.array_plan import (ElementGeometry, Material, default_design_data, plan_from_dict,
                      with_overrides)
from tactcad.design.readout_section import DEFAULTS
from tactcad.mechanics.closed_form import closed_form_compliance
from tactcad.mechanics.correction import CORRECTION_FILE
from tactcad.studies.correction_fit import build_document
from tactcad.mechanics.fem.fem3d import fem3d_convergence

#: Domain of the sweep (mm; Poisson ratio dimensionless).
WEB_MM = (0.05, 1.0)
NOTCH_RADIUS_MAX_MM = 2.0
ARM_MM = (2.0, 20.0)
SHEET_MM = (0.5, 10.0)
POISSON = (0.27, 0.34)

#: Young's modulus of the sweep (MPa); K scales with E.
E_SWEEP_MPA = 69000.0

#: Clamped base length behind the notch (mm), as in the default design.
BASE_LENGTH_MM = 12.5
TIP_WIDTH_MAX_MM = 2.0
CORNER_RADIUS_MM = 0.2
NOTCH_CLEARANCE_MM = 0.5

#: Where the per-point results are appended (one JSON object per line).
POINTS_FILE = Path("exports/reports/correction_points.jsonl")


def tip_width_mm(arm_mm: float) -> float:
    """Contact-face width of the grid rule (mm)."""
    return min(TIP_WIDTH_MAX_MM, arm_mm / 2.0)


def arm_height_mm(web_mm: float, notch_radius_mm: float, arm_mm: float) -> float:
    """Arm height of the grid rule: max(2, t + R + 0.5, a / 4), at most 5 mm."""
    return min(5.0, max(2.0, web_mm + notch_radius_mm + NOTCH_CLEARANCE_MM, arm_mm / 4.0))


def arm_min_mm(notch_radius_mm: float) -> float:
    """Shortest arm (mm) whose tip-root fillet clears the notch by 0.5 mm
    (a >= w(a) / 2 + r_corner + R + 0.5 with the grid rule's tip width)."""
    room = notch_radius_mm + CORNER_RADIUS_MM + NOTCH_CLEARANCE_MM
    a = room + TIP_WIDTH_MAX_MM / 2.0
    if a < 2.0 * TIP_WIDTH_MAX_MM:  # tip narrowed to a / 2: a >= a / 4 + room
        a = room * 4.0 / 3.0
    return max(ARM_MM[0], a)


def grid_geometry(web_mm: float, arm_mm: float, notch_radius_mm: float, *,
                  sheet_mm: float = 3.0, poisson_ratio: float = 0.33,
                  youngs_modulus_MPa: float = E_SWEEP_MPA) -> tuple[ElementGeometry, Material]:
    """A validated design of the grid rule (module docstring) and its material.

    Args:
        web_mm: web thickness t (mm). arm_mm: lever a (mm).
        notch_radius_mm: notch radius R (mm). sheet_mm: sheet thickness b (mm).
        poisson_ratio: nu. youngs_modulus_MPa: E (MPa).

    Returns:
        (geometry of element 1 as cut, without its gauge: the correction and the strain
        factors are of the bare element's closed form, material) of the validated plan.

    Raises:
        DesignError: the combination breaks a design rule (field named).
    """
    t, a, R, b = float(web_mm), float(arm_mm), float(notch_radius_mm), float(sheet_mm)
    w = tip_width_mm(a)
    data = default_design_data()
    over = {"element.web_thickness_mm": t, "element.notch_radius_mm": R,
            "element.arm_height_mm": round(arm_height_mm(t, R, a), 9),
            "element.tip_width_mm": w,
            "element.overall_length_mm": round(a + R + w / 2 + BASE_LENGTH_MM, 9),
            "element.inside_corner_radius_mm": CORNER_RADIUS_MM,
            "arms.lengths_mm": [a, a], "array.columns": 1, "sheet.thickness_mm": b,
            "array.pitch_mm": max(6.0, b + 1.0), "edm.wire_diameter_mm": 0.02,
            "edm.spark_gap_mm": 0.0, "material.poisson_ratio": float(poisson_ratio),
            "material.youngs_modulus_MPa": float(youngs_modulus_MPa),
            # the bare element carries no gauge; a grid that fits the sheet passes its rule
            "readout.grid_width_mm": min(b, DEFAULTS["grid_width_mm"][0])}
    plan = plan_from_dict(with_overrides(data, over), source="<correction grid>")
    return plan.element(1).geometry.bare(), plan.material


def _log_between(lo: float, hi: float, u: float) -> float:
    return float(lo * (hi / lo) ** u)


def design_from_unit(u: Sequence[float]) -> tuple[float, float, float, float, float]:
    """Map a point of the unit 5-cube to (t, R, a, b, nu) in the domain."""
    t = _log_between(*WEB_MM, u[0])
    R = _log_between(t, NOTCH_RADIUS_MAX_MM, u[1])
    a = _log_between(arm_min_mm(R), ARM_MM[1], u[2])
    b = _log_between(*SHEET_MM, u[3])
    nu = POISSON[0] + (POISSON[1] - POISSON[0]) * float(u[4])
    return (t, R, a, b, nu)


def sobol_designs(n: int, seed: int) -> list[tuple[float, float, float, float, float]]:
    """``n`` designs (t, R, a, b, nu) from a scrambled Sobol sequence."""
    from scipy.stats import qmc

    m = max(1, math.ceil(math.log2(max(n, 1))))  # Sobol balance needs a power of two
    u = qmc.Sobol(d=5, scramble=True, seed=seed).random_base2(m)[:n]
    return [design_from_unit(row) for row in u]


def corner_designs() -> list[tuple[float, float, float, float, float]]:
    """Domain corners: t, R/t, a, b at their bounds, nu alternating."""
    out = []
    k = 0
    for ut in (0.0, 1.0):
        for us in (0.0, 1.0):
            for ua in (0.0, 1.0):
                for ub in (0.0, 1.0):
                    if ut == 1.0 and us == 0.0:
                        continue  # t = R = 1 mm repeats for every R
                    out.append(design_from_unit((ut, us, ua, ub, float(k % 2))))
                    k += 1
    return out


def evaluate_point(design: Sequence[float], label: str = "fit") -> dict:
    """fem3d and the closed form's compliance terms at one design (t, R, a, b, nu).

    Returns:
        A JSON-ready dict: the design, the grid rule's other dimensions, the
        closed form's compliance terms (mm/N), K_fem3d (finest mesh),
        K_fem3d_extrapolated, the Richardson error, wall time (s), unknowns
        and peak memory (MiB).
    """
    t, R, a, b, nu = (float(v) for v in design)
    g, mat = grid_geometry(t, a, R, sheet_mm=b, poisson_ratio=nu)
    t0 = time.perf_counter()
    conv = fem3d_convergence(g, mat)
    parts = closed_form_compliance(t, R, a, arm_height_mm=g.arm_height_mm,
                                   tip_width_mm=g.tip_width_mm, tip_height_mm=g.tip_height_mm,
                                   E=mat.youngs_modulus_MPa, nu=nu, b=b)
    return {"set": label, "web_mm": t, "notch_radius_mm": R, "arm_mm": a,
            "sheet_mm": b, "poisson_ratio": nu, "youngs_modulus_MPa": mat.youngs_modulus_MPa,
            "arm_height_mm": g.arm_height_mm, "tip_width_mm": g.tip_width_mm,
            "tip_height_mm": g.tip_height_mm,
            "C_notch_bending": float(parts.notch_bending), "C_notch_shear": float(parts.notch_shear),
            "C_arm_bending": float(parts.arm_bending), "C_arm_shear": float(parts.arm_shear),
            "K_fem3d": conv.finest.stiffness_N_per_mm,
            "K_fem3d_extrapolated": conv.stiffness.extrapolated,
            "err_fem3d": conv.stiffness.error_rel, "n_dofs": conv.finest.n_dofs,
            "peak_rss_mib": conv.peak_rss_mib, "wall_time_s": time.perf_counter() - t0}


def read_points(path: str | Path = POINTS_FILE) -> list[dict]:
    """The points stored so far (empty if the file does not exist)."""
    p = Path(path)
    if not p.exists():
        return []
    return [json.loads(line) for line in p.read_text(encoding="utf-8").splitlines() if line]


def run(designs: Iterable[tuple[Sequence[float], str]], path: str | Path = POINTS_FILE,
        verbose: bool = True) -> list[dict]:
    """Evaluate every (design, label) not yet in ``path`` and append it there.

    Resumable: a design already stored (same t, R, a, b, nu) is skipped.
    """
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    done = {_key(r) for r in read_points(p)}
    rows = []
    for design, label in designs:
        if _key(dict(zip(("web_mm", "notch_radius_mm", "arm_mm", "sheet_mm", "poisson_ratio"),
                         design))) in done:
            continue
        row = evaluate_point(design, label)
        with open(p, "a", encoding="utf-8") as fh:
            fh.write(json.dumps(row) + "\n")
        rows.append(row)
        if verbose:
            print(f"{label:8s} t={row['web_mm']:.4g} R={row['notch_radius_mm']:.4g} "
                  f"a={row['arm_mm']:.4g} b={row['sheet_mm']:.4g} nu={row['poisson_ratio']:.3f}: "
                  f"K_3D={row['K_fem3d']:.5g} N/mm (Richardson {100 * row['err_fem3d']:.3f} %), "
                  f"{row['n_dofs']} dofs, {row['wall_time_s']:.1f} s", flush=True)
    return rows


def _key(row: dict) -> tuple:
    return tuple(round(float(row[k]), 9) for k in
                 ("web_mm", "notch_radius_mm", "arm_mm", "sheet_mm", "poisson_ratio"))


def earlier_points(path: str | Path = CORRECTION_FILE) -> list[dict]:
    """Points of earlier grids stored in the correction file (sets other than
    "fit" and "holdout", e.g. the 3 mm aluminium grid of the first fit), so a
    new sweep keeps them."""
    p = Path(path)
    if not p.exists():
        return []
    doc = json.loads(p.read_text(encoding="utf-8"))
    return [{k: v for k, v in q.items() if k != "residual_rel"} for q in doc.get("points", [])
            if q.get("set") not in ("fit", "holdout")]


def plan_designs(n_fit: int, n_holdout: int) -> list[tuple[tuple, str]]:
    """Corners and ``n_fit`` Sobol designs for the fit, ``n_holdout`` Sobol
    designs (another seed) for the hold-out, interleaved so that a run
    stopped early still spans the domain with both sets."""
    sets = [[(d, "fit") for d in sobol_designs(n_fit, seed=1)],
            [(d, "fit") for d in corner_designs()],
            [(d, "holdout") for d in sobol_designs(n_holdout, seed=2)]]
    total = sum(len(s) for s in sets)
    out: list[tuple[tuple, str]] = []
    taken = [0, 0, 0]
    while len(out) < total:  # take from the set furthest behind its share
        k = min((i for i in range(3) if taken[i] < len(sets[i])),
                key=lambda i: taken[i] / len(sets[i]))
        out.append(sets[k][taken[k]])
        taken[k] += 1
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m tactcad.studies.correction_sweep [--fit N] [--holdout N] [--points F]``.

    Runs the sweep (resumable) and writes the fitted correction.
    """
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fit", type=int, default=64, help="Sobol designs in the fit set")
    ap.add_argument("--holdout", type=int, default=16, help="Sobol designs held out")
    ap.add_argument("--points", default=str(POINTS_FILE))
    ap.add_argument("--out", default=str(CORRECTION_FILE))
    ap.add_argument("--no-run", action="store_true", help="fit the stored points only")
    args = ap.parse_args(argv)
    if not args.no_run:
        run(plan_designs(args.fit, args.holdout), args.points)
    doc = build_document(read_points(args.points) + earlier_points(args.out))
    Path(args.out).write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(json.dumps({k: doc[k] for k in ("model", "coefficients", "fit_range", "residual_rel_max",
                                          "residual_rel_rms", "holdout")}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
