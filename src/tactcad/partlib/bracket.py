"""Array bracket (a made part): the L of aluminium that holds the array on
the XY stages (calibration) or hangs it from the hanger bar (array
evaluation). Its ear bolts to the front clamp plate through the clamp
plate's two bridge mounting holes (``plan.clamp.holes[-2:]``) with through
bolts of the array's size that also pass the back clamp plate; its foot
stands on a stage table or takes the hanger bar (the M3 screw through the
foot's hole is not modelled: the stage is an envelope without tapped holes).
The solder-terminal board sits on its foot (:mod:`tactcad.partlib.terminal_board`).

Part frame: the array frame shifted so that the origin lies on the ear's
inner face at the height of the clamp plate's two mounting holes: ear in
``-ear_thickness <= z <= 0``, foot below the array in ``-foot_length <= z <= 0``.
Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

from tactcad.partlib.base import DrawingRecord, Fastener, PartData, RigPart, Seat
from tactcad.kernel.shapes import box, cylinder, fuse, single
from tactcad.partlib.stock import PLATE_ALUMINIUM
from tactcad.partlib.array.clamp_fixes import clamp_fixes
from tactcad.errors import DesignError
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import LIMIT_TOLERANCE_MM, Derived, Problems, Section, fmt, number
from tactcad.vocabulary.standards import BoltSpec, shortest_stock_length

COLOR, BOLT_COLOR = (0.30, 0.35, 0.60), (0.11, 0.12, 0.16)
#: Clearance between the bracket's ear and the array's clamp bolt heads, mm.
EAR_HEAD_CLEARANCE_MM = 0.3
#: Bracket ear width when the rigs file gives none and the array leaves room, mm.
BRACKET_WIDTH_MM = 20.0
#: Ear height above the mounting holes when the rigs file gives none, mm
#: (lower when the clamp plate ends sooner).
EAR_TOP_MM = 4.0


class BracketSection(Section):
    """``[bracket]`` of ``rigs.toml``: the width and ear height may follow the array."""

    width_mm: Optional[number(5.0, 200.0)] = None  # default: follows the array's bolt pattern
    ear_thickness_mm: number(0.5, 20.0)
    ear_top_mm: Optional[number(1.0, 50.0)] = None  # default: 4 mm, lower on a short clamp plate
    foot_thickness_mm: number(1.0, 30.0)
    foot_length_mm: number(5.0, 200.0)
    foot_clearance_mm: number(0.3, 20.0)
    foot_hole_diameter_mm: number(1.0, 20.0)


@dataclass(frozen=True)
class BracketGeometry:
    """The bracket the builder reads (mm; part frame in the module doc)."""

    width_mm: float
    ear_thickness_mm: float
    ear_top_mm: float  # ear top above the mounting holes
    foot_thickness_mm: float
    foot_length_mm: float
    foot_top_mm: float  # foot's top face relative to the mounting holes (negative)
    foot_hole_diameter_mm: float
    hole_xs_mm: tuple[float, float]  # mounting holes (x), from the clamp plate
    hole_diameter_mm: float
    bolt: BoltSpec
    bolt_length_mm: float

    @property
    def foot_bottom_mm(self) -> float:
        return self.foot_top_mm - self.foot_thickness_mm


def bracket_width_range(plan) -> tuple[float, float]:
    """(narrowest, widest) bracket ear (mm) for the array's ``plan``: it carries
    both mounting holes and the bolt heads, and must clear the heads of the
    array's clamp bolts."""
    mount = plan.clamp.holes[-2:]
    b = plan.bolt
    lo = abs(mount[0].x_mm - mount[1].x_mm) + mount[0].diameter_mm + b.head_diameter_mm
    clamp_heads = min(abs(h.x_mm) for h in plan.clamp.holes[:4]) - b.head_diameter_mm / 2
    return lo, 2 * (clamp_heads - EAR_HEAD_CLEARANCE_MM)


def derive(br: BracketSection, context, p: Problems) -> PartData:
    """The bracket for the array's clamp plate (``context.plan``), its foot long
    enough for the hanger bar (``hanger_bar``). A design the bracket cannot
    fit is refused naming the design file's field."""
    plan, bar = context.plan, context.part("hanger_bar").geometry
    c = plan.clamp
    mount = c.holes[-2:]
    y_h = mount[0].y_mm
    b = plan.bolt
    lo, hi = bracket_width_range(plan)
    if br.width_mm is None:
        width = min(max(BRACKET_WIDTH_MM, lo), hi)
        if lo > hi + LIMIT_TOLERANCE_MM:  # the array leaves no room: name the design field
            p.add("clamp.bolt_spacing_mm", plan.raw["clamp"]["bolt_spacing_mm"],
                  "a pattern that leaves the bracket ear room between the clamp bolt heads",
                  f"the ear needs {fmt(lo)} mm between heads {fmt(hi)} mm apart",
                  file=Path(plan.source).name)
    else:
        width = p.within("bracket.width_mm", br.width_mm, lo, hi,
                         why="the ear must carry both mounting holes and the bolt heads, and clear "
                             "the heads of the array's clamp bolts")
    head_bottom = y_h - b.head_diameter_mm / 2  # array frame
    nut_bottom = y_h - b.nut_width_across_flats_mm / 2  # nuts sit flats up, as in the array
    foot_top = min(0.0, head_bottom, nut_bottom) - br.foot_clearance_mm - y_h
    grip = br.ear_thickness_mm + 2 * c.thickness_mm + plan.stack_length_mm
    needed = grip + b.nut_height_mm + 2 * b.thread_pitch_mm
    bolt_len = shortest_stock_length(b, needed)
    if bolt_len is None:  # the array's stack leaves no stock bolt for the ear: name the design
        bolt_len = max(b.catalogue_lengths_mm)
        # offer only the changes that pass this rule (with the ear) and the design's others
        allowed, alternatives = clamp_fixes(plan.raw, br.ear_thickness_mm)
        p.errors.append(DesignError(
            "array.columns", plan.columns, allowed,
            f"the bracket bolt through ear {fmt(br.ear_thickness_mm)} mm, both "
            f"clamp plates and the stack needs {fmt(needed)} mm, longest stock {b.size} is "
            f"{fmt(bolt_len)} mm", Path(plan.source).name, alternatives))
    bolt_derived = Derived("bracket_bolt_length", bolt_len, "mm",
                           f"shortest stock {b.size} through ear {fmt(br.ear_thickness_mm)}, both "
                           f"clamp plates and the stack (grip {fmt(grip)}) + nut + 2 thread pitches")
    top_lo, top_hi = mount[0].diameter_mm / 2 + 0.5, c.height_mm - y_h  # around the hole, on the plate
    ear_top = min(EAR_TOP_MM, top_hi) if br.ear_top_mm is None else \
        p.within("bracket.ear_top_mm", br.ear_top_mm, top_lo, top_hi,
                 why="the ear reaches around the mounting holes and stays on the clamp plate")
    p.within("bracket.foot_length_mm", br.foot_length_mm, br.ear_thickness_mm + bar.section_mm,
             lo_open=True)
    p.within("bracket.foot_hole_diameter_mm", br.foot_hole_diameter_mm, hi=width - 2.0)
    if br.foot_length_mm / 2 - br.foot_hole_diameter_mm / 2 < br.ear_thickness_mm + 0.5:
        p.add("bracket.foot_length_mm", br.foot_length_mm,
              f">= {fmt(2 * (br.ear_thickness_mm + 0.5) + br.foot_hole_diameter_mm)} mm",
              "the foot's centre hole must clear the ear")
    g = BracketGeometry(
        width_mm=width, ear_thickness_mm=br.ear_thickness_mm, ear_top_mm=ear_top,
        foot_thickness_mm=br.foot_thickness_mm, foot_length_mm=br.foot_length_mm,
        foot_top_mm=foot_top, foot_hole_diameter_mm=br.foot_hole_diameter_mm,
        hole_xs_mm=(mount[0].x_mm, mount[1].x_mm), hole_diameter_mm=mount[0].diameter_mm,
        bolt=b, bolt_length_mm=bolt_len)
    # a bolt as long as the array's own is the array's part (bolt_M2x30 ...), not listed again
    own = f"{bolt_len:g}" == f"{plan.bolt_length_mm:g}"
    return _data(g, bolt_derived, () if own else (Fastener(b, bolt_len, BOLT_COLOR),))


def _data(g: BracketGeometry, bolt_derived: Derived, fasteners: tuple[Fastener, ...]) -> PartData:
    w = g.width_mm
    vol = w * (g.ear_thickness_mm * (g.ear_top_mm - g.foot_bottom_mm)
               + (g.foot_length_mm - g.ear_thickness_mm) * g.foot_thickness_mm)
    vol -= 2 * math.pi * (g.hole_diameter_mm / 2) ** 2 * g.ear_thickness_mm
    vol -= math.pi * (g.foot_hole_diameter_mm / 2) ** 2 * g.foot_thickness_mm
    frames = {"array_mount": Seat((0, 0, 0), (0, 0, 1), (1, 0, 0)),
              "foot": Seat((0, g.foot_bottom_mm, -g.foot_length_mm / 2), (0, -1, 0), (0, 0, 1))}
    for n, x in enumerate(g.hole_xs_mm, start=1):
        frames[f"bolt_{n}"] = Seat((x, 0, -g.ear_thickness_mm), (0, 0, -1), (1, 0, 0))
    return PartData(
        name="array_bracket", kind="fabricated", process=Process("milling from plate", Method.PLATE),
        material=PLATE_ALUMINIUM, color=COLOR, expected_volume_mm3=vol,
        expected_bbox_mm=(-w / 2, float(g.foot_bottom_mm), -float(g.foot_length_mm), w / 2,
                          float(g.ear_top_mm), 0.0),
        geometry=g, frames=frames, derived=(bolt_derived,), fasteners=fasteners)


def build(g: BracketGeometry):
    """L bracket (build123d ``Solid``) with two through-bolt holes in the ear and
    one screw hole in the foot."""
    w = g.width_mm
    ear = box(-w / 2, g.foot_bottom_mm, -g.ear_thickness_mm, w / 2, g.ear_top_mm, 0)
    foot = box(-w / 2, g.foot_bottom_mm, -g.foot_length_mm, w / 2, g.foot_top_mm, 0)
    body = fuse(ear, foot)
    holes = [cylinder(g.hole_diameter_mm / 2, (x, 0, -g.ear_thickness_mm), (0, 0, 1),
                      g.ear_thickness_mm) for x in g.hole_xs_mm]
    holes.append(cylinder(g.foot_hole_diameter_mm / 2, (0, g.foot_bottom_mm, -g.foot_length_mm / 2),
                          (0, 1, 0), g.foot_thickness_mm))
    return single(body.cut(*holes))


def dimensions(d, solid, pen) -> None:
    """The shop drawing's dimension set (drawn with the drawings layer's
    ``pen``; views from :func:`tactcad.drawings.views.orientation`: front from
    +y with u = z, v = x; from above u = z, v = -y; from the left u = y,
    v = x): the general set (outline, foot hole), the L section's ear and foot
    thicknesses and ear height in the view from above, the ear's two through
    holes in the view from the left."""
    g, fmt_mm = d.spec.geometry, pen.fmt_mm
    pen.generic_dims(d, solid)
    t, lv = d.views["top"], d.views["left"]
    fb_, ft = g.foot_bottom_mm, g.foot_top_mm
    pen.dim(d, t, (-g.ear_thickness_mm, -g.ear_top_mm), (0.0, -g.ear_top_mm), "h", "top", 0,
            fmt_mm(g.ear_thickness_mm), "ear_thickness")
    pen.dim(d, t, (-g.foot_length_mm, -ft), (-g.foot_length_mm, -fb_), "v", "left", 0,
            fmt_mm(g.foot_thickness_mm), "foot_thickness")
    xs = sorted(g.hole_xs_mm)
    holes = [pen.Hole2D(0.0, x, g.hole_diameter_mm) for x in xs]
    pen.hole_marks(d, lv, holes)
    pen.dim(d, lv, (fb_, xs[0]), (0.0, xs[0]), "h", "below", 0, fmt_mm(-fb_), "ear_hole_height")
    pen.dim(d, lv, (0.0, -g.width_mm / 2), (0.0, xs[0]), "v", "right", 0,
            fmt_mm(xs[0] + g.width_mm / 2), "ear_hole_1_x")
    if len(xs) > 1:
        pen.dim(d, lv, (0.0, xs[0]), (0.0, xs[1]), "v", "right", 1, fmt_mm(xs[1] - xs[0]),
                "ear_hole_spacing")
    lb = lv.paper_box()
    text = f"{len(xs)}× Ø{fmt_mm(g.hole_diameter_mm)} {holes[0].depth_text}"
    d.sheet.leader([lv.paper(g.hole_diameter_mm / 2 * 0.7, xs[-1] + g.hole_diameter_mm / 2 * 0.7),
                    (lb[2] + 4.0, lb[1] - 6.0)], text, "ear_holes")
    d.dimensions["ear_holes"] = text


PART = RigPart(key="bracket", section=BracketSection, host="", derive=derive, build=build,
               needs=("hanger_bar",), order=120, builder="array_bracket",
               drawing=DrawingRecord(dimensions=dimensions))
