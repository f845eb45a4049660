"""What each part family's drawing shows beyond the common sheet, gathered
under its builder key (``PartSpec.builder``) in one :class:`PartDrawing`:
dimension set, notes (the web's stiffness sensitivity from
:func:`tactcad.mechanics.closed_form.web_tolerance_stiffness_change`, the
paper's Table 1 spread from :mod:`tactcad.paper.data`), section
view, fixed view directions, detail view, hole table or not, and the plan
values it prints. A rig part's drawing is its module's
:class:`~tactcad.partlib.base.DrawingRecord` (dimension set, section, notes,
view directions), drawn with :data:`PEN`. Any other fabricated part gets
:data:`GENERIC` (overall sizes, thickness, inside radii, holes; its process
and material)."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Callable

import numpy as np

from tactcad.catalogue.array import PartSpec
from tactcad.catalogue.files import profile_dxf_name, sheet_dxf_name
from tactcad.catalogue.shop import tap_drill_mm, thread_text
from tactcad.design.array import Plan
from tactcad.design.tolerances import tolerances_of
from tactcad.drawings.dimensioning import (add_section, dim, hole_callout, hole_dims_linear,
                                           hole_marks, hole_table, plus_minus, radius_callouts,
                                           section_marks, thickness_dim)
from tactcad.drawings.drawing import (FIRST_TIER, TIER, Drawing, Hole2D, holes_seen, inside_radii,
                                      part_thickness, web_text)
from tactcad.drawings.sheet import fmt_mm
from tactcad.geometry.profile import Arc
from tactcad.drawings.views import CAMERAS, cameras_for, orientation
from tactcad.mechanics.closed_form import web_tolerance_stiffness_change
from tactcad.paper.data import largest_equal_arm_spread
from tactcad.drawings.design_notes import full_scale_note, web_tolerance_note
from tactcad.partlib.base import DrawingRecord
from tactcad.partlib.registry import rig_parts_lib


def detail_circle(spec: PartSpec):
    """(centre, radius) of the part's detail view in model mm, or None."""
    detail = drawing_of(spec).detail
    return detail(spec) if detail is not None else None


def choose_cameras(spec: PartSpec) -> dict:
    """View set of a part: its family's fixed directions, the sketch plane
    for a profiled part, else by its bounding box."""
    fixed = drawing_of(spec).cameras
    if fixed is not None:
        return fixed
    if spec.profile is None:
        return orientation(spec.expected_bbox_mm)
    return dict(CAMERAS)


def hole_table_rows(d: Drawing, solid) -> int:
    """Rows of the hole table the generic set will draw (0: none)."""
    if not drawing_of(d.spec).hole_table:
        return 0
    holes = holes_seen(d.spec, solid, d.cameras)
    if not holes or len({(h.x, h.y) for h in holes}) == 1:
        return 0
    if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
        return 0
    return len(holes)


def element_dims(d: Drawing, solid) -> None:
    """Flexure element: contact face, arm length, overall sizes, arm and tip
    heights, hole pattern, tip-root radius; the web (thickness with its
    tolerance, notch radius) in detail A."""
    g = d.spec.geometry
    tol = tolerances_of(d.plan.raw)  # the table the tolerance study draws from
    f = d.front
    L, H = g.overall_length_mm, g.base_height_mm
    top = g.tip_top_y_mm
    xl = L - g.tip_width_mm
    dim(d, f, (xl, top), (L, top), "h", "top", 0, plus_minus(g.tip_width_mm, tol.contact_face_mm),
        "tip_width")
    dim(d, f, (g.hinge_x_mm, H), (g.tip_centre_x_mm, top), "h", "top", 1,
        plus_minus(g.arm_length_mm, tol.arm_length_mm), "arm_length")
    dim(d, f, (0.0, H), (L, top), "h", "top", 2, fmt_mm(L), "overall_length")
    d.sheet.line("centre-lines", f.paper(g.tip_centre_x_mm, top - g.tip_height_mm / 2),
                 f.paper(g.tip_centre_x_mm, top + 0.3), "centre")
    d.sheet.line("centre-lines", f.paper(g.hinge_x_mm, g.notch_centre_y_mm - 1.3 * g.notch_radius_mm),
                 f.paper(g.hinge_x_mm, H + 0.3), "centre")
    xr = xl - g.inside_corner_radius_mm
    dim(d, f, (L, g.arm_underside_y_mm), (xr, H), "v", "right", 0, fmt_mm(g.arm_height_mm),
         "arm_height")
    dim(d, f, (xr, H), (L, top), "v", "right", 0, fmt_mm(g.tip_height_mm), "tip_height")
    dim(d, f, (g.base_length_mm, 0.0), (L, top), "v", "right", 1, fmt_mm(top),
         "overall_height")
    holes = holes_seen(d.spec, solid, d.cameras)
    hole_dims_linear(d, f, holes, (0.0, 0.0))
    dim(d, f, (0.0, 0.0), (0.0, H), "v", "left", 1, fmt_mm(H), "base_height")
    hole_marks(d, f, holes)
    hole_callout(d, f, holes, (g.base_length_mm + g.notch_radius_mm * 2 + 0.8,
                                g.arm_underside_y_mm * 0.35))
    # tip-root radius, leader from the empty side
    fil = next(s for s in d.spec.profile.outer if isinstance(s, Arc) and not s.ccw
               and abs(s.radius - g.inside_corner_radius_mm) < 1e-9)
    c = f.paper(*fil.centre)
    d.sheet.radius_dimension(c, fil.radius * f.scale, -45.0, f"R{fmt_mm(fil.radius)}",
                             "corner_radius", dist=-10.0, shoulder_right=False)
    d.dimensions["corner_radius"] = f"R{fmt_mm(fil.radius)}"
    # detail A: the web
    dv = d.views["detail"]
    xh = g.hinge_x_mm
    yc = g.notch_centre_y_mm
    d.sheet.centre_mark("centre-lines", dv.paper(xh, yc), 3.0)
    wt = web_text(g)
    d.sheet.linear_dimension(dv.paper(xh, yc + g.notch_radius_mm), dv.paper(xh, H), "v",
                             dv.paper(xh, 0)[0], wt, "web_thickness")
    d.dimensions["web_thickness"] = wt
    rtext = f"R{plus_minus(g.notch_radius_mm, tol.notch_radius_mm)}"
    d.sheet.radius_dimension(dv.paper(xh, yc), g.notch_radius_mm * dv.scale, 60.0, rtext,
                             "notch_radius", dist=-10.0, shoulder_right=True)
    d.dimensions["notch_radius"] = rtext
    # contact face, in the view from above
    t = d.views["top"]
    cf = (f"contact face {plus_minus(g.contact_face_mm[0], tol.contact_face_mm)} × "
          f"{plus_minus(g.contact_face_mm[1], tol.sheet_thickness_mm)}")
    p0 = t.paper(g.tip_centre_x_mm, -g.sheet_thickness_mm / 2)
    p1 = (t.paper_box()[2] + 6.0, t.paper_box()[3] + 8.0)
    d.sheet.leader([p0, p1], cf, "contact_face")
    d.dimensions["contact_face"] = cf
    thickness_dim(d, tol=tol.sheet_thickness_mm)


def clamp_dims(d: Drawing, solid) -> None:
    """U clamp plate: the generic set plus window width and bridge height."""
    c = d.plan.clamp
    f = d.front
    dim(d, f, (-c.window_half_width_mm, c.height_mm), (c.window_half_width_mm, c.height_mm),
         "h", "top", 0, fmt_mm(2 * c.window_half_width_mm), "window_width")
    dim(d, f, (c.half_length_mm, 0.0), (c.window_half_width_mm, c.bridge_height_mm), "v", "right",
         0, fmt_mm(c.bridge_height_mm), "bridge_height")
    generic_dims(d, solid, top_k=1, right_k=1)


def round_outline(d: Drawing, solid) -> float | None:
    """Diameter of the front view's outline if it is a circle (a turned part
    seen along its axis): an outer cylinder coaxial with the view direction
    whose diameter equals both sizes of the view."""
    if d.spec.profile is not None:
        return None
    f = d.front
    u0, v0, u1, v1 = f.bbox
    if abs((u1 - u0) - (v1 - v0)) > 1e-6:
        return None
    direction, _ = d.cameras["front"]
    dv = np.array(direction, float)
    for face in solid.faces():
        if face.geom_type.name != "CYLINDER":
            continue
        ax = face.axis_of_rotation
        if ax is None or abs(abs(np.array(tuple(ax.direction)) @ dv) - 1.0) > 1e-6:
            continue
        if abs(2 * face.radius - (u1 - u0)) < 1e-6:
            return 2 * face.radius
    return None


def generic_dims(d: Drawing, solid, top_k: int = 0, right_k: int = 0) -> None:
    """Any fabricated part: overall length / height in the front view (a
    diameter for a turned part seen along its axis), thickness in the view
    from above, inside radii, and its holes (concentric holes of a round part
    by diameter only; linear dimensions from the lower-left datum for up to
    two holes on one line; else a hole table)."""
    f = d.front
    u0, v0, u1, v1 = f.bbox
    outer = round_outline(d, solid)
    if outer is not None:
        dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, f"Ø{fmt_mm(outer)}", "outer_diameter")
    else:
        dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, fmt_mm(u1 - u0), "overall_length")
        dim(d, f, (u1, v0), (u1, v1), "v", "right", right_k, fmt_mm(v1 - v0), "overall_height")
    thickness_dim(d)
    holes = holes_seen(d.spec, solid, d.cameras)
    centre = ((u0 + u1) / 2, (v0 + v1) / 2)
    if holes and outer is not None and all(abs(h.x - centre[0]) < 1e-6 and abs(h.y - centre[1]) < 1e-6
                                           for h in holes):
        hole_marks(d, f, holes)
        hole_callout(d, f, holes, (centre[0] + (u1 - u0) * 0.3, v1 + (v1 - v0) * 0.05))
    elif holes:
        hole_marks(d, f, holes)
        if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
            hole_dims_linear(d, f, holes, (u0, v0))
            hole_callout(d, f, holes, ((u0 + u1) / 2, v1 - (v1 - v0) * 0.15))
        else:
            datum = (0.0, 0.0) if (u0 - 1e-9 <= 0 <= u1 + 1e-9 and v0 - 1e-9 <= 0 <= v1 + 1e-9) \
                else (u0, v0)
            hole_table(d, f, holes, datum)
    radius_callouts(d, inside_radii(d.spec))


def gauge_note(plan: Plan, g) -> str:
    """Where the strain gauge goes: its grid (``[readout]``) centred over the web."""
    from tactcad.design.readout import readout_of

    ro = readout_of(plan.raw, plan.strength.gauge)
    return (f"A strain gauge (grid {fmt_mm(ro.grid_length_mm)} x {fmt_mm(ro.grid_width_mm)}, "
            f"{ro.gauge_resistance_ohm:g} ohm) is bonded on the flat top face, its grid centred "
            f"over the web {fmt_mm(g.hinge_x_mm)} from the back face and across the sheet.")


def element_notes(d: Drawing) -> list[str]:
    """Flexure element: the web as the critical dimension, wire EDM, edges, use, strength limit."""
    plan, spec = d.plan, d.spec
    n: list[str] = []
    g = spec.geometry
    used = [s.number for s in plan.slots if s.geometry.part_name == spec.name]
    a, k0, k1, ratio = largest_equal_arm_spread()
    up, dn = web_tolerance_stiffness_change(g.web_thickness_mm, g.web_tolerance_mm)
    n.append(web_tolerance_note(plan, g, web_text(g), up, dn, (a, k0, k1, ratio)))
    n.append(f"Wire EDM from {fmt_mm(g.sheet_thickness_mm)} mm {spec.material} sheet along "
             f"the nominal contour of {Path(profile_dxf_name(spec.name, len(used))).name} "
             f"(or the nested sheet {Path(sheet_dxf_name(spec.material, g.sheet_thickness_mm)).name})"
             + f"; wire offset is the shop's CAM setting. Start holes "
             f"Ø{fmt_mm(g.start_hole_diameter_mm)} at the bolt-hole centres.")
    n.append(f"Inside corners not dimensioned: R >= {fmt_mm(plan.edm.min_inside_radius_mm)} "
             f"(wire radius + spark gap). Do not break the edges of the web or of the "
             f"contact face; deburr elsewhere.")
    n.append(f"Used as array element{'s' if len(used) > 1 else ''} "
             + ", ".join(str(k) for k in used)
             + f". {gauge_note(plan, g)}")
    n.append(full_scale_note(plan, spec.name, plan.material.yield_strength_MPa,
                             plan.material.grade or plan.material.name))
    e_tol = tolerances_of(plan.raw).youngs_modulus_rel
    n.append(f"Young's modulus {plan.material.youngs_modulus_MPa:g} MPa "
             f"±{100 * e_tol:g} %: check the sheet's mill certificate.")
    return n


def spacer_notes(d: Drawing) -> list[str]:
    """Spacer: it sets the pitch."""
    plan = d.plan
    return [f"{sentence(d.spec.process)}, {d.spec.material}. Thickness "
            f"{fmt_mm(plan.spacer.thickness_mm)} = pitch {fmt_mm(plan.pitch_mm)} - sheet "
            f"{fmt_mm(plan.sheet_thickness_mm)}: it sets the array pitch; faces parallel "
            f"within 0.01 (ISO 1101)."]


def clamp_notes(d: Drawing) -> list[str]:
    """Clamp plate: stock, window corners, bolt clearance."""
    bolt = d.plan.bolt
    return [f"{sentence(d.spec.process)} from {fmt_mm(part_thickness(d.spec))} mm "
            f"{d.spec.material} plate. Window corners R = cutter radius. Holes "
            f"Ø{fmt_mm(bolt.clearance_hole_mm)}: ISO 273 medium clearance for {bolt.size}."]


def process_note(d: Drawing) -> list[str]:
    """Any other part: its process and material."""
    return [f"{sentence(d.spec.process)}, {d.spec.material}."]


def sentence(text: str) -> str:
    """``text`` with its first letter in capitals."""
    return text[:1].upper() + text[1:]


def _no_plan_values(plan: Plan, spec: PartSpec) -> tuple:
    return ()


def element_detail(spec: PartSpec):
    """(centre, radius) of the web detail A in model mm."""
    g = spec.geometry
    r = 1.6 * (g.notch_radius_mm + g.web_thickness_mm)
    return (g.hinge_x_mm, g.notch_centre_y_mm + 0.35 * g.notch_radius_mm + 0.5 * g.web_thickness_mm), r


@dataclass(frozen=True)
class PartDrawing:
    """What one part family's drawing shows beyond the common sheet, under its builder key.

    Attributes:
        dimensions: the dimension set, ``(drawing, solid) -> None``.
        notes: the family's notes, ``drawing -> [sentence]`` (the general
            tolerance note follows them).
        section: a section view added after the main views, or None.
        cameras: fixed view directions, or None (sketch plane, else by bounding box).
        detail: ``spec -> (centre, radius)`` of a detail view in model mm, or None.
        hole_table: whether many holes go in a coordinate table.
        plan_values: ``(plan, spec) -> tuple`` of the plan values the notes
            and dimensions print (they are part of the drawing's hash).
    """

    dimensions: Callable[[Drawing, object], None] = generic_dims
    notes: Callable[[Drawing], list[str]] = process_note
    section: Callable[[Drawing, object], None] | None = None
    cameras: dict | None = None
    detail: Callable[[PartSpec], tuple | None] | None = None
    hole_table: bool = True
    plan_values: Callable[[Plan, PartSpec], tuple] = _no_plan_values


def _element_values(plan: Plan, spec: PartSpec) -> tuple:
    from tactcad.design.readout import readout_of

    used = tuple(s.number for s in plan.slots if s.geometry.part_name == spec.name)
    return (spec.geometry, used, plan.edm, plan.material, plan.strength,
            readout_of(plan.raw, plan.strength.gauge))


GENERIC = PartDrawing()

#: The drawing of each part family by builder key; any other: :data:`GENERIC`.
DRAWINGS: dict[str, PartDrawing] = {
    "element": PartDrawing(element_dims, element_notes, detail=element_detail, hole_table=False,
                           plan_values=_element_values),
    "spacer": PartDrawing(notes=spacer_notes, plan_values=lambda plan, spec: (
        plan.spacer, plan.pitch_mm, plan.sheet_thickness_mm)),
    "clamp_plate": PartDrawing(clamp_dims, clamp_notes,
                               plan_values=lambda plan, spec: (plan.clamp, plan.bolt)),
}


def drawing_of(spec: PartSpec) -> PartDrawing:
    """The :class:`PartDrawing` of a part's family: :data:`DRAWINGS`, a part
    module's :class:`~tactcad.partlib.base.DrawingRecord`, else :data:`GENERIC`."""
    if spec.builder in DRAWINGS:
        return DRAWINGS[spec.builder]
    part = next((p for p in rig_parts_lib().values() if p.builder_key == spec.builder), None)
    if part is not None and part.drawing is not None:
        return _from_record(part.drawing)
    return GENERIC


#: What a part module's drawing (:class:`~tactcad.partlib.base.DrawingRecord`)
#: draws with: the dimensioning helpers of this layer, handed over so that the
#: part modules, which sit above it, import none of it.
PEN = SimpleNamespace(
    dim=dim, hole_marks=hole_marks, Hole2D=Hole2D, thickness_dim=thickness_dim,
    generic_dims=generic_dims, section_marks=section_marks, add_section=add_section, fmt_mm=fmt_mm,
    thread_text=thread_text, tap_drill_mm=tap_drill_mm, FIRST_TIER=FIRST_TIER, TIER=TIER)


@functools.cache
def _from_record(record: DrawingRecord) -> PartDrawing:
    """The part module's drawing: its dimension set (else the general one) and
    section drawn with :data:`PEN`, its notes around the process note, its
    fixed view directions."""
    def dimensions(d: Drawing, solid) -> None:
        record.dimensions(d, solid, PEN)

    def section(d: Drawing, solid) -> None:
        record.section(d, solid, PEN)

    def notes(d: Drawing) -> list[str]:
        after = record.notes_after(d.spec.geometry, PEN) if record.notes_after else []
        return list(record.notes) + process_note(d) + after

    return PartDrawing(dimensions if record.dimensions else generic_dims, notes,
                       section=section if record.section else None,
                       cameras=cameras_for(*record.view_from) if record.view_from else None,
                       hole_table=record.hole_table)
