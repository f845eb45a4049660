"""The K_obj error budget: eq. 3's derivative, each source against its own module, the totals."""
from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np
import pytest

from tactcad.in_use import kobj_budget as kb
from tactcad.studies.verification import calibration_gauge

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
MACRO = ROOT / "hardware" / "macro_array" / "macro_array.toml"
#: The Ti example widened to 2 x 4: each row's soft elements beside its reference.
FOUR_COLUMNS = [19.605, 6.196, 19.605, 19.605] * 2


@pytest.fixture(scope="module")
def ti_plan():
    from tactcad.api import load

    return load(str(TI)).plan


def _context(plan, force=0.5, delta_T=5.0, calibrations=None):
    from tactcad.mechanics.ladder import estimate

    est = {n: estimate("closed-form", g, plan.material) for n, g in plan.distinct_elements.items()}
    return kb.Context(plan, "closed-form", {n: e.stiffness_N_per_mm for n, e in est.items()},
                      {n: e.error_estimate_rel for n, e in est.items()}, force, delta_T,
                      calibrations or {}, calibration_gauge(plan))


def _uncoupled(ctx):
    """``ctx`` with a sample whose tips do not couple (Ĉ = I): the coupled chain is then
    eq. 1-3 exactly, so each term is eq. 3's partials times what moves the reading."""
    from tactcad.in_use.tissue_coupling import CoupledSample, Tissue

    numbers = tuple(s.number for s in ctx.plan.slots)
    ctx.cache["tissue sample"] = CoupledSample(numbers, np.eye(len(numbers)), Tissue(),
                                               (1.0, 1.0))
    return ctx


def _first_unit(ctx):
    from tactcad.mechanics.readout_chain import row_units

    ref, meas = row_units(ctx.plan, dict(ctx.k))[0]
    return kb.Unit(ref.number, meas.number)


def _op(ctx, unit, k_obj):
    return kb.operating_point(ctx.k_of(unit.measuring), ctx.k_of(unit.reference), k_obj,
                              ctx.force_N)


def test_eq3_partials_match_a_finite_difference():
    op = kb.operating_point(6.0, 40.0, [1.5, 7.0, 30.0], 0.8)
    p = kb.eq3_partials(op)
    base = kb.kobj_from_deflections(op.e_m, op.e_r, op.k_m, op.k_r)
    assert np.allclose(base, op.k_obj, rtol=1e-12)  # eq. 1 then eq. 3 gives K_obj back
    h = 1e-7
    fd = {"de_m": (kb.kobj_from_deflections(op.e_m * (1 + h), op.e_r, op.k_m, op.k_r) - base)
          / (op.e_m * h),
          "de_r": (kb.kobj_from_deflections(op.e_m, op.e_r * (1 + h), op.k_m, op.k_r) - base)
          / (op.e_r * h),
          "dK_m": (kb.kobj_from_deflections(op.e_m, op.e_r, op.k_m * (1 + h), op.k_r) - base)
          / (op.k_m * h),
          "dK_r": (kb.kobj_from_deflections(op.e_m, op.e_r, op.k_m, op.k_r * (1 + h)) - base)
          / (op.k_r * h)}
    for key, value in fd.items():
        assert np.allclose(p[key], value, rtol=1e-5), key


def test_eq3_partials_agree_with_the_lumped_models_sensitivity():
    from tactcad.mechanics.lumped_model import sensitivity

    op = kb.operating_point(6.0, 40.0, [1.5, 7.0, 30.0], 0.8)
    assert np.allclose(kb.eq3_partials(op)["dR"], sensitivity(op.ratio, 6.0, 40.0).value)


def test_readout_noise_is_the_resolution_of_the_mechanics(plan):
    from tactcad.mechanics.readout_chain import element_force_resolution_N
    from tactcad.mechanics.resolution import unit_resolution

    ctx = _uncoupled(_context(plan))
    unit = _first_unit(ctx)
    k_obj = np.geomspace(2.0, 10.0, 5)
    got = kb.readout_noise(ctx, unit, _op(ctx, unit, k_obj))
    df = element_force_resolution_N(plan)
    part = lambda n: plan.element(n).geometry.part_name  # noqa: E731
    want = unit_resolution(ctx.k_of(unit.measuring), ctx.k_of(unit.reference), k_obj, 0.5,
                           df[part(unit.measuring)]["dF"],
                           force_resolution_reference_N=df[part(unit.reference)]["dF"])
    assert np.allclose(got.after, want["K_obj_resolution_rel"], rtol=1e-6)
    assert np.array_equal(got.before, got.after)


def test_thermal_zero_from_the_apparent_forces_and_eq_3(ti_plan):
    from tactcad.mechanics.lumped_model import sensitivity
    from tactcad.mechanics.thermal_drift import thermal_report

    ctx = _uncoupled(_context(ti_plan, force=0.1, delta_T=4.0))
    unit = _first_unit(ctx)
    k_obj = np.geomspace(1.0, 5.0, 5)
    op = _op(ctx, unit, k_obj)
    got = kb.thermal_zero(ctx, unit, op).after
    rep = thermal_report(ti_plan, _Needs(0.1, (1.0, 5.0)))
    f = {r["element"]: r["apparent_force_N_per_K"] for r in rep.records}
    # dR / R = f_m dT / F_m - f_r dT / F_r (each force read off by its own apparent force);
    # the thermal model takes R's exact change, this its first order: within 1 %
    dR = op.ratio * (f[unit.measuring] * 4.0 / op.force_m - f[unit.reference] * 4.0 / 0.1)
    want = sensitivity(op.ratio, op.k_m, op.k_r).value * dR / k_obj
    assert np.allclose(np.abs(got), np.abs(want), rtol=1e-2)
    assert np.array_equal(np.sign(got), np.sign(want))


class _Needs(NamedTuple):
    full_scale_force_N: float
    kobj_range_N_per_mm: tuple[float, float]


def test_thermal_zero_scales_as_one_over_the_force(ti_plan):
    a, b = _context(ti_plan, force=0.1), _context(ti_plan, force=0.2)
    unit = _first_unit(a)
    k_obj = np.array([1.3, 4.0])
    za = kb.thermal_zero(a, unit, _op(a, unit, k_obj)).after
    zb = kb.thermal_zero(b, unit, _op(b, unit, k_obj)).after
    assert np.allclose(za, 2 * zb, rtol=1e-2)  # first order in 1 / F; R changes exactly


def test_thermal_span_is_the_modulus_and_expansion_term_the_gauge_factor_cancels(plan):
    from tactcad.vocabulary.material_library import material_grade

    ctx = _context(plan, delta_T=3.0)
    unit = _first_unit(ctx)
    tc, _ = kb.modulus_tc_per_K(plan)
    alpha = material_grade(plan.material.grade).cte_ppm_per_K * 1e-6
    got = kb.thermal_span(ctx, unit, _op(ctx, unit, np.geomspace(2, 10, 4))).after
    # K_m and K_r scale alike by (1 + tc dT)(1 + alpha dT); eq. 3 reads K_obj scaled the same
    assert np.allclose(got, 1.0 / ((1 + tc * 3.0) * (1 + alpha * 3.0)) - 1.0, rtol=1e-9)
    assert got[0] > 0  # E falls with temperature faster than the spring grows


def test_manufacturing_tolerance_from_the_web_band_and_gone_after_calibration(plan):
    from tactcad.studies.verification import web_band_rel

    ctx = _uncoupled(_context(plan))
    unit = _first_unit(ctx)
    bands = {n: kb.web_tolerance_k_rel(g, plan.material) for n, g in plan.distinct_elements.items()}
    assert max(bands.values()) == pytest.approx(web_band_rel(plan), rel=1e-12)
    op = _op(ctx, unit, np.array([3.0]))
    got = kb.manufacturing_tolerance(ctx, unit, op)
    R = op.ratio
    part = lambda n: plan.element(n).geometry.part_name  # noqa: E731
    want = (R / (R - 1) * op.k_m * bands[part(unit.measuring)]
            + op.k_r / (R - 1) * bands[part(unit.reference)]) / 3.0
    assert np.allclose(got.before, want, rtol=1e-6)
    assert np.all(got.after == 0)


def test_crosstalk_from_the_sensitivity_matrix(plan):
    from tactcad.mechanics.stack_crosstalk import VERIFY_MODEL, plan_crosstalk

    ctx = _uncoupled(_context(plan))
    unit = _first_unit(ctx)
    k_obj = 4.0
    op = _op(ctx, unit, np.array([k_obj]))
    got = kb.crosstalk(ctx, unit, op)
    r = plan_crosstalk(plan, VERIFY_MODEL)
    S, numbers = r.sensitivity, list(r.elements)
    travel = op.travel[0]

    def seen(i):  # equivalent force on gauge i from every other tip (N)
        return sum(S[i, j] / S[i, i] * ctx.k_of(n) * k_obj * travel / (ctx.k_of(n) + k_obj)
                   for j, n in enumerate(numbers) if j != i)

    x_m, x_r = seen(numbers.index(unit.measuring)), seen(numbers.index(unit.reference))
    e_m, e_r = op.e_m[0] + x_m / op.k_m, op.e_r[0] + x_r / op.k_r
    read = kb.kobj_from_deflections(e_m, e_r, op.k_m, op.k_r)
    assert got.before[0] == pytest.approx(abs(read / k_obj - 1), rel=1e-3)
    assert got.after[0] == pytest.approx(got.before[0] * r.error_estimate_rel, rel=1e-12)


def test_tissue_coupling_from_the_rig_model_and_eq_3(ti_plan):
    from tactcad.mechanics.evaluation import (SampleSpec, elements_from_plan, simulate_rig)
    from tactcad.mechanics.lumped_model import object_stiffness

    ctx = _context(ti_plan, force=0.1)
    unit = _first_unit(ctx)
    k_obj = 2.0
    got = kb.tissue_coupling(ctx, unit, _op(ctx, unit, np.array([k_obj])))
    elements = elements_from_plan(ti_plan, {s.number: ctx.k_of(s.number) for s in ti_plan.slots})
    refs = {s.number: ti_plan.reference_for(s).number for s in ti_plan.slots}
    res = simulate_rig(elements, k_obj, SampleSpec("halfspace"), references=refs)
    R = res.ratio[0, list(res.elements).index(unit.measuring)]
    read = object_stiffness(R, ctx.k_of(unit.measuring), ctx.k_of(unit.reference))
    assert got.before[0] == pytest.approx(abs(read / k_obj - 1), rel=1e-9)
    assert got.before[0] > 0.01  # tips 3 mm apart on one sample couple by several percent
    # after the coupled inversion: the model's error of the R shift, read back on the
    # coupled curve itself (a coarser central difference of R over ln K_obj here)
    from tactcad.in_use.tissue_coupling import coupled_ratio, coupled_sample

    op = _op(ctx, unit, np.array([k_obj]))
    sample = coupled_sample(ti_plan)
    k = {s.number: ctx.k_of(s.number) for s in ti_plan.slots}
    pair = (unit.measuring, unit.reference)
    slope = (coupled_ratio(sample, k, pair, k_obj * 1.01)
             - coupled_ratio(sample, k, pair, k_obj / 1.01)) / (2 * np.log(1.01))
    shift = (kb.COUPLING_MODEL_ERROR_REL + sample.error_rel) * (R - op.ratio[0])
    assert got.after[0] == pytest.approx(abs(shift / slope), rel=1e-3)


def test_the_tissue_terms_slope_is_the_coupled_models_not_eq_3s():
    """On the macro array, whose R is compressed, the coupled R moves with ln K_obj about
    half as fast as eq. 2's: the model's error costs twice what eq. 3's slope said."""
    from tactcad.api import load

    plan = load(str(MACRO)).plan
    ctx = _context(plan, force=0.3)
    unit = kb.Unit(1, 3)
    op = _op(ctx, unit, np.array([2.34]))
    eq3_slope = op.k_obj * kb.eq3_partials(op)["dR"] ** -1
    coupled = kb.coupled_slope(ctx, unit, op.k_obj)
    assert 0.3 < float(coupled[0] / eq3_slope[0]) < 0.7


def test_gauge_model_is_the_levels_own_strain_error(plan):
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    err = kb.gauge_model_error_rel(plan, "closed-form")
    name, g = next(iter(plan.distinct_elements.items()))
    want = grid_strain_per_N(g, plan.material, readout_chain(plan), "closed-form")["error_rel"]
    assert err[name] == pytest.approx(want, rel=1e-12) and err[name] > 0
    ctx = _context(plan)
    unit = _first_unit(ctx)
    c = kb.gauge_model(ctx, unit, _op(ctx, unit, np.array([3.0])))
    assert c.before[0] > 0 and c.after[0] == 0


def test_expected_calibration_error_matches_fits_of_simulated_runs():
    from tactcad.mechanics.calibration import (CALIBRATION_STEPS_UM, fit_calibration,
                                               synthetic_calibration)

    k, k_v, noise_v = 30.0, -40.0, 3e-4
    want_k, want_kv = kb.expected_calibration_stderr_rel(k, k_v, noise_v, force_noise_N=0.001,
                                                         steps_um=CALIBRATION_STEPS_UM)
    fits = [fit_calibration(d.z_travel_um, d.force_N, d.signal_V)
            for d in (synthetic_calibration(k, k_v, 0.1, noise_signal_V=noise_v,
                                            noise_force_N=0.001, seed=s)
                      for s in range(400))]
    # the scatter of the fitted slopes is their standard error
    assert np.std([f.K_N_per_mm for f in fits]) / k == pytest.approx(want_k, rel=0.1)
    assert np.std([f.K_v_V_per_mm for f in fits]) / abs(k_v) == pytest.approx(want_kv, rel=0.1)


def test_calibration_takes_a_files_fit_for_its_elements(plan):
    from tactcad.mechanics.calibration import fit_calibration, synthetic_calibration

    ctx0 = _context(plan)
    unit = _first_unit(ctx0)
    data = synthetic_calibration(ctx0.k_of(unit.measuring), -50.0, 0.0, noise_force_N=0.01)
    fit = fit_calibration(data.z_travel_um, data.force_N, data.signal_V)
    ctx = _context(plan, calibrations={unit.measuring: fit})
    op = _op(ctx, unit, np.array([3.0]))
    se = kb._calibration_stderr(ctx)
    assert se[unit.measuring] == (fit.stderr_K_N_per_mm / fit.K_N_per_mm,
                                  fit.stderr_K_v_V_per_mm / abs(fit.K_v_V_per_mm))
    assert kb.calibration(ctx, unit, op).after[0] > kb.calibration(ctx0, unit, op).after[0]


def test_totals_are_the_rss_and_the_sum_and_the_dominant_source_is_the_largest(ti_plan):
    b = kb.kobj_budget(ti_plan, (1.0, 5.0), 0.1, 5.0, force_gauge=calibration_gauge(ti_plan))
    assert len(b.k_obj) == kb.BUDGET_POINTS and b.k_obj[0] == 1.0 and b.k_obj[-1] == 5.0
    for u in b.units:
        after = np.array([u["sources"][k]["after_rel"] for k in kb.SOURCE_KEYS])
        assert np.allclose(u["rss_rel"], np.sqrt((after ** 2).sum(0)))
        assert np.allclose(u["worst_case_rel"], np.abs(after).sum(0))
        assert u["dominant"] == [kb.SOURCE_KEYS[i] for i in np.abs(after).argmax(0)]
        assert np.all(np.array(u["worst_case_rel"]) >= np.array(u["rss_rel"]))
    arr = b.array
    assert arr["rss_rel"] == [min(u["rss_rel"][i] for u in b.units) for i in range(len(b.k_obj))]


def test_a_design_of_four_columns_has_its_budget():
    from tactcad.api import load

    plan = load(str(TI), set={"array.columns": 4, "arms.lengths_mm": FOUR_COLUMNS}).plan
    b = kb.kobj_budget(plan, (1.0, 5.0), 0.1, force_gauge=calibration_gauge(plan))
    assert b.units and all(np.all(np.isfinite(u["rss_rel"])) for u in b.units)


@pytest.mark.parametrize("kwargs, field", [({"force_N": 0.0}, "force_N"),
                                           ({"delta_T_K": 101.0}, "delta_T_K"),
                                           ({"kobj_range": (5.0, 1.0)}, "kobj_range_N_per_mm"),
                                           ({"points": 1}, "points")])
def test_bad_inputs_are_named(ti_plan, kwargs, field):
    from tactcad.errors import DesignError

    args = {"kobj_range": (1.0, 5.0), "force_N": 0.1, **kwargs}
    with pytest.raises(DesignError, match=field):
        kb.kobj_budget(ti_plan, **args, force_gauge=calibration_gauge(ti_plan))


def test_the_modulus_coefficient_is_the_readout_sections_when_it_states_one(ti_plan):
    from tactcad.api import load

    tc, where = kb.modulus_tc_per_K(ti_plan)
    assert tc < 0 and "grade" in where
    stated = load(str(TI), set={"readout.substrate_modulus_tc_per_K": -5.5e-4}).plan
    assert kb.modulus_tc_per_K(stated)[0] == -5.5e-4
    ctx = _context(stated, delta_T=2.0)
    unit = _first_unit(ctx)
    span = kb.thermal_span(ctx, unit, _op(ctx, unit, np.array([2.0]))).after
    assert span[0] == pytest.approx(1.0 / ((1 - 5.5e-4 * 2.0) * (1 + 2.0 * 8.6e-6)) - 1.0,
                                    rel=2e-2)


def test_the_calibration_term_reads_the_projects_rigs_force_gauge(ti_plan):
    """The budget's calibration term is on the rigs' force gauge (the one ``calibrate`` uses),
    named with its source; a coarser gauge in the rigs makes it larger; a plan without rigs
    takes the catalogue's gauge for its rated force, and says so."""
    from dataclasses import replace

    from tactcad.vocabulary.force_gauge_catalogue import calibration_gauge_need, choose_force_gauge
    from tactcad.studies.verification import requirements_of

    rigs_gauge = ti_plan.rigs_force_gauge
    assert rigs_gauge is not None and calibration_gauge(ti_plan)[0] == rigs_gauge

    def budget(plan):
        return kb.kobj_budget(plan, (1.0, 5.0), 0.1, 5.0, points=3,
                              force_gauge=calibration_gauge(plan)).as_json()

    def calibration_rel(b):
        return max(max(u["sources"]["calibration"]["after_rel"]) for u in b["units"])

    own = budget(ti_plan)
    assert own["notes"]["calibration_force_gauge"] == rigs_gauge.model
    assert "rigs" in own["notes"]["calibration_force_gauge_source"]
    assert rigs_gauge.model in own["notes"]["calibration"]
    coarse = replace(rigs_gauge, model="coarse lab gauge",
                     resolution_N=20 * rigs_gauge.resolution_N)
    theirs = budget(replace(ti_plan, rigs_force_gauge=coarse))
    assert theirs["notes"]["calibration_force_gauge"] == "coarse lab gauge"
    assert calibration_rel(theirs) > calibration_rel(own)
    bare = replace(ti_plan, rigs_force_gauge=None)
    want, _ = choose_force_gauge(calibration_gauge_need(requirements_of(bare).full_scale_force_N))
    none = budget(bare)
    assert none["notes"]["calibration_force_gauge"] == want.model
    assert "no rigs" in none["notes"]["calibration_force_gauge_source"]


def test_budget_and_calibrate_name_the_gauge_written_in_the_projects_rigs(tmp_path, capsys):
    """``tactcad budget --json`` follows a gauge changed in rigs.toml, as ``calibrate`` does."""
    import json
    import shutil

    from tactcad.cli import main

    folder = tmp_path / "ti"
    shutil.copytree(TI.parent, folder)
    rigs = folder / "rigs.toml"
    text = rigs.read_text(encoding="utf-8")
    model = next(line.split("=", 1)[1].strip().strip('"') for line in text.splitlines()
                 if line.startswith("model ="))
    rigs.write_text(text.replace(f'model = "{model}"', 'model = "Lab gauge 7"', 1),
                    encoding="utf-8")
    design = str(folder / TI.name)
    assert main(["budget", "--design", design, "--json", "--points", "2"]) == 0
    notes = json.loads(capsys.readouterr().out)["notes"]
    assert notes["calibration_force_gauge"] == "Lab gauge 7"
    assert main(["calibrate", "--design", design, "--simulate", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["force_gauge"]["model"] == "Lab gauge 7"


def test_an_offset_tip_on_an_uncoupled_sample_is_eq_1_with_the_offset():
    """The coplanarity model against eq. 1-3 by hand: with no coupling (Ĉ = I) a reference
    standing d proud meets the object first; at the reference force F_r, e_r = F_r/K_r,
    the body travel is e_r (K_r + K)/K - d and e_m = K travel / (K + K_m)."""
    from tactcad.in_use.tissue_coupling import CoupledSample, Tissue, offset_ratio

    k = {1: 30.0, 2: 8.0}
    sample = CoupledSample((1, 2), np.eye(2), Tissue(), (2.0, 3.0))
    for d in (1e-3, -2e-3, 5e-3):
        e_r = 0.3 / 30.0
        e_m = 2.34 * (e_r * (30.0 + 2.34) / 2.34 - d) / (2.34 + 8.0)
        got = offset_ratio(sample, k, (2, 1), 2.34, 0.3, {1: d})
        assert got == pytest.approx(e_m / e_r, rel=1e-12)
    assert offset_ratio(sample, k, (2, 1), 2.34, 0.3, {}) == pytest.approx(
        (2.34 / (2.34 + 8.0)) / (2.34 / (2.34 + 30.0)), rel=1e-12)  # eq. 2


def test_tip_coplanarity_is_in_the_budget_from_the_drawings_tolerance(ti_plan):
    """A 1 um mismatch moves K_obj by several percent (the Ti units at their rating), so the
    drawing's +/-0.02 mm cannot be read uncorrected; zeroing on a rigid flat leaves the
    flat's flatness and the deflection resolution."""
    req = ti_plan.raw["requirements"]
    budget = kb.kobj_budget(ti_plan, tuple(req["kobj_range_N_per_mm"]), req["full_scale_force_N"],
                            force_gauge=calibration_gauge(ti_plan))
    assert "tip_coplanarity" in kb.SOURCE_KEYS
    ctx = _context(ti_plan, force=req["full_scale_force_N"])
    unit = _first_unit(ctx)
    op = _op(ctx, unit, np.array(budget.k_obj))
    one_um = kb._mismatch_rel(ctx, unit, op, 1e-3)
    assert np.all(one_um > 0.01)
    rec = next(u for u in budget.units if (u["reference_element"], u["measuring_element"])
               == (unit.reference, unit.measuring))["sources"]["tip_coplanarity"]
    before = np.array([x if x is not None else np.inf for x in rec["before_rel"]])
    assert np.all(before > one_um)  # twice 0.02 mm is far worse than 1 um
    after = np.array(rec["after_rel"])
    residual = kb.tip_mismatch_after_zeroing_mm(ctx, unit)
    assert kb.ZEROING_FLAT_FLATNESS_MM <= residual < 1e-3
    assert after == pytest.approx(one_um * residual / 1e-3, rel=0.1)  # about linear in a small one
    assert budget.tip_height["tolerance_mm"] == 0.02 and budget.tip_height["kobj_accuracy_rel"] is None


def test_a_stated_accuracy_gives_the_tip_tolerance_the_drawing_must_hold(ti_plan):
    """The budget drives the drawing: with kobj_accuracy_rel the budget names the tip-height
    tolerance whose uncorrected mismatch fits what the other terms leave; drawn to it, the
    coplanarity term before correction fills that room at each K_obj in the unit that reads
    it."""
    from tactcad.design.array_plan import plan_from_dict, with_overrides

    req = ti_plan.raw["requirements"]
    rng, force = tuple(req["kobj_range_N_per_mm"]), req["full_scale_force_N"]
    stated = plan_from_dict(with_overrides(ti_plan.raw, {"requirements.kobj_accuracy_rel": 0.1}))
    needed = kb.kobj_budget(stated, rng, force, force_gauge=calibration_gauge(stated)
                            ).tip_height["tolerance_for_accuracy_mm"]
    assert needed is not None and 1e-5 < needed < 0.01  # microns: below what wire EDM holds
    drawn = plan_from_dict(with_overrides(stated.raw, {"tolerances.tip_height_mm": needed}))
    budget = kb.kobj_budget(drawn, rng, force, force_gauge=calibration_gauge(drawn))
    reading = kb.reading_unit_index(budget.units)
    worst = 0.0
    for i, u in enumerate(budget.units):
        read = reading == i
        if not np.any(read):
            continue
        before = np.array(u["sources"]["tip_coplanarity"]["before_rel"])[read]
        others = np.array([u["sources"][k]["after_rel"] for k in kb.SOURCE_KEYS
                           if k != "tip_coplanarity"])[:, read]
        worst = max(worst, float(np.max(np.sqrt(before ** 2 + np.sum(others ** 2, axis=0)))))
    assert worst == pytest.approx(0.1, rel=0.01)
    assert f"+/-{needed:.3g} mm" in budget.notes["tip_coplanarity"]


def test_gauge_creep_on_tips_that_do_not_couple_is_eq3s(ti_plan):
    """(j): each element's reading creeping by 0.1 % of itself, independently, moves K_obj by
    the quadrature of eq. 3's partials times 0.1 % of each deflection when the tips do not
    couple (computed here by finite differences of eq. 3, not its partials); compensation
    leaves 0.02 %. The coupled sample's own check is test_kobj_budget_coupled.py."""
    ctx = _uncoupled(_context(ti_plan, force=0.1))
    unit = _first_unit(ctx)
    op = _op(ctx, unit, kb.kobj_grid((1.0, 5.0)))
    got = kb.gauge_creep(ctx, unit, op)

    def kobj(e_m, e_r):
        return kb.kobj_from_deflections(e_m / e_r, 1.0, op.k_m, op.k_r)

    for creep, rel in ((kb.GAUGE_CREEP_REL, got.before), (kb.COMPENSATED_CREEP_REL, got.after)):
        d_m = kobj(op.e_m * (1 + creep), op.e_r) / op.k_obj - 1
        d_r = kobj(op.e_m, op.e_r * (1 + creep)) / op.k_obj - 1
        assert rel == pytest.approx(np.hypot(d_m, d_r), rel=2e-3)
    assert np.all(got.after < got.before) and np.all(got.before > 0)


def test_gauge_hysteresis_is_the_stated_fraction_of_each_reading(ti_plan):
    """(k): not stated, the assumed 0.1 % (its source says it is an assumption); stated from a
    load-unload cycle, that fraction of each deflection, independently, moves K_obj by the
    quadrature of eq. 3's change on tips that do not couple (finite differences here; the
    coupled sample's own check is test_kobj_budget_coupled.py); nothing corrects it."""
    from tactcad.design.array_plan import plan_from_dict, with_overrides

    ctx = _context(ti_plan, force=0.1)
    h, source = kb.gauge_hysteresis_rel(ctx)
    assert h == 1e-3 and source.startswith("assumption") and "OIML R 60" in source
    measured = plan_from_dict(with_overrides(ti_plan.raw, {"readout.gauge_hysteresis_rel": 4e-3}))
    ctx = _uncoupled(_context(measured, force=0.1))
    assert kb.gauge_hysteresis_rel(ctx) == (4e-3, "design file")
    unit = _first_unit(ctx)
    op = _op(ctx, unit, kb.kobj_grid((1.0, 5.0)))
    got = kb.gauge_hysteresis(ctx, unit, op)

    def kobj(e_m, e_r):
        return kb.kobj_from_deflections(e_m / e_r, 1.0, op.k_m, op.k_r)

    d_m = kobj(op.e_m * (1 + 4e-3), op.e_r) / op.k_obj - 1
    d_r = kobj(op.e_m, op.e_r * (1 + 4e-3)) / op.k_obj - 1
    assert got.before == pytest.approx(np.hypot(d_m, d_r), rel=5e-3)
    assert np.array_equal(got.after, got.before) and np.all(got.before > 0)


@pytest.mark.parametrize("value", [-1e-3, 0.2, "small"])
def test_a_hysteresis_outside_its_range_is_refused_naming_the_key(ti_plan, value):
    from tactcad.design.array_plan import plan_from_dict, with_overrides
    from tactcad.errors import DesignError

    with pytest.raises(DesignError) as e:
        plan_from_dict(with_overrides(ti_plan.raw, {"readout.gauge_hysteresis_rel": value}))
    assert "readout.gauge_hysteresis_rel" in str(e.value) and "0.05" in str(e.value)


def test_a_combs_crosstalk_term_reads_the_combs_own_level(ti_plan):
    # the comb's term was left out ("no stack crosstalk model"): it reads comb-beam now
    from tactcad.api import load
    from tactcad.commands.budget import render
    from tactcad.mechanics.crosstalk_ladder import plan_crosstalk

    comb = load(str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")).plan
    b = kb.kobj_budget(comb, (1.0, 5.0), 0.05, 5.0, points=3,
                       force_gauge=calibration_gauge(comb))
    r = plan_crosstalk(comb, "comb-beam")
    for u in b.units:
        term = u["sources"]["crosstalk"]
        assert "not_modelled" not in term and min(term["before_rel"]) > 0
        # its decoupling leaves its error estimate of it, never more than all of it (the
        # comb-beam level's estimate is over 100 %: the term grew after its correction)
        left = min(r.error_estimate_rel, 1.0)
        assert np.allclose(term["after_rel"], np.array(term["before_rel"]) * left)
        assert all(a <= b for a, b in zip(term["after_rel"], term["before_rel"]))
    assert b.notes["crosstalk_N_per_N"] == pytest.approx(r.crosstalk_rel, rel=1e-12)
    assert "(comb-beam)" in b.notes["crosstalk_basis"]
    assert f"{r.error_estimate_rel:.3g}" in b.notes["crosstalk_basis"]
    assert ("remove nothing" in b.notes["crosstalk_basis"]) == (r.error_estimate_rel >= 1)
    assert "| crosstalk | not modelled |" not in render(b)
    stacked = kb.kobj_budget(ti_plan, (1.0, 5.0), 0.1, 5.0, points=3,
                             force_gauge=calibration_gauge(ti_plan))
    assert "(stack-timoshenko)" in stacked.notes["crosstalk_basis"]


def test_a_construction_no_crosstalk_level_describes_leaves_the_term_out(monkeypatch):
    from tactcad.api import load
    from tactcad.commands.budget import render
    from tactcad.mechanics import crosstalk_ladder
    from tactcad.mechanics.crosstalk_ladder import CROSSTALK_LEVELS, crosstalk_reason

    comb = load(str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")).plan
    monkeypatch.setattr(crosstalk_ladder, "CROSSTALK_LEVELS",  # no level describes a comb
                        {n: lv for n, lv in CROSSTALK_LEVELS.items()
                         if lv.construction != "monolithic-comb"})
    why = crosstalk_reason(comb)
    assert "monolithic-comb" in why
    b = kb.kobj_budget(comb, (1.0, 5.0), 0.05, 5.0, points=3,
                       force_gauge=calibration_gauge(comb))
    for u in b.units:
        assert u["sources"]["crosstalk"]["not_modelled"] == why
        assert u["sources"]["crosstalk"]["after_rel"] == [0.0] * 3  # not in the sums
    assert b.notes["crosstalk_basis"] == f"not modelled, left out of the sums: {why}"
    assert "| crosstalk | not modelled |" in render(b)


def _unit_record(reference, measuring, others_rel, coplanarity_after_rel):
    """A unit's budget record with one other term: ``others_rel`` (the RSS of every term but
    the coplanarity) and the zeroed coplanarity term over a K_obj grid (relative)."""
    sources = {k: {"after_rel": [0.0] * len(others_rel)} for k in kb.SOURCE_KEYS}
    sources["calibration"]["after_rel"] = list(others_rel)
    sources["tip_coplanarity"]["after_rel"] = list(coplanarity_after_rel)
    rss = np.hypot(others_rel, coplanarity_after_rel)
    return {"reference_element": reference, "measuring_element": measuring,
            "sources": sources, "rss_rel": list(rss)}


def test_the_tip_tolerance_reads_each_kobj_in_the_unit_that_reads_it():
    """A unit the array reads no K_obj with (its other terms larger than the accuracy) does
    not leave the tips 'no room': the accuracy's row passes on the unit that reads each
    K_obj, so the tolerance is what that unit leaves, and a looser accuracy a looser one."""
    reads = _unit_record(2, 1, [0.010, 0.012], [0.002, 0.003])
    spare = _unit_record(2, 3, [0.040, 0.045], [0.002, 0.002])  # never the best
    residual = {(2, 1): 1e-4, (2, 3): 1e-4}
    tol = kb.tip_height_tolerance_for_accuracy_mm([reads, spare], 0.03, residual)
    alone = kb.tip_height_tolerance_for_accuracy_mm([reads], 0.03, residual)
    assert tol is not None and tol == pytest.approx(alone)
    assert list(kb.reading_unit_index([reads, spare])) == [0, 0]
    # the reading unit's room at its worst K_obj (the second): sqrt(0.03^2 - 0.012^2) over a
    # slope of 0.003 per 1e-4 mm of mismatch, half of it per tip
    assert tol == pytest.approx(np.sqrt(0.03 ** 2 - 0.012 ** 2) / (0.003 / 1e-4) / 2)
    looser = kb.tip_height_tolerance_for_accuracy_mm([reads, spare], 0.5, residual)
    assert looser > tol
    # no room in the unit that reads a K_obj: none fits
    assert kb.tip_height_tolerance_for_accuracy_mm([reads, spare], 0.011, residual) is None
