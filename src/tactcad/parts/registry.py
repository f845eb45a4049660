"""Builds part solids on demand, once each, and counts the builds.

A scene asks for the parts it names; nothing else is built. The counter lets
tests prove it.
"""

from __future__ import annotations

from collections import Counter
from typing import Callable

import build123d as bd

from tactcad.catalogue.array import PartSpec
from tactcad.design.array import Placement, Plan
from tactcad.parts.element import build_element
from tactcad.parts.fasteners import build_bolt, build_nut
from tactcad.parts.plates import build_clamp_plate, build_spacer
from tactcad.parts.rig_registry import RIG_BUILDERS

BUILD_COUNTS: Counter[str] = Counter()  # part name -> times built in this process


def _element(plan: Plan, spec: PartSpec) -> bd.Solid:
    return build_element(plan.distinct_elements[spec.name])


BUILDERS: dict[str, Callable[[Plan, PartSpec], bd.Solid]] = {
    "element": _element,
    "spacer": lambda plan, spec: build_spacer(plan.spacer),
    "clamp_plate": lambda plan, spec: build_clamp_plate(plan.clamp),
    "bolt": lambda plan, spec: build_bolt(plan.bolt, plan.bolt_length_mm),
    "nut": lambda plan, spec: build_nut(plan.bolt),
}
BUILDERS.update(RIG_BUILDERS)  # rig parts (spec.geometry carries their dimensions)


class PartCache:
    """Solids of one plan's parts, built on first request."""

    def __init__(self, plan: Plan, specs: dict[str, PartSpec]):
        self.plan = plan
        self.specs = specs
        self._solids: dict[str, bd.Solid] = {}

    def solid(self, name: str) -> bd.Solid:
        if name not in self._solids:
            self._solids[name] = build_part(self.plan, self.specs[name])
        return self._solids[name]


def build_part(plan: Plan, spec: PartSpec) -> bd.Solid:
    """Build one part's solid and count the build in :data:`BUILD_COUNTS`."""
    solid = BUILDERS[spec.builder](plan, spec)
    BUILD_COUNTS[spec.name] += 1
    return solid


def location(p: Placement) -> bd.Location:
    """CAD location of a plan placement (turned = 180 degrees about y)."""
    return bd.Location((p.dx_mm, p.dy_mm, p.dz_mm), (0, 180 if p.turned else 0, 0))
