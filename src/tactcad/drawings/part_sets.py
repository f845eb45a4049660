"""What each part family's drawing shows beyond the common sheet, gathered
under its builder key (``PartSpec.builder``) in one :class:`PartDrawing`:
dimension set, notes, section view, fixed view directions, detail view, hole
table or not, and the plan values it prints. A made part's drawing is its
part module's :class:`~tactcad.partlib.base.DrawingRecord` (the array's
element, spacer and clamp plate as much as a rig part), drawn with
:data:`PEN`. Any other fabricated part gets :data:`GENERIC` (overall sizes,
thickness, inside radii, holes; its process and material)."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Callable


from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.catalogue.files import profile_dxf_name, sheet_dxf_name, sheet_names_by_process
from tactcad.catalogue.shop import tap_drill_mm, thread_text
from tactcad.design.array_plan import Plan
from tactcad.design.readout_section import readout_of
from tactcad.design.tolerances import tolerances_of
from tactcad.drawings.dimensioning import (add_section, arc_angles, dim, hole_callout,
                                           hole_dims_linear, hole_marks, hole_table, plus_minus,
                                           radius_callouts, section_marks, thickness_dim)
from tactcad.drawings.drawing import (FIRST_TIER, TIER, Drawing, Hole2D, holes_seen, inside_radii,
                                      part_thickness, web_text)
from tactcad.drawings.sheet import fmt_mm
from tactcad.drawings.views import CAMERAS, cameras_for, orientation
from tactcad.drawings.design_notes import (element_web_note, full_scale_note, gauge_note,
                                           resonance_note, row_full_scale_note)
from tactcad.partlib.base import DrawingRecord
from tactcad.partlib.registry import drawing_record


def detail_circle(spec: PartSpec):
    """(centre, radius) of the part's detail view in model mm, or None."""
    detail = drawing_of(spec).detail
    return detail(spec) if detail is not None else None


def choose_cameras(spec: PartSpec) -> dict:
    """View set of a part: its family's fixed directions, the sketch plane
    for a profiled part, else by its bounding box."""
    fixed = drawing_of(spec).cameras
    if fixed is not None:
        return fixed
    if spec.profile is None:
        return orientation(spec.expected_bbox_mm)
    return dict(CAMERAS)


def hole_table_rows(d: Drawing, solid) -> int:
    """Rows of the hole table the generic set will draw (0: none)."""
    if not drawing_of(d.spec).hole_table:
        return 0
    holes = holes_seen(d.spec, solid, d.cameras)
    if not holes or len({(h.x, h.y) for h in holes}) == 1:
        return 0
    if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
        return 0
    return len(holes)


def round_outline(d: Drawing, solid) -> float | None:
    """Diameter of the front view's outline if it is a circle (a turned part
    seen along its axis): an outer cylinder coaxial with the view direction
    whose diameter equals both sizes of the view."""
    if d.spec.profile is not None:
        return None
    f = d.front
    u0, v0, u1, v1 = f.bbox
    if abs((u1 - u0) - (v1 - v0)) > 1e-6:
        return None
    from tactcad.kernel.inspect import cylinder_diameters_along

    direction, _ = d.cameras["front"]
    for diameter in cylinder_diameters_along(solid, direction):
        if abs(diameter - (u1 - u0)) < 1e-6:
            return diameter
    return None


def generic_dims(d: Drawing, solid, top_k: int = 0, right_k: int = 0) -> None:
    """Any fabricated part: overall length / height in the front view (a
    diameter for a turned part seen along its axis), thickness in the view
    from above, inside radii, and its holes (concentric holes of a round part
    by diameter only; linear dimensions from the lower-left datum for up to
    two holes on one line; else a hole table)."""
    f = d.front
    u0, v0, u1, v1 = f.bbox
    outer = round_outline(d, solid)
    if outer is not None:
        dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, f"Ø{fmt_mm(outer)}", "outer_diameter")
    else:
        dim(d, f, (u0, v1), (u1, v1), "h", "top", top_k, fmt_mm(u1 - u0), "overall_length")
        dim(d, f, (u1, v0), (u1, v1), "v", "right", right_k, fmt_mm(v1 - v0), "overall_height")
    thickness_dim(d)
    holes = holes_seen(d.spec, solid, d.cameras)
    centre = ((u0 + u1) / 2, (v0 + v1) / 2)
    if holes and outer is not None and all(abs(h.x - centre[0]) < 1e-6 and abs(h.y - centre[1]) < 1e-6
                                           for h in holes):
        hole_marks(d, f, holes)
        hole_callout(d, f, holes, (centre[0] + (u1 - u0) * 0.3, v1 + (v1 - v0) * 0.05))
    elif holes:
        hole_marks(d, f, holes)
        if len(holes) <= 2 and len({round(h.y, 9) for h in holes}) == 1:
            hole_dims_linear(d, f, holes, (u0, v0))
            hole_callout(d, f, holes, ((u0 + u1) / 2, v1 - (v1 - v0) * 0.15))
        else:
            datum = (0.0, 0.0) if (u0 - 1e-9 <= 0 <= u1 + 1e-9 and v0 - 1e-9 <= 0 <= v1 + 1e-9) \
                else (u0, v0)
            hole_table(d, f, holes, datum)
    radius_callouts(d, inside_radii(d.spec))


def process_note(d: Drawing) -> list[str]:
    """Any other part: its process and material."""
    return [f"{sentence(d.spec.process)}, {d.spec.material}."]


def sentence(text: str) -> str:
    """``text`` with its first letter in capitals."""
    return text[:1].upper() + text[1:]


def _no_plan_values(plan: Plan, spec: PartSpec) -> tuple:
    return ()


@dataclass(frozen=True)
class PartDrawing:
    """What one part family's drawing shows beyond the common sheet, under its builder key.

    Attributes:
        dimensions: the dimension set, ``(drawing, solid) -> None``.
        notes: the family's notes, ``drawing -> [sentence]`` (the general
            tolerance note follows them).
        section: a section view added after the main views, or None.
        cameras: fixed view directions, or None (sketch plane, else by bounding box).
        detail: ``spec -> (centre, radius)`` of a detail view in model mm, or None.
        hole_table: whether many holes go in a coordinate table.
        plan_values: ``(plan, spec) -> tuple`` of the plan values the notes
            and dimensions print (they are part of the drawing's hash).
    """

    dimensions: Callable[[Drawing, object], None] = generic_dims
    notes: Callable[[Drawing], list[str]] = process_note
    section: Callable[[Drawing, object], None] | None = None
    cameras: dict | None = None
    detail: Callable[[PartSpec], tuple | None] | None = None
    hole_table: bool = True
    plan_values: Callable[[Plan, PartSpec], tuple] = _no_plan_values


GENERIC = PartDrawing()


def drawing_of(spec: PartSpec) -> PartDrawing:
    """The :class:`PartDrawing` of a part's family: its part module's
    :class:`~tactcad.partlib.base.DrawingRecord`
    (:func:`tactcad.partlib.registry.drawing_record`), else :data:`GENERIC`."""
    record = drawing_record(spec.builder)
    return _from_record(record) if record is not None else GENERIC


#: What a part module's drawing (:class:`~tactcad.partlib.base.DrawingRecord`)
#: draws with: the dimensioning helpers of this layer and the design values a
#: note prints (tolerances, read-out, the design notes, file names), handed
#: over so that the part modules, which sit below, import none of them.
PEN = SimpleNamespace(
    dim=dim, hole_marks=hole_marks, Hole2D=Hole2D, thickness_dim=thickness_dim,
    generic_dims=generic_dims, section_marks=section_marks, add_section=add_section, fmt_mm=fmt_mm,
    thread_text=thread_text, tap_drill_mm=tap_drill_mm, FIRST_TIER=FIRST_TIER, TIER=TIER,
    plus_minus=plus_minus, arc_angles=arc_angles, holes_seen=holes_seen, hole_dims_linear=hole_dims_linear,
    hole_callout=hole_callout, web_text=web_text, part_thickness=part_thickness, sentence=sentence,
    tolerances=lambda plan: tolerances_of(plan.raw),
    tip_height_tolerance=lambda d: tip_height_tolerance_mm(d),
    readout=lambda plan: readout_of(plan.raw, plan.strength.gauge),
    web_note=element_web_note, gauge_note=gauge_note, full_scale_note=full_scale_note,
    row_full_scale_note=row_full_scale_note,
    resonance_note=resonance_note,
    profile_dxf_name=profile_dxf_name, sheet_dxf_name=sheet_dxf_name,
    sheet_dxf_of=lambda plan, spec: sheet_dxf_of(plan, spec))


def tip_height_tolerance_mm(d: Drawing) -> float:
    """The +/- mm a drawing holds the contact face's height to.

    Args:
        d: the drawing being made.

    Returns:
        The export's tip-height decision's tolerance (:attr:`Drawing.tip_height`, from the
        K_obj budget), else ``[tolerances] tip_height_mm`` (mm).
    """
    if d.tip_height is not None:
        return d.tip_height.drawn_mm
    return tolerances_of(d.plan.raw).tip_height_mm


def sheet_dxf_of(plan: Plan, spec: PartSpec) -> str:
    """The nested sheet DXF a cut part is on: its family's name, or its grade's
    when another grade of the family is cut at that thickness, with its process
    when another process cuts that sheet
    (:func:`~tactcad.catalogue.files.sheet_names_by_process`)."""
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.catalogue.shop import material_designation
    from tactcad.vocabulary.process import DEFAULT_CUT_PROCESS

    cut = array_parts(plan, ("element", "spacer"))
    names = sheet_names_by_process([(s.material, material_designation(s, plan), s.thickness_mm,
                                     s.process.key or DEFAULT_CUT_PROCESS) for s in cut.values()])
    return sheet_dxf_name(dict(zip(cut, names)).get(spec.name, spec.material), spec.thickness_mm)


@functools.cache
def _from_record(record: DrawingRecord) -> PartDrawing:
    """The part module's drawing: its dimension set (else the general one) and
    section drawn with :data:`PEN`, its notes (all of them, else its notes
    around the process note), its fixed view directions, detail view and the
    plan values it prints."""
    def dimensions(d: Drawing, solid) -> None:
        record.dimensions(d, solid, PEN)

    def section(d: Drawing, solid) -> None:
        record.section(d, solid, PEN)

    def notes(d: Drawing) -> list[str]:
        if record.notes_of is not None:
            return record.notes_of(d, PEN)
        after = record.notes_after(d.spec.geometry, PEN) if record.notes_after else []
        return list(record.notes) + process_note(d) + after

    def detail(spec: PartSpec):
        return record.detail(spec.geometry)

    def plan_values(plan: Plan, spec: PartSpec) -> tuple:
        return record.plan_values(plan, spec, PEN)

    return PartDrawing(dimensions if record.dimensions else generic_dims, notes,
                       section=section if record.section else None,
                       cameras=cameras_for(*record.view_from) if record.view_from else None,
                       detail=detail if record.detail else None, hole_table=record.hole_table,
                       plan_values=plan_values if record.plan_values else _no_plan_values)
