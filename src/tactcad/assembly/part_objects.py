"""The flexure element and the array as build123d part objects.

:class:`FlexureElement` and :class:`FlexureArray` are
``build123d.BasePartObject`` subclasses, as bd_warehouse's parts are: they
take their design parameters as arguments (mm), can be placed inside a
``BuildPart`` (``rotation``, ``align``, ``mode``) or used alone, and show in
a notebook or OCP CAD Viewer. Their parameters go through the design file's
validator: a value out of range is refused with the message the design file
gives (:class:`~tactcad.errors.DesignErrors`). A parameter left ``None``
takes the design's value (default: ``hardware/macro_array.toml``).

    >>> from build123d import BuildPart, Box, Mode
    >>> from tactcad import FlexureElement
    >>> with BuildPart() as jaw:  # doctest: +SKIP
    ...     Box(30, 20, 10)
    ...     FlexureElement(arm_length_mm=5, web_thickness_mm=0.3, mode=Mode.ADD)
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Mapping

from tactcad.assembly.plan_locations import location
from tactcad.kernel.locations import placed
from tactcad.catalogue.array_catalogue import array_instances, array_parts
from tactcad.design.array_plan import DEFAULT_DESIGN, Plan, plan_from_dict, read_toml, with_overrides
from tactcad.errors import DesignErrors
from tactcad.kernel.objects import BUILD_PART, Align, Mode, PartObject, RotationLike, labelled_part
from tactcad.solids.cache import PartCache

#: Element parameters -> their key in the design file.
ELEMENT_KEYS = {
    "web_thickness_mm": "element.web_thickness_mm",
    "notch_radius_mm": "element.notch_radius_mm",
    "tip_width_mm": "element.tip_width_mm",
    "tip_height_mm": "element.tip_height_mm",
    "arm_height_mm": "element.arm_height_mm",
    "base_height_mm": "element.base_height_mm",
    "overall_length_mm": "element.overall_length_mm",
    "inside_corner_radius_mm": "element.inside_corner_radius_mm",
    "sheet_thickness_mm": "sheet.thickness_mm",
}


def validated_plan(design: str | Path | None, overrides: Mapping[str, Any],
                   every_arm_mm: float | None = None) -> Plan:
    """The plan of ``design`` with ``overrides`` (dotted keys), through the design validator.

    Args:
        every_arm_mm: when given, every element's arm length (mm), so that
            the rules tying arms to the base and bolts judge this arm.

    Raises:
        DesignErrors: every refusal, worded as for the design file.
    """
    path = Path(design) if design is not None else DEFAULT_DESIGN
    data = with_overrides(read_toml(path, "design file"), overrides)
    if every_arm_mm is None:
        return plan_from_dict(data, source=str(path), file=path.name)
    arms = data.get("arms", {}).get("lengths_mm") if isinstance(data.get("arms"), dict) else None
    count = len(arms) if isinstance(arms, list) and arms else 1
    data = with_overrides(data, {"arms.lengths_mm": [every_arm_mm] * count})
    try:
        return plan_from_dict(data, source=str(path), file=path.name)
    except DesignErrors as exc:  # the same arm refused once, not once per element
        raise _once_per_arm(exc) from None


def _once_per_arm(exc: DesignErrors) -> DesignErrors:
    """``exc`` without the repeats of one refusal for each copy of the arm."""
    seen, kept = set(), []
    for e in exc.errors:
        key = (re.sub(r"^arms\.lengths_mm\[\d+\]$", "arms.lengths_mm[]", e.field), e.allowed, e.why)
        if key not in seen:
            seen.add(key)
            kept.append(e)
    return DesignErrors(kept)


def _given(values: Mapping[str, Any]) -> dict[str, Any]:
    """The design keys of the parameters given (not None)."""
    return {ELEMENT_KEYS[k]: v for k, v in values.items() if k in ELEMENT_KEYS and v is not None}


class FlexureElement(PartObject):
    """A wire-cut flexure sensing element: clamped base, single-sided
    circular notch hinge, measuring arm and tip (element frame, mm: the
    profile in x-y, extruded along +z by the sheet thickness; x along the
    arm, y up, the contact face on the tip's top).

    Args:
        arm_length_mm: lever from the notch centre to the contact face's
            centre (mm); default element 1's arm of the design.
        web_thickness_mm: thinnest section of the notch hinge (mm).
        notch_radius_mm: radius of the circular notch (mm).
        tip_width_mm, tip_height_mm: tip size (mm).
        arm_height_mm, base_height_mm, overall_length_mm: profile (mm).
        inside_corner_radius_mm: wire-EDM inside corner radius (mm).
        sheet_thickness_mm: sheet (extrusion) thickness (mm).
        design: the design file whose values fill the parameters left None.
        rotation, align, mode: as for every ``BasePartObject``.

    Attributes:
        geometry: the validated :class:`~tactcad.design.array_plan.ElementGeometry`.

    Raises:
        DesignErrors: a parameter out of its range, or a combination the
            design rules refuse (the design file's messages, naming the key).
    """

    _applies_to = [BUILD_PART]

    def __init__(self, arm_length_mm: float | None = None, web_thickness_mm: float | None = None,
                 notch_radius_mm: float | None = None, tip_width_mm: float | None = None,
                 tip_height_mm: float | None = None, arm_height_mm: float | None = None,
                 base_height_mm: float | None = None, overall_length_mm: float | None = None,
                 inside_corner_radius_mm: float | None = None,
                 sheet_thickness_mm: float | None = None, design: str | Path | None = None,
                 rotation: RotationLike = (0, 0, 0),
                 align: Align | tuple[Align, Align, Align] | None = None,
                 mode: Mode = Mode.ADD):
        plan = validated_plan(design, _given(locals()), arm_length_mm)
        self.geometry = plan.slots[0].geometry
        solid = PartCache(plan).solid(array_parts(plan)[self.geometry.part_name])
        solid.label = self.geometry.part_name
        super().__init__(part=solid, rotation=rotation, align=align, mode=mode)


class FlexureArray(PartObject):
    """The clamped array: every element, spacer, clamp plate, bolt and nut
    placed in the array frame (mm), one solid each, as one part.

    Args:
        arm_lengths_mm: every element's arm (rows x columns values, mm).
        pitch_mm: element pitch within a row (mm).
        columns: elements per row.
        web_thickness_mm, notch_radius_mm, sheet_thickness_mm ...: as for
            :class:`FlexureElement`, for every element.
        design: the design file whose values fill the parameters left None.
        rotation, align, mode: as for every ``BasePartObject``.

    Attributes:
        plan: the validated :class:`~tactcad.design.array_plan.Plan`.

    Raises:
        DesignErrors: as :class:`FlexureElement`.
    """

    _applies_to = [BUILD_PART]

    def __init__(self, arm_lengths_mm: list[float] | None = None, pitch_mm: float | None = None,
                 columns: int | None = None, web_thickness_mm: float | None = None,
                 notch_radius_mm: float | None = None, tip_width_mm: float | None = None,
                 tip_height_mm: float | None = None, arm_height_mm: float | None = None,
                 base_height_mm: float | None = None, overall_length_mm: float | None = None,
                 inside_corner_radius_mm: float | None = None,
                 sheet_thickness_mm: float | None = None, design: str | Path | None = None,
                 rotation: RotationLike = (0, 0, 0),
                 align: Align | tuple[Align, Align, Align] | None = None,
                 mode: Mode = Mode.ADD):
        overrides = _given(locals())
        for key, value in (("arms.lengths_mm", arm_lengths_mm), ("array.pitch_mm", pitch_mm),
                           ("array.columns", columns)):
            if value is not None:
                overrides[key] = value
        self.plan = validated_plan(design, overrides)
        cache, specs = PartCache(self.plan), array_parts(self.plan)
        children = []
        for inst in array_instances(self.plan):
            child = placed(cache.solid(specs[inst.part]), location(inst.placement))
            child.label = inst.name
            children.append(child)
        part = labelled_part(children, self.plan.name)
        super().__init__(part=part, rotation=rotation, align=align, mode=mode)


def show(*objects, **options) -> bool:
    """Show build123d objects in OCP CAD Viewer when ``ocp_vscode`` is installed.

    Returns:
        True when shown; False (nothing happens) without ``ocp_vscode``, which
        tactcad does not require.
    """
    try:
        from ocp_vscode import show as viewer_show
    except ImportError:
        return False
    viewer_show(*objects, **options)
    return True
