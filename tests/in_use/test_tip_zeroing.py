"""Zeroing on a rigid flat: the tips' heights read back, and K_obj with them taken out."""

import json
from pathlib import Path

import numpy as np
import pytest

from tactcad.cli import main
from tactcad.in_use.tip_zeroing import (ZEROING_FLAT_FLATNESS_MM, ZeroingError,
                                        simulated_flat_steps, tip_heights_on_flat)
from tactcad.in_use.tissue_coupling import (CoupledSample, Tissue, coupled_object_stiffness,
                                            coupled_ratio, coupled_sample, design_units,
                                            offset_object_stiffness, offset_ratio)
from tactcad.mechanics.calibration import CalibrationError
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.mechanics.measured_io import read_flat_readings

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
TRAVELS_MM = (0.0, 0.004, 0.008, 0.012, 0.016)


def _heights(elements, seed=3) -> dict[int, float]:
    """Tip heights of a few um about zero (mm), as a drawing's tolerance leaves them."""
    rng = np.random.default_rng(seed)
    return {n: float(rng.uniform(-2e-3, 2e-3)) for n in elements}


def _write_flat(path: Path, steps: dict, sep: str = ",", decimal: str = ".") -> Path:
    lines = [sep.join(("element", "step", "deflection_um"))]
    for s, row in steps.items():
        for e, d in row.items():
            lines.append(sep.join((str(e), str(s), f"{1e3 * d:.6f}".replace(".", decimal))))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_the_heights_come_back_about_the_mean_tip_and_steps_out_of_contact_are_left_out():
    truth = _heights(range(1, 7))
    steps = simulated_flat_steps(truth, TRAVELS_MM)
    got = tip_heights_on_flat(steps, tuple(range(1, 7)), flatness_mm=0.0)
    mean = np.mean(list(truth.values()))
    for n, h in truth.items():
        assert got.heights_mm[n] == pytest.approx(h - mean, abs=1e-12)
        assert got.sigma_mm[n] == pytest.approx(0.0, abs=1e-12)
    # the first step touches only the proudest tip: it cannot count
    assert 1 in got.steps_skipped and len(got.steps_used) >= 2
    # a unit's mismatch is the difference of its two heights, whatever the datum
    assert got.mismatch_mm((2, 1))[0] == pytest.approx(truth[2] - truth[1], abs=1e-12)


def test_noise_is_averaged_over_the_steps_and_stated_with_the_flatness():
    truth = _heights(range(1, 7))
    travels = np.linspace(0.005, 0.05, 40)
    errors, sigmas = [], []
    for seed in range(20):
        got = tip_heights_on_flat(simulated_flat_steps(truth, travels, 0.2e-3, seed),
                                  tuple(range(1, 7)))
        errors += [got.mismatch_mm((2, 1))[0] - (truth[2] - truth[1])]
        sigmas += [got.mismatch_mm((2, 1))[1]]
    assert min(sigmas) >= np.sqrt(2) * ZEROING_FLAT_FLATNESS_MM
    # the stated uncertainty covers the scatter of the estimate (no flatness in the noise)
    assert np.std(errors) <= 1.2 * np.mean(sigmas)
    assert abs(np.mean(errors)) < 3 * np.mean(sigmas) / np.sqrt(len(errors)) + 1e-9


def test_the_inversion_with_the_heights_returns_the_true_kobj_the_plain_one_does_not():
    """On the Ti example, a 1-2 um mismatch biases the coupled inversion by several percent;
    taking the heights read on the flat out gives K_obj back to the root tolerance."""
    from tactcad.design.array_plan import load_design

    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    sample = coupled_sample(plan)
    truth = _heights(k)
    heights = tip_heights_on_flat(simulated_flat_steps(truth, TRAVELS_MM), tuple(k),
                                  flatness_mm=0.0).heights_mm
    worst_plain = 0.0
    for unit in design_units(plan, k):
        for k_obj in (0.5, 2.0, 8.0):
            r = offset_ratio(sample, k, unit, k_obj, 0.05, truth)
            back = offset_object_stiffness(sample, k, unit, r, 0.05, heights)
            assert back == pytest.approx(k_obj, rel=1e-9)
            worst_plain = max(worst_plain, abs(coupled_object_stiffness(sample, k, unit, r)
                                               / k_obj - 1))
    assert worst_plain > 0.02


def test_without_heights_the_offset_forms_are_the_coupled_ones():
    sample = CoupledSample((1, 2, 3), np.array([[1.0, 0.2, 0.05], [0.2, 1.0, 0.2],
                                                [0.05, 0.2, 1.0]]), Tissue(), (2.0, 3.0))
    k = {1: 40.0, 2: 6.0, 3: 9.0}
    r = coupled_ratio(sample, k, (2, 1), 3.0)
    assert offset_ratio(sample, k, (2, 1), 3.0, 0.7, {}) == pytest.approx(r, rel=1e-12)
    assert offset_object_stiffness(sample, k, (2, 1), r, 0.7, {}) == pytest.approx(
        coupled_object_stiffness(sample, k, (2, 1), r), rel=1e-9)


@pytest.mark.parametrize("steps, message", [
    ({1: {1: 0.01, 2: 0.01}, 2: {1: 0.02, 2: 0.02}}, "missing [3]"),
    ({1: {1: 0.01, 2: 0.01, 3: 0.01, 9: 0.0}}, "not in the design [9]"),
    ({1: {1: 0.01, 2: 0.01, 3: 0.01}, 2: {1: 0.02, 2: 0.0, 3: 0.02}}, "allowed >= 2"),
])
def test_a_run_that_gives_no_heights_is_refused_naming_what_it_lacks(steps, message):
    with pytest.raises(ZeroingError, match=r".*" + message.replace("[", r"\[").replace("]", r"\]")):
        tip_heights_on_flat(steps, (1, 2, 3))


def test_the_file_is_read_with_its_separator_and_decimal_comma(tmp_path):
    steps = simulated_flat_steps({1: 0.0, 2: -1e-3, 3: 0.5e-3}, TRAVELS_MM)
    read, info = read_flat_readings(_write_flat(tmp_path / "f.csv", steps, ";", ","))
    assert info.separator == ";" and info.decimal == "," and info.readings == 15
    assert read[3][2] == pytest.approx(steps[3][2], abs=1e-9)


@pytest.mark.parametrize("text, where", [
    ("element,step\n1,1\n", "missing ['deflection_um']"),
    ("element,step,deflection_um\n1,1,abc\n", "line 2, column deflection_um"),
    ("element,step,deflection_um\n1,1,3\n1,1,4\n", "read twice in step 1"),
    ("element,step,deflection_um\n0,1,3\n", "line 2, column element"),
    ("element,step,deflection_um\n1,1,1e9\n", "allowed |value| <= "),
])
def test_a_bad_file_is_refused_naming_the_line_and_column(tmp_path, text, where):
    path = tmp_path / "flat.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(CalibrationError) as exc:
        read_flat_readings(path)
    assert where in str(exc.value)


def test_calibrate_and_lumped_read_one_flat_on_a_non_paper_design(tmp_path, capsys):
    from tactcad.design.array_plan import load_design

    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    truth = _heights(k, seed=5)
    flat = _write_flat(tmp_path / "flat.csv", simulated_flat_steps(truth, TRAVELS_MM))
    assert main(["calibrate", "--design", str(TI), "--flat", str(flat), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    unit = design_units(plan, k)[0]
    row = next(u for u in report["units"] if u["measuring"] == unit[0])
    assert row["mismatch_um"] == pytest.approx(1e3 * (truth[unit[0]] - truth[unit[1]]),
                                               abs=1e-3)
    assert "paper" not in json.dumps(report).lower()

    r = offset_ratio(coupled_sample(plan), k, unit, 1.5, 0.05, truth)
    assert main(["lumped", "--km", str(k[unit[0]]), "--kr", str(k[unit[1]]), "--r", str(r),
                 "--coupled-design", str(TI), "--unit", str(unit[0]), "--flat", str(flat),
                 "--force-r", "0.05", "--json"]) == 0
    zeroed = json.loads(capsys.readouterr().out)["coupled"]["zeroed"]
    assert zeroed["k_obj_zeroed_N_per_mm"] == pytest.approx(1.5, rel=1e-5)
    lo, hi = zeroed["k_obj_zeroed_N_per_mm_at_sigma"]
    assert lo < 1.5 < hi


@pytest.mark.parametrize("extra, message", [
    (["--flat", "f.csv"], "--force-r (not given): allowed > 0 N with --flat"),
    (["--flat", "f.csv", "--force-r", "-1"], "--force-r = -1.0: allowed > 0 N with --flat"),
    (["--force-r", "0.1"], "--force-r = given without --coupled-design"),
    (["--flat", "f.csv", "--force-r", "50"], "--force-r = 50.0: allowed <= "),
])
def test_lumped_refuses_a_flat_without_its_force_or_design(tmp_path, capsys, extra, message):
    flat = _write_flat(tmp_path / "f.csv", simulated_flat_steps(
        {n: 0.0 for n in range(1, 7)}, TRAVELS_MM))
    argv = ["lumped", "--km", "2", "--kr", "20", "--r", "3", "--json"]
    if "--flat" in extra:
        argv += ["--coupled-design", str(TI), "--unit", "1", "--flat", str(flat),
                 *extra[2:]]
    else:
        argv += extra
    assert main(argv) == 2
    assert message in json.loads(capsys.readouterr().out)["error"]["message"]


def test_a_recessed_tip_clear_of_the_tissue_carries_nothing_at_a_light_load():
    """By hand, uncoupled (Ĉ = I): the reference at height 0 carries F_r, so the body has
    travelled F_r (1/K_r + 1/K_obj); a measuring tip recessed by d touches only past that,
    and then carries (travel - d) / (1/K_m + 1/K_obj). The linear model alone gave it a
    pulling force, and R < 0, at loads below contact."""
    sample = CoupledSample((1, 2), np.eye(2), Tissue(), (2.0, 3.0))
    k_r, k_m, k_obj, d = 30.0, 3.0, 2.0, 0.004
    k = {1: k_r, 2: k_m}
    for f_r in (1e-4, 0.005, 0.02, 0.3):
        travel = f_r * (1 / k_r + 1 / k_obj)
        p_m = max(travel - d, 0.0) / (1 / k_m + 1 / k_obj)
        r = offset_ratio(sample, k, (2, 1), k_obj, f_r, {2: -d})
        assert r >= 0.0
        assert r == pytest.approx((p_m / k_m) / (f_r / k_r), rel=1e-9, abs=1e-12)
    # inverted at a load where both touch, the heights taken out give K_obj back
    r = offset_ratio(sample, k, (2, 1), k_obj, 0.3, {2: -d})
    assert offset_object_stiffness(sample, k, (2, 1), r, 0.3, {2: -d}) == pytest.approx(
        k_obj, rel=1e-8)
