"""Spacer plates (set the pitch) and the U-shaped clamp plates (hold both rows)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from tactcad.design.array import ClampPlateGeometry, SpacerGeometry
from tactcad.geometry.profile import Profile, rectangle_profile, u_plate_profile
from tactcad.kernel.shapes import extrude_profile

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid


def spacer_profile(s: SpacerGeometry) -> Profile:
    return rectangle_profile(s.length_mm, s.height_mm,
                             [(h.x_mm, h.y_mm, h.diameter_mm) for h in s.holes])


def build_spacer(s: SpacerGeometry) -> Solid:
    """Spacer in the element frame (same bolt holes as the element base), mm."""
    return extrude_profile(spacer_profile(s), s.thickness_mm)


def clamp_profile(c: ClampPlateGeometry) -> Profile:
    return u_plate_profile(c.half_length_mm, c.window_half_width_mm, c.height_mm,
                           c.bridge_height_mm, c.window_corner_radius_mm,
                           [(h.x_mm, h.y_mm, h.diameter_mm) for h in c.holes])


def build_clamp_plate(c: ClampPlateGeometry) -> Solid:
    """U-shaped clamp plate in the array frame (x, y), thickness along +z, mm."""
    return extrude_profile(clamp_profile(c), c.thickness_mm)
