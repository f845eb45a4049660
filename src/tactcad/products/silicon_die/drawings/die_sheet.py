"""The drawing of a silicon die and its carrier: one A3 sheet (ISO 5457 frame).

* the die in plan at the largest of :data:`DIE_SCALES` at which it fits its room
  (:data:`DIE_ROOM_MM`), device side up: its outline, the two rows' cavities in the handle
  (hidden, dashed), each beam and its post, dimensioned: the die's length and width, the
  pitch, both beams' lengths from their roots, the beam width and the post;
* below it the carrier in plan at the largest of :data:`CARRIER_SCALES` that fits
  :data:`CARRIER_ROOM_MM`: its length, width and bond shelf;
* notes: the wafer and the beams' direction, the layer stack with the device layer's
  tolerance (the one the beams' stiffness goes as the cube of), the cavities' depth
  tolerance, the carrier's material, thickness and die attach; units; the process's
  tolerances on the beams' lengths (the front masks' alignment to the cavities), the
  beams' width (DRIE's bias) and the die's outline (dicing), printed on those dimensions.

A die is made by its masks (the GDS is the master; this sheet is for reading and
inspection), so the dimensions are the plan's, in mm on the sheet.

Units: mm on paper; die dimensions given in mm (um in the notes).
"""

from __future__ import annotations

from tactcad.products.silicon_die.design.die_mount import DieMount
from tactcad.products.silicon_die.design.mems_die import DiePlan
from tactcad.drawings.frame import FRAME, sheet_frame, title_cells
from tactcad.drawings.sheet import Sheet, fmt_mm
from tactcad.drawings.views import fitting_scale
from tactcad.drawings.dimensioning import plus_minus
from tactcad.products.silicon_die.vocabulary.soi_process import (CAVITY_ALIGNMENT_UM,
                                                                 CAVITY_DEPTH_TOLERANCE_REL,
                                                                 DICING_TOLERANCE_UM,
                                                                 DRIE_WIDTH_TOLERANCE_UM)

#: Scales of the die's and of the carrier's plan views (paper mm per mm), largest first: a
#: view takes the largest at which it fits its room (ISO 5455's enlargements, and 40:1 and
#: 15:1, the example's).
DIE_SCALES = (40.0, 20.0, 10.0, 5.0, 2.0)
CARRIER_SCALES = (15.0, 10.0, 5.0, 2.0)
#: The room of the die's plan view (paper mm, along and across the die): the frame's width
#: less the beams' length dimensions on the left and the die's width on the right, and the
#: top part of the sheet (the carrier and the notes below it).
DIE_ROOM_MM = (330.0, 110.0)
#: The carrier's room (paper mm): left of the notes, under the die's view.
CARRIER_ROOM_MM = (170.0, 60.0)
NOTE_MM = 2.5


#: The die's dimensions print to 0.1 um (mm to four places): a beam's width is the pitch
#: less a DRIE slot in 5 um steps (92.5 um on a 50 um layer), its length any length.
DIE_DECIMALS = 4


def die_sheet(plan: DiePlan, mount: DieMount, post_height=None) -> Sheet:
    """The die's and its carrier's sheet (see the module doc)."""
    sh = Sheet("A3", title=f"{plan.name}: die and carrier")
    sheet_frame(sh)
    x0, y0 = FRAME[0] + 35.0, FRAME[1] + 40.0  # the die's corner (x = 0, y = die width)
    die_scale = fitting_scale((plan.die_length_um / 1000, plan.die_width_um / 1000), DIE_ROOM_MM,
                              DIE_SCALES)
    carrier_scale = fitting_scale((mount.carrier_length_mm, mount.carrier_width_mm),
                                  CARRIER_ROOM_MM, CARRIER_SCALES)
    s = die_scale / 1000.0  # paper mm per um

    def at(x_um: float, y_um: float) -> tuple[float, float]:
        return (x0 + x_um * s, y0 + (plan.die_width_um - y_um) * s)

    length, width = plan.die_length_um, plan.die_width_um
    sh.polyline("die", [at(0, 0), at(length, 0), at(length, width), at(0, width)], "visible",
                closed=True)
    for cx0, cy0, cx1, cy1 in plan.cavities_um.values():
        sh.polyline("die", [at(cx0, cy0), at(cx1, cy0), at(cx1, cy1), at(cx0, cy1)], "hidden",
                    closed=True)
    for b in plan.beams:
        tip = b.tip_y_um + b.direction * plan.post_um / 2
        sh.polyline("die", [at(b.x_um - b.width_um / 2, b.y_root_um),
                            at(b.x_um + b.width_um / 2, b.y_root_um),
                            at(b.x_um + b.width_um / 2, tip),
                            at(b.x_um - b.width_um / 2, tip)], "visible", closed=True)
        p = plan.post_um / 2
        sh.polyline("die", [at(b.x_um - p, b.tip_y_um - p), at(b.x_um + p, b.tip_y_um - p),
                            at(b.x_um + p, b.tip_y_um + p), at(b.x_um - p, b.tip_y_um + p)],
                    "visible", closed=True)
    _die_dimensions(sh, plan, at)
    bottom = at(0, 0)[1]  # the die's lower edge on paper; its dimensions 8 mm below
    _carrier_view(sh, plan, mount, x0, bottom + 45.0, carrier_scale)
    _notes(sh, plan, mount, FRAME[0] + 235.0, bottom + 25.0, post_height)
    _title_block(sh, plan, mount, post_height, (die_scale, carrier_scale))
    return sh


#: The title block's size (paper mm): four rows of 9 mm, the assembly sheet's.
TITLE_BLOCK_MM = (180.0, 36.0)


def die_title_cells(plan: DiePlan, mount: DieMount, post_height,
                    scales: tuple[float, float]) -> list[tuple]:
    """The die sheet's title-block cells (ISO 7200), as
    :func:`~tactcad.drawings.frame.title_cells` takes them: what is drawn and at which
    scales, the design's name with a digest of what the sheet draws (so two sheets of one
    name tell apart), the drawing number, the version that wrote it, the units, the process
    and the date (``SOURCE_DATE_EPOCH``'s, else left for the signer: a die file states
    none).

    Args:
        plan: the die. mount: its carrier. post_height: the posts' height check or None.
        scales: the die's and the carrier's view scales (paper mm per mm).

    Returns:
        ``(row, x offset mm, width mm, label, value, id, value height mm)`` cells.
    """
    import hashlib
    import os

    from tactcad.drawings.sheet import LABEL_TEXT_MM
    from tactcad.drawings.source_date import epoch_date
    from tactcad.store import stable_repr
    from tactcad.version import VERSION

    digest = hashlib.sha256(stable_repr((plan, mount, post_height)).encode()).hexdigest()
    date = epoch_date(os.environ) or "\u2014"
    die_scale, carrier_scale = scales
    cells = [(0, 0, 120, "Drawing", f"silicon die ({plan.rows} x {plan.columns} beams) "
              "and its carrier", "tb-part"),
             (0, 120, 60, "Scale", f"die {die_scale:g}:1, carrier {carrier_scale:g}:1",
              "tb-scale"),
             (1, 0, 120, "Design", f"{plan.name}  sheet sha256 {digest[:12]}", "tb-design"),
             (1, 120, 60, "Drawing no.", f"{plan.name}-die", "tb-number"),
             (2, 0, 120, "Generated by", f"tactcad {VERSION}", "tb-version"),
             (2, 120, 60, "Units", "mm (um in the notes)", "tb-units"),
             (3, 0, 120, "Process", "SOI, DRIE both sides; the GDS masks are the master",
              "tb-process"),
             (3, 120, 25, "Revision", "A", "tb-revision"),
             (3, 145, 35, "Date", date, "tb-date")]
    return [(*c, LABEL_TEXT_MM) for c in cells]


def _title_block(sh: Sheet, plan: DiePlan, mount: DieMount, post_height,
                 scales: tuple[float, float]) -> None:
    tw, th = TITLE_BLOCK_MM
    x0, y0 = FRAME[2] - tw, FRAME[3] - th
    sh.rect("title-block", x0, y0, tw, th, "frame")
    title_cells(sh, x0, y0, th / 4, die_title_cells(plan, mount, post_height, scales))


def _die_dimensions(sh: Sheet, plan: DiePlan, at) -> None:
    length, width = plan.die_length_um, plan.die_width_um
    top, bottom = at(0, width)[1], at(0, 0)[1]
    cut = DICING_TOLERANCE_UM / 1000
    sh.linear_dimension(at(0, width), at(length, width), "h", top - 12.0,
                        plus_minus(length / 1000, cut, DIE_DECIMALS), "die-length")
    sh.linear_dimension(at(length, 0), at(length, width), "v", at(length, 0)[0] + 12.0,
                        plus_minus(width / 1000, cut, DIE_DECIMALS), "die-width")
    ref, meas = plan.beams[0], plan.beams[plan.columns]
    if plan.columns > 1:
        nxt = plan.beams[1]
        sh.linear_dimension(at(ref.x_um, width), at(nxt.x_um, width), "h", top - 6.0,
                            fmt_mm(plan.pitch_um / 1000, DIE_DECIMALS), "pitch")
    for b, name, dx in ((ref, "reference", -8.0), (meas, "measuring", -8.0)):
        sh.linear_dimension(at(b.x_um, b.y_root_um), at(b.x_um, b.tip_y_um), "v",
                            at(0, 0)[0] + dx if b is ref else at(0, 0)[0] + dx - 8.0,
                            plus_minus(b.length_um / 1000, CAVITY_ALIGNMENT_UM / 1000,
                                       DIE_DECIMALS), f"{name}-length")
    last = plan.beams[plan.columns - 1]
    sh.linear_dimension(at(last.x_um - last.width_um / 2, 0),
                        at(last.x_um + last.width_um / 2, 0), "h", bottom + 8.0,
                        plus_minus(last.width_um / 1000, DRIE_WIDTH_TOLERANCE_UM / 1000,
                                   DIE_DECIMALS), "beam-width")


def _carrier_view(sh: Sheet, plan: DiePlan, m: DieMount, x0: float, y0: float,
                  s: float) -> None:
    w, h = m.carrier_length_mm * s, m.carrier_width_mm * s
    sh.rect("carrier", x0, y0, w, h, "visible")
    shelf = (m.die_x0_mm - m.carrier_x0_mm) * s
    sh.line("carrier", (x0 + shelf, y0), (x0 + shelf, y0 + h), "thin")
    _die_label(sh, f"die {plan.name}", (x0 + (shelf + w) / 2, y0 + h / 2),
               w - shelf - 2 * LABEL_MARGIN_MM, (y0, y0 - 14.0))
    sh.linear_dimension((x0, y0 + h), (x0 + w, y0 + h), "h", y0 + h + 10.0,
                        fmt_mm(m.carrier_length_mm), "carrier-length")
    sh.linear_dimension((x0, y0), (x0 + shelf, y0), "h", y0 - 6.0,
                        f"{fmt_mm(m.die_x0_mm - m.carrier_x0_mm)} bond shelf", "bond-shelf")
    sh.linear_dimension((x0 + w, y0), (x0 + w, y0 + h), "v", x0 + w + 10.0,
                        fmt_mm(m.carrier_width_mm), "carrier-width")


#: Clear paper each side of the die's label inside the carrier's outline (mm).
LABEL_MARGIN_MM = 1.0
#: The smallest lettering a drawing carries (ISO 3098-1's smallest nominal height, mm).
SMALLEST_TEXT_MM = 1.8


def _die_label(sh: Sheet, text: str, centre: tuple[float, float], room_mm: float,
               above: tuple[float, float]) -> None:
    """The die's name on the carrier view: centred on the die at the notes' height where it
    fits across the die, smaller (down to ISO 3098's 1.8 mm) where that fits, else above
    the carrier (``above``: its top edge and the label's baseline, mm) with a leader down to
    the die's edge (a long name on a small die)."""
    from tactcad.drawings.sheet import text_width

    full = text_width(text, NOTE_MM)
    height = NOTE_MM * min(1.0, room_mm / full) if full > 0 else NOTE_MM
    if height >= SMALLEST_TEXT_MM:
        sh.text("carrier", (centre[0], centre[1] + height / 2), text, height, anchor="middle")
        return
    edge, baseline = above
    sh.line("carrier", (centre[0], edge), (centre[0], baseline + 0.25 * NOTE_MM + 0.5), "thin")
    sh.text("carrier", (centre[0], baseline), text, NOTE_MM, anchor="middle")


def _notes(sh: Sheet, plan: DiePlan, m: DieMount, x: float, y: float,
           post_height=None) -> None:
    from tactcad.products.silicon_die.vocabulary.soi_process import POST_HEIGHT_TOLERANCE_REL

    st = plan.stack
    post_tol_um = POST_HEIGHT_TOLERANCE_REL * plan.post_height_um
    lines = [
        "NOTES",
        "1. Die: SOI on a (100) wafer, beams along <110>; the GDS masks are the master.",
        f"2. Stack: device {st.device_um:g} um +-{st.device_tolerance_um:g} um (K as t^3), "
        f"buried oxide {st.box_um:g} um,",
        f"   handle {st.handle_um:g} um; posts {plan.post_height_um:g} um +-{post_tol_um:.3g} um "
        f"high, {plan.post_um:g} um square.",
        f"3. Cavities (dashed) in the handle under each row, reference "
        f"{plan.cavity_depths_um[0]:g} um, measuring {plan.cavity_depths_um[1]:g} um deep",
        f"   +-{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %: their floors are the hard stops; the "
        "beams free over them.",
        f"4. Carrier: alumina {m.carrier_mm:g} mm; die attach {m.attach_mm:g} mm "
        "(its material: the BOM).",
        f"5. In the jaw: the device layer flush with the face, the posts "
        f"{m.post_proud_mm * 1000:.4g} um proud.",
        f"6. Dimensions in mm. Tolerances: beam lengths +-{CAVITY_ALIGNMENT_UM:g} um (the "
        "front masks aligned to the",
        f"   cavities' marks), beam width +-{DRIE_WIDTH_TOLERANCE_UM:g} um (DRIE's bias), "
        f"die outline +-{DICING_TOLERANCE_UM:g} um (dicing);",
        "   the pitch and the posts as the masks draw them.",
        *_post_height_note(post_height),
    ]
    for k, text in enumerate(lines):
        sh.text("notes", (x, y + k * (NOTE_MM + 2.0)), text, NOTE_MM, bold=k == 0)


def _post_height_note(post_height) -> list[str]:
    """Note 7, when the K_obj accuracy needs the posts flatter than their process holds: the
    procedure the die then relies on and the mismatch it leaves
    (:attr:`tactcad.in_use.tip_height_drawing.TipHeightDrawing.note`), wrapped to the notes'
    width; none otherwise."""
    import textwrap

    note = None if post_height is None else post_height.note
    if note is None:
        return []
    text = note.replace("+/-", "+-")
    return textwrap.wrap(f"7. {text}", NOTE_WIDTH_CHARS, subsequent_indent="   ")


#: The notes' width in characters (note 6's longest line).
NOTE_WIDTH_CHARS = 92
