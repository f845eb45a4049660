"""Flexure sensing element: the wire-cut profile extruded by the sheet thickness.

Also holds the profile -> face -> prism helpers the other plate parts share."""

from __future__ import annotations

import build123d as bd

from tactcad.design.array import ElementGeometry
from tactcad.geometry.profile import Arc, Circle, Profile, element_profile


def _edges(profile_segments) -> list[bd.Edge]:
    edges = []
    for s in profile_segments:
        if isinstance(s, Arc):
            edges.append(bd.Edge.make_three_point_arc(bd.Vector(*s.start), bd.Vector(*s.midpoint),
                                                      bd.Vector(*s.end)))
        else:
            edges.append(bd.Edge.make_line(bd.Vector(*s.start), bd.Vector(*s.end)))
    return edges


def _circle_wire(c: Circle) -> bd.Wire:
    return bd.Wire([bd.Edge.make_circle(c.radius, bd.Plane.XY.shift_origin((c.centre[0], c.centre[1], 0)))])


def profile_face(profile: Profile) -> bd.Face:
    """The planar face (z = 0) bounded by the profile's outer contour, minus its holes."""
    return bd.Face(bd.Wire(_edges(profile.outer)), [_circle_wire(c) for c in profile.holes])


def extrude_profile(profile: Profile, thickness_mm: float) -> bd.Solid:
    """Prism of a planar profile: the face at z = 0 extruded along +z (mm)."""
    return bd.Solid.extrude(profile_face(profile), bd.Vector(0, 0, thickness_mm))


def build_element(g: ElementGeometry) -> bd.Solid:
    """Solid of one element (element frame, mm): the wire-cut profile extruded
    along +z by the sheet thickness."""
    return extrude_profile(element_profile(g), g.sheet_thickness_mm)
