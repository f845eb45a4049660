"""The monolithic comb's sheet (a made part, one per row): one row's elements
cut from one thin sheet, each element's flexure profile standing on a common
spine, with a stop ledge under every arm and the screw and dowel holes in the
spine.

Here under the key ``comb_sheet``: the design file's ``[comb]`` table, the
sheet's dimensions (:class:`CombSheet`, :class:`CombGeometry`), its exact
outline (:func:`comb_profile`), spec, builder and shop drawing's notes. The
comb's derivation (pitch, spine, fasteners, stops) is
:mod:`tactcad.design.comb_plan` (above this layer); this module reads the
result from the plan.

Sheet frame: x along the row (0 = the first post's back face), y up (0 = the
spine's underside, the tips' contact faces on top), z through the sheet (0 ...
sheet thickness). Each element's own frame is the sheet frame shifted by its
offset along x, so its :class:`~tactcad.partlib.array.element.ElementGeometry`
is the element's profile the mechanics read. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Profile, comb_sheet_profile
from tactcad.kernel.shapes import extrude_profile
from tactcad.partlib.array.element import WEB_RANGE_MM, FITTED_DOMAIN, ElementGeometry
from tactcad.partlib.array.prism import Hole, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, DrawingRecord, PartData
from tactcad.vocabulary.process import CUT_PROCESSES, DEFAULT_CUT_PROCESS, cut_process
from tactcad.vocabulary.schema import Section, choice, listing, number
from tactcad.vocabulary.standards import DOWEL_PINS, MINIATURE_SCREWS, BoltSpec

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

COLOR: RGB = (0.72, 0.70, 0.66)  # titanium grey


def sheet_shade(row: int) -> RGB:
    """Row ``row``'s sheet colour: the titanium grey, each next row 0.1 darker,
    so the facing rows tell apart in STEP, GLB and FreeCAD (a scene refuses
    two parts of one colour)."""
    return tuple(round(max(c - 0.1 * row, 0.0), 4) for c in COLOR)  # type: ignore[return-value]
#: Most elements one comb carries (two rows of twelve, as the stacked array).
MAX_COMB_ELEMENTS = 24
#: Widest stop gap a comb's tables take (mm; the range of ``comb.stop_gaps_mm``).
MAX_STOP_GAP_MM = 1.0


class CombSection(Section):
    """``[comb]`` of a ``monolithic-comb`` design (mm): the posts, the spacer
    between the rows, the screws and dowel pins, each element's stop gap and
    web."""

    post_length_mm: number(0.3, 5.0, why="each element's clamped post along the row")
    spacer_thickness_mm: number(0.1, 2.0, why="the plate between the two rows' sheets; "
                                               "the two rows' arms flex on either side of it")
    screw_size: choice(MINIATURE_SCREWS, "socket head cap screws (DIN 912 M1.2, ISO 4762 M1.6)")
    dowel_diameter_mm: choice(tuple(f"{d:g}" for d in DOWEL_PINS),
                              "ISO 8734 dowel pin diameters (mm), as text")
    #: each element's stop travel at its arm's free end (element order); left
    #: out: the process's minimum slot for every element
    stop_gaps_mm: listing(number(0.0, MAX_STOP_GAP_MM, lo_open=True), 2, MAX_COMB_ELEMENTS,
                          f"one gap per element, each > 0 ... {MAX_STOP_GAP_MM:g} mm, rows x "
                          "columns") = None
    #: each element's web (element order); left out: ``element.web_thickness_mm``
    web_thicknesses_mm: listing(number(*WEB_RANGE_MM, why=FITTED_DOMAIN), 2, MAX_COMB_ELEMENTS,
                                f"one web per element, each {WEB_RANGE_MM[0]:g} ... "
                                f"{WEB_RANGE_MM[1]:g} mm, rows x columns") = None
    #: how the spacer is cut (:data:`tactcad.vocabulary.process.CUT_PROCESSES`); left out:
    #: the first process whose sheet range holds the spacer's thickness (wire EDM from
    #: 0.5 mm, laser cutting below)
    spacer_process: choice(CUT_PROCESSES, "the processes that cut a part from sheet") = None


@dataclass(frozen=True)
class CombSheet:
    """One row's comb sheet (sheet frame, mm).

    Attributes:
        row: the row (0-based).
        elements: each element's profile in its own frame (offset along x).
        offsets_mm: x of each element's frame origin in the sheet frame.
        ledges_mm: y of the stop ledge under each element's arm (the spine's
            top there): the arm's underside less the element's cut gap.
        length_mm: the row's length along x.
        spine_height_mm: the spine's height (the fasteners' band).
        thickness_mm: the sheet's thickness.
        holes: the screw and dowel holes in the spine.
        start_hole_diameter_mm: the wire's start holes in the holes.
        stop_gaps_mm: each element's stop gap as designed (a gap narrower than the cut
            one is set with a shim on the ledge: :attr:`shims_mm`).
    """

    row: int
    elements: tuple[ElementGeometry, ...]
    offsets_mm: tuple[float, ...]
    ledges_mm: tuple[float, ...]
    length_mm: float
    spine_height_mm: float
    thickness_mm: float
    holes: tuple[Hole, ...]
    start_hole_diameter_mm: float
    stop_gaps_mm: tuple[float, ...] = ()

    @property
    def cut_gaps_mm(self) -> tuple[float, ...]:
        """Each element's gap as the wire cuts it (mm): arm underside to its ledge."""
        return tuple(e.arm_underside_y_mm - ledge for e, ledge in zip(self.elements, self.ledges_mm))

    @property
    def shims_mm(self) -> tuple[float, ...]:
        """The shim bonded on each element's ledge under its tip (mm; 0: the gap is cut as
        designed): the cut gap less the stop gap."""
        gaps = self.stop_gaps_mm or self.cut_gaps_mm
        return tuple(round(max(cut - gap, 0.0), 6) for cut, gap in zip(self.cut_gaps_mm, gaps))

    @property
    def part_name(self) -> str:
        """``comb_row1``, ``comb_row2``: one part per row (their arms differ)."""
        return f"comb_row{self.row + 1}"


@dataclass(frozen=True)
class CombGeometry:
    """The comb: its row sheets, the spacer between them and the fasteners (mm).

    Attributes:
        sheets: the rows' sheets.
        spacer_thickness_mm: the plate between the rows (its outline is the spine's).
        screw: the screws through sheets and spacer (head on row 1, nut on row 2).
        screw_length_mm: their ISO stock length.
        dowel_diameter_mm, dowel_length_mm: the ISO 8734 dowel pins that locate the rows.
        screw_x_mm, dowel_x_mm: the fasteners' positions along the row.
        fastener_y_mm: their height (mid-spine).
        envelope_mm: (across the rows with head and screw end, along the row,
            height to the contact faces).
        spacer_process: the cut process of the spacer (its name).
        envelope_from_x_mm: where the envelope starts across the rows (mm, array frame):
            the screw's head, or a dowel pin's end where a stock pin reaches further.
    """

    sheets: tuple[CombSheet, ...]
    spacer_thickness_mm: float
    screw: BoltSpec
    screw_length_mm: float
    dowel_diameter_mm: float
    dowel_length_mm: float
    screw_x_mm: tuple[float, ...]
    dowel_x_mm: tuple[float, ...]
    fastener_y_mm: float
    envelope_mm: tuple[float, float, float]
    spacer_process: str = DEFAULT_CUT_PROCESS
    #: the envelope's lowest x across the rows (mm; None: the screw's head)
    envelope_from_x_mm: float | None = None

    @property
    def envelope_centre_mm(self) -> tuple[float, float]:
        """(x across the rows, z along the row) of the envelope's centre in the array frame
        (mm): it reaches from the screw's head on row 1's outer face across to the screw's
        end, and over the row's length from z = 0."""
        across, along, _ = self.envelope_mm
        if self.envelope_from_x_mm is not None:
            return self.envelope_from_x_mm + across / 2, along / 2
        head = -(self.spacer_thickness_mm / 2 + self.sheets[0].thickness_mm) - self.screw.head_height_mm
        return head + across / 2, along / 2


def comb_profile(sheet: CombSheet) -> Profile:
    """Exact outline of one row's comb sheet (CCW, lines and arcs; sheet frame, mm):
    :func:`tactcad.geometry.profile.comb_sheet_profile`, the one walk the solid, the DXF and
    the mechanics' plane model of the sheet cut."""
    return comb_sheet_profile(sheet)


def build(sheet: CombSheet) -> Solid:
    """The comb sheet in its sheet frame, extruded along +z (mm)."""
    return extrude_profile(comb_profile(sheet), sheet.thickness_mm)


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """One part per row sheet of the plan's comb (none without a comb)."""
    comb = context.plan.comb
    if comb is None:
        return ()
    out = []
    for sheet in comb.sheets:
        prof = comb_profile(sheet)
        out.append(PartData(
            name=sheet.part_name, kind="fabricated",
            process=cut_process(sheet.elements[0].process).part_process(),
            material=context.plan.material.name, color=sheet_shade(sheet.row),
            expected_volume_mm3=prof.area_mm2 * sheet.thickness_mm,
            expected_bbox_mm=prism_bbox(prof, sheet.thickness_mm), geometry=sheet, profile=prof,
            thickness_mm=sheet.thickness_mm))
    return tuple(out)


def dimensions(d, solid, pen) -> None:
    """The general set (overall sizes one tier out, holes, radii) and, on the tier nearest
    the part, the first column's arm (notch centre to tip centre, with its tolerance) chained
    to the pitch of the next tip centre; each column's web, tip and stop gap are in the
    notes (:func:`element_lines`)."""
    pen.generic_dims(d, solid, top_k=1)
    sheet, f = d.spec.geometry, d.front
    tol = pen.tolerances(d.plan)
    top = max(e.tip_top_y_mm for e in sheet.elements)
    first = sheet.elements[0]
    hinge = sheet.offsets_mm[0] + first.hinge_x_mm
    tip = sheet.offsets_mm[0] + first.tip_centre_x_mm
    pen.dim(d, f, (hinge, top), (tip, top), "h", "top", 0,
            pen.plus_minus(first.arm_length_mm, tol.arm_length_mm), "arm_length")
    if len(sheet.elements) > 1:
        nxt = sheet.offsets_mm[1] + sheet.elements[1].tip_centre_x_mm
        pen.dim(d, f, (tip, top), (nxt, top), "h", "top", 0, pen.fmt_mm(nxt - tip), "pitch")


def gap_tolerance_mm(plan, sheet: CombSheet) -> float:
    """The +/- a stop gap is held to (mm): what the rows' cut process holds on the sheet
    (the gap as cut; a narrower gap is set by a shim on the cut ledge)."""
    e = sheet.elements[0]
    return cut_process(e.process).limits(sheet.thickness_mm, plan.edm,
                                         plan.material.name).tolerance_mm.value_mm


def element_lines(d, pen) -> list[str]:
    """The sheet's elements as the shop makes and inspects them: each run of like columns
    with its arm (tip centre to notch centre), web and notch, tip and stop gap, each with the
    tolerance the design's table gives it (the tolerance study's), and the pitch of the tip
    centres (its general tolerance)."""
    sheet = d.spec.geometry
    tol = pen.tolerances(d.plan)
    gaps = sheet.stop_gaps_mm or sheet.cut_gaps_mm
    keys = [(e.arm_length_mm, e.web_thickness_mm, e.web_tolerance_mm, e.notch_radius_mm,
             e.tip_width_mm, e.tip_height_mm, gap) for e, gap in zip(sheet.elements, gaps)]
    runs: list[list[int]] = []
    for i, key in enumerate(keys):
        if runs and keys[runs[-1][-1]] == key:
            runs[-1].append(i)
        else:
            runs.append([i])
    held = gap_tolerance_mm(d.plan, sheet)
    lines = []
    for run in runs:
        e, gap = sheet.elements[run[0]], gaps[run[0]]
        cols = (f"column {run[0] + 1}" if len(run) == 1
                else f"columns {run[0] + 1}-{run[-1] + 1}")
        lines.append(f"{pen.sentence(cols)}: arm {pen.plus_minus(e.arm_length_mm, tol.arm_length_mm)}"
                     f" (notch centre to tip centre), web {pen.web_text(e)} in notch "
                     f"R{pen.fmt_mm(e.notch_radius_mm)} ±{pen.fmt_mm(tol.notch_radius_mm)}, "
                     f"tip {pen.plus_minus(e.tip_width_mm, tol.contact_face_mm)} wide x "
                     f"{pen.fmt_mm(e.tip_height_mm)}, stop gap {pen.plus_minus(gap, held)} at the "
                     "arm's end.")
    centres = [off + e.tip_centre_x_mm for off, e in zip(sheet.offsets_mm, sheet.elements)]
    steps = {round(b - a, 6) for a, b in zip(centres, centres[1:])}
    if len(steps) == 1:
        lines.append(f"Tip centres at a pitch of {pen.fmt_mm(steps.pop())} mm "
                     f"({len(centres)} tips; general tolerance).")
    if d.tip_height is not None:  # the K_obj budget sets the tips' coplanarity
        top = max(e.tip_top_y_mm for e in sheet.elements)
        lines.append(f"Contact faces {pen.plus_minus(top, pen.tip_height_tolerance(d))} above "
                     f"the spine's underside, every tip.")
    return lines


def notes(d, pen) -> list[str]:
    """The comb sheet's notes: the process, each run of like elements with its tolerances,
    the stops, the holes' fits and the rated full-scale force judged against the row's
    lowest element force limit (as a stacked element's drawing judges its own)."""
    sheet = d.spec.geometry
    gaps = sheet.stop_gaps_mm or sheet.cut_gaps_mm
    stops = ", ".join(pen.fmt_mm(gap) + (f" (cut {pen.fmt_mm(cut)}, shim {pen.fmt_mm(shim)})"
                                         if shim > 0 else "")
                      for gap, cut, shim in zip(gaps, sheet.cut_gaps_mm, sheet.shims_mm))
    return [f"{pen.sentence(d.spec.process)}, {d.spec.material}, sheet "
            f"{pen.fmt_mm(sheet.thickness_mm)}: {len(sheet.elements)} elements on one spine.",
            *element_lines(d, pen),
            f"Stop gaps under the arms' ends, element by element: {stops}; a gap narrower "
            f"than the wire's slot is cut at the slot and closed to the stop gap by a shim "
            f"bonded on the ledge under the tip.",
            "Dowel holes reamed H7; screw holes ISO 273 medium.",
            pen.row_full_scale_note(d.plan, sheet.row, d.plan.material.yield_strength_MPa,
                                    d.plan.material.grade or d.plan.material.name)]


def plan_values(plan, spec, pen) -> tuple:
    """What of the plan the drawing prints: the comb, the sheet and the tolerance table."""
    return (plan.comb, plan.sheet_thickness_mm, pen.tolerances(plan))


def stacking_notes(book) -> tuple[str, ...]:
    """The comb's assembly: rows on the dowels, the screws, then each hard stop's shim."""
    return ("Press the two dowel pins into row 1's reamed holes, then slide on the spacer "
            "and row 2's sheet, gauged faces outward as the assembly model shows.",
            "Fit the screws from row 1's side and their nuts on row 2's; tighten them evenly "
            "with the rows pressed flat on a plate.",
            "Set each hard stop cut wider than its gap: bond the shim the sheet's drawing "
            "names for the element (the cut gap less the stop gap) on the ledge under its tip, "
            "then check the gap left with feeler gauges: the stop gap passes under the arm's "
            "end, a blade 0.01 mm thicker does not, and the arm moves freely down to it.")


PART = ArrayPart(key="comb_sheet", build=build, specs=specs, order=5,
                 drawing=DrawingRecord(dimensions=dimensions, notes_of=notes,
                                       plan_values=plan_values),
                 assembly=BuildStep("comb-rows", "Stack the comb's rows on their dowels and set "
                                    "the hard stops",
                                    tools=lambda book: ("flat granite or glass plate",
                                                        "feeler gauges"),
                                    notes=stacking_notes))
