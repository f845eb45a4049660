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
(:mod:`tactcad.mechanics.element_strength`), gauge strain x F <= the gauge's fatigue
strain. The design's own web is kept while it is feasible with room to
spare ("arms only"); otherwise the feasible web (0.005 mm steps over the web
range) that leaves the most room to every limit is taken (:data:`WEB_RULE`,
:func:`limit_room`): not the one with the largest force margin, which
pressed the arms to the end of their range. The notch radius stays
the design's, raised to the web where the web is thicker (t/R <= 1). When no
web is feasible, :class:`InverseDesignError` names the limit that binds: one
that no web meets, or else two limits whose allowed webs do not overlap.

Array layout (2 x N, paper numbering: elements 1 ... N in row 1, N+1 ... 2N
in row 2). The reference element of each row sits in its middle column
(elements 3 and 8 of the 2 x 5 array; element 8 was also the paper's
reference), every other slot is a measuring element. Each measuring element
forms a unit with the nearer reference (see
:func:`tactcad.studies.tolerance_montecarlo.sensing_units`), at most two pitches
away along the row or one pitch across the rows, so both press nearly the
same object, as the lumped model assumes. One reference per row keeps eight
of ten slots measuring, and a middle column keeps the longest lever
between reference and measuring tip short.

Resolution. Pressed until the reference carries F, the measuring element
carries F R / X (eq. 1: F_m / F_r = K_m (K_r + K_obj) / (K_r (K_m + K_obj))).
Each force is read to Table 1's resolution dF = 0.01 N, so
dR / R = sqrt((dF / F_m)^2 + (dF / F_r)^2) (independent readings, root sum
of squares), and the K_obj resolution is |dK_obj/dR| dR (eq. 3,
:func:`tactcad.mechanics.lumped_model.sensitivity`).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import math
import re
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from tactcad.vocabulary.schema import copy_tables, plain_reason, reason_as_read
from tactcad.design.array_plan import (ARM_RANGE_MM, BOLTS, DEFAULT_DESIGN, MIN_BASE_BELOW_ARM_MM,
                                       MIN_FASTENER_GAP_MM, MIN_LIGAMENT_MM, WEB_RANGE_MM, Plan,
                                       element_process_limits, plan_from_dict)
from tactcad.design.tolerances import WEB_DEFAULT_MM
from tactcad.design.requirements_section import (MAX_FULL_SCALE_FORCE_N, MAX_KOBJ_N_PER_MM,
                                                 MIN_FULL_SCALE_FORCE_N, MIN_KOBJ_N_PER_MM)
from tactcad.errors import DesignError
from tactcad.mechanics.correction import load_correction, range_warnings_unsaid
from tactcad.mechanics.resolution import FORCE_RESOLUTION_N, unit_resolution  # noqa: F401 (API)
from tactcad.mechanics.element_strength import force_limits, notch_fatigue_strength
from tactcad.mechanics.readout_chain import closed_form_grid_read_per_N, readout_chain
from tactcad.studies.tolerance_montecarlo import corrected_stiffness

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
    out = copy_tables(dict(data))
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
                f"Raised to {el['arm_height_mm']:g} mm, the web plus the notch radius plus a "
                f"{1000 * ARM_HEIGHT_CLEARANCE_MM:g} um clearance, so the notch opens below "
                "the arm.")
    fit_to_bolt(out)
    arms = out["arms"]["lengths_mm"]
    if arms and all(isinstance(a, (int, float)) for a in arms):
        need = required_overall_length_mm(out, max(arms), R)
        if el["overall_length_mm"] < need:
            set_overall_length(out, math.ceil(need / LENGTH_STEP_MM) * LENGTH_STEP_MM)
    return out


def overall_length_reason(overall_length_mm: float, longest_arm_mm: float) -> str:
    """Why the overall element length is what it is: the shortest, in
    :data:`LENGTH_STEP_MM` steps, whose clamped base behind the longest arm holds the bolt
    pattern (both in mm, as the design file writes them)."""
    # the step is said in words: a reason quotes in mm only dimensions the file holds
    return (f"tactcad design: {overall_length_mm:g} mm, the shortest (in half-millimetre "
            f"steps) whose clamped base behind the longest arm ({longest_arm_mm:g} mm) still "
            "holds the bolt pattern.")


def set_overall_length(data: dict[str, Any], overall_length_mm: float) -> None:
    """Write, in place, the overall element length (mm) and its reason under
    ``[assumptions]`` (:func:`overall_length_reason`), quoting the longest arm the tables
    hold now: the arms are set first."""
    data["element"]["overall_length_mm"] = float(overall_length_mm)
    why = data.get("assumptions")
    if isinstance(why, dict):
        why["element.overall_length_mm"] = overall_length_reason(
            float(overall_length_mm), max(data["arms"]["lengths_mm"]))


def notch_radius_reason(notch_radius_mm: float) -> str:
    """Why the inverse design's notch radius (mm) differs from its base's: it follows a
    web thicker than the base's radius (the search's rule, :func:`web_candidates`)."""
    return (f"tactcad design: raised to {notch_radius_mm:g} mm, the chosen web's thickness: "
            "the notch radius is kept at least the web (t/R <= 1, the range the closed form's "
            "fem3d correction was fitted over), so it follows a web thicker than the base "
            "design's radius.")


def set_notch_radius(data: dict[str, Any], notch_radius_mm: float) -> bool:
    """Write, in place, the notch radius (mm) the web search chose; where it differs
    from the tables' own, its reason too (:func:`notch_radius_reason`).

    Returns:
        True when the radius changed.
    """
    el = data["element"]
    if math.isclose(float(el["notch_radius_mm"]), notch_radius_mm, rel_tol=1e-12):
        return False
    el["notch_radius_mm"] = float(notch_radius_mm)
    data.setdefault("assumptions", {})["element.notch_radius_mm"] = \
        notch_radius_reason(float(notch_radius_mm))
    return True


#: Dimensions raised to hold a bolt are rounded up to this step (mm).
def grid_fitted_to_sheet(data: Mapping[str, Any]) -> dict[str, Any]:
    """Raw design tables whose gauge grid fits the element's top face, one sheet thick.

    A searched sheet thinner than the library default's grid width
    (:data:`tactcad.design.readout_section.DEFAULTS`) would be refused by the grid rule
    (:func:`tactcad.design.readout_section.check_readout`); where the tables state no
    ``readout.grid_width_mm``, the search takes a grid as wide as the sheet instead, its reason
    under ``[assumptions]`` (the gauge to bond). A stated grid is kept (the rule judges it), and
    a sheet narrower than the narrowest grid the schema allows gets none.

    Args:
        data: raw tables (``sheet``, ``readout`` optional); not modified.

    Returns:
        A new dict of raw tables (not validated).
    """
    from tactcad.design.readout_section import DEFAULTS, GRID_WIDTH_RANGE_MM

    out = copy_tables(dict(data))
    readout = dict(out.get("readout") or {})
    sheet = float(out["sheet"]["thickness_mm"])
    default = float(DEFAULTS["grid_width_mm"][0])
    narrowest = GRID_WIDTH_RANGE_MM[0]
    if "grid_width_mm" in readout or sheet >= default or sheet < narrowest:
        return out
    out["readout"] = {**readout, "grid_width_mm": sheet}
    out.setdefault("assumptions", {})["readout.grid_width_mm"] = (
        f"{sheet:g} mm, as wide as the sheet: the library default's grid (readout's "
        f"grid_width_mm) is wider than the sheet the search chose, and the grid lies on the "
        f"element's top face: bond a gauge whose grid is at most {sheet:g} mm wide (the grid "
        f"strain was read over the face either way).")
    return out


def held_to_process(data: Mapping[str, Any]) -> dict[str, Any]:
    """Raw design tables whose element the cut process can make on the design's sheet:
    the web's drawn tolerance raised to what the process holds, the notch radius to half
    its narrowest slot and the inside-corner radius to its smallest, each raised value's
    reason under ``[assumptions]``; values already within the rules are kept. The web
    itself is the web search's (its limit: :func:`search_webs`).

    Args:
        data: raw tables (``element``, ``sheet``, ``material``, ``edm``); not modified.

    Returns:
        A new dict of raw tables (not validated).
    """
    out = copy_tables(dict(data))
    el = out["element"]
    lim = element_process_limits(out)
    why = out.setdefault("assumptions", {})
    where = f"{lim.process} on {float(out['sheet']['thickness_mm']):g} mm sheet"
    tol_table = out.get("tolerances") or {}
    tol = tol_table.get("web_thickness_mm", el.get("web_tolerance_mm", WEB_DEFAULT_MM))
    if float(tol) < lim.tolerance_mm.value_mm - 1e-12:
        raised = round(lim.tolerance_mm.value_mm, 6)
        el["web_tolerance_mm"] = raised
        if "web_thickness_mm" in tol_table:
            out["tolerances"] = {**tol_table, "web_thickness_mm": raised}
        why["element.web_tolerance_mm"] = (f"+/-{raised:g} mm: what {where} holds "
                                           f"({lim.tolerance_mm.rule}; {lim.tolerance_mm.source}).")
    for key, fig, need in (("notch_radius_mm", lim.min_slot_mm, lim.min_slot_mm.value_mm / 2),
                           ("inside_corner_radius_mm", lim.min_inside_radius_mm,
                            lim.min_inside_radius_mm.value_mm)):
        if float(el[key]) < need - 1e-12:
            el[key] = math.ceil(need * 1000 - 1e-9) / 1000
            why[f"element.{key}"] = (f"Raised to {el[key]:g} mm: what {where} cuts "
                                     f"({fig.rule}; {fig.source}).")
    return out


BOLT_FIT_STEP_MM = 0.1


def _up(x: float) -> float:
    return round(math.ceil(x / BOLT_FIT_STEP_MM - 1e-9) * BOLT_FIT_STEP_MM, 6)


def fit_to_bolt(data: dict[str, Any]) -> None:
    """Raise, in place, the dimensions that must hold the clamp bolt where they
    are below the rules of :func:`tactcad.design.plan_from_dict` (a larger bolt
    or a taller arm asks more): the bolt spacing (nuts and heads apart, holes
    with a ligament), the base height (holes below the arm with a ligament each
    side) and the bridge (mounting holes with 0.5 mm around them, below the
    arm with its clearance). Each raised value's reason is written under
    ``[assumptions]``; a table the rules would refuse for another reason is left
    to them."""
    el, cl = data.get("element", {}), data.get("clamp", {})
    bolt = BOLTS.get(cl.get("bolt_size"))
    keys = (el.get("arm_height_mm"), el.get("base_height_mm"), cl.get("bolt_spacing_mm"),
            cl.get("bridge_height_mm"), cl.get("arm_clearance_mm"))
    if bolt is None or not all(_finite(v) for v in keys):
        return
    arm_h, hole = float(el["arm_height_mm"]), bolt.clearance_hole_mm
    widest = max(bolt.nut_across_corners_mm, bolt.head_diameter_mm)
    need = {("clamp", "bolt_spacing_mm"): max(hole + MIN_LIGAMENT_MM, widest + MIN_FASTENER_GAP_MM),
            ("clamp", "bridge_height_mm"): hole + 1.0}
    need[("element", "base_height_mm")] = max(
        arm_h + hole + 2 * MIN_LIGAMENT_MM, arm_h + MIN_BASE_BELOW_ARM_MM,
        arm_h + float(cl["arm_clearance_mm"]) + max(float(cl["bridge_height_mm"]),
                                                    need[("clamp", "bridge_height_mm")]))
    why = data.get("assumptions")
    for (section, key), least in need.items():
        if float(data[section][key]) < least - 1e-9:
            data[section][key] = _up(least)
            if isinstance(why, dict):
                # only the base height reads the arm height: the other reasons do not
                # quote it (a later, taller arm would leave them quoting a stale one)
                below = f" below a {arm_h:g} mm arm" if key == "base_height_mm" else ""
                why[f"{section}.{key}"] = (
                    f"tactcad design: raised to {data[section][key]:g} mm, the least that holds "
                    f"the {bolt.size} clamp bolt{below}.")


# ---------------------------------------------------------------------------
# Targets and limits
# ---------------------------------------------------------------------------
#: Step of the candidate webs (mm): finer than a wire-EDM web tolerance.
WEB_STEP_MM = 0.005
#: Arm lengths written to the design are rounded to 1 um.
ARM_DECIMALS = 3
#: Object stiffnesses of the report: the range ends and points between (log).
REPORT_POINTS = 5


class InverseDesignError(DesignError):
    """The targets cannot be met; the message names every limit that binds and
    the largest full-scale force the other targets allow.

    A :class:`~tactcad.errors.DesignError` whose field is the option it
    refuses (``--full-scale-force`` when none is named), with the limits'
    words as its message and what to ask instead as ``alternatives``.
    """

    def __init__(self, message: str, field: str = "--full-scale-force", value: Any = None,
                 allowed: str = "", alternatives: Sequence[dict] = ()):
        self.message = message
        super().__init__(field, value, allowed, alternatives=alternatives)

    def line(self) -> str:
        return self.message


@dataclass(frozen=True)
class Targets:
    """What a sensing unit must do.

    Attributes:
        kr_over_km: X = K_r / K_m (> 1).
        k_obj_range_N_per_mm: (K_lo, K_hi), object stiffnesses to read (N/mm).
        full_scale_force_N: F, force every element must carry (N).
        tissue: the sample under the tips
            (:class:`tactcad.in_use.tissue_coupling.Tissue`), or None for eq. 2
            alone (each tip on its own object spring).
        kobj_seen_factor: the factor by which eq. 2 sees K_obj through the tissue
            coupling; the stiffnesses centre on the range so seen
            (:func:`design_from_tables` sets it; 1: eq. 2 alone).

    Raises:
        DesignError: naming the option (``--kr-over-km``, ``--kobj-range``,
            ``--full-scale-force``), the value and the allowed range.
    """

    kr_over_km: float
    k_obj_range_N_per_mm: tuple[float, float]
    full_scale_force_N: float
    tissue: Any = None
    kobj_seen_factor: float = 1.0

    def __post_init__(self):
        x = self.kr_over_km
        if not _finite(x) or not 1.0 < x <= 1000.0:
            raise DesignError("--kr-over-km", x, "1 < value <= 1000",
                              "eq. 2 needs a reference stiffer than the measuring element")
        rng = tuple(self.k_obj_range_N_per_mm)
        if len(rng) != 2 or not all(_finite(k) and MIN_KOBJ_N_PER_MM <= k <= MAX_KOBJ_N_PER_MM
                                    for k in rng) or not rng[0] < rng[1]:
            raise DesignError("--kobj-range", list(rng),
                              f"two stiffnesses {MIN_KOBJ_N_PER_MM:g} <= LO < HI <= "
                              f"{MAX_KOBJ_N_PER_MM:g} (N/mm)")
        object.__setattr__(self, "k_obj_range_N_per_mm", (float(rng[0]), float(rng[1])))
        f = self.full_scale_force_N
        if not _finite(f) or not MIN_FULL_SCALE_FORCE_N <= f <= MAX_FULL_SCALE_FORCE_N:
            raise DesignError("--full-scale-force", f, f"{MIN_FULL_SCALE_FORCE_N:g} <= value <= "
                                                       f"{MAX_FULL_SCALE_FORCE_N:g} N")
        s = self.kobj_seen_factor
        if not _finite(s) or not 0.01 <= s <= 100.0:
            raise DesignError("--tissue-coupling", s, "a K_obj factor 0.01 ... 100 seen through the tissue")

    @property
    def k_m(self) -> float:
        """K_m = s sqrt(K_lo K_hi / X) (N/mm), s the K_obj factor the tissue coupling makes
        eq. 2 see (1 without it), see the module docstring."""
        lo, hi = self.k_obj_range_N_per_mm
        return self.kobj_seen_factor * math.sqrt(lo * hi / self.kr_over_km)

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


def reference_column_words(columns: int) -> str:
    """Which column :func:`reference_elements` takes, in words for the design's reasons."""
    col = (columns - 1) // 2 + 1
    if columns % 2:
        return f"column {col} of {columns}, the middle one"
    return f"column {col} of {columns}, the lower of the two middle ones"


def tip_root_min_arm_mm(tip_width_mm: float, corner_radius_mm: float, notch_radius_mm):
    """Shortest arm whose tip-root fillet clears the notch by 0.5 mm (the rule
    of :func:`tactcad.design.plan_from_dict`), mm; broadcasts over R."""
    return tip_width_mm / 2 + corner_radius_mm + np.asarray(notch_radius_mm, float) + 0.5


def mounting_min_arm_mm(bolt, arm_clearance_mm: float, pitch_mm: float,
                        notch_radius_mm) -> np.ndarray:
    """Shortest arm (mm) that leaves the two mounting bolts (a
    :class:`~tactcad.vocabulary.standards.BoltSpec`) room between the rows'
    innermost bases (the rule of :func:`tactcad.design.plan_from_dict`: the
    bases end at pitch/2 + arm + R, the bolts sit half way, their shanks keep
    the arm clearance to the bases and their heads a gap); broadcasts over R."""
    inner_end = max(2 * arm_clearance_mm + bolt.nominal_diameter_mm,
                    max(bolt.nut_across_corners_mm, bolt.head_diameter_mm) + MIN_FASTENER_GAP_MM)
    return inner_end - pitch_mm / 2 - np.asarray(notch_radius_mm, float)


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


# ---------------------------------------------------------------------------
# Geometry search
# ---------------------------------------------------------------------------
def arm_for_stiffness(k_target: float, webs, radii, g, material, correction,
                      arm_lo, arm_hi) -> np.ndarray:
    """Arm length (mm) giving corrected closed-form K = ``k_target`` (N/mm) at each
    web, NaN where the target lies outside [K(arm_hi), K(arm_lo)].

    K falls monotonically with the arm, so the root is unique in the bracket
    (scipy ``elementwise.find_root``, Chandrupatla's method, on ln K).

    Args:
        k_target: the stiffness sought, N/mm. webs, radii: web and notch radius per
            candidate (mm). g, material, correction: the element, its material and the
            closed form's correction. arm_lo, arm_hi: the arm bracket per candidate (mm).

    Returns:
        The arm per candidate (mm), NaN outside the bracket.
    """
    return arms_for_stiffnesses((k_target,), webs, radii, g, material, correction,
                                arm_lo, arm_hi)[0]


def arms_for_stiffnesses(k_targets: Sequence[float], webs, radii, g, material, correction,
                         arm_lo, arm_hi) -> list[np.ndarray]:
    """:func:`arm_for_stiffness` for several targets (N/mm) in one root find: the
    candidates of every target are stacked, so the solver's iterations are paid once
    (each element's iterates are its own, so every arm is the one a separate find gives).

    Args:
        k_targets: the stiffnesses sought (N/mm), e.g. K_r and K_m. The rest: as
            :func:`arm_for_stiffness`.

    Returns:
        Per target, the arm per candidate (mm), NaN where the target lies outside
        [K(arm_hi), K(arm_lo)]. Source: Chandrupatla (1997), as scipy implements it.
    """
    from scipy.optimize.elementwise import find_root

    webs, radii, lo, hi = np.broadcast_arrays(*(np.asarray(v, float)
                                                for v in (webs, radii, arm_lo, arm_hi)))
    n = len(k_targets)
    webs, radii, lo, hi = (np.tile(v, (n,) + (1,) * v.ndim) for v in (webs, radii, lo, hi))
    k = np.broadcast_to(np.asarray(k_targets, float).reshape((n,) + (1,) * (webs.ndim - 1)),
                        webs.shape)

    def f(a, t, R, k_t):
        return np.log(corrected_stiffness(t, R, a, material.youngs_modulus_MPa, g,
                                          material.poisson_ratio, correction) / k_t)

    f_lo, f_hi = f(lo, webs, radii, k), f(hi, webs, radii, k)
    ok = (f_lo >= 0) & (f_hi <= 0) & (lo < hi)
    out = np.full(webs.shape, np.nan)
    if ok.any():
        res = find_root(f, (lo[ok], hi[ok]), args=(webs[ok], radii[ok], k[ok]),
                        tolerances={"xatol": 1e-9, "xrtol": 1e-12})
        out[ok] = res.x
    return list(out)


@dataclass(frozen=True)
class WebSearch:
    """Candidate webs, the arms meeting K_r and K_m at each, and the limits."""

    webs_mm: np.ndarray
    radii_mm: np.ndarray
    arm_r_mm: np.ndarray
    arm_m_mm: np.ndarray
    margin: np.ndarray
    limits: tuple[Limit, ...]
    force_N: float = 0.0
    arm_lo_mm: np.ndarray | None = None
    arm_hi_mm: np.ndarray | None = None
    force_error_rel: float = 0.0

    @property
    def feasible(self) -> np.ndarray:
        ok = np.ones(self.webs_mm.shape, bool)
        for lim in self.limits:
            ok &= lim.allowed
        return ok

    @property
    def room(self) -> np.ndarray:
        """Per web, its smallest room to any limit (relative; see :func:`limit_room`)."""
        return limit_room(self)


#: The design's own web is kept while every limit leaves it at least this room.
KEEP_WEB_ROOM = 0.05


def force_room(search: WebSearch) -> np.ndarray:
    """Per candidate web, the force limits' room: the margin beyond the closed
    form's error on them, ``F_limit / (F (1 + e)) - 1``
    (``e``: :attr:`WebSearch.force_error_rel`); below 0 the verification's
    closed form cannot tell the margin from its error."""
    return search.margin / (1.0 + search.force_error_rel) - 1.0


def dimension_room(search: WebSearch) -> np.ndarray:
    """Per candidate web, the smallest room of each arm in the arm range and
    of the web in the web range: the distance to the nearer end over the
    range's span (an arm whose target lies outside the range: -inf)."""
    lo, hi = WEB_RANGE_MM
    rooms = [np.minimum(search.webs_mm - lo, hi - search.webs_mm) / (hi - lo)]
    if search.arm_lo_mm is not None and search.arm_hi_mm is not None:
        span = np.maximum(search.arm_hi_mm - search.arm_lo_mm, 1e-12)
        for arm in (search.arm_r_mm, search.arm_m_mm):
            room = np.minimum(arm - search.arm_lo_mm, search.arm_hi_mm - arm) / span
            rooms.append(np.where(np.isnan(arm), -np.inf, room))
    return np.minimum.reduce(rooms)


def limit_room(search: WebSearch) -> np.ndarray:
    """Per candidate web, the smallest room it leaves to any limit, relative:
    :func:`force_room` and :func:`dimension_room`, whichever is smaller. The
    web the design chooses maximises it (:func:`choose_web`), so the next edit
    (a longer arm, a thinner web, a larger force) finds room either way
    instead of a design pressed to a domain end."""
    return np.minimum(force_room(search), dimension_room(search))


def webs_the_process_cuts(plan: Plan, webs_mm: np.ndarray) -> np.ndarray:
    """The candidate webs (mm) the element's cut process leaves on the plan's sheet: a
    web thinner than its minimum web is not a candidate (wire EDM has none).

    Raises:
        DesignError: ``sheet.thickness_mm``: no candidate web is left (the process's
            minimum web on this sheet exceeds them all).
    """
    limits = element_process_limits(plan.raw)
    min_web = limits.min_web_mm
    kept = webs_mm[webs_mm >= min_web.value_mm - 1e-9]
    if kept.size == 0:
        raise DesignError("sheet.thickness_mm", plan.sheet_thickness_mm,
                          f"a sheet on which {limits.process} leaves a web of at most "
                          f"{float(np.max(webs_mm)):g} mm", f"{min_web.rule} = "
                          f"{min_web.value_mm:.4g} mm ({min_web.source})")
    return kept


#: Inside :func:`web_searches_kept`: (plan's design hash, K_r, K_m, correction's id, webs,
#: arm bound) -> (correction, :func:`web_candidates`' arrays); None outside it.
_WEB_SEARCHES: ContextVar[dict | None] = ContextVar("tactcad_web_searches", default=None)


@contextmanager
def web_searches_kept():
    """Within it, :func:`search_webs` works out the candidates of one plan at one K_r and
    K_m once (:func:`web_candidates`: the arms, limits and errors do not read the force)
    and judges every full-scale force asked of them on those: a refusal's alternatives
    seek the largest force of the same tables force after force. Range warnings are not
    said again for a search read back (a refusal's searches say none). Nested uses share
    the outer one's searches."""
    if _WEB_SEARCHES.get() is not None:
        yield
        return
    token = _WEB_SEARCHES.set({})
    try:
        yield
    finally:
        _WEB_SEARCHES.reset(token)


def _kept_web_candidates(plan: Plan, targets: Targets, corr, webs_mm, arm_max_mm
                         ) -> dict[str, Any]:
    """:func:`web_candidates`, read back inside :func:`web_searches_kept` for the same
    plan tables, stiffness targets, correction (the same object: it is kept with the
    answer, so its id is not another's), webs and arm bound."""
    kept = _WEB_SEARCHES.get()
    if kept is None:
        return web_candidates(plan, targets, corr, webs_mm, arm_max_mm)
    key = (plan.design_hash, plan.source, targets.k_r, targets.k_m, id(corr),
           None if webs_mm is None else tuple(float(v) for v in webs_mm), arm_max_mm)
    if key not in kept:
        kept[key] = (corr, web_candidates(plan, targets, corr, webs_mm, arm_max_mm))
    return kept[key][1]


def _kept_in_searches(key: tuple, compute: Callable[[], Any]) -> Any:
    """``compute()``, or inside :func:`web_searches_kept` its value kept under ``key`` (a
    tag first, so it meets no search's key): the same plan's closed-form limits, the same
    element's strain error and the same tips' K_obj seen factor are asked again by every
    target a refusal's scan tries."""
    kept = _WEB_SEARCHES.get()
    if kept is None:
        return compute()
    if key not in kept:
        kept[key] = compute()
    return kept[key]


def web_candidates(plan: Plan, targets: Targets, corr, webs_mm: Sequence[float] | None,
                   arm_max_mm: float | None) -> dict[str, Any]:
    """What :func:`search_webs` works out before it reads the full-scale force: the
    candidate webs and notch radii (mm), the arm bounds and the arms for K_r and K_m (mm,
    corrected closed form), K at the shortest and longest arms (N/mm), each web's yield,
    gauge and fatigue force limits (N, the smaller of the two arms'), the closed form's
    gauge-strain error per web and the plan's closed-form limits.

    Args:
        plan: the design. targets: its K_r and K_m are read (N/mm). corr: the correction.
        webs_mm, arm_max_mm: as :func:`search_webs`.

    Returns:
        The arrays by name (shared when kept: read them, do not change them).
    """
    from tactcad.mechanics.limits import plan_limits

    g, mat = plan.element(1).geometry, plan.material
    if webs_mm is None:
        lo, hi = WEB_RANGE_MM
        grid = np.round(np.arange(lo, hi + WEB_STEP_MM / 2, WEB_STEP_MM), 6)
        webs = np.unique(np.append(grid, g.web_thickness_mm))
    else:
        webs = np.asarray(webs_mm, float)
    webs = webs_the_process_cuts(plan, webs)
    radii = np.maximum(g.notch_radius_mm, webs)
    arm_lo = np.maximum.reduce([np.full_like(webs, ARM_RANGE_MM[0]),
                                tip_root_min_arm_mm(g.tip_width_mm, g.inside_corner_radius_mm,
                                                    radii),
                                mounting_min_arm_mm(plan.bolt,
                                                    float(plan.raw["clamp"]["arm_clearance_mm"]),
                                                    plan.pitch_mm, radii)])
    arm_hi = np.full_like(webs, ARM_RANGE_MM[1] if arm_max_mm is None
                          else min(ARM_RANGE_MM[1], arm_max_mm))
    a_r, a_m = arms_for_stiffnesses((targets.k_r, targets.k_m), webs, radii, g, mat, corr,
                                    arm_lo, arm_hi)

    def k(a):
        return corrected_stiffness(webs, radii, a, mat.youngs_modulus_MPa, g, mat.poisson_ratio,
                                   corr)

    k_short, k_long = k(arm_lo), k(arm_hi)
    b = g.sheet_thickness_mm
    # Stress and gauge limits on the arms the stiffness targets ask for, held
    # to the arm range where a target leaves it (those webs fail there anyway).
    arms = [np.where(np.isnan(a), np.where(k_short < k_t, arm_lo, arm_hi), a)
            for a, k_t in ((a_r, targets.k_r), (a_m, targets.k_m))]
    chain = readout_chain(plan)  # the gauge limits on what the design's grid reads
    limits_r, limits_m = (force_limits(webs, radii, a, b, mat, plan.strength,
                                       closed_form_grid_read_per_N(webs, radii, a, g, mat, chain))
                          for a in arms)
    # a gauge limit holds when its margin clears the closed form's error on the grid's
    # strain (two-sided: a level of the ladder within it may read more), each web's own
    # (a thinner web may lie further outside the grid factor's fit); the stress limits'
    # plane-stress bound is one-sided, the 3D stress lower, so they hold at 1
    return {"webs": webs, "radii": radii, "arm_lo": arm_lo, "arm_hi": arm_hi, "a_r": a_r,
            "a_m": a_m, "k_short": k_short, "k_long": k_long,
            "f_yield": np.minimum(limits_r["yield"], limits_m["yield"]),
            "f_gauge": np.minimum(limits_r["gauge_fatigue"], limits_m["gauge_fatigue"]),
            "f_gauge_max": np.minimum(limits_r["gauge_max"], limits_m["gauge_max"]),
            "f_fatigue": np.fmin(limits_r["fatigue"], limits_m["fatigue"]),  # NaN: none
            "cf_limits": _kept_in_searches(("closed-form limits", plan.design_hash, plan.source),
                                           lambda: plan_limits(plan, "closed-form")),
            "web_err": web_strain_errors(g, mat, chain, webs, radii, arms)}


def search_webs(plan: Plan, targets: Targets, correction=None,
                webs_mm: Sequence[float] | None = None,
                arm_max_mm: float | None = None) -> WebSearch:
    """Evaluate every candidate web (default: the web range in 0.005 mm
    steps plus the design's own web) against the targets' limits; the arms
    are searched up to ``arm_max_mm`` (default the arm range's end; a
    footprint's shorter elements ask less).

    Raises:
        DesignError: the plan's material has no yield strength.
    """

    corr = load_correction() if correction is None else correction
    g, mat = plan.element(1).geometry, plan.material
    if mat.yield_strength_MPa is None:
        raise DesignError("material.yield_strength_MPa", None,
                          "a value in MPa, or a material.grade",
                          "the full-scale force limit needs the yield strength")
    w = _kept_web_candidates(plan, targets, corr, webs_mm, arm_max_mm)
    webs, radii, arm_lo, arm_hi, a_r, a_m = (np.array(w[k]) for k in (
        "webs", "radii", "arm_lo", "arm_hi", "a_r", "a_m"))
    k_short, k_long, web_err = w["k_short"], w["k_long"], w["web_err"]
    f_yield, f_gauge, f_gauge_max, f_fatigue = (w[k] for k in (
        "f_yield", "f_gauge", "f_gauge_max", "f_fatigue"))
    cf_limits = w["cf_limits"]
    F = targets.full_scale_force_N
    sf, gauge = plan.strength.safety_factor, plan.strength.gauge
    clear = 1.0 + web_err
    err = float(web_err[int(np.argmax(f_gauge / clear))])
    y_margin, g_margin = f_yield / F, f_gauge / (F * clear)
    gm_margin = f_gauge_max / (F * clear)
    fat_margin = np.where(np.isnan(f_fatigue), np.inf, f_fatigue / F)
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
              f"the stiffness targets' arms carry at most {np.max(f_gauge / clear):.3g} N at any "
              f"web{_cleared(err)} "
              f"within {1e6 * gauge.fatigue_strain:.0f} microstrain, asked {F:g} N"),
        Limit(f"gauge maximum strain ({gauge.name}) at the full-scale force", "strength.gauge",
              gm_margin >= 1.0,
              f"the stiffness targets' arms carry at most {np.max(f_gauge_max / clear):.3g} N at "
              f"any web{_cleared(err)} "
              f"within {1e6 * gauge.max_strain:.0f} microstrain, asked {F:g} N"),
    )
    notch = notch_fatigue_strength(mat)
    if notch is not None:
        limits += (Limit("material fatigue strength at the notch at the full-scale force",
                         "material.fatigue_strength_MPa", fat_margin >= 1.0,
                         f"the stiffness targets' arms carry at most {np.nanmax(f_fatigue):.3g} N "
                         f"at any web within {notch.strength_MPa:.4g} MPa (surface factor "
                         f"{notch.surface_factor:.2f}), asked {F:g} N"),)
    margin = np.minimum.reduce([y_margin, g_margin, gm_margin, fat_margin])
    return WebSearch(webs, radii, a_r, a_m, margin, limits, F, arm_lo, arm_hi,
                     max(lim.error_estimate_rel for lim in cf_limits))


#: Webs at which :func:`web_strain_errors` evaluates the closed form's gauge-strain error
#: (each row's); between them a web takes the larger of its two neighbours'.
ERROR_SAMPLES = 9


def web_strain_errors(g, material, chain, webs: np.ndarray, radii: np.ndarray,
                      arms: Sequence[np.ndarray]) -> np.ndarray:
    """Per candidate web, the closed form's error on the gauge limits of the elements it
    makes (:func:`tactcad.mechanics.limits.closed_form_gauge_error_rel`, the larger of the
    rows'), relative, shape of ``webs``: evaluated at :data:`ERROR_SAMPLES` webs spread
    over the candidates, a web between two of them taking the larger (the error grows
    stepwise where a web leaves the grid factor's fit).

    Args:
        g: the layout's element (its sheet, profile and tip); material, chain: the design's.
        webs, radii: the candidates' webs and notch radii (mm), ascending webs.
        arms: per row, each candidate's arm (mm), shape of ``webs``.
    """
    from dataclasses import replace

    from tactcad.mechanics.limits import closed_form_gauge_error_rel

    order = np.argsort(webs)
    picks = np.unique(np.linspace(0, len(webs) - 1, min(ERROR_SAMPLES, len(webs))).round()
                      .astype(int))
    sampled = order[picks]
    def error(element) -> float:
        try:
            key = ("gauge strain error", element, material, chain)
            hash(key)
        except TypeError:  # a table the key cannot hold: worked out each time
            return closed_form_gauge_error_rel(element, material, chain)
        return _kept_in_searches(key, lambda: closed_form_gauge_error_rel(element, material,
                                                                          chain))

    at = np.array([max(error(replace(g, web_thickness_mm=float(webs[i]),
                                     notch_radius_mm=float(radii[i]), arm_length_mm=float(a[i])))
                       for a in arms) for i in sampled])
    t = webs[sampled]
    right = np.clip(np.searchsorted(t, webs), 0, len(t) - 1)
    left = np.clip(right - 1, 0, len(t) - 1)
    exact = np.isclose(t[right], webs)
    return np.where(exact, at[right], np.maximum(at[left], at[right]))


def _cleared(error_rel: float) -> str:
    """The words for a force carried with the closed form's strain error cleared."""
    return f" (its {100 * error_rel:.2g} % closed-form strain error cleared)" if error_rel > 0 else ""


#: Number of leading limits of :func:`search_webs` that concern stiffness (the
#: rest are force limits, proportional to the full-scale force).
STIFFNESS_LIMITS = 4


def max_full_scale_force_N(search: WebSearch, force_N: float) -> float:
    """The largest full-scale force (N) some web carries while meeting the
    stiffness limits (its gauge limits clearing the closed form's strain error:
    :func:`search_webs`); 0 when none does. ``force_N`` is the force the search was
    run for."""
    ok = np.ones(search.webs_mm.shape, bool)
    for lim in search.limits[:STIFFNESS_LIMITS]:
        ok &= lim.allowed
    return float(np.max(search.margin[ok]) * force_N) if ok.any() else 0.0


def binding_limits(search: WebSearch) -> list[Limit]:
    """Every limit that binds when no web is feasible, in the order listed:
    each limit without which some web would be feasible, and every limit the
    most nearly feasible web (fewest failures, then largest force margin)
    misses; so two limits whose allowed webs do not overlap (the soft arm's
    range on the thick webs, the gauge's strain on the thin ones) are both named."""
    allowed = np.array([lim.allowed for lim in search.limits])
    freeing = {i for i in range(len(search.limits))
               if np.all(np.delete(allowed, i, axis=0), axis=0).any()}
    misses = (~allowed).sum(axis=0)
    best = np.flatnonzero(misses == misses.min())
    j = int(best[np.argmax(search.margin[best])])
    nearest = {i for i, lim in enumerate(search.limits) if not lim.allowed[j]}
    return [search.limits[i] for i in sorted(freeing | nearest)]


def best_stiffness_web(search: WebSearch) -> int | None:
    """Index of the web with the largest force margin among those meeting the
    stiffness limits, or None when no web meets them."""
    ok = np.ones(search.webs_mm.shape, bool)
    for lim in search.limits[:STIFFNESS_LIMITS]:
        ok &= lim.allowed
    if not ok.any():
        return None
    return int(np.argmax(np.where(ok, search.margin, -np.inf)))


def refusal_text(search: WebSearch) -> str:
    """Why no web is feasible: every binding limit with what it asks, and the
    largest full-scale force the stiffness targets allow."""
    lims = binding_limits(search)
    text = "targets cannot be met; binding limits: " + "; ".join(
        f"{lim.name} ({lim.field}): {lim.detail}, met by {_web_span(search.webs_mm, lim.allowed)}"
        for lim in lims)
    if search.force_N:
        f_max = max_full_scale_force_N(search, search.force_N)
        text += (f". Largest feasible full-scale force for these stiffness targets: {f_max:.4g} N"
                 if f_max > 0 else ". No full-scale force is feasible for these stiffness targets")
        j = best_stiffness_web(search)
        if j is not None:
            missed = [lim.name for lim in search.limits[STIFFNESS_LIMITS:] if not lim.allowed[j]]
            if missed:
                text += (f", at web {search.webs_mm[j]:.3f} mm, where the asked force misses "
                         + "; ".join(missed))
    return text


#: The web rule in words, for the design's reasons and its report.
WEB_RULE = ("among the feasible webs (each force limit's margin clearing the closed form's error "
            "on it), the design's own web while it leaves "
            f"{100 * KEEP_WEB_ROOM:g} % room, else the one whose smallest room is largest (room: an "
            "arm's or the web's distance to the nearer end of its range over the range's span, "
            "and a force limit's margin beyond the closed form's error)")


def web_pool(search: WebSearch) -> tuple[np.ndarray, np.ndarray]:
    """(pool, room) of :func:`choose_web`: the feasible webs, whose force margins
    clear the closed form's error, with :func:`limit_room`."""
    return search.feasible, limit_room(search)


def choose_web(search: WebSearch, design_web_mm: float) -> int:
    """Index of the chosen web (:data:`WEB_RULE`).

    The feasible webs are the pool (their force margins clear the closed form's
    error: :func:`search_webs`), room is :func:`limit_room`. The design's own web
    is kept while it is in the pool with at least :data:`KEEP_WEB_ROOM` room; else
    the pool's web with the largest room (ties: the thinner web).

    Raises:
        InverseDesignError: no web is feasible (the binding limit named).
    """
    if not search.feasible.any():
        raise InverseDesignError(refusal_text(search), value=search.force_N)
    pool, room = web_pool(search)
    own = np.flatnonzero(np.isclose(search.webs_mm, design_web_mm) & pool
                         & (room >= KEEP_WEB_ROOM))
    if own.size:
        return int(own[0])
    return int(np.argmax(np.where(pool, room, -np.inf)))


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
    #: ``(field, base value, new value)`` of each layout value the search changed
    #: (:mod:`tactcad.studies.layout_search`); empty when the base layout met the targets.
    layout_changes: tuple[tuple[str, Any, Any], ...] = ()
    max_full_scale_force_N: float = 0.0
    binding_limits: tuple[str, ...] = ()
    #: The largest full-scale force (N) the layout search designs at, across the layouts it
    #: searched (the figure its refusal names), and the layout in words; None when not
    #: sought (a single layout's design, or a footprint): ``max_full_scale_force_N`` is
    #: this design's layout's alone.
    across_layouts_force_N: float | None = None
    across_layouts_layout: str = ""
    #: This design's layout in words ("sheet 4 mm, pitch 4.2 mm, ..."; "" when not searched).
    layout_words: str = ""
    #: The K_obj factor the units see through the tissue coupling (1: no tissue). It differs
    #: from ``targets.kobj_seen_factor`` (the centring used) when eq. 2's centring was kept.
    coupling_seen_factor: float = 1.0
    #: The notch radius differs from the tables the search started from (it follows a
    #: thicker web: :func:`set_notch_radius`).
    notch_changed: bool = False


#: The binding limits are those of a force this much above the largest feasible one.
MAX_FORCE_PROBE = 0.001


#: Largest arm / arm height of the closed-form correction's fit (the sweep's
#: rule keeps a/h <= 4), and the tallest arm the design file allows (mm).
MAX_ARM_OVER_HEIGHT = 4.0
MAX_ARM_HEIGHT_MM = 5.0
#: Rounds of "choose arms, raise the arm height, choose again".
ARM_HEIGHT_ROUNDS = 4


def arm_height_for(longest_arm_mm: float, arm_height_mm: float) -> float | None:
    """The arm height (mm, 0.1 mm steps, at most 5 mm) that keeps the longest
    arm within a/h <= 4, or None when the present height already does (or
    cannot be raised further)."""
    need = math.ceil(longest_arm_mm / MAX_ARM_OVER_HEIGHT * 10 - 1e-9) / 10
    need = min(need, MAX_ARM_HEIGHT_MM)
    return need if need > arm_height_mm + 1e-9 else None


def arm_height_reason(arm_height_mm: float, longest_arm_mm: float) -> str:
    """Why the inverse design raised the arm height (mm): the longest arm (mm, as written)
    within a/h <= :data:`MAX_ARM_OVER_HEIGHT`, or, where the tallest arm the file allows
    cannot hold it, that height and the ratio left."""
    ratio = longest_arm_mm / arm_height_mm
    if ratio <= MAX_ARM_OVER_HEIGHT + 1e-9:
        return (f"tactcad design: raised to {arm_height_mm:g} mm so the longest arm "
                f"({longest_arm_mm:g} mm) keeps arm / arm height <= {MAX_ARM_OVER_HEIGHT:g}, "
                "inside the range the closed form's fem3d correction was fitted over.")
    return (f"tactcad design: raised to {arm_height_mm:g} mm, the tallest arm the design file "
            f"allows: the longest arm ({longest_arm_mm:g} mm) leaves arm / arm height "
            f"{ratio:.3g}, beyond the {MAX_ARM_OVER_HEIGHT:g} the closed form's fem3d "
            "correction was fitted over.")


def _mentions_paper(text: str) -> bool:
    """True when ``text`` names the paper, its tables or its design (the
    shipped ``macro_array``, the "macro array"), which no new design may carry."""
    low = text.lower()
    return any(word in low for word in ("paper", "table 1", "table 2", DEFAULT_DESIGN.stem,
                                        DEFAULT_DESIGN.stem.replace("_", " ")))


#: The pointer a reason carried from an earlier base design starts with
#: (:func:`neutral_assumptions`); its own words, if any, follow the colon.
_KEPT_FROM = re.compile(r"^Kept from the base design(?: \([^)]*\)|[^,:]*), where it is an "
                        r"assumption[.:]\s*")
#: A reason's pointer to the base design, named or not (:func:`with_base_named`).
_BASE_POINTER = re.compile(r"^Kept from the base design(?: \([^)]*\)| [^,:()]+)?(?=[,:])")
#: A layout reason's base value (:func:`tactcad.studies.layout_search.searched_design`).
_BASE_VALUE = re.compile(r" instead of the base design's ([^;]+);")


def with_base_named(data: Mapping[str, Any], label: str) -> dict[str, Any]:
    """``data`` with every reason that points to the base design naming it (``label``,
    e.g. "the shipped default example" or "paste264.toml"): "Kept from the base design
    (paste264.toml), where it is an assumption.", "4 instead of 3 in the base design
    (paste264.toml)", so a written design says what it was made from.

    Args:
        data: a new design's raw tables (not modified).
        label: the words naming the base design.

    Returns:
        The tables with their ``[assumptions]`` so worded.
    """
    out = dict(data)
    named = f"the base design ({label})"
    out["assumptions"] = {
        key: _BASE_VALUE.sub(lambda m: f" instead of {m.group(1)} in {named};",
                             _BASE_POINTER.sub(f"Kept from {named}", as_read(key, why, data)))
        for key, why in dict(data.get("assumptions", {})).items()}
    return out


def as_read(key: str, why: Any, data: Mapping[str, Any]) -> str:
    """A reason carried into a new design as its outputs would show it
    (:func:`tactcad.vocabulary.schema.reason_as_read`): without the base's record of its
    value, and saying so where that value is not the new design's (the record is written
    anew with the file).

    Args:
        key: the assumption's key. why: its reason. data: the new design's tables.

    Returns:
        The reason's text.
    """
    return reason_as_read(key, why, data)[0] if isinstance(why, str) else str(why)


def neutral_assumptions(data: Mapping[str, Any], base_name: str) -> dict[str, str]:
    """The base design's ``[assumptions]`` for a new design that does not
    cite the paper.

    A reason that says the value is not in the paper keeps its own argument,
    as does one the base itself carried from its own base (the older pointer
    dropped: a reason does not pass on a chain of designs). One that still
    mentions the paper, its tables or its design is replaced by a neutral
    pointer (the base, when it is the paper's design, is not named).

    Args:
        data: the base design's raw tables.
        base_name: the base design's name, named in the pointer.

    Returns:
        The new design's reasons by key.
    """
    from tactcad.design.requirements_section import cites_paper

    named = "" if cites_paper(data) or _mentions_paper(base_name) else f" {base_name}"
    return {key: with_record(neutral_reason(words, named), written)
            for key, (words, written) in ((key, plain_reason(str(why))) for key, why
                                          in dict(data.get("assumptions", {})).items())}


def neutral_reason(words: str, named: str) -> str:
    """One reason of the base design, without its record of the value
    (:func:`tactcad.vocabulary.schema.plain_reason`), as a new design carries it
    (:func:`neutral_assumptions`).

    Args:
        words: the reason's words. named: " " and the base's name, or "" (not named).

    Returns:
        The reason's own argument, or a pointer to the base design where it has none of
        its own or cites the paper.
    """
    pointer = f"Kept from the base design{named}, where it is an assumption."
    text = _KEPT_FROM.sub("", words) or words or pointer
    if text.startswith("Not in the paper."):
        text = text[len("Not in the paper."):].strip() or text
    return pointer if _mentions_paper(text) else text


def with_record(words: str, written: str | None) -> str:
    """A reason's words with the base's record of the value it was written for put back
    (:data:`tactcad.vocabulary.schema.WRITTEN_FOR`), so :func:`with_base_named` can tell
    whether it still applies; the words alone where there was none.

    Args:
        words: the reason's words. written: the recorded value text, or None.

    Returns:
        The reason's text.
    """
    return words if written is None else f"{words} [written for {written}]"


#: What a reason quotes of its design: dimensions ("1.5 mm", "2 x 3 mm") and bolt sizes ("M2").
_QUOTED_DIMENSION = re.compile(r"\d+(?:\.\d+)?(?:\s*[x×]\s*\d+(?:\.\d+)?)*(?=\s*mm\b)")
_QUOTED_BOLT = re.compile(r"\bM\d+(?:\.\d+)?\b")
_REASON_KEY = re.compile(r"^(\w+)\.(\w+)(?:\[(\d+)\])?$")


def _own_values(key: str, data: Mapping[str, Any]) -> list[Any]:
    """The value(s) the reason ``key`` ("element.tip_height_mm",
    "arms.lengths_mm[5]", 1-based) is given for in the design ``data``."""
    m = _REASON_KEY.match(key)
    table = data.get(m.group(1)) if m else None
    value = table.get(m.group(2)) if isinstance(table, Mapping) else None
    if isinstance(value, list):
        k = int(m.group(3)) - 1 if m.group(3) else None
        return value if k is None else value[k:k + 1]
    return [] if value is None else [value]


def quotes_not_its_own(key: str, reason: str, data: Mapping[str, Any]) -> list[str]:
    """The dimensions ("2 x 3 mm") and bolt sizes ("M2") the reason for
    ``key`` quotes that are not ``key``'s own value in the design ``data``:
    values of other fields, or of another design, which a reason carried
    into a new design cannot vouch for. Empty: the reason quotes only its
    own value, as the design has it."""
    own = _own_values(key, data)
    numbers = [float(v) for v in own if isinstance(v, (int, float)) and not isinstance(v, bool)]

    def held(quote: str) -> bool:
        return all(any(math.isclose(float(v), n, rel_tol=1e-9) for n in numbers)
                   for v in re.findall(r"\d+(?:\.\d+)?", quote))

    dims = [f"{q} mm" for q in _QUOTED_DIMENSION.findall(reason) if not held(q)]
    return dims + [b for b in _QUOTED_BOLT.findall(reason) if b not in own]


def with_reasons_that_hold(data: dict[str, Any], carried: Mapping[str, str]) -> None:
    """Replace, in ``data``'s ``[assumptions]``, each reason still as it was
    carried from the base design (``carried``) that quotes other values than
    its field's own in this design (:func:`quotes_not_its_own`), e.g. the
    base's contact face in the tip height's reason, by a pointer
    that says so without repeating them (they are the base design's, the paper's when it is
    the base): a reason is derived from the design it stands in."""
    why = data.get("assumptions", {})
    for key, text in carried.items():
        quoted = quotes_not_its_own(key, text, data) if why.get(key) == text else []
        if quoted:
            why[key] = ("Kept from the base design, whose reason quotes values this design "
                        "does not have (left out, not checked for this one): state this "
                        "value's own reason here.")


def with_grid(data: Mapping[str, Any], rows: int | None, columns: int | None) -> dict[str, Any]:
    """Raw tables with a new rows x columns grid; every arm the base's first
    (the inverse design rewrites them). Rows and columns are validated with
    the design (``array.rows``, ``array.columns``)."""
    out = copy_tables(dict(data))
    if rows is None and columns is None:
        return out
    arr = out["array"]
    if rows is not None:
        arr["rows"] = rows
    if columns is not None:
        arr["columns"] = columns
    n = arr["rows"] * arr["columns"] if all(isinstance(arr.get(k), int) and not isinstance(
        arr.get(k), bool) for k in ("rows", "columns")) else 0
    if 0 < n <= 1000:
        out["arms"]["lengths_mm"] = [out["arms"]["lengths_mm"][0]] * n
    return out


def design_for_targets(base: Plan, targets: Targets, *, grade: str | None = None,
                       pitch_mm: float | None = None, rows: int | None = None,
                       columns: int | None = None, name: str = "inverse_design",
                       correction=None) -> InverseDesign:
    """Reference and measuring elements meeting ``targets`` on ``base``'s
    design (see the module docstring for the method and layout).

    Args:
        base: the design whose other dimensions are kept.
        targets: the sensing targets.
        grade: material grade of the library (:mod:`tactcad.vocabulary.material_library`) to
            use instead of the base material.
        pitch_mm: array pitch (mm) instead of the base's.
        name: ``design.name`` of the new design.
        correction: closed-form correction (default: the stored one).

    Raises:
        InverseDesignError: the targets cannot be met (the binding limit named).
        DesignError: a bad grade or pitch, or the result breaks a design rule
            (field named).
    """
    data = design_tables(base, grade=grade, pitch_mm=pitch_mm, rows=rows, columns=columns)
    return design_from_tables(data, targets, name=name, correction=correction)


#: Values a base design chose for its own gauge grid and web, left out of a new design so
#: their rule chooses again: the bridge excitation (stated: the base's; not stated: the
#: grid power density of Micro-Measurements TN-502 for the new grid).
CHOSEN_FOR_THE_BASE = frozenset({"readout.excitation_V"})


def design_tables(base: Plan, *, grade: str | None = None, pitch_mm: float | None = None,
                  rows: int | None = None, columns: int | None = None) -> dict[str, Any]:
    """The raw tables an inverse design starts from: ``base``'s, with its
    requirements, files and paper-bound reasons left out, and the grade, pitch
    and grid asked for (arguments as :func:`design_for_targets`).

    Raises:
        DesignError: a bad grade.
    """
    return start_tables(base.raw, base.name, grade=grade, pitch_mm=pitch_mm, rows=rows,
                        columns=columns)


def start_tables(raw: Mapping[str, Any], base_name: str, *, grade: str | None = None,
                 pitch_mm: float | None = None, rows: int | None = None,
                 columns: int | None = None, kept: frozenset[str] = frozenset()) -> dict[str, Any]:
    """:func:`design_tables` on a base design's raw tables (not validated: its
    values are where the search starts, e.g. the shipped design's bolt with
    more columns than it holds) and its name.

    Choices the base made for its own grid are not carried over (see
    :data:`CHOSEN_FOR_THE_BASE`) unless ``kept`` names them (the ``--set`` keys
    the user wrote): the new design gets their rule's value.

    Raises:
        DesignError: a bad grade.
    """
    data = copy_tables(dict(raw))
    data["assumptions"] = neutral_assumptions(data, base_name)
    for key in CHOSEN_FOR_THE_BASE - kept:
        section, field = key.split(".")
        if isinstance(data.get(section), dict) and data[section].pop(field, None) is not None:
            data["assumptions"].pop(key, None)
            if not data[section]:
                del data[section]
    data.pop("requirements", None)  # the new design's are written below
    data.pop("files", None)  # where the base design's rigs and scenes lie: not the new design's
    if grade is not None:
        from tactcad.vocabulary.material_library import material_grade

        library = material_grade(grade)
        grade = library.name  # "ti-6al-4v-annealed" -> the library's spelling
        data["material"] = {"name": grade, "grade": grade}
        data["assumptions"] = {k: v for k, v in data.get("assumptions", {}).items()
                               if not k.startswith("material.")}
        data["assumptions"]["material.grade"] = grade_reason(library)
    else:  # the base's own material values (an E of its own, say) kept: so said
        material = data.get("material")
        own = [key for key in (material if isinstance(material, dict) else {})
               if key != "name" and f"material.{key}" not in kept]  # not the user's --set
        data["assumptions"] = {**{f"material.{key}": kept_reason(raw, base_name)
                                  for key in own}, **data["assumptions"]}
    if pitch_mm is not None:
        data = design_variant(data, pitch_mm=pitch_mm)
    return with_grid(data, rows, columns)


def grade_reason(library) -> str:
    """The reason a design's ``material.grade`` chosen by ``--material`` is written with: the
    library's grade and where its values come from
    (:meth:`tactcad.vocabulary.material_library.MaterialGrade.cited`)."""
    return f"tactcad design --material {library.name}: {library.cited()}."


def kept_reason(raw: Mapping[str, Any], base_name: str) -> str:
    """The reason a value kept from the base design is written with where the base gives
    none: the base named, unless it is the paper's design (:func:`neutral_assumptions`)."""
    from tactcad.design.requirements_section import cites_paper

    named = "" if cites_paper(raw) or _mentions_paper(base_name) else f" {base_name}"
    return f"Kept from the base design{named}, where it is an assumption."


def sensing_unit_numbers(plan: Plan) -> list[tuple[int, int]]:
    """(measuring, reference) element numbers an inverse design makes on ``plan``'s grid
    (whatever the base file's own references): each element of a row against its row's
    reference (:func:`reference_elements`)."""
    refs = reference_elements(plan.rows, plan.columns)
    return [(s.number, refs[s.row]) for s in plan.slots if s.number not in refs]


def centred_for_tissue(plan: Plan, targets: Targets) -> Targets:
    """``targets`` with the K_obj factor eq. 2 sees through the tissue on ``plan``'s tips
    (:func:`tactcad.in_use.tissue_coupling.centred_seen_factor`); unchanged without a tissue."""
    if targets.tissue is None:
        return targets
    from tactcad.in_use.tissue_coupling import centred_seen_factor, tip_punches

    units = sensing_unit_numbers(plan)

    def factor() -> float:
        return centred_seen_factor(plan, units, targets.kr_over_km,
                                   targets.k_obj_range_N_per_mm, targets.tissue)

    # the factor reads the plan only through its tips: a refusal's force bisection on one
    # layout asks it again for every force
    key = ("seen factor", tip_punches(plan), tuple(units), targets.kr_over_km,
           tuple(targets.k_obj_range_N_per_mm), targets.tissue)
    try:
        hash(key)
    except TypeError:
        return replace(targets, kobj_seen_factor=factor())
    return replace(targets, kobj_seen_factor=_kept_in_searches(key, factor))


def coupled_span_misses(plan: Plan, targets: Targets) -> list[str]:
    """Units whose coupled R does not fall strictly, above 1, over the asked K_obj range on
    ``targets.tissue`` (one line each; none without a tissue): the coupled inversion
    (eq. 3 corrected) then has no single answer there."""
    if targets.tissue is None:
        return []
    from tactcad.in_use.tissue_coupling import coupled_ratio, coupled_sample, unit_label
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element

    k = ladder_stiffness_by_element(plan)
    sample = coupled_sample(plan, targets.tissue)
    points = report_points(targets)
    out = []
    for unit in sensing_unit_numbers(plan):
        r = np.atleast_1d(coupled_ratio(sample, k, unit, points))
        if not (np.all(np.diff(r) < 0) and r[-1] > 1.0):
            out.append(f"unit {unit_label(unit)}: coupled R {r[0]:.4g} ... {r[-1]:.4g} over K_obj "
                       f"{points[0]:g} ... {points[-1]:g} N/mm")
    return out


def tissue_assumption(targets: Targets, note: str = "") -> str:
    """The design's stated assumption on the object under the tips."""
    if targets.tissue is None:
        return ("tactcad design --tissue-coupling off: K_r and K_m centred on the range by eq. 2 "
                "alone (each tip on its own object spring); tips on one sample couple and bias "
                "eq. 3's K_obj (`verify` reports it)")
    return (f"tactcad design --tissue-coupling on: {targets.tissue.describe()}; "
            + (note or f"K_r and K_m centred on the K_obj range as the units see it through the "
                       f"coupling (K_obj seen x{targets.kobj_seen_factor:.3g})")
            + "; every unit's coupled R spans the range (read it with the coupled inversion, "
              "eq. 3 corrected)")


def design_from_tables(data: dict[str, Any], targets: Targets, *, name: str = "inverse_design",
                       correction=None, arm_max_mm: float | None = None,
                       shortest_element: bool = False) -> InverseDesign:
    """:func:`design_for_targets` on raw design tables already holding the
    material, grid and pitch (``data`` is changed: pass a copy); a refusal
    names the binding limits only (no alternatives searched). ``arm_max_mm``:
    the longest arm allowed (as :func:`search_webs`); ``shortest_element``:
    the overall length becomes the shortest that holds the longest arm's bolt
    pattern (0.5 mm steps) instead of only growing when it must.

    With a tissue (``targets.tissue``) the stiffnesses centre on the K_obj
    range as the units see it through the coupling (:func:`centred_for_tissue`);
    where that centring breaks a limit, eq. 2's centring is kept if every unit's
    coupled R still spans the range (so stated); a design whose coupled R does
    not span it is refused naming the coupling.

    Raises:
        InverseDesignError: the targets cannot be met.
        DesignError: the tables break a design rule (field named).
    """
    kw = dict(name=name, correction=correction, arm_max_mm=arm_max_mm,
              shortest_element=shortest_element)
    centred = centred_for_tissue(plan_from_dict(copy_tables(data), source="<inverse design>"),
                                 targets)
    note = ""
    try:
        d = _design_from_tables(copy_tables(data), centred, **kw)
    except InverseDesignError as exc:
        if centred is targets:
            raise
        try:  # eq. 2's centring: the range may still be read through the coupling
            d = _design_from_tables(data, targets, **kw)
        except InverseDesignError:
            raise exc from None
        note = (f"K_r and K_m at eq. 2's centring: centred for the coupling (K_obj seen "
                f"x{centred.kobj_seen_factor:.3g}, K_m {centred.k_m:.4g} N/mm) they break "
                f"{', '.join(d.binding_limits) or 'a limit'} at this force, so the sensitivity "
                f"peak sits off the range's centre by that factor")
    misses = coupled_span_misses(d.plan, d.targets)
    if misses:
        raise InverseDesignError(
            "the tissue coupling binds: a unit's coupled R does not fall over the K_obj range ("
            + "; ".join(misses) + ")", field="--tissue-coupling", value="on",
            allowed="off (eq. 2 alone), or a wider pitch or a narrower K_obj range")
    d.data.setdefault("assumptions", {})["requirements.kobj_range_N_per_mm"] = \
        tissue_assumption(d.targets, note)
    return replace(d, coupling_seen_factor=centred.kobj_seen_factor)


def _design_from_tables(data: dict[str, Any], targets: Targets, *, name: str = "inverse_design",
                        correction=None, arm_max_mm: float | None = None,
                        shortest_element: bool = False) -> InverseDesign:
    """:func:`design_from_tables` for the stiffnesses of ``targets`` as they stand."""
    base_web = float(data["element"]["web_thickness_mm"])
    carried = dict(data.get("assumptions", {}))  # the base's reasons, checked once values are set
    refusal, height_raised = None, False
    for _ in range(ARM_HEIGHT_ROUNDS):
        plan = plan_from_dict(data, source="<inverse design>")
        with range_warnings_unsaid():  # the candidates, not the design written (its own warn)
            search = search_webs(plan, targets, correction, arm_max_mm=arm_max_mm)
        try:
            i, refusal = choose_web(search, base_web), None
        except InverseDesignError as exc:  # judge the targets on the arm height they need
            i, refusal = best_stiffness_web(search), exc
            if i is None:
                raise
        longest = max(float(search.arm_r_mm[i]), float(search.arm_m_mm[i]))
        raised = arm_height_for(longest, plan.element(1).geometry.arm_height_mm)
        if raised is None:
            break
        data["element"]["arm_height_mm"] = raised
        fit_to_bolt(data)  # a taller arm asks a taller base below it
        height_raised = True  # its reason quotes the arms the last round chooses
    if refusal is not None:
        raise refusal
    f_max = max_full_scale_force_N(search, targets.full_scale_force_N)
    above = replace(targets, full_scale_force_N=f_max * (1 + MAX_FORCE_PROBE))
    with range_warnings_unsaid():
        probe = search_webs(plan, above, correction, arm_max_mm=arm_max_mm)
    bind = tuple(lim.name for lim in binding_limits(probe))
    t, R = float(search.webs_mm[i]), float(search.radii_mm[i])
    a_r = round(float(search.arm_r_mm[i]), ARM_DECIMALS)
    a_m = round(float(search.arm_m_mm[i]), ARM_DECIMALS)
    refs = reference_elements(plan.rows, plan.columns)
    arms = [a_r if n in refs else a_m for n in range(1, len(plan.slots) + 1)]
    web_changed = not math.isclose(t, base_web)
    data["arms"]["lengths_mm"] = [float(a) for a in arms]
    if height_raised:
        data.setdefault("assumptions", {})["element.arm_height_mm"] = arm_height_reason(
            float(data["element"]["arm_height_mm"]), max(arms))
    notch_changed = set_notch_radius(data, R)
    if shortest_element:
        need = required_overall_length_mm(data, max(arms), R)
        set_overall_length(data, math.ceil(need / LENGTH_STEP_MM - 1e-9) * LENGTH_STEP_MM)
    data = design_variant(data, web_mm=t)
    lo, hi = targets.k_obj_range_N_per_mm
    data["design"] = {"name": name, "description": (
        f"Inverse design: K_r/K_m = {targets.kr_over_km:g} for K_obj {lo:g}-{hi:g} N/mm, "
        f"full-scale force {targets.full_scale_force_N:g} N (K_r {targets.k_r:.4g}, K_m "
        f"{targets.k_m:.4g} N/mm)")}
    why = data.setdefault("assumptions", {})
    data["arms"]["reference_elements"] = list(refs)  # each row declares its reference
    why["arms.lengths_mm"] = (
        f"tactcad design: elements {' and '.join(map(str, refs))} ({reference_column_words(plan.columns)}"
        f" of each row) are "
        f"the references, arm {a_r:g} mm for K_r = {targets.k_r:.4g} N/mm; the others measure, "
        f"arm {a_m:g} mm for K_m = {targets.k_m:.4g} N/mm = sqrt(K_lo K_hi / X) (corrected "
        f"closed form).")
    why.pop("arms.lengths_mm[5]", None)  # the paper's missing element 5 is not this design's
    if web_changed:
        why["element.web_thickness_mm"] = (
            f"tactcad design: {t:g} mm by the web rule at {targets.full_scale_force_N:g} N: "
            f"{WEB_RULE}.")
    with_reasons_that_hold(data, carried)
    data["requirements"], derived = requirements_table(targets, data)
    data.setdefault("assumptions", {}).update(
        {f"requirements.{key}": reason for key, reason in derived.items()})
    new_plan = plan_from_dict(data, source="<inverse design>")
    return InverseDesign(targets, data, new_plan, refs, web_changed, a_r, a_m,
                         max_full_scale_force_N=f_max, binding_limits=bind,
                         notch_changed=notch_changed)


def requirements_table(targets: Targets,
                       data: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
    """The ``[requirements]`` table an inverse design writes: the targets and the K_obj
    resolution the elements reach over the range at the full-scale force, each element
    read through the design's own read-out chain, padded by the closed form's error on it
    and rounded up, so that its margin is at least that error and ``verify --model auto``
    decides it at the closed form (:mod:`tactcad.studies.verification`). No
    ``k_tolerance_rel``: the K band over the web tolerance is the design's own figure, and
    a band derived from it could never fail; ``verify`` reports it, not judged, and notes a
    spread beyond :data:`~tactcad.studies.verification.K_SPREAD_NOTE_REL`.

    Returns:
        (the table, keys of :data:`tactcad.design.requirements_section.REQUIREMENT_KEYS`;
        the reason of the one it derives from the prediction, ``kobj_resolution_rel``, by
        key, starting with :data:`~tactcad.design.requirements_section.DERIVED_BY_DESIGN`
        so that ``verify`` does not call it stated by the lab).
    """
    plan = plan_from_dict(data, source="<inverse design>")
    lo, hi = targets.k_obj_range_N_per_mm
    resolution, why = written_kobj_resolution(plan, targets)
    table = {"full_scale_force_N": float(targets.full_scale_force_N),
             "kobj_range_N_per_mm": [float(lo), float(hi)],
             "kr_over_km": float(targets.kr_over_km),
             "kobj_resolution_rel": resolution}
    # no k_tolerance_rel: a band derived from the design's own K spread could never fail;
    # verify reports the spread as a figure (and notes a large one) until the lab states one
    return table, {"kobj_resolution_rel": why}


def written_kobj_resolution(plan: Plan, targets: Targets) -> tuple[float, str]:
    """The K_obj resolution requirement ``tactcad design`` writes, for every construction
    (a stacked array's :func:`requirements_table`, a comb's), and its reason: the worst
    K_obj resolution over the targets' range at their full-scale force, each element read
    through the design's own read-out chain (closed form), padded by its error and rounded
    up (:func:`tactcad.studies.verification.kobj_resolution_requirement`). What the design
    reaches, not what the lab asked: the reason starts with
    :data:`~tactcad.design.requirements_section.DERIVED_BY_DESIGN`, so ``verify`` judges it
    as a guard on later edits, not as the lab's; a lab's own value replaces it.

    Args:
        plan: the designed plan. targets: the targets it was designed for (N/mm, N).

    Returns:
        (the requirement, relative; possibly above what a design file may state, or inf
        where no unit reads K_obj; the reason).
    """
    from tactcad.design.requirements_section import DERIVED_BY_DESIGN
    from tactcad.studies.verification import (element_figures, kobj_resolution_requirement,
                                              sensing_units)

    lo, hi = targets.k_obj_range_N_per_mm
    F = targets.full_scale_force_N
    units = sensing_units(plan, element_figures(plan, "closed-form"))
    resolution, worst = kobj_resolution_requirement(units, (lo, hi), F)
    return resolution, (
        f"{DERIVED_BY_DESIGN}: the worst K_obj resolution over {lo:g}-{hi:g} N/mm at "
        f"the full-scale force {F:g} N, {100 * worst:.3g} % (closed form, each element "
        "read through the design's [readout] chain), padded by its error and rounded up; "
        "state the resolution your use needs in its place (and this reason with it) to "
        "hold the design to it.")


def report_points(targets: Targets, n: int = REPORT_POINTS) -> np.ndarray:
    """K_obj values of the report: log-spaced over the range, ends included (N/mm)."""
    lo, hi = targets.k_obj_range_N_per_mm
    return np.geomspace(lo, hi, n)
