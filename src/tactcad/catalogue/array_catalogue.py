"""What each part is, without building it: name, process, colour, expected
volume and bounding box (independent estimates the checks compare against),
and the assembly's instances. No CAD kernel here.

Each part's data is its part module's (:mod:`tactcad.partlib.array`, found
by the one registry); this module turns them into specs and places the
parts. Expected volumes are computed from the plan by elementary formulas
(profile area x thickness, cylinder and hexagon volumes), never from the
solid itself.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field
from typing import Any, Collection

from tactcad.catalogue.gauges import gauge_body, gauge_placements
from tactcad.design.array_plan import Placement, Plan
from tactcad.design.construction_registry import construction_of
from tactcad.partlib.array.fasteners import bolt_name, bolt_volume, nut_name  # noqa: F401 (re-exported)
from tactcad.partlib.array.strain_gauge import GAUGE_PART
from tactcad.partlib.array import strain_gauge
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, Bbox, PartData
from tactcad.partlib.registry import array_parts_for, array_parts_lib
from tactcad.vocabulary.process import Method, Process
from tactcad.geometry.profile import Profile

#: Names the layers above read from here (the part modules hold them).
__all__ = ["GAUGE_PART", "RGB", "Bbox", "Instance", "Method", "PartSpec", "Process",
           "array_contacts", "array_instances", "array_parts", "array_spec", "bolt_name",
           "bolt_volume", "nut_name", "part_material_names"]


@dataclass(frozen=True)
class PartSpec:
    """A distinct part of a scene.

    Attributes:
        name: file and label name (``element_a4mm``, ``spacer``, ...).
        kind: ``fabricated`` or ``purchased``.
        process: how it is made (wire EDM, milling) or its catalogue reference,
            typed by its :class:`Method`.
        material: material name.
        color: RGB in 0 ... 1 for STEP/GLB.
        builder: key of the builder in :func:`tactcad.partlib.registry.builders`.
        expected_volume_mm3: independent volume estimate.
        expected_bbox_mm: designed bounding box in the part's own frame.
        profile: planar profile (sketch plane z = 0) for extruded parts.
        thickness_mm: extrusion thickness for extruded parts.
        geometry: the frozen dimensions the builder, drawing and DXF writers
            read (an element's :class:`~tactcad.design.array_plan.ElementGeometry`,
            the spacer's, the clamp's, a rig part's), so no writer reaches back
            into the plan.
    """

    name: str
    kind: str
    process: Process
    material: str
    color: RGB
    builder: str
    expected_volume_mm3: float
    expected_bbox_mm: Bbox
    profile: Profile | None = None
    thickness_mm: float = 0.0
    # Left out of an array part's stable text (store keys, the drawing's part
    # hash): its profile and thickness already fix its solid, and the
    # drawing's inputs name the geometry itself. A rig part keeps it in.
    geometry: Any = field(default=None, repr=False)


@dataclass(frozen=True)
class Instance:
    """A part placed in the scene frame."""

    name: str
    part: str
    placement: Placement


#: (id(plan), families) -> (weak reference to the plan, its array parts): each
#: plan's parts are made once (every element profile is built), however many
#: writers ask.
_ARRAY_PARTS: dict[tuple, tuple[weakref.ref, dict[str, PartSpec]]] = {}


def array_parts(plan: Plan, families: Collection[str] | None = None) -> dict[str, PartSpec]:
    """Every distinct part of the array assembly, keyed by part name (a fresh
    dict of the specs made once per plan); ``families``: only the parts of
    these part modules (by key; a variant counts as the family it replaces),
    for a writer that needs no more (the shop DXF: elements and spacers)."""
    key = (id(plan), None if families is None else tuple(sorted(families)))
    hit = _ARRAY_PARTS.get(key)
    if hit is None or hit[0]() is not plan:
        ref = weakref.ref(plan, lambda _, k=key: _ARRAY_PARTS.pop(k, None))
        hit = _ARRAY_PARTS[key] = (ref, _make_array_parts(plan, families))
    return dict(hit[1])


def _make_array_parts(plan: Plan, families: Collection[str] | None) -> dict[str, PartSpec]:
    """The parts of the array part modules the design uses (those of its
    construction, :mod:`tactcad.design.construction_registry`, and of them
    :func:`tactcad.partlib.registry.array_parts_for` its tables, in order), as specs."""
    lib = array_parts_lib()
    made_by = construction_of(plan).parts
    modules = [part for part in array_parts_for(plan.raw)
               if (part.replaces or part.key) in made_by
               and (families is None or (part.replaces or part.key) in families)]
    tables = {key: part.section.model_validate(plan.raw[key]) for key, part in lib.items()
              if part.section is not None and key in plan.raw}
    # the gauge's body reads the read-out chain: made only when the gauge is asked for
    gauge = gauge_body(plan) if any(part is strain_gauge.PART for part in modules) else None
    context = ArrayContext(plan, part_material_names(plan), gauge, tables)
    return {data.name: array_spec(part, data) for part in modules for data in part.specs(context)}


def array_spec(part: ArrayPart, data: PartData) -> PartSpec:
    """The spec of a part an array part module derived (builder
    :attr:`PartData.builder`, else the module's key)."""
    return PartSpec(
        name=data.name, kind=data.kind, process=data.process, material=data.material,
        color=data.color, builder=data.builder or part.key,
        expected_volume_mm3=data.expected_volume_mm3, expected_bbox_mm=data.expected_bbox_mm,
        profile=data.profile, thickness_mm=data.thickness_mm, geometry=data.geometry)


def part_material_names(plan: Plan) -> dict[str, str]:
    """Material name of the clamp plates and spacers (``clamp.material``,
    ``clamp.spacer_material``; :func:`tactcad.design.bom_section.clamp_grades`): the grade's family,
    or the element material's name when it is the elements' own grade."""
    from tactcad.design.bom_section import clamp_grades
    from tactcad.vocabulary.material_library import material_grade

    out = {}
    for part, grade in clamp_grades(plan.raw).items():
        g = material_grade(grade)
        out[part] = plan.material.name if grade == plan.material.grade else (g.family or g.name)
    return out


def array_instances(plan: Plan) -> list[Instance]:
    """Every placed part of the array assembly (array frame, mm): those its
    construction places (:meth:`~tactcad.design.construction_registry.Construction.placed_parts`)
    and each element's strain gauge."""
    out = [Instance(*placed) for placed in construction_of(plan).placed_parts(plan)]
    out += [Instance(f"gauge_{n}", GAUGE_PART, pl) for n, pl in gauge_placements(plan)]
    return out


def array_contacts(plan: Plan) -> set[frozenset[str]]:
    """Instance pairs the design declares as touching (face contact, zero
    volume): its construction's and each gauge bonded to its element's holder."""
    made = construction_of(plan)
    names = {i.name for i in array_instances(plan)}
    pairs = made.touching(plan)
    pairs |= {frozenset({made.element_holder(plan, s), f"gauge_{s.number}"}) for s in plan.slots}
    return {p for p in pairs if p <= names}
