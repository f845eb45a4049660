"""What each part is, without building it: name, process, colour, expected
volume and bounding box (independent estimates the checks compare against),
and the assembly's instances. No CAD kernel here.

Expected volumes are computed from the plan by elementary formulas (profile
area x thickness, cylinder and hexagon volumes), never from the solid itself.
"""

from __future__ import annotations

import colorsys
import math
import weakref
from dataclasses import dataclass, field
from typing import Any

from tactcad.catalogue.gauges import gauge_body, gauge_placements
from tactcad.design.array import BoltSpec, Placement, Plan
from tactcad.vocabulary.process import Method, Process
from tactcad.geometry.profile import Profile, element_profile, rectangle_profile, u_plate_profile

Bbox = tuple[float, float, float, float, float, float]  # xmin, ymin, zmin, xmax, ymax, zmax (mm)
RGB = tuple[float, float, float]

SPACER: RGB = (0.60, 0.64, 0.68)
ANODISED_BLUE: RGB = (0.25, 0.40, 0.70)
GAUGE_AMBER: RGB = (0.85, 0.55, 0.15)  # polyimide carrier
#: Part name of the strain gauge body (one per element).
GAUGE_PART = "strain_gauge"
BLACK_OXIDE: RGB = (0.12, 0.12, 0.13)
ZINC: RGB = (0.45, 0.46, 0.48)


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
        builder: key of the builder in :mod:`tactcad.parts.registry`.
        expected_volume_mm3: independent volume estimate.
        expected_bbox_mm: designed bounding box in the part's own frame.
        profile: planar profile (sketch plane z = 0) for extruded parts.
        thickness_mm: extrusion thickness for extruded parts.
        geometry: the frozen dimensions the builder, drawing and DXF writers
            read (an element's :class:`~tactcad.design.array.ElementGeometry`,
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


def _prism_bbox(profile: Profile, thickness: float) -> Bbox:
    x0, y0, x1, y1 = profile.bbox_mm
    return (x0, y0, 0.0, x1, y1, thickness)


#: id(plan) -> (weak reference to the plan, its array parts): each plan's parts are
#: made once (every element profile is built), however many writers ask.
_ARRAY_PARTS: dict[int, tuple[weakref.ref, dict[str, PartSpec]]] = {}


def array_parts(plan: Plan) -> dict[str, PartSpec]:
    """Every distinct part of the array assembly, keyed by part name (a fresh
    dict of the specs made once per plan)."""
    hit = _ARRAY_PARTS.get(id(plan))
    if hit is None or hit[0]() is not plan:
        ref = weakref.ref(plan, lambda _, key=id(plan): _ARRAY_PARTS.pop(key, None))
        hit = _ARRAY_PARTS[id(plan)] = (ref, _make_array_parts(plan))
    return dict(hit[1])


def _make_array_parts(plan: Plan) -> dict[str, PartSpec]:
    parts: dict[str, PartSpec] = {}
    mat = plan.material.name
    own = part_material_names(plan)  # clamp plates and spacers: their own grade
    for name, g in plan.distinct_elements.items():
        prof = element_profile(g)
        parts[name] = PartSpec(
            name=name, kind="fabricated", process=Process("wire EDM from sheet", Method.SHEET), material=mat,
            color=_element_shade(g.arm_length_mm), builder="element",
            expected_volume_mm3=prof.area_mm2 * g.sheet_thickness_mm,
            expected_bbox_mm=_prism_bbox(prof, g.sheet_thickness_mm),
            profile=prof, thickness_mm=g.sheet_thickness_mm, geometry=g)
    s = plan.spacer
    if plan.spacer_placements:  # a one-column array has no spacer part
        sp = rectangle_profile(s.length_mm, s.height_mm,
                               [(h.x_mm, h.y_mm, h.diameter_mm) for h in s.holes])
        parts["spacer"] = PartSpec(
            name="spacer", kind="fabricated", process=Process("wire EDM or laser cut from sheet", Method.SHEET),
            material=own["spacer"], color=SPACER, builder="spacer",
            expected_volume_mm3=sp.area_mm2 * s.thickness_mm,
            expected_bbox_mm=_prism_bbox(sp, s.thickness_mm), profile=sp, thickness_mm=s.thickness_mm,
            geometry=s)
    c = plan.clamp
    cp = u_plate_profile(c.half_length_mm, c.window_half_width_mm, c.height_mm, c.bridge_height_mm,
                         c.window_corner_radius_mm, [(h.x_mm, h.y_mm, h.diameter_mm) for h in c.holes])
    parts["clamp_plate"] = PartSpec(
        name="clamp_plate", kind="fabricated", process=Process("milling", Method.PLATE),
        material=own["clamp_plate"],
        color=ANODISED_BLUE, builder="clamp_plate",
        expected_volume_mm3=cp.area_mm2 * c.thickness_mm,
        expected_bbox_mm=_prism_bbox(cp, c.thickness_mm), profile=cp, thickness_mm=c.thickness_mm,
        geometry=c)
    gb = gauge_body(plan)
    gauge = plan.strength.gauge
    parts[GAUGE_PART] = PartSpec(
        name=GAUGE_PART, kind="purchased",
        process=Process(f"{gauge.description}; grid {gb.grid_length_mm:g} x {gb.grid_width_mm:g} "
                        f"mm, {gauge.resistance_ohm:g} ohm ({gauge.name}), bonded over the web",
                        Method.BOUGHT),
        material=f"{gauge.alloy} foil on polyimide", color=GAUGE_AMBER, builder="gauge",
        expected_volume_mm3=gb.volume_mm3, expected_bbox_mm=gb.bbox_mm, geometry=gb)
    b = plan.bolt
    L = plan.bolt_length_mm
    rh = b.head_diameter_mm / 2
    parts[bolt_name(b, L)] = PartSpec(
        name=bolt_name(b, L), kind="purchased",
        process=Process(f"ISO 4762 {b.size}x{L:g} socket head cap screw", Method.BOUGHT),
        material="steel 8.8",
        color=BLACK_OXIDE, builder="bolt", expected_volume_mm3=bolt_volume(b, L),
        expected_bbox_mm=(-rh, -rh, -b.head_height_mm, rh, rh, L), geometry=(b, L))
    s_af = b.nut_width_across_flats_mm
    nut_vol = (hexagon_area(s_af) - math.pi * (b.nominal_diameter_mm / 2) ** 2) * b.nut_height_mm
    rc = s_af / math.sqrt(3)
    parts[nut_name(b)] = PartSpec(
        name=nut_name(b), kind="purchased", process=Process(f"ISO 4032 {b.size} hex nut", Method.BOUGHT),
        material="steel 8",
        color=ZINC, builder="nut", expected_volume_mm3=nut_vol,
        expected_bbox_mm=(-rc, -s_af / 2, 0.0, rc, s_af / 2, b.nut_height_mm), geometry=b)
    return parts


def part_material_names(plan: Plan) -> dict[str, str]:
    """Material name of the clamp plates and spacers (``clamp.material``,
    ``clamp.spacer_material``; :func:`tactcad.design.bom.clamp_grades`): the grade's family,
    or the element material's name when it is the elements' own grade."""
    from tactcad.design.bom import clamp_grades
    from tactcad.vocabulary.materials import material_grade

    out = {}
    for part, grade in clamp_grades(plan.raw).items():
        g = material_grade(grade)
        out[part] = plan.material.name if grade == plan.material.grade else (g.family or g.name)
    return out


def bolt_name(b: BoltSpec, length_mm: float) -> str:
    """Part name of a bolt, safe for file names and STEP labels: ``bolt_M2p5x30``."""
    return f"bolt_{b.safe_name}x" + f"{length_mm:g}".replace(".", "p")


def nut_name(b: BoltSpec) -> str:
    """Part name of a nut: ``nut_M2p5``."""
    return f"nut_{b.safe_name}"


def bolt_volume(b: BoltSpec, length_mm: float) -> float:
    """Volume (mm^3) of the socket head cap screw envelope of
    :func:`tactcad.parts.fasteners.build_bolt`: head + shank - half-depth socket."""
    return (math.pi * (b.head_diameter_mm / 2) ** 2 * b.head_height_mm
            + math.pi * (b.nominal_diameter_mm / 2) ** 2 * length_mm
            - hexagon_area(b.socket_across_flats_mm) * b.head_height_mm / 2)


def _element_shade(arm_length_mm: float) -> RGB:
    """A clearly distinct anodising colour per arm length (stiffness class),
    the same in STEP, GLB and FreeCAD: the hue walks 0.19 of the colour wheel
    per mm of arm, from violet (4 mm) through pink, orange and green to
    turquoise (8 mm), away from the clamp plates' blue; deterministic, so a
    design always shows the same colours."""
    hue = (0.72 + (arm_length_mm - 4.0) * 0.19) % 1.0
    return tuple(round(c, 4) for c in colorsys.hsv_to_rgb(hue, 0.65, 0.85))  # type: ignore[return-value]


def hexagon_area(across_flats: float) -> float:
    """Area (mm^2) of a regular hexagon of the given width across flats."""
    return math.sqrt(3) / 2 * across_flats**2


def array_instances(plan: Plan) -> list[Instance]:
    """Every placed part of the array assembly (array frame, mm)."""
    out = [Instance(f"element_{s.number}", s.geometry.part_name, s.placement) for s in plan.slots]
    for i, pl in enumerate(plan.spacer_placements, start=1):
        out.append(Instance(f"spacer_{i}", "spacer", pl))
    z_front, z_back = plan.clamp_plate_z_mm
    out += [Instance(f"gauge_{n}", GAUGE_PART, pl) for n, pl in gauge_placements(plan)]
    out.append(Instance("clamp_plate_front", "clamp_plate", Placement(0.0, 0.0, z_front)))
    out.append(Instance("clamp_plate_back", "clamp_plate", Placement(0.0, 0.0, z_back)))
    bolt = bolt_name(plan.bolt, plan.bolt_length_mm)
    nut = nut_name(plan.bolt)
    z_nut = z_back + plan.clamp.thickness_mm
    for i, (x, y) in enumerate(plan.bolt_positions_xy_mm, start=1):
        out.append(Instance(f"bolt_{i}", bolt, Placement(x, y, z_front)))
        out.append(Instance(f"nut_{i}", nut, Placement(x, y, z_nut)))
    return out


def array_contacts(plan: Plan) -> set[frozenset[str]]:
    """Instance pairs the design declares as touching (face contact, zero volume)."""
    inst = array_instances(plan)
    names = {i.name for i in inst}
    pairs: set[frozenset[str]] = set()
    per_row = plan.columns
    for s in plan.slots:
        col = s.column
        row_offset = s.row * (per_row - 1)
        for k in (col, col + 1):  # spacer before / after the element in its row
            if 1 <= k <= per_row - 1:
                pairs.add(frozenset({f"element_{s.number}", f"spacer_{row_offset + k}"}))
        pairs.add(frozenset({f"element_{s.number}", f"gauge_{s.number}"}))  # bonded
        if col == 0:
            pairs.add(frozenset({f"element_{s.number}", "clamp_plate_front"}))
        if col == per_row - 1:
            pairs.add(frozenset({f"element_{s.number}", "clamp_plate_back"}))
    for i in range(1, len(plan.bolt_positions_xy_mm) + 1):
        pairs.add(frozenset({f"bolt_{i}", "clamp_plate_front"}))
        pairs.add(frozenset({f"nut_{i}", "clamp_plate_back"}))
        pairs.add(frozenset({f"bolt_{i}", f"nut_{i}"}))
    return {p for p in pairs if p <= names}
