"""The die's crosstalk through its handle and attach: the solid-on-a-bed solver against
Hetenyi's infinite plate on a Winkler foundation (a model of another kind: Kirchhoff plate
theory in closed form), and the die's matrix as its geometry says it must be."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import kei, keip, ker

from tactcad.products.silicon_die.design.mems_die import die_plan
from tactcad.products.silicon_die.mechanics import die_crosstalk as dx
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.studies.inverse_design import Targets

# one worker solves the small die's crosstalk (the module's fixture) for every test of it
pytestmark = pytest.mark.xdist_group("die_crosstalk")

#: The mesh of this module's die (finest and largest edge in um, handle layers) where a
#: test holds the matrix's structure (the diagonal is the read-out's, the worst pair is
#: the largest ratio, a farther post reads less), which a coarser mesh than the command's
#: keeps: there crosstalk_rel is 4.0e-5 against 4.2e-5 at the command's mesh, in 15 CPU s
#: against 39. How the attach's stiffness moves the coupling needs the resistors' own
#: edges (80 um): on this mesh a stiffer attach seemed to couple more.
COARSE = (200.0, 400.0, 2)
#: One handle layer at the command's edges: the attach's tests.
ONE_LAYER = (80.0, 400.0, 1)
#: the tests that read the die's solve (3D FE of its handle on the attach, four meshes)
needs_the_solve = pytest.mark.slow


def _isotropic(e_MPa: float, nu: float) -> np.ndarray:
    lam, mu = e_MPa * nu / ((1 + nu) * (1 - 2 * nu)), e_MPa / (2 * (1 + nu))
    d = np.eye(3)
    return (lam * np.einsum("ij,kl->ijkl", d, d)
            + mu * (np.einsum("ik,jl->ijkl", d, d) + np.einsum("il,jk->ijkl", d, d)))


def _hetenyi_top_strain(r: float, force: float, d: float, l: float, h: float):
    """Top-face strains (radial, tangential) at r of an infinite Kirchhoff plate on a
    Winkler bed under a point force on top (Timoshenko and Woinowsky-Krieger, Theory of
    Plates and Shells, 2nd ed., section 57): w = -(P l^2 / (2 pi D)) kei(r / l), and
    kei'' = ker - kei' / x (the Kelvin functions' equation)."""
    x = r / l
    w1 = -force * l / (2 * math.pi * d) * keip(x)
    w2 = -force / (2 * math.pi * d) * (ker(x) - keip(x) / x)
    return h / 2 * w2, h / 2 * w1 / r


@pytest.mark.slow  # a 3D FE plate of 120 x 120 elements
def test_a_thin_plate_on_its_bed_bends_as_hetenyis_infinite_plate():
    from skfem import MeshHex

    e, nu, h, l, force = 169e3, 0.25, 0.1, 1.0, 1.0
    d = e * h ** 3 / (12 * (1 - nu ** 2))
    k_n = d / l ** 4  # the bed that makes the plate's characteristic length l
    patch, half_window = 0.1, 0.05
    radii = (1.2, 2.0)  # clear of the radial strain's zero near 0.8 l
    cuts = [-patch, patch, -half_window, half_window]
    for r in radii:
        cuts += [r - half_window, r + half_window]
    planes = dx.graded_planes(-6 * l, 6 * l, cuts, 0.1, 1.0)
    mesh = MeshHex.init_tensor(planes, planes, np.array([0.0, h]))
    load = mesh.facets_satisfying(lambda x: np.isclose(x[2], h) & (np.abs(x[0]) < patch + 1e-9)
                                  & (np.abs(x[1]) < patch + 1e-9), boundaries_only=True)

    def pressure(x):
        return np.array([0 * x[0], 0 * x[0], np.full_like(x[0], -force / (2 * patch) ** 2)])

    windows = [(r - half_window, -half_window, r + half_window, half_window) for r in radii]
    strains, _ = dx.strains_on_springs(mesh, _isotropic(e, nu), (k_n, 1e-6 * k_n),
                                       [(load, pressure)], windows)
    for r, strain in zip(radii, strains[:, 0]):
        radial, tangential = _hetenyi_top_strain(r, force, d, l, h)
        scale = max(abs(radial), abs(tangential))
        assert abs(strain[0, 0] - radial) < 0.03 * scale, (r, strain[0, 0], radial)
        assert abs(strain[1, 1] - tangential) < 0.03 * scale, (r, strain[1, 1], tangential)


def test_the_beds_stiffness_is_the_films_constrained_and_shear_modulus_over_its_thickness():
    k_n, k_t = dx.attach_springs_N_per_mm3(4000.0, 0.35, 0.025)
    assert k_n == pytest.approx(4000 * 0.65 / (1.35 * 0.3) / 0.025)
    assert k_t == pytest.approx(4000 / 2.7 / 0.025)
    for bad in ((0.0, 0.3, 0.025), (4000.0, 0.5, 0.025), (4000.0, 0.3, -1.0)):
        with pytest.raises(ValueError):
            dx.attach_springs_N_per_mm3(*bad)


def test_graded_planes_pass_every_cut_and_grow_from_it():
    planes = dx.graded_planes(0.0, 1000.0, [300.0, 310.0], 10.0, 200.0)
    assert {0.0, 300.0, 310.0, 1000.0} <= set(np.round(planes, 9))
    gaps = np.diff(planes)
    assert gaps.max() <= 200.0 + 1e-9 and np.all(gaps > 0)
    assert np.all(gaps[1:] / gaps[:-1] <= dx.GROWTH * 1.3)  # stretched to fit: near GROWTH
    with pytest.raises(ValueError):
        dx.graded_planes(0.0, 1.0, [], 0.0, 1.0)


@pytest.fixture(scope="module")
def small_die():
    return die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"), columns=3)


@pytest.fixture(scope="module")
def result(small_die):
    return dx.die_crosstalk(small_die, mesh=COARSE)


@needs_the_solve
def test_the_dies_crosstalk_is_each_units_own_reading_and_the_frames_share(small_die, result):
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_resistor

    n = len(small_die.beams)
    s = result.reading_per_N
    assert s.shape == (n, n) and result.beams == tuple(b.number for b in small_die.beams)
    own = [die_resistor(small_die, b).resistance_change_per_N() for b in small_die.beams]
    assert np.diag(s) == pytest.approx(own)  # the read-out's own figure, unchanged
    ratio = np.abs(s / np.diag(s)[:, None])
    np.fill_diagonal(ratio, 0.0)
    assert result.crosstalk_rel == pytest.approx(ratio.max())
    i, j = (result.beams.index(b) for b in result.worst)
    assert ratio[i, j] == ratio.max()
    # through a die bonded on its attach the coupling is small: below 1e-3 of a unit's own
    assert 0 < result.crosstalk_rel < 1e-3
    assert 0 < result.error_estimate_rel and result.dofs > 1000 and result.seconds > 0


@needs_the_solve
def test_a_units_reading_falls_with_the_loaded_posts_distance_along_its_row(small_die, result):
    s = np.abs(result.reading_per_N)
    columns = small_die.columns
    for row in range(2):
        first = row * columns  # the row's first unit: its neighbours at 1 and 2 pitches
        assert s[first, first + 2] < s[first, first + 1]


@pytest.mark.slow  # two solves at the resistors' edges (about 25 CPU s)
def test_a_stiffer_attach_holds_the_frame_closer_and_the_mesh_is_stated(small_die):
    footprints = dx.resistor_footprints(small_die)
    one_layer = ONE_LAYER
    soft = dx._solve(small_die, one_layer, small_die.attach.modulus_MPa / 4, footprints)
    hard = dx._solve(small_die, one_layer, small_die.attach.modulus_MPa * 4, footprints)
    off = ~np.eye(len(small_die.beams), dtype=bool)
    assert np.abs(hard[0][off]).max() < np.abs(soft[0][off]).max()
    with pytest.raises(ValueError, match="even"):
        dx.die_crosstalk(small_die, mesh=one_layer)


@needs_the_solve
def test_the_worst_crosstalk_in_newtons_is_the_ratio_times_the_loaded_posts_force(small_die,
                                                                                 result):
    resolution = {"reference": 1e-6, "measuring": 2e-6}
    q = dx.crosstalk_in_force(small_die, result, resolution)
    i = result.beams.index(q["beam"])
    j = result.beams.index(q["loaded_beam"])
    s = result.reading_per_N
    beam_j = small_die.beams[j]
    expected = abs(s[i, j] / s[i, i]) * small_die.rated_force_N(beam_j)
    assert q["crosstalk_force_N"] == pytest.approx(expected)
    assert q["force_resolution_steps"] == pytest.approx(
        expected / resolution[small_die.beams[i].role])


@pytest.mark.slow
def test_a_stated_attach_is_the_one_the_die_rests_on_and_narrows_the_error(small_die, result):
    from dataclasses import replace

    assumed = small_die.attach
    stated = replace(small_die, attach=replace(assumed, stated=True, source="a data sheet"))
    same = dx.die_crosstalk(stated, mesh=COARSE)
    assert same.reading_per_N == pytest.approx(result.reading_per_N)
    # the modulus spans a quarter either way, not the assumption's half and double
    assert same.error_estimate_rel < result.error_estimate_rel
    assert "a data sheet" in same.basis and f"x/ {dx.STATED_MODULUS_SPAN:g}" in same.basis
    # a four times thicker film is a four times softer bed: the frame tilts more
    footprints, one_layer = dx.resistor_footprints(small_die), ONE_LAYER
    thicker = replace(small_die, attach=replace(assumed, thickness_um=4 * assumed.thickness_um))
    off = ~np.eye(len(small_die.beams), dtype=bool)
    thin = dx._solve(small_die, one_layer, assumed.modulus_MPa, footprints)[0]
    thick = dx._solve(thicker, one_layer, assumed.modulus_MPa, footprints)[0]
    assert np.abs(thick[off]).max() > np.abs(thin[off]).max()


def test_a_windows_mean_strains_are_scikit_fems_interpolated_ones():
    """:func:`mean_strains` sums every load's gradient at once: the same means as
    scikit-fem's ``interpolate`` of each load's each component, on a box's top facets."""
    import numpy as np
    from skfem import ElementHex2, FacetBasis, MeshHex

    from tactcad.products.silicon_die.mechanics.die_crosstalk import mean_strains

    mesh = MeshHex.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 0.5, 3),
                               np.linspace(0, 0.2, 3))
    fb = FacetBasis(mesh, ElementHex2(), facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[2], 0.2) & (x[0] < 0.7), boundaries_only=True), intorder=5)
    u = np.random.default_rng(1).standard_normal((3 * fb.N, 4))
    weights = fb.dx / np.sum(fb.dx)
    for j in range(u.shape[1]):
        grad = np.array([fb.interpolate(u[a::3, j]).grad for a in range(3)])
        strain = 0.5 * (grad + np.swapaxes(grad, 0, 1))
        expected = np.einsum("ijfq,fq->ij", strain, weights)
        assert np.allclose(mean_strains(fb, u)[j], expected, rtol=1e-12, atol=1e-14)
