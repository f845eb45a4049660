"""The layer's exact kernels on a bonded and a frictionless base: their limits, an
independent plane-strain derivation, the thick-layer limit, and Hayes et al.'s (1972)
published correction factor for a rigid circular punch on a bonded layer."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from tactcad.mechanics.contact import (BASES, CellMesh, ContactError, DEFAULT_BASE, Punch,
                                       Sample, influence_matrix, layer_correction, layer_kernel,
                                       mesh_punches, solve_punches, unit_punch_compliance)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45, 0.5])
def test_the_kernels_reach_the_half_space_for_short_waves_and_their_thin_limits(nu):
    long_wave = np.array([1e-4, 1e-3])
    # bonded: the constrained (oedometric) modulus, K ~ t (1 - 2 nu) / (2 (1 - nu)^2)
    thin = long_wave * (1 - 2 * nu) / (2 * (1 - nu) ** 2)
    bonded = layer_kernel(long_wave, "bonded", nu)
    if nu < 0.5:
        assert bonded == pytest.approx(thin, rel=1e-3)
    else:  # incompressible: no first-order term, K ~ 2 t^3 / 3
        assert bonded == pytest.approx(2 * long_wave ** 3 / 3, rel=1e-3)
    # frictionless: a long wave compresses the layer as p h (1 - nu^2) / E, K ~ t / 2
    assert layer_kernel(long_wave, "frictionless", nu) == pytest.approx(long_wave / 2, rel=1e-3)
    for base in ("bonded", "frictionless"):
        short = layer_kernel(np.array([10.0, 50.0, 1e3]), base, nu)  # no overflow
        assert np.all(np.isfinite(short)) and short == pytest.approx(1.0, abs=1e-6)


def plane_strain_kernel(t: float, nu: float, base: str) -> float:
    """K(t) by a derivation of its own: the plane-strain layer under p cos(kx), its Navier
    equations as a first-order system in depth for the state (U, V, shear, normal stress),
    carried across the layer by the matrix exponential and matched to the base's
    condition; K = w E k / (2 (1 - nu^2) p), the half-space's w over its own."""
    e, k = 1.0, 1.0
    g = e / (2 * (1 + nu))
    lam = 2 * g * nu / (1 - 2 * nu)
    a = np.zeros((4, 4))
    a[0, 1], a[0, 2] = k, 1 / g  # U' = S/G + k V
    a[1, 0], a[1, 3] = -lam * k / (lam + 2 * g), 1 / (lam + 2 * g)  # V' from the normal stress
    a[2, 0] = k * k * (lam + 2 * g) + k * lam * a[1, 0]  # S' balances the x-direction
    a[2, 3] = k * lam * a[1, 3]
    a[3, 2] = -k  # N' balances the y-direction
    carry = expm(-a * t / k)  # from the base (depth h) to the surface
    free = [2, 3] if base == "bonded" else [0, 3]  # the base's unknowns
    amplitudes = np.linalg.solve(carry[np.ix_([2, 3], free)], [0.0, -1.0])
    return abs((carry[:, free] @ amplitudes)[1]) * e * k / (2 * (1 - nu ** 2))


@pytest.mark.parametrize("base", ["bonded", "frictionless"])
@pytest.mark.parametrize("nu", [0.25, 0.45, 0.4999])
def test_the_kernels_are_the_plane_strain_layers_own(base, nu):
    for t in (0.05, 0.3, 1.0, 2.5, 5.0):
        assert layer_kernel(t, base, nu) == pytest.approx(plane_strain_kernel(t, nu, base),
                                                          rel=1e-6, abs=1e-9)


def test_the_correction_is_the_half_spaces_far_field_and_smooth_near_the_load():
    rho = np.array([0.0, 0.5, 5.0, 29.9, 30.1, 60.0])
    for base in ("bonded", "frictionless"):
        f = layer_correction(rho, base, 0.5)
        assert np.all(np.isfinite(f)) and f[0] > 0  # finite under the load
        # far away the layer's own deflection is gone: f -> 1/rho, continuous at the table's end
        assert f[3:] == pytest.approx(1.0 / rho[3:], rel=1e-6)


def _every_pair_by_quadrature(mesh: CellMesh, sample: Sample, points: int) -> np.ndarray:
    """The layer's influence with the correction summed by Gauss-Legendre on every cell
    pair, far or near (the rule the influence matrix takes on its near pairs only)."""
    from tactcad.mechanics.contact import love_rectangle_displacement

    h, nu, e = sample.thickness_mm, sample.poisson_ratio, sample.youngs_modulus_MPa
    c, half = mesh.centres, mesh.half
    love = love_rectangle_displacement(c[:, None, 0], c[:, None, 1], (c[:, 0] - half[:, 0])[None],
                                       (c[:, 0] + half[:, 0])[None], (c[:, 1] - half[:, 1])[None],
                                       (c[:, 1] + half[:, 1])[None], 1.0, e, nu)
    x, w = np.polynomial.legendre.leggauss(points)
    correction = np.zeros_like(love)
    for xi, wi in zip(x, w):
        for zj, wj in zip(x, w):
            r = np.hypot(c[:, None, 0] - (c[:, 0] + half[:, 0] * xi)[None],
                         c[:, None, 1] - (c[:, 1] + half[:, 1] * zj)[None])
            correction += wi * wj * layer_correction(r / h, sample.base, nu)
    area = half[:, 0] * half[:, 1]
    return love - correction * ((1 - nu ** 2) / (np.pi * e * h) * area)[None, :]


@pytest.mark.parametrize("base", ["bonded", "frictionless"])
def test_a_thin_layers_far_cell_pairs_are_loves_closed_form_not_a_quadrature(base):
    # past 30 h the correction is 1/rho, so the layer's part of a far pair is Love's integral
    # less itself: zero, where the 12 x 12 rule on 1/rho left its own small error
    punches = [Punch(0.0, 0.0, 1.0, 2.0), Punch(1.5, 0.0, 1.0, 2.0)]
    sample = Sample(0.05, 0.49, 0.002, base)
    mesh = mesh_punches(punches)
    fast = influence_matrix(mesh, sample)
    full = _every_pair_by_quadrature(mesh, sample, 12)
    far = np.hypot(*np.maximum(np.abs(mesh.centres[:, None] - mesh.centres[None]) - mesh.half[None],
                               0.0).transpose(2, 0, 1)) >= 30 * 0.002
    assert far.mean() > 0.9 and np.all(fast[far] == 0.0)
    assert np.abs(fast - full).max() < 1e-4 * np.abs(full).max()  # the rule's error on 1/rho
    # near: the same sum (Love less the correction cancels to round-off of the largest entry)
    assert np.abs(fast[~far] - full[~far]).max() < 1e-12 * np.abs(full).max()


@pytest.mark.parametrize("base", ["bonded", "frictionless"])
def test_a_thick_layer_is_the_half_space(base):
    punch = [Punch(0.0, 0.0, 1.0, 1.0)]
    half = solve_punches(punch, Sample(1.0, 0.5), 0.25, 8).compliance_mm_per_N[0, 0]
    gaps = []
    for h in (5.0, 50.0):
        layer = solve_punches(punch, Sample(1.0, 0.5, h, base), 0.25, 8).compliance_mm_per_N
        gaps.append(1 - layer[0, 0] / half)
    assert 0 < gaps[1] < gaps[0] and gaps[1] < 0.02  # stiffer than, and closing on, it


def test_a_base_is_named_and_checked_and_steinbrenner_stays_the_default():
    assert Sample(1.0, 0.5, 1.0).base == DEFAULT_BASE == "steinbrenner"
    assert set(BASES) == {"bonded", "frictionless", "steinbrenner"}
    with pytest.raises(ContactError) as err:
        unit_punch_compliance([Punch(0.0, 0.0, 1.0, 1.0)], 0.5, 1.0, "glued")
    assert err.value.field == "base" and "bonded | frictionless | steinbrenner" in str(err.value)
    with pytest.raises(ContactError):
        layer_kernel(1.0, "steinbrenner", 0.5)  # an approximation has no kernel


#: Hayes, Keer, Herrmann and Mockros (J. Biomech. 5, 541-551, 1972), their table of kappa
#: for a rigid flat circular punch of radius a on a layer of thickness h bonded to a rigid
#: base, P = 2 a kappa E w / (1 - nu^2): a/h = 0.2, 0.6, 1.0, 2.0.
HAYES_KAPPA = {0.3: (1.207, 1.784, 2.480, 4.336), 0.5: (1.268, 2.129, 3.359, 7.644)}
HAYES_A_OVER_H = (0.2, 0.6, 1.0, 2.0)


def disc_stiffness(sample: Sample, cells_across: int = 40) -> float:
    """A rigid disc of radius 1 mm as the square cells whose centres lie in it (N/mm)."""
    d = 2.0 / cells_across
    x = -1.0 + d * (np.arange(cells_across) + 0.5)
    gx, gz = np.meshgrid(x, x, indexing="ij")
    inside = gx ** 2 + gz ** 2 <= 1.0
    centres = np.column_stack([gx[inside], gz[inside]])
    mesh = CellMesh(centres, np.full_like(centres, d / 2), np.zeros(len(centres), int))
    pressure = np.linalg.solve(influence_matrix(mesh, sample), np.ones(len(centres)))
    return float(mesh.area_mm2 @ pressure)


@pytest.mark.slow  # a contact solve per table entry, eleven in all
def test_a_disc_on_a_bonded_layer_has_hayes_correction_factor():
    """kappa = the disc's stiffness on the layer over its stiffness on the half-space, both
    on the same cells (their staircase edge cancels to about 0.3 %): within 1 % of the
    table at nu = 0.3 for every a/h; at nu = 0.5 within 1.5 % at a/h = 0.2, the table's
    thicker layers, where it and the exact kernel part (see the explanation page)."""
    for nu, table in HAYES_KAPPA.items():
        half = disc_stiffness(Sample(1.0, nu))
        for a_over_h, kappa in zip(HAYES_A_OVER_H, table):
            if nu == 0.5 and a_over_h > 0.2:
                continue
            layer = disc_stiffness(Sample(1.0, nu, 1.0 / a_over_h, "bonded"))
            assert layer / half == pytest.approx(kappa, rel=0.01 if nu == 0.3 else 0.015)


def fredholm_kappa(a_over_h: float, nu: float, points: int = 64) -> float:
    """kappa of a rigid disc (radius 1) on a bonded layer by the punch's Fredholm equation
    of the second kind, g(x) - (1/pi) int_0^1 g(t) [k(x - t) + k(x + t)] dt = 1 with
    k(u) = int_0^inf (1 - K(s h)) cos(s u) ds and kappa = int_0^1 g (the way Hayes et al.
    solve it), by Nystrom's method on Gauss-Legendre points."""
    h = 1.0 / a_over_h
    x, w = np.polynomial.legendre.leggauss(points)
    x, w = 0.5 * (x + 1), 0.5 * w
    panel = 0.05
    sx, sw = np.polynomial.legendre.leggauss(8)
    starts = np.arange(0.0, 40.0, panel)
    t = (starts[:, None] + 0.5 * panel * (sx + 1)).ravel()
    weights = (1 - layer_kernel(t, "bonded", nu)) * np.tile(0.5 * panel * sw, len(starts))

    # k(x - t) + k(x + t) by cos(a - b) + cos(a + b) = 2 cos(a) cos(b): one cosine per
    # point and wavenumber instead of one per pair of points and wavenumber
    c = np.cos(np.outer(x, t / h))
    m = 2.0 * (c * weights) @ c.T / h / np.pi * w[None, :]
    return float(w @ np.linalg.solve(np.eye(points) - m, np.ones(points)))


def test_at_nu_half_the_cells_agree_with_the_punchs_own_equation_where_the_table_parts():
    """Where the cells part from Hayes et al.'s nu = 0.5 column (a/h = 1: 7 %), the punch's
    Fredholm equation on the same kernel, an axisymmetric solution with no cells, gives the
    cells' value: the difference is the table's, not the boundary elements'."""
    half = disc_stiffness(Sample(1.0, 0.5))
    cells = disc_stiffness(Sample(1.0, 0.5, 1.0, "bonded")) / half
    assert cells == pytest.approx(fredholm_kappa(1.0, 0.5), rel=0.01)
    assert cells / HAYES_KAPPA[0.5][2] - 1 > 0.05
    assert fredholm_kappa(0.6, 0.3) == pytest.approx(HAYES_KAPPA[0.3][1], rel=0.005)
