"""Bought parts as simplified envelopes with catalogue dimensions.

Each builder returns one solid in the part's own frame; the catalogue
reference is the part's ``process`` (:mod:`tactcad.catalogue.rigs`) and the
sources are listed in ``hardware/purchased-parts.md``:

* Z axis with micrometer head: fixed body with the micrometer on top, and
  the moving carriage (documented envelope; the paper gives no model).
* XY micro-stages: two single-axis stages crossed, each a fixed base and a
  moving table (documented envelope).
* Vertical linear axis: HIWIN MGNR12R rail and MGN12H block (HIWIN catalogue
  dimensions W_R, H_R, W, L, H, H1).
* Ball bearing: ISO 15 boundary dimensions d x D x B as an annulus.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import BearingSpec, LinearAxisSpec, XYStageSpec, ZAxisSpec
from tactcad.partlib.shapes import box, cylinder, fuse, ring, single


def build_z_body(z: ZAxisSpec) -> bd.Solid:
    """Fixed body: y = -depth (back, on the column) ... 0 (front, the carriage
    slides on it), z = 0 ... height; micrometer head standing on the top."""
    body = box(-z.body_width_mm / 2, -z.body_depth_mm, 0, z.body_width_mm / 2, 0, z.body_height_mm)
    head = cylinder(z.micrometer_diameter_mm / 2, (0, -z.body_depth_mm / 2, z.body_height_mm),
                    (0, 0, 1), z.micrometer_length_mm)
    return fuse(body, head)


def build_z_carriage(z: ZAxisSpec) -> bd.Solid:
    """Moving carriage: y = 0 (on the body) ... thickness, centred in x and z."""
    return box(-z.body_width_mm / 2, 0, -z.carriage_height_mm / 2, z.body_width_mm / 2,
               z.carriage_thickness_mm, z.carriage_height_mm / 2)


def build_stage_base(s: XYStageSpec) -> bd.Solid:
    """Fixed part of a single-axis micro-stage, z = 0 ... base height."""
    a = s.size_mm / 2
    return box(-a, -a, 0, a, a, s.base_height_mm)


def build_stage_table(s: XYStageSpec) -> bd.Solid:
    """Moving table of a single-axis micro-stage, z = 0 ... table height."""
    a = s.size_mm / 2
    return box(-a, -a, 0, a, a, s.table_height_mm)


def build_rail(a: LinearAxisSpec) -> bd.Solid:
    """Guide rail: x = 0 ... length, y across, z = 0 (mounting face) ... rail height."""
    return box(0, -a.rail_width_mm / 2, 0, a.rail_length_mm, a.rail_width_mm / 2, a.rail_height_mm)


def build_block(a: LinearAxisSpec) -> bd.Solid:
    """Carriage block around the rail: z = H1 ... H above the rail's mounting
    face, with the channel the rail runs in (up to the rail's top)."""
    L, W = a.block_length_mm, a.block_width_mm
    block = box(-L / 2, -W / 2, a.block_clearance_mm, L / 2, W / 2, a.block_height_mm)
    channel = box(-L / 2, -a.rail_width_mm / 2, a.block_clearance_mm, L / 2, a.rail_width_mm / 2,
                  a.rail_height_mm)
    return single(block.cut(channel))


def build_bearing(b: BearingSpec) -> bd.Solid:
    """Deep groove ball bearing envelope: annulus d ... D, z = 0 ... B."""
    return ring(b.bore_mm / 2, b.outer_diameter_mm / 2, b.width_mm)
