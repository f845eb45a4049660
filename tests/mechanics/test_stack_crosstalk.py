"""Crosstalk of the clamped stack: reciprocity, plate thickness, decoupling, refusals."""

import numpy as np
import pytest

import tactcad
from tactcad.mechanics.stack_crosstalk import (CrosstalkInputError, UnknownCrosstalkModelError,
                                         construction_levels, estimate_crosstalk, plan_crosstalk,
                                         stack_inputs, with_changes)

TI = "src/tactcad/examples/ti_array_2x3/ti_array_2x3.toml"
BEAM_LEVELS = [m for m in construction_levels("stacked") if m != "stack-fem3d"]
#: the 3D level's coarsest mesh: 2 x 2 hexahedra across, one per layer (h/2 on the fine level)
FEM_COARSEST = (2, 2, 1)


@pytest.fixture(scope="module")
def small():
    """A 2 x 3 array of the paper's design (three elements per row)."""
    return tactcad.load(None, {"array.columns": 3, "arms.lengths_mm": [4, 6, 8, 5, 7, 4]}).plan


@pytest.fixture(scope="module")
def small_inputs(small):
    return stack_inputs(small)


@pytest.mark.parametrize("model", BEAM_LEVELS)
def test_tip_displacement_matrix_is_reciprocal(small_inputs, model):
    r = estimate_crosstalk(small_inputs, model)
    C = r.compliance
    off = C - np.diag(np.diag(C))
    assert np.max(np.abs(off)) > 0  # neighbours do move
    assert np.allclose(C, C.T, rtol=0, atol=1e-12 * np.max(np.abs(C)))
    assert r.asymmetry_rel < 1e-12


@pytest.mark.parametrize("model", BEAM_LEVELS)
def test_crosstalk_falls_as_the_clamp_plates_thicken(small_inputs, model):
    rels = [estimate_crosstalk(with_changes(small_inputs, plate_thickness_mm=t), model)
            .crosstalk_rel for t in (2.0, 4.0, 8.0)]
    assert rels[0] > rels[1] > rels[2] > 0


@pytest.mark.slow  # fem3d
def test_fem3d_tip_matrix_is_reciprocal_and_near_the_beam(small_inputs):
    from tactcad.mechanics.stack_fem3d import estimate_stack_fem3d

    r = estimate_stack_fem3d(small_inputs, FEM_COARSEST)
    C = r.compliance
    assert np.max(np.abs(C - np.diag(np.diag(C)))) > 0
    assert np.allclose(C, C.T, rtol=0, atol=1e-12 * np.max(np.abs(C)))
    beam = estimate_crosstalk(small_inputs, "stack-timoshenko").crosstalk_rel
    # the same stack in 3D: within the same order of magnitude as the beam
    assert 0.1 * beam < r.crosstalk_rel < 10 * beam and r.error_estimate_rel > 0


@pytest.mark.slow
def test_fem3d_crosstalk_falls_as_the_clamp_plates_thicken(small_inputs):
    from tactcad.mechanics.stack_fem3d import estimate_stack_fem3d

    rels = [estimate_stack_fem3d(with_changes(small_inputs, plate_thickness_mm=t), FEM_COARSEST)
            .crosstalk_rel for t in (2.0, 4.0, 8.0)]
    assert rels[0] > rels[1] > rels[2] > 0


def test_neighbours_couple_within_a_row_only(small_inputs):
    r = estimate_crosstalk(small_inputs)
    rows = np.array(small_inputs.rows)
    across = rows[:, None] != rows[None, :]
    assert np.all(r.sensitivity[across] == 0)
    assert np.all(r.sensitivity[~across] != 0)


def test_decoupling_matrix_inverts_the_normalised_sensitivity(small_inputs):
    r = estimate_crosstalk(small_inputs)
    normalised = r.sensitivity / np.diag(r.sensitivity)[:, None]
    assert np.allclose(r.decoupling @ normalised, np.eye(len(r.elements)), atol=1e-12)


def test_softer_spacers_let_the_neighbours_move_more(small_inputs):
    stiff = estimate_crosstalk(small_inputs)
    soft = estimate_crosstalk(with_changes(small_inputs, spacer_E_MPa=2e3))
    off = ~np.eye(len(stiff.elements), dtype=bool)
    # the soft layers next to the loaded base take the bending: the nearest neighbour moves more
    assert np.max(soft.compliance[off]) > np.max(stiff.compliance[off])
    assert soft.crosstalk_rel != pytest.approx(stiff.crosstalk_rel, rel=1e-3)


def test_ti_example_gets_a_number():
    r = plan_crosstalk(tactcad.load(TI).plan)
    assert 0 < r.crosstalk_rel < 1 and len(r.elements) == 6


def test_bad_input_is_refused(small, small_inputs):
    with pytest.raises(UnknownCrosstalkModelError, match="stack-beam"):
        plan_crosstalk(small, "fem9d")
    with pytest.raises(CrosstalkInputError, match=r"plate_thickness_mm = -1.*\[0.5, 20\]"):
        with_changes(small_inputs, plate_thickness_mm=-1)
    with pytest.raises(CrosstalkInputError, match="bolt_length_mm"):
        with_changes(small_inputs, bolt_length_mm=3.0)


def test_stated_requirement_gets_a_record(small):
    from dataclasses import replace

    from tactcad.mechanics.stack_crosstalk import crosstalk_records

    assert crosstalk_records(small) == []
    raw = {**small.raw, "requirements": {"max_crosstalk_rel": 1e-9}}
    (rec,) = crosstalk_records(replace(small, raw=raw))
    assert rec["requirement"] == "max_crosstalk_rel" and not rec["pass"]
    assert rec["predicted"] > 1e-9 and rec["margin_rel"] < 0


def test_each_level_estimates_its_error_against_the_next_level_up(small_inputs):
    """stack-beam's error is its distance to stack-timoshenko plus that level's own
    estimate (as the stiffness ladder's): not the shear term alone, which is tiny."""
    beam = estimate_crosstalk(small_inputs, "stack-beam")
    timo = estimate_crosstalk(small_inputs, "stack-timoshenko")
    distance = abs(beam.crosstalk_rel - timo.crosstalk_rel) / beam.crosstalk_rel
    assert beam.error_estimate_rel == pytest.approx(distance + timo.error_estimate_rel)
    assert beam.error_estimate_rel >= timo.error_estimate_rel > 100 * distance


def test_crosstalk_in_force_against_the_force_resolution(small_inputs):
    """A neighbour at full scale reads |S_ij / S_ii| F_fs on gauge i; set against that
    element's force-resolution step, the worst pair is the largest such ratio."""
    from tactcad.mechanics.stack_crosstalk import crosstalk_in_force

    r = estimate_crosstalk(small_inputs, "stack-beam")
    n = len(r.elements)
    steps = {e: 1e-5 * (1 + k) for k, e in enumerate(r.elements)}  # unequal steps
    q = crosstalk_in_force(r, 0.5, steps)
    i, j = r.elements.index(q["gauge"]), r.elements.index(q["loaded_element"])
    ratio = abs(r.sensitivity[i, j] / r.sensitivity[i, i])
    assert q["force_per_N_of_neighbour_load"] == pytest.approx(ratio)
    assert q["crosstalk_force_N"] == pytest.approx(ratio * 0.5)
    assert q["force_resolution_steps"] == pytest.approx(ratio * 0.5 / steps[q["gauge"]])
    every = [abs(r.sensitivity[a, b] / r.sensitivity[a, a]) * 0.5 / steps[r.elements[a]]
             for a in range(n) for b in range(n) if a != b]
    assert q["force_resolution_steps"] == pytest.approx(max(every))


def test_verify_record_states_the_crosstalk_in_force(small):
    from dataclasses import replace

    from tactcad.mechanics.stack_crosstalk import crosstalk_records

    raw = {**small.raw, "requirements": {"max_crosstalk_rel": 1e-3}}
    steps = {s.number: 1e-5 for s in small.slots}
    (rec,) = crosstalk_records(replace(small, raw=raw), 0.2, steps)
    q = rec["in_force"]
    assert q["crosstalk_force_N"] == pytest.approx(q["force_per_N_of_neighbour_load"] * 0.2)
    assert q["force_resolution_N"] == 1e-5
