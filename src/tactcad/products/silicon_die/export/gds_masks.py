"""The silicon die's masks as GDSII (gdstk): one layer per mask of
:data:`tactcad.products.silicon_die.vocabulary.soi_process.MASKS`, for the die and for a wafer of dies.

The polygons come from the die's plan alone (:func:`die_polygons`, a pure function of
:class:`tactcad.products.silicon_die.design.mems_die.DiePlan`); the writers put them into cells. The GDS
database unit is 1 nm, the user unit 1 um. Files are written whole or not at all (a
temporary file beside the target, renamed).

Each beam's outline (:func:`beam_outline`) carries a fillet of the plan's
``root_fillet_um`` at each root corner, where a sidewall meets the window's edge: the device
etch's mask, the STEP solid and the checks all read it.

Layout per beam (beam-local u across it, v along it from the root towards the tip):
the U-shaped resistor runs from v = -run on the frame to v = l_res on the beam; a contact
sits at each leg's end on the frame, covered by metal that runs in a jog to a bond pad on
the frame behind it. Beside it on the frame (its axis at u = REFERENCE_AXIS_UM), the
reference resistor, a U of the same implant, legs and gap, its closed end
REFERENCE_CLEAR_UM from the window's edge and its contacts below. The two resistors form
the beam's half bridge: pad 1 (u < 0) the beam resistor's first end, pad 2 (u > 0) the
middle node (the beam resistor's second end and the reference's first, whose lead jogs
below both), pad 3 (u = THIRD_PAD_AXIS_UM) the reference's second end.
"""

from __future__ import annotations

import math
from pathlib import Path

from tactcad.products.silicon_die.design import mems_die as md
from tactcad.products.silicon_die.design.mems_die import Beam, DiePlan
from tactcad.products.silicon_die.vocabulary.soi_process import MASK_BY_NAME

#: GDSII units: 1 um user unit, 1 nm database unit.
GDS_UNIT_M, GDS_PRECISION_M = 1e-6, 1e-9
#: A wafer layout's defaults: diameter and edge exclusion (mm), dicing lane (um).
WAFER_MM, EDGE_EXCLUSION_MM, DICING_LANE_UM = 100.0, 5.0, 100.0

Polygon = list[tuple[float, float]]


def _rect(x0: float, y0: float, x1: float, y1: float) -> Polygon:
    return [(min(x0, x1), min(y0, y1)), (max(x0, x1), min(y0, y1)),
            (max(x0, x1), max(y0, y1)), (min(x0, x1), max(y0, y1))]


def _local(beam: Beam, points) -> Polygon:
    """Beam-local (u across, v from the root towards the tip) to die coordinates (um)."""
    return [(beam.x_um + u, beam.y_root_um + beam.direction * v) for u, v in points]


#: Straight segments each root fillet's quarter circle is drawn with: the chords lie within
#: r (1 - cos(pi / 4 / n)) of the arc, 0.2 % of r at 16 (8 nm at the 4 um default, under
#: the DRIE's +-0.5 um bias and on the GDS's 1 nm grid).
FILLET_SEGMENTS = 16


def fillet_arc(radius_um: float, half_width_um: float, side: int,
               segments: int = FILLET_SEGMENTS) -> Polygon:
    """One root fillet's quarter circle (beam-local u across, v from the root, um), from
    the window's edge (v = 0, u = side (w/2 + r)) to the beam's sidewall (u = side w/2,
    v = r): the arc tangent to both, centred at (side (w/2 + r), r), ``segments`` + 1
    vertices.

    Args:
        radius_um: r, > 0. half_width_um: w / 2. side: -1 (the beam's u < 0 side) or +1.
        segments: chords along the quarter circle, >= 1.

    Returns:
        The arc's vertices, from the window's edge to the sidewall.
    """
    cu, cv = side * (half_width_um + radius_um), radius_um
    out = []
    for i in range(segments + 1):
        a = 0.5 * math.pi * i / segments  # 0 at the window's edge, pi/2 at the sidewall
        out.append((cu - side * radius_um * math.sin(a), cv - radius_um * math.cos(a)))
    return out


def beam_outline(plan: DiePlan, beam: Beam) -> Polygon:
    """The beam in the device layer over the window: root to the post's far edge, with a
    fillet of the plan's ``root_fillet_um`` where each sidewall meets the window's edge
    (:func:`fillet_arc`); one polygon (um), counter-clockwise. The masks, the solid and the
    checks all take the beam's outline from here."""
    w, reach, r = beam.width_um, beam.length_um + plan.post_um / 2, plan.root_fillet_um
    right = fillet_arc(r, w / 2, +1)  # from (w/2 + r, 0) up to (w/2, r)
    left = fillet_arc(r, w / 2, -1)[::-1]  # from (-w/2, r) down to (-w/2 - r, 0)
    return _local(beam, [*right, (w / 2, reach), (-w / 2, reach), *left])


def _u_shape(legs_um: float, u0: float = 0.0, v0: float = 0.0) -> Polygon:
    """A U of the implant's legs and gap (beam-local u, v; counter-clockwise): open end
    (the contacts) at v0 - run, closed end at v0 + legs_um, axis at u0."""
    g, leg, run, l = md.LEG_GAP_UM, md.LEG_UM, md.RESISTOR_RUN_UM, legs_um
    h = g / 2 + leg
    return [(u0 + u, v0 + v) for u, v in
            [(-h, -run), (-g / 2, -run), (-g / 2, l - leg), (g / 2, l - leg), (g / 2, -run),
             (h, -run), (h, l), (-h, l)]]


def resistor_outline(plan: DiePlan, beam: Beam) -> Polygon:
    """The beam's U-shaped implant at its root (one polygon, counter-clockwise)."""
    return _local(beam, _u_shape(plan.resistor_length_um))


def reference_resistor_outline(plan: DiePlan, beam: Beam) -> Polygon:
    """The beam's reference resistor on the frame (one polygon, counter-clockwise)."""
    return _local(beam, _u_shape(plan.reference_resistor_length_um, md.REFERENCE_AXIS_UM,
                                 md.reference_resistor_v0_um(plan)))


def _contact_centres(plan: DiePlan) -> list[tuple[float, float]]:
    """The four contacts' centres (beam-local): on each leg of each U, a contact's
    enclosure from the leg's open end; the beam resistor's two, then the reference's."""
    u = md.LEG_GAP_UM / 2 + md.LEG_UM / 2
    v = -md.RESISTOR_RUN_UM + md.LEG_UM / 2
    a, v_ref = md.REFERENCE_AXIS_UM, md.reference_resistor_v0_um(plan) + v
    return [(-u, v), (u, v), (a - u, v_ref), (a + u, v_ref)]


def contact_outlines(plan: DiePlan, beam: Beam) -> list[Polygon]:
    c = md.CONTACT_UM / 2
    return [_local(beam, _rect(u - c, v - c, u + c, v + c))
            for u, v in _contact_centres(plan)]


def metal_outlines(plan: DiePlan, beam: Beam) -> list[Polygon]:
    """The half bridge's three nets, each its contacts' covers, leads and bond pad, merged
    (beam-local construction; the nets do not touch): pad 1 the beam resistor's first end,
    pad 2 the middle node, pad 3 the reference's second end."""
    half, lead = md.CONTACT_UM / 2 + md.METAL_ENCLOSURE_UM, md.LEAD_UM / 2
    pad_v0 = -md.PAD_SETBACK_UM
    pad_v1 = pad_v0 - md.PAD_UM
    (ua, va), (ub, vb), (uc, vc), (ud, vd) = _contact_centres(plan)
    jog_v = -md.RESISTOR_RUN_UM - md.LEAD_JOG_UM
    ref_jog_v = vc - md.LEG_UM / 2 - md.LEAD_JOG_UM

    def pad(u_axis):
        return pad_rect(u_axis)

    def cover(u, v):
        return (u - half, v - half, u + half, v + half)

    def route(u, v, jog, u_axis, into_pad_from_below=False):
        """Down from a contact to the jog, along it to the pad's axis, then into the pad."""
        x0, x1 = sorted((u, u_axis))
        stem = ((u_axis - lead, jog - lead, u_axis + lead, pad_v1) if into_pad_from_below
                else (u_axis - lead, pad_v0, u_axis + lead, jog))
        return [cover(u, v), (u - lead, jog - lead, u + lead, v),
                (x0 - lead, jog - lead, x1 + lead, jog + lead), stem]

    first, middle, third = pad_axes_um()
    nets = [route(ua, va, jog_v, first) + [pad(first)],
            route(ub, vb, jog_v, middle) + route(uc, vc, ref_jog_v, middle, True)
            + [pad(middle)],
            route(ud, vd, ref_jog_v, third, True) + [pad(third)]]
    return [_local(beam, p) for net in nets for p in _union_of_rects(net)]


def pad_rect(u_axis: float, inset: float = 0.0) -> tuple[float, float, float, float]:
    """A bond pad on its axis ``u_axis`` (beam-local u0, v0, u1, v1, um), shrunk by
    ``inset`` on every side."""
    v0 = -md.PAD_SETBACK_UM
    return (u_axis - md.PAD_UM / 2 + inset, v0 - md.PAD_UM + inset,
            u_axis + md.PAD_UM / 2 - inset, v0 - inset)


def pad_axes_um() -> tuple[float, float, float]:
    """The three bond pads' axes of a beam's half bridge (beam-local u, um)."""
    first = -(md.PAD_SPACE_UM / 2 + md.PAD_UM / 2)
    return first, -first, md.THIRD_PAD_AXIS_UM


def pad_openings(plan: DiePlan, beam: Beam) -> list[Polygon]:
    """The hard mask's openings over ``beam``'s three bond pads (um): each pad inset by
    :data:`~tactcad.products.silicon_die.vocabulary.soi_process.PAD_OPEN_INSET_UM`."""
    from tactcad.products.silicon_die.vocabulary.soi_process import PAD_OPEN_INSET_UM

    return [_local(beam, _rect(*pad_rect(u, PAD_OPEN_INSET_UM))) for u in pad_axes_um()]


def alignment_marks(plan: DiePlan) -> tuple[list[Polygon], list[Polygon]]:
    """The handle's alignment marks, a cross in each end of the die's frame, and the windows
    cleared over them in the device layer (um): (marks, windows)."""
    from tactcad.products.silicon_die.vocabulary.soi_process import (MARK_ARM_UM,
                                                                     MARK_WIDTH_UM,
                                                                     MARK_WINDOW_MARGIN_UM)

    arm, half = MARK_ARM_UM / 2, MARK_WIDTH_UM / 2
    marks, windows = [], []
    for x in (plan.end_um / 2, plan.die_length_um - plan.end_um / 2):
        y = plan.die_width_um / 2
        marks += _union_of_rects([(x - arm, y - half, x + arm, y + half),
                                  (x - half, y - arm, x + half, y + arm)])
        reach = arm + MARK_WINDOW_MARGIN_UM
        windows.append(_rect(x - reach, y - reach, x + reach, y + reach))
    return marks, windows


def _union_of_rects(rects) -> list[Polygon]:
    import gdstk

    polys = [gdstk.rectangle((x0, y0), (x1, y1)) for x0, y0, x1, y1 in rects]
    merged = gdstk.boolean(polys[:1], polys[1:], "or", precision=1e-3)
    return [[tuple(p) for p in poly.points] for poly in merged]


def post_outline(plan: DiePlan, beam: Beam) -> Polygon:
    p = plan.post_um / 2
    return _local(beam, _rect(-p, beam.length_um - p, p, beam.length_um + p))


def die_polygons(plan: DiePlan) -> dict[str, list[Polygon]]:
    """Every mask's polygons of the die (um), keyed by mask name
    (:data:`tactcad.products.silicon_die.vocabulary.soi_process.MASKS`)."""
    import gdstk

    window = _rect(*plan.window_um)
    beams = [beam_outline(plan, b) for b in plan.beams]
    etched = gdstk.boolean(gdstk.Polygon(window), [gdstk.Polygon(b) for b in beams], "not",
                           precision=1e-3)
    marks, windows = alignment_marks(plan)
    return {
        "die": [_rect(0.0, 0.0, plan.die_length_um, plan.die_width_um)],
        "align": marks,
        "mark_window": windows,
        "pad_open": [o for b in plan.beams for o in pad_openings(plan, b)],
        "cavity_reference": [_rect(*plan.cavities_um["reference"])],
        "cavity_measuring": [_rect(*plan.cavities_um["measuring"])],
        "device_etch": [[tuple(p) for p in poly.points] for poly in etched],
        "tip": [post_outline(plan, b) for b in plan.beams],
        "piezo": [r for b in plan.beams
                  for r in (resistor_outline(plan, b), reference_resistor_outline(plan, b))],
        "contact": [c for b in plan.beams for c in contact_outlines(plan, b)],
        "metal": [m for b in plan.beams for m in metal_outlines(plan, b)],
    }


def die_cell(plan: DiePlan):
    """A gdstk cell named for the die holding :func:`die_polygons` on their layers."""
    import gdstk

    cell = gdstk.Cell(plan.name.upper())
    for mask, polys in die_polygons(plan).items():
        m = MASK_BY_NAME[mask]
        for p in polys:
            cell.add(gdstk.Polygon(p, layer=m.gds_layer, datatype=m.datatype))
    return cell


def wafer_sites(plan: DiePlan, wafer_mm: float = WAFER_MM,
                edge_exclusion_mm: float = EDGE_EXCLUSION_MM,
                lane_um: float = DICING_LANE_UM) -> list[tuple[float, float]]:
    """Lower-left corners (um) of the dies a wafer holds whole inside its usable radius,
    on a grid of die + dicing lane centred on the wafer."""
    usable = (wafer_mm / 2 - edge_exclusion_mm) * 1e3
    sx, sy = plan.die_length_um + lane_um, plan.die_width_um + lane_um
    nx, ny = int(2 * usable // sx) + 2, int(2 * usable // sy) + 2
    sites = []
    for i in range(-nx // 2, nx // 2 + 1):
        for j in range(-ny // 2, ny // 2 + 1):
            x0, y0 = i * sx - plan.die_length_um / 2, j * sy - plan.die_width_um / 2
            corners = [(x0, y0), (x0 + plan.die_length_um, y0), (x0, y0 + plan.die_width_um),
                       (x0 + plan.die_length_um, y0 + plan.die_width_um)]
            if all(math.hypot(x, y) <= usable for x, y in corners):
                sites.append((x0, y0))
    return sites


def gds_timestamp():
    """The time a GDSII library's header records: ``SOURCE_DATE_EPOCH`` (the
    reproducible-builds convention) when set, else 1970-01-01 UTC; never the clock, so that
    the same die writes the same bytes (gdstk stamps the current time otherwise).

    Raises:
        DesignError: ``SOURCE_DATE_EPOCH`` is not a whole number of seconds (named).
    """
    import datetime
    import os

    from tactcad.drawings.frame import epoch_date

    epoch_date(os.environ)  # a bad value refused by name
    seconds = int(os.environ.get("SOURCE_DATE_EPOCH", "").strip() or 0)
    return datetime.datetime.fromtimestamp(seconds, datetime.timezone.utc).replace(tzinfo=None)


def _write(lib, path: Path) -> Path:
    """``lib`` to ``path`` whole (:func:`tactcad.atomic.write_atomic`), stamped
    :func:`gds_timestamp`."""
    from tactcad.atomic import write_atomic

    stamp = gds_timestamp()
    return write_atomic(path, lambda tmp: lib.write_gds(str(tmp), timestamp=stamp))


def write_die_gds(plan: DiePlan, path: Path) -> Path:
    """The die's masks as one top cell (GDSII, um / nm)."""
    import gdstk

    lib = gdstk.Library(plan.name, unit=GDS_UNIT_M, precision=GDS_PRECISION_M)
    lib.add(die_cell(plan))
    return _write(lib, path)


def write_wafer_gds(plan: DiePlan, path: Path, wafer_mm: float = WAFER_MM,
                    edge_exclusion_mm: float = EDGE_EXCLUSION_MM) -> tuple[Path, int]:
    """A wafer of dies (a ``WAFER`` top cell referencing the die cell at every site, and
    the wafer's outline and usable circle on layer 11); returns (path, dies)."""
    import gdstk

    lib = gdstk.Library(f"{plan.name}_wafer", unit=GDS_UNIT_M, precision=GDS_PRECISION_M)
    die = die_cell(plan)
    wafer = gdstk.Cell("WAFER")
    sites = wafer_sites(plan, wafer_mm, edge_exclusion_mm)
    for x, y in sites:
        wafer.add(gdstk.Reference(die, (x, y)))
    wafer.add(gdstk.ellipse((0, 0), wafer_mm / 2 * 1e3, layer=11, tolerance=1.0))
    lib.add(die, wafer)
    return _write(lib, path), len(sites)


#: The mask picture's size (pixels).
PICTURE_PX = (1600, 640)


def write_mask_picture(gds_path: Path, png_path: Path, size_px: tuple[int, int] = PICTURE_PX
                       ) -> Path:
    """A picture of every mask layer of the GDS at ``gds_path`` (PNG; KLayout's own
    renderer, headless), written whole."""
    import klayout.lay as lay

    from tactcad.atomic import write_atomic

    view = lay.LayoutView()
    view.load_layout(str(gds_path), True)
    view.max_hier()
    view.add_missing_layers()
    view.zoom_fit()
    return write_atomic(png_path, lambda tmp: view.save_image(str(tmp), *size_px))
