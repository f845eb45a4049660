"""Calibration of a sensing element against a commercial force sensor (paper eq. 4-6).

The paper's procedure: a force sensor of stiffness K_s (Sauter FH5, 57.04 N/mm)
on a Z axis is driven in 25 um steps to 150 um against the element tip; each
run is repeated three times. Force sensor and element are two springs in
series, so the element deflection is the Z travel minus the sensor's own
deflection, Δ = z − F/K_s. Straight lines are fitted to force vs deflection
(slope K, eq. 5) and bridge signal vs deflection (slope K_v, intercept V0,
eq. 4). Then

* eq. 4: Δ = (V − V0)/K_v
* eq. 5: F = K Δ
* eq. 6: F = (K/K_v)(V − V0)

Units: Z travel in um at the interface (as the paper states it), deflection in
mm, force in N, stiffness in N/mm, signal in V, K_v in V/mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol

import numpy as np

from tactcad.errors import TactcadError

#: Stiffness of the force sensor's load cell in series with the element, N/mm:
#: the Sauter FH5 as the paper measured it; pass your own gauge's.
K_SENSOR_N_PER_MM = 57.04
#: Calibration Z travel: 25 um steps from 0 to 150 um (the paper's "Calibration").
CALIBRATION_STEPS_UM = (0.0, 25.0, 50.0, 75.0, 100.0, 125.0, 150.0)
#: Equal Z steps of a design's calibration up to the travel at its full-scale force.
FULL_SCALE_STEPS = 6
#: Default noise of the synthetic bridge signal (V): about three LSB of a
#: 16-bit DAQ on its +-10 V range (assumption; the paper gives no figure).
DEFAULT_NOISE_SIGNAL_V = 0.001


class CalibrationError(TactcadError, ValueError):
    """Calibration input that cannot be fitted or is physically impossible.

    Attributes:
        field: the column (``force_N``) or option (``--data``) refused, None when the
            message names none.
        value: the value refused (a cell's text, a file's path), None when none.
        allowed: what is allowed, in words with units, None when the message says it.
    """

    def __init__(self, message: str, field: str | None = None, value: object = None,
                 allowed: str | None = None):
        super().__init__(message)
        self.field, self.value, self.allowed = field, value, allowed


# ---------------------------------------------------------------------------
# Data and results
# ---------------------------------------------------------------------------
def _readonly(values) -> np.ndarray:
    a = np.array(values, dtype=float)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class CalibrationData:
    """Raw calibration readings, one entry per reading (all arrays shape (n,)).

    Attributes:
        z_travel_um: Z-axis travel from first contact (um).
        force_N: force read by the commercial sensor (N).
        signal_V: element bridge signal after amplification (V).
        k_sensor_N_per_mm: stiffness of the commercial sensor's load cell (N/mm).
    """

    z_travel_um: np.ndarray
    force_N: np.ndarray
    signal_V: np.ndarray
    k_sensor_N_per_mm: float


class SignalModel(Protocol):
    """Anything carrying the three eq. 4-6 constants (e.g. :class:`Calibration`)."""

    K_N_per_mm: float
    K_v_V_per_mm: float
    V0_V: float


@dataclass(frozen=True)
class PaperSignalModel:
    """Eq. 4-6 constants as printed in paper Table 1 for one element.

    Attributes:
        element: element number.
        K_N_per_mm: stiffness K (N/mm).
        K_v_V_per_mm: signal per deflection K_v (V/mm).
        V0_V: signal at zero deflection V0 (V).
    """

    element: int
    K_N_per_mm: float
    K_v_V_per_mm: float
    V0_V: float


@dataclass(frozen=True, eq=False)
class Calibration:
    """Least-squares calibration of one element (result of :func:`fit_calibration`).

    Both fits are ordinary least-squares straight lines with intercept against
    the element deflection Δ = z − F/K_s: F = K Δ + F0 and V = V0 + K_v Δ.
    F0 is the force offset at zero deflection (ideally 0; eq. 5 has none).

    Linearity error (independent, best-fit straight line): the largest absolute
    residual from the fitted line divided by the fitted full-scale output span
    (|slope| x (Δ_max − Δ_min)), in percent.

    Attributes:
        K_N_per_mm: element stiffness K (N/mm), eq. 5.
        K_v_V_per_mm: signal sensitivity to deflection K_v (V/mm), eq. 4.
        V0_V: signal at zero deflection V0 (V), eq. 4.
        F0_N: force intercept of the force–deflection line (N).
        k_sensor_N_per_mm: commercial sensor stiffness used for Δ (N/mm).
        stderr_K_N_per_mm, stderr_K_v_V_per_mm, stderr_V0_V: standard errors
            of the fitted parameters from the residual scatter (OLS covariance).
        linearity_force_pct, linearity_signal_pct: linearity errors (% of
            full-scale output) of the force and signal fits.
        deflection_mm: element deflection of each reading, shape (n,) (mm).
        residuals_force_N: F − (K Δ + F0), shape (n,) (N).
        residuals_signal_V: V − (V0 + K_v Δ), shape (n,) (V).
    """

    K_N_per_mm: float
    K_v_V_per_mm: float
    V0_V: float
    F0_N: float
    k_sensor_N_per_mm: float
    stderr_K_N_per_mm: float
    stderr_K_v_V_per_mm: float
    stderr_V0_V: float
    linearity_force_pct: float
    linearity_signal_pct: float
    deflection_mm: np.ndarray
    residuals_force_N: np.ndarray
    residuals_signal_V: np.ndarray

    @property
    def K_over_K_v_N_per_V(self) -> float:
        """K/K_v (N/V), the factor of eq. 6."""
        return self.K_N_per_mm / self.K_v_V_per_mm

    @property
    def K_v_over_K_V_per_N(self) -> float:
        """K_v/K (V/N), signal per unit force (Table 1 column K_v/K)."""
        return self.K_v_V_per_mm / self.K_N_per_mm


# ---------------------------------------------------------------------------
# Fitting
# ---------------------------------------------------------------------------
class _Line(NamedTuple):
    slope: float
    intercept: float
    stderr_slope: float
    stderr_intercept: float
    residuals: np.ndarray
    linearity_pct: float


def _fit_line(x: np.ndarray, y: np.ndarray) -> _Line:
    """OLS y = slope x + intercept, with standard errors and linearity error."""
    design = np.column_stack([x, np.ones_like(x)])
    (slope, intercept), *_ = np.linalg.lstsq(design, y, rcond=None)
    slope, intercept = float(slope), float(intercept)
    residuals = y - (slope * x + intercept)
    dof = x.size - 2
    variance = float(residuals @ residuals) / dof
    cov = variance * np.linalg.inv(design.T @ design)
    span = abs(slope) * float(np.ptp(x))
    linearity = 100.0 * float(np.max(np.abs(residuals))) / span if span > 0 else float("nan")
    return _Line(slope, intercept, float(np.sqrt(cov[0, 0])),
                 float(np.sqrt(cov[1, 1])), residuals, linearity)


def _as_vector(name: str, values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim != 1:
        raise CalibrationError(f"{name}: must be a 1-D sequence, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise CalibrationError(f"{name}: all readings must be finite")
    return a


def fit_calibration(z_travel_um, force_N, signal_V,
                    k_sensor_N_per_mm: float = K_SENSOR_N_PER_MM) -> Calibration:
    """Fit K, K_v and V0 of one element from calibration readings (paper eq. 4-5).

    Element deflection: Δ = z − F/K_s (commercial sensor and element are two
    springs in series). Then OLS lines F = K Δ + F0 and V = V0 + K_v Δ over all
    readings (repeated runs included as separate points, which gives the same
    slopes as fitting the run averages when every step has the same number of
    repeats).

    Args:
        z_travel_um: Z travel of each reading (um), shape (n,), n >= 3.
        force_N: commercial sensor force of each reading (N), shape (n,).
        signal_V: element signal of each reading (V), shape (n,).
        k_sensor_N_per_mm: commercial sensor stiffness K_s (N/mm), > 0.

    Returns:
        :class:`Calibration`.

    Raises:
        CalibrationError: lengths differ, fewer than 3 readings, non-finite
            readings, K_s <= 0, or all readings at the same deflection.
    """
    z_mm = _as_vector("z_travel_um", z_travel_um) * 1e-3
    force = _as_vector("force_N", force_N)
    signal = _as_vector("signal_V", signal_V)
    if not (z_mm.size == force.size == signal.size):
        raise CalibrationError(
            f"readings: z_travel_um, force_N, signal_V must have equal lengths, "
            f"got {z_mm.size}, {force.size}, {signal.size}")
    if z_mm.size < 3:
        raise CalibrationError(f"readings: need >= 3 for a line with a residual, got {z_mm.size}")
    if not (np.isfinite(k_sensor_N_per_mm) and k_sensor_N_per_mm > 0):
        raise CalibrationError(f"k_sensor_N_per_mm = {k_sensor_N_per_mm!r}: must be finite and > 0")
    deflection = z_mm - force / k_sensor_N_per_mm
    if np.ptp(deflection) == 0:
        raise CalibrationError("readings: all at the same element deflection; no slope to fit")
    f_line = _fit_line(deflection, force)
    v_line = _fit_line(deflection, signal)
    return Calibration(
        K_N_per_mm=f_line.slope, K_v_V_per_mm=v_line.slope, V0_V=v_line.intercept,
        F0_N=f_line.intercept, k_sensor_N_per_mm=float(k_sensor_N_per_mm),
        stderr_K_N_per_mm=f_line.stderr_slope, stderr_K_v_V_per_mm=v_line.stderr_slope,
        stderr_V0_V=v_line.stderr_intercept,
        linearity_force_pct=f_line.linearity_pct, linearity_signal_pct=v_line.linearity_pct,
        deflection_mm=_readonly(deflection), residuals_force_N=_readonly(f_line.residuals),
        residuals_signal_V=_readonly(v_line.residuals))


def deflection_from_signal(v, cal: SignalModel):
    """Element deflection from its signal, paper eq. 4: Δ = (V − V0)/K_v.

    Args:
        v: signal (V), scalar or array.
        cal: calibration constants (:class:`Calibration` or :class:`PaperSignalModel`).

    Returns:
        Δ (mm), float for scalar input, else ndarray of the shape of ``v``.
    """
    out = (np.asarray(v, dtype=float) - cal.V0_V) / cal.K_v_V_per_mm
    return float(out) if out.ndim == 0 else out


def force_from_signal(v, cal: SignalModel):
    """Force on the element from its signal, paper eq. 6: F = (K/K_v)(V − V0).

    Eq. 6 assumes F = K Δ (no force offset); a fitted ``F0_N`` is not added.

    Args:
        v: signal (V), scalar or array.
        cal: calibration constants (:class:`Calibration` or :class:`PaperSignalModel`).

    Returns:
        F (N), float for scalar input, else ndarray of the shape of ``v``.
    """
    out = (cal.K_N_per_mm / cal.K_v_V_per_mm) * (np.asarray(v, dtype=float) - cal.V0_V)
    return float(out) if out.ndim == 0 else out


# ---------------------------------------------------------------------------
# Two springs in series
# ---------------------------------------------------------------------------
def apparent_stiffness(k_element: float, k_sensor: float = K_SENSOR_N_PER_MM) -> float:
    """Stiffness seen at the Z axis, element and force sensor in series (N/mm).

    K_app = 1/(1/K + 1/K_s) = K K_s/(K + K_s).

    Raises:
        CalibrationError: a stiffness <= 0 or not finite.
    """
    _check_positive("k_element", k_element)
    _check_positive("k_sensor", k_sensor)
    return k_element * k_sensor / (k_element + k_sensor)


def element_stiffness_from_series(k_apparent: float, k_sensor: float = K_SENSOR_N_PER_MM) -> float:
    """Element stiffness from the series stiffness, K = 1/(1/K_app − 1/K_s) (N/mm).

    Written as K_app K_s/(K_s − K_app).

    Raises:
        CalibrationError: a stiffness <= 0, or K_app >= K_s (a series
            combination is softer than either spring).
    """
    _check_positive("k_apparent", k_apparent)
    _check_positive("k_sensor", k_sensor)
    if not k_apparent < k_sensor:
        raise CalibrationError(
            f"k_apparent = {k_apparent!r} N/mm: must be < k_sensor = {k_sensor!r} N/mm "
            "(springs in series are softer than either)")
    return k_apparent * k_sensor / (k_sensor - k_apparent)


class SeriesAmplification(NamedTuple):
    """How relative errors reach the element stiffness through the series correction.

    With K = 1/(1/K_app − 1/K_s):

    * ∂K/∂K_app = K²/K_app², and K/K_app = 1 + K/K_s, so
      dK/K = (1 + K/K_s) dK_app/K_app;
    * ∂K/∂K_s = −K²/K_s², so dK/K = −(K/K_s) dK_s/K_s.

    Both grow with K/K_s: the stiffer the element relative to the sensor, the
    more of the Z travel the sensor absorbs and the more an error in either
    measured quantity is magnified.

    Attributes:
        k_element: element stiffness K (N/mm).
        k_sensor: commercial sensor stiffness K_s (N/mm).
        k_apparent: series stiffness K_app (N/mm).
        from_k_apparent: (dK/K)/(dK_app/K_app) = 1 + K/K_s.
        from_k_sensor: (dK/K)/(dK_s/K_s) = −K/K_s.
        element_share_of_travel: fraction of the Z travel taken by the
            element, K_s/(K + K_s).
    """

    k_element: float
    k_sensor: float
    k_apparent: float
    from_k_apparent: float
    from_k_sensor: float
    element_share_of_travel: float


def _check_positive(name: str, value: float) -> None:
    if not (np.isfinite(value) and value > 0):
        raise CalibrationError(f"{name} = {value!r} N/mm: must be finite and > 0")


def series_error_amplification(k_element: float,
                               k_sensor: float = K_SENSOR_N_PER_MM) -> SeriesAmplification:
    """Error amplification of the series-spring correction for one element.

    Args:
        k_element: element stiffness K (N/mm), > 0.
        k_sensor: commercial sensor stiffness K_s (N/mm), > 0.

    Returns:
        :class:`SeriesAmplification` (see its docstring for the derivation).

    Raises:
        CalibrationError: a stiffness <= 0 or not finite.
    """
    k_app = apparent_stiffness(k_element, k_sensor)
    ratio = k_element / k_sensor
    return SeriesAmplification(
        k_element=float(k_element), k_sensor=float(k_sensor), k_apparent=float(k_app),
        from_k_apparent=1.0 + ratio, from_k_sensor=-ratio,
        element_share_of_travel=k_sensor / (k_element + k_sensor))


# ---------------------------------------------------------------------------
# Synthetic calibration runs
# ---------------------------------------------------------------------------
def synthetic_calibration(k_element: float, k_v: float, v0: float, *,
                          noise_force_N: float = 0.001,
                          noise_signal_V: float = DEFAULT_NOISE_SIGNAL_V,
                          steps_um=CALIBRATION_STEPS_UM,
                          repeats: int = 3,
                          seed: int | None = 0,
                          k_sensor_N_per_mm: float = K_SENSOR_N_PER_MM) -> CalibrationData:
    """Simulate the paper's calibration runs of one element, with Gaussian read-out noise.

    For each Z step z (exact): the true force is F = K_app z with
    K_app = K K_s/(K + K_s); the element deflects Δ = F/K; the sensor reads
    F + N(0, noise_force_N²) and the bridge gives V0 + K_v Δ + N(0, noise_signal_V²).
    The steps are run ``repeats`` times (readings concatenated run after run).

    Args:
        k_element: element stiffness K (N/mm), > 0.
        k_v: signal sensitivity K_v (V/mm), any sign (Table 1 values are negative).
        v0: signal at zero deflection V0 (V).
        noise_force_N: standard deviation of the force reading (N), >= 0.
        noise_signal_V: standard deviation of the signal (V), >= 0.
        steps_um: Z travel of the steps (um); default 0, 25, ..., 150.
        repeats: number of runs, >= 1.
        seed: seed of ``numpy.random.default_rng``.
        k_sensor_N_per_mm: commercial sensor stiffness K_s (N/mm), > 0.

    Returns:
        :class:`CalibrationData` with ``len(steps_um) * repeats`` readings.

    Raises:
        CalibrationError: a stiffness <= 0, negative noise, or repeats < 1.
    """
    _check_positive("k_element", k_element)
    _check_positive("k_sensor_N_per_mm", k_sensor_N_per_mm)
    for name, value in (("noise_force_N", noise_force_N), ("noise_signal_V", noise_signal_V)):
        if not (np.isfinite(value) and value >= 0):
            raise CalibrationError(f"{name} = {value!r}: must be finite and >= 0")
    if repeats < 1:
        raise CalibrationError(f"repeats = {repeats!r}: must be >= 1")
    rng = np.random.default_rng(seed)
    z_um = np.tile(np.asarray(steps_um, dtype=float), repeats)
    force_true = apparent_stiffness(k_element, k_sensor_N_per_mm) * z_um * 1e-3
    deflection_true = force_true / k_element
    force = force_true + rng.normal(0.0, noise_force_N, z_um.size)
    signal = v0 + k_v * deflection_true + rng.normal(0.0, noise_signal_V, z_um.size)
    return CalibrationData(_readonly(z_um), _readonly(force), _readonly(signal),
                           float(k_sensor_N_per_mm))


# ---------------------------------------------------------------------------
# Measured-calibration CSV: one reading per row
# ---------------------------------------------------------------------------
#: Columns of a calibration CSV, in order (docs/how-to/calibration-data.md).
CSV_COLUMNS = ("element", "run", "z_um", "force_N", "signal_V")
#: Optional first comment line giving the force sensor stiffness, e.g. ``# k_sensor_N_per_mm = 57.04``.
CSV_SENSOR_KEY = "k_sensor_N_per_mm"


def format_calibration_csv(data: dict[int, CalibrationData], comments: tuple[str, ...] = ()) -> str:
    """The CSV text (read by :func:`tactcad.mechanics.measured_io.read_measured`) of
    readings keyed by element.

    Readings of one element are numbered into runs by the repeats of its Z
    steps (a reading whose Z is not above the previous one starts a new run). Every
    number is written to its shortest exact form (``repr``), so a refit of the text
    gives the fit of ``data``: a rounded signal would add its rounding to the noise.

    Args:
        data: element -> its readings (one force gauge for all).
        comments: lines written first, each after ``# ``.

    Returns:
        The CSV text, ending in a newline.

    Raises:
        CalibrationError: the elements were read on gauges of different stiffness.
    """
    sensors = {d.k_sensor_N_per_mm for d in data.values()}
    if len(sensors) > 1:
        raise CalibrationError(f"k_sensor_N_per_mm = {sorted(sensors)}: allowed one value per file")
    lines = [f"# {c}" for c in comments]
    if sensors:
        lines.append(f"# {CSV_SENSOR_KEY} = {float(sensors.pop())!r}")
    lines.append(",".join(CSV_COLUMNS))
    for element, d in data.items():
        run, previous = 1, -np.inf
        for z, f, v in zip(d.z_travel_um, d.force_N, d.signal_V):
            if z <= previous:
                run += 1
            previous = z
            lines.append(f"{element},{run},{float(z)!r},{float(f)!r},{float(v)!r}")
    return "\n".join(lines) + "\n"


class CalibrationGauge(NamedTuple):
    """The force gauge a design's elements are calibrated on, and how far the calibration
    drives them: what ``calibrate`` and the K_obj budget both read, so that the budget's
    expected standard errors are those of the steps the calibration drives.

    Attributes:
        gauge: the force gauge: ``model``, ``range_N``, ``resolution_N`` (N),
            ``stiffness_N_per_mm`` (N/mm).
        source: where the gauge comes from, and why it, in words.
        full_scale_force_N: the force (N) the Z steps load each element to, or None for
            the paper's own design (its steps, :data:`CALIBRATION_STEPS_UM`).
    """

    gauge: Any
    source: str
    full_scale_force_N: float | None

    def steps_um(self, k_element: float) -> np.ndarray:
        """The Z steps (um) the calibration drives on an element of K ``k_element`` (N/mm):
        :func:`calibration_steps_um` with this gauge's stiffness."""
        return calibration_steps_um(k_element, self.gauge.stiffness_N_per_mm,
                                    self.full_scale_force_N)


def calibration_steps_um(k_element: float, k_sensor_N_per_mm: float,
                         full_scale_force_N: float | None) -> np.ndarray:
    """The Z steps (um) a static calibration of one element drives: the paper's
    (:data:`CALIBRATION_STEPS_UM`) for its own design (``full_scale_force_N`` None); any
    other design :data:`FULL_SCALE_STEPS` equal steps up to the travel at which the element,
    in series with the force gauge, carries its full-scale force (past it an element
    would run onto its stop or past its fatigue limit).

    Args:
        k_element: the element's K (N/mm). k_sensor_N_per_mm: the force gauge's (N/mm).
        full_scale_force_N: the design's rated force (N), or None for the paper's steps.

    Returns:
        The steps, from 0 (um), shape (7,).
    """
    if full_scale_force_N is None:
        return np.asarray(CALIBRATION_STEPS_UM, float)
    z_max = full_scale_force_N / apparent_stiffness(k_element, k_sensor_N_per_mm) * 1e3
    return np.linspace(0.0, z_max, FULL_SCALE_STEPS + 1)
