"""One fabrication drawing per fabricated part: views, dimensions, notes, title block.

A3 landscape sheet (ISO 5457 frame: 20 mm filing margin on the left, 10 mm
elsewhere), title block at the bottom right after ISO 7200, first-angle
projection (ISO 128-30), dimensions after ISO 129-1 taken from the plan (or,
for a part without a plan profile, measured on its solid), untoleranced
dimensions to ISO 2768-f.

Dimension sets are chosen by the part's builder key (``PartSpec.builder``):
:data:`DIMENSION_SETS` names the special ones; any other fabricated part gets
the generic set (overall sizes, thickness, inside radii, holes).
"""

from __future__ import annotations

import csv
import hashlib
import math

import numpy as np
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from tactcad.catalogue.array import PartSpec
from tactcad.design.array import ElementGeometry, Plan
from tactcad.store import stable_repr
from tactcad.catalogue.files import profile_dxf_name, sheet_dxf_name
from tactcad.catalogue.shop import material_designation, stock_size, surface_finish
from tactcad.geometry.profile import Arc
from tactcad.design.tolerances import tolerances_of
from tactcad.drawings.design_notes import full_scale_note, web_tolerance_note
from tactcad.drawings.sheet import DIM_TEXT_MM, LABEL_TEXT_MM, Sheet, fmt_mm, text_width
from tactcad.drawings.views import (CAMERAS, ISO_5455_SCALES, View, cameras_for, detail, orientation, project,
                    scale_text)

GENERAL_TOLERANCE = "ISO 2768-f"


def general_tolerance(plan: Plan) -> str:
    """The design's general tolerance class (``[tolerances] general``), e.g. ``ISO 2768-f``."""
    return tolerances_of(plan.raw).general_text


def pm(value: float, tol: float) -> str:
    """A dimension with its symmetric tolerance, ``19.8 ±0.02`` (no tolerance: the value)."""
    return f"{fmt_mm(value)} ±{fmt_mm(tol)}" if tol > 0 else fmt_mm(value)
FRAME = (20.0, 10.0, 410.0, 287.0)  # left, top, right, bottom (A3, ISO 5457)
TITLE_W, TITLE_H = 180.0, 63.0        # seven rows of 9 mm
NOTES_TOP = 208.0                    # views stay above this line (higher if the notes need it):
                                     # clear of the title block and its surface symbol
NOTE_LINE = 4.2                      # line pitch of the notes (paper mm)
TIER = 7.0                           # spacing of stacked dimension lines (paper mm)
FIRST_TIER = 9.0                     # first dimension line from the view outline
MARGIN = {"top": 3 * TIER + FIRST_TIER + 4, "left": 3 * TIER + FIRST_TIER + 4,
          "right": 2 * TIER + FIRST_TIER + 6, "below": 2 * TIER + FIRST_TIER + 8}
TABLE1 = Path(__file__).resolve().parents[1] / "data" / "table1_calibration.csv"


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

    @property
    def front(self) -> View:
        return self.views["front"]


# ---------------------------------------------------------------------------
# part data
# ---------------------------------------------------------------------------
def _holes(spec: PartSpec, solid, cameras: dict | None = None) -> list[Hole2D]:
    """Round holes seen end-on in the front view (front-view coordinates):
    from the plan profile, else from the solid's cylindrical faces whose axis
    is parallel to the viewing direction and whose normal faces the axis
    (a bore, not a boss)."""
    if spec.profile is not None:
        return [Hole2D(c.centre[0], c.centre[1], 2 * c.radius) for c in spec.profile.holes]
    direction, up = (cameras or CAMERAS)["front"]
    dv = np.array(direction, float)
    uv = np.array(up, float)
    rv = np.cross(uv, dv)
    out: dict[tuple, Hole2D] = {}
    # flat hole bottoms: plane faces bounded by one circle (a blind hole's floor)
    floors = []
    for f in solid.faces():
        es = f.edges()
        if f.geom_type.name == "PLANE" and len(es) == 1 and es[0].geom_type.name == "CIRCLE":
            floors.append((np.array(tuple(es[0].arc_center)), es[0].radius))
    for f in solid.faces():
        if f.geom_type.name != "CYLINDER":
            continue
        ax = f.axis_of_rotation
        a = np.array(tuple(ax.direction)) if ax is not None else None
        if a is None or abs(abs(a @ dv) - 1.0) > 1e-6:
            continue
        if not any(e.geom_type.name == "CIRCLE" and e.is_closed for e in f.edges()):
            continue  # a fillet (quarter cylinder) of a pocket or window, not a hole
        c = f.center()
        n = np.array(tuple(f.normal_at(c)))
        pos = np.array(tuple(ax.position))
        to_axis = pos - np.array(tuple(c))
        to_axis -= (to_axis @ a) * a
        if n @ to_axis <= 0:  # normal away from the axis: a boss
            continue
        along = [float(np.array(tuple(v)) @ dv) for v in f.vertices()]
        blind = any(abs(r - f.radius) < 1e-6
                    and np.linalg.norm(np.cross(c - pos, a)) < 1e-6 for c, r in floors)
        span = max(along) - min(along) if along else 0.0
        h = Hole2D(round(float(pos @ rv), 6) + 0.0, round(float(pos @ uv), 6) + 0.0,
                   round(2 * f.radius, 6), round(span, 6) if blind and span > 0 else None)
        out[(h.x, h.y)] = h
    return sorted(out.values(), key=lambda h: (h.y, h.x))


def _thickness(spec: PartSpec) -> float:
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


def revision_and_date(plan: Plan) -> tuple[str, str]:
    """(revision, date) of the drawing: the design file's ``[design]``
    ``revision`` and ``date`` when given, else ``A`` and ``—``. Never today's
    date: the same design writes the same bytes."""
    table = plan.raw.get("design", {}) if isinstance(plan.raw, dict) else {}
    rev = str(table.get("revision", "") or "A")
    date = str(table.get("date", "") or "—")
    return rev, date


def _inside_radii(spec: PartSpec) -> list[Arc]:
    """Concave arcs of the profile's outer contour, one per distinct radius."""
    if spec.profile is None:
        return []
    seen: dict[str, Arc] = {}
    for s in spec.profile.outer:
        if isinstance(s, Arc) and not s.ccw:
            seen.setdefault(fmt_mm(s.radius), s)
    return list(seen.values())


def table1_spread() -> tuple[float, float, float, float]:
    """Largest stiffness spread among Table 1 elements of equal arm length.

    Returns:
        (arm length mm, lowest K, highest K in N/mm, highest / lowest).
    """
    groups: dict[float, list[float]] = {}
    with open(TABLE1, newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            groups.setdefault(float(row["flexing_arm_length_mm"]), []).append(
                float(row["stiffness_N_per_mm"]))
    best = max((g for g in groups.items() if len(g[1]) > 1), key=lambda g: max(g[1]) / min(g[1]))
    a, ks = best
    return a, min(ks), max(ks), max(ks) / min(ks)


def web_text(g: ElementGeometry) -> str:
    """Printed web thickness with its tolerance, e.g. ``0.25 ±0.02``."""
    t = fmt_mm(g.web_thickness_mm)
    return f"{t} ±{fmt_mm(g.web_tolerance_mm)}" if g.web_tolerance_mm > 0 else t


# ---------------------------------------------------------------------------
# layout
# ---------------------------------------------------------------------------
def _detail_params(spec: PartSpec, plan: Plan):
    """(centre, radius) of the web detail in model mm, or None."""
    if spec.builder != "element":
        return None
    g = plan.distinct_elements[spec.name]
    r = 1.6 * (g.notch_radius_mm + g.web_thickness_mm)
    return (g.hinge_x_mm, g.notch_centre_y_mm + 0.35 * g.notch_radius_mm + 0.5 * g.web_thickness_mm), r


def _fits(views: dict[str, View], s: float, det_d: float, notes_top: float = NOTES_TOP) -> bool:
    f, t, l = views["front"], views["top"], views["left"]
    fw = (f.bbox[2] - f.bbox[0]) * s
    fh = (f.bbox[3] - f.bbox[1]) * s
    lw = (l.bbox[2] - l.bbox[0]) * s
    th = (t.bbox[3] - t.bbox[1]) * s
    width = MARGIN["left"] + fw + MARGIN["right"] + lw + 12 + (det_d + 30 if det_d else 0)
    height = MARGIN["top"] + fh + MARGIN["below"] + th + 14
    return (width <= FRAME[2] - FRAME[0] - 6) and (height <= notes_top - FRAME[1])


def choose_cameras(spec: PartSpec) -> dict:
    """View set of a part: fixed for builders in :data:`CAMERA_SETS`, the
    sketch plane for a profiled part, else by its bounding box."""
    if spec.builder in CAMERA_SETS:
        return CAMERA_SETS[spec.builder]
    if spec.profile is None:
        return orientation(spec.expected_bbox_mm)
    return dict(CAMERAS)


def hole_table_rows(d: Drawing, solid) -> int:
    """Rows of the hole table the generic set will draw (0: none)."""
    if d.spec.builder in ("element", "indenter", "cart"):
        return 0
    holes = _holes(d.spec, solid, d.cameras)
    if not holes or len({(h.x, h.y) for h in holes}) == 1:
        return 0
    if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
        return 0
    return len(holes)


TABLE_COLS = (14.0, 22.0, 22.0, 18.0, 22.0)
TABLE_ROW = 6.0


def layout(d: Drawing, solid) -> None:
    """Project the views, pick the largest ISO 5455 scale that fits, place them.

    A part with a plan profile is drawn in its sketch plane (front view from
    +z); any other part from the axis of its smallest extent (see
    :func:`tactcad.drawings.views.orientation`)."""
    views = {name: project(solid, name, cameras=d.cameras) for name in ("front", "top", "left")}
    det = _detail_params(d.spec, d.plan)
    chosen = ISO_5455_SCALES[-1]
    for s in ISO_5455_SCALES:
        ds = _detail_scale(s) if det else 0.0
        if _fits(views, s, 2 * det[1] * ds if det else 0.0, d.notes_top):
            chosen = s
            break
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
        room = min(FRAME[2] - 8.0 - left_d, d.notes_top - top - 16.0, 150.0)
        fitting = [s for s in ISO_5455_SCALES if s >= 4 * chosen - 1e-9 and 2 * det[1] * s <= room]
        d.detail_scale = max(fitting) if fitting else _detail_scale(chosen)
        dv = detail(f, det[0], det[1], d.detail_scale, "A")
        dv.place(left_d, top)
        d.views["detail"] = dv


def _detail_scale(main: float) -> float:
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


# ---------------------------------------------------------------------------
# dimension helpers (model points -> paper)
# ---------------------------------------------------------------------------
def _tier(view: View, side: str, k: int) -> float:
    """Paper coordinate of the k-th dimension line (k = 0, 1, ...) on a side."""
    x0, y0, x1, y1 = view.paper_box()
    off = FIRST_TIER + k * TIER
    return {"top": y0 - off, "below": y1 + off, "left": x0 - off, "right": x1 + off}[side]


def _dim(d: Drawing, view: View, p, q, axis: str, side: str, k: int, value: str, name: str) -> None:
    d.sheet.linear_dimension(view.paper(*p), view.paper(*q), axis, _tier(view, side, k), value,
                             name)
    d.dimensions[name] = value


def _hole_marks(d: Drawing, view: View, holes: list[Hole2D]) -> None:
    for h in holes:
        d.sheet.centre_mark("centre-lines", view.paper(h.x, h.y), h.d / 2 * view.scale + 2.0)


def _hole_callout(d: Drawing, view: View, holes: list[Hole2D], toward: tuple[float, float]) -> None:
    """One leader per distinct hole size and depth: ``2× Ø2.4 through`` at
    the nearest such hole."""
    by_size: dict[tuple[str, str], list[Hole2D]] = {}
    for h in holes:
        by_size.setdefault((fmt_mm(h.d), h.depth_text), []).append(h)
    for k, ((size, _), hs) in enumerate(by_size.items()):
        h = min(hs, key=lambda h: (h.x - toward[0]) ** 2 + (h.y - toward[1]) ** 2)
        ang = math.atan2(toward[1] - h.y, toward[0] - h.x)
        r = h.d / 2
        p0 = view.paper(h.x + r * math.cos(ang), h.y + r * math.sin(ang))
        p1 = view.paper(*toward)
        p1 = (p1[0], p1[1] + 6.0 * k)
        text = (f"{len(hs)}× " if len(hs) > 1 else "") + f"Ø{size} {h.depth_text}"
        name = "hole_diameter" if len(by_size) == 1 else f"hole_diameter_{k + 1}"
        d.sheet.leader([p0, p1], text, name)
        d.dimensions[name] = text


def _hole_dims_linear(d: Drawing, view: View, holes: list[Hole2D], datum: tuple[float, float],
                      bottom_k: int = 0, left_k: int = 0) -> None:
    """Hole centres from the datum edges: x below the view, y on its left."""
    for i, h in enumerate(sorted(holes, key=lambda h: h.x), start=1):
        _dim(d, view, (datum[0], datum[1]), (h.x, h.y), "h", "below", bottom_k + i - 1,
             fmt_mm(h.x - datum[0]), f"hole_{i}_x")
    ys = sorted({round(h.y, 9) for h in holes})
    for j, y in enumerate(ys):
        h = next(h for h in holes if round(h.y, 9) == y)
        name = "hole_y" if len(ys) == 1 else f"hole_y_{j + 1}"
        _dim(d, view, (datum[0], datum[1]), (h.x, h.y), "v", "left", left_k + j,
             fmt_mm(h.y - datum[1]), name)


def _hole_table(d: Drawing, view: View, holes: list[Hole2D], datum: tuple[float, float]) -> None:
    """Coordinate table of the holes (ISO 129-1 tabular dimensioning), each
    hole labelled on the view, coordinates from the marked origin."""
    sh = d.sheet
    o = view.paper(*datum)
    sh.line("dimensions", (o[0] - 3, o[1]), (o[0] + 3, o[1]))
    sh.line("dimensions", (o[0], o[1] - 3), (o[0], o[1] + 3))
    sh.circle("dimensions", o, 1.2)
    sh.text("dimensions", (o[0] + 1.5, o[1] + 4.5), "0,0", DIM_TEXT_MM, id="hole-origin")
    ordered = sorted(holes, key=lambda h: (h.y, h.x))
    for i, h in enumerate(ordered, start=1):
        c = view.paper(h.x, h.y)
        r = h.d / 2 * view.scale
        sh.text("dimensions", (c[0] + r * 0.7 + 0.8, c[1] - r * 0.7 - 0.8), f"H{i}", DIM_TEXT_MM,
                id=f"hole-label-{i}")
    cols = TABLE_COLS
    x0 = FRAME[2] - TITLE_W - 4 - sum(cols)
    row_h = TABLE_ROW
    y0 = FRAME[3] - 8 - row_h * (len(ordered) + 1)  # clear of the centring mark
    sh.rect("hole-table", x0, y0, sum(cols), row_h * (len(ordered) + 1), "table")
    heads = ("Hole", "X", "Y", "Ø", "Depth")
    for r_i in range(len(ordered) + 2):
        y = y0 + r_i * row_h
        if 0 < r_i < len(ordered) + 1:
            sh.line("hole-table", (x0, y), (x0 + sum(cols), y), "thin")
    x = x0
    for w in cols[:-1]:
        x += w
        sh.line("hole-table", (x, y0), (x, y0 + row_h * (len(ordered) + 1)), "thin")
    def cell(col: int, row: int, text: str, id: str = "") -> None:
        cx = x0 + sum(cols[:col]) + cols[col] / 2
        cy = y0 + row * row_h + row_h / 2 + DIM_TEXT_MM / 2
        sh.text("hole-table", (cx, cy), text, DIM_TEXT_MM, anchor="middle", id=id,
                cls="dim" if id else "")
    for c, hd in enumerate(heads):
        cell(c, 0, hd)
    for i, h in enumerate(ordered, start=1):
        vals = (fmt_mm(h.x - datum[0]), fmt_mm(h.y - datum[1]), fmt_mm(h.d), h.depth_text)
        cell(0, i, f"H{i}")
        for c, (suffix, v) in enumerate(zip(("x", "y", "d", "depth"), vals), start=1):
            cell(c, i, v, f"dim-hole_{i}_{suffix}")
            d.dimensions[f"hole_{i}_{suffix}"] = v
    sh.text("hole-table", (x0, y0 - 2.0), "Hole positions from origin 0,0", DIM_TEXT_MM)


def _thickness_dim(d: Drawing, name: str = "thickness", tol: float = 0.0) -> None:
    t = d.views["top"]
    u1 = t.bbox[2]
    x = max((p[0] for poly in t.visible for p in poly if abs(p[1] - t.bbox[3]) < 1e-6),
            default=u1)
    _dim(d, t, (x, t.bbox[3]), (x, t.bbox[1]), "v", "right", 0,
         pm(t.bbox[3] - t.bbox[1], tol), name)


def _radius_callouts(d: Drawing, arcs: list[Arc], prefix: str = "inside_radius") -> None:
    f = d.front
    for k, a in enumerate(arcs):
        c = f.paper(*a.centre)
        mid = a.midpoint
        ang = math.degrees(math.atan2(mid[1] - a.centre[1], mid[0] - a.centre[0]))
        r = a.radius * f.scale
        text = f"R{fmt_mm(a.radius)}"
        name = prefix if len(arcs) == 1 else f"{prefix}_{k + 1}"
        left = math.cos(math.radians(ang)) > 0
        d.sheet.radius_dimension(c, r, ang, text, name, dist=-max(8.0, 3 * r), shoulder_right=not left)
        d.dimensions[name] = text


# ---------------------------------------------------------------------------
# dimension sets
# ---------------------------------------------------------------------------
def element_dims(d: Drawing, solid) -> None:
    """Flexure element: contact face, arm length, overall sizes, arm and tip
    heights, hole pattern, tip-root radius; the web (thickness with its
    tolerance, notch radius) in detail A."""
    g = d.plan.distinct_elements[d.spec.name]
    tol = tolerances_of(d.plan.raw)  # the table the tolerance study draws from
    f = d.front
    L, H = g.overall_length_mm, g.base_height_mm
    top = g.tip_top_y_mm
    xl = L - g.tip_width_mm
    _dim(d, f, (xl, top), (L, top), "h", "top", 0, pm(g.tip_width_mm, tol.contact_face_mm),
         "tip_width")
    _dim(d, f, (g.hinge_x_mm, H), (g.tip_centre_x_mm, top), "h", "top", 1,
         pm(g.arm_length_mm, tol.arm_length_mm), "arm_length")
    _dim(d, f, (0.0, H), (L, top), "h", "top", 2, fmt_mm(L), "overall_length")
    d.sheet.line("centre-lines", f.paper(g.tip_centre_x_mm, top - g.tip_height_mm / 2),
                 f.paper(g.tip_centre_x_mm, top + 0.3), "centre")
    d.sheet.line("centre-lines", f.paper(g.hinge_x_mm, g.notch_centre_y_mm - 1.3 * g.notch_radius_mm),
                 f.paper(g.hinge_x_mm, H + 0.3), "centre")
    xr = xl - g.inside_corner_radius_mm
    _dim(d, f, (L, g.arm_underside_y_mm), (xr, H), "v", "right", 0, fmt_mm(g.arm_height_mm),
         "arm_height")
    _dim(d, f, (xr, H), (L, top), "v", "right", 0, fmt_mm(g.tip_height_mm), "tip_height")
    _dim(d, f, (g.base_length_mm, 0.0), (L, top), "v", "right", 1, fmt_mm(top),
         "overall_height")
    holes = _holes(d.spec, solid, d.cameras)
    _hole_dims_linear(d, f, holes, (0.0, 0.0))
    _dim(d, f, (0.0, 0.0), (0.0, H), "v", "left", 1, fmt_mm(H), "base_height")
    _hole_marks(d, f, holes)
    _hole_callout(d, f, holes, (g.base_length_mm + g.notch_radius_mm * 2 + 0.8,
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
    rtext = f"R{pm(g.notch_radius_mm, tol.notch_radius_mm)}"
    d.sheet.radius_dimension(dv.paper(xh, yc), g.notch_radius_mm * dv.scale, 60.0, rtext,
                             "notch_radius", dist=-10.0, shoulder_right=True)
    d.dimensions["notch_radius"] = rtext
    # contact face, in the view from above
    t = d.views["top"]
    cf = (f"contact face {pm(g.contact_face_mm[0], tol.contact_face_mm)} × "
          f"{pm(g.contact_face_mm[1], tol.sheet_thickness_mm)}")
    p0 = t.paper(g.tip_centre_x_mm, -g.sheet_thickness_mm / 2)
    p1 = (t.paper_box()[2] + 6.0, t.paper_box()[3] + 8.0)
    d.sheet.leader([p0, p1], cf, "contact_face")
    d.dimensions["contact_face"] = cf
    _thickness_dim(d, tol=tol.sheet_thickness_mm)


def clamp_dims(d: Drawing, solid) -> None:
    """U clamp plate: the generic set plus window width and bridge height."""
    c = d.plan.clamp
    f = d.front
    _dim(d, f, (-c.window_half_width_mm, c.height_mm), (c.window_half_width_mm, c.height_mm),
         "h", "top", 0, fmt_mm(2 * c.window_half_width_mm), "window_width")
    _dim(d, f, (c.half_length_mm, 0.0), (c.window_half_width_mm, c.bridge_height_mm), "v", "right",
         0, fmt_mm(c.bridge_height_mm), "bridge_height")
    generic_dims(d, solid, top_k=1, right_k=1)


def _round_outline(d: Drawing, solid) -> float | None:
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
    outer = _round_outline(d, solid)
    if outer is not None:
        _dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, f"Ø{fmt_mm(outer)}", "outer_diameter")
    else:
        _dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, fmt_mm(u1 - u0), "overall_length")
        _dim(d, f, (u1, v0), (u1, v1), "v", "right", right_k, fmt_mm(v1 - v0), "overall_height")
    _thickness_dim(d)
    holes = _holes(d.spec, solid, d.cameras)
    centre = ((u0 + u1) / 2, (v0 + v1) / 2)
    if holes and outer is not None and all(abs(h.x - centre[0]) < 1e-6 and abs(h.y - centre[1]) < 1e-6
                                           for h in holes):
        _hole_marks(d, f, holes)
        _hole_callout(d, f, holes, (centre[0] + (u1 - u0) * 0.3, v1 + (v1 - v0) * 0.05))
    elif holes:
        _hole_marks(d, f, holes)
        if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
            _hole_dims_linear(d, f, holes, (u0, v0))
            _hole_callout(d, f, holes, ((u0 + u1) / 2, v1 - (v1 - v0) * 0.15))
        else:
            datum = (0.0, 0.0) if (u0 - 1e-9 <= 0 <= u1 + 1e-9 and v0 - 1e-9 <= 0 <= v1 + 1e-9) \
                else (u0, v0)
            _hole_table(d, f, holes, datum)
    _radius_callouts(d, _inside_radii(d.spec))


def indenter_dims(d: Drawing, solid) -> None:
    """Indenter (``spec.geometry`` with contact_width_mm, contact_depth_mm,
    tip_length_mm, body_diameter_mm, body_length_mm; part frame: contact face
    at z = 0, width along x, depth along y): the contact face in the front
    view (width) and the view from the left (depth), tip and body lengths,
    body diameter. Falls back to the generic set for other geometry."""
    g = d.spec.geometry
    need = ("contact_width_mm", "contact_depth_mm", "tip_length_mm", "body_diameter_mm",
            "body_length_mm")
    if not all(hasattr(g, k) for k in need):
        generic_dims(d, solid)
        return
    f, left = d.front, d.views["left"]
    w, dp, L = g.contact_width_mm, g.contact_depth_mm, g.tip_length_mm
    D, B = g.body_diameter_mm, g.body_length_mm
    # front view: u = -x, v = z; view from the left: u = y, v = z
    _dim(d, f, (w / 2, 0.0), (-w / 2, 0.0), "h", "below", 0, fmt_mm(w), "contact_width")
    _dim(d, left, (-dp / 2, 0.0), (dp / 2, 0.0), "h", "below", 0, fmt_mm(dp), "contact_depth")
    _dim(d, f, (D / 2, L + B), (-D / 2, L + B), "h", "top", 0, f"Ø{fmt_mm(D)}", "body_diameter")
    _dim(d, f, (-w / 2, 0.0), (-w / 2, L), "v", "right", 0, fmt_mm(L), "tip_length")
    _dim(d, f, (-D / 2, L), (-D / 2, L + B), "v", "right", 0, fmt_mm(B), "body_length")
    _dim(d, f, (-w / 2, 0.0), (-D / 2, L + B), "v", "right", 1, fmt_mm(L + B), "overall_height")
    from tactcad.catalogue.rigs import INDENTER_THREAD_DIAMETER_MM, indenter_thread_depth_mm
    from tactcad.catalogue.shop import tap_drill_mm, thread_text

    fb = f.paper_box()
    depth = indenter_thread_depth_mm(g)
    th = (f"{thread_text(INDENTER_THREAD_DIAMETER_MM, depth)} (tap drill "
          f"Ø{fmt_mm(tap_drill_mm(INDENTER_THREAD_DIAMETER_MM))}), onto the gauge shaft")
    sv = d.views.get("section", f)
    sb = sv.paper_box()
    rt = INDENTER_THREAD_DIAMETER_MM / 2
    d.sheet.leader([sv.paper(rt, L + B - depth / 2), (sb[2] + FIRST_TIER + TIER, sb[1] - 8.0)],
                   th, "mount_thread")
    d.dimensions["mount_thread"] = th
    if sv is not f:
        _dim(d, sv, (-rt, L + B), (-rt, L + B - depth), "v", "right", 0, fmt_mm(depth),
             "thread_depth")
        _section_marks(d, "top", "A-A")
    cf = f"contact face {fmt_mm(w)} × {fmt_mm(dp)}"
    d.sheet.leader([f.paper(0.0, 0.0), (fb[2] + 4.0, fb[3] + 18.0)], cf, "contact_face")
    d.dimensions["contact_face"] = cf


# ---------------------------------------------------------------------------
# the cart: vacuum pocket, suction holes, channel and port, tapped holes, section A-A
# ---------------------------------------------------------------------------
SECTION_GAP = 30.0  # paper mm between the view from the left and a section view


def add_section(d: Drawing, solid, normal: tuple, up: tuple, length_mm: float,
                height_mm: float) -> None:
    """Section A-A through the part frame's origin, plane normal ``normal``
    pointing at the viewer, ``up`` upwards; placed right of the view from the
    left at up to four times the main scale (the largest ISO 5455 scale at
    which ``length_mm`` x ``height_mm`` fits the room left on the sheet)."""
    from tactcad.drawings.section import section_view

    lb = d.views["left"].paper_box()
    left = lb[2] + SECTION_GAP
    room = FRAME[2] - 8.0 - left - FIRST_TIER - 2 * TIER
    top = lb[1] + 12.0
    room_h = d.notes_top - top - FIRST_TIER - 2 * TIER - 12.0
    scale = next((s for s in ISO_5455_SCALES if s <= 4 * d.scale and length_mm * s <= room
                  and height_mm * s <= room_h), d.scale)
    sv = section_view(solid, (0.0, 0.0, 0.0), normal, up, "A-A", scale)
    sv.hidden = []  # ISO 128-40: no hidden edges in a section
    sv.place(left, lb[1] + 12.0)
    d.views["section"] = sv


def cart_section(d: Drawing, solid) -> None:
    """Cart: section in the mid plane y = 0 (through the channel, the port
    and the suction holes), seen from -y."""
    g = d.spec.geometry
    add_section(d, solid, (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), g.length_mm, g.thickness_mm)


def indenter_section(d: Drawing, solid) -> None:
    """Indenter: section through its axis (plane y = 0, seen from +y, as the
    front view), showing the blind tapped hole."""
    g = d.spec.geometry
    add_section(d, solid, (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), g.body_diameter_mm,
                g.tip_length_mm + g.body_length_mm)


def _section_marks(d: Drawing, host: str, label: str) -> None:
    """Cutting plane (ISO 128-40: long-dash-dot, thick at the ends) along the
    line v = 0 of view ``host``, arrows for the viewing direction (paper up),
    the letters, and the section's own label with its scale."""
    sh, f, sv = d.sheet, d.views[host], d.views["section"]
    x0, _, x1, _ = f.paper_box()
    y = f.paper(0.0, 0.0)[1]
    out = FIRST_TIER + TIER + 4.0  # beyond two tiers of dimensions
    sh.line("section-plane", (x0 - out, y), (x1 + out, y), "centre")
    for x in (x0 - out, x1 + out):
        sh.line("section-plane", (x - 2.5 if x < x0 else x - 2.5, y), (x + 2.5, y), "visible")
        sh.line("section-plane", (x, y), (x, y - 5.0), "thin")
        sh.arrow("section-plane", (x, y - 7.5), (0.0, -1.0))
        sh.text("section-plane", (x + (-3.0 if x < x0 else 3.0), y - 6.0), label[0], LABEL_TEXT_MM,
                anchor="middle", id=f"section-letter-{'l' if x < x0 else 'r'}")
    b = sv.paper_box()
    sh.text("view-section", ((b[0] + b[2]) / 2, b[3] + FIRST_TIER + 2 * TIER + 5.0),
            f"{label} ({scale_text(sv.scale)})", LABEL_TEXT_MM, anchor="middle",
            id="section-label")


def cart_dims(d: Drawing, solid) -> None:
    """Cart (``spec.geometry``: :class:`tactcad.design.rigs.CartGeometry`;
    part frame: x along the grooves, z up from the underside, centred):
    outline and pocket in the front view (from +z), the wheel axles' tapped
    holes in the view from above (from +y), the hose port in the view from the
    left (from -x), channel, port, suction holes and pocket depth in section A-A."""
    from tactcad.catalogue.shop import thread_text
    from tactcad.design.rigs import POCKET_CORNER_RADIUS_MM

    g = d.spec.geometry
    f, t, lv, sv = d.front, d.views["top"], d.views["left"], d.views["section"]
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    pl, pw = g.pocket_length_mm, g.pocket_width_mm
    # front view: outline, pocket, holder screws
    _dim(d, f, (-pl / 2, pw / 2), (pl / 2, pw / 2), "h", "top", 0, fmt_mm(pl), "pocket_length")
    _dim(d, f, (-L / 2, W / 2), (L / 2, W / 2), "h", "top", 1, fmt_mm(L), "overall_length")
    _dim(d, f, (pl / 2, -pw / 2), (pl / 2, pw / 2), "v", "right", 0, fmt_mm(pw), "pocket_width")
    _dim(d, f, (L / 2, -W / 2), (L / 2, W / 2), "v", "right", 1, fmt_mm(W), "overall_height")
    ys = g.holder_screw_y_mm
    _dim(d, f, (0.0, -ys), (0.0, ys), "v", "left", 0, fmt_mm(2 * ys), "holder_screw_spacing")
    holes = [Hole2D(0.0, s * ys, g.holder_screw_diameter_mm) for s in (-1, 1)]
    _hole_marks(d, f, holes)
    d.sheet.line("centre-lines", f.paper(0.0, -W / 2 - 2.0), f.paper(0.0, W / 2 + 2.0), "centre")
    fb = f.paper_box()
    texts = {
        # both leaders end below the view, clear of its edges and of each other
        "holder_thread": (f"2× {thread_text(g.holder_screw_diameter_mm, g.holder_tapped_depth_mm)}",
                          f.paper(g.holder_screw_diameter_mm / 2 * 0.7, -ys - 0.7),
                          (fb[0] + 0.62 * (fb[2] - fb[0]), fb[3] + 12.0)),
        "pocket": (f"pocket depth {fmt_mm(g.pocket_depth_mm)}, 4× R{fmt_mm(POCKET_CORNER_RADIUS_MM)}",
                   f.paper(-pl / 2, -pw / 2 + POCKET_CORNER_RADIUS_MM * 2),
                   (fb[0] + 8.0, fb[3] + 6.0)),
    }
    for name, (text, at, to) in texts.items():
        d.sheet.leader([at, to], text, name)
        d.dimensions[name] = text
    # view from above (u = x, v = -z): axles
    ax, ah = g.axle_x_mm, g.axle_height_mm
    _dim(d, t, (-ax, -ah), (ax, -ah), "h", "below", 0, fmt_mm(2 * ax), "axle_spacing")
    _dim(d, t, (-L / 2, 0.0), (-ax, -ah), "v", "left", 0, fmt_mm(ah), "axle_height")
    _hole_marks(d, t, [Hole2D(s * ax, -ah, g.axle_bolt.nominal_diameter_mm) for s in (-1, 1)])
    axle = (f"4× {thread_text(g.axle_bolt.nominal_diameter_mm, g.axle_hole_depth_mm)} "
            f"(both sides)")
    tb = t.paper_box()
    d.sheet.leader([t.paper(ax + 1.0, -ah - 1.0), (tb[2] - 10.0, tb[3] + 12.0)], axle, "axle_thread")
    d.dimensions["axle_thread"] = axle
    _thickness_dim(d)
    # view from the left (u = z, v = y): the hose port
    port = thread_text(g.port_diameter_mm, g.port_depth_mm)
    lb = lv.paper_box()
    _hole_marks(d, lv, [Hole2D(T / 2, 0.0, g.port_diameter_mm)])
    d.sheet.leader([lv.paper(T / 2 + g.port_diameter_mm / 2 * 0.7, g.port_diameter_mm / 2 * 0.7),
                    (lb[2] + 6.0, lb[1] - 4.0)], f"hose port {port}", "port_thread")
    d.dimensions["port_thread"] = f"hose port {port}"
    # section A-A (u = x, v = z)
    xs = g.suction_hole_xs_mm
    _dim(d, sv, (-L / 2, T), (xs[0], T), "h", "top", 0, fmt_mm(xs[0] + L / 2), "suction_hole_first_x")
    if len(xs) > 1:
        _dim(d, sv, (xs[0], T), (xs[1], T), "h", "top", 1, fmt_mm(xs[1] - xs[0]), "suction_hole_pitch")
    _dim(d, sv, (-L / 2, T / 2), (-L / 2 + g.port_depth_mm, T / 2), "h", "below", 0,
         fmt_mm(g.port_depth_mm), "port_depth")
    _dim(d, sv, (-L / 2, T / 2), (g.channel_end_x_mm, T / 2), "h", "below", 1,
         fmt_mm(g.channel_end_x_mm + L / 2), "channel_length")
    _dim(d, sv, (L / 2, 0.0), (g.channel_end_x_mm, T / 2), "v", "right", 0, fmt_mm(T / 2),
         "channel_height")
    _dim(d, sv, (L / 2, T), (pl / 2, T - g.pocket_depth_mm), "v", "right", 1,
         fmt_mm(g.pocket_depth_mm), "pocket_depth")
    sb = sv.paper_box()
    ch = f"channel Ø{fmt_mm(g.channel_diameter_mm)}"
    d.sheet.leader([sv.paper(g.channel_end_x_mm - 4.0, T / 2 - g.channel_diameter_mm / 2),
                    (sv.paper(g.channel_end_x_mm, 0.0)[0] + 4.0, sb[3] + 5.0)], ch, "channel_diameter")
    d.dimensions["channel_diameter"] = ch
    sh_text = f"{len(xs)}× Ø{fmt_mm(g.suction_hole_diameter_mm)} to channel"
    d.sheet.leader([sv.paper(xs[-1] + g.suction_hole_diameter_mm / 2, T - 1.5),
                    (sb[0] + 0.72 * (sb[2] - sb[0]), sb[1] - 2 * TIER - FIRST_TIER)], sh_text,
                   "suction_holes")
    d.dimensions["suction_holes"] = sh_text
    _section_marks(d, "front", "A-A")


def base_plate_dims(d: Drawing, solid) -> None:
    """Base plate (:class:`tactcad.design.rigs.BasePlateGeometry`; frame
    centred, z up): the generic set, and the two full-length grooves in the
    view from the left (u = z, v = y): width, depth and centre distance."""
    g = d.spec.geometry
    generic_dims(d, solid)
    lv = d.views["left"]
    T, yc, gw = g.thickness_mm, g.track_half_mm, g.groove_width_mm
    _dim(d, lv, (T - g.groove_depth_mm, yc + gw / 2), (T, yc + gw / 2), "h", "top", 0,
         fmt_mm(g.groove_depth_mm), "groove_depth")
    _dim(d, lv, (T, yc - gw / 2), (T, yc + gw / 2), "v", "right", 0, fmt_mm(gw), "groove_width")
    _dim(d, lv, (T - g.groove_depth_mm, -yc), (T - g.groove_depth_mm, yc), "v", "right", 1,
         fmt_mm(2 * yc), "groove_spacing")
    for s_ in (-1, 1):
        d.sheet.line("centre-lines", lv.paper(T - g.groove_depth_mm - 1.0, s_ * yc),
                     lv.paper(T + 1.0, s_ * yc), "centre")


def sample_holder_dims(d: Drawing, solid) -> None:
    """Sample holder (:class:`tactcad.design.rigs.SampleHolderGeometry`;
    frame centred, z up): the generic set plus the window (length, width,
    corner radius)."""
    g = d.spec.geometry
    f = d.front
    wl, ww = g.window_length_mm, g.window_width_mm
    _dim(d, f, (-wl / 2, ww / 2), (wl / 2, ww / 2), "h", "top", 0, fmt_mm(wl), "window_length")
    _dim(d, f, (wl / 2, -ww / 2), (wl / 2, ww / 2), "v", "right", 0, fmt_mm(ww), "window_width")
    generic_dims(d, solid, top_k=1, right_k=1)
    r = g.corner_radius_mm
    text = f"window through, 4× R{fmt_mm(r)}"
    c = (wl / 2 - r + r * 0.7, -ww / 2 + r - r * 0.7)
    fb = f.paper_box()
    d.sheet.leader([f.paper(*c), (fb[2] - 6.0, fb[3] + FIRST_TIER + 2 * TIER + 4.0)], text,
                   "window_corner")
    d.dimensions["window_corner"] = text


def bracket_dims(d: Drawing, solid) -> None:
    """Array bracket (:class:`tactcad.design.rigs.BracketGeometry`; views from
    :func:`tactcad.drawings.views.orientation`: front from +y with u = z,
    v = x; from above u = z, v = -y; from the left u = y, v = x): the generic
    set (outline, foot hole), the L section's ear and foot thicknesses and
    ear height in the view from above, the ear's two through holes in the
    view from the left."""
    g = d.spec.geometry
    generic_dims(d, solid)
    t, lv = d.views["top"], d.views["left"]
    fb_, ft = g.foot_bottom_mm, g.foot_top_mm
    _dim(d, t, (-g.ear_thickness_mm, -g.ear_top_mm), (0.0, -g.ear_top_mm), "h", "top", 0,
         fmt_mm(g.ear_thickness_mm), "ear_thickness")
    _dim(d, t, (-g.foot_length_mm, -ft), (-g.foot_length_mm, -fb_), "v", "left", 0,
         fmt_mm(g.foot_thickness_mm), "foot_thickness")
    xs = sorted(g.hole_xs_mm)
    holes = [Hole2D(0.0, x, g.hole_diameter_mm) for x in xs]
    _hole_marks(d, lv, holes)
    _dim(d, lv, (fb_, xs[0]), (0.0, xs[0]), "h", "below", 0, fmt_mm(-fb_), "ear_hole_height")
    _dim(d, lv, (0.0, -g.width_mm / 2), (0.0, xs[0]), "v", "right", 0,
         fmt_mm(xs[0] + g.width_mm / 2), "ear_hole_1_x")
    if len(xs) > 1:
        _dim(d, lv, (0.0, xs[0]), (0.0, xs[1]), "v", "right", 1, fmt_mm(xs[1] - xs[0]),
             "ear_hole_spacing")
    lb = lv.paper_box()
    text = f"{len(xs)}× Ø{fmt_mm(g.hole_diameter_mm)} {holes[0].depth_text}"
    d.sheet.leader([lv.paper(g.hole_diameter_mm / 2 * 0.7, xs[-1] + g.hole_diameter_mm / 2 * 0.7),
                    (lb[2] + 4.0, lb[1] - 6.0)], text, "ear_holes")
    d.dimensions["ear_holes"] = text


DIMENSION_SETS: dict[str, Callable[[Drawing, object], None]] = {
    "array_bracket": bracket_dims,
    "base_plate": base_plate_dims,
    "sample_holder": sample_holder_dims,
    "element": element_dims,
    "clamp_plate": clamp_dims,
    "indenter": indenter_dims,
    "cart": cart_dims,
}

#: Section views by builder key, added after the main views are placed.
SECTIONS: dict[str, Callable[[Drawing, object], None]] = {
    "cart": cart_section,
    "indenter": indenter_section,
}

# Parts drawn from fixed directions (builder key -> view set); others see
# :func:`layout`.
CAMERA_SETS: dict[str, dict] = {
    "indenter": cameras_for((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
}


# ---------------------------------------------------------------------------
# notes, title block, frame
# ---------------------------------------------------------------------------
def notes_for(d: Drawing) -> list[str]:
    plan, spec = d.plan, d.spec
    n: list[str] = []
    if spec.builder == "element":
        g = plan.distinct_elements[spec.name]
        used = [s.number for s in plan.slots if s.geometry.part_name == spec.name]
        a, k0, k1, ratio = table1_spread()
        up = ((g.web_thickness_mm + g.web_tolerance_mm) / g.web_thickness_mm) ** 2.5 - 1
        dn = 1 - ((g.web_thickness_mm - g.web_tolerance_mm) / g.web_thickness_mm) ** 2.5
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
                 + ". A strain gauge is bonded on the flat top face over the web.")
        n.append(full_scale_note(plan, spec.name, plan.material.yield_strength_MPa,
                                 plan.material.grade or plan.material.name))
        e_tol = tolerances_of(plan.raw).youngs_modulus_rel
        n.append(f"Young's modulus {plan.material.youngs_modulus_MPa:g} MPa "
                 f"±{100 * e_tol:g} %: check the sheet's mill certificate.")
    elif spec.builder == "spacer":
        n.append(f"{_sentence(spec.process)}, {spec.material}. Thickness "
                 f"{fmt_mm(plan.spacer.thickness_mm)} = pitch {fmt_mm(plan.pitch_mm)} - sheet "
                 f"{fmt_mm(plan.sheet_thickness_mm)}: it sets the array pitch; faces parallel "
                 f"within 0.01 (ISO 1101).")
    elif spec.builder == "clamp_plate":
        n.append(f"{_sentence(spec.process)} from {fmt_mm(_thickness(spec))} mm {spec.material}"
                 f" plate. Window corners R = cutter radius. Holes Ø"
                 f"{fmt_mm(plan.bolt.clearance_hole_mm)}: ISO 273 medium clearance for "
                 f"{plan.bolt.size}.")
    elif spec.builder == "cart":
        g = spec.geometry
        n.append(f"{_sentence(spec.process)}, {spec.material}.")
        n.append(f"Vacuum: drill the channel Ø{fmt_mm(g.channel_diameter_mm)} from the port end "
                 f"(section A-A), then the suction holes from the pocket floor into it; deburr "
                 f"the channel and holes so no chip stays inside. Top face and pocket rim: "
                 f"flatness 0.05 (ISO 1101), so the sample seals on the vacuum.")
    elif spec.builder == "indenter":
        n.append(f"{_sentence(spec.process)}, {spec.material}.")
        n.append("The M6 thread screws the indenter onto the force gauge's measuring shaft; "
                 "contact face perpendicular to the thread axis within 0.02 (ISO 1101), so the "
                 "2 x 3 mm face lies flat on the element's tip.")
    else:
        n.append(f"{_sentence(spec.process)}, {spec.material}.")
    n.append(f"Untoleranced dimensions: {general_tolerance(plan)}. Dimensions in mm (ISO 129-1), "
             f"first-angle projection. Break sharp edges 0.1 max unless noted.")
    return n


def _sentence(text: str) -> str:
    return text[:1].upper() + text[1:]


def _note_lines(d: Drawing) -> list[list[str]]:
    x0 = FRAME[0] + 5.0
    right = FRAME[2] - TITLE_W - 6.0 - (sum(TABLE_COLS) + 6.0 if d.table_rows else 0.0)
    width = 0.8 * (right - x0)  # room for a wider fallback font
    return [_wrap(f"{k}. {note}", width, DIM_TEXT_MM) for k, note in enumerate(d.notes, start=1)]


def notes_top(d: Drawing) -> float:
    """Paper y where the views must end: above the notes block (which ends
    3 mm above the frame) and above the hole table, if any."""
    lines = _note_lines(d)
    height = 5.0 + sum(len(ls) * NOTE_LINE + 0.8 for ls in lines) + 3.0
    table = (d.table_rows + 1) * TABLE_ROW + 8.0 + 8.0 if d.table_rows else 0.0
    return min(NOTES_TOP, FRAME[3] - height, FRAME[3] - table)


def draw_notes(d: Drawing) -> None:
    sh = d.sheet
    x0, y = FRAME[0] + 5.0, d.notes_top + 5.0
    sh.text("notes", (x0, y), "NOTES", LABEL_TEXT_MM, bold=True)
    y += 5.0
    for k, lines in enumerate(_note_lines(d), start=1):
        for j, line in enumerate(lines):
            sh.text("notes", (x0 + (4.0 if j else 0.0), y), line, DIM_TEXT_MM,
                    id=f"note-{k}" if j == 0 else "")
            y += NOTE_LINE
        y += 0.8
    if d.notes_top < FRAME[1] + 60.0:
        raise ValueError(f"notes of {d.spec.name} leave no room for the views")


def _wrap(text: str, width: float, h: float) -> list[str]:
    words = text.split()
    lines, cur = [], ""
    for w in words:
        trial = f"{cur} {w}".strip()
        if text_width(trial, h) <= width or not cur:
            cur = trial
        else:
            lines.append(cur)
            cur = w
    if cur:
        lines.append(cur)
    return lines


def draw_frame(d: Drawing) -> None:
    sheet_frame(d.sheet)


def sheet_frame(sh: Sheet) -> None:
    """ISO 5457 frame and centring marks of an A3 sheet."""
    x0, y0, x1, y1 = FRAME
    sh.rect("frame", x0, y0, x1 - x0, y1 - y0, "frame")
    # centring marks (ISO 5457)
    w, h = sh.width_mm, sh.height_mm
    for p, q in (((w / 2, 0.0), (w / 2, y0 + 5)), ((w / 2, h), (w / 2, y1 - 5)),
                 ((0.0, h / 2), (x0 + 5, h / 2)), ((w, h / 2), (x1 - 5, h / 2))):
        sh.line("frame", p, q, "frame")


def draw_title_block(d: Drawing) -> None:
    from tactcad import __version__

    sh = d.sheet
    plan, spec = d.plan, d.spec
    x0, y0 = FRAME[2] - TITLE_W, FRAME[3] - TITLE_H
    rh = TITLE_H / 7
    rev, date = revision_and_date(plan)
    sh.rect("title-block", x0, y0, TITLE_W, TITLE_H, "frame")
    scale = scale_text(d.scale) + (f", detail {scale_text(d.detail_scale)}" if d.detail_scale else "")
    cells = [
        # row, x offset, width, label, value, id, value height
        (0, 0, 120, "Part", spec.name, "tb-part", 3.5),
        (0, 120, 60, "Quantity", str(d.quantity), "tb-quantity", LABEL_TEXT_MM),
        (1, 0, 120, "Material", material_text(spec, plan), "tb-material", LABEL_TEXT_MM),
        (1, 120, 60, "Scale", scale, "tb-scale", LABEL_TEXT_MM),
        (2, 0, 120, "Process", spec.process, "tb-process", LABEL_TEXT_MM),
        (2, 120, 60, "Units", "mm", "tb-units", LABEL_TEXT_MM),
        (3, 0, 60, "General tolerances", general_tolerance(plan), "tb-tolerance", LABEL_TEXT_MM),
        (3, 60, 60, "Dimensioning", "ISO 129-1", "tb-standard", LABEL_TEXT_MM),
        (3, 120, 60, "Projection", "", "tb-projection", LABEL_TEXT_MM),
        (4, 0, 120, "Design", f"{plan.name}  part sha256 {part_hash(plan, spec)[:12]}",
         "tb-design", LABEL_TEXT_MM),
        (4, 120, 60, "Sheet", "1 / 1", "tb-sheet", LABEL_TEXT_MM),
        (5, 0, 120, "Generated by", f"tactcad {__version__}", "tb-version", LABEL_TEXT_MM),
        (5, 120, 60, "Drawing no.", f"{plan.name}-{spec.name}", "tb-number", LABEL_TEXT_MM),
        (6, 0, 120, "Surface finish (ISO 1302, Ra in µm)", finish_text(spec), "tb-finish",
         LABEL_TEXT_MM),
        (6, 120, 25, "Revision", rev, "tb-revision", LABEL_TEXT_MM),
        (6, 145, 35, "Date", date, "tb-date", LABEL_TEXT_MM),
    ]
    title_cells(sh, x0, y0, rh, cells)
    # first-angle projection symbol (ISO 128-30), in the projection cell
    px, py = x0 + 120 + 30, y0 + 3 * rh + rh / 2 + 0.8
    sh.polyline("title-block", [(px - 12, py - 1.4), (px - 4, py - 3.0), (px - 4, py + 3.0),
                                (px - 12, py + 1.4)], "thin", closed=True)
    sh.line("title-block", (px - 14, py), (px - 2, py), "centre")
    sh.circle("title-block", (px + 6, py), 3.0)
    sh.circle("title-block", (px + 6, py), 1.4)
    sh.line("title-block", (px + 2, py), (px + 10, py), "centre")
    sh.line("title-block", (px + 6, py - 4), (px + 6, py + 4), "centre")
    draw_finish_symbol(d, (x0 + 8.0, y0 - 3.0))


def draw_finish_symbol(d: Drawing, at: tuple[float, float]) -> None:
    """ISO 1302 general surface texture indication above the title block:
    the symbol "material removal required" with the general Ra, followed in
    brackets by the basic symbol when some faces are finer (indicated by
    note). ``at``: paper point of the symbol's root (mm)."""
    f = surface_finish(d.spec)
    if not f.general_ra_um:
        return
    sh = d.sheet
    x, y = at
    h = 5.0  # ISO 1302 H1 for 2.5 mm lettering: 3.5; H2 = 2 H1, here scaled to 5 / 10
    sh.polyline("surface-finish", [(x - h * 0.58, y - h), (x, y), (x + h * 1.15, y - 2 * h),
                                   (x + h * 1.15 + 14.0, y - 2 * h)], "thin")
    sh.line("surface-finish", (x - h * 0.58, y - h), (x + h * 0.58, y - h), "thin")
    sh.text("surface-finish", (x + h * 1.15 + 1.0, y - 2 * h - 1.0), f"Ra {f.general_ra_um:g}",
            DIM_TEXT_MM, id="finish-general")
    if f.special:
        sh.text("surface-finish", (x + h * 1.15 + 16.0, y - 2 * h + 4.0),
                "( " + ", ".join(f"Ra {ra:g} {face}" for face, ra in f.special) + " )",
                DIM_TEXT_MM, id="finish-special")


def title_cells(sh: Sheet, x0: float, y0: float, rh: float, cells: list[tuple]) -> None:
    """Title-block cells (ISO 7200): each ``(row, x offset, width, label,
    value, id, value height)`` in paper mm from the block's corner
    ``(x0, y0)``, rows ``rh`` high; a value too wide for its cell is set smaller."""
    for row, dx, w, label, value, id, vh in cells:
        x, y = x0 + dx, y0 + row * rh
        sh.rect("title-block", x, y, w, rh, "table")
        sh.text("title-block", (x + 1.2, y + 2.4), label, 1.6)
        if value:
            while text_width(value, vh) > 0.9 * (w - 3) and vh > 1.8:
                vh -= 0.25
            sh.text("title-block", (x + 1.5, y + rh - 1.6), value, vh, id=id)


def drawing_inputs(plan: Plan, spec: PartSpec) -> tuple:
    """Everything of the plan that shapes the part's drawing: the part itself
    and, by part family, the plan values its notes and dimensions print."""
    inputs: tuple = (plan.name, spec, material_designation(spec, plan), revision_and_date(plan),
                     tolerances_of(plan.raw))
    if spec.builder == "element":
        used = tuple(s.number for s in plan.slots if s.geometry.part_name == spec.name)
        inputs += (plan.distinct_elements[spec.name], used, plan.edm, plan.material,
                   plan.strength)
    elif spec.builder == "spacer":
        inputs += (plan.spacer, plan.pitch_mm, plan.sheet_thickness_mm)
    elif spec.builder == "clamp_plate":
        inputs += (plan.clamp, plan.bolt)
    return inputs


def part_hash(plan: Plan, spec: PartSpec) -> str:
    """sha256 of :func:`drawing_inputs`: it changes with any file value that
    shapes the part (design, rigs or scenes file), and with nothing else."""
    return hashlib.sha256(stable_repr(drawing_inputs(plan, spec)).encode()).hexdigest()


def compose(plan: Plan, spec: PartSpec, solid, quantity: int) -> Drawing:
    """The finished drawing of one fabricated part.

    Args:
        plan: validated design.
        spec: the part (``kind == "fabricated"``).
        solid: its build123d solid in the part frame (mm).
        quantity: parts per build, counted from the assemblies' instances.

    Raises:
        ValueError: ``spec`` is not a fabricated part, or its notes do not fit.
    """
    if spec.kind != "fabricated":
        raise ValueError(f"{spec.name} is {spec.kind}; drawings are for fabricated parts")
    d = Drawing(plan, spec, quantity)
    d.sheet.title = f"{spec.name} - {plan.name}"
    d.cameras = choose_cameras(spec)
    d.table_rows = hole_table_rows(d, solid)
    d.notes = notes_for(d)
    d.notes_top = notes_top(d)
    layout(d, solid)
    if spec.builder in SECTIONS:
        SECTIONS[spec.builder](d, solid)
    draw_frame(d)
    draw_views(d)
    DIMENSION_SETS.get(spec.builder, generic_dims)(d, solid)
    draw_notes(d)
    draw_title_block(d)
    return d
