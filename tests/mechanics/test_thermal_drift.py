"""Thermal drift: apparent strain from the CTE / STC mismatch (TN-504), equivalent tip force and
K_obj error per kelvin, self-heating, the half-bridge dummy gauge, and the requirement."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
from tactcad.errors import DesignError
from tactcad.mechanics.readout_chain import readout_report
from tactcad.mechanics.thermal_drift import matched_stc_ppm_per_K, thermal_report
from tactcad.studies.verification import requirements_of, verification_matrix
from tactcad.vocabulary.material_library import material_grades

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _plan(**overrides):
    return plan_from_dict(with_overrides(default_design_data(), overrides))


def _report(plan):
    return thermal_report(plan, requirements_of(plan))


def test_one_element_matches_the_hand_calculation_from_the_published_relation():
    # 6061-T6 (23.6 ppm/K) under a steel-matched STC 06 gauge (6 ppm/degF = 10.8 ppm/K), K_t 1 %:
    # TN-504: eps/dT = (1 + K_t) / (1 - 0.285 K_t) (alpha_S - alpha_STC)
    plan = _plan(**{"readout.gauge_stc_ppm_per_K": 10.8,
                    "readout.gauge_transverse_sensitivity": 0.01})
    hand_strain = 1.01 / (1 - 0.285 * 0.01) * (23.6 - 10.8) * 1e-6
    rep = _report(plan)
    assert rep.apparent_strain_per_K == pytest.approx(hand_strain, rel=1e-12)
    eps_per_N = readout_report(plan, requirements_of(plan)).records[3]["gauge_strain_per_N"]
    elem = rep.records[3]
    assert elem["apparent_force_N_per_K"] == pytest.approx(hand_strain / eps_per_N, rel=1e-9)
    # gauge factor term: full-scale force x 115 ppm/K
    F = requirements_of(plan).full_scale_force_N
    assert elem["drift_N_per_K"] == pytest.approx(abs(hand_strain / eps_per_N) + F * 115e-6)


def test_steel_matched_gauge_on_6061_drifts_more_than_an_aluminium_matched_one():
    steel = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8}))
    alu = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 23.4}))
    assert steel.worst["drift_N_per_K"] > 5 * alu.worst["drift_N_per_K"]
    for s, a in zip(steel.records, alu.records):
        assert abs(s["apparent_force_N_per_K"]) > abs(a["apparent_force_N_per_K"])
        if s["kobj_error_rel_per_K"] is not None:
            assert s["kobj_error_rel_per_K"] > a["kobj_error_rel_per_K"]


def test_unstated_stc_is_the_series_nearest_the_material_and_says_so():
    assert matched_stc_ppm_per_K(23.6) == (pytest.approx(23.4), 13)
    assert matched_stc_ppm_per_K(8.6) == (pytest.approx(9.0), 5)
    rep = _report(_plan())
    assert rep.setting.stc_ppm_per_K == pytest.approx(23.4)
    assert "not stated" in rep.setting.sources["gauge_stc_ppm_per_K"]
    assert "6061-T6" in rep.setting.sources["substrate_cte_ppm_per_K"]


def test_zero_mismatch_leaves_only_the_gauge_factor_term_and_no_kobj_error():
    rep = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 23.6}))
    F = rep.full_scale_force_N
    for r in rep.records:
        assert r["apparent_force_N_per_K"] == 0.0
        assert r["drift_N_per_K"] == pytest.approx(F * 115e-6)
        assert r["kobj_error_rel_per_K"] in (None, 0.0)


def test_huge_cte_scales_the_apparent_force_linearly():
    small = _report(_plan(**{"readout.substrate_cte_ppm_per_K": 33.4,
                             "readout.gauge_stc_ppm_per_K": 23.4}))
    huge = _report(_plan(**{"readout.substrate_cte_ppm_per_K": 200.0,
                            "readout.gauge_stc_ppm_per_K": 0.0}))
    ratio = huge.records[0]["apparent_force_N_per_K"] / small.records[0]["apparent_force_N_per_K"]
    assert ratio == pytest.approx(20.0)


def test_half_bridge_dummy_cancels_the_apparent_term_and_self_heating():
    quarter = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8}))
    half = _report(_plan(**{"readout.gauge_stc_ppm_per_K": 10.8,
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


@pytest.mark.parametrize("key, value", [("gauge_stc_ppm_per_K", 60.0),
                                        ("gauge_factor_tc_pct_per_100K", 20.0),
                                        ("substrate_cte_ppm_per_K", -1.0),
                                        ("gauge_heat_transfer_W_per_mm2_K", 0.0),
                                        ("dummy_gauge", "full-bridge")])
def test_bad_readout_values_are_refused_naming_field_value_and_range(key, value):
    with pytest.raises(DesignError) as e:
        _plan(**{f"readout.{key}": value})
    assert f"readout.{key}" in str(e.value) and str(value) in str(e.value)
    assert "allowed" in str(e.value)


def test_every_grade_carries_a_cte_with_its_source():
    for g in material_grades().values():
        assert 0 < g.cte_ppm_per_K < 200 and g.source("cte_ppm_per_K")


def test_stated_requirement_is_verified_and_fails_when_too_tight():
    loose = _plan(**{"requirements.max_thermal_drift_N_per_K": 1.0})
    tight = _plan(**{"requirements.max_thermal_drift_N_per_K": 1e-6,
                     "readout.gauge_stc_ppm_per_K": 10.8})
    rec = {r["requirement"]: r for r in verification_matrix(loose)}
    assert rec["max_thermal_drift_N_per_K"]["verdict"] == "pass"
    bad = {r["requirement"]: r for r in verification_matrix(tight)}["max_thermal_drift_N_per_K"]
    assert bad["verdict"] == "fail" and bad["margin_rel"] < 0
    assert "max_thermal_drift_N_per_K" not in {r["requirement"] for r in
                                               verification_matrix(_plan())}


def test_thermal_command_json_on_the_ti_example(capsys):
    assert main(["thermal", "--design", str(EXAMPLE), "--element", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [r["element"] for r in out["elements"]] == [2]
    assert out["setting"]["substrate_cte_ppm_per_K"] == pytest.approx(8.6)
    assert "paper" not in json.dumps(out).lower()
