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
of the layer's change of the section's bending flexibility over the carrier: exact in u
where the section is flat, a 10-point rule in a coordinate that flattens the notch's
peak across it, checked against the 24-point Gauss-Legendre quadrature in u
(:func:`layer_compliance_change_quadrature`, the reference).

Units: mm, MPa.
"""

from __future__ import annotations

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


#: Gauss-Legendre points on the notch piece in the flattening coordinate sigma of
#: :func:`_layer_moments` (the fast quadrature of :func:`layer_compliance_change`; 5
#: evaluations of g on a carrier centred over the notch). Measured in K against the 24-point
#: reference on the benchmark's designs and the examples' elements +-30 %: 8 points err by
#: up to 2.2e-4, 10 by 8e-6, 12 by 1e-6; over webs 0.04-0.8 mm and radii 0.04-4 mm
#: against the converged integral: 10 points 8.5e-5, 12 1.4e-5, 14 1.2e-6.
NOTCH_POINTS = 10


def _section_flexibility_change(h, eb, ea_layer, ei_layer, layer_height_mm):
    """g(h) = 1 / EI_c - 1 / EI_0 of :func:`_flexibility_change` (1/(N mm^2), <= 0) from
    the web's E b, the layer's E A and its own E I: EI_c = EI_0 + EI_l + EA_w EA_l d^2 /
    (EA_w + EA_l), d = (h + h_l) / 2 the distance of the two centroids, the same
    transformed section with the rise written as one sum (no 1 / (1 + s) - 1). In place
    on a node's arrays; a flat piece's one height (h not of E b h's shape) out of place."""
    ea_web = eb * h
    if np.ndim(ea_web) == 0 or np.shape(h) != np.shape(ea_web):
        rise = ei_layer + ea_web * ea_layer * (0.25 * (h + layer_height_mm) ** 2) / (
            ea_web + ea_layer)
        ei0 = ea_web * h * h / 12.0
        return -rise / ((ei0 + rise) * ei0)
    d = h + layer_height_mm
    d *= d
    d *= 0.25 * ea_layer
    d *= ea_web
    d /= ea_web + ea_layer
    d += ei_layer  # EI_c - EI_0
    ei0 = h * h
    ei0 *= ea_web
    ei0 *= 1.0 / 12.0
    out = ei0 + d
    out *= ei0
    np.divide(d, out, out=out)
    np.negative(out, out=out)
    return out


def _sigma(u, R, k, positive: bool):
    """sigma = tan(psi / 2) of :func:`_layer_moments` at u on the notch (clipped to its
    walls; ``positive``: u >= 0): tan(theta / 2) = s / (1 + sqrt(1 - s^2)), s = sin(theta)
    = u / R, tan(psi) = tan(theta / 2) / k, and the half angle of that."""
    s = np.minimum(u / R, 1.0) if positive else np.clip(u / R, -1.0, 1.0)
    tan_psi = s / ((1.0 + np.sqrt(1.0 - s * s)) * k)
    return tan_psi / (1.0 + np.sqrt(1.0 + tan_psi * tan_psi))


def _layer_moments(web_mm, notch_radius_mm, sheet_mm, youngs_modulus_MPa, base_height_mm,
                   arm_height_mm, hinge_offsets_mm, layer_height_mm, layer_modulus_MPa,
                   layer_width_mm):
    """(I0, I1, I2) of :func:`_layer_moments_quadrature`, fast: on the flat pieces
    (behind and in front of the notch) g is constant and int u^k du exact; on the notch
    u = R sin(theta), tan(theta / 2) = k tan(psi), k = sqrt(t / (t + 2 R)), which makes
    h = t sec^2(psi) / (1 + k^2 tan^2(psi)) and dtheta / h^3 a trigonometric polynomial
    in psi (the web's peak of width sqrt(t R) spread over the range, the walls' square-root
    slope gone); Gauss-Legendre with :data:`NOTCH_POINTS` points in sigma = tan(psi / 2)
    (the nodes' tan(psi) = 2 sigma / (1 - sigma^2) rational: no tangent per node), the
    nodes in sigma > 0 alone on a carrier symmetric about the notch centre (the integrand
    even, the notch's part of I1 nil)."""
    from tactcad.mechanics.notch_profile import gauss_legendre

    t, R = np.broadcast_arrays(*(np.asarray(v, float) for v in (web_mm, notch_radius_mm)))
    b, E, hb, ha, hl, El, wl = (np.asarray(v, float) for v in (
        sheet_mm, youngs_modulus_MPa, base_height_mm, arm_height_mm, layer_height_mm,
        layer_modulus_MPa, layer_width_mm))
    eb = E * b
    ea_layer = El * wl * hl
    ei_layer = ea_layer * hl * hl / 12.0
    u0, u1 = (np.asarray(v, float) for v in hinge_offsets_mm)
    two_r = 2.0 * R
    k2 = t / (t + two_r)
    k = np.sqrt(k2)
    symmetric = bool(np.all(u0 == -u1))
    s1 = _sigma(u1, R, k, symmetric)
    nodes, weights = gauss_legendre(NOTCH_POINTS)
    if symmetric:  # the rule's nodes come in +- pairs: the integrand is even in sigma
        half, mid = s1, 0.0
        keep = nodes > 0
        nodes, weights = nodes[keep], 2.0 * weights[keep]
    else:
        s0 = _sigma(u0, R, k, False)
        half, mid = 0.5 * (s1 - s0), 0.5 * (s1 + s0)
    # in sigma: tan(theta / 2) = k tan(psi) = 2 k sigma / m, m = 1 - sigma^2, so with
    # p = 2 k sigma and D = m^2 + p^2: sin^2(theta / 2) = p^2 / D, cos^2(theta / 2) = m^2 / D,
    # cos(theta) = (m^2 - p^2) / D, and du / dsigma = R cos(theta) dtheta / dsigma
    # = 4 R k (1 + sigma^2) cos(theta) / D
    scale = 4.0 * R * k * half
    four_k2 = 4.0 * k2
    four_r2 = 4.0 * R * R
    i0 = i1 = i2 = 0.0
    for z, w in zip(nodes, weights):
        sg = half * z
        if not symmetric:
            sg += mid
        sg2 = sg * sg
        m2 = 1.0 - sg2
        m2 *= m2
        p2 = four_k2 * sg2
        inv = 1.0 / (m2 + p2)
        y = p2 * inv  # sin^2(theta / 2)
        jac = m2 - p2
        jac *= inv  # cos(theta)
        jac *= inv
        sg2 += 1.0
        jac *= sg2
        jac *= scale * w
        u2 = m2 * inv
        u2 *= y
        u2 *= four_r2  # u^2 = R^2 sin^2(theta)
        y *= two_r
        y += t  # h
        gj = _section_flexibility_change(y, eb, ea_layer, ei_layer, hl)
        gj *= jac
        if not symmetric:
            i1 = i1 + gj * np.copysign(np.sqrt(u2), sg)
        i0 = i0 + gj
        i2 = i2 + gj * u2
    # the flat pieces, g constant: behind the notch (u0 ... -R), in front (R ... u1)
    gb, ga = (_section_flexibility_change(h, eb, ea_layer, ei_layer, hl) for h in (hb, ha))
    if symmetric:  # -c ... -w and w ... c, w = min(R, c)
        w = np.minimum(R, u1)
        w2 = w * w
        c2 = u1 * u1
        g = gb + ga
        i0 = i0 + g * (u1 - w)
        i1 = (ga - gb) * (0.5 * (c2 - w2))
        i2 = i2 + g * ((c2 * u1 - w2 * w) / 3.0)
        return i0, i1, i2
    for g, lo, hi in ((gb, u0, np.clip(-R, u0, u1)), (ga, np.clip(R, u0, u1), u1)):
        lo2, hi2 = lo * lo, hi * hi
        i0 = i0 + g * (hi - lo)
        i1 = i1 + g * (0.5 * (hi2 - lo2))
        i2 = i2 + g * ((hi2 * hi - lo2 * lo) / 3.0)
    return i0, i1, i2


#: The fast quadrature's largest error in K against the 24-point reference, stated
#: (tests/mechanics/test_bonded_layer.py measures it on the benchmark's designs, with the
#: modulus fixed and drawn per design, and on the examples' elements with webs and radii
#: +-30 %, the grasper's 78 um webs down to 55 um, whose K the layer raises by up to 75 %:
#: at most 8e-6, on the Ti example's elements; 6e-6 on the benchmark's). Over webs 0.04-0.8 mm and radii 0.04-4 mm it holds 1e-4 of the converged
#: integral (its worst: the thinnest webs with the notch just inside the carrier), where
#: the 24-point reference itself errs by up to 1.2e-4.
LAYER_K_ERROR_REL = 1e-4


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
    g = 1 / EI_c - 1 / EI_0. Behind and in front of the notch g is constant and the
    integrals in u exact; across the notch a substitution that flattens the web's peak
    and the walls' square-root slope (:func:`_layer_moments`) takes Gauss-Legendre with
    :data:`NOTCH_POINTS` points (5 evaluations of g on a carrier centred over the notch),
    within :data:`LAYER_K_ERROR_REL` in K of the 24-point quadrature
    (:func:`layer_compliance_change_quadrature`, the reference), for one element or many,
    a modulus fixed or varying along the arrays.

    Args:
        hinge_offsets_mm: the carrier's ends from the notch centre (u0 < u1, mm).
        layer_height_mm, layer_modulus_MPa, layer_width_mm: the layer (mm, MPa, mm).

    Source: the unit-load (Castigliano) compliance of a beam of varying section, e.g.
    Young and Budynas, Roark's Formulas for Stress and Strain, 7th ed., sec. 8.1; the
    transformed section, e.g. Gere and Goodno, Mechanics of Materials, sec. 6.2.
    """
    i0, i1, i2 = _layer_moments(web_mm, notch_radius_mm, sheet_mm, youngs_modulus_MPa,
                                base_height_mm, arm_height_mm, hinge_offsets_mm,
                                layer_height_mm, layer_modulus_MPa, layer_width_mm)
    a = np.asarray(arm_length_mm, float)
    i1 = i1 * (2.0 * a)
    i0 = i0 * (a * a)
    i0 -= i1
    i0 += i2
    return i0


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
    candidate's notch); ``k_bare_N_per_mm`` as it is for a bare ``g`` (N/mm)."""
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
