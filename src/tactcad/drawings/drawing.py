"""A part drawing before it is written out (:class:`Drawing`), what it reads
off the part (holes seen end-on, thickness, inside radii, material and finish
texts) and how its views are laid out: projected, scaled to the largest
ISO 5455 scale that fits, placed in first-angle projection, with the web
detail when the part has one."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.catalogue.shop import material_designation, stock_size, surface_finish
from tactcad.design.array_plan import ElementGeometry, Plan
from tactcad.drawings.frame import FRAME, TITLE_H, TITLE_W
from tactcad.drawings.sheet import LABEL_TEXT_MM, Sheet, fmt_mm
from tactcad.drawings.views import (CAMERAS, ISO_5455_SCALES, View, detail, kept_projection,
                                    scale_text)
from tactcad.geometry.profile import Arc

NOTES_TOP = 208.0                    # views stay above this line (higher if the notes need it):
                                     # clear of the title block and its surface symbol
NOTE_LINE = 4.2                      # line pitch of the notes (paper mm)
TIER = 7.0                           # spacing of stacked dimension lines (paper mm)
FIRST_TIER = 9.0                     # first dimension line from the view outline
MARGIN = {"top": 3 * TIER + FIRST_TIER + 4, "left": 3 * TIER + FIRST_TIER + 4,
          "right": 2 * TIER + FIRST_TIER + 6, "below": 2 * TIER + FIRST_TIER + 8}


@dataclass
class Hole2D:
    """A round hole seen end-on in the front view (model mm); ``depth`` None
    for a through hole."""

    x: float
    y: float
    d: float
    depth: float | None = None

    @property
    def depth_text(self) -> str:
        """``through`` or ``depth 8`` (mm)."""
        return "through" if self.depth is None else f"depth {fmt_mm(self.depth)}"


@dataclass
class Drawing:
    """Everything one sheet shows, before it is written out."""

    plan: Plan
    spec: PartSpec
    quantity: int
    views: dict[str, View] = field(default_factory=dict)
    scale: float = 1.0
    detail_scale: float = 0.0
    notes: list[str] = field(default_factory=list)
    sheet: Sheet = field(default_factory=lambda: Sheet("A3"))
    dimensions: dict[str, str] = field(default_factory=dict)  # name -> printed text
    cameras: dict = field(default_factory=lambda: dict(CAMERAS))
    notes_top: float = NOTES_TOP
    table_rows: int = 0
    table_beside: bool = False   # the hole table right of the views, not under them
    table_blocks: int = 1        # the hole table's rows in this many blocks side by side
    notes_over_title: bool = False  # the notes over the title block, the table under the views
    #: the tip-height decision the export hands a part with tips
    #: (:class:`tactcad.in_use.tip_height_drawing.TipHeightDrawing`), None: the stated tolerance
    tip_height: Any = None

    @property
    def table_block_rows(self) -> int:
        """Hole rows per block of the hole table (the last block may hold fewer)."""
        return -(-self.table_rows // self.table_blocks)

    @property
    def front(self) -> View:
        return self.views["front"]

    @property
    def right_mm(self) -> float:
        """Paper x the views, their dimensions and any detail or section view
        stay left of: the frame, or the hole table standing beside them."""
        return table_box(self)[0] - 6.0 if self.table_rows and self.table_beside else FRAME[2]



def holes_seen(spec: PartSpec, solid, cameras: dict | None = None) -> list[Hole2D]:
    """Round holes seen end-on in the front view (front-view coordinates):
    from the plan profile, else from the solid's cylindrical faces whose axis
    is parallel to the viewing direction and whose normal faces the axis
    (a bore, not a boss)."""
    if spec.profile is not None:
        return [Hole2D(c.centre[0], c.centre[1], 2 * c.radius) for c in spec.profile.holes]
    from tactcad.kernel.inspect import bores_along

    direction, up = (cameras or CAMERAS)["front"]
    uv = np.array(up, float)
    rv = np.cross(uv, np.array(direction, float))
    out: dict[tuple, Hole2D] = {}
    for bore in bores_along(solid, direction):
        pos = np.array(bore.axis_point)
        depth = bore.blind_depth_mm
        h = Hole2D(round(float(pos @ rv), 6) + 0.0, round(float(pos @ uv), 6) + 0.0,
                   round(bore.diameter_mm, 6), None if depth is None else round(depth, 6))
        out[(h.x, h.y)] = h
    return sorted(out.values(), key=lambda h: (h.y, h.x))


def part_thickness(spec: PartSpec) -> float:
    """Sheet or plate thickness of a profiled part (mm)."""
    if spec.thickness_mm > 0:
        return spec.thickness_mm
    bb = spec.expected_bbox_mm
    return bb[5] - bb[2]


def material_text(spec: PartSpec, plan: Plan | None = None) -> str:
    """Material with alloy and temper and the raw stock:
    ``aluminium EN AW-6061-T6; sheet 3 mm, blank 32 x 20`` (see
    :func:`tactcad.catalogue.shop.material_designation` and
    :func:`tactcad.catalogue.shop.stock_size`)."""
    return f"{material_designation(spec, plan)}; {stock_size(spec)}"


def finish_text(spec: PartSpec) -> str:
    """Surface finish as the title block prints it (ISO 1302 general
    indication): ``Ra 1.6 general; Ra 0.8: contact face, web``."""
    f = surface_finish(spec)
    if not f.general_ra_um:
        return f.reason
    text = f"Ra {f.general_ra_um:g} general"
    for face, ra in f.special:
        text += f"; Ra {ra:g}: {face}"
    return text


def inside_radii(spec: PartSpec) -> list[Arc]:
    """Concave arcs of the profile's outer contour, one per distinct radius."""
    if spec.profile is None:
        return []
    seen: dict[str, Arc] = {}
    for s in spec.profile.outer:
        if isinstance(s, Arc) and not s.ccw:
            seen.setdefault(fmt_mm(s.radius), s)
    return list(seen.values())


def web_text(g: ElementGeometry) -> str:
    """Printed web thickness with its tolerance, e.g. ``0.25 ±0.02``."""
    t = fmt_mm(g.web_thickness_mm)
    return f"{t} ±{fmt_mm(g.web_tolerance_mm)}" if g.web_tolerance_mm > 0 else t


def views_fit(views: dict[str, View], s: float, det_d: float, notes_top: float = NOTES_TOP,
              right: float = FRAME[2]) -> bool:
    """Whether the three views at scale ``s`` (with a detail view ``det_d``
    paper mm across, 0 for none) and their dimension margins fit between the
    frame's left edge and paper x ``right``, and above ``notes_top`` (mm)."""
    f, t, l = views["front"], views["top"], views["left"]
    fw = (f.bbox[2] - f.bbox[0]) * s
    fh = (f.bbox[3] - f.bbox[1]) * s
    lw = (l.bbox[2] - l.bbox[0]) * s
    th = (t.bbox[3] - t.bbox[1]) * s
    width = MARGIN["left"] + fw + MARGIN["right"] + lw + 12 + (det_d + 30 if det_d else 0)
    height = MARGIN["top"] + fh + MARGIN["below"] + th + 14
    return (width <= right - FRAME[0] - 6) and (height <= notes_top - FRAME[1])


TABLE_COLS = (14.0, 22.0, 22.0, 18.0, 22.0)
TABLE_ROW = 6.0
TABLE_BLOCK_GAP = 3.0  # paper mm between the hole table's blocks
#: Most blocks a long hole table is split into (a terminal board's 32 holes: two).
MAX_TABLE_BLOCKS = 3
TABLE_BESIDE_BOTTOM = FRAME[3] - TITLE_H - 14.0  # a table beside the views ends above the finish symbol


def table_box(d: Drawing) -> tuple[float, float, float, float]:
    """(left, top, width, height) on paper (mm) of the hole table's
    ``d.table_rows`` rows and its head: under the views, between the notes
    and the title block (clear of the centring mark); or, with
    ``d.table_beside``, in the right column over the title block."""
    w = d.table_blocks * sum(TABLE_COLS) + (d.table_blocks - 1) * TABLE_BLOCK_GAP
    h = TABLE_ROW * (d.table_block_rows + 1)
    if d.table_beside:
        # clear of the centring mark, and of the finish symbol when it reaches over it
        bottom = TABLE_BESIDE_BOTTOM if w <= TITLE_W - 30.0 else TABLE_BESIDE_BOTTOM - 5.0
        return (FRAME[2] - 6.0 - w, bottom - h, w, h)
    if d.notes_over_title:  # from the frame's left, the notes gone over the title block
        return (FRAME[0] + 5.5, FRAME[3] - 8.0 - h, w, h)
    return (FRAME[2] - TITLE_W - 4.0 - w, FRAME[3] - 8.0 - h, w, h)


def project_views(d: Drawing, solid) -> dict[str, View]:
    """The front, top and left views of ``solid`` in the drawing's cameras.

    A part with a plan profile is drawn in its sketch plane (front view from
    +z); any other part from the axis of its smallest extent (see
    :func:`tactcad.drawings.views.orientation`). Each view is kept in the result store
    by the part's spec (:func:`tactcad.drawings.views.kept_projection`)."""
    return {name: kept_projection(d.spec, solid, name, d.cameras)
            for name in ("front", "top", "left")}


def largest_scale(views: dict[str, View], det: tuple | None, notes_top: float,
                  right: float) -> float:
    """The largest ISO 5455 scale at which the views fit (:func:`views_fit`),
    else the smallest; ``det``: (centre, radius) of the detail view in model
    mm, or None."""
    for s in ISO_5455_SCALES:
        ds = smallest_detail_scale(s) if det else 0.0
        if views_fit(views, s, 2 * det[1] * ds if det else 0.0, notes_top, right):
            return s
    return ISO_5455_SCALES[-1]


def layout(d: Drawing, views: dict[str, View], det: tuple | None = None) -> None:
    """Pick the largest ISO 5455 scale at which the projected ``views`` fit
    (:func:`largest_scale`) and place them. ``det``: (centre, radius) of the
    detail view in model mm, or None for none."""
    chosen = largest_scale(views, det, d.notes_top, d.right_mm)
    d.scale = chosen
    for v in views.values():
        v.scale = chosen
    f, t, l = views["front"], views["top"], views["left"]
    left = FRAME[0] + MARGIN["left"]
    top = FRAME[1] + MARGIN["top"]
    f.place(left, top)
    fb = f.paper_box()
    # first angle: view from above below the front view, view from the left on its right
    t.origin = (f.origin[0], fb[3] + MARGIN["below"] + t.bbox[3] * chosen)
    l.origin = (fb[2] + MARGIN["right"] - l.bbox[0] * chosen, f.origin[1])
    d.views = {"front": f, "top": t, "left": l}
    if det:
        lb = l.paper_box()
        left_d = lb[2] + 28.0
        room = min(d.right_mm - 8.0 - left_d, d.notes_top - top - 16.0, 150.0)
        fitting = [s for s in ISO_5455_SCALES if s >= 4 * chosen - 1e-9 and 2 * det[1] * s <= room]
        d.detail_scale = max(fitting) if fitting else smallest_detail_scale(chosen)
        dv = detail(f, det[0], det[1], d.detail_scale, "A")
        dv.place(left_d, top)
        d.views["detail"] = dv


def smallest_detail_scale(main: float) -> float:
    """Smallest ISO 5455 scale at least four times the main scale."""
    cands = [s for s in ISO_5455_SCALES if s >= 4 * main - 1e-9]
    return min(cands) if cands else ISO_5455_SCALES[0]


def draw_views(d: Drawing) -> None:
    sh = d.sheet
    for name, v in d.views.items():
        g = f"view-{name}"
        for poly in v.hidden:
            sh.polyline(g, [v.paper(*p) for p in poly], "hidden", cls="hidden")
        for poly in v.visible:
            sh.polyline(g, [v.paper(*p) for p in poly], "visible", cls="visible")
        for poly in v.hatch:
            sh.polyline(g, [v.paper(*p) for p in poly], "thin", cls="hatch")
    dv = d.views.get("detail")
    if dv is not None:
        (cu, cv), r = dv.clip
        f = d.front
        sh.circle("view-front", f.paper(cu, cv), r * f.scale, "boundary")
        lab = f.paper(cu - r * 0.72, cv + r * 0.72)
        sh.text("view-front", (lab[0] - 1.0, lab[1] - 1.0), "A", LABEL_TEXT_MM, anchor="end",
                id="detail-mark")
        sh.circle("view-detail", dv.paper(cu, cv), r * dv.scale, "boundary")
        bx = dv.paper(cu, cv - r)
        sh.text("view-detail", (bx[0], bx[1] + 8.0), f"A ({scale_text(dv.scale)})",
                LABEL_TEXT_MM, anchor="middle", id="detail-label")


