"""The grasp as a virtual experiment: travels, stops, readings, paired vs as laid out."""
import numpy as np
import pytest

from tactcad.design.array_plan import load_design
from tactcad.errors import DesignError
from tactcad.in_use.grasp_experiment import (grasp, overload_warning, solve_tips,
                                             tissue_compliance)
from tactcad.in_use.jaw_kinematics import JawGeometry
from tactcad.mechanics.contact import Punch
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.mechanics.readout_chain import row_units
from comb_variants import row_paired_comb

COMB = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"  # paired along its rows here
TI = "hardware/ti_array_2x3/ti_array_2x3.toml"


def setup(path):
    plan = row_paired_comb() if path == COMB else load_design(path)
    k = ladder_stiffness_by_element(plan)
    units = [(r.number, m.number)
             for r, m in row_units(plan, {s.geometry.part_name: k[s.number] for s in plan.slots})]
    return plan, k, units


JAW = JawGeometry(-5.0, 0.0, 40.0, 60.0, 3.0)


@pytest.mark.parametrize("path", [COMB, TI])
def test_without_coupling_paired_units_read_the_true_kobj(path):
    plan, k, units = setup(path)
    g = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.05, coupling="none", profile="wedge")
    for u in g.paired.units:
        assert u["valid"] and u["radius_ratio"] == pytest.approx(1.0)
        assert u["K_obj_read_N_per_mm"] == pytest.approx(1.0, rel=1e-9)


def test_as_laid_out_R_carries_the_travel_ratio_and_the_correction_removes_it():
    plan, k, units = setup(COMB)
    g = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.3, coupling="none", profile="wedge")
    for u in g.as_laid_out.units:
        ratio = u["travel_measuring_mm"] / u["travel_reference_mm"]
        assert u["R_read"] == pytest.approx(ratio * u["R_true"], rel=1e-9)
        assert u["K_obj_corrected_N_per_mm"] == pytest.approx(1.0, rel=1e-9)
        # wedge: travel in proportion to the radius
        assert ratio == pytest.approx(u["radius_ratio"], rel=1e-9)


def test_tissue_coupling_biases_the_paired_reading_but_not_its_radius():
    plan, k, units = setup(COMB)
    g = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.3, coupling="layer", profile="wedge")
    errors = [u["error_rel"] for u in g.paired.units]
    laid = [abs(u["error_rel"]) for u in g.as_laid_out.units]
    assert all(abs(e) > 1e-3 for e in errors)
    assert max(abs(e) for e in errors) < min(laid)


def test_the_force_mode_finds_the_angle_of_the_grasp_force():
    plan, k, units = setup(COMB)
    g = grasp(plan, JAW, k, units, 2.0, 0.05, force_N=0.4, profile="slab")
    assert g.as_laid_out.total_force_N == pytest.approx(0.4, rel=1e-6)
    assert g.paired.total_force_N == pytest.approx(0.4, rel=1e-6)


def test_a_hard_grasp_puts_elements_on_their_stops_and_the_stop_takes_the_rest():
    plan, k, units = setup(COMB)
    g = grasp(plan, JAW, k, units, 2.0, 0.05, angle_deg=4.0)
    on = [t for t in g.as_laid_out.tips if t["on_stop"]]
    assert on
    for t in on:
        assert t["deflection_mm"] == pytest.approx(t["stop_engage_mm"])
        assert t["element_force_N"] + t["stop_force_N"] == pytest.approx(t["tip_force_N"])
        assert t["stop_force_N"] > 0
    assert not any(u["valid"] for u in g.as_laid_out.units if "on its stop" in u["why"])


def test_solve_tips_lifts_a_tip_that_would_pull():
    c = np.array([[1.0, 0.9], [0.9, 1.0]])
    sol = solve_tips([1.0, 0.01], [10.0, 10.0], [np.inf, np.inf], c)
    assert not sol.in_contact[1] and sol.tip_force_N[1] == 0.0 and sol.tip_force_N[0] > 0


def test_the_coupled_tissue_is_symmetric_and_one_face_sees_kobj():
    faces = [Punch(0.0, 0.0, 1.0, 1.0), Punch(0.0, 4.6, 1.0, 1.0)]
    for coupling in ("layer", "halfspace"):
        c = tissue_compliance(faces, 2.0, 3.0, coupling)
        assert np.allclose(c, c.T)
        assert 1 / c[0, 0] == pytest.approx(2.0, rel=0.05)
    assert tissue_compliance(faces, 2.0, 3.0, "halfspace")[0, 1] > 0


@pytest.mark.parametrize("kw,field", [(dict(angle_deg=5.0, force_N=1.0), "angle_deg / force_N"),
                                      (dict(force_N=1e4), "force_N"),
                                      (dict(angle_deg=80.0), "angle_deg"),
                                      (dict(angle_deg=5.0, coupling="x"), "coupling"),
                                      (dict(angle_deg=5.0, profile="x"), "profile")])
def test_bad_grasp_inputs_name_the_field(kw, field):
    plan, k, units = setup(COMB)
    with pytest.raises(DesignError) as e:
        grasp(plan, JAW, k, units, 1.0, 0.05, **kw)
    assert e.value.field == field


def test_each_tip_is_judged_on_its_own_overload_limit_apart_from_its_rating():
    plan, k, units = setup(COMB)
    loose = grasp(plan, JAW, k, units, 2.0, 0.05, angle_deg=4.0)
    assert all(t["overload_limit_N"] is None and not t["over_overload_limit"]
               for t in loose.as_laid_out.tips)  # none given: the rating alone
    hardest = max(t["element_force_N"] for t in loose.as_laid_out.tips)
    # each element's limit between its rating and the hardest force: the loaded ones are past it
    limits = {s.number: 0.5 * (0.05 + hardest) for s in plan.slots}
    g = grasp(plan, JAW, k, units, 2.0, 0.05, angle_deg=4.0, overload_N=limits)
    for lay in (g.as_laid_out, g.paired):
        for t in lay.tips:
            assert t["overload_limit_N"] == limits[t["site"]]
            assert t["over_overload_limit"] == (t["element_force_N"] > limits[t["site"]])
        assert any(t["over_overload_limit"] for t in lay.tips)
        # a unit on an overloaded element reads nothing; the others keep their readings
        over = {t["site"] for t in lay.tips if t["over_overload_limit"]}
        for u in lay.units:
            hit = bool({u["reference"], u["measuring"]} & over)
            assert u["overloaded"] == hit and (u["K_obj_read_N_per_mm"] is None) == hit
            assert not (hit and u["valid"])
        warning = overload_warning(lay)
        assert warning and f"{lay.total_force_N:.4g} N" in warning
        assert all(str(n) in warning for n in over)
    assert overload_warning(loose.as_laid_out) is None


def test_under_a_wedge_each_unit_is_judged_on_its_own_thickness_with_one_modulus():
    """Under the wedge the tissue's thickness varies along the jaw (h r / r_last) and its
    modulus does not: each equal-radius unit's true K_obj is its face alone on its own
    thickness (higher where the tissue is thinner; the outermost unit's, on the slab's
    thickness, is K_obj), and its bias follows the local thickness; each unit reads as its
    two tips alone on a uniform layer of their thickness (an isolated two-face solve; the
    rest of the jaw moves it by < 1 %)."""
    from tactcad.in_use.grasp_experiment import (DEFAULT_TISSUE_BASE, TISSUE_POISSON_RATIO,
                                                 tips_as_laid_out)
    from tactcad.mechanics.contact import single_punch_unit_compliance, unit_punch_compliance

    plan, k, units = setup(COMB)
    wedge = grasp(plan, JAW, k, units, 1.5, 1.0, force_N=0.3, profile="wedge")
    paired = sorted(wedge.paired.units, key=lambda u: u["r_reference_mm"])
    assert all(u["valid"] for u in paired)
    thickness = [u["tissue_thickness_reference_mm"] for u in paired]
    true = [u["K_obj_true_N_per_mm"] for u in paired]
    errors = [u["error_rel"] for u in paired]
    assert thickness == sorted(thickness) and thickness[-1] == pytest.approx(JAW.slab_thickness_mm)
    assert true == sorted(true, reverse=True) and true[-1] == pytest.approx(1.5, rel=1e-9)
    assert errors == sorted(errors) and errors[-1] - errors[0] > 0.05
    tips = tips_as_laid_out(plan, JAW, k)
    face = tips.punches[0]
    E = 1.5 * single_punch_unit_compliance(face.width_x_mm, face.depth_z_mm,
                                           TISSUE_POISSON_RATIO,
                                           JAW.slab_thickness_mm, DEFAULT_TISSUE_BASE)
    for u in paired:
        i, j = (tips.labels.index(n) for n in (u["reference"], u["measuring"]))
        c = unit_punch_compliance([tips.punches[i], tips.punches[j]], TISSUE_POISSON_RATIO,
                                  round(u["tissue_thickness_reference_mm"], 9),
                                  DEFAULT_TISSUE_BASE) / E
        d = u["travel_reference_mm"]
        assert u["travel_measuring_mm"] == pytest.approx(d, rel=1e-9)
        kr, km = u["K_r_N_per_mm"], u["K_m_N_per_mm"]
        p = np.linalg.solve(c + np.diag([1 / kr, 1 / km]), [d, d])
        r_alone = (p[1] / km) / (p[0] / kr)
        assert u["R_read"] == pytest.approx(r_alone, rel=0.01)


def test_the_correction_takes_out_each_tips_travel_and_tissue():
    """Eq. 1 per tip, each on its own tissue K_0 / s (a wedge: the thinner tissue is
    stiffer) and its own travel: the corrected K_obj is the two tips' geometric mean
    exactly, the travel alone (eq. 3 on R Δ_r / Δ_m) misses it."""
    from tactcad.in_use.grasp_experiment import TipSolution, Tips, unit_reading

    k0, k_r, k_m = 3.0, 24.0, 3.0
    s = np.array([0.4, 0.75])  # the reference on the thinner tissue
    travel = np.array([0.006, 0.012])
    k_tissue = k0 / s
    deflection = travel * k_tissue / (np.array([k_r, k_m]) + k_tissue)  # eq. 1 per tip
    force = np.array([k_r, k_m]) * deflection
    sol = TipSolution(travel, deflection, force, force, np.zeros(2), np.zeros(2, bool),
                      np.ones(2, bool))
    tips = Tips((1, 2), np.array([6.0, 12.0]), [Punch(0, 0, 1, 1), Punch(6, 0, 1, 1)],
                np.array([k_r, k_m]), np.full(2, np.inf), np.full(2, np.inf))
    u = unit_reading(1, 2, sol, tips, k_tissue, softening=s)
    assert u["K_obj_true_N_per_mm"] == pytest.approx(k0 / np.sqrt(s.prod()), rel=1e-12)
    assert u["error_corrected_rel"] == pytest.approx(0.0, abs=1e-9)
    assert u["R_corrected"] == pytest.approx(u["R_true"], rel=1e-9)
    travel_only = unit_reading(1, 2, sol, tips, k_tissue)  # one tissue assumed under both
    assert abs(travel_only["error_corrected_rel"]) > 0.2


def test_the_corrected_reading_along_the_rows_beats_the_read_and_says_what_it_leaves():
    """The shipped comb's units laid one pitch apart along the rows under the wedge: each
    reads its travel ratio and its two tips' tissue; corrected for both, the tissue's
    coupling between neighbouring tips is left, and each layout states its size."""
    plan = load_design(COMB)  # paired across the rows: grasp lays its units along them too
    k = ladder_stiffness_by_element(plan)
    units = [(r.number, m.number)
             for r, m in row_units(plan, {s.geometry.part_name: k[s.number] for s in plan.slots})]
    g = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.3, coupling="layer", profile="wedge")
    apart = g.along_rows.units
    assert apart and all(u["valid"] and u["radius_ratio"] > 1.02 for u in apart)
    for u in apart:
        assert abs(u["error_corrected_rel"]) < abs(u["error_rel"]) / 3, u["unit"]
        assert not u["correction_worse"]
    left = g.along_rows.correction_residual
    worst = max(apart, key=lambda u: abs(u["error_corrected_rel"]))
    assert left["largest_rel"] == worst["error_corrected_rel"] and left["unit"] == worst["unit"]
    assert "coupling" in left["cause"] and not left["worse_than_read"]
    assert g.along_rows.as_json()["correction_residual"] == left
    # without the coupling nothing is left: the correction is exact
    none = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.3, coupling="none", profile="wedge")
    assert none.along_rows.correction_residual is None


def test_a_corrected_reading_further_off_than_read_is_named():
    """The comb paired along its rows presses twelve tips into one tissue: the coupling the
    correction leaves can exceed the error it takes out, and the layout names those units."""
    plan, k, units = setup(COMB)
    g = grasp(plan, JAW, k, units, 1.0, 1.0, force_N=0.3, coupling="layer", profile="wedge")
    worse = [u["unit"] for u in g.as_laid_out.units
             if abs(u["error_corrected_rel"]) > abs(u["error_rel"])]
    left = g.as_laid_out.correction_residual
    assert worse and left["worse_than_read"] == worse
    assert all(u["correction_worse"] == (u["unit"] in worse) for u in g.as_laid_out.units)


def test_a_correction_that_leaves_a_unit_further_off_is_named():
    from tactcad.in_use.grasp_experiment import correction_residual

    base = {"valid": True, "unit": "1/2", "error_rel": 0.05, "error_corrected_rel": 0.3,
            "correction_worse": True}
    better = {**base, "unit": "3/4", "error_rel": -0.4, "error_corrected_rel": 0.1,
              "correction_worse": False}
    left = correction_residual([base, better], "layer")
    assert left["worse_than_read"] == ["1/2"] and left["range_rel"] == [0.1, 0.3]
    assert correction_residual([{**better, "error_corrected_rel": 1e-12}], "layer") is None
