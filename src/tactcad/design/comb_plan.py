"""The ``monolithic-comb`` construction: design file -> validated plan.

One row's elements are cut from one thin sheet, each element's flexure
profile (the stacked element's: base, notch hinge, arm, tip) standing on a
common spine; the two rows' sheets face each other across a thin spacer and
are located by two ISO 8734 dowel pins and held by miniature socket head cap
screws through the spine. A row runs along the array's z (a grasper jaw's
length), so the two rows' tips of one column lie at the same distance from the
jaw's pivot. Under every arm a ledge of the spine is a hard stop: the arm's
free end lands on it after a set travel (the stop gap).

The derivation here gives every dimension with its reason (:class:`Derived`);
each element's profile is an :class:`~tactcad.partlib.array.element.ElementGeometry`,
so the mechanics (closed form, FEM) read the comb's elements as they read the
stacked array's. The wire-EDM rule of the minimum slot (wire diameter + two
spark gaps, ``[edm]``) bounds every cut gap: the column pitch less the
element, the notch and each stop gap. Units: mm, N, MPa.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Mapping

from pydantic import create_model

from tactcad.design.array_plan import (MIN_ARM_STEP_MM, MIN_FASTENER_GAP_MM, MIN_LIGAMENT_MM,
                                       MIN_SPACER_MM, MIN_TIP_WALL_MM, ArmsSection, ArraySection,
                                       DesignSection, EdmSection, ElementSlot, FilesSection,
                                       HardStop, Material, MaterialSection, Placement, Plan,
                                       SheetSection, StrengthSection, check_references,
                                       check_in_use, check_web_tolerance_held, design_hash,
                                       EdmRules, edm_rules, in_use_tables, pairing_of,
                                       shaping_tables, unit_references,
                                       with_grade_defaults, grade_filled, _grade_error,
                                       refuse_grade)
from tactcad.design.bom_section import BomSection
from tactcad.design.readout_section import ReadoutSection, check_readout
from tactcad.design.requirements_section import (RequirementsSection, check_requirements,
                                                 stated_footprint)
from tactcad.design.tolerances import TolerancesSection, check_tolerances, tolerances_of
from tactcad.errors import DesignError
from tactcad.partlib.array.comb_sheet import CombGeometry, CombSection, CombSheet
# the widest stop gap, here for the studies (they do not read the part library)
from tactcad.partlib.array.comb_sheet import MAX_STOP_GAP_MM  # noqa: F401
from tactcad.partlib.array.element import (ARM_RANGE_MM, FITTED_DOMAIN, NOTCH_RADIUS_MAX_MM,
                                           WEB_TOLERANCE_RANGE_MM,
                                           WEB_RANGE_MM, ElementGeometry)
from tactcad.partlib.array.prism import Hole
from tactcad.vocabulary.material_library import material_fields, strength_settings
from tactcad.vocabulary.process import (CUT_PROCESSES, DEFAULT_CUT_PROCESS, ProcessLimits,
                                        check_sheet_process, first_process_holding)
from tactcad.vocabulary.schema import (Derived, Problems, Section, choice, copy_tables, fmt,
                                       number, read_assumptions, with_counts, validate)
from tactcad.vocabulary.standards import (DOWEL_PINS, MINIATURE_SCREWS, shortest_dowel_length,
                                          shortest_stock_length)

#: Thinnest shim a stop gap is set with at assembly (mm): feeler stock starts at 0.02 mm.
MIN_SET_GAP_MM = 0.02
#: Fasteners: two dowel pins (one at each end of the row) and two screws.
DOWELS_PER_ROW = 2
SCREWS_PER_ROW = 2


class CombElementSection(Section):
    """``[element]`` of a comb: the profile every element shares (mm). The
    base is each element's post (``[comb] post_length_mm``) and its height
    follows from the spine and the stop gaps, so neither is given here."""

    #: every element's web, where ``[comb] web_thicknesses_mm`` does not give each its own
    #: (one of the two, not both: a web the other overrides would be read by nothing)
    web_thickness_mm: number(*WEB_RANGE_MM, why=FITTED_DOMAIN) = None
    notch_radius_mm: number(0.0, NOTCH_RADIUS_MAX_MM, lo_open=True)
    tip_width_mm: number(0.3, 20.0)
    tip_height_mm: number(0.3, 5.0)
    arm_height_mm: number(0.0, 5.0, lo_open=True)
    inside_corner_radius_mm: number(0.0, 1.0, lo_open=True)
    web_tolerance_mm: number(*WEB_TOLERANCE_RANGE_MM) = None  # or [tolerances] web_thickness_mm
    #: how the row sheets are cut (:data:`tactcad.vocabulary.process.CUT_PROCESSES`); wire-edm
    #: when left out. Its slot, inside radius, thinnest web and tolerance shape the rows.
    process: choice(CUT_PROCESSES, "the processes that cut a part from sheet") = None


class CombTables(Section):
    """A ``monolithic-comb`` design file: ``[comb]`` in place of ``[clamp]``."""

    design: DesignSection
    material: MaterialSection
    sheet: SheetSection
    array: ArraySection
    element: CombElementSection
    arms: ArmsSection
    comb: CombSection
    edm: EdmSection
    strength: StrengthSection = None
    requirements: RequirementsSection = None
    readout: ReadoutSection = None
    tolerances: TolerancesSection = None
    bom: BomSection = None
    files: FilesSection = None
    assumptions: dict[str, Any] = {}


#: A comb's design file: :class:`CombTables` and the table of each part in use
#: (the grasper's jaw and shaft, the tissue slab; each optional).
CombFile = create_model("CombFile", __base__=CombTables, __doc__=CombTables.__doc__,
                        **in_use_tables())


# ---------------------------------------------------------------------------
# Derivations: small pure functions from the validated file
# ---------------------------------------------------------------------------
def element_count(d: CombTables) -> int:
    return d.array.rows * d.array.columns


def webs(d: CombTables) -> list[float]:
    """Each element's web (mm): ``[comb] web_thicknesses_mm``, else the shared one."""
    given = d.comb.web_thicknesses_mm
    return list(given) if given is not None else [d.element.web_thickness_mm] * element_count(d)


@dataclass(frozen=True)
class RowRules:
    """What the rows' cut process makes on the comb's sheet (mm): its narrowest slot and
    smallest inside radius (the shapes the comb's layout keeps to) and all its limits."""

    limits: ProcessLimits

    @property
    def min_slot_width_mm(self) -> float:
        return self.limits.min_slot_mm.value_mm

    @property
    def min_inside_radius_mm(self) -> float:
        return self.limits.min_inside_radius_mm.value_mm


def row_process(d: CombTables) -> str:
    """The rows' cut process (``[element] process``, else wire EDM)."""
    return d.element.process or DEFAULT_CUT_PROCESS


def row_rules(d: CombTables) -> RowRules:
    """:class:`RowRules` of the rows' process on the comb's sheet and material (for wire
    EDM: the design's ``[edm]`` wire and spark gap)."""
    material = " ".join(str(v or "") for v in (d.material.grade, d.material.name))
    return _row_rules(row_process(d), d.sheet.thickness_mm, edm_rules(d), material)


@functools.lru_cache(maxsize=64)
def _row_rules(process: str, sheet_mm: float, wire: EdmRules, material: str) -> RowRules:
    # one validation asks a dozen times for the same rules: worked out once per inputs
    return RowRules(CUT_PROCESSES[process].limits(sheet_mm, wire, material))


def stop_gaps(d: CombTables) -> list[float]:
    """Each element's stop travel at its arm's free end (mm): ``[comb]
    stop_gaps_mm``, else the process's minimum slot."""
    given = d.comb.stop_gaps_mm
    slot = row_rules(d).min_slot_width_mm
    return list(given) if given is not None else [slot] * element_count(d)


def cut_gap(gap_mm: float, min_slot_mm: float) -> tuple[float, str]:
    """(the gap the process cuts, the stop's kind): a gap at least the minimum
    slot is cut as it is (``cut``); a narrower one is cut at the slot and set
    to its width with a shim at assembly (``set``)."""
    return (gap_mm, "cut") if gap_mm >= min_slot_mm else (min_slot_mm, "set")


def element_length(d: CombTables, arm_mm: float) -> float:
    """An element's length along the row (mm): post + notch radius + arm + half the tip."""
    e = d.element
    return d.comb.post_length_mm + e.notch_radius_mm + arm_mm + e.tip_width_mm / 2


def screw(d: CombTables):
    return MINIATURE_SCREWS[d.comb.screw_size]


def dowel_diameter(d: CombTables) -> float:
    return float(d.comb.dowel_diameter_mm)


def spine_height(d: CombTables) -> Derived:
    """The spine's height (mm): the screw's head and nut lie on the sheets'
    outer faces and must stay below the arms (a head over a flexing arm would
    clamp it), with the fastener gap above and below; the holes keep a ligament."""
    s = screw(d)
    widest = max(s.head_diameter_mm, s.nut_across_corners_mm)
    height = max(widest + 2 * MIN_FASTENER_GAP_MM, s.clearance_hole_mm + 2 * MIN_LIGAMENT_MM,
                 dowel_diameter(d) + 2 * MIN_LIGAMENT_MM)
    return Derived("spine_height", height, "mm",
                   f"{s.size} head ({fmt(s.head_diameter_mm)} mm) and nut "
                   f"({fmt(s.nut_across_corners_mm)} mm across corners) below the arms with a "
                   f"{fmt(MIN_FASTENER_GAP_MM)} mm gap each side")


def row_length(d: CombTables) -> Derived:
    return Derived("row_length", d.array.columns * d.array.pitch_mm, "mm",
                   "columns x pitch: every element's cell with the slot after it")


def fastener_positions(d: CombTables) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(screw x, dowel x) along the row (mm): a dowel pin near each end, its
    hole a ligament from the end; the screws at the quarter points between."""
    length = row_length(d).value
    edge = dowel_diameter(d) / 2 + MIN_LIGAMENT_MM
    return (length / 4, 3 * length / 4), (edge, length - edge)


def arm_underside(d: CombTables) -> float:
    """y of every arm's underside (mm): the spine plus the widest cut stop gap,
    so the tips' contact faces lie in one plane."""
    slot = row_rules(d).min_slot_width_mm
    return spine_height(d).value + max(cut_gap(g, slot)[0] for g in stop_gaps(d))


def comb_element(d: CombTables, arm_mm: float, web_mm: float,
                 shared: dict[str, Any] | None = None) -> ElementGeometry:
    """An element's profile in its own frame (the sheet frame at its offset).

    Every element of the comb is as long as the longest (:func:`element_length` of the
    longest arm): a shorter arm's post grows by the difference, so every tip lies at one
    place in its cell and a column's tips sit side by side across the rows (one radius
    from a jaw's pivot, whatever their arms).

    Args:
        d: the comb's tables. arm_mm, web_mm: the element's arm and web (mm).
        shared: :func:`shared_element_sizes` of ``d`` where already worked out.

    Returns:
        The element's geometry (mm).
    """
    return ElementGeometry(arm_length_mm=arm_mm, web_thickness_mm=web_mm,
                           **(shared if shared is not None else shared_element_sizes(d)))


def shared_element_sizes(d: CombTables) -> dict[str, Any]:
    """Every :class:`ElementGeometry` field but the arm and the web, which every element of
    the comb shares (mm; its process): worked out once for a sheet's elements.

    Args:
        d: the comb's tables.

    Returns:
        Field name -> value.
    """
    e = d.element
    return dict(
        notch_radius_mm=e.notch_radius_mm, tip_width_mm=e.tip_width_mm,
        tip_height_mm=e.tip_height_mm, arm_height_mm=e.arm_height_mm,
        base_height_mm=arm_underside(d) + e.arm_height_mm,
        overall_length_mm=element_length(d, max(d.arms.lengths_mm)),
        inside_corner_radius_mm=e.inside_corner_radius_mm, sheet_thickness_mm=d.sheet.thickness_mm,
        web_tolerance_mm=tolerances_of(d.model_dump(exclude_none=True)).web_thickness_mm,
        bolt_holes=(), start_hole_diameter_mm=d.edm.start_hole_diameter_mm,
        process=row_process(d))


def fastener_holes(d: CombTables) -> tuple[Hole, ...]:
    """The screw (ISO 273 medium clearance) and dowel (reamed) holes of a sheet and the spacer."""
    screws, dowels = fastener_positions(d)
    y = spine_height(d).value / 2
    return (tuple(Hole(x, y, screw(d).clearance_hole_mm) for x in screws)
            + tuple(Hole(x, y, dowel_diameter(d)) for x in dowels))


def comb_sheets(d: CombTables) -> tuple[CombSheet, ...]:
    cols, pitch = d.array.columns, d.array.pitch_mm
    slot = row_rules(d).min_slot_width_mm
    y_arm = arm_underside(d)
    arms, web, gaps = d.arms.lengths_mm, webs(d), stop_gaps(d)
    shared = shared_element_sizes(d)  # the same for every element: worked out once
    out = []
    for row in range(d.array.rows):
        numbers = range(row * cols, row * cols + cols)
        out.append(CombSheet(
            row=row, elements=tuple(comb_element(d, arms[i], web[i], shared) for i in numbers),
            offsets_mm=tuple(c * pitch for c in range(cols)),
            ledges_mm=tuple(y_arm - cut_gap(gaps[i], slot)[0] for i in numbers),
            length_mm=row_length(d).value, spine_height_mm=spine_height(d).value,
            thickness_mm=d.sheet.thickness_mm, holes=fastener_holes(d),
            start_hole_diameter_mm=d.edm.start_hole_diameter_mm,
            stop_gaps_mm=tuple(gaps[i] for i in numbers)))
    return tuple(out)


def grip(d: CombTables) -> float:
    """The screws' grip (mm): both sheets and the spacer."""
    return d.array.rows * d.sheet.thickness_mm + d.comb.spacer_thickness_mm


def screw_length(d: CombTables) -> tuple[float | None, Derived]:
    s = screw(d)
    needed = grip(d) + s.nut_height_mm + 2 * s.thread_pitch_mm
    length = shortest_stock_length(s, needed)
    return length, Derived("screw_length", length or needed, "mm",
                           f"shortest stock {s.size} length >= grip {fmt(grip(d))} + nut "
                           f"{fmt(s.nut_height_mm)} + 2 thread pitches")


def dowel_length(d: CombTables) -> tuple[float | None, Derived]:
    length = shortest_dowel_length(dowel_diameter(d), grip(d))
    return length, Derived("dowel_length", length or grip(d), "mm",
                           f"shortest ISO 8734 stock length >= grip {fmt(grip(d))}, "
                           "the pin's ends flush or proud")


def across_extent(d: CombTables) -> tuple[float, float]:
    """(lowest, highest) x across the rows of the comb's parts (mm, from the stack's
    middle): the screw from its head on row 1's outer face to its end (or the grip), and
    the dowel pins, centred on the stack, where a stock pin is longer than that."""
    s = screw(d)
    length = screw_length(d)[0] or screw_length(d)[1].value
    outer = grip(d) / 2  # each row's outer face
    half_pin = (dowel_length(d)[0] or grip(d)) / 2
    return (min(-outer - s.head_height_mm, -half_pin), max(-outer + max(length, grip(d)), half_pin))


def envelope(d: CombTables) -> tuple[float, float, float]:
    """(across the rows: the screw's head to its end, or a longer dowel pin's ends; along
    the row; height to the contact faces), mm."""
    lo, hi = across_extent(d)
    height = arm_underside(d) + d.element.arm_height_mm + d.element.tip_height_mm
    return (hi - lo, row_length(d).value, height)


def spacer_process(d: CombTables) -> Derived:
    """The spacer's cut process (``[comb] spacer_process``), else the first registered
    process whose sheet range holds its thickness (value: the process's name)."""
    t = d.comb.spacer_thickness_mm
    if d.comb.spacer_process is not None:
        return Derived("spacer_process", d.comb.spacer_process, "", "stated")
    name = first_process_holding(t)
    return Derived("spacer_process", name, "",
                   f"the first process whose sheet range holds the {fmt(t)} mm spacer")


def _check_spacer_process(d: CombTables, p: Problems) -> None:
    """The spacer's thickness lies in its process's sheet range."""
    name = spacer_process(d).value
    lo, hi = CUT_PROCESSES[name].sheet_range_mm
    t = d.comb.spacer_thickness_mm
    if not CUT_PROCESSES[name].holds_sheet(t):
        field = "comb.spacer_process" if d.comb.spacer_process else "comb.spacer_thickness_mm"
        p.add(field, d.comb.spacer_process or t,
              f"a process whose sheet range holds the {fmt(t)} mm spacer ({name}: {lo:g} ... "
              f"{hi:g} mm)", CUT_PROCESSES[name].sheet_source)


def comb_geometry(d: CombTables, sheets: tuple[CombSheet, ...] | None = None) -> CombGeometry:
    """The comb's geometry (mm); ``sheets``: :func:`comb_sheets` of ``d`` where already
    worked out."""
    screws, dowels = fastener_positions(d)
    return CombGeometry(
        sheets=comb_sheets(d) if sheets is None else sheets, spacer_thickness_mm=d.comb.spacer_thickness_mm, screw=screw(d),
        screw_length_mm=screw_length(d)[1].value, dowel_diameter_mm=dowel_diameter(d),
        dowel_length_mm=dowel_length(d)[1].value, screw_x_mm=screws, dowel_x_mm=dowels,
        fastener_y_mm=spine_height(d).value / 2, envelope_mm=envelope(d),
        envelope_from_x_mm=across_extent(d)[0],
        spacer_process=spacer_process(d).value)


def element_slots(d: CombTables, sheets: tuple[CombSheet, ...]) -> tuple[ElementSlot, ...]:
    """Each row's sheet turned a quarter about y so its row runs along the
    array's +z: row 1's sheet on the -x side of the spacer, row 2's on the +x
    side; element c of both rows at the same z (the same radius from a jaw's pivot)."""
    t, s = d.sheet.thickness_mm, d.comb.spacer_thickness_mm
    dx = (-s / 2, s / 2 + t)
    out = []
    for sheet in sheets:
        for c, (g, x0) in enumerate(zip(sheet.elements, sheet.offsets_mm)):
            out.append(ElementSlot(sheet.row * d.array.columns + c + 1, sheet.row, c, g,
                                   Placement(dx[sheet.row], 0.0, x0, quarter_turn=True)))
    return tuple(out)


def hard_stops(d: CombTables, sheets: tuple[CombSheet, ...]) -> tuple[HardStop, ...]:
    slot = row_rules(d).min_slot_width_mm
    out, gaps = [], stop_gaps(d)
    for sheet in sheets:
        for c, g in enumerate(sheet.elements):
            number = sheet.row * d.array.columns + c + 1
            gap = gaps[number - 1]
            cut, kind = cut_gap(gap, slot)
            out.append(HardStop(number, gap, g.arm_length_mm + g.tip_width_mm / 2, kind, cut))
    return tuple(out)


def derived_values(d: CombTables) -> tuple[Derived, ...]:
    slot = row_rules(d).min_slot_width_mm
    longest = max(element_length(d, a) for a in d.arms.lengths_mm)
    return (
        row_length(d), spine_height(d),
        Derived("arm_underside_y", arm_underside(d), "mm",
                "spine + the widest cut stop gap: every contact face in one plane"),
        Derived("min_slot", slot, "mm", f"{row_process(d)}'s narrowest slot on the "
                f"{fmt(d.sheet.thickness_mm)} mm sheet ({row_rules(d).limits.min_slot_mm.rule})"),
        Derived("slot_after_longest_element", d.array.pitch_mm - longest, "mm",
                f"pitch - the longest element ({fmt(longest)} mm: post + notch radius + arm + "
                "half the tip)"),
        Derived("fastener_y", spine_height(d).value / 2, "mm", "screws and dowels mid-spine"),
        Derived("dowel_x", fastener_positions(d)[1][0], "mm",
                f"a dowel near each end: its radius + a {fmt(MIN_LIGAMENT_MM)} mm ligament from the end"),
        Derived("screw_x", fastener_positions(d)[0][0], "mm", "screws at the row's quarter points"),
        screw_length(d)[1], dowel_length(d)[1],
        Derived("envelope_across_rows", envelope(d)[0], "mm",
                "screw head + screw length (the rows, spacer, nut and thread end between)"),
    )


# ---------------------------------------------------------------------------
# Cross-field rules (every one reported)
# ---------------------------------------------------------------------------
def _check_element(d: CombTables, p: Problems) -> None:
    e, rules = d.element, row_rules(d)
    r_min, cut = rules.min_inside_radius_mm, row_process(d)
    p.within("element.notch_radius_mm", e.notch_radius_mm,
             max(max(webs(d)), r_min, rules.min_slot_width_mm / 2), NOTCH_RADIUS_MAX_MM,
             why=f"R >= every web (t/R <= 1) and the notch (2 R wide) >= {cut}'s narrowest slot")
    over = max(webs(d)) + e.notch_radius_mm
    p.within("element.arm_height_mm", e.arm_height_mm, over + r_min,
             why=f"the arm must reach below web + notch radius = {fmt(over)} mm by {cut}'s "
                 f"smallest inside radius {fmt(r_min)} mm")
    p.within("element.inside_corner_radius_mm", e.inside_corner_radius_mm, r_min,
             why=f"{cut}'s smallest inside radius ({rules.limits.min_inside_radius_mm.rule})")
    p.within("element.tip_height_mm", e.tip_height_mm, e.inside_corner_radius_mm + MIN_TIP_WALL_MM,
             why=f"the tip-root fillet must end on the tip's side, {fmt(MIN_TIP_WALL_MM)} mm "
                 "below the contact face")


def _check_one_web_source(d: CombTables, p: Problems) -> bool:
    """The webs come from one place: ``[comb] web_thicknesses_mm`` (each element's) or
    ``[element] web_thickness_mm`` (every element's); False when neither or both."""
    shared, each = d.element.web_thickness_mm, d.comb.web_thicknesses_mm
    if shared is None and each is None:
        p.add("comb.web_thicknesses_mm", None, "each element's web (mm), a list of rows x "
              "columns values; or element.web_thickness_mm, one web for every element")
        return False
    if shared is not None and each is not None:
        p.add("element.web_thickness_mm", shared, "left out where comb.web_thicknesses_mm "
              "gives each element's web", "nothing would read it: change "
              "comb.web_thicknesses_mm, or leave that out to give every element this web")
        return False
    return True


def _check_lists(d: CombTables, p: Problems) -> bool:
    """Every per-element list has rows x columns entries; False when one has not."""
    n, ok = element_count(d), True
    for field, value in (("arms.lengths_mm", d.arms.lengths_mm),
                         ("comb.stop_gaps_mm", d.comb.stop_gaps_mm),
                         ("comb.web_thicknesses_mm", d.comb.web_thicknesses_mm)):
        if value is not None and len(value) != n:
            p.add(field, list(value), f"a list of {n} values (rows x columns)")
            ok = False
    return ok


def _check_arms(d: CombTables, p: Problems) -> None:
    e, arms = d.element, d.arms.lengths_mm
    slot = row_rules(d).min_slot_width_mm
    tip_root = e.tip_width_mm / 2 + e.inside_corner_radius_mm + e.notch_radius_mm + 0.5
    seen: dict[float, float] = {}
    for i, (a, web) in enumerate(zip(arms, webs(d)), start=1):
        # the slot after the tip: the process's narrowest, and room for the fillet at the next post
        gap = max(slot, e.inside_corner_radius_mm)
        room = d.array.pitch_mm - gap - (element_length(d, a) - a)
        if a < tip_root - 1e-9:
            p.add(f"arms.lengths_mm[{i}]", a, f">= {fmt(tip_root)} mm",
                  "the tip root fillet must clear the notch by 0.5 mm")
        elif a > room + 1e-9:
            p.add(f"arms.lengths_mm[{i}]", a,
                  f"<= {fmt(room)} mm, or array.pitch_mm >= {fmt(element_length(d, a) + gap)} mm",
                  f"the element (post + notch radius + arm + half the tip) and a {fmt(gap)} mm "
                  f"slot after it (the process's narrowest slot, the fillet at the next post) must fit the "
                  f"pitch {fmt(d.array.pitch_mm)} mm")
        for other, other_web in seen.items():
            if abs(a - other) < MIN_ARM_STEP_MM and web != other_web:
                p.add(f"comb.web_thicknesses_mm[{i}]", web, f"{fmt(other_web)} mm (the web of "
                      f"the other {fmt(other)} mm arm)", "one arm length is one element part")
        seen.setdefault(a, web)


def _check_comb(d: CombTables, p: Problems) -> None:
    c = d.comb
    p.within("comb.spacer_thickness_mm", c.spacer_thickness_mm, MIN_SPACER_MM,
             why=f"the two rows' arms flex on either side of it: a {fmt(MIN_SPACER_MM)} mm "
                 "plate at the least")
    p.within("comb.post_length_mm", c.post_length_mm, row_rules(d).min_inside_radius_mm * 2,
             why="the post must hold the notch's back wall and the tip's neighbour's slot")
    if c.stop_gaps_mm is not None:
        for i, g in enumerate(c.stop_gaps_mm, start=1):
            p.within(f"comb.stop_gaps_mm[{i}]", g, MIN_SET_GAP_MM,
                     why=f"a gap narrower than the process's slot is set with a shim; the thinnest "
                         f"is {fmt(MIN_SET_GAP_MM)} mm")
    length = row_length(d).value
    screws, dowels = fastener_positions(d)
    s = screw(d)
    reach = max(s.head_diameter_mm, s.nut_across_corners_mm) / 2 + dowel_diameter(d) / 2
    if screws[0] - dowels[0] < reach + MIN_FASTENER_GAP_MM - 1e-9:
        p.add("array.pitch_mm", d.array.pitch_mm,
              f">= {fmt(4 * (dowels[0] + reach + MIN_FASTENER_GAP_MM) / d.array.columns)} mm, or "
              "more columns, or a smaller screw",
              f"the row ({fmt(length)} mm) is too short for the dowels and {s.size} screws "
              f"{fmt(MIN_FASTENER_GAP_MM)} mm apart")
    if screw_length(d)[0] is None:
        p.add("comb.screw_size", c.screw_size, "a longer screw's size",
              f"the grip needs {fmt(screw_length(d)[1].value)} mm; longest stock "
              f"{fmt(max(s.catalogue_lengths_mm))} mm")
    if dowel_length(d)[0] is None:
        p.add("comb.dowel_diameter_mm", c.dowel_diameter_mm, "a dowel with longer stock",
              f"the grip is {fmt(grip(d))} mm; longest stock "
              f"{fmt(max(DOWEL_PINS[dowel_diameter(d)]))} mm")


def _check_footprint(d: CombTables, p: Problems) -> None:
    """A stated footprint [X, Y(, Z)] holds the comb's envelope (across the
    rows, along the row, height)."""
    stated = stated_footprint(d.model_dump(exclude_none=True))
    if stated is None:
        return
    env = envelope(d)
    for axis, (have, room) in enumerate(zip(env, stated)):
        if have > room + 1e-9:
            p.add(f"requirements.footprint_mm[{axis + 1}]", room, f">= {fmt(have)} mm",
                  f"the comb's envelope is {' x '.join(fmt(v) for v in env)} mm")


def _check_arm_domain(d: CombTables, p: Problems) -> None:
    for i, a in enumerate(d.arms.lengths_mm, start=1):
        p.within(f"arms.lengths_mm[{i}]", a, *ARM_RANGE_MM, why=FITTED_DOMAIN)


def _check_row_process(d: CombTables, p: Problems) -> None:
    """The rows' process cuts the comb's sheet (its flexure range), leaves each web no
    thinner than it can and cuts the fastener holes no smaller (the ``process`` check's
    figures, refused when the file is read)."""
    check_sheet_process(d, p)
    limits = row_rules(d).limits
    web, hole = limits.min_web_mm, limits.min_hole_mm
    where = f"{limits.process} on a {fmt(d.sheet.thickness_mm)} mm sheet"
    field = "comb.web_thicknesses_mm" if d.comb.web_thicknesses_mm else "element.web_thickness_mm"
    thinnest = min(webs(d))
    if thinnest < web.value_mm - 1e-9:
        p.add(field, thinnest, f">= {fmt(web.value_mm)} mm: the thinnest web {where} leaves "
              f"({web.rule}), or a thinner sheet or another element.process", web.source)
    smallest = min(screw(d).clearance_hole_mm, dowel_diameter(d))
    if smallest < hole.value_mm - 1e-9:
        p.add("comb.dowel_diameter_mm" if dowel_diameter(d) <= screw(d).clearance_hole_mm
              else "comb.screw_size", smallest,
              f"a hole >= {fmt(hole.value_mm)} mm: the smallest {where} cuts ({hole.rule})",
              hole.source)


COMB_RULES = (_check_element, _check_arms, _check_comb, _check_arm_domain, check_requirements,
              check_readout, check_tolerances, check_web_tolerance_held, check_in_use,
              _check_spacer_process, _check_row_process)


# ---------------------------------------------------------------------------
# The construction's entry points (tactcad.design.construction_registry)
# ---------------------------------------------------------------------------
def validate_tables(data: Mapping[str, Any], file: str = "") -> tuple[CombTables | None, Problems]:
    """The comb's model of the design file and every refusal: types and
    ranges, then the cross-field rules, then the envelope against a stated
    footprint.

    Args:
        data: the design file's tables.
        file: the file's name for the messages.

    Returns:
        (the model or None, the refusals).
    """
    p = Problems(file)
    data = with_grade_defaults(data)
    model = validate(CombFile, data, p)
    with_counts(p, data)  # a per-element list refused: how many values it takes
    read_assumptions(data, CombFile, p, "comb.post_length_mm")
    grade_error = _grade_error(data)
    refuse_grade(p, grade_error)  # the grade, not the E and nu it would have supplied
    if model is None:
        return None, p
    try:
        material_fields(data["material"])
        strength_settings(data.get("strength"))
    except DesignError as exc:
        if grade_error is None:
            p.extend([exc])
    check_references(model, p)
    if not (_check_one_web_source(model, p) and _check_lists(model, p)):
        return model, p
    for rule in COMB_RULES:
        rule(model, p)
    if not p:
        _check_footprint(model, p)
    return model, p


def derive_plan(d: CombTables, data: Mapping[str, Any], source: str) -> Plan:
    """The comb's plan of a design that passed :func:`validate_tables`."""
    p = Problems()
    from_grade = grade_filled(data)
    data = with_grade_defaults(data)
    sheets = comb_sheets(d)
    refs, why = unit_references(d)
    return Plan(
        name=d.design.name, description=d.design.description, source=source,
        design_hash=design_hash(shaping_tables(data)),
        material=Material(d.material.name, d.material.youngs_modulus_MPa, d.material.poisson_ratio,
                          **material_fields(data["material"])),
        strength=strength_settings(data.get("strength")),
        sheet_thickness_mm=d.sheet.thickness_mm, rows=d.array.rows, columns=d.array.columns,
        pitch_mm=d.array.pitch_mm, slots=element_slots(d, sheets), edm=edm_rules(d),
        derived=derived_values(d), references=refs, references_reason=why, pairing=pairing_of(d),
        assumptions=read_assumptions(data, CombFile, p, "comb.post_length_mm"),
        construction="monolithic-comb", comb=comb_geometry(d, sheets), hard_stops=hard_stops(d, sheets),
        raw=copy_tables(dict(data)), from_grade=from_grade)


def sheet_placement(plan: Plan, row: int) -> Placement:
    """Row ``row``'s sheet in the array frame: turned a quarter about y as its
    elements are (:func:`element_slots`), its first element at z = 0."""
    first = next(s for s in plan.slots if s.row == row and s.column == 0)
    return Placement(first.placement.dx_mm, first.placement.dy_mm, first.placement.dz_mm,
                     quarter_turn=True)


def placed_parts(plan: Plan) -> list[tuple[str, str, Placement]]:
    """The comb's placed parts but the gauges (the construction registry's
    ``placed_parts``), array frame, mm: one sheet per row, the spacer between them, a dowel
    pin through each dowel hole (centred on the stack), a screw from row 1's outer face
    through each screw hole and its nut on row 2's, a shim on the ledge under each tip whose
    gap is cut wider than its stop gap."""
    from tactcad.partlib.array.comb_hardware import (SPACER_PART, DowelPin, dowel_name,
                                                     shim_name, stop_shims)
    from tactcad.partlib.array.fasteners import bolt_name, nut_name

    c, t = plan.comb, plan.sheet_thickness_mm
    outer = c.spacer_thickness_mm / 2 + t  # each row's outer face, off the stack's middle
    y = c.fastener_y_mm
    out = [(sheet.part_name, sheet.part_name, sheet_placement(plan, sheet.row))
           for sheet in c.sheets]
    # the spacer as a sheet: its thickness along -x from +s/2
    out.append((SPACER_PART, SPACER_PART,
                Placement(c.spacer_thickness_mm / 2, 0.0, 0.0, quarter_turn=True)))
    pin = DowelPin(c.dowel_diameter_mm, c.dowel_length_mm)
    # turned and quarter-turned: a part's +z runs along the array's +x (row 1 to row 2)
    out += [(f"dowel_{k}", dowel_name(pin), Placement(-pin.length_mm / 2, y, z, True, True))
            for k, z in enumerate(c.dowel_x_mm, start=1)]
    out += [(f"screw_{k}", bolt_name(c.screw, c.screw_length_mm),
             Placement(-outer, y, z, True, True)) for k, z in enumerate(c.screw_x_mm, start=1)]
    out += [(f"nut_{k}", nut_name(c.screw), Placement(outer, y, z, True, True))
            for k, z in enumerate(c.screw_x_mm, start=1)]
    for row, column, shim, (x, y_ledge) in stop_shims(c):
        sheet = sheet_placement(plan, row)  # the shim in its sheet's frame, turned with it
        out.append((shim_placed_name(plan, row, column), shim_name(shim),
                    Placement(sheet.dx_mm, sheet.dy_mm + y_ledge, sheet.dz_mm + x,
                              quarter_turn=True)))
    return out


def shim_placed_name(plan: Plan, row: int, column: int) -> str:
    """The placed name of the shim under element (row, column): ``shim_<element number>``."""
    return f"shim_{row * plan.columns + column + 1}"


def element_holder(plan: Plan, slot: ElementSlot) -> str:
    """An element is cut in its row's sheet."""
    return plan.comb.sheets[slot.row].part_name


def touching(plan: Plan) -> set[frozenset[str]]:
    """The comb's face contacts: the spacer on both rows, each dowel in its reamed holes
    (rows and spacer), each screw's head on row 1 and its nut on row 2, screw and nut on
    the thread, each stop shim on its row's ledge."""
    from tactcad.partlib.array.comb_hardware import SPACER_PART

    rows = [sheet.part_name for sheet in plan.comb.sheets]
    pairs = {frozenset({SPACER_PART, r}) for r in rows}
    for k in range(1, len(plan.comb.dowel_x_mm) + 1):
        pairs |= {frozenset({f"dowel_{k}", r}) for r in (*rows, SPACER_PART)}
    for k in range(1, len(plan.comb.screw_x_mm) + 1):
        pairs |= {frozenset({f"screw_{k}", rows[0]}), frozenset({f"nut_{k}", rows[-1]}),
                  frozenset({f"screw_{k}", f"nut_{k}"})}
    from tactcad.partlib.array.comb_hardware import stop_shims

    pairs |= {frozenset({shim_placed_name(plan, row, column), rows[row]})
              for row, column, _, _ in stop_shims(plan.comb)}
    return pairs


def mount_frames(plan: Plan) -> dict:
    """The comb's frames for a host (array frame, mm): ``jaw_seat``, the centre of its
    envelope (:attr:`CombGeometry.envelope_centre_mm`) on the tip plane, normal up (+y),
    x across the rows; a grasper's jaw takes it. No mount for the test rigs' bracket yet."""
    from tactcad.geometry.frames import Frame

    x, z = plan.comb.envelope_centre_mm
    return {"jaw_seat": Frame((x, plan.comb.envelope_mm[2], z), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))}
