"""Rig design file (``hardware/rigs.toml``) -> validated, immutable rig plan.

The three test rigs of the paper (calibration under a force gauge on
micro-stages, rubber-sample stiffness on a wheeled cart, array evaluation on
a vertical linear axis with 100 g weights) need dimensions the paper does not
give. They live in their own file, each with a one-line reason under
``[assumptions]``, and are checked here the same way as the array design
(:mod:`tactcad.design.array`): every bad value raises :class:`DesignError` naming
the field, the value and the allowed range. No CAD kernel here.

Units: mm, N, g.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from tactcad.design.array import (BOLTS, BoltSpec, Derived, _check_number, _fmt, _Reader, check_keys,
                     read_assumptions, read_toml)
from tactcad.errors import DesignError

DEFAULT_RIGS = Path(__file__).resolve().parents[3] / "hardware" / "rigs.toml"

POCKET_CORNER_RADIUS_MM = 1.0  # end mill radius of the cart's vacuum pocket

# ISO 4762 / ISO 4032 / ISO 273 data for M4 (the wheel axles), next to the
# design's M1.6 ... M3. Values in mm.
RIG_BOLTS: dict[str, BoltSpec] = {
    **BOLTS,
    "M4": BoltSpec("M4", 4.0, 4.5, 0.7, 7.0, 4.0, 7.0, 3.2,
                   (6, 8, 10, 12, 16, 20, 25, 30, 35, 40)),
}


@dataclass(frozen=True)
class BearingSpec:
    """Deep groove ball bearing, ISO 15 boundary dimensions (mm)."""

    designation: str
    bore_mm: float  # d
    outer_diameter_mm: float  # D
    width_mm: float  # B


# ISO 15, dimension series 02 (62xx) for the small sizes used as cart wheels.
BEARINGS: dict[str, BearingSpec] = {
    "623ZZ": BearingSpec("623ZZ", 3.0, 10.0, 4.0),
    "624ZZ": BearingSpec("624ZZ", 4.0, 13.0, 5.0),
    "625ZZ": BearingSpec("625ZZ", 5.0, 16.0, 5.0),
    "626ZZ": BearingSpec("626ZZ", 6.0, 19.0, 6.0),
}


@dataclass(frozen=True)
class BasePlateGeometry:
    """Base plate with two wheel grooves along x (part frame: x along the
    grooves, y across, z up from the underside; centred in x and y)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    groove_width_mm: float
    groove_depth_mm: float
    track_half_mm: float  # |y| of the groove centre lines
    mount_hole_diameter_mm: float
    mount_hole_inset_mm: float
    column_x_mm: float  # x of the column's centre on the plate


@dataclass(frozen=True)
class ColumnGeometry:
    thickness_mm: float
    width_mm: float
    height_mm: float


@dataclass(frozen=True)
class CartGeometry:
    """Wheeled cart top plate with a vacuum clamping area (mm)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    bearing: BearingSpec
    axle_bolt: BoltSpec
    axle_bolt_length_mm: float
    axle_height_mm: float
    axle_x_mm: float  # |x| of the axles
    axle_hole_depth_mm: float
    spacer_outer_diameter_mm: float
    spacer_inner_diameter_mm: float
    spacer_thickness_mm: float
    pocket_length_mm: float
    pocket_width_mm: float
    pocket_depth_mm: float
    suction_hole_diameter_mm: float
    suction_hole_xs_mm: tuple[float, ...]
    channel_diameter_mm: float
    channel_end_x_mm: float
    port_diameter_mm: float
    port_depth_mm: float
    holder_screw_y_mm: float  # |y| of the sample holder's two tapped holes (x = 0)
    holder_screw_diameter_mm: float
    holder_tapped_depth_mm: float

    @property
    def wheel_clearance_mm(self) -> float:
        """Underside of the cart above the wheels' contact line."""
        return self.bearing.outer_diameter_mm / 2 - self.axle_height_mm


@dataclass(frozen=True)
class SampleGeometry:
    length_mm: float
    width_mm: float
    height_mm: float
    material: str


@dataclass(frozen=True)
class SampleHolderGeometry:
    """Frame around the sample: window = sample + clearance, two screw holes."""

    window_length_mm: float
    window_width_mm: float
    outer_length_mm: float
    outer_width_mm: float
    thickness_mm: float
    corner_radius_mm: float
    screw: BoltSpec
    screw_length_mm: float
    screw_y_mm: float


@dataclass(frozen=True)
class IndenterGeometry:
    contact_width_mm: float
    contact_depth_mm: float
    tip_length_mm: float
    body_diameter_mm: float
    body_length_mm: float


@dataclass(frozen=True)
class ForceGaugeSpec:
    model: str
    range_N: float
    resolution_N: float
    stiffness_N_per_mm: float
    length_mm: float
    width_mm: float
    depth_mm: float
    shaft_diameter_mm: float
    shaft_length_mm: float
    mount_height_mm: float


@dataclass(frozen=True)
class ZAxisSpec:
    body_width_mm: float
    body_depth_mm: float
    body_height_mm: float
    carriage_thickness_mm: float
    carriage_height_mm: float
    travel_mm: float
    position_mm: float
    micrometer_diameter_mm: float
    micrometer_length_mm: float
    micrometer_resolution_mm: float


@dataclass(frozen=True)
class XYStageSpec:
    size_mm: float
    base_height_mm: float
    table_height_mm: float
    travel_mm: float


@dataclass(frozen=True)
class LinearAxisSpec:
    rail: str
    block: str
    rail_width_mm: float
    rail_height_mm: float
    rail_length_mm: float
    block_width_mm: float
    block_length_mm: float
    block_height_mm: float
    block_clearance_mm: float
    rail_mount_height_mm: float


@dataclass(frozen=True)
class CarrierGeometry:
    width_mm: float
    height_mm: float
    thickness_mm: float
    shelf_depth_mm: float


@dataclass(frozen=True)
class HangerBarGeometry:
    section_mm: float
    length_mm: float


@dataclass(frozen=True)
class BracketGeometry:
    """L bracket holding the array by its front clamp plate (mm).

    Part frame = array frame shifted so that the origin lies on the ear's
    inner face at the height of the clamp plate's two mounting holes: ear in
    ``-ear_thickness <= z <= 0``, foot below the array in ``-foot_length <= z <= 0``.
    """

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


@dataclass(frozen=True)
class WeightSpec:
    mass_g: float
    density_g_per_cm3: float
    diameter_mm: float
    height_mm: float
    count: int

    @property
    def volume_mm3(self) -> float:
        return self.mass_g / self.density_g_per_cm3 * 1000.0


@dataclass(frozen=True)
class RigDesign:
    """Validated rig dimensions, immutable. Build with :func:`load_rigs`."""

    name: str
    description: str
    source: str
    rigs_hash: str
    base: BasePlateGeometry
    column: ColumnGeometry
    cart: CartGeometry
    sample: SampleGeometry
    sample_stiffness_N_per_mm: tuple[float, ...]
    holder: SampleHolderGeometry
    indenter: IndenterGeometry
    gauge: ForceGaugeSpec
    z_axis: ZAxisSpec
    xy_stage: XYStageSpec
    linear_axis: LinearAxisSpec
    carrier: CarrierGeometry
    bar: HangerBarGeometry
    bracket: BracketGeometry
    weights: WeightSpec
    calibration_element: int
    derived: tuple[Derived, ...]
    assumptions: tuple[tuple[str, str], ...]


# ---------------------------------------------------------------------------
# Schema: section -> key -> (lo, hi) for numbers, "text", "int" or "list".
# ---------------------------------------------------------------------------
_SCHEMA: dict[str, dict[str, Any]] = {
    "rigs": {"name": "text", "description": "text"},
    "base_plate": {"length_mm": (100.0, 1000.0), "width_mm": (40.0, 500.0),
                   "thickness_mm": (4.0, 40.0), "groove_width_mm": (1.0, 30.0),
                   "groove_depth_mm": (0.5, 10.0), "mount_hole_diameter_mm": (2.0, 20.0),
                   "mount_hole_inset_mm": (3.0, 50.0), "column_inset_mm": (0.0, 200.0)},
    "column": {"thickness_mm": (5.0, 60.0), "width_mm": (20.0, 300.0),
               "height_mm": (50.0, 1000.0)},
    "cart": {"length_mm": (30.0, 300.0), "width_mm": (30.0, 300.0), "thickness_mm": (5.0, 40.0),
             "bearing": "text", "axle_height_mm": (1.0, 20.0), "axle_inset_mm": (3.0, 100.0),
             "axle_hole_depth_mm": (3.0, 40.0), "spacer_outer_diameter_mm": (2.0, 30.0),
             "spacer_thickness_mm": (0.2, 5.0), "pocket_length_mm": (2.0, 200.0),
             "pocket_width_mm": (2.0, 200.0), "pocket_depth_mm": (0.1, 5.0),
             "suction_hole_diameter_mm": (0.5, 5.0), "suction_hole_count": "int",
             "suction_hole_pitch_mm": (0.5, 50.0), "channel_diameter_mm": (1.0, 10.0),
             "port_diameter_mm": (2.0, 20.0), "port_depth_mm": (1.0, 30.0)},
    "sample": {"length_mm": (5.0, 200.0), "width_mm": (5.0, 200.0), "height_mm": (1.0, 100.0),
               "material": "text", "stiffness_N_per_mm": "list"},
    "sample_holder": {"thickness_mm": (1.0, 50.0), "wall_mm": (2.0, 50.0),
                      "clearance_mm": (0.05, 5.0), "corner_radius_mm": (0.1, 10.0),
                      "screw_size": "text", "tapped_depth_mm": (2.0, 40.0)},
    "indenter": {"contact_width_mm": (0.5, 20.0), "contact_depth_mm": (0.5, 20.0),
                 "tip_length_mm": (0.5, 30.0), "body_diameter_mm": (1.0, 50.0),
                 "body_length_mm": (1.0, 50.0)},
    "force_gauge": {"model": "text", "range_N": (0.1, 1e5), "resolution_N": (1e-6, 10.0),
                    "stiffness_N_per_mm": (0.1, 1e6), "length_mm": (20.0, 500.0),
                    "width_mm": (10.0, 300.0), "depth_mm": (10.0, 300.0),
                    "shaft_diameter_mm": (1.0, 30.0), "shaft_length_mm": (1.0, 100.0),
                    "mount_height_mm": (0.0, 500.0)},
    "z_axis": {"body_width_mm": (10.0, 300.0), "body_depth_mm": (5.0, 300.0),
               "body_height_mm": (10.0, 500.0), "carriage_thickness_mm": (2.0, 100.0),
               "carriage_height_mm": (5.0, 500.0), "travel_mm": (0.5, 200.0),
               "position_mm": (0.0, 200.0), "micrometer_diameter_mm": (3.0, 60.0),
               "micrometer_length_mm": (5.0, 200.0), "micrometer_resolution_mm": (1e-6, 0.1)},
    "xy_stage": {"size_mm": (10.0, 300.0), "base_height_mm": (2.0, 100.0),
                 "table_height_mm": (2.0, 100.0), "travel_mm": (1.0, 200.0)},
    "linear_axis": {"rail": "text", "block": "text", "rail_width_mm": (3.0, 60.0),
                    "rail_height_mm": (2.0, 60.0), "rail_length_mm": (20.0, 2000.0),
                    "block_width_mm": (5.0, 200.0), "block_length_mm": (5.0, 300.0),
                    "block_height_mm": (3.0, 100.0), "block_clearance_mm": (0.0, 20.0),
                    "rail_mount_height_mm": (0.0, 1000.0)},
    "carrier": {"width_mm": (5.0, 300.0), "height_mm": (10.0, 500.0),
                "thickness_mm": (1.0, 50.0), "shelf_depth_mm": (5.0, 300.0)},
    "hanger_bar": {"section_mm": (2.0, 100.0), "length_mm": (5.0, 1000.0)},
    "bracket": {"width_mm": (5.0, 200.0), "ear_thickness_mm": (0.5, 20.0),
                "ear_top_mm": (1.0, 50.0), "foot_thickness_mm": (1.0, 30.0),
                "foot_length_mm": (5.0, 200.0), "foot_clearance_mm": (0.3, 20.0),
                "foot_hole_diameter_mm": (1.0, 20.0)},
    "weights": {"mass_g": (1.0, 10000.0), "density_g_per_cm3": (0.5, 25.0),
                "diameter_mm": (5.0, 200.0), "count": "int"},
    "calibration": {"element": "int"},
}
class _RigReader(_Reader):
    """The design file's reader, with the ranges of this file's schema."""

    def n(self, section: str, key: str, lo: float | None = None, hi: float | None = None,
          why: str = "", **kw) -> float:
        slo, shi = _SCHEMA[section][key]
        return self.number(section, key, slo if lo is None else max(lo, slo),
                           shi if hi is None else min(hi, shi), why=why, **kw)


def rigs_hash(data: Mapping[str, Any]) -> str:
    """sha256 of the rig file's content (canonical JSON)."""
    return hashlib.sha256(json.dumps(data, sort_keys=True, separators=(",", ":"),
                                     default=str).encode()).hexdigest()


def _shortest_bolt(bolt: BoltSpec, needed: float, field: str, value: Any) -> float:
    lengths = [L for L in bolt.catalogue_lengths_mm if L >= needed - 1e-9]
    if not lengths:
        raise DesignError(field, value, f"a smaller grip: {bolt.size} needs {_fmt(needed)} mm, "
                          f"longest stock is {_fmt(max(bolt.catalogue_lengths_mm))} mm")
    return float(lengths[0])


def load_rigs(path: str | Path | None = None, *, array_plan=None) -> RigDesign:
    """Read a rig file and return its validated rig plan.

    Args:
        path: TOML rig file; ``None`` means ``hardware/rigs.toml``.
        array_plan: the array's :class:`~tactcad.design.array.Plan`, needed for the
            bracket (mounting holes, bolt grip); ``None`` loads the default design.

    Raises:
        DesignError: unreadable file, missing/unknown key, or a value outside
            its allowed range (the message names field, value and range).
    """
    p = Path(path) if path is not None else DEFAULT_RIGS
    data = read_toml(p, "rigs file")
    if array_plan is None:
        from tactcad.design.array import load_design
        array_plan = load_design()
    return rigs_from_dict(data, array_plan, source=str(p))


def rigs_from_dict(data: Mapping[str, Any], plan, source: str = "<dict>") -> RigDesign:
    """Validate raw rig tables against the array ``plan``. See :func:`load_rigs`."""
    check_keys(data, _SCHEMA, ("assumptions",), what="<rigs>")
    r = _RigReader(data)
    assumptions = read_assumptions(data, _SCHEMA, example="cart.bearing")
    derived: list[Derived] = []

    # --- cart wheels first: the base plate's grooves follow from them ---
    bearing_name = r.raw("cart", "bearing")
    if bearing_name not in BEARINGS:
        raise DesignError("cart.bearing", bearing_name, "one of " + ", ".join(BEARINGS))
    bearing = BEARINGS[bearing_name]
    axle_size = f"M{bearing.bore_mm:g}"
    if axle_size not in RIG_BOLTS:
        raise DesignError("cart.bearing", bearing_name,
                          "a bearing whose bore takes one of " + ", ".join(RIG_BOLTS),
                          "the wheel rides on a socket head screw of the bore's size")
    axle_bolt = RIG_BOLTS[axle_size]

    cart_l = r.n("cart", "length_mm")
    cart_w = r.n("cart", "width_mm")
    cart_t = r.n("cart", "thickness_mm")
    axle_hole_d = axle_bolt.nominal_diameter_mm
    axle_h = r.n("cart", "axle_height_mm", axle_hole_d / 2 + 0.8, bearing.outer_diameter_mm / 2,
                 why="0.8 mm of material below the tapped axle hole, and the wheel must reach "
                     "below the cart", hi_open=True)
    axle_inset = r.n("cart", "axle_inset_mm", bearing.outer_diameter_mm / 2 + 1.0, cart_l / 2,
                     why="the wheels stay inside the cart's length", hi_open=True)
    axle_depth = r.n("cart", "axle_hole_depth_mm", 1.5 * axle_hole_d, cart_w / 2 - 2.0,
                     why="at least 1.5 d of thread, and the holes of both sides must not meet")
    sp_t = r.n("cart", "spacer_thickness_mm")
    sp_id = axle_bolt.clearance_hole_mm
    sp_od = r.n("cart", "spacer_outer_diameter_mm", sp_id + 0.5,
                bearing.bore_mm + 0.4 * (bearing.outer_diameter_mm - bearing.bore_mm),
                why="the spacer may bear on the inner ring only (about 40 % of the ring width)")
    grip = bearing.width_mm + sp_t
    axle_len = _shortest_bolt(axle_bolt, grip + 1.5 * axle_hole_d, "cart.bearing", bearing_name)
    if axle_len - grip > axle_depth - 0.5:
        raise DesignError("cart.axle_hole_depth_mm", axle_depth,
                          f">= {_fmt(axle_len - grip + 0.5)} mm",
                          f"the {axle_size} x {axle_len:g} wheel screw needs the thread depth")
    derived.append(Derived("wheel_screw_length", axle_len, "mm",
                           f"shortest stock {axle_size} >= wheel {_fmt(bearing.width_mm)} + spacer "
                           f"{_fmt(sp_t)} + 1.5 d of thread"))

    pocket_l = r.n("cart", "pocket_length_mm", hi=cart_l - 10.0)
    pocket_w = r.n("cart", "pocket_width_mm", hi=cart_w - 10.0)
    pocket_d = r.n("cart", "pocket_depth_mm", hi=cart_t / 4)
    suction_d = r.n("cart", "suction_hole_diameter_mm")
    n_holes = r.integer("cart", "suction_hole_count", 1, 20)
    pitch = r.n("cart", "suction_hole_pitch_mm", suction_d + 0.5, why="0.5 mm between holes")
    span = (n_holes - 1) * pitch + suction_d
    if span > pocket_l - 1.0:
        raise DesignError("cart.suction_hole_count", n_holes,
                          f"<= {int((pocket_l - 1.0 - suction_d) // pitch) + 1}",
                          f"the holes span {_fmt(span)} mm in a {_fmt(pocket_l)} mm pocket")
    hole_xs = tuple((k - (n_holes - 1) / 2) * pitch for k in range(n_holes))
    channel_d = r.n("cart", "channel_diameter_mm", suction_d, cart_t / 3,
                    why="wider than the suction holes, and a third of the plate at most")
    port_d = r.n("cart", "port_diameter_mm", channel_d, cart_t - 4.0, lo_open=True)
    port_depth = r.n("cart", "port_depth_mm", hi=cart_l / 2 - pocket_l / 2)
    channel_end = hole_xs[-1] + suction_d / 2 + channel_d / 2

    # --- sample and its holder ---
    s_l = r.n("sample", "length_mm")
    s_w = r.n("sample", "width_mm")
    s_h = r.n("sample", "height_mm")
    if s_l < pocket_l + 4.0 or s_w < pocket_w + 4.0:
        raise DesignError("sample.length_mm" if s_l < pocket_l + 4.0 else "sample.width_mm",
                          s_l if s_l < pocket_l + 4.0 else s_w,
                          f">= vacuum pocket + 4 mm ({_fmt(pocket_l + 4)} x {_fmt(pocket_w + 4)} mm)",
                          "the sample must seal the pocket with a 2 mm margin")
    stiff = r.raw("sample", "stiffness_N_per_mm")
    if not isinstance(stiff, list) or not stiff:
        raise DesignError("sample.stiffness_N_per_mm", stiff, "a non-empty list of stiffnesses (N/mm)")
    stiffness = tuple(_check_number(f"sample.stiffness_N_per_mm[{i}]", k, 0.01, 1e4, unit="N/mm")
                      for i, k in enumerate(stiff, start=1))
    if len(set(stiffness)) != len(stiffness):
        raise DesignError("sample.stiffness_N_per_mm", stiff, "distinct values",
                          "each stiffness names one sample part")
    sample = SampleGeometry(s_l, s_w, s_h, r.text("sample", "material"))

    clear = r.n("sample_holder", "clearance_mm")
    wall = r.n("sample_holder", "wall_mm")
    h_t = r.n("sample_holder", "thickness_mm", hi=s_h, hi_open=True,
              why="the sample must stand proud of its holder")
    corner = r.n("sample_holder", "corner_radius_mm", hi=clear * (2 + math.sqrt(2)),
                 why="the window's corner arc must clear the sample's sharp corner")
    screw_size = r.raw("sample_holder", "screw_size")
    if screw_size not in RIG_BOLTS:
        raise DesignError("sample_holder.screw_size", screw_size, "one of " + ", ".join(RIG_BOLTS))
    screw = RIG_BOLTS[screw_size]
    if wall < screw.head_diameter_mm + 1.0:
        raise DesignError("sample_holder.wall_mm", wall, f">= {_fmt(screw.head_diameter_mm + 1.0)} mm",
                          f"the {screw_size} head must sit on the wall")
    tapped = r.n("sample_holder", "tapped_depth_mm", hi=cart_t - 1.0)
    screw_len = _shortest_bolt(screw, h_t + 1.5 * screw.nominal_diameter_mm,
                               "sample_holder.thickness_mm", h_t)
    if screw_len - h_t > tapped - 0.5:
        raise DesignError("sample_holder.tapped_depth_mm", tapped, f">= {_fmt(screw_len - h_t + 0.5)} mm",
                          f"the {screw_size} x {screw_len:g} holder screw needs the thread depth")
    win_l, win_w = s_l + 2 * clear, s_w + 2 * clear
    screw_y = win_w / 2 + wall / 2
    holder = SampleHolderGeometry(win_l, win_w, win_l + 2 * wall, win_w + 2 * wall, h_t, corner,
                                  screw, screw_len, screw_y)
    if win_l + 2 * wall > cart_l or win_w + 2 * wall > cart_w:
        raise DesignError("sample_holder.wall_mm", wall,
                          f"<= {_fmt(min((cart_l - win_l) / 2, (cart_w - win_w) / 2))} mm",
                          "the holder must fit on the cart")
    if screw_y - screw.nominal_diameter_mm / 2 < channel_d / 2 + 1.0 or \
            screw_y + screw.nominal_diameter_mm / 2 > cart_w / 2 - 1.0:
        raise DesignError("sample_holder.wall_mm", wall, "a value that keeps the holder screws "
                          "1 mm from the vacuum channel and the cart's sides")
    if screw_y - screw.nominal_diameter_mm / 2 < pocket_w / 2 + 1.0:
        raise DesignError("cart.pocket_width_mm", pocket_w,
                          f"<= {_fmt(2 * (screw_y - screw.nominal_diameter_mm / 2 - 1.0))} mm",
                          "the holder screws must stay 1 mm outside the vacuum pocket")
    derived.append(Derived("sample_holder_screw_length", screw_len, "mm",
                           f"shortest stock {screw_size} >= holder {_fmt(h_t)} + 1.5 d of thread"))

    cart = CartGeometry(
        length_mm=cart_l, width_mm=cart_w, thickness_mm=cart_t, bearing=bearing,
        axle_bolt=axle_bolt, axle_bolt_length_mm=axle_len, axle_height_mm=axle_h,
        axle_x_mm=cart_l / 2 - axle_inset, axle_hole_depth_mm=axle_depth,
        spacer_outer_diameter_mm=sp_od, spacer_inner_diameter_mm=sp_id, spacer_thickness_mm=sp_t,
        pocket_length_mm=pocket_l, pocket_width_mm=pocket_w, pocket_depth_mm=pocket_d,
        suction_hole_diameter_mm=suction_d, suction_hole_xs_mm=hole_xs,
        channel_diameter_mm=channel_d, channel_end_x_mm=channel_end, port_diameter_mm=port_d,
        port_depth_mm=port_depth, holder_screw_y_mm=screw_y,
        holder_screw_diameter_mm=screw.nominal_diameter_mm, holder_tapped_depth_mm=tapped)

    # --- base plate: grooves under the wheels ---
    b_l = r.n("base_plate", "length_mm")
    b_w = r.n("base_plate", "width_mm")
    b_t = r.n("base_plate", "thickness_mm")
    g_w = r.n("base_plate", "groove_width_mm", bearing.width_mm, bearing.width_mm + 2.0,
              lo_open=True, why=f"wider than the {bearing.designation} wheel (guided, not jammed)")
    g_d = r.n("base_plate", "groove_depth_mm", hi=b_t / 2)
    if cart.wheel_clearance_mm - g_d < 0.5:
        raise DesignError("base_plate.groove_depth_mm", g_d,
                          f"<= {_fmt(cart.wheel_clearance_mm - 0.5)} mm",
                          "the cart's underside must clear the base plate by 0.5 mm")
    track = cart_w / 2 + sp_t + bearing.width_mm / 2
    derived.append(Derived("groove_track_half", track, "mm",
                           "cart half-width + spacer + half a wheel: the grooves lie under the wheels"))
    head_r = axle_bolt.head_diameter_mm / 2
    if track + bearing.width_mm / 2 + axle_bolt.head_height_mm > b_w / 2 - 2.0:
        raise DesignError("base_plate.width_mm", b_w,
                          f">= {_fmt(2 * (track + bearing.width_mm / 2 + axle_bolt.head_height_mm + 2))} mm",
                          "the wheels and their screw heads must stay on the plate")
    if bearing.outer_diameter_mm / 2 - head_r < g_d + 0.5 - 1e-9:
        raise DesignError("base_plate.groove_depth_mm", g_d,
                          f"<= {_fmt(bearing.outer_diameter_mm / 2 - head_r - 0.5)} mm",
                          "the wheel screw heads must clear the plate beside the groove")
    hole_d = r.n("base_plate", "mount_hole_diameter_mm")
    inset = r.n("base_plate", "mount_hole_inset_mm", hole_d / 2 + 1.0, b_w / 2 - hole_d)
    col_t = r.n("column", "thickness_mm")
    col_w = r.n("column", "width_mm", hi=b_w - 2 * (inset + hole_d / 2),
                why="the column must stand between the corner holes")
    col_h = r.n("column", "height_mm")
    col_inset = r.n("base_plate", "column_inset_mm", hi=b_l / 3)
    column_x = b_l / 2 - col_inset - col_t / 2
    base = BasePlateGeometry(b_l, b_w, b_t, g_w, g_d, track, hole_d, inset, column_x)
    column = ColumnGeometry(col_t, col_w, col_h)

    # --- indenter and bought parts ---
    indenter = IndenterGeometry(
        contact_width_mm=r.n("indenter", "contact_width_mm"),
        contact_depth_mm=r.n("indenter", "contact_depth_mm"),
        tip_length_mm=r.n("indenter", "tip_length_mm"),
        body_diameter_mm=r.n("indenter", "body_diameter_mm"),
        body_length_mm=r.n("indenter", "body_length_mm"))
    if math.hypot(indenter.contact_width_mm, indenter.contact_depth_mm) > indenter.body_diameter_mm:
        raise DesignError("indenter.body_diameter_mm", indenter.body_diameter_mm,
                          f">= {_fmt(math.hypot(indenter.contact_width_mm, indenter.contact_depth_mm))} mm",
                          "the tip must sit inside the body")
    if indenter.tip_length_mm < plan.element(1).geometry.tip_height_mm:
        raise DesignError("indenter.tip_length_mm", indenter.tip_length_mm,
                          f">= {_fmt(plan.element(1).geometry.tip_height_mm)} mm",
                          "the body must clear the neighbouring element tips")
    g_len = r.n("force_gauge", "length_mm")
    gauge = ForceGaugeSpec(
        model=r.text("force_gauge", "model"), range_N=r.n("force_gauge", "range_N", unit="N"),
        resolution_N=r.n("force_gauge", "resolution_N", unit="N"),
        stiffness_N_per_mm=r.n("force_gauge", "stiffness_N_per_mm", unit="N/mm"),
        length_mm=g_len, width_mm=r.n("force_gauge", "width_mm"),
        depth_mm=r.n("force_gauge", "depth_mm"),
        shaft_diameter_mm=r.n("force_gauge", "shaft_diameter_mm"),
        shaft_length_mm=r.n("force_gauge", "shaft_length_mm"),
        mount_height_mm=r.n("force_gauge", "mount_height_mm", hi=g_len))
    if gauge.shaft_diameter_mm > indenter.body_diameter_mm:
        raise DesignError("force_gauge.shaft_diameter_mm", gauge.shaft_diameter_mm,
                          f"<= indenter.body_diameter_mm = {_fmt(indenter.body_diameter_mm)} mm")
    zb_h = r.n("z_axis", "body_height_mm")
    zc_h = r.n("z_axis", "carriage_height_mm", hi=zb_h)
    travel = r.n("z_axis", "travel_mm", hi=zb_h - zc_h,
                 why="the carriage travels along the body")
    z_axis = ZAxisSpec(
        body_width_mm=r.n("z_axis", "body_width_mm"), body_depth_mm=r.n("z_axis", "body_depth_mm"),
        body_height_mm=zb_h, carriage_thickness_mm=r.n("z_axis", "carriage_thickness_mm"),
        carriage_height_mm=zc_h, travel_mm=travel,
        position_mm=r.n("z_axis", "position_mm", 0.0, travel),
        micrometer_diameter_mm=r.n("z_axis", "micrometer_diameter_mm"),
        micrometer_length_mm=r.n("z_axis", "micrometer_length_mm"),
        micrometer_resolution_mm=r.n("z_axis", "micrometer_resolution_mm"))
    if z_axis.micrometer_diameter_mm > min(z_axis.body_width_mm, z_axis.body_depth_mm):
        raise DesignError("z_axis.micrometer_diameter_mm", z_axis.micrometer_diameter_mm,
                          f"<= {_fmt(min(z_axis.body_width_mm, z_axis.body_depth_mm))} mm",
                          "the micrometer stands on the body's top face")
    if z_axis.body_height_mm > col_h:
        raise DesignError("z_axis.body_height_mm", zb_h, f"<= column.height_mm = {_fmt(col_h)} mm")
    xy = XYStageSpec(size_mm=r.n("xy_stage", "size_mm"),
                     base_height_mm=r.n("xy_stage", "base_height_mm"),
                     table_height_mm=r.n("xy_stage", "table_height_mm"),
                     travel_mm=r.n("xy_stage", "travel_mm"))
    if xy.size_mm / 2 > track - g_w / 2:
        raise DesignError("xy_stage.size_mm", xy.size_mm, f"<= {_fmt(2 * (track - g_w / 2))} mm",
                          "the stages stand on the base plate between the grooves")
    rail_w = r.n("linear_axis", "rail_width_mm")
    rail_h = r.n("linear_axis", "rail_height_mm")
    blk_h = r.n("linear_axis", "block_height_mm", rail_h, lo_open=True)
    blk_c = r.n("linear_axis", "block_clearance_mm", hi=rail_h, hi_open=True)
    rail_len = r.n("linear_axis", "rail_length_mm")
    blk_l = r.n("linear_axis", "block_length_mm", hi=rail_len)
    lin = LinearAxisSpec(
        rail=r.text("linear_axis", "rail"), block=r.text("linear_axis", "block"),
        rail_width_mm=rail_w, rail_height_mm=rail_h, rail_length_mm=rail_len,
        block_width_mm=r.n("linear_axis", "block_width_mm", rail_w + 2.0),
        block_length_mm=blk_l, block_height_mm=blk_h, block_clearance_mm=blk_c,
        rail_mount_height_mm=r.n("linear_axis", "rail_mount_height_mm", hi=col_h - rail_len))
    carrier = CarrierGeometry(
        width_mm=r.n("carrier", "width_mm"), height_mm=r.n("carrier", "height_mm"),
        thickness_mm=r.n("carrier", "thickness_mm"),
        shelf_depth_mm=r.n("carrier", "shelf_depth_mm"))
    bar = HangerBarGeometry(section_mm=r.n("hanger_bar", "section_mm"),
                            length_mm=r.n("hanger_bar", "length_mm"))
    if carrier.shelf_depth_mm - carrier.thickness_mm < bar.section_mm + 2.0:
        raise DesignError("carrier.shelf_depth_mm", carrier.shelf_depth_mm,
                          f">= {_fmt(carrier.thickness_mm + bar.section_mm + 2.0)} mm",
                          "the hanger bar hangs from the shelf clear of the carrier plate")
    if carrier.thickness_mm > carrier.height_mm / 2:
        raise DesignError("carrier.thickness_mm", carrier.thickness_mm,
                          f"<= {_fmt(carrier.height_mm / 2)} mm")

    # --- bracket: bolted through the clamp plates' two bridge holes ---
    c = plan.clamp
    mount = c.holes[-2:]
    y_h = mount[0].y_mm
    b = plan.bolt
    br_w = r.n("bracket", "width_mm", abs(mount[0].x_mm - mount[1].x_mm) + mount[0].diameter_mm
               + b.head_diameter_mm, why="the ear must carry both mounting holes and the bolt heads")
    array_heads = [(h.x_mm, h.y_mm) for h in c.holes[:4]]
    limit = min(abs(x) for x, _ in array_heads) - b.head_diameter_mm / 2
    if br_w / 2 > limit - 0.3:
        raise DesignError("bracket.width_mm", br_w, f"<= {_fmt(2 * (limit - 0.3))} mm",
                          "the ear must clear the heads of the array's clamp bolts")
    ear_t = r.n("bracket", "ear_thickness_mm")
    foot_clear = r.n("bracket", "foot_clearance_mm")
    head_bottom = y_h - b.head_diameter_mm / 2  # array frame
    nut_bottom = y_h - b.nut_width_across_flats_mm / 2  # nuts sit flats up, as in the array
    foot_top = min(0.0, head_bottom, nut_bottom) - foot_clear - y_h  # relative to the holes
    grip = ear_t + 2 * c.thickness_mm + plan.stack_length_mm
    br_bolt_len = _shortest_bolt(b, grip + b.nut_height_mm + 2 * b.thread_pitch_mm,
                                 "bracket.ear_thickness_mm", ear_t)
    derived.append(Derived("bracket_bolt_length", br_bolt_len, "mm",
                           f"shortest stock {b.size} through ear {_fmt(ear_t)}, both clamp plates "
                           f"and the stack (grip {_fmt(grip)}) + nut + 2 thread pitches"))
    bracket = BracketGeometry(
        width_mm=br_w, ear_thickness_mm=ear_t,
        ear_top_mm=r.n("bracket", "ear_top_mm", mount[0].diameter_mm / 2 + 0.5,
                       c.height_mm - y_h),
        foot_thickness_mm=r.n("bracket", "foot_thickness_mm"),
        foot_length_mm=r.n("bracket", "foot_length_mm", ear_t + bar.section_mm, lo_open=True),
        foot_top_mm=foot_top,
        foot_hole_diameter_mm=r.n("bracket", "foot_hole_diameter_mm", hi=br_w - 2.0),
        hole_xs_mm=(mount[0].x_mm, mount[1].x_mm), hole_diameter_mm=mount[0].diameter_mm,
        bolt=b, bolt_length_mm=br_bolt_len)
    if bracket.foot_length_mm / 2 - bracket.foot_hole_diameter_mm / 2 < ear_t + 0.5:
        raise DesignError("bracket.foot_length_mm", bracket.foot_length_mm,
                          f">= {_fmt(2 * (ear_t + 0.5) + bracket.foot_hole_diameter_mm)} mm",
                          "the foot's centre hole must clear the ear")

    mass = r.n("weights", "mass_g", unit="g")
    rho = r.n("weights", "density_g_per_cm3", unit="g/cm3")
    w_d = r.n("weights", "diameter_mm", hi=min(carrier.width_mm,
                                               2 * (carrier.shelf_depth_mm - carrier.thickness_mm)),
              why="the weights stand on the carrier's shelf")
    w_h = mass / rho * 1000.0 / (math.pi * (w_d / 2) ** 2)
    derived.append(Derived("weight_height", w_h, "mm",
                           f"{_fmt(mass)} g of density {_fmt(rho)} g/cm3 as a cylinder of "
                           f"diameter {_fmt(w_d)} mm"))
    weights = WeightSpec(mass, rho, w_d, w_h, r.integer("weights", "count", 0, 20))

    n_el = len(plan.slots)
    cal = r.integer("calibration", "element", 1, n_el)

    return RigDesign(
        name=r.text("rigs", "name"), description=r.text("rigs", "description"), source=source,
        rigs_hash=rigs_hash(data), base=base, column=column, cart=cart, sample=sample,
        sample_stiffness_N_per_mm=stiffness, holder=holder, indenter=indenter, gauge=gauge,
        z_axis=z_axis, xy_stage=xy, linear_axis=lin, carrier=carrier, bar=bar, bracket=bracket,
        weights=weights, calibration_element=cal, derived=tuple(derived), assumptions=assumptions)


def default_rigs_data() -> dict[str, Any]:
    """Raw TOML tables of the default rig file (a fresh copy)."""
    return read_toml(DEFAULT_RIGS, "rigs file")


def rigs_path_for(plan) -> Path:
    """``rigs.toml`` beside the design file, else the default one."""
    src = Path(getattr(plan, "source", "") or "")
    candidate = src.parent / "rigs.toml"
    return candidate if src.name and candidate.is_file() else DEFAULT_RIGS
