"""Sample holder (a made part): the frame screwed onto the cart's top that
locates the rubber sample over the vacuum pocket; its window is the sample
plus a clearance, with milled corners, and two socket head cap screws
mid-wall beside the window fix it (the cart checks the screws and the frame
against its own features).

Part frame: centred in x and y, z = 0 on its underside; the two screw
clearance holes on the y axis. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.partlib.base import DrawingRecord, Fastener, PartData, RigPart, Seat
from tactcad.partlib.screws import stock_length
from tactcad.kernel.shapes import box, cylinder, extrude, rounded_rect_face, single
from tactcad.partlib.stock import PLATE_ALUMINIUM
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, choice, fmt, number
from tactcad.vocabulary.standards import RIG_BOLTS, BoltSpec

COLOR, BOLT_COLOR = (0.35, 0.55, 0.45), (0.14, 0.13, 0.12)


class SampleHolderSection(Section):
    """``[sample_holder]`` of ``rigs.toml``."""

    thickness_mm: number(1.0, 50.0)
    wall_mm: number(2.0, 50.0)
    clearance_mm: number(0.05, 5.0)
    corner_radius_mm: number(0.1, 10.0)
    screw_size: choice(RIG_BOLTS, "ISO 4762 socket head cap screws of the catalogue")
    tapped_depth_mm: number(2.0, 40.0)


@dataclass(frozen=True)
class SampleHolderGeometry:
    """Frame around the sample: window = sample + clearance, two screw holes (mm)."""

    window_length_mm: float
    window_width_mm: float
    outer_length_mm: float
    outer_width_mm: float
    thickness_mm: float
    corner_radius_mm: float
    screw: BoltSpec
    screw_length_mm: float
    screw_y_mm: float


def derive(h: SampleHolderSection, context, p: Problems) -> PartData:
    """The holder around the sample (``sample``)."""
    s = context.part("sample").geometry
    p.within("sample_holder.thickness_mm", h.thickness_mm, hi=s.height_mm, hi_open=True,
             why="the sample must stand proud of its holder")
    p.within("sample_holder.corner_radius_mm", h.corner_radius_mm,
             hi=h.clearance_mm * (2 + math.sqrt(2)),
             why="the window's corner arc must clear the sample's sharp corner")
    screw = RIG_BOLTS[h.screw_size]
    if h.wall_mm < screw.head_diameter_mm + 1.0:
        p.add("sample_holder.wall_mm", h.wall_mm, f">= {fmt(screw.head_diameter_mm + 1.0)} mm",
              f"the {h.screw_size} head must sit on the wall")
    screw_len = stock_length(screw, h.thickness_mm + 1.5 * screw.nominal_diameter_mm,
                             "sample_holder.thickness_mm", h.thickness_mm, p)
    if screw_len - h.thickness_mm > h.tapped_depth_mm - 0.5:
        p.add("sample_holder.tapped_depth_mm", h.tapped_depth_mm,
              f">= {fmt(screw_len - h.thickness_mm + 0.5)} mm",
              f"the {h.screw_size} x {screw_len:g} holder screw needs the thread depth")
    win_l, win_w = s.length_mm + 2 * h.clearance_mm, s.width_mm + 2 * h.clearance_mm
    screw_y = win_w / 2 + h.wall_mm / 2  # mid-wall beside the window
    g = SampleHolderGeometry(win_l, win_w, win_l + 2 * h.wall_mm, win_w + 2 * h.wall_mm,
                             h.thickness_mm, h.corner_radius_mm, screw, screw_len, screw_y)
    window = g.window_length_mm * g.window_width_mm - (4 - math.pi) * g.corner_radius_mm ** 2
    holes = 2 * math.pi * (g.screw.clearance_hole_mm / 2) ** 2
    return PartData(
        name="sample_holder", kind="fabricated", process=Process("milling from plate", Method.PLATE),
        material=PLATE_ALUMINIUM, color=COLOR,
        expected_volume_mm3=(g.outer_length_mm * g.outer_width_mm - window - holes) * g.thickness_mm,
        expected_bbox_mm=(-g.outer_length_mm / 2, -g.outer_width_mm / 2, 0.0,
                          g.outer_length_mm / 2, g.outer_width_mm / 2, float(g.thickness_mm)),
        geometry=g,
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                **{f"screw_{i}": Seat((0, sy * g.screw_y_mm, g.thickness_mm), (0, 0, 1), (1, 0, 0))
                   for i, sy in ((1, -1), (2, 1))}},
        derived=(Derived("sample_holder_screw_length", screw_len, "mm",
                         f"shortest stock {h.screw_size} >= holder {fmt(h.thickness_mm)} + 1.5 d "
                         "of thread"),),
        fasteners=(Fastener(screw, screw_len, BOLT_COLOR),))


def build(g: SampleHolderGeometry):
    """Frame plate with a rounded-corner window and two screw clearance holes
    (a kernel ``Solid``)."""
    t = g.thickness_mm
    plate = box(-g.outer_length_mm / 2, -g.outer_width_mm / 2, 0, g.outer_length_mm / 2,
                g.outer_width_mm / 2, t)
    window = extrude(rounded_rect_face(g.window_length_mm, g.window_width_mm, g.corner_radius_mm),
                     t)
    holes = [cylinder(g.screw.clearance_hole_mm / 2, (0, s * g.screw_y_mm, 0), (0, 0, 1), t)
             for s in (-1, 1)]
    return single(plate.cut(window, *holes))


def dimensions(d, solid, pen) -> None:
    """The shop drawing's dimension set (drawn with the drawings layer's
    ``pen``): the general set plus the window (length, width, corner radius)."""
    g = d.spec.geometry
    f = d.front
    wl, ww = g.window_length_mm, g.window_width_mm
    pen.dim(d, f, (-wl / 2, ww / 2), (wl / 2, ww / 2), "h", "top", 0, pen.fmt_mm(wl),
            "window_length")
    pen.dim(d, f, (wl / 2, -ww / 2), (wl / 2, ww / 2), "v", "right", 0, pen.fmt_mm(ww),
            "window_width")
    pen.generic_dims(d, solid, top_k=1, right_k=1)
    r = g.corner_radius_mm
    text = f"window through, 4× R{pen.fmt_mm(r)}"
    c = (wl / 2 - r + r * 0.7, -ww / 2 + r - r * 0.7)
    fb = f.paper_box()
    d.sheet.leader([f.paper(*c), (fb[2] - 6.0, fb[3] + pen.FIRST_TIER + 2 * pen.TIER + 4.0)], text,
                   "window_corner")
    d.dimensions["window_corner"] = text


PART = RigPart(key="sample_holder", section=SampleHolderSection, host="", derive=derive,
               build=build, needs=("sample",), order=30,
               drawing=DrawingRecord(dimensions=dimensions))
