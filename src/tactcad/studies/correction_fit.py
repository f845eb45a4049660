"""The refit of the closed-form stiffness correction to its fem3d points.

The model, its range and its JSON document are
:mod:`tactcad.mechanics.correction`'s (the closed form reads them); the
points come from the sweep (:mod:`tactcad.studies.correction_sweep`). Here the
model is fitted (least squares, relative residuals), checked by leave-one-out,
on the hold-out points and on the range-check points, and written as the
document of ``src/tactcad/data/stiffness_correction.json``.
``python -m tactcad.studies.correction_fit`` refits the stored points.

Units: mm, N/mm (K).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

from tactcad.mechanics.correction import (COEFFICIENT_NAMES, CORRECTION_FILE, N_COEFFICIENTS,
                                          Correction, FitRange, _gain_and_denominator)


@dataclass(frozen=True)
class FitData:
    """Per-point arrays of a fit (1-D, equal length).

    Attributes:
        t_over_R, width_ratio, poisson_ratio, notch_share, shear_share, arm_share,
            web_over_sheet: s, w, nu, q, p, r, v.
        K_eb: uncorrected closed-form stiffness (N/mm).
        K_ref: reference stiffness, fem3d (N/mm).
    """

    t_over_R: np.ndarray
    width_ratio: np.ndarray
    poisson_ratio: np.ndarray
    notch_share: np.ndarray
    shear_share: np.ndarray
    arm_share: np.ndarray
    web_over_sheet: np.ndarray
    K_eb: np.ndarray
    K_ref: np.ndarray

    @classmethod
    def from_points(cls, points: Sequence[Mapping[str, Any]]) -> "FitData":
        """From sweep points (keys of :func:`tactcad.studies.correction_sweep.evaluate_point`)."""
        c = {k: np.array([float(p[k]) for p in points]) for k in
             ("C_notch_bending", "C_notch_shear", "C_arm_bending", "C_arm_shear")}
        total = sum(c.values())
        t = np.array([float(p["web_mm"]) for p in points])
        R = np.array([float(p["notch_radius_mm"]) for p in points])
        b = np.array([float(p["sheet_mm"]) for p in points])
        return cls(t_over_R=t / R, width_ratio=np.sqrt(t * R) / b,
                   poisson_ratio=np.array([float(p["poisson_ratio"]) for p in points]),
                   notch_share=c["C_notch_bending"] / total,
                   shear_share=c["C_notch_shear"] / total, arm_share=c["C_arm_bending"] / total,
                   web_over_sheet=t / b, K_eb=1.0 / total,
                   K_ref=np.array([float(p["K_fem3d"]) for p in points]))

    def residuals(self, correction: Correction) -> np.ndarray:
        """K_model / K_ref - 1 per point."""
        f = correction.factor(self.t_over_R, self.width_ratio, self.poisson_ratio,
                              self.notch_share, self.shear_share, self.arm_share,
                              self.web_over_sheet)
        return self.K_eb * f / self.K_ref - 1.0


def fit_correction(data: FitData, *, fit_range: FitRange, source: str,
                   free: Sequence[str] = COEFFICIENT_NAMES) -> Correction:
    """Least-squares fit (relative residuals) of the model to reference stiffnesses.

    Args:
        data: the points (:class:`FitData`, at least as many as free coefficients).
        fit_range: the range to store with the correction.
        source: description of the reference.
        free: coefficients to fit; the others stay 0.

    Returns:
        :class:`Correction` with its largest residual.

    Raises:
        ValueError: too few points, non-positive or non-finite K, or an
            unknown coefficient name.

    Source: scipy.optimize.least_squares (trust-region reflective).
    """
    from scipy.optimize import least_squares

    if any(name not in COEFFICIENT_NAMES for name in free):
        raise ValueError(f"free coefficients must be among {COEFFICIENT_NAMES}, got {free!r}")
    n = data.K_ref.size
    if n < len(free):
        raise ValueError(f"the fit needs at least {len(free)} points, got {n}")
    if np.any(data.K_eb <= 0) or np.any(data.K_ref <= 0) or \
            not np.all(np.isfinite(data.K_eb * data.K_ref)):
        raise ValueError("stiffnesses must be finite and > 0")
    idx = [COEFFICIENT_NAMES.index(k) for k in free]
    start = np.array([0.5, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0])

    def coeffs(x):
        c = np.zeros(N_COEFFICIENTS)
        c[idx] = x
        return c

    def res(x):
        gain, den = _gain_and_denominator(coeffs(x), data.t_over_R, data.width_ratio,
                                          data.poisson_ratio, data.notch_share,
                                          data.shear_share, data.arm_share, data.web_over_sheet)
        return data.K_eb * gain / den / data.K_ref - 1.0

    sol = least_squares(res, start[idx], method="lm" if n > len(idx) else "trf")
    c = coeffs(sol.x)
    corr = Correction(coefficients=tuple(float(v) for v in c), fit_range=fit_range,
                      residual_rel=0.0, source=source)
    worst = float(np.max(np.abs(data.residuals(corr))))
    return Correction(coefficients=corr.coefficients, fit_range=fit_range, residual_rel=worst,
                      source=source)


def range_of_points(points: Sequence[Mapping[str, Any]]) -> FitRange:
    """The :class:`FitRange` spanned by sweep points."""
    def span(vals):
        return (float(min(vals)), float(max(vals)))

    t = [float(p["web_mm"]) for p in points]
    R = [float(p["notch_radius_mm"]) for p in points]
    b = [float(p["sheet_mm"]) for p in points]
    return FitRange(t_over_R=span([x / y for x, y in zip(t, R)]),
                    width_ratio=span([math.sqrt(x * y) / z for x, y, z in zip(t, R, b)]),
                    web_over_sheet=span([x / z for x, z in zip(t, b)]),
                    poisson_ratio=span([float(p["poisson_ratio"]) for p in points]),
                    web_mm=span(t), notch_radius_mm=span(R),
                    arm_mm=span([float(p["arm_mm"]) for p in points]), sheet_mm=span(b),
                    arm_over_arm_height=span([float(p["arm_mm"]) / float(p["arm_height_mm"])
                                              for p in points]))


def _stats(r: np.ndarray) -> dict:
    a = np.abs(r)
    return {"n": int(r.size), "max": float(a.max()), "mean": float(a.mean()),
            "rms": float(np.sqrt(np.mean(r * r)))}


def leave_one_out(points: Sequence[Mapping[str, Any]],
                  free: Sequence[str] = COEFFICIENT_NAMES) -> np.ndarray:
    """Relative error at each point of a fit to all the other points."""
    out = []
    for i in range(len(points)):
        rest = list(points[:i]) + list(points[i + 1:])
        c = fit_correction(FitData.from_points(rest), fit_range=FitRange(), source="loo",
                           free=free)
        out.append(float(FitData.from_points([points[i]]).residuals(c)[0]))
    return np.array(out)


def build_document(points: Sequence[Mapping[str, Any]], *, source: str | None = None,
                   free: Sequence[str] = COEFFICIENT_NAMES) -> dict:
    """Fit the points of the set "fit" (and "fit-*"), check the "holdout"
    points and the "check-*" points (fem3d points that extend the range the
    correction is stated for, e.g. to a library material's Poisson ratio),
    and return the JSON document of ``stiffness_correction.json``.

    Raises:
        ValueError: no fit points.
    """
    fit_pts = [p for p in points if str(p["set"]).startswith("fit")]
    hold_pts = [p for p in points if p["set"] == "holdout"]
    # fem3d points that extend the checked range beyond the fit's (e.g. a
    # library material's nu): not fitted, their residuals stored
    check_pts = [p for p in points if str(p["set"]).startswith("check")]
    if not fit_pts:
        raise ValueError("no fit points")
    src = source or (f"fem3d (P2 tetrahedra, half model, finest of three meshes), {len(fit_pts)} "
                     "designs of tactcad.studies.correction_sweep")
    corr = fit_correction(FitData.from_points(fit_pts),
                          fit_range=range_of_points(fit_pts + check_pts), source=src, free=free)
    r_fit = FitData.from_points(fit_pts).residuals(corr)
    doc = corr.as_json()
    doc["residual_rel_rms"] = _stats(r_fit)["rms"]
    doc["fit"] = _stats(r_fit)
    doc["leave_one_out"] = _stats(leave_one_out(fit_pts, free))
    rows = []
    for p, r in zip(fit_pts, r_fit):
        rows.append(dict(p, residual_rel=float(r)))
    if hold_pts:
        r_hold = FitData.from_points(hold_pts).residuals(corr)
        doc["holdout"] = _stats(r_hold)
        rows += [dict(p, residual_rel=float(r)) for p, r in zip(hold_pts, r_hold)]
    if check_pts:
        r_check = FitData.from_points(check_pts).residuals(corr)
        doc["range_checks"] = _stats(r_check)
        rows += [dict(p, residual_rel=float(r)) for p, r in zip(check_pts, r_check)]
    doc["fem3d_error_rel_max"] = max(float(p["err_fem3d"]) for p in points)
    doc["points"] = rows
    return doc


def refit(path: str | Path = CORRECTION_FILE) -> dict:
    """Fit the model again to the points stored in ``path`` (no FEM run) and
    rewrite the file; for a change of the model."""
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    new = build_document([{k: v for k, v in p.items() if k != "residual_rel"}
                          for p in doc["points"]], source=doc.get("source"))
    if "arm_aspect_extrapolation" in doc:  # measured past the fit, not refitted: kept as is
        new["arm_aspect_extrapolation"] = doc["arm_aspect_extrapolation"]
    Path(path).write_text(json.dumps(new, indent=2) + "\n", encoding="utf-8")
    return new


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m tactcad.studies.correction_fit [--path F]``: refit the stored points."""
    import argparse

    ap = argparse.ArgumentParser(description="refit the closed-form correction to its stored "
                                             "fem3d points")
    ap.add_argument("--path", default=str(CORRECTION_FILE))
    args = ap.parse_args(argv)
    doc = refit(args.path)
    print(json.dumps({k: doc[k] for k in ("model", "coefficients", "fit", "holdout")
                      if k in doc}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
