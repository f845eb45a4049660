"""The bonded gauge as a layer on the element: the glue line and carrier between the
flat top face over the notch and the grid, which stiffens the web and lifts the grid off
the face.

The layer is one region of the gauge installation's stated modulus
(:attr:`~tactcad.design.readout_section.ReadoutChain.gauge_backing_modulus_MPa`) and
height (face to grid plane, :attr:`~tactcad.design.readout_section.ReadoutChain.
grid_height_mm`), as long as the carrier (the grid plus
:data:`~tactcad.design.readout_section.CARRIER_SIDE_MM` at each end, centred over the
notch) and as wide as the carrier across the sheet
(:func:`~tactcad.design.readout_section.carrier_width_mm`). The plane and 3D models
spread it over the sheet's thickness with its modulus scaled by width / sheet, which
keeps its axial and bending stiffness about the web (a plane-stress region of the
carrier's own thickness, as a finite-element code with a section thickness per region
would model it).

The closed form's layer term (:func:`layer_compliance_change`) is the unit-load integral
of the layer's change of the section's bending flexibility over the carrier; its moments
in u depend on the web and notch radius alone for one element family, so large vectorised
calls (design searches, ``tactcad bench closed-form``) read them from a table built once
from the Gauss-Legendre quadrature, which stays the reference for everything else.

Units: mm, MPa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from tactcad.design.array_plan import ElementGeometry

#: Poisson's ratio of the layer: polyimide film (DuPont Kapton HN datasheet: 0.34) and
#: epoxy adhesives (0.33-0.38); the layer's K rise is insensitive to it (a thin soft layer
#: bent with the web acts through its axial stiffness).
LAYER_POISSON_RATIO = 0.35


@dataclass(frozen=True)
class BondedLayer:
    """The gauge's glue line and carrier on an element's top face (element frame, mm, MPa).

    Attributes:
        x0_mm, x1_mm: the carrier's ends along the element (x0 < x1).
        grid_x0_mm, grid_x1_mm: the grid's ends (inside the carrier).
        face_y_mm: the top face it is bonded to (y).
        height_mm: face to grid plane (glue line and carrier), > 0.
        modulus_MPa: the layer's Young's modulus, > 0.
        width_mm: the carrier's width across the sheet (<= the sheet).
        poisson_ratio: :data:`LAYER_POISSON_RATIO`.
    """

    x0_mm: float
    x1_mm: float
    grid_x0_mm: float
    grid_x1_mm: float
    face_y_mm: float
    height_mm: float
    modulus_MPa: float
    width_mm: float
    poisson_ratio: float = LAYER_POISSON_RATIO

    @property
    def grid_plane_y_mm(self) -> float:
        """y of the grid: the layer's top (mm)."""
        return self.face_y_mm + self.height_mm

    @property
    def grid_length_mm(self) -> float:
        return self.grid_x1_mm - self.grid_x0_mm

    def box(self, x_min_mm: float | None = None) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1) of the layer's rectangle in the element's plane (mm), its back
        end cut at ``x_min_mm`` (a model's clamp line) where it lies behind it."""
        x0 = self.x0_mm if x_min_mm is None else max(self.x0_mm, x_min_mm)
        return (x0, self.face_y_mm, self.x1_mm, self.grid_plane_y_mm)

    def modulus_over_sheet_MPa(self, sheet_mm: float) -> float:
        """The layer's modulus spread over the sheet's thickness: E_l w_l / b (MPa)."""
        return self.modulus_MPa * self.width_mm / sheet_mm


def bonded_layer(g: ElementGeometry, grid_length_mm: float, grid_width_mm: float,
                 grid_height_mm: float, modulus_MPa: float) -> BondedLayer:
    """The layer of a gauge whose grid (length along the element, width across it, mm) is
    centred over ``g``'s notch, ``grid_height_mm`` above the face, of modulus
    ``modulus_MPa`` (the read-out section's
    :attr:`~tactcad.design.readout_section.ReadoutChain` values).

    Raises:
        ValueError: a length, width, height or modulus not > 0.
    """
    from tactcad.design.readout_section import CARRIER_SIDE_MM, carrier_width_mm

    for name, value in (("grid_length_mm", grid_length_mm), ("grid_width_mm", grid_width_mm),
                        ("grid_height_mm", grid_height_mm), ("modulus_MPa", modulus_MPa)):
        if not value > 0:
            raise ValueError(f"{name} = {value!r}: allowed > 0")
    half = grid_length_mm / 2
    return BondedLayer(x0_mm=g.hinge_x_mm - half - CARRIER_SIDE_MM,
                       x1_mm=g.hinge_x_mm + half + CARRIER_SIDE_MM,
                       grid_x0_mm=g.hinge_x_mm - half, grid_x1_mm=g.hinge_x_mm + half,
                       face_y_mm=g.base_height_mm, height_mm=grid_height_mm,
                       modulus_MPa=modulus_MPa,
                       width_mm=carrier_width_mm(grid_width_mm, g.sheet_thickness_mm))


def layer_of(g: ElementGeometry) -> BondedLayer | None:
    """The layer of the gauge ``g`` carries (:attr:`~tactcad.partlib.array.element.
    ElementGeometry.gauge`), or None for a bare element."""
    s = g.gauge
    if s is None:
        return None
    return bonded_layer(g, s.grid_length_mm, s.grid_width_mm, s.height_mm, s.modulus_MPa)


def chain_layer(g: ElementGeometry, chain) -> BondedLayer:
    """The layer of the read-out chain's gauge (:class:`~tactcad.design.readout_section.
    ReadoutChain`: grid length and width, grid height, the installation's modulus) on ``g``."""
    return bonded_layer(g, chain.grid_length_mm, chain.grid_width_mm, chain.grid_height_mm,
                        chain.gauge_backing_modulus_MPa)


def layer_face_factor(g: ElementGeometry, youngs_modulus_MPa: float,
                      layer: BondedLayer | None) -> float:
    """The face strain at the notch centre under ``layer`` over the bare face's, under
    the same moment: the transformed section of ``g``'s web and the layer
    (:func:`tactcad.mechanics.gauge_strain.face_under_layer_factor`; dimensionless, about
    0.89 for the default gauge on the examples' webs); 1 for no layer. The closed form and
    the beam level carry their face strain to the face under the gauge, which fem2d and
    fem3d read with the layer meshed."""
    if layer is None:
        return 1.0
    from tactcad.mechanics.gauge_strain import face_under_layer_factor

    return float(face_under_layer_factor(g.web_thickness_mm, g.sheet_thickness_mm,
                                         youngs_modulus_MPa, layer.height_mm,
                                         layer.modulus_MPa, layer.width_mm))


#: Gauss-Legendre points on each smooth piece of the covered span (the reference quadrature).
_GAUSS_POINTS = 24


def _flexibility_change(h, sheet_mm, youngs_modulus_MPa, layer_height_mm, layer_modulus_MPa,
                        layer_width_mm):
    """g(h) = 1 / EI_c - 1 / EI_0 of the section of height h under the layer (1/(N mm^2),
    <= 0; broadcast): 12 / (E b h^3) (1 / (1 + s) - 1), s the layer's rise of EI
    (:func:`tactcad.mechanics.gauge_strain.transformed_section`)."""
    from tactcad.mechanics.gauge_strain import transformed_section

    rise = transformed_section(h, sheet_mm, youngs_modulus_MPa, layer_height_mm,
                               layer_modulus_MPa, layer_width_mm)[1]
    return 12.0 / (youngs_modulus_MPa * sheet_mm * h ** 3) * (1.0 / (1.0 + rise) - 1.0)


def _layer_moments_quadrature(web_mm, notch_radius_mm, sheet_mm, youngs_modulus_MPa,
                              base_height_mm, arm_height_mm, hinge_offsets_mm, layer_height_mm,
                              layer_modulus_MPa, layer_width_mm) -> np.ndarray:
    """(I0, I1, I2), I_k = int u^k g(h(u)) du over the carrier (:func:`_flexibility_change`),
    stacked on a leading axis of 3 (:func:`layer_compliance_change_quadrature`)."""
    from tactcad.mechanics.notch_profile import notch_integral

    b, E, wl = np.broadcast_arrays(*(np.asarray(v, float)[..., None] for v in (
        sheet_mm, youngs_modulus_MPa, layer_width_mm)))
    u0, u1 = hinge_offsets_mm

    def moments(u, h):
        g = _flexibility_change(h, b, E, layer_height_mm, layer_modulus_MPa, wl)
        return np.stack((g, u * g, u * u * g))

    return notch_integral(u0, u1, web_mm, notch_radius_mm, base_height_mm, arm_height_mm,
                          moments, _GAUSS_POINTS)


def layer_compliance_change_quadrature(web_mm, notch_radius_mm, arm_length_mm, sheet_mm,
                                       youngs_modulus_MPa, base_height_mm, arm_height_mm,
                                       hinge_offsets_mm: tuple[float, float],
                                       layer_height_mm: float, layer_modulus_MPa: float,
                                       layer_width_mm) -> np.ndarray:
    """:func:`layer_compliance_change` by quadrature: the reference (mm/N, <= 0).

    dC = a^2 I0 - 2 a I1 + I2 with I_k = int u^k g(h(u)) du over the carrier (u from the
    notch centre, a the arm length), g(h) = 1 / EI_c(h) - 1 / EI_0(h) the change of the
    bending flexibility of the section of height h under the flat top face (EI_0 = E b h^3
    / 12, EI_c = EI_0 (1 + s) of the transformed section,
    :func:`tactcad.mechanics.gauge_strain.transformed_section`), Gauss-Legendre with
    :data:`_GAUSS_POINTS` points on each smooth piece of the span
    (:func:`tactcad.mechanics.notch_profile.notch_integral`). Arguments as
    :func:`layer_compliance_change`.
    """
    i0, i1, i2 = _layer_moments_quadrature(web_mm, notch_radius_mm, sheet_mm,
                                           youngs_modulus_MPa, base_height_mm, arm_height_mm,
                                           hinge_offsets_mm, layer_height_mm,
                                           layer_modulus_MPa, layer_width_mm)
    a = np.asarray(arm_length_mm, float)
    return a * a * i0 - 2.0 * a * i1 + i2


#: The table's domain (mm; its nodes reach a little beyond): webs and notch radii inside it,
#: on a symmetric carrier, take the table (:class:`_MomentTable`), others the quadrature.
#: It holds the benchmark's designs (webs 0.15-0.4 mm, radii web-2 mm) and the shipped
#: examples' (webs 78-250 um, radii 0.3-0.5 mm).
TABLE_WEB_RANGE_MM = (0.04, 0.8)
TABLE_RADIUS_RANGE_MM = (0.04, 4.0)
#: The table's nodes per octave of t and of its radius coordinate (:class:`_MomentTable`):
#: 2^5, spaced 1/64 to 1/32 in ln.
TABLE_OCTAVE_BITS = 5
#: Calls of fewer elements than this take the quadrature (a table costs about 0.1 s to
#: build, once per element family, modulus and layer; the quadrature 2 us an element).
TABLE_MIN_ELEMENTS = 4096
#: The table's largest error in K against the quadrature over its domain, stated
#: (tests/mechanics/test_bonded_layer.py measures it on the benchmark's designs and on the
#: examples' elements with webs and radii +-30 %: at most about 4e-5, at the grasper's
#: thinnest webs, whose K the layer raises by up to 75 %).
TABLE_K_ERROR_REL = 1e-4

_MANTISSA_BITS = 52  # IEEE 754 double


def _octave_cells(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(k, f) of v > 0 (float64) on a grid of 2^TABLE_OCTAVE_BITS cells per octave,
    uniform in v within each octave: k the cell's key (the float's exponent and leading
    mantissa bits, rising with v), f in [0, 1) the position in the cell (the rest of the
    mantissa). A log-spaced grid without a logarithm: two integer operations."""
    shift = _MANTISSA_BITS - TABLE_OCTAVE_BITS
    bits = v.view(np.int64)
    rest = (bits & ((1 << shift) - 1)).astype(float)
    rest *= 2.0 ** -shift
    return bits >> shift, rest


def _octave_nodes(lo: float, hi: float) -> tuple[int, np.ndarray]:
    """(key of the first node, node values) of the grid of :func:`_octave_cells` from the
    node at or below ``lo`` to the node above ``hi``."""
    k0 = int(_octave_cells(np.array([lo]))[0][0])
    k1 = int(_octave_cells(np.array([hi]))[0][0]) + 1
    keys = np.arange(k0, k1 + 1)
    shift = _MANTISSA_BITS - TABLE_OCTAVE_BITS
    return k0, (keys << shift).view(np.float64)


class _MomentTable:
    """I0 and I2 of :func:`layer_compliance_change_quadrature` on a grid over (t, R), for
    one sheet, modulus, base and arm height, layer, and a carrier symmetric about the notch
    centre (-c ... c); bilinear between the nodes. I1 is exact: on a symmetric carrier the
    notch's share of it is nil (h is even in u), and the flat pieces' is
    (g(h_a) - g(h_b)) (c^2 - R^2) / 2 for R < c.

    Coordinates: t, and Y = R / c + sqrt(max((R / c)^2 - 1, 0)), i.e. R / c while the notch
    lies inside the carrier (R <= c) and exp(arccosh(R / c)) once the carrier clips it:
    there the moments go as sqrt(R - c), which Y makes smooth, and R = c (Y = 1, the kink
    between the two) is a node. Both on grids of :data:`TABLE_OCTAVE_BITS` (32 nodes an
    octave, :func:`_octave_cells`). Values: I0 t^3 / sqrt(R) (the web's 1/t^3 peak over
    a width sqrt(t R) taken out) and I2 / I0, the flat pieces included. The bilinear
    error in I0 is about 1e-4 relative at most, in I2 / I0 a few 1e-4, which enters dC
    over a^2 + I2 / I0 at a few per cent at most; in K about 4e-5 at most
    (:data:`TABLE_K_ERROR_REL`).
    """

    def __init__(self, sheet_mm, youngs_modulus_MPa, base_height_mm, arm_height_mm, half_mm,
                 layer_height_mm, layer_modulus_MPa, layer_width_mm):
        from tactcad.mechanics.notch_profile import gauss_legendre, notched_height_mm

        (t_lo, t_hi), (r_lo, r_hi) = TABLE_WEB_RANGE_MM, TABLE_RADIUS_RANGE_MM
        c = half_mm
        self.inv_half, self.half2 = 1.0 / c, c * c
        self.kx0, web = _octave_nodes(t_lo, t_hi)
        self.ky0, y = _octave_nodes(r_lo / c, (r_hi + math.sqrt(max(r_hi ** 2 - c * c, 0.0)))
                                    / c)
        self.ny = y.size
        radius = c * np.where(y <= 1.0, y, (y * y + 1.0) / (2.0 * y))
        # inside: a node at or below and one above in each direction (R a hair inside:
        # Y is R's image under rounding)
        self.t_range = (web[0], web[-1])
        self.r_range = (radius[0] * (1 + 1e-12), radius[-1] * (1 - 1e-12))
        t, R = np.meshgrid(web, radius, indexing="ij")

        def g(h):
            return _flexibility_change(h, sheet_mm, youngs_modulus_MPa, layer_height_mm,
                                       layer_modulus_MPa, layer_width_mm)

        # the notch piece as the quadrature takes it (its Gauss-Legendre rule on -w ... w,
        # w = min(R, c)), the flat pieces exactly (g constant; the rule is exact there too)
        nodes, weights = gauss_legendre(_GAUSS_POINTS)
        w = np.minimum(R, c)
        u = w[..., None] * nodes
        gu = g(notched_height_mm(u, t[..., None], R[..., None], base_height_mm, arm_height_mm))
        gb, ga = g(base_height_mm), g(arm_height_mm)
        i0 = w * (gu @ weights) + (gb + ga) * np.maximum(c - R, 0.0)
        i2 = w * ((u * u * gu) @ weights) + (gb + ga) * np.maximum(c ** 3 - R ** 3, 0.0) / 3.0
        self.i0_scaled = np.ascontiguousarray((i0 * t ** 3 / np.sqrt(R)).ravel())
        self.i2_over_i0 = np.ascontiguousarray((i2 / i0).ravel())
        self.i1_flat = 0.5 * float(ga - gb)

    def covers(self, t: np.ndarray, R: np.ndarray) -> np.ndarray:
        """True where (t, R) lies inside the nodes."""
        return ((t >= self.t_range[0]) & (t < self.t_range[1])
                & (R >= self.r_range[0]) & (R < self.r_range[1]))

    def change(self, t: np.ndarray, R: np.ndarray, a: np.ndarray) -> np.ndarray:
        """dC = I0 (a^2 + I2 / I0) - 2 a I1 at (t, R) inside the nodes (mm/N)."""
        r = R * self.inv_half
        d2 = r * r
        d2 -= 1.0  # (R^2 - c^2) / c^2
        y = np.maximum(d2, 0.0)
        np.sqrt(y, out=y)
        y += r
        kx, px = _octave_cells(np.ascontiguousarray(t))
        ky, py = _octave_cells(y)
        n00 = kx - self.kx0
        n00 *= self.ny
        n00 += ky
        n00 -= self.ky0
        n01, n10 = n00 + 1, n00 + self.ny
        n11 = n10 + 1
        i0, q = (self._bilinear(v, n00, n01, n10, n11, px, py)
                 for v in (self.i0_scaled, self.i2_over_i0))
        i0 *= np.sqrt(R)
        i0 /= t * t * t
        q += a * a
        q *= i0
        np.minimum(d2, 0.0, out=d2)  # -(c^2 - R^2) / c^2 inside the carrier, else 0
        d2 *= 2.0 * self.i1_flat * self.half2
        d2 *= a
        q += d2  # - 2 a I1
        return q

    @staticmethod
    def _bilinear(values, n00, n01, n10, n11, px, py):
        v00, v01, v10, v11 = (values.take(n) for n in (n00, n01, n10, n11))
        v01 -= v00
        v01 *= py
        v00 += v01  # along y at x_i
        v11 -= v10
        v11 *= py
        v10 += v11  # along y at x_i+1
        v10 -= v00
        v10 *= px
        v00 += v10
        return v00


@functools.lru_cache(maxsize=16)
def _moment_table(*key) -> _MomentTable:
    return _MomentTable(*key)


def layer_compliance_change(web_mm, notch_radius_mm, arm_length_mm, sheet_mm,
                            youngs_modulus_MPa, base_height_mm, arm_height_mm,
                            hinge_offsets_mm: tuple[float, float], layer_height_mm: float,
                            layer_modulus_MPa: float, layer_width_mm) -> np.ndarray:
    """The tip compliance a bonded layer takes away, Euler-Bernoulli, broadcast over arrays
    of element dimensions (mm, MPa; mm/N, <= 0):
    dC = int M(u)^2 / (E I(u)) (1 / (1 + s(u)) - 1) du over the carrier,
    M = 1 N x (a - u) the unit tip force's moment, u from the notch centre,
    I = b h(u)^3 / 12 the section under the flat top face, and s(u) the layer's rise of
    EI on that section (the transformed section,
    :func:`tactcad.mechanics.gauge_strain.transformed_section`).

    The arm length leaves the integral: dC = a^2 I0 - 2 a I1 + I2, I_k = int u^k g(h(u)) du,
    g = 1 / EI_c - 1 / EI_0, and the I_k depend only on (t, R) for one element family,
    modulus and layer. So a call of :data:`TABLE_MIN_ELEMENTS` or more elements on one
    sheet, modulus, base and arm height and layer, with a carrier symmetric about the
    notch centre, reads them from a table over (t, R) built once from the quadrature
    (:class:`_MomentTable`, cached; elements outside :data:`TABLE_WEB_RANGE_MM` x
    :data:`TABLE_RADIUS_RANGE_MM` take the quadrature), within
    :data:`TABLE_K_ERROR_REL` of it in K; every other call (one element, a modulus that
    varies along the arrays) is the quadrature
    (:func:`layer_compliance_change_quadrature`, the reference).

    Args:
        hinge_offsets_mm: the carrier's ends from the notch centre (u0 < u1, mm).
        layer_height_mm, layer_modulus_MPa, layer_width_mm: the layer (mm, MPa, mm).

    Source: the unit-load (Castigliano) compliance of a beam of varying section, e.g.
    Young and Budynas, Roark's Formulas for Stress and Strain, 7th ed., sec. 8.1; the
    transformed section, e.g. Gere and Goodno, Mechanics of Materials, sec. 6.2.
    """
    args = (web_mm, notch_radius_mm, arm_length_mm, sheet_mm, youngs_modulus_MPa,
            base_height_mm, arm_height_mm, hinge_offsets_mm, layer_height_mm,
            layer_modulus_MPa, layer_width_mm)
    table = _table_for(*args)
    if table is None:
        return layer_compliance_change_quadrature(*args)
    t, R, a = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        web_mm, notch_radius_mm, arm_length_mm)))
    # the extremes first: one pass each, where a mask is four
    if (t.min() >= table.t_range[0] and t.max() < table.t_range[1]
            and R.min() >= table.r_range[0] and R.max() < table.r_range[1]):
        return table.change(t, R, a)
    inside = table.covers(t, R)
    out = np.empty(t.shape)
    out[inside] = table.change(t[inside], R[inside], a[inside])
    rest = ~inside
    out[rest] = layer_compliance_change_quadrature(
        t[rest], R[rest], a[rest], *args[3:])
    return out


def _table_for(web_mm, notch_radius_mm, arm_length_mm, sheet_mm, youngs_modulus_MPa,
               base_height_mm, arm_height_mm, hinge_offsets_mm, layer_height_mm,
               layer_modulus_MPa, layer_width_mm) -> _MomentTable | None:
    """The table of a call that can take one (:func:`layer_compliance_change`), else None."""
    if max(np.size(web_mm), np.size(notch_radius_mm), np.size(arm_length_mm)) \
            < TABLE_MIN_ELEMENTS:
        return None
    one = []
    for v in (sheet_mm, youngs_modulus_MPa, base_height_mm, arm_height_mm, layer_height_mm,
              layer_modulus_MPa, layer_width_mm):
        arr = np.asarray(v, float)
        first = float(arr.flat[0]) if arr.size else math.nan
        if arr.size != 1 and not (arr.size and np.all(arr == first)):
            return None
        one.append(first)
    u0, u1 = (float(v) for v in hinge_offsets_mm)
    half = 0.5 * (u1 - u0)
    if not (abs(u0 + u1) <= 1e-9 * half and TABLE_RADIUS_RANGE_MM[0] < half
            < TABLE_RADIUS_RANGE_MM[1]):
        return None
    if not all(math.isfinite(v) and v > 0 for v in one):
        return None
    b, E, hb, ha, hl, El, wl = one
    return _moment_table(b, E, hb, ha, half, hl, El, wl)


def layer_compliance_change_of(g: ElementGeometry, youngs_modulus_MPa: float,
                               layer: BondedLayer) -> float:
    """:func:`layer_compliance_change` of one element and its layer (mm/N, <= 0)."""
    return float(layer_compliance_change(
        g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm, g.sheet_thickness_mm,
        youngs_modulus_MPa, g.base_height_mm, g.arm_height_mm,
        (layer.x0_mm - g.hinge_x_mm, layer.x1_mm - g.hinge_x_mm), layer.height_mm,
        layer.modulus_MPa, layer.width_mm))


#: The closed form's layer term against fem3d with the layer meshed (the K rise, relative
#: to it): -5.6 % (macro array, 4 mm element), +2.2 % (Ti example, 19.6 mm), -7.3 % and
#: +7.5 % (the grasper insert's 2 mm reference and 3 mm measuring element, whose 78 um web
#: the layer stiffens by 34 %); stated as 10 % of the rise
#: (tests/mechanics/test_bonded_layer.py).
CLOSED_FORM_LAYER_ERROR_REL = 0.10
#: The beam level's layer term (its EI raised over the carrier's whole length) against the
#: same: +12.8, +10.2, +16.3 and +15.0 % of the rise (the soft layer's shear lag at the
#: carrier's ends and the notch's plane field are not in a beam); stated as 20 %.
BEAM_LAYER_ERROR_REL = 0.20


def closed_form_layer_k(k_bare_N_per_mm: float, g: ElementGeometry, youngs_modulus_MPa: float,
                        layer: BondedLayer) -> float:
    """K with the layer at the closed-form level: 1 / (1 / K_bare + dC), dC the compliance
    the layer takes away (:func:`layer_compliance_change_of`; N/mm)."""
    return 1.0 / (1.0 / k_bare_N_per_mm + layer_compliance_change_of(g, youngs_modulus_MPa,
                                                                      layer))


def with_gauge_layer(k_bare_N_per_mm, g: ElementGeometry, web_mm, notch_radius_mm,
                     arm_length_mm, youngs_modulus_MPa) -> np.ndarray:
    """Closed-form K with the bonded gauge ``g`` carries, broadcast over candidate webs,
    notch radii, arm lengths and moduli (mm, MPa; the other dimensions ``g``'s):
    1 / (1 / K + dC) (:func:`layer_compliance_change`, the carrier centred over each
    candidate's notch); ``k_bare_N_per_mm`` as it is for a bare ``g`` (N/mm). Calls of
    :data:`TABLE_MIN_ELEMENTS` or more candidates at one modulus read dC's moments from
    the cached table over (t, R) (within :data:`TABLE_K_ERROR_REL` of the quadrature in
    K); one element, few, or a modulus varying along the arrays take the quadrature."""
    from tactcad.design.readout_section import CARRIER_SIDE_MM, carrier_width_mm

    k = np.asarray(k_bare_N_per_mm, float)
    s = g.gauge
    if s is None:
        return k
    half = s.grid_length_mm / 2 + CARRIER_SIDE_MM
    dc = layer_compliance_change(web_mm, notch_radius_mm, arm_length_mm, g.sheet_thickness_mm,
                                 youngs_modulus_MPa, g.base_height_mm, g.arm_height_mm,
                                 (-half, half), s.height_mm, s.modulus_MPa,
                                 carrier_width_mm(s.grid_width_mm, g.sheet_thickness_mm))
    return 1.0 / (1.0 / k + dc)
