"""DXF files for the cutting shop: one file per distinct cut profile, and a
nested sheet per material and thickness.

* ``dxf/<part>_qty<n>.dxf``: one distinct profile (five element variants,
  the spacer), its quantity in the name, in the custom header properties
  (R2010) and in the part mark. Elements 1 and 8 share ``element_a4mm``.
* ``dxf/sheet_<material>_<t>mm.dxf``: every copy of every profile cut from
  that sheet, laid out in shelves (rows of parts sorted by height) with a gap
  of at least 2 x (wire radius + spark gap) + :data:`SHEET_MARGIN_MM`
  between outer contours, each copy marked with its element number and arm
  length (``E1 A4``) or part name on the ``MARK`` layer.

Which parts: the elements (wire EDM) and the spacer (wire EDM or laser cut).
The clamp plate is milled (pockets and window from the drawing), not cut from
a profile, so it has no DXF here.

Lead-ins (layer ``LEAD_IN``): the outer cut enters on the straight edge
farthest from the flexure web and the contact face (for the elements the
base's back face), from a start point :data:`LEAD_IN_MM` outside the part;
each hole is entered from its start hole at the hole centre, on the side away
from the web. Units mm throughout.

Each part is drawn as its cut process's shop expects
(:attr:`tactcad.vocabulary.process.CutProcess.shop`): wire EDM and laser the
nominal contour with lead-ins, holding tabs (layer ``TAB``, by the part's
size) and the cut order (layer ``CUT_ORDER`` and the ``CUT_ORDER`` header
property: inner contours, outer contour, tabs last); etching the artwork, the
outline offset outward by the etch compensation (holes smaller by it), with
no lead-ins. The header carries the process, its compensation, kerf and
tolerance and the notes its shop needs.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Callable, Sequence

import shapely.geometry as sg

from tactcad.catalogue.array_catalogue import PartSpec, array_parts
from tactcad.design.array_plan import ElementGeometry, Plan
from tactcad.geometry.profile import Circle, Line, Point, Profile, contour_points
from tactcad.errors import DesignError
from tactcad.catalogue.files import profile_dxf_name, sheet_dxf_name, sheet_names_by_process
from tactcad.catalogue.shop import material_designation
from tactcad.partlib.array.comb_hardware import SPACER_PART as COMB_SPACER_PART
from tactcad.partlib.array.comb_sheet import CombSheet
from tactcad.export.dxf import (DEFAULT_DXF_VERSION, DXF_VERSIONS, DxfFile, LeadIn, Mark, PlacedProfile, Tab,
                                circle_entry, placed_extents, write_dxf)
from tactcad.vocabulary.process import (DEFAULT_CUT_PROCESS, CutProcess, ProcessLimits, WireSettings,
                                        cut_process)

DXF_VERSION_ENV = "TACTCAD_DXF_VERSION"  # the writer's option: R2010 (default) or R12
LEAD_IN_MM = 1.0  # start point of the outer cut, this far outside the part
SHEET_MARGIN_MM = 2.0  # added to two wire offsets between parts: room for the lead-ins
MARK_HEIGHTS_MM = (1.0, 0.8, 0.6, 0.5)
MARK_CHAR_WIDTH = 0.9  # width of a mark character / text height, an upper bound for simple fonts
MARK_CLEARANCE_MM = 0.3  # between a mark and any cut edge


@dataclass(frozen=True)
class ShopProfile:
    """One distinct cut profile and what the shop needs to know about it.

    Attributes:
        part: part name (``element_a4mm``, ``spacer``).
        profile: nominal contour (mm), start holes included.
        quantity: copies in the array.
        material, thickness_mm: the sheet it is cut from.
        copy_marks: one mark text per copy (``E1 A4``, ``E8 A4``; ``SPACER``).
        file_mark: mark of the single-profile file (``E1/E8 A4 QTY 2``).
        keep_out: points (mm, profile frame) the lead-ins stay away from: the
            web (thinnest section over the notch) and the contact-face centre.
        web_thickness_mm: the design web for elements, None otherwise.
        web_tolerance_mm: +/- on the web as the drawing gives it, None without a web.
        designation: the material with alloy and temper, as the BOM and the
            drawings write it (:func:`tactcad.catalogue.shop.material_designation`).
        sheet_material: the material its nested sheet is named by
            (:func:`~tactcad.catalogue.files.sheet_names_by_process`).
        process: the name of its cut process (:func:`~tactcad.vocabulary.process.cut_process`).
        wire: the design's wire-EDM settings (``plan.edm``), which wire EDM's limits read.
    """

    part: str
    profile: Profile
    quantity: int
    material: str
    thickness_mm: float
    copy_marks: tuple[str, ...]
    keep_out: tuple[Point, ...]
    file_mark: str
    web_thickness_mm: float | None = None
    web_tolerance_mm: float | None = None
    designation: str = ""
    sheet_material: str = ""
    process: str = DEFAULT_CUT_PROCESS
    wire: WireSettings | None = None

    @property
    def file_name(self) -> str:
        return profile_dxf_name(self.part, self.quantity)

    @property
    def cut(self) -> CutProcess:
        """Its cut process."""
        return cut_process(self.process)

    @property
    def limits(self) -> ProcessLimits:
        """What its process makes from its sheet (mm)."""
        return self.cut.limits(self.thickness_mm, self.wire, self.designation or self.material)

    @property
    def drawn(self) -> Profile:
        """The contour its shop file draws: the nominal one (with its start
        holes where the process drills them), or the etch artwork's
        compensated outline (:func:`compensated_profile`)."""
        if not self.cut.shop.offset_outline:
            return self.profile if self.cut.shop.start_holes else replace(self.profile,
                                                                            start_holes=())
        return compensated_profile(self.profile, self.limits.compensation_per_side_mm.value_mm)


def compensated_profile(profile: Profile, offset_mm: float) -> Profile:
    """``profile`` with its outline moved outward by ``offset_mm`` (round at
    convex corners; a straight chain of short lines, 1e-4 mm from the exact
    offset) and every hole smaller in radius by it; no start holes (etch
    artwork is not entered by a tool).

    Raises:
        ValueError: a hole would close (radius <= ``offset_mm``).
    """
    import shapely.geometry as sg

    if offset_mm <= 0:
        return replace(profile, start_holes=())
    grown = sg.Polygon(contour_points(profile.outer, 1e-4)).buffer(offset_mm, quad_segs=64)
    ring = sg.polygon.orient(grown, 1.0).exterior.coords[:-1]
    outer = tuple(Line(tuple(a), tuple(b)) for a, b in zip(ring, ring[1:] + ring[:1]))
    for h in profile.holes:
        if h.radius <= offset_mm:
            raise ValueError(f"hole of radius {h.radius:g} mm closes under an etch compensation "
                             f"of {offset_mm:g} mm")
    return Profile(outer, tuple(Circle(h.centre, h.radius - offset_mm) for h in profile.holes), ())


def element_keep_out(g: ElementGeometry) -> tuple[Point, ...]:
    """The web's middle and the contact-face centre (mm): no lead-in may start there."""
    return (g.web_centre_mm, g.contact_centre_mm)


def _arm_mark(a_mm: float) -> str:
    return "A" + f"{a_mm:g}".replace(".", "P")


def _with_start_holes(profile: Profile, start_diameter_mm: float) -> Profile:
    """A start hole at the centre of every hole, as the wire needs one for each closed cut-out."""
    starts = tuple(Circle(h.centre, start_diameter_mm / 2) for h in profile.holes)
    return replace(profile, start_holes=starts)


#: The part modules whose parts are cut from a profile (the clamp plate is milled; of the
#: comb's hardware only its spacer is cut, the rest is bought).
CUT_FAMILIES = ("element", "spacer", "comb_sheet", "comb_hardware")


def shop_profiles(plan: Plan) -> list[ShopProfile]:
    """The cut profiles of ``plan``: the distinct elements in order of first use,
    then the spacer. Quantities count the plan's element slots and spacers."""
    specs = array_parts(plan, CUT_FAMILIES)
    counts: dict[str, int] = {"spacer": len(plan.spacer_placements)}
    for slot in plan.slots:
        counts[slot.geometry.part_name] = counts.get(slot.geometry.part_name, 0) + 1
    out = [_row_sheet_profile(plan, spec) for spec in specs.values()
           if isinstance(spec.geometry, CombSheet)]
    out += [_plate_profile(plan, spec, "SPACER") for spec in specs.values()
            if spec.name == COMB_SPACER_PART]
    for name in (n for n in plan.distinct_elements if n in specs):
        g = specs[name].geometry
        numbers = [s.number for s in plan.slots if s.geometry.part_name == name]
        out.append(ShopProfile(
            part=name, profile=specs[name].profile, quantity=counts[name],
            material=specs[name].material, thickness_mm=specs[name].thickness_mm,
            copy_marks=tuple(f"E{n} {_arm_mark(g.arm_length_mm)}" for n in numbers),
            keep_out=element_keep_out(g), web_thickness_mm=g.web_thickness_mm,
            web_tolerance_mm=g.web_tolerance_mm,
            designation=material_designation(specs[name], plan),
            process=specs[name].process.key or DEFAULT_CUT_PROCESS, wire=plan.edm,
            file_mark=f"{'/'.join(f'E{n}' for n in numbers)} {_arm_mark(g.arm_length_mm)} "
                      f"QTY {counts[name]}"))
    if "spacer" not in specs:  # one column: no spacer
        return _named_sheets(out)
    sp: PartSpec = specs["spacer"]
    out.append(ShopProfile(
        part="spacer", profile=_with_start_holes(sp.profile, plan.edm.start_hole_diameter_mm),
        quantity=counts["spacer"], material=sp.material, thickness_mm=sp.thickness_mm,
        copy_marks=("SPACER",) * counts["spacer"], keep_out=(),
        designation=material_designation(sp, plan),
        process=sp.process.key or DEFAULT_CUT_PROCESS, wire=plan.edm,
        file_mark=f"SPACER QTY {counts['spacer']}"))
    return _named_sheets(out)


def _row_sheet_profile(plan: Plan, spec: PartSpec) -> ShopProfile:
    """The cut profile of a sheet that carries a whole row's elements (one
    copy): the lead-ins keep away from every element's web and contact face,
    and the read-back holds the sheet to its thinnest web."""
    sheet: CombSheet = spec.geometry
    keep = tuple((x + x0, y) for g, x0 in zip(sheet.elements, sheet.offsets_mm)
                 for x, y in element_keep_out(g))
    thinnest = min(sheet.elements, key=lambda g: g.web_thickness_mm)
    numbers = [s.number for s in plan.slots if s.row == sheet.row]
    mark = f"ROW{sheet.row + 1} E{numbers[0]}-E{numbers[-1]}"
    return ShopProfile(
        part=spec.name, profile=spec.profile, quantity=1, material=spec.material,
        thickness_mm=spec.thickness_mm, copy_marks=(mark,), keep_out=keep,
        web_thickness_mm=thinnest.web_thickness_mm, web_tolerance_mm=thinnest.web_tolerance_mm,
        designation=material_designation(spec, plan),
        process=spec.process.key or DEFAULT_CUT_PROCESS, wire=plan.edm,
        file_mark=f"{mark} QTY 1")


def _plate_profile(plan: Plan, spec: PartSpec, mark: str) -> ShopProfile:
    """The cut profile of a plate without a flexure (one copy; its holes with the start
    holes a wire needs: the shop file keeps them only for a process that drills them)."""
    return ShopProfile(
        part=spec.name, profile=_with_start_holes(spec.profile, plan.edm.start_hole_diameter_mm),
        quantity=1, material=spec.material, thickness_mm=spec.thickness_mm,
        copy_marks=(mark,), keep_out=(), designation=material_designation(spec, plan),
        process=spec.process.key or DEFAULT_CUT_PROCESS, wire=plan.edm,
        file_mark=f"{mark} QTY 1")


def _named_sheets(profiles: Sequence[ShopProfile]) -> list[ShopProfile]:
    """``profiles`` each with the name of its nested sheet: one grade, one
    thickness and one process per sheet (:func:`~tactcad.catalogue.files.sheet_names_by_process`)."""
    names = sheet_names_by_process([(sp.material, sp.designation, sp.thickness_mm, sp.process)
                                    for sp in profiles])
    return [replace(sp, sheet_material=n) for sp, n in zip(profiles, names)]




# --- lead-ins -------------------------------------------------------------------
def _distance_to(points: Sequence[Point], p: Point) -> float:
    return min((math.dist(p, q) for q in points), default=math.inf)


def outer_lead_in(profile: Profile, keep_out: Sequence[Point], length_mm: float = LEAD_IN_MM) -> LeadIn:
    """Lead-in of the outer cut: the entry is the middle of the straight edge
    whose middle lies farthest from every keep-out point (the longest edge
    when there is none), among the edges whose lead-in runs clear of the part;
    the start lies ``length_mm`` outside, on the edge's outward normal.

    An edge facing a slot narrower than ``length_mm`` (between a long arm and the
    base) is passed over: its start would lie in the part across the slot.

    Raises:
        ValueError: the outer contour has no straight edge with room for a lead-in.
    """
    part = sg.Polygon(contour_points(profile.outer))
    ccw = part.exterior.is_ccw
    edges = [(s, _edge_lead_in(s, length_mm, ccw)) for s in profile.outer if isinstance(s, Line)]
    clear = [(s, lead) for s, lead in edges if _runs_clear(lead, part)]
    if not clear:
        raise ValueError(f"outer contour has no straight edge with {length_mm} mm clear outside "
                         "it for a lead-in")
    return max(clear, key=lambda e: (min(_distance_to(keep_out, e[1].entry), 1e9), e[0].length()))[1]


def _edge_lead_in(edge: Line, length_mm: float, ccw: bool) -> LeadIn:
    """The lead-in onto the middle of ``edge`` from ``length_mm`` outside, the
    outside being the right of a counter-clockwise contour's direction."""
    (x0, y0), (x1, y1) = edge.start, edge.end
    n = edge.length()
    side = 1.0 if ccw else -1.0
    outward = (side * (y1 - y0) / n, -side * (x1 - x0) / n)
    entry = ((x0 + x1) / 2, (y0 + y1) / 2)
    return LeadIn((entry[0] + length_mm * outward[0], entry[1] + length_mm * outward[1]), entry)


def _runs_clear(lead: LeadIn, part: sg.Polygon) -> bool:
    """Whether ``lead``'s line, its entry aside, lies outside ``part``."""
    (sx, sy), (ex, ey) = lead.start, lead.entry
    # stop a hair short of the entry, which lies on the part's edge
    near_entry = (ex + (sx - ex) * 1e-6, ey + (sy - ey) * 1e-6)
    return not sg.LineString([lead.start, near_entry]).intersects(part)


def hole_lead_ins(profile: Profile, keep_out: Sequence[Point]) -> tuple[LeadIn, ...]:
    """One lead-in per hole: from its centre (the start hole) to the hole's
    point farthest from the nearest keep-out point."""
    out = []
    for h in profile.holes:
        nearest = min(keep_out, key=lambda q: math.dist(q, h.centre)) if keep_out else None
        out.append(LeadIn(h.centre, circle_entry(h, nearest)))
    return tuple(out)


def lead_ins(sp: ShopProfile) -> tuple[LeadIn, ...]:
    """The lead-ins of ``sp``'s shop file: the outer cut's, then each hole's;
    none for a process whose tool does not enter the sheet (etching)."""
    if not sp.cut.shop.lead_ins:
        return ()
    return (outer_lead_in(sp.profile, sp.keep_out),) + hole_lead_ins(sp.profile, sp.keep_out)


# --- holding tabs and the cut order ----------------------------------------------
#: A tab stays this far from a keep-out point (web, contact face) and from the lead-in's entry.
TAB_CLEARANCE_MM = 1.0
ORDER_HEIGHT_MM = 0.5


def part_tabs(sp: ShopProfile, leads: Sequence[LeadIn]) -> tuple[Tab, ...]:
    """The holding tabs of ``sp`` by its process's tab rule and its largest
    side: each centred on a straight outer edge long enough for it, edges
    farthest from the keep-out points (web, contact face) and from the outer
    lead-in's entry first, one tab per edge while edges last, then more on the
    longest. None for a process without tabs."""
    rule = sp.cut.shop.tabs
    if rule is None:
        return ()
    x0, y0, x1, y1 = sp.profile.bbox_mm
    count, width = rule.tabs_for(max(x1 - x0, y1 - y0))
    if count == 0:
        return ()
    avoid = list(sp.keep_out) + [li.entry for li in leads[:1]]
    edges = [s for s in sp.profile.outer
             if isinstance(s, Line) and s.length() >= width + 2 * TAB_CLEARANCE_MM]

    def clearance(s: Line, f: float) -> float:
        p = (s.start[0] + f * (s.end[0] - s.start[0]), s.start[1] + f * (s.end[1] - s.start[1]))
        return _distance_to(avoid, p)

    spots = sorted(((clearance(s, f), s.length(), i, f) for i, s in enumerate(edges)
                    for f in (0.5, 0.25, 0.75)), key=lambda c: (c[3] != 0.5, -c[0], -c[1]))
    tabs = []
    for _, _, i, f in spots[:count]:
        s = edges[i]
        ux, uy = (s.end[0] - s.start[0]) / s.length(), (s.end[1] - s.start[1]) / s.length()
        cx = s.start[0] + f * (s.end[0] - s.start[0])
        cy = s.start[1] + f * (s.end[1] - s.start[1])
        h = width / 2
        tabs.append(Tab((round(cx - h * ux, 9), round(cy - h * uy, 9)),
                        (round(cx + h * ux, 9), round(cy + h * uy, 9))))
    return tuple(tabs)


def cut_order_labels(sp: ShopProfile, leads: Sequence[LeadIn]) -> tuple[Mark, ...]:
    """The cut order at the lead-in starts: the holes 1 ... n, the outer
    contour n + 1 (its lead-in is the first of ``leads``); none without lead-ins."""
    if not leads:
        return ()
    outer, holes = leads[0], leads[1:]
    out = [Mark(str(k), li.start, ORDER_HEIGHT_MM) for k, li in enumerate(holes, start=1)]
    return tuple(out) + (Mark(str(len(holes) + 1), outer.start, ORDER_HEIGHT_MM),)


def placed(sp: ShopProfile, offset: Point, mark: Mark) -> PlacedProfile:
    """One copy of ``sp`` as its process's shop file draws it, moved by ``offset``."""
    leads = lead_ins(sp)
    return PlacedProfile(sp.drawn, offset, leads, (mark,), part_tabs(sp, leads),
                         cut_order_labels(sp, leads))


# --- part marks -----------------------------------------------------------------
def _cut_area(profile: Profile):
    import shapely.geometry as sg

    poly = sg.Polygon(contour_points(profile.outer))
    for h in profile.holes:
        poly = poly.difference(sg.Point(h.centre).buffer(h.radius, 64))
    return poly


@lru_cache(maxsize=64)
def _mark_area(profile: Profile):
    """Where a mark may go: the part's cut area shrunk by :data:`MARK_CLEARANCE_MM`,
    prepared for many containment tests (made once per profile and process)."""
    import shapely

    area = _cut_area(profile).buffer(-MARK_CLEARANCE_MM)
    shapely.prepare(area)
    return area


def place_mark(profile: Profile, text: str, step_mm: float = 0.25) -> Mark:
    """A mark inside the part, clear of every cut edge by :data:`MARK_CLEARANCE_MM`:
    the largest height of :data:`MARK_HEIGHTS_MM` that fits, lowest then
    leftmost position on a grid (one row of the grid tested at once). When
    nothing fits, the mark goes just below the part at the smallest height."""
    import numpy as np
    import shapely

    area = _mark_area(profile)
    x0, y0, x1, y1 = profile.bbox_mm
    nx, ny = int((x1 - x0) / step_mm), int((y1 - y0) / step_mm)
    xs = x0 + np.arange(nx + 1) * step_mm
    for h in MARK_HEIGHTS_MM:
        w = MARK_CHAR_WIDTH * h * len(text)
        for j in range(ny + 1):
            y = y0 + j * step_mm
            fits = shapely.contains(area, shapely.box(xs, y, xs + w, y + h))
            if fits.any():
                return Mark(text, (round(float(xs[fits.argmax()]), 6), round(y, 6)), h)
    h = MARK_HEIGHTS_MM[-1]
    return Mark(text, (x0, y0 - MARK_CLEARANCE_MM - h), h)


# --- nesting --------------------------------------------------------------------
def sheet_gap_mm(plan: Plan) -> float:
    """Smallest gap between two parts' outer contours on a sheet (mm):
    2 x (wire radius + spark gap) + :data:`SHEET_MARGIN_MM`."""
    return 2 * plan.edm.min_inside_radius_mm + SHEET_MARGIN_MM


def shelf_layout(sizes: Sequence[tuple[float, float]], gap_mm: float,
                 row_width_mm: float | None = None) -> list[Point]:
    """Lower-left corners (mm) of boxes ``sizes`` (width, height) packed in
    shelves: boxes sorted by height (tallest first, then input order), filled
    left to right with ``gap_mm`` between them and around the sheet border; a
    new shelf starts when the next box would pass ``row_width_mm`` (default:
    about a square sheet). Returns the corners in input order."""
    if not sizes:
        return []
    if row_width_mm is None:
        area = sum((w + gap_mm) * (h + gap_mm) for w, h in sizes)
        row_width_mm = max(max(w for w, _ in sizes), math.sqrt(area) * 1.2)
    order = sorted(range(len(sizes)), key=lambda i: (-sizes[i][1], i))
    corners: list[Point] = [(0.0, 0.0)] * len(sizes)
    x, y, shelf_h = gap_mm, gap_mm, 0.0
    for i in order:
        w, h = sizes[i]
        if x > gap_mm and x + w > gap_mm + row_width_mm:
            x, y, shelf_h = gap_mm, y + shelf_h + gap_mm, 0.0
        corners[i] = (x, y)
        x += w + gap_mm
        shelf_h = max(shelf_h, h)
    return corners


def _lead_extents(sp: ShopProfile, leads: Sequence[LeadIn]) -> tuple[float, float, float, float]:
    x0, y0, x1, y1 = sp.drawn.bbox_mm
    xs = [x0, x1] + [li.start[0] for li in leads]
    ys = [y0, y1] + [li.start[1] for li in leads]
    return (min(xs), min(ys), max(xs), max(ys))


def nested_sheet(profiles: Sequence[ShopProfile], gap_mm: float) -> list[PlacedProfile]:
    """Every copy of ``profiles`` placed on one sheet by :func:`shelf_layout`;
    boxes include the lead-in start points, so the gap holds between parts
    and from one part's lead-in to the next part."""
    copies = []
    for sp in profiles:
        ext = _lead_extents(sp, lead_ins(sp))
        for text in sp.copy_marks:
            copies.append((sp, ext, place_mark(sp.profile, text)))
    sizes = [(e[2] - e[0], e[3] - e[1]) for _, e, _ in copies]
    corners = shelf_layout(sizes, gap_mm)
    return [placed(sp, (round(cx - ext[0], 6), round(cy - ext[1], 6)), mark)
            for (sp, ext, mark), (cx, cy) in zip(copies, corners)]


# --- the writer -----------------------------------------------------------------
def dxf_version_option() -> str:
    """The DXF version the writer uses: ``$TACTCAD_DXF_VERSION`` (set by
    ``tactcad export --dxf-version``), ``R2010`` when unset.

    Raises:
        DesignError: a version other than ``R2010`` or ``R12``.
    """
    version = os.environ.get(DXF_VERSION_ENV, DEFAULT_DXF_VERSION)
    if version not in DXF_VERSIONS:
        raise DesignError("--dxf-version", version, " or ".join(DXF_VERSIONS))
    return version


def process_properties(sp: ShopProfile) -> dict[str, str]:
    """What the shop file's header says of the process: its name, the file's
    kind, compensation, kerf, tolerance, tab rule, cut order and notes."""
    cut, lim = sp.cut, sp.limits
    out = {"PROCESS": cut.name, "FILE_KIND": cut.shop.kind,
           "COMPENSATION_PER_SIDE_MM": f"{lim.compensation_per_side_mm.value_mm:.4g}",
           "TOLERANCE_MM": f"+/-{lim.tolerance_mm.value_mm:.3g}"}
    if lim.kerf_mm is not None:
        out["KERF_MM"] = f"{lim.kerf_mm.value_mm:.4g}"
    if cut.shop.tabs is not None:
        out["TABS"] = cut.shop.tabs.text()
    if cut.shop.cut_order:
        out["CUT_ORDER"] = "; ".join(cut.shop.cut_order)
    out["NOTES"] = " | ".join(cut.shop.notes)
    return out


def _properties(plan: Plan, sp: ShopProfile) -> dict[str, str]:
    return {"DESIGN": plan.name, "PART": sp.part, "QUANTITY": str(sp.quantity),
            "MATERIAL": sp.designation or sp.material, "THICKNESS_MM": f"{sp.thickness_mm:g}",
            "MARKS": ", ".join(sp.copy_marks), "UNITS": "mm", **process_properties(sp)}


def sheets(plan: Plan) -> dict[tuple[str, float], list[ShopProfile]]:
    """Cut profiles grouped by sheet: (sheet material, thickness mm), one
    grade, one thickness and one process per sheet
    (:func:`~tactcad.catalogue.files.sheet_names_by_process`), in order
    of first use."""
    return group_by_sheet(shop_profiles(plan))


def group_by_sheet(profiles: Sequence[ShopProfile]) -> dict[tuple[str, float], list[ShopProfile]]:
    """``profiles`` grouped by (sheet material, thickness mm): one key per grade and thickness."""
    out: dict[tuple[str, float], list[ShopProfile]] = {}
    for sp in profiles:
        out.setdefault((sp.sheet_material or sp.material, sp.thickness_mm), []).append(sp)
    return out


def write_shop_profile(path: Path, plan: Plan, sp: ShopProfile, version: str = DEFAULT_DXF_VERSION) -> Path:
    """One profile's shop file: profile at its origin, lead-ins, the file mark,
    quantity and material in the header (R2010)."""
    item = placed(sp, (0.0, 0.0), place_mark(sp.profile, sp.file_mark))
    title = f"{plan.name} {sp.part} qty {sp.quantity}"
    return write_dxf(path, DxfFile((item,), title, _properties(plan, sp)), version)


def write_shop_dxf_files(plan: Plan, staging: Path, log: Callable[[str], None],
                         version: str | None = None) -> list[dict]:
    """Write the per-profile DXF files and the nested sheets into ``staging/dxf``
    (``version`` None: :func:`dxf_version_option`).

    Returns:
        File records: ``{"path", "part", "kind": "dxf-profile", "quantity",
        "marks", "material", "thickness_mm", "dxf_version"}`` per profile and
        ``{"path", "part": "sheet", "kind": "dxf-sheet", "material",
        "thickness_mm", "parts": {part: quantity}, "gap_mm", "sheet_mm": [width,
        height] (parts plus the gap as border), "dxf_version"}`` per sheet.

    Raises:
        DesignError: ``version`` is not ``R2010`` or ``R12``.
    """
    version = _checked_version(version)
    records: list[dict] = []
    for (material, t), group in sheets(plan).items():
        for sp in group:
            records.append(_write_profile_file(plan, staging, sp, material, version))
        rel = sheet_dxf_name(material, t)
        gap = sheet_gap_mm(plan)
        grades = ", ".join(dict.fromkeys(sp.designation or sp.material for sp in group))
        props = {"DESIGN": plan.name, "MATERIAL": grades, "THICKNESS_MM": f"{t:g}",
                 "PARTS": ", ".join(f"{sp.part} x{sp.quantity}" for sp in group),
                 "GAP_MM": f"{gap:g}", "UNITS": "mm", **process_properties(group[0])}
        placed = tuple(nested_sheet(group, gap))
        write_dxf(staging / rel, DxfFile(placed, f"{plan.name} sheet {grades} {t:g} mm", props),
                  version)
        x0, y0, x1, y1 = placed_extents(placed)
        records.append({"path": rel, "part": "sheet", "kind": "dxf-sheet", "material": material,
                        "thickness_mm": t, "parts": {sp.part: sp.quantity for sp in group},
                        "gap_mm": gap, "sheet_mm": [round(x1 + gap, 3), round(y1 + gap, 3)],
                        "dxf_version": version, "process": group[0].process})
    log(f"  wrote {len(records)} DXF files in dxf/ ({version})")
    return records


def write_part_dxf_files(plan: Plan, staging: Path, part: str, log: Callable[[str], None],
                         version: str | None = None) -> list[dict]:
    """Write ``part``'s own profile DXF files into ``staging/dxf`` (``dxf/<part>_qty<n>.dxf``,
    as :func:`write_shop_dxf_files` writes them), without the nested sheets: a sheet nests
    every part cut from it, so it is no one part's file (``tactcad export --part``).

    Args:
        plan: the array's plan.
        staging: the folder the files go in.
        part: a part cut from sheet (:func:`shop_profiles`).
        log: told what was written.
        version: ``R2010`` or ``R12`` (None: :func:`dxf_version_option`).

    Returns:
        One ``dxf-profile`` record per file, as :func:`write_shop_dxf_files` gives.

    Raises:
        DesignError: ``version`` is not ``R2010`` or ``R12``.
    """
    version = _checked_version(version)
    records = [_write_profile_file(plan, staging, sp, material, version)
               for (material, _), group in sheets(plan).items() for sp in group
               if sp.part == part]
    log(f"  wrote {len(records)} DXF file(s) of {part} in dxf/ ({version})")
    return records


def _checked_version(version: str | None) -> str:
    """``version``, or :func:`dxf_version_option` when None; refused unless a known one."""
    version = version or dxf_version_option()
    if version not in DXF_VERSIONS:
        raise DesignError("--dxf-version", version, " or ".join(DXF_VERSIONS))
    return version


def _write_profile_file(plan: Plan, staging: Path, sp: ShopProfile, material: str,
                        version: str) -> dict:
    """Write one profile's shop file into ``staging``; its ``dxf-profile`` record."""
    write_shop_profile(staging / sp.file_name, plan, sp, version)
    return {"path": sp.file_name, "part": sp.part, "kind": "dxf-profile",
            "quantity": sp.quantity, "marks": list(sp.copy_marks), "material": material,
            "thickness_mm": sp.thickness_mm, "dxf_version": version, "process": sp.process}


def shop_section(plan: Plan) -> dict:
    """The DXF kind's section of the manifest: per cut part its process, what
    its shop file is, the process's figures for its sheet (each with its rule
    and source), its tabs and the stated cut order (mm)."""
    out = {}
    for sp in shop_profiles(plan):
        cut, lim = sp.cut, sp.limits
        x0, y0, x1, y1 = sp.profile.bbox_mm
        count, width = cut.shop.tabs.tabs_for(max(x1 - x0, y1 - y0)) if cut.shop.tabs else (0, 0.0)
        out[sp.part] = {"process": cut.name, "file_kind": cut.shop.kind,
                        "thickness_mm": sp.thickness_mm,
                        "figures": {k: f.as_json() for k, f in lim.figures().items()},
                        "tabs": {"count": count, "width_mm": width},
                        "cut_order": list(cut.shop.cut_order), "surface": cut.surface}
    return out

