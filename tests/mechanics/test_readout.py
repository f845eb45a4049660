"""The read-out chain: grid-averaged gauge strain, quarter-bridge signal, noise, resolution,
and the paper's Table 1 beside the prediction."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import default_design_data, load_design, plan_from_dict, with_overrides
from tactcad.design.readout_section import DEFAULTS
from tactcad.errors import DesignError
from tactcad.paper.data import table1
from tactcad.mechanics.readout_chain import (beam_face_mean_strain_per_N,
                                             beam_surface_strain_per_N, bridge_nonlinearity_rel,
                                             grid_strain_per_N, noise_budget_V, readout_chain,
                                             readout_report)
from tactcad.studies.verification import requirements_of, verification_matrix

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
PAPER_TEXT = re.compile(r"paper|table ?[12]\b", re.IGNORECASE)


def _report(plan):
    return readout_report(plan, requirements_of(plan))


def _plan(**overrides):
    return plan_from_dict(with_overrides(default_design_data(), overrides))


def test_grid_average_is_below_the_peak_and_tends_to_it_for_a_short_grid():
    plan = load_design()
    g, m = plan.element(4).geometry, plan.material
    peak = float(beam_surface_strain_per_N(g, m, g.hinge_x_mm))
    # peak: eps/F = 6 a / (E b t^2), compressive on the top face
    assert peak == pytest.approx(-6 * g.arm_length_mm / (m.youngs_modulus_MPa * 3.0 * 0.25 ** 2))
    short, default, long_ = (beam_face_mean_strain_per_N(g, m, L) for L in (0.02, 0.6, 2.0))
    assert short == pytest.approx(peak, rel=1e-3)
    assert abs(long_) < abs(default) < abs(peak)


def test_the_searchs_vectorised_grid_reading_is_the_read_outs_for_each_element():
    """closed_form_grid_read_per_N (design searches, over arrays of candidates) reads what
    grid_strain_per_N reads for one element, on every shipped example (three materials,
    grids inside and outside the fitted range), and an independent trapezoid average of the
    EB face strain agrees with the Gauss-Legendre one to 1e-5."""
    import numpy as np

    from tactcad.mechanics.readout_chain import closed_form_grid_read_per_N, eb_face_mean_strain_per_N

    from tactcad.project_folder import die_examples

    for design in sorted((ROOT / "hardware").glob("*/*.toml")):
        if design.stem in ("rigs", "scenes") or design.parent.name in die_examples():
            continue
        plan = load_design(design)
        chain = readout_chain(plan)
        gs = [s.geometry for s in plan.slots]
        vec = closed_form_grid_read_per_N([g.web_thickness_mm for g in gs],
                                          [g.notch_radius_mm for g in gs],
                                          [g.arm_length_mm for g in gs], gs[0], plan.material,
                                          chain)
        one = [grid_strain_per_N(g, plan.material, chain, "closed-form")["grid"] for g in gs]
        assert vec == pytest.approx(one, rel=1e-12), design.name
        g = gs[0]
        L = chain.grid_length_mm
        x = np.linspace(g.hinge_x_mm - L / 2, g.hinge_x_mm + L / 2, 200001)
        trapezoid = np.trapezoid(beam_surface_strain_per_N(g, plan.material, x), x) / L
        assert float(eb_face_mean_strain_per_N(g.web_thickness_mm, g.notch_radius_mm,
                                          g.arm_length_mm, L, g.sheet_thickness_mm,
                                          plan.material.youngs_modulus_MPa, g.base_height_mm,
                                          g.arm_height_mm)) == pytest.approx(trapezoid, rel=1e-5)


def test_fem2d_field_average_agrees_with_beam_theory_over_the_grid():
    plan = load_design()
    g, m = plan.element(1).geometry, plan.material
    chain = readout_chain(plan)
    fem = grid_strain_per_N(g, m, chain, "fem2d")
    beam = grid_strain_per_N(g, m, chain, "closed-form")
    assert fem["grid"] < 0 and beam["grid"] < 0
    # both carry the fitted width factor; fem2d's own profile against EB x C's: the fit's error
    assert fem["surface"] == pytest.approx(beam["surface"], rel=beam["error_rel"] + 0.01)
    # fem2d meshes the glue line and carrier and reads the grid's own plane; the closed
    # form multiplies the face by the transformed section's read factor: two models of the
    # layer, within 3 % of each other
    assert fem["read_factor"] != beam["read_factor"]
    assert fem["read_factor"] == pytest.approx(beam["read_factor"], rel=0.03)
    assert fem["grid"] == pytest.approx(beam["grid"], rel=beam["error_rel"] + 0.04)
    assert fem["source"] != beam["source"] and "meshed" in fem["grid_source"]


def test_quarter_bridge_signal_scales_with_excitation_gain_and_gauge_factor():
    base = _report(load_design())
    changed = _report(_plan(**{"readout.excitation_V": 5.0, "readout.amplifier_gain": 10.0,
                                      "readout.gauge_factor": 4.0}))
    for a, b in zip(base.records, changed.records):
        # V = G V_ex GF eps / 4: 2 x 0.1 x 2 = 0.4
        assert b["sensitivity_V_per_N"] == pytest.approx(0.4 * a["sensitivity_V_per_N"])
        assert a["k_v_V_per_mm"] == pytest.approx(a["sensitivity_V_per_N"]
                                                  * a["stiffness_N_per_mm"])
    assert base.chain.volts_per_strain == pytest.approx(100 * 2.5 * 2.0 / 4)


def test_averaging_more_samples_improves_force_resolution_by_its_square_root():
    """Samples far apart against the filtered noise's correlation time (1 kS/s behind a
    1 kHz RC: rho = exp(-2 pi) = 0.002) average their white noise as independent ones (to
    0.2 %), while the 1/f part stays; sampled
    far faster than the filter passes (1 MS/s), averaging 40 gains almost nothing, as
    the exponential autocorrelation's sum says (computed here as a direct double sum)."""
    white = {"readout.amplifier_flicker_nV_per_rtHz_at_1Hz": 0.0}  # 1/f does not average
    a = _report(_plan(**white))
    b = _report(_plan(**white, **{"readout.samples_averaged": 40}))
    for x, y in zip(a.records, b.records):
        assert y["force_resolution_N"] == pytest.approx(x["force_resolution_N"] / 2, rel=2e-3)
    assert b.array_kobj_resolution_rel < a.array_kobj_resolution_rel
    # with the amplifier's 1/f noise, averaging 4 x as many gains less than 2 x
    c, d = _report(load_design()), _report(_plan(**{"readout.samples_averaged": 40}))
    for x, y in zip(c.records, d.records):
        assert x["force_resolution_N"] / 2 < y["force_resolution_N"] < x["force_resolution_N"]
    fast = readout_chain(_plan(**{"readout.samples_averaged": 40,
                                  "readout.sample_rate_Hz": 1e6}))
    rho = math.exp(-1e-6 / fast.noise_correlation_time_s)
    n = 40
    variance_of_mean = sum(rho ** abs(i - j) for i in range(n) for j in range(n)) / n ** 2
    assert fast.effective_samples == pytest.approx(1 / variance_of_mean, rel=1e-9)
    assert 1.0 < fast.effective_samples < 1.1


def test_noise_budget_uses_the_daq_range_noise_of_the_spec_sheet():
    chain = readout_chain(_plan(**{"readout.daq_range_V": 10.0}))
    assert chain.daq_noise_uV_rms == 280.0
    n = noise_budget_V(chain)
    assert n["per_sample"] ** 2 == pytest.approx(sum(n[k] ** 2 for k in (
        "amplifier", "bridge_johnson", "daq", "quantisation")))
    assert chain.lsb_V == pytest.approx(20.0 / 2 ** 16)


def test_bridge_nonlinearity_is_gf_eps_over_two_for_small_strain():
    assert bridge_nonlinearity_rel(2.0, 1e-3) == pytest.approx(1e-3, rel=2e-3)
    assert bridge_nonlinearity_rel(2.0, -1e-3) < 0


def test_gauge_factor_and_resistance_follow_the_library_gauge():
    plan = _plan(**{"strength.gauge": "constantan-foil-hbm-y"})
    chain = readout_chain(plan)
    assert chain.gauge_name == "constantan-foil-hbm-y"
    assert dict(chain.sources)["gauge_factor"].startswith("library gauge")


@pytest.mark.parametrize("key, value, field", [
    ("readout.grid_width_mm", 3.5, "readout.grid_width_mm"),
    ("readout.grid_length_mm", 0.0, "readout.grid_length_mm"),
    ("readout.bridge", "full", "readout.bridge"),
    ("readout.daq_bits", 12.5, "readout.daq_bits"),
    ("readout.excitation_V", "2.5", "readout.excitation_V"),
    ("readout.gain", 100, "readout.gain"),
    ("readout.filter_order", 9, "readout.filter_order"),
    ("readout.filter_corner_Hz", 0.0, "readout.filter_corner_Hz"),
    ("readout.daq_ranges_V", [], "readout.daq_ranges_V"),
    ("readout.daq_ranges_V", [0.5, -1.0], "readout.daq_ranges_V[2]"),
    ("readout.daq_range_margin", 0.5, "readout.daq_range_margin"),
])
def test_bad_readout_values_are_refused_naming_the_field(key, value, field):
    with pytest.raises(DesignError) as exc:
        _plan(**{key: value})
    assert exc.value.field == field


def test_readout_json_on_the_papers_design_sets_table1_beside_each_element(capsys):
    assert main(["readout", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    measured = {r.element: r for r in table1()}
    recs = {r["element"]: r for r in out["elements"]}
    for number, row in measured.items():
        r = recs[number]
        for key in ("grid_strain_per_N", "k_v_V_per_mm", "sensitivity_V_per_N",
                    "force_resolution_N", "kobj_resolution_rel"):
            assert key in r
        assert r["table1_k_v_V_per_mm"] == row.K_v_V_per_mm
        assert r["table1_sensitivity_V_per_N"] == row.K_v_over_K_V_per_N
        assert r["table1_sensitivity_ratio"] == pytest.approx(
            row.K_v_over_K_V_per_N / r["sensitivity_V_per_N"])
        # the gain that would reconcile: assumed gain x ratio
        assert r["reconciling_gain"] == pytest.approx(100 * r["table1_sensitivity_ratio"])
    assert recs[5]["table1_k_v_V_per_mm"] is None  # element 5 was not calibrated
    t = out["table1"]
    assert t["elements"] == 9 and t["sensitivity_ratio_min"] < 1 < t["sensitivity_ratio_max"]
    # the measured signals and the prediction agree in sign (compressed top face)
    assert all(r["sensitivity_V_per_N"] < 0 for r in out["elements"])


def test_readout_of_the_example_design_is_paper_neutral(capsys):
    assert main(["readout", "--design", str(EXAMPLE), "--json"]) == 0
    text = capsys.readouterr().out
    out = json.loads(text)
    assert "table1" not in out and not PAPER_TEXT.search(text)
    assert all("table1_k_v_V_per_mm" not in r for r in out["elements"])
    assert out["full_scale_force_N"] == 0.1
    assert main(["readout", "--design", str(EXAMPLE)]) == 0
    assert not PAPER_TEXT.search(capsys.readouterr().out)


def test_verify_checks_kobj_resolution_through_the_read_out_chain():
    records = verification_matrix(load_design())
    rec = next(r for r in records if r["requirement"] == "kobj_resolution_rel")
    # the paper's design states none: derived from this very prediction, reported (info)
    assert rec["verdict"] == "info" and rec["predicted"] == pytest.approx(
        _report(load_design()).array_kobj_resolution_rel)
    # a noisier chain (one sample, +/-10 V range, gain 10) against a tight requirement fails
    tight = _plan(**{"requirements.kobj_resolution_rel": 0.05, "readout.samples_averaged": 1,
                     "readout.amplifier_gain": 10.0, "readout.daq_range_V": 10.0})
    rec = next(r for r in verification_matrix(tight)
               if r["requirement"] == "kobj_resolution_rel")
    assert not rec["pass"] and rec["margin_rel"] < 0


def test_as_built_webs_explain_part_of_table1s_signal_spread(capsys):
    """Each element's own web (from its measured K) narrows the spread of measured over
    predicted signal per newton: the thicker web of element 8 gives less strain."""
    assert main(["readout", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    t = out["table1"]
    assert t["as_built_web_ratio_rel_std"] < t["sensitivity_ratio_rel_std"]
    recs = {r["element"]: r for r in out["elements"]}
    assert recs[8]["table1_as_built_web_mm"] > recs[1]["table1_as_built_web_mm"]
    assert recs[8]["table1_sensitivity_ratio"] < recs[1]["table1_sensitivity_ratio"]


def test_readout_piped_into_a_reader_that_stops_early_is_no_error():
    import subprocess
    import sys

    p = subprocess.run(f"{sys.executable} -m tactcad.cli readout --quiet | head -c 10",
                       shell=True, capture_output=True, text=True, cwd=ROOT)
    assert "error" not in p.stderr and len(p.stdout) == 10


def test_a_smaller_variant_of_the_papers_design_compares_only_its_table1_elements(capsys):
    argv = ["readout", "--json", "--set", "array.columns=2", "--set", "arms.lengths_mm=[4,5,4,5]"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    recs = {r["element"]: r for r in out["elements"]}
    assert recs[1]["table1_k_v_V_per_mm"] == -7.3  # element 1: Table 1's arm, 4 mm
    assert recs[2]["table1_k_v_V_per_mm"] is None  # element 2 has 5 mm, Table 1's has 7 mm
    assert out["table1"]["elements"] == 1


def test_butterworth_noise_bandwidth_is_the_integral_of_the_power_response():
    """ENBW / f_c = integral of 1 / (1 + x^2n) dx over x >= 0 (pi/2 for the RC filter)."""
    import numpy as np

    from tactcad.design.readout_section import butterworth_noise_bandwidth_ratio

    x = np.linspace(0.0, 2000.0, 2_000_001)
    for n in (1, 2, 4):
        integral = np.trapezoid(1.0 / (1.0 + x ** (2 * n)), x) + (
            2000.0 ** (1 - 2 * n) / (2 * n - 1))  # the tail beyond x = 2000
        assert butterworth_noise_bandwidth_ratio(n) == pytest.approx(integral, rel=1e-4)


def test_anti_alias_filter_sets_the_noise_bandwidth_and_lowers_the_force_resolution():
    """The amplifier and bridge noise scale with sqrt(noise bandwidth): the filter's
    bandwidth replaces the amplifier's 200 kHz pole, the DAQ and quantisation terms stay."""
    import math

    filtered = readout_chain(_plan())
    open_chain = readout_chain(_plan(**{"readout.filter_order": 0,
                                        "readout.daq_range_V": filtered.daq_range_V}))
    assert filtered.filter_order >= 1 and open_chain.filter_corner_Hz == math.inf
    assert open_chain.noise_bandwidth_Hz == pytest.approx(math.pi / 2 * open_chain.bandwidth_Hz)
    assert filtered.noise_bandwidth_Hz == pytest.approx(math.pi / 2 * filtered.filter_corner_Hz)
    a, b = noise_budget_V(open_chain), noise_budget_V(filtered)
    ratio = math.sqrt(filtered.noise_bandwidth_Hz / open_chain.noise_bandwidth_Hz)
    assert b["amplifier"] == pytest.approx(a["amplifier"] * ratio)
    assert b["bridge_johnson"] == pytest.approx(a["bridge_johnson"] * ratio)
    assert b["daq"] == a["daq"] and b["quantisation"] == a["quantisation"]
    ra = _report(_plan(**{"readout.filter_order": 0,
                          "readout.daq_range_V": filtered.daq_range_V}))
    rb = _report(_plan())
    for x, y in zip(ra.records, rb.records):
        assert y["force_resolution_N"] == pytest.approx(
            x["force_resolution_N"] * b["reading"] / a["reading"])
        assert y["force_resolution_N"] < x["force_resolution_N"]
    with pytest.raises(DesignError) as exc:
        _plan(**{"readout.filter_order": 0, "readout.filter_corner_Hz": 500.0})
    assert exc.value.field == "readout.filter_corner_Hz"


def test_daq_range_is_the_smallest_that_holds_the_signal_with_margin():
    """Not stated, the range is the smallest of the DAQ's that holds the margin times the
    signal at the gauge's fatigue strain; a higher gain moves it up; a stated range stays."""
    plan = _plan()
    chain = readout_chain(plan)
    need = chain.daq_range_margin * chain.volts_per_strain * plan.strength.gauge.fatigue_strain
    assert chain.daq_range_V >= need
    assert all(r < need for r in chain.daq_ranges_V if r < chain.daq_range_V)
    assert chain.source("daq_range_V").startswith("chosen")
    # the full-scale signal fits in it
    assert all(r["daq_range_used_rel"] <= 1 for r in _report(plan).records)
    louder = readout_chain(_plan(**{"readout.excitation_V": 10.0}))
    assert louder.daq_range_V > chain.daq_range_V
    stated = readout_chain(_plan(**{"readout.daq_range_V": 5.0}))
    assert stated.daq_range_V == 5.0 and stated.source("daq_range_V") == "design file"
    # a smaller range lowers the DAQ noise and the quantisation step, so the resolution
    assert noise_budget_V(chain)["reading"] < noise_budget_V(stated)["reading"]
    none_holds = readout_chain(_plan(**{"readout.daq_ranges_V": [0.1, 0.2]}))
    assert none_holds.daq_range_V == 0.2 and "none holds" in none_holds.source("daq_range_V")


def test_the_bonded_layer_raises_k_by_less_than_it_stiffens_the_web():
    """The layer's K rise (EB over the carrier) is positive, below its stiffening of the
    web's thinnest section (it covers only the carrier, and thicker sections gain less),
    nil for a layer of no modulus, and grows with the glue line; the read-out states the
    rise its own K carries."""
    import dataclasses

    from tactcad.mechanics.ladder import estimate, gauge_k_rise

    plan = load_design()
    g, m = plan.element(4).geometry, plan.material
    chain = readout_chain(plan)
    rel = gauge_k_rise("closed-form", g, m)
    web = grid_strain_per_N(g, m, chain, "closed-form")["stiffening_rel"]
    assert 0.02 < rel < web
    soft = dataclasses.replace(g, gauge=dataclasses.replace(g.gauge, modulus_MPa=1e-6))
    assert gauge_k_rise("closed-form", soft, m) == pytest.approx(0.0, abs=1e-9)
    thicker = dataclasses.replace(g, gauge=dataclasses.replace(
        g.gauge, height_mm=g.gauge.height_mm + 0.02))
    assert gauge_k_rise("closed-form", thicker, m) > rel
    assert gauge_k_rise("closed-form", g.bare(), m) == 0.0
    report = _report(plan)
    assert all(r["gauge_layer_k_rel"] == pytest.approx(gauge_k_rise(
        report.model, plan.element(r["element"]).geometry, m)) for r in report.records)
    assert all(r["stiffness_N_per_mm"] == pytest.approx(estimate(
        report.model, plan.element(r["element"]).geometry, m).stiffness_N_per_mm)
        for r in report.records)


def test_readout_and_calibrate_fit_one_gain_of_the_grids_strain_through_table1():
    """One quantity, one number: the gain through Table 1's signals at each element's
    as-built web is the read-out's (its V per unit strain of the grid's strain) and
    `calibrate`'s audit's, and both read the grid's strain, compressive over the web."""
    from tactcad.paper import calibration_audit as ca

    from tactcad.paper.table1 import readout_table1

    plan = load_design()
    report = _report(plan)
    t = readout_table1(report.records, report.chain, plan, "closed-form")
    audit = ca.audit(plan, ca.from_table1())
    assert audit["gauge_gain_V_per_strain"] > 0
    assert t["fitted_volts_per_strain_as_built"] == pytest.approx(
        audit["gauge_gain_V_per_strain"], rel=1e-4)
    assert all(r["grid_strain_per_N"] < 0 for r in audit["elements"])


def test_the_ad621s_1_over_f_density_gives_back_its_data_sheets_low_band_figure():
    """e_f from the AD621's 0.28 uV p-p over 0.1-10 Hz and its 9 nV/sqrt(Hz) floor: the
    integral of e_w^2 + e_f^2 / f over the band (quadrature, not the closed form) is the
    band's rms squared, (0.28 uV / 6.6)^2; a floor that accounts for the whole figure
    leaves no 1/f part."""
    from scipy.integrate import quad

    from tactcad.design.readout_section import flicker_density_at_1Hz

    e_f = flicker_density_at_1Hz(0.28, (0.1, 10.0), 9.0)
    variance, _ = quad(lambda f: 9.0 ** 2 + e_f ** 2 / f, 0.1, 10.0)
    assert variance == pytest.approx((280.0 / 6.6) ** 2, rel=1e-9)
    assert 10.0 < e_f < 20.0  # a 1/f corner of a few Hz, as instrumentation amplifiers have
    assert flicker_density_at_1Hz(0.28, (0.1, 10.0), 20.0) == 0.0
    assert readout_chain(load_design()).amplifier_flicker_nV_per_rtHz_at_1Hz == pytest.approx(
        e_f, rel=1e-12)


def test_a_readings_1_over_f_noise_spans_tare_to_averaging_window_and_is_not_averaged():
    """The reading's variance is the white part averaged plus the 1/f part over 1/T_tare ...
    f_s / (2 N), by hand: G e_f sqrt(ln(f_hi / f_lo)) for the amplifier and
    G (V_ex / 4) sqrt(alpha_H / N_e ln(f_hi / f_lo)) for the foil grid (Hooge's 2e-3, 8.7e22
    electrons per cm^3 in half the grid's area of 5 um foil); a longer wait after the tare
    reads more of it, a stated zero removes the amplifier's, another amplifier has none."""
    chain = readout_chain(load_design())
    f_lo, f_hi = 1 / 10.0, min(chain.noise_bandwidth_Hz, 1000.0 / (2 * 10))
    assert chain.flicker_band_Hz == pytest.approx((f_lo, f_hi))
    g, logs = chain.amplifier_gain, math.log(f_hi / f_lo)
    n = noise_budget_V(chain)
    assert n["amplifier_flicker"] == pytest.approx(
        g * chain.amplifier_flicker_nV_per_rtHz_at_1Hz * 1e-9 * math.sqrt(logs), rel=1e-12)
    electrons = 8.7e22 * 0.5 * (chain.grid_length_mm * 0.1) * (chain.grid_width_mm * 0.1) * 5e-4
    assert n["gauge_flicker"] == pytest.approx(
        g * chain.excitation_V / 4 * math.sqrt(2e-3 / electrons * logs), rel=1e-12)
    assert n["gauge_flicker"] < 0.01 * n["amplifier_flicker"]  # a metal grid: negligible
    quiet = readout_chain(_plan(**{"readout.amplifier_flicker_nV_per_rtHz_at_1Hz": 0.0}))
    q = noise_budget_V(quiet)
    assert q["amplifier_flicker"] == 0.0
    assert n["reading"] ** 2 - q["reading"] ** 2 == pytest.approx(
        n["amplifier_flicker"] ** 2, rel=1e-9)
    later = noise_budget_V(readout_chain(_plan(**{"readout.tare_interval_s": 600.0})))
    assert later["amplifier_flicker"] > n["amplifier_flicker"] and later["reading"] > n["reading"]
    other = readout_chain(_plan(**{"readout.amplifier": "INA128",
                                   "readout.amplifier_noise_nV_per_rtHz": 8.0}))
    assert other.amplifier_flicker_nV_per_rtHz_at_1Hz == 0.0
    assert "not stated for INA128" in other.source("amplifier_flicker_nV_per_rtHz_at_1Hz")
    assert "state readout.amplifier_gain for INA128" in other.source("amplifier_gain")


def test_another_amplifier_without_its_noise_is_refused_by_the_key_it_needs():
    """The noise defaults are the AD621's data sheet's: naming another amplifier without its
    noise density is refused by that key, not read with the AD621's figures."""
    with pytest.raises(DesignError) as refused:
        _plan(**{"readout.amplifier": "INA128"})
    assert "readout.amplifier_noise_nV_per_rtHz" in str(refused.value)
    assert "INA128" in str(refused.value)


@pytest.mark.parametrize("drop_readout_table", [False, True])
def test_the_default_grid_wider_than_the_sheet_is_refused_as_a_stated_one(drop_readout_table):
    """The grid-on-the-sheet rule holds for the library default's width, not only a stated
    one, with or without a [readout] table."""
    data = with_overrides(default_design_data(), {"sheet.thickness_mm": 0.8})
    if drop_readout_table:
        data.pop("readout", None)
    default_width = DEFAULTS["grid_width_mm"][0]
    assert default_width > 0.8
    with pytest.raises(DesignError) as exc:
        plan_from_dict(data)
    errors = {e.field: e for e in getattr(exc.value, "errors", (exc.value,))}
    assert "readout.grid_width_mm" in errors
    refusal = errors["readout.grid_width_mm"]
    assert refusal.value == default_width and "0.8 mm" in refusal.allowed
    assert "not stated" in refusal.why
    stated = with_overrides(data, {"readout.grid_width_mm": 0.8})
    try:
        plan_from_dict(stated)
    except DesignError as other:
        assert "readout.grid_width_mm" not in {e.field for e in getattr(other, "errors", (other,))}


@pytest.mark.parametrize("gauge, cites_own", [("constantan-foil", False),
                                              ("constantan-foil-hbm-y", True)])
def test_the_gauge_factor_tc_cites_what_the_library_gauge_is(gauge, cites_own):
    """The default gauge is a Micro-Measurements WA class gauge, yet the gauge factor's
    temperature coefficient was cited from the HBM Y series data sheet as its own: for it the
    figure is a typical constantan value and its own data sheet governs; for the HBM Y
    series gauge it is that data sheet's."""
    from tactcad.design.readout_section import readout_of
    from tactcad.vocabulary.material_library import strain_gauge

    lib = strain_gauge(gauge)
    source = dict(readout_of({}, lib).sources)["gauge_factor_tc_pct_per_100K"]
    assert "HBM Y series data sheet" in source
    assert source.startswith(f"library gauge {gauge}: HBM Y series") == cites_own
    assert ("typical of constantan" in source and "its own data sheet governs" in source
            and "Micro-Measurements WA" in source) != cites_own


def test_design_rows_help_says_two_and_a_wrong_count_is_refused_as_the_option(capsys):
    with pytest.raises(SystemExit):
        main(["design", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "--rows 2 rows of the new grid: 2, the only value taken" in help_text
    code = main(["design", "--rows", "3", "--kr-over-km", "5", "--kobj-range", "0.2", "1.5",
                 "--full-scale-force", "0.05", "--out", "never_written.toml", "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--rows" and err["allowed"] == "2"


def test_a_read_out_chain_is_kept_by_its_table_and_gauge_and_told_apart_by_each():
    # a search reads every candidate's chain: one chain per [readout] table and gauge,
    # shared; a table differing in an entry's value or type (2 against 2.0) is its own
    from tactcad.design.readout_section import readout_of, resolved_readout
    from tactcad.vocabulary.material_library import strain_gauge

    gauge = strain_gauge("constantan-foil-hbm-y")
    for table in ({}, {"excitation_V": 2}, {"excitation_V": 2.0},
                  {"daq_ranges_V": [1.0, 10.0]}):
        raw = {"design": {"name": "x"}, "readout": dict(table)}
        chain = readout_of(raw, gauge)
        assert chain == resolved_readout(raw, gauge)
        assert readout_of({"other": 1, "readout": dict(table)}, gauge) is chain
    two, two_float = (readout_of({"readout": {"excitation_V": v}}, gauge) for v in (2, 2.0))
    assert two is not two_float and type(two.excitation_V) is int
    assert readout_of({}, gauge) is readout_of({"readout": {}}, gauge) or \
        readout_of({}, gauge) == readout_of({"readout": {}}, gauge)
