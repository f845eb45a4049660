"""The flexure sensing element (a made part, one per distinct arm length):
the wire-cut profile (:func:`tactcad.geometry.profile.element_profile`)
extruded along +z by the sheet thickness.

Here under the key ``element``: the design file's ``[element]`` table, the
element's dimensions (:class:`ElementGeometry`), its spec, builder and shop
drawing (dimension set, notes, the web in detail A, drawn with the drawings
layer's pen). Which arm each slot has and where the clamp's bolt holes go is
the array's one coupled derivation, :mod:`tactcad.design.array_plan` (above this
layer); this module reads the result from the plan.

Element frame: x along the arm (0 = back face of the clamped base, tip at
+x), y up (0 = underside of the base), z through the sheet (0 ... sheet
thickness). Units: mm, MPa.
"""

from __future__ import annotations

import colorsys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Arc, element_profile
from tactcad.kernel.shapes import extrude_profile
from tactcad.partlib.array.prism import Hole, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, DrawingRecord, PartData
from tactcad.vocabulary.process import CUT_PROCESSES, DEFAULT_CUT_PROCESS, cut_process
from tactcad.vocabulary.schema import Section, choice, name_number, number

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

# Design domain: the range over which the closed-form stiffness correction is
# fitted to fem3d (data/stiffness_correction.json; web 0.05-1 mm, arm 2-20 mm,
# sheet 0.5-10 mm). The plan refuses designs outside it rather than
# extrapolate silently.
WEB_RANGE_MM = (0.05, 1.0)
#: The web's +/- tolerance a design file may state (mm): the finest a grinder holds to a
#: laser cut's 0.1 mm and more (a process finer than the stated one is asked for).
WEB_TOLERANCE_RANGE_MM = (0.0, 0.25)
ARM_RANGE_MM = (2.0, 20.0)
NOTCH_RADIUS_MAX_MM = 2.0
#: Why a value must lie in the design domain (the refusal's reason).
FITTED_DOMAIN = "the range over which the closed-form correction is fitted to fem3d"


class ElementSection(Section):
    """``[element]`` of the design file: the profile every element shares (mm)."""

    web_thickness_mm: number(*WEB_RANGE_MM, why=FITTED_DOMAIN)
    notch_radius_mm: number(0.0, NOTCH_RADIUS_MAX_MM, lo_open=True)
    tip_width_mm: number(0.5, 20.0)
    tip_height_mm: number(0.3, 5.0)
    arm_height_mm: number(0.0, 5.0, lo_open=True)
    base_height_mm: number(0.0, 30.0, lo_open=True)
    overall_length_mm: number(10.0, 60.0)
    inside_corner_radius_mm: number(0.0, 1.0, lo_open=True)
    web_tolerance_mm: number(*WEB_TOLERANCE_RANGE_MM) = None  # or [tolerances] web_thickness_mm
    #: how the elements are cut (:data:`tactcad.vocabulary.process.CUT_PROCESSES`); wire-edm when left out
    process: choice(CUT_PROCESSES, "the processes that cut a part from sheet") = None


@dataclass(frozen=True)
class GaugeStack:
    """The foil strain gauge bonded on the element's flat top face, centred over the notch:
    its grid, and the glue line and carrier under it (mm, MPa). The mechanics model it as a
    layer that stiffens the web and lifts the grid off the face
    (:mod:`tactcad.mechanics.bonded_layer`).

    Attributes:
        grid_length_mm: the grid along the element.
        grid_width_mm: the grid across the sheet.
        height_mm: face to grid plane (glue line and carrier).
        modulus_MPa: the glue line and carrier's Young's modulus.
    """

    grid_length_mm: float
    grid_width_mm: float
    height_mm: float
    modulus_MPa: float


@dataclass(frozen=True)
class ElementGeometry:
    """One distinct wire-cut flexure profile (element frame, mm).

    Profile: a clamped base block, a single-sided circular notch hinge at the
    base's upper front corner (flat top face over the web carries the strain
    gauge), a measuring arm of height ``arm_height_mm`` and a tip whose top
    face is the 2 x 3 mm contact face. ``arm_length_mm`` (paper: flexing arm
    length) is the lever from the notch centre to the centre of the contact
    face.
    """

    arm_length_mm: float
    web_thickness_mm: float
    notch_radius_mm: float
    tip_width_mm: float
    tip_height_mm: float
    arm_height_mm: float
    base_height_mm: float
    overall_length_mm: float
    inside_corner_radius_mm: float
    sheet_thickness_mm: float
    web_tolerance_mm: float
    bolt_holes: tuple[Hole, ...]
    start_hole_diameter_mm: float
    #: the cut process's name (:func:`tactcad.vocabulary.process.cut_process`)
    process: str = DEFAULT_CUT_PROCESS
    #: the bonded gauge the element carries in use (None: the bare element as cut); every
    #: stiffness level models it (:mod:`tactcad.mechanics.bonded_layer`)
    gauge: GaugeStack | None = None

    def bare(self) -> "ElementGeometry":
        """This element as cut, without its bonded gauge."""
        from dataclasses import replace

        return self if self.gauge is None else replace(self, gauge=None)

    @property
    def part_name(self) -> str:
        """Distinct part name, e.g. ``element_a4mm`` or ``element_a4p5mm``."""
        return "element_a" + name_number(self.arm_length_mm) + "mm"

    @property
    def tip_centre_x_mm(self) -> float:
        return self.overall_length_mm - self.tip_width_mm / 2

    @property
    def hinge_x_mm(self) -> float:
        """x of the notch centre, i.e. the thinnest section of the web."""
        return self.tip_centre_x_mm - self.arm_length_mm

    @property
    def notch_centre_y_mm(self) -> float:
        return self.base_height_mm - self.web_thickness_mm - self.notch_radius_mm

    @property
    def base_length_mm(self) -> float:
        """Length of the clamped base block (x from 0 to the notch's back wall)."""
        return self.hinge_x_mm - self.notch_radius_mm

    @property
    def arm_underside_y_mm(self) -> float:
        return self.base_height_mm - self.arm_height_mm

    @property
    def tip_top_y_mm(self) -> float:
        return self.base_height_mm + self.tip_height_mm

    @property
    def web_centre_mm(self) -> tuple[float, float]:
        """(x, y) of the web's middle (mm): mid-thickness over the notch centre,
        where the gauge's strain and the hinge's rotation are; the one place
        the web's position is computed (DXF lead-in keep-out, drawing detail)."""
        return (self.hinge_x_mm, self.base_height_mm - self.web_thickness_mm / 2)

    @property
    def contact_centre_mm(self) -> tuple[float, float]:
        """(x, y) of the middle of the tip's contact face (mm), the tip frame's origin."""
        return (self.tip_centre_x_mm, self.tip_top_y_mm)

    @property
    def contact_face_mm(self) -> tuple[float, float]:
        """(width along x, depth along z) of the tip contact face."""
        return (self.tip_width_mm, self.sheet_thickness_mm)



def build(g: ElementGeometry) -> Solid:
    """Solid of one element (element frame, mm): the wire-cut profile extruded
    along +z by the sheet thickness."""
    return extrude_profile(element_profile(g), g.sheet_thickness_mm)


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """One part per distinct profile (``plan.distinct_elements``), in order of first use."""
    material = context.plan.material.name
    return tuple(element_data(g, material) for g in context.plan.distinct_elements.values())


def element_data(g: ElementGeometry, material: str) -> PartData:
    """The spec of one distinct element: cut by its process (``[element]
    process``) from ``material`` sheet, volume = profile area x sheet thickness (mm^3)."""
    prof = element_profile(g)
    return PartData(
        name=g.part_name, kind="fabricated", process=cut_process(g.process).part_process(),
        material=material, color=element_shade(g.arm_length_mm),
        expected_volume_mm3=prof.area_mm2 * g.sheet_thickness_mm,
        expected_bbox_mm=prism_bbox(prof, g.sheet_thickness_mm), geometry=g, profile=prof,
        thickness_mm=g.sheet_thickness_mm)


def element_shade(arm_length_mm: float) -> RGB:
    """A clearly distinct anodising colour per arm length (stiffness class),
    the same in STEP, GLB and FreeCAD: the hue walks 0.19 of the colour wheel
    per mm of arm, from violet (4 mm) through pink, orange and green to
    turquoise (8 mm), away from the clamp plates' blue; deterministic, so a
    design always shows the same colours."""
    hue = (0.72 + (arm_length_mm - 4.0) * 0.19) % 1.0
    return tuple(round(c, 4) for c in colorsys.hsv_to_rgb(hue, 0.65, 0.85))  # type: ignore[return-value]


def slots_using(plan, part_name: str) -> tuple[int, ...]:
    """The numbers of the array's elements cut as part ``part_name``."""
    return tuple(s.number for s in plan.slots if s.geometry.part_name == part_name)


def dimensions(d, solid, pen) -> None:
    """The element's dimension set (drawn with the drawings layer's ``pen``):
    contact face, arm length, overall sizes, arm and tip heights, hole
    pattern, tip-root radius; the web (thickness with its tolerance, notch
    radius) in detail A."""
    g = d.spec.geometry
    tol = pen.tolerances(d.plan)  # the table the tolerance study draws from
    f = d.front
    L, H = g.overall_length_mm, g.base_height_mm
    top = g.tip_top_y_mm
    xl = L - g.tip_width_mm
    pen.dim(d, f, (xl, top), (L, top), "h", "top", 0,
            pen.plus_minus(g.tip_width_mm, tol.contact_face_mm), "tip_width")
    pen.dim(d, f, (g.hinge_x_mm, H), (g.tip_centre_x_mm, top), "h", "top", 1,
            pen.plus_minus(g.arm_length_mm, tol.arm_length_mm), "arm_length")
    pen.dim(d, f, (0.0, H), (L, top), "h", "top", 2, pen.fmt_mm(L), "overall_length")
    d.sheet.line("centre-lines", f.paper(g.tip_centre_x_mm, top - g.tip_height_mm / 2),
                 f.paper(g.tip_centre_x_mm, top + 0.3), "centre")
    d.sheet.line("centre-lines", f.paper(g.hinge_x_mm, g.notch_centre_y_mm - 1.3 * g.notch_radius_mm),
                 f.paper(g.hinge_x_mm, H + 0.3), "centre")
    xr = xl - g.inside_corner_radius_mm
    # the arm and tip heights are one chain: a low arm's value goes below it, clear of the tip's
    pen.dim(d, f, (L, g.arm_underside_y_mm), (xr, H), "v", "right", 0, pen.fmt_mm(g.arm_height_mm),
            "arm_height", outside="below")
    pen.dim(d, f, (xr, H), (L, top), "v", "right", 0, pen.fmt_mm(g.tip_height_mm), "tip_height")
    # the tip face's height above the clamped edge sets the tips' coplanarity (K_obj budget)
    pen.dim(d, f, (g.base_length_mm, 0.0), (L, top), "v", "right", 1,
            pen.plus_minus(top, pen.tip_height_tolerance(d)), "overall_height")
    holes = pen.holes_seen(d.spec, solid, d.cameras)
    pen.hole_dims_linear(d, f, holes, (0.0, 0.0))
    pen.dim(d, f, (0.0, 0.0), (0.0, H), "v", "left", 1, pen.fmt_mm(H), "base_height")
    pen.hole_marks(d, f, holes)
    pen.hole_callout(d, f, holes, (g.base_length_mm + g.notch_radius_mm * 2 + 0.8,
                                   g.arm_underside_y_mm * 0.35))
    _tip_root_radius(d, pen)
    _web_detail(d, pen, tol)
    _contact_face(d, pen, tol)
    pen.thickness_dim(d, tol=tol.sheet_thickness_mm)


def _tip_root_radius(d, pen) -> None:
    """The tip-root radius, its leader from the empty side."""
    g = d.spec.geometry
    fil = next(s for s in d.spec.profile.outer if isinstance(s, Arc) and not s.ccw
               and abs(s.radius - g.inside_corner_radius_mm) < 1e-9)
    c = d.front.paper(*fil.centre)
    text = f"R{pen.fmt_mm(fil.radius)}"
    d.sheet.radius_dimension(c, fil.radius * d.front.scale, pen.arc_angles(fil, -45.0), text,
                             "corner_radius", dist=(-10.0, -14.0, -18.0, -22.0),
                             shoulder_right=False)
    d.dimensions["corner_radius"] = text


def _web_detail(d, pen, tol) -> None:
    """Detail A: the web's thickness with its tolerance and the notch radius."""
    g = d.spec.geometry
    dv = d.views["detail"]
    xh, yc, H = g.hinge_x_mm, g.notch_centre_y_mm, g.base_height_mm
    d.sheet.centre_mark("centre-lines", dv.paper(xh, yc), 3.0)
    wt = pen.web_text(g)
    d.sheet.linear_dimension(dv.paper(xh, yc + g.notch_radius_mm), dv.paper(xh, H), "v",
                             dv.paper(xh, 0)[0], wt, "web_thickness")
    d.dimensions["web_thickness"] = wt
    rtext = f"R{pen.plus_minus(g.notch_radius_mm, tol.notch_radius_mm)}"
    notch = next(s for s in d.spec.profile.outer if isinstance(s, Arc)
                 and abs(s.radius - g.notch_radius_mm) < 1e-9 and abs(s.centre[0] - xh) < 1e-9)
    d.sheet.radius_dimension(dv.paper(xh, yc), g.notch_radius_mm * dv.scale,
                             pen.arc_angles(notch, 60.0), rtext, "notch_radius", dist=-10.0,
                             shoulder_right=True)
    d.dimensions["notch_radius"] = rtext


def _contact_face(d, pen, tol) -> None:
    """The contact face with its tolerances, in the view from above."""
    g = d.spec.geometry
    t = d.views["top"]
    cf = (f"contact face {pen.plus_minus(g.contact_face_mm[0], tol.contact_face_mm)} × "
          f"{pen.plus_minus(g.contact_face_mm[1], tol.sheet_thickness_mm)}")
    p0 = t.paper(g.tip_centre_x_mm, -g.sheet_thickness_mm / 2)
    p1 = (t.paper_box()[2] + 6.0, t.paper_box()[3] + 8.0)
    d.sheet.leader([p0, p1], cf, "contact_face")
    d.dimensions["contact_face"] = cf


def notes(d, pen) -> list[str]:
    """The element's notes: the web as the critical dimension, wire EDM,
    edges, use (and where its gauge goes), strength limit, the first natural
    frequency where the design states a minimum, Young's modulus."""
    plan, spec = d.plan, d.spec
    g = spec.geometry
    used = slots_using(plan, spec.name)
    fmt_mm = pen.fmt_mm
    resonance = pen.resonance_note(plan, spec.name)
    cut = cut_process(g.process)
    lim = cut.limits(g.sheet_thickness_mm, plan.edm, plan.material.grade or spec.material)
    files = (f"{Path(pen.profile_dxf_name(spec.name, len(used))).name} (or the nested sheet "
             f"{Path(pen.sheet_dxf_of(plan, spec)).name})")
    if cut.shop.offset_outline:  # the file is the artwork, not the part
        how = (f"; the file is the etch artwork, its outline "
               f"{fmt_mm(lim.compensation_per_side_mm.value_mm)} mm outside the nominal contour")
    else:
        how = (f" along the nominal contour; the tool offset is the shop's CAM setting. Start "
               f"holes Ø{fmt_mm(g.start_hole_diameter_mm)} at the bolt-hole centres")
    return [
        pen.web_note(plan, g),
        f"{pen.sentence(cut.text)} ({fmt_mm(g.sheet_thickness_mm)} mm {spec.material}) "
        f"from {files}{how}.",
        f"Inside corners not dimensioned: R >= {fmt_mm(lim.min_inside_radius_mm.value_mm)} "
        f"({lim.min_inside_radius_mm.rule}). Do not break the edges of the web or of the "
        f"contact face; deburr elsewhere.",
        f"Used as array element{'s' if len(used) > 1 else ''} "
        + ", ".join(str(k) for k in used) + f". {pen.gauge_note(plan, g)}",
        pen.full_scale_note(plan, spec.name, plan.material.yield_strength_MPa,
                            plan.material.grade or plan.material.name),
        *([resonance] if resonance else []),
        f"Young's modulus {plan.material.youngs_modulus_MPa:g} MPa "
        f"±{100 * pen.tolerances(plan).youngs_modulus_rel:g} %: check the sheet's mill certificate.",
    ]


def detail(g: ElementGeometry) -> tuple[tuple[float, float], float]:
    """((x, y) centre, radius) of the web's detail A in model mm."""
    r = 1.6 * (g.notch_radius_mm + g.web_thickness_mm)
    return (g.hinge_x_mm, g.notch_centre_y_mm + 0.35 * g.notch_radius_mm + 0.5 * g.web_thickness_mm), r


def plan_values(plan, spec, pen) -> tuple:
    """What of the plan the drawing prints: the element, the slots using it,
    the wire-EDM limits, the material, the strength settings and the read-out."""
    return (spec.geometry, slots_using(plan, spec.name), plan.edm, plan.material, plan.strength,
            pen.readout(plan))


def stacking_notes(book) -> tuple[str, ...]:
    return ("Stack in the order the assembly model shows: clamp plate, element, spacer, "
            "element ... clamp plate; align on the bolt holes before tightening.",
            "Keep the gauges' leads free of the clamp faces.")


PART = ArrayPart(key="element", build=build, specs=specs, order=10,
                 drawing=DrawingRecord(dimensions=dimensions, notes_of=notes, detail=detail,
                                       hole_table=False, plan_values=plan_values),
                 assembly=BuildStep("array-stack",
                                    "Stack elements and spacers between the clamp plates",
                                    tools=lambda book: ("flat granite or glass plate",),
                                    notes=stacking_notes))
