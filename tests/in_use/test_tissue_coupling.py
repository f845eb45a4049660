"""The tissue under the tips: coupled compliance, eq. 2 / eq. 3 corrected, their limits."""
import math

import numpy as np
import pytest

from tactcad.design.array_plan import load_design
from tactcad.in_use.tissue_coupling import (Tissue, coupled_object_stiffness, coupled_ratio, coupled_sample,
                                            coupled_sample_from_punches, design_units, tip_punches, unit_bias)
from tactcad.mechanics.contact import ContactError, Punch, Sample, single_punch_compliance
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.mechanics.lumped_model import deflection_ratio

TI = "hardware/ti_array_2x3/ti_array_2x3.toml"


def two_tips(pitch_mm, face=(2.0, 3.0), tissue=Tissue()):
    punches = [Punch(0.0, 0.0, *face), Punch(pitch_mm, 0.0, *face)]
    return coupled_sample_from_punches((1, 2), punches, tissue)


def test_far_tips_couple_as_boussinesq_point_loads():
    """At a pitch of ten faces the neighbour's load acts as a point load: κ = (1 − ν²)/(π E r) / C₁."""
    pitch, nu = 30.0, 0.5
    c1 = single_punch_compliance(2.0, 3.0, Sample(1.0, nu))
    point = (1 - nu ** 2) / (math.pi * 1.0 * pitch) / c1
    assert two_tips(pitch).coupling(1, 2) == pytest.approx(point, rel=0.01)


def test_coupling_falls_with_pitch():
    kappas = [two_tips(p).coupling(1, 2) for p in (2.5, 4.0, 8.0)]
    assert kappas[0] > kappas[1] > kappas[2] > 0


def test_two_tips_alone_read_eq2_with_the_coupled_compliance():
    """Two tips on one spring each: R = (1 + K_r c')/(1 + K_m c'), c' = (Ĉ_mm − Ĉ_mr)/K_obj (eq. 2 form)."""
    sample = two_tips(4.0)
    c = sample.normalised
    k = {1: 2.0, 2: 20.0}
    for k_obj in (0.5, 3.0, 40.0):
        c_eff = (c[0, 0] - c[0, 1]) / k_obj
        expected = (1 + k[2] * c_eff) / (1 + k[1] * c_eff)
        assert coupled_ratio(sample, k, (1, 2), k_obj) == pytest.approx(expected, rel=1e-10)


def test_uncoupled_limit_is_eq2():
    sample = two_tips(400.0)
    k = {1: 2.0, 2: 20.0}
    assert coupled_ratio(sample, k, (1, 2), 5.0) == pytest.approx(deflection_ratio(2.0, 20.0, 5.0), rel=2e-3)


def test_a_batch_of_kobj_reads_what_each_kobj_reads_alone():
    """R over an array of K_obj (one batched solve, every pressing tip) equals R at each."""
    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    sample = coupled_sample(plan)
    unit = design_units(plan, k)[0]
    k_obj = np.geomspace(0.05, 80.0, 12).reshape(3, 4)
    batch = coupled_ratio(sample, k, unit, k_obj)
    assert batch.shape == (3, 4)
    alone = np.vectorize(lambda x: coupled_ratio(sample, k, unit, float(x)))(k_obj)
    np.testing.assert_allclose(batch, alone, rtol=1e-12)
    assert np.all(np.diff(batch.ravel()) < 0)  # R falls with K_obj


def test_the_die_tolerance_solves_the_one_coupled_model():
    from tactcad.in_use import tissue_coupling
    from tactcad.products.silicon_die.studies import die_tolerance

    assert die_tolerance.coupled_deflections is tissue_coupling.coupled_deflections


def test_coupled_inversion_reads_back_the_sample_on_a_design():
    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    sample = coupled_sample(plan)
    unit = design_units(plan, k)[0]
    for k_obj in (0.7, 2.0, 6.0):
        r = coupled_ratio(sample, k, unit, k_obj)
        assert coupled_object_stiffness(sample, k, unit, r) == pytest.approx(k_obj, rel=1e-8)


def test_bias_of_eq3_is_the_coupling_and_the_correction_removes_it():
    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    sample = coupled_sample(plan)
    b = unit_bias(sample, k, design_units(plan, k)[0], np.geomspace(1, 5, 3))
    assert min(b.bias_eq3_rel) > 0.02  # tips at 4 mm on one sample: eq. 3 reads high
    assert abs(b.worst_corrected_rel) < 1e-8


def test_tips_are_the_designs_own_faces_and_positions():
    plan = load_design(TI)
    numbers, punches = tip_punches(plan)
    assert numbers == tuple(s.number for s in plan.slots)
    for slot, p in zip(plan.slots, punches):
        assert (p.width_x_mm, p.depth_z_mm) == tuple(slot.geometry.contact_face_mm)
        assert p.x_mm == pytest.approx(slot.tip_centre_world_mm[0])


@pytest.mark.parametrize("design", [TI, "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"])
def test_each_tip_face_is_the_faces_footprint_on_the_sample_turned_with_its_element(design):
    """A comb's elements are quarter-turned (their sheets across the jaw): their faces were
    laid on the sample unturned, the tip's 1 mm width across the rows 0.9 mm apart, so the
    two rows' faces overlapped, the tips' compliance was no compliance and a written design's
    budget, check, verify and export failed "a travel whose contact set settles"."""
    plan = load_design(design)
    _, punches = tip_punches(plan)
    for slot, p in zip(plan.slots, punches):
        g, place = slot.geometry, slot.placement
        w, b = g.contact_face_mm
        corners = [place.apply(g.tip_centre_x_mm + sx * w / 2, g.tip_top_y_mm, sz * b)
                   for sx in (-1, 1) for sz in (0, 1)]
        xs, zs = [c[0] for c in corners], [c[2] for c in corners]
        assert p.width_x_mm == pytest.approx(max(xs) - min(xs))
        assert p.depth_z_mm == pytest.approx(max(zs) - min(zs))
        assert (p.x_mm, p.z_mm) == pytest.approx(((max(xs) + min(xs)) / 2, (max(zs) + min(zs)) / 2))
    coupled = coupled_sample(plan)
    assert np.all(np.linalg.eigvalsh(coupled.normalised) > 0)  # a compliance
    # the grasp's tips and the array evaluation's read the same faces
    from tactcad.in_use.grasp_experiment import _punches
    from tactcad.mechanics.evaluation import elements_from_plan

    assert _punches(plan) == list(punches)
    k = {s.number: 1.0 for s in plan.slots}
    assert [e.punch for e in elements_from_plan(plan, k)] == list(punches)


def test_overlapping_tip_faces_are_refused_naming_their_elements():
    punches = [Punch(-0.45, 0.0, 1.0, 0.5), Punch(0.45, 0.0, 1.0, 0.5), Punch(0.0, 3.0, 1.0, 0.5)]
    with pytest.raises(ContactError, match="elements 1 and 2") as info:
        coupled_sample_from_punches((1, 2, 3), punches)
    assert info.value.field == "tip faces"
    touching = [Punch(-0.5, 0.0, 1.0, 0.5), Punch(0.5, 0.0, 1.0, 0.5)]  # edge to edge: apart
    assert coupled_sample_from_punches((1, 2), touching).normalised.shape == (2, 2)


def test_the_contact_set_is_the_complementarity_solution_where_single_changes_would_cycle():
    """The one-change active set is backed by NNLS: on random compliant systems the forces
    meet the complementarity conditions that enumerating every contact set finds."""
    import itertools
    import types

    from tactcad.in_use import tissue_coupling

    rng = np.random.default_rng(3)
    for _ in range(20):
        n = 6
        m = rng.standard_normal((n, n))
        normalised = m @ m.T / n + np.eye(n) * 0.05
        k = rng.uniform(1.0, 30.0, n)
        heights = rng.uniform(-0.05, 0.05, n)
        system = np.diag(1.0 / k) + normalised
        load = 0.01 + heights
        best = None
        for mask in itertools.product((0, 1), repeat=n):
            active = np.array(mask, bool)
            f = tissue_coupling._forces_on(system, load, active)
            gap = system @ f - load
            if f.min() >= -1e-12 and gap[~active].min(initial=0.0) >= -1e-12:
                best = f
        assert best is not None
        sample = types.SimpleNamespace(normalised=normalised)
        assert tissue_coupling.contact_forces(sample, k, heights, 1.0, 0.01) == \
            pytest.approx(best, abs=1e-12)
        assert tissue_coupling._settled_by_nnls(system, load, 0.01) == pytest.approx(best, abs=1e-12)


def test_a_system_that_is_no_compliance_is_a_contact_error_not_a_crash():
    from tactcad.in_use import tissue_coupling

    system = np.array([[1.0, 2.0], [2.0, 1.0]])  # indefinite
    with pytest.raises(ContactError, match="not positive definite"):
        tissue_coupling._settled_by_nnls(system, np.array([0.01, 0.02]), 0.01)


def test_a_measured_ratio_outside_the_model_is_refused_by_name():
    sample = two_tips(4.0)
    with pytest.raises(ContactError, match="R = 50"):
        coupled_object_stiffness(sample, {1: 2.0, 2: 20.0}, (1, 2), 50.0)


@pytest.mark.parametrize("field, kwargs", [("poisson_ratio", {"poisson_ratio": 0.7}),
                                           ("thickness_mm", {"thickness_mm": -1.0}),
                                           ("tissue.convergence_rel", {"convergence_rel": 0.0})])
def test_bad_tissue_is_refused_by_name(field, kwargs):
    with pytest.raises(ContactError, match=field):
        Tissue(**kwargs)


def test_lumped_offers_the_coupled_inversion_beside_eq3(capsys):
    """`lumped --coupled-design` reads back the K_obj its coupled R came from; eq. 3 reads it high."""
    import json

    from tactcad.cli import main

    plan = load_design(TI)
    k = ladder_stiffness_by_element(plan)
    unit = design_units(plan, k)[0]
    r = coupled_ratio(coupled_sample(plan), k, unit, 2.0)
    argv = ["lumped", "--km", repr(k[unit[0]]), "--kr", repr(k[unit[1]]), "--r", repr(r),
            "--coupled-design", TI, "--unit", str(unit[0]), "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["coupled"]["k_obj_coupled_N_per_mm"] == pytest.approx(2.0, rel=1e-8)
    assert out["k_obj_N_per_mm"] > 2.0 * 1.02


def test_lumped_names_a_unit_that_is_not_measuring(capsys):
    from tactcad.cli import main

    assert main(["lumped", "--km", "1", "--kr", "10", "--r", "2", "--coupled-design", TI,
                 "--unit", "2"]) == 2
    assert "--unit = 2" in capsys.readouterr().err


def test_an_R_the_coupled_model_cannot_invert_is_unreadable_not_an_error(monkeypatch):
    """A coupled R outside the range the model spans over its bracket has no answer: the
    unit's corrected bias is None there (an unreadable K_obj), never a refused export."""
    import tactcad.in_use.tissue_coupling as tc
    from tactcad.mechanics.contact import ContactError, Punch

    punches = (Punch(0.0, 0.0, 2.0, 3.0), Punch(4.0, 0.0, 2.0, 3.0))
    sample = tc.coupled_sample_from_punches((1, 2), punches, tc.Tissue())

    def refuse(*args, **kwargs):
        raise ContactError("R", 0.99, "1.0 ... 1.02")

    monkeypatch.setattr(tc, "coupled_object_stiffness", refuse)
    bias = tc.unit_bias(sample, {1: 1.0, 2: 10.0}, (1, 2), [1.0, 5.0])
    record = bias.as_json()
    assert record["bias_corrected_rel"] == [None, None]
    assert record["worst_corrected_rel"] is None and bias.worst_corrected_rel == float("inf")


def test_the_face_alone_is_solved_once_a_process_without_a_store():
    # every layout of one face and tissue is normalised by the same face's solve: solved
    # once, each layout's compliance the same as with the face solved afresh
    from tactcad.in_use import tissue_coupling as tc
    from tactcad.mechanics.contact import converged_punches

    tissue = Tissue(poisson_ratio=0.5, thickness_mm=None)
    tc._face_alone.cache_clear()
    tc._normalised_compliance.cache_clear()
    for pitch in (0.7, 0.9):
        punches = [Punch(0.0, 0.0, 0.1, 0.1), Punch(pitch, 0.0, 0.1, 0.1)]
        sample = tc.coupled_sample_from_punches([1, 2], punches, tissue)
        unit = Sample(1.0, tissue.poisson_ratio, tissue.thickness_mm)
        alone = converged_punches([Punch(0.0, 0.0, 0.1, 0.1)], unit, tissue.convergence_rel)
        tips = converged_punches(punches, unit, tissue.convergence_rel)
        assert np.array_equal(sample.normalised,
                              tips.compliance_mm_per_N / float(alone.compliance_mm_per_N[0, 0]))
    info = tc._face_alone.cache_info()
    assert (info.misses, info.hits) == (1, 1)
