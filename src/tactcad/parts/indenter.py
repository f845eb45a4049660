"""Indenter of the force gauge: a cylindrical body seated on the gauge's shaft
end and a rectangular tip whose end face is the 2 mm x 3 mm contact area
(paper: the same contact area as a sensing element).

Part frame: contact face at z = 0 (centred), tip along +z, then the body;
the contact width lies along x, the depth along y. Dimensions:
:class:`tactcad.design.rigs.IndenterGeometry`.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import IndenterGeometry
from tactcad.catalogue.rigs import INDENTER_THREAD_DIAMETER_MM, indenter_thread_depth_mm
from tactcad.partlib.shapes import box, cylinder, fuse, single


def build_indenter(g: IndenterGeometry) -> bd.Solid:
    """Tip (contact face at z = 0) fused with the body above it, and the
    tapped M6 hole in the body's top face that screws it onto the gauge's
    shaft, modelled at the thread's nominal diameter (mm; see
    :func:`tactcad.catalogue.rigs.indenter_thread_depth_mm`)."""
    w, d, L = g.contact_width_mm, g.contact_depth_mm, g.tip_length_mm
    tip = box(-w / 2, -d / 2, 0, w / 2, d / 2, L)
    body = cylinder(g.body_diameter_mm / 2, (0, 0, L), (0, 0, 1), g.body_length_mm)
    depth = indenter_thread_depth_mm(g)
    top = L + g.body_length_mm
    thread = cylinder(INDENTER_THREAD_DIAMETER_MM / 2, (0, 0, top - depth), (0, 0, 1), depth)
    return single(fuse(tip, body).cut(thread))
