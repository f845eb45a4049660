"""The bonded gauge in the mechanics: every element of a design carries its gauge's glue line
and carrier (:class:`tactcad.partlib.array.element.GaugeStack`), every stiffness level models
it (the closed form and the beam by their section, fem2d and fem3d by meshing it), and the
stated error of each level's layer term holds against the meshed layer.

The plane model's layer is checked against CalculiX in
``test_gauge_layer_calculix.py``; fem3d's here (slow).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tactcad.design.array_plan import EXAMPLES, load_design, plan_from_dict, with_overrides
from tactcad.mechanics.bonded_layer import (CLOSED_FORM_LAYER_ERROR_REL, BEAM_LAYER_ERROR_REL,
                                            chain_layer, layer_of)
from tactcad.mechanics.correction import load_correction
from tactcad.mechanics.ladder import estimate, gauge_k_rise
from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain
from tactcad.studies.tolerance_montecarlo import corrected_stiffness

from shared_solves import ONE_WORKER, shared_store

EXAMPLE_NAMES = ("macro_array", "ti_array_2x3", "grasper_jaw_10mm")


def _plan(name: str):
    return load_design(EXAMPLES / name / f"{name}.toml")


@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_every_element_carries_the_gauge_its_readout_names(name):
    plan = _plan(name)
    chain = readout_chain(plan)
    for slot in plan.slots:
        g = slot.geometry
        assert g.gauge is not None and g.bare().gauge is None and g.bare().bare() == g.bare()
        assert (g.gauge.grid_length_mm, g.gauge.grid_width_mm, g.gauge.height_mm,
                g.gauge.modulus_MPa) == (chain.grid_length_mm, chain.grid_width_mm,
                                         chain.grid_height_mm, chain.gauge_backing_modulus_MPa)
        assert layer_of(g) == chain_layer(g, chain)
        layer = layer_of(g)
        assert layer.x0_mm < layer.grid_x0_mm < g.hinge_x_mm < layer.grid_x1_mm < layer.x1_mm
        assert layer.width_mm <= g.sheet_thickness_mm


def test_a_design_whose_glue_line_is_thicker_gives_its_elements_a_taller_stack_and_a_stiffer_k():
    base = load_design()
    thick = plan_from_dict(with_overrides(base.raw, {"readout.adhesive_thickness_mm": 0.05}))
    g0, g1 = base.element(1).geometry, thick.element(1).geometry
    assert g1.gauge.height_mm > g0.gauge.height_mm
    assert g1.bare() == g0.bare()  # the element as cut is the same
    k0, k1 = (estimate("closed-form", g, base.material).stiffness_N_per_mm for g in (g0, g1))
    assert k1 > k0


@pytest.mark.slow  # each example element at fem2d with and without its layer meshed
@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_each_level_raises_k_and_the_closed_and_beam_terms_hold_against_the_meshed_layer(name):
    """The closed form's and the beam's layer terms against fem2d with the layer meshed
    (whose rise matches fem3d's to 2 %, slow test below): within the error each states."""
    plan = _plan(name)
    m = plan.material
    for g in plan.distinct_elements.values():
        rises = {model: gauge_k_rise(model, g, m) for model in ("closed-form", "beam", "fem2d")}
        assert all(r > 0.01 for r in rises.values()), rises
        fem = rises["fem2d"]
        assert abs(rises["closed-form"] / fem - 1) <= CLOSED_FORM_LAYER_ERROR_REL, (g, rises)
        assert abs(rises["beam"] / fem - 1) <= BEAM_LAYER_ERROR_REL, (g, rises)
        # each level's error estimate carries its layer term's
        bare = estimate("closed-form", g.bare(), m).error_estimate_rel
        assert estimate("closed-form", g, m).error_estimate_rel == pytest.approx(
            bare + CLOSED_FORM_LAYER_ERROR_REL * rises["closed-form"])


@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_the_design_search_and_the_ladder_give_one_k_with_the_gauge(name):
    """The vectorised closed form the design searches and the tolerance studies use, and
    the ladder's closed-form level, are one number for an element with its gauge."""
    plan = _plan(name)
    m = plan.material
    for g in plan.distinct_elements.values():
        k = float(corrected_stiffness(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
                                      m.youngs_modulus_MPa, g, m.poisson_ratio,
                                      load_correction()))
        assert k == pytest.approx(estimate("closed-form", g, m).stiffness_N_per_mm, rel=1e-12)
        bare = float(corrected_stiffness(g.web_thickness_mm, g.notch_radius_mm,
                                         g.arm_length_mm, m.youngs_modulus_MPa, g.bare(),
                                         m.poisson_ratio, load_correction()))
        assert k > bare


def test_a_layer_of_no_stiffness_lifts_the_grid_as_the_transformed_section_says():
    """With the layer's modulus near nil the meshed grid plane reads the face's strain
    extended linearly through the layer's height: the section's height factor
    ((t/2 + h) / (t/2)) at the notch, averaged over the grid; the same mesh with the
    layer's own modulus reads less (the layer stiffens the web)."""
    from tactcad.mechanics.fem.fem2d import solve_fem2d

    plan = load_design()
    g, m = plan.element(1).geometry, plan.material
    layer = layer_of(g)
    limp = dataclasses.replace(layer, modulus_MPa=layer.modulus_MPa * 1e-6)
    bonded = solve_fem2d(g.bare(), m, force_N=1.0, layer=layer).grid_strain
    lifted = solve_fem2d(g.bare(), m, force_N=1.0, layer=limp).grid_strain
    chain = readout_chain(plan)
    face = grid_strain_per_N(g, m, chain, "fem2d")
    # the face's grid average (fem2d's own, before the width factor) times the lift
    from tactcad.mechanics.gauge_strain import width_strain_factor

    surface = face["surface"] / width_strain_factor(g.bare(), m, chain.grid_width_mm).factor
    t, h = g.web_thickness_mm, layer.height_mm
    assert lifted / surface == pytest.approx((t / 2 + h) / (t / 2), rel=0.05)
    assert abs(bonded) < abs(lifted)


def test_the_modal_fem_levels_mesh_the_layer_and_give_it_no_mass_of_its_own():
    """The layer stiffens the element: fem2d's first frequency rises with it; its mass is
    the gauge installation's added mass, not the layer's cells."""
    from tactcad.mechanics.fem.fem_modal import solve_element_modes

    plan = load_design()
    g, m = plan.element(1).geometry, plan.material
    with_layer = solve_element_modes(g, m, dim=2, modes=1).frequencies_Hz[0]
    bare = solve_element_modes(g.bare(), m, dim=2, modes=1).frequencies_Hz[0]
    rise = gauge_k_rise("fem2d", g, m)
    # f ~ sqrt(K / m): the frequency rises by about half the K rise
    assert with_layer / bare - 1 == pytest.approx(np.sqrt(1 + rise) - 1, rel=0.2)


@pytest.mark.slow  # fem3d with and without the layer on four elements (about 2 min)
@ONE_WORKER  # its fem3d solves are test_gauge_strain_fem3d's and the CalculiX test's
@pytest.mark.parametrize("name,part", [("macro_array", "element_a4mm"),
                                       ("ti_array_2x3", "element_a19p605mm"),
                                       ("grasper_jaw_10mm", "element_a2mm"),
                                       ("grasper_jaw_10mm", "element_a3mm")])
def test_the_stated_layer_errors_hold_against_fem3d_with_the_layer_meshed(name, part):
    from tactcad.store import keeping_results

    plan = _plan(name)
    g, m = plan.distinct_elements[part], plan.material
    chain = readout_chain(plan)
    # one block, as a command opens: the grid strain reads the solves of the K rise
    with keeping_results(shared_store()):
        rises = {model: gauge_k_rise(model, g, m) for model in ("closed-form", "beam", "fem2d",
                                                                "fem3d")}
        fem = grid_strain_per_N(g, m, chain, "fem3d")
        cf = grid_strain_per_N(g, m, chain, "closed-form")
    fem3d = rises["fem3d"]
    print(f"{name} {part}: K rise " + ", ".join(f"{k} {100 * v:.2f} %" for k, v in rises.items()))
    assert abs(rises["closed-form"] / fem3d - 1) <= CLOSED_FORM_LAYER_ERROR_REL
    assert abs(rises["beam"] / fem3d - 1) <= BEAM_LAYER_ERROR_REL
    assert rises["fem2d"] == pytest.approx(fem3d, rel=0.03)
    # the grid's strain: fem3d's own plane against the closed form's face x read factor
    assert "meshed" in fem["grid_source"]
    assert fem["grid"] == pytest.approx(cf["grid"], rel=cf["error_rel"] + 0.05)


@pytest.mark.parametrize("stack", [{"readout.gauge_backing_modulus_MPa": 0.0},
                                   {"readout.gauge_backing_thickness_mm": 0.0,
                                    "readout.adhesive_thickness_mm": 0.0}])
def test_a_gauge_stack_of_no_modulus_or_no_height_leaves_the_element_bare(stack):
    """The file may state 0 for either (the ranges allow it): no layer, K as cut, no crash."""
    base = load_design()
    plan = plan_from_dict(with_overrides(base.raw, stack))
    g = plan.element(1).geometry
    assert g.gauge is None
    assert estimate("closed-form", g, plan.material).stiffness_N_per_mm == pytest.approx(
        estimate("closed-form", base.element(1).geometry.bare(), base.material).stiffness_N_per_mm)


@pytest.mark.slow  # five fem2d solves, the layer meshed
def test_the_peak_stress_is_the_elements_not_the_layers():
    """With the layer meshed, the hinge's peak stress is read on the element's cells: the
    layer takes a little of the moment (a few per cent below the bare element's), and the
    peak lies in the element, not in the layer above the face (whose strain read with the
    element's modulus once gave a peak 20 % high). The strength check itself reads the
    element as cut (that margin kept), with the installed K."""
    from tactcad.mechanics.element_strength import STRESS_WEB_DIVISIONS_2D
    from tactcad.studies.strength_studies import _fem2d_peaks, element_stress

    plan = load_design()
    g, m = plan.element(4).geometry, plan.material
    bare = _fem2d_peaks(g.bare(), m, STRESS_WEB_DIVISIONS_2D, 3)[1][-1]
    layered = _fem2d_peaks(g, m, STRESS_WEB_DIVISIONS_2D, 3)[1][-1]
    assert 0.85 * bare.per_newton_MPa_per_N < layered.per_newton_MPa_per_N \
        < bare.per_newton_MPa_per_N
    assert layered.location_mm[1] <= g.base_height_mm + 1e-9
    checked = element_stress(g, m, "fem2d")
    assert checked.stress_MPa_per_N == pytest.approx(
        element_stress(g.bare(), m, "fem2d").stress_MPa_per_N)
    assert checked.stiffness_N_per_mm == pytest.approx(
        estimate("fem2d", g, m).stiffness_N_per_mm)


def _layer_args(g):
    """The layer arguments of :func:`layer_compliance_change` for ``g``'s gauge."""
    from tactcad.design.readout_section import CARRIER_SIDE_MM, carrier_width_mm

    s = g.gauge
    half = s.grid_length_mm / 2 + CARRIER_SIDE_MM
    return (g.sheet_thickness_mm, g.base_height_mm, g.arm_height_mm, (-half, half),
            s.height_mm, s.modulus_MPa, carrier_width_mm(s.grid_width_mm, g.sheet_thickness_mm))


def _layer_error_in_k(g, material, t, R, a, modulus=None, span=None):
    """max |K_fast / K_quadrature - 1| of the layered closed form at (t, R, a): the layer
    term of :func:`layer_compliance_change` against the 24-point reference, at the
    material's modulus or ``modulus`` (broadcast), on ``g``'s carrier or ``span``."""
    from tactcad.mechanics.bonded_layer import (layer_compliance_change,
                                                layer_compliance_change_quadrature)

    E = material.youngs_modulus_MPa if modulus is None else modulus
    b, hb, ha, carrier, hl, El, wl = _layer_args(g)
    args = (b, E, hb, ha, carrier if span is None else span, hl, El, wl)
    k_bare = corrected_stiffness(t, R, a, E, g.bare(), material.poisson_ratio, load_correction())
    fast = layer_compliance_change(t, R, a, *args)
    ref = layer_compliance_change_quadrature(t, R, a, *args)
    return float(np.max(np.abs((1 / k_bare + ref) / (1 / k_bare + fast) - 1)))


def _benchmark_designs(n=20_000):
    rng = np.random.default_rng(7)
    t = rng.uniform(0.15, 0.4, n)
    a = rng.uniform(4.0, 8.0, n)
    R = rng.uniform(t, 2.0)
    return t, R, a, rng


def test_the_layer_term_holds_the_reference_quadrature_over_the_benchmarks_designs():
    """``bench closed-form``'s designs (webs 0.15-0.4 mm, arms 4-8 mm, radii web-2 mm):
    K within the stated error of the 24-point quadrature, and within 1e-4, at the
    material's modulus and with a modulus drawn per design (the Monte Carlo's draw)."""
    from tactcad.mechanics.bonded_layer import LAYER_K_ERROR_REL

    plan = load_design()
    g, m = plan.element(1).geometry, plan.material
    t, R, a, rng = _benchmark_designs()
    err = _layer_error_in_k(g, m, t, R, a)
    err_e = _layer_error_in_k(g, m, t, R, a, m.youngs_modulus_MPa * rng.uniform(0.9, 1.1, t.size))
    assert max(err, err_e) <= LAYER_K_ERROR_REL <= 1e-4
    print(f"benchmark's designs: max |dK/K| {err:.2e}, modulus per design {err_e:.2e}")


@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_the_layer_term_holds_the_reference_quadrature_around_the_examples_elements(name):
    """Every element of the shipped examples with its web and notch radius +-30 % (the
    grasper's 78 um web down to 55 um, whose K the layer raises by 75 %) and the modulus
    +-10 %, as a Monte Carlo draws them (an (n, elements) array, a modulus per row): K
    within the stated error of the 24-point quadrature."""
    from tactcad.mechanics.bonded_layer import LAYER_K_ERROR_REL

    plan = _plan(name)
    rng = np.random.default_rng(3)
    n = 4096
    for g in plan.distinct_elements.values():
        t = g.web_thickness_mm * rng.uniform(0.7, 1.3, (n, 2))
        R = g.notch_radius_mm * rng.uniform(0.7, 1.3, (n, 2))
        a = np.full(2, g.arm_length_mm)
        modulus = plan.material.youngs_modulus_MPa * rng.uniform(0.9, 1.1, (n, 1))
        err = _layer_error_in_k(g, plan.material, t, R, a)
        err_e = _layer_error_in_k(g, plan.material, t, R, a, modulus)
        assert max(err, err_e) <= LAYER_K_ERROR_REL, (g, err, err_e)
        print(f"{name} a = {g.arm_length_mm} mm: max |dK/K| {err:.2e}, "
              f"modulus per sample {err_e:.2e}")


def test_one_element_a_modulus_per_sample_and_an_off_centre_carrier_give_one_layer_term():
    """The layer term of one element is the same number as that element's entry in a
    vectorised call, whether the modulus is one or drawn per sample (the modulus enters
    each sample's own section: no first-order term, no table); a carrier off the notch
    centre (the general rule, both signs of u) holds the reference as the centred one."""
    from tactcad.mechanics.bonded_layer import (LAYER_K_ERROR_REL, layer_compliance_change,
                                                layer_compliance_change_quadrature)

    plan = load_design()
    g, m = plan.element(1).geometry, plan.material
    b, hb, ha, (u0, u1), hl, El, wl = _layer_args(g)
    rest = (hb, ha, (u0, u1), hl, El, wl)
    t, R, a, rng = _benchmark_designs(2048)
    modulus = m.youngs_modulus_MPa * rng.uniform(0.9, 1.1, t.size)
    many = layer_compliance_change(t, R, a, b, modulus, *rest)
    for i in range(0, t.size, 97):
        one = layer_compliance_change(t[i], R[i], a[i], b, modulus[i], *rest)
        assert np.ndim(one) == 0
        assert one == pytest.approx(many[i], rel=1e-13)
    np.testing.assert_allclose(many, layer_compliance_change_quadrature(t, R, a, b, modulus,
                                                                         *rest), rtol=1e-4)
    for span in ((0.6 * u0, u1), (u0, 0.3 * u1), (0.1, u1)):
        assert _layer_error_in_k(g, m, t, R, a, modulus, span) <= LAYER_K_ERROR_REL
