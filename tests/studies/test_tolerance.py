"""Tolerance Monte Carlo: reproducible, convergent, exact at zero tolerance, CLI JSON."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tactcad.cli import main
from tactcad.errors import DesignError
from tactcad.mechanics.correction import load_correction
from tactcad.studies.tolerance_montecarlo import (Tolerances, corrected_stiffness, nominal_stiffness,
                                         run_tolerance, sensing_units, web_tolerance_for_band)

ZERO = dict(web_mm=0.0, notch_radius_mm=0.0, arm_length_mm=0.0, modulus_rel=0.0)


def test_equal_seeds_give_equal_numbers_and_other_seeds_do_not(plan):
    a = run_tolerance(plan, 3000, seed=7).as_json()
    b = run_tolerance(plan, 3000, seed=7).as_json()
    c = run_tolerance(plan, 3000, seed=8).as_json()
    assert a == b
    assert a["elements"][0]["K_mean_N_per_mm"] != c["elements"][0]["K_mean_N_per_mm"]


def test_result_does_not_depend_on_the_order_chunks_are_evaluated(plan):
    def backwards(func, items):
        items = list(items)
        return [func(i) for i in reversed(items)][::-1]

    a = run_tolerance(plan, 6000, seed=3).as_json()
    b = run_tolerance(plan, 6000, seed=3, mapper=backwards).as_json()
    assert a == b


def test_zero_tolerance_reports_nominal_k_and_true_k_obj(plan):
    rep = run_tolerance(plan, 50, tolerances=Tolerances(**ZERO), k_obj=[3.0, 9.0])
    corr = load_correction()
    for e, k in zip(rep.elements, nominal_stiffness(plan, corr)):
        assert e["K_mean_N_per_mm"] == pytest.approx(k, rel=1e-12)
        assert e["K_std_N_per_mm"] == pytest.approx(0.0, abs=1e-9)
    for u in rep.units:
        assert u["K_obj_reported_N_per_mm"]["mean"] == pytest.approx(u["K_obj_true_N_per_mm"],
                                                                      rel=1e-9)
        assert u["fraction_outside_eq3_domain"] == 0.0


def test_k_spread_converges_to_the_linearised_web_sensitivity(plan):
    """Web only, normal with sigma = tol/3: std(K)/K -> |d ln K / dt| sigma_t."""
    tol = 0.006
    rep = run_tolerance(plan, 40_000, seed=1,
                        tolerances=Tolerances(**dict(ZERO, web_mm=tol)))
    g, mat, corr = plan.element(4).geometry, plan.material, load_correction()
    t, h = g.web_thickness_mm, 1e-6

    def k(x):
        return float(corrected_stiffness(x, g.notch_radius_mm, g.arm_length_mm,
                                         mat.youngs_modulus_MPa, g, mat.poisson_ratio, corr))

    dlnk = (np.log(k(t + h)) - np.log(k(t - h))) / (2 * h)
    expected = dlnk * tol / 3
    got = rep.elements[3]["K_rel_std"]
    assert got == pytest.approx(expected, rel=0.03)


def test_uniform_draws_stay_inside_the_tolerance(plan):
    tol = Tolerances(web_mm=0.01, notch_radius_mm=0.0, arm_length_mm=0.0, modulus_rel=0.0,
                     distribution="uniform")
    rep = run_tolerance(plan, 5000, tolerances=tol)
    g, mat, corr = plan.element(1).geometry, plan.material, load_correction()
    k_lo, k_hi = (float(corrected_stiffness(g.web_thickness_mm + d, g.notch_radius_mm,
                                            g.arm_length_mm, mat.youngs_modulus_MPa, g,
                                            mat.poisson_ratio, corr)) for d in (-0.01, 0.01))
    e = rep.elements[0]
    assert k_lo <= e["K_p2_5_N_per_mm"] < e["K_p97_5_N_per_mm"] <= k_hi


def test_web_tolerance_for_band_puts_k_on_the_band_edge(plan):
    g, mat, corr = plan.element(2).geometry, plan.material, load_correction()
    tol = web_tolerance_for_band(g, mat, corr, 0.05)

    def k(x):
        return float(corrected_stiffness(x, g.notch_radius_mm, g.arm_length_mm,
                                         mat.youngs_modulus_MPa, g, mat.poisson_ratio, corr))

    k0 = k(g.web_thickness_mm)
    ratios = [k(g.web_thickness_mm + s * tol) / k0 for s in (-1, 1)]
    assert all(0.95 - 1e-9 <= r <= 1.05 + 1e-9 for r in ratios)
    assert max(abs(r - 1) for r in ratios) == pytest.approx(0.05, rel=1e-6)


def test_units_pair_each_element_with_the_nearest_stiffest(plan):
    k = nominal_stiffness(plan, load_correction())
    units = dict(sensing_units(plan, k))
    assert set(units.values()) == {1, 8}  # both 4 mm arms
    assert units[3] == 8 and units[2] == 1  # 3 faces 8 across the rows; 2 is next to 1
    # element 1 is as stiff as 8: either is a valid reference of every unit, the other
    # none's measuring element
    assert sensing_units(plan, k, reference=8) == [(n, 8) for n in (2, 3, 4, 5, 6, 7, 9, 10)]
    with pytest.raises(DesignError, match="--reference 1 or --reference 8") as refused:
        sensing_units(plan, k, reference=2)
    assert [a["option"] for a in refused.value.alternatives] == ["--reference 1", "--reference 8"]


def test_a_combs_reference_is_any_of_its_stiff_elements(capsys):
    from tactcad.design.array_plan import EXAMPLES

    comb = str(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    assert main(["tolerance", "--design", comb, "--samples", "200", "--reference", "3",
                 "--json"]) == 0
    units = json.loads(capsys.readouterr().out)["units"]
    assert {u["measuring"] for u in units} == set(range(7, 13))
    assert {u["reference"] for u in units} == {3}
    assert main(["tolerance", "--design", comb, "--samples", "200", "--reference", "9",
                 "--json"]) == 2
    error = json.loads(capsys.readouterr().out)["error"]
    assert [a["option"] for a in error["alternatives"]] == [f"--reference {n}"
                                                            for n in range(1, 7)]


def test_bad_tolerance_and_samples_are_refused(plan):
    with pytest.raises(DesignError, match="tolerance.web_mm"):
        Tolerances(web_mm=-0.01)
    with pytest.raises(DesignError, match="samples"):
        run_tolerance(plan, 1)


def test_cli_json_keys(capsys):
    assert main(["tolerance", "--samples", "400", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert {"samples", "seed", "tolerances", "elements", "units", "web_tolerance_for_5pct_K",
            "table1_equal_arm_spread"} <= set(doc)
    assert {"mean", "std", "p2_5", "p97_5"} == set(doc["units"][0]["K_obj_reported_N_per_mm"])
    assert doc["table1_equal_arm_spread"][0]["ratio_max_over_min"] == pytest.approx(2.0, abs=0.01)


def test_cli_refuses_bad_input(capsys):
    # a metal array's range, not a die's (one range per product: the parser reads no design)
    for n in ("1", "10000001"):
        assert main(["tolerance", "--samples", n]) == 2
        err = capsys.readouterr().err
        assert f"--samples = {n}: allowed an integer 2 ... 10000000 (arrays drawn)" in err
        assert "1000000 (dies" not in err
    assert main(["tolerance", "--samples", "x"]) == 2  # no integer: both products' ranges
    err = " ".join(capsys.readouterr().err.split())
    assert ("'x': allowed an integer 2 ... 10000000 (arrays drawn); on a silicon die's design "
            "an integer 2 ... 1000000 (dies drawn)") in err
    with pytest.raises(SystemExit):
        main(["tolerance", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert ("as-built arrays drawn, 2 ... 10000000 (default 10000, as verify draws); on a "
            "silicon die's design the dies drawn, 2 ... 1000000") in help_text


def test_runs_on_a_design_other_than_the_paper(design_data):
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.inverse_design import design_variant

    plan = plan_from_dict(design_variant(design_data, arms_mm=[4.0] + [12.0] * 9))
    from tactcad.paper.table1 import equal_arm_spread

    rep = run_tolerance(plan, 500)
    assert {u["reference"] for u in rep.units} == {1}
    # the general report borrows nothing from the paper, and its element 8 (a 12 mm
    # arm) cannot be Table 1's: the paper's comparison has no spread for it either
    assert rep.table1_spread == [] and equal_arm_spread(plan) == []
    assert equal_arm_spread(plan_from_dict(design_data))[0]["elements"] == [1, 8]


def test_vectorised_stiffness_equals_the_closed_form_estimator(plan):
    from tactcad.mechanics.ladder import estimate

    k = nominal_stiffness(plan, load_correction())
    for slot, kv in zip(plan.slots, k):
        ref = estimate("closed-form", slot.geometry, plan.material).stiffness_N_per_mm
        assert kv == pytest.approx(ref, rel=1e-12)


def test_the_element_band_report_draws_run_tolerances_element_figures(plan):
    """The K band check reads the elements alone; drawn on their own they are the full
    report's numbers exactly, and the band record judges the same band."""
    from tactcad.studies.tolerance_budget import mc_band, toleranced_band_record
    from tactcad.studies.tolerance_montecarlo import (MONTE_CARLO_SAMPLES, MONTE_CARLO_SEED,
                                                      element_band_report)

    full = run_tolerance(plan, 6000, seed=4, k_obj=[1.0])
    alone = element_band_report(plan, 6000, seed=4)
    assert alone.elements == full.elements and alone.tolerances == full.tolerances
    assert alone.units == [] and alone.web_tolerance == []
    assert element_band_report(plan, 6000, seed=5).elements != full.elements
    record = toleranced_band_record(plan, 0.05, 0.01)
    expected = mc_band(run_tolerance(plan, MONTE_CARLO_SAMPLES, seed=MONTE_CARLO_SEED))[0]
    assert record["predicted"] == expected


@pytest.mark.parametrize("overrides", [{}, {"sheet_mm": 0.01}, {"distribution": "uniform"}])
def test_a_chunks_samples_are_its_own_draw_to_the_bit(plan, overrides):
    from tactcad.studies.tolerance_montecarlo import chunk_samples, chunk_specs, draw_samples

    tol = Tolerances.of_plan(plan, **overrides)
    for spec in chunk_specs(plan, tol, 2600, 5):
        drawn = draw_samples(plan, tol, spec.n, np.random.default_rng(spec.seed))
        for _ in range(2):  # the second from the normal draws kept by the first
            samples = chunk_samples(spec)
            for name in ("web_mm", "notch_radius_mm", "arm_length_mm", "youngs_modulus_MPa",
                         "sheet_scale"):
                want, got = np.asarray(getattr(drawn, name)), np.asarray(getattr(samples, name))
                assert got.shape == want.shape and got.tobytes() == want.tobytes(), name


def test_an_element_band_report_is_kept_by_its_inputs_and_each_caller_gets_its_own(plan):
    """The K band's Monte Carlo is kept per process by everything it reads: the same plan
    elements, samples, seed, tolerances and correction give the same report without
    drawing again, each caller its own copy; a change of any one draws anew."""
    from dataclasses import replace

    from tactcad.studies import tolerance_montecarlo as mc

    first = mc.element_band_report(plan, 4000, seed=9)
    draws = []
    real = mc.run_chunk
    try:
        mc.run_chunk = lambda spec: draws.append(spec) or real(spec)
        again = mc.element_band_report(plan, 4000, seed=9)
        assert not draws and again.elements == first.elements
        again.elements[0]["K_mean_N_per_mm"] = -1.0  # a caller's own copy
        assert mc.element_band_report(plan, 4000, seed=9).elements == first.elements
        tol = Tolerances.of_plan(plan)
        others = [mc.element_band_report(plan, 4001, seed=9),
                  mc.element_band_report(plan, 4000, seed=10),
                  mc.element_band_report(plan, 4000, seed=9,
                                         tolerances=replace(tol, web_mm=2 * tol.web_mm)),
                  mc.element_band_report(plan, 4000, seed=9, correction=replace(
                      load_correction(), coefficients=(0.0, 0.0, 0.0)))]
        assert len(draws) > 4 and all(o.elements != first.elements for o in others)
    finally:
        mc.run_chunk = real
