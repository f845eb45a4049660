"""Rigs sized to a design: the force gauge from the catalogue and the
evaluation rig's weights follow the design's rated full-scale force and its
K_obj range; tried on the titanium 2 x 3 example and a 2 x 6 variant rated
0.077 N (the grasper jaw's insert)."""

from __future__ import annotations

from pathlib import Path

import pytest

import tactcad
from tactcad.design.rig_plan import rigs_from_dict
from tactcad.project_folder import companion_tables
from tactcad.studies.rig_sizing import (WEIGHT_COUNT_RANGE, element_loads_per_newton, gauge_need,
                                        weight_series_g, weights_for)
from tactcad.studies.verification import rated_full_scale_force
from tactcad.vocabulary.force_gauge_catalogue import (RESOLUTION_SHARE, choose_force_gauge,
                                                      force_gauges, gauge_shortfalls)

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
TWO_BY_SIX = {"array.columns": 6, "sheet.thickness_mm": 2.0, "array.pitch_mm": 3.0,
              "arms.lengths_mm": [19.6, 6.196, 19.6, 19.6, 19.6, 19.6,
                                  19.6, 19.6, 19.6, 6.196, 19.6, 19.6],
              "requirements.full_scale_force_N": 0.077}


@pytest.fixture(scope="module", params=[None, TWO_BY_SIX], ids=["ti_2x3", "ti_2x6"])
def plan(request):
    return tactcad.load(EXAMPLE, set=request.param).plan


def test_the_papers_gauge_cannot_resolve_a_0p077_N_rating_and_the_chosen_one_can():
    need = gauge_need(0.077, [5.0, 1.58, 0.5])  # the grasper: K_obj 0.5 ... 5 N/mm
    # every sample pressed as deep as one element at the rating presses the softest
    assert need.sample_depth_mm == pytest.approx(0.077 / 0.5)
    assert need.range_N == pytest.approx(0.077 * 5.0 / 0.5)
    assert need.resolution_N == pytest.approx(RESOLUTION_SHARE * 0.077)
    assert gauge_shortfalls(5.0, 0.001, need) == ["resolution 0.001 N > 0.00077 N"]
    gauge, misses = choose_force_gauge(need)
    assert not misses and not gauge_shortfalls(gauge.range_N, gauge.resolution_N, need)
    # the smallest range that fits: every gauge of smaller range misses the need
    assert all(gauge_shortfalls(g.range_N, g.resolution_N, need)
               for g in force_gauges() if g.range_N < gauge.range_N)


def test_a_need_no_catalogue_gauge_meets_names_what_the_nearest_misses():
    gauge, misses = choose_force_gauge(gauge_need(0.001, [30.0, 1.0]))  # 30 mN to read to 10 uN
    assert misses and gauge.range_N >= 0.03 and any("resolution" in m for m in misses)


@pytest.mark.parametrize("rated", [0.01, 0.077, 0.33, 1.0, 2.5])
@pytest.mark.parametrize("ratio", [1.0, 10.0, 20.0])
def test_a_catalogue_gauge_fits_every_usual_rating_and_kobj_range(rated, ratio):
    """Ratings of 10 mN to 2.5 N over K_obj ranges up to 20:1 all find a gauge
    (the rigs made for a design then pass the check)."""
    gauge, misses = choose_force_gauge(gauge_need(rated, [ratio, 1.0]))
    assert not misses, (rated, ratio, gauge.model)


def test_weights_take_the_most_loaded_element_to_at_most_the_rating(plan):
    rated = rated_full_scale_force(plan)
    per_newton = element_loads_per_newton(plan, [5.0, 2.24, 1.0])
    w = weights_for(per_newton, rated)
    assert WEIGHT_COUNT_RANGE[0] <= w.count <= WEIGHT_COUNT_RANGE[1]
    assert w.mass_g in weight_series_g(1e6)
    assert w.top_load_N == pytest.approx(w.preload_N + w.count * w.mass_g * 9.80665e-3)
    assert w.element_load_N == pytest.approx(w.top_load_N * max(per_newton.values()))
    assert w.element_load_N <= rated
    # the largest weights that fit: the next mass of the series would not give the least count
    heavier = [m for m in weight_series_g(1e6) if m > w.mass_g][-1]
    top = rated / max(per_newton.values())
    assert heavier * 9.80665e-3 * (WEIGHT_COUNT_RANGE[0] + 1) > top
    # the paper's three 100 g weights would break the array
    assert (3.235 + 3 * 0.980665) * max(per_newton.values()) > 10 * rated


def test_the_rigs_made_for_a_design_are_sized_to_it(plan):
    tables = companion_tables(plan)["rigs"]
    rigs = rigs_from_dict(tables, plan)
    rated = rated_full_scale_force(plan)
    gauge = rigs.part("force_gauge")
    need = gauge_need(rated, rigs.sample_stiffness_N_per_mm)
    assert not gauge_shortfalls(gauge.range_N, gauge.resolution_N, need)
    assert gauge.model == choose_force_gauge(need)[0].model
    assert rigs.library["force_gauge"].process.startswith(gauge.model)  # the BOM's text
    assert rigs.library["weights"].name == f"weight_{rigs.part('weights').mass_g:g}g"
    assert rigs.evaluation_preload_N == pytest.approx(rigs.part("weights").mass_g * 9.80665e-3,
                                                      rel=1e-4)
    reasons = dict(rigs.assumptions)
    assert f"{rated:g} N" in reasons["weights.mass_g"]
    assert "force_gauge.model" in reasons and "evaluation.preload_N" in reasons


def test_the_shipped_ti_example_keeps_the_rig_made_for_it():
    plan = tactcad.load(EXAMPLE).plan
    made = rigs_from_dict(companion_tables(plan)["rigs"], plan)
    shipped = tactcad.load(EXAMPLE).validated.rigs
    for key in ("force_gauge", "weights"):
        assert shipped.part(key) == made.part(key), key
    assert shipped.evaluation_preload_N == made.evaluation_preload_N
