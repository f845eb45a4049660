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

Labels (dimension values, leaders' texts, radius values, hole labels) are set
last (:meth:`Sheet.settle`), each at the first of its :class:`Spot` s that is
clear (:meth:`Sheet.is_clear`: no text and no stroke within
:data:`CLEARANCE_MM`, inside the sheet's room) of everything drawn, the lines
of every view and dimension included, and of the labels set before it; the
overlap is measured as the drawings check measures it
(:mod:`tactcad.drawings.room`).
Coordinates are written with 3 decimals: the same drawing gives the same bytes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterable, Iterator, Sequence
from xml.sax.saxutils import escape, quoteattr

from tactcad.drawings.room import Box, Point, Segments, box_overlap, grown, length_in_box

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
CLEARANCE_MM = 0.2      # a label keeps this much paper clear around it (past a line's ink)
THIN_HALF_MM = STYLES["thin"][0] / 2  # the ink either side of a leader's centre line
#: Steps (paper mm) a leader's end moves to find room for its text: the near
#: places a hand would try first, then rings of eight directions further out.
LEADER_MOVES: tuple[Point, ...] = (
    (0.0, 0.0), (0.0, -6.0), (0.0, 6.0), (12.0, -6.0), (-12.0, -6.0), (0.0, -12.0), (0.0, 12.0),
    (20.0, 0.0), (-20.0, 0.0),
    *((round(r * math.cos(math.radians(a)), 6) + 0.0, round(-r * math.sin(math.radians(a)), 6) + 0.0)
      for r in (18.0, 26.0, 36.0, 48.0) for a in (90, -90, 45, -45, 135, -135, 0, 180)))
ALONG_MM = 3.0          # more of a stroke than this along a label's line: it runs on that stroke
NEAR_MOVES = 9          # the first moves of LEADER_MOVES: a hand's nearby tries
FAR_STEPS_MM = (4.0, 8.0, 12.0, 18.0, 26.0, 36.0)  # a dimension value's steps out along its line


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
    boxes = sheet.text_boxes
    return [(ta, tb) for i, (ta, a) in enumerate(boxes) for tb, b in boxes[i + 1:]
            if box_overlap(a, b) > tol]


def _n(v: float) -> str:
    return fmt_mm(v, 3)


@dataclass(frozen=True)
class Spot:
    """One place a label may take: its text's baseline point, anchor and
    rotation (as :meth:`Sheet.text`), and the thin lines and filled
    arrowheads that come with it there (a leader and its shoulder, a
    dimension line carried on under the value).

    Attributes:
        at: paper point of the text's baseline (mm).
        anchor: ``start``, ``middle`` or ``end``.
        rotate: degrees, 0 or -90 (reads upwards).
        lines: thin polylines (paper points) drawn with the text.
        arrows: ``(tip, direction)`` of each arrowhead drawn with it.
    """

    at: Point
    anchor: str = "start"
    rotate: float = 0.0
    lines: tuple[tuple[Point, ...], ...] = ()
    arrows: tuple[tuple[Point, Point], ...] = ()


def arrow_points(tip: Point, direction: Point) -> list[Point]:
    """The closed filled arrowhead's corners (ISO 129-1: 30 deg included
    angle, :data:`ARROW_LENGTH_MM` long), its point at ``tip``, pointing
    along ``direction``; the first corner repeated at the end."""
    dx, dy = direction
    n = math.hypot(dx, dy) or 1.0
    dx, dy = dx / n, dy / n
    L, hw = ARROW_LENGTH_MM, ARROW_LENGTH_MM * math.tan(ARROW_HALF_ANGLE_RAD)
    bx, by = tip[0] - dx * L, tip[1] - dy * L
    return [tip, (bx - dy * hw, by + dx * hw), (bx + dy * hw, by - dx * hw), tip]


def leader_spot(points: Sequence[Point], text: str, height_mm: float = DIM_TEXT_MM,
                arrow: bool = True) -> Spot:
    """A leader through ``points`` (arrowhead at the first) ending in a
    horizontal shoulder on the side its last segment runs to, the text
    standing on the shoulder."""
    tail, prev = points[-1], points[-2]
    right = tail[0] >= prev[0]
    tw = text_width(text, height_mm)
    shoulder = (tail[0] + (tw + 2.0 if right else -(tw + 2.0)), tail[1])
    x = tail[0] + 1.0 if right else shoulder[0] + 1.0
    a, b = points[0], points[1]
    return Spot((x, tail[1] - TEXT_LIFT_MM), lines=((*points, shoulder),),
                arrows=((a, (a[0] - b[0], a[1] - b[1])),) if arrow else ())


def leader_spots(points: Sequence[Point], text: str, height_mm: float = DIM_TEXT_MM,
                 arrow: bool = True) -> Iterator[Spot]:
    """:func:`leader_spot` with the leader's end where asked, then moved by
    each of :data:`LEADER_MOVES`; the near moves first from the end asked,
    then from its mirror image across the point before it (the shoulder on
    the other side), then the far ones from both in turn. Moves that bring
    the end within 3 mm of the point before it are left out."""
    tail, prev = points[-1], points[-2]
    mirror = (2 * prev[0] - tail[0], tail[1])
    near, far = LEADER_MOVES[:NEAR_MOVES], LEADER_MOVES[NEAR_MOVES:]
    tries = [(tail, m) for m in near] + [(mirror, m) for m in near]
    tries += [(t, m) for m in far for t in (tail, mirror)]
    for (x, y), (dx, dy) in tries:
        end = (x + dx, y + dy)
        if end == tail or math.dist(end, prev) >= 3.0:
            yield leader_spot([*points[:-1], end], text, height_mm, arrow)


def radius_spot(centre: Point, radius: float, angle_deg: float, dist: float, text: str,
                shoulder_right: bool = True) -> Spot:
    """ISO 129-1 radius value: the arrowhead on the arc at ``angle_deg``
    (counter-clockwise as seen, 0 = +x), the dimension line radially to the
    point at signed distance ``dist`` from the centre (negative: through the
    centre), then a shoulder carrying the value on the side the line runs to
    (``shoulder_right`` where it runs straight up or down)."""
    a = math.radians(angle_deg)
    ux, uy = math.cos(a), -math.sin(a)
    on_arc = (centre[0] + ux * radius, centre[1] + uy * radius)
    end = (centre[0] + ux * dist, centre[1] + uy * dist)
    if abs(end[0] - on_arc[0]) > 1e-6:  # the shoulder carries on the way the line runs,
        shoulder_right = end[0] > on_arc[0]  # so the line does not cross the value
    tw = text_width(text, DIM_TEXT_MM)
    shoulder = (end[0] + (tw + 2.0 if shoulder_right else -(tw + 2.0)), end[1])
    x = end[0] + 1.0 if shoulder_right else shoulder[0] + 1.0
    return Spot((x, end[1] - TEXT_LIFT_MM), lines=((on_arc, end, shoulder),),
                arrows=((on_arc, (on_arc[0] - end[0], on_arc[1] - end[1])),))


def radius_dists(dist: float | Sequence[float], radius: float) -> tuple[list[float], list[float]]:
    """The lengths a radius's dimension line is tried at: (those asked,
    those further the same way, through the centre or out from the arc, and
    then out from the arc, ISO 129-1's form for a small radius)."""
    asked = [dist] if isinstance(dist, (int, float)) else list(dist)
    far = min(asked) if asked[0] < 0 else max(asked)
    sign = -1.0 if far < 0 else 1.0
    more = [far + sign * step for step in FAR_STEPS_MM]
    outward = [radius + 4.0 + step for step in (0.0, *FAR_STEPS_MM)] if sign < 0 else []
    return asked, [t for t in dict.fromkeys(more + outward) if t not in asked]


def value_spots(e0: Point, e1: Point, axis: str, text: str, inside: bool, fits: bool,
                outside: str | None) -> Iterator[Spot]:
    """Where a linear dimension's value may stand (ISO 129-1), in order:
    between the arrows when it clears them, above (left of) the line, then
    below (right of) it; beyond the end ``outside`` names, then the other end;
    over the middle of the line, clear of its arrowheads; beyond the ends
    below (right of) the line; then further out along the line, which is
    carried on under the value; last, on a leader from the line's middle.

    Args:
        e0, e1: the dimension line's ends at the extension lines (paper mm).
        axis: ``h`` (e0 left of e1) or ``v`` (e0 above e1).
        inside: the arrows stand between the extension lines (the line ends there).
        fits: the value clears both arrowheads between them.
        outside: the preferred end, ``right``/``left`` (h) or ``above``/``below`` (v).
    Yields:
        The spots, the first choice first.
    """
    h = DIM_TEXT_MM
    w = text_width(text, h)
    k = 0 if axis == "h" else 1
    lo, hi, level = e0[k], e1[k], e0[1 - k]
    # across the line: the text's baseline on the ISO side, and mirrored to the other side;
    # "away": the box clear of the arrowheads' half width by the clearance
    iso, other = -TEXT_LIFT_MM, TEXT_LIFT_MM + 0.75 * h
    lift = ARROW_LENGTH_MM * math.tan(ARROW_HALF_ANGLE_RAD) + CLEARANCE_MM + 0.05 \
        - (TEXT_LIFT_MM - 0.25 * h)
    away = (iso - lift, other + lift)
    line_end = 0.0 if inside else ARROW_LENGTH_MM + 2.0   # the line runs on past the arrows
    gap = 1.5 if inside else ARROW_LENGTH_MM + 2.5
    first_high = (outside or ("right" if axis == "h" else "above")) in ("right", "below")

    def spot(centre: float, off: float, reach: float = 0.0) -> Spot:
        at = (centre, level + off) if axis == "h" else (level + off, centre)
        lines = ()
        if reach:  # carry the dimension line on under the value
            start = hi + line_end if centre > hi else lo - line_end
            a, b = (start, level), (reach, level)
            lines = ((a, b),) if axis == "h" else (((level, start), (level, reach)),)
        return Spot(at, "middle", 0.0 if axis == "h" else -90.0, lines)

    ends = ((hi, 1.0), (lo, -1.0)) if first_high else ((lo, -1.0), (hi, 1.0))
    mid = (lo + hi) / 2
    if fits:
        yield from (spot(mid, iso), spot(mid, other))
    yield from (spot(e + s * (gap + w / 2), iso) for e, s in ends)
    if not fits:
        yield from (spot(mid, off) for off in away)
    yield from (spot(e + s * (gap + w / 2), other) for e, s in ends)
    for step in FAR_STEPS_MM:
        yield from (spot(e + s * (gap + step + w / 2), off, e + s * (gap + step + w + 0.5))
                    for off in (iso, other) for e, s in ends)
    # last, ISO 129-1's value on a leader from the dimension line, out to free room
    on_line = (mid, level) if axis == "h" else (level, mid)
    for dx in (6.0, -6.0):
        yield from leader_spots([on_line, (on_line[0] + dx, on_line[1] - 6.0)], text, h,
                                arrow=False)


@dataclass
class _Label:
    group: str
    text: str
    spots: Iterable[Spot]
    height_mm: float
    id: str
    cls: str


@dataclass
class Sheet:
    """An SVG document on a sheet of ``size`` (ISO 216 name), landscape.

    Attributes:
        text_boxes: ``(text, box)`` of every text set so far (paper mm).
        ink: every stroke drawn so far, with its ink's half width.
        room: the paper box (mm) a label must stay inside; the whole sheet
            until a frame is drawn (:func:`tactcad.drawings.frame.sheet_frame`).
    """

    size: str = "A3"
    title: str = ""
    _groups: dict[str, list[str]] = field(default_factory=dict)
    text_boxes: list[tuple[str, Box]] = field(default_factory=list)
    ink: Segments = field(default_factory=Segments, repr=False, compare=False)
    room: Box | None = None
    _labels: list[_Label] = field(default_factory=list, repr=False, compare=False)

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
        """The whole document as SVG 1.1 text (UTF-8, no time stamps); the
        labels not yet set are set first (:meth:`settle`)."""
        self.settle()
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

    # -- room for labels ----------------------------------------------------
    def _room(self) -> Box:
        return self.room or (0.0, 0.0, self.width_mm, self.height_mm)

    def is_clear(self, box: Box, margin: float = CLEARANCE_MM) -> bool:
        """Whether paper ``box`` (left, top, right, bottom; mm), grown by
        ``margin`` mm, lies in the sheet's room and meets no text and no
        stroke's ink drawn so far."""
        return self._crowding(box, margin) == 0.0

    def _crowding(self, box: Box, margin: float) -> float:
        """How much (mm) of ``box`` grown by ``margin`` other items take: the
        ink of the strokes in it (:meth:`Segments.ink_in`), the texts' overlaps
        (:func:`box_overlap`) and how far it leaves the room; 0 when clear."""
        g = grown(box, margin)
        r = self._room()
        out = sum(max(0.0, d) for d in (r[0] - g[0], r[1] - g[1], g[2] - r[2], g[3] - r[3]))
        out += sum(max(0.0, box_overlap(g, b)) for _, b in self.text_boxes)
        return out + float(self.ink_in(g).sum())

    def ink_in(self, box: Box):
        """Length (mm) of each stroke drawn so far inside ``box`` (grown by its
        half width), as an array in drawing order."""
        return self.ink.ink_in(box)

    def _spot_crowding(self, spot: Spot, text: str, height_mm: float) -> float:
        """:meth:`_crowding` of the spot's text, plus the length of its own
        lines and arrowheads inside a text (its own included) or out of the room."""
        box = text_box(spot.at, text, height_mm, spot.anchor, spot.rotate)
        out = self._crowding(box, CLEARANCE_MM)
        if out:
            return out
        strokes = [(pts, THIN_HALF_MM) for pts in spot.lines]
        strokes += [(arrow_points(tip, d), 0.0) for tip, d in spot.arrows]
        r = self._room()
        for pts, half in strokes:
            for p, q in zip(pts, pts[1:]):
                out += sum(length_in_box(p, q, grown(b, half + CLEARANCE_MM))
                           for _, b in self.text_boxes)
                out += length_in_box(p, q, grown(box, half))
                out += math.dist(p, q) - length_in_box(p, q, r)
                out += self._ink_along(p, q)
        return out

    def _ink_along(self, p: Point, q: Point) -> float:
        """Ink (mm) of a stroke drawn so far that runs along the level or
        upright segment ``p``-``q`` rather than across it: a leader's shoulder
        or a carried-on dimension line on another line reads as that line."""
        if abs(p[0] - q[0]) > 1e-9 and abs(p[1] - q[1]) > 1e-9:
            return 0.0
        ink = self.ink_in(grown((min(p[0], q[0]), min(p[1], q[1]), max(p[0], q[0]),
                                 max(p[1], q[1])), THIN_HALF_MM + CLEARANCE_MM))
        along = ink[ink > ALONG_MM]
        return float(along.sum())

    def label(self, group: str, text: str, spots: Iterable[Spot], height_mm: float = DIM_TEXT_MM,
              id: str = "", cls: str = "") -> None:
        """A text set later (:meth:`settle`) at the first of ``spots`` (at
        least one; made as they are tried) that is clear of everything drawn
        by then, with that spot's lines and arrows."""
        self._labels.append(_Label(group, text, spots, height_mm, id, cls))

    def settle(self) -> None:
        """Set every label waiting (:meth:`label`), in the order they came:
        each at its first clear spot, else at the spot the least crowded
        (:meth:`_spot_crowding`; the drawings check then names it)."""
        labels, self._labels = self._labels, []
        for lab in labels:
            best, least = None, math.inf
            for spot in lab.spots:
                crowd = self._spot_crowding(spot, lab.text, lab.height_mm)
                if crowd < least:
                    best, least = spot, crowd
                if crowd == 0.0:
                    break
            if best is None:
                raise ValueError(f"label {lab.text!r}: no place given to set it")
            for pts in best.lines:
                self.polyline(lab.group, list(pts), "thin")
            for tip, d in best.arrows:
                self.arrow(lab.group, tip, d)
            self.text(lab.group, best.at, lab.text, lab.height_mm, best.anchor, best.rotate,
                      id=lab.id, cls=lab.cls)

    # -- primitives ---------------------------------------------------------
    @staticmethod
    def _stroke(style: str) -> str:
        width, dash = STYLES[style]
        s = f'fill="none" stroke="#000000" stroke-width="{_n(width)}" stroke-linecap="round" ' \
            f'stroke-linejoin="round"'
        if dash:
            s += f' stroke-dasharray="{dash}"'
        return s

    def line(self, group: str, p: Point, q: Point, style: str = "thin") -> None:
        self.ink.add([p, q], STYLES[style][0] / 2)
        self._add(group, f'<line x1="{_n(p[0])}" y1="{_n(p[1])}" x2="{_n(q[0])}" '
                         f'y2="{_n(q[1])}" {self._stroke(style)}/>')

    def polyline(self, group: str, points: list[Point], style: str, closed: bool = False,
                 cls: str = "") -> None:
        if len(points) < 2:
            return
        self.ink.add(list(points) + ([points[0]] if closed else []), STYLES[style][0] / 2)
        d = "M" + " L".join(f"{_n(x)} {_n(y)}" for x, y in points) + (" Z" if closed else "")
        c = f' class="{cls}"' if cls else ""
        self._add(group, f'<path{c} d="{d}" {self._stroke(style)}/>')

    def rect(self, group: str, x: float, y: float, w: float, h: float, style: str = "thin") -> None:
        self.ink.add([(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y)], STYLES[style][0] / 2)
        self._add(group, f'<rect x="{_n(x)}" y="{_n(y)}" width="{_n(w)}" height="{_n(h)}" '
                         f'{self._stroke(style)}/>')

    def circle(self, group: str, c: Point, r: float, style: str = "thin") -> None:
        self.ink.add([(c[0] + r * math.cos(k * math.pi / 36), c[1] + r * math.sin(k * math.pi / 36))
                      for k in range(73)], STYLES[style][0] / 2)
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
        pts = arrow_points(tip, direction)
        self.ink.add(pts, 0.0)
        d = "M" + " L".join(f"{_n(x)} {_n(y)}" for x, y in pts[:-1]) + " Z"
        self._add(group, f'<path d="{d}" fill="#000000" stroke="none"/>')

    # -- ISO 129-1 dimensions -------------------------------------------------
    def linear_dimension(self, p: Point, q: Point, axis: str, at: float, text: str, name: str,
                         group: str = "dimensions", outside: str | None = None) -> None:
        """Dimension the distance between paper points ``p`` and ``q`` along
        ``axis`` ("h": x distance, "v": y distance), with the dimension line at
        paper ``y = at`` (h) or ``x = at`` (v). The value text gets
        ``id="dim-<name>"`` and is set where there is room
        (:func:`value_spots`): a value too long for the space between the
        extension lines goes beyond one of them, ``outside`` "above" (the
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
        self.label(g, text, value_spots(e0, e1, axis, text, inside, fits, outside),
                   id=f"dim-{name}", cls="dim")

    def leader(self, points: list[Point], text: str, name: str, group: str = "dimensions",
               arrow: bool = True) -> None:
        """Leader line through ``points`` (arrowhead at the first), ending in a
        horizontal shoulder that carries ``text`` (``id="dim-<name>"``); its
        end moves (:func:`leader_spots`) until the text finds room."""
        self.label(group, text, leader_spots(points, text, arrow=arrow), id=f"dim-{name}",
                   cls="dim")

    def radius_dimension(self, centre: Point, radius: float, angle_deg: float | Sequence[float],
                         text: str, name: str, dist: float | Sequence[float],
                         shoulder_right: bool = True, group: str = "dimensions") -> None:
        """ISO 129-1 radius dimension (paper mm, :func:`radius_spot`): the
        arrowhead touches the arc at ``angle_deg`` (counter-clockwise as seen,
        0 = +x; a sequence: the angles the arc allows, preferred first); the
        dimension line runs radially from there to the point at signed
        distance ``dist`` from the centre (negative: through and past the
        centre; greater than the radius: outside the arc; a sequence: those
        first, see :func:`radius_dists`), then a horizontal shoulder carries
        the value (``id="dim-<name>"``). The value takes the first of these
        places with room for it."""
        angles = [angle_deg] if isinstance(angle_deg, (int, float)) else list(angle_deg)
        asked, further = radius_dists(dist, radius)
        spots = (radius_spot(centre, radius, a, t, text, shoulder_right)
                 for dists in (asked, further) for a in angles for t in dists)
        self.label(group, text, spots, id=f"dim-{name}", cls="dim")

    def centre_mark(self, group: str, c: Point, half: float) -> None:
        """Centre lines of a circle: a cross of two long-dash-dot lines."""
        self.line(group, (c[0] - half, c[1]), (c[0] + half, c[1]), "centre")
        self.line(group, (c[0], c[1] - half), (c[0], c[1] + half), "centre")
