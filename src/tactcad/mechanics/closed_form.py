"""Level 1 of the element-stiffness ladder: closed-form flexure-hinge model.

The sensing element is a cantilever clamped at the back wall of the notch
(x = x_h - R, the base block is rigid) and loaded by a tip force F along +y at
the centre of the contact face (x = x_t, lever a = x_t - x_h). Its tip
compliance is the sum of four Euler-Bernoulli / Timoshenko terms (unit-load
method, statically determinate cantilever, M(x) = F (x_t - x), V = F):

* notch bending   12/(E b) * integral over the notch of (x_t - x)^2 / h(x)^3
* notch shear     alpha/(G b) * integral over the notch of 1 / h(x)
* arm bending     (x_t - x)^2 / (E I) over the measuring arm (height h_a) and
                  over the tip block up to the load point (height h_a + h_tip)
* arm shear       alpha * length / (G b h) over the same two prisms

with alpha = 6/5 (rectangular section, shear coefficient kappa = 5/6) and
G = E / (2 (1 + nu)).

Notch integrals (single-sided circular notch hinge of notch radius R, web
thickness t, flat top face; u = x - x_h, h(u) = t + R - sqrt(R^2 - u^2)).
With u = R sin(theta), h = R (p - cos(theta)), s = t/R, p = 1 + s,
m = sqrt(s (2 + s)) = sqrt(p^2 - 1) and A = arctan(sqrt((2 + s)/s)):

    integral du / h^3        = [ (2p^2 + 1)/(p m^4) + 6 p A / m^5 ] / R^2
    integral u du / h^3      = 0                       (symmetric notch)
    integral u^2 du / h^3    = p A (6 - 4p^2)/m^3 + (2p^2 - 1)/(p m^2) + pi
    integral du / h          = 4 p A / m - pi

These follow from K1(p) = integral d(theta)/(p - cos(theta)) = 4A/m over
[-pi/2, pi/2] and K_{k+1} = -(1/k) dK_k/dp; they are the exact
Euler-Bernoulli notch compliances of Paros & Weisbord (1965, "How to design
flexure hinges", Machine Design 37), Lobontiu (2002, "Compliant Mechanisms:
Design of Flexure Hinges", CRC Press, ch. 2) and Wu & Zhou (2002, Rev. Sci.
Instrum. 73, 3101), written here for the single-sided notch. The form uses
s and m = sqrt(s (2 + s)) instead of p^2 - 1 (and A as above, well conditioned
for every s > 0), so no term cancels at small t/R: relative accuracy is ~1e-15
for t/R from 1e-4 to 2 and ~1e-13 at t/R = 10 (mild cancellation in the u^2 integral at large t/R).
For t/R -> 0 the hinge rotational stiffness tends to the classical
2 E b t^(5/2) / (9 pi sqrt(2 R)).

Face strain (``face_strain_per_N``, 1/N: strain per newton of tip force, x 1e6 for
microstrain/N): the strain of the flat top face at the grid's centre (the notch
centre, mid-width) under the bonded gauge's glue line and carrier, the quantity
fem2d and fem3d read with the layer meshed. The bare section's Euler-Bernoulli
face strain eps / F = M c / (E I F) = 6 a / (E b t^2) (neutral axis at the
centroid of the b x t section), times the fem3d-fitted point factor of
:mod:`tactcad.mechanics.gauge_strain` (a wide sheet holds the web near plane
strain: about 1 - nu^2 at b/t = 12; fitted error about 2 %), times the layer's
face factor (the transformed section of web and layer: the layer stiffens the
web and lifts its neutral axis, about 0.89 for the default gauge on the
examples' webs; :func:`face_strain_factor`). An element without a gauge has the
bare face's.

Correction: the Euler-Bernoulli notch formulas are too stiff against fem3d
at large t/R, and a wide sheet holds the web near plane strain. The
estimator applies the fem3d-fitted correction of
:mod:`tactcad.mechanics.correction`,

    K = K_EB * (1 + g(w, t/b, nu)) / (1 + q (c1 s + c2 s^2) + p c6 + r c7),
    s = t / R,  w = sqrt(t R) / b,
    q, p, r = notch-bending, notch-shear and arm-bending shares of 1 / K_EB,

read from ``src/tactcad/data/stiffness_correction.json`` (identity without
the file), and warns with the estimated error outside the fitted range.

Units: mm, N, MPa, N/mm. Arrays broadcast with numpy rules.
"""

from __future__ import annotations

import math
import time
from typing import Any, NamedTuple

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.mechanics.correction import (IDENTITY, Correction, CorrectionRangeWarning, apply_correction,
                         load_correction)
from tactcad.mechanics.bonded_layer import layer_face_factor, layer_of, with_gauge_layer
from tactcad.mechanics.stiffness_result import StiffnessResult

#: Shear coefficient of a rectangular section in the compliance integral,
#: alpha = 1 / kappa with kappa = 5/6 (Timoshenko & Gere, "Mechanics of
#: Materials"); the one shear constant of the ladder (the beam level uses it too).
ALPHA_SHEAR = 6.0 / 5.0

#: Bracket (mm) of the web-thickness inverse: the design domain's web range.
WEB_BRACKET_MM = (0.05, 1.0)

__all__ = ["ALPHA_SHEAR", "ComplianceParts", "Correction", "CorrectionRangeWarning",
           "IDENTITY", "NotchIntegrals", "closed_form_compliance", "closed_form_stiffness",
           "correction_factor", "correction_factor_and_error", "corrected_element_k", "corrected_point_strain",
           "estimate_closed_form", "face_strain_factor", "gauge_strain_per_newton", "notch_integrals",
           "web_for_stiffness"]

MODEL_NAME = "closed-form"


# ---------------------------------------------------------------------------
# Notch integrals and compliance
# ---------------------------------------------------------------------------
def _check_positive(name: str, value: Any) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    # one comparison pair, not isfinite + any + all: this runs for every
    # argument of every estimate (an inverse design makes many thousand)
    ok = (arr > 0) & (arr < math.inf)  # NaN fails both
    if not ok.all():
        bad = arr[~ok] if arr.ndim else arr
        raise ValueError(f"{name} must be finite and > 0; got {np.ravel(bad)[:3].tolist()}")
    return arr


class NotchIntegrals(NamedTuple):
    """Integrals over a single-sided circular notch (u = x - x_h, |u| <= R).

    Attributes (arrays, broadcast shape of the inputs):
        inv_h3: integral du / h^3 (1/mm^2).
        u2_h3: integral u^2 du / h^3 (dimensionless).
        inv_h: integral du / h (dimensionless).
    The first moment integral u du / h^3 is zero by symmetry.
    """

    inv_h3: np.ndarray
    u2_h3: np.ndarray
    inv_h: np.ndarray


def notch_integrals(web_mm, notch_radius_mm) -> NotchIntegrals:
    """Exact notch integrals of a single-sided circular notch hinge.

    Args:
        web_mm: web thickness t at the notch centre (mm), array-like.
        notch_radius_mm: notch radius R (mm), array-like, broadcast with ``web_mm``.

    Returns:
        :class:`NotchIntegrals` of the broadcast shape.

    Raises:
        ValueError: a non-finite or non-positive input.

    Source: Paros & Weisbord (1965); Lobontiu (2002), ch. 2 (circular notch
    hinges); stable form in s = t/R documented in the module docstring.
    """
    t = _check_positive("web_mm", web_mm)
    R = _check_positive("notch_radius_mm", notch_radius_mm)
    return _notch_integrals(t, R)


def _notch_integrals(t: np.ndarray, R: np.ndarray) -> NotchIntegrals:
    s = t / R
    p = 1.0 + s
    q = 2.0 + s
    m2 = s * q
    m = np.sqrt(m2)
    A = np.arctan(np.sqrt(q / s))  # one pass of arctan: arctan2 costs two
    pA = p * A
    pp = p * p
    m4 = m2 * m2
    inv_h3 = ((2.0 * pp + 1.0) / (p * m4) + 6.0 * pA / (m4 * m)) / (R * R)
    u2_h3 = pA * (6.0 - 4.0 * pp) / (m2 * m) + (2.0 * pp - 1.0) / (p * m2) + np.pi
    inv_h = 4.0 * pA / m - np.pi
    return NotchIntegrals(inv_h3, u2_h3, inv_h)


class ComplianceParts(NamedTuple):
    """Tip compliance (mm/N) split into its terms; arrays of the broadcast shape."""

    notch_bending: np.ndarray
    notch_shear: np.ndarray
    arm_bending: np.ndarray
    arm_shear: np.ndarray

    @property
    def total(self) -> np.ndarray:
        return self.notch_bending + self.notch_shear + self.arm_bending + self.arm_shear


def closed_form_compliance(web_mm, notch_radius_mm, arm_length_mm, *, arm_height_mm,
                           tip_width_mm, tip_height_mm, E, nu, b) -> ComplianceParts:
    """Tip compliance of the flexure element, term by term (mm/N).

    Args:
        web_mm: web thickness t (mm).
        notch_radius_mm: notch radius R (mm).
        arm_length_mm: lever a from the notch centre to the contact-face centre (mm).
        arm_height_mm: measuring-arm height h_a (mm).
        tip_width_mm: contact-face width w along x (mm); the tip block of height
            h_a + tip_height_mm spans the last w/2 before the load point.
        tip_height_mm: height of the tip above the arm's top face (mm).
        E: Young's modulus (MPa). nu: Poisson ratio. b: sheet thickness (mm).
        All array-like and broadcast together.

    Returns:
        :class:`ComplianceParts` (mm/N).

    Raises:
        ValueError: a non-finite or non-positive input, nu outside (-1, 0.5),
            or a lever too short for notch and tip (a < R + w/2).

    Source: unit-load method for a cantilever with Timoshenko shear
    (Timoshenko & Gere, "Mechanics of Materials"); notch integrals of
    :func:`notch_integrals` (Lobontiu 2002).
    """
    t = _check_positive("web_mm", web_mm)
    R = _check_positive("notch_radius_mm", notch_radius_mm)
    a = _check_positive("arm_length_mm", arm_length_mm)
    ha = _check_positive("arm_height_mm", arm_height_mm)
    w = _check_positive("tip_width_mm", tip_width_mm)
    htip = _check_positive("tip_height_mm", tip_height_mm)
    E_ = _check_positive("E", E)
    b_ = _check_positive("b", b)
    nu_ = np.asarray(nu, dtype=float)
    if not np.all(np.isfinite(nu_)) or np.any(nu_ <= -1.0) or np.any(nu_ >= 0.5):
        raise ValueError("nu must lie in (-1, 0.5)")
    d1 = a - R                # lever at the arm root (notch front wall)
    d2 = 0.5 * w              # lever at the tip-block root
    if np.any(d1 < d2):
        raise ValueError("arm_length_mm must be >= notch_radius_mm + tip_width_mm / 2 "
                         "(the lever must reach past the notch and the tip root)")
    G = E_ / (2.0 * (1.0 + nu_))
    ni = _notch_integrals(t, R)
    Eb = E_ * b_
    notch_bending = 12.0 / Eb * (a * a * ni.inv_h3 + ni.u2_h3)
    notch_shear = ALPHA_SHEAR / (G * b_) * ni.inv_h
    ht = ha + htip
    d2c = d2 * d2 * d2
    arm_bending = 4.0 / Eb * ((d1 * d1 * d1 - d2c) / (ha * ha * ha) + d2c / (ht * ht * ht))
    arm_shear = ALPHA_SHEAR / (G * b_) * ((d1 - d2) / ha + d2 / ht)
    return ComplianceParts(notch_bending, notch_shear, arm_bending, arm_shear)


def closed_form_stiffness(web_mm, notch_radius_mm, arm_length_mm, *, arm_height_mm,
                          tip_width_mm, tip_height_mm, E, nu, b) -> np.ndarray:
    """Uncorrected (Euler-Bernoulli + Timoshenko shear) tip stiffness K (N/mm).

    Vectorised: all arguments broadcast; returns an array of the broadcast
    shape (0-d for scalar inputs). Arguments, errors and sources as
    :func:`closed_form_compliance`.
    """
    return 1.0 / closed_form_compliance(
        web_mm, notch_radius_mm, arm_length_mm, arm_height_mm=arm_height_mm,
        tip_width_mm=tip_width_mm, tip_height_mm=tip_height_mm, E=E, nu=nu, b=b).total


def gauge_strain_per_newton(web_mm, arm_length_mm, *, E, b) -> np.ndarray:
    """Surface strain on the bare flat top face over the thinnest section per newton
    (1/N, strain per N).

    eps / F = 6 a / (E b t^2) (Euler-Bernoulli, M = F a at the notch centre,
    neutral axis at the centroid of the bare b x t section). Arrays broadcast. The
    closed form's ``face_strain_per_N`` is this times :func:`face_strain_factor`.

    Raises:
        ValueError: a non-finite or non-positive input.
    """
    t = _check_positive("web_mm", web_mm)
    a = _check_positive("arm_length_mm", arm_length_mm)
    E_ = _check_positive("E", E)
    b_ = _check_positive("b", b)
    return 6.0 * a / (E_ * b_ * t * t)


def _geometry_kwargs(g: ElementGeometry, material: Material) -> dict[str, float]:
    return dict(arm_height_mm=g.arm_height_mm, tip_width_mm=g.tip_width_mm,
                tip_height_mm=g.tip_height_mm, E=material.youngs_modulus_MPa,
                nu=material.poisson_ratio, b=g.sheet_thickness_mm)


# ---------------------------------------------------------------------------
# Element-level API
# ---------------------------------------------------------------------------
def _resolve(corrected: bool, correction: Correction | None) -> Correction:
    if not corrected:
        return IDENTITY
    return correction if correction is not None else load_correction()


def correction_coordinates(parts: ComplianceParts, web_mm, notch_radius_mm, sheet_mm,
                           poisson_ratio) -> dict[str, np.ndarray]:
    """The coordinates of :meth:`Correction.factor` for compliance ``parts``:
    t/R, sqrt(t R)/b, nu, the notch-bending, notch-shear and arm-bending
    shares of the compliance and t/b (arrays broadcast; mm)."""
    t = np.asarray(web_mm, float)
    R = np.asarray(notch_radius_mm, float)
    b = np.asarray(sheet_mm, float)
    total = parts.total
    return dict(t_over_R=t / R, width_ratio=np.sqrt(t * R) / b, poisson_ratio=poisson_ratio,
                notch_share=parts.notch_bending / total, shear_share=parts.notch_shear / total,
                arm_share=parts.arm_bending / total, web_over_sheet=t / b)


def _corrected(parts: ComplianceParts, g: ElementGeometry, material: Material, web_mm: float,
               corr: Correction, warn: bool) -> tuple[float, float]:
    """Corrected K (N/mm) and its estimated relative error for compliance ``parts``."""
    t, R, b = web_mm, g.notch_radius_mm, g.sheet_thickness_mm
    coords = {k: float(v) for k, v in correction_coordinates(
        parts, t, R, b, material.poisson_ratio).items()}
    aspect = g.arm_length_mm / g.arm_height_mm
    k, _ = apply_correction(1.0 / float(parts.total), correction=corr, web_mm=t,
                            notch_radius_mm=R, arm_mm=g.arm_length_mm, sheet_mm=b,
                            arm_over_arm_height=aspect, warn=warn, **coords)
    # past the fitted arm / arm height the error grows (the file's measured slope)
    return float(k), float(corr.error_estimate_rel(**coords, arm_over_arm_height=aspect))


def _parts(g: ElementGeometry, material: Material, web_mm: float) -> ComplianceParts:
    return closed_form_compliance(web_mm, g.notch_radius_mm, g.arm_length_mm,
                                  **_geometry_kwargs(g, material))


def correction_factor(g: ElementGeometry, material: Material,
                      correction: Correction | None = None) -> float:
    """K_corrected / K_EB of one element (dimensionless; no range warning).

    ``correction`` defaults to the file read by
    :func:`~tactcad.mechanics.correction.load_correction`.
    """
    corr = _resolve(True, correction)
    parts = _parts(g, material, g.web_thickness_mm)
    k, _ = _corrected(parts, g, material, g.web_thickness_mm, corr, warn=False)
    return k * float(parts.total)


def correction_factor_and_error(g: ElementGeometry, material: Material,
                                correction: Correction | None = None) -> tuple[float, float]:
    """K_corrected / K_EB of one element and the correction's own error estimate there.

    Args:
        g: element geometry (mm); its bonded gauge is not counted (the bare element's).
        material: its material (MPa).
        correction: explicit correction (default: the file of
            :func:`~tactcad.mechanics.correction.load_correction`).

    Returns:
        (f, e): the factor (dimensionless) and the relative error of the corrected K
        against fem3d (dimensionless: the fit's residual plus, outside the fitted range,
        its extrapolation and its measured growth past the fitted arm / arm height), no
        range warning.
    """
    corr = _resolve(True, correction)
    parts = _parts(g, material, g.web_thickness_mm)
    k, err = _corrected(parts, g, material, g.web_thickness_mm, corr, warn=False)
    return k * float(parts.total), err


def width_gain(g: ElementGeometry, material: Material,
               correction: Correction | None = None) -> float:
    """1 + g of the fem3d-fitted correction: how much stiffer the 3D element is
    than its plane-stress section (a wide sheet holds the web towards plane
    strain; g -> 0 for a thin sheet). Dimensionless, >= 1 for the fitted c3."""
    from tactcad.mechanics.correction import _gain_and_denominator

    corr = _resolve(True, correction)
    parts = _parts(g, material, g.web_thickness_mm)
    c = correction_coordinates(parts, g.web_thickness_mm, g.notch_radius_mm,
                               g.sheet_thickness_mm, material.poisson_ratio)
    gain, _ = _gain_and_denominator(np.asarray(corr.coefficients, float), c["t_over_R"],
                                    c["width_ratio"], c["poisson_ratio"], c["notch_share"],
                                    c["shear_share"], c["arm_share"], c["web_over_sheet"])
    return float(gain)


def closed_form_error_estimate_rel(g: ElementGeometry, material: Material) -> float:
    """The error estimate :func:`estimate_closed_form` gives element ``g`` (corrected by
    the correction file), relative, without the gauge strain it also works out: the
    stiffness correction's error plus the bonded layer's share of the rise, by the same
    steps, so the number is the same to the bit.

    Args:
        g: element geometry (mm). material: its material (MPa).

    Returns:
        The relative error estimate of the corrected closed-form K (dimensionless).

    Warns:
        CorrectionRangeWarning: the geometry lies outside the correction's fitted range.

    Source: the fem3d-fitted correction's residual and extrapolation
    (:meth:`~tactcad.mechanics.correction.Correction.error_estimate_rel`) and
    :data:`~tactcad.mechanics.bonded_layer.CLOSED_FORM_LAYER_ERROR_REL`.
    """
    corr = _resolve(True, None)
    t = g.web_thickness_mm
    k, err = _corrected(_parts(g, material, t), g, material, t, corr, warn=True)
    layer = layer_of(g)
    if layer is not None:
        from tactcad.mechanics.bonded_layer import CLOSED_FORM_LAYER_ERROR_REL, closed_form_layer_k

        err += CLOSED_FORM_LAYER_ERROR_REL * (
            closed_form_layer_k(k, g, material.youngs_modulus_MPa, layer) / k - 1.0)
    return err


def corrected_element_k(g: ElementGeometry, material: Material,
                        correction: Correction | None = None) -> float:
    """The corrected closed-form K (N/mm) of one element, alone: the number
    :func:`estimate_closed_form` gives as ``stiffness_N_per_mm``, by the same steps (the
    bare compliance, the fem3d-fitted correction, the bonded gauge's layer), so it is the
    same to the bit; without the gauge strain, the error estimate or the range warning,
    which a web search's trial webs need none of (a root finder reads K alone).

    Args:
        g: element geometry (mm). material: its material (MPa).
        correction: explicit correction (default: the file of
            :func:`~tactcad.mechanics.correction.load_correction`).

    Returns:
        K (N/mm).

    Raises:
        ValueError: a non-positive dimension, or a correction factor not positive there.

    Source: the closed form of this module (Tseytlin's notch compliance and the arm's
    Euler-Bernoulli bending) with its fem3d-fitted correction.
    """
    corr = _resolve(True, correction)
    t = g.web_thickness_mm
    parts = _parts(g, material, t)
    c = {key: float(v) for key, v in correction_coordinates(
        parts, t, g.notch_radius_mm, g.sheet_thickness_mm, material.poisson_ratio).items()}
    # apply_correction's product, less its range check (it does not move K)
    k = float(np.asarray(1.0 / float(parts.total), dtype=float) * corr.factor(
        c["t_over_R"], c["width_ratio"], c["poisson_ratio"], c["notch_share"],
        c["shear_share"], c["arm_share"], c["web_over_sheet"]))
    layer = layer_of(g)
    if layer is not None:
        from tactcad.mechanics.bonded_layer import closed_form_layer_k

        k = closed_form_layer_k(k, g, material.youngs_modulus_MPa, layer)
    return k


def estimate_closed_form(g: ElementGeometry, material: Material, *, element: int | None = None,
                         corrected: bool = True,
                         correction: Correction | None = None) -> StiffnessResult:
    """Closed-form stiffness and gauge strain of one flexure element.

    Args:
        g: element geometry (plan). material: plan material.
        element: paper element number to carry in the result.
        corrected: apply the fem3d-fitted correction (``correction``, or the
            file read by :func:`~tactcad.mechanics.correction.load_correction`;
            identity when absent).
        correction: explicit correction, overrides the file.

    The bonded gauge ``g`` carries (:attr:`ElementGeometry.gauge`) makes K
    1 / (1 / K + dC), dC the Euler-Bernoulli compliance its layer takes away
    (:func:`~tactcad.mechanics.bonded_layer.closed_form_layer_k`), and the error
    estimate adds :data:`~tactcad.mechanics.bonded_layer.CLOSED_FORM_LAYER_ERROR_REL`
    of the rise.

    Returns:
        :class:`StiffnessResult` with model ``closed-form``. The gauge strain
        (1/N) is the face strain at the grid's centre under the gauge's layer: the
        bare section's Euler-Bernoulli value at the notch centre times
        :func:`face_strain_factor` (the fem3d-fitted point factor,
        :func:`~tactcad.mechanics.gauge_strain.point_strain_factor`, left out when
        ``corrected=False``, and the layer's face factor). The error estimate is the stiffness
        correction's (fit residual, plus the extrapolation change outside the
        fitted range and, past the fitted arm / arm height, its measured growth per
        unit of a / h_a beyond it), or 0.39 t/R when uncorrected.

    Warns:
        CorrectionRangeWarning: the geometry lies outside the stiffness
            correction's fitted range (the message gives the estimated error).
        GaugeStrainRangeWarning: outside the gauge-strain factor's fitted range.
    """
    start = time.perf_counter()
    corr = _resolve(corrected, correction)
    t = g.web_thickness_mm
    k, err = _corrected(_parts(g, material, t), g, material, t, corr, warn=True)
    eps = gauge_strain_per_newton(t, g.arm_length_mm, E=material.youngs_modulus_MPa,
                                  b=g.sheet_thickness_mm)
    eps = eps * face_strain_factor(g, material, corrected=corrected)
    layer = layer_of(g)
    if layer is not None:
        from tactcad.mechanics.bonded_layer import CLOSED_FORM_LAYER_ERROR_REL, closed_form_layer_k

        k_layer = closed_form_layer_k(k, g, material.youngs_modulus_MPa, layer)
        err += CLOSED_FORM_LAYER_ERROR_REL * (k_layer / k - 1.0)
        k = k_layer
    return StiffnessResult(element=element, model=MODEL_NAME, stiffness_N_per_mm=k,
                           face_strain_per_N=float(eps), error_estimate_rel=err,
                           wall_time_s=time.perf_counter() - start)


def face_strain_factor(g: ElementGeometry, material: Material, *,
                       corrected: bool = True) -> float:
    """What carries the bare section's Euler-Bernoulli face strain at the notch centre
    (6 a / (E b t^2), or the beam level's M (t/2) / (E I)) to the closed form's and the
    beam level's ``face_strain_per_N``: the face strain at the grid's centre (the notch
    centre, mid-width) under the bonded gauge ``g`` carries, as fem2d and fem3d read it
    with the layer meshed. Dimensionless: the fem3d-fitted point factor
    (:func:`corrected_point_strain`, of the bare element; 1 when not ``corrected``) x the
    layer's face factor (:func:`~tactcad.mechanics.bonded_layer.layer_face_factor`, the
    transformed section of web and layer; 1 for a bare ``g``).

    Warns:
        GaugeStrainRangeWarning: ``corrected`` and outside the point factor's fitted range.
    """
    point = corrected_point_strain(g, material, stacklevel=4) if corrected else 1.0
    return point * layer_face_factor(g, material.youngs_modulus_MPa, layer_of(g))


def corrected_point_strain(g: ElementGeometry, material: Material, *,
                           stacklevel: int = 3) -> float:
    """The fem3d-fitted factor on the EB surface strain at the notch centre
    (:func:`~tactcad.mechanics.gauge_strain.point_strain_factor`), warning outside
    its fitted range (dimensionless; the bare element's).

    Args:
        stacklevel: the warning's, as :func:`warnings.warn` takes it (3: the caller of
            the estimator that calls this).

    Warns:
        GaugeStrainRangeWarning: outside the range (names the coordinates and the
            estimated error).
    """
    import warnings

    from tactcad.mechanics.gauge_strain import (GaugeStrainRangeWarning, coordinate_words,
                                                point_strain_factor)

    f = point_strain_factor(g, material)
    if f.outside:
        detail = (f"{coordinate_words(f.outside)} outside the fem3d fit of the plane-strain "
                  f"factor (t/R {f.coordinates['t_over_R']:.3g}, b/t "
                  f"{f.coordinates['sheet_over_web']:.3g}, nu "
                  f"{f.coordinates['poisson_ratio']:.3g}); estimated error "
                  f"{100 * f.error_rel:.1f} %")
        warnings.warn(GaugeStrainRangeWarning(
            f"gauge strain of {g.part_name} (web {g.web_thickness_mm:g} mm): {detail}",
            f.error_rel, detail), stacklevel=stacklevel)
    return f.factor


def web_for_stiffness(k_target: float, g: ElementGeometry, material: Material, *,
                      corrected: bool = True, correction: Correction | None = None,
                      bracket_mm: tuple[float, float] = WEB_BRACKET_MM,
                      xtol_mm: float = 1e-9) -> float:
    """Web thickness t (mm) for which the closed form gives stiffness ``k_target``.

    All other dimensions are taken from ``g``; K(t) is strictly increasing, so
    the root in ``bracket_mm`` is unique (scipy ``brentq``). Used to infer the
    as-built web of a calibrated element (Table 1). K is the element's with the bonded
    gauge ``g`` carries (:func:`~tactcad.mechanics.bonded_layer.with_gauge_layer`).

    Raises:
        ValueError: ``k_target`` not finite and > 0, or outside
            [K(bracket low), K(bracket high)] (the message gives that range).

    Warns:
        CorrectionRangeWarning: the solution lies outside the correction's fit range.
    """
    if not (isinstance(k_target, (int, float, np.floating)) and math.isfinite(k_target)
            and k_target > 0):
        raise ValueError(f"k_target must be a finite stiffness > 0 N/mm; got {k_target!r}")
    corr = _resolve(corrected, correction)
    R, a = g.notch_radius_mm, g.arm_length_mm

    def k_of(t: float) -> float:
        k = _corrected(_parts(g, material, t), g, material, t, corr, warn=False)[0]
        return float(with_gauge_layer(k, g, t, R, a, material.youngs_modulus_MPa))

    lo, hi = bracket_mm
    k_lo, k_hi = k_of(lo), k_of(hi)
    if not k_lo <= k_target <= k_hi:
        raise ValueError(f"k_target = {k_target:g} N/mm: allowed {k_lo:.4g} ... {k_hi:.4g} N/mm "
                         f"(web {lo:g} ... {hi:g} mm at arm {a:g} mm, R {R:g} mm)")
    from scipy.optimize import brentq  # here: the closed form itself needs no scipy.optimize

    t = float(brentq(lambda x: k_of(x) - k_target, lo, hi, xtol=xtol_mm, rtol=1e-14))
    _corrected(_parts(g, material, t), g, material, t, corr, warn=True)
    return t


#: Exponent of the thin circular-notch hinge law K ~ t^(5/2) (t << R).
THIN_HINGE_WEB_EXPONENT = 2.5


def web_tolerance_stiffness_change(web_mm: float, tolerance_mm: float) -> tuple[float, float]:
    """Relative stiffness change of a thin notch hinge at the web's tolerance limits.

    A circular notch hinge with t << R has K proportional to t^(5/2), so a web
    ``tolerance_mm`` thicker or thinner moves K by ``(1 + tol/t)^2.5 - 1`` up
    and ``1 - (1 - tol/t)^2.5`` down (all of it, 1, when the tolerance
    reaches the web: no web is left at its low limit).

    Args:
        web_mm: nominal web thickness t (mm), > 0.
        tolerance_mm: symmetric web tolerance (mm), >= 0.

    Returns:
        (rise, fall): relative stiffness changes (dimensionless, >= 0; fall <= 1).

    Raises:
        ValueError: t <= 0 or a negative tolerance (or either not finite).

    Source: Paros & Weisbord (1965), thin-hinge limit of the circular notch
    compliance; Lobontiu (2002), ch. 2.
    """
    if not (math.isfinite(web_mm) and web_mm > 0 and math.isfinite(tolerance_mm)
            and tolerance_mm >= 0):
        raise ValueError(f"web_tolerance_stiffness_change: web_mm = {web_mm!r} must be > 0 and "
                         f"tolerance_mm = {tolerance_mm!r} >= 0, both finite")
    n = THIN_HINGE_WEB_EXPONENT
    up = ((web_mm + tolerance_mm) / web_mm) ** n - 1
    down = 1 - (max(web_mm - tolerance_mm, 0.0) / web_mm) ** n
    return up, down
