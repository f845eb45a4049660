"""Calibration of a sensing element (paper eq. 4-6), series-spring correction, Table 1."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tactcad.errors import TactcadError
from tactcad.mechanics import calibration as cal
from tactcad.paper import calibration_table1 as cal1
from tactcad.paper import data as paper_data
from tactcad.mechanics.calibration import CalibrationError

K_S = paper_data.K_SENSOR_N_PER_MM
TABLE1 = paper_data.table1()


def fit(data: cal.CalibrationData) -> cal.Calibration:
    return cal.fit_calibration(data.z_travel_um, data.force_N, data.signal_V, data.k_sensor_N_per_mm)


def expected_standard_errors(k, k_v, noise_f, noise_v, steps_um=paper_data.CALIBRATION_STEPS_UM,
                             repeats=3, k_s=K_S):
    """OLS standard errors of K, K_v, V0 from the noise levels (first order).

    With Δ = z − F/K_s and F = K Δ_true + e: F = K Δ + e (1 + K/K_s), so the force
    line sees noise σ_F (1 + K/K_s); the signal line sees sqrt(σ_V² + (K_v σ_F/K_s)²).
    Slope SE = σ/sqrt(Sxx), intercept SE = σ sqrt(1/n + mean(Δ)²/Sxx).
    """
    d = np.tile(np.asarray(steps_um) * 1e-3 * k_s / (k + k_s), repeats)
    sxx = float(np.sum((d - d.mean()) ** 2))
    sigma_f = noise_f * (1 + k / k_s)
    sigma_v = math.hypot(noise_v, k_v * noise_f / k_s)
    return (sigma_f / math.sqrt(sxx), sigma_v / math.sqrt(sxx),
            sigma_v * math.sqrt(1 / d.size + d.mean() ** 2 / sxx))


# ---------------------------------------------------------------------------
# Fit recovery
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("row", TABLE1, ids=lambda r: f"element{r.element}")
def test_fit_is_exact_without_noise(row):
    data = cal.synthetic_calibration(row.stiffness_N_per_mm, row.K_v_V_per_mm, row.V0_V,
                                     noise_force_N=0.0, noise_signal_V=0.0)
    c = fit(data)
    assert c.K_N_per_mm == pytest.approx(row.stiffness_N_per_mm, rel=1e-9)
    assert c.K_v_V_per_mm == pytest.approx(row.K_v_V_per_mm, rel=1e-9)
    assert c.V0_V == pytest.approx(row.V0_V, abs=1e-9)
    assert abs(c.F0_N) < 1e-9
    assert c.linearity_force_pct < 1e-9 and c.linearity_signal_pct < 1e-9
    assert c.K_v_over_K_V_per_N == pytest.approx(row.K_v_V_per_mm / row.stiffness_N_per_mm, rel=1e-9)
    assert c.K_over_K_v_N_per_V == pytest.approx(row.stiffness_N_per_mm / row.K_v_V_per_mm, rel=1e-9)


@pytest.mark.parametrize("row", TABLE1, ids=lambda r: f"element{r.element}")
def test_fit_recovers_parameters_within_noise_derived_tolerance(row):
    noise_f, noise_v = 0.001, 0.001
    data = cal.synthetic_calibration(row.stiffness_N_per_mm, row.K_v_V_per_mm, row.V0_V,
                                     noise_force_N=noise_f, noise_signal_V=noise_v, seed=row.element)
    c = fit(data)
    se_k, se_kv, se_v0 = expected_standard_errors(row.stiffness_N_per_mm, row.K_v_V_per_mm,
                                                   noise_f, noise_v)
    z = 4.5  # two-sided tail 7e-6 per check: 27 checks pass by chance with probability > 0.9998
    assert abs(c.K_N_per_mm - row.stiffness_N_per_mm) <= z * se_k
    assert abs(c.K_v_V_per_mm - row.K_v_V_per_mm) <= z * se_kv
    assert abs(c.V0_V - row.V0_V) <= z * se_v0


@pytest.mark.parametrize("element", [8, 4])
def test_fit_scatter_and_reported_errors_match_noise_model(element):
    """Over many synthetic runs the fitted K scatters as the noise model says.

    This covers the series amplification: element 8 (K/K_s = 1.41) scatters
    (1 + K/K_s) times more in K than a force-noise-only line fit would.
    """
    row = paper_data.table1_by_element()[element]
    n = 400
    fits = [fit(cal.synthetic_calibration(row.stiffness_N_per_mm, row.K_v_V_per_mm, row.V0_V,
                                          seed=1000 + i)) for i in range(n)]
    k = np.array([f.K_N_per_mm for f in fits])
    kv = np.array([f.K_v_V_per_mm for f in fits])
    se_k, se_kv, _ = expected_standard_errors(row.stiffness_N_per_mm, row.K_v_V_per_mm,
                                              0.001, cal.DEFAULT_NOISE_SIGNAL_V)
    # unbiased: mean within 4 standard errors of the mean
    assert abs(k.mean() - row.stiffness_N_per_mm) <= 4 * se_k / math.sqrt(n)
    assert abs(kv.mean() - row.K_v_V_per_mm) <= 4 * se_kv / math.sqrt(n)
    # scatter: sample std has relative standard error 1/sqrt(2(n−1)) = 3.5 %; allow 4 of them
    tol = 4 / math.sqrt(2 * (n - 1))
    assert k.std(ddof=1) == pytest.approx(se_k, rel=tol)
    assert kv.std(ddof=1) == pytest.approx(se_kv, rel=tol)
    # the fit's own standard errors estimate the same (mean of s over 400 fits: bias
    # c4(19 dof) = 0.987, scatter < 1 %)
    assert np.mean([f.stderr_K_N_per_mm for f in fits]) == pytest.approx(se_k, rel=0.05)
    assert np.mean([f.stderr_K_v_V_per_mm for f in fits]) == pytest.approx(se_kv, rel=0.05)


def test_linearity_error_definition_on_a_hand_computed_case():
    # With a near-rigid force sensor Δ = z. Points (Δ, y) = (0, 0), (1, 2), (2, 2) mm:
    # OLS line y = Δ + 1/3, residuals −1/3, 2/3, −1/3; full-scale span |1| x 2 = 2;
    # linearity = (2/3)/2 = 33.3 %.
    z_um = [0.0, 1000.0, 2000.0]
    y = [0.0, 2.0, 2.0]
    c = cal.fit_calibration(z_um, y, y, k_sensor_N_per_mm=1e15)
    assert c.K_N_per_mm == pytest.approx(1.0, rel=1e-9)
    assert c.F0_N == pytest.approx(1 / 3, rel=1e-9)
    assert c.linearity_force_pct == pytest.approx(100 / 3, rel=1e-9)
    assert c.linearity_signal_pct == pytest.approx(100 / 3, rel=1e-9)
    assert np.allclose(c.residuals_force_N, [-1 / 3, 2 / 3, -1 / 3])


def test_synthetic_data_follows_the_paper_procedure():
    data = cal.synthetic_calibration(80.38, -9.0, 0.2, noise_force_N=0.0, noise_signal_V=0.0)
    assert data.z_travel_um.tolist() == [0, 25, 50, 75, 100, 125, 150] * 3
    # two springs in series: F = K_app z
    k_app = 80.38 * K_S / (80.38 + K_S)
    assert np.allclose(data.force_N, k_app * data.z_travel_um * 1e-3, rtol=1e-14)
    noisy = cal.synthetic_calibration(80.38, -9.0, 0.2, seed=7)
    again = cal.synthetic_calibration(80.38, -9.0, 0.2, seed=7)
    assert np.array_equal(noisy.force_N, again.force_N)
    assert not np.array_equal(noisy.force_N, data.force_N)


# ---------------------------------------------------------------------------
# Eq. 4-6
# ---------------------------------------------------------------------------
def test_signal_conversions_invert_the_calibration():
    k, k_v, v0 = 15.25, -3.7, -1.47
    data = cal.synthetic_calibration(k, k_v, v0, noise_force_N=0.0, noise_signal_V=0.0)
    c = fit(data)
    deflection_true = data.force_N / k  # noise-free: F = K Δ
    assert np.allclose(cal.deflection_from_signal(data.signal_V, c), deflection_true, rtol=0, atol=1e-12)
    assert np.allclose(cal.force_from_signal(data.signal_V, c), data.force_N, rtol=0, atol=1e-10)
    # eq. 6 = eq. 5 applied to eq. 4, scalar in -> float out
    v = v0 + k_v * 0.05
    f = cal.force_from_signal(v, c)
    assert isinstance(f, float)
    assert f == pytest.approx(c.K_N_per_mm * cal.deflection_from_signal(v, c), rel=1e-14)
    assert f == pytest.approx(k * 0.05, rel=1e-9)


def test_paper_signal_model_uses_table1_constants():
    m = cal1.paper_signal_model(8)
    assert (m.K_N_per_mm, m.K_v_V_per_mm, m.V0_V) == (80.38, -9.0, 0.20)
    # the printed max signal change of element 8 (0.47 V) corresponds to its max deflection
    deflection = abs(cal.deflection_from_signal(m.V0_V - 0.47, m)) * 1e3
    assert deflection == pytest.approx(paper_data.table1_by_element()[8].max_deflection_um, rel=0.1)
    with pytest.raises(CalibrationError, match="element = 5"):
        cal1.paper_signal_model(5)


# ---------------------------------------------------------------------------
# Two springs in series
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("row", TABLE1, ids=lambda r: f"element{r.element}")
def test_series_amplification_matches_finite_differences(row):
    k = row.stiffness_N_per_mm
    amp = cal.series_error_amplification(k)
    k_app = cal.apparent_stiffness(k)
    assert cal.element_stiffness_from_series(k_app) == pytest.approx(k, rel=1e-13)
    h = 1e-6
    # central differences of K(K_app, K_s) in relative terms; truncation ~h² x O(1) factors
    dk_app = (cal.element_stiffness_from_series(k_app * (1 + h))
              - cal.element_stiffness_from_series(k_app * (1 - h))) / (2 * h * k)
    dk_s = (cal.element_stiffness_from_series(k_app, K_S * (1 + h))
            - cal.element_stiffness_from_series(k_app, K_S * (1 - h))) / (2 * h * k)
    assert amp.from_k_apparent == pytest.approx(dk_app, rel=1e-7)
    assert amp.from_k_sensor == pytest.approx(dk_s, rel=1e-7)
    assert amp.element_share_of_travel == pytest.approx(k_app / k, rel=1e-14)


def test_series_amplification_grows_with_element_stiffness():
    table = cal1.series_amplification_table1()
    assert sorted(table) == [row.element for row in sorted(TABLE1, key=lambda r: r.element)]
    by_k = sorted(table.values(), key=lambda a: a.k_element)
    factors = [a.from_k_apparent for a in by_k]
    assert factors == sorted(factors) and len(set(factors)) == len(factors)
    # element 8 is stiffer than the force sensor: errors more than double
    assert table[8].k_element > K_S
    assert table[8].from_k_apparent > 2 and table[8].from_k_apparent == max(factors)


# ---------------------------------------------------------------------------
# Paper Table 1
# ---------------------------------------------------------------------------
def test_table1_loader():
    assert [row.element for row in TABLE1] == [1, 2, 3, 4, 6, 7, 8, 9, 10]
    k = {row.element: row.stiffness_N_per_mm for row in TABLE1}
    assert k[8] / k[4] == pytest.approx(13.9, abs=0.05)  # paper: "stiffness ratio of 13.9"
    # paper: elements 3, 7, 9 within 2.3 %
    assert (max(k[3], k[7], k[9]) - min(k[3], k[7], k[9])) / min(k[3], k[7], k[9]) < 0.023
    # longer measuring arm = softer: every element is softer than every element with a shorter arm
    for a in TABLE1:
        for b in TABLE1:
            if a.flexing_arm_length_mm > b.flexing_arm_length_mm:
                assert a.stiffness_N_per_mm < b.stiffness_N_per_mm


def test_table1_kv_over_k_column_follows_from_eq6_within_rounding():
    checks = cal1.table1_kv_over_k_check()
    assert [c.element for c in checks] == [row.element for row in TABLE1]
    for c, row in zip(checks, TABLE1):
        assert c.computed_V_per_N == row.K_v_V_per_mm / row.stiffness_N_per_mm
        assert c.low_V_per_N < c.computed_V_per_N < c.high_V_per_N
    mismatched = [c.element for c in checks if not c.consistent]
    assert mismatched == [], f"Table 1 rows whose K_v/K does not follow from K_v and K: {mismatched}"


# ---------------------------------------------------------------------------
# Errors
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("call, match", [
    (lambda: cal.fit_calibration([0, 25, 50], [0, 1], [0, 1, 2]), "equal lengths"),
    (lambda: cal.fit_calibration([0, 25], [0, 1], [0, 1]), ">= 3"),
    (lambda: cal.fit_calibration([0, 25, float("nan")], [0, 1, 2], [0, 1, 2]), "finite"),
    (lambda: cal.fit_calibration([0, 25, 50], [0, 1, 2], [0, 1, 2], k_sensor_N_per_mm=0), "k_sensor"),
    (lambda: cal.fit_calibration([10, 10, 10], [0, 0, 0], [0, 1, 2]), "same element deflection"),
    (lambda: cal.element_stiffness_from_series(60.0), "must be < k_sensor"),
    (lambda: cal.series_error_amplification(-1.0), "k_element = -1.0"),
    (lambda: cal.synthetic_calibration(10.0, -3.0, 0.0, noise_force_N=-1.0), "noise_force_N"),
    (lambda: cal.synthetic_calibration(10.0, -3.0, 0.0, repeats=0), "repeats"),
])
def test_bad_input_raises_calibration_error(call, match):
    with pytest.raises(CalibrationError, match=match) as info:
        call()
    assert isinstance(info.value, TactcadError)
