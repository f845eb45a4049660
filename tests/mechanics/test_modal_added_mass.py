"""Modal honest: added mass (gauge, adhesive, leads, pads) by Rayleigh's quotient, and the
first out-of-plane mode beside the in-plane one, found and classified at the closed-form
and fem levels on a bar whose frequencies are known."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tactcad.design.array_plan import Material, load_design
from tactcad.mechanics.modal_closed_form import (bending_rayleigh, effective_mass_t,
                                                 estimate_modal_closed_form, in_plane_shape_sq)
from tactcad.mechanics.modal_result import PointMass

#: first bending eigenvalue of a clamped-free Euler-Bernoulli beam, (beta L)^2
BETA1_SQ = 1.875104 ** 2
STEEL = Material("steel", 200000.0, 0.3, density_g_per_cm3=7.8)


def _bar_frequency(depth, width, length, E=200000.0, rho=7.8e-9):
    """Euler-Bernoulli first bending frequency of a clamped-free bar (Hz)."""
    return BETA1_SQ / (2 * math.pi) * math.sqrt(E * width * depth ** 3 / 12
                                                 / (rho * width * depth * length ** 4))


def test_added_mass_at_the_tip_lowers_f1_as_rayleigh_says():
    """A tip mass m adds m to m_eff (|u| = 1 at the contact centre):
    f = f_bare sqrt(m_eff / (m_eff + m)); behind the hinge a mass changes nothing."""
    plan = load_design("hardware/ti_array_2x3/ti_array_2x3.toml")
    g = plan.distinct_elements["element_a19p605mm"]
    bare = estimate_modal_closed_form(g, plan.material, modes=2)
    from tactcad.mechanics.closed_form import _geometry_kwargs, closed_form_compliance

    parts = closed_form_compliance(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
                                   **_geometry_kwargs(g, plan.material))
    beta = float((parts.arm_bending + parts.arm_shear) / parts.total)
    m_eff = effective_mass_t(g, plan.material, beta)
    # at the contact centre the shape is 1 across the arm and the hinge's small swing along it
    at_tip = in_plane_shape_sq(g, beta, *g.contact_centre_mm)
    assert at_tip == pytest.approx(1.0, rel=0.01)
    for mg in (5.0, 20.0):
        tip = PointMass("tip", mg * 1e-3, *g.contact_centre_mm)
        r = estimate_modal_closed_form(g, plan.material, modes=2, added_masses=(tip,))
        want = bare.first_of("in-plane") * math.sqrt(m_eff / (m_eff + at_tip * tip.mass_t))
        assert r.first_of("in-plane") == pytest.approx(want, rel=1e-9)
        assert r.bare_first_Hz == pytest.approx(bare.first_Hz)
        assert r.first_of("out-of-plane") < bare.first_of("out-of-plane")
    still = PointMass("on the base", 0.05, g.web_centre_mm[0] - 2.0, 1.0)
    r = estimate_modal_closed_form(g, plan.material, modes=2, added_masses=(still,))
    assert r.first_of("in-plane") == pytest.approx(bare.first_of("in-plane"))


def test_rayleigh_of_a_uniform_bar_in_both_directions():
    """The closed form's bending quotient on a uniform bar: 1.5 % above the exact
    first frequency (sqrt(140/11) over 1.875^2) in either direction; the out-of-plane
    direction is the one whose depth is the smaller."""
    length, depth_y, depth_z = 40.0, 1.0, 0.6
    n = 4000
    dx = length / n
    xs = dx * (np.arange(n) + 0.5)
    E, G, rho = 200000.0, 200000.0 / 2.6, 7.8e-9
    for depth, width in ((depth_y, depth_z), (depth_z, depth_y)):
        k, m, shape = bending_rayleigh(xs, dx, depth, np.full(n, width), E, G, rho, length)
        f = math.sqrt(k / m) / (2 * math.pi)
        exact = _bar_frequency(depth, width, length)
        assert f / exact == pytest.approx(math.sqrt(140 / 11) / BETA1_SQ, rel=3e-3)
        assert k == pytest.approx(3 * E * width * depth ** 3 / 12 / length ** 3, rel=3e-3)
        assert shape[-1] == pytest.approx(1.0, abs=1e-3)


def test_fem3d_finds_and_classifies_both_directions_on_a_bar():
    """A 3D P2 half-model bar (1 mm deep in the plane, 0.6 mm through the sheet): the
    first mode is out of the plane, the second in it, each named by its modal
    displacement and each within 1 % of Euler-Bernoulli (L/h = 10)."""
    from skfem import MeshTet

    from tactcad.mechanics.fem.fem_modal import solve_modes

    length, h, b = 10.0, 1.0, 0.6
    mesh = MeshTet.init_tensor(np.linspace(0, length, 31), np.linspace(0, h, 4),
                               np.linspace(0, b / 2, 3))
    sol = solve_modes(mesh, STEEL, thickness=1.0, x_clamp=0.0, modes=2, plane=None,
                      sym_plane_z=b / 2, families=("in-plane", "out-of-plane"))
    assert sol.families == ("out-of-plane", "in-plane")
    assert sol.frequencies_Hz[0] == pytest.approx(_bar_frequency(b, h, length), rel=0.01)
    assert sol.frequencies_Hz[1] == pytest.approx(_bar_frequency(h, b, length), rel=0.01)


def _tip_mass_eigenvalue(mass_ratio: float) -> float:
    """lambda = beta L of a clamped-free Euler-Bernoulli beam with a tip mass M = ratio x
    its mass: 1 + cos l cosh l + ratio l (cos l sinh l - sin l cosh l) = 0 (first root)."""
    from scipy.optimize import brentq

    def equation(x):
        return (1 + math.cos(x) * math.cosh(x)
                + mass_ratio * x * (math.cos(x) * math.sinh(x) - math.sin(x) * math.cosh(x)))

    return brentq(equation, 0.5, 1.875105)


def test_fem_point_mass_at_the_tip_lowers_the_bar_as_the_beam_equation_says():
    """A tip mass M = 0.2 x the bar's mass on the 3D bar: f drops by the exact
    Euler-Bernoulli ratio (lambda_M / lambda_0)^2 to within 0.5 %."""
    from skfem import MeshTet

    from tactcad.mechanics.fem.fem_modal import solve_modes

    length, h, b = 10.0, 1.0, 0.6
    mesh = MeshTet.init_tensor(np.linspace(0, length, 31), np.linspace(0, h, 4),
                               np.linspace(0, b / 2, 3))
    kw = dict(thickness=1.0, x_clamp=0.0, modes=1, plane=None, sym_plane_z=b / 2,
              families=("in-plane",))
    bare = solve_modes(mesh, STEEL, **kw).frequencies_Hz[0]
    bar_g = 7.8e-3 * length * h * b
    tip = PointMass("tip", 0.2 * bar_g, length, h / 2)
    loaded = solve_modes(mesh, STEEL, added_masses=(tip,), **kw).frequencies_Hz[0]
    want = (_tip_mass_eigenvalue(0.2) / _tip_mass_eigenvalue(0.0)) ** 2
    assert loaded / bare == pytest.approx(want, rel=0.005)


OUT_OF_PLANE = json.loads((Path(__file__).resolve().parents[1] / "data"
                           / "modal_fem3d_out_of_plane.json").read_text(encoding="utf-8"))["elements"]


@pytest.mark.parametrize("row", OUT_OF_PLANE, ids=lambda r: r["part"])
def test_closed_form_out_of_plane_bounds_hold_fem3d(row):
    """fem3d's first out-of-plane frequency (stored) lies between the closed form's
    bounds (twist restrained, twist free), so within the reported value's error estimate;
    the closed form names the in-plane mode first where fem3d does."""
    from tactcad.mechanics.modal_closed_form import out_of_plane_bounds, out_of_plane_frequency

    plan = load_design(row["design"])
    g = plan.distinct_elements[row["part"]].bare()  # stored: fem3d of the element as cut
    upper, lower = out_of_plane_bounds(g, plan.material)
    assert lower <= row["first_out_of_plane_Hz"] <= upper
    f, err = out_of_plane_frequency(g, plan.material)
    assert abs(f / row["first_out_of_plane_Hz"] - 1) <= err
    r = estimate_modal_closed_form(g, plan.material, modes=2)
    assert [m.family for m in r.modes] == ["in-plane", "out-of-plane"]
    assert r.first_of("in-plane") == pytest.approx(row["first_in_plane_Hz"], rel=0.03)


def test_out_of_plane_bounds_with_and_without_added_masses_are_each_their_own_calls():
    # one pass over the chords gives both pairs, each to the bit what its own call gives
    from tactcad.mechanics.modal_closed_form import (out_of_plane_bounds,
                                                     out_of_plane_bounds_with_and_without)

    plan = load_design("hardware/ti_array_2x3/ti_array_2x3.toml")
    g = plan.distinct_elements["element_a19p605mm"]
    tip = PointMass("tip", 20e-3, *g.contact_centre_mm)
    for added in ((tip,), ()):
        loaded, bare = out_of_plane_bounds_with_and_without(g, plan.material, added)
        assert loaded == out_of_plane_bounds(g, plan.material, added)
        assert bare == out_of_plane_bounds(g, plan.material)
    assert loaded == bare  # nothing added: the one pair
