"""Stacked weights on the axis carrier's shelf (bought parts): they load the
array in the array-evaluation rig (the paper's 100 g steel weights; a new design's
sized to its rating by :mod:`tactcad.studies.rig_sizing`).

Each weight is modelled as a steel cylinder of the given mass and density
and diameter; its height follows. The rig stacks ``count`` of them on the
carrier's shelf (:mod:`tactcad.assembly.rig_models`). Part frame: axis z, z = 0 on
the underside, centred in x and y. Units: mm, g, g/cm^3.
"""

from __future__ import annotations

import math
from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import cylinder
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, fmt, integer, name_number, number

COLOR = (0.36, 0.38, 0.40)


class WeightsSection(Section):
    """``[weights]`` of ``rigs.toml``."""

    mass_g: number(0.001, 10000.0, unit="g",
                   why="OIML R 111 nominal masses start at 1 mg; a rig for a design rated at "
                       "centinewtons takes sub-gram weights")
    density_g_per_cm3: number(0.5, 25.0, unit="g/cm3")
    diameter_mm: number(5.0, 200.0)
    count: integer(0, 20)


class WeightSpec(table_values(WeightsSection, height_mm=float)):
    """One weight (mm, g, g/cm^3), how many the rig stacks and its height."""

    @property
    def volume_mm3(self) -> float:
        return self.mass_g / self.density_g_per_cm3 * 1000.0


def derive(w: WeightsSection, context, p: Problems) -> PartData:
    """The weight on the carrier's shelf (``carrier``)."""
    carrier = context.part("carrier").geometry
    p.within("weights.diameter_mm", w.diameter_mm,
             hi=min(carrier.width_mm, 2 * (carrier.shelf_depth_mm - carrier.thickness_mm)),
             why="the weights stand on the carrier's shelf")
    height = w.mass_g / w.density_g_per_cm3 * 1000.0 / (math.pi * (w.diameter_mm / 2) ** 2)
    g = values_from(WeightSpec, w, height_mm=height)
    r = g.diameter_mm / 2
    return PartData(
        name=f"weight_{name_number(g.mass_g)}g", kind="purchased",
        process=Process(f"{g.mass_g:g} g steel weight (cylinder of {g.volume_mm3:.0f} mm3 at "
                        f"{g.density_g_per_cm3:g} g/cm3)", Method.BOUGHT),
        material="steel", color=COLOR, expected_volume_mm3=g.volume_mm3,
        expected_bbox_mm=(-r, -r, 0.0, r, r, float(height)), geometry=g,
        derived=(Derived("weight_height", height, "mm",
                         f"{fmt(w.mass_g)} g of density {fmt(w.density_g_per_cm3)} g/cm3 as a "
                         f"cylinder of diameter {fmt(w.diameter_mm)} mm"),),
        attributes={"mass_g": g.mass_g},
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, height), (0, 0, 1), (1, 0, 0))})


def build(w: WeightSpec):
    """Steel cylinder (build123d ``Solid``), axis z, z = 0 ... height."""
    return cylinder(w.diameter_mm / 2, (0, 0, 0), (0, 0, 1), w.height_mm)


PART = RigPart(key="weights", section=WeightsSection, host="", derive=derive, build=build,
               needs=("carrier",), order=130, builder="weight")
