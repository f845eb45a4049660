"""The array's assembly sheet (A3, ISO 5457 frame, ISO 7200 title block):
two views of the assembled array by hidden-line removal, balloons with the
BOM item numbers (ISO 6433), the slot map (which element goes in which slot:
number, row, column, arm length, its DXF file, row 2 turned 180 degrees), the
stack order of each row, and the bolts with their tightening torque.

Units: mm on paper and model, N·m for torque.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import numpy as np

from tactcad.catalogue.array_catalogue import Instance, PartSpec, array_instances, array_parts, bolt_name, nut_name
from tactcad.catalogue.files import profile_dxf_name
from tactcad.catalogue.shop import TORQUE_SOURCE, tightening_torque_Nm
from tactcad.design.array_plan import Plan
from tactcad.assembly.inventory import array_envelope_mm
from tactcad.drawings.design_notes import numbering_note
from tactcad.drawings.drawing import FIRST_TIER
from tactcad.drawings.frame import (FRAME, general_tolerance, revision_and_date, sheet_frame,
                                    title_cells, wrap_text)
from tactcad.drawings.sheet import (DIM_TEXT_MM, LABEL_TEXT_MM, Point, Sheet, Spot, fmt_mm,
                                    text_width)
from tactcad.drawings.views import View, cameras_for, fitting_scale, project, scale_text
from tactcad.store import stable_repr

BALLOON_R = 4.0       # paper mm (ISO 6433: circle, item number inside)
ROW_H = 5.5           # slot map row height (paper mm)
SLOT_COLS = (("Slot", 12.0), ("Row", 10.0), ("Col.", 10.0), ("Part", 30.0), ("Arm", 12.0),
             ("DXF file", 50.0), ("Orientation", 38.0))
SIDE_BOX = (FRAME[0] + 15.0, FRAME[1] + 80.0, 200.0, 110.0)  # left, top, width, height (paper)
FRONT_TOP_LIMIT = (FRAME[1] + 100.0, FRAME[1] + 190.0)         # paper y range of the other view
SLOT_MAP_TOP = FRAME[1] + 12.0  # paper y of the slot map's top edge
#: The slot map's greatest height (paper mm): the view along the bolts keeps 45 mm under it.
SLOT_MAP_MAX_HEIGHT = FRONT_TOP_LIMIT[1] - 45.0 - 12.0 - SLOT_MAP_TOP
# the views: along the bolts (+z) and across the stack (+x), y up
ASSEMBLY_CAMERAS = {"front": cameras_for((0.0, 0.0, 1.0), (0.0, 1.0, 0.0))["front"],
                    "side": cameras_for((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))["front"]}


@dataclass
class AssemblySheet:
    """The composed sheet and what it states (for tests and the manifest)."""

    sheet: Sheet
    scale: float = 1.0
    slot_rows: list[dict] = field(default_factory=list)
    stack_order: dict[int, list[str]] = field(default_factory=dict)
    balloons: dict[str, int] = field(default_factory=dict)  # part -> BOM item
    torque_Nm: float = 0.0
    envelope: dict[str, float] = field(default_factory=dict)  # envelope_x/_y/_z (mm)


def stack_order(plan: Plan) -> dict[int, list[str]]:
    """Instance names of each row from the front clamp plate to the back one
    (row index 0, 1 -> names), as :func:`tactcad.catalogue.array_catalogue.array_instances`
    places them: element of column 0, spacer, element of column 1, ..."""
    out: dict[int, list[str]] = {}
    per_row = plan.columns
    for r in range(plan.rows):
        slots = sorted((s for s in plan.slots if s.row == r), key=lambda s: s.column)
        names = ["clamp_plate_front"]
        for k, s in enumerate(slots):
            if k:
                names.append(f"spacer_{r * (per_row - 1) + k}")
            names.append(f"element_{s.number}")
        out[r] = names + ["clamp_plate_back"]
    return out


def slot_map(plan: Plan) -> list[dict]:
    """One row per element: slot (= element number), row and column (1-based),
    the part that carries it (the element, or a comb's row sheet), arm length (mm), the DXF
    file the shop cuts it from (its profile's, or its row sheet's: the files the export
    writes, :func:`tactcad.catalogue.files.profile_dxf_name`), orientation."""
    sheets = {sh.row: sh.part_name for sh in plan.comb.sheets} if plan.comb is not None else {}

    def carrier(s) -> str:
        return sheets.get(s.row, s.geometry.part_name)

    counts: dict[str, int] = {}
    for s in plan.slots:  # a row sheet is one part, whatever it carries
        counts[carrier(s)] = 1 if s.row in sheets else counts.get(carrier(s), 0) + 1
    rows = []
    for s in sorted(plan.slots, key=lambda s: s.number):
        part = carrier(s)
        rows.append({"slot": s.number, "row": s.row + 1, "column": s.column + 1, "part": part,
                     "arm_mm": fmt_mm(s.geometry.arm_length_mm),
                     "dxf": profile_dxf_name(part, counts[part]).split("/")[-1],
                     "orientation": "turned 180° about y" if s.placement.turned else "as drawn"})
    return rows


def assembly_inputs(plan: Plan, items: dict[str, int]) -> tuple:
    """Everything that shapes the sheet: parts, instances, slots, items, the footprint note."""
    return (plan.name, list(array_parts(plan).values()), array_instances(plan), plan.slots,
            plan.bolt, plan.bolt_length_mm, sorted(items.items()), revision_and_date(plan),
            envelope_note(plan))


def _fit_scale(v: View, width: float, height: float) -> float:
    """Largest ISO 5455 scale at which view ``v`` fits ``width`` x ``height`` (paper mm)."""
    return fitting_scale((v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1]), (width, height))


def _compound(specs: dict[str, PartSpec], inst: list[Instance], solids: dict):
    from tactcad.assembly.plan_locations import location
    from tactcad.kernel.objects import labelled_compound
    from tactcad.kernel.locations import placed

    return labelled_compound([placed(solids[i.part], location(i.placement)) for i in inst])


def _to_view(cam, p) -> tuple[float, float]:
    n, up = np.array(cam[0], float), np.array(cam[1], float)
    r = np.cross(up, n)
    q = np.array(p, float)
    return (float(q @ r), float(q @ up))


def compose_assembly(plan: Plan, solids: dict, items: dict[str, int]) -> AssemblySheet:
    """The assembly sheet of the array.

    Args:
        plan: validated design.
        solids: build123d solid of every array part by part name (part frame, mm).
        items: BOM item number by part name (the exported bom.csv's numbering).
    """
    specs = array_parts(plan)
    inst = array_instances(plan)
    a = AssemblySheet(Sheet("A3", title=f"array assembly - {plan.name}"))
    sh = a.sheet
    comp = _compound(specs, inst, solids)
    views = {n: project(comp, "front", cameras={"front": cam}) for n, cam in ASSEMBLY_CAMERAS.items()}
    f, s = views["front"], views["side"]
    # the stack (side view) large on the left under its balloons, the view
    # along the bolts right of it, under the slot map
    sx, sy, sw, sh_ = SIDE_BOX
    s.scale = _fit_scale(s, sw, sh_)
    s.place(sx, sy)
    fx = s.paper_box()[2] + 30.0
    fw = FRAME[2] - 10.0 - fx
    # under the slot map, whose height grows with the elements (a 2 x 8 strip's reaches
    # past the view's usual top)
    top = max(FRONT_TOP_LIMIT[0], SLOT_MAP_TOP + slot_map_height(len(plan.slots)) + 12.0)
    f.scale = _fit_scale(f, fw, FRONT_TOP_LIMIT[1] - top)
    f.place(fx + (fw - f.width) / 2, top)
    a.scale = s.scale
    sheet_frame(sh)
    for name, v in views.items():
        for poly in v.hidden:
            sh.polyline(f"view-{name}", [v.paper(*p) for p in poly], "hidden")
        for poly in v.visible:
            sh.polyline(f"view-{name}", [v.paper(*p) for p in poly], "visible")
        b = v.paper_box()
        label = (f"view along the bolts, from +z ({scale_text(v.scale)})" if name == "front"
                 else f"stack, view from +x ({scale_text(v.scale)})")
        below = 10.0 if name == "front" else FIRST_TIER + 4.0 + 9.0  # under the stack's Z dimension
        sh.text(f"view-{name}", ((b[0] + b[2]) / 2, b[3] + below), label, DIM_TEXT_MM,
                anchor="middle", id=f"label-{name}")
    _envelope(a, plan, views)
    _balloons(a, s, ASSEMBLY_CAMERAS["side"], specs, inst, items)
    _slot_table(a, plan)
    _notes(a, plan)
    _title_block(a, plan, items)
    sh.settle()  # the labels last: each finds room among everything drawn
    return a


def _axis_of(direction) -> int:
    """0, 1 or 2: the model axis (x, y, z) a view direction runs along."""
    return int(np.argmax(np.abs(np.array(direction, float))))


def envelope_note(plan: Plan) -> str:
    """The envelope in words, with the margins to ``[requirements] footprint_mm`` when stated."""
    from tactcad.design.requirements_section import stated_footprint

    env = array_envelope_mm(plan)
    text = "Envelope of the clamped array " + " x ".join(fmt_mm(v, 2) for v in env) + " mm (X x Y x Z)"
    stated = stated_footprint(plan.raw)
    if stated is None:
        return text + "."
    margins = ", ".join(f"{'XYZ'[k]} {fmt_mm(lim - env[k], 2)}" for k, lim in enumerate(stated))
    return (text + "; required footprint " + " x ".join(fmt_mm(v, 2) for v in stated)
            + f" mm, margin {margins} mm.")


def _envelope(a: AssemblySheet, plan: Plan, views: dict[str, View]) -> None:
    """The clamped array's overall envelope (X, Y: on the view along the bolts;
    Z: on the stack), from :func:`~tactcad.assembly.inventory.array_envelope_mm`,
    its dimension lines at the views' outlines; the footprint note under them."""
    env = array_envelope_mm(plan)
    f, s = views["front"], views["side"]
    fb, sb = f.paper_box(), s.paper_box()
    # the paper's right is up x n of the camera, its up the camera's up
    f_right = _axis_of(np.cross(ASSEMBLY_CAMERAS["front"][1], ASSEMBLY_CAMERAS["front"][0]))
    f_up = _axis_of(ASSEMBLY_CAMERAS["front"][1])
    a.envelope = {}
    for axis, k, p, q, at in (("h", f_right, (fb[0], fb[1]), (fb[2], fb[1]), fb[1] - FIRST_TIER),
                              ("v", f_up, (fb[2], fb[1]), (fb[2], fb[3]), fb[2] + FIRST_TIER)):
        name = f"envelope_{'xyz'[k]}"
        a.sheet.linear_dimension(p, q, axis, at, fmt_mm(env[k], 2), name)
        a.envelope[name] = env[k]
    s_up = _axis_of(ASSEMBLY_CAMERAS["side"][1])
    s_right = _axis_of(np.cross(ASSEMBLY_CAMERAS["side"][1], ASSEMBLY_CAMERAS["side"][0]))
    if 2 == s_up:
        a.sheet.linear_dimension((sb[0], sb[1]), (sb[0], sb[3]), "v", sb[0] - FIRST_TIER,
                                 fmt_mm(env[2], 2), "envelope_z")
    elif 2 == s_right:
        a.sheet.linear_dimension((sb[0], sb[3]), (sb[2], sb[3]), "h", sb[3] + FIRST_TIER + 4.0,
                                 fmt_mm(env[2], 2), "envelope_z")
    a.envelope["envelope_z"] = env[2]
    lines = wrap_text(envelope_note(plan), fb[2] - fb[0] + 40.0, DIM_TEXT_MM)
    for j, line in enumerate(lines):
        a.sheet.text("envelope", ((fb[0] + fb[2]) / 2, fb[3] + 16.0 + 4.2 * j), line, DIM_TEXT_MM,
                     anchor="middle", id="envelope-note" if j == 0 else "")


def _balloons(a: AssemblySheet, v: View, cam, specs, inst, items: dict[str, int]) -> None:
    """One balloon per distinct part, in a row above the side view, each with
    a leader to one of its instances (ISO 6433)."""
    sh = a.sheet
    def centre(i: Instance):
        x0, y0, z0, x1, y1, z1 = specs[i.part].expected_bbox_mm
        return i.placement.apply((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)

    anchors: dict[str, tuple[float, float]] = {}
    for part in dict.fromkeys(i.part for i in inst):
        if part not in items:
            continue
        # the first instance whose point no other balloon uses; else lift it
        cands = [v.paper(*_to_view(cam, centre(i))) for i in inst if i.part == part]
        free = [p for p in cands if all(math.dist(p, q) > 1.0 for q in anchors.values())]
        p = free[0] if free else cands[0]
        while any(math.dist(p, q) <= 1.0 for q in anchors.values()):
            p = (p[0], p[1] - 2.5)
        anchors[part] = p
    b = v.paper_box()
    ends = {n: v.paper(*_to_view(cam, centre(i)))[0] for i in inst for n in ("front", "back")
            if i.name == f"clamp_plate_{n}"}
    for n, x in ends.items():
        # under its clamp plate, else moved out past the stack's end or lower, where there is room
        out = -1.0 if x < (b[0] + b[2]) / 2 else 1.0
        spots = [Spot((x + out * dx, b[3] + 5.0 + dy), "middle")
                 for dy in (0.0, 4.0, -3.0) for dx in (0.0, 4.0, 8.0, 12.0, 18.0)]
        sh.label("balloons", n.upper(), spots, id=f"stack-{n}")
    order = sorted(anchors, key=lambda p: anchors[p][0])
    n = len(order)
    pitch = max(2 * BALLOON_R + 3.0, (b[2] - b[0]) / max(n - 1, 1))
    # centred over the view, but inside the frame when the row is wider than the view
    x_start = max((b[0] + b[2]) / 2 - pitch * (n - 1) / 2, FRAME[0] + BALLOON_R + 3.0)
    y = b[1] - 14.0
    row = [(x_start + k * pitch, y) for k in range(n)]
    order = uncrossed(order, row, anchors)
    for k, part in enumerate(order):
        c = row[k]
        p = anchors[part]
        ang = math.atan2(p[1] - c[1], p[0] - c[0])
        start = (c[0] + BALLOON_R * math.cos(ang), c[1] + BALLOON_R * math.sin(ang))
        sh.line("balloons", start, p, "thin")
        sh.circle("balloons", p, 0.5)
        sh.circle("balloons", c, BALLOON_R, "thin")
        sh.text("balloons", (c[0], c[1] + LABEL_TEXT_MM / 2), str(items[part]), LABEL_TEXT_MM,
                anchor="middle", id=f"balloon-{part}")
        a.balloons[part] = items[part]


def segments_cross(p: Point, q: Point, r: Point, t: Point) -> bool:
    """Whether the segments ``p``-``q`` and ``r``-``t`` cross at a point inside both."""
    def side(a: Point, b: Point, c: Point) -> float:
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (side(p, q, r) * side(p, q, t) < 0) and (side(r, t, p) * side(r, t, q) < 0)


def uncrossed(order: list[str], row: list[Point], anchors: dict[str, Point]) -> list[str]:
    """``order`` (the parts of the balloons at ``row``'s places, left to
    right) with neighbours swapped until no two neighbours' leaders (balloon
    centre to its part's ``anchors`` point) cross: a crossing leader runs
    through the next balloon's number."""
    order = list(order)
    for _ in range(len(order) ** 2):
        swapped = False
        for k in range(len(order) - 1):
            if segments_cross(row[k], anchors[order[k]], row[k + 1], anchors[order[k + 1]]):
                order[k], order[k + 1] = order[k + 1], order[k]
                swapped = True
        if not swapped:
            break
    return order


def slot_map_row_height(elements: int) -> float:
    """Row height of the slot map (paper mm): :data:`ROW_H`, less for an array whose map
    would leave the view along the bolts under it less than its least height."""
    return min(ROW_H, SLOT_MAP_MAX_HEIGHT / (elements + 1))


def slot_map_height(elements: int) -> float:
    """The slot map's height (paper mm): a header and one row per element."""
    return slot_map_row_height(elements) * (elements + 1)


def _slot_table(a: AssemblySheet, plan: Plan) -> None:
    sh = a.sheet
    rows = slot_map(plan)
    a.slot_rows = rows
    total = sum(w for _, w in SLOT_COLS)
    x0 = FRAME[2] - 6.0 - total
    y0 = SLOT_MAP_TOP
    row_h = slot_map_row_height(len(rows))
    sh.text("slot-map", (x0, y0 - 2.0), "SLOT MAP (element number = slot)", LABEL_TEXT_MM,
            bold=True, id="slot-map-title")
    keys = ("slot", "row", "column", "part", "arm_mm", "dxf", "orientation")
    sh.rect("slot-map", x0, y0, total, row_h * (len(rows) + 1), "table")
    for r_i, row in enumerate([None, *rows]):
        y = y0 + r_i * row_h
        if r_i:
            sh.line("slot-map", (x0, y), (x0 + total, y), "thin")
        x = x0
        for c_i, (head, w) in enumerate(SLOT_COLS):
            if r_i == 0 and c_i:
                sh.line("slot-map", (x, y0), (x, y0 + row_h * (len(rows) + 1)), "thin")
            text = head if row is None else str(row[keys[c_i]])
            h = min(DIM_TEXT_MM, row_h - 2.0)
            while text_width(text, h) > w - 1.5 and h > 1.5:
                h -= 0.1
            sh.text("slot-map", (x + 1.0, y + row_h - 1.5), text, h,
                    id="" if row is None else f"slot-{row['slot']}-{keys[c_i]}")
            x += w


def _clamp_lines(a: AssemblySheet, plan: Plan) -> list[str]:
    """The stack and its clamp bolts, for a plan that has them (none otherwise)."""
    if plan.bolt is None:
        return []
    b = plan.bolt
    bolt = bolt_name(b, plan.bolt_length_mm)
    n_bolts = len(plan.bolt_positions_xy_mm)
    a.stack_order = stack_order(plan)
    a.torque_Nm = tightening_torque_Nm(b)
    lines = []
    for r, names in a.stack_order.items():
        turned = " (turned 180° about y: its tips face row 1's)" if r == 1 else ""
        lines.append(f"Stack of row {r + 1}{turned}, front to back: " + ", ".join(names) + ".")
    lines.append(f"Bolts: {n_bolts}× ISO 4762 {b.size}x{fmt_mm(plan.bolt_length_mm)} - 8.8 "
                 f"({bolt}) through both clamp plates, elements and spacers, with {n_bolts}× "
                 f"ISO 4032 {b.size} - 8 nut ({nut_name(b)}).")
    lines.append(f"Tighten the nuts crosswise in two passes to {a.torque_Nm:.2f} N·m "
                 f"({TORQUE_SOURCE}); check the tips of each row lie in one plane "
                 f"before the second pass.")
    return lines


def _row_sheet_lines(plan: Plan) -> list[str]:
    """The row sheets facing each other on their spine, for a plan of row sheets."""
    comb = plan.comb
    if comb is None:
        return []
    s = comb.screw
    return [f"Row sheets {', '.join(sh.part_name for sh in comb.sheets)} face each other across a "
            f"{fmt_mm(comb.spacer_thickness_mm)} mm spacer, located on {len(comb.dowel_x_mm)}× "
            f"ISO 8734 {fmt_mm(comb.dowel_diameter_mm)} x {fmt_mm(comb.dowel_length_mm)} dowel "
            f"pins and held by {len(comb.screw_x_mm)}× DIN 912 {s.size}x"
            f"{fmt_mm(comb.screw_length_mm)} screws with DIN 934 nuts (spacer, pins and screws: "
            f"purchased-parts.md; not drawn)."]


def _notes(a: AssemblySheet, plan: Plan) -> None:
    sh = a.sheet
    lines = _clamp_lines(a, plan) + _row_sheet_lines(plan)
    lines.append("Balloon numbers are the items of bom.csv / bom.md. Element profiles: the DXF "
                 "files of the slot map (dxf/); " + numbering_note(plan))
    lines.append(f"Untoleranced dimensions of the parts: {general_tolerance(plan)}; see each part's "
                 f"drawing.")
    x0, y = FRAME[0] + 5.0, FRAME[3] - 63.0 - 4.0
    width = FRAME[2] - 180.0 - 10.0 - x0
    wrapped = [wrap_text(f"{k}. {t}", width * 0.95, DIM_TEXT_MM) for k, t in enumerate(lines, start=1)]
    y = FRAME[3] - 4.0 - sum(len(w) * 4.2 + 0.8 for w in wrapped)
    sh.text("notes", (x0, y - 5.0), "ASSEMBLY NOTES", LABEL_TEXT_MM, bold=True)
    for k, ws in enumerate(wrapped, start=1):
        for j, line in enumerate(ws):
            sh.text("notes", (x0 + (4.0 if j else 0.0), y), line, DIM_TEXT_MM,
                    id=f"note-{k}" if j == 0 else "")
            y += 4.2
        y += 0.8


def _title_block(a: AssemblySheet, plan: Plan, items: dict[str, int]) -> None:
    from tactcad.version import VERSION

    sh = a.sheet
    tw, rh = 180.0, 9.0
    x0, y0 = FRAME[2] - tw, FRAME[3] - 4 * rh
    rev, date = revision_and_date(plan)
    digest = hashlib.sha256(stable_repr(assembly_inputs(plan, items)).encode()).hexdigest()
    cells = [(0, 0, 120, "Assembly", f"array ({plan.rows} x {plan.columns} elements)", "tb-part"),
             (0, 120, 60, "Scale", scale_text(a.scale), "tb-scale"),
             (1, 0, 120, "Design", f"{plan.name}  sheet sha256 {digest[:12]}", "tb-design"),
             (1, 120, 60, "Drawing no.", f"{plan.name}-assembly", "tb-number"),
             (2, 0, 120, "Generated by", f"tactcad {VERSION}", "tb-version"),
             (2, 120, 60, "Units", "mm, N·m", "tb-units"),
             (3, 0, 120, "Projection", "first angle (ISO 128-30)", "tb-projection"),
             (3, 120, 25, "Revision", rev, "tb-revision"),
             (3, 145, 35, "Date", date, "tb-date")]
    sh.rect("title-block", x0, y0, tw, 4 * rh, "frame")
    title_cells(sh, x0, y0, rh, [(*c, LABEL_TEXT_MM) for c in cells])
