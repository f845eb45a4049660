"""Round trip of a wire-EDM DXF: read it back and compare with the design.

Everything is measured on what ezdxf reads from the file (bulges turned back
into exact arcs), never on the in-memory profile that wrote it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import ezdxf
import numpy as np
import shapely.geometry as sg

from tactcad.checks.check_result import CheckResult
from tactcad.design.array_plan import EdmRules
from tactcad.export.dxf import CUT_LAYER, LEAD_LAYER, MARK_LAYER, ORDER_LAYER, START_LAYER, TAB_LAYER
from tactcad.geometry.profile import (Arc, Line, Point, Segment, contour_area, contour_bbox,
                                      contour_points, inside_corners)

ALLOWED_TYPES = {"LINE", "ARC", "CIRCLE", "LWPOLYLINE", "POLYLINE", "POINT", "TEXT"}
NON_CUT_TYPES = {LEAD_LAYER: {"LINE", "POINT"}, MARK_LAYER: {"TEXT"}, START_LAYER: {"CIRCLE"},
                 TAB_LAYER: {"LINE"}, ORDER_LAYER: {"TEXT"}}
LEAD_IN_CLEARANCE_MM = 1.0  # an entry point this far at least from the web and the contact face
CLOSE_TOL_MM = 1e-6
AREA_RTOL = 1e-6
BBOX_TOL_MM = 1e-6
WEB_TOL_MM = 1e-6


@dataclass(frozen=True)
class Contour:
    segments: tuple[Segment, ...]
    closed: bool
    gap_mm: float


def bulge_segment(p0: Point, p1: Point, bulge: float) -> Segment:
    """Line or exact arc of an LWPOLYLINE edge: sweep = 4 atan(bulge), the centre
    offset from the chord midpoint by c (1 - b^2) / (4 b) along the left normal."""
    if abs(bulge) < 1e-15:
        return Line(p0, p1)
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    c = math.hypot(dx, dy)
    d = c * (1 - bulge * bulge) / (4 * bulge)
    mx, my = (p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2
    centre = (mx - dy / c * d, my + dx / c * d)
    return Arc(p0, p1, centre, bulge > 0)


def _lwpolyline_contour(e) -> Contour:
    if e.dxftype() == "POLYLINE":  # R12: bulges on the VERTEX entities
        pts = [(v.dxf.location[0], v.dxf.location[1], v.dxf.bulge) for v in e.vertices]
        closed = bool(e.is_closed)
    else:
        pts = [(x, y, b) for x, y, _s, _e, b in e.get_points("xyseb")]
        closed = bool(e.closed)
    if not closed and len(pts) > 2 and math.dist(pts[0][:2], pts[-1][:2]) <= CLOSE_TOL_MM:
        pts = pts[:-1]
        closed = True
    n = len(pts)
    last = n if closed else n - 1
    segs = tuple(bulge_segment(pts[i][:2], pts[(i + 1) % n][:2], pts[i][2]) for i in range(last))
    gap = 0.0 if closed else math.dist(pts[0][:2], pts[-1][:2])
    return Contour(segs, closed, gap)


def _circle_contour(center, r) -> Contour:
    x, y = center[0], center[1]
    return Contour((Arc((x + r, y), (x - r, y), (x, y), True),
                    Arc((x - r, y), (x + r, y), (x, y), True)), True, 0.0)


def _loose_segment(e) -> Segment:
    if e.dxftype() == "LINE":
        return Line(tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2])
    c, r = e.dxf.center, e.dxf.radius
    a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
    return Arc((c[0] + r * math.cos(a0), c[1] + r * math.sin(a0)),
               (c[0] + r * math.cos(a1), c[1] + r * math.sin(a1)), (c[0], c[1]), True)


def _chain_loose(segments: list[Segment]) -> list[Contour]:
    """Join loose LINE/ARC entities end to start (either direction) into chains."""
    pool = list(segments)
    out = []
    while pool:
        chain = [pool.pop(0)]
        grown = True
        while grown:
            grown = False
            end = chain[-1].end
            for i, s in enumerate(pool):
                if math.dist(s.start, end) <= CLOSE_TOL_MM:
                    chain.append(pool.pop(i))
                    grown = True
                    break
                if math.dist(s.end, end) <= CLOSE_TOL_MM:
                    s = pool.pop(i)
                    chain.append(Line(s.end, s.start) if isinstance(s, Line)
                                 else Arc(s.end, s.start, s.centre, not s.ccw))
                    grown = True
                    break
        gap = math.dist(chain[0].start, chain[-1].end)
        out.append(Contour(tuple(chain), gap <= CLOSE_TOL_MM, gap))
    return out


@dataclass(frozen=True)
class DxfReading:
    """What a DXF holds, as read back."""

    types: set[str]
    units: int
    audit_errors: int
    max_abs_z: float
    contours: list[Contour]
    start_holes: list[tuple[Point, float]]
    lead_lines: list[tuple[Point, Point]]
    lead_points: list[Point]
    marks: list[str]
    extents: tuple[float, float, float, float]
    misplaced: list[str]  # "TYPE on LAYER" for entities on a layer that does not hold them
    version: str
    tabs: list[tuple[Point, Point]] = field(default_factory=list)  # TAB layer lines
    order: list[tuple[str, Point]] = field(default_factory=list)  # CUT_ORDER texts at their insert
    properties: dict[str, str] = field(default_factory=dict)  # custom header properties (R2010)


def read_dxf(path: str | Path) -> DxfReading:
    """Read a profile DXF back with ezdxf (auditor run) into exact contours.

    Raises:
        ezdxf.DXFError: the file is not a readable DXF.
    """
    doc = ezdxf.readfile(str(path))
    auditor = doc.audit()
    msp = doc.modelspace()
    types: set[str] = set()
    contours: list[Contour] = []
    loose: list[Segment] = []
    starts: list[tuple[Point, float]] = []
    leads: list[tuple[Point, Point]] = []
    points: list[Point] = []
    marks: list[str] = []
    misplaced: list[str] = []
    tabs: list[tuple[Point, Point]] = []
    order: list[tuple[str, Point]] = []
    max_z = 0.0
    for e in msp:
        t = e.dxftype()
        types.add(t)
        layer = e.dxf.layer
        if t == "LWPOLYLINE":
            max_z = max(max_z, abs(e.dxf.elevation))
        elif t == "POLYLINE":
            max_z = max([max_z] + [abs(v.dxf.location[2]) for v in e.vertices])
        elif t in ("POINT", "TEXT"):
            max_z = max(max_z, abs((e.dxf.location if t == "POINT" else e.dxf.insert)[2]))
        elif t in ("CIRCLE", "ARC"):
            max_z = max(max_z, abs(e.dxf.center[2]))
        elif t == "LINE":
            max_z = max(max_z, abs(e.dxf.start[2]), abs(e.dxf.end[2]))
        if hasattr(e.dxf, "extrusion") and tuple(e.dxf.extrusion) != (0.0, 0.0, 1.0):
            max_z = max(max_z, math.inf)
        if layer in NON_CUT_TYPES and t not in NON_CUT_TYPES[layer]:
            misplaced.append(f"{t} on {layer}")
        elif layer == START_LAYER:
            starts.append(((e.dxf.center[0], e.dxf.center[1]), e.dxf.radius))
        elif layer == LEAD_LAYER and t == "LINE":
            leads.append((tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]))
        elif layer == LEAD_LAYER:
            points.append(tuple(e.dxf.location)[:2])
        elif layer == MARK_LAYER:
            marks.append(e.dxf.text)
        elif layer == TAB_LAYER:
            tabs.append((tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]))
        elif layer == ORDER_LAYER:
            order.append((e.dxf.text, tuple(e.dxf.insert)[:2]))
        elif layer != CUT_LAYER or t in ("POINT", "TEXT"):
            misplaced.append(f"{t} on {layer}")
        else:
            if t in ("LWPOLYLINE", "POLYLINE"):
                contours.append(_lwpolyline_contour(e))
            elif t == "CIRCLE":
                contours.append(_circle_contour(e.dxf.center, e.dxf.radius))
            elif t in ("LINE", "ARC"):
                loose.append(_loose_segment(e))
    contours.extend(_chain_loose(loose))
    lo, hi = doc.header.get("$EXTMIN", (1e20,) * 3), doc.header.get("$EXTMAX", (-1e20,) * 3)
    return DxfReading(types=types, units=int(doc.header.get("$INSUNITS", 0)),
                      audit_errors=len(auditor.errors), max_abs_z=max_z, contours=contours,
                      start_holes=starts, lead_lines=leads, lead_points=points, marks=marks,
                      extents=(lo[0], lo[1], hi[0], hi[1]), misplaced=misplaced,
                      version=doc.dxfversion, tabs=tabs, order=order,
                      properties=dict(doc.header.custom_vars) if doc.dxfversion != "AC1009" else {})


# --- geometry on exact segments -------------------------------------------------
def _angle_in_arc(arc: Arc, p: Point) -> bool:
    a0 = math.atan2(arc.start[1] - arc.centre[1], arc.start[0] - arc.centre[0])
    a = math.atan2(p[1] - arc.centre[1], p[0] - arc.centre[0])
    sweep = arc.sweep
    d = (a - a0) % (2 * math.pi) if sweep > 0 else (a0 - a) % (2 * math.pi)
    return d <= abs(sweep) + 1e-12


def _ray_hits(origins: np.ndarray, directions: np.ndarray, lines: np.ndarray) -> np.ndarray:
    """Distance along each ray to the first line segment it meets (inf if none).

    Args:
        origins, directions: shape (m, 2), the rays (mm; unit directions).
        lines: shape (n, 4), each segment's (x0, y0, x1, y1) (mm).

    Returns:
        shape (m,), mm.
    """
    x0, y0, x1, y1 = (lines[:, k] for k in range(4))
    ex, ey = x1 - x0, y1 - y0
    dx, dy = directions[:, :1], directions[:, 1:]
    den = dx * ey - dy * ex  # (m, n): parallel where it vanishes
    wx, wy = x0 - origins[:, :1], y0 - origins[:, 1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (wx * ey - wy * ex) / den  # along the ray
        u = (wx * dy - wy * dx) / den  # along the segment
    met = (np.abs(den) >= 1e-15) & (t > 1e-12) & (u >= -1e-12) & (u <= 1 + 1e-12)
    return np.where(met, t, np.inf).min(axis=1, initial=np.inf)


def thinnest_ligament(segments: tuple[Segment, ...], samples: int = 720) -> float:
    """Thinnest material section at a concave arc of a CCW contour (mm).

    From points of each concave arc a ray goes radially outward (into the
    material) to the first straight edge it meets; the shortest such chord is
    the ligament. Candidate directions: the perpendicular foot on every edge
    (where the exact minimum lies), the arc ends and ``samples`` directions in
    between. For a notch flexure hinge this is the web thickness.
    """
    best = math.inf
    lines = [o for o in segments if isinstance(o, Line)]
    ends = np.array([(*ln.start, *ln.end) for ln in lines], dtype=float).reshape(-1, 4)
    for s in segments:
        if not (isinstance(s, Arc) and not s.ccw):
            continue
        cx, cy = s.centre
        a0 = math.atan2(s.start[1] - cy, s.start[0] - cx)
        angles = [a0 + s.sweep * k / samples for k in range(samples + 1)]
        for ln in lines:
            (x0, y0), (x1, y1) = ln.start, ln.end
            ex, ey = x1 - x0, y1 - y0
            L2 = ex * ex + ey * ey
            u = ((cx - x0) * ex + (cy - y0) * ey) / L2 if L2 else 0.0
            fx, fy = x0 + u * ex, y0 + u * ey
            angles.append(math.atan2(fy - cy, fx - cx))
        rays = [((cx + s.radius * math.cos(a), cy + s.radius * math.sin(a)),
                 (math.cos(a), math.sin(a))) for a in angles]
        rays = [(p, d) for p, d in rays if _angle_in_arc(s, p)]
        if rays:
            origins, directions = (np.array(v, dtype=float) for v in zip(*rays))
            best = min(best, float(_ray_hits(origins, directions, ends).min()))
    return best


def _polygon(segments: tuple[Segment, ...], sagitta: float = 1e-4) -> sg.Polygon:
    return sg.Polygon(contour_points(segments, sagitta))


def _file_checks(r: DxfReading, name: str) -> list[CheckResult]:
    """Checks of the file as a whole: auditor, entity types, layers, units, z = 0, extents."""
    if r.version == "AC1009":  # R12 has no units variable: mm by the file's convention
        units = CheckResult("dxf_units_mm", name, True, "R12: no $INSUNITS, mm by convention")
    else:
        units = CheckResult("dxf_units_mm", name, r.units == 4, f"$INSUNITS = {r.units}")
    out = [
        CheckResult("dxf_audit", name, r.audit_errors == 0, f"{r.audit_errors} auditor errors"),
        CheckResult("dxf_entity_types", name, r.types <= ALLOWED_TYPES, ", ".join(sorted(r.types))),
        CheckResult("dxf_layers", name, not r.misplaced,
                    "; ".join(sorted(set(r.misplaced))) or "cut, start hole, lead-in and mark layers apart"),
        units,
        CheckResult("dxf_flat_z0", name, r.max_abs_z <= CLOSE_TOL_MM, f"max |z| {r.max_abs_z:.1e}"),
    ]
    if r.contours:
        boxes = [contour_bbox(c.segments) for c in r.contours]
        xs = [b[0] for b in boxes] + [b[2] for b in boxes] + [p[0] for p in r.lead_points]
        ys = [b[1] for b in boxes] + [b[3] for b in boxes] + [p[1] for p in r.lead_points]
        real = (min(xs), min(ys), max(xs), max(ys))
        dev = max(abs(a - b) for a, b in zip(real, r.extents))
        out.append(CheckResult("dxf_extents", name, dev <= BBOX_TOL_MM,
                               f"$EXTMIN/$EXTMAX {tuple(round(float(v), 4) for v in r.extents)}, "
                               f"drawn {tuple(round(float(v), 4) for v in real)}"))
    return out


def _net_area(outer: Contour, inner: list[Contour]) -> float:
    return abs(contour_area(outer.segments)) - sum(abs(contour_area(c.segments)) for c in inner)


def _ccw(segments: tuple[Segment, ...]) -> tuple[Segment, ...]:
    return segments if contour_area(segments) > 0 else _reverse(segments)


def _piece_checks(name: str, outer: Contour, inner: list[Contour], starts: list[tuple[Point, float]],
                  face_area_mm2: float, edm: EdmRules, web_thickness_mm: float | None,
                  start_holes: bool = True) -> list[CheckResult]:
    """Area, wire-EDM rules and web of one part (outer contour and its cut-outs) read from a file."""
    net = _net_area(outer, inner)
    rel = abs(net - face_area_mm2) / face_area_mm2
    out = [CheckResult("dxf_area", name, rel <= AREA_RTOL,
                       f"{net:.6f} mm2 vs CAD face {face_area_mm2:.6f} (rel {rel:.1e})")]
    segs = _ccw(outer.segments)
    corners = inside_corners(segs)
    min_r = min((rad for _, rad in corners), default=math.inf)
    for c in inner:
        min_r = min([min_r] + [s.radius for s in c.segments if isinstance(s, Arc)])
    out.append(CheckResult("edm_inside_radius", name, min_r >= edm.min_inside_radius_mm - 1e-9,
                           f"smallest inside radius {min_r:.4g} mm, wire needs >= "
                           f"{edm.min_inside_radius_mm:.4g} mm"))
    slot_widths = [2 * s.radius for s in segs
                   if isinstance(s, Arc) and not s.ccw and abs(s.sweep) >= math.pi - 1e-9]
    min_slot = min(slot_widths, default=math.inf)
    out.append(CheckResult("edm_slot_width", name, min_slot >= edm.min_slot_width_mm - 1e-9,
                           f"narrowest slot {min_slot:.4g} mm, wire needs >= {edm.min_slot_width_mm:.4g} mm"))
    if start_holes:
        missing = 0
        for c in inner:
            poly = _polygon(c.segments)
            if not any(poly.contains(sg.Point(p).buffer(rad)) for p, rad in starts):
                missing += 1
        out.append(CheckResult("edm_start_holes", name, missing == 0,
                               f"{len(inner)} closed cut-outs, {missing} without a start hole"))
    if web_thickness_mm is not None:
        web = thinnest_ligament(segs)
        out.append(CheckResult("dxf_web_thickness", name, abs(web - web_thickness_mm) <= WEB_TOL_MM,
                               f"measured {web:.6f} mm vs design {web_thickness_mm:.6f} mm"))
    return out


def _on_contour(p: Point, c: Contour) -> bool:
    return _polygon(c.segments).exterior.distance(sg.Point(p)) <= 1e-3


def _lead_in_checks(name: str, r: DxfReading, pieces: list[tuple[Contour, list[Contour]]],
                    web_parts: list[bool]) -> list[CheckResult]:
    """Each contour has exactly one lead-in: a LINE from a marked POINT to a
    point on the contour, starting outside the part for the outer cut and
    inside the cut-out for a hole. On a part with a web, every entry keeps
    :data:`LEAD_IN_CLEARANCE_MM` from the concave arcs (notch over the web,
    tip-root fillet) and is not on the topmost edge (the contact face)."""
    problems: list[str] = []
    unmatched = list(r.lead_lines)
    starts = {(round(p[0], 6), round(p[1], 6)) for p in r.lead_points}
    n_contours = 0
    for (outer, inner), has_web in zip(pieces, web_parts):
        outer_poly = _polygon(outer.segments)
        keep = []
        if has_web:
            segs = _ccw(outer.segments)
            keep = [s for s in segs if isinstance(s, Arc) and not s.ccw]
            top = max(max(s.start[1], s.end[1]) for s in segs)
            keep += [s for s in segs if isinstance(s, Line) and abs(s.start[1] - top) < 1e-9
                     and abs(s.end[1] - top) < 1e-9]
        for k, c in enumerate([outer] + inner):
            n_contours += 1
            hits = [ln for ln in unmatched if _on_contour(ln[1], c)]
            if len(hits) != 1:
                problems.append(f"{len(hits)} lead-ins on a contour")
                continue
            start, entry = hits[0]
            unmatched.remove(hits[0])
            inside = outer_poly.contains(sg.Point(start)) if k == 0 else _polygon(c.segments).contains(sg.Point(start))
            if (k == 0 and inside) or (k > 0 and not inside):
                problems.append(f"lead-in start {start} on the wrong side")
            if (round(start[0], 6), round(start[1], 6)) not in starts:
                problems.append(f"lead-in start {start} not marked by a POINT")
            for s in keep:
                d = sg.LineString(contour_points((s,))+[s.end]).distance(sg.Point(entry))
                if d < LEAD_IN_CLEARANCE_MM - 1e-9:
                    problems.append(f"entry {tuple(round(v, 3) for v in entry)} {d:.3f} mm from "
                                    "the web or contact face")
    if unmatched:
        problems.append(f"{len(unmatched)} lead-ins on no contour")
    return [CheckResult("dxf_lead_in", name, not problems,
                        "; ".join(problems[:3]) or f"{n_contours} contours, one lead-in each, "
                        "off the web and contact face")]


def _pieces(contours: list[Contour]) -> list[tuple[Contour, list[Contour]]]:
    """Outer contours (inside no other) with the contours they enclose."""
    polys = [_polygon(c.segments) for c in contours]
    outer_idx = [i for i, p in enumerate(polys)
                 if not any(j != i and q.contains(p.representative_point()) and q.area > p.area
                            for j, q in enumerate(polys))]
    out = []
    for i in outer_idx:
        inner = [contours[j] for j in range(len(contours))
                 if j not in outer_idx and polys[i].contains(polys[j].representative_point())]
        out.append((contours[i], inner))
    return out


def check_profile_dxf(path: str | Path, name: str, face_area_mm2: float,
                      face_bbox_mm: tuple[float, float, float, float], edm: EdmRules,
                      web_thickness_mm: float | None = None, lead_ins: bool = True,
                      marks: Sequence[str] = (), start_holes: bool = True) -> list[CheckResult]:
    """Every DXF check for one wire-cut profile.

    Args:
        path: the DXF file.
        name: subject name for the report.
        face_area_mm2, face_bbox_mm: area and (xmin, ymin, xmax, ymax) of the CAD face.
        edm: wire-EDM rules of the design.
        web_thickness_mm: the design's web thickness, when the part has a flexure hinge.
        lead_ins: whether the file must carry one lead-in per contour (shop files do).
        marks: the part-mark texts the ``MARK`` layer must hold.
        start_holes: whether every cut-out must hold a drilled start hole (wire EDM).
    """
    r = read_dxf(path)
    out = _file_checks(r, name)
    if not r.contours:
        return out + [CheckResult("dxf_contours", name, False, f"no contour on layer {CUT_LAYER}")]
    worst_gap = max(c.gap_mm for c in r.contours)
    out.append(CheckResult("dxf_closed_contours", name, all(c.closed for c in r.contours),
                           f"{len(r.contours)} contours, worst gap {worst_gap:.1e} mm"))
    areas = [contour_area(c.segments) for c in r.contours]
    outer_i = max(range(len(areas)), key=lambda i: abs(areas[i]))
    outer = r.contours[outer_i]
    inner = [c for i, c in enumerate(r.contours) if i != outer_i]
    bb = contour_bbox(outer.segments)
    dev = max(abs(a - b) for a, b in zip(bb, face_bbox_mm))
    out.append(CheckResult("dxf_bbox", name, dev <= BBOX_TOL_MM, f"max deviation {dev:.1e} mm"))
    out += _piece_checks(name, outer, inner, r.start_holes, face_area_mm2, edm, web_thickness_mm,
                         start_holes=start_holes)
    if lead_ins:
        out += _lead_in_checks(name, r, [(outer, inner)], [web_thickness_mm is not None])
    if marks:
        out.append(CheckResult("dxf_part_marks", name, sorted(r.marks) == sorted(marks),
                               f"MARK layer: {', '.join(r.marks) or 'none'}"))
    return out


@dataclass(frozen=True)
class SheetPart:
    """What a nested sheet must hold of one profile: face area (mm^2), width
    and height of its bounding box (mm), web thickness (mm) or None, and the
    mark of each copy."""

    part: str
    face_area_mm2: float
    size_mm: tuple[float, float]
    web_thickness_mm: float | None
    marks: tuple[str, ...]


def check_sheet_dxf(path: str | Path, name: str, parts: Sequence[SheetPart], edm: EdmRules,
                    gap_mm: float, lead_ins: bool = True,
                    start_holes: bool = True) -> list[CheckResult]:
    """Every check of a nested sheet, read from the file: file checks, closed
    contours, one outer contour per copy matched to its profile by area and
    box size, each copy's cutting rules (``edm``: anything with
    ``min_inside_radius_mm`` and ``min_slot_width_mm``) and web, lead-ins
    (``lead_ins``: a cutting tool's file) and drilled start holes
    (``start_holes``: wire EDM's), part marks, and the gap
    between copies (outer contours >= ``gap_mm`` apart, no lead-in line
    crossing another copy)."""
    r = read_dxf(path)
    out = _file_checks(r, name)
    out.append(CheckResult("dxf_closed_contours", name, bool(r.contours) and all(c.closed for c in r.contours),
                           f"{len(r.contours)} contours"))
    pieces = _pieces(r.contours)
    expected = [p for p in parts for _ in p.marks]
    out.append(CheckResult("sheet_copies", name, len(pieces) == len(expected),
                           f"{len(pieces)} parts on the sheet, {len(expected)} expected"))
    pool = list(expected)
    web_flags = []
    for k, (outer, inner) in enumerate(pieces):
        net = _net_area(outer, inner)
        x0, y0, x1, y1 = contour_bbox(outer.segments)
        match = min(pool, key=lambda p: abs(p.face_area_mm2 - net) + abs(p.size_mm[0] - (x1 - x0))
                    + abs(p.size_mm[1] - (y1 - y0)), default=None)
        if match is None:
            out.append(CheckResult("sheet_copies", f"{name}: part {k + 1}", False, "no such profile expected"))
            web_flags.append(False)
            continue
        pool.remove(match)
        sub = f"{name}: {match.part} at ({x0:.1f}, {y0:.1f})"
        size_dev = max(abs(match.size_mm[0] - (x1 - x0)), abs(match.size_mm[1] - (y1 - y0)))
        out.append(CheckResult("dxf_bbox", sub, size_dev <= BBOX_TOL_MM, f"size deviation {size_dev:.1e} mm"))
        out += _piece_checks(sub, outer, inner, r.start_holes, match.face_area_mm2, edm,
                             match.web_thickness_mm, start_holes=start_holes)
        web_flags.append(match.web_thickness_mm is not None)
    if lead_ins:
        out += _lead_in_checks(name, r, pieces, web_flags)
    polys = [_polygon(o.segments) for o, _ in pieces]
    closest = min((polys[i].distance(polys[j]) for i in range(len(polys)) for j in range(i)),
                  default=math.inf)
    crossing = sum(1 for a, b in r.lead_lines
                   if sum(1 for p in polys if p.intersects(sg.LineString([a, b]))) > 1)
    out.append(CheckResult("sheet_gap", name, closest >= gap_mm - 1e-6 and crossing == 0,
                           f"closest parts {closest:.3f} mm apart (>= {gap_mm:.3f} mm), "
                           f"{crossing} lead-ins crossing another part"))
    want = sorted(m for p in parts for m in p.marks)
    out.append(CheckResult("dxf_part_marks", name, sorted(r.marks) == want,
                           f"{len(r.marks)} marks on MARK, {len(want)} expected"))
    return out


def _reverse(segments: tuple[Segment, ...]) -> tuple[Segment, ...]:
    return tuple((Line(s.end, s.start) if isinstance(s, Line) else Arc(s.end, s.start, s.centre, not s.ccw))
                 for s in reversed(segments))


# --- what a process adds to the file: tabs, cut order, etch compensation ---------
TAB_TOL_MM = 1e-6
#: How close the artwork's outline lies to the nominal one offset by the
#: compensation (mm): the offset is drawn as short lines 1e-4 mm from the exact one.
OFFSET_TOL_MM = 1e-3


def outer_contours(r: DxfReading) -> list[Contour]:
    """The outer contours of a file read back (one per part)."""
    return [outer for outer, _ in _pieces(r.contours)]


def tab_checks(name: str, r: DxfReading, expected: Sequence[tuple[int, float]]) -> list[CheckResult]:
    """The holding tabs on layer ``TAB``: each a LINE with both ends on a
    part's outer contour, as many per part and as wide as ``expected``
    ((count, width mm) per outer contour, in the order of
    :func:`outer_contours`)."""
    outers = [_polygon(c.segments).exterior for c in outer_contours(r)]
    problems = []
    if len(outers) != len(expected):
        problems.append(f"{len(outers)} parts, {len(expected)} expected")
    counts = [0] * len(outers)
    for a, b in r.tabs:
        on = [i for i, ring in enumerate(outers)
              if ring.distance(sg.Point(a)) <= 1e-6 and ring.distance(sg.Point(b)) <= 1e-6]
        if not on:
            problems.append(f"tab {tuple(round(v, 3) for v in a)} off every outer contour")
            continue
        counts[on[0]] += 1
        want = expected[on[0]][1] if on[0] < len(expected) else 0.0
        if abs(math.dist(a, b) - want) > TAB_TOL_MM:
            problems.append(f"tab {math.dist(a, b):.4g} mm wide, rule {want:g} mm")
    for i, (count, width) in enumerate(expected[:len(outers)]):
        if counts[i] != count:
            problems.append(f"part {i + 1}: {counts[i]} tabs, rule {count} x {width:g} mm")
    total = sum(c for c, _ in expected)
    return [CheckResult("dxf_tabs", name, not problems,
                        "; ".join(problems[:3]) or f"{total} tabs on layer TAB, on the outer "
                        "contours, by the rule's count and width")]


def cut_order_checks(name: str, r: DxfReading, stated: bool) -> list[CheckResult]:
    """The cut order: every lead-in start carries a number on ``CUT_ORDER``,
    numbered 1 ... n per part with the outer contour last (its start lies
    outside the part), and the file states the order in its ``CUT_ORDER``
    property (R2010; ``stated``: the process states one)."""
    problems = []
    at = {(round(p[0], 6), round(p[1], 6)): t for t, p in r.order}
    for start, _entry in r.lead_lines:
        if (round(start[0], 6), round(start[1], 6)) not in at:
            problems.append(f"lead-in at {tuple(round(v, 3) for v in start)} has no number")
    for outer, inner in _pieces(r.contours):
        poly = _polygon(outer.segments)
        mine = [(t, p) for t, p in r.order if poly.buffer(2.0).contains(sg.Point(p))]
        numbers = sorted(int(t) for t, _ in mine if t.isdigit())
        if numbers != list(range(1, len(inner) + 2)):
            problems.append(f"numbers {numbers}, expected 1 ... {len(inner) + 1}")
            continue
        last = [p for t, p in mine if t == str(len(inner) + 1)]
        if any(poly.contains(sg.Point(p)) for p in last):
            problems.append("the outer contour is not cut last")
    if stated and r.version != "AC1009" and "CUT_ORDER" not in r.properties:
        problems.append("no CUT_ORDER property")
    return [CheckResult("dxf_cut_order", name, not problems,
                        "; ".join(problems[:3]) or "inner contours first, the outer contour "
                        "last, each lead-in numbered; " + r.properties.get("CUT_ORDER", "")[:60])]


def check_etch_artwork(path: str | Path, name: str, nominal_outer: Sequence[Segment],
                       nominal_holes: Sequence[tuple[Point, float]], offset_mm: float,
                       marks: Sequence[str] = ()) -> list[CheckResult]:
    """Every check of one etch artwork file: the file checks, closed contours,
    the outline ``offset_mm`` outside the nominal one all round (its points
    that far from the nominal contour, the nominal inside it) and each hole
    the nominal's, smaller in radius by ``offset_mm``; no lead-ins (the etch
    enters nowhere)."""
    r = read_dxf(path)
    out = _file_checks(r, name)
    if not r.contours:
        return out + [CheckResult("dxf_contours", name, False, f"no contour on layer {CUT_LAYER}")]
    out.append(CheckResult("dxf_closed_contours", name, all(c.closed for c in r.contours),
                           f"{len(r.contours)} contours"))
    areas = [abs(contour_area(c.segments)) for c in r.contours]
    outer = r.contours[max(range(len(areas)), key=areas.__getitem__)]
    art = _polygon(outer.segments)
    nominal = _polygon(tuple(nominal_outer))
    dist = [nominal.exterior.distance(sg.Point(p)) for p in art.exterior.coords]
    worst = max(abs(d - offset_mm) for d in dist)
    out.append(CheckResult(
        "etch_compensation", name, worst <= OFFSET_TOL_MM and art.contains(nominal),
        f"outline {min(dist):.4f}-{max(dist):.4f} mm outside the nominal, compensation "
        f"{offset_mm:.4f} mm per side (worst {worst:.1e} mm off)"))
    circles = [(c.segments[0].centre, c.segments[0].radius) for c in r.contours
               if c is not outer and len(c.segments) == 2 and all(isinstance(s, Arc) for s in c.segments)]
    missing = [h for h in nominal_holes
               if not any(math.dist(h[0], c) <= 1e-6 and abs(h[1] - offset_mm - rad) <= 1e-6
                          for c, rad in circles)]
    out.append(CheckResult("etch_holes", name, not missing and len(circles) == len(nominal_holes),
                           f"{len(circles)} holes, each the nominal's radius less "
                           f"{offset_mm:.4f} mm" + (f"; {len(missing)} not found" if missing else "")))
    out.append(CheckResult("etch_no_lead_ins", name, not r.lead_lines and not r.start_holes,
                           f"{len(r.lead_lines)} lead-ins, {len(r.start_holes)} start holes"))
    if marks:
        out.append(CheckResult("dxf_part_marks", name, sorted(r.marks) == sorted(marks),
                               f"MARK layer: {', '.join(r.marks) or 'none'}"))
    return out
