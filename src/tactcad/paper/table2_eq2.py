"""Paper Table 2 against eq. 2: the lumped model of a stiffness sensing unit
(:mod:`tactcad.mechanics.lumped_model`) evaluated on each of the table's 48 measured
rows, nothing fitted. Units: N/mm."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from tactcad.mechanics.lumped_model import LumpedDomainError, deflection_ratio, object_stiffness
from tactcad.paper import data as paper_data


def _readonly(values) -> np.ndarray:
    a = np.array(values)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Table2Comparison:
    """Eq. 2 evaluated for each of Table 2's 48 rows, next to the measured R.

    Arrays have shape (48,), in table order.

    Attributes:
        element: Table 1 element number of the measuring element.
        k_m_measured: K_m of the table (N/mm).
        k_m_used: K_m used in eq. 2 (measured or predicted) (N/mm).
        k_r_used: K_r used in eq. 2 (N/mm).
        k_obj: sample stiffness K_obj (N/mm).
        r_measured: R measured (table).
        r_predicted: R from eq. 2 with ``k_m_used``, ``k_r_used``, ``k_obj``.
        error: r_measured − r_predicted.
        relative_error: error / r_predicted.
        measured_in_domain: True where 1 < r_measured < k_r_used/k_m_used,
            i.e. where eq. 3 can invert the measured R.
        k_obj_from_measured: eq. 3 applied to the measured R (N/mm); NaN where
            the measured R is out of domain.
    """

    element: np.ndarray
    k_m_measured: np.ndarray
    k_m_used: np.ndarray
    k_r_used: float
    k_obj: np.ndarray
    r_measured: np.ndarray
    r_predicted: np.ndarray
    error: np.ndarray
    relative_error: np.ndarray
    measured_in_domain: np.ndarray
    k_obj_from_measured: np.ndarray

    @property
    def mean_abs_error(self) -> float:
        """Mean of |R_measured − R_predicted| over the rows."""
        return float(np.mean(np.abs(self.error)))

    @property
    def max_abs_error(self) -> float:
        """Largest |R_measured − R_predicted|."""
        return float(np.max(np.abs(self.error)))

    @property
    def rms_error(self) -> float:
        """Root-mean-square of R_measured − R_predicted."""
        return float(np.sqrt(np.mean(self.error ** 2)))

    @property
    def n_measured_below_one(self) -> int:
        """Rows whose measured R < 1, impossible under the model for K_r > K_m."""
        return int(np.count_nonzero(self.r_measured < 1.0))

    def as_json(self) -> dict:
        """Plain-Python form: summary figures and one dict per row."""
        keys = ("element", "k_m_measured", "k_m_used", "k_obj", "r_measured", "r_predicted",
                "error", "relative_error", "measured_in_domain", "k_obj_from_measured")
        rows = [{k: (getattr(self, k)[i].item()
                     if not (k == "k_obj_from_measured" and math.isnan(self.k_obj_from_measured[i]))
                     else None)
                 for k in keys} for i in range(len(self.element))]
        return {"k_r_used": self.k_r_used, "mean_abs_error": self.mean_abs_error,
                "max_abs_error": self.max_abs_error, "rms_error": self.rms_error,
                "n_measured_below_one": self.n_measured_below_one, "rows": rows}


def table2_comparison(k_r: float = paper_data.K_R_N_PER_MM,
                      k_m_predicted: Mapping[float, float] | None = None) -> Table2Comparison:
    """Evaluate eq. 2 for every row of paper Table 2 and compare with the measured R.

    Nothing is fitted: R_predicted = (K_r + K_obj)/(K_m + K_obj) with the
    table's (or the given) stiffnesses. Rows whose measured R lies outside the
    model's range (1, K_r/K_m), including the R < 1 readings of the
    K_r/K_m = 2.004 element, are kept and flagged in ``measured_in_domain``.

    Args:
        k_r: reference-element stiffness K_r (N/mm); default Table 1 element 8.
        k_m_predicted: optional mapping measured K_m (N/mm, as in Table 2) ->
            K_m to use instead (N/mm), e.g. a model's predicted stiffness of the
            same element. Must cover all six Table 2 K_m values.

    Returns:
        :class:`Table2Comparison`.

    Raises:
        LumpedDomainError: a K_m missing from ``k_m_predicted``, or a used
            stiffness out of domain (<= 0, or K_m >= K_r).
    """
    rows = paper_data.table2()
    used = []
    for row in rows:
        if k_m_predicted is None:
            used.append(row.K_m_N_per_mm)
        elif row.K_m_N_per_mm in k_m_predicted:
            used.append(float(k_m_predicted[row.K_m_N_per_mm]))
        else:
            raise LumpedDomainError(
                "k_m_predicted", sorted(k_m_predicted),
                f"a key for every Table 2 K_m (missing {row.K_m_N_per_mm} N/mm)")
    k_obj = np.array([row.K_obj_N_per_mm for row in rows])
    r_meas = np.array([row.R for row in rows])
    r_pred = np.array([deflection_ratio(km, k_r, ko) for km, ko in zip(used, k_obj)])
    error = r_meas - r_pred
    inferred = object_stiffness(r_meas, np.array(used), k_r)
    return Table2Comparison(
        element=_readonly([row.element for row in rows]),
        k_m_measured=_readonly([row.K_m_N_per_mm for row in rows]),
        k_m_used=_readonly(used),
        k_r_used=float(k_r),
        k_obj=_readonly(k_obj),
        r_measured=_readonly(r_meas),
        r_predicted=_readonly(r_pred),
        error=_readonly(error),
        relative_error=_readonly(error / r_pred),
        measured_in_domain=_readonly(inferred.valid),
        k_obj_from_measured=_readonly(inferred.value),
    )
