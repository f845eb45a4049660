"""Modal level "closed-form": the first in-plane and the first out-of-plane
natural frequency from Rayleigh quotients, f1 = (1 / 2 pi) sqrt(K / m_eff).

Trial shape: the element's static deflection under a tip force at the
contact centre (the shape the stiffness K is defined by), split as the
closed form splits its compliance (:func:`tactcad.mechanics.closed_form.closed_form_compliance`):

* the notch share (1 - beta) of the compliance turns everything in front of
  the hinge (x >= x_h) rigidly about the web centre (x_h, y_w):
  u = theta (-(y - y_w), x - x_h);
* the arm share beta bends the arm as a cantilever from the hinge loaded at
  the lever a = x_t - x_h: u_y = s^2 (3a - s) / (2 a^3) per unit deflection
  at the load (s = x - x_h), continued linearly beyond the load point.

With the shape normalised to unit deflection of the contact centre, the
kinetic energy gives the effective mass

    m_eff = rho b * integral over x >= x_h of |u|^2 dA,

and the strain energy of the same static shape is K / 2 per unit
deflection squared, so omega1^2 = K / m_eff (Rayleigh's quotient with the
static deflection as trial function: an upper bound on the exact first
frequency for the exact K; Rayleigh, "The Theory of Sound" (1877), sec. 88;
W. T. Thomson, "Theory of Vibration with Applications", 5th ed., ch. 7).
K is the corrected closed-form stiffness. The area integral runs over the
exact wire-cut profile (:func:`tactcad.geometry.profile.element_profile`)
clipped at x = x_h, by vertical chords (exact in y, midpoint rule in x).
The material behind the hinge (notch walls, base) is taken as still.

Error estimate: half the closed form's K error (f ~ sqrt K) plus
:data:`SHAPE_ERROR_REL`, which bounds the distance of this quotient to
fem3d's first in-plane frequency measured over the design domain's corners
(at most 1.5 %, thick web in a thin sheet; tests/mechanics/test_modal.py).

Added mass (gauge, adhesive, leads, solder pads, anything bonded on):
each :class:`~tactcad.mechanics.modal_result.PointMass` m_i at (x_i, y_i)
adds m_i |u(x_i, y_i)|^2 to m_eff (the same trial shape; zero behind the
hinge, which is taken as still): omega1^2 = K / (m_eff + sum m_i |u_i|^2).
A mass at the contact centre (|u| = 1) lowers f1 by 1 - sqrt(m_eff /
(m_eff + m)).

Out of the plane: the arm swings out of the sheet's plane by bending about
the other axis and by twisting the web about its own axis; two bounds by
Rayleigh(-Ritz) (:func:`out_of_plane_bounds`), from x = x_h - R (where the
notch begins) on the exact profile's vertical chords (h(x) by b):

* upper, the web's twist restrained: the static deflection of a Timoshenko
  cantilever (I = h b^3 / 12, A = h b, shear factor 5/6) under a load out of
  the plane at the contact centre (:func:`bending_rayleigh`);
* lower, the web free to twist as a Saint-Venant strip (J of each chord's
  rectangle, Roark table 10.1): Rayleigh-Ritz on that bending shape and the
  twist about the web's axis (x, y = y_w), the lowest root.

A short web (length ~ 2R, a few webs wide) twists with its ends' warping
held, between the two. The level reports their geometric mean, with the
error estimate sqrt(upper / lower) - 1 that reaches both. fem3d's first
out-of-plane mode lay inside the bounds on every element of both shipped
examples (docs/explanation/modal.md).

That error estimate is a factor, not a +/-: the geometric mean f times and over
(1 + e) gives the bounds. Where the bounds lie far apart (a stiff sheet whose free
twist is much softer than its bending: a 17-4PH array's 0.105 mm web, 1352.9 Hz
with bounds a factor 6.84 apart, e = 1.61) e exceeds 1 and f (1 - e) is below 0 Hz: the formula, made for
close bounds, says nothing as a +/- there. Each out-of-plane mode therefore carries
its bounds (``Mode.bounds_Hz``, f / (1 + e) and f (1 + e), e the mode's whole error
estimate), and the modal tables print them instead of a +/- above 100 %; fem3d is
the level that computes the mode.

Units: mm, N, MPa, t/mm^3, Hz, s.
"""

from __future__ import annotations

import math
import time
from typing import Callable

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.geometry.profile import contour_points, element_profile
from tactcad.mechanics.fem.fem_mesh import clip_chain
from tactcad.mechanics.modal_result import ModalResult, Mode, PointMass, density_t_per_mm3

#: Model error of the Rayleigh quotient against fem3d's first in-plane
#: frequency (relative), beyond half the K error: measured at the domain's corners.
SHAPE_ERROR_REL = 0.03

#: Vertical chords of the mass integral.
N_CHORDS = 1200

#: Sheet thickness / web thickness below which the out-of-plane modes may come
#: first and the base behind the notch bends out of the plane too: there the
#: closed form's out-of-plane bounds are not verified (resonance takes fem3d).
OUT_OF_PLANE_SHEET_OVER_WEB = 3.0
#: The out-of-plane error estimate taken in such a thin sheet: at the domain's
#: thin-sheet corner (0.5 mm sheet, 1 mm web) both bounds lay 35 % above
#: fem3d's 2321 Hz.
THIN_SHEET_OUT_OF_PLANE_ERROR_REL = 0.5

#: Shear correction factor of a rectangular section (Timoshenko and Gere,
#: Mechanics of Materials): the out-of-plane cantilever's shear deflection.
SHEAR_FACTOR = 5.0 / 6.0



def chord_integrals(points: np.ndarray, xs: np.ndarray, y0: float,
                    powers: tuple[int, ...]) -> tuple[np.ndarray, ...]:
    """integral (y - y0)^n dy over the polygon's vertical chords at ``xs``, for each n of
    ``powers`` (shapes (m,), mm^(n+1)); the polygon closed, first point not repeated."""
    p = np.asarray(points, float)
    q = np.roll(p, -1, axis=0)
    x0, y_0, x1, y1 = p[:, 0], p[:, 1], q[:, 0], q[:, 1]
    X = xs[:, None]
    crosses = (np.minimum(x0, x1) <= X) & (X < np.maximum(x0, x1)) & (x0 != x1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ys = y_0 + (X - x0) * (y1 - y_0) / (x1 - x0)
    ys = np.where(crosses, ys, np.nan)
    ys = np.sort(ys, axis=1)  # NaN last; crossings come in pairs (inside between)
    out = [np.zeros(len(xs)) for _ in powers]
    cnt = np.sum(crosses, axis=1)
    for k in range(0, int(cnt.max(initial=0)) - 1, 2):
        a, b = ys[:, k], ys[:, k + 1]
        ok = np.isfinite(a) & np.isfinite(b)
        for total, n in zip(out, powers):
            total += np.where(ok, ((b - y0) ** (n + 1) - (a - y0) ** (n + 1)) / (n + 1), 0.0)
    return tuple(out)


def chord_moments(points: np.ndarray, xs: np.ndarray, y0: float) -> tuple[np.ndarray, np.ndarray]:
    """Length and second moment about y0 of the polygon's vertical chords.

    Args:
        points: closed polygon, shape (n, 2) (mm; first point not repeated).
        xs: abscissae of the chords, shape (m,) (mm).
        y0: reference height (mm).

    Returns:
        (integral dy, integral (y - y0)^2 dy) at each x, shapes (m,), (mm, mm^3).
    """
    length, second = chord_integrals(points, xs, y0, (0, 2))
    return length, second


def arm_shape(s: np.ndarray, a: float) -> np.ndarray:
    """Cantilever deflection per unit deflection at the load (lever a, mm):
    s^2 (3a - s) / (2 a^3) up to the load, then along its end slope 3 / (2a)."""
    s = np.asarray(s, float)
    inside = s**2 * (3 * a - s) / (2 * a**3)
    beyond = 1.0 + 1.5 * (s - a) / a
    return np.where(s <= a, inside, beyond)


def in_plane_shape_sq(g: ElementGeometry, arm_share: float, x_mm: float, y_mm: float) -> float:
    """|u|^2 of the in-plane trial shape at (x, y) per unit deflection of the contact
    centre (0 behind the hinge, taken as still)."""
    xh, yw = g.web_centre_mm
    a = g.contact_centre_mm[0] - xh
    s = x_mm - xh
    if s < 0:
        return 0.0
    rot = 1.0 - arm_share
    uy = rot * s / a + arm_share * float(arm_shape(np.array(s), a))
    ux = -rot * (y_mm - yw) / a
    return ux * ux + uy * uy


def added_mass_t(masses, shape_sq) -> float:
    """sum m_i |u_i|^2 (t) of ``masses`` (:class:`PointMass`) for a trial shape
    ``shape_sq(x, y)`` normalised at the contact centre."""
    return float(sum(m.mass_t * shape_sq(m.x_mm, m.y_mm) for m in masses))


def bending_rayleigh(xs: np.ndarray, dx: float, depth_mm: float, width_mm: np.ndarray,
                     E_MPa: float, G_MPa: float, rho_t_per_mm3: float, x_load_mm: float,
                     ) -> tuple[float, float, np.ndarray]:
    """Rayleigh quotient of a Timoshenko cantilever of varying width with its
    static deflection under a unit load at ``x_load_mm`` as the trial shape.

    The cantilever is clamped at xs[0] - dx/2 and sampled at the cell
    centres ``xs`` (mm, spacing ``dx``); the section is ``width_mm`` (array)
    by ``depth_mm`` in the bending direction: I = w d^3 / 12, A = w d.
    Slope = integral of M / (E I) plus the shear angle V / (k G A) (k = 5/6).

    Returns:
        (K at the load (N/mm), m_eff (t), shape normalised to 1 at the load).
        For a uniform bar loaded at its end, f = sqrt(K / m_eff) / 2 pi is
        1.5 % above the exact first bending frequency (Rayleigh's upper bound:
        sqrt(140 / 11) against 1.875^2).
    """
    w = np.asarray(width_mm, float)
    inertia = w * depth_mm ** 3 / 12.0
    area = w * depth_mm
    moment = np.clip(x_load_mm - xs, 0.0, None)
    shear = (xs < x_load_mm).astype(float)
    curvature = moment / (E_MPa * inertia)
    edges = np.concatenate([[0.0], np.cumsum(curvature * dx)])
    slope = 0.5 * (edges[:-1] + edges[1:]) + shear / (SHEAR_FACTOR * G_MPa * area)
    w_edges = np.concatenate([[0.0], np.cumsum(slope * dx)])
    deflection = 0.5 * (w_edges[:-1] + w_edges[1:])
    at_load = float(np.interp(x_load_mm, xs, deflection))
    shape = deflection / at_load
    m_eff = float(rho_t_per_mm3 * np.sum(shape ** 2 * area) * dx)
    return 1.0 / at_load, m_eff, shape


def rectangle_torsion_constant(long_mm, short_mm) -> np.ndarray:
    """Saint-Venant torsion constant J (mm^4) of a solid rectangle (array-like sides):
    a c^3 (1/3 - 0.21 c/a (1 - c^4 / (12 a^4))), a the longer side, c the shorter
    (Roark's Formulas for Stress and Strain, 7th ed., table 10.1 case 4)."""
    a = np.maximum(long_mm, short_mm)
    c = np.minimum(long_mm, short_mm)
    return a * c ** 3 * (1 / 3 - 0.21 * c / a * (1 - c ** 4 / (12 * a ** 4)))


def out_of_plane_bounds(g: ElementGeometry, material: Material,
                        added_masses: tuple[PointMass, ...] = ()) -> tuple[float, float]:
    """(upper, lower) bound on the first out-of-plane frequency (Hz) (module docstring):
    the web's twist restrained (bending alone) and free as a Saint-Venant strip, each by
    Rayleigh(-Ritz) on the shapes below: the Timoshenko cantilever's bending out of the plane
    (:func:`bending_rayleigh`) and the twist about the web's axis (x, y = y_w) under a
    unit torque, phi(x) = integral of dx / (G J(x)) with J of each chord's h(x) x b
    rectangle (:func:`rectangle_torsion_constant`); the mass matrix from the exact
    profile's chords (u_z = w(x) + phi(x) (y - y_w), plus the twist's u_y) and the
    ``added_masses`` at their places; the lowest root of det(K - omega^2 M) = 0."""
    return out_of_plane_bounds_with_and_without(g, material, added_masses)[0]


def out_of_plane_bounds_with_and_without(g: ElementGeometry, material: Material,
                                         added_masses: tuple[PointMass, ...] = ()
                                         ) -> tuple[tuple[float, float], tuple[float, float]]:
    """:func:`out_of_plane_bounds` with ``added_masses`` and without them (the bare
    element), from one pass over the profile's chords: the shapes, stiffnesses and the
    element's own mass terms do not depend on the added masses, which only add to the
    mass terms, so each pair is, to the bit, what its own call gives.

    Args:
        g: element geometry (mm). material: E (MPa), nu, density (g/cm^3).
        added_masses: :class:`~tactcad.mechanics.modal_result.PointMass` on the element.

    Returns:
        ((upper, lower) with the added masses, (upper, lower) without them) (Hz).

    Raises:
        DesignError: the material has no density.
    """
    rho = density_t_per_mm3(material)
    xh, yw = g.web_centre_mm
    x0 = xh - g.notch_radius_mm
    outline = clip_chain(element_profile(g).outer, x0)
    pts = np.array(contour_points(outline, sagitta_mm=1e-4))
    x_max = float(pts[:, 0].max())
    dx = (x_max - x0) / N_CHORDS
    xs = x0 + dx * (np.arange(N_CHORDS) + 0.5)
    height, first, second = chord_integrals(pts, xs, yw, (0, 1, 2))
    b = g.sheet_thickness_mm
    E = material.youngs_modulus_MPa
    G = E / (2 * (1 + material.poisson_ratio))
    h = np.maximum(height, 1e-9)
    k_w, _, w = bending_rayleigh(xs, dx, b, h, E, G, rho, g.contact_centre_mm[0])
    twist_edges = np.concatenate([[0.0], np.cumsum(dx / (G * rectangle_torsion_constant(h, b)))])
    phi = 0.5 * (twist_edges[:-1] + twist_edges[1:])
    k_phi = 1.0 / phi[-1]  # N mm / rad at the free end
    phi = phi / phi[-1]
    # kinetic energy: u_z = a w + c phi (y - yw), u_y = -c phi z (about the mid-plane)
    bare = (rho * b * np.sum(w * w * h) * dx, rho * b * np.sum(w * phi * first) * dx,
            rho * b * np.sum(phi * phi * (second + h * b * b / 12.0)) * dx)
    m_ww, m_wp, m_pp = bare
    for m in added_masses:
        wi = float(np.interp(m.x_mm, xs, w, left=0.0))
        pi = float(np.interp(m.x_mm, xs, phi, left=0.0)) * (m.y_mm - yw)
        m_ww, m_wp, m_pp = m_ww + m.mass_t * wi * wi, m_wp + m.mass_t * wi * pi, \
            m_pp + m.mass_t * pi * pi
    stiffness = np.diag([k_w, k_phi])
    loaded = _rayleigh_ritz_bounds(stiffness, k_w, m_ww, m_wp, m_pp)
    return loaded, (_rayleigh_ritz_bounds(stiffness, k_w, *bare) if added_masses else loaded)


def _rayleigh_ritz_bounds(stiffness: np.ndarray, k_w: float, m_ww: float, m_wp: float,
                          m_pp: float) -> tuple[float, float]:
    """(bending alone, bending and twist) frequencies (Hz) of the two-shape Rayleigh-Ritz
    problem: ``stiffness`` diag(k_w (N/mm), k_phi (N mm/rad)), the mass terms (t, t mm,
    t mm^2)."""
    from scipy.linalg import eigh

    mass = np.array([[m_ww, m_wp], [m_wp, m_pp]])
    lam = eigh(stiffness, mass, eigvals_only=True)
    return (math.sqrt(k_w / m_ww) / (2 * math.pi), math.sqrt(max(lam[0], 0.0)) / (2 * math.pi))


def out_of_plane_may_lead(g: ElementGeometry) -> bool:
    """True when the sheet is thinner than :data:`OUT_OF_PLANE_SHEET_OVER_WEB` webs: the
    out-of-plane modes may come first and the closed form's bounds are not verified."""
    return g.sheet_thickness_mm < OUT_OF_PLANE_SHEET_OVER_WEB * g.web_thickness_mm


def out_of_plane_frequency(g: ElementGeometry, material: Material,
                           added_masses: tuple[PointMass, ...] = ()) -> tuple[float, float]:
    """(first out-of-plane frequency (Hz), its relative error estimate): the geometric
    mean of :func:`out_of_plane_bounds`, with the error sqrt(upper / lower) - 1 that
    reaches both bounds; in a thin sheet (:func:`out_of_plane_may_lead`) at least
    :data:`THIN_SHEET_OUT_OF_PLANE_ERROR_REL`. The error is a factor about the mean, made
    for close bounds: above 1 (bounds more than a factor 4 apart) it is no +/- (the mean
    less it is below 0 Hz), and only the bounds (:func:`mode_with_error`) say anything."""
    return frequency_of_bounds(g, *out_of_plane_bounds(g, material, added_masses))


def frequency_of_bounds(g: ElementGeometry, upper: float, lower: float) -> tuple[float, float]:
    """:func:`out_of_plane_frequency` of its bounds (Hz): (their geometric mean (Hz), the
    relative error sqrt(upper / lower) - 1, at least
    :data:`THIN_SHEET_OUT_OF_PLANE_ERROR_REL` in a thin sheet)."""
    err = math.sqrt(upper / lower) - 1.0
    if out_of_plane_may_lead(g):
        err = max(err, THIN_SHEET_OUT_OF_PLANE_ERROR_REL)
    return math.sqrt(upper * lower), err


def mode_with_error(number: int, frequency_Hz: float, family: str, error_rel: float) -> Mode:
    """A closed-form mode with its relative error estimate; an out-of-plane one also with
    its bounds (Hz) f / (1 + e) and f (1 + e) (module docstring: its error is a factor
    about the bounds' geometric mean, above 1 no +/-).

    Args:
        number: the mode's number (1 = lowest). frequency_Hz: its frequency (Hz).
        family: "in-plane" or "out-of-plane". error_rel: its relative error estimate e.

    Returns:
        The :class:`~tactcad.mechanics.modal_result.Mode`.
    """
    bounds = ((frequency_Hz / (1 + error_rel), frequency_Hz * (1 + error_rel))
              if family == "out-of-plane" else None)
    return Mode(number, frequency_Hz, family, error_rel, bounds)


def effective_mass_t(g: ElementGeometry, material: Material, arm_share: float) -> float:
    """m_eff (t) of the element at its contact centre (module docstring).

    Args:
        arm_share: beta, the arm's share of the tip compliance (0..1).

    Raises:
        DesignError: the material has no density.
    """
    rho = density_t_per_mm3(material)
    xh, yw = g.web_centre_mm
    a = g.contact_centre_mm[0] - xh
    outline = clip_chain(element_profile(g).outer, xh)
    pts = np.array(contour_points(outline, sagitta_mm=1e-4))
    x_max = float(pts[:, 0].max())
    dx = (x_max - xh) / N_CHORDS
    xs = xh + dx * (np.arange(N_CHORDS) + 0.5)
    length, second = chord_moments(pts, xs, yw)
    s = xs - xh
    rot = 1.0 - arm_share
    uy = rot * s / a + arm_share * arm_shape(s, a)
    # |u|^2 = u_x^2 + u_y^2 with u_x = -rot (y - yw) / a from the rotation
    integrand = (rot / a) ** 2 * second + uy**2 * length
    return float(rho * g.sheet_thickness_mm * np.sum(integrand) * dx)


def estimate_modal_closed_form(g: ElementGeometry, material: Material, *,
                               element: int | None = None, modes: int = 1,
                               progress=None, keep_shapes: bool = False,
                               added_masses: tuple[PointMass, ...] = ()) -> ModalResult:
    """First in-plane and first out-of-plane natural frequency by Rayleigh's
    quotient (module docstring), with ``added_masses`` counted.

    Args:
        g: element geometry (mm). material: E (MPa), nu, density (g/cm^3).
        element: paper element number, carried into the result.
        modes: modes asked for: 1 gives the lower of the two, 2 or more both.
        added_masses: :class:`~tactcad.mechanics.modal_result.PointMass` on the element.

    Returns:
        :class:`~tactcad.mechanics.modal_result.ModalResult` with the modes
        (Hz), ascending, the frequency without the added masses
        (``bare_first_Hz``) and the error estimate of each mode and of the first
        (half the K error + :data:`SHAPE_ERROR_REL` in the plane; half the K error +
        the bounds' half-spread out of it, :func:`out_of_plane_frequency`); the
        out-of-plane mode with its bounds (Hz, :func:`mode_with_error`).

    Raises:
        DesignError: the material has no density. ValueError: modes < 1.
    """
    from tactcad.mechanics.closed_form import _geometry_kwargs, closed_form_compliance, \
        estimate_closed_form

    if modes < 1:
        raise ValueError(f"modes = {modes!r}: allowed 1 or more")
    t0 = time.perf_counter()
    k = estimate_closed_form(g, material)
    parts = closed_form_compliance(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
                                   **_geometry_kwargs(g, material))
    beta = float((parts.arm_bending + parts.arm_shear) / parts.total)
    m = effective_mass_t(g, material, beta)
    m_add = added_mass_t(added_masses, lambda x, y: in_plane_shape_sq(g, beta, x, y))
    f_in = math.sqrt(k.stiffness_N_per_mm / (m + m_add)) / (2 * math.pi)
    # with and without the added masses from one pass over the chords
    loaded, bare = out_of_plane_bounds_with_and_without(g, material, added_masses)
    f_out, out_error = frequency_of_bounds(g, *loaded)
    f_out_bare = frequency_of_bounds(g, *bare)[0] if added_masses else f_out
    found = sorted([(f_in, "in-plane", math.sqrt(k.stiffness_N_per_mm / m) / (2 * math.pi),
                     SHAPE_ERROR_REL),
                    (f_out, "out-of-plane", f_out_bare, out_error)])[:max(1, min(modes, 2))]
    total = sum(p.mass_g for p in added_masses)
    return ModalResult(element=element, model="closed-form",
                       modes=tuple(mode_with_error(i + 1, f, fam,
                                                   0.5 * k.error_estimate_rel + shape_error)
                                   for i, (f, fam, _, shape_error) in enumerate(found)),
                       error_estimate_rel=0.5 * k.error_estimate_rel + found[0][3],
                       wall_time_s=time.perf_counter() - t0,
                       added_mass_g=total, bare_first_Hz=found[0][2] if added_masses else None,
                       basis=(f"Rayleigh quotient: in the plane K {k.stiffness_N_per_mm:.4g} N/mm "
                              f"over m_eff {m * 1e6:.4g} g (static deflection shape, arm share "
                              f"{beta:.3f}); out of it {f_out:.4g} Hz +/- {100 * out_error:.0f} %, "
                              "between the web's twist restrained and free (Rayleigh-Ritz)"
                              + (f"; added {total * 1e3:.3g} mg, effective {m_add * 1e9:.3g} mg "
                                 "in the plane" if added_masses else "")))
