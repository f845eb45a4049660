"""An SVG drawing sheet in paper millimetres, with the drafting primitives.

Conventions (paper frame: x right, y down, 1 user unit = 1 mm of paper):

* line types and widths after ISO 128-20 / ISO 128-24: visible outlines
  0.5 mm continuous, hidden outlines 0.25 mm dashed, centre lines 0.18 mm
  long-dash-dot, dimension / extension / leader lines 0.18 mm continuous;
* dimensions after ISO 129-1: extension lines leave a 1 mm gap at the feature
  and run 2 mm past the dimension line; closed filled arrowheads (30 deg
  included angle); the value stands above a horizontal dimension line and to
  the left of a vertical one, read from the bottom or the right side; where
  the feature is too small the arrows point inward from outside;
* lettering after ISO 3098 (type B, upright), set in Helvetica, whose metrics
  (from reportlab) place the text; its em size is the nominal height / 0.718
  (Helvetica's cap height), so capitals are exactly the nominal height. The
  SVG names Arial and Liberation Sans (same metrics) as alternatives.

Every text element may carry an ``id`` and a ``class``; dimension values use
``id="dim-<name>"`` and ``class="dim"``, so a reader can find each value.
Coordinates are written with 3 decimals: the same drawing gives the same bytes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

Point = tuple[float, float]

PAPER_SIZES_MM: dict[str, tuple[float, float]] = {"A3": (420.0, 297.0), "A4": (297.0, 210.0)}

FONT = "Helvetica"
# Arial and Liberation Sans share Helvetica's metrics, so text fits wherever one is installed
FONT_FAMILY = "Helvetica, Arial, 'Liberation Sans', sans-serif"
CAP_HEIGHT_EM = 0.718  # Helvetica cap height / em

# ISO 128-20 line widths (mm) and dash patterns (mm of paper).
STYLES: dict[str, tuple[float, str]] = {
    "visible": (0.5, ""),
    "hidden": (0.25, "2.5 1"),
    "centre": (0.18, "6 1 0.5 1"),
    "thin": (0.18, ""),
    "boundary": (0.25, ""),
    "frame": (0.7, ""),
    "table": (0.25, ""),
}

ARROW_LENGTH_MM = 2.5
ARROW_HALF_ANGLE_RAD = math.radians(15.0)
EXT_GAP_MM = 1.0       # gap between the feature and an extension line
EXT_OVERSHOOT_MM = 2.0  # extension line past the dimension line
TEXT_LIFT_MM = 1.0      # text baseline above the dimension line
DIM_TEXT_MM = 2.5       # ISO 3098 nominal height of dimension values
LABEL_TEXT_MM = 3.5     # view labels, title block values


def fmt_mm(value: float, decimals: int = 3) -> str:
    """A length as a drawing prints it: rounded to ``decimals`` places,
    trailing zeros dropped (``22``, ``11.5``, ``0.25``); ``-0`` prints ``0``."""
    text = f"{round(value, decimals):.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def text_width(text: str, height_mm: float) -> float:
    """Printed width (mm) of ``text`` in Helvetica of nominal (cap) height ``height_mm``."""
    from reportlab.pdfbase.pdfmetrics import stringWidth

    return stringWidth(text, FONT, height_mm / CAP_HEIGHT_EM)


def text_box(at: Point, text: str, height_mm: float, anchor: str = "start",
             rotate: float = 0.0) -> tuple[float, float, float, float]:
    """Paper box (left, top, right, bottom; mm) a text covers: its advance
    width, from the cap line to the descender (0.25 of the height below the
    baseline); ``rotate`` 0 or +-90 degrees."""
    w = text_width(text, height_mm)
    start = {"start": 0.0, "middle": -w / 2, "end": -w}[anchor]
    a0, a1 = start, start + w            # along the baseline
    b0, b1 = -height_mm, 0.25 * height_mm  # across it (y down)
    if abs(rotate) < 1e-9:
        return (at[0] + a0, at[1] + b0, at[0] + a1, at[1] + b1)
    if abs(rotate + 90) < 1e-9:          # reads upwards
        return (at[0] + b0, at[1] - a1, at[0] + b1, at[1] - a0)
    return (at[0] - b1, at[1] + a0, at[0] - b0, at[1] + a1)


def overlapping_texts(sheet: "Sheet", tol: float = 0.05) -> list[tuple[str, str]]:
    """Pairs of texts of ``sheet`` whose boxes (:func:`text_box`) overlap by
    more than ``tol`` mm in both directions."""
    out = []
    boxes = sheet.text_boxes
    for i, (ta, a) in enumerate(boxes):
        for tb, b in boxes[i + 1:]:
            if min(a[2], b[2]) - max(a[0], b[0]) > tol and min(a[3], b[3]) - max(a[1], b[1]) > tol:
                out.append((ta, tb))
    return out


def _segment_meets_box(p: Point, q: Point, box: tuple[float, float, float, float]) -> bool:
    """Whether the segment ``p``-``q`` has a point inside ``box`` (Liang-Barsky clipping)."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    t0, t1 = 0.0, 1.0
    for ep, eq in ((-dx, p[0] - box[0]), (dx, box[2] - p[0]), (-dy, p[1] - box[1]),
                   (dy, box[3] - p[1])):
        if abs(ep) < 1e-15:
            if eq < 0:
                return False
            continue
        t = eq / ep
        t0, t1 = (max(t0, t), t1) if ep < 0 else (t0, min(t1, t))
        if t0 >= t1:
            return False
    return True


def _n(v: float) -> str:
    return fmt_mm(v, 3)


@dataclass
class Sheet:
    """An SVG document on a sheet of ``size`` (ISO 216 name), landscape."""

    size: str = "A3"
    title: str = ""
    _groups: dict[str, list[str]] = field(default_factory=dict)
    text_boxes: list[tuple[str, tuple[float, float, float, float]]] = field(default_factory=list)
    #: every stroke drawn so far as paper points (circles as 72-gons), for placing labels clear
    strokes: list[list[Point]] = field(default_factory=list)
    _extents: list[tuple[float, float, float, float]] = field(default_factory=list, init=False,
                                                             repr=False, compare=False)

    @property
    def width_mm(self) -> float:
        return PAPER_SIZES_MM[self.size][0]

    @property
    def height_mm(self) -> float:
        return PAPER_SIZES_MM[self.size][1]

    # -- output -------------------------------------------------------------
    def _add(self, group: str, item: str) -> None:
        self._groups.setdefault(group, []).append(item)

    def svg(self) -> str:
        """The whole document as SVG 1.1 text (UTF-8, no time stamps)."""
        w, h = _n(self.width_mm), _n(self.height_mm)
        out = ['<?xml version="1.0" encoding="UTF-8"?>',
               f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w}mm" '
               f'height="{h}mm" viewBox="0 0 {w} {h}">']
        if self.title:
            out.append(f"<title>{escape(self.title)}</title>")
        out.append(f'<rect x="0" y="0" width="{w}" height="{h}" fill="#ffffff" stroke="none"/>')
        for name, items in self._groups.items():
            out.append(f'<g id={quoteattr(name)}>')
            out.extend(items)
            out.append("</g>")
        out.append("</svg>")
        return "\n".join(out) + "\n"

    # -- primitives ---------------------------------------------------------
    @staticmethod
    def _stroke(style: str) -> str:
        width, dash = STYLES[style]
        s = f'fill="none" stroke="#000000" stroke-width="{_n(width)}" stroke-linecap="round" ' \
            f'stroke-linejoin="round"'
        if dash:
            s += f' stroke-dasharray="{dash}"'
        return s

    def is_clear(self, box: tuple[float, float, float, float], margin: float = 0.3) -> bool:
        """Whether paper ``box`` (left, top, right, bottom; mm), grown by
        ``margin`` mm, meets no stroke and no text drawn so far."""
        x0, y0, x1, y1 = box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin
        if any(min(x1, b[2]) > max(x0, b[0]) and min(y1, b[3]) > max(y0, b[1])
               for _, b in self.text_boxes):
            return False
        grown = (x0, y0, x1, y1)
        # only strokes whose extent reaches the box (edges included) can meet it:
        # a label is tried against every segment of the sheet otherwise
        return not any(_segment_meets_box(p, q, grown)
                       for pts, (sx0, sy0, sx1, sy1) in zip(self.strokes, self._stroke_extents())
                       if sx0 <= x1 and sx1 >= x0 and sy0 <= y1 and sy1 >= y0
                       for p, q in zip(pts, pts[1:]))

    def _stroke_extents(self) -> list[tuple[float, float, float, float]]:
        """(left, top, right, bottom) of each stroke, made for the strokes added
        since the last call (strokes are only ever appended)."""
        for pts in self.strokes[len(self._extents):]:
            xs, ys = [p[0] for p in pts], [p[1] for p in pts]
            self._extents.append((min(xs), min(ys), max(xs), max(ys)))
        return self._extents

    def line(self, group: str, p: Point, q: Point, style: str = "thin") -> None:
        self.strokes.append([p, q])
        self._add(group, f'<line x1="{_n(p[0])}" y1="{_n(p[1])}" x2="{_n(q[0])}" '
                         f'y2="{_n(q[1])}" {self._stroke(style)}/>')

    def polyline(self, group: str, points: list[Point], style: str, closed: bool = False,
                 cls: str = "") -> None:
        if len(points) < 2:
            return
        self.strokes.append(list(points) + ([points[0]] if closed else []))
        d = "M" + " L".join(f"{_n(x)} {_n(y)}" for x, y in points) + (" Z" if closed else "")
        c = f' class="{cls}"' if cls else ""
        self._add(group, f'<path{c} d="{d}" {self._stroke(style)}/>')

    def rect(self, group: str, x: float, y: float, w: float, h: float, style: str = "thin") -> None:
        self.strokes.append([(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y)])
        self._add(group, f'<rect x="{_n(x)}" y="{_n(y)}" width="{_n(w)}" height="{_n(h)}" '
                         f'{self._stroke(style)}/>')

    def circle(self, group: str, c: Point, r: float, style: str = "thin") -> None:
        self.strokes.append([(c[0] + r * math.cos(k * math.pi / 36), c[1] + r * math.sin(k * math.pi / 36))
                             for k in range(73)])
        self._add(group, f'<circle cx="{_n(c[0])}" cy="{_n(c[1])}" r="{_n(r)}" '
                         f'{self._stroke(style)}/>')

    def text(self, group: str, at: Point, text: str, height_mm: float = DIM_TEXT_MM,
             anchor: str = "start", rotate: float = 0.0, id: str = "", cls: str = "",
             bold: bool = False) -> None:
        """Text with its baseline at ``at``; ``rotate`` in degrees (SVG sense,
        -90 = reading upwards); ``anchor`` start / middle / end."""
        attrs = [f'x="{_n(at[0])}"', f'y="{_n(at[1])}"']
        if id:
            attrs.insert(0, f"id={quoteattr(id)}")
        if cls:
            attrs.insert(1 if id else 0, f"class={quoteattr(cls)}")
        attrs.append(f'font-family="{FONT_FAMILY}" font-size="{_n(height_mm / CAP_HEIGHT_EM)}"')
        if bold:
            attrs.append('font-weight="bold"')
        if anchor != "start":
            attrs.append(f'text-anchor="{anchor}"')
        if rotate:
            attrs.append(f'transform="rotate({_n(rotate)} {_n(at[0])} {_n(at[1])})"')
        attrs.append('fill="#000000" stroke="none"')
        self._add(group, f"<text {' '.join(attrs)}>{escape(text)}</text>")
        self.text_boxes.append((text, text_box(at, text, height_mm, anchor, rotate)))

    def arrow(self, group: str, tip: Point, direction: Point) -> None:
        """Closed filled arrowhead with its point at ``tip``, pointing along ``direction``."""
        dx, dy = direction
        n = math.hypot(dx, dy)
        dx, dy = dx / n, dy / n
        L, hw = ARROW_LENGTH_MM, ARROW_LENGTH_MM * math.tan(ARROW_HALF_ANGLE_RAD)
        bx, by = tip[0] - dx * L, tip[1] - dy * L
        pts = [tip, (bx - dy * hw, by + dx * hw), (bx + dy * hw, by - dx * hw)]
        self.strokes.append(pts + [tip])
        d = "M" + " L".join(f"{_n(x)} {_n(y)}" for x, y in pts) + " Z"
        self._add(group, f'<path d="{d}" fill="#000000" stroke="none"/>')

    # -- ISO 129-1 dimensions -------------------------------------------------
    def linear_dimension(self, p: Point, q: Point, axis: str, at: float, text: str, name: str,
                         group: str = "dimensions", outside: str | None = None) -> None:
        """Dimension the distance between paper points ``p`` and ``q`` along
        ``axis`` ("h": x distance, "v": y distance), with the dimension line at
        paper ``y = at`` (h) or ``x = at`` (v). The value text gets
        ``id="dim-<name>"``. A value too long for the space between the
        extension lines goes beyond one of them: ``outside`` "above" (the
        default of "v") or "below", "right" (the default of "h") or "left";
        in a chain of dimensions, the side away from the neighbour.

        Raises:
            ValueError: ``axis`` or ``outside`` not one of those.
        """
        allowed = {"h": (None, "right", "left"), "v": (None, "above", "below")}
        if axis in allowed and outside not in allowed[axis]:
            raise ValueError(f"outside must be one of {allowed[axis][1:]} for axis {axis!r}, "
                             f"not {outside!r}")
        g = f"{group}"
        if axis == "h":
            a, b = sorted((p, q), key=lambda t: t[0])
            ends = [(a[0], at), (b[0], at)]
            for f, e in ((a, ends[0]), (b, ends[1])):
                self._extension(g, f, e, vertical=True)
            length = ends[1][0] - ends[0][0]
        elif axis == "v":
            a, b = sorted((p, q), key=lambda t: t[1])
            ends = [(at, a[1]), (at, b[1])]
            for f, e in ((a, ends[0]), (b, ends[1])):
                self._extension(g, f, e, vertical=False)
            length = ends[1][1] - ends[0][1]
        else:
            raise ValueError(f"axis must be 'h' or 'v', not {axis!r}")
        self._dimension_line(g, ends[0], ends[1], length, axis, text, name, outside)

    def _extension(self, g: str, feature: Point, end: Point, vertical: bool) -> None:
        k = 1 if vertical else 0
        span = end[k] - feature[k]
        if abs(span) < 1e-9:
            return
        s = 1.0 if span > 0 else -1.0
        start = list(feature)
        start[k] += s * min(EXT_GAP_MM, abs(span) / 2)
        stop = list(end)
        stop[k] += s * EXT_OVERSHOOT_MM
        self.line(g, (start[0], start[1]), (stop[0], stop[1]), "thin")

    def _dimension_line(self, g: str, e0: Point, e1: Point, length: float, axis: str, text: str,
                        name: str, outside: str | None = None) -> None:
        tw = text_width(text, DIM_TEXT_MM)
        ux, uy = (1.0, 0.0) if axis == "h" else (0.0, 1.0)
        inside = length >= 2 * ARROW_LENGTH_MM + 1.0
        if inside:
            self.line(g, e0, e1)
            self.arrow(g, e0, (-ux, -uy))
            self.arrow(g, e1, (ux, uy))
        else:  # arrows outside, pointing inward
            ext = ARROW_LENGTH_MM + 2.0
            self.line(g, (e0[0] - ux * ext, e0[1] - uy * ext), (e1[0] + ux * ext, e1[1] + uy * ext))
            self.arrow(g, e0, (ux, uy))
            self.arrow(g, e1, (-ux, -uy))
        fits = inside and length >= tw + 2 * ARROW_LENGTH_MM + 1.0  # clear of both arrowheads
        if axis == "h":
            y = e0[1] - TEXT_LIFT_MM
            if fits:
                self.text(g, ((e0[0] + e1[0]) / 2, y), text, anchor="middle", id=f"dim-{name}",
                          cls="dim")
            else:
                gap = ARROW_LENGTH_MM + 2.5 if not inside else 1.5
                if outside == "left":
                    self.text(g, (e0[0] - gap, y), text, anchor="end", id=f"dim-{name}",
                              cls="dim")
                else:
                    self.text(g, (e1[0] + gap, y), text, id=f"dim-{name}", cls="dim")
        else:
            x = e0[0] - TEXT_LIFT_MM
            if fits:
                self.text(g, (x, (e0[1] + e1[1]) / 2), text, anchor="middle", rotate=-90,
                          id=f"dim-{name}", cls="dim")
            else:
                gap = ARROW_LENGTH_MM + 2.5 if not inside else 1.5
                if outside == "below":  # reads upwards, ending below the lower end
                    self.text(g, (x, e1[1] + gap), text, anchor="end", rotate=-90,
                              id=f"dim-{name}", cls="dim")
                else:
                    self.text(g, (x, e0[1] - gap), text, anchor="start", rotate=-90,
                              id=f"dim-{name}", cls="dim")

    def leader(self, points: list[Point], text: str, name: str, group: str = "dimensions",
               arrow: bool = True) -> None:
        """Leader line through ``points`` (arrowhead at the first), ending in a
        horizontal shoulder that carries ``text`` (``id="dim-<name>"``)."""
        g = group
        tail = points[-1]
        prev = points[-2]
        right = tail[0] >= prev[0]
        tw = text_width(text, DIM_TEXT_MM)
        shoulder = (tail[0] + (tw + 2.0 if right else -(tw + 2.0)), tail[1])
        self.polyline(g, [*points, shoulder], "thin")
        if arrow:
            a, b = points[0], points[1]
            self.arrow(g, a, (a[0] - b[0], a[1] - b[1]))
        x = tail[0] + 1.0 if right else shoulder[0] + 1.0
        self.text(g, (x, tail[1] - TEXT_LIFT_MM), text, id=f"dim-{name}", cls="dim")

    def radius_dimension(self, centre: Point, radius: float, angle_deg: float, text: str,
                         name: str, dist: float | tuple[float, ...], shoulder_right: bool = True,
                         group: str = "dimensions") -> None:
        """ISO 129-1 radius dimension (paper mm): the arrowhead touches the arc
        at ``angle_deg`` (counter-clockwise as seen, 0 = +x); the dimension line
        runs radially from there to the point at signed distance ``dist`` from
        the centre (negative: through and past the centre; greater than the
        radius: outside the arc; a sequence: the first whose value crosses no
        line or text drawn so far), then a horizontal shoulder, on the side the
        line runs to, carries the value (``id="dim-<name>"``)."""
        a = math.radians(angle_deg)
        ux, uy = math.cos(a), -math.sin(a)
        on_arc = (centre[0] + ux * radius, centre[1] + uy * radius)
        if isinstance(dist, (tuple, list)):  # the first length whose value stands clear
            dist = next((t for t in dist if self._radius_value_clear(centre, radius, angle_deg,
                                                                      text, t, shoulder_right)),
                        dist[0])
        end = (centre[0] + ux * dist, centre[1] + uy * dist)
        if abs(end[0] - on_arc[0]) > 1e-6:  # the shoulder carries on the way the line runs,
            shoulder_right = end[0] > on_arc[0]  # so the line does not cross the value
        self.arrow(group, on_arc, (on_arc[0] - end[0], on_arc[1] - end[1]))
        tw = text_width(text, DIM_TEXT_MM)
        shoulder = (end[0] + (tw + 2.0 if shoulder_right else -(tw + 2.0)), end[1])
        self.polyline(group, [on_arc, end, shoulder], "thin")
        x = end[0] + 1.0 if shoulder_right else shoulder[0] + 1.0
        self.text(group, (x, end[1] - TEXT_LIFT_MM), text, id=f"dim-{name}", cls="dim")

    def _radius_value_clear(self, centre: Point, radius: float, angle_deg: float, text: str,
                            dist: float, shoulder_right: bool) -> bool:
        a = math.radians(angle_deg)
        ux, uy = math.cos(a), -math.sin(a)
        on_x = centre[0] + ux * radius
        end = (centre[0] + ux * dist, centre[1] + uy * dist)
        right = end[0] > on_x if abs(end[0] - on_x) > 1e-6 else shoulder_right
        tw = text_width(text, DIM_TEXT_MM)
        x = end[0] + 1.0 if right else end[0] - tw - 1.0
        return self.is_clear(text_box((x, end[1] - TEXT_LIFT_MM), text, DIM_TEXT_MM))

    def centre_mark(self, group: str, c: Point, half: float) -> None:
        """Centre lines of a circle: a cross of two long-dash-dot lines."""
        self.line(group, (c[0] - half, c[1]), (c[0] + half, c[1]), "centre")
        self.line(group, (c[0], c[1] - half), (c[0], c[1] + half), "centre")
