"""Models of paper Table 2 (48 measured deflection ratios R) and their honest scores.

Each model predicts R for a (measuring element, sample) row. Models without a
free parameter are scored on all 48 rows. A model with a fitted parameter is
scored only on rows its fit did not see: leave-one-sample-out (8 folds of 6
rows) and leave-one-element-out (6 folds of 8 rows); each row is predicted
exactly once per scheme. Fits minimise the relative residual
(R_pred − R_meas)/R_meas with ``scipy.optimize.least_squares``.

Score per row: relative error |R_pred − R_meas|/R_meas; a model's record
gives the median and the maximum over its scored rows.

Models (K from paper Table 1, K_r = 80.38 N/mm unless fitted):

* ``eq2``: eq. 2, R = (K_r + K_obj)/(K_m + K_obj).
* ``coupled-halfspace``: the evaluation rig with the sample as an elastic
  half-space (ν = 0.5) coupling all ten tips (:mod:`.evaluation`); element 5
  (no Table 1 entry) gets the ladder's stiffness of its design geometry.
* ``eq2-effective-K_r``: eq. 2 with the reference stiffness K_r fitted.
* ``eq2-reference-gain``: R = g (K_r + K_obj)/(K_m + K_obj): a wrong gain of
  the reference element's signal scales every R by g.
* ``eq2-sample-scale``: eq. 2 with the sample stiffness s K_obj (the rig's
  sample stiffer or softer than on the indenter rig), s fitted.
* ``coupled-layer-fitted-thickness``: the coupled rig with the sample as a
  layer on a rigid base, thickness picked from a grid on the training rows.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.optimize import least_squares

from tactcad.errors import DesignError
from tactcad.paper import data as paper_data
from tactcad.mechanics import evaluation as ev

LAYER_THICKNESS_GRID_MM = (1.0, 1.5, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0)


@dataclass(frozen=True, eq=False)
class Rows:
    """Table 2 as arrays, shape (48,): element, K_m (N/mm), K_obj (N/mm), measured R."""

    element: np.ndarray
    k_m: np.ndarray
    k_obj: np.ndarray
    r: np.ndarray

    @classmethod
    def table2(cls) -> "Rows":
        t = paper_data.table2()
        return cls(np.array([x.element for x in t]), np.array([x.K_m_N_per_mm for x in t]),
                   np.array([x.K_obj_N_per_mm for x in t]), np.array([x.R for x in t]))


def eq2(k_m, k_r, k_obj):
    """Paper eq. 2, R = (K_r + K_obj)/(K_m + K_obj), broadcasting (N/mm in, dimensionless out)."""
    return (k_r + k_obj) / (k_m + k_obj)


@dataclass(frozen=True)
class FittedModel:
    """A model with named parameters: ``predict(params, rows, index)`` -> R at rows[index].

    Attributes:
        name: model name.
        parameters: parameter names.
        start: starting values for the fit.
        predict: prediction function.
        grid: if given, the fit picks the best grid value (one parameter) instead
            of a continuous least-squares fit.
    """

    name: str
    parameters: tuple[str, ...]
    start: tuple[float, ...]
    predict: Callable[[np.ndarray, Rows, np.ndarray], np.ndarray]
    grid: tuple[float, ...] | None = None

    def fit(self, rows: Rows, index: np.ndarray) -> np.ndarray:
        """Parameter values fitted on rows[index] only."""
        def residual(p):
            return (self.predict(p, rows, index) - rows.r[index]) / rows.r[index]

        if self.grid is not None:
            costs = [float(np.sum(residual(np.array([g])) ** 2)) for g in self.grid]
            return np.array([self.grid[int(np.argmin(costs))]])
        return least_squares(residual, np.array(self.start, float)).x


def relative_errors(predicted: np.ndarray, measured: np.ndarray) -> np.ndarray:
    return np.abs(predicted - measured) / measured


def cross_validate(model: FittedModel, rows: Rows, groups: np.ndarray):
    """Held-out predictions: for each group value, fit on the other rows, predict this group.

    Returns:
        (predicted R for every row, shape (48,), fitted parameters per fold, shape (folds, p)).
    """
    predicted = np.full(rows.r.shape, np.nan)
    folds = []
    for g in np.unique(groups):
        test = np.flatnonzero(groups == g)
        train = np.flatnonzero(groups != g)
        params = model.fit(rows, train)
        predicted[test] = model.predict(params, rows, test)
        folds.append(params)
    return predicted, np.array(folds)


def _record(name: str, predicted: np.ndarray, rows: Rows, fitted: dict, held_out: bool,
            scheme: str, extra: dict | None = None) -> dict:
    err = relative_errors(predicted, rows.r)
    rec = {"name": name, "fitted_parameters": fitted,
           "median_rel_error": float(np.median(err)), "max_rel_error": float(np.max(err)),
           "held_out": held_out, "scored_rows": int(err.size), "scheme": scheme,
           "predicted_R": [float(v) for v in predicted]}
    if extra:
        rec.update(extra)
    return rec


def paper_stiffness_by_element(plan, model: str = "closed-form") -> dict[int, float]:
    """Element stiffness (N/mm): Table 1 where measured, the ladder's estimate for the rest."""
    measured = {r.element: r.stiffness_N_per_mm for r in paper_data.table1()}
    predicted = ev.ladder_stiffness_by_element(plan, model)
    return {n: measured.get(n, k) for n, k in predicted.items()}


class CoupledPredictor:
    """R of Table 2 rows from the coupled rig, the unit compliance cached per sample spec."""

    def __init__(self, plan, stiffness: dict[int, float]):
        """Raises DesignError: the plan lacks an element of Table 2 or the reference element 8."""
        needed = {r.element for r in paper_data.table2()} | {paper_data.REFERENCE_ELEMENT}
        have = {slot.number for slot in plan.slots}
        if not needed <= have:
            raise DesignError("array", f"{len(have)} elements",
                              f"elements {sorted(needed)} present (Table 2 needs them)")
        self.elements = ev.elements_from_plan(plan, stiffness)
        self._unit: dict[tuple, np.ndarray] = {}

    def ratios(self, rows: Rows, index: np.ndarray, spec: ev.SampleSpec) -> np.ndarray:
        key = (spec.coupling, spec.poisson_ratio, spec.layer_thickness_mm)
        if key not in self._unit:
            self._unit[key] = ev.unit_punch_compliance(self.elements, spec)
        numbers = [e.number for e in self.elements]
        out = np.empty(len(index))
        by_sample: dict[float, ev.RigResult] = {}
        for n, i in enumerate(index):
            k_obj = float(rows.k_obj[i])
            if k_obj not in by_sample:
                by_sample[k_obj] = ev.simulate_rig(
                    self.elements, k_obj, spec, loads_N=[ev.DEAD_WEIGHT_N],
                    reference=paper_data.REFERENCE_ELEMENT, unit_compliance=self._unit[key])
            out[n] = by_sample[k_obj].ratio[0, numbers.index(int(rows.element[i]))]
        return out


def fitted_models(coupled: CoupledPredictor | None,
                  k_r: float = paper_data.K_R_N_PER_MM) -> list[FittedModel]:
    """The one-parameter models scored by cross-validation (the coupled one only with ``coupled``)."""
    def layer(p, rows, idx):
        return coupled.ratios(rows, idx, ev.SampleSpec("layer", thickness_mm=float(p[0])))

    models = [
        FittedModel("eq2-effective-K_r", ("K_r_N_per_mm",), (k_r,),
                    lambda p, rows, idx: eq2(rows.k_m[idx], p[0], rows.k_obj[idx])),
        FittedModel("eq2-reference-gain", ("reference_gain",), (1.0,),
                    lambda p, rows, idx: p[0] * eq2(rows.k_m[idx], k_r, rows.k_obj[idx])),
        FittedModel("eq2-sample-scale", ("K_obj_scale",), (1.0,),
                    lambda p, rows, idx: eq2(rows.k_m[idx], k_r, p[0] * rows.k_obj[idx])),
    ]
    if coupled is not None:
        models.append(FittedModel("coupled-layer-fitted-thickness", ("thickness_mm",), (5.0,), layer,
                                  grid=LAYER_THICKNESS_GRID_MM))
    return models


def table2_report(plan, model: str = "closed-form") -> dict:
    """Every model's error against Table 2's 48 measured R (see module docstring).

    Args:
        plan: design plan (tip positions and faces for the coupled models;
            element 5's stiffness from the ladder).
        model: ladder level for element 5's stiffness.

    The coupled models need the paper's element numbers at the plan's tip
    positions; a plan without them skips those models (``skipped_models``).

    Returns:
        {"models": [record, ...], "rows": 48, ...}; each record has name,
        fitted_parameters, median_rel_error, max_rel_error, held_out, and
        scheme ("none", "leave-one-sample-out", "leave-one-element-out") and
        predicted_R (the scored prediction of each row, table order); "table2"
        lists the measured rows.
    """
    rows = Rows.table2()
    everything = np.arange(rows.r.size)
    k_r = paper_data.K_R_N_PER_MM
    records = [_record("eq2", eq2(rows.k_m, k_r, rows.k_obj), rows, {}, True, "none")]
    skipped = []
    try:
        coupled = CoupledPredictor(plan, paper_stiffness_by_element(plan, model))
    except DesignError as exc:  # the coupled models need the paper's element numbers
        coupled = None
        skipped = [{"name": n, "reason": str(exc)}
                   for n in ("coupled-halfspace", "coupled-layer-fitted-thickness")]
    if coupled is not None:
        records.append(_record(
            "coupled-halfspace", coupled.ratios(rows, everything, ev.SampleSpec("halfspace")),
            rows, {}, True, "none", {"poisson_ratio": ev.DEFAULT_POISSON_RATIO}))
    schemes = {"leave-one-sample-out": rows.k_obj, "leave-one-element-out": rows.element}
    for fm in fitted_models(coupled, k_r):
        for scheme, groups in schemes.items():
            predicted, folds = cross_validate(fm, rows, groups)
            fitted = {name: float(np.median(folds[:, j])) for j, name in enumerate(fm.parameters)}
            extra = {"fold_parameters": {name: [float(v) for v in folds[:, j]]
                                         for j, name in enumerate(fm.parameters)}}
            records.append(_record(fm.name, predicted, rows, fitted, True, scheme, extra))
    return {"rows": int(rows.r.size), "k_r_N_per_mm": k_r,
            "table2": [{"element": int(e), "K_m_N_per_mm": float(km), "K_obj_N_per_mm": float(ko),
                        "R": float(r)} for e, km, ko, r in zip(rows.element, rows.k_m, rows.k_obj, rows.r)],
            "measured_r_below_one": int(np.count_nonzero(rows.r < 1.0)), "models": records,
            "skipped_models": skipped}
