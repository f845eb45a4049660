"""The grasp as a virtual experiment: a pivoting jaw closes on a tissue slab; each element's
travel, deflection and force, each unit's R and K_obj reading against the true K_obj, for the
units as the design lays them out, paired at equal radius and, where the design is paired
already, laid along the rows (one pitch apart in radius), side by side.

Model (units mm, N, N/mm, degrees):

* Kinematics (:mod:`tactcad.in_use.jaw_kinematics`): at a closing angle θ the jaw presses a
  tip at radius r into the tissue by Δ = max(0, t(r) − r sin θ), t(r) the tissue's thickness
  there: a flat ``slab`` (t = h: the tips near the pivot are pressed most) or a ``wedge``
  that fills the open jaw (t = h r / r_last, h at the last tip: the jaw closing from first
  contact presses every tip in proportion to its radius, Δ = r (h / r_last − sin θ)).
* Each tip is a rigid flat punch (the design's contact face) on a spring K (the element);
  the tissue couples the tips: its surface displacements are w = C P for the tip forces P
  (:func:`tissue_compliance`: rigid punches on a layer of the slab's thickness on the
  opposing jaw, bonded to it unless the design's ``[tissue_slab] base`` says otherwise, or
  a half-space, :mod:`tactcad.mechanics.contact`), its modulus set so that
  one tip face alone sees K_obj (the tissue's local stiffness per tip). Coupling "none" is
  eq. 1: C = I / K_obj.
* A tip with deflection e: e + w = Δ, P = K e until its hard stop engages at the tip travel
  e_s (:func:`tactcad.mechanics.hard_stops.engagement_travel_mm`); then e = e_s, the element
  carries K e_s and the stop the rest of P. Tips whose force would pull (P < 0) lift off.
* A unit reads R = e_m / e_r and K_obj by eq. 3, and corrected for its tips' travels,
  R Δ_r / Δ_m, and, under a wedge on the layer, for each tip's own tissue (thinner tissue
  is stiffer: :func:`corrected_kobj`), the jaw's angle known from the grasper, the tissue's
  profile and thickness assumed. The tissue's coupling between neighbouring tips stays in
  the corrected reading; each layout states the error it leaves
  (:func:`correction_residual`).
* Force mode: the angle at which the tips' forces on the slab sum to the grasp force
  (bisection; the force falls as the jaw opens).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Sequence

import numpy as np

from tactcad.errors import DesignError
from tactcad.in_use.jaw_kinematics import (OPENING_ANGLE_RANGE_DEG, JawGeometry, check_angle_deg,
                                            PIN_TO_TIP_RANGE_MM, indentation_mm)
from tactcad.in_use.kobj_budget import kobj_from_deflections
from tactcad.in_use.tissue_coupling import TISSUE_POISSON_RATIO as TISSUE_COUPLING_POISSON_RATIO
from tactcad.in_use.radius_pairs import (PairedLayout, along_row_layout, insert_frame,
                                         paired_layout, unit_radii)
from tactcad.mechanics.contact import (BASES, Punch, single_punch_unit_compliance,
                                       unit_punch_compliance)
from tactcad.mechanics.hard_stops import engagement_travel_mm

if TYPE_CHECKING:  # annotations only: the design model costs a second to import
    from tactcad.design.array_plan import Plan

#: Tissue profiles between the jaws (see the module docstring).
PROFILES = ("slab", "wedge")
#: The tissue's profile a grasp that reads the units assumes unless told (``tactcad grasp``,
#: a die's grasp): tissue filling the open jaw, so that every unit reads (on a flat slab at
#: the grasper example's default force only the unit nearest the pin touches).
DEFAULT_PROFILE = "wedge"
#: The profile verify's ``max_grasp_force_N`` judges an overload on: a flat slab loads the
#: tips near the pin first and most (their stops engage before the far tips touch), the
#: harder case for those tips (on ti_array_2x3 at 1 N the slab overloads elements the wedge
#: does not).
OVERLOAD_PROFILE = "slab"
#: Tissue couplings: none (eq. 1), a half-space, a layer of the slab's thickness.
COUPLINGS = ("none", "halfspace", "layer")
#: What the correction leaves in a reading, by whether the tips are coupled.
COUPLING_LEFT_IN = ("", "; the tissue's coupling between neighbouring tips stays in it "
                        "(verify's coupled inversion and tactcad budget's tissue-coupling "
                        "source take it out): each layout states what it leaves")
#: Poisson's ratio of soft tissue: the tissue coupling's, one figure for every command.
TISSUE_POISSON_RATIO = TISSUE_COUPLING_POISSON_RATIO
#: What the tissue between the jaws rests on: the opposing jaw, a rigid base holding the layer
#: by one of :data:`tactcad.mechanics.contact.BASES`.
TISSUE_BASES = BASES
#: The base a grasp assumes unless the design's ``[tissue_slab]`` states one: tissue gripped
#: on a jaw face (serrated or profiled to hold it, Heijnsdijk et al. 2004) does not slide on
#: it, so bonded; ``frictionless`` bounds it from the other side (a smooth, wet face), and
#: Steinbrenner's approximation lies between the two.
DEFAULT_TISSUE_BASE = "bonded"
#: Bisection steps of the force mode (the angle to 90° / 2^60).
BISECTION_STEPS = 60
#: Active-set passes of the stops and lift-off before the solve is declared stuck.
ACTIVE_SET_PASSES = 100
#: The grasp's default jaw and tissue (mm, degrees), each an assumption stated where used:
#: the pin behind the first tip along the rows, the slab, the jaw's full opening, the jaw
#: beyond the last tip.
DEFAULT_PIVOT_BEHIND_MM = 5.0
DEFAULT_SLAB_MM = 3.0
DEFAULT_OPENING_DEG = 60.0
DEFAULT_JAW_BEYOND_MM = 2.0


def check_kobj(k_obj_N_per_mm: float) -> None:
    """Refuse a tissue K_obj the grasp cannot read: outside the K_obj a design file's range
    may state (:data:`tactcad.design.requirements_section.MIN_KOBJ_N_PER_MM` ...
    ``MAX_KOBJ_N_PER_MM``). Far below the least the tissue is lost in the elements' K (K +
    K_obj rounds to K): a unit's K_obj read is round-off (on the 10 mm grasper's comb at
    1e-30 N/mm it reads 1e-15 N/mm), and at 1e-200 N/mm the unit's true K_obj, the
    geometric mean of its two tips', underflows to 0.

    Args:
        k_obj_N_per_mm: the tissue's true local stiffness under one tip (N/mm).

    Raises:
        DesignError: not a finite number in the range, as the field ``k_obj_N_per_mm``
            (a command names its ``--kobj``, the API its ``kobj``).
    """
    from tactcad.design.requirements_section import MAX_KOBJ_N_PER_MM, MIN_KOBJ_N_PER_MM

    ok = (isinstance(k_obj_N_per_mm, (int, float)) and not isinstance(k_obj_N_per_mm, bool)
          and math.isfinite(k_obj_N_per_mm)
          and MIN_KOBJ_N_PER_MM <= k_obj_N_per_mm <= MAX_KOBJ_N_PER_MM)
    if not ok:
        raise DesignError("k_obj_N_per_mm", k_obj_N_per_mm,
                          f"{MIN_KOBJ_N_PER_MM:g} ... {MAX_KOBJ_N_PER_MM:g} N/mm",
                          "a softer tissue is lost in the elements' stiffness: its readings "
                          "would be round-off")


def tissue_compliance(punches: list[Punch], k_obj_N_per_mm: float, slab_thickness_mm: float,
                      coupling: str = "layer",
                      poisson_ratio: float = TISSUE_POISSON_RATIO,
                      local_thickness_mm=None,
                      base: str = DEFAULT_TISSUE_BASE) -> np.ndarray:
    """The tissue's compliance under the tips (mm/N), shape (m, m): the one place the grasp
    asks the tissue model (re-point it here for another).

    Args:
        punches: the tips' contact faces in the surface plane (mm).
        k_obj_N_per_mm: the tissue's local stiffness under one tip face alone on the
            ``slab_thickness_mm`` layer (N/mm), > 0: it sets the one modulus of the tissue.
        slab_thickness_mm: the slab on the opposing jaw (mm), > 0 (``layer`` only).
        coupling: ``none`` (I / K_obj), ``halfspace`` or ``layer`` (a layer on the opposing
            jaw, a rigid base, :mod:`tactcad.mechanics.contact`).
        poisson_ratio: ν of the tissue.
        local_thickness_mm: the layer's thickness under each tip (mm, shape (m,); a wedge),
            ``layer`` only; None: ``slab_thickness_mm`` under every tip
            (:func:`local_layer_compliance`).
        base: how the opposing jaw holds the layer, one of :data:`TISSUE_BASES` (``layer``
            only; default :data:`DEFAULT_TISSUE_BASE`).

    Returns:
        C (mm/N), symmetric, one face alone seeing 1/K_obj on the slab's thickness.

    Raises:
        DesignError: K_obj <= 0, an unknown coupling or base.
    """
    if not (math.isfinite(k_obj_N_per_mm) and k_obj_N_per_mm > 0):
        raise DesignError("k_obj_N_per_mm", k_obj_N_per_mm, "> 0 N/mm")
    if coupling not in COUPLINGS:
        raise DesignError("coupling", coupling, " | ".join(COUPLINGS))
    if base not in TISSUE_BASES:
        raise DesignError("tissue_base", base, " | ".join(TISSUE_BASES))
    if coupling == "none":
        return np.eye(len(punches)) / k_obj_N_per_mm
    thickness = slab_thickness_mm if coupling == "layer" else None
    unit = unit_punch_compliance(punches, poisson_ratio, thickness, base)  # converged
    # E such that one face alone sees K_obj: every compliance scales as 1/E
    own = np.mean([single_punch_unit_compliance(p.width_x_mm, p.depth_z_mm, poisson_ratio,
                                                thickness, base) for p in punches])
    if local_thickness_mm is not None and coupling == "layer":
        unit = local_layer_compliance(punches, slab_thickness_mm, local_thickness_mm,
                                      poisson_ratio, unit, base)
    return unit / (k_obj_N_per_mm * own)


def local_layer_compliance(punches: list[Punch], slab_thickness_mm: float, local_thickness_mm,
                           poisson_ratio: float, slab_unit: np.ndarray,
                           base: str = DEFAULT_TISSUE_BASE) -> np.ndarray:
    """The faces' compliance at E = 1 MPa (mm/N, shape (m, m)) on a layer whose thickness
    varies from tip to tip: faces on one thickness (a unit paired at equal radius under a
    wedge) are solved together on a uniform layer of that thickness; between faces on
    different thicknesses the slab's coupling is kept, scaled by each face's own softening,
    C_ij = C_ij(slab) sqrt(s_i s_j) (:func:`local_softening`; an approximation, small
    where such faces are far apart), all on the one ``base``."""
    t = np.round(np.broadcast_to(np.asarray(local_thickness_mm, float), (len(punches),)),
                 LAYER_THICKNESS_DECIMALS)
    s = local_softening(punches, slab_thickness_mm, t, poisson_ratio, base)
    out = slab_unit * np.sqrt(np.outer(s, s))
    for h in np.unique(t):
        group = np.flatnonzero(t == h)
        out[np.ix_(group, group)] = unit_punch_compliance([punches[i] for i in group],
                                                          poisson_ratio, float(h), base)
    return out


#: The layer's thickness under each tip is solved to this many decimals (mm): faces on one
#: thickness to 1e-9 mm are solved together (:func:`local_layer_compliance`), and a tip on
#: less than half of it would sit on no tissue.
LAYER_THICKNESS_DECIMALS = 9
#: The thinnest tissue under a tip the layer takes (mm): :data:`LAYER_THICKNESS_DECIMALS`.
MIN_LOCAL_THICKNESS_MM = 10.0 ** -LAYER_THICKNESS_DECIMALS
#: The thinnest layer, over the tip face's shorter edge, on which the punch solves converge
#: (:func:`tactcad.mechanics.contact.converged_punches`, nu 0.5 on a bonded base): at a
#: tenth every face measured (0.2 x 0.2 to 0.5 x 2 mm) converged to its 0.1 %; at a
#: twentieth the extrapolations still moved 0.3-0.5 %, at 0.03 by 3-270 %, and below it a
#: face's compliance came out negative (the thin incompressible layer's displacement is the
#: small difference of two large ones the cells no longer resolve). That case is the
#: hardest: at a tenth, nu 0.3, 0.45 and 0.5 on a bonded, frictionless or Steinbrenner
#: base all converged to 0.1 % (faces 0.2 x 0.2 and 0.5 x 2 mm); at a twentieth the
#: frictionless base and the compressible bonded layer still did, the rest did not.
MIN_LAYER_OVER_FACE = 0.1


def least_layer_mm(punches: Sequence[Punch]) -> float:
    """The thinnest tissue the contact solves take under any of ``punches`` (mm):
    :data:`MIN_LAYER_OVER_FACE` of the smallest face edge, and at least
    :data:`MIN_LOCAL_THICKNESS_MM`.

    Args:
        punches: the tip faces (:class:`~tactcad.mechanics.contact.Punch`, mm); none: the
            layer's resolution alone.

    Returns:
        The least thickness (mm).
    """
    edges = [min(p.width_x_mm, p.depth_z_mm) for p in punches]
    return max(MIN_LOCAL_THICKNESS_MM, MIN_LAYER_OVER_FACE * min(edges, default=0.0))


def check_layer_thick_enough(jaw: JawGeometry, punches: Sequence[Punch]) -> None:
    """A flat slab of tissue coupled as one layer is at least :func:`least_layer_mm` thick.

    Args:
        jaw: the jaw and its ``slab_thickness_mm`` (mm). punches: the tip faces (mm).

    Raises:
        DesignError: ``jaw.slab_thickness_mm`` thinner, named with the range that works (its
            least rounded up), so that a command names its ``--slab-thickness-mm``.
    """
    least = least_layer_mm(punches)
    if jaw.slab_thickness_mm >= least * (1 - 1e-9):
        return
    least = _rounded_up(least)
    raise DesignError("jaw.slab_thickness_mm", jaw.slab_thickness_mm,
                      f"{least:g} ... 100 mm (at least {MIN_LAYER_OVER_FACE:g} of the smallest "
                      "tip face's edge, where the tissue layer's contact solves converge)",
                      f"a layer {jaw.slab_thickness_mm:g} mm thick under tip faces of "
                      f"{least / MIN_LAYER_OVER_FACE:.3g} mm is thinner than the contact "
                      "model resolves: give a thicker tissue")


def _rounded_up(x: float) -> float:
    """``x`` rounded up to three significant digits."""
    step = 10.0 ** (math.floor(math.log10(x)) - 2)
    return float(f"{math.ceil(x / step * (1 - 1e-12)) * step:.3g}")


def check_wedge_thick_enough(jaw: JawGeometry, radius_mm,
                             punches: Sequence[Punch] = ()) -> None:
    """The wedge of the jaw's slab thickness (at the last tip) leaves at least
    :func:`least_layer_mm` of tissue under the tip nearest the pin (the wedge's
    thickness h r / r_last): on a thinner wedge the contact solves there do not converge
    (or its tissue rounds to nothing).

    Args:
        jaw: the jaw and its ``slab_thickness_mm`` (mm).
        radius_mm: each tip's radius from the pin (mm), shape (m,).
        punches: the tip faces (mm); none: the layer's resolution alone.

    Raises:
        DesignError: ``jaw.slab_thickness_mm`` thinner than that, named with the range
            that works (its least rounded up; at most the open jaw's gap at the last tip,
            :func:`check_wedge_fits`) so that a command names its ``--slab-thickness-mm``.
    """
    r = np.asarray(radius_mm, float)
    first, last = float(r.min()), float(r.max())
    floor = least_layer_mm(punches)
    if jaw.slab_thickness_mm * first / last >= floor * (1 - 1e-9):
        return
    gap = math.floor(last * math.sin(math.radians(jaw.opening_angle_deg)) * 1e3) / 1e3
    hi = min(gap, 100.0)
    if first <= 0:
        raise DesignError("jaw.slab_thickness_mm", jaw.slab_thickness_mm,
                          "none under a wedge (a tip at the pin has no tissue under it)",
                          "the wedge thins to nothing at the pin and a tip sits there: "
                          "a flat slab of tissue, or the pin moved off the tip")
    least = _rounded_up(floor * last / first)  # three digits, up: it works
    raise DesignError("jaw.slab_thickness_mm", jaw.slab_thickness_mm,
                      f"{least:g} ... {hi:g} mm (the wedge leaves at least "
                      f"{floor:.3g} mm of tissue under the tip nearest the "
                      f"pin, {first:.4g} mm from it against {last:.4g} mm at the last tip, "
                      "where the contact solves converge; at most the open jaw's gap there)",
                      f"a wedge {jaw.slab_thickness_mm:g} mm thick at the last tip leaves "
                      f"{jaw.slab_thickness_mm * first / last:.3g} mm under the tip nearest "
                      "the pin, thinner than the contact model resolves: give a thicker "
                      "tissue")


def local_softening(punches: list[Punch], slab_thickness_mm: float, local_thickness_mm,
                    poisson_ratio: float = TISSUE_POISSON_RATIO,
                    base: str = DEFAULT_TISSUE_BASE) -> np.ndarray:
    """Each face's compliance alone on its own layer thickness over its compliance on the
    ``slab_thickness_mm`` layer (one modulus: below 1 where the tissue is thinner), shape
    (m,), on the layer's ``base``. Each is a converged single-punch solve
    (:mod:`tactcad.mechanics.contact`).

    Raises:
        DesignError: a thickness <= 0.
    """
    t = np.broadcast_to(np.asarray(local_thickness_mm, float), (len(punches),))
    if not np.all(np.isfinite(t) & (t > 0)):
        raise DesignError("local_thickness_mm", t.tolist(), "> 0 mm at every tip")

    def alone(p: Punch, h: float) -> float:
        return single_punch_unit_compliance(p.width_x_mm, p.depth_z_mm, poisson_ratio,
                                            float(round(h, LAYER_THICKNESS_DECIMALS)), base)

    return np.array([alone(p, h) / alone(p, slab_thickness_mm) for p, h in zip(punches, t)])


@dataclass(frozen=True)
class TipSolution:
    """The tips pressed by given travels (arrays over the tips)."""

    travel_mm: np.ndarray
    deflection_mm: np.ndarray
    tip_force_N: np.ndarray
    element_force_N: np.ndarray
    stop_force_N: np.ndarray
    engaged: np.ndarray
    in_contact: np.ndarray


def solve_tips(travel_mm, stiffness_N_per_mm, engage_mm, compliance) -> TipSolution:
    """Tip deflections and forces for imposed travels, with hard stops and lift-off
    (active set: free tips P/K + (C P) = Δ, engaged tips (C P) = Δ − e_s, lifted tips P = 0).

    Args:
        travel_mm: Δ per tip (mm), shape (m,).
        stiffness_N_per_mm: K per tip, shape (m,).
        engage_mm: stop engagement travel per tip (mm; inf without a stop), shape (m,).
        compliance: the tissue's C (mm/N), shape (m, m).

    Raises:
        DesignError: the active set does not settle (should not happen for C positive definite).
    """
    d = np.asarray(travel_mm, float)
    k = np.asarray(stiffness_N_per_mm, float)
    e_s = np.asarray(engage_mm, float)
    c = np.asarray(compliance, float)
    contact = d > 0
    engaged = np.zeros(len(d), bool)
    force = np.zeros(len(d))
    for _ in range(ACTIVE_SET_PASSES):
        idx = np.flatnonzero(contact)
        force = np.zeros(len(d))
        if idx.size:
            a = c[np.ix_(idx, idx)] + np.diag(np.where(engaged[idx], 0.0, 1.0 / k[idx]))
            rhs = d[idx] - np.where(engaged[idx], e_s[idx], 0.0)
            force[idx] = np.linalg.solve(a, rhs)
        deflection = np.where(engaged, e_s, force / k) * contact
        lifted = contact & (force < -1e-12)
        new_engaged = contact & ~lifted & (engaged & (force >= k * e_s) | (deflection > e_s))
        if not lifted.any() and np.array_equal(new_engaged, engaged):
            element = k * deflection
            return TipSolution(d, deflection, force, element, force - element, engaged, contact)
        contact &= ~lifted
        engaged = new_engaged & contact
    raise UnsettledContact("grasp", "the stops and lift-off did not settle",
                           f"a settled contact within {ACTIVE_SET_PASSES} passes")


class UnsettledContact(DesignError):
    """The tips' contact (their stops and lift-off) did not settle in
    :data:`ACTIVE_SET_PASSES` passes of :func:`solve_tips`: on a very thin tissue layer.
    Raised by :func:`press` as the field ``jaw.slab_thickness_mm`` with the thickness the
    solve was on (mm; given or the default); a command names its ``--slab-thickness-mm``
    with that value, given or default, and the thicker range
    (:func:`tactcad.commands.options.grasp_option_error`)."""


@dataclass(frozen=True)
class Tips:
    """The tips of one layout: label, radius, face, stiffness, stop and overload limit
    (N; inf where none is given) per tip, and each tip's own rated force (N; None: every
    tip is rated at the layout's one rated force)."""

    labels: tuple[int, ...]
    radius_mm: np.ndarray
    punches: list[Punch]
    stiffness_N_per_mm: np.ndarray
    engage_mm: np.ndarray
    overload_N: np.ndarray
    rated_N: np.ndarray | None = None


def tips_as_laid_out(plan: Plan, jaw: JawGeometry, stiffness: dict[int, float],
                     overload_N: dict[int, float] | None = None) -> Tips:
    """The design's own tips: each element at its slot, with its stiffness, stop and
    overload limit (``overload_N``: element -> N; none given: no limit)."""
    frame = insert_frame(plan)
    stops = stop_travels(plan)
    numbers = tuple(s.number for s in plan.slots)
    radii = unit_radii(jaw, frame, [(n, n) for n in numbers])
    return Tips(numbers, np.array([r.r_reference_mm for r in radii]), _punches(plan),
                np.array([stiffness[n] for n in numbers]),
                np.array([stops.get(n, math.inf) for n in numbers]),
                np.array([(overload_N or {}).get(n, math.inf) for n in numbers]))


def stop_travels(plan: Plan) -> dict[int, float]:
    """Element number -> the tip travel (mm) at which its hard stop engages (none: absent)."""
    return {s.element: engagement_travel_mm(s, plan.element(s.element).geometry.arm_length_mm)
            for s in plan.hard_stops}


def _punches(plan: Plan) -> list[Punch]:
    out = []
    for slot in plan.slots:
        x, _, z = slot.tip_centre_world_mm
        out.append(Punch(x, z, *slot.contact_face_world_mm))
    return out


def tips_on(plan: Plan, jaw: JawGeometry, stiffness: dict[int, float], layout: PairedLayout,
            overload_N: dict[int, float] | None = None) -> tuple[Tips, list[tuple]]:
    """The plan's tip sites with the units laid as ``layout`` lays them
    (:func:`tactcad.in_use.radius_pairs.paired_layout` or
    :func:`~tactcad.in_use.radius_pairs.along_row_layout`): a site takes the stiffness, stop
    and overload limit of the element laid on it; sites no unit takes keep their own element.

    Returns:
        (tips, the laid units as (reference site, measuring site, design unit)).
    """
    base = tips_as_laid_out(plan, jaw, stiffness, overload_N)
    k, e_s = base.stiffness_N_per_mm.copy(), base.engage_mm.copy()
    limit = base.overload_N.copy()
    index = {n: i for i, n in enumerate(base.labels)}
    sites = []
    for s in layout.sites:
        for element, site in zip(s.unit, (s.reference_site, s.measuring_site)):
            k[index[site]] = base.stiffness_N_per_mm[index[element]]
            e_s[index[site]] = base.engage_mm[index[element]]
            limit[index[site]] = base.overload_N[index[element]]
        sites.append((s.reference_site, s.measuring_site, s.unit))
    return Tips(base.labels, base.radius_mm, base.punches, k, e_s, limit), sites


def layout_json(layout: PairedLayout) -> dict:
    """``layout``'s JSON with ``as_laid_out``: whether it is the design's own layout."""
    return {**layout.as_json(), "as_laid_out": is_own_layout(layout)}


def is_own_layout(layout: PairedLayout) -> bool:
    """True when ``layout`` lays every unit on its own elements' sites (the design is laid
    out so already)."""
    return not layout.unplaced and all(s.unit == (s.reference_site, s.measuring_site)
                                       for s in layout.sites)


@dataclass(frozen=True)
class LayoutGrasp:
    """One layout's grasp: the angle, each tip's state, each unit's reading, and the tissue's
    ``coupling`` (one of :data:`COUPLINGS`) it was closed on."""

    name: str
    angle_deg: float
    total_force_N: float
    tips: list[dict]
    units: list[dict]
    coupling: str = "layer"

    @property
    def correction_residual(self) -> dict | None:
        """What the correction leaves in the units' readings (:func:`correction_residual`)."""
        return correction_residual(self.units, self.coupling)

    def as_json(self) -> dict:
        return {"layout": self.name, "angle_deg": self.angle_deg,
                "total_force_N": self.total_force_N, "tips": self.tips, "units": self.units,
                "correction_residual": self.correction_residual}


#: What the tissue rests on: by coupling where it has no base, else by the layer's base.
BASE_WORDS = {"none": "no base: each tip on its own spring K_obj (eq. 1)",
              "halfspace": "no base: an elastic half-space",
              "bonded": "bonded to the opposing jaw (no slip at the base: tissue gripped on "
                        "the jaw's face), the layer's exact solution (Burmister 1945; "
                        "Hayes et al. 1972)",
              "frictionless": "on a frictionless opposing jaw (the base slides freely: a "
                              "smooth, wet face), the layer's exact solution (Burmister 1945)",
              "steinbrenner": "a rigid base under the layer, its shear condition not modelled "
                              "(Steinbrenner's approximation: between a frictionless and a "
                              "bonded base; a bonded, nearly incompressible thin layer is "
                              "stiffer)"}


def base_words(coupling: str, base: str) -> str:
    """What the tissue rests on, in words (:data:`BASE_WORDS`).

    Args:
        coupling: one of :data:`COUPLINGS`.
        base: one of :data:`TISSUE_BASES` (read for the ``layer`` coupling only).

    Returns:
        The base's words where the tissue is coupled as a layer, else the coupling's.
    """
    return BASE_WORDS[base if coupling == "layer" else coupling]


def wedge_words(jaw: JawGeometry, radius_mm) -> str:
    """The wedge in words: its thickness law, its range under the tips and the angle at
    which the jaw meets every tip at once."""
    r = np.asarray(radius_mm, float)
    t = tissue_thickness_mm(r, jaw.slab_thickness_mm, "wedge")
    touch = math.degrees(math.asin(min(1.0, jaw.slab_thickness_mm / float(r.max()))))
    return (f"thickness h r / r_last, {t.min():.3g} ... {t.max():.3g} mm under the tips, "
            f"meeting every tip at once at {touch:.3g} degrees (the jaw opens to "
            f"{jaw.opening_angle_deg:g})")


def check_wedge_fits(jaw: JawGeometry, last_radius_mm: float) -> None:
    """A wedge of the jaw's slab thickness at the last tip fits the open jaw: the jaw's face
    there stands r_last sin(opening) above the opposing jaw.

    Raises:
        DesignError: ``jaw.slab_thickness_mm`` thicker than that gap (the largest named).
    """
    gap = last_radius_mm * math.sin(math.radians(jaw.opening_angle_deg))
    if jaw.slab_thickness_mm > gap:
        thinner = math.floor(gap * 1e3) / 1e3  # three decimals, down: it fits
        wider = math.ceil(math.degrees(math.asin(min(1.0, jaw.slab_thickness_mm
                                                      / last_radius_mm))) * 100) / 100
        alternatives = [{"option": f"--slab-thickness-mm {thinner:g}",
                         "words": "a thinner tissue that fits the open jaw"}]
        if jaw.slab_thickness_mm < last_radius_mm and wider <= OPENING_ANGLE_RANGE_DEG[1]:
            alternatives.append({"option": f"--opening-deg {wider:g}",
                                 "words": "the jaw opened wide enough for this tissue"})
        raise DesignError("jaw.slab_thickness_mm", jaw.slab_thickness_mm,
                          f"at most {thinner:g} mm (the open jaw's gap at the last tip, "
                          f"{last_radius_mm:.4g} mm from the pin at {jaw.opening_angle_deg:g} "
                          "degrees)", "a wedge of tissue thicker than the open jaw does not "
                          "fit between the jaws: open the jaw wider or give a thinner tissue",
                          alternatives=alternatives)


def tissue_thickness_mm(radius_mm: np.ndarray, thickness_mm: float, profile: str) -> np.ndarray:
    """The tissue's thickness under each tip (mm): ``slab`` h everywhere; ``wedge`` h r / r_last.

    Raises:
        DesignError: an unknown profile.
    """
    r = np.asarray(radius_mm, float)
    if profile == "slab":
        return np.full(r.shape, thickness_mm)
    if profile == "wedge":
        return thickness_mm * r / r.max()
    raise DesignError("profile", profile, " | ".join(PROFILES))


def press(tips: Tips, compliance: np.ndarray, slab_mm: float, angle_deg: float,
          profile: str = DEFAULT_PROFILE) -> TipSolution:
    """The tips' solution with the jaw closed to ``angle_deg`` on the tissue's profile.

    Args:
        tips: the layout's tips. compliance: the tissue's C (mm/N), shape (m, m).
        slab_mm: the tissue's thickness (mm; a wedge's at the last tip).
        angle_deg: the jaw's closing angle (degrees). profile: ``slab`` or ``wedge``.

    Returns:
        :class:`TipSolution`.

    Raises:
        UnsettledContact: the contact did not settle on this thickness, as the field
            ``jaw.slab_thickness_mm`` with ``slab_mm``.
    """
    thickness = tissue_thickness_mm(tips.radius_mm, slab_mm, profile)
    travel = np.array([indentation_mm(t, r, angle_deg)
                       for t, r in zip(thickness, tips.radius_mm)])
    try:
        return solve_tips(travel, tips.stiffness_N_per_mm, tips.engage_mm, compliance)
    except UnsettledContact as exc:  # said as the thickness it happened on, not "grasp"
        raise UnsettledContact("jaw.slab_thickness_mm", float(slab_mm),
                               f"a tissue thicker than {float(slab_mm):g} mm, on which the "
                               "contact settles", f"{exc.allowed} was not reached: the "
                               f"stops and lift-off did not settle on the {float(slab_mm):g} "
                               f"mm {profile}") from None


def angle_for_force(tips: Tips, compliance: np.ndarray, slab_mm: float, opening_deg: float,
                    force_N: float, profile: str = DEFAULT_PROFILE) -> float:
    """The closing angle (degrees) at which the tips' forces on the slab sum to ``force_N``.

    Raises:
        DesignError: the force is out of reach between the jaw closed and fully open.
    """
    def total(angle: float) -> float:
        return float(press(tips, compliance, slab_mm, angle, profile).tip_force_N.sum())

    closed, opened = total(0.0), total(opening_deg)
    if not opened <= force_N <= closed:
        raise DesignError("force_N", force_N,
                          f"{opened:.4g} ... {closed:.4g} N (jaw open {opening_deg:g} degrees "
                          f"... closed flat on the {slab_mm:g} mm {profile})")
    lo, hi = 0.0, opening_deg  # force(lo) >= force_N >= force(hi)
    for _ in range(BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if total(mid) >= force_N else (lo, mid)
    return 0.5 * (lo + hi)


def corrected_kobj(r_read: float, travel_r_mm: float, travel_m_mm: float, k_r: float,
                   k_m: float, softening_r: float = 1.0, softening_m: float = 1.0) -> float:
    """K_obj a unit reads once its tips' travels and the tissue under each are taken out.

    Eq. 1 per tip, each on its own tissue K_i = K_0 / s_i (one modulus; s_i the tip's
    compliance on its own thickness over that on the slab's, :func:`local_softening`),
    gives R = (Δ_m / Δ_r) (s_r K_r + K_0) / (s_m K_m + K_0): eq. 2 with the elements'
    K scaled by their tissue. Eq. 3 on those scaled K and R Δ_r / Δ_m gives K_0, and the
    unit's K_obj is its two tips' geometric mean, K_0 / sqrt(s_r s_m). The travel ratio
    alone (s_r = s_m) is the paper's eq. 3 on R Δ_r / Δ_m; a tip on thinner tissue reads
    stiffer tissue, which eq. 3 on one K_obj puts into R (paper eq. 1-3,
    :mod:`tactcad.mechanics.lumped_model`).

    Args:
        r_read: R = e_m / e_r as read.
        travel_r_mm, travel_m_mm: the reference's and the measuring tip's travel (mm), > 0.
        k_r, k_m: the elements' stiffness (N/mm).
        softening_r, softening_m: each tip's tissue softening s (dimensionless, > 0; 1 on
            the slab's thickness).

    Returns:
        K_obj (N/mm); inf where the corrected R is 1 (no answer).
    """
    ratio = r_read * travel_r_mm / travel_m_mm
    if ratio == 1:
        return math.inf
    k0 = float(kobj_from_deflections(ratio, 1.0, softening_m * k_m, softening_r * k_r))
    return k0 / math.sqrt(softening_r * softening_m)


def ratio_of_kobj(k_r: float, k_m: float, k_obj: float) -> float:
    """Eq. 2, R = (K_r + K_obj) / (K_m + K_obj), for any K_obj eq. 3 may give back (N/mm):
    1 at an infinite K_obj, inf at K_obj = -K_m."""
    if math.isinf(k_obj):
        return 1.0
    return (k_r + k_obj) / (k_m + k_obj) if k_obj != -k_m else math.inf


def unit_reading(ref: int, meas: int, sol: TipSolution, tips: Tips, k_obj,
                 unit: tuple[int, int] | None = None, thickness_mm=None,
                 softening=None) -> dict:
    """One unit's travels, deflections, R and K_obj read (eq. 3), raw and corrected for its
    tips' travels and the tissue under each (:func:`corrected_kobj`), against the true
    K_obj; ``valid`` False with why when a tip lifted off or sits on its stop. ``unit``: the
    design's unit laid on these sites (default the sites).

    Args:
        k_obj: the true K_obj (N/mm): one for every tip, or per tip (shape (m,): the tissue
            under a wedge); a unit is judged against the geometric mean of its two tips'.
        thickness_mm: the tissue's thickness under each tip (mm, shape (m,)), reported.
        softening: the tissue's softening under each tip the correction assumes (shape
            (m,), :func:`local_softening` on the assumed profile and thickness); None: one
            tissue under every tip.

    Returns:
        The unit's record; ``R_corrected`` is the R its tips would read at one travel on
        one tissue of the corrected K_obj (eq. 2).
    """
    i, j = tips.labels.index(ref), tips.labels.index(meas)
    k_tips = np.broadcast_to(np.asarray(k_obj, float), (len(tips.labels),))
    k_obj = float(math.sqrt(k_tips[i] * k_tips[j]))
    s = np.ones(len(tips.labels)) if softening is None else np.asarray(softening, float)
    k_r, k_m = float(tips.stiffness_N_per_mm[i]), float(tips.stiffness_N_per_mm[j])
    e_r, e_m = float(sol.deflection_mm[i]), float(sol.deflection_mm[j])
    d_r, d_m = float(sol.travel_mm[i]), float(sol.travel_mm[j])
    why = [f"element at site {n} {w}" for n, w, bad in
           ((ref, "not in contact", not sol.in_contact[i]),
            (meas, "not in contact", not sol.in_contact[j]),
            (ref, "on its stop", sol.engaged[i]), (meas, "on its stop", sol.engaged[j])) if bad]
    name = unit or (ref, meas)
    out = {"unit": f"{name[0]}/{name[1]}", "reference": ref, "measuring": meas, "r_reference_mm": float(tips.radius_mm[i]),
           "r_measuring_mm": float(tips.radius_mm[j]),
           "radius_ratio": float(tips.radius_mm[j] / tips.radius_mm[i]),
           "travel_reference_mm": d_r, "travel_measuring_mm": d_m,
           "deflection_reference_mm": e_r, "deflection_measuring_mm": e_m,
           "K_r_N_per_mm": k_r, "K_m_N_per_mm": k_m,
           "R_true": (k_r + k_obj) / (k_m + k_obj), "K_obj_true_N_per_mm": k_obj,
           "valid": not why, "why": "; ".join(why)}
    if thickness_mm is not None:
        out["tissue_thickness_reference_mm"] = float(thickness_mm[i])
        out["tissue_thickness_measuring_mm"] = float(thickness_mm[j])
    if e_r <= 0 or d_m <= 0:
        return {**out, "R_read": None, "K_obj_read_N_per_mm": None, "error_rel": None,
                "R_corrected": None, "K_obj_corrected_N_per_mm": None,
                "error_corrected_rel": None, "correction_worse": False}
    r_read = e_m / e_r
    k_read = float(kobj_from_deflections(r_read, 1.0, k_m, k_r)) if r_read != 1 else math.inf
    k_corr = corrected_kobj(r_read, d_r, d_m, k_r, k_m, float(s[i]), float(s[j]))
    r_corr = ratio_of_kobj(k_r, k_m, k_corr)
    error, error_corr = k_read / k_obj - 1, k_corr / k_obj - 1
    return {**out, "R_read": r_read, "K_obj_read_N_per_mm": k_read,
            "error_rel": error, "R_corrected": r_corr,
            "K_obj_corrected_N_per_mm": k_corr, "error_corrected_rel": error_corr,
            # the correction leaves more error than it took out: said, never shown bare
            "correction_worse": bool(abs(error_corr) > abs(error) + CORRECTION_RESIDUAL_TOL)}


#: A corrected reading's error below this (relative) is the solver's round-off, not a
#: residual the correction leaves.
CORRECTION_RESIDUAL_TOL = 1e-6


def correction_residual(units: list[dict], coupling: str) -> dict | None:
    """What the correction leaves in a layout's readings: the corrected K_obj's error over
    the units with a reading (those whose tips are in contact and off their stops).

    Args:
        units: the layout's unit records (:func:`unit_reading`).
        coupling: the tissue's coupling (one of :data:`COUPLINGS`): what is left is its
            coupling between neighbouring tips, which the correction does not model.

    Returns:
        ``{"largest_rel", "unit", "range_rel", "worse_than_read", "cause"}`` (the error of
        largest size, its unit, the least and largest error, the units the correction leaves
        worse than read), or None where every corrected reading is within
        :data:`CORRECTION_RESIDUAL_TOL`.
    """
    read = [u for u in units if u["valid"] and u["error_corrected_rel"] is not None
            and math.isfinite(u["error_corrected_rel"])]
    if not read:
        return None
    worst = max(read, key=lambda u: abs(u["error_corrected_rel"]))
    if abs(worst["error_corrected_rel"]) <= CORRECTION_RESIDUAL_TOL:
        return None
    errors = [u["error_corrected_rel"] for u in read]
    cause = ("the tissue's coupling between neighbouring tips, which the correction for the "
             "travels and the tissue under each tip does not model (verify's coupled "
             "inversion and tactcad budget's tissue-coupling source take it out)"
             if coupling != "none" else "the tips' contact (stops, lift-off)")
    return {"largest_rel": float(worst["error_corrected_rel"]), "unit": worst["unit"],
            "range_rel": [float(min(errors)), float(max(errors))],
            "worse_than_read": [u["unit"] for u in read if u["correction_worse"]],
            "cause": cause}


#: The tissue's compression under a tip past which the linear model no longer describes it
#: (assumption: soft tissue stiffens beyond about 20 % strain).
LINEAR_TISSUE_STRAIN = 0.2


def tip_records(tips: Tips, sol: TipSolution, rated_force_N: float,
                thickness_mm=None) -> list[dict]:
    """Each tip's travel, deflection, forces (element, stop, on the slab), its verdicts on
    its rating (a reading past full scale: the tip's own ``tips.rated_N`` where given, else
    ``rated_force_N``) and on the overload limit (damage; None where no limit is given),
    and the tissue's compression under it (travel less deflection over the tissue's
    thickness there, ``thickness_mm``; None without it) with whether it passes
    :data:`LINEAR_TISSUE_STRAIN`."""
    out = []
    for i, n in enumerate(tips.labels):
        f = float(sol.element_force_N[i])
        limit = float(tips.overload_N[i])
        rated = rated_force_N if tips.rated_N is None else float(tips.rated_N[i])
        out.append({"site": n, "radius_mm": float(tips.radius_mm[i]),
                    "K_N_per_mm": float(tips.stiffness_N_per_mm[i]),
                    "travel_mm": float(sol.travel_mm[i]),
                    "deflection_mm": float(sol.deflection_mm[i]),
                    "tip_force_N": float(sol.tip_force_N[i]), "element_force_N": f,
                    "stop_force_N": float(sol.stop_force_N[i]),
                    "stop_engage_mm": float(tips.engage_mm[i]) if math.isfinite(tips.engage_mm[i])
                    else None,
                    "on_stop": bool(sol.engaged[i]), "in_contact": bool(sol.in_contact[i]),
                    "rated_force_N": rated, "over_rating": f > rated * (1 + 1e-9),
                    "overload_limit_N": limit if math.isfinite(limit) else None,
                    "over_overload_limit": f > limit * (1 + 1e-9)})
        if thickness_mm is not None:
            strain = float((sol.travel_mm[i] - sol.deflection_mm[i]) / thickness_mm[i])
            out[-1].update(tissue_strain=strain, past_linear_tissue=strain > LINEAR_TISSUE_STRAIN)
    return out


@dataclass(frozen=True)
class GraspResult:
    """The grasp experiment: inputs, the as-laid-out, the paired and, where the design is laid
    out paired already, the along-the-rows layouts side by side."""

    design: str
    jaw: JawGeometry
    k_obj_N_per_mm: float
    coupling: str
    profile: str
    rated_force_N: float
    as_laid_out: LayoutGrasp
    paired: LayoutGrasp
    layout: dict
    notes: dict = field(default_factory=dict)
    along_rows: LayoutGrasp | None = None
    along_rows_layout: dict | None = None
    tissue_base: str = DEFAULT_TISSUE_BASE

    def as_json(self) -> dict:
        j = self.jaw
        return {"design": self.design,
                "jaw": {"pivot_u_mm": j.pivot_u_mm, "pivot_v_mm": j.pivot_v_mm,
                        "pin_to_tip_mm": j.pin_to_tip_mm,
                        "opening_angle_deg": j.opening_angle_deg,
                        "slab_thickness_mm": j.slab_thickness_mm,
                        "axis_angle_deg": j.axis_angle_deg},
                "K_obj_N_per_mm": self.k_obj_N_per_mm, "coupling": self.coupling,
                "tissue_base": self.tissue_base if self.coupling == "layer" else None,
                "profile": self.profile, "rated_force_N": self.rated_force_N, "as_laid_out": self.as_laid_out.as_json(),
                "paired": self.paired.as_json(), "paired_layout": self.layout,
                "along_rows": self.along_rows.as_json() if self.along_rows else None,
                "along_rows_layout": self.along_rows_layout, "notes": self.notes}


def grasp_layout(name: str, tips: Tips, units: list[tuple[int, int]], jaw: JawGeometry,
                 k_obj: float, coupling: str, rated_force_N: float,
                 angle_deg: float | None, force_N: float | None,
                 profile: str = DEFAULT_PROFILE,
                 base: str = DEFAULT_TISSUE_BASE) -> LayoutGrasp:
    """One layout closed at ``angle_deg`` or to the grasp force ``force_N`` (one of them),
    the tissue a layer on ``base`` (:data:`TISSUE_BASES`) where it is coupled as one."""
    thickness = tissue_thickness_mm(tips.radius_mm, jaw.slab_thickness_mm, profile)
    if profile == "wedge":
        check_wedge_fits(jaw, float(np.max(tips.radius_mm)))
    local = thickness if profile != "slab" and coupling == "layer" else None
    if local is not None:  # the layer under each tip: thick enough for its contact solves
        check_wedge_thick_enough(jaw, tips.radius_mm, tips.punches)
    elif coupling == "layer":
        check_layer_thick_enough(jaw, tips.punches)
    c = tissue_compliance(tips.punches, k_obj, jaw.slab_thickness_mm, coupling,
                          local_thickness_mm=local, base=base)
    # one modulus along the jaw: where the tissue is thinner, its true K_obj is higher; the
    # correction assumes the same profile and thickness (a lab's assumption, stated)
    softening = (np.ones(len(tips.labels)) if local is None else
                 local_softening(tips.punches, jaw.slab_thickness_mm, local, base=base))
    k_local = k_obj / softening
    if angle_deg is None:
        angle_deg = angle_for_force(tips, c, jaw.slab_thickness_mm, jaw.opening_angle_deg,
                                    float(force_N), profile)
    check_angle_deg(jaw, angle_deg)
    sol = press(tips, c, jaw.slab_thickness_mm, angle_deg, profile)
    records = tip_records(tips, sol, rated_force_N, thickness)
    return LayoutGrasp(name, float(angle_deg), float(sol.tip_force_N.sum()), records,
                       with_overload([unit_reading(u[0], u[1], sol, tips, k_local,
                                                   u[2] if len(u) > 2 else u[:2],
                                                   thickness, softening)
                                      for u in units], records), coupling)


#: A unit's figures an overloaded element leaves without meaning (the element yields or its
#: gauge passes its largest strain): never shown as a reading.
OVERLOADED_READING_KEYS = ("R_read", "K_obj_read_N_per_mm", "error_rel", "R_corrected",
                           "K_obj_corrected_N_per_mm", "error_corrected_rel")


def overloaded_sites(tips: list[dict]) -> list[int]:
    """The sites whose element carries more than its overload limit (:func:`tip_records`'
    ``over_overload_limit``)."""
    return [t["site"] for t in tips if t.get("over_overload_limit")]


def with_overload(units: list[dict], tips: list[dict]) -> list[dict]:
    """``units`` with ``overloaded``: True for a unit with an element past its overload
    limit, which then does not read (``valid`` False, ``why`` naming the site) and whose R
    and K_obj read and corrected are None (:data:`OVERLOADED_READING_KEYS`).

    Args:
        units: one layout's unit records (:func:`unit_reading`).
        tips: the same layout's tip records (:func:`tip_records`).

    Returns:
        New unit records; the others unchanged but for ``overloaded`` False.
    """
    over = set(overloaded_sites(tips))
    out = []
    for u in units:
        sites = [n for n in (u["reference"], u["measuring"]) if n in over]
        if not sites:
            out.append({**u, "overloaded": False})
            continue
        over_words = (f"element at site {sites[0]} over its overload limit" if len(sites) == 1
                      else f"elements at sites {', '.join(map(str, sites))} over their "
                           "overload limits")
        why = "; ".join(filter(None, [u["why"], over_words]))
        out.append({**u, **dict.fromkeys(OVERLOADED_READING_KEYS), "valid": False, "why": why,
                    "correction_worse": False, "overloaded": True})
    return out


def overload_warning(layout: LayoutGrasp) -> str | None:
    """The warning a grasp gives where it puts an element past its overload limit.

    Args:
        layout: one layout's grasp (:func:`grasp_layout`, units through :func:`with_overload`).

    Returns:
        One line naming the layout, its grasp force (N), the sites over their limit with the
        largest force against its limit (N) and the units that then read nothing; None where
        no element is past its limit.
    """
    over = [t for t in layout.tips if t.get("over_overload_limit")]
    if not over:
        return None
    worst = max(over, key=lambda t: t["element_force_N"] / t["overload_limit_N"])
    units = [u["unit"] for u in layout.units if u.get("overloaded")]
    return (f"warning: {layout.name}, the grasp force {layout.total_force_N:.4g} N puts the "
            f"elements at sites {', '.join(str(t['site']) for t in over)} past their overload "
            f"limit (site {worst['site']}: {worst['element_force_N']:.4g} N against "
            f"{worst['overload_limit_N']:.4g} N): the element yields or its gauge passes its "
            f"largest strain; units {', '.join(units) or 'none'} read nothing (overloaded)")


def correction_words(coupling: str, profile: str) -> str:
    """How the grasp corrects a unit's reading, in words (:func:`corrected_kobj`).

    Args:
        coupling: one of :data:`COUPLINGS`; profile: one of :data:`PROFILES`.

    Returns:
        The correction and the assumptions it rests on; what it leaves where the tips are
        coupled (:data:`COUPLING_LEFT_IN`).
    """
    tissue = (" and each tip's own tissue (thinner tissue under the wedge is stiffer: eq. 3 "
              "with K_r and K_m scaled by their tips' tissue compliance, K_obj the two tips' "
              "geometric mean)" if coupling == "layer" and profile == "wedge" else "")
    return (f"K_obj corrected = eq. 3 on R read x travel_r / travel_m{tissue} (the jaw's "
            f"angle known, the tissue's {profile} and thickness assumed)"
            + COUPLING_LEFT_IN[coupling != "none"])


def grasp(plan: Plan, jaw: JawGeometry, stiffness: dict[int, float], units: list[tuple[int, int]],
          k_obj_N_per_mm: float, rated_force_N: float, angle_deg: float | None = None,
          force_N: float | None = None, coupling: str = "layer",
          profile: str = DEFAULT_PROFILE, overload_N: dict[int, float] | None = None,
          tissue_base: str = DEFAULT_TISSUE_BASE) -> GraspResult:
    """The jaw closed on the slab: the design's layout, the equal-radius one and the units laid
    along the rows, side by side.

    Args:
        plan: the design.
        jaw: the jaw and the slab.
        stiffness: element number -> K (N/mm), e.g.
            :func:`tactcad.mechanics.evaluation.ladder_stiffness_by_element`.
        units: the design's (reference, measuring) element numbers
            (:func:`tactcad.mechanics.readout_chain.row_units`).
        k_obj_N_per_mm: the tissue's true local stiffness under one tip (N/mm),
            :func:`check_kobj`'s range (1e-06 ... 10000).
        rated_force_N: each element's rated full-scale force (N), > 0.
        angle_deg: the closing angle (degrees), 0 ... the jaw's opening; or
        force_N: the grasp force (N) the tips put on the slab, > 0 (each layout finds its angle).
        coupling: ``layer`` (default), ``halfspace`` or ``none``.
        profile: the tissue between the jaws, ``wedge`` or ``slab`` (default
            :data:`DEFAULT_PROFILE`).
        overload_N: element number -> its overload limit (N; e.g.
            :func:`tactcad.studies.verification.element_overload_limits_N`), judged per tip
            beside the rating; None: the rating alone.
        tissue_base: how the opposing jaw holds the tissue layer, one of
            :data:`TISSUE_BASES` (default :data:`DEFAULT_TISSUE_BASE`; ``layer`` only).

    Returns:
        :class:`GraspResult`; its ``along_rows`` (the units laid along the rows, the side the
        equal-radius rule is measured against) only where the design's own layout is the
        paired one and the plan has two tips along a row.

    Raises:
        DesignError: both or neither of angle and force, or a value out of range.
    """
    if (angle_deg is None) == (force_N is None):
        raise DesignError("angle_deg / force_N", (angle_deg, force_N), "exactly one of them")
    check_kobj(k_obj_N_per_mm)
    if force_N is not None and not (math.isfinite(force_N) and force_N > 0):
        raise DesignError("force_N", force_N, "> 0 N")
    if not (math.isfinite(rated_force_N) and rated_force_N > 0):
        raise DesignError("rated_force_N", rated_force_N, "> 0 N")
    if angle_deg is not None:  # refused before any contact is solved
        check_angle_deg(jaw, angle_deg)
    if coupling not in COUPLINGS:
        raise DesignError("coupling", coupling, " | ".join(COUPLINGS))
    if tissue_base not in TISSUE_BASES:
        raise DesignError("tissue_base", tissue_base, " | ".join(TISSUE_BASES))
    laid = tips_as_laid_out(plan, jaw, stiffness, overload_N)
    pairing = paired_layout(plan, units)
    paired, sites = tips_on(plan, jaw, stiffness, pairing, overload_N)
    along = along_row_layout(plan, units)
    if profile not in PROFILES:
        raise DesignError("profile", profile, " | ".join(PROFILES))
    args = (jaw, k_obj_N_per_mm, coupling, rated_force_N, angle_deg, force_N, profile,
            tissue_base)
    notes = {"profile": f"{profile}: " + ("uniform thickness h" if profile == "slab" else
                                          wedge_words(jaw, laid.radius_mm)),
             "tissue": "none coupling: each tip on its own spring K_obj (eq. 1), no tissue "
                       "between the tips" if coupling == "none" else
                       f"{coupling} coupling, ν {TISSUE_POISSON_RATIO:g}, one modulus set so "
                       f"one tip face alone on the {jaw.slab_thickness_mm:g} mm layer sees "
                       "K_obj" + ("; under the wedge each tip's true K_obj is its face alone "
                                  "on its own thickness, and each unit is judged against "
                                  "its tips' (the geometric mean)"
                                  if profile == "wedge" and coupling == "layer" else ""),
             "base": base_words(coupling, tissue_base),
             "correction": correction_words(coupling, profile),
             "paired_units": "each paired unit is the design unit named, laid on the two "
                             "sites across the jaw"}
    along_rows = None
    if along.sites and is_own_layout(pairing):  # else the design's own is the unpaired side
        tips, row_pairs = tips_on(plan, jaw, stiffness, along, overload_N)
        along_rows = grasp_layout("along the rows", tips, row_pairs, *args)
        notes["along_rows_units"] = ("each unit laid along the rows is the design unit named, "
                                     "on two sites side by side along a row")
    return GraspResult(plan.name, jaw, float(k_obj_N_per_mm), coupling, profile,
                       float(rated_force_N),
                       grasp_layout("as laid out", laid, units, *args),
                       grasp_layout("paired", paired, sites, *args), layout_json(pairing),
                       notes, along_rows, layout_json(along) if along_rows else None,
                       tissue_base)


def default_jaw(plan: Plan, pivot_mm: tuple[float, float] | None = None,
                pin_to_tip_mm: float | None = None, opening_deg: float | None = None,
                slab_mm: float | None = None) -> JawGeometry:
    """The jaw of a design's grasp, each value not given taken from the grasper the design
    states (``[grasper_jaw]``, ``[tissue_slab]``: :func:`tactcad.design.grasper_in_use.stated_grasper`),
    else by default: the pin :data:`DEFAULT_PIVOT_BEHIND_MM` behind the first tip along the
    rows, the jaw reaching :data:`DEFAULT_JAW_BEYOND_MM` beyond the last tip,
    :data:`DEFAULT_OPENING_DEG` open, a :data:`DEFAULT_SLAB_MM` slab (mm, degrees).

    Raises:
        DesignError: a value out of range (:class:`JawGeometry`).
        DesignErrors: the stated jaw cannot take the insert (each refusal names its field).
    """
    from tactcad.design.grasper_in_use import stated_grasper

    stated = stated_grasper(plan)
    if stated is not None:
        pivot = pivot_mm or (stated.pivot_u_mm, stated.pivot_v_mm)
        length = pin_to_tip_mm or stated.pin_to_tip_mm
        opening = opening_deg or stated.opening_angle_deg
        return JawGeometry(pivot[0], pivot[1], length, opening, slab_mm or stated.slab_thickness_mm)
    pivot = pivot_mm or (-DEFAULT_PIVOT_BEHIND_MM, 0.0)
    last = max(u for u, _ in insert_frame(plan).values())
    length = pin_to_tip_mm or (last - pivot[0] + DEFAULT_JAW_BEYOND_MM)
    lo, hi = PIN_TO_TIP_RANGE_MM
    if not pin_to_tip_mm and not lo <= length <= hi:  # the pin given, the length derived
        reach = last + DEFAULT_JAW_BEYOND_MM
        raise DesignError("jaw.pivot_u_mm", pivot[0], f"{reach - hi:g} ... {reach - lo:g} mm "
                          "along the rows", f"the jaw then reaches from its pin to "
                          f"{DEFAULT_JAW_BEYOND_MM:g} mm beyond the last tip (u = {last:g} mm), "
                          f"{lo:g} ... {hi:g} mm; or give the pin-to-tip length")
    return JawGeometry(pivot[0], pivot[1], length, opening_deg or DEFAULT_OPENING_DEG,
                       slab_mm or DEFAULT_SLAB_MM)


def tissue_base_of(plan: Plan) -> str:
    """How the opposing jaw holds the design's tissue.

    Args:
        plan: the design.

    Returns:
        One of :data:`TISSUE_BASES`: the design's ``[tissue_slab] base`` where it states
        its grasper (:func:`tactcad.design.grasper_in_use.stated_grasper`), else
        :data:`DEFAULT_TISSUE_BASE`.

    Raises:
        DesignErrors: the stated tables refused (each refusal names its field).
    """
    from tactcad.design.grasper_in_use import stated_grasper

    stated = stated_grasper(plan)
    return stated.tissue_base if stated is not None else DEFAULT_TISSUE_BASE


def default_assumptions(k_obj_range: tuple[float, float], plan: Plan | None = None) -> str:
    """The grasp's jaw and tissue in words (for a record that uses them): the design's
    stated grasper (:func:`default_jaw`) or the defaults."""
    from tactcad.design.grasper_in_use import stated_grasper

    lo, hi = k_obj_range
    stated = None if plan is None else stated_grasper(plan)
    jaw = stated.words() if stated is not None else (
        f"pin {DEFAULT_PIVOT_BEHIND_MM:g} mm behind the first tip along the rows, jaw "
        f"{DEFAULT_JAW_BEYOND_MM:g} mm beyond the last tip, {DEFAULT_OPENING_DEG:g} degrees "
        f"open, a {DEFAULT_SLAB_MM:g} mm {OVERLOAD_PROFILE} on a {DEFAULT_TISSUE_BASE} base")
    return (f"{jaw} coupled as a layer on the opposing jaw (ν {TISSUE_POISSON_RATIO:g}), K_obj "
            f"the geometric mean of the range {lo:g} ... {hi:g} N/mm; the design's layout")


def design_grasp_at_force(plan: Plan, force_N: float, rated_force_N: float,
                          k_obj_range: tuple[float, float],
                          model: str = "closed-form") -> GraspResult:
    """The grasp of a design at a grasp force with its jaw and tissue (the design's stated
    grasper or the defaults: :func:`default_jaw`, :func:`default_assumptions`), the
    elements' K at ``model``, on the :data:`OVERLOAD_PROFILE` (the overload check's).

    Args:
        force_N: the grasp force the tips put on the slab (N), > 0.
        rated_force_N: each element's rated full-scale force (N).
        k_obj_range: the required K_obj range (N/mm); the tissue's K_obj is its geometric mean.

    Raises:
        DesignError: the force is out of the jaw's reach, or a value out of range.
    """
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.mechanics.readout_chain import row_units

    k = ladder_stiffness_by_element(plan, model)
    by_part = {s.geometry.part_name: k[s.number] for s in plan.slots}
    units = [(r.number, m.number) for r, m in row_units(plan, by_part)]
    return grasp(plan, default_jaw(plan), k, units, math.sqrt(k_obj_range[0] * k_obj_range[1]),
                 rated_force_N, force_N=force_N, profile=OVERLOAD_PROFILE,
                 tissue_base=tissue_base_of(plan))


def design_grasp_reach_N(plan: Plan, rated_force_N: float, k_obj_range: tuple[float, float],
                         model: str = "closed-form") -> tuple[float, float]:
    """The grasp forces (N) a design's jaw reaches on its tissue, as
    :func:`design_grasp_at_force` grasps it: from the jaw fully open to closed flat on the
    slab, in every layout the grasp solves (the largest open force, the least closed one:
    :func:`angle_for_force` refuses a force outside any layout's reach).

    Args:
        plan: the design.
        rated_force_N: each element's rated full-scale force (N), > 0.
        k_obj_range: the required K_obj range (N/mm); the tissue's K_obj is its geometric mean.
        model: the level of the elements' K.

    Returns:
        (least, largest) grasp force (N) in reach.

    Raises:
        DesignError: a value out of range (:func:`grasp`).
    """
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.mechanics.readout_chain import row_units

    k = ladder_stiffness_by_element(plan, model)
    by_part = {s.geometry.part_name: k[s.number] for s in plan.slots}
    units = [(r.number, m.number) for r, m in row_units(plan, by_part)]
    jaw, k_obj = default_jaw(plan), math.sqrt(k_obj_range[0] * k_obj_range[1])

    def totals(angle_deg: float) -> list[float]:
        result = grasp(plan, jaw, k, units, k_obj, rated_force_N, angle_deg=angle_deg,
                       profile=OVERLOAD_PROFILE, tissue_base=tissue_base_of(plan))
        layouts = [result.as_laid_out, result.paired, result.along_rows]
        return [layout.total_force_N for layout in layouts if layout is not None]

    return max(totals(jaw.opening_angle_deg)), min(totals(0.0))


def in_kobj_range(k_obj_N_per_mm: float, kobj_range: tuple[float, float]) -> bool:
    """Whether a K_obj (N/mm) lies in the design's required K_obj range (N/mm, its ends
    included to 1e-9 relative): the range the design is made to read."""
    lo, hi = kobj_range
    return lo * (1 - 1e-9) <= k_obj_N_per_mm <= hi * (1 + 1e-9)


def kobj_range_warning(k_obj_N_per_mm: float, kobj_range: tuple[float, float],
                       option: str = "--kobj") -> str | None:
    """The warning a grasp prints where the tissue's K_obj is outside the design's range.

    Args:
        k_obj_N_per_mm: the tissue's K_obj (N/mm).
        kobj_range: the design's required K_obj range (N/mm).
        option: the option that set it.

    Returns:
        One line naming the option, the value and the range; None inside the range.
    """
    if in_kobj_range(k_obj_N_per_mm, kobj_range):
        return None
    lo, hi = kobj_range
    return (f"warning: {option} {k_obj_N_per_mm:g} N/mm is outside the design's K_obj range "
            f"{lo:g} ... {hi:g} N/mm: the design is not made to read it; a unit whose true "
            "K_obj is outside that range does not read (its R and K_obj read are shown, not "
            "rated)")


def with_kobj_range(layout: LayoutGrasp, kobj_range: tuple[float, float]) -> LayoutGrasp:
    """``layout`` with each unit's ``in_kobj_range`` (its true K_obj in the design's range,
    :func:`in_kobj_range`) and ``reads``: its tips give a reading (``valid``) of a K_obj
    the design is made to read; ``out_of_range`` says why not where it is outside."""
    from dataclasses import replace

    lo, hi = kobj_range
    units = []
    for u in layout.units:
        inside = in_kobj_range(u["K_obj_true_N_per_mm"], kobj_range)
        units.append({**u, "in_kobj_range": inside, "reads": bool(u["valid"] and inside),
                      "out_of_range": "" if inside else
                      f"true K_obj {u['K_obj_true_N_per_mm']:.4g} N/mm outside the design's "
                      f"range {lo:g} ... {hi:g} N/mm"})
    return replace(layout, units=units)


def result_with_kobj_range(result: GraspResult,
                           kobj_range: tuple[float, float]) -> GraspResult:
    """``result`` with :func:`with_kobj_range` on each of its layouts."""
    from dataclasses import replace

    return replace(result, as_laid_out=with_kobj_range(result.as_laid_out, kobj_range),
                   paired=with_kobj_range(result.paired, kobj_range),
                   along_rows=None if result.along_rows is None else
                   with_kobj_range(result.along_rows, kobj_range))


def grasp_summary(result: GraspResult) -> dict:
    """One layout per key (``as_laid_out``, ``paired``): its angle, grasp force, the largest
    element force and its element, the elements over their rating and those on a stop (N,
    degrees)."""
    def layout(lay: LayoutGrasp) -> dict:
        top = max(lay.tips, key=lambda t: t["element_force_N"])
        return {"angle_deg": lay.angle_deg, "grasp_force_N": lay.total_force_N,
                "largest_element_force_N": top["element_force_N"],
                "largest_element": top["site"],
                "over_rating": [t["site"] for t in lay.tips if t["over_rating"]],
                "over_overload_limit": [t["site"] for t in lay.tips
                                        if t["over_overload_limit"]],
                "on_stop": [t["site"] for t in lay.tips if t["on_stop"]],
                "stop_force_N": sum(t["stop_force_N"] for t in lay.tips)}

    return {"rated_force_N": result.rated_force_N, "K_obj_N_per_mm": result.k_obj_N_per_mm,
            "slab_thickness_mm": result.jaw.slab_thickness_mm, "coupling": result.coupling,
            "tissue_base": result.tissue_base if result.coupling == "layer" else None,
            "profile": result.profile, "opening_angle_deg": result.jaw.opening_angle_deg,
            "as_laid_out": layout(result.as_laid_out), "paired": layout(result.paired)}
