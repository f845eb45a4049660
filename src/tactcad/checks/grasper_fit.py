"""The insert in the grasper, kernel-free: the array's envelope inside the
jaw's pocket (a box test in the jaw's frame) and the insert's leads through
the shaft's lead channel (:mod:`tactcad.in_use.shaft_leads`).

The jaw and shaft are the design's ``[grasper_jaw]`` and ``[grasper_shaft]``
(:mod:`tactcad.partlib.grasper_jaw`, :mod:`tactcad.partlib.grasper_shaft`;
their defaults where left out); the check runs on a construction whose
envelope the plan gives without a kernel
(the monolithic comb, the grasper's insert). Units: mm.
"""

from __future__ import annotations

from typing import Iterator

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found
from tactcad.vocabulary.schema import fmt


def grasper_group(context: CheckContext) -> Iterator[Found]:
    """``grasper``: the insert in the design's jaw and its leads through its shaft
    (``[grasper_jaw]``, ``[grasper_shaft]``; their defaults where left out; none for a
    construction without a kernel-free envelope). A jaw that cannot take the insert (a
    plan made in code, or the default jaw of a design that states none) fails its
    ``pocket fit`` row with every refusal, so the other checks and the report still run."""
    from tactcad.errors import DesignErrors
    from tactcad.partlib.grasper_jaw import design_table, insert_envelope_mm, jaw_part
    from tactcad.partlib.grasper_shaft import shaft_part

    envelope = insert_envelope_mm(context.plan)
    if envelope is None:
        return
    shaft = shaft_part(design_table(context.plan, "grasper_shaft")).geometry
    tip_h = context.plan.slots[0].geometry.tip_height_mm
    try:
        jaw = jaw_part(context.plan).geometry
    except DesignErrors as exc:  # the radii are judged about this jaw's pin: not judged
        yield "grasper", [jaw_refused_result(envelope, exc),
                          shaft_leads_result(context.plan, shaft),
                          CheckResult("equal radius", "array: every unit's tips at one radius",
                                      False, "not judged: the design's jaw is refused (pocket "
                                      "fit), and the radii are about its pin")]
        return
    yield "grasper", [pocket_fit(envelope, jaw, tip_h),
                      shaft_leads_result(context.plan, shaft),
                      equal_radius_result(context.plan)]


def jaw_refused_result(envelope_mm: tuple[float, float, float], refused) -> CheckResult:
    """The ``pocket fit`` row of a jaw its rules refuse for the insert: failed, naming
    each refused key, its value and the allowed range.

    Args:
        envelope_mm: the insert's envelope (across the rows, along the row, height), mm.
        refused: the jaw's :class:`~tactcad.errors.DesignErrors`.

    Returns:
        The failed :class:`CheckResult`.
    """
    reasons = "; ".join(f"{e.field} = {e.value}: allowed {e.allowed}"
                        + (f" ({e.why})" if e.why else "") for e in refused.errors)
    return CheckResult("pocket fit", "grasper_jaw: insert in the pocket", False,
                       f"insert {' x '.join(fmt(v) for v in envelope_mm)} mm: the jaw cannot "
                       f"take it: {reasons}")


def equal_radius_result(plan) -> CheckResult:
    """Fails when a unit's two tips lie at radii from the jaw's pin that differ by more
    than :data:`~tactcad.in_use.radius_pairs.EQUAL_RADIUS_TOLERANCE_REL` (the jaw of the
    grasp experiment, :func:`~tactcad.in_use.grasp_experiment.default_jaw`): its R would
    carry their ratio (:mod:`tactcad.in_use.jaw_kinematics`)."""
    from tactcad.in_use.grasp_experiment import default_jaw
    from tactcad.in_use.radius_pairs import EQUAL_RADIUS_TOLERANCE_REL, insert_frame, unit_radii

    radii = unit_radii(default_jaw(plan), insert_frame(plan), list(plan.unit_pairs))
    worst = max(radii, key=lambda u: abs(u.ratio - 1.0), default=None)
    if worst is None:
        return CheckResult("equal radius", "array: every unit's tips at one radius", True,
                           "no sensing unit")
    ok = all(u.equal for u in radii)
    return CheckResult("equal radius", "array: every unit's tips at one radius", ok,
                       f"{len(radii)} units ({plan.pairing} pairing), worst r_m / r_r "
                       f"{worst.ratio:.4f} (unit {worst.reference}/{worst.measuring}: "
                       f"{worst.r_reference_mm:.4g} / {worst.r_measuring_mm:.4g} mm), allowed "
                       f"within {EQUAL_RADIUS_TOLERANCE_REL:.0%}")


def pocket_clearances_mm(envelope_mm: tuple[float, float, float], jaw,
                         tip_height_mm: float) -> dict[str, float]:
    """The insert's room in the jaw (mm), negative where it interferes.

    The insert is centred in the pocket with its contact faces ``jaw.tip_proud_mm``
    above the jaw's face.

    Args:
        envelope_mm: the insert's envelope (across the rows, along the row, height), mm.
        jaw: the jaw's :class:`~tactcad.partlib.grasper_jaw.GrasperJawGeometry`.
        tip_height_mm: the tips' height above the arms (mm).

    Returns:
        ``across`` and ``along``: pocket less envelope, each side; ``back``:
        the insert's underside above the jaw's back; ``under_wall``: the arms'
        tops below the face wall's underside; with a stated pocket outline,
        ``outline``: the pocket's least distance inside it (negative: the depth
        of the pocket's part outside it).
    """
    across, along, height = envelope_mm
    underside = jaw.thickness_mm + jaw.tip_proud_mm - height
    arm_top = jaw.thickness_mm + jaw.tip_proud_mm - tip_height_mm
    out = {"across": (jaw.pocket_width_mm - across) / 2,
           "along": (jaw.pocket_length_mm - along) / 2,
           "back": underside,
           "under_wall": jaw.pocket_depth_mm - arm_top}
    if getattr(jaw, "pocket_outline_mm", None):
        out["outline"] = pocket_inside_outline_mm(jaw)
    return out


def pocket_inside_outline_mm(jaw) -> float:
    """How far the jaw's pocket lies inside its stated outline (mm): the least distance
    from the pocket's edge to the outline's, negative by the farthest point outside."""
    import shapely.geometry as sg

    outline = sg.Polygon(jaw.pocket_outline_mm)
    x0, w = jaw.pocket_x0_mm, jaw.pocket_width_mm / 2
    pocket = sg.box(x0, -w, x0 + jaw.pocket_length_mm, w)
    if outline.covers(pocket):
        return outline.exterior.distance(pocket)
    return -max(outline.distance(sg.Point(q)) for q in pocket.exterior.coords)


def pocket_fit(envelope_mm: tuple[float, float, float], jaw, tip_height_mm: float) -> CheckResult:
    """Fails when the insert's envelope leaves the jaw's pocket (any clearance
    of :func:`pocket_clearances_mm` below zero); the detail gives every one."""
    room = pocket_clearances_mm(envelope_mm, jaw, tip_height_mm)
    detail = ", ".join(f"{k} {fmt(round(v, 6))} mm" for k, v in room.items())
    worst = min(room, key=room.get)
    ok = room[worst] >= 0.0
    return CheckResult("pocket fit", "grasper_jaw: insert in the pocket", ok,
                       f"insert {' x '.join(fmt(v) for v in envelope_mm)} mm in pocket "
                       f"{fmt(jaw.pocket_width_mm)} x {fmt(jaw.pocket_length_mm)} x "
                       f"{fmt(jaw.pocket_depth_mm)} mm: {detail}"
                       + ("" if ok else f"; interferes at {worst}"))


def shaft_leads_result(plan, shaft) -> CheckResult:
    """Fails when the bundle of the insert's leads (one quarter bridge per
    element, the design's lead-wire connection) is wider than the shaft's
    lead channel."""
    from tactcad.in_use.shaft_leads import leads_check
    from tactcad.mechanics.readout_chain import readout_chain

    leads = leads_check(len(plan.slots), shaft.bore_diameter_mm, readout_chain(plan).lead_wires)
    return CheckResult("lead channel", "grasper_shaft: leads in the bore", leads.fits,
                       f"{leads.leads} leads ({leads.connection}, Ø{fmt(leads.wire_diameter_mm)} "
                       f"mm) bundle Ø{fmt(round(leads.bundle_diameter_mm, 4))} mm in the "
                       f"Ø{fmt(leads.channel_diameter_mm)} mm channel, fill "
                       f"{leads.fill:.0%}")
