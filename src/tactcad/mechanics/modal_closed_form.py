"""Modal level "closed-form": the first in-plane natural frequency from a
Rayleigh quotient, f1 = (1 / 2 pi) sqrt(K / m_eff).

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

In-plane only: out-of-plane bending and twisting of the web are not
estimated here (beam-theory quotients for them missed fem3d by 20-170 %
at the corners: a short wide web does not twist as a Saint-Venant strip).
In a thin sheet (b below about the web's height: 0.5 mm sheet, 1 mm web)
the first mode is out of the plane; only fem3d finds it.

Units: mm, N, MPa, t/mm^3, Hz, s.
"""

from __future__ import annotations

import math
import time

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.geometry.profile import contour_points, element_profile
from tactcad.mechanics.fem.fem_mesh import clip_chain
from tactcad.mechanics.modal_result import ModalResult, Mode, density_t_per_mm3

#: Model error of the Rayleigh quotient against fem3d's first in-plane
#: frequency (relative), beyond half the K error: measured at the domain's corners.
SHAPE_ERROR_REL = 0.03

#: Vertical chords of the mass integral.
N_CHORDS = 1200


def chord_moments(points: np.ndarray, xs: np.ndarray, y0: float) -> tuple[np.ndarray, np.ndarray]:
    """Length and second moment about y0 of the polygon's vertical chords.

    Args:
        points: closed polygon, shape (n, 2) (mm; first point not repeated).
        xs: abscissae of the chords, shape (m,) (mm).
        y0: reference height (mm).

    Returns:
        (integral dy, integral (y - y0)^2 dy) at each x, shapes (m,), (mm, mm^3).
    """
    p = np.asarray(points, float)
    q = np.roll(p, -1, axis=0)
    x0, y_0, x1, y1 = p[:, 0], p[:, 1], q[:, 0], q[:, 1]
    X = xs[:, None]
    crosses = (np.minimum(x0, x1) <= X) & (X < np.maximum(x0, x1)) & (x0 != x1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ys = y_0 + (X - x0) * (y1 - y_0) / (x1 - x0)
    ys = np.where(crosses, ys, np.nan)
    ys = np.sort(ys, axis=1)  # NaN last; crossings come in pairs (inside between)
    length = np.zeros(len(xs))
    second = np.zeros(len(xs))
    cnt = np.sum(crosses, axis=1)
    for k in range(0, int(cnt.max(initial=0)) - 1, 2):
        a, b = ys[:, k], ys[:, k + 1]
        ok = np.isfinite(a) & np.isfinite(b)
        length += np.where(ok, b - a, 0.0)
        second += np.where(ok, ((b - y0) ** 3 - (a - y0) ** 3) / 3.0, 0.0)
    return length, second


def arm_shape(s: np.ndarray, a: float) -> np.ndarray:
    """Cantilever deflection per unit deflection at the load (lever a, mm):
    s^2 (3a - s) / (2 a^3) up to the load, then along its end slope 3 / (2a)."""
    s = np.asarray(s, float)
    inside = s**2 * (3 * a - s) / (2 * a**3)
    beyond = 1.0 + 1.5 * (s - a) / a
    return np.where(s <= a, inside, beyond)


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
                               progress=None, keep_shapes: bool = False) -> ModalResult:
    """First in-plane natural frequency by Rayleigh's quotient (module docstring).

    Args:
        g: element geometry (mm). material: E (MPa), nu, density (g/cm^3).
        element: paper element number, carried into the result.
        modes: modes asked for (the closed form gives the first in-plane one only).

    Returns:
        :class:`~tactcad.mechanics.modal_result.ModalResult` with one mode
        (Hz) and the error estimate (half the K error + :data:`SHAPE_ERROR_REL`).

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
    f1 = math.sqrt(k.stiffness_N_per_mm / m) / (2 * math.pi)
    return ModalResult(element=element, model="closed-form", modes=(Mode(1, f1, "in-plane"),),
                       error_estimate_rel=0.5 * k.error_estimate_rel + SHAPE_ERROR_REL,
                       wall_time_s=time.perf_counter() - t0,
                       basis=(f"Rayleigh quotient: K {k.stiffness_N_per_mm:.4g} N/mm over "
                              f"m_eff {m * 1e6:.4g} g (static deflection shape, arm share "
                              f"{beta:.3f})"))
