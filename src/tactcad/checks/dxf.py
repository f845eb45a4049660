"""Round trip of a wire-EDM DXF: read it back and compare with the design.

Everything is measured on what ezdxf reads from the file (bulges turned back
into exact arcs), never on the in-memory profile that wrote it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import ezdxf
import shapely.geometry as sg

from tactcad.design.array import EdmRules
from tactcad.export.dxf import CUT_LAYER, START_LAYER
from tactcad.geometry.profile import Arc, Line, Point, Segment, contour_area, contour_bbox, inside_corners
from tactcad.checks.result import CheckResult

ALLOWED_TYPES = {"LINE", "ARC", "CIRCLE", "LWPOLYLINE"}
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
    max_z = 0.0
    for e in msp:
        t = e.dxftype()
        types.add(t)
        layer = e.dxf.layer
        if t == "LWPOLYLINE":
            max_z = max(max_z, abs(e.dxf.elevation))
        elif t in ("CIRCLE", "ARC"):
            max_z = max(max_z, abs(e.dxf.center[2]))
        elif t == "LINE":
            max_z = max(max_z, abs(e.dxf.start[2]), abs(e.dxf.end[2]))
        if hasattr(e.dxf, "extrusion") and tuple(e.dxf.extrusion) != (0.0, 0.0, 1.0):
            max_z = max(max_z, math.inf)
        if layer == START_LAYER and t == "CIRCLE":
            starts.append(((e.dxf.center[0], e.dxf.center[1]), e.dxf.radius))
        elif layer == CUT_LAYER:
            if t == "LWPOLYLINE":
                contours.append(_lwpolyline_contour(e))
            elif t == "CIRCLE":
                contours.append(_circle_contour(e.dxf.center, e.dxf.radius))
            elif t in ("LINE", "ARC"):
                loose.append(_loose_segment(e))
    contours.extend(_chain_loose(loose))
    return DxfReading(types=types, units=int(doc.header.get("$INSUNITS", 0)),
                      audit_errors=len(auditor.errors), max_abs_z=max_z, contours=contours,
                      start_holes=starts)


# --- geometry on exact segments -------------------------------------------------
def _angle_in_arc(arc: Arc, p: Point) -> bool:
    a0 = math.atan2(arc.start[1] - arc.centre[1], arc.start[0] - arc.centre[0])
    a = math.atan2(p[1] - arc.centre[1], p[0] - arc.centre[0])
    sweep = arc.sweep
    d = (a - a0) % (2 * math.pi) if sweep > 0 else (a0 - a) % (2 * math.pi)
    return d <= abs(sweep) + 1e-12


def _ray_hit(origin: Point, direction: Point, line: Line) -> float:
    """Distance along a ray to a line segment (inf if it misses)."""
    (x0, y0), (x1, y1) = line.start, line.end
    ex, ey = x1 - x0, y1 - y0
    dx, dy = direction
    den = dx * ey - dy * ex
    if abs(den) < 1e-15:
        return math.inf
    wx, wy = x0 - origin[0], y0 - origin[1]
    t = (wx * ey - wy * ex) / den  # along the ray
    u = (wx * dy - wy * dx) / den  # along the segment
    return t if t > 1e-12 and -1e-12 <= u <= 1 + 1e-12 else math.inf


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
        for ang in angles:
            direction = (math.cos(ang), math.sin(ang))
            p = (cx + s.radius * direction[0], cy + s.radius * direction[1])
            if not _angle_in_arc(s, p):
                continue
            hit = min(_ray_hit(p, direction, ln) for ln in lines)
            best = min(best, hit)
    return best


def _polygon(segments: tuple[Segment, ...], sagitta: float = 1e-4) -> sg.Polygon:
    pts: list[Point] = []
    for s in segments:
        pts.append(s.start)
        if isinstance(s, Arc):
            r, sweep = s.radius, s.sweep
            n = max(2, int(math.ceil(abs(sweep) / (2 * math.acos(max(-1.0, 1 - sagitta / r))))))
            a0 = math.atan2(s.start[1] - s.centre[1], s.start[0] - s.centre[0])
            pts.extend((s.centre[0] + r * math.cos(a0 + sweep * k / n),
                        s.centre[1] + r * math.sin(a0 + sweep * k / n)) for k in range(1, n))
    return sg.Polygon(pts)


def check_profile_dxf(path: str | Path, name: str, face_area_mm2: float,
                      face_bbox_mm: tuple[float, float, float, float], edm: EdmRules,
                      web_thickness_mm: float | None = None) -> list[CheckResult]:
    """Every DXF check for one wire-cut profile.

    Args:
        path: the DXF file.
        name: subject name for the report.
        face_area_mm2, face_bbox_mm: area and (xmin, ymin, xmax, ymax) of the CAD face.
        edm: wire-EDM rules of the design.
        web_thickness_mm: the design's web thickness, when the part has a flexure hinge.
    """
    r = read_dxf(path)
    out = [
        CheckResult("dxf_audit", name, r.audit_errors == 0, f"{r.audit_errors} auditor errors"),
        CheckResult("dxf_entity_types", name, r.types <= ALLOWED_TYPES, ", ".join(sorted(r.types))),
        CheckResult("dxf_units_mm", name, r.units == 4, f"$INSUNITS = {r.units}"),
        CheckResult("dxf_flat_z0", name, r.max_abs_z <= CLOSE_TOL_MM, f"max |z| {r.max_abs_z:.1e}"),
    ]
    if not r.contours:
        return out + [CheckResult("dxf_contours", name, False, f"no contour on layer {CUT_LAYER}")]
    worst_gap = max(c.gap_mm for c in r.contours)
    out.append(CheckResult("dxf_closed_contours", name, all(c.closed for c in r.contours),
                           f"{len(r.contours)} contours, worst gap {worst_gap:.1e} mm"))
    areas = [contour_area(c.segments) for c in r.contours]
    outer_i = max(range(len(areas)), key=lambda i: abs(areas[i]))
    outer = r.contours[outer_i]
    inner = [c for i, c in enumerate(r.contours) if i != outer_i]
    net = abs(areas[outer_i]) - sum(abs(a) for i, a in enumerate(areas) if i != outer_i)
    rel = abs(net - face_area_mm2) / face_area_mm2
    out.append(CheckResult("dxf_area", name, rel <= AREA_RTOL,
                           f"{net:.6f} mm2 vs CAD face {face_area_mm2:.6f} (rel {rel:.1e})"))
    bb = contour_bbox(outer.segments)
    dev = max(abs(a - b) for a, b in zip(bb, face_bbox_mm))
    out.append(CheckResult("dxf_bbox", name, dev <= BBOX_TOL_MM, f"max deviation {dev:.1e} mm"))
    # Wire-EDM manufacturability, measured on the file.
    segs = outer.segments if areas[outer_i] > 0 else _reverse(outer.segments)
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
    missing = 0
    for c in inner:
        poly = _polygon(c.segments)
        if not any(poly.contains(sg.Point(p).buffer(rad)) for p, rad in r.start_holes):
            missing += 1
    out.append(CheckResult("edm_start_holes", name, missing == 0,
                           f"{len(inner)} closed cut-outs, {missing} without a start hole"))
    if web_thickness_mm is not None:
        web = thinnest_ligament(segs)
        out.append(CheckResult("dxf_web_thickness", name, abs(web - web_thickness_mm) <= WEB_TOL_MM,
                               f"measured {web:.6f} mm vs design {web_thickness_mm:.6f} mm"))
    return out


def _reverse(segments: tuple[Segment, ...]) -> tuple[Segment, ...]:
    return tuple((Line(s.end, s.start) if isinstance(s, Line) else Arc(s.end, s.start, s.centre, not s.ccw))
                 for s in reversed(segments))
