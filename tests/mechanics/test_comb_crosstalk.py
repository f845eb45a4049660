"""Crosstalk of the monolithic comb: the spine beam and the row sheet's plane FE.

Reciprocity, a stiffer spine couples less, the FE's diagonal is the gauge's own reading,
the beam errs high within its stated error, a level of the other construction is refused
before anything is solved.
"""

from dataclasses import replace

import numpy as np
import pytest

import tactcad
from tactcad.errors import DesignError
from tactcad.mechanics.comb_crosstalk import (CHANGE_RANGES, comb_inputs, estimate_comb_beam,
                                              grid_share, spine_layout)
from tactcad.mechanics.crosstalk_ladder import (CROSSTALK_LEVELS, CrosstalkInputError,
                                                construction_levels, crosstalk_reason,
                                                default_level, level_for, plan_crosstalk,
                                                verify_level)

COMB = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def comb():
    return tactcad.load(COMB).plan


@pytest.fixture(scope="module")
def inputs(comb):
    return comb_inputs(comb)


@pytest.fixture(scope="module")
def fem(inputs):
    """The shipped comb's rows as plane-stress solids (two meshes; about 5 s)."""
    from tactcad.mechanics.comb_fem2d import estimate_comb_fem2d

    return estimate_comb_fem2d(inputs)


def test_the_comb_has_its_own_levels_the_cheapest_first():
    assert construction_levels("monolithic-comb") == ("comb-beam", "comb-fem2d")
    assert default_level("monolithic-comb") == "comb-beam"
    assert default_level("stacked") == "stack-beam"
    assert CROSSTALK_LEVELS["comb-fem2d"].meshed and not CROSSTALK_LEVELS["comb-beam"].meshed


def test_each_construction_is_answered_for_at_the_level_the_ladder_gives_it(comb):
    # the export's files, the budget and the verification record read this one level
    assert verify_level("stacked") == "stack-timoshenko"  # marked: not the stack's cheapest
    assert verify_level("monolithic-comb") == "comb-beam"  # none marked: its cheapest
    assert verify_level("no-such-construction") is None
    assert crosstalk_reason(comb) == ""
    from types import SimpleNamespace

    why = crosstalk_reason(SimpleNamespace(construction="no-such-construction"))
    assert "no-such-construction" in why and "monolithic-comb" in why


def test_the_beam_answers_in_the_stack_results_shape(comb, inputs):
    r = plan_crosstalk(comb)  # left out: the comb's cheapest level
    assert r.model == "comb-beam" and r.elements == tuple(range(1, 13))
    assert r.sensitivity.shape == r.compliance.shape == r.decoupling.shape == (12, 12)
    stack = plan_crosstalk(tactcad.load(None, {"array.columns": 2,
                                               "arms.lengths_mm": [4, 6, 5, 7]}).plan)
    assert set(r.as_json()) == set(stack.as_json())
    assert 0 < r.crosstalk_rel < 1e-3 and r.error_estimate_rel > 0 and r.seconds > 0
    # the diagonal is each gauge's own grid strain at the closed form, as the stack's
    assert np.allclose(np.diag(r.sensitivity), inputs.own_strain_per_N)


def test_the_beams_tip_matrix_is_reciprocal_and_the_rows_do_not_couple(inputs):
    r = estimate_comb_beam(inputs)
    C = r.compliance
    assert np.max(np.abs(C - np.diag(np.diag(C)))) > 0  # neighbours do move
    assert r.asymmetry_rel < 1e-12
    rows = np.array(inputs.rows)
    across = rows[:, None] != rows[None, :]
    assert np.all(r.sensitivity[across] == 0) and np.all(C[across] == 0)
    normalised = r.sensitivity / np.diag(r.sensitivity)[:, None]
    assert np.allclose(r.decoupling @ normalised, np.eye(12), atol=1e-12)


def test_a_stiffer_spine_couples_less_and_a_rigid_one_not_at_all(inputs):
    rels = [estimate_comb_beam(replace(inputs, spine_modulus_factor=f)).crosstalk_rel
            for f in (0.1, 1.0, 10.0, 1e6)]
    assert rels[0] > rels[1] > rels[2] > rels[3] > 0
    assert rels[3] < 1e-5 * rels[1]  # the spine carries all the coupling


def test_the_grids_share_dies_out_faster_on_a_longer_post_and_at_papkovichs_rate(inputs):
    from tactcad.mechanics.comb_crosstalk import PAPKOVICH_DECAY, SAINT_VENANT_DECAY

    lay = spine_layout(inputs, 0)
    taller = replace(lay, post_height_mm=tuple(h * 2 for h in lay.post_height_mm))
    for rate in (PAPKOVICH_DECAY, SAINT_VENANT_DECAY):
        assert 0 < grid_share(taller, 0, rate) < grid_share(lay, 0, rate) < 1
    assert grid_share(lay, 0, PAPKOVICH_DECAY) < grid_share(lay, 0, SAINT_VENANT_DECAY)


def test_a_change_the_comb_has_not_is_refused(comb):
    with pytest.raises(CrosstalkInputError, match="spine_modulus_factor"):
        comb_inputs(comb, plate_thickness_mm=4.0)
    lo, hi = CHANGE_RANGES["spine_modulus_factor"]
    with pytest.raises(CrosstalkInputError, match=r"\[0.01, 1e\+06\]"):
        comb_inputs(comb, spine_modulus_factor=hi * 10)
    assert comb_inputs(comb, spine_modulus_factor=2.0).spine_modulus_factor == 2.0


def _no_solve(monkeypatch):
    """Every level's estimator and input reader raise: a refusal must come first."""
    from tactcad.mechanics import crosstalk_ladder

    def solved(*args, **kwargs):
        raise AssertionError("a level was read or solved")

    monkeypatch.setattr(crosstalk_ladder.CrosstalkLevel, "read_inputs", solved)
    monkeypatch.setattr(crosstalk_ladder.CROSSTALK_LADDER, "run", solved)


@pytest.mark.parametrize("level", ["stack-beam", "stack-timoshenko", "stack-fem3d"])
def test_a_stack_level_on_a_comb_is_refused_before_any_solve_naming_the_combs(
        comb, level, monkeypatch):
    _no_solve(monkeypatch)
    with pytest.raises(DesignError) as caught:
        plan_crosstalk(comb, level)
    e = caught.value
    assert (e.field, e.value) == ("--model", level)
    assert "comb-beam" in e.allowed and "comb-fem2d" in e.allowed
    assert [a["option"] for a in e.alternatives] == ["--model comb-beam", "--model comb-fem2d"]
    assert "clamped stack" in e.why and "spine" in e.why


@pytest.mark.parametrize("level", ["comb-beam", "comb-fem2d"])
def test_a_comb_level_on_a_stacked_array_is_refused_naming_the_stacks(level, monkeypatch):
    stacked = tactcad.load(None, {"array.columns": 2, "arms.lengths_mm": [4, 6, 5, 7]}).plan
    _no_solve(monkeypatch)
    with pytest.raises(DesignError) as caught:
        level_for(stacked, level)
    e = caught.value
    assert e.field == "--model" and "stack-beam" in e.allowed
    assert [a["option"] for a in e.alternatives][0] == "--model stack-beam"


@pytest.mark.xdist_group("comb-crosstalk-fe")  # fem: made once, on one worker
def test_the_fe_answers_in_seconds_and_its_tip_matrix_is_reciprocal(fem, inputs):
    assert fem.model == "comb-fem2d" and fem.seconds < 60
    C = fem.compliance
    assert fem.asymmetry_rel < 1e-12  # f_i^T K^-1 f_j: Maxwell-Betti to the solver's precision
    rows = np.array(inputs.rows)
    across = rows[:, None] != rows[None, :]
    assert np.all(fem.sensitivity[across] == 0) and np.all(C[across] == 0)
    within = ~across & ~np.eye(12, dtype=bool)
    assert np.all(np.abs(C[within]) > 0)  # every neighbour in a row moves
    assert 0 < fem.crosstalk_rel < 1e-5 and 0 < fem.error_estimate_rel < 0.1


@pytest.mark.xdist_group("comb-crosstalk-fe")  # fem: made once, on one worker
def test_the_fes_diagonal_is_the_gauges_own_reading(fem, inputs):
    """The FE's own grid strain (the layer meshed, the width factor) and tip compliance
    against the closed form's: the same element, its post and spine added and plane
    stress (softer than 3D by up to about 11 %)."""
    own = np.diag(fem.sensitivity)
    assert np.all(own < 0)  # an upward tip force compresses the top face over the web
    assert np.allclose(own, inputs.own_strain_per_N, rtol=0.05)
    K = 1 / np.diag(fem.compliance)
    assert np.all(K < np.array(inputs.stiffness_N_per_mm)) and \
        np.allclose(K, inputs.stiffness_N_per_mm, rtol=0.15)


@pytest.mark.xdist_group("comb-crosstalk-fe")  # fem: made once, on one worker
def test_the_beam_errs_high_within_its_stated_error(fem, inputs):
    beam = estimate_comb_beam(inputs)
    assert beam.crosstalk_rel > fem.crosstalk_rel
    distance = abs(beam.crosstalk_rel - fem.crosstalk_rel) / beam.crosstalk_rel
    assert distance <= beam.error_estimate_rel


def test_the_fes_error_is_its_two_meshes_richardson(inputs):
    from tactcad.mechanics.comb_fem2d import ASSUMED_ORDER, estimate_comb_fem2d

    coarse = estimate_comb_fem2d(inputs, (4.0, 2.0))
    with pytest.raises(ValueError, match="coarse then fine"):
        estimate_comb_fem2d(inputs, (1.0, 2.0))
    assert coarse.error_estimate_rel > 0
    ratio = 2.0 ** ASSUMED_ORDER - 1.0
    # the (4, 2) pair's fine mesh is the default pair's coarse one: their errors chain
    assert coarse.error_estimate_rel * ratio * coarse.crosstalk_rel == pytest.approx(
        abs(coarse.crosstalk_rel - _coarsest(inputs)), rel=1e-9)


def _coarsest(inputs):
    from tactcad.mechanics.comb_fem2d import _matrices
    from tactcad.mechanics.crosstalk_ladder import crosstalk_of

    return crosstalk_of(_matrices(inputs, 4.0)[0])[0]


@pytest.mark.xdist_group("comb-crosstalk-fe")  # fem: made once, on one worker
@pytest.mark.slow  # the plane FE twice more (about 10-20 s)
def test_the_fe_couples_less_through_a_stiffer_or_taller_spine(comb, fem):
    from tactcad.mechanics.comb_fem2d import estimate_comb_fem2d

    stiff = estimate_comb_fem2d(comb_inputs(comb, spine_modulus_factor=1e3))
    assert stiff.crosstalk_rel < 1e-2 * fem.crosstalk_rel
    from tactcad.design.array_plan import plan_from_dict

    # an M1.6 screw's head and nut ask a taller spine (4.1 mm against 3.9); the comb alone,
    # without the 10 mm jaw it no longer fits (refused when the design file is read)
    raw = {key: table for key, table in comb.raw.items() if key != "grasper_jaw"}
    taller = plan_from_dict({**raw, "comb": {**raw["comb"], "screw_size": "M1.6"}})
    with pytest.raises(DesignError, match="grasper_jaw"):
        tactcad.load(COMB, {"comb.screw_size": "M1.6"})
    assert taller.comb.sheets[0].spine_height_mm > comb.comb.sheets[0].spine_height_mm
    tall = estimate_comb_fem2d(comb_inputs(taller))
    assert tall.crosstalk_rel < fem.crosstalk_rel
    assert estimate_comb_beam(comb_inputs(taller)).crosstalk_rel < \
        estimate_comb_beam(comb_inputs(comb)).crosstalk_rel


def test_a_comb_stating_its_crosstalk_is_verified_at_its_cheapest_level(comb):
    from tactcad.mechanics.stack_crosstalk import crosstalk_records

    assert crosstalk_records(comb) == []
    raw = {**comb.raw, "requirements": {**comb.raw["requirements"], "max_crosstalk_rel": 1e-4}}
    (rec,) = crosstalk_records(replace(comb, raw=raw))
    assert rec["model"] == "comb-beam" and rec["pass"] and 0 < rec["predicted"] < 1e-4
