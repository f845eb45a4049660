"""A metal design's grasp as ``tactcad grasp --json`` prints it and
:meth:`tactcad.api.Project.grasp` returns it: one computation for both.

A pivoting jaw closes on tissue (:func:`tactcad.in_use.grasp_experiment.grasp`); each
sensing unit's R and K_obj read, as laid out and paired, every element's force against its
rating and overload limit, and the leads through the shaft. Units: mm, N, N/mm, degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from tactcad.design.requirement_limits import MAX_KOBJ_N_PER_MM, MIN_KOBJ_N_PER_MM
from tactcad.errors import DesignError
from tactcad.in_use.grasp_experiment import (DEFAULT_JAW_BEYOND_MM, DEFAULT_OPENING_DEG,
                                             DEFAULT_PIVOT_BEHIND_MM, DEFAULT_PROFILE,
                                             DEFAULT_SLAB_MM, DEFAULT_TISSUE_BASE)

#: The shaft's lead channel where the design states no grasper (mm, assumed).
DEFAULT_LEAD_CHANNEL_MM = 3.0

#: The smallest grasp force asked (N): a micronewton. Off its stops the grasp is linear in
#: its force, so its readings should not depend on it; the contact solve's round-off makes
#: them: on the 2 x 3 Ti array a unit's K_obj error read at 1e-6 N is a 1 mN grasp's to
#: 1e-6, at 1e-10 N it drifts in the fourth digit, at 1e-12 N by a per cent, and at 1e-300 N
#: the "readings" are round-off alone (deflections of 2e-16 mm). Three decades below the
#: lightest rating of the shipped designs (a die's millinewtons).
MIN_GRASP_FORCE_N = 1e-6

#: Each number a grasp is asked with: (low, high, unit, low end open); the command's
#: options and the API's keyword arguments take the same ranges.
GRASP_NUMBERS: dict[str, tuple[float, float, str, bool]] = {
    "angle_deg": (0.0, 90.0, "degrees", False),
    "force_N": (MIN_GRASP_FORCE_N, 1000.0, "N", False),
    "slab_thickness_mm": (0.0, 100.0, "mm", True),
    # the K_obj a design file's range may state: far below it the tissue is lost in the
    # elements' K (K + K_obj rounds to K) and the grasp's readings are round-off
    "kobj": (MIN_KOBJ_N_PER_MM, MAX_KOBJ_N_PER_MM, "N/mm", False),
    "pivot_mm": (-500.0, 500.0, "mm", False),
    "pin_to_tip_mm": (1.0, 200.0, "mm", False),
    "opening_deg": (0.0, 90.0, "degrees", True),
    "lead_channel_mm": (0.0, 50.0, "mm", True),
}


#: The grasp record's renamed keys, old -> new: the design's K_obj range is
#: ``kobj_range_N_per_mm``, as ``budget --json``, ``verify --json`` and the design file
#: name it. The old key is still written beside the new one with the same value, and the
#: record lists this mapping as ``deprecated_keys`` (the budget's mechanism,
#: :func:`tactcad.in_use.kobj_budget.with_deprecated_keys`); it goes in a later release.
GRASP_DEPRECATED_KEYS = {"K_obj_range_N_per_mm": "kobj_range_N_per_mm"}  # KOBJ_RANGE_RENAMED


def with_grasp_deprecated_keys(record: dict) -> dict:
    """A grasp record (a metal design's or a die's) with the old name of each renamed key
    beside the new one (:data:`GRASP_DEPRECATED_KEYS`) and ``deprecated_keys`` listing them.

    Args:
        record: the record, written under the new keys.

    Returns:
        A new dict; ``record`` unchanged.
    """
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys

    return with_declared_deprecated_keys(record, GRASP_DEPRECATED_KEYS)


@dataclass(frozen=True)
class GraspAsked:
    """What a grasp is asked with; None: the default each field's reason states.

    Attributes:
        model: ladder level of the elements' K.
        force_N, angle_deg: the grasp force on the tissue (N) or the jaw's closing angle
            (degrees), at most one of them.
        kobj: the tissue's true local stiffness under one tip (N/mm).
        coupling, profile: the tissue's coupling between the tips and its shape.
        pivot_mm: the pin (X along the rows, Y across them; mm from the first tip).
        pin_to_tip_mm, opening_deg, slab_thickness_mm, lead_channel_mm: the jaw from pin to
            tip (mm), its full opening (degrees), the tissue's thickness (mm), the shaft's
            lead channel (mm).
    """

    model: str = "closed-form"
    force_N: float | None = None
    angle_deg: float | None = None
    kobj: float | None = None
    coupling: str = "layer"
    profile: str = DEFAULT_PROFILE
    pivot_mm: tuple[float, float] | None = None
    pin_to_tip_mm: float | None = None
    opening_deg: float | None = None
    slab_thickness_mm: float | None = None
    lead_channel_mm: float | None = None


def grasp_record(plan, asked: GraspAsked) -> dict:
    """The grasp of a metal design, as ``tactcad grasp --json`` prints it.

    Args:
        plan: the design's plan (a stacked array or a comb).
        asked: what the grasp is asked with (:class:`GraspAsked`).

    Returns:
        The jaw, each layout's tips and units (``as_laid_out``, ``paired``,
        ``along_rows``), the leads, the design's ``kobj_range_N_per_mm`` (N/mm; also under
        its deprecated name, :data:`GRASP_DEPRECATED_KEYS`, listed in ``deprecated_keys``),
        ``warnings`` (a K_obj outside the range, an element past
        its overload limit), ``passed`` (False where the design's own layout overloads an
        element) and ``reasons`` (where each default comes from).

    Raises:
        DesignError: a value the grasp cannot take, named by the grasp's field
            (``force_N``, ``jaw.slab_thickness_mm`` ...:
            :data:`tactcad.commands.options.GRASP_OPTION_OF` maps each to its option).
    """
    from tactcad.design.grasper_in_use import stated_grasper
    from tactcad.in_use.grasp_experiment import (default_jaw, grasp, kobj_range_warning,
                                                 overload_warning, overloaded_sites,
                                                 result_with_kobj_range, tissue_base_of)
    from tactcad.in_use.jaw_kinematics import check_angle_deg
    from tactcad.in_use.shaft_leads import leads_check
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.mechanics.readout_chain import readout_chain, row_units
    from tactcad.studies.verification import requirements_of

    if asked.force_N is not None and asked.angle_deg is not None:
        raise DesignError("force_N", asked.force_N, "a grasp force or a closing angle, not "
                          f"both (the angle {asked.angle_deg:g} degrees is given too)")
    # the jaw and the closing angle asked are checked before any model runs: a refused
    # option then says no model's warnings
    jaw = default_jaw(plan, asked.pivot_mm, asked.pin_to_tip_mm, asked.opening_deg,
                      asked.slab_thickness_mm)
    if asked.angle_deg is not None:
        check_angle_deg(jaw, asked.angle_deg)
    req = requirements_of(plan)
    rated = float(req.full_scale_force_N)
    lo, hi = req.kobj_range_N_per_mm
    k_obj = asked.kobj if asked.kobj is not None else math.sqrt(lo * hi)
    given = asked.angle_deg is not None or asked.force_N is not None
    force = asked.force_N if given else round(0.5 * rated * len(plan.slots), 12)
    force_why = ("--force-N" if asked.force_N is not None else "--angle-deg"
                 if asked.angle_deg is not None else
                 f"half the rated {rated:g} N on each of {len(plan.slots)} elements")
    k = ladder_stiffness_by_element(plan, asked.model)
    overload = overload_limits_of(plan)
    by_part = {s.geometry.part_name: k[s.number] for s in plan.slots}
    units = [(r.number, m.number) for r, m in row_units(plan, by_part)]
    stated = stated_grasper(plan) is not None
    unused = "grasper_jaw" in plan.raw and not stated
    base = tissue_base_of(plan)

    def closed(**how: Any):
        return grasp(plan, jaw, k, units, k_obj, rated, coupling=asked.coupling,
                     profile=asked.profile, overload_N=overload, tissue_base=base, **how)

    try:
        result = closed(angle_deg=asked.angle_deg, force_N=force)
    except DesignError as exc:
        if given or exc.field != "force_N":
            raise
        # the default force outside what the tissue takes: below it with the jaw fully
        # open (the grasp the jaw cannot make lighter), or above it closed flat (a
        # tissue too thin or soft for it)
        result = closed(angle_deg=jaw.opening_angle_deg)
        tissue = f"{jaw.slab_thickness_mm:g} mm {asked.profile}"
        if result.as_laid_out.total_force_N > force:
            force_why = (f"the jaw at its full opening: {force_why} ({force:g} N) is less "
                         f"than the {result.as_laid_out.total_force_N:.4g} N the {tissue} "
                         f"takes with the jaw open {jaw.opening_angle_deg:g} degrees")
        else:
            result = closed(angle_deg=0.0)
            force_why = (f"the jaw closed flat: {force_why} ({force:g} N) is more than "
                         f"the {result.as_laid_out.total_force_N:.4g} N the {tissue} "
                         f"takes with the jaw closed")
    channel, channel_why = lead_channel_of(plan, asked.lead_channel_mm)
    leads = leads_check(len(plan.slots), channel, readout_chain(plan).lead_wires)
    result = result_with_kobj_range(result, (lo, hi))
    warnings = [w for w in (kobj_range_warning(k_obj, (lo, hi)),
                            *map(overload_warning, shown_layouts(result)),
                            leads_warning(leads, channel_why)) if w]
    # an element past its overload limit in the design's own layout (the grasp the hardware
    # makes damages it) or leads the shaft cannot take: a result that does not pass
    passed = not overloaded_sites(result.as_laid_out.tips) and leads.fits
    return with_grasp_deprecated_keys({
            **result.as_json(), "model": asked.model, "leads": leads.as_json(),
            "kobj_range_N_per_mm": [lo, hi], "warnings": warnings, "passed": passed,
            "reasons": {
                "rated_force_N": req.reasons["full_scale_force_N"],
                "overload_limit_N": "each element's yield with the design's safety factor "
                                    "or its gauge's largest strain, the smaller, at the "
                                    "closed form (as verify's max_grasp_force_N reads it)",
                "K_obj": "--kobj" if asked.kobj is not None else
                f"the geometric mean of the K_obj range {lo:g} ... {hi:g} N/mm",
                "force_N": force_why,
                "pivot": "--pivot-mm" if asked.pivot_mm else
                "the design's [grasper_jaw]" if stated else
                f"{DEFAULT_PIVOT_BEHIND_MM:g} mm behind the first tip along the rows"
                + (f" (the design's [grasper_jaw] is not used: the {plan.construction} "
                   "construction's envelope needs the CAD kernel)" if unused else ""),
                "pin_to_tip_mm": "--pin-to-tip-mm" if asked.pin_to_tip_mm else
                "the design's [grasper_jaw]" if stated else
                f"the last tip's radius + {DEFAULT_JAW_BEYOND_MM:g} mm",
                "opening_angle_deg": "--opening-deg" if asked.opening_deg else
                "the design's [grasper_jaw]" if stated else
                f"{DEFAULT_OPENING_DEG:g} degrees, assumed",
                "lead_channel_mm": channel_why,
                "slab_thickness_mm": "--slab-thickness-mm" if asked.slab_thickness_mm else
                stated_table_words(plan, "tissue_slab") if stated else
                f"{DEFAULT_SLAB_MM:g} mm, assumed",
                "tissue_base": (stated_table_words(plan, "tissue_slab") if stated and
                                "base" in (plan.raw.get("tissue_slab") or {}) else
                                f"{DEFAULT_TISSUE_BASE}, assumed: tissue gripped on the jaw's "
                                "face does not slip on it")}})


def leads_warning(leads, channel_why: str) -> str | None:
    """The warning a grasp gives where the leads do not fit the shaft's lead channel.

    Args:
        leads: :class:`tactcad.in_use.shaft_leads.LeadsCheck`. channel_why: where the
            channel's diameter comes from.

    Returns:
        One line with the bundle's and the channel's diameters (mm) and the channel's
        source; None where the leads fit.
    """
    if leads.fits:
        return None
    return (f"the {leads.leads} leads (a {leads.bundle_diameter_mm:.3g} mm bundle) do not fit "
            f"the {leads.channel_diameter_mm:g} mm lead channel ({channel_why}): a wider "
            "channel, fewer or thinner leads")


def shown_layouts(result) -> list:
    """The layouts a grasp reports on their own: the design's, the paired one unless it is
    the design's, and the one along the rows where there is one."""
    own = result.layout["as_laid_out"]
    return [result.as_laid_out, *([] if own else [result.paired]),
            *([result.along_rows] if result.along_rows is not None else [])]


def overload_limits_of(plan) -> dict[int, float]:
    """Element number -> its overload limit (N) at the closed form
    (:func:`tactcad.studies.verification.element_overload_limits_N`)."""
    from tactcad.studies.verification import element_figures, element_overload_limits_N

    return element_overload_limits_N(plan, element_figures(plan))


def stated_table_words(plan, table: str) -> str:
    """Where a grasper table's values come from: the design's own ``[table]``, or that
    table's defaults for its stated jaw when the design leaves the table out."""
    raw = getattr(plan, "raw", None) or {}
    return (f"the design's [{table}]" if table in raw else
            f"the [{table}] defaults (the design leaves the table out)")


def lead_channel_of(plan, given_mm: float | None) -> tuple[float, str]:
    """(the lead channel's diameter in mm, where it comes from): the one asked, the bore
    of the design's shaft when the design states its grasper (as the ``grasper`` check
    reads it), else :data:`DEFAULT_LEAD_CHANNEL_MM`, assumed."""
    if given_mm is not None:
        return given_mm, "--lead-channel-mm"
    from tactcad.design.grasper_in_use import stated_shaft_bore_mm

    bore = stated_shaft_bore_mm(plan)
    if bore is not None:
        return bore, "the bore of " + stated_table_words(plan, "grasper_shaft")
    return DEFAULT_LEAD_CHANNEL_MM, f"{DEFAULT_LEAD_CHANNEL_MM:g} mm, assumed"
