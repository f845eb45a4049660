"""Lumped model of a stiffness sensing unit (paper eq. 1-3), Table 2, and ``tactcad lumped``."""

from __future__ import annotations

import argparse
import csv
import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from tactcad.commands import lumped as lumped_cmd
from tactcad.errors import TactcadError
from tactcad.mechanics import lumped_model as lumped
from tactcad.paper import data as paper_data
from tactcad.paper import table2_eq2
from tactcad.mechanics.lumped_model import LumpedDomainError

U = 2.0 ** -53  # unit round-off of float64
# Second-order rounding terms (O(u^2)) are covered by this relative slack.
SLACK = 1.0 + 1e-9
TABLE2_CSV = Path(__file__).resolve().parents[2] / "src" / "tactcad" / "data" / "table2_deflection_ratio.csv"


def exact_k_obj(r: float, k_m: float, k_r: float) -> Fraction:
    """Eq. 3 in exact rational arithmetic on the float inputs."""
    r, k_m, k_r = Fraction(r), Fraction(k_m), Fraction(k_r)
    return (k_r - r * k_m) / (r - 1)


def exact_r(k_m: float, k_r: float, k_obj: float) -> Fraction:
    """Eq. 2 in exact rational arithmetic on the float inputs."""
    k_m, k_r, k_obj = Fraction(k_m), Fraction(k_r), Fraction(k_obj)
    return (k_r + k_obj) / (k_m + k_obj)


def rel_err(value: float, exact: Fraction) -> float:
    return float(abs(Fraction(value) - exact) / abs(exact))


def k_obj_bound(k_m: float, k_obj: float) -> float:
    """Rounding bound of the rearranged eq. 3, K_obj = (K_r − K_m)/(R − 1) − K_m.

    K_r − K_m: <= u; R − 1: <= u (exact for R <= 2); the quotient q = K_m + K_obj
    thus <= 3u; the final subtraction adds u and scales q's error by q/K_obj.
    """
    return (4.0 + 3.0 * k_m / k_obj) * U * SLACK


# ---------------------------------------------------------------------------
# Strategies over the domain: K_m in [1e-3, 1e3] N/mm, K_r/K_m - 1 in [1e-12, 1e3],
# K_obj in [1e-4, 1e5] N/mm.
# ---------------------------------------------------------------------------
log_k_m = st.floats(-3.0, 3.0)
log_gap = st.floats(-12.0, 3.0)
log_k_obj = st.floats(-4.0, 5.0)


def unit(a: float, b: float) -> tuple[float, float]:
    k_m = 10.0 ** a
    k_r = k_m * (1.0 + 10.0 ** b)
    assume(k_r > k_m)
    return k_m, k_r


# ---------------------------------------------------------------------------
# Exact-arithmetic accuracy at the extremes
# ---------------------------------------------------------------------------
EXTREMES = [
    # (R, K_m, K_r): R -> 1 (stiff object), K_r -> K_m, R -> K_r/K_m (soft object), paper unit
    (1.0 + 1e-12, 15.25, 80.38),
    (1.0 + 2.0 ** -52, 15.25, 80.38),
    (1.0 + 0.5e-12, 40.12, 40.12 * (1.0 + 1e-12)),
    (1.0 + 1e-15, 40.12, 40.12 * (1.0 + 1e-12)),
    ((80.38 / 15.25) * (1.0 - 1e-9), 15.25, 80.38),
    (4.41, 15.25, 80.38),
    (1e3, 1e-3, 1e3),
]


@pytest.mark.parametrize("r, k_m, k_r", EXTREMES)
def test_object_stiffness_matches_exact_arithmetic(r, k_m, k_r):
    exact = exact_k_obj(r, k_m, k_r)
    assert exact > 0
    got = lumped.object_stiffness(r, k_m, k_r)
    # R > 2 adds one more rounding (R − 1 no longer exact): one more u.
    bound = k_obj_bound(k_m, float(exact)) + (U if r > 2 else 0.0)
    assert rel_err(got, exact) <= bound


def test_printed_form_of_eq3_loses_accuracy_where_rearranged_form_does_not():
    # K_r = K_m(1 + 1e-12): (K_r − R K_m)/(R − 1) rounds R K_m at ~u K_m,
    # an error 1e-4 of the difference K_r − R K_m ~ 1e-12 K_m.
    r, k_m, k_r = 1.0 + 0.5e-12, 40.12, 40.12 * (1.0 + 1e-12)
    exact = exact_k_obj(r, k_m, k_r)
    printed = (k_r - r * k_m) / (r - 1.0)
    assert rel_err(printed, exact) > 1e3 * k_obj_bound(k_m, float(exact))
    assert rel_err(lumped.object_stiffness(r, k_m, k_r), exact) <= k_obj_bound(k_m, float(exact))


@pytest.mark.parametrize("k_m, k_r, k_obj", [
    (15.25, 80.38, 1e12), (40.12, 40.12 * (1 + 1e-12), 3.85), (5.78, 80.38, 1e-6), (15.25, 80.38, 3.85)])
def test_forward_ratio_and_excess_match_exact_arithmetic(k_m, k_r, k_obj):
    exact = exact_r(k_m, k_r, k_obj)
    # R − 1: a difference, a sum and a quotient, <= 3u. R = 1 + (R − 1): one more u.
    assert rel_err(lumped.deflection_ratio(k_m, k_r, k_obj), exact) <= 4 * U * SLACK
    assert rel_err(lumped.deflection_ratio_excess(k_m, k_r, k_obj), exact - 1) <= 3 * U * SLACK


@pytest.mark.parametrize("r, k_m, k_r", EXTREMES)
def test_sensitivity_matches_exact_derivative(r, k_m, k_r):
    rf, km, kr = Fraction(r), Fraction(k_m), Fraction(k_r)
    exact = (km - kr) / (rf - 1) ** 2  # d/dR of (K_r − R K_m)/(R − 1)
    # K_r − K_m, R − 1 (twice, if inexact) and two quotients: <= 5u.
    assert rel_err(lumped.sensitivity(r, k_m, k_r), exact) <= 5 * U * SLACK


@settings(max_examples=300, deadline=None)
@given(log_k_m, log_gap, st.floats(1e-6, 1 - 1e-6))
def test_object_stiffness_within_rounding_bound_over_domain(a, b, t):
    k_m, k_r = unit(a, b)
    r = 1.0 + t * (k_r / k_m - 1.0)
    assume(1 < Fraction(r) < Fraction(k_r) / Fraction(k_m))
    exact = exact_k_obj(r, k_m, k_r)
    bound = k_obj_bound(k_m, float(exact)) + (U if r > 2 else 0.0)
    assert rel_err(lumped.object_stiffness(r, k_m, k_r), exact) <= bound


# ---------------------------------------------------------------------------
# Properties: round trips, monotonicity, range
# ---------------------------------------------------------------------------
@settings(max_examples=300, deadline=None)
@given(log_k_m, log_gap, log_k_obj)
def test_round_trip_through_r_within_conditioning_bound(a, b, c):
    k_m, k_r = unit(a, b)
    k_obj = 10.0 ** c
    r = lumped.deflection_ratio(k_m, k_r, k_obj)
    assume(r > 1.0)  # R rounds to 1 once R − 1 < u: K_obj is then not recoverable from R
    try:
        back = lumped.object_stiffness(r, k_m, k_r)
    except LumpedDomainError:
        # refused only when the true R lies within R's rounding (4u R) of the bound K_r/K_m
        gap = (k_r - k_m) / k_m * k_obj / (k_m + k_obj)  # K_r/K_m − R, exactly
        assert gap <= 8 * U * r
        return
    # R carries <= 4u relative error; eq. 3's condition number with respect to R is
    # |dK/dR| R/K_obj = (K_m + K_obj)(K_r + K_obj)/((K_r − K_m) K_obj); the inversion adds
    # its own rounding.
    cond = (k_m + k_obj) * (k_r + k_obj) / ((k_r - k_m) * k_obj)
    bound = (4.0 * U * cond + k_obj_bound(k_m, k_obj) + U) * SLACK
    assert abs(back - k_obj) / k_obj <= bound


@settings(max_examples=300, deadline=None)
@given(log_k_m, log_gap, log_k_obj)
def test_round_trip_through_excess_is_accurate_everywhere(a, b, c):
    k_m, k_r = unit(a, b)
    k_obj = 10.0 ** c
    s = lumped.deflection_ratio_excess(k_m, k_r, k_obj)
    back = lumped.object_stiffness_from_excess(s, k_m, k_r)
    # s: <= 3u; quotient (K_r − K_m)/s: <= 3u more; subtraction of K_m: scale by
    # (K_m + K_obj)/K_obj and add u.
    assert abs(back - k_obj) / k_obj <= (7.0 + 6.0 * k_m / k_obj) * U * SLACK


@settings(max_examples=300, deadline=None)
@given(log_k_m, log_gap, log_k_obj, st.floats(-6.0, 2.0))
# (K_r + K_obj)/(K_m + K_obj) rounds to 1 + 2u for the stiffer and to 1 for the softer object here
@example(a=-0.8715819952480568, b=-11.0, c=4.5, d=0.0)
def test_r_decreases_as_object_stiffens(a, b, c, d):
    k_m, k_r = unit(a, b)
    soft, stiff = 10.0 ** c, 10.0 ** c * (1.0 + 10.0 ** d)
    # R − 1 differs by a relative >= 1e-6 >> its 3u error: strictly ordered.
    assert lumped.deflection_ratio_excess(k_m, k_r, stiff) < lumped.deflection_ratio_excess(k_m, k_r, soft)
    # R itself may round to equal values, but must never increase (no one-ulp inversions).
    assert lumped.deflection_ratio(k_m, k_r, stiff) <= lumped.deflection_ratio(k_m, k_r, soft)


@settings(max_examples=200, deadline=None)
@given(log_k_m, st.floats(-6.0, 3.0), log_k_obj)
def test_r_lies_in_open_range_and_sensitivity_is_negative(a, b, c):
    k_m, k_r = unit(a, b)
    k_obj = 10.0 ** c
    r = lumped.deflection_ratio(k_m, k_r, k_obj)
    assert 1.0 <= r <= k_r / k_m * (1 + 6 * U)  # R: <= 4u; K_r/K_m: u
    assume(1.0 < r < k_r / k_m)
    try:
        slope = lumped.sensitivity(r, k_m, k_r)
    except LumpedDomainError:
        # R within a rounding of K_r/K_m may give q <= K_m: refused, never a wrong sign
        assert abs(r * k_m - k_r) <= 8 * U * k_r
        return
    assert slope < 0


def test_sensitivity_matches_central_difference_of_eq3():
    k_m, k_r = 15.25, 80.38
    for r in (1.2, 2.283, 4.0, 5.0):
        h = 1e-6 * (r - 1)
        fd = (lumped.object_stiffness(r + h, k_m, k_r) - lumped.object_stiffness(r - h, k_m, k_r)) / (2 * h)
        # central difference truncation: K''' h²/6 relative ~ (h/(R−1))² = 1e-12, plus
        # rounding ~u K_obj/h; 1e-7 bounds both for these R.
        assert lumped.sensitivity(r, k_m, k_r) == pytest.approx(fd, rel=1e-7)
        k_obj = lumped.object_stiffness(r, k_m, k_r)
        assert lumped.sensitivity(r, k_m, k_r) == pytest.approx(-(k_m + k_obj) ** 2 / (k_r - k_m), rel=1e-13)


def test_propagated_sigma_matches_monte_carlo():
    k_m, k_r, r, sigma_r = 15.25, 80.38, 2.283, 0.002  # sigma_R/(R − 1) = 1.6e-3
    n = 200_000
    rng = np.random.default_rng(12345)
    samples = lumped.object_stiffness(r + sigma_r * rng.standard_normal(n), k_m, k_r)
    assert samples.valid.all()
    predicted = lumped.propagate_sigma(r, sigma_r, k_m, k_r)
    # sample std has relative standard error 1/sqrt(2n) = 1.6e-3; the neglected
    # second-order term is ~ sigma_R/(R−1) = 1.6e-3 relative. Allow 5 standard errors + it.
    tol = 5 / math.sqrt(2 * n) + 2 * sigma_r / (r - 1)
    assert np.std(samples.value) == pytest.approx(predicted, rel=tol)
    assert predicted == pytest.approx(abs(lumped.sensitivity(r, k_m, k_r)) * sigma_r, rel=1e-15)


# ---------------------------------------------------------------------------
# Eq. 1 and the independent spring-network simulation
# ---------------------------------------------------------------------------
@settings(max_examples=200, deadline=None)
@given(st.floats(-1.0, 2.0), st.floats(-2.0, 1.5), log_k_obj, st.floats(1e-3, 1.0))
def test_simulated_unit_reproduces_eq1_and_eq2(a, b, c, delta):
    k_m, k_r = unit(a, b)
    k_obj = 10.0 ** c
    sim = lumped.simulate_unit(k_m, k_r, k_obj, delta)
    eq1 = lumped.element_deflections(delta, k_m, k_r, k_obj)
    # a 2 x 2 solve (here diagonal): backward stable, relative error a few u per component
    tol = 64 * U
    for got, want in ((sim.delta_m, eq1.delta_m), (sim.delta_r, eq1.delta_r)):
        assert got == pytest.approx(want, rel=tol)
    # element deflections Δ − δ come from a subtraction in the simulation: absolute error ~u Δ
    for got, want in ((sim.element_m, eq1.element_m), (sim.element_r, eq1.element_r)):
        assert got == pytest.approx(want, rel=tol, abs=tol * delta)
    # series springs carry the same force: K (Δ − δ) = K_obj δ
    assert sim.force_m == pytest.approx(k_obj * sim.delta_m, rel=tol, abs=tol * k_m * delta)
    assert sim.total_force == pytest.approx(sim.force_m + sim.force_r, rel=tol)
    if min(sim.element_m, sim.element_r) > 1e-6 * delta:
        r_sim = sim.element_m / sim.element_r
        cancel = delta / min(sim.element_m, sim.element_r)  # error growth of Δ − δ
        assert r_sim == pytest.approx(lumped.deflection_ratio(k_m, k_r, k_obj), rel=4 * tol * cancel)


def test_eq1_deflections_satisfy_series_force_balance_exactly():
    d = lumped.element_deflections(0.1, 15.25, 80.38, 3.85)
    assert d.delta_m + d.element_m == pytest.approx(0.1, rel=4 * U)
    assert 15.25 * d.element_m == pytest.approx(3.85 * d.delta_m, rel=8 * U)
    assert 80.38 * d.element_r == pytest.approx(3.85 * d.delta_r, rel=8 * U)


# ---------------------------------------------------------------------------
# Domain errors and the array API
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("call, words", [
    (lambda: lumped.object_stiffness(0.98, 40.12, 80.38), ["R = 0.98", "1 < R < K_r/K_m = 2.00349"]),
    (lambda: lumped.object_stiffness(2.01, 40.12, 80.38), ["R = 2.01", "K_r/K_m = 2.00349"]),
    (lambda: lumped.object_stiffness(1.0, 40.12, 80.38), ["R = 1.0"]),
    (lambda: lumped.sensitivity(float("nan"), 40.12, 80.38), ["R = nan"]),
    (lambda: lumped.deflection_ratio(-1.0, 80.38, 3.0), ["K_m = -1.0", "> 0"]),
    (lambda: lumped.deflection_ratio(15.0, 80.38, 0.0), ["K_obj = 0.0", "> 0"]),
    (lambda: lumped.deflection_ratio(90.0, 80.38, 3.0), ["K_r = 80.38", "K_r > K_m = 90.0"]),
    (lambda: lumped.propagate_sigma(2.0, -0.1, 15.25, 80.38), ["sigma_R = -0.1", ">= 0"]),
    (lambda: lumped.element_deflections(-0.1, 15.25, 80.38, 3.0), ["Delta = -0.1", ">= 0 mm"]),
    (lambda: lumped.object_stiffness_from_excess(0.0, 15.25, 80.38), ["R - 1 = 0.0", "0 < R - 1"]),
    (lambda: lumped.simulate_unit(15.25, 80.38, -3.0, 0.1), ["K_obj = -3.0"]),
])
def test_scalar_domain_errors_name_condition_and_value(call, words):
    with pytest.raises(LumpedDomainError) as info:
        call()
    assert isinstance(info.value, TactcadError) and isinstance(info.value, ValueError)
    for word in words:
        assert word in str(info.value)


def test_array_call_returns_nan_and_mask_and_matches_scalar_calls():
    r = np.array([[0.98, 1.5], [2.283, 6.0]])
    k_m = np.array([15.25, 40.12])  # broadcasts along the last axis
    out = lumped.object_stiffness(r, k_m, 80.38)
    assert isinstance(out, lumped.Masked)
    assert out.value.shape == out.valid.shape == (2, 2)
    expected_valid = (r > 1) & (r < 80.38 / k_m)
    assert np.array_equal(out.valid, expected_valid)
    assert np.isnan(out.value[~expected_valid]).all()
    for i, j in zip(*np.nonzero(expected_valid)):
        assert out.value[i, j] == lumped.object_stiffness(float(r[i, j]), float(k_m[j]), 80.38)


def test_array_element_deflections_are_masked_per_entry():
    out = lumped.element_deflections(np.array([0.1, -0.1, 0.2]), 15.25, 80.38, 3.85)
    assert out.valid.tolist() == [True, False, True]
    assert np.isnan(out.value.element_m[1])
    assert out.value.element_m[2] == pytest.approx(2 * out.value.element_m[0], rel=4 * U)


# ---------------------------------------------------------------------------
# Paper Table 2
# ---------------------------------------------------------------------------
def raw_table2() -> list[dict[str, float]]:
    with TABLE2_CSV.open() as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def test_table2_loader_matches_csv_and_table1_elements():
    rows, raw = paper_data.table2(), raw_table2()
    assert len(rows) == len(raw) == 48
    assert {row.element for row in rows} == {1, 7, 2, 10, 6, 4}
    by_element = paper_data.table1_by_element()
    for row, ref in zip(rows, raw):
        assert (row.K_m_N_per_mm, row.K_obj_N_per_mm, row.R) == (
            ref["K_m_N_per_mm"], ref["K_obj_N_per_mm"], ref["R"])
        assert by_element[row.element].stiffness_N_per_mm == row.K_m_N_per_mm


def test_table2_printed_columns_are_consistent_with_kr_and_one_stiffness_per_sample():
    rows = paper_data.table2()
    # K_r/K_m column: 80.38/K_m to within 0.05 % (the printed values use a slightly
    # different K_r, e.g. 80.384 N/mm quoted in the text).
    for row in rows:
        assert row.K_r_over_K_m == pytest.approx(paper_data.K_R_N_PER_MM / row.K_m_N_per_mm, rel=5e-4)
    # K_m/K_obj column: within each sample column it implies one K_obj; rounding to
    # three decimals (<= 0.0005/0.588 = 0.09 %) bounds the spread.
    implied = np.array([row.K_obj_implied_N_per_mm for row in rows]).reshape(6, 8)
    spread = (implied.max(axis=0) - implied.min(axis=0)) / implied.mean(axis=0)
    assert (spread < 2 * 0.0005 / 0.588).all()


def test_table2_comparison_evaluates_eq2_on_every_row_without_tuning():
    cmp = table2_eq2.table2_comparison()
    raw = raw_table2()
    assert len(cmp.r_measured) == 48
    for i, ref in enumerate(raw):
        exact = exact_r(ref["K_m_N_per_mm"], 80.38, ref["K_obj_N_per_mm"])
        assert rel_err(cmp.r_predicted[i], exact) <= 4 * U * SLACK
        assert cmp.r_measured[i] == ref["R"]
        assert cmp.error[i] == ref["R"] - cmp.r_predicted[i]
    assert cmp.mean_abs_error == pytest.approx(np.mean([abs(e) for e in cmp.error]))
    # Measured R < 1 (element 1, K_r/K_m = 2.004) is kept and reported, not dropped.
    below = [ref for ref in raw if ref["R"] < 1]
    assert cmp.n_measured_below_one == len(below) > 0
    in_domain = np.array([1 < ref["R"] < 80.38 / ref["K_m_N_per_mm"] for ref in raw])
    assert np.array_equal(cmp.measured_in_domain, in_domain)
    assert np.isnan(cmp.k_obj_from_measured[~in_domain]).all()
    assert (cmp.k_obj_from_measured[in_domain] > 0).all()
    json.dumps(cmp.as_json())  # serialisable


def test_table2_comparison_accepts_predicted_element_stiffnesses():
    measured = sorted({row.K_m_N_per_mm for row in paper_data.table2()})
    same = table2_eq2.table2_comparison(k_m_predicted={k: k for k in measured})
    base = table2_eq2.table2_comparison()
    assert np.array_equal(same.r_predicted, base.r_predicted)
    softer = table2_eq2.table2_comparison(k_m_predicted={k: 0.9 * k for k in measured})
    assert np.array_equal(softer.k_m_measured, base.k_m_measured)
    assert (softer.r_predicted > base.r_predicted).all()  # smaller K_m -> larger R
    with pytest.raises(LumpedDomainError, match="missing 5.78"):
        table2_eq2.table2_comparison(k_m_predicted={k: k for k in measured if k != 5.78})
    with pytest.raises(LumpedDomainError, match="K_r > K_m"):
        table2_eq2.table2_comparison(k_r=10.0)


# ---------------------------------------------------------------------------
# CLI
# ---------------------------------------------------------------------------
def parse(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="tactcad")
    lumped_cmd.register(parser.add_subparsers(dest="command"))
    return parser.parse_args(argv)


def test_cli_forward_and_inverse_json(capsys):
    args = parse(["lumped", "--km", "15.25", "--kr", "80.38", "--kobj", "3.85", "--json"])
    assert args.func(args) == 0
    fwd = json.loads(capsys.readouterr().out)
    assert rel_err(fwd["r"], exact_r(15.25, 80.38, 3.85)) <= 4 * U * SLACK
    args = parse(["lumped", "--km", "15.25", "--kr", "80.38", "--r", str(fwd["r"]),
                  "--sigma-r", "0.01", "--json"])
    assert args.func(args) == 0
    inv = json.loads(capsys.readouterr().out)
    assert inv["k_obj_N_per_mm"] == pytest.approx(3.85, rel=1e-12)
    slope = -(15.25 + 3.85) ** 2 / (80.38 - 15.25)  # dK_obj/dR = −(K_m + K_obj)²/(K_r − K_m)
    assert inv["sensitivity_dk_obj_dr_N_per_mm"] == pytest.approx(slope, rel=1e-12)
    assert inv["sigma_k_obj_N_per_mm"] == pytest.approx(abs(slope) * 0.01, rel=1e-12)


def test_cli_text_output(capsys):
    args = parse(["lumped", "--km", "15.25", "--kr", "80.38", "--r", "2.283", "--sigma-r", "0.05"])
    assert args.func(args) == 0
    out = capsys.readouterr().out
    assert "K_obj = " in out and "dK_obj/dR = " in out and "sigma_K_obj = " in out


def test_cli_requires_exactly_one_of_kobj_and_r():
    with pytest.raises(SystemExit):
        parse(["lumped", "--km", "15.25", "--kr", "80.38"])
    with pytest.raises(SystemExit):
        parse(["lumped", "--km", "15.25", "--kr", "80.38", "--r", "2", "--kobj", "3"])


def test_cli_domain_error_propagates_and_main_exits_2(monkeypatch, capsys):
    args = parse(["lumped", "--km", "40.12", "--kr", "80.38", "--r", "0.98"])
    with pytest.raises(TactcadError, match="--r = 0.98"):
        args.func(args)
    from tactcad import cli
    monkeypatch.setattr(cli, "COMMAND_MODULES", ("tactcad.commands.lumped",))
    assert cli.main(["lumped", "--km", "40.12", "--kr", "80.38", "--r", "0.98"]) == 2
    # named by the option that gave it (it was "R = 0.98: must satisfy ...", no option)
    assert "--r = 0.98: allowed 1 < R < K_r/K_m" in capsys.readouterr().err
