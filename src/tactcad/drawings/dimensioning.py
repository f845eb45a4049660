"""Dimensioning a view (ISO 129-1): model points to dimension lines in
stacked tiers, hole marks, callouts, coordinates and tables, thickness and
radius callouts, and section views with their cutting-plane marks
(ISO 128-40). The per-part dimension sets are made of these."""

from __future__ import annotations

import math
from typing import Iterator

from tactcad.drawings.drawing import (FIRST_TIER, TABLE_BLOCK_GAP, TABLE_COLS, TABLE_ROW, TIER,
                                      Drawing, Hole2D, table_box)
from tactcad.drawings.frame import FRAME, TITLE_W
from tactcad.drawings.sheet import (CLEARANCE_MM, DIM_TEXT_MM, LABEL_TEXT_MM, Point, Sheet,
                                    Spot, fmt_mm, leader_spot, text_width)
from tactcad.drawings.views import ISO_5455_SCALES, View, scale_text
from tactcad.geometry.profile import Arc

def tier(view: View, side: str, k: int) -> float:
    """Paper coordinate of the k-th dimension line (k = 0, 1, ...) on a side."""
    x0, y0, x1, y1 = view.paper_box()
    off = FIRST_TIER + k * TIER
    return {"top": y0 - off, "below": y1 + off, "left": x0 - off, "right": x1 + off}[side]


def dim(d: Drawing, view: View, p, q, axis: str, side: str, k: int, value: str, name: str,
        outside: str | None = None) -> None:
    """A linear dimension of part points ``p``-``q`` on tier ``k`` of ``side``
    (:meth:`~tactcad.drawings.sheet.Sheet.linear_dimension`; ``outside``: where a
    value too long for its space goes)."""
    d.sheet.linear_dimension(view.paper(*p), view.paper(*q), axis, tier(view, side, k), value,
                             name, outside=outside)
    d.dimensions[name] = value


def hole_marks(d: Drawing, view: View, holes: list[Hole2D]) -> None:
    for h in holes:
        d.sheet.centre_mark("centre-lines", view.paper(h.x, h.y), h.d / 2 * view.scale + 2.0)


def hole_callout(d: Drawing, view: View, holes: list[Hole2D], toward: tuple[float, float]) -> None:
    """One leader per distinct hole size and depth: ``2× Ø2.4 through`` at
    the nearest such hole, its text where there is room near ``toward``
    (:meth:`~tactcad.drawings.sheet.Sheet.leader`)."""
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


def hole_dims_linear(d: Drawing, view: View, holes: list[Hole2D], datum: tuple[float, float],
                      bottom_k: int = 0, left_k: int = 0) -> None:
    """Hole centres from the datum edges: x below the view, y on its left."""
    for i, h in enumerate(sorted(holes, key=lambda h: h.x), start=1):
        dim(d, view, (datum[0], datum[1]), (h.x, h.y), "h", "below", bottom_k + i - 1,
             fmt_mm(h.x - datum[0]), f"hole_{i}_x")
    ys = sorted({round(h.y, 9) for h in holes})
    for j, y in enumerate(ys):
        h = next(h for h in holes if round(h.y, 9) == y)
        name = "hole_y" if len(ys) == 1 else f"hole_y_{j + 1}"
        dim(d, view, (datum[0], datum[1]), (h.x, h.y), "v", "left", left_k + j,
             fmt_mm(h.y - datum[1]), name)


#: Where a label may stand around its feature, tried in this order: up-right
#: first (the habit of a hand drawing), then the other diagonals and sides.
LABEL_DIRECTIONS_DEG = (45, 135, -45, -135, 0, 180, 90, -90)
LABEL_GAPS_MM = (0.8, 2.0, 3.5, 5.0, 8.0)            # beside the feature
LABEL_LEADER_MM = (6.0, 10.0, 15.0, 20.0, 28.0, 36.0, 46.0)  # further out, on a leader
#: Leaders also run at these angles (deg) when the main ones are taken: a long row of
#: close holes (a terminal board's) staggers its labels in more tiers.
LABEL_LEADER_EXTRA_DEG = (60, 120, -60, -120, 30, 150, -30, -150)


def feature_label_spots(centre: Point, radius: float, text: str,
                        height_mm: float = DIM_TEXT_MM) -> Iterator[Spot]:
    """Where the label of a round feature (paper ``centre`` and ``radius``,
    mm) may stand: beside it, :data:`LABEL_GAPS_MM` out in each of
    :data:`LABEL_DIRECTIONS_DEG`; then on a leader from its edge, ending
    :data:`LABEL_LEADER_MM` out in those directions."""
    w, h = text_width(text, height_mm), height_mm
    for gap in LABEL_GAPS_MM:
        for deg in LABEL_DIRECTIONS_DEG:
            ux, uy = math.cos(math.radians(deg)), -math.sin(math.radians(deg))
            # the box's corner (or side middle) nearest the feature sits at the gap
            ex, ey = centre[0] + ux * (radius + gap), centre[1] + uy * (radius + gap)
            left = ex if ux > 0.3 else ex - w if ux < -0.3 else ex - w / 2
            # baseline: box bottom (0.25 h below it) at ey above the feature,
            # box top (h above it) at ey below it, box middle at ey beside it
            base = ey - 0.25 * h if uy < -0.3 else ey + h if uy > 0.3 else ey + 0.375 * h
            yield Spot((left, base))
    for reach in LABEL_LEADER_MM:
        for deg in LABEL_DIRECTIONS_DEG + LABEL_LEADER_EXTRA_DEG:
            ux, uy = math.cos(math.radians(deg)), -math.sin(math.radians(deg))
            edge = (centre[0] + ux * radius, centre[1] + uy * radius)
            end = (centre[0] + ux * (radius + reach), centre[1] + uy * (radius + reach))
            if abs(ux) < 1e-9:  # straight up or down: the shoulder turns right
                end = (end[0] + 1e-6, end[1])
            yield leader_spot([edge, end], text, height_mm)


def clear_label(sh: Sheet, centre: Point, radius: float, text: str, id: str) -> None:
    """Set ``text`` (``DIM_TEXT_MM`` high) by the round feature of paper
    ``centre`` and ``radius`` (mm), at the first of
    :func:`feature_label_spots` with room for it."""
    sh.label("dimensions", text, feature_label_spots(centre, radius, text), id=id)


def labelled_holes(ordered: list[Hole2D], scale: float) -> list[int]:
    """Which holes of a hole table are labelled on the view: in each row (one
    y) every hole whose label has room beside its labelled neighbour's, the
    row's first and last always. A row at a pitch narrower than a label (a
    terminal board's 24 pairs at 2:1) labels every second or third hole, so
    its labels stand side by side rather than in ever more leader tiers that
    run out of room.

    Args:
        ordered: the holes in table order (by y, then x; model mm).
        scale: the view's scale (paper mm per model mm).
    Returns:
        The labelled holes' table numbers (1 = the first of ``ordered``), ascending.
    """
    # the widest label plus the room a label keeps clear on either side
    need = text_width(f"H{len(ordered)}", DIM_TEXT_MM) + 2 * CLEARANCE_MM
    rows: dict[float, list[int]] = {}
    for i, h in enumerate(ordered, start=1):
        rows.setdefault(round(h.y, 9), []).append(i)
    out: list[int] = []
    for numbers in rows.values():
        kept = [numbers[0]]
        for i in numbers[1:]:
            if (ordered[i - 1].x - ordered[kept[-1] - 1].x) * scale >= need:
                kept.append(i)
        last = numbers[-1]
        if kept[-1] != last:  # the row's end is labelled; the one before it makes room
            if len(kept) > 1 and (ordered[last - 1].x - ordered[kept[-1] - 1].x) * scale < need:
                kept.pop()
            kept.append(last)
        out += kept
    return sorted(out)


def hole_table(d: Drawing, view: View, holes: list[Hole2D], datum: tuple[float, float]) -> None:
    """Coordinate table of the holes (ISO 129-1 tabular dimensioning), the
    holes labelled on the view (all those with room, :func:`labelled_holes`),
    coordinates from the marked origin."""
    sh = d.sheet
    o = view.paper(*datum)
    sh.line("dimensions", (o[0] - 3, o[1]), (o[0] + 3, o[1]))
    sh.line("dimensions", (o[0], o[1] - 3), (o[0], o[1] + 3))
    sh.circle("dimensions", o, 1.2)
    clear_label(sh, o, 1.2, "0,0", "hole-origin")
    ordered = sorted(holes, key=lambda h: (h.y, h.x))
    labelled = labelled_holes(ordered, view.scale)
    for i in labelled:
        h = ordered[i - 1]
        clear_label(sh, view.paper(h.x, h.y), h.d / 2 * view.scale, f"H{i}", f"hole-label-{i}")
    x0, y0, _, _ = table_box(d)
    per_block, numbered = d.table_block_rows, list(enumerate(ordered, start=1))
    for b in range(d.table_blocks):
        block = numbered[b * per_block:(b + 1) * per_block]
        if block:
            _hole_table_block(d, x0 + b * (sum(TABLE_COLS) + TABLE_BLOCK_GAP), y0, block,
                              datum)
    title = "Hole positions from origin 0,0"
    if len(labelled) < len(ordered):  # a reader looks for H2 on the view: say where it is
        title += "; numbers run along each row, labelled where they fit"
    sh.text("hole-table", (x0, y0 - 2.0), title, DIM_TEXT_MM)


def _hole_table_block(d: Drawing, x0: float, y0: float, rows: list[tuple[int, Hole2D]],
                      datum: tuple[float, float]) -> None:
    """One block of the hole table: its head and ``rows`` (number, hole) at paper
    (``x0``, ``y0``), the top left corner (mm)."""
    sh, cols, row_h = d.sheet, TABLE_COLS, TABLE_ROW
    sh.rect("hole-table", x0, y0, sum(cols), row_h * (len(rows) + 1), "table")
    for r_i in range(1, len(rows) + 1):
        y = y0 + r_i * row_h
        sh.line("hole-table", (x0, y), (x0 + sum(cols), y), "thin")
    x = x0
    for w in cols[:-1]:
        x += w
        sh.line("hole-table", (x, y0), (x, y0 + row_h * (len(rows) + 1)), "thin")

    def cell(col: int, row: int, text: str, id: str = "") -> None:
        cx = x0 + sum(cols[:col]) + cols[col] / 2
        cy = y0 + row * row_h + row_h / 2 + DIM_TEXT_MM / 2
        sh.text("hole-table", (cx, cy), text, DIM_TEXT_MM, anchor="middle", id=id,
                cls="dim" if id else "")
    for c, hd in enumerate(("Hole", "X", "Y", "Ø", "Depth")):
        cell(c, 0, hd)
    for row, (i, h) in enumerate(rows, start=1):
        vals = (fmt_mm(h.x - datum[0]), fmt_mm(h.y - datum[1]), fmt_mm(h.d), h.depth_text)
        cell(0, row, f"H{i}")
        for c, (suffix, v) in enumerate(zip(("x", "y", "d", "depth"), vals), start=1):
            cell(c, row, v, f"dim-hole_{i}_{suffix}")
            d.dimensions[f"hole_{i}_{suffix}"] = v


def plus_minus(value: float, tol: float, decimals: int = 3) -> str:
    """A dimension with its symmetric tolerance, ``19.8 ±0.02`` (no tolerance: the value),
    each to ``decimals`` places."""
    return (f"{fmt_mm(value, decimals)} ±{fmt_mm(tol, decimals)}" if tol > 0
            else fmt_mm(value, decimals))


def thickness_dim(d: Drawing, name: str = "thickness", tol: float = 0.0) -> None:
    t = d.views["top"]
    u1 = t.bbox[2]
    x = max((p[0] for poly in t.visible for p in poly if abs(p[1] - t.bbox[3]) < 1e-6),
            default=u1)
    dim(d, t, (x, t.bbox[3]), (x, t.bbox[1]), "v", "right", 0,
         plus_minus(t.bbox[3] - t.bbox[1], tol), name)


def arc_angles(arc: Arc, preferred: float | None = None, step: float = 15.0) -> tuple[float, ...]:
    """Where a radius dimension's arrowhead may touch ``arc`` (degrees,
    counter-clockwise as seen in a view whose u, v are the arc's x, y):
    ``preferred`` (default the arc's middle), then ``step`` apart on either
    side of it in turn, a tenth of the sweep clear of the arc's ends.

    Args:
        arc: the arc, in view coordinates (mm).
        preferred: the angle tried first (deg), or None.
        step: spacing of the others (deg).
    Returns:
        The angles, preferred first.
    """
    a0 = math.degrees(math.atan2(arc.start[1] - arc.centre[1], arc.start[0] - arc.centre[0]))
    sweep = math.degrees(arc.sweep)
    lo, hi = sorted((a0, a0 + sweep))
    lo, hi = lo + 0.1 * abs(sweep), hi - 0.1 * abs(sweep)
    mid = (lo + hi) / 2
    pref = mid if preferred is None else preferred + 360.0 * round((mid - preferred) / 360.0)
    out = [pref]
    for k in range(1, int(360 / step) + 1):
        out += [a for a in (pref + k * step, pref - k * step) if lo <= a <= hi]
    return tuple(out)


def radius_callouts(d: Drawing, arcs: list[Arc], prefix: str = "inside_radius") -> None:
    f = d.front
    for k, a in enumerate(arcs):
        c = f.paper(*a.centre)
        mid = a.midpoint
        ang = math.degrees(math.atan2(mid[1] - a.centre[1], mid[0] - a.centre[0]))
        r = a.radius * f.scale
        text = f"R{fmt_mm(a.radius)}"
        name = prefix if len(arcs) == 1 else f"{prefix}_{k + 1}"
        left = math.cos(math.radians(ang)) > 0
        d.sheet.radius_dimension(c, r, arc_angles(a, ang), text, name, dist=-max(8.0, 3 * r),
                                 shoulder_right=not left)
        d.dimensions[name] = text


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
    room = d.right_mm - 8.0 - left - FIRST_TIER - 2 * TIER
    top = lb[1] + 12.0
    room_h = d.notes_top - top - FIRST_TIER - 2 * TIER - 12.0
    scale = next((s for s in ISO_5455_SCALES if s <= 4 * d.scale and length_mm * s <= room
                  and height_mm * s <= room_h), d.scale)
    sv = section_view(solid, (0.0, 0.0, 0.0), normal, up, "A-A", scale, spec=d.spec)
    sv.hidden = []  # ISO 128-40: no hidden edges in a section
    sv.place(left, lb[1] + 12.0)
    d.views["section"] = sv


def section_marks(d: Drawing, host: str, label: str) -> None:
    """Cutting plane (ISO 128-40: long-dash-dot, thick at the ends) along the
    line v = 0 of view ``host``, arrows for the viewing direction (paper up),
    the letters, and the section's own label with its scale."""
    sh, f, sv = d.sheet, d.views[host], d.views["section"]
    x0, _, x1, _ = f.paper_box()
    y = f.paper(0.0, 0.0)[1]
    out = FIRST_TIER + TIER + 4.0  # beyond two tiers of dimensions
    # the chain line spans the view; the thick ends stand outside the dimension
    # tiers, pointing away from the view, so no dimension value sits on the plane
    sh.line("section-plane", (x0 - 3.0, y), (x1 + 3.0, y), "centre")
    for x in (x0 - out, x1 + out):
        sh.line("section-plane", (x, y), (x - 5.0 if x < x0 else x + 5.0, y), "visible")
        sh.line("section-plane", (x, y), (x, y - 5.0), "thin")
        sh.arrow("section-plane", (x, y - 7.5), (0.0, -1.0))
        sh.text("section-plane", (x + (-3.0 if x < x0 else 3.0), y - 6.0), label[0], LABEL_TEXT_MM,
                anchor="middle", id=f"section-letter-{'l' if x < x0 else 'r'}")
    b = sv.paper_box()
    sh.text("view-section", ((b[0] + b[2]) / 2, b[3] + FIRST_TIER + 2 * TIER + 5.0),
            f"{label} ({scale_text(sv.scale)})", LABEL_TEXT_MM, anchor="middle",
            id="section-label")


