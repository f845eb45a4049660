"""Indenter of the force gauge (a made part): a cylindrical body screwed onto
the gauge's shaft end and a rectangular tip whose end face is the contact
area (paper: the same contact area as a sensing element, 2 mm x 3 mm).

The indenter follows the array's element unless the ``[indenter]`` table sets
its sizes: contact face = the element's contact face, body >= the face's
diagonal + 1 mm (8 mm at least), tip longer than the element tip's height
(3 mm at least). It screws onto the gauge's measuring shaft (Sauter FH
attachments have an M6 female thread; ``force_gauge.shaft_diameter_mm`` = 6):
a tapped M6 hole in the body's top face, as deep as the body less 2 mm of
floor above the tip, at most 1.5 d (full strength in steel by 1 d; the load
is at most the gauge's 5 N range).

Part frame: contact face at z = 0 (centred), tip along +z, then the body;
the contact width along x, the depth along y. Units: mm.
"""

from __future__ import annotations

import math
from typing import Optional

from tactcad.partlib.base import DrawingRecord, PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box, cylinder, fuse, single
from tactcad.partlib.stock import INDENTER_STEEL
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, number

COLOR = (0.85, 0.65, 0.20)
#: Smallest body diameter and tip length when the rigs file gives none, mm.
INDENTER_BODY_MM = 8.0
INDENTER_TIP_MM = 3.0
INDENTER_THREAD_DIAMETER_MM = 6.0
INDENTER_THREAD_FLOOR_MM = 2.0


class IndenterSection(Section):
    """``[indenter]`` of ``rigs.toml``: sizes left out follow the array."""

    contact_width_mm: Optional[number(0.5, 20.0)] = None  # default: the element's contact face
    contact_depth_mm: Optional[number(0.5, 20.0)] = None
    tip_length_mm: Optional[number(0.5, 30.0)] = None  # default: clears the element tips
    body_diameter_mm: Optional[number(1.0, 50.0)] = None  # default: carries the contact face
    body_length_mm: number(1.0, 50.0)


class IndenterGeometry(table_values(IndenterSection)):
    """The indenter, every size filled in (mm)."""


def indenter_thread_depth_mm(g) -> float:
    """Depth (mm) of the indenter's M6 mounting thread (see the module doc)."""
    return min(g.body_length_mm - INDENTER_THREAD_FLOOR_MM, 1.5 * INDENTER_THREAD_DIAMETER_MM)


def derive(i: IndenterSection, context, p: Problems) -> PartData:
    """The indenter for the array's element (``context.plan``)."""
    plan = context.plan
    face_w, face_d = plan.slots[0].geometry.contact_face_mm
    tip_h = plan.slots[0].geometry.tip_height_mm
    w = face_w if i.contact_width_mm is None else p.within(
        "indenter.contact_width_mm", i.contact_width_mm, face_w, face_w,
        why="the indenter's face is the element's contact face (element.tip_width_mm); leave it "
            "out to follow the design")
    d = face_d if i.contact_depth_mm is None else p.within(
        "indenter.contact_depth_mm", i.contact_depth_mm, face_d, face_d,
        why="the indenter's face is the element's contact face (sheet.thickness_mm); leave it "
            "out to follow the design")
    diagonal = math.hypot(w, d)
    body = max(INDENTER_BODY_MM, math.ceil(diagonal + 1.0)) if i.body_diameter_mm is None else \
        p.within("indenter.body_diameter_mm", i.body_diameter_mm, diagonal,
                 why="the tip must sit inside the body")
    tip_len = max(INDENTER_TIP_MM, tip_h + 0.5) if i.tip_length_mm is None else \
        p.within("indenter.tip_length_mm", i.tip_length_mm, tip_h,
                 why="the body must clear the neighbouring element tips (element.tip_height_mm)")
    g = values_from(IndenterGeometry, i, contact_width_mm=w, contact_depth_mm=d,
                    tip_length_mm=tip_len, body_diameter_mm=body)
    top = g.tip_length_mm + g.body_length_mm
    rr = g.body_diameter_mm / 2
    return PartData(
        name="indenter", kind="fabricated",
        process=Process(f"turning and milling, {w:g} x {d:g} mm contact face", Method.ROUND_BAR),
        material=INDENTER_STEEL, color=COLOR,
        expected_volume_mm3=w * d * g.tip_length_mm + math.pi * rr * rr * g.body_length_mm
        - math.pi * (INDENTER_THREAD_DIAMETER_MM / 2) ** 2 * indenter_thread_depth_mm(g),
        expected_bbox_mm=(-float(rr), -float(rr), 0.0, float(rr), float(rr), float(top)),
        geometry=g,
        frames={"mount": Seat((0, 0, top), (0, 0, 1), (1, 0, 0)),
                "contact": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0))})


def build(g: IndenterGeometry):
    """Tip (contact face at z = 0) fused with the body above it, and the
    tapped M6 hole in the body's top face, modelled at the thread's nominal
    diameter (build123d ``Solid``; see :func:`indenter_thread_depth_mm`)."""
    w, d, L = g.contact_width_mm, g.contact_depth_mm, g.tip_length_mm
    tip = box(-w / 2, -d / 2, 0, w / 2, d / 2, L)
    body = cylinder(g.body_diameter_mm / 2, (0, 0, L), (0, 0, 1), g.body_length_mm)
    depth = indenter_thread_depth_mm(g)
    top = L + g.body_length_mm
    thread = cylinder(INDENTER_THREAD_DIAMETER_MM / 2, (0, 0, top - depth), (0, 0, 1), depth)
    return single(fuse(tip, body).cut(thread))


def section(d, solid, pen) -> None:
    """Section A-A of the shop drawing: through the axis (plane y = 0, seen
    from +y, as the front view), showing the blind tapped hole."""
    g = d.spec.geometry
    pen.add_section(d, solid, (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), g.body_diameter_mm,
                    g.tip_length_mm + g.body_length_mm)


def dimensions(d, solid, pen) -> None:
    """The shop drawing's dimension set (drawn with the drawings layer's
    ``pen``): the contact face in the front view (width) and the view from
    the left (depth), tip and body lengths, body diameter, the mounting
    thread in section A-A."""
    g, fmt_mm, dim = d.spec.geometry, pen.fmt_mm, pen.dim
    f, left = d.front, d.views["left"]
    w, dp, L = g.contact_width_mm, g.contact_depth_mm, g.tip_length_mm
    D, B = g.body_diameter_mm, g.body_length_mm
    # front view: u = -x, v = z; view from the left: u = y, v = z
    dim(d, f, (w / 2, 0.0), (-w / 2, 0.0), "h", "below", 0, fmt_mm(w), "contact_width")
    dim(d, left, (-dp / 2, 0.0), (dp / 2, 0.0), "h", "below", 0, fmt_mm(dp), "contact_depth")
    dim(d, f, (D / 2, L + B), (-D / 2, L + B), "h", "top", 0, f"Ø{fmt_mm(D)}", "body_diameter")
    dim(d, f, (-w / 2, 0.0), (-w / 2, L), "v", "right", 0, fmt_mm(L), "tip_length")
    dim(d, f, (-D / 2, L), (-D / 2, L + B), "v", "right", 0, fmt_mm(B), "body_length")
    dim(d, f, (-w / 2, 0.0), (-D / 2, L + B), "v", "right", 1, fmt_mm(L + B), "overall_height")
    fb = f.paper_box()
    depth = indenter_thread_depth_mm(g)
    th = (f"{pen.thread_text(INDENTER_THREAD_DIAMETER_MM, depth)} (tap drill "
          f"Ø{fmt_mm(pen.tap_drill_mm(INDENTER_THREAD_DIAMETER_MM))}), onto the gauge shaft")
    sv = d.views.get("section", f)
    sb = sv.paper_box()
    rt = INDENTER_THREAD_DIAMETER_MM / 2
    d.sheet.leader([sv.paper(rt, L + B - depth / 2), (sb[2] + pen.FIRST_TIER + pen.TIER, sb[1] - 8.0)],
                   th, "mount_thread")
    d.dimensions["mount_thread"] = th
    if sv is not f:
        dim(d, sv, (-rt, L + B), (-rt, L + B - depth), "v", "right", 0, fmt_mm(depth),
            "thread_depth")
        pen.section_marks(d, "top", "A-A")
    cf = f"contact face {fmt_mm(w)} × {fmt_mm(dp)}"
    d.sheet.leader([f.paper(0.0, 0.0), (fb[2] + 4.0, fb[3] + 18.0)], cf, "contact_face")
    d.dimensions["contact_face"] = cf


def notes_after(g: IndenterGeometry, pen) -> list[str]:
    """The shop drawing's note after the process note: the mounting thread
    and the contact face."""
    return ["The M6 thread screws the indenter onto the force gauge's measuring shaft; "
            "contact face perpendicular to the thread axis within 0.02 (ISO 1101), so the "
            f"{pen.fmt_mm(g.contact_width_mm)} x {pen.fmt_mm(g.contact_depth_mm)} mm face lies "
            "flat on the element's tip."]


PART = RigPart(key="indenter", section=IndenterSection, host="", derive=derive, build=build,
               order=50,
               drawing=DrawingRecord(hole_table=False, dimensions=dimensions, section=section,
                                     notes_after=notes_after,
                                     view_from=((0.0, 1.0, 0.0), (0.0, 0.0, 1.0))))
