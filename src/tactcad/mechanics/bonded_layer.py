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


#: Gauss-Legendre points on each smooth piece of the covered span.
_GAUSS_POINTS = 24


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

    Args:
        hinge_offsets_mm: the carrier's ends from the notch centre (u0 < u1, mm).
        layer_height_mm, layer_modulus_MPa, layer_width_mm: the layer (mm, MPa, mm).

    Source: the unit-load (Castigliano) compliance of a beam of varying section, e.g.
    Young and Budynas, Roark's Formulas for Stress and Strain, 7th ed., sec. 8.1; the
    transformed section, e.g. Gere and Goodno, Mechanics of Materials, sec. 6.2.
    """
    from tactcad.mechanics.gauge_strain import transformed_section

    from tactcad.mechanics.notch_profile import notch_integral

    a, b, E, wl = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        arm_length_mm, sheet_mm, youngs_modulus_MPa, layer_width_mm)))
    u0, u1 = hinge_offsets_mm

    def change(u, h):  # M^2 / EI x (1 / (1 + s) - 1), s the layer's rise of EI
        rise = transformed_section(h, b[..., None], E[..., None], layer_height_mm,
                                   layer_modulus_MPa, wl[..., None])[1]
        moment = a[..., None] - u
        ei = E[..., None] * b[..., None] * h ** 3 / 12.0
        return moment * moment / ei * (1.0 / (1.0 + rise) - 1.0)

    return notch_integral(u0, u1, web_mm, notch_radius_mm, base_height_mm, arm_height_mm,
                          change, _GAUSS_POINTS)


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
