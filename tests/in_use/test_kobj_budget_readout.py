"""The budget's read-out term against ``readout``'s and ``verify``'s K_obj resolution: one
function for both (:func:`tactcad.mechanics.resolution.noise_kobj_rel`), differing only by the
tips' coupling, which the budget states; and a unit that cannot read K_obj (K_r / K_m near 1)
unreadable in the budget exactly where verify's readable range says so."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tactcad.in_use import kobj_budget as kb

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: The Ti example in 17-4PH, widened to 2 x 4.
STEEL_2X4 = {"array.columns": 4, "arms.lengths_mm": [19.605, 6.196, 19.605, 19.605] * 2,
             "material.name": "17-4PH-H900", "material.grade": "17-4PH-H900"}
#: The Ti example with K_r / K_m about 1.002: R hardly moves with K_obj.
NEAR_ONE = {"arms.lengths_mm": [10.0, 9.99, 10.0, 10.0, 9.99, 10.0]}
#: The agreement of two evaluations of one formula (relative).
SAME_REL = 1e-9
#: The budget's records keep 6 significant digits (kb.BUDGET_DIGITS).
LISTED_REL = 1e-5
#: The coupled slope is a central difference of step kb.SLOPE_STEP_REL: its truncation
#: error, of order that step squared, against eq. 3's exact slope.
SLOPE_REL = 10 * kb.SLOPE_STEP_REL ** 2


def _plan(overrides):
    from tactcad.api import load

    return load(str(TI), set=overrides).plan if overrides else load(str(TI)).plan


def _context(plan, uncoupled=False):
    """The budget's context at the design's full-scale force and required resolution;
    ``uncoupled``: a sample whose tips do not couple (Ĉ = I), where the coupled chain is
    eq. 1-3 exactly."""
    from tactcad.in_use.tissue_coupling import CoupledSample, Tissue
    from tactcad.mechanics.ladder import estimate
    from tactcad.studies.verification import calibration_gauge, requirements_of

    req = requirements_of(plan)
    est = {n: estimate("closed-form", g, plan.material) for n, g in plan.distinct_elements.items()}
    ctx = kb.Context(plan, "closed-form", {n: e.stiffness_N_per_mm for n, e in est.items()},
                     {n: e.error_estimate_rel for n, e in est.items()}, req.full_scale_force_N,
                     5.0, {}, calibration_gauge(plan),
                     readable_within_rel=req.kobj_resolution_rel)
    if uncoupled:
        numbers = tuple(s.number for s in plan.slots)
        ctx.cache["tissue sample"] = CoupledSample(numbers, np.eye(len(numbers)), Tissue(),
                                                   (1.0, 1.0))
    return ctx, req


def _units(ctx):
    from tactcad.mechanics.readout_chain import row_units

    return [kb.Unit(r.number, m.number) for r, m in row_units(ctx.plan, dict(ctx.k))]


def _op(ctx, unit, k_obj):
    return kb.operating_point(ctx.k_of(unit.measuring), ctx.k_of(unit.reference), k_obj,
                              ctx.force_N)


@pytest.fixture(scope="module", params=["ti", "steel_2x4"])
def design(request):
    return _plan(None if request.param == "ti" else STEEL_2X4)


def test_the_unit_alone_is_readouts_kobj_resolution(design):
    """Same force, noise, units and K_obj grid: the budget's unit-alone figure, worst over
    readout's grid, is readout's per-element K_obj resolution."""
    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.mechanics.resolution import KOBJ_POINTS

    ctx, req = _context(design)
    shown = {r["element"]: r["kobj_resolution_rel"]
             for r in readout_report(design, req).records if r["kobj_resolution_rel"]}
    k_obj = np.geomspace(*req.kobj_range_N_per_mm, KOBJ_POINTS)
    units = _units(ctx)
    assert units and {u.measuring for u in units} == set(shown)
    for unit in units:
        worst = float(np.max(kb.unit_alone_resolution_rel(ctx, unit, _op(ctx, unit, k_obj))))
        assert worst == pytest.approx(shown[unit.measuring], rel=SAME_REL)


def test_without_coupling_the_readout_term_is_readouts_resolution(design):
    """On a sample whose tips do not couple, the budget's read-out term is readout's
    resolution (to the coupled slope's finite difference): the two differ only by the
    coupling the budget states."""
    ctx, req = _context(design, uncoupled=True)
    k_obj = kb.kobj_grid(req.kobj_range_N_per_mm)
    for unit in _units(ctx):
        op = _op(ctx, unit, k_obj)
        term = kb.readout_noise(ctx, unit, op).after
        assert np.all(np.isfinite(term))
        np.testing.assert_allclose(term, kb.unit_alone_resolution_rel(ctx, unit, op),
                                   rtol=SLOPE_REL)


def test_the_budget_states_its_term_as_the_unit_alone_times_the_coupling(design):
    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.studies.verification import calibration_gauge, requirements_of

    req = requirements_of(design)
    b = kb.kobj_budget(design, req.kobj_range_N_per_mm, req.full_scale_force_N,
                       force_gauge=calibration_gauge(design),
                       readable_within_rel=req.kobj_resolution_rel)
    shown = {r["element"]: r["kobj_resolution_rel"]
             for r in readout_report(design, req).records if r["kobj_resolution_rel"]}
    for u in b.units:
        alone = np.array(u["readout_alone_rel"])
        term = np.array(u["sources"]["readout_noise"]["after_rel"])
        np.testing.assert_allclose(term, alone * np.array(u["readout_coupled_over_alone"]),
                                   rtol=LISTED_REL)
        # the budget's grid holds the range's ends, where readout's worst lies
        assert max(alone[0], alone[-1]) == pytest.approx(shown[u["measuring_element"]],
                                                         rel=LISTED_REL)
        assert all(u["reads_kobj"])


def test_a_near_one_ratio_reads_no_kobj_in_the_budget_as_in_verify():
    """K_r / K_m about 1.002: readout and verify give a K_obj resolution far past the
    requirement and no readable range; the budget's read-out term and sums are unreadable at
    exactly the K_obj verify cannot read, never a small error."""
    from tactcad.mechanics.resolution import best_unit_resolution_rel, reads_within
    from tactcad.studies.verification import (calibration_gauge, element_figures, kobj_records,
                                              requirements_of, sensing_units)

    plan = _plan(NEAR_ONE)
    req = requirements_of(plan)
    units = sensing_units(plan, element_figures(plan))
    resolution, span = kobj_records(units, req, req.full_scale_force_N, "closed-form")
    assert not resolution["pass"] and span["predicted"] is None
    # the design's own requirement, as every command's budget passes it
    b = kb.kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                       force_gauge=calibration_gauge(plan),
                       readable_within_rel=req.kobj_resolution_rel)
    verify_reads = reads_within(best_unit_resolution_rel(units.read, b.k_obj,
                                                         req.full_scale_force_N),
                                req.kobj_resolution_rel)
    assert not np.any(verify_reads)
    assert b.units
    assert b.array["rss_rel"] == [None] * len(b.k_obj)
    for u in b.units:
        assert u["rss_rel"] == [None] * len(b.k_obj)
        assert u["sources"]["readout_noise"]["after_rel"] == [None] * len(b.k_obj)
        assert u["reads_kobj"] == [False] * len(b.k_obj)


@pytest.mark.parametrize("target", [0.002, 0.001, 0.00085, 0.0007])
def test_the_budget_reads_exactly_where_verify_reads(target):
    """A requirement between the Ti example's best and worst resolution: the budget's array
    reads K_obj at the same grid points as verify's readable-range test wherever the level's
    error decides it, and reads (undecided) every point verify reads at the nominal K."""
    from tactcad.mechanics.resolution import best_unit_resolution_rel, reads_within
    from tactcad.studies.verification import (calibration_gauge, element_figures,
                                              requirements_of, sensing_units)

    plan = _plan(None)
    req = requirements_of(plan)
    units = sensing_units(plan, element_figures(plan))
    b = kb.kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                       force_gauge=calibration_gauge(plan), readable_within_rel=target)
    verify_reads = reads_within(best_unit_resolution_rel(units.read, b.k_obj,
                                                         req.full_scale_force_N), target)
    budget_reads = np.array([x is not None for x in b.array["rss_rel"]])
    undecided = np.array(b.array["reads_undecided"], bool)
    assert np.array_equal(budget_reads[~undecided], verify_reads[~undecided])
    assert np.all(budget_reads[verify_reads])


def test_a_readable_limit_not_above_zero_is_refused():
    from tactcad.errors import DesignError
    from tactcad.studies.verification import calibration_gauge

    plan = _plan(None)
    with pytest.raises(DesignError, match="readable_within_rel"):
        kb.kobj_budget(plan, (1.0, 5.0), 0.1, force_gauge=calibration_gauge(plan),
                       readable_within_rel=0.0)
