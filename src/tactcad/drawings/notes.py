"""The notes block of a part drawing: what to make it from and how, what is
critical and why (the web's stiffness sensitivity from
:func:`tactcad.mechanics.closed_form.web_tolerance_stiffness_change`, the
paper's Table 1 spread from :mod:`tactcad.mechanics.paper.data`), the
strength limit, and the general tolerance; wrapped to the room left of the
title block."""

from __future__ import annotations

from pathlib import Path

from tactcad.catalogue.files import profile_dxf_name, sheet_dxf_name
from tactcad.drawings.drawing import NOTE_LINE, NOTES_TOP, TABLE_COLS, TABLE_ROW, Drawing, part_thickness, web_text
from tactcad.drawings.frame import FRAME, GENERAL_TOLERANCE, TITLE_W, wrap_text
from tactcad.drawings.sheet import DIM_TEXT_MM, LABEL_TEXT_MM, fmt_mm
from tactcad.mechanics.closed_form import web_tolerance_stiffness_change
from tactcad.mechanics.paper.data import largest_equal_arm_spread
from tactcad.mechanics.strength import strength_summary

def notes_for(d: Drawing) -> list[str]:
    plan, spec = d.plan, d.spec
    n: list[str] = []
    if spec.builder == "element":
        g = spec.geometry
        used = [s.number for s in plan.slots if s.geometry.part_name == spec.name]
        a, k0, k1, ratio = largest_equal_arm_spread()
        up, dn = web_tolerance_stiffness_change(g.web_thickness_mm, g.web_tolerance_mm)
        n.append(f"Web thickness {web_text(g)} is the critical dimension: hinge stiffness "
                 f"scales with t^2.5, so the tolerance alone moves stiffness by "
                 f"+{up * 100:.0f} % / -{dn * 100:.0f} %. The paper's as-built elements "
                 f"(Table 1) of equal {fmt_mm(a)} mm arm measured {k0:.2f} and {k1:.2f} N/mm "
                 f"(x{ratio:.2f}). Measure the web of every part and record it.")
        n.append(f"Wire EDM from {fmt_mm(g.sheet_thickness_mm)} mm {spec.material} sheet along "
                 f"the nominal contour of {Path(profile_dxf_name(spec.name, len(used))).name} "
                 f"(or the nested sheet {Path(sheet_dxf_name(spec.material, g.sheet_thickness_mm)).name})"
                 + f"; wire offset is the shop's CAM setting. Start holes "
                 f"Ø{fmt_mm(g.start_hole_diameter_mm)} at the bolt-hole centres.")
        n.append(f"Inside corners not dimensioned: R >= {fmt_mm(plan.edm.min_inside_radius_mm)} "
                 f"(wire radius + spark gap). Do not break the edges of the web or of the "
                 f"contact face; deburr elsewhere.")
        n.append(f"Used as array element{'s' if len(used) > 1 else ''} "
                 + ", ".join(str(k) for k in used)
                 + ". A strain gauge is bonded on the flat top face over the web.")
        st = next(r for r in strength_summary(plan) if r["part_name"] == spec.name)
        n.append(f"Full-scale tip force {st['full_scale_force_N']:.2f} N: yield safety factor "
                 f"{st['yield_safety_factor_at_full_scale']:g} on "
                 f"{fmt_mm(plan.material.yield_strength_MPa)} MPa ({plan.material.grade}), peak "
                 f"web stress {st['stress_MPa_per_N']:.0f} MPa/N ({st['model']}). Do not load "
                 f"the tip beyond it.")
    elif spec.builder == "spacer":
        n.append(f"{sentence(spec.process)}, {spec.material}. Thickness "
                 f"{fmt_mm(plan.spacer.thickness_mm)} = pitch {fmt_mm(plan.pitch_mm)} - sheet "
                 f"{fmt_mm(plan.sheet_thickness_mm)}: it sets the array pitch; faces parallel "
                 f"within 0.01 (ISO 1101).")
    elif spec.builder == "clamp_plate":
        n.append(f"{sentence(spec.process)} from {fmt_mm(part_thickness(spec))} mm {spec.material}"
                 f" plate. Window corners R = cutter radius. Holes Ø"
                 f"{fmt_mm(plan.bolt.clearance_hole_mm)}: ISO 273 medium clearance for "
                 f"{plan.bolt.size}.")
    elif spec.builder == "cart":
        g = spec.geometry
        n.append(f"{sentence(spec.process)}, {spec.material}.")
        n.append(f"Vacuum: drill the channel Ø{fmt_mm(g.channel_diameter_mm)} from the port end "
                 f"(section A-A), then the suction holes from the pocket floor into it; deburr "
                 f"the channel and holes so no chip stays inside. Top face and pocket rim: "
                 f"flatness 0.05 (ISO 1101), so the sample seals on the vacuum.")
    elif spec.builder == "indenter":
        n.append(f"{sentence(spec.process)}, {spec.material}.")
        n.append("The M6 thread screws the indenter onto the force gauge's measuring shaft; "
                 "contact face perpendicular to the thread axis within 0.02 (ISO 1101), so the "
                 "2 x 3 mm face lies flat on the element's tip.")
    else:
        n.append(f"{sentence(spec.process)}, {spec.material}.")
    n.append(f"Untoleranced dimensions: {GENERAL_TOLERANCE}. Dimensions in mm (ISO 129-1), "
             f"first-angle projection. Break sharp edges 0.1 max unless noted.")
    return n


def sentence(text: str) -> str:
    return text[:1].upper() + text[1:]


def note_lines(d: Drawing) -> list[list[str]]:
    x0 = FRAME[0] + 5.0
    right = FRAME[2] - TITLE_W - 6.0 - (sum(TABLE_COLS) + 6.0 if d.table_rows else 0.0)
    width = 0.8 * (right - x0)  # room for a wider fallback font
    return [wrap_text(f"{k}. {note}", width, DIM_TEXT_MM) for k, note in enumerate(d.notes, start=1)]


def notes_top(d: Drawing) -> float:
    """Paper y where the views must end: above the notes block (which ends
    3 mm above the frame) and above the hole table, if any."""
    lines = note_lines(d)
    height = 5.0 + sum(len(ls) * NOTE_LINE + 0.8 for ls in lines) + 3.0
    table = (d.table_rows + 1) * TABLE_ROW + 8.0 + 8.0 if d.table_rows else 0.0
    return min(NOTES_TOP, FRAME[3] - height, FRAME[3] - table)


def draw_notes(d: Drawing) -> None:
    sh = d.sheet
    x0, y = FRAME[0] + 5.0, d.notes_top + 5.0
    sh.text("notes", (x0, y), "NOTES", LABEL_TEXT_MM, bold=True)
    y += 5.0
    for k, lines in enumerate(note_lines(d), start=1):
        for j, line in enumerate(lines):
            sh.text("notes", (x0 + (4.0 if j else 0.0), y), line, DIM_TEXT_MM,
                    id=f"note-{k}" if j == 0 else "")
            y += NOTE_LINE
        y += 0.8
    if d.notes_top < FRAME[1] + 60.0:
        raise ValueError(f"notes of {d.spec.name} leave no room for the views")


