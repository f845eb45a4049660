"""Wheeled cart (a made part) with its wheels: a top plate with a vacuum
clamping area that rolls in the base plate's grooves on four ball bearings,
each on a socket head cap screw in a tapped axle hole with a turned brass
spacer between the cart's side and the bearing's inner ring. It carries the
sample holder and the sample (it checks both against its own features) and
the push-in fitting in its hose port (:mod:`tactcad.partlib.push_in_fitting`).

The vacuum area: a shallow pocket on the top face under the sample, suction
holes from the pocket floor down into a drilled channel at mid-thickness,
and a tapped hose port on the -x end face feeding the channel. Tapped holes
(wheel axles, sample holder screws, port) are modelled at the thread's
nominal diameter. Companions: the wheel spacer (made, turned) and the
bearing (bought, ISO 15 boundary dimensions d x D x B as an annulus).

Part frame: x along the base plate's grooves, y across, z up from the
underside, centred in x and y. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.partlib.base import DrawingRecord, Fastener, PartData, RigPart, Seat
from tactcad.partlib.screws import stock_length
from tactcad.kernel.shapes import box, cylinder, extrude, ring, rounded_rect_face, single
from tactcad.partlib.stock import PLATE_ALUMINIUM, TURNED_BRASS
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, choice, fmt, integer, number
from tactcad.vocabulary.standards import BEARINGS, RIG_BOLTS, BearingSpec, BoltSpec

COLOR, SPACER_COLOR, BEARING_COLOR = (0.70, 0.72, 0.76), (0.66, 0.62, 0.58), (0.72, 0.73, 0.74)
WHEEL_BOLT_COLOR = (0.10, 0.10, 0.11)
POCKET_CORNER_RADIUS_MM = 1.0  # end mill radius of the cart's vacuum pocket


class CartSection(Section):
    """``[cart]`` of ``rigs.toml``."""

    length_mm: number(30.0, 300.0)
    width_mm: number(30.0, 300.0)
    thickness_mm: number(5.0, 40.0)
    bearing: choice(BEARINGS, "ISO 15 deep groove ball bearings of the catalogue")
    axle_height_mm: number(1.0, 20.0)
    axle_inset_mm: number(3.0, 100.0)
    axle_hole_depth_mm: number(3.0, 40.0)
    spacer_outer_diameter_mm: number(2.0, 30.0)
    spacer_thickness_mm: number(0.2, 5.0)
    pocket_length_mm: number(2.0, 200.0)
    pocket_width_mm: number(2.0, 200.0)
    pocket_depth_mm: number(0.1, 5.0)
    suction_hole_diameter_mm: number(0.5, 5.0)
    suction_hole_count: integer(1, 20)
    suction_hole_pitch_mm: number(0.5, 50.0)
    channel_diameter_mm: number(1.0, 10.0)
    port_diameter_mm: number(2.0, 20.0)
    port_depth_mm: number(1.0, 30.0)


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


def wheel_tag(sx: int, sy: int) -> str:
    """Tag of the wheel at the cart's (sign x, sign y) corner: ``mm``, ``mp``, ``pm``, ``pp``."""
    return f"{'m' if sx < 0 else 'p'}{'m' if sy < 0 else 'p'}"


def _wheels(c: CartSection, p: Problems) -> tuple[BearingSpec, BoltSpec, float]:
    """The wheel's bearing, its axle screw and the screw's stock length, checked."""
    bearing = BEARINGS[c.bearing]
    axle_bolt = RIG_BOLTS.get(f"M{bearing.bore_mm:g}")
    if axle_bolt is None:
        p.add("cart.bearing", c.bearing, "a bearing whose bore takes one of " + ", ".join(RIG_BOLTS),
              "the wheel rides on a socket head screw of the bore's size")
        axle_bolt = RIG_BOLTS["M4"]
    axle_d = axle_bolt.nominal_diameter_mm
    p.within("cart.axle_height_mm", c.axle_height_mm, axle_d / 2 + 0.8,
             bearing.outer_diameter_mm / 2, hi_open=True,
             why="0.8 mm of material below the tapped axle hole, and the wheel must reach below "
                 "the cart")
    p.within("cart.axle_inset_mm", c.axle_inset_mm, bearing.outer_diameter_mm / 2 + 1.0,
             c.length_mm / 2, hi_open=True, why="the wheels stay inside the cart's length")
    p.within("cart.axle_hole_depth_mm", c.axle_hole_depth_mm, 1.5 * axle_d, c.width_mm / 2 - 2.0,
             why="at least 1.5 d of thread, and the holes of both sides must not meet")
    p.within("cart.spacer_outer_diameter_mm", c.spacer_outer_diameter_mm,
             axle_bolt.clearance_hole_mm + 0.5,
             bearing.bore_mm + 0.4 * (bearing.outer_diameter_mm - bearing.bore_mm),
             why="the spacer may bear on the inner ring only (about 40 % of the ring width)")
    grip = bearing.width_mm + c.spacer_thickness_mm
    axle_len = stock_length(axle_bolt, grip + 1.5 * axle_d, "cart.bearing", c.bearing, p)
    if axle_len - grip > c.axle_hole_depth_mm - 0.5:
        p.add("cart.axle_hole_depth_mm", c.axle_hole_depth_mm, f">= {fmt(axle_len - grip + 0.5)} mm",
              f"the {axle_bolt.size} x {axle_len:g} wheel screw needs the thread depth")
    return bearing, axle_bolt, axle_len


def _vacuum(c: CartSection, p: Problems) -> tuple[float, ...]:
    """The suction holes' x (mm), the pocket, channel and port checked."""
    p.within("cart.pocket_length_mm", c.pocket_length_mm, hi=c.length_mm - 10.0)
    p.within("cart.pocket_width_mm", c.pocket_width_mm, hi=c.width_mm - 10.0)
    p.within("cart.pocket_depth_mm", c.pocket_depth_mm, hi=c.thickness_mm / 4)
    pitch = p.within("cart.suction_hole_pitch_mm", c.suction_hole_pitch_mm,
                     c.suction_hole_diameter_mm + 0.5, why="0.5 mm between holes")
    n = c.suction_hole_count
    span = (n - 1) * pitch + c.suction_hole_diameter_mm
    if span > c.pocket_length_mm - 1.0:
        p.add("cart.suction_hole_count", n,
              f"<= {int((c.pocket_length_mm - 1.0 - c.suction_hole_diameter_mm) // pitch) + 1}",
              f"the holes span {fmt(span)} mm in a {fmt(c.pocket_length_mm)} mm pocket")
    p.within("cart.channel_diameter_mm", c.channel_diameter_mm, c.suction_hole_diameter_mm,
             c.thickness_mm / 3, why="wider than the suction holes, and a third of the plate at most")
    p.within("cart.port_diameter_mm", c.port_diameter_mm, c.channel_diameter_mm,
             c.thickness_mm - 4.0, lo_open=True)
    p.within("cart.port_depth_mm", c.port_depth_mm, hi=c.length_mm / 2 - c.pocket_length_mm / 2)
    return tuple((k - (n - 1) / 2) * pitch for k in range(n))


def _carried(c: CartSection, sample, holder, holder_table, p: Problems) -> None:
    """The sample seals the pocket; the holder (its geometry and table) and its
    screws fit the cart."""
    if sample.length_mm < c.pocket_length_mm + 4.0 or sample.width_mm < c.pocket_width_mm + 4.0:
        short = sample.length_mm < c.pocket_length_mm + 4.0
        p.add("sample.length_mm" if short else "sample.width_mm",
              sample.length_mm if short else sample.width_mm,
              f">= vacuum pocket + 4 mm ({fmt(c.pocket_length_mm + 4)} x "
              f"{fmt(c.pocket_width_mm + 4)} mm)", "the sample must seal the pocket with a 2 mm margin")
    h, wall, tapped = holder, holder_table.wall_mm, holder_table.tapped_depth_mm
    p.within("sample_holder.tapped_depth_mm", tapped, hi=c.thickness_mm - 1.0)
    if h.outer_length_mm > c.length_mm or h.outer_width_mm > c.width_mm:
        p.add("sample_holder.wall_mm", wall,
              f"<= {fmt(min((c.length_mm - h.window_length_mm) / 2, (c.width_mm - h.window_width_mm) / 2))} mm",
              "the holder must fit on the cart")
    d, screw_y = h.screw.nominal_diameter_mm, h.screw_y_mm
    if screw_y - d / 2 < c.channel_diameter_mm / 2 + 1.0 or screw_y + d / 2 > c.width_mm / 2 - 1.0:
        p.add("sample_holder.wall_mm", wall, "a value that keeps the holder screws "
              "1 mm from the vacuum channel and the cart's sides")
    if screw_y - d / 2 < c.pocket_width_mm / 2 + 1.0:
        p.add("cart.pocket_width_mm", c.pocket_width_mm,
              f"<= {fmt(2 * (screw_y - d / 2 - 1.0))} mm",
              "the holder screws must stay 1 mm outside the vacuum pocket")


def derive(c: CartSection, context, p: Problems) -> PartData:
    """The cart and its wheels, carrying the sample (``sample``) in the holder
    (``sample_holder``)."""
    bearing, axle_bolt, axle_len = _wheels(c, p)
    hole_xs = _vacuum(c, p)
    holder, holder_table = context.part("sample_holder").geometry, context.table("sample_holder")
    _carried(c, context.part("sample").geometry, holder, holder_table, p)
    g = CartGeometry(
        length_mm=c.length_mm, width_mm=c.width_mm, thickness_mm=c.thickness_mm, bearing=bearing,
        axle_bolt=axle_bolt, axle_bolt_length_mm=axle_len, axle_height_mm=c.axle_height_mm,
        axle_x_mm=c.length_mm / 2 - c.axle_inset_mm, axle_hole_depth_mm=c.axle_hole_depth_mm,
        spacer_outer_diameter_mm=c.spacer_outer_diameter_mm,
        spacer_inner_diameter_mm=axle_bolt.clearance_hole_mm,
        spacer_thickness_mm=c.spacer_thickness_mm, pocket_length_mm=c.pocket_length_mm,
        pocket_width_mm=c.pocket_width_mm, pocket_depth_mm=c.pocket_depth_mm,
        suction_hole_diameter_mm=c.suction_hole_diameter_mm, suction_hole_xs_mm=hole_xs,
        channel_diameter_mm=c.channel_diameter_mm,
        channel_end_x_mm=hole_xs[-1] + c.suction_hole_diameter_mm / 2 + c.channel_diameter_mm / 2,
        port_diameter_mm=c.port_diameter_mm, port_depth_mm=c.port_depth_mm,
        holder_screw_y_mm=holder.screw_y_mm,
        holder_screw_diameter_mm=holder.screw.nominal_diameter_mm,
        holder_tapped_depth_mm=holder_table.tapped_depth_mm)
    return PartData(**_cart(g), companions=(_spacer(g), _bearing(g.bearing)),
                    fasteners=(Fastener(g.axle_bolt, g.axle_bolt_length_mm, WHEEL_BOLT_COLOR),),
                    derived=(Derived("wheel_screw_length", axle_len, "mm",
                                     f"shortest stock {axle_bolt.size} >= wheel "
                                     f"{fmt(bearing.width_mm)} + spacer "
                                     f"{fmt(c.spacer_thickness_mm)} + 1.5 d of thread"),))


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


def _cart(k: CartGeometry) -> dict:
    """The cart plate's :class:`PartData` fields (volume from the features)."""
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
    frames = {"top": Seat((0, 0, T), (0, 0, 1), (1, 0, 0))}
    for sx in (-1, 1):
        for sy in (-1, 1):
            frames["axle_" + wheel_tag(sx, sy)] = Seat(
                (sx * k.axle_x_mm, sy * W / 2, k.axle_height_mm), (0, sy, 0), (1, 0, 0))
    return dict(
        name="cart", kind="fabricated",
        process=Process("milling and drilling from plate", Method.PLATE), material=PLATE_ALUMINIUM,
        color=COLOR, expected_volume_mm3=L * W * T - pocket - port - channel - suction - tapped - axles,
        expected_bbox_mm=(-L / 2, -W / 2, 0.0, L / 2, W / 2, float(T)), geometry=k, frames=frames)


def _spacer(k: CartGeometry) -> PartData:
    ro, ri, t = k.spacer_outer_diameter_mm / 2, k.spacer_inner_diameter_mm / 2, k.spacer_thickness_mm
    return PartData(
        name="wheel_spacer", kind="fabricated", process=Process("turning", Method.ROUND_BAR),
        material=TURNED_BRASS, color=SPACER_COLOR, expected_volume_mm3=math.pi * (ro * ro - ri * ri) * t,
        expected_bbox_mm=(-ro, -ro, 0.0, ro, ro, float(t)), geometry=k, builder="wheel_spacer",
        frames={"cart_side": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "wheel_side": Seat((0, 0, t), (0, 0, 1), (1, 0, 0))})


def _bearing(b: BearingSpec) -> PartData:
    R, rb = b.outer_diameter_mm / 2, b.bore_mm / 2
    return PartData(
        name=f"bearing_{b.designation}", kind="purchased",
        process=Process(f"deep groove ball bearing {b.designation}, ISO 15: d {b.bore_mm:g} x D "
                        f"{b.outer_diameter_mm:g} x B {b.width_mm:g} mm", Method.BOUGHT),
        material="bearing steel", color=BEARING_COLOR,
        expected_volume_mm3=math.pi * (R * R - rb * rb) * b.width_mm,
        expected_bbox_mm=(-R, -R, 0.0, R, R, float(b.width_mm)), geometry=b, builder="bearing",
        frames={"inner": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "outer": Seat((0, 0, b.width_mm), (0, 0, 1), (1, 0, 0)),
                "tread": Seat((0, -R, b.width_mm / 2), (0, -1, 0), (1, 0, 0))})


def build(g: CartGeometry):
    """The cart's top plate (a kernel ``Solid``; see the module doc)."""
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    plate = box(-L / 2, -W / 2, 0, L / 2, W / 2, T)
    pocket = extrude(rounded_rect_face(g.pocket_length_mm, g.pocket_width_mm,
                                       POCKET_CORNER_RADIUS_MM, z=T - g.pocket_depth_mm),
                     g.pocket_depth_mm)
    zc = T / 2
    x_port = -L / 2
    tools = [pocket,
             cylinder(g.port_diameter_mm / 2, (x_port, 0, zc), (1, 0, 0), g.port_depth_mm),
             # the channel starts inside the port so the two cuts overlap (robust boolean)
             cylinder(g.channel_diameter_mm / 2, (x_port + g.port_depth_mm / 2, 0, zc), (1, 0, 0),
                      g.channel_end_x_mm - x_port - g.port_depth_mm / 2)]
    for x in g.suction_hole_xs_mm:  # from the channel axis up into the pocket
        tools.append(cylinder(g.suction_hole_diameter_mm / 2, (x, 0, zc), (0, 0, 1), T - zc))
    for s in (-1, 1):
        tools.append(cylinder(g.holder_screw_diameter_mm / 2,
                              (0, s * g.holder_screw_y_mm, T - g.holder_tapped_depth_mm),
                              (0, 0, 1), g.holder_tapped_depth_mm))
        for sx in (-1, 1):
            tools.append(cylinder(g.axle_bolt.nominal_diameter_mm / 2,
                                  (sx * g.axle_x_mm, s * W / 2, g.axle_height_mm), (0, -s, 0),
                                  g.axle_hole_depth_mm))
    return single(plate.cut(*tools))


def build_wheel_spacer(g: CartGeometry):
    """Spacer ring (build123d ``Solid``) between the cart side and the wheel's
    inner ring, axis z."""
    return ring(g.spacer_inner_diameter_mm / 2, g.spacer_outer_diameter_mm / 2,
                g.spacer_thickness_mm)


def build_bearing(b: BearingSpec):
    """Deep groove ball bearing envelope (build123d ``Solid``): annulus d ... D, z = 0 ... B."""
    return ring(b.bore_mm / 2, b.outer_diameter_mm / 2, b.width_mm)


def section(d, solid, pen) -> None:
    """Section A-A of the shop drawing: the mid plane y = 0 (through the
    channel, the port and the suction holes), seen from -y."""
    g = d.spec.geometry
    pen.add_section(d, solid, (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), g.length_mm, g.thickness_mm)


def dimensions(d, solid, pen) -> None:
    """The shop drawing's dimension set (drawn with the drawings layer's
    ``pen``): outline and pocket in the front view (from +z), the wheel
    axles' tapped holes in the view from above (from +y), the hose port in
    the view from the left (from -x), channel, port, suction holes and pocket
    depth in section A-A."""
    g, fmt_mm, dim, thread_text = d.spec.geometry, pen.fmt_mm, pen.dim, pen.thread_text
    f, t, lv, sv = d.front, d.views["top"], d.views["left"], d.views["section"]
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    pl, pw = g.pocket_length_mm, g.pocket_width_mm
    # front view: outline, pocket, holder screws
    dim(d, f, (-pl / 2, pw / 2), (pl / 2, pw / 2), "h", "top", 0, fmt_mm(pl), "pocket_length")
    dim(d, f, (-L / 2, W / 2), (L / 2, W / 2), "h", "top", 1, fmt_mm(L), "overall_length")
    dim(d, f, (pl / 2, -pw / 2), (pl / 2, pw / 2), "v", "right", 0, fmt_mm(pw), "pocket_width")
    dim(d, f, (L / 2, -W / 2), (L / 2, W / 2), "v", "right", 1, fmt_mm(W), "overall_height")
    ys = g.holder_screw_y_mm
    dim(d, f, (0.0, -ys), (0.0, ys), "v", "left", 0, fmt_mm(2 * ys), "holder_screw_spacing")
    holes = [pen.Hole2D(0.0, s * ys, g.holder_screw_diameter_mm) for s in (-1, 1)]
    pen.hole_marks(d, f, holes)
    d.sheet.line("centre-lines", f.paper(0.0, -W / 2 - 2.0), f.paper(0.0, W / 2 + 2.0), "centre")
    fb = f.paper_box()
    texts = {
        # both leaders end below the view, clear of its edges and of each other
        "holder_thread": (f"2× {thread_text(g.holder_screw_diameter_mm, g.holder_tapped_depth_mm)}",
                          f.paper(g.holder_screw_diameter_mm / 2 * 0.7, -ys - 0.7),
                          (fb[0] + 0.62 * (fb[2] - fb[0]), fb[3] + 12.0)),
        "pocket": (f"pocket depth {fmt_mm(g.pocket_depth_mm)}, 4× R{fmt_mm(POCKET_CORNER_RADIUS_MM)}",
                   f.paper(-pl / 2, -pw / 2 + POCKET_CORNER_RADIUS_MM * 2),
                   (fb[0] + 8.0, fb[3] + 6.0)),
    }
    for name, (text, at, to) in texts.items():
        d.sheet.leader([at, to], text, name)
        d.dimensions[name] = text
    # view from above (u = x, v = -z): axles
    ax, ah = g.axle_x_mm, g.axle_height_mm
    dim(d, t, (-ax, -ah), (ax, -ah), "h", "below", 0, fmt_mm(2 * ax), "axle_spacing")
    dim(d, t, (-L / 2, 0.0), (-ax, -ah), "v", "left", 0, fmt_mm(ah), "axle_height")
    pen.hole_marks(d, t, [pen.Hole2D(s * ax, -ah, g.axle_bolt.nominal_diameter_mm) for s in (-1, 1)])
    axle = (f"4× {thread_text(g.axle_bolt.nominal_diameter_mm, g.axle_hole_depth_mm)} "
            f"(both sides)")
    tb = t.paper_box()
    d.sheet.leader([t.paper(ax + 1.0, -ah - 1.0), (tb[2] - 10.0, tb[3] + 12.0)], axle, "axle_thread")
    d.dimensions["axle_thread"] = axle
    pen.thickness_dim(d)
    # view from the left (u = z, v = y): the hose port
    port = thread_text(g.port_diameter_mm, g.port_depth_mm)
    lb = lv.paper_box()
    pen.hole_marks(d, lv, [pen.Hole2D(T / 2, 0.0, g.port_diameter_mm)])
    d.sheet.leader([lv.paper(T / 2 + g.port_diameter_mm / 2 * 0.7, g.port_diameter_mm / 2 * 0.7),
                    (lb[2] + 6.0, lb[1] - 4.0)], f"hose port {port}", "port_thread")
    d.dimensions["port_thread"] = f"hose port {port}"
    # section A-A (u = x, v = z)
    xs = g.suction_hole_xs_mm
    dim(d, sv, (-L / 2, T), (xs[0], T), "h", "top", 0, fmt_mm(xs[0] + L / 2), "suction_hole_first_x")
    if len(xs) > 1:
        dim(d, sv, (xs[0], T), (xs[1], T), "h", "top", 1, fmt_mm(xs[1] - xs[0]), "suction_hole_pitch")
    dim(d, sv, (-L / 2, T / 2), (-L / 2 + g.port_depth_mm, T / 2), "h", "below", 0,
        fmt_mm(g.port_depth_mm), "port_depth")
    dim(d, sv, (-L / 2, T / 2), (g.channel_end_x_mm, T / 2), "h", "below", 1,
        fmt_mm(g.channel_end_x_mm + L / 2), "channel_length")
    dim(d, sv, (L / 2, 0.0), (g.channel_end_x_mm, T / 2), "v", "right", 0, fmt_mm(T / 2),
        "channel_height")
    dim(d, sv, (L / 2, T), (pl / 2, T - g.pocket_depth_mm), "v", "right", 1,
        fmt_mm(g.pocket_depth_mm), "pocket_depth")
    sb = sv.paper_box()
    ch = f"channel Ø{fmt_mm(g.channel_diameter_mm)}"
    d.sheet.leader([sv.paper(g.channel_end_x_mm - 4.0, T / 2 - g.channel_diameter_mm / 2),
                    (sv.paper(g.channel_end_x_mm, 0.0)[0] + 4.0, sb[3] + 5.0)], ch, "channel_diameter")
    d.dimensions["channel_diameter"] = ch
    sh_text = f"{len(xs)}× Ø{fmt_mm(g.suction_hole_diameter_mm)} to channel"
    d.sheet.leader([sv.paper(xs[-1] + g.suction_hole_diameter_mm / 2, T - 1.5),
                    (sb[0] + 0.72 * (sb[2] - sb[0]), sb[1] - 2 * pen.TIER - pen.FIRST_TIER)], sh_text,
                   "suction_holes")
    d.dimensions["suction_holes"] = sh_text
    pen.section_marks(d, "front", "A-A")


def notes_after(g: CartGeometry, pen) -> list[str]:
    """The shop drawing's note after the process note: drilling the vacuum
    channel and holes, sealing faces."""
    return [f"Vacuum: drill the channel Ø{pen.fmt_mm(g.channel_diameter_mm)} from the "
            f"port end (section A-A), then the suction holes from the pocket floor into it; deburr "
            f"the channel and holes so no chip stays inside. Top face and pocket rim: "
            f"flatness 0.05 (ISO 1101), so the sample seals on the vacuum."]


PART = RigPart(key="cart", section=CartSection, host="", derive=derive, build=build,
               needs=("sample", "sample_holder"), order=20,
               companion_builders={"wheel_spacer": build_wheel_spacer, "bearing": build_bearing},
               drawing=DrawingRecord(hole_table=False, dimensions=dimensions, section=section,
                                     notes_after=notes_after))
