"""What each rig part is, without building it: name, kind, process (for a
bought part its catalogue reference), colour, expected volume and bounding
box (independent estimates from elementary formulas), its joint frames, and
attributes such as a rubber sample's measured stiffness. No CAD kernel here.

Every rig part is written as one module of :mod:`tactcad.partlib`, which
derives these data (:class:`~tactcad.partlib.base.PartData`, part frames in
each module's doc); this module turns them into specs, with the socket head
cap screws the parts are fixed with.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Mapping

from tactcad.catalogue.array_catalogue import RGB, PartSpec, bolt_name
from tactcad.design.array_plan import BoltSpec, Plan
from tactcad.design.rig_plan import RigDesign
from tactcad.geometry.frames import Frame, face
from tactcad.partlib.array.fasteners import screw_data
from tactcad.partlib.base import PartData, Seat
from tactcad.partlib.registry import rig_parts_lib


@dataclass(frozen=True)
class RigPartSpec(PartSpec):
    """A rig part: a :class:`~tactcad.catalogue.array_catalogue.PartSpec` plus what scenes need.

    Attributes:
        geometry: the frozen rig dataclass the builder reads (in the part's
            stable text: nothing else of the spec fixes the solid).
        frames: joint frames in the part's frame (see :mod:`tactcad.geometry.frames`).
        attributes: data carried with the part into manifest and GLB (e.g.
            ``stiffness_N_per_mm`` of a rubber sample).
    """

    geometry: Any = None
    frames: Mapping[str, Frame] = field(default_factory=dict)
    attributes: Mapping[str, Any] = field(default_factory=dict)


def level_of(spec: PartSpec) -> str:
    """The level of detail a part is modelled at: bought parts as catalogue
    envelopes, fabricated parts in full."""
    return "envelope" if spec.kind == "purchased" else "full"


def _bolt_spec(b: BoltSpec, length_mm: float, color: RGB) -> RigPartSpec:
    """A rig part's screw: the array's socket head cap screw
    (:func:`tactcad.partlib.array.fasteners.screw_data`) under the builder
    ``rig_bolt``, with its seat frame."""
    return replace(library_spec(screw_data(b, length_mm, color, "rig_bolt"), ""),
                   frames=bolt_frames())


def rig_parts(plan: Plan, rigs: RigDesign) -> dict[str, RigPartSpec]:
    """Every distinct rig part, keyed by part name: each part module's part and
    companions (all the rubber samples ...), then the screws it is fixed with
    unless a part before has the same screw (which keeps its colour; distinct
    colours keep the STEP writer's colour records in a fixed order)."""
    parts: dict[str, RigPartSpec] = {}
    for key, part in rig_parts_lib().items():
        data = rigs.library[key]
        for one in (data, *data.companions):
            parts[one.name] = library_spec(one, part.builder_key)
        for f in data.fasteners:
            name = bolt_name(f.bolt, f.length_mm)
            if name not in parts:
                parts[name] = _bolt_spec(f.bolt, f.length_mm, f.color)
    return parts


def library_spec(data: PartData, builder: str) -> RigPartSpec:
    """The spec of a part written as one module (:mod:`tactcad.partlib`) or of
    one of its companions: its data, built by its module (builder
    :attr:`PartData.builder`, else ``builder``, the module's
    :attr:`RigPart.builder_key`), joint frames ``seat`` (when it has one) and
    its named frames."""
    frames = {"seat": seat_frame(data.seat)} if data.seat is not None else {}
    frames |= {name: seat_frame(seat) for name, seat in data.frames.items()}
    return RigPartSpec(
        name=data.name, kind=data.kind, process=data.process, material=data.material,
        color=data.color, builder=data.builder or builder,
        expected_volume_mm3=data.expected_volume_mm3,
        expected_bbox_mm=data.expected_bbox_mm, geometry=data.geometry, frames=frames,
        attributes=data.attributes)


def seat_frame(seat: Seat) -> Frame:
    """A part module's seat as a joint frame."""
    return face(seat.origin, seat.normal, seat.x_dir)


def nut_frames() -> dict[str, Frame]:
    """Joint frames of the ISO 4032 nut of :func:`tactcad.partlib.array.fasteners.build_nut`."""
    return {"seat": face((0, 0, 0), (0, 0, -1), (1, 0, 0))}


def bolt_frames() -> dict[str, Frame]:
    """Joint frames of a socket head cap screw (head underside at z = 0, shank
    along +z: the face's outward normal is +z)."""
    return {"seat": face((0, 0, 0), (0, 0, 1), (1, 0, 0))}
