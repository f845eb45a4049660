"""The die's beams in motion: Rayleigh's first resonance against the exact frequency
equation of a cantilever with a tip mass, and the closed form's K and f1 against an
anisotropic CalculiX model of each beam (another kind of model: 3D elasticity with
silicon's full stiffness tensor, shear and the width's plate effect)."""

from __future__ import annotations

import dataclasses
import math
import shutil

import pytest

from tactcad.design.mems_die import die_plan
from tactcad.mechanics import die_dynamics as dd
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.studies.inverse_design import Targets


@pytest.fixture(scope="module")
def plan():
    return die_plan(Targets(10.0, (0.5, 5.0), 0.02), jaw_room("5"))


def test_rayleigh_is_within_one_percent_of_the_exact_root_and_above_it(plan):
    for role, m in dd.die_modes(plan).items():
        assert 0.0 < m.rayleigh_error_rel < 0.01, (role, m)  # an upper bound, as it must be


def test_without_a_post_the_exact_root_is_the_bare_cantilevers(plan):
    """Blevins: f = 1.8751^2 / (2 pi) sqrt(EI / (rho A L^4)) with no tip mass."""
    bare = dataclasses.replace(plan, post_height_um=0.0, post_um=1e-9)
    beam = bare.beams[0]
    m, tip = dd._masses_kg(bare, beam)
    assert tip < 1e-9 * m
    length = beam.length_um * 1e-6
    ei = bare.k_r_N_per_mm * 1e3 * length ** 3 / 3
    blevins = 1.8751041 ** 2 / (2 * math.pi) * math.sqrt(ei / (m / length * length ** 4))
    assert dd.exact_first_resonance_Hz(bare, beam) == pytest.approx(blevins, rel=1e-6)


@pytest.mark.slow  # CalculiX, six solves
@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (calculix-ccx) not installed")
def test_the_closed_form_against_anisotropic_calculix(plan):
    """K = E<110> w t^3 / (4 L^3) within 0.5 % of the 3D anisotropic model for both rows
    (the mesh converged: a coarser and the default mesh agree to 0.5 %); the lumped-post
    Rayleigh f1 within 4 % (it leaves out the post's rotary inertia: +3 % on the stiff
    reference beam)."""
    for beam in plan.beams[:: plan.columns]:
        check = dd.calculix_beam_check(plan, beam)
        coarse = dd.calculix_beam_check(plan, beam, (24, 3, 2))
        assert coarse.k_fe_N_per_mm == pytest.approx(check.k_fe_N_per_mm, rel=5e-3)
        assert abs(check.k_error_rel) < 5e-3, check
        assert 0.0 < check.f1_error_rel < 0.04, check
