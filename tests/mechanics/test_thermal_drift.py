"""Thermal drift, zero and span apart: thermal output from the CTE / STC mismatch (TN-504), the
leads (TT-612), the modulus and expansion of the springs, the gauge factor, self-heating of the
grid (TN-502 / TN-504), the half-bridge dummy gauge, K_obj per kelvin across the force range,
and the requirement."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tactcad.cli import main
from tactcad.commands.thermal import render
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
from tactcad.design.readout_section import TN502_POWER_DENSITY_W_PER_MM2
from tactcad.errors import DesignError
from tactcad.mechanics.readout_chain import readout_chain, readout_report
from tactcad.mechanics.resolution import KOBJ_POINTS
from tactcad.mechanics.thermal_drift import (COPPER_TCR_PER_K, kobj_thermal_error,
                                             matched_stc_ppm_per_K, thermal_report)
from tactcad.studies.verification import requirements_of, verification_matrix
from tactcad.vocabulary.material_library import material_grade, material_grades

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: NIST cryogenic material properties, 6061-T6 aluminium: E(T) = a + bT + cT^2 + dT^3 + eT^4
#: (GPa, T in K), the fit the library's 6061-T6 modulus coefficient is taken from.
NIST_6061_E_FIT = (77.71221, 1.030646e-2, -2.9241e-4, 8.9936e-7, -1.0709e-9)


def _plan(**overrides):
    return plan_from_dict(with_overrides(default_design_data(), overrides))


def _report(plan):
    return thermal_report(plan, requirements_of(plan))


def _nist_6061_modulus_tc(T: float = 293.0) -> float:
    """(1/E) dE/dT of the NIST fit at T (1/K)."""
    c = NIST_6061_E_FIT
    E = sum(ci * T ** i for i, ci in enumerate(c))
    dE = sum(i * ci * T ** (i - 1) for i, ci in enumerate(c) if i)
    return dE / E


def _hand_span_per_K(plan, n_leads: int) -> float:
    """-(1/E) dE/dT - 2 alpha_S + TC_GF - n R_L TCR / (R_g + n R_L) from the library and the
    read-out defaults."""
    g, chain = material_grade(plan.material.grade), readout_chain(plan)
    r_l = chain.lead_resistance_ohm_per_m * chain.lead_length_mm / 1000.0
    return (-g.youngs_modulus_tc_per_K - 2 * g.cte_ppm_per_K * 1e-6
            + chain.gauge_factor_tc_pct_per_100K * 1e-4
            - n_leads * r_l * COPPER_TCR_PER_K / (chain.gauge_resistance_ohm + n_leads * r_l))


def test_one_element_matches_the_hand_calculation_from_the_published_relations():
    # 6061-T6 (23.6 ppm/K) under a steel-matched STC 06 gauge (6 ppm/degF = 10.8 ppm/K), K_t 1 %:
    # TN-504: eps/dT = (1 + K_t) / (1 - 0.285 K_t) (alpha_S - alpha_STC)
    plan = _plan(**{"readout.gauge_stc_ppm_per_K": 10.8,
                    "readout.gauge_transverse_sensitivity": 0.01})
    hand_strain = 1.01 / (1 - 0.285 * 0.01) * (23.6 - 10.8) * 1e-6
    rep = _report(plan)
    assert rep.apparent_strain_per_K == pytest.approx(hand_strain, rel=1e-12)
    eps_per_N = readout_report(plan, requirements_of(plan)).records[3]["grid_strain_per_N"]
    elem = rep.records[3]
    assert elem["zero_drift_N_per_K"] == pytest.approx(hand_strain / eps_per_N, rel=1e-9)
    # span: modulus, expansion, gauge factor and one lead (three-wire) at full scale
    F = requirements_of(plan).full_scale_force_N
    span = _hand_span_per_K(plan, 1)
    assert rep.span_rel_per_K == pytest.approx(span, rel=1e-9)
    assert elem["drift_N_per_K"] == pytest.approx(abs(hand_strain / eps_per_N) + F * abs(span))


def test_6061_span_drift_includes_the_modulus_term_of_the_nist_fit():
    nist = _nist_6061_modulus_tc()
    assert -5.5e-4 < nist < -4.5e-4
    rep = _report(_plan())
    terms = rep.span_terms_per_K
    assert terms["modulus"] == pytest.approx(-nist, rel=0.01)  # the library rounds to 3 digits
    # the modulus term is several times the gauge factor's (the term the drift once held alone)
    assert terms["modulus"] > 4 * terms["gauge_factor"]
    assert 4e-4 < rep.span_rel_per_K < 7e-4
    assert rep.setting.modulus_tc_sourced
    assert "NIST" in rep.setting.sources["substrate_modulus_tc_per_K"]


def test_the_span_does_not_cancel_in_a_half_bridge_and_enters_kobj():
    half = _report(_plan(**{"readout.dummy_gauge": "half-bridge"}))
    quarter = _report(_plan())
    assert half.span_rel_per_K == pytest.approx(quarter.span_rel_per_K)
    g = material_grade("6061-T6")
    k_scale = (1 + g.youngs_modulus_tc_per_K) * (1 + g.cte_ppm_per_K * 1e-6)
    for r in half.records:
        assert r["zero_drift_N_per_K"] == 0.0
        if r["kobj_error_rel_per_K"] is not None:  # K_obj / K_obj_true = 1 / k_scale per kelvin
            assert r["kobj_error_rel_per_K"] == pytest.approx(abs(1 / k_scale - 1), rel=1e-9)
            assert 4e-4 < r["kobj_error_rel_per_K"] < 6e-4


def test_steel_matched_gauge_on_6061_drifts_more_than_an_aluminium_matched_one():
    steel = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8}))
    alu = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 23.4}))
    assert steel.worst["drift_N_per_K"] > 5 * alu.worst["drift_N_per_K"]
    for s, a in zip(steel.records, alu.records):
        assert abs(s["zero_drift_N_per_K"]) > abs(a["zero_drift_N_per_K"])
        if s["kobj_error_rel_per_K"] is not None:
            assert s["kobj_error_rel_per_K"] > a["kobj_error_rel_per_K"]


def test_readout_reports_the_thermal_values_thermal_uses_under_the_same_keys(capsys):
    """An unstated CTE, modulus coefficient and STC: `readout --json` states the values
    `thermal --json` resolves (it said null), with the same sources; a stated one as stated."""
    rep = _report(_plan())
    from tactcad.studies.project_reports import readout_record

    chain = readout_record(_plan()).chain.as_json()
    thermal = rep.setting.as_json()
    for key in ("substrate_cte_ppm_per_K", "gauge_stc_ppm_per_K", "substrate_modulus_tc_per_K"):
        assert chain[key] == thermal[key] is not None, key
        assert chain["sources"][key] == thermal["sources"][key]
    assert main(["readout", "--json", "--set", "readout.gauge_stc_ppm_per_K=10.8"]) == 0
    said = json.loads(capsys.readouterr().out)["chain"]
    assert said["gauge_stc_ppm_per_K"] == 10.8
    assert said["sources"]["gauge_stc_ppm_per_K"] == "design file"
    assert said["substrate_cte_ppm_per_K"] == thermal["substrate_cte_ppm_per_K"]


def test_unstated_stc_is_the_series_nearest_the_material_and_says_so():
    assert matched_stc_ppm_per_K(23.6) == (pytest.approx(23.4), 13)
    assert matched_stc_ppm_per_K(8.6) == (pytest.approx(9.0), 5)
    rep = _report(_plan())
    assert rep.setting.stc_ppm_per_K == pytest.approx(23.4)
    assert "not stated" in rep.setting.sources["gauge_stc_ppm_per_K"]
    assert "6061-T6" in rep.setting.sources["substrate_cte_ppm_per_K"]


def test_zero_mismatch_leaves_only_the_span():
    rep = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 23.6}))
    F = rep.full_scale_force_N
    for r in rep.records:
        assert r["zero_drift_N_per_K"] == 0.0
        assert r["drift_N_per_K"] == pytest.approx(F * abs(rep.span_rel_per_K))
        if r["kobj_error_rel_per_K"] is not None:
            assert r["kobj_error_rel_per_K"] == pytest.approx(r["kobj_span_rel_per_K"])


def test_huge_cte_scales_the_apparent_force_linearly():
    small = _report(_plan(**{"readout.substrate_cte_ppm_per_K": 33.4,
                             "readout.gauge_stc_ppm_per_K": 23.4}))
    huge = _report(_plan(**{"readout.substrate_cte_ppm_per_K": 200.0,
                            "readout.gauge_stc_ppm_per_K": 0.0}))
    ratio = huge.records[0]["apparent_force_N_per_K"] / small.records[0]["apparent_force_N_per_K"]
    assert ratio == pytest.approx(20.0)


def test_half_bridge_dummy_cancels_the_zero_terms_and_self_heating():
    quarter = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8,
                               "readout.lead_wires": "two-wire"}))
    half = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8, "readout.lead_wires": "two-wire",
                            "readout.dummy_gauge": "half-bridge"}))
    for q, h in zip(quarter.records, half.records):
        assert h["drift_N_per_K"] == pytest.approx(q["drift_N_per_K"]
                                                   - q["half_bridge_cancels_N_per_K"])
        assert h["self_heating_offset_N"] == 0.0 != q["self_heating_offset_N"]


def test_self_heating_follows_the_excitation_squared():
    low = _report(_plan(**{"readout.excitation_V": 1.0}))
    high = _report(_plan(**{"readout.excitation_V": 2.0}))
    assert low.grid_power_W == pytest.approx(1.0 / (4 * 120.0))
    assert high.self_heating_K == pytest.approx(4 * low.self_heating_K)


def test_self_heating_offset_is_the_warm_grid_form_not_the_substrate_mismatch():
    # a grid warmer than its substrate reads -(1+K_t)/(1-0.285 K_t) alpha_STC dT_grid (the
    # substrate does not expand): with STC 13 on 6061 that is -23.4 ppm/K x dT_grid, not the
    # 0.2 ppm/K mismatch; the top-face gauge is in compression under load (strain per N < 0),
    # so the offset reads as a positive force
    plan = _plan(**{"readout.excitation_V": 2.5})
    rep = _report(plan)
    eps = rep.records[0]["grid_strain_per_N"]
    assert eps < 0
    hand = -rep.setting.stc_ppm_per_K * 1e-6 * rep.self_heating_K / eps
    assert rep.records[0]["self_heating_offset_N"] == pytest.approx(hand, rel=1e-12)
    assert rep.records[0]["self_heating_offset_N"] > 0
    mismatch_form = rep.apparent_strain_per_K * rep.self_heating_K / eps
    assert abs(rep.records[0]["self_heating_offset_N"]) > 50 * abs(mismatch_form)


def test_two_wire_leads_drift_more_than_three_wire_ones_as_tt612_says():
    three, two = _report(_plan()), _report(_plan(**{"readout.lead_wires": "two-wire"}))
    assert three.lead_wires["zero_strain_per_K"] == 0.0  # the adjacent arm balances the lead
    chain = readout_chain(_plan())
    r_l = chain.lead_resistance_ohm
    hand = 2 * r_l * COPPER_TCR_PER_K / (chain.gauge_factor * (chain.gauge_resistance_ohm
                                                               + 2 * r_l))
    assert two.lead_wires["zero_strain_per_K"] == pytest.approx(hand, rel=1e-12)
    # desensitisation drift: two leads in the gauge's arm against one
    assert two.span_terms_per_K["lead_wires"] < three.span_terms_per_K["lead_wires"] < 0
    assert two.span_rel_per_K == pytest.approx(_hand_span_per_K(_plan(), 2), rel=1e-9)
    for t3, t2 in zip(three.records, two.records):
        assert t2["drift_N_per_K"] > t3["drift_N_per_K"]
    longer = _report(_plan(**{"readout.lead_wires": "two-wire", "readout.lead_length_mm": 5000.0}))
    assert longer.lead_wires["zero_strain_per_K"] > two.lead_wires["zero_strain_per_K"]


def test_kobj_drift_grows_as_one_over_the_force():
    plan = _plan()
    req = requirements_of(plan)
    k_obj = np.geomspace(*req.kobj_range_N_per_mm, KOBJ_POINTS)
    F = req.full_scale_force_N
    full = kobj_thermal_error(plan, None, F, 1.0, k_obj)
    tenth = kobj_thermal_error(plan, None, F / 10, 1.0, k_obj)
    assert full and [u.element for u in full] == [u.element for u in tenth]
    for a, b in zip(full, tenth):
        assert np.max(np.abs(b.zero_rel)) == pytest.approx(10 * np.max(np.abs(a.zero_rel)),
                                                           rel=0.01)
        np.testing.assert_allclose(a.span_rel, b.span_rel)
    rep = thermal_report(plan, req)
    for r in rep.records:
        if r["kobj_error_rel_per_K"] is None:
            continue
        by = r["kobj_error_rel_per_K_by_force_fraction"]
        zero = {phi: v - r["kobj_span_rel_per_K"] for phi, v in by.items()}
        assert zero["0.1"] == pytest.approx(10 * zero["1"], rel=0.01)
        assert r["kobj_error_rel_per_K"] == by["0.1"] > r["kobj_error_rel_per_K_at_full_scale"]
    assert rep.worst_kobj["kobj_error_rel_per_K"] == max(
        r["kobj_error_rel_per_K"] for r in rep.records if r["kobj_error_rel_per_K"] is not None)


def test_kobj_thermal_error_span_is_the_springs_scale_and_refuses_a_zero_force():
    plan = _plan()
    g = material_grade("6061-T6")
    units = kobj_thermal_error(plan, None, 0.1, 5.0, [1.0, 3.0])
    scale = (1 + 5 * g.youngs_modulus_tc_per_K) * (1 + 5 * g.cte_ppm_per_K * 1e-6)
    np.testing.assert_allclose(units[0].span_rel, 1 / scale - 1, rtol=1e-12)
    np.testing.assert_allclose(units[0].total_rel, units[0].zero_rel + units[0].span_rel)
    with pytest.raises(DesignError) as e:
        kobj_thermal_error(plan, None, 0.0, 1.0, [1.0])
    assert "force_N" in str(e.value)


def _plan_with_unstated_readout(**overrides):
    data = default_design_data()
    data.pop("readout", None)
    return plan_from_dict(with_overrides(data, overrides))


def test_default_excitation_follows_tn502_and_a_stated_one_wins():
    chain = readout_chain(_plan_with_unstated_readout())
    area = chain.grid_length_mm * chain.grid_width_mm
    assert chain.grid_power_density_W_per_mm2 <= TN502_POWER_DENSITY_W_PER_MM2
    step_up = (chain.excitation_V + 0.1) ** 2 / (4 * chain.gauge_resistance_ohm * area)
    assert step_up > TN502_POWER_DENSITY_W_PER_MM2
    assert "TN-502" in dict(chain.sources)["excitation_V"]
    bigger = readout_chain(_plan_with_unstated_readout(**{"readout.grid_length_mm": 2.0,
                                                          "readout.grid_width_mm": 2.0}))
    assert bigger.excitation_V > chain.excitation_V
    stated = readout_chain(_plan_with_unstated_readout(**{"readout.excitation_V": 2.5}))
    assert stated.excitation_V == 2.5 and dict(stated.sources)["excitation_V"] == "design file"
    # above TN-502's thin-section guidance: the thermal report says so
    assert "ABOVE" in render(_report(_plan(**{"readout.excitation_V": 2.5})))
    assert "ABOVE" not in render(_report(_plan_with_unstated_readout()))


@pytest.mark.parametrize("key, value", [("gauge_stc_ppm_per_K", 60.0),
                                        ("gauge_factor_tc_pct_per_100K", 20.0),
                                        ("substrate_cte_ppm_per_K", -1.0),
                                        ("gauge_heat_transfer_W_per_mm2_K", 0.0),
                                        ("dummy_gauge", "full-bridge"),
                                        ("lead_wires", "four-wire"),
                                        ("lead_length_mm", -1.0),
                                        ("lead_resistance_ohm_per_m", 1000.0),
                                        ("substrate_modulus_tc_per_K", 0.01)])
def test_bad_readout_values_are_refused_naming_field_value_and_range(key, value):
    with pytest.raises(DesignError) as e:
        _plan(**{f"readout.{key}": value})
    assert f"readout.{key}" in str(e.value) and str(value) in str(e.value)
    assert "allowed" in str(e.value)


def test_a_material_without_grade_needs_the_modulus_coefficient_stated():
    data = default_design_data()
    data["material"].pop("grade", None)
    data["material"]["yield_strength_MPa"] = 276.0
    data["readout"] = {"substrate_cte_ppm_per_K": 23.6}
    plan = plan_from_dict(data)
    with pytest.raises(DesignError) as e:
        _report(plan)
    assert "readout.substrate_modulus_tc_per_K" in str(e.value)
    data["readout"]["substrate_modulus_tc_per_K"] = -5e-4
    rep = _report(plan_from_dict(data))
    assert rep.span_terms_per_K["modulus"] == pytest.approx(5e-4)
    assert rep.setting.sources["substrate_modulus_tc_per_K"] == "design file"


def test_every_grade_carries_a_cte_and_a_modulus_coefficient_with_their_sources():
    for g in material_grades().values():
        assert 0 < g.cte_ppm_per_K < 200 and g.source("cte_ppm_per_K")
        assert g.provenance("youngs_modulus_tc_per_K")


@pytest.mark.parametrize("grade", ["6061-T6", "17-4PH-H900", "Ti-6Al-4V-annealed",
                                   "CuBe-C17200-TF00"])
def test_the_report_names_a_document_for_every_sourced_grade(grade):
    """Every grade but 7075-T6 carries a document for its modulus coefficient: the report
    names it, and neither the source nor the text calls it a stand-in."""
    data = json.loads(json.dumps(_load(EXAMPLE)))
    data["material"] = {"name": grade, "grade": grade}
    rep = _report(plan_from_dict(data))
    where = rep.setting.sources["substrate_modulus_tc_per_K"]
    assert rep.setting.modulus_tc_sourced and where.startswith(f"grade {grade}: ")
    text = render(rep)
    assert "UNSOURCED" not in text and "stand-in" not in where
    tc = material_grades()[grade].youngs_modulus_tc_per_K
    assert rep.span_terms_per_K["modulus"] == pytest.approx(-tc)


def test_an_unsourced_modulus_coefficient_is_named_so_in_the_report():
    data = json.loads(json.dumps(_load(EXAMPLE)))
    data["material"] = {"name": "7075-T6", "grade": "7075-T6"}  # 6061's figure stands in
    plan = plan_from_dict(data)
    rep = _report(plan)
    assert not rep.setting.modulus_tc_sourced
    assert rep.setting.sources["substrate_modulus_tc_per_K"].split(": ", 1)[1].startswith(
        "unsourced")
    assert "UNSOURCED" in render(rep)


def _load(path):
    import tomllib

    return tomllib.loads(path.read_text())


def test_stated_requirement_is_verified_and_fails_when_too_tight():
    loose = _plan(**{"requirements.max_thermal_drift_N_per_K": 1.0})
    tight = _plan(**{"requirements.max_thermal_drift_N_per_K": 1e-6,
                     "readout.gauge_stc_ppm_per_K": 10.8})
    rec = {r["requirement"]: r for r in verification_matrix(loose)}
    good = rec["max_thermal_drift_N_per_K"]
    assert good["verdict"] == "pass"
    assert good["span_rel_per_K"] == pytest.approx(_hand_span_per_K(loose, 1), rel=1e-9)
    assert 0 < good["kobj_error_rel_per_K_worst"] and good["kobj_error_force_fraction"] == 0.1
    bad = {r["requirement"]: r for r in verification_matrix(tight)}["max_thermal_drift_N_per_K"]
    assert bad["verdict"] == "fail" and bad["margin_rel"] < 0
    assert "max_thermal_drift_N_per_K" not in {r["requirement"] for r in
                                               verification_matrix(_plan())}


def test_thermal_command_json_on_the_ti_example(capsys):
    assert main(["thermal", "--design", str(EXAMPLE), "--element", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [r["element"] for r in out["elements"]] == [2]
    assert out["setting"]["substrate_cte_ppm_per_K"] == pytest.approx(8.6)
    assert out["span_rel_per_K"] == pytest.approx(sum(out["span_terms_rel_per_K"].values()))
    assert out["setting"]["lead_wires"] == "three-wire"
    assert "paper" not in json.dumps(out).lower()
    assert math.isfinite(out["grid_power_density_W_per_mm2"])


def test_thermal_command_text_says_the_kobj_error_scales_as_one_over_f(capsys):
    assert main(["thermal", "--design", str(EXAMPLE)]) == 0
    text = capsys.readouterr().out
    assert "1/F" in text and "K_obj %/K at 10 %" in text and "span per K" in text


def test_self_heating_is_stated_against_the_force_resolution_readout_quotes():
    plan = _plan()
    report = _report(plan)
    by_part = {r["part"]: r for r in report.records}
    quoted = {r["part"]: r["force_resolution_N"]
              for r in readout_report(plan, requirements_of(plan)).records}
    for part, rec in by_part.items():  # one figure: the read-out's own resolution
        assert rec["force_resolution_N"] == pytest.approx(quoted[part], rel=1e-12)
    worst = max(report.records, key=lambda r: abs(r["self_heating_offset_N"]))
    line = next(x for x in render(report).splitlines() if "self-heating:" in x)
    ratio = abs(worst["self_heating_offset_N"]) / worst["force_resolution_N"]
    assert f"{ratio:.3g} x its force resolution" in line and f"element {worst['element']}" in line


def test_a_new_design_chooses_its_excitation_instead_of_keeping_the_bases():
    from tactcad.studies.inverse_design import start_tables

    base = _plan(**{"readout.excitation_V": 2.5}).raw
    data = start_tables(base, "base")
    assert "excitation_V" not in data.get("readout", {})
    assert "readout.excitation_V" not in data.get("assumptions", {})
    kept = start_tables(base, "base", kept=frozenset({"readout.excitation_V"}))
    assert kept["readout"]["excitation_V"] == 2.5  # the user's --set stays
