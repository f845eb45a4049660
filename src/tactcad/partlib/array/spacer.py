"""The spacer plate (a made part): it sits between neighbouring elements of a
row, drilled with the elements' bolt holes, and its thickness (pitch - sheet)
sets the array's pitch.

Here under the key ``spacer``: its dimensions (:class:`SpacerGeometry`), spec,
builder and shop drawing's notes. Its size is derived with the clamp's bolt
pattern in :mod:`tactcad.design.array_plan` (above this layer), which this module
reads from the plan. Part frame: the element frame (x along the base, y up,
thickness along +z). Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Profile, rectangle_profile
from tactcad.kernel.shapes import extrude_profile
from tactcad.partlib.array.prism import DrilledPlate, hole_circles, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, DrawingRecord, PartData
from tactcad.vocabulary.process import CUT_PROCESSES, Process, cut_process, first_process_holding
from tactcad.vocabulary.schema import Section, choice

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

COLOR: RGB = (0.60, 0.64, 0.68)


class SpacerSection(Section):
    """``[spacer]`` of the design file (optional): how the spacers are cut."""

    #: the cut process (:data:`tactcad.vocabulary.process.CUT_PROCESSES`); left out: the
    #: first registered process whose cutting range holds the spacer's thickness
    process: choice(CUT_PROCESSES, "the processes that cut a part from sheet") = None


def spacer_process(context: ArrayContext, thickness_mm: float) -> Process:
    """The spacer's process: ``[spacer] process`` where the design states it, else the
    first registered cut process whose cutting range holds ``thickness_mm`` (mm); a plain
    plate, so the flexure model's sheet range does not apply
    (:meth:`~tactcad.vocabulary.process.CutProcess.holds_sheet`)."""
    table = context.tables.get(PART.key)
    name = getattr(table, "process", None) or first_process_holding(thickness_mm)
    return cut_process(name, "spacer.process").part_process()


@dataclass(frozen=True)
class SpacerGeometry(DrilledPlate):
    """Spacer plate between neighbouring elements of a row (mm); sets the pitch."""

    length_mm: float
    height_mm: float
    thickness_mm: float


def spacer_profile(s: SpacerGeometry) -> Profile:
    """The spacer's outline with its bolt holes (sketch plane, mm)."""
    return rectangle_profile(s.length_mm, s.height_mm, hole_circles(s.holes))


def build(s: SpacerGeometry) -> Solid:
    """Spacer in the element frame (same bolt holes as the element base), mm."""
    return extrude_profile(spacer_profile(s), s.thickness_mm)


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The spacer (``plan.spacer``) when the array has one: a one-column array has none."""
    plan = context.plan
    if not plan.spacer_placements:
        return ()
    s = plan.spacer
    prof = spacer_profile(s)
    return (PartData(
        name="spacer", kind="fabricated", process=spacer_process(context, s.thickness_mm),
        material=context.materials["spacer"], color=COLOR,
        expected_volume_mm3=prof.area_mm2 * s.thickness_mm,
        expected_bbox_mm=prism_bbox(prof, s.thickness_mm), geometry=s, profile=prof,
        thickness_mm=s.thickness_mm),)


def notes(d, pen) -> list[str]:
    """The spacer's note: it sets the pitch, so its faces are parallel."""
    plan = d.plan
    return [f"{pen.sentence(d.spec.process)}, {d.spec.material}. Thickness "
            f"{pen.fmt_mm(d.spec.geometry.thickness_mm)} = pitch {pen.fmt_mm(plan.pitch_mm)} - sheet "
            f"{pen.fmt_mm(plan.sheet_thickness_mm)}: it sets the array pitch; faces parallel "
            f"within 0.01 (ISO 1101)."]


def plan_values(plan, spec, pen) -> tuple:
    """What of the plan the drawing prints: the spacer, the pitch and the sheet."""
    return (plan.spacer, plan.pitch_mm, plan.sheet_thickness_mm)


PART = ArrayPart(key="spacer", build=build, specs=specs, order=20, section=SpacerSection,
                 drawing=DrawingRecord(notes_of=notes, plan_values=plan_values),
                 assembly=BuildStep("array-stack"))
