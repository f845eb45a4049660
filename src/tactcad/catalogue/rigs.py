"""What each rig part is, without building it: name, kind, process (for a
bought part its catalogue reference), colour, expected volume and bounding
box (independent estimates from elementary formulas), its joint frames, and
attributes such as a rubber sample's measured stiffness. No CAD kernel here.

Part frames are described in each part's module under :mod:`tactcad.parts`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from tactcad.catalogue.array import RGB, Bbox, Method, PartSpec, Process, bolt_name, bolt_volume
from tactcad.design.array import BoltSpec, Plan
from tactcad.geometry.frames import Frame, face
from tactcad.design.rigs import POCKET_CORNER_RADIUS_MM, RigDesign
from tactcad.design.scenes import LEVELS
from tactcad.partlib.base import PartData, RigPart, Seat
from tactcad.partlib.registry import rig_parts_lib
from tactcad.partlib.stock import PLATE_ALUMINIUM, TURNED_BRASS



@dataclass(frozen=True)
class RigPartSpec(PartSpec):
    """A rig part: a :class:`~tactcad.catalogue.array.PartSpec` plus what scenes need.

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


# Distinct colours: the STEP writer keeps colour records in a fixed order only
# when no two parts of a file share a colour.
_COLORS: dict[str, RGB] = {
    "cart": (0.70, 0.72, 0.76),
    "wheel_spacer": (0.66, 0.62, 0.58), "sample_holder": (0.35, 0.55, 0.45),
   
    "bearing": (0.72, 0.73, 0.74), "wheel_bolt": (0.10, 0.10, 0.11),
    "holder_bolt": (0.14, 0.13, 0.12),
}


def sample_name(stiffness_N_per_mm: float) -> str:
    """Part name of the rubber sample of the given stiffness, e.g. ``sample_k3p85``."""
    return "sample_k" + f"{stiffness_N_per_mm:g}".replace(".", "p")


def _sample_color(k: float, ks: tuple[float, ...]) -> RGB:
    """Pink rubber, darker for a stiffer sample."""
    lo, hi = min(ks), max(ks)
    t = 0.0 if hi == lo else (k - lo) / (hi - lo)
    return (round(0.95 - 0.35 * t, 4), round(0.60 - 0.30 * t, 4), round(0.65 - 0.30 * t, 4))


def _bolt_frames() -> dict[str, Frame]:
    # head underside at z = 0, shank along +z: the face's outward normal is +z
    return {"seat": face((0, 0, 0), (0, 0, 1), (1, 0, 0))}


def _bolt_spec(b: BoltSpec, length_mm: float, color: RGB) -> RigPartSpec:
    rh = b.head_diameter_mm / 2
    return RigPartSpec(
        name=bolt_name(b, length_mm), kind="purchased",
        process=Process(f"ISO 4762 {b.size}x{length_mm:g} socket head cap screw", Method.BOUGHT),
        material="steel 8.8",
        color=color, builder="rig_bolt", expected_volume_mm3=bolt_volume(b, length_mm),
        expected_bbox_mm=(-rh, -rh, -b.head_height_mm, rh, rh, length_mm),
        geometry=(b, length_mm), frames=_bolt_frames())


def _box_bbox(x0, y0, z0, x1, y1, z1) -> Bbox:
    return (float(x0), float(y0), float(z0), float(x1), float(y1), float(z1))


def _suction_overlap(hole_r: float, channel_r: float, n: int = 64) -> float:
    """Volume (mm^3) a vertical hole of radius ``hole_r`` ending on the axis of
    a horizontal channel of radius ``channel_r`` shares with the channel:
    int_{-a}^{a} 2 sqrt(a^2 - v^2) sqrt(R^2 - v^2) dv, by Gauss-Legendre
    quadrature in v = a sin(theta) (smooth integrand)."""
    import numpy as np

    x, w = np.polynomial.legendre.leggauss(n)
    th = x * math.pi / 2
    a, R = hole_r, channel_r
    f = 2 * a * a * np.cos(th) ** 2 * np.sqrt(R * R - (a * np.sin(th)) ** 2)
    return float(np.sum(w * f) * math.pi / 2)


def rig_parts(plan: Plan, rigs: RigDesign) -> dict[str, RigPartSpec]:
    """Every distinct rig part, keyed by part name (all 8 rubber samples)."""
    parts: dict[str, RigPartSpec] = {}

    def add(spec: RigPartSpec) -> None:
        parts[spec.name] = spec

    al = PLATE_ALUMINIUM
    # --- cart ---
    k = rigs.cart
    L, W, T = k.length_mm, k.width_mm, k.thickness_mm
    rp = POCKET_CORNER_RADIUS_MM
    pocket = (k.pocket_length_mm * k.pocket_width_mm - (4 - math.pi) * rp * rp) * k.pocket_depth_mm
    port = math.pi * (k.port_diameter_mm / 2) ** 2 * k.port_depth_mm
    channel = math.pi * (k.channel_diameter_mm / 2) ** 2 * (k.channel_end_x_mm + L / 2 - k.port_depth_mm)
    hr, cr = k.suction_hole_diameter_mm / 2, k.channel_diameter_mm / 2
    suction = len(k.suction_hole_xs_mm) * (math.pi * hr * hr * (T / 2 - k.pocket_depth_mm)
                                           - _suction_overlap(hr, cr))
    tapped = 2 * math.pi * (k.holder_screw_diameter_mm / 2) ** 2 * k.holder_tapped_depth_mm
    axles = 4 * math.pi * (k.axle_bolt.nominal_diameter_mm / 2) ** 2 * k.axle_hole_depth_mm
    frames = {"top": face((0, 0, T), (0, 0, 1), (1, 0, 0))}
    for sx in (-1, 1):
        for sy in (-1, 1):
            frames[_wheel(sx, sy)] = face((sx * k.axle_x_mm, sy * W / 2, k.axle_height_mm),
                                          (0, sy, 0), (1, 0, 0))
    add(RigPartSpec(
        name="cart", kind="fabricated", process=Process("milling and drilling from plate", Method.PLATE), material=al,
        color=_COLORS["cart"], builder="cart",
        expected_volume_mm3=L * W * T - pocket - port - channel - suction - tapped - axles,
        expected_bbox_mm=_box_bbox(-L / 2, -W / 2, 0, L / 2, W / 2, T), geometry=k, frames=frames))
    ro, ri, t = k.spacer_outer_diameter_mm / 2, k.spacer_inner_diameter_mm / 2, k.spacer_thickness_mm
    add(RigPartSpec(
        name="wheel_spacer", kind="fabricated", process=Process("turning", Method.ROUND_BAR), material=TURNED_BRASS,
        color=_COLORS["wheel_spacer"], builder="wheel_spacer",
        expected_volume_mm3=math.pi * (ro * ro - ri * ri) * t,
        expected_bbox_mm=_box_bbox(-ro, -ro, 0, ro, ro, t), geometry=k,
        frames={"cart_side": face((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "wheel_side": face((0, 0, t), (0, 0, 1), (1, 0, 0))}))
    b = k.bearing
    R, rb = b.outer_diameter_mm / 2, b.bore_mm / 2
    add(RigPartSpec(
        name=f"bearing_{b.designation}", kind="purchased",
        process=Process(f"deep groove ball bearing {b.designation}, ISO 15: d {b.bore_mm:g} x D "
                        f"{b.outer_diameter_mm:g} x B {b.width_mm:g} mm", Method.BOUGHT),
        material="bearing steel", color=_COLORS["bearing"], builder="bearing",
        expected_volume_mm3=math.pi * (R * R - rb * rb) * b.width_mm,
        expected_bbox_mm=_box_bbox(-R, -R, 0, R, R, b.width_mm), geometry=b,
        frames={"inner": face((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "outer": face((0, 0, b.width_mm), (0, 0, 1), (1, 0, 0)),
                "tread": face((0, -R, b.width_mm / 2), (0, -1, 0), (1, 0, 0))}))
    add(_bolt_spec(k.axle_bolt, k.axle_bolt_length_mm, _COLORS["wheel_bolt"]))
    # --- samples and holder ---
    s = rigs.sample
    for kk in rigs.sample_stiffness_N_per_mm:
        add(RigPartSpec(
            name=sample_name(kk), kind="fabricated",
            process=Process(f"cast {s.material} block, measured stiffness {kk:g} N/mm", Method.CAST),
            material=s.material, color=_sample_color(kk, rigs.sample_stiffness_N_per_mm),
            builder="sample", expected_volume_mm3=s.length_mm * s.width_mm * s.height_mm,
            expected_bbox_mm=_box_bbox(-s.length_mm / 2, -s.width_mm / 2, 0, s.length_mm / 2,
                                       s.width_mm / 2, s.height_mm),
            geometry=s, attributes={"stiffness_N_per_mm": kk},
            frames={"bottom": face((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                    "top": face((0, 0, s.height_mm), (0, 0, 1), (1, 0, 0))}))
    h = rigs.holder
    window = h.window_length_mm * h.window_width_mm - (4 - math.pi) * h.corner_radius_mm ** 2
    holes = 2 * math.pi * (h.screw.clearance_hole_mm / 2) ** 2
    add(RigPartSpec(
        name="sample_holder", kind="fabricated", process=Process("milling from plate", Method.PLATE), material=al,
        color=_COLORS["sample_holder"], builder="sample_holder",
        expected_volume_mm3=(h.outer_length_mm * h.outer_width_mm - window - holes) * h.thickness_mm,
        expected_bbox_mm=_box_bbox(-h.outer_length_mm / 2, -h.outer_width_mm / 2, 0,
                                   h.outer_length_mm / 2, h.outer_width_mm / 2, h.thickness_mm),
        geometry=h,
        frames={"bottom": face((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                **{f"screw_{i}": face((0, sy * h.screw_y_mm, h.thickness_mm), (0, 0, 1), (1, 0, 0))
                   for i, sy in ((1, -1), (2, 1))}}))
    if bolt_name(h.screw, h.screw_length_mm) not in parts:
        add(_bolt_spec(h.screw, h.screw_length_mm, _COLORS["holder_bolt"]))
    listed = {bolt_name(plan.bolt, plan.bolt_length_mm)}  # the array's own bolt
    for key, part in rig_parts_lib().items():
        data = rigs.library[key]
        for one in (data, *data.companions):
            add(library_spec(part, one))
        for f in data.fasteners:
            name = bolt_name(f.bolt, f.length_mm)
            if name not in parts and name not in listed:
                add(_bolt_spec(f.bolt, f.length_mm, f.color))
    return parts


def library_spec(part: RigPart, data: PartData) -> RigPartSpec:
    """The spec of a part written as one module (:mod:`tactcad.partlib`) or of
    one of its companions: its data, built by its module (builder
    :attr:`PartData.builder`, else :attr:`RigPart.builder_key`), joint frames
    ``seat`` (when it has one) and its named frames."""
    frames = {"seat": seat_frame(data.seat)} if data.seat is not None else {}
    frames |= {name: seat_frame(seat) for name, seat in data.frames.items()}
    return RigPartSpec(
        name=data.name, kind=data.kind, process=data.process, material=data.material,
        color=data.color, builder=data.builder or part.builder_key,
        expected_volume_mm3=data.expected_volume_mm3,
        expected_bbox_mm=data.expected_bbox_mm, geometry=data.geometry, frames=frames,
        attributes=data.attributes)


def seat_frame(seat: Seat) -> Frame:
    """A part module's seat as a joint frame."""
    return face(seat.origin, seat.normal, seat.x_dir)


def _wheel(sx: int, sy: int) -> str:
    return "axle_" + wheel_tag(sx, sy)


def wheel_tag(sx: int, sy: int) -> str:
    """Tag of the wheel at the cart's (sign x, sign y) corner: ``mm``, ``mp``, ``pm``, ``pp``."""
    return f"{'m' if sx < 0 else 'p'}{'m' if sy < 0 else 'p'}"


def nut_frames() -> dict[str, Frame]:
    """Joint frames of the ISO 4032 nut of :func:`tactcad.parts.fasteners.build_nut`."""
    return {"seat": face((0, 0, 0), (0, 0, -1), (1, 0, 0))}


def bolt_frames() -> dict[str, Frame]:
    """Joint frames of a socket head cap screw (head underside at z = 0)."""
    return _bolt_frames()
