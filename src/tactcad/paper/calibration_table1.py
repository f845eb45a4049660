"""Paper Table 1 through the calibration equations (eq. 4-6,
:mod:`tactcad.mechanics.calibration`): each element's printed constants as a
signal model, the series error amplification of every element against the
force gauge, and the table's K_v/K column checked against its own K and K_v
within the printed rounding. Units: N/mm, V/mm, V/N."""

from __future__ import annotations

from typing import NamedTuple

from tactcad.mechanics.calibration import (K_SENSOR_N_PER_MM, CalibrationError, PaperSignalModel,
                                           SeriesAmplification, series_error_amplification)
from tactcad.paper import data as paper_data


def paper_signal_model(element: int) -> PaperSignalModel:
    """Eq. 4-6 constants of one element as printed in Table 1.

    Raises:
        CalibrationError: the element is not in Table 1 (5 did not work).
    """
    rows = paper_data.table1_by_element()
    if element not in rows:
        raise CalibrationError(f"element = {element!r}: must be one of {sorted(rows)} (Table 1)")
    row = rows[element]
    return PaperSignalModel(element, row.stiffness_N_per_mm, row.K_v_V_per_mm, row.V0_V)


def series_amplification_table1(k_sensor: float = K_SENSOR_N_PER_MM) -> dict[int, SeriesAmplification]:
    """:func:`series_error_amplification` for every element of paper Table 1, keyed by element."""
    return {row.element: series_error_amplification(row.stiffness_N_per_mm, k_sensor)
            for row in paper_data.table1()}


# ---------------------------------------------------------------------------
# Table 1 self-consistency (eq. 6)
# ---------------------------------------------------------------------------
class KvOverKCheck(NamedTuple):
    """Table 1's K_v/K column against K_v and K of the same row.

    Attributes:
        element: element number.
        computed_V_per_N: K_v/K from the printed K_v and K.
        printed_V_per_N: the printed K_v/K.
        low_V_per_N, high_V_per_N: range of K_v/K over all K_v, K that round
            to the printed values, widened by half a unit of the printed K_v/K.
        consistent: low <= printed <= high.
    """

    element: int
    computed_V_per_N: float
    printed_V_per_N: float
    low_V_per_N: float
    high_V_per_N: float
    consistent: bool


#: Half a unit in the last printed digit of Table 1's K (N/mm), K_v (V/mm), K_v/K (V/N).
TABLE1_HALF_UNIT = {"K": 0.005, "K_v": 0.05, "K_v_over_K": 0.0005}


def table1_kv_over_k_check() -> tuple[KvOverKCheck, ...]:
    """Check eq. 6's K_v/K column of Table 1 against its K and K_v, within the printed rounding.

    The true K and K_v lie within half a unit of their printed values
    (:data:`TABLE1_HALF_UNIT`); K_v/K over that box is bracketed by its corner
    values (the quotient is monotonic in each argument for K > 0). A row is
    consistent when the printed K_v/K, +- half its own unit, meets the bracket.
    """
    h = TABLE1_HALF_UNIT
    out = []
    for row in paper_data.table1():
        corners = [(row.K_v_V_per_mm + a) / (row.stiffness_N_per_mm + b)
                   for a in (-h["K_v"], h["K_v"]) for b in (-h["K"], h["K"])]
        low = min(corners) - h["K_v_over_K"]
        high = max(corners) + h["K_v_over_K"]
        printed = row.K_v_over_K_V_per_N
        out.append(KvOverKCheck(row.element, row.K_v_V_per_mm / row.stiffness_N_per_mm,
                                printed, low, high, bool(low <= printed <= high)))
    return tuple(out)
