"""Inverse design: sensing targets -> element geometry -> a design file.

Targets: the stiffness ratio X = K_r/K_m of a sensing unit, the range
[K_lo, K_hi] of object stiffness K_obj it must read, and the full-scale
force F every element must carry (within the yield strength over the
design's safety factor and the strain gauge's fatigue strain).

Element stiffnesses. Eq. 2 gives the unit's relative sensitivity

    d ln R / d ln K_obj = -(X - 1) / (X + 1 + 2 sqrt(X) cosh u),
    u = ln(K_obj / sqrt(K_m K_r)),

which is even in u: it peaks where K_obj is the geometric mean of K_m and
K_r and falls symmetrically on a log scale either side. Centring that peak
on the range, sqrt(K_m K_r) = sqrt(K_lo K_hi), maximises the worst
sensitivity over the range, so

    K_m = sqrt(K_lo K_hi / X),    K_r = X K_m

(the elements straddle the objects: K_m < K_obj < K_r over a range narrower
than X).

Geometry. All elements of a design share web, notch radius and sheet; only
the arm differs (the paper tunes K by the arm). For a web t the arms a_r, a_m
meeting K_r and K_m are found on the corrected closed form (vectorised
bracketing root search, scipy ``find_root``). A web is feasible when both
arms lie in the design's arm range (and clear the tip-root rule), and both
elements carry F: peak notch stress x F x safety factor <= yield
(:mod:`tactcad.mechanics.strength`), gauge strain x F <= the gauge's fatigue
strain. The design's own web is kept when it is feasible ("arms only");
otherwise the feasible web (0.005 mm steps over the web range) with the
largest worst-case margin on those limits is taken. The notch radius stays
the design's, raised to the web where the web is thicker (t/R <= 1). When no
web is feasible, :class:`InverseDesignError` names the limit that binds: one
that no web meets, or else two limits whose allowed webs do not overlap.

Array layout (2 x N, paper numbering: elements 1 ... N in row 1, N+1 ... 2N
in row 2). The reference element of each row sits in its middle column
(elements 3 and 8 of the 2 x 5 array; element 8 was also the paper's
reference), every other slot is a measuring element. Each measuring element
forms a unit with the nearer reference (see
:func:`tactcad.mechanics.tolerance.sensing_units`), at most two pitches
away along the row or one pitch across the rows, so both press nearly the
same object, as the lumped model assumes. One reference per row keeps eight
of ten slots measuring, and a middle column keeps the longest lever
between reference and measuring tip short.

Resolution. Pressed until the reference carries F, the measuring element
carries F R / X (eq. 1: F_m / F_r = K_m (K_r + K_obj) / (K_r (K_m + K_obj))).
Each force is read to Table 1's resolution dF = 0.01 N, so
dR / R = sqrt((dF / F_m)^2 + (dF / F_r)^2) (independent readings, root sum
of squares), and the K_obj resolution is |dK_obj/dR| dR (eq. 3,
:func:`tactcad.mechanics.paper.lumped.sensitivity`).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from tactcad.design.array import ARM_RANGE_MM, BOLTS, MIN_LIGAMENT_MM, WEB_RANGE_MM, Plan, plan_from_dict
from tactcad.errors import DesignError, TactcadError
from tactcad.mechanics.correction import load_correction
from tactcad.mechanics.paper.lumped import deflection_ratio, sensitivity
from tactcad.mechanics.strength import force_limits
from tactcad.mechanics.tolerance import corrected_stiffness

#: Clearance (mm) between the notch bottom and the arm's underside when the
#: arm height has to grow with the web and notch radius (as the correction fit).
ARM_HEIGHT_CLEARANCE_MM = 0.5
#: Overall element lengths are rounded up to this step (mm).
LENGTH_STEP_MM = 0.5


def required_overall_length_mm(data: Mapping[str, Any], longest_arm_mm: float,
                               notch_radius_mm: float) -> float:
    """Shortest overall element length (mm) whose clamped base still holds the
    bolt pattern with the longest arm: the rule of
    :func:`tactcad.design.plan_from_dict` solved for the length.

    base = overall - tip_width/2 - arm - R, and base - arm clearance must
    hold bolt spacing + clearance hole + two 1 mm ligaments.
    """
    el, cl = data["element"], data["clamp"]
    bolt = BOLTS.get(cl["bolt_size"])
    hole = bolt.clearance_hole_mm if bolt else 0.0
    return (longest_arm_mm + notch_radius_mm + el["tip_width_mm"] / 2 + cl["arm_clearance_mm"]
            + cl["bolt_spacing_mm"] + hole + 2 * MIN_LIGAMENT_MM)


def design_variant(data: Mapping[str, Any], *, web_mm: float | None = None,
                   notch_radius_mm: float | None = None,
                   arms_mm: Sequence[float] | None = None,
                   pitch_mm: float | None = None) -> dict[str, Any]:
    """Raw design tables with web, notch radius, arm lengths and pitch replaced.

    Dimensions that the change forces are adjusted with it: the arm height
    grows to web + notch radius + 0.5 mm when the notch would otherwise open
    through the arm, and the overall length grows (in 0.5 mm steps) when the
    longest arm leaves the clamped base too short for its bolt pattern. The
    result is not validated: pass it to :func:`tactcad.design.plan_from_dict`.

    Args:
        data: raw tables of a design (e.g. ``Plan.raw`` or
            :func:`tactcad.design.default_design_data`); not modified.
        web_mm, notch_radius_mm, pitch_mm: new values (mm) or ``None``.
        arms_mm: one arm length per element (mm), paper numbering order.

    Returns:
        A new dict of raw tables.
    """
    out = copy.deepcopy(dict(data))
    el = out["element"]
    if web_mm is not None:
        el["web_thickness_mm"] = float(web_mm)
    if notch_radius_mm is not None:
        el["notch_radius_mm"] = float(notch_radius_mm)
    if arms_mm is not None:
        out["arms"]["lengths_mm"] = [float(a) for a in arms_mm]
    if pitch_mm is not None:
        out["array"]["pitch_mm"] = float(pitch_mm)
    t, R = el["web_thickness_mm"], el["notch_radius_mm"]
    why = out.get("assumptions")
    if el["arm_height_mm"] <= t + R:
        el["arm_height_mm"] = round(t + R + ARM_HEIGHT_CLEARANCE_MM, 6)
        if isinstance(why, dict):
            why["element.arm_height_mm"] = (
                f"Raised to web + notch radius + {ARM_HEIGHT_CLEARANCE_MM:g} mm so the notch "
                "opens below the arm.")
    arms = out["arms"]["lengths_mm"]
    if arms and all(isinstance(a, (int, float)) for a in arms):
        need = required_overall_length_mm(out, max(arms), R)
        if el["overall_length_mm"] < need:
            el["overall_length_mm"] = math.ceil(need / LENGTH_STEP_MM) * LENGTH_STEP_MM
            if isinstance(why, dict):
                why["element.overall_length_mm"] = (
                    f"Raised to {el['overall_length_mm']:g} mm so the clamped base behind the "
                    f"longest arm ({max(arms):g} mm) still holds the bolt pattern.")
    return out


# ---------------------------------------------------------------------------
# Targets and limits
# ---------------------------------------------------------------------------
#: Force resolution of the read-out (N): Table 1's calibration, "force
#: resolution >= 0.01 N".
FORCE_RESOLUTION_N = 0.01
#: Step of the candidate webs (mm): finer than a wire-EDM web tolerance.
WEB_STEP_MM = 0.005
#: Arm lengths written to the design are rounded to 1 um.
ARM_DECIMALS = 3
#: Object stiffnesses of the report: the range ends and points between (log).
REPORT_POINTS = 5


class InverseDesignError(TactcadError):
    """The targets cannot be met; the message names the limit that binds."""


@dataclass(frozen=True)
class Targets:
    """What a sensing unit must do.

    Attributes:
        kr_over_km: X = K_r / K_m (> 1).
        k_obj_range_N_per_mm: (K_lo, K_hi), object stiffnesses to read (N/mm).
        full_scale_force_N: F, force every element must carry (N).

    Raises:
        DesignError: naming the option (``--kr-over-km``, ``--kobj-range``,
            ``--full-scale-force``), the value and the allowed range.
    """

    kr_over_km: float
    k_obj_range_N_per_mm: tuple[float, float]
    full_scale_force_N: float

    def __post_init__(self):
        x = self.kr_over_km
        if not _finite(x) or not 1.0 < x <= 1000.0:
            raise DesignError("--kr-over-km", x, "1 < value <= 1000",
                              "eq. 2 needs a reference stiffer than the measuring element")
        rng = tuple(self.k_obj_range_N_per_mm)
        if len(rng) != 2 or not all(_finite(k) and k > 0 for k in rng) or not rng[0] < rng[1]:
            raise DesignError("--kobj-range", list(rng), "two stiffnesses 0 < LO < HI (N/mm)")
        object.__setattr__(self, "k_obj_range_N_per_mm", (float(rng[0]), float(rng[1])))
        f = self.full_scale_force_N
        if not _finite(f) or not 0.0 < f <= 1000.0:
            raise DesignError("--full-scale-force", f, "0 < value <= 1000 N")

    @property
    def k_m(self) -> float:
        """K_m = sqrt(K_lo K_hi / X) (N/mm), see the module docstring."""
        lo, hi = self.k_obj_range_N_per_mm
        return math.sqrt(lo * hi / self.kr_over_km)

    @property
    def k_r(self) -> float:
        """K_r = X K_m (N/mm)."""
        return self.kr_over_km * self.k_m


def _finite(x: Any) -> bool:
    return not isinstance(x, bool) and isinstance(x, (int, float)) and math.isfinite(x)


def reference_elements(rows: int, columns: int) -> tuple[int, ...]:
    """Element numbers of the reference slots: the middle column of each row
    (ties to the lower column), paper numbering (row-major, 1-based)."""
    col = (columns - 1) // 2
    return tuple(r * columns + col + 1 for r in range(rows))


def tip_root_min_arm_mm(tip_width_mm: float, corner_radius_mm: float, notch_radius_mm):
    """Shortest arm whose tip-root fillet clears the notch by 0.5 mm (the rule
    of :func:`tactcad.design.plan_from_dict`), mm; broadcasts over R."""
    return tip_width_mm / 2 + corner_radius_mm + np.asarray(notch_radius_mm, float) + 0.5


@dataclass(frozen=True)
class Limit:
    """One limit over the candidate webs.

    Attributes:
        name: the limit in words.
        field: the design field or option that sets it.
        allowed: boolean per candidate web.
        detail: what it asks for, in words with numbers (for the error).
    """

    name: str
    field: str
    allowed: np.ndarray
    detail: str


def _web_span(webs: np.ndarray, mask: np.ndarray) -> str:
    w = webs[mask]
    return f"web {w.min():.3f} ... {w.max():.3f} mm" if w.size else "no web"


def binding_limit(webs: np.ndarray, limits: Sequence[Limit]) -> str:
    """Why no candidate web meets every limit: the first limit no web meets,
    else the first pair of limits whose allowed webs do not overlap."""
    for lim in limits:
        if not lim.allowed.any():
            return f"{lim.name} ({lim.field}) is met by no web in " \
                   f"{webs.min():g} ... {webs.max():g} mm: {lim.detail}"
    for i, a in enumerate(limits):
        for b in limits[i + 1:]:
            if not (a.allowed & b.allowed).any():
                return (f"{a.name} ({a.field}) needs {_web_span(webs, a.allowed)} but "
                        f"{b.name} ({b.field}) needs {_web_span(webs, b.allowed)}")
    return "the limits " + ", ".join(f"{lim.name} ({lim.field})" for lim in limits) + \
        " leave no common web"


# ---------------------------------------------------------------------------
# Geometry search
# ---------------------------------------------------------------------------
def arm_for_stiffness(k_target: float, webs, radii, g, material, correction,
                      arm_lo, arm_hi) -> np.ndarray:
    """Arm length (mm) giving corrected closed-form K = ``k_target`` at each
    web, NaN where the target lies outside [K(arm_hi), K(arm_lo)].

    K falls monotonically with the arm, so the root is unique in the bracket
    (scipy ``elementwise.find_root``, Chandrupatla's method, on ln K).
    """
    from scipy.optimize.elementwise import find_root


    webs, radii, lo, hi = np.broadcast_arrays(*(np.asarray(v, float)
                                                for v in (webs, radii, arm_lo, arm_hi)))

    def f(a, t, R):
        return np.log(corrected_stiffness(t, R, a, material.youngs_modulus_MPa, g,
                                          material.poisson_ratio, correction) / k_target)

    f_lo, f_hi = f(lo, webs, radii), f(hi, webs, radii)
    ok = (f_lo >= 0) & (f_hi <= 0) & (lo < hi)
    out = np.full(webs.shape, np.nan)
    if ok.any():
        res = find_root(f, (lo[ok], hi[ok]), args=(webs[ok], radii[ok]),
                        tolerances={"xatol": 1e-9, "xrtol": 1e-12})
        out[ok] = res.x
    return out


@dataclass(frozen=True)
class WebSearch:
    """Candidate webs, the arms meeting K_r and K_m at each, and the limits."""

    webs_mm: np.ndarray
    radii_mm: np.ndarray
    arm_r_mm: np.ndarray
    arm_m_mm: np.ndarray
    margin: np.ndarray
    limits: tuple[Limit, ...]

    @property
    def feasible(self) -> np.ndarray:
        ok = np.ones(self.webs_mm.shape, bool)
        for lim in self.limits:
            ok &= lim.allowed
        return ok


def search_webs(plan: Plan, targets: Targets, correction=None,
                webs_mm: Sequence[float] | None = None) -> WebSearch:
    """Evaluate every candidate web (default: the web range in 0.005 mm
    steps plus the design's own web) against the targets' limits.

    Raises:
        DesignError: the plan's material has no yield strength.
    """

    corr = load_correction() if correction is None else correction
    g, mat = plan.element(1).geometry, plan.material
    if mat.yield_strength_MPa is None:
        raise DesignError("material.yield_strength_MPa", None,
                          "a value in MPa, or a material.grade",
                          "the full-scale force limit needs the yield strength")
    if webs_mm is None:
        lo, hi = WEB_RANGE_MM
        grid = np.round(np.arange(lo, hi + WEB_STEP_MM / 2, WEB_STEP_MM), 6)
        webs = np.unique(np.append(grid, g.web_thickness_mm))
    else:
        webs = np.asarray(webs_mm, float)
    radii = np.maximum(g.notch_radius_mm, webs)
    arm_lo = np.maximum(ARM_RANGE_MM[0], tip_root_min_arm_mm(g.tip_width_mm,
                                                             g.inside_corner_radius_mm, radii))
    arm_hi = np.full_like(webs, ARM_RANGE_MM[1])
    a_r = arm_for_stiffness(targets.k_r, webs, radii, g, mat, corr, arm_lo, arm_hi)
    a_m = arm_for_stiffness(targets.k_m, webs, radii, g, mat, corr, arm_lo, arm_hi)


    def k(a):
        return corrected_stiffness(webs, radii, a, mat.youngs_modulus_MPa, g, mat.poisson_ratio,
                                   corr)

    k_short, k_long = k(arm_lo), k(arm_hi)
    F, b = targets.full_scale_force_N, g.sheet_thickness_mm
    sf, gauge = plan.strength.safety_factor, plan.strength.gauge
    # Stress and gauge limits on the arms the stiffness targets ask for, held
    # to the arm range where a target leaves it (those webs fail there anyway).
    arms = [np.where(np.isnan(a), np.where(k_short < k_t, arm_lo, arm_hi), a)
            for a, k_t in ((a_r, targets.k_r), (a_m, targets.k_m))]
    limits_r, limits_m = (force_limits(webs, radii, a, b, mat, plan.strength) for a in arms)
    f_yield = np.minimum(limits_r["yield"], limits_m["yield"])
    f_gauge = np.minimum(limits_r["gauge_fatigue"], limits_m["gauge_fatigue"])
    y_margin, g_margin = f_yield / F, f_gauge / F
    i_thick, i_thin = int(np.argmax(webs)), int(np.argmin(webs))
    a_lo_txt = f"{arm_lo[i_thick]:.3g}"
    limits = (
        Limit("K_r within the arm range (stiff enough at the shortest arm)", "arms.lengths_mm",
              k_short >= targets.k_r,
              f"K_r = {targets.k_r:.4g} N/mm, but the stiffest element (web {webs[i_thick]:g} "
              f"mm, arm {a_lo_txt} mm) has K = {k_short[i_thick]:.4g} N/mm"),
        Limit("K_m within the arm range (soft enough at the longest arm)", "arms.lengths_mm",
              k_long <= targets.k_m,
              f"K_m = {targets.k_m:.4g} N/mm, but the softest element (web {webs[i_thin]:g} mm, "
              f"arm {arm_hi[i_thin]:g} mm) has K = {k_long[i_thin]:.4g} N/mm"),
        Limit("K_r within the arm range (soft enough at the longest arm)", "arms.lengths_mm",
              k_long <= targets.k_r,
              f"K_r = {targets.k_r:.4g} N/mm, but the softest element has K = "
              f"{k_long[i_thin]:.4g} N/mm"),
        Limit("K_m within the arm range (stiff enough at the shortest arm)", "arms.lengths_mm",
              k_short >= targets.k_m,
              f"K_m = {targets.k_m:.4g} N/mm, but the stiffest element has K = "
              f"{k_short[i_thick]:.4g} N/mm"),
        Limit(f"yield strength / safety factor {sf:g} at the full-scale force",
              "material.yield_strength_MPa, strength.safety_factor", y_margin >= 1.0,
              f"the stiffness targets' arms carry at most {np.max(f_yield):.3g} N at any web "
              f"(yield {mat.yield_strength_MPa:g} MPa / {sf:g}), asked {F:g} N"),
        Limit(f"gauge fatigue strain ({gauge.name}) at the full-scale force", "strength.gauge",
              g_margin >= 1.0,
              f"the stiffness targets' arms carry at most {np.max(f_gauge):.3g} N at any web "
              f"within {1e6 * gauge.fatigue_strain:.0f} microstrain, asked {F:g} N"),
    )
    return WebSearch(webs, radii, a_r, a_m, np.minimum(y_margin, g_margin), limits)


def choose_web(search: WebSearch, design_web_mm: float) -> int:
    """Index of the chosen web: the design's own when feasible, else the
    feasible web with the largest worst-case margin.

    Raises:
        InverseDesignError: no web is feasible (the binding limit named).
    """
    ok = search.feasible
    if not ok.any():
        raise InverseDesignError("targets cannot be met: "
                                 + binding_limit(search.webs_mm, search.limits))
    own = np.flatnonzero(np.isclose(search.webs_mm, design_web_mm) & ok)
    if own.size:
        return int(own[0])
    margins = np.where(ok, search.margin, -np.inf)
    return int(np.argmax(margins))


# ---------------------------------------------------------------------------
# The design
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class InverseDesign:
    """The result: raw tables (to write), validated plan and the figures."""

    targets: Targets
    data: dict[str, Any]
    plan: Plan
    references: tuple[int, ...]
    web_changed: bool
    arm_r_mm: float
    arm_m_mm: float
    notes: tuple[str, ...] = field(default=())


def design_for_targets(base: Plan, targets: Targets, *, grade: str | None = None,
                       pitch_mm: float | None = None, name: str = "inverse_design",
                       correction=None) -> InverseDesign:
    """Reference and measuring elements meeting ``targets`` on ``base``'s
    design (see the module docstring for the method and layout).

    Args:
        base: the design whose other dimensions are kept.
        targets: the sensing targets.
        grade: material grade of the library (:mod:`tactcad.design.materials`) to
            use instead of the base material.
        pitch_mm: array pitch (mm) instead of the base's.
        name: ``design.name`` of the new design.
        correction: closed-form correction (default: the stored one).

    Raises:
        InverseDesignError: the targets cannot be met (the binding limit named).
        DesignError: a bad grade or pitch, or the result breaks a design rule
            (field named).
    """
    data = copy.deepcopy(dict(base.raw))
    if grade is not None:
        data["material"] = {"name": grade, "grade": grade}
        data["assumptions"] = {k: v for k, v in data.get("assumptions", {}).items()
                               if not k.startswith("material.")}
    if pitch_mm is not None:
        data = design_variant(data, pitch_mm=pitch_mm)
    plan = plan_from_dict(data, source="<inverse design>")
    search = search_webs(plan, targets, correction)
    i = choose_web(search, plan.element(1).geometry.web_thickness_mm)
    t, R = float(search.webs_mm[i]), float(search.radii_mm[i])
    a_r = round(float(search.arm_r_mm[i]), ARM_DECIMALS)
    a_m = round(float(search.arm_m_mm[i]), ARM_DECIMALS)
    refs = reference_elements(plan.rows, plan.columns)
    arms = [a_r if n in refs else a_m for n in range(1, len(plan.slots) + 1)]
    web_changed = not math.isclose(t, plan.element(1).geometry.web_thickness_mm)
    data = design_variant(data, web_mm=t, notch_radius_mm=R, arms_mm=arms)
    lo, hi = targets.k_obj_range_N_per_mm
    data["design"] = {"name": name, "description": (
        f"Inverse design: K_r/K_m = {targets.kr_over_km:g} for K_obj {lo:g}-{hi:g} N/mm, "
        f"full-scale force {targets.full_scale_force_N:g} N (K_r {targets.k_r:.4g}, K_m "
        f"{targets.k_m:.4g} N/mm)")}
    why = data.setdefault("assumptions", {})
    why["arms.lengths_mm"] = (
        f"tactcad design: elements {' and '.join(map(str, refs))} (middle column of each row) are "
        f"the references, arm {a_r:g} mm for K_r = {targets.k_r:.4g} N/mm; the others measure, "
        f"arm {a_m:g} mm for K_m = {targets.k_m:.4g} N/mm = sqrt(K_lo K_hi / X) (corrected "
        f"closed form).")
    why.pop("arms.lengths_mm[5]", None)  # the paper's missing element 5 is not this design's
    if web_changed:
        why["element.web_thickness_mm"] = (
            f"tactcad design: {t:g} mm, the feasible web with the largest margin on yield / "
            f"safety factor and gauge fatigue strain at {targets.full_scale_force_N:g} N (the "
            f"base design's web met not every limit).")
    new_plan = plan_from_dict(data, source="<inverse design>")
    return InverseDesign(targets, data, new_plan, refs, web_changed, a_r, a_m)


def unit_resolution(k_m: float, k_r: float, k_obj, full_scale_force_N: float,
                    force_resolution_N: float = FORCE_RESOLUTION_N) -> dict[str, np.ndarray]:
    """R, dR/dK_obj and the K_obj resolution at each K_obj (arrays, N/mm).

    The unit is pressed until the reference carries ``full_scale_force_N``;
    the measuring element then carries F R / X (eq. 1). Each force is read to
    ``force_resolution_N``: dR/R = sqrt((dF/F_m)^2 + (dF/F_r)^2), and
    dK_obj = |dK_obj/dR| dR (eq. 3 sensitivity).

    Raises:
        LumpedDomainError: a stiffness outside eq. 2's domain.
    """

    k_obj = np.atleast_1d(np.asarray(k_obj, float))
    km, kr = np.full_like(k_obj, k_m), np.full_like(k_obj, k_r)
    R = deflection_ratio(km, kr, k_obj).value
    dk_dr = sensitivity(R, km, kr).value
    F_r = np.full_like(k_obj, full_scale_force_N)
    F_m = F_r * R * k_m / k_r
    dR = R * np.hypot(force_resolution_N / F_m, force_resolution_N / F_r)
    dk = np.abs(dk_dr) * dR
    return {"K_obj_N_per_mm": k_obj, "R": R, "dR_dKobj_per_N_per_mm": 1.0 / dk_dr,
            "force_measuring_N": F_m, "force_reference_N": F_r, "R_resolution": dR,
            "K_obj_resolution_N_per_mm": dk, "K_obj_resolution_rel": dk / k_obj}


def report_points(targets: Targets, n: int = REPORT_POINTS) -> np.ndarray:
    """K_obj values of the report: log-spaced over the range, ends included (N/mm)."""
    lo, hi = targets.k_obj_range_N_per_mm
    return np.geomspace(lo, hi, n)
