"""The bought ISO metric fasteners, as simplified envelopes: the ISO 4762
socket head cap screws that clamp the array's stack and the ISO 4032 hex nuts
on them; the rig parts' screws (:class:`tactcad.partlib.base.Fastener`) are
built by the same screw under the key ``rig_bolt``.

Here under the key ``bolt``: their spec (bolt and nut), names, volumes and
builders. The bolt's size and length come from the array's derivation
(``[clamp] bolt_size``, the stack's grip; :mod:`tactcad.design.array_plan`).
Dimensions: :data:`tactcad.vocabulary.standards.BOLTS`. Part frames: axis +z.
Units: mm.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from tactcad.kernel.shapes import cylinder_z, difference, extrude, moved, polygon_face, union
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, PartData
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import name_number
from tactcad.vocabulary.standards import NUT_FACTOR, BoltSpec, tightening_torque_Nm

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

BLACK_OXIDE: RGB = (0.12, 0.12, 0.13)
ZINC: RGB = (0.45, 0.46, 0.48)


def build_bolt(spec: BoltSpec, length_mm: float) -> Solid:
    """Socket head cap screw, axis +z; underside of the head at z = 0, the head
    in z < 0 with a hexagon socket, the plain shank (nominal diameter) to z = length."""
    head = cylinder_z(spec.head_diameter_mm / 2, spec.head_height_mm, z0=-spec.head_height_mm)
    shank = cylinder_z(spec.nominal_diameter_mm / 2, length_mm)
    socket = extrude(moved(polygon_face(_hexagon(spec.socket_across_flats_mm)),
                           (0, 0, -spec.head_height_mm)), spec.head_height_mm / 2)
    return difference(union(head, shank), socket)


def build_screw(geometry: tuple[BoltSpec, float]) -> Solid:
    """:func:`build_bolt` of a spec's geometry ``(bolt, length mm)``."""
    return build_bolt(*geometry)


def build_nut(spec: BoltSpec) -> Solid:
    """Hex nut, axis +z, from z = 0 to the nut height, bore = nominal diameter."""
    prism = extrude(polygon_face(_hexagon(spec.nut_width_across_flats_mm)), spec.nut_height_mm)
    bore = cylinder_z(spec.nominal_diameter_mm / 2, spec.nut_height_mm)
    return difference(prism, bore)


def _hexagon(across_flats: float) -> list[tuple[float, float, float]]:
    r = across_flats / math.sqrt(3)  # corner radius of a regular hexagon
    return [(r * math.cos(k * math.pi / 3), r * math.sin(k * math.pi / 3), 0.0) for k in range(6)]


def hexagon_area(across_flats: float) -> float:
    """Area (mm^2) of a regular hexagon of the given width across flats."""
    return math.sqrt(3) / 2 * across_flats**2


def bolt_name(b: BoltSpec, length_mm: float) -> str:
    """Part name of a bolt, safe for file names and STEP labels: ``bolt_M2p5x30``."""
    return f"bolt_{b.safe_name}x{name_number(length_mm)}"


def nut_name(b: BoltSpec) -> str:
    """Part name of a nut: ``nut_M2p5``."""
    return f"nut_{b.safe_name}"


def bolt_volume(b: BoltSpec, length_mm: float) -> float:
    """Volume (mm^3) of the socket head cap screw envelope of
    :func:`build_bolt`: head + shank - half-depth socket."""
    return (math.pi * (b.head_diameter_mm / 2) ** 2 * b.head_height_mm
            + math.pi * (b.nominal_diameter_mm / 2) ** 2 * length_mm
            - hexagon_area(b.socket_across_flats_mm) * b.head_height_mm / 2)


def screw_data(b: BoltSpec, length_mm: float, color: RGB, builder: str = "") -> PartData:
    """The spec of an ISO 4762 ``b`` x ``length_mm`` screw in ``color``
    (``builder``: its key when not ``bolt``)."""
    rh = b.head_diameter_mm / 2
    return PartData(
        name=bolt_name(b, length_mm), kind="purchased",
        process=Process(f"ISO 4762 {b.size}x{length_mm:g} socket head cap screw", Method.BOUGHT),
        material="steel 8.8", color=color, expected_volume_mm3=bolt_volume(b, length_mm),
        expected_bbox_mm=(-rh, -rh, -b.head_height_mm, rh, rh, length_mm),
        geometry=(b, length_mm), builder=builder)


def nut_data(b: BoltSpec) -> PartData:
    """The spec of an ISO 4032 ``b`` hex nut (builder ``nut``)."""
    s_af = b.nut_width_across_flats_mm
    rc = s_af / math.sqrt(3)
    return PartData(
        name=nut_name(b), kind="purchased", process=Process(f"ISO 4032 {b.size} hex nut", Method.BOUGHT),
        material="steel 8", color=ZINC,
        expected_volume_mm3=(hexagon_area(s_af) - math.pi * (b.nominal_diameter_mm / 2) ** 2)
        * b.nut_height_mm,
        expected_bbox_mm=(-rc, -s_af / 2, 0.0, rc, s_af / 2, b.nut_height_mm), geometry=b,
        builder="nut")


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The stack's bolt (``plan.bolt`` x ``plan.bolt_length_mm``) and its nut."""
    plan = context.plan
    return (screw_data(plan.bolt, plan.bolt_length_mm, BLACK_OXIDE), nut_data(plan.bolt))


def torque_notes(book) -> tuple[str, ...]:
    """The clamp bolts' torque: :func:`tactcad.vocabulary.standards.tightening_torque_Nm`."""
    bolt = book.bolt
    torque = tightening_torque_Nm(bolt.nominal_diameter_mm, bolt.thread_pitch_mm)
    return (f"Tighten the {bolt.size} clamp bolts crosswise in three passes to {torque:.2f} N m "
            f"(class 8.8, K = {NUT_FACTOR:g}, preload 75 % of proof load).",)


PART = ArrayPart(key="bolt", build=build_screw, specs=specs, order=50,
                 companion_builders={"nut": build_nut, "rig_bolt": build_screw},
                 assembly=BuildStep("array-bolts", "Torque the clamp bolts", tools=lambda book: (
                     f"torque screwdriver with {book.bolt.socket_across_flats_mm:g} mm hex bit",),
                     notes=torque_notes, companions=("nut",)))
