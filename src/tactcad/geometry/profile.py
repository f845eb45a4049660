r"""The wire-cut flexure profile as exact lines and arcs (no CAD kernel).

This one description feeds the solid (:mod:`tactcad.partlib.array.element`), the
wire-EDM DXF (:mod:`tactcad.export.dxf`), the FEM meshes and the closed-form
web function, so all of them see the same contour. Element frame, mm (see
:mod:`tactcad.design.array_plan`).

Outer contour, counter-clockwise from the base's lower back corner::

                                        +--+  <- contact face (tip_width)
    +-----------------------------------+  |   top face y = base_height:
    |  o   o        base      web ^ (_) |  |   the gauge sits over the web
    |                               / \_______|   arm underside
    |                              |
    +------------------------------+   notch: circle of radius R whose top
                                        point is web_thickness below the top
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, Protocol, Sequence

Point = tuple[float, float]


class NotchShape(Protocol):
    """What the notch's web function reads of an element (mm, element frame):
    the notch centre's x, its radius and the web over it."""

    @property
    def hinge_x_mm(self) -> float: ...
    @property
    def notch_radius_mm(self) -> float: ...
    @property
    def web_thickness_mm(self) -> float: ...


class RoundHole(Protocol):
    """A round through hole of the profile (mm, element frame)."""

    @property
    def x_mm(self) -> float: ...
    @property
    def y_mm(self) -> float: ...
    @property
    def diameter_mm(self) -> float: ...


class ElementOutline(NotchShape, Protocol):
    """What the wire-cut profile reads of an element (mm, element frame): the
    plan's element geometry (:class:`tactcad.partlib.array.element.ElementGeometry`)
    is one; geometry names no part module."""

    @property
    def overall_length_mm(self) -> float: ...
    @property
    def base_height_mm(self) -> float: ...
    @property
    def notch_centre_y_mm(self) -> float: ...
    @property
    def tip_width_mm(self) -> float: ...
    @property
    def inside_corner_radius_mm(self) -> float: ...
    @property
    def arm_underside_y_mm(self) -> float: ...
    @property
    def tip_top_y_mm(self) -> float: ...
    @property
    def bolt_holes(self) -> Sequence[RoundHole]: ...
    @property
    def start_hole_diameter_mm(self) -> float: ...


@dataclass(frozen=True)
class Line:
    start: Point
    end: Point

    def length(self) -> float:
        return math.dist(self.start, self.end)


@dataclass(frozen=True)
class Arc:
    """Circular arc from ``start`` to ``end`` about ``centre``; ``ccw`` gives the sense."""

    start: Point
    end: Point
    centre: Point
    ccw: bool

    @property
    def radius(self) -> float:
        return math.dist(self.start, self.centre)

    @property
    def sweep(self) -> float:
        """Signed sweep angle (rad), positive counter-clockwise, |sweep| < 2 pi."""
        a0 = math.atan2(self.start[1] - self.centre[1], self.start[0] - self.centre[0])
        a1 = math.atan2(self.end[1] - self.centre[1], self.end[0] - self.centre[0])
        d = a1 - a0
        if self.ccw:
            while d <= 0:
                d += 2 * math.pi
        else:
            while d >= 0:
                d -= 2 * math.pi
        return d

    @property
    def midpoint(self) -> Point:
        a0 = math.atan2(self.start[1] - self.centre[1], self.start[0] - self.centre[0])
        am = a0 + self.sweep / 2
        r = self.radius
        return (self.centre[0] + r * math.cos(am), self.centre[1] + r * math.sin(am))

    @property
    def bulge(self) -> float:
        """DXF LWPOLYLINE bulge: tan(sweep / 4), positive counter-clockwise."""
        return math.tan(self.sweep / 4)

    def length(self) -> float:
        return abs(self.sweep) * self.radius


Segment = Line | Arc


@dataclass(frozen=True)
class Circle:
    centre: Point
    radius: float


@dataclass(frozen=True)
class Profile:
    """A planar part outline: one closed outer contour (CCW), round holes,
    and the start hole drilled inside each closed cut-out for the wire."""

    outer: tuple[Segment, ...]
    holes: tuple[Circle, ...]
    start_holes: tuple[Circle, ...]

    @property
    def area_mm2(self) -> float:
        return contour_area(self.outer) - sum(math.pi * h.radius**2 for h in self.holes)

    @property
    def bbox_mm(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the outer contour, exact for arcs."""
        return contour_bbox(self.outer)


def contour_area(segments: Sequence[Segment]) -> float:
    """Signed area (mm^2) of a closed chain of lines and arcs (positive if CCW).

    Shoelace over the chord polygon plus, for each arc, the circular segment
    between arc and chord: (r^2 / 2)(theta - sin theta), signed by the sweep.
    """
    area = 0.0
    for s in segments:
        (x0, y0), (x1, y1) = s.start, s.end
        area += 0.5 * (x0 * y1 - x1 * y0)
        if isinstance(s, Arc):
            th = s.sweep
            area += 0.5 * s.radius**2 * (th - math.sin(th))
    return area


def contour_points(segments: Sequence[Segment], sagitta_mm: float = 1e-4) -> list[Point]:
    """Vertices of a polygon through a closed chain (mm): arcs split so that
    no chord departs from its arc by more than ``sagitta_mm``."""
    pts: list[Point] = []
    for s in segments:
        pts.append(s.start)
        if isinstance(s, Arc):
            r, sweep = s.radius, s.sweep
            n = max(2, int(math.ceil(abs(sweep) / (2 * math.acos(max(-1.0, 1 - sagitta_mm / r))))))
            a0 = math.atan2(s.start[1] - s.centre[1], s.start[0] - s.centre[0])
            pts.extend((s.centre[0] + r * math.cos(a0 + sweep * k / n),
                        s.centre[1] + r * math.sin(a0 + sweep * k / n)) for k in range(1, n))
    return pts


def _arc_extremes(arc: Arc) -> list[Point]:
    pts = [arc.start, arc.end]
    a0 = math.atan2(arc.start[1] - arc.centre[1], arc.start[0] - arc.centre[0])
    sweep = arc.sweep
    r = arc.radius
    for k in range(-8, 9):
        ang = k * math.pi / 2
        rel = (ang - a0) / sweep if sweep else -1
        if 0 < rel < 1:
            pts.append((arc.centre[0] + r * math.cos(ang), arc.centre[1] + r * math.sin(ang)))
    return pts


def contour_bbox(segments: Iterable[Segment]) -> tuple[float, float, float, float]:
    pts: list[Point] = []
    for s in segments:
        pts.extend(_arc_extremes(s) if isinstance(s, Arc) else [s.start, s.end])
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    return (min(xs), min(ys), max(xs), max(ys))


def _chain(points_and_arcs: list) -> tuple[Segment, ...]:
    """Close a list of vertices, where an ``("arc", centre, ccw)`` marker between
    two vertices makes that edge an arc, into a chain of segments."""
    verts: list[Point] = []
    kinds: list[tuple | None] = []
    for item in points_and_arcs:
        if isinstance(item, tuple) and item and item[0] == "arc":
            kinds[-1] = item
        else:
            verts.append(item)
            kinds.append(None)
    segs: list[Segment] = []
    for i, p in enumerate(verts):
        q = verts[(i + 1) % len(verts)]
        k = kinds[i]
        segs.append(Line(p, q) if k is None else Arc(p, q, k[1], k[2]))
    return tuple(segs)


def element_profile(g: ElementOutline) -> Profile:
    """Exact wire-cut profile of a flexure sensing element.

    Args:
        g: element geometry from the plan (mm), any :class:`ElementOutline`.

    Returns:
        :class:`Profile` with the CCW outer contour (lines and arcs only), the
        bolt holes and one start hole at the centre of each bolt hole.
    """
    L, H = g.overall_length_mm, g.base_height_mm
    R = g.notch_radius_mm
    xh, yc = g.hinge_x_mm, g.notch_centre_y_mm
    w, r = g.tip_width_mm, g.inside_corner_radius_mm
    y_arm = g.arm_underside_y_mm
    y_tip = g.tip_top_y_mm
    x_tip_l = L - w
    outer = _chain([
        (0.0, 0.0),
        (xh - R, 0.0),                      # underside of the base
        (xh - R, yc), ("arc", (xh, yc), False),   # notch: concave, clockwise over the top
        (xh + R, yc),
        (xh + R, y_arm),                    # notch front wall down to the arm underside
        (L, y_arm),                         # arm underside
        (L, y_tip),                         # tip front face
        (x_tip_l, y_tip),                   # contact face
        (x_tip_l, H + r), ("arc", (x_tip_l - r, H + r), False),  # tip-root fillet
        (x_tip_l - r, H),
        (0.0, H),                           # flat top face: gauge over the web
    ])
    holes = tuple(Circle((h.x_mm, h.y_mm), h.diameter_mm / 2) for h in g.bolt_holes)
    starts = tuple(Circle(c.centre, g.start_hole_diameter_mm / 2) for c in holes)
    return Profile(outer=outer, holes=holes, start_holes=starts)


class CombSheetOutline(Protocol):
    """What the comb sheet's outline reads of one row's sheet (mm, sheet frame): the plan's
    :class:`tactcad.partlib.array.comb_sheet.CombSheet` is one; geometry names no part
    module."""

    @property
    def elements(self) -> Sequence[ElementOutline]: ...
    @property
    def offsets_mm(self) -> Sequence[float]: ...
    @property
    def ledges_mm(self) -> Sequence[float]: ...
    @property
    def length_mm(self) -> float: ...
    @property
    def holes(self) -> Sequence[RoundHole]: ...
    @property
    def start_hole_diameter_mm(self) -> float: ...


def comb_sheet_profile(sheet: CombSheetOutline) -> Profile:
    """Exact outline of one row's comb sheet (CCW, lines and arcs; sheet frame, mm).

    The walk runs along the spine's underside, up the row's far end, then back
    over every element from the last to the first: along its stop ledge to its
    post (an inside corner filleted at the element's inside corner radius, as is
    the slot's floor at the post's back), up the notch's back wall, over the notch, down the arm's front wall,
    along the arm's underside, up the tip's front face, over the contact face
    and back along the flat top over the web to the post's back face. The
    element's own contour (:func:`element_profile`) is walked the same way, so the web,
    notch and arm are the element's. The part's solid, its DXF and the comb's plane
    finite-element model (:mod:`tactcad.mechanics.comb_fem2d`) all cut this one outline.
    """
    pts: list = [(0.0, 0.0), (sheet.length_mm, 0.0), (sheet.length_mm, sheet.ledges_mm[-1])]
    n = len(sheet.elements)
    for i in reversed(range(n)):
        g, x0 = sheet.elements[i], sheet.offsets_mm[i]
        R, xh, yc = g.notch_radius_mm, x0 + g.hinge_x_mm, g.notch_centre_y_mm
        L, H, w, r = x0 + g.overall_length_mm, g.base_height_mm, g.tip_width_mm, g.inside_corner_radius_mm
        ledge = sheet.ledges_mm[i]
        # the ledge meets the post's front wall in a fillet of the wire's inside radius
        pts += [(xh - R + r, ledge), ("arc", (xh - R + r, ledge + r), False), (xh - R, ledge + r),
                (xh - R, yc), ("arc", (xh, yc), False), (xh + R, yc),
                (xh + R, g.arm_underside_y_mm), (L, g.arm_underside_y_mm), (L, g.tip_top_y_mm),
                (L - w, g.tip_top_y_mm), (L - w, H + r), ("arc", (L - w - r, H + r), False),
                (L - w - r, H), (x0, H)]
        if i == 0:
            pts.append((x0, 0.0))
        else:  # the post's back wall meets the slot's floor in a fillet too
            floor = sheet.ledges_mm[i - 1]
            pts += [(x0, floor + r), ("arc", (x0 - r, floor + r), False), (x0 - r, floor)]
    holes = tuple(Circle((h.x_mm, h.y_mm), h.diameter_mm / 2) for h in sheet.holes)
    starts = tuple(Circle(c.centre, sheet.start_hole_diameter_mm / 2) for c in holes)
    return Profile(outer=_chain(_without_repeats(pts)), holes=holes, start_holes=starts)


def _without_repeats(points: list) -> list:
    """The walk less a vertex that repeats the one before (the first post's
    back face ends where the walk began)."""
    out: list = []
    for p in points:
        if out and not (isinstance(p, tuple) and p and p[0] == "arc") and p == out[-1]:
            continue
        out.append(p)
    if len(out) > 1 and out[-1] == out[0]:
        out.pop()
    return out


def web_thickness_at(g: NotchShape, x: float) -> float:
    """Material height (mm) over the notch at ``x`` (element frame):
    h(x) = t + R - sqrt(R^2 - (x - x_h)^2) for |x - x_h| <= R."""
    d = x - g.hinge_x_mm
    R = g.notch_radius_mm
    if abs(d) > R:
        raise ValueError(f"x = {x} mm is outside the notch ({g.hinge_x_mm - R} ... {g.hinge_x_mm + R} mm)")
    return g.web_thickness_mm + R - math.sqrt(R * R - d * d)


def inside_corners(segments: Sequence[Segment], tol_rad: float = 1e-9) -> list[tuple[Point, float]]:
    """Concave (inside) corners of a CCW contour with the radius the wire cuts there.

    A sharp concave vertex has radius 0. A concave (clockwise) arc is an inside
    corner of its own radius. Returns a list of (location, radius_mm).
    """
    out: list[tuple[Point, float]] = []
    n = len(segments)
    for i, s in enumerate(segments):
        if isinstance(s, Arc) and not s.ccw:
            out.append((s.midpoint, s.radius))
        nxt = segments[(i + 1) % n]
        d_in = _tangent(s, at_end=True)
        d_out = _tangent(nxt, at_end=False)
        cross = d_in[0] * d_out[1] - d_in[1] * d_out[0]
        dot = d_in[0] * d_out[0] + d_in[1] * d_out[1]
        turn = math.atan2(cross, dot)
        if turn < -tol_rad:  # right turn on a CCW contour: a concave vertex
            out.append((s.end, 0.0))
    return out


def _tangent(s: Segment, at_end: bool) -> Point:
    if isinstance(s, Line):
        dx, dy = s.end[0] - s.start[0], s.end[1] - s.start[1]
    else:
        p = s.end if at_end else s.start
        rx, ry = p[0] - s.centre[0], p[1] - s.centre[1]
        dx, dy = (-ry, rx) if s.ccw else (ry, -rx)
    n = math.hypot(dx, dy)
    return (dx / n, dy / n)


def rectangle_profile(length: float, height: float, holes: Iterable[tuple[float, float, float]]) -> Profile:
    """Rectangle [0, length] x [0, height] (mm) with round holes (x, y, diameter)."""
    outer = _chain([(0.0, 0.0), (length, 0.0), (length, height), (0.0, height)])
    return Profile(outer=outer, holes=tuple(Circle((x, y), d / 2) for x, y, d in holes),
                   start_holes=())


def u_plate_profile(half_length: float, window_half_width: float, height: float,
                    bridge_height: float, corner_radius: float,
                    holes: Iterable[tuple[float, float, float]]) -> Profile:
    """U-shaped plate centred on x = 0 (mm): two legs joined by a bridge of
    ``bridge_height``; the window's inside corners are rounded to ``corner_radius``
    (the milling cutter radius)."""
    a, w, h, b, r = half_length, window_half_width, height, bridge_height, corner_radius
    outer = _chain([
        (-a, 0.0), (a, 0.0), (a, h), (w, h),
        (w, b + r), ("arc", (w - r, b + r), False),
        (w - r, b),
        (-w + r, b), ("arc", (-w + r, b + r), False),
        (-w, b + r),
        (-w, h), (-a, h),
    ])
    return Profile(outer=outer, holes=tuple(Circle((x, y), d / 2) for x, y, d in holes),
                   start_holes=())
