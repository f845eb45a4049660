"""Rigid flat rectangular punches on an elastic sample: half-space or layer on a rigid base.

The sample surface is the plane (x, z) of the array frame (mm); the punches are
the elements' contact faces pressed along y. The model is a boundary-element
model with piecewise-constant pressure cells (collocation at cell centres):

* half-space influence kernel: Love's (1929) closed-form surface displacement
  of a uniformly loaded rectangle on an elastic half-space (A. E. H. Love,
  "The stress produced in a semi-infinite solid by pressure on part of the
  boundary", Phil. Trans. R. Soc. A 228, 1929; K. L. Johnson, *Contact
  Mechanics*, 1985, sec. 3.3): with I = ∫∫ dA / r over the rectangle,
  w = (1 − ν²) p I / (π E);
* layer of thickness h on a rigid base, by the base's condition (:data:`BASES`):

  - ``bonded`` and ``frictionless``: the layer's exact surface response from its
    Hankel-transform solution (D. M. Burmister, J. Appl. Phys. 16, 1945; the bonded
    layer as W. C. Hayes, L. M. Keer, G. Herrmann and L. F. Mockros, J. Biomech. 5,
    1972, use it for cartilage): a point load P gives
    w(r) = P (1 − ν²)/(π E) ∫₀^∞ K(k h) J₀(k r) dk, K = 1 for the half-space
    (:func:`layer_kernel`); the layer's influence is Love's rectangle formula less a
    smooth correction tabulated once per base and ν (:func:`layer_correction`);
  - ``steinbrenner``: Steinbrenner's approximation
  (W. Steinbrenner, *Die Strasse* 1, 1934; H. G. Poulos and E. H. Davis,
  *Elastic Solutions for Soil and Rock Mechanics*, 1974, ch. 5): the surface
  displacement of the layer is the half-space surface displacement minus the
  half-space displacement at depth h under the same load (Boussinesq,
  u_z = P (1 + ν) / (2 π E) [z²/ρ³ + 2 (1 − ν)/ρ], ρ = √(r² + z²)). It is an
  engineering approximation: it ignores the base's shear condition and is
  least accurate for thin, nearly incompressible layers (h much smaller than
  the punch and ν → 0.5), where a bonded layer is stiffer than it predicts. It
  stays the default base (:data:`DEFAULT_BASE`): the rig models, the budget and the
  paper's comparisons were built on it; the grasp states its base.

A rigid punch moves its whole face by one displacement; the cells' pressures
follow from the collocation equations and the punch forces from their sum.
The pressure under a rigid punch is singular at its edges (as 1/√distance), so
uniform cells converge slowly (first order: 0.25 mm cells left the macro array's
coupling 4 % low); the cells are graded towards each face's edges (cosine
spacing), and :func:`converged_punches` refines them with Richardson
extrapolation until the compliances change by less than 0.1 %, reporting the
error it reached.
All compliances scale as 1/E; the functions work with a given modulus E (MPa).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from tactcad.mechanics.blas_threads import single_threaded_blas
from tactcad.store import kept_per_process, kept_result
from tactcad.errors import TactcadError

#: Largest cell edge the boundary-element mesh aims for (mm): the cosine-graded cells of a
#: 2 x 3 mm face are at most this in its middle, finer towards its edges.
DEFAULT_CELL_MM = 0.25
#: Fewest cells along a face edge, whatever its size: a 0.5 mm tip got 2 x 2 cells of 0.25 mm,
#: its coupling to a tip 1.5 mm away 7 % off the converged one; with 8 per edge a square
#: punch's stiffness is 3 % below its exact value (King 1987).
MIN_CELLS_PER_EDGE = 8
#: Rigid square punch on a half-space: K = β (2/√π) E/(1 − ν²) √A with β = 1.012
#: (J. R. Barber, *Contact Mechanics*, 2018, sec. 6.4, after King 1987; circle β = 1).
SQUARE_PUNCH_BETA = 1.012


class ContactError(TactcadError, ValueError):
    """A contact-model input outside its range; names the field, value and allowed range."""

    def __init__(self, field: str, value: object, allowed: str):
        self.field, self.value, self.allowed = field, value, allowed
        super().__init__(f"{field} = {value!r}: allowed {allowed}")


@dataclass(frozen=True)
class Punch:
    """A rigid flat rectangular punch face on the sample surface (mm).

    Attributes:
        x_mm, z_mm: centre of the face in the surface plane.
        width_x_mm, depth_z_mm: edge lengths along x and z, > 0.
    """

    x_mm: float
    z_mm: float
    width_x_mm: float
    depth_z_mm: float


#: The conditions a layer's rigid base can hold it by: ``bonded`` (no slip: the layer's
#: underside neither moves nor slides), ``frictionless`` (it slides freely, does not lift),
#: ``steinbrenner`` (Steinbrenner's approximation, which states neither).
BASES = ("bonded", "frictionless", "steinbrenner")
#: The base a :class:`Sample` has unless told. Steinbrenner's, though a clamped tissue is
#: closer to bonded: the rig models, the budget and the paper's comparisons were built and
#: checked on it, and a caller that knows its base states it (the grasp does).
DEFAULT_BASE = "steinbrenner"


@dataclass(frozen=True)
class Sample:
    """The elastic sample under the punches.

    Attributes:
        youngs_modulus_MPa: E (MPa), > 0.
        poisson_ratio: ν, 0 <= ν <= 0.5 (rubber: about 0.5).
        thickness_mm: layer thickness h on a rigid base (mm), > 0, or None
            for a half-space.
        base: how the rigid base holds the layer, one of :data:`BASES` (ignored for a
            half-space). Default :data:`DEFAULT_BASE`, Steinbrenner's approximation, for
            the models built on it; tissue gripped by a serrated jaw face is closer to
            ``bonded``, tissue lying on a smooth wet plate closer to ``frictionless``.
    """

    youngs_modulus_MPa: float
    poisson_ratio: float
    thickness_mm: float | None = None
    base: str = DEFAULT_BASE


def check_sample(sample: Sample) -> None:
    """Check a sample's fields.

    Raises:
        ContactError: a modulus <= 0, ν outside [0, 0.5], a thickness <= 0 or a base not
            in :data:`BASES`, naming the field.
    """
    if not (np.isfinite(sample.youngs_modulus_MPa) and sample.youngs_modulus_MPa > 0):
        raise ContactError("youngs_modulus_MPa", sample.youngs_modulus_MPa, "> 0 MPa")
    if not (np.isfinite(sample.poisson_ratio) and 0.0 <= sample.poisson_ratio <= 0.5):
        raise ContactError("poisson_ratio", sample.poisson_ratio, "0 ... 0.5")
    h = sample.thickness_mm
    if h is not None and not (np.isfinite(h) and h > 0):
        raise ContactError("thickness_mm", h, "> 0 mm (or none for a half-space)")
    check_base(sample.base)


def check_base(base: object) -> None:
    """Check a layer's base condition.

    Args:
        base: the base's name.

    Raises:
        ContactError: ``base`` not one of :data:`BASES`, naming the field and the allowed
            words.
    """
    if base not in BASES:
        raise ContactError("base", base, " | ".join(BASES))


# ---------------------------------------------------------------------------
# Kernels
# ---------------------------------------------------------------------------
def _corner_primitive(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """F(u, v) with ∂²F/∂u∂v = 1/√(u² + v²), odd in u and in v, F = 0 on the axes.

    F = u asinh(v/|u|) + v asinh(u/|v|) (each term 0 where its divisor is 0), evaluated as
    sign(u) sign(v) (|u| L(|v|, |u|) + |v| L(|u|, |v|)) with
    L(p, q) = asinh(p/q) = log1p(p/q (1 + p/(ρ + q))), ρ = √(u² + v²) shared by the two
    (ρ − q = p²/(ρ + q): no cancellation, and one root instead of two).
    """
    # |u|, |v|, their squares, floors and signs on the arguments' own shapes: on a grid
    # (u along one axis, v along another, as :func:`_love_on_edges` passes them) these are a
    # small fraction of the broadcast result, whose elements then see each step once; every
    # element is the same operation on the same values as on the broadcast arrays (same bits)
    u, v = np.asarray(u, float), np.asarray(v, float)
    shape = np.broadcast_shapes(u.shape, v.shape)
    u, v = np.atleast_1d(u), np.atleast_1d(v)  # the in-place steps below need arrays
    au, av = np.abs(u), np.abs(v)
    rho = np.add(au * au, av * av)  # a new array of the broadcast shape
    np.sqrt(rho, out=rho)  # not np.hypot: libm's is five times slower, and no side overflows
    # a nil |u| or |v| zeroes F by its sign; 1e-300 mm in its place keeps the logs finite
    su, sv = np.maximum(au, 1e-300), np.maximum(av, 1e-300)
    a = np.add(rho, su)
    np.divide(av, a, out=a)
    a += 1.0
    a *= av / su
    np.log1p(a, out=a)
    a *= au
    b = np.add(rho, sv, out=rho)  # ρ's last use: its array holds b
    np.divide(au, b, out=b)
    b += 1.0
    b *= au / sv
    np.log1p(b, out=b)
    b *= av
    a += b
    a *= np.sign(u)  # a sign product of +-1 and +-0 is exact in either order
    a *= np.sign(v)
    return a.reshape(shape)


def rectangle_inverse_distance_integral(x, z, x1, x2, z1, z2):
    """I = ∫∫ dξ dζ / √((ξ − x)² + (ζ − z)²) over the rectangle [x1, x2] x [z1, z2] (mm).

    Closed form (Love 1929) from the corner primitive; exact at any point of
    the plane, inside the rectangle included. Arguments broadcast.
    """
    x, z = np.asarray(x, float), np.asarray(z, float)
    return (_corner_primitive(x2 - x, z2 - z) - _corner_primitive(x1 - x, z2 - z)
            - _corner_primitive(x2 - x, z1 - z) + _corner_primitive(x1 - x, z1 - z))


def love_rectangle_displacement(x, z, x1, x2, z1, z2, pressure_MPa: float,
                                youngs_modulus_MPa: float, poisson_ratio: float):
    """Surface displacement of a half-space under uniform pressure on a rectangle (mm).

    Love (1929); Johnson, *Contact Mechanics*, eq. 3.25: w = (1 − ν²) p I/(π E)
    with I from :func:`rectangle_inverse_distance_integral`.
    """
    scale = (1.0 - poisson_ratio ** 2) / (np.pi * youngs_modulus_MPa)
    return scale * pressure_MPa * rectangle_inverse_distance_integral(x, z, x1, x2, z1, z2)


def boussinesq_depth_displacement(r, depth_mm: float, youngs_modulus_MPa: float,
                                  poisson_ratio: float):
    """Vertical displacement per newton at depth z and radial distance r of a point load (mm/N).

    Boussinesq: u_z = (1 + ν)/(2 π E) [z²/ρ³ + 2 (1 − ν)/ρ], ρ = √(r² + z²);
    Johnson, *Contact Mechanics*, eq. 3.21. Requires depth > 0.
    """
    rho = np.sqrt(np.asarray(r, float) ** 2 + depth_mm ** 2)
    return ((1 + poisson_ratio) / (2 * np.pi * youngs_modulus_MPa)
            * (depth_mm ** 2 / rho ** 3 + 2 * (1 - poisson_ratio) / rho))


def layer_kernel(t, base: str, poisson_ratio: float) -> np.ndarray:
    """The layer's surface-deflection kernel K(t), t = k h (k the Hankel wavenumber, 1/mm;
    h the thickness, mm): w(r) = P (1 − ν²)/(π E) ∫₀^∞ K(k h) J₀(k r) dk under a point
    load P; K = 1 is the half-space (Boussinesq).

    With κ = 3 − 4ν (Burmister 1945; the bonded case as Hayes, Keer, Herrmann and
    Mockros, J. Biomech. 5, 1972, use it):

    * bonded: K = (2κ sinh 2t − 4t)/(2κ cosh 2t + 4t² + 1 + κ²), → t (1 − 2ν)/(2 (1 − ν)²)
      as t → 0 (the constrained modulus of a thin layer);
    * frictionless: K = (cosh 2t − 1)/(sinh 2t + 2t), → t/2 as t → 0.

    Both → 1 as t → ∞ (short waves do not reach the base). Computed as 1 − (1 − K),
    the latter in decaying exponentials (:func:`_one_minus_kernel`), so large t does not
    overflow.

    Args:
        t: k h >= 0 (array).
        base: ``bonded`` or ``frictionless``.
        poisson_ratio: ν, 0 ... 0.5.

    Returns:
        K(t), the shape of ``t``.

    Raises:
        ContactError: another base (Steinbrenner's has no such kernel).
    """
    return 1.0 - _one_minus_kernel(np.asarray(t, float), base, float(poisson_ratio))


#: The exact bases, those with a kernel (:func:`layer_kernel`).
KERNEL_BASES = ("bonded", "frictionless")


def _one_minus_kernel(t: np.ndarray, base: str, nu: float) -> np.ndarray:
    """1 − K(t), numerator and denominator multiplied by e^(−2t): every term stays finite."""
    if base not in KERNEL_BASES:
        raise ContactError("base", base, " | ".join(KERNEL_BASES) + " (a layer kernel)")
    e2 = np.exp(-2.0 * t)
    e4 = e2 * e2
    if base == "bonded":
        kappa = 3.0 - 4.0 * nu
        return ((2 * kappa * e4 + ((2 * t + 1) ** 2 + kappa ** 2) * e2)
                / (kappa * (1 + e4) + (4 * t * t + 1 + kappa ** 2) * e2))
    with np.errstate(invalid="ignore", divide="ignore"):
        out = 2 * (1 + 2 * t - e2) * e2 / (1 - e4 + 4 * t * e2)
    return np.where(t > 0, out, 1.0)


#: The correction's table (in ρ = r/h): its spacing and end; past the end the correction
#: is 1/ρ (the layer's own deflection there is below 1e-10 of the half-space's).
CORRECTION_STEP = 0.01
CORRECTION_END = 30.0
#: Quadrature of the correction's t integral: panels of this width (a fraction of J₀'s
#: period at the table's end, 2π/30), Gauss-Legendre points per panel, and the end of
#: the t range (1 − K < 1e-23 there).
_T_PANEL = 0.05
_T_POINTS = 8
_T_END = 36.0


#: The kind the result store keeps a correction table under (:func:`_correction_spline`).
CORRECTION_KIND = "layer correction table"


@functools.lru_cache(maxsize=16)
def _correction_spline(base: str, poisson_ratio: float) -> np.ndarray:
    """Cubic-spline coefficients of f(ρ) on [0, :data:`CORRECTION_END`], shape (4, n − 1);
    kept per process and in the result store of :func:`tactcad.store.keeping_results`: the
    table is the same for every design on the base and ν, and tabulating it (17 million
    Bessel values, and SciPy to import) cost a grasp on a new tissue thickness seconds."""
    return kept_result(CORRECTION_KIND, lambda: _tabulated_correction(base, poisson_ratio),
                       base, poisson_ratio, CORRECTION_STEP, CORRECTION_END, _T_PANEL,
                       _T_POINTS, _T_END)


def _tabulated_correction(base: str, poisson_ratio: float) -> np.ndarray:
    """:func:`_correction_spline`'s coefficients, computed."""
    from scipy.interpolate import CubicSpline
    from scipy.special import j0

    x, w = np.polynomial.legendre.leggauss(_T_POINTS)
    starts = np.arange(0.0, _T_END, _T_PANEL)
    t = (starts[:, None] + 0.5 * _T_PANEL * (x + 1)).ravel()
    weighted = _one_minus_kernel(t, base, poisson_ratio) * np.tile(0.5 * _T_PANEL * w, len(starts))
    rho = np.linspace(0.0, CORRECTION_END, int(round(CORRECTION_END / CORRECTION_STEP)) + 1)
    f = np.concatenate([j0(np.outer(chunk, t)) @ weighted for chunk in np.array_split(rho, 12)])
    # f is even in ρ: a clamped zero slope at the axis
    return CubicSpline(rho, f, bc_type=((1, 0.0), "not-a-knot")).c


def layer_correction(rho, base: str, poisson_ratio: float) -> np.ndarray:
    """f(ρ) = ∫₀^∞ (1 − K(t)) J₀(t ρ) dt, ρ = r/h: the half-space's point-load deflection
    less the layer's, in units of P (1 − ν²)/(π E h) (:func:`layer_kernel`).

    1 − K decays as e^(−2t), so f is smooth; it is tabulated once per base and ν
    (Gauss-Legendre over t, cubic spline over ρ, accurate to about 1e-9) and is 1/ρ past
    :data:`CORRECTION_END` (K(0) = 0: the layer's own deflection decays exponentially).

    Args:
        rho: r/h >= 0 (array).
        base: ``bonded`` or ``frictionless``.
        poisson_ratio: ν, 0 ... 0.5.

    Returns:
        f(ρ), the shape of ``rho``.

    Raises:
        ContactError: a base without a kernel.
    """
    if base not in KERNEL_BASES:
        raise ContactError("base", base, " | ".join(KERNEL_BASES) + " (a layer kernel)")
    c = _correction_spline(base, float(poisson_ratio))
    rho = np.asarray(rho, float)
    i = np.minimum((rho / CORRECTION_STEP).astype(np.intp), c.shape[1] - 1)
    s = rho - i * CORRECTION_STEP
    inside = ((c[0, i] * s + c[1, i]) * s + c[2, i]) * s + c[3, i]
    with np.errstate(divide="ignore"):
        return np.where(rho <= CORRECTION_END, inside, 1.0 / rho)


# ---------------------------------------------------------------------------
# Boundary-element model
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class FaceGrid:
    """One punch face and the graded cells :func:`mesh_punches` splits it into.

    Attributes:
        x_mm, z_mm: the face's centre (mm).
        width_x_mm, depth_z_mm: its edges (mm).
        cells_x, cells_z: cells along each edge (:func:`graded_edges`).
    """

    x_mm: float
    z_mm: float
    width_x_mm: float
    depth_z_mm: float
    cells_x: int
    cells_z: int

    @property
    def shape(self) -> tuple[float, float, int, int]:
        """What its cells relative to its centre depend on: edges (mm) and counts."""
        return (self.width_x_mm, self.depth_z_mm, self.cells_x, self.cells_z)


@dataclass(frozen=True, eq=False)
class CellMesh:
    """Piecewise-constant pressure cells of a set of punches.

    Attributes:
        centres: cell centres (x, z), shape (n, 2) (mm).
        half: half edge lengths (hx, hz) of each cell, shape (n, 2) (mm).
        punch: index of the punch each cell belongs to, shape (n,).
        face_grids: each punch's face and graded grid (:class:`FaceGrid`), as
            :func:`mesh_punches` lays them out; None for cells laid out otherwise.
    """

    centres: np.ndarray
    half: np.ndarray
    punch: np.ndarray
    face_grids: tuple[FaceGrid, ...] | None = None

    @property
    def area_mm2(self) -> np.ndarray:
        return 4.0 * self.half[:, 0] * self.half[:, 1]


def _check_punches(punches) -> None:
    if not punches:
        raise ContactError("punches", len(punches), "at least one punch")
    for i, p in enumerate(punches):
        for name in ("width_x_mm", "depth_z_mm"):
            value = getattr(p, name)
            if not (np.isfinite(value) and value > 0):
                raise ContactError(f"punches[{i}].{name}", value, "> 0 mm")


def graded_edges(n: int) -> np.ndarray:
    """``n + 1`` cell edges on [0, 1], cosine-graded: cells shrink towards both ends as
    the edge-singular pressure of a rigid punch needs (middle cell about π/(2n) long)."""
    return 0.5 * (1.0 - np.cos(np.pi * np.arange(n + 1) / n))


def cells_per_edge(edge_mm: float, cell_mm: float, min_cells: int) -> int:
    """Cells along a face edge of ``edge_mm`` (mm) whose graded middle cell is at most
    ``cell_mm`` (mm), at least ``min_cells``."""
    return max(int(min_cells), int(np.ceil(np.pi * edge_mm / (2.0 * cell_mm) - 1e-9)))


def mesh_punches(punches, cell_mm: float = DEFAULT_CELL_MM,
                 min_cells: int = MIN_CELLS_PER_EDGE) -> CellMesh:
    """Split each punch face into a grid of cells graded towards its edges
    (:func:`graded_edges`), the middle cells about ``cell_mm`` (mm), at least
    ``min_cells`` (default :data:`MIN_CELLS_PER_EDGE`) along each edge.

    Raises:
        ContactError: no punch, a face edge <= 0, or cell_mm <= 0.
    """
    _check_punches(punches)
    if not (np.isfinite(cell_mm) and cell_mm > 0):
        raise ContactError("cell_mm", cell_mm, "> 0 mm")
    centres, half, owner, faces = [], [], [], []
    for k, p in enumerate(punches):
        nx = cells_per_edge(p.width_x_mm, cell_mm, min_cells)
        nz = cells_per_edge(p.depth_z_mm, cell_mm, min_cells)
        faces.append(FaceGrid(float(p.x_mm), float(p.z_mm), float(p.width_x_mm),
                              float(p.depth_z_mm), nx, nz))
        ex = p.x_mm - p.width_x_mm / 2 + p.width_x_mm * graded_edges(nx)
        ez = p.z_mm - p.depth_z_mm / 2 + p.depth_z_mm * graded_edges(nz)
        gx, gz = np.meshgrid((ex[1:] + ex[:-1]) / 2, (ez[1:] + ez[:-1]) / 2, indexing="ij")
        hx, hz = np.meshgrid(np.diff(ex) / 2, np.diff(ez) / 2, indexing="ij")
        centres.append(np.column_stack([gx.ravel(), gz.ravel()]))
        half.append(np.column_stack([hx.ravel(), hz.ravel()]))
        owner.append(np.full(gx.size, k))
    return CellMesh(np.vstack(centres), np.vstack(half), np.concatenate(owner), tuple(faces))


@functools.lru_cache(maxsize=256)
def face_cells(width_x_mm: float, depth_z_mm: float, cells_x: int,
               cells_z: int) -> tuple[np.ndarray, np.ndarray]:
    """A face's graded cells relative to its centre, as :func:`mesh_punches` lays them out
    (x major). A function of the face alone: every face of an array shares one set of bits.

    Args:
        width_x_mm, depth_z_mm: the face's edges (mm). cells_x, cells_z: cells along each.

    Returns:
        (centres, half edges), each shape (cells, 2) (mm), read-only.
    """
    ex = -width_x_mm / 2 + width_x_mm * graded_edges(cells_x)
    ez = -depth_z_mm / 2 + depth_z_mm * graded_edges(cells_z)
    gx, gz = np.meshgrid((ex[1:] + ex[:-1]) / 2, (ez[1:] + ez[:-1]) / 2, indexing="ij")
    hx, hz = np.meshgrid(np.diff(ex) / 2, np.diff(ez) / 2, indexing="ij")
    centres = np.column_stack([gx.ravel(), gz.ravel()])
    half = np.column_stack([hx.ravel(), hz.ravel()])
    centres.setflags(write=False)
    half.setflags(write=False)
    return centres, half


def _layer_depth_term(centres: np.ndarray, src_centres: np.ndarray, src_half: np.ndarray,
                      sample: Sample, n_gauss: int) -> np.ndarray:
    """Half-space displacement at depth h at each of ``centres`` per unit pressure on each
    source cell, shape (n, m) (mm/MPa).

    Gauss-Legendre quadrature over the loaded cell (the integrand is smooth,
    ρ >= h); the order grows when cells are large against h.
    """
    h = float(sample.thickness_mm)
    pts, wts = np.polynomial.legendre.leggauss(n_gauss)
    # Boussinesq's u_z (boussinesq_depth_displacement) as c (h²/ρ³ + b/ρ), ρ² = dx² + dz² + h²;
    # dx² and dz² of each quadrature column and row computed once (the cell is a product rule)
    c = (1 + sample.poisson_ratio) / (2 * np.pi * sample.youngs_modulus_MPa)
    b = 2 * (1 - sample.poisson_ratio)
    dx2 = [(centres[:, None, 0] - (src_centres[:, 0] + src_half[:, 0] * p)[None, :]) ** 2 + h * h
           for p in pts]
    dz2 = [(centres[:, None, 1] - (src_centres[:, 1] + src_half[:, 1] * p)[None, :]) ** 2
           for p in pts]
    area = src_half[:, 0] * src_half[:, 1]
    out = np.zeros((len(centres), len(src_centres)))
    inv = np.empty_like(out)
    term = np.empty_like(out)
    for i, wi in enumerate(wts):
        for j, wj in enumerate(wts):
            np.add(dx2[i], dz2[j], out=inv)
            np.sqrt(inv, out=inv)
            np.reciprocal(inv, out=inv)  # 1/ρ
            np.multiply(inv, inv, out=term)
            term *= h * h
            term += b
            term *= inv  # h²/ρ³ + b/ρ
            term *= (c * wi * wj) * area[None, :]
            out += term
    return out


def _far_from_cell(centres: np.ndarray, src_centres: np.ndarray, src_half: np.ndarray,
                   distance_mm: float) -> np.ndarray:
    """Whether every point of each source cell lies at least ``distance_mm`` (mm) from each
    of ``centres``, shape (n, m): the nearest point of a rectangle is its centre moved by
    at most its half edges."""
    gap_x = np.maximum(np.abs(centres[:, None, 0] - src_centres[None, :, 0])
                       - src_half[None, :, 0], 0.0)
    gap_z = np.maximum(np.abs(centres[:, None, 1] - src_centres[None, :, 1])
                       - src_half[None, :, 1], 0.0)
    return gap_x * gap_x + gap_z * gap_z >= distance_mm * distance_mm


def _layer_kernel_term(centres: np.ndarray, src_centres: np.ndarray, src_half: np.ndarray,
                       sample: Sample, n_gauss: int,
                       half_space: np.ndarray) -> np.ndarray:
    """The half-space's displacement less the layer's at each of ``centres`` per unit
    pressure on each source cell, shape (n, m) (mm/MPa): (1 − ν²)/(π E h) ∫∫ f(ρ/h) dA
    (:func:`layer_correction`), Gauss-Legendre over the loaded cell (f is smooth).

    A cell pair whose every point lies past :data:`CORRECTION_END` h has f = 1/ρ on the
    whole cell, so the integral is the half-space's own, ``half_space`` (Love's closed
    form): it is taken from there, not summed (on a layer thin against its cells nearly
    every pair is such, and the quadrature's n_gauss² kernel calls were the grasp's cost)."""
    h = float(sample.thickness_mm)
    pts, wts = np.polynomial.legendre.leggauss(n_gauss)
    scale = (1 - sample.poisson_ratio ** 2) / (np.pi * sample.youngs_modulus_MPa * h)
    area = src_half[:, 0] * src_half[:, 1]
    out = np.array(half_space, dtype=float, copy=True)
    rows, cols = np.nonzero(~_far_from_cell(centres, src_centres, src_half, CORRECTION_END * h))
    if len(rows) == 0:
        return out
    near = np.zeros(len(rows))
    for i, wi in enumerate(wts):
        dx2 = (centres[rows, 0] - (src_centres[cols, 0] + src_half[cols, 0] * pts[i])) ** 2
        for j, wj in enumerate(wts):
            dz2 = (centres[rows, 1] - (src_centres[cols, 1] + src_half[cols, 1] * pts[j])) ** 2
            near += (wi * wj) * layer_correction(np.sqrt(dx2 + dz2) / h, sample.base,
                                                 sample.poisson_ratio)
    out[rows, cols] = near * scale * area[cols]
    return out


def _tensor_edges(src_centres: np.ndarray, src_half: np.ndarray):
    """The cell edges (ex, ez) along x and z (mm) of source cells laid out as
    :func:`mesh_punches` lays out one face (a tensor grid, x major), or None when they are
    not: checked by rebuilding every cell's centre and half edge from them (to 1e-12 of the
    face)."""
    n = len(src_centres)
    nz = int(np.argmax(src_centres[:, 0] != src_centres[0, 0])) or n
    if nz < 1 or n % nz:
        return None
    nx = n // nz
    lo, hi = src_centres - src_half, src_centres + src_half
    ex = np.append(lo[::nz, 0], hi[-1, 0])
    ez = np.append(lo[:nz, 1], hi[nz - 1, 1])
    cx, hx = np.repeat((ex[1:] + ex[:-1]) / 2, nz), np.repeat(np.diff(ex) / 2, nz)
    cz, hz = np.tile((ez[1:] + ez[:-1]) / 2, nx), np.tile(np.diff(ez) / 2, nx)
    size = 1e-12 * float(max(ex[-1] - ex[0], ez[-1] - ez[0]))
    rebuilt = np.column_stack([cx, cz, hx, hz])
    if not np.allclose(rebuilt, np.hstack([src_centres, src_half]), rtol=0, atol=size):
        return None
    return ex, ez


def _love_on_edges(centres: np.ndarray, ex: np.ndarray, ez: np.ndarray) -> np.ndarray:
    """:func:`rectangle_inverse_distance_integral` at ``centres`` over every cell of the
    tensor grid of edges ``ex`` x ``ez``, shape (n, cells) in x-major order (mm): the
    corner primitive once per grid node, each cell's integral the difference across its
    four corners (a node is the corner of up to four cells: four times fewer primitives)."""
    u = ex[None, :, None] - centres[:, 0, None, None]
    v = ez[None, None, :] - centres[:, 1, None, None]
    f = _corner_primitive(u, v)  # u and v on their own axes (see there)
    cells = f[:, 1:, 1:] - f[:, :-1, 1:] - f[:, 1:, :-1] + f[:, :-1, :-1]
    return cells.reshape(len(centres), -1)


def _influence_block(centres: np.ndarray, src_centres: np.ndarray, src_half: np.ndarray,
                     sample: Sample, n_gauss: int) -> np.ndarray:
    """Displacement at ``centres`` per unit pressure on the source cells (mm/MPa)."""
    edges = _tensor_edges(src_centres, src_half)
    if edges is not None:
        scale = (1.0 - sample.poisson_ratio ** 2) / (np.pi * sample.youngs_modulus_MPa)
        a = scale * _love_on_edges(centres, *edges)
    else:
        x1, x2 = src_centres[:, 0] - src_half[:, 0], src_centres[:, 0] + src_half[:, 0]
        z1, z2 = src_centres[:, 1] - src_half[:, 1], src_centres[:, 1] + src_half[:, 1]
        a = love_rectangle_displacement(centres[:, None, 0], centres[:, None, 1], x1[None, :],
                                        x2[None, :], z1[None, :], z2[None, :], 1.0,
                                        sample.youngs_modulus_MPa, sample.poisson_ratio)
    if sample.thickness_mm is None:
        return a
    if sample.base == "steinbrenner":
        return a - _layer_depth_term(centres, src_centres, src_half, sample, n_gauss)
    return a - _layer_kernel_term(centres, src_centres, src_half, sample, n_gauss, a)


#: Cell coordinates are compared to this (mm) when two punch pairs share one block.
_BLOCK_KEY_MM = 1e-9
#: Bytes of influence blocks kept across meshes (:func:`kept_block`): the self and
#: same-row blocks of an array recur from one design to the next.
BLOCK_CACHE_BYTES = 256 * 2 ** 20


def _block_key(local: np.ndarray, half_a: np.ndarray, src: np.ndarray,
               half_b: np.ndarray) -> tuple:
    return tuple(np.round(arr / _BLOCK_KEY_MM).astype(np.int64).tobytes()
                 for arr in (local, half_a, src, half_b))


class _BlockCache:
    """Influence blocks keyed by their exact inputs, least recently used dropped first past
    :data:`BLOCK_CACHE_BYTES` (locked: a threaded Dask worker shares it)."""

    def __init__(self, budget_bytes: int):
        import threading
        from collections import OrderedDict

        self.budget = budget_bytes
        self.kept: OrderedDict = OrderedDict()
        self.bytes = 0
        self.hits = self.misses = 0
        self.lock = threading.Lock()

    def get(self, key):
        with self.lock:
            block = self.kept.get(key)
            if block is not None:
                self.kept.move_to_end(key)
                self.hits += 1
            return block

    def put(self, key, block: np.ndarray) -> None:
        block.setflags(write=False)
        with self.lock:
            self.misses += 1
            if key not in self.kept:
                self.bytes += block.nbytes
            self.kept[key] = block
            while self.bytes > self.budget and len(self.kept) > 1:
                _, dropped = self.kept.popitem(last=False)
                self.bytes -= dropped.nbytes

    def clear(self) -> None:
        with self.lock:
            self.kept.clear()
            self.bytes = self.hits = self.misses = 0


_BLOCKS = _BlockCache(BLOCK_CACHE_BYTES)


def face_block(target: FaceGrid, source: FaceGrid, sample: Sample, n_gauss: int) -> np.ndarray:
    """Displacement at the cells of face ``target`` per unit pressure on those of ``source``
    (mm/MPa), read-only; computed in ``target``'s frame from the faces' shapes and their
    offset alone, and kept across calls: the next design's array has the same faces at the
    same pitch, and a block is the same bits wherever its pair lies.

    Args:
        target, source: the faces and their grids (:class:`FaceGrid`).
        sample: the sample (its E, nu, layer). n_gauss: the layer's quadrature order.

    Returns:
        The block, shape (target's cells, source's cells).
    """
    offset = (source.x_mm - target.x_mm, source.z_mm - target.z_mm)
    key = (sample, n_gauss, target.shape, source.shape, offset)
    block = _BLOCKS.get(key)
    if block is None:
        local, _ = face_cells(*target.shape)
        cells, half = face_cells(*source.shape)
        block = _influence_block(local, cells + np.array(offset), half, sample, n_gauss)
        _BLOCKS.put(key, block)
    return block


def influence_matrix(mesh: CellMesh, sample: Sample,
                     targets: Sequence[int] | None = None,
                     cells: np.ndarray | None = None) -> np.ndarray:
    """Displacement at each cell centre per unit pressure on each cell, shape (n, n) (mm/MPa).

    Half-space: Love's rectangle formula. Layer: that less the layer's correction
    (:func:`layer_correction`) on a bonded or frictionless base, or less the depth-h
    half-space displacement (Steinbrenner's approximation). Assembled punch by punch:
    on :func:`mesh_punches`' grids a block is a function of the two faces and their offset
    (:func:`face_block`, kept across calls); on other cells, two punch pairs whose cells
    lie alike relative to each other share one computed block.

    Args:
        mesh: the cells. sample: the sample.
        targets: the punches whose cells' rows are built, in ascending order (default every
            punch): the rows of the cells :func:`target_cells` lists, in that order.
        cells: the cells whose rows are built (default every cell of ``targets``), in
            the order :func:`built_cells` gives; given, ``targets`` is ignored. A
            symmetric solve reads the rows of its orbits' representatives alone
            (:func:`solve_by_symmetry`): built so, no other row is written or gathered.

    Returns:
        The matrix, shape (rows, n) (mm/MPa): each row the same bits whichever rows are built.

    Raises:
        ContactError: a bad sample.
    """
    check_sample(sample)
    n_gauss = 0
    if sample.thickness_mm is not None:
        cell = float(2 * mesh.half.max())
        n_gauss = int(min(12, max(3, np.ceil(4 * cell / sample.thickness_mm))))
    punches = np.unique(mesh.punch)
    owners = [_as_slice(np.flatnonzero(mesh.punch == k)) for k in punches]
    if cells is None:
        wanted = punches if targets is None else np.asarray(targets)
        picks = [slice(None)] * len(wanted)
    else:
        wanted, picks = _picked_rows(mesh, punches, owners, np.asarray(cells))
    out = np.empty((sum(_picked_size(owners[int(np.searchsorted(punches, a))], pick)
                        for a, pick in zip(wanted, picks)), len(mesh.punch)))
    done: dict[tuple, np.ndarray] = {}
    row = 0
    for a, pick in zip(wanted, picks):
        ia = owners[int(np.searchsorted(punches, a))]
        size = _picked_size(ia, pick)
        rows = slice(row, row + size)
        row += size
        for b, ib in zip(punches, owners):
            if mesh.face_grids is not None:
                block = face_block(mesh.face_grids[a], mesh.face_grids[b], sample, n_gauss)
            else:
                block = _shared_block(mesh, ia, ib, sample, n_gauss, done)
            block = block[pick]
            if isinstance(ib, slice):
                out[rows, ib] = block
            else:
                out[rows, _as_index(ib)] = block
    return out


def _picked_rows(mesh: CellMesh, punches: np.ndarray, owners: list,
                 cells: np.ndarray) -> tuple[np.ndarray, list]:
    """The punches holding ``cells`` and, for each, which of its own cells they are.

    Args:
        mesh: the cells. punches: the punch indices, ascending. owners: each punch's cells
            (a slice or an index array, :func:`_as_slice`). cells: cell indices.

    Returns:
        (the punches, ascending; per punch a slice of every cell or an index array of the
        picked cells' places among its own).
    """
    wanted = np.unique(mesh.punch[cells])
    picks = []
    for a in wanted:
        own = _as_index(owners[int(np.searchsorted(punches, a))])
        place = np.flatnonzero(np.isin(own, cells))
        picks.append(slice(None) if len(place) == len(own) else place)
    return wanted, picks


def _picked_size(owner, pick) -> int:
    """Rows :func:`influence_matrix` builds for a punch of cells ``owner`` picked by ``pick``."""
    return _size(owner) if isinstance(pick, slice) else len(pick)


def _shared_block(mesh: CellMesh, ia, ib, sample: Sample, n_gauss: int,
                  done: dict[tuple, np.ndarray]) -> np.ndarray:
    """The block of cells ``ia`` from cells ``ib`` in ``ia``'s first cell's frame, shared
    with an earlier pair of ``done`` whose cells lie alike (to :data:`_BLOCK_KEY_MM`)."""
    origin = mesh.centres[ia][0]
    local = mesh.centres[ia] - origin
    src = mesh.centres[ib] - origin
    key = _block_key(local, mesh.half[ia], src, mesh.half[ib])
    block = done.get(key)
    if block is None:
        block = done[key] = _influence_block(local, src, mesh.half[ib], sample, n_gauss)
    return block


def built_cells(mesh: CellMesh, cells: np.ndarray) -> np.ndarray:
    """The cells whose rows :func:`influence_matrix` builds when asked for ``cells``, in
    the order of its rows: punch by punch, each punch's in the mesh's order.

    Args:
        mesh: the cells. cells: cell indices.

    Returns:
        Cell indices, shape (len(unique cells),).
    """
    every = target_cells(mesh, np.unique(mesh.punch[np.asarray(cells)]))
    return every[np.isin(every, cells)]


def _size(index) -> int:
    return index.stop - index.start if isinstance(index, slice) else len(index)


def target_cells(mesh: CellMesh, targets: Sequence[int]) -> np.ndarray:
    """The cells of some punches: the rows :func:`influence_matrix` builds for them.

    Args:
        mesh: the cells. targets: punch indices, ascending.

    Returns:
        Cell indices, punch by punch.
    """
    return np.concatenate([np.flatnonzero(mesh.punch == k) for k in targets])


def _as_slice(index: np.ndarray):
    """``index`` as a slice where it is a contiguous ascending run (a punch's cells as
    :func:`mesh_punches` lays them out; a block is then written without fancy indexing)."""
    if index.size and index[-1] - index[0] + 1 == index.size:
        return slice(int(index[0]), int(index[-1]) + 1)
    return index


def _as_index(index) -> np.ndarray:
    return np.arange(index.start, index.stop) if isinstance(index, slice) else index


@dataclass(frozen=True, eq=False)
class PunchSolution:
    """Rigid punches on the sample.

    Attributes:
        stiffness_N_per_mm: punch stiffness matrix S, forces = S displacements, shape (m, m).
        compliance_mm_per_N: C = S⁻¹, displacements = C forces, shape (m, m).
        cell_pressure_MPa: cell pressures for a unit displacement of each punch alone, shape (n, m).
        mesh: the cells.
    """

    stiffness_N_per_mm: np.ndarray
    compliance_mm_per_N: np.ndarray
    cell_pressure_MPa: np.ndarray
    mesh: CellMesh


def solve_punches(punches, sample: Sample, cell_mm: float = DEFAULT_CELL_MM,
                  min_cells: int = MIN_CELLS_PER_EDGE) -> PunchSolution:
    """Stiffness and compliance matrices of rigid flat punches on the sample (N/mm, mm/N).

    Collocation: A p = B u, with A the influence matrix, B the cell-to-punch
    incidence and u the punch displacements; forces F = Bᵀ diag(area) p.

    The dense algebra runs with BLAS on one thread
    (:func:`~tactcad.mechanics.blas_threads.single_threaded_blas`): its systems of a few
    thousand cells gain little from a second thread, whose idle spinning cost a design
    search's contact solves about three times the CPU time on a shared two-core machine.

    Args:
        punches: sequence of :class:`Punch` (m >= 1), non-overlapping faces.
        sample: :class:`Sample`.
        cell_mm: target cell edge (mm), > 0.
        min_cells: fewest cells along a face edge.

    Returns:
        :class:`PunchSolution`.

    Raises:
        ContactError: bad punch, sample or cell size.
    """
    mesh = mesh_punches(punches, cell_mm, min_cells)
    maps = mirror_maps(mesh)
    # the symmetric solve reads only the rows of the cells that represent their mirror
    # orbits: those rows are all that is built
    rows = built_cells(mesh, representatives(maps, len(mesh.punch)))
    a = influence_matrix(mesh, sample, cells=rows)
    incidence = np.zeros((len(mesh.punch), len(punches)))
    incidence[np.arange(len(mesh.punch)), mesh.punch] = 1.0
    with single_threaded_blas():
        pressure = solve_by_symmetry(a, incidence, maps, rows)
        stiffness = incidence.T @ (mesh.area_mm2[:, None] * pressure)
        stiffness = 0.5 * (stiffness + stiffness.T)  # symmetric by reciprocity; remove round-off
        compliance = np.linalg.inv(stiffness)
    return PunchSolution(stiffness, compliance, pressure, mesh)


def mirror_maps(mesh: CellMesh, tol_mm: float = 1e-9) -> list[np.ndarray]:
    """The mesh's mirror symmetries about its centre lines along x and along z: for each
    line the cells hold, the index of every cell's mirror image (an involution); a line
    some cell has no image across (unequal tips, an uneven layout) is left out."""
    lo = (mesh.centres - mesh.half).min(axis=0)
    hi = (mesh.centres + mesh.half).max(axis=0)
    centre = (lo + hi) / 2

    def keys(points: np.ndarray) -> list[bytes]:
        # each cell's (centre, half) in units of tol_mm, as the bytes of its int64 row
        rows = np.round(np.concatenate([points, mesh.half], axis=1) / tol_mm).astype(np.int64)
        raw, width = rows.tobytes(), rows.shape[1] * 8
        return [raw[i:i + width] for i in range(0, len(raw), width)]

    index = {k: i for i, k in enumerate(keys(mesh.centres))}
    maps = []
    for axis in (0, 1):
        image = mesh.centres.copy()
        image[:, axis] = 2 * centre[axis] - image[:, axis]
        found = [index.get(k) for k in keys(image)]
        if None not in found:
            maps.append(np.array(found))
    return maps


def mirror_group(maps: list[np.ndarray], n: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The group the commuting mirrors ``maps`` generate on ``n`` cells, and its characters.

    Args:
        maps: the mirrors (:func:`mirror_maps`), involutions that commute. n: the cells.

    Returns:
        (the elements as index arrays, identity first; the characters, each a sign per
        element in that order).
    """
    group = [np.arange(n)]
    for m in maps:  # the mirrors commute: 2 or 4 elements
        group += [m[g] for g in group]
    signs = [np.array([1.0])]
    for _ in maps:
        signs = [np.concatenate([s, t * s]) for s in signs for t in (1.0, -1.0)]
    return group, signs


def representatives(maps: list[np.ndarray], n: int) -> np.ndarray:
    """The cells that represent their orbits under the mirrors: the least index of each.

    Args:
        maps: the mirrors (:func:`mirror_maps`). n: the cells.

    Returns:
        Their indices, ascending; every cell without ``maps``.
    """
    group, _ = mirror_group(maps, n)
    return np.flatnonzero(np.stack(group).min(axis=0) == np.arange(n))


def signed_sum(signs: np.ndarray, arrays: list[np.ndarray]) -> np.ndarray:
    """sum(s * a) over signs of +-1 and equal-shaped arrays, in their order, added or
    subtracted in place: the same bits as the products' sum, a quarter of the memory passes.

    Args:
        signs: +1 or -1 per array. arrays: equal shapes.

    Returns:
        The sum, a new array.
    """
    out = arrays[0] * signs[0]
    for sign, array in zip(signs[1:], arrays[1:]):
        if sign > 0:
            out += array
        else:
            out -= array
    return out


def solve_by_symmetry(a: np.ndarray, rhs: np.ndarray, maps: list[np.ndarray],
                      rows: np.ndarray | None = None) -> np.ndarray:
    """``solve(a, rhs)`` for a matrix that commutes with the cell permutations ``maps``
    (mirror images: commuting involutions), one smaller system per character of their group.

    For a character chi (a sign per mirror) and orbit representatives r, r' (cells
    whose stabiliser chi is 1 on), A_chi[r, r'] = sum_g chi(g) A[r, g r'] / |Stab r'| and
    b_chi[r] = sum_g chi(g) b[g r] / |G|; the solution is x at r and chi(g) x at g r. Two
    mirrors split a dense n x n solve into four of about n/4 (about 16 times less work).
    Without ``maps`` it is ``numpy.linalg.solve``.

    Args:
        a: (n, n) with ``a[g i, g j] == a[i, j]`` for every map g; or, with ``rows``, the
            rows of ``a`` at those cells (they must hold :func:`representatives`).
        rhs: (n, k).
        maps: index arrays of length n (see :func:`mirror_maps`).
        rows: the cell of each row of ``a`` (default: row i is cell i).

    Returns:
        (n, k) solution.
    """
    if not maps:
        return np.linalg.solve(a, rhs)
    n = len(rhs)
    group, signs = mirror_group(maps, n)
    orbits = np.stack(group)  # (|G|, n): g(i)
    reps = np.flatnonzero(orbits.min(axis=0) == np.arange(n))
    at = reps
    if rows is not None:  # the row of a holding each representative
        row_of = np.full(n, -1)
        row_of[np.asarray(rows)] = np.arange(len(rows))
        at = row_of[reps]
    fixed = orbits[:, reps] == reps[None, :]  # (|G|, reps): g fixes the representative
    out = np.zeros((n, rhs.shape[1]))
    # a's rows of the representatives at each image of them, gathered once for all characters
    # (a row take, then column takes: twice as fast as one np.ix_ gather)
    every_row = len(at) == len(a) and np.array_equal(at, np.arange(len(a)))
    rep_rows = a if every_row else a.take(at, axis=0)
    blocks = [rep_rows.take(g[reps], axis=1) for g in group]
    for chi in signs:
        keep = np.all(~fixed | (chi[:, None] > 0), axis=0)
        valid = reps[keep]
        if valid.size == 0:
            continue
        stab = np.sum(orbits[:, valid] == valid[None, :], axis=0)
        part = (lambda b: b) if keep.all() else (lambda b: b[np.ix_(keep, keep)])
        a_chi = signed_sum(chi, [part(b) for b in blocks])
        if np.any(stab != 1):
            a_chi /= stab[None, :]
        b_chi = sum(c * rhs[g[valid]] for c, g in zip(chi, group)) / len(group)
        x = np.linalg.solve(a_chi, b_chi)
        for c, g in zip(chi, group):  # the solution at each image, summed over characters
            out[g[valid]] += c * x / (np.sum(orbits[:, valid] == g[valid][None, :], axis=0)
                                      [:, None])
    return out


#: Cells along every face edge at each level of :func:`converged_punches`.
CONVERGENCE_CELLS = (8, 12, 16, 24, 32)
#: The converged compliances' target: successive extrapolations agree within it.
CONVERGED_REL = 1e-3
#: Most cells a level may have (a dense (n, n) matrix: 6000 cells take 0.3 GB).
MAX_CELLS = 6000
#: Couplings below this are too small to judge the convergence by (far tips: their
#: relative change is large while what they add to a tip's travel is not).
JUDGED_COUPLING = 0.01
#: The order the graded cells converge at (observed: the macro array's C12/C11 over 8 ...
#: 48 cells per edge; successive extrapolations agree to 0.02 %).
GRADED_ORDER = 2.0


@dataclass(frozen=True, eq=False)
class ConvergedPunches:
    """Rigid punches solved on a sequence of graded meshes and extrapolated.

    Attributes:
        compliance_mm_per_N: the extrapolated compliance matrix C, shape (m, m) (mm/N).
        stiffness_N_per_mm: S = C⁻¹, shape (m, m) (N/mm).
        error_rel: the last change of the extrapolation (the largest relative change of a
            compliance's diagonal or of a coupling C_ij/C_ii >= :data:`JUDGED_COUPLING`);
            where the cell budget held only two levels, the one extrapolation's change from
            the finer level (Richardson's correction, an upper estimate).
        cells_per_edge: the levels solved (cells along each face edge).
        converged: ``error_rel`` within the asked tolerance (else the cell budget ran out).
    """

    compliance_mm_per_N: np.ndarray
    stiffness_N_per_mm: np.ndarray
    error_rel: float
    cells_per_edge: tuple[int, ...]
    converged: bool


def _extrapolated(coarse: np.ndarray, fine: np.ndarray, ratio: float) -> np.ndarray:
    return fine + (fine - coarse) / (ratio ** GRADED_ORDER - 1.0)


def _change_rel(before: np.ndarray, after: np.ndarray) -> float:
    """The largest relative change of a diagonal entry or of a judged coupling C_ij/C_ii."""
    d0, d1 = np.diag(before), np.diag(after)
    change = np.abs(d1 / d0 - 1.0)
    k0, k1 = before / d0[:, None], after / d1[:, None]
    judged = np.abs(k1) >= JUDGED_COUPLING
    couplings = np.abs(k1[judged] / k0[judged] - 1.0)
    return float(max(change.max(), couplings.max(initial=0.0)))


def converged_punches(punches, sample: Sample, rtol: float = CONVERGED_REL,
                      max_cells: int = MAX_CELLS) -> ConvergedPunches:
    """Compliance of rigid flat punches converged in the mesh (mm/N, N/mm).

    Solves on graded meshes of :data:`CONVERGENCE_CELLS` cells per face edge, extrapolates
    each successive pair (Richardson, order :data:`GRADED_ORDER`) and stops when two
    extrapolations agree within ``rtol`` or the next level would exceed ``max_cells``.

    Args:
        punches: sequence of :class:`Punch` (m >= 1), non-overlapping faces.
        sample: :class:`Sample`.
        rtol: relative agreement asked of two successive extrapolations (> 0).
        max_cells: the largest mesh solved (at least the first two levels are).

    Returns:
        :class:`ConvergedPunches`.

    Raises:
        ContactError: bad punch, sample or tolerance.
    """
    _check_punches(punches)
    if not (np.isfinite(rtol) and rtol > 0):
        raise ContactError("rtol", rtol, "> 0")
    coarse_mm = 10.0 * max(max(p.width_x_mm, p.depth_z_mm) for p in punches)
    levels: list[tuple[int, np.ndarray]] = []
    extrapolations: list[np.ndarray] = []
    change = float("inf")
    for n in CONVERGENCE_CELLS:
        if len(levels) >= 2 and n * n * len(punches) > max_cells:
            break
        sol = solve_punches(list(punches), sample, coarse_mm, n)
        if levels:
            previous_n, previous = levels[-1]
            extrapolations.append(_extrapolated(previous, sol.compliance_mm_per_N, n / previous_n))
        levels.append((n, sol.compliance_mm_per_N))
        if len(extrapolations) >= 2:
            change = _change_rel(extrapolations[-2], extrapolations[-1])
            if change <= rtol:
                break
    if len(extrapolations) == 1:  # the cell budget held two levels: the correction's size
        change = _change_rel(levels[-1][1], extrapolations[-1])
    best = extrapolations[-1]
    best = 0.5 * (best + best.T)
    return ConvergedPunches(best, np.linalg.inv(best), change, tuple(n for n, _ in levels),
                            len(extrapolations) >= 2 and change <= rtol)


def single_punch_compliance(width_x_mm: float, depth_z_mm: float, sample: Sample,
                            cell_mm: float = DEFAULT_CELL_MM,
                            min_cells: int = MIN_CELLS_PER_EDGE) -> float:
    """Compliance of one rigid rectangular punch alone on the sample (mm/N)."""
    sol = solve_punches([Punch(0.0, 0.0, width_x_mm, depth_z_mm)], sample, cell_mm, min_cells)
    return float(sol.compliance_mm_per_N[0, 0])


def modulus_from_punch_stiffness(k_obj_N_per_mm: float, width_x_mm: float, depth_z_mm: float,
                                 poisson_ratio: float, thickness_mm: float | None = None,
                                 base: str = DEFAULT_BASE) -> float:
    """Young's modulus E (MPa) of a sample whose single-punch stiffness is K_obj.

    The paper measures K_obj with a 2 x 3 mm flat indenter; the compliance of
    one punch scales as 1/E, so E = K_obj C(E = 1), C converged in the mesh
    (:func:`converged_punches`).

    Raises:
        ContactError: K_obj <= 0 or another input out of range.
    """
    if not (np.isfinite(k_obj_N_per_mm) and k_obj_N_per_mm > 0):
        raise ContactError("K_obj_N_per_mm", k_obj_N_per_mm, "> 0 N/mm")
    return float(k_obj_N_per_mm * single_punch_unit_compliance(
        float(width_x_mm), float(depth_z_mm), float(poisson_ratio), thickness_mm, base))


def single_punch_unit_compliance(width_x_mm: float, depth_z_mm: float, poisson_ratio: float,
                                 thickness_mm: float | None = None,
                                 base: str = DEFAULT_BASE) -> float:
    """Compliance of one rigid face alone at E = 1 MPa (mm/N), converged in the mesh
    (:func:`unit_punch_compliance`, whose cache serves it: samples differ only in E).

    Raises:
        ContactError: a face edge <= 0 or a bad sample.
    """
    return float(unit_punch_compliance((Punch(0.0, 0.0, width_x_mm, depth_z_mm),),
                                       poisson_ratio, thickness_mm, base)[0, 0])


#: The kind the result store keeps a converged solve under (:func:`tactcad.store.kept_result`):
#: one for every caller (the grasp, the rig models, the budget), so each reads the others'.
CONVERGED_KIND = "converged punches"


@kept_per_process(maxsize=64)
def _converged_unit(punches: tuple[Punch, ...], poisson_ratio: float,
                    thickness_mm: float | None, base: str) -> ConvergedPunches:
    """The punches converged at E = 1 MPa, kept per process and in the result store of
    :func:`tactcad.store.keeping_results` (a command's ``--cache``): a later run (the grasp
    again, verify, the budget) reads a solve back instead of solving it afresh."""
    unit = Sample(1.0, poisson_ratio, thickness_mm, base)
    return kept_result(CONVERGED_KIND,
                       lambda: converged_punches(list(punches), unit, CONVERGED_REL),
                       tuple(punches), unit, CONVERGED_REL)


def unit_punch_compliance(punches, poisson_ratio: float, thickness_mm: float | None = None,
                          base: str = DEFAULT_BASE) -> np.ndarray:
    """The punches' compliance matrix at E = 1 MPa (mm/N), shape (m, m), converged in the
    mesh (:func:`converged_punches`); every compliance scales as 1/E. Cached: the rig
    models, the budget and the grasp ask the same tips at many K_obj.

    Args:
        punches: the faces (:class:`Punch`).
        poisson_ratio: ν, 0 ... 0.5.
        thickness_mm: the layer's thickness h (mm), or None for a half-space.
        base: the layer's base, one of :data:`BASES` (a half-space has none).

    Raises:
        ContactError: bad punches or sample.
    """
    check_base(base)
    if thickness_mm is None:  # a half-space: one cache entry whatever base is named
        base = DEFAULT_BASE
    return _converged_unit(tuple(punches), float(poisson_ratio), thickness_mm, base) \
        .compliance_mm_per_N.copy()
