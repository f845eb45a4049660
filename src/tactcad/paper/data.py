"""The paper's measured tables as immutable rows.

* Table 1 (calibration of the sensing elements): :func:`table1`.
* Table 2 (deflection ratio R of each measuring element against the reference
  element 8, for eight rubber samples): :func:`table2`.

The CSV files ship inside the package (``tactcad/data``); field names are the
CSV column names, which carry the units (mm, um, N, V, N/mm, V/mm, V/N).
Importing this module reads nothing; the tables are parsed once on first use.
"""

from __future__ import annotations

import csv
import functools
import io
from dataclasses import dataclass
from importlib import resources

# The calibration rig's defaults and the evaluation rig's preferred reference
# are the paper's (the general models keep them as their defaults): the Sauter
# FH5's load cell, K_SENSOR_N_PER_MM N/mm; the Z travel, CALIBRATION_STEPS_UM;
# Table 2's reference element, REFERENCE_ELEMENT.
from tactcad.mechanics.calibration import CALIBRATION_STEPS_UM as CALIBRATION_STEPS_UM
from tactcad.mechanics.calibration import K_SENSOR_N_PER_MM as K_SENSOR_N_PER_MM
from tactcad.mechanics.evaluation import PREFERRED_REFERENCE as REFERENCE_ELEMENT

#: The stiffness of Table 2's reference element, N/mm.
K_R_N_PER_MM = 80.38
#: Distinct rubber sample stiffnesses, N/mm (paper; Table 2 column headers).
SAMPLE_STIFFNESSES_N_PER_MM = (10.01, 7.26, 6.28, 5.41, 4.51, 3.85, 3.57, 2.34)

TABLE1_FILE = "table1_calibration.csv"
TABLE2_FILE = "table2_deflection_ratio.csv"


@dataclass(frozen=True)
class Table1Row:
    """One sensing element's calibration (paper Table 1).

    Attributes:
        element: element number (1-10; 5 did not work and is absent).
        stiffness_N_per_mm: K, slope of force vs element deflection (N/mm).
        max_deflection_um: largest element deflection in calibration (um).
        max_support_force_N: largest force in calibration (N).
        max_signal_change_V: largest change of the bridge signal (V).
        K_v_V_per_mm: K_v, slope of signal vs element deflection (V/mm), eq. 4.
        K_v_over_K_V_per_N: K_v/K, signal per unit force (V/N), eq. 6.
        V0_V: V0, signal at zero deflection (V), eq. 4.
        flexing_arm_length_mm: measuring-arm length of the element (mm).
    """

    element: int
    stiffness_N_per_mm: float
    max_deflection_um: float
    max_support_force_N: float
    max_signal_change_V: float
    K_v_V_per_mm: float
    K_v_over_K_V_per_N: float
    V0_V: float
    flexing_arm_length_mm: float


@dataclass(frozen=True)
class Table2Row:
    """One (measuring element, rubber sample) cell of paper Table 2 (K_r = 80.38 N/mm).

    Attributes:
        element: Table 1 element whose stiffness equals ``K_m_N_per_mm``.
        K_m_N_per_mm: stiffness of the measuring element, K_m (N/mm).
        K_r_over_K_m: the table's K_r/K_m column (dimensionless, as printed).
        K_obj_N_per_mm: stiffness of the rubber sample, K_obj (N/mm), from the
            column header.
        K_m_over_K_obj: the table's K_m/K_obj column (as printed).
        R: measured deflection ratio (Δ−δ_m)/(Δ−δ_r) (dimensionless).
    """

    element: int
    K_m_N_per_mm: float
    K_r_over_K_m: float
    K_obj_N_per_mm: float
    K_m_over_K_obj: float
    R: float

    @property
    def K_obj_implied_N_per_mm(self) -> float:
        """K_m / (printed K_m/K_obj): the sample stiffness the K_m/K_obj column implies (N/mm)."""
        return self.K_m_N_per_mm / self.K_m_over_K_obj


def _read_csv(name: str) -> list[dict[str, str]]:
    text = resources.files("tactcad").joinpath("data", name).read_text(encoding="utf-8")
    return list(csv.DictReader(io.StringIO(text)))


@functools.cache
def table1() -> tuple[Table1Row, ...]:
    """Paper Table 1, one row per working element, in table order (9 rows)."""
    rows = []
    for raw in _read_csv(TABLE1_FILE):
        rows.append(Table1Row(
            element=int(raw["element"]),
            stiffness_N_per_mm=float(raw["stiffness_N_per_mm"]),
            max_deflection_um=float(raw["max_deflection_um"]),
            max_support_force_N=float(raw["max_support_force_N"]),
            max_signal_change_V=float(raw["max_signal_change_V"]),
            K_v_V_per_mm=float(raw["K_v_V_per_mm"]),
            K_v_over_K_V_per_N=float(raw["K_v_over_K_V_per_N"]),
            V0_V=float(raw["V0_V"]),
            flexing_arm_length_mm=float(raw["flexing_arm_length_mm"]),
        ))
    return tuple(rows)


def largest_equal_arm_spread() -> tuple[float, float, float, float]:
    """The largest stiffness spread among Table 1 elements of equal arm length.

    Returns:
        (arm length mm, lowest K, highest K in N/mm, highest / lowest).
    """
    groups: dict[float, list[float]] = {}
    for row in table1():
        groups.setdefault(row.flexing_arm_length_mm, []).append(row.stiffness_N_per_mm)
    arm, ks = max((g for g in groups.items() if len(g[1]) > 1), key=lambda g: max(g[1]) / min(g[1]))
    return arm, min(ks), max(ks), max(ks) / min(ks)


def table1_by_element() -> dict[int, Table1Row]:
    """Paper Table 1 keyed by element number."""
    return {row.element: row for row in table1()}


@functools.cache
def table2() -> tuple[Table2Row, ...]:
    """Paper Table 2 as 48 rows (6 measuring elements x 8 samples), in table order.

    Raises:
        ValueError: a K_m of Table 2 matches no element stiffness of Table 1.
    """
    element_of = {row.stiffness_N_per_mm: row.element for row in table1()}
    rows = []
    for raw in _read_csv(TABLE2_FILE):
        k_m = float(raw["K_m_N_per_mm"])
        if k_m not in element_of:
            raise ValueError(f"Table 2 K_m = {k_m} N/mm matches no Table 1 element")
        rows.append(Table2Row(
            element=element_of[k_m],
            K_m_N_per_mm=k_m,
            K_r_over_K_m=float(raw["K_r_over_K_m"]),
            K_obj_N_per_mm=float(raw["K_obj_N_per_mm"]),
            K_m_over_K_obj=float(raw["K_m_over_K_obj"]),
            R=float(raw["R"]),
        ))
    return tuple(rows)
