"""What the array's extruded parts (element, spacer, clamp plate) share:
round through holes in the sketch plane, the drilled plate they make and a
prism's bounding box. Units: mm."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Iterable

if TYPE_CHECKING:
    from tactcad.geometry.profile import Profile


@dataclass(frozen=True)
class Hole:
    """A round through hole in a part's sketch plane (mm)."""

    x_mm: float
    y_mm: float
    diameter_mm: float


@dataclass(frozen=True)
class DrilledPlate:
    """A flat plate drilled through (mm): its through holes, keyword-only so
    each plate lists its own outline and thickness first (and keeps its
    constructor's order)."""

    holes: tuple[Hole, ...] = field(kw_only=True)


def hole_circles(holes: Iterable[Hole]) -> list[tuple[float, float, float]]:
    """(x mm, y mm, diameter mm) of each hole, as the profiles take them."""
    return [(h.x_mm, h.y_mm, h.diameter_mm) for h in holes]


def prism_bbox(profile: Profile, thickness_mm: float) -> tuple[float, float, float, float, float, float]:
    """Box (mm) of ``profile`` extruded from z = 0 by ``thickness_mm``."""
    x0, y0, x1, y1 = profile.bbox_mm
    return (x0, y0, 0.0, x1, y1, thickness_mm)
