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
s and m = sqrt(s (2 + s)) instead of p^2 - 1 and A via arctan2, so no term
cancels at small t/R: relative accuracy is ~1e-15 for t/R from 1e-4 to 2 and
~1e-13 at t/R = 10 (mild cancellation in the u^2 integral at large t/R).
For t/R -> 0 the hinge rotational stiffness tends to the classical
2 E b t^(5/2) / (9 pi sqrt(2 R)).

Gauge strain: surface strain on the flat top face over the thinnest section,
eps / F = M c / (E I F) = 6 a / (E b t^2) (Euler-Bernoulli, neutral axis at the
centroid of the b x t section).

Correction hook: Euler-Bernoulli notch formulas are too stiff against
plane-stress FEM (about 39 % x t/R for a circular notch) and plane stress is
softer than 3D at b = 3 mm. :class:`Correction` carries a fitted factor

    K = K_EB * (1 + c3) / (1 + c1 s + c2 s^2),    s = t / R,

with the range it was fitted over; :func:`apply_correction` flags use
outside that range. The FEM levels store a fit in
``src/tactcad/data/stiffness_correction.json`` (schema in
:func:`load_correction`); without the file the correction is the identity.

Units: mm, N, MPa, N/mm. Arrays broadcast with numpy rules.
"""

from __future__ import annotations

import json
import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, NamedTuple

import numpy as np
from scipy.optimize import brentq

from tactcad.design.array import ElementGeometry, Material
from tactcad.errors import DesignError
from tactcad.mechanics.result import StiffnessResult

#: Shear correction of a rectangular section in the compliance integral
#: (alpha = 1 / kappa, kappa = 5/6; Timoshenko & Gere, "Mechanics of
#: Materials").
ALPHA_SHEAR = 6.0 / 5.0

#: Relative stiffness bias of uncorrected Euler-Bernoulli notch formulas
#: against converged plane-stress FEM per unit t/R (circular notch; used as the
#: error estimate of the uncorrected closed form).
UNCORRECTED_BIAS_PER_T_OVER_R = 0.39

#: Default location of the FEM-fitted correction.
CORRECTION_FILE = Path(__file__).resolve().parents[1] / "data" / "stiffness_correction.json"

#: Bracket (mm) of the web-thickness inverse.
WEB_BRACKET_MM = (0.05, 0.6)

MODEL_NAME = "closed-form"


# ---------------------------------------------------------------------------
# Notch integrals and compliance
# ---------------------------------------------------------------------------
def _check_positive(name: str, value: Any) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        bad = arr[~(np.isfinite(arr) & (arr > 0))] if arr.ndim else arr
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
    m2 = s * (2.0 + s)
    m = np.sqrt(m2)
    A = np.arctan2(np.sqrt(2.0 + s), np.sqrt(s))
    pA = p * A
    m4 = m2 * m2
    inv_h3 = ((2.0 * p * p + 1.0) / (p * m4) + 6.0 * pA / (m4 * m)) / (R * R)
    u2_h3 = pA * (6.0 - 4.0 * p * p) / (m2 * m) + (2.0 * p * p - 1.0) / (p * m2) + np.pi
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
    """Surface strain on the flat top face over the thinnest section per newton (1/N).

    eps / F = 6 a / (E b t^2) (Euler-Bernoulli, M = F a at the notch centre,
    neutral axis at the centroid of the b x t section). Arrays broadcast.

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
# Correction hook
# ---------------------------------------------------------------------------
class CorrectionRangeWarning(UserWarning):
    """A correction is applied outside the range it was fitted over."""


_INF_RANGE = (0.0, math.inf)


def _as_range(name: str, value: Any) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise DesignError(name, value, "a pair [low, high]") from None
    if math.isnan(lo) or math.isnan(hi) or lo < 0 or hi < lo:
        raise DesignError(name, value, "0 <= low <= high")
    return (lo, hi)


@dataclass(frozen=True)
class FitRange:
    """Ranges a correction was fitted over (closed intervals).

    Attributes:
        t_over_R: web thickness over notch radius (dimensionless).
        web_mm: web thickness t (mm).
        arm_mm: lever a (mm).
    """

    t_over_R: tuple[float, float] = _INF_RANGE
    web_mm: tuple[float, float] = _INF_RANGE
    arm_mm: tuple[float, float] = _INF_RANGE

    def __post_init__(self):
        for name in ("t_over_R", "web_mm", "arm_mm"):
            object.__setattr__(self, name, _as_range(f"fit_range.{name}", getattr(self, name)))

    def contains(self, t_over_R, web_mm=None, arm_mm=None) -> np.ndarray:
        """Boolean mask (broadcast shape) of points inside every given range.

        A small relative slack (1e-9) absorbs rounding at the range ends.
        """
        def inside(v, rng):
            v = np.asarray(v, dtype=float)
            lo, hi = rng
            tol = 1e-9 * max(abs(lo), abs(hi) if math.isfinite(hi) else abs(lo), 1e-300)
            return (v >= lo - tol) & (v <= hi + tol)

        mask = inside(t_over_R, self.t_over_R)
        if web_mm is not None:
            mask = mask & inside(web_mm, self.web_mm)
        if arm_mm is not None:
            mask = mask & inside(arm_mm, self.arm_mm)
        return np.asarray(mask)


@dataclass(frozen=True)
class Correction:
    """FEM-fitted correction of the Euler-Bernoulli stiffness.

    Model: K = K_EB * (1 + c3 + c4 w) / (1 + c1 s + c2 s^2), s = t / R,
    w = sqrt(t R) / b.
    c1, c2 carry the notch-theory error against plane-stress FEM (c1 of order
    0.39 for a symmetric circular notch, 0.56 for the single-sided one), c3
    and c4 the plane-stress -> 3D stiffening. A web much wider (b) than the
    hinge's bending length sqrt(t R) is held near plane strain, so the 3D
    gain falls as w grows (measured: 1.059 ... 1.107 over the design range).

    Attributes:
        coefficients: (c1, c2, c3, c4); three numbers mean c4 = 0.
        fit_range: :class:`FitRange` the coefficients were fitted over.
        residual_rel: largest relative residual of the fit, |K_fit / K_ref - 1|
            (``None`` for the identity).
        source: what the reference stiffness was (model, mesh, date, commit).

    Raises:
        DesignError: non-finite coefficients, a negative residual, or a
            denominator 1 + c1 s + c2 s^2 <= 0 at the ends of a finite
            t/R fit range.
    """

    coefficients: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0)
    fit_range: FitRange = field(default_factory=FitRange)
    residual_rel: float | None = None
    source: str = "none: uncorrected Euler-Bernoulli"

    def __post_init__(self):
        try:
            coeffs = tuple(float(c) for c in self.coefficients)
        except (TypeError, ValueError):
            raise DesignError("coefficients", self.coefficients, "numbers c1, c2, c3[, c4]") from None
        if len(coeffs) == 3:
            coeffs = coeffs + (0.0,)
        if len(coeffs) != 4 or not all(math.isfinite(c) for c in coeffs):
            raise DesignError("coefficients", self.coefficients, "finite numbers c1, c2, c3[, c4]")
        if coeffs[2] <= -1.0:
            raise DesignError("coefficients.c3", coeffs[2], "c3 > -1")
        object.__setattr__(self, "coefficients", coeffs)
        if not isinstance(self.fit_range, FitRange):
            raise DesignError("fit_range", self.fit_range, "a FitRange")
        if self.residual_rel is not None:
            r = float(self.residual_rel)
            if not math.isfinite(r) or r < 0:
                raise DesignError("residual_rel", self.residual_rel, "a finite number >= 0")
            object.__setattr__(self, "residual_rel", r)
        lo, hi = self.fit_range.t_over_R
        if math.isfinite(hi):
            s = np.linspace(lo, hi, 65)
            if np.any(self._denominator(s) <= 0):
                raise DesignError("coefficients", coeffs,
                                  "1 + c1 s + c2 s^2 > 0 over the t/R fit range")

    @property
    def is_identity(self) -> bool:
        return self.coefficients == (0.0, 0.0, 0.0, 0.0)

    def _denominator(self, s) -> np.ndarray:
        c1, c2 = self.coefficients[:2]
        s = np.asarray(s, dtype=float)
        return 1.0 + c1 * s + c2 * s * s

    def factor(self, t_over_R, width_ratio=0.0) -> np.ndarray:
        """K / K_EB at t/R and w = sqrt(t R) / b (array-like, broadcast).

        Raises:
            ValueError: the denominator is <= 0 at some t/R (far outside the fit).
        """
        den = self._denominator(t_over_R)
        if np.any(den <= 0):
            raise ValueError("correction denominator 1 + c1 s + c2 s^2 <= 0 at t/R = "
                             f"{np.ravel(np.asarray(t_over_R, float)[den <= 0])[:3].tolist()}")
        c3, c4 = self.coefficients[2:]
        return (1.0 + c3 + c4 * np.asarray(width_ratio, dtype=float)) / den

    def error_estimate_rel(self, t_over_R) -> np.ndarray:
        """Relative model error of the (corrected) closed form: the fit residual,
        or 0.39 t/R for the identity (the uncorrected Euler-Bernoulli bias)."""
        s = np.asarray(t_over_R, dtype=float)
        if self.is_identity or self.residual_rel is None:
            return UNCORRECTED_BIAS_PER_T_OVER_R * s
        return np.full_like(s, self.residual_rel)

    def as_json(self) -> dict:
        """The JSON object :func:`load_correction` reads."""
        c1, c2, c3, c4 = self.coefficients
        return {
            "model": "K = K_EB * (1 + c3 + c4*w) / (1 + c1*s + c2*s^2), s = t/R, w = sqrt(t*R)/b",
            "coefficients": {"c1": c1, "c2": c2, "c3": c3, "c4": c4},
            "fit_range": {"t_over_R": list(self.fit_range.t_over_R),
                          "web_mm": list(self.fit_range.web_mm),
                          "arm_mm": list(self.fit_range.arm_mm)},
            "residual_rel": self.residual_rel,
            "source": self.source,
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> "Correction":
        """Inverse of :meth:`as_json`.

        Raises:
            DesignError: missing keys or invalid values (field named).
        """
        if not isinstance(data, Mapping):
            raise DesignError("stiffness_correction", type(data).__name__, "a JSON object")
        try:
            co = data["coefficients"]
            coeffs = (co["c1"], co["c2"], co["c3"], co.get("c4", 0.0))
            fr = data["fit_range"]
            rng = FitRange(t_over_R=fr["t_over_R"], web_mm=fr["web_mm"], arm_mm=fr["arm_mm"])
            # The FEM fit writes residual_rel_max / reference; as_json writes
            # residual_rel / source. Either pair is read.
            residual = data["residual_rel"] if "residual_rel" in data else data["residual_rel_max"]
            source = data["source"] if "source" in data else data["reference"]
        except (KeyError, TypeError) as exc:
            raise DesignError(f"stiffness_correction.{exc.args[0] if exc.args else '?'}", None,
                              "keys coefficients{c1,c2,c3}, fit_range{t_over_R,web_mm,arm_mm}, "
                              "residual_rel, source") from None
        if not isinstance(source, str) or not source.strip():
            raise DesignError("stiffness_correction.source", source, "a non-empty string")
        return cls(coefficients=coeffs, fit_range=rng, residual_rel=residual, source=source)


#: The identity correction (uncorrected Euler-Bernoulli).
IDENTITY = Correction()


def load_correction(path: str | Path | None = None) -> Correction:
    """Read the FEM-fitted correction; the identity when the file does not exist.

    File (JSON, default ``src/tactcad/data/stiffness_correction.json``)::

        {
          "model": "K = K_EB * (1 + c3) / (1 + c1*s + c2*s^2), s = t/R",
          "coefficients": {"c1": 0.39, "c2": 0.0, "c3": 0.09},
          "fit_range": {"t_over_R": [0.075, 1.0], "web_mm": [0.15, 0.4],
                        "arm_mm": [4.0, 8.0]},
          "residual_rel": 0.01,
          "source": "fem3d C3D10, h = t/6, Richardson; commit abc1234"
        }

    ``model`` is informative; the others are required. Produce the object with
    :func:`fit_correction` and :meth:`Correction.as_json`.

    Raises:
        DesignError: unreadable JSON or invalid content (the field is named).
    """
    p = Path(path) if path is not None else CORRECTION_FILE
    if not p.exists():
        return IDENTITY
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise DesignError("stiffness_correction", str(p), "a readable JSON file", str(exc)) from None
    return Correction.from_json(data)


def apply_correction(K_eb, t_over_R, correction: Correction = IDENTITY, *, web_mm=None,
                     arm_mm=None, width_ratio=0.0,
                     warn: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Corrected stiffness and the mask of points inside the fit range.

    Args:
        K_eb: Euler-Bernoulli stiffness (N/mm), array-like.
        t_over_R: web thickness over notch radius, broadcast with ``K_eb``.
        correction: the correction (default: identity).
        web_mm, arm_mm: optional, also checked against the fit range.
        width_ratio: w = sqrt(t R) / b, the hinge length over the sheet width.
        warn: emit :class:`CorrectionRangeWarning` when any point is outside.

    Returns:
        (K, inside): corrected K (N/mm) and a boolean mask, True where every
        given parameter lies in the fit range (all True for the identity).

    Raises:
        ValueError: the correction's denominator is <= 0 at some t/R.
    """
    K = np.asarray(K_eb, dtype=float) * correction.factor(t_over_R, width_ratio)
    inside = np.broadcast_to(correction.fit_range.contains(t_over_R, web_mm, arm_mm),
                             K.shape).copy()
    if warn:
        _warn_outside(correction, inside)
    return K, inside


def _warn_outside(correction: Correction, inside: np.ndarray) -> None:
    n_out = int(np.size(inside) - np.count_nonzero(inside))
    if n_out:
        fr = correction.fit_range
        warnings.warn(
            f"stiffness correction used outside its fit range at {n_out} of {np.size(inside)} "
            f"points (t/R {fr.t_over_R}, web {fr.web_mm} mm, arm {fr.arm_mm} mm; "
            f"source: {correction.source})", CorrectionRangeWarning, stacklevel=3)


def fit_correction(t_over_R, K_eb, K_ref, *, web_mm, arm_mm, source: str) -> Correction:
    """Least-squares fit of the correction to reference stiffnesses (e.g. FEM).

    K_eb / K_ref = (1 + c1 s + c2 s^2) / (1 + c3) is linear in
    d = (1, c1, c2) / (1 + c3); the fit solves for d in the relative sense
    (rows scaled by K_ref / K_eb) and reports the largest relative residual.

    Args:
        t_over_R, K_eb, K_ref, web_mm, arm_mm: 1-D arrays of equal length (>= 3).
        source: description of the reference (stored in the correction).

    Returns:
        :class:`Correction` whose fit range spans the given samples.

    Raises:
        ValueError: fewer than 3 samples, unequal lengths, or non-positive K.
    """
    s = np.ravel(np.asarray(t_over_R, float))
    ke = np.ravel(np.asarray(K_eb, float))
    kr = np.ravel(np.asarray(K_ref, float))
    web = np.ravel(np.asarray(web_mm, float))
    arm = np.ravel(np.asarray(arm_mm, float))
    n = s.size
    if n < 3 or any(v.size != n for v in (ke, kr, web, arm)):
        raise ValueError("fit_correction needs >= 3 samples and equal-length arrays")
    if np.any(ke <= 0) or np.any(kr <= 0) or not np.all(np.isfinite(ke * kr)):
        raise ValueError("stiffnesses must be finite and > 0")
    ratio = ke / kr
    X = np.stack([np.ones_like(s), s, s * s], axis=1)
    wgt = 1.0 / ratio
    d, *_ = np.linalg.lstsq(X * wgt[:, None], ratio * wgt, rcond=None)
    c3 = 1.0 / d[0] - 1.0
    c1, c2 = d[1] / d[0], d[2] / d[0]
    k_fit = ke * (1.0 + c3) / (1.0 + c1 * s + c2 * s * s)
    residual = float(np.max(np.abs(k_fit / kr - 1.0)))
    rng = FitRange(t_over_R=(float(s.min()), float(s.max())),
                   web_mm=(float(web.min()), float(web.max())),
                   arm_mm=(float(arm.min()), float(arm.max())))
    return Correction(coefficients=(c1, c2, c3), fit_range=rng, residual_rel=residual,
                      source=source)


# ---------------------------------------------------------------------------
# Element-level API
# ---------------------------------------------------------------------------
def _resolve(corrected: bool, correction: Correction | None) -> Correction:
    if not corrected:
        return IDENTITY
    return correction if correction is not None else load_correction()


def estimate_closed_form(g: ElementGeometry, material: Material, element: int | None = None,
                         corrected: bool = True, *,
                         correction: Correction | None = None) -> StiffnessResult:
    """Closed-form stiffness and gauge strain of one flexure element.

    Args:
        g: element geometry (plan). material: plan material.
        element: paper element number to carry in the result.
        corrected: apply the FEM-fitted correction (``correction``, or the
            file read by :func:`load_correction`; identity when absent).
        correction: explicit correction, overrides the file.

    Returns:
        :class:`StiffnessResult` with model ``closed-form``. The gauge strain is
        the Euler-Bernoulli value (the correction acts on K only). The error
        estimate is the correction's residual, or 0.39 t/R when uncorrected.

    Warns:
        CorrectionRangeWarning: the geometry lies outside the correction's fit range.
    """
    start = time.perf_counter()
    corr = _resolve(corrected, correction)
    t, R, a = g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm
    kw = _geometry_kwargs(g, material)
    k_eb = closed_form_stiffness(t, R, a, **kw)
    w = math.sqrt(t * R) / g.sheet_thickness_mm
    k, _ = apply_correction(k_eb, t / R, corr, web_mm=t, arm_mm=a, width_ratio=w)
    eps = gauge_strain_per_newton(t, a, E=kw["E"], b=kw["b"])
    err = corr.error_estimate_rel(t / R)
    return StiffnessResult(element=element, model=MODEL_NAME, stiffness_N_per_mm=float(k),
                           gauge_strain_per_N=float(eps), error_estimate_rel=float(err),
                           wall_time_s=time.perf_counter() - start)


def web_for_stiffness(k_target: float, g: ElementGeometry, material: Material, *,
                      corrected: bool = True, correction: Correction | None = None,
                      bracket_mm: tuple[float, float] = WEB_BRACKET_MM,
                      xtol_mm: float = 1e-9) -> float:
    """Web thickness t (mm) for which the closed form gives stiffness ``k_target``.

    All other dimensions are taken from ``g``; K(t) is strictly increasing, so
    the root in ``bracket_mm`` is unique (scipy ``brentq``). Used to infer the
    as-built web of a calibrated element (Table 1).

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
    kw = _geometry_kwargs(g, material)

    def k_of(t: float) -> float:
        k_eb = closed_form_stiffness(t, R, a, **kw)
        w = math.sqrt(t * R) / g.sheet_thickness_mm
        return float(apply_correction(k_eb, t / R, corr, width_ratio=w, warn=False)[0])

    lo, hi = bracket_mm
    k_lo, k_hi = k_of(lo), k_of(hi)
    if not k_lo <= k_target <= k_hi:
        raise ValueError(f"k_target = {k_target:g} N/mm: allowed {k_lo:.4g} ... {k_hi:.4g} N/mm "
                         f"(web {lo:g} ... {hi:g} mm at arm {a:g} mm, R {R:g} mm)")
    t = brentq(lambda x: k_of(x) - k_target, lo, hi, xtol=xtol_mm, rtol=1e-14)
    _warn_outside(corr, corr.fit_range.contains(t / R, t, a))
    return float(t)
