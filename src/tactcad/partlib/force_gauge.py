"""Digital force gauge on the Z axis's carriage (a bought part, modelled as
its housing envelope with the measuring shaft): it carries the indenter and
reads the force in the calibration and sample-stiffness rigs (the paper's
Sauter FH 5; a new design's from the catalogue ``tactcad/data/force_gauges.toml``,
chosen by :mod:`tactcad.studies.rig_sizing`; sources in ``hardware/purchased-parts.md``).

Part frame: housing x = +-width/2 (across), y = 0 ... depth (y = 0: back face
on the Z carriage), z = 0 ... length (lower end at z = 0); the shaft along
-z from the lower end's centre. Units: mm, N, N/mm.
"""

from __future__ import annotations

import math
from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box, cylinder, fuse
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, Text, fmt, number

COLOR = (0.90, 0.90, 0.88)


class ForceGaugeSection(Section):
    """``[force_gauge]`` of ``rigs.toml``."""

    model: Text
    range_N: number(0.1, 1e5, unit="N")
    resolution_N: number(1e-6, 10.0, unit="N")
    stiffness_N_per_mm: number(0.1, 1e6, unit="N/mm")
    length_mm: number(20.0, 500.0)
    width_mm: number(10.0, 300.0)
    depth_mm: number(10.0, 300.0)
    shaft_diameter_mm: number(1.0, 30.0)
    shaft_length_mm: number(1.0, 100.0)
    mount_height_mm: number(0.0, 500.0)


class ForceGaugeSpec(table_values(ForceGaugeSection)):
    """The gauge's data and envelope as its table gives them (N, N/mm, mm)."""


def derive(g: ForceGaugeSection, context, p: Problems) -> PartData:
    """The gauge, its shaft carrying the indenter (``indenter``)."""
    indenter = context.part("indenter").geometry
    p.within("force_gauge.mount_height_mm", g.mount_height_mm, hi=g.length_mm)
    if g.shaft_diameter_mm > indenter.body_diameter_mm:
        p.add("force_gauge.shaft_diameter_mm", g.shaft_diameter_mm,
              f"<= indenter.body_diameter_mm = {fmt(indenter.body_diameter_mm)} mm")
    s = values_from(ForceGaugeSpec, g)
    rs = s.shaft_diameter_mm / 2
    return PartData(
        name="force_gauge", kind="purchased",
        process=Process(f"{s.model} digital force gauge, {s.range_N:g} N range, "
                        f"{s.resolution_N:g} N resolution (housing envelope)", Method.BOUGHT),
        material="housing", color=COLOR,
        expected_volume_mm3=s.width_mm * s.depth_mm * s.length_mm
        + math.pi * rs * rs * s.shaft_length_mm,
        expected_bbox_mm=(-s.width_mm / 2, 0.0, -s.shaft_length_mm, s.width_mm / 2, s.depth_mm,
                          s.length_mm),
        geometry=s, attributes={"stiffness_N_per_mm": s.stiffness_N_per_mm, "range_N": s.range_N,
                                "resolution_N": s.resolution_N},
        frames={"back": Seat((0, 0, s.mount_height_mm), (0, -1, 0), (0, 0, 1)),
                "shaft_end": Seat((0, s.depth_mm / 2, -s.shaft_length_mm), (0, 0, -1), (1, 0, 0))})


def build(g: ForceGaugeSpec):
    """Housing box and shaft (build123d ``Solid``) in the part frame."""
    housing = box(-g.width_mm / 2, 0, 0, g.width_mm / 2, g.depth_mm, g.length_mm)
    shaft = cylinder(g.shaft_diameter_mm / 2, (0, g.depth_mm / 2, -g.shaft_length_mm), (0, 0, 1),
                     g.shaft_length_mm)
    return fuse(housing, shaft)


PART = RigPart(key="force_gauge", section=ForceGaugeSection, host="", derive=derive, build=build,
               needs=("indenter",), order=60)
