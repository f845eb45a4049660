"""Flexure sensing element: the wire-cut profile extruded by the sheet thickness."""

from __future__ import annotations

from typing import TYPE_CHECKING

from tactcad.design.array import ElementGeometry
from tactcad.geometry.profile import element_profile
from tactcad.kernel.shapes import extrude_profile

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid


def build_element(g: ElementGeometry) -> Solid:
    """Solid of one element (element frame, mm): the wire-cut profile extruded
    along +z by the sheet thickness."""
    return extrude_profile(element_profile(g), g.sheet_thickness_mm)
