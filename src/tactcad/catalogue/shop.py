"""What the shop needs to know about a fabricated part besides its shape:
material designation with alloy and temper, surface finish, raw stock, metric
threads and bolt tightening torques. No CAD kernel here.

Units: mm, N, N·m, MPa, Ra in micrometres.

Every value that is a choice, not a fact of the design, carries its reason
(:data:`FINISH_REASON`, :data:`STOCK_REASON`, :func:`tightening_torque_Nm`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.catalogue.array_catalogue import Method, PartSpec
from tactcad.design.array_plan import BoltSpec, Plan

#: ISO 261 / ISO 262 coarse pitch (mm) by nominal diameter (mm).
COARSE_PITCH_MM: dict[float, float] = {1.6: 0.35, 2.0: 0.4, 2.5: 0.45, 3.0: 0.5, 4.0: 0.7,
                                       5.0: 0.8, 6.0: 1.0, 8.0: 1.25, 10.0: 1.5, 12.0: 1.75}

#: General surface finish (ISO 21920-1 Ra, micrometres) of a machined part.
GENERAL_RA_UM = 1.6
#: Finish of the element's contact face and of the web (micrometres).
CRITICAL_RA_UM = 0.8
FINISH_REASON = ("Ra 1.6 is what finish milling and a finishing wire-EDM pass give without "
                 "extra cost; Ra 0.8 on the element's web and contact face because surface "
                 "roughness there adds scatter to the web thickness (hinge stiffness ~ t^2.5) "
                 "and to the contact with tissue (fine wire-EDM skim cuts reach it)")

#: Raw-blank allowances (mm) by kind of process.
SHEET_MARGIN_MM = 5.0   # per side on a cut-from-sheet blank: clamping and wire start
PLATE_MARGIN_MM = 3.0   # per side on a sawn plate blank: saw cut and squaring
PLATE_FACE_MM = 1.0     # per face: facing both sides of a milled plate part
BAR_DIAMETER_MM = 2.0   # on the diameter of turned round bar
BAR_LENGTH_MM = 5.0     # facing and parting off a turned part
STOCK_REASON = (f"blank allowances: {SHEET_MARGIN_MM:g} mm per side on sheet (clamping, wire "
                f"start), {PLATE_MARGIN_MM:g} mm per side and {PLATE_FACE_MM:g} mm per face on "
                f"sawn plate (squaring, facing), +{BAR_DIAMETER_MM:g} mm on the diameter and "
                f"+{BAR_LENGTH_MM:g} mm on the length of round bar (turning, parting off)")

#: Tightening of the array's clamp bolts (VDI 2230-1:2015, eq. R4 / R13 and Table A1 method).
FRICTION = 0.12                 # thread and head friction, lightly oiled black-oxide screw
UTILISATION = 0.9               # of the proof stress by the equivalent stress when tightening
YIELD_8_8_MPA = 640.0           # ISO 898-1 property class 8.8, R_p0.2 (d <= 16 mm)


def _fmt(v: float) -> str:
    return f"{v:g}"


def material_designation(spec: PartSpec, plan: Plan | None = None) -> str:
    """Material with alloy and temper, e.g. ``aluminium EN AW-6061-T6``.

    The array's parts are cut from the design's material: its library grade
    (:mod:`tactcad.vocabulary.material_library`, ``[material] grade``) gives alloy and
    temper, written with the EN 573-1 prefix ``EN AW-`` for aluminium. Rig
    parts carry their designation in their catalogue entry already.
    """
    mat = plan.material if plan is not None else None
    if mat is None:
        return spec.material
    grade = mat.grade if spec.material == mat.name else None
    if spec.builder in ("clamp_plate", "spacer"):  # their own grade (clamp.material)
        from tactcad.design.bom_section import clamp_grades

        grade = clamp_grades(plan.raw)[spec.builder]
    if not grade:
        return spec.material
    name = spec.material
    if "alumin" in name.lower() and not grade.upper().startswith("EN"):
        grade = f"EN AW-{grade}"
    if name.casefold() in grade.casefold():  # name and grade alike: say it once
        return grade
    return f"{name} {grade}"


@dataclass(frozen=True)
class Finish:
    """Surface finish of a part: the general Ra and the faces finer than it."""

    general_ra_um: float
    special: tuple[tuple[str, float], ...]  # (face, Ra um)
    reason: str


def surface_finish(spec: PartSpec) -> Finish:
    """Finish of a fabricated part (ISO 21920-1 Ra, indicated after ISO 1302):
    Ra 1.6 in general; on a flexure element Ra 0.8 on the contact face and the
    web (reason: :data:`FINISH_REASON`). A cast rubber sample gets the mould's
    finish."""
    if spec.process.method is Method.CAST:
        return Finish(0.0, (), "as cast: the mould's surface")
    special: tuple[tuple[str, float], ...] = ()
    if spec.builder == "element":
        special = (("contact face", CRITICAL_RA_UM), ("web (notch flanks)", CRITICAL_RA_UM))
    return Finish(GENERAL_RA_UM, special, FINISH_REASON)


def stock_size(spec: PartSpec) -> str:
    """Raw blank of a fabricated part (mm), from its designed bounding box
    and the allowances of its process's :class:`~tactcad.catalogue.array_catalogue.Method`
    (:data:`STOCK_REASON`):

    * cut from sheet: ``sheet T, blank L x W``;
    * milled from plate: ``plate T x L x W`` (the next whole mm above);
    * turned: ``round bar ØD x L``;
    * cut from bar: ``bar T x W, cut to L``;
    * cast: ``cast to size``.

    Raises:
        ValueError: a bought part (it has no stock).
    """
    x0, y0, z0, x1, y1, z1 = spec.expected_bbox_mm
    ext = sorted((x1 - x0, y1 - y0, z1 - z0))
    t, w, L = ext
    method = spec.process.method
    if method is Method.BOUGHT:
        raise ValueError(f"{spec.name} is bought ({spec.process}): no raw stock")
    if method is Method.CAST:
        return "cast to size"
    if method is Method.SHEET:
        thick = spec.thickness_mm or t
        return (f"sheet {_fmt(thick)} mm, blank {_fmt(math.ceil(L + 2 * SHEET_MARGIN_MM))} x "
                f"{_fmt(math.ceil(w + 2 * SHEET_MARGIN_MM))}")
    if method is Method.ROUND_BAR:
        d = max(x1 - x0, y1 - y0)
        return (f"round bar Ø{_fmt(math.ceil(d + BAR_DIAMETER_MM))} x "
                f"{_fmt(math.ceil((z1 - z0) + BAR_LENGTH_MM))}")
    if method is Method.BAR:
        return f"bar {_fmt(t)} x {_fmt(w)}, cut to {_fmt(math.ceil(L + BAR_LENGTH_MM))}"
    return (f"plate {_fmt(math.ceil(t + 2 * PLATE_FACE_MM))} x "
            f"{_fmt(math.ceil(L + 2 * PLATE_MARGIN_MM))} x {_fmt(math.ceil(w + 2 * PLATE_MARGIN_MM))}")


def coarse_pitch_mm(diameter_mm: float) -> float:
    """ISO 261 coarse pitch of an M thread.

    Raises:
        ValueError: no coarse thread of that nominal diameter in the table.
    """
    for d, p in COARSE_PITCH_MM.items():
        if abs(d - diameter_mm) < 1e-9:
            return p
    raise ValueError(f"thread diameter {diameter_mm:g} mm: allowed "
                     + ", ".join(_fmt(d) for d in COARSE_PITCH_MM))


def thread_text(diameter_mm: float, depth_mm: float | None = None) -> str:
    """ISO 6410 call-out of a tapped hole: ``M3x0.5 depth 8`` (thread depth,
    mm; the word instead of the depth symbol, which the drawing font lacks)
    or ``M3x0.5`` for a through thread."""
    text = f"M{_fmt(diameter_mm)}x{_fmt(coarse_pitch_mm(diameter_mm))}"
    return text + (f" depth {_fmt(depth_mm)}" if depth_mm else "")


def tap_drill_mm(diameter_mm: float) -> float:
    """Tap drill diameter (mm): nominal diameter minus pitch (ISO 2306 practice)."""
    return round(diameter_mm - coarse_pitch_mm(diameter_mm), 2)


def tightening_torque_Nm(bolt: BoltSpec, friction: float = FRICTION,
                         yield_MPa: float = YIELD_8_8_MPA) -> float:
    """Assembly torque (N·m) of a property class 8.8 socket head cap screw.

    VDI 2230-1:2015: assembly preload F_M at :data:`UTILISATION` of R_p0.2 by
    the von Mises stress of tension and thread torsion (eq. R13, as its
    Table A1 is computed), then M_A = F_M (0.16 P + 0.58 d2 mu_G +
    mu_K D_Km / 2) (eq. R4), D_Km = mean of head diameter and clearance
    hole. d2 = d - 0.6495 P, d3 = d - 1.2269 P (ISO 724).
    """
    d, P = bolt.nominal_diameter_mm, bolt.thread_pitch_mm
    d2, d3 = d - 0.6495 * P, d - 1.2269 * P
    d0 = (d2 + d3) / 2
    area = math.pi / 4 * d0 * d0
    torsion = 1.5 * d2 / d0 * (P / (math.pi * d2) + 1.155 * friction)
    preload = UTILISATION * yield_MPa * area / math.sqrt(1 + 3 * torsion ** 2)
    d_km = (bolt.head_diameter_mm + bolt.clearance_hole_mm) / 2
    return preload * (0.16 * P + 0.58 * d2 * friction + friction * d_km / 2) / 1000.0


TORQUE_SOURCE = (f"VDI 2230-1:2015 (eq. R4, R13), property class 8.8 (ISO 898-1, "
                 f"R_p0.2 {YIELD_8_8_MPA:g} MPa), mu_G = mu_K = {FRICTION:g}, "
                 f"{UTILISATION * 100:g} % utilisation")
