"""The modal ladder: closed form, fem2d and fem3d natural frequencies.

The FEM eigen-solver is checked against Euler-Bernoulli's clamped-free beam
on a plain bar; the closed form against fem3d at the corners of the design
domain (thin and thick web, short and long arm, thin and thick sheet); fem3d
against an independent CalculiX ``*FREQUENCY`` model of an exported element
in tests/mechanics/test_modal_calculix.py.
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tactcad.errors import DesignError
from tactcad.mechanics.modal_closed_form import SHAPE_ERROR_REL, chord_moments
from tactcad.mechanics.modal_ladder import (MODAL_LEVELS, UnknownModalModelError, estimate_modes,
                                            modal_level_for, modal_models)


def _elem(plan, arm_mm):
    return next(g for g in plan.distinct_elements.values() if g.arm_length_mm == arm_mm)


def test_levels_are_declared_once_cheapest_first():
    assert modal_models() == ("closed-form", "fem2d", "fem3d")
    assert MODAL_LEVELS["fem3d"].families == ("in-plane", "out-of-plane")
    # a stiffness level without a modal level of its own gets the nearest cheaper one
    assert modal_level_for("beam") == "closed-form"
    assert modal_level_for("fem3d") == "fem3d"


def test_fem_eigensolver_matches_the_clamped_free_beam():
    """A 20 x 1 mm bar, plane stress, clamped at x = 0: Euler-Bernoulli gives
    f1 = (1.8751^2 / 2 pi L^2) sqrt(E I / rho A); shear and rotary inertia
    lower it by about (h/L)^2, under 0.3 % here."""
    import skfem

    from tactcad.design.array_plan import Material
    from tactcad.mechanics.fem.fem_modal import solve_modes

    L, h, b = 20.0, 1.0, 2.0
    mat = Material("steel", 200000.0, 0.3, density_g_per_cm3=7.8)
    mesh = skfem.MeshTri.init_tensor(np.linspace(0, L, 81), np.linspace(0, h, 5))
    sol = solve_modes(mesh, mat, thickness=b, x_clamp=0.0, modes=2, plane="stress")
    rho = 7.8e-9
    beam = 1.875104**2 / (2 * math.pi * L**2) * math.sqrt(200000.0 * h**2 / 12 / rho)
    assert sol.frequencies_Hz[0] == pytest.approx(beam, rel=3e-3)
    assert sol.frequencies_Hz[0] < beam  # Timoshenko effects only soften
    # second bending mode: 4.69409^2 / 1.875104^2 = 6.267 times the first, less shear
    assert 5.9 < sol.frequencies_Hz[1] / sol.frequencies_Hz[0] < 6.27


def test_lobpcg_finds_the_modes_shift_invert_finds_on_a_3d_bar():
    """The 3D meshes' eigensolver (LOBPCG with the p-multigrid preconditioner)
    against shift-invert with SuperLU on a clamped 3D bar: the same three
    lowest frequencies in both mid-plane families, within the solver's tolerance."""
    import skfem

    from tactcad.design.array_plan import Material
    from tactcad.mechanics.fem.fem_modal import FAMILIES, EIGEN_RTOL, solve_modes

    mat = Material("steel", 200000.0, 0.3, density_g_per_cm3=7.8)
    mesh = skfem.MeshTet.init_tensor(np.linspace(0, 12, 25), np.linspace(0, 1.5, 4),
                                     np.linspace(0, 0.5, 3))
    found = {solver: solve_modes(mesh, mat, thickness=1.0, x_clamp=0.0, modes=3, plane=None,
                                 sym_plane_z=0.5, families=tuple(FAMILIES), solver=solver)
             for solver in ("direct", "lobpcg")}
    direct, lobpcg = found["direct"], found["lobpcg"]
    assert lobpcg.families == direct.families
    assert set(direct.families) == set(FAMILIES)  # the bar bends both ways among its lowest three
    assert lobpcg.frequencies_Hz == pytest.approx(direct.frequencies_Hz, rel=10 * EIGEN_RTOL)


def test_an_unknown_eigensolver_is_refused():
    import skfem

    from tactcad.design.array_plan import Material
    from tactcad.mechanics.fem.fem_modal import solve_modes

    mesh = skfem.MeshTri.init_tensor(np.linspace(0, 4, 5), np.linspace(0, 1, 3))
    with pytest.raises(ValueError, match="solver = 'arpack': allowed direct, lobpcg"):
        solve_modes(mesh, Material("steel", 2e5, 0.3, density_g_per_cm3=7.8), thickness=1.0,
                    x_clamp=0.0, modes=1, plane="stress", solver="arpack")


def test_chord_moments_of_a_rectangle_are_exact():
    pts = np.array([[0, 0], [4, 0], [4, 2], [0, 2]], float)
    length, second = chord_moments(pts, np.array([0.5, 3.5, 5.0]), 1.0)
    assert length.tolist() == [2.0, 2.0, 0.0]
    assert second[:2] == pytest.approx([2 / 3, 2 / 3])  # integral of y^2 over [-1, 1]


def test_closed_form_and_fem2d_agree_on_the_default_short_arm(plan):
    g = _elem(plan, 4.0)
    cf = estimate_modes("closed-form", g, plan.material)
    f2 = estimate_modes("fem2d", g, plan.material, modes=2)
    # the closed form gives the first in-plane and the first out-of-plane mode
    assert [m.family for m in cf.modes] == ["in-plane", "out-of-plane"]
    assert [m.family for m in f2.modes] == ["in-plane", "in-plane"]
    # plane stress is softer than the 3D element the closed form is fitted to
    assert f2.first_Hz < cf.first_Hz
    assert abs(f2.first_Hz / cf.first_Hz - 1) <= f2.error_estimate_rel + cf.error_estimate_rel
    assert cf.error_estimate_rel >= SHAPE_ERROR_REL


def test_a_longer_arm_rings_lower(plan):
    f = [estimate_modes("closed-form", _elem(plan, a), plan.material).first_Hz
         for a in (4.0, 6.0, 8.0)]
    assert f[0] > f[1] > f[2] > 0


def test_mode_shapes_are_written_to_vtu(plan, tmp_path):
    import meshio

    from tactcad.mechanics.fem.fem_modal import write_modes_vtu

    r = estimate_modes("fem2d", _elem(plan, 8.0), plan.material, modes=2, keep_shapes=True)
    path = write_modes_vtu(tmp_path / "m.vtu", r.solve)
    m = meshio.read(path)
    names = sorted(m.point_data)
    assert len(names) == 2 and names[0].startswith("mode_1_")
    shape = m.point_data[names[0]]
    assert shape.shape == (len(m.points), 3) and np.abs(shape[:, 1]).max() > 0


def test_bad_input_is_refused(plan):
    g = _elem(plan, 4.0)
    with pytest.raises(UnknownModalModelError, match="allowed closed-form, fem2d, fem3d"):
        estimate_modes("beam", g, plan.material)
    with pytest.raises(DesignError, match="material.density_g_per_cm3"):
        estimate_modes("closed-form", g, replace(plan.material, density_g_per_cm3=None))
    with pytest.raises(ValueError, match="modes = 0"):
        estimate_modes("fem2d", g, plan.material, modes=0)


#: fem3d's first frequencies at the corners of the correction grid's domain,
#: as `tactcad bench modal --designs corners` measured them (10-60 s each).
STORED = json.loads((Path(__file__).resolve().parents[1] / "data" / "modal_fem3d_corners.json")
                    .read_text(encoding="utf-8"))["corners"]


def _corner(c):
    from tactcad.studies.correction_sweep import grid_geometry

    g, mat = grid_geometry(c["web_mm"], c["arm_mm"], c["notch_radius_mm"], sheet_mm=c["sheet_mm"],
                           poisson_ratio=0.27)
    return g, replace(mat, density_g_per_cm3=7.8)


def _closed_form(g, mat):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # outside the correction's fitted range: its error grows
        return estimate_modes("closed-form", g, mat)


@pytest.mark.parametrize("corner", STORED, ids=lambda c: f"t{c['web_mm']:g}_a{c['arm_mm']:g}_b{c['sheet_mm']:g}")
def test_closed_form_lies_within_its_error_of_fem3d_at_the_corners(corner):
    """The closed form's first in-plane frequency within its stated error of
    fem3d's (stored, measured -1.5 % to -0.2 %); fem3d's own Richardson
    estimate under 0.5 %. The slow test below computes one corner again."""
    cf = _closed_form(*_corner(corner))
    assert abs(cf.first_of("in-plane") / corner["first_in_plane_Hz"] - 1.0) \
        <= cf.error_estimate_rel
    assert corner["error_estimate_rel"] < 0.005


@pytest.mark.slow
def test_fem3d_computes_its_stored_corner_again():
    """The stored fem3d figures are today's: the quickest corner (thin sheet,
    thick web, about 10 s) solved again gives its stored first in-plane
    frequency within fem3d's error, and there fem3d finds an out-of-plane mode
    first, which the in-plane closed form cannot see."""
    corner = min(STORED, key=lambda c: c["seconds"])
    g, mat = _corner(corner)
    f3 = estimate_modes("fem3d", g, mat, modes=3)
    in_plane = next(m.frequency_Hz for m in f3.modes if m.family == "in-plane")
    assert in_plane == pytest.approx(corner["first_in_plane_Hz"], rel=max(
        f3.error_estimate_rel, 1e-6))
    assert f3.modes[0].family == corner["first_family"] == "out-of-plane"
    assert abs(_closed_form(g, mat).first_Hz / in_plane - 1.0) <= _closed_form(
        g, mat).error_estimate_rel


def test_each_closed_form_mode_carries_its_own_error_estimate():
    """The closed form's two families are estimated each its own way: the out-of-plane
    mode's error is its bounds' spread (far above the in-plane Rayleigh quotient's), said
    for that mode, not the first's error for both."""
    from tactcad.design.array_plan import EXAMPLES, plan_from_dict
    from tactcad.mechanics.closed_form import estimate_closed_form
    from tactcad.mechanics.modal_closed_form import (estimate_modal_closed_form,
                                                     out_of_plane_frequency)
    from tactcad.vocabulary.schema import read_toml

    plan = plan_from_dict(read_toml(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml", "d"))
    g, material = plan.slots[1].geometry, plan.material
    r = estimate_modal_closed_form(g, material, modes=2)
    half_k = 0.5 * estimate_closed_form(g, material).error_estimate_rel
    errors = {m.family: m.error_estimate_rel for m in r.modes}
    assert errors["in-plane"] == pytest.approx(half_k + SHAPE_ERROR_REL)
    assert errors["out-of-plane"] == pytest.approx(half_k + out_of_plane_frequency(g, material)[1])
    assert errors["out-of-plane"] > 3 * errors["in-plane"]
    assert r.error_estimate_rel == r.modes[0].error_estimate_rel
    assert [m["frequency_Hz_error_rel"] for m in r.as_json()["modes"]] == \
        [m.error_estimate_rel for m in r.modes]
