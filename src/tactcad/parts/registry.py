"""Every part family's builder, keyed by :attr:`PartSpec.builder`, and the one
place where a solid is built (and counted, so tests can prove that a scene
builds only its own parts and a run builds each part once)."""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING, Callable

from tactcad.catalogue.array import PartSpec
from tactcad.design.array import Plan
from tactcad.partlib.registry import rig_parts_lib
from tactcad.parts.element import build_element
from tactcad.parts.fasteners import build_bolt, build_nut
from tactcad.parts.gauge import build_gauge
from tactcad.parts.plates import build_clamp_plate, build_spacer

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

BUILD_COUNTS: Counter[str] = Counter()  # part name -> times built in this process

Builder = Callable[[Plan, PartSpec], "Solid"]

#: builder key -> builder(plan, spec) of the part families of this package.
#: Every part carries its dimensions in ``spec.geometry``; none reads the plan.
FAMILY_BUILDERS: dict[str, Builder] = {
    "element": lambda plan, spec: build_element(spec.geometry),
    "spacer": lambda plan, spec: build_spacer(spec.geometry),
    "clamp_plate": lambda plan, spec: build_clamp_plate(spec.geometry),
    "bolt": lambda plan, spec: build_bolt(*spec.geometry),
    "nut": lambda plan, spec: build_nut(spec.geometry),
    "gauge": lambda plan, spec: build_gauge(spec.geometry),
    "rig_bolt": lambda plan, spec: build_bolt(*spec.geometry),
}


def _all_builders() -> dict[str, Builder]:
    """:data:`FAMILY_BUILDERS` and the part modules of :mod:`tactcad.partlib`
    (each builds itself) under their keys.

    Raises:
        ValueError: a part module's key is also a family's key.
    """
    library = {key: build for part in rig_parts_lib().values()
               for key, build in part.builders().items()}
    clash = sorted(set(library) & set(FAMILY_BUILDERS))
    if clash:
        raise ValueError(f"part module builder key(s) {', '.join(clash)} already name a builder "
                         "of tactcad.parts: choose another key")
    return {**FAMILY_BUILDERS, **{key: (lambda plan, spec, build=build: build(spec.geometry))
                                  for key, build in library.items()}}


#: builder key -> builder(plan, spec), every part's.
BUILDERS: dict[str, Builder] = _all_builders()


def build_part(plan: Plan, spec: PartSpec) -> Solid:
    """Build one part's solid (part frame, mm) and count the build in :data:`BUILD_COUNTS`.

    Raises:
        KeyError: the spec names no known builder (a catalogue error).
    """
    solid = BUILDERS[spec.builder](plan, spec)
    BUILD_COUNTS[spec.name] += 1
    return solid
