"""Solder-terminal board on the array bracket's foot (a made part): the
strain gauges' connection wires are soldered to it, one pair of plated
terminal holes per element (a quarter bridge gauge has two leads), and the
cable to the bridge amplifier leaves from it.

An FR4 board bonded with double-sided tape to the top face of the bracket's
foot, at the foot's rear end (clear of the bolt heads on the ear and of the
screw through the foot's centre hole), so the bracket needs no change. The
pairs run along the bracket's width in element order; the board may overhang
the foot's sides. Part frame: x along the row of pairs, y across a pair,
z up from the underside, centred in x and y. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.kernel.shapes import centred_box, centred_cylinder, difference
from tactcad.partlib.base import BuildStep, DrawingRecord, PartData, RigPart, Seat
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, Text, fmt, number

COLOR = (0.10, 0.45, 0.22)  # solder-mask green; distinct from every rig part
ANNULAR_RING_MM = 0.25  # least copper around a terminal hole (IPC-2221 class 2 order)


class TerminalBoardSection(Section):
    """``[terminal_board]`` of ``rigs.toml`` (every field has its default)."""

    material: Text = "FR4 glass epoxy laminate, 35 um copper both sides"
    thickness_mm: number(0.4, 3.2) = 1.6
    hole_diameter_mm: number(0.5, 2.0) = 1.0
    pitch_mm: number(1.27, 10.0) = 2.54
    edge_margin_mm: number(0.5, 10.0) = 2.0
    rear_margin_mm: number(0.0, 20.0) = 1.0


@dataclass(frozen=True)
class BoardGeometry:
    """The board the builder reads (mm): outline, thickness and the terminal holes."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    hole_diameter_mm: float
    hole_xs_mm: tuple[float, ...]  # one pair per element, element order
    hole_ys_mm: tuple[float, float]  # the two leads of a pair


def derive(s: TerminalBoardSection, context, p: Problems) -> PartData:
    """The board for the array's elements (``context.plan.slots``) on the
    bracket's foot (``bracket``)."""
    br = context.part("bracket").geometry
    pairs = len(context.plan.slots)
    p.within("terminal_board.pitch_mm", s.pitch_mm, s.hole_diameter_mm + 2 * ANNULAR_RING_MM + 0.2,
             why=f"a {fmt(ANNULAR_RING_MM)} mm copper ring around each hole and 0.2 mm between pads")
    p.within("terminal_board.edge_margin_mm", s.edge_margin_mm,
             s.hole_diameter_mm / 2 + ANNULAR_RING_MM + 0.3,
             why="the pads stay 0.3 mm inside the board's edge")
    length = (pairs - 1) * s.pitch_mm + 2 * s.edge_margin_mm
    width = s.pitch_mm + 2 * s.edge_margin_mm
    # the foot's rear part, behind the screw through its centre hole (a head ~1.6 d wide)
    room = br.foot_length_mm / 2 - br.foot_hole_diameter_mm
    p.within("terminal_board.rear_margin_mm", s.rear_margin_mm, hi=room - width,
             why=f"the {fmt(width)} mm wide board stays on the foot's rear "
                 f"{fmt(room)} mm, clear of the screw through the foot (bracket.foot_length_mm)")
    g = BoardGeometry(length, width, s.thickness_mm, s.hole_diameter_mm,
                      tuple((k - (pairs - 1) / 2) * s.pitch_mm for k in range(pairs)),
                      (-s.pitch_mm / 2, s.pitch_mm / 2))
    hole = math.pi * (s.hole_diameter_mm / 2) ** 2 * s.thickness_mm
    z_centre = -br.foot_length_mm + s.rear_margin_mm + width / 2  # bracket frame
    return PartData(
        name="terminal_board", kind="fabricated",
        process=Process(f"FR4 board {fmt(s.thickness_mm)} mm, {2 * pairs} plated terminal holes, "
                        "routed outline", Method.SHEET),
        material=s.material, color=COLOR,
        expected_volume_mm3=length * width * s.thickness_mm - 2 * pairs * hole,
        expected_bbox_mm=(-length / 2, -width / 2, 0.0, length / 2, width / 2, s.thickness_mm),
        geometry=g,
        seat=Seat((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0)),
        host_seat=Seat((0.0, br.foot_top_mm, z_centre), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)),
        derived=(Derived("terminal_board_length", length, "mm",
                         f"{pairs} pairs of terminal holes at {fmt(s.pitch_mm)} mm pitch + "
                         f"{fmt(s.edge_margin_mm)} mm at each end"),),
        attributes={"terminal_pairs": pairs})


def build(g: BoardGeometry):
    """The board (a kernel ``Solid``) in the part frame."""
    board = centred_box(g.length_mm, g.width_mm, g.thickness_mm)
    holes = [centred_cylinder(g.hole_diameter_mm / 2, g.thickness_mm, at=(x, y))
             for x in g.hole_xs_mm for y in g.hole_ys_mm]
    return difference(board, holes)


def wiring_notes(book) -> tuple[str, ...]:
    """Element k's quarter bridge on terminal pair k (three-wire connection,
    Micro-Measurements instruction bulletin B-129 for the soldering)."""
    return tuple(f"Element {k}: gauge leads to terminals {2 * k - 1} and {2 * k}; a third lead "
                 f"from terminal {2 * k} carries the sense line (three-wire quarter bridge), the "
                 "three completion resistors sit at the amplifier end."
                 for k in range(1, min(book.elements, book.terminal_pairs) + 1)) + (
        "Solder at the lowest iron temperature that wets (about 300 degC); check each bridge "
        "arm reads the gauge's resistance before closing the clamp.",)


PART = RigPart(
    key="terminal_board", section=TerminalBoardSection, host="array_bracket", derive=derive,
    build=build, needs=("bracket",),
    drawing=DrawingRecord(notes=(
        "Terminal holes plated through, each with a round pad 0.5 mm larger than the hole on both "
        "sides; HASL finish.",
        "One pair of holes per element, element 1 at the left: the strain gauge's two leads are "
        "soldered into its pair.",
        "Bonded to the bracket's foot with double-sided adhesive tape.")),
    assembly=BuildStep("array-wiring", "Wire the quarter bridges through the terminal board",
                       tools=lambda book: ("temperature-controlled soldering iron", "multimeter"),
                       notes=wiring_notes))
