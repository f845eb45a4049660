"""A pivoting grasper jaw closing on a tissue slab: each tip's radius and indentation, and
the bias a difference in travel puts into the deflection ratio R.

The jaw turns about a pin that runs across the jaw's width, in the plane of the closed
jaw faces. The insert's frame is the plane of the tips' contact faces: origin the first
element's tip centre, ``u`` along the rows (first tip to last tip of the first row), ``v``
across them. The jaw's axis (its length) makes ``axis_angle_deg`` with ``u``; a tip's
radius is its distance from the pin along that axis (the pin is perpendicular to it, so
two tips side by side across the jaw are at one radius).

Closing to an angle θ (degrees throughout this module) above the opposing jaw, the jaw
face at radius r stands r sin θ above it; a slab of thickness h is indented by
max(0, h − r sin θ) there (small angles: h − r θ, θ in rad). The tip nearer the pivot is
pressed further.

With each tip's own travel Δ, eq. 1 gives the element deflections
e_m = K_obj Δ_m / (K_m + K_obj) and e_r = K_obj Δ_r / (K_r + K_obj), so the read ratio is

    R_read = e_m / e_r = (Δ_m / Δ_r) (K_r + K_obj) / (K_m + K_obj) = (Δ_m / Δ_r) R,

eq. 2 scaled by the travel ratio; the correction is R = R_read Δ_r / Δ_m. Where the
travels grow in proportion to the radius (a jaw turning by a small angle from a pose in
which every tip just touches: Δ = r dθ) the correction is R = R_read r_r / r_m, known from
the layout alone. On a flat slab the travels follow h − r sin θ instead, and the
correction needs θ and h. Units: mm, N/mm, degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.errors import DesignError

#: Ranges of the jaw's fields (mm, degrees).
PIVOT_RANGE_MM = (-500.0, 500.0)
PIN_TO_TIP_RANGE_MM = (1.0, 200.0)
OPENING_ANGLE_RANGE_DEG = (0.0, 90.0)
SLAB_THICKNESS_RANGE_MM = (0.0, 100.0)
AXIS_ANGLE_RANGE_DEG = (-90.0, 90.0)


def _within(field: str, value: float, lo: float, hi: float, unit: str,
            lo_open: bool = False) -> None:
    ok = math.isfinite(value) and (lo < value if lo_open else lo <= value) and value <= hi
    if not ok:
        raise DesignError(field, value, f"{'>' if lo_open else ''}{lo:g} ... {hi:g} {unit}")


@dataclass(frozen=True)
class JawGeometry:
    """A pivoting jaw over the insert (insert frame: see the module docstring).

    Attributes:
        pivot_u_mm, pivot_v_mm: the pin's position in the insert's frame (mm), each
            −500 ... 500.
        pin_to_tip_mm: from the pin to the jaw's end (mm), 1 ... 200; every tip lies on it.
        opening_angle_deg: the jaw's full opening (degrees), > 0 ... 90.
        slab_thickness_mm: the tissue slab's thickness (mm), > 0 ... 100.
        axis_angle_deg: the jaw's axis against the rows (degrees), −90 ... 90; 0: along them.

    Raises:
        DesignError: a field outside its range (names the field, value and range).
    """

    pivot_u_mm: float
    pivot_v_mm: float
    pin_to_tip_mm: float
    opening_angle_deg: float
    slab_thickness_mm: float
    axis_angle_deg: float = 0.0

    def __post_init__(self):
        _within("jaw.pivot_u_mm", self.pivot_u_mm, *PIVOT_RANGE_MM, "mm")
        _within("jaw.pivot_v_mm", self.pivot_v_mm, *PIVOT_RANGE_MM, "mm")
        _within("jaw.pin_to_tip_mm", self.pin_to_tip_mm, *PIN_TO_TIP_RANGE_MM, "mm")
        _within("jaw.opening_angle_deg", self.opening_angle_deg, *OPENING_ANGLE_RANGE_DEG,
                "degrees", lo_open=True)
        _within("jaw.slab_thickness_mm", self.slab_thickness_mm, *SLAB_THICKNESS_RANGE_MM, "mm",
                lo_open=True)
        _within("jaw.axis_angle_deg", self.axis_angle_deg, *AXIS_ANGLE_RANGE_DEG, "degrees")

    @property
    def axis(self) -> tuple[float, float]:
        """Unit vector of the jaw's length in the insert frame (u, v)."""
        a = math.radians(self.axis_angle_deg)
        return math.cos(a), math.sin(a)


def along_jaw_mm(jaw: JawGeometry, u_mm: float, v_mm: float) -> float:
    """A point's distance from the pin along the jaw's axis (mm; negative behind the pin),
    unchecked: :func:`tip_radius_mm` is the checked radius."""
    au, av = jaw.axis
    return (u_mm - jaw.pivot_u_mm) * au + (v_mm - jaw.pivot_v_mm) * av


def tip_radius_mm(jaw: JawGeometry, u_mm: float, v_mm: float) -> float:
    """A tip's radius (mm): its distance from the pin along the jaw's axis.

    Args:
        jaw: the jaw.
        u_mm, v_mm: the tip centre in the insert frame (mm).

    Returns:
        The radius (mm), > 0.

    Raises:
        DesignError: the tip lies behind the pin or beyond the jaw's end.
    """
    r = along_jaw_mm(jaw, u_mm, v_mm)
    where = f"a tip at u = {u_mm:g}, v = {v_mm:g} mm is at r = {r:.4g} mm"
    if r <= 0.0:
        raise DesignError("jaw.pivot_u_mm", round(jaw.pivot_u_mm, 9),
                          "a pin behind every tip (0 < r)", where)
    if r > jaw.pin_to_tip_mm:
        raise DesignError("jaw.pin_to_tip_mm", round(jaw.pin_to_tip_mm, 9),
                          f"a jaw that reaches every tip, at least {r:.4g} mm from the pin",
                          where)
    return r


def check_angle_deg(jaw: JawGeometry, angle_deg: float) -> None:
    """Raise :class:`DesignError` for a closing angle outside 0 ... the jaw's opening."""
    _within("angle_deg", angle_deg, 0.0, jaw.opening_angle_deg, "degrees (the jaw's opening)")


def indentation_mm(slab_thickness_mm: float, radius_mm: float, angle_deg: float) -> float:
    """The slab's indentation (mm) under the jaw face at radius r, jaw closed to θ:
    max(0, h − r sin θ) (small angles: h − r θ with θ in rad).

    Args:
        slab_thickness_mm: h (mm), > 0.
        radius_mm: r (mm), > 0.
        angle_deg: θ (degrees), 0 ... 90.

    Raises:
        DesignError: an argument outside its range.
    """
    _within("slab_thickness_mm", slab_thickness_mm, *SLAB_THICKNESS_RANGE_MM, "mm", lo_open=True)
    _within("radius_mm", radius_mm, 0.0, PIN_TO_TIP_RANGE_MM[1], "mm", lo_open=True)
    _within("angle_deg", angle_deg, *OPENING_ANGLE_RANGE_DEG, "degrees")
    return max(0.0, slab_thickness_mm - radius_mm * math.sin(math.radians(angle_deg)))


def travel_ratio(travel_m_mm: float, travel_r_mm: float) -> float:
    """Δ_m / Δ_r: the measuring tip's travel over its reference's.

    Raises:
        DesignError: the reference's travel is not > 0 (it reads nothing).
    """
    if not (math.isfinite(travel_r_mm) and travel_r_mm > 0):
        raise DesignError("travel_r_mm", travel_r_mm, "> 0 mm (the reference must be pressed)")
    return travel_m_mm / travel_r_mm


def ratio_read(k_m: float, k_r: float, k_obj: float, travel_m_mm: float,
               travel_r_mm: float) -> float:
    """R a unit reads when its tips travel Δ_m and Δ_r (eq. 1 per tip, eq. 2):
    (Δ_m / Δ_r) (K_r + K_obj) / (K_m + K_obj). Stiffnesses in N/mm."""
    return travel_ratio(travel_m_mm, travel_r_mm) * (k_r + k_obj) / (k_m + k_obj)


def ratio_bias_rel(travel_m_mm: float, travel_r_mm: float) -> float:
    """The relative error of R from unequal travels: Δ_m / Δ_r − 1."""
    return travel_ratio(travel_m_mm, travel_r_mm) - 1.0


def corrected_ratio(r_read: float, travel_m_mm: float, travel_r_mm: float) -> float:
    """R corrected for unequal travels: R_read Δ_r / Δ_m (the module docstring's derivation;
    with travels in proportion to the radius pass the radii)."""
    return r_read / travel_ratio(travel_m_mm, travel_r_mm)
