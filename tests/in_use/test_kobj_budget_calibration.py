"""The budget's calibration term: the steps ``calibrate`` drives, the gauge it is driven on,
and the resolution the term asks of that gauge."""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pytest

from tactcad.in_use import kobj_budget as kb
from tactcad.studies.verification import calibration_gauge

ROOT = Path(__file__).resolve().parents[2]
COMB = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
#: The comb with references stiff against the catalogue's softest gauges (web 0.25 mm:
#: K_r about 100 N/mm) and its rated 0.05 N.
STIFF_WEBS = [0.25] * 6 + [0.08] * 6
#: Simulated calibrations whose scatter is compared with the expected standard errors: the
#: scatter's own relative standard error is about 1 / sqrt(2 x 300) = 4 %.
SEEDS = 300


@pytest.fixture(scope="module")
def comb():
    from tactcad.api import load

    return load(str(COMB)).plan


def _context(plan, rig=None):
    from tactcad.mechanics.ladder import estimate

    est = {n: estimate("closed-form", g, plan.material) for n, g in plan.distinct_elements.items()}
    return kb.Context(plan, "closed-form", {n: e.stiffness_N_per_mm for n, e in est.items()},
                      {n: e.error_estimate_rel for n, e in est.items()}, 0.05, 5.0, {},
                      rig or calibration_gauge(plan))


def _calibration_rel(budget) -> float:
    return max(v for u in budget.units for v in u["sources"]["calibration"]["after_rel"]
               if v is not None)


def test_the_expected_errors_are_the_scatter_of_calibrate_s_simulated_runs(comb):
    """Fits of calibrations simulated as ``calibrate --simulate`` runs them (its force and
    signal noise, its steps to the full-scale force on its gauge) scatter as the budget
    expects: K and K_v of one element of each part."""
    from tactcad.commands.calibrate import simulated_noise
    from tactcad.mechanics.calibration import fit_calibration
    from tactcad.paper.calibration_audit import simulate_design_calibration

    rig = calibration_gauge(comb)
    assert rig.full_scale_force_N == pytest.approx(0.05)  # the comb is not the paper's design
    args = argparse.Namespace(noise_force=None, noise_signal=None, gain=None)
    (force_noise, _), (signal_noise, _) = simulated_noise(args, argparse.Namespace(plan=comb))
    expected = kb._calibration_stderr(_context(comb))
    one_per_part = {s.geometry.part_name: s.number for s in comb.slots}
    fits = {n: [] for n in one_per_part.values()}
    for seed in range(SEEDS):
        data = simulate_design_calibration(
            comb, "closed-form", None, force_noise, signal_noise, seed,
            full_scale_force_N=rig.full_scale_force_N,
            k_sensor_N_per_mm=rig.gauge.stiffness_N_per_mm)
        for n in fits:
            d = data[n]
            fits[n].append(fit_calibration(d.z_travel_um, d.force_N, d.signal_V,
                                           d.k_sensor_N_per_mm))
    for n, runs in fits.items():
        k = np.array([f.K_N_per_mm for f in runs])
        k_v = np.array([f.K_v_V_per_mm for f in runs])
        assert np.std(k) / np.mean(k) == pytest.approx(expected[n][0], rel=0.15)
        assert np.std(k_v) / abs(np.mean(k_v)) == pytest.approx(expected[n][1], rel=0.15)


def test_the_budget_takes_the_steps_calibrate_drives(comb):
    """Each element's expected errors are those of the rig's steps (six to its full-scale
    travel), not the paper's 150 um."""
    from tactcad.mechanics.calibration import CALIBRATION_STEPS_UM, calibration_steps_um
    from tactcad.mechanics.readout_chain import (element_force_resolution_N, noise_budget_V,
                                                 readout_chain)

    ctx = _context(comb)
    rig = ctx.force_gauge
    per_part = element_force_resolution_N(comb, "closed-form")
    noise = noise_budget_V(readout_chain(comb))["reading"]
    got = kb._calibration_stderr(ctx)
    for s in comb.slots:
        k = ctx.k_of(s.number)
        steps = calibration_steps_um(k, rig.gauge.stiffness_N_per_mm, 0.05)
        assert steps[-1] < CALIBRATION_STEPS_UM[-1]  # the comb's full-scale travel is short
        want = kb.expected_calibration_stderr_rel(
            k, per_part[s.geometry.part_name]["S"] * k, noise, rig.gauge.stiffness_N_per_mm,
            force_noise_N=rig.gauge.resolution_N, steps_um=steps)
        assert got[s.number] == pytest.approx(want, rel=1e-12)


def test_the_papers_design_keeps_the_papers_steps(plan):
    """The paper's design (its file cites the paper) is calibrated on the paper's steps, and
    its budget's expected errors are those of the steps, whatever the element's K."""
    from tactcad.mechanics.calibration import CALIBRATION_STEPS_UM
    from tactcad.mechanics.readout_chain import (element_force_resolution_N, noise_budget_V,
                                                 readout_chain)

    rig = calibration_gauge(plan)
    assert rig.full_scale_force_N is None
    assert np.array_equal(rig.steps_um(10.0), CALIBRATION_STEPS_UM)
    ctx = _context(plan)
    per_part = element_force_resolution_N(plan, "closed-form")
    noise = noise_budget_V(readout_chain(plan))["reading"]
    got = kb._calibration_stderr(ctx)
    for s in plan.slots:
        k = ctx.k_of(s.number)
        want = kb.expected_calibration_stderr_rel(
            k, per_part[s.geometry.part_name]["S"] * k, noise, rig.gauge.stiffness_N_per_mm,
            force_noise_N=rig.gauge.resolution_N, steps_um=CALIBRATION_STEPS_UM)
        assert got[s.number] == pytest.approx(want, rel=1e-12)
    assert "the paper's Z steps" in kb.calibration_steps_words(ctx)


def test_a_stiff_low_force_comb_without_rigs_is_calibrated_on_the_gauge_leaving_least_error():
    """On stiff references the soft small-range gauge leaves the element a small share of the
    Z travel: a stiffer gauge of coarser resolution leaves a smaller calibration term, and the
    design without rigs takes it, saying why."""
    from dataclasses import replace

    from tactcad.api import load
    from tactcad.mechanics.calibration import CalibrationGauge
    from tactcad.vocabulary.force_gauge_catalogue import (calibration_gauge_need,
                                                          choose_force_gauge, force_gauges)

    stiff = load(str(COMB), set={"comb.web_thicknesses_mm": STIFF_WEBS}).plan
    rig = calibration_gauge(stiff)
    by_share, _ = choose_force_gauge(calibration_gauge_need(0.05))
    assert rig.gauge.model != by_share.model
    assert "least expected calibration error" in rig.source and "no rigs" in rig.source

    def term(gauge) -> float:
        return _calibration_rel(kb.kobj_budget(
            stiff, (0.5, 5.0), 0.05, points=3,
            force_gauge=CalibrationGauge(gauge, "test", rig.full_scale_force_N)))

    chosen = term(rig.gauge)
    assert chosen < term(by_share)
    assert all(chosen <= term(g) * (1 + 1e-9) for g in force_gauges()
               if g.range_N >= 0.05 and g.model != rig.gauge.model)
    # a project with rigs keeps its rigs' gauge
    rigs = replace(stiff, rigs_force_gauge=by_share)
    assert calibration_gauge(rigs).gauge == by_share


def test_the_budget_names_the_resolution_that_brings_the_term_within_its_allowance(comb):
    """The comb's term exceeds the other terms' RSS; a gauge of the same stiffness read to
    the resolution the budget names brings it just within, a little coarser does not."""
    from dataclasses import replace

    from tactcad.mechanics.calibration import CalibrationGauge

    rig = calibration_gauge(comb)

    def budget(resolution_N: float):
        gauge = replace(rig.gauge, resolution_N=resolution_N)
        return kb.kobj_budget(comb, (0.5, 5.0), 0.05, points=3,
                              force_gauge=CalibrationGauge(gauge, "test", rig.full_scale_force_N))

    notes = budget(rig.gauge.resolution_N).notes
    needed = notes["calibration_gauge_resolution_needed_N"]
    assert notes["calibration_gauge_fits"] is False and 0 < needed < rig.gauge.resolution_N
    assert notes["calibration_force_share_rel"] > 0.5  # the force gauge makes the term
    assert budget(0.98 * needed).notes["calibration_gauge_fits"] is True
    assert budget(1.05 * needed).notes["calibration_gauge_fits"] is False


def test_the_budget_names_the_runs_that_bring_the_term_within_on_the_same_gauge(comb,
                                                                              monkeypatch):
    """Every reading independent, the term's variance falls as 1 / runs: the count the budget
    names brings it within its allowance, one fewer does not."""
    def notes(runs: int) -> dict:
        monkeypatch.setattr(kb, "CALIBRATION_REPEATS", runs)
        return kb.kobj_budget(comb, (0.5, 5.0), 0.05, points=3,
                              force_gauge=calibration_gauge(comb)).notes

    assert kb.CALIBRATION_REPEATS == 3
    first = notes(3)
    runs = first["calibration_runs_needed"]
    assert first["calibration_gauge_fits"] is False and runs > 3
    assert f"{runs} runs of the calibration" in first["calibration_allowance"]
    assert notes(runs)["calibration_gauge_fits"] is True
    assert notes(runs)["calibration_runs_needed"] is None
    assert notes(runs - 1)["calibration_gauge_fits"] is False


def test_an_accuracy_the_other_terms_fill_names_no_resolution():
    """Where the other terms alone fill the stated accuracy, no force gauge helps, and the
    words say so rather than naming a resolution."""
    from tactcad.api import load

    strict = load(str(COMB), set={"requirements.kobj_accuracy_rel": 0.001}).plan
    notes = kb.kobj_budget(strict, (0.5, 5.0), 0.05, points=3,
                           force_gauge=calibration_gauge(strict)).notes
    assert notes["calibration_gauge_fits"] is False
    assert notes["calibration_gauge_resolution_needed_N"] is None
    assert "the other terms alone fill the accuracy" in notes["calibration_allowance"]
