"""``tactcad tolerance`` on a silicon die: the Monte Carlo of its process tolerances (device
layer, cavity alignment) against its budget's linearised terms, its options and its refusals."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli


@pytest.fixture(scope="module")
def plan():
    from tactcad.api import load_die

    return load_die(EXAMPLE).plan


def test_the_monte_carlo_agrees_with_the_budgets_device_and_alignment_terms(plan, monkeypatch):
    # small tolerances (a tenth of the process's): the budget's terms are linear there
    from tactcad.products.silicon_die.studies.die_tolerance import run_die_tolerance
    from tactcad.products.silicon_die.vocabulary import soi_process

    monkeypatch.setattr(soi_process, "CAVITY_ALIGNMENT_UM", soi_process.CAVITY_ALIGNMENT_UM / 10)
    small = dataclasses.replace(plan, stack=dataclasses.replace(
        plan.stack, device_tolerance_um=plan.stack.device_tolerance_um / 10))
    check = run_die_tolerance(small, 20_000, 1).budget_check
    assert check["K_obj_N_per_mm"] == pytest.approx([0.5, math.sqrt(2.5), 5.0])
    for mc, rss in zip(check["monte_carlo_rel_std"], check["budget_rss_rel"]):
        assert 0 < rss < 0.01  # a tenth of the process's terms (about 2-3 % at its own)
        # the budget takes K ~ t^3 exactly; the closed form's root give (dL ~ t) and shear
        # make K a little less sensitive to t (d ln K / d ln t 2.86 on the reference row,
        # 2.94 on the measuring row): the Monte Carlo reads about 4 % less, never more than 5
        assert 0.95 * rss < mc <= rss


def test_the_cavity_alignment_alone_matches_its_budget_term_closely(plan):
    # the same closed form (K ~ (L + dL)^-3) and the same coupled reading: within 1 %
    from tactcad.products.silicon_die.studies.die_tolerance import (DieTolerances,
                                                                    run_die_tolerance)

    tol = dataclasses.replace(DieTolerances.of_plan(plan), device_um=1e-9)
    check = run_die_tolerance(plan, 20_000, 2, tol).budget_check
    for mc, term in zip(check["monte_carlo_rel_std"], check["budget_cavity_alignment_rel"]):
        assert mc == pytest.approx(term, rel=0.01)


def test_a_die_without_tolerances_reads_every_kobj_exactly(plan):
    from tactcad.products.silicon_die.studies.die_tolerance import (DieTolerances,
                                                                    run_die_tolerance)

    report = run_die_tolerance(plan, 4, 0, DieTolerances(0.0, 0.0), k_obj=[0.2, 2.0, 50.0])
    for row in report.rows:
        assert row["K_mean_N_per_mm"] == pytest.approx(row["K_nominal_N_per_mm"], rel=1e-12)
    assert len(report.units) == 3 * plan.columns
    for unit in report.units:
        read = unit["K_obj_reported_N_per_mm"]
        assert read["mean"] == pytest.approx(unit["K_obj_true_N_per_mm"], rel=1e-9)
        assert unit["R"]["mean"] == pytest.approx(unit["R_nominal"], rel=1e-12)
        assert unit["fraction_unreadable"] == 0.0


def test_the_row_stiffness_is_the_dies_closed_form_with_k_as_t_cubed(plan):
    from tactcad.products.silicon_die.studies.die_tolerance import row_stiffness_N_per_mm

    ref = plan.beams[0]
    k = row_stiffness_N_per_mm(plan, ref, np.array([0.0, 0.04]), np.array([0.0, 0.0]))
    assert k[0] == pytest.approx(plan.k_r_N_per_mm, rel=1e-12)
    # about 3 dt / t (a little less: the root's give grows with t)
    assert 2.7 < (k[1] / k[0] - 1) / (0.04 / ref.thickness_um) < 3.0


def test_tolerance_on_a_dies_file_prints_and_writes_json(die_folder):
    r = run_cli("tolerance", "--samples", "400", "--seed", "5", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    for words in ("tolerance Monte Carlo of die", "400 samples, seed 5", "device layer +-0.5 um",
                  "cavity alignment +-2 um", "reference", "measuring", "against the die's budget"):
        assert words in r.stdout, words
    first = json.loads(run_cli("tolerance", "--samples", "400", "--seed", "5", "--kobj", "1",
                               "3", "--json", cwd=die_folder).stdout)
    again = json.loads(run_cli("tolerance", "--samples", "400", "--seed", "5", "--kobj", "1",
                               "3", "--json", cwd=die_folder).stdout)
    assert first["units"] == again["units"]  # seeded
    assert first["samples"] == 400 and first["seed"] == 5
    assert {u["K_obj_true_N_per_mm"] for u in first["units"]} == {1.0, 3.0}
    assert {"K_nominal_N_per_mm", "K_mean_N_per_mm", "K_std_N_per_mm", "K_rel_std",
            "K_p2_5_N_per_mm", "K_p97_5_N_per_mm"} <= set(first["rows"][0])
    assert {"mean", "std", "p2_5", "p97_5"} == set(first["units"][0]["K_obj_reported_N_per_mm"])
    assert first["tolerances"]["distribution"] == "uniform"
    other = json.loads(run_cli("tolerance", "--samples", "400", "--seed", "6", "--json",
                               cwd=die_folder).stdout)
    assert other["units"][0]["R"] != first["units"][0]["R"]


@pytest.mark.parametrize("argv, option", [(("--reference", "1"), "--reference"),
                                          (("--arm-tol", "0.1"), "--arm-tol"),
                                          (("--workers", "2"), "--workers"),
                                          (("--kobj", "1e5"), "--kobj")])
def test_an_option_a_die_cannot_take_is_refused_by_name(die_folder, argv, option):
    r = run_cli("tolerance", *argv, "--json", cwd=die_folder)
    assert r.returncode == 2, r.stdout + r.stderr
    assert json.loads(r.stdout)["error"]["field"] == option


def test_a_kobj_at_the_searched_ranges_end_is_refused_with_an_open_range(die_folder):
    """K_m / 1000 itself is outside the search: the range is said open, so the value given
    does not read as allowed."""
    r = run_cli("tolerance", "--kobj", "0.0005", "--json", cwd=die_folder)  # its K_m / 1000
    error = json.loads(r.stdout)["error"]
    assert r.returncode == 2 and error["field"] == "--kobj"
    assert error["allowed"].startswith("0.0005 < K_obj < ")


def test_the_draw_is_solved_a_chunk_of_dies_at_a_time_with_the_same_statistics(plan,
                                                                              monkeypatch):
    # memory bounded by the chunk, not the dies drawn: no coupled solve (the draws' or the
    # inversion's Newton steps) holds more dies than a chunk, and chunking changes no number
    from tactcad.products.silicon_die.studies import die_tolerance as dt

    whole = dt.run_die_tolerance(plan, 300, 4, k_obj=[1.0, 3.0]).as_json()
    solved = []
    solve = dt.coupled_deflections

    def counted(c_hat, k, k_obj):
        solved.append(len(k_obj))
        return solve(c_hat, k, k_obj)

    monkeypatch.setattr(dt, "CHUNK_SAMPLES", 64)
    monkeypatch.setattr(dt, "coupled_deflections", counted)
    chunked = dt.run_die_tolerance(plan, 300, 4, k_obj=[1.0, 3.0]).as_json()
    # (the nominal R(K_obj) table of the inversion is one fixed solve, whatever the draw)
    assert max(n for n in solved if n != dt.INVERSION_TABLE_POINTS) <= 64 < 300
    assert json.dumps(chunked) == json.dumps(whole)


def test_the_rows_stiffness_at_once_is_the_scalar_closed_form(plan):
    from tactcad.products.silicon_die.design.mems_die import (beam_stiffness_N_per_mm,
                                                              beam_stiffnesses_N_per_mm)

    beam = plan.beams[0]
    t = beam.thickness_um + np.array([-0.5, 0.0, 0.3, 0.0])
    t[-1] = beam.width_um * 20  # w / t past the root table's end: held at its end value
    length = beam.length_um + np.array([2.0, 0.0, -2.0, 1.0])
    at_once = beam_stiffnesses_N_per_mm(plan.youngs_modulus_MPa, beam.width_um, t, length)
    one_by_one = [beam_stiffness_N_per_mm(plan.youngs_modulus_MPa, beam.width_um, a, b)
                  for a, b in zip(t, length)]
    assert at_once == pytest.approx(one_by_one, rel=1e-13)
    with pytest.raises(ValueError, match="thickness_um"):
        beam_stiffnesses_N_per_mm(plan.youngs_modulus_MPa, beam.width_um,
                                  np.array([1.0, -1.0]), np.array([10.0, 10.0]))


def test_a_dies_samples_past_its_range_are_refused_naming_the_range():
    import tactcad
    from tactcad.errors import DesignError
    from tactcad.products.silicon_die.studies.die_tolerance import DIE_SAMPLES_RANGE

    die = tactcad.load(EXAMPLE)
    with pytest.raises(DesignError) as err:
        die.tolerance(samples=DIE_SAMPLES_RANGE[1] + 1)
    assert err.value.field == "samples" and f"2 ... {DIE_SAMPLES_RANGE[1]}" in err.value.allowed
    with pytest.raises(DesignError) as err:  # below it: the die's range too, not an array's
        die.tolerance(samples=1)
    assert (err.value.field, err.value.value) == ("samples", 1)
    assert err.value.allowed == f"an integer 2 ... {DIE_SAMPLES_RANGE[1]} (dies drawn)"


@pytest.mark.parametrize("samples", ["1", "5000000"])
def test_the_command_refuses_a_dies_samples_with_the_dies_range_alone(die_folder, samples):
    # the parser reads no design: the range is the product's, one message either side of it
    from tactcad.products.silicon_die.studies.die_tolerance import DIE_SAMPLES_RANGE

    r = run_cli("tolerance", "--samples", samples, cwd=die_folder)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert (f"--samples = {samples}: allowed an integer 2 ... {DIE_SAMPLES_RANGE[1]} "
            "(dies drawn)") in r.stderr
    assert "10000000" not in r.stderr
