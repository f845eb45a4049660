"""The notes block of a part drawing: the part family's notes
(:mod:`tactcad.drawings.part_sets`) and the general tolerance, wrapped to the
room left of the title block."""

from __future__ import annotations

from tactcad.drawings.drawing import NOTE_LINE, NOTES_TOP, TABLE_ROW, Drawing, table_box
from tactcad.drawings.frame import FRAME, TITLE_H, TITLE_W, general_tolerance, wrap_text
from tactcad.drawings.part_sets import drawing_of
from tactcad.drawings.sheet import DIM_TEXT_MM, LABEL_TEXT_MM, text_box

def notes_for(d: Drawing) -> list[str]:
    """The part family's notes (:attr:`PartDrawing.notes`), the tip-height procedure's
    when the drawing relies on one (:attr:`Drawing.tip_height`), then the general one."""
    procedure = getattr(d.tip_height, "note", None)
    return drawing_of(d.spec).notes(d) + ([procedure] if procedure else []) + [
        f"Untoleranced dimensions: {general_tolerance(d.plan)}. Dimensions in mm (ISO 129-1), "
        f"first-angle projection. Break sharp edges 0.1 max unless noted."]


def note_lines(d: Drawing) -> list[list[str]]:
    x0, right = _notes_column(d)
    width = 0.8 * (right - x0)  # room for a wider fallback font
    return [wrap_text(f"{k}. {note}", width, DIM_TEXT_MM) for k, note in enumerate(d.notes, start=1)]


def _notes_column(d: Drawing) -> tuple[float, float]:
    """Paper x (left, right) of the notes block: over the title block when a wide hole
    table stands under the views, else from the frame to the title block (less the
    table, under the views)."""
    if d.notes_over_title:
        return FRAME[2] - TITLE_W + 2.0, FRAME[2] - 4.0
    under = d.table_rows and not d.table_beside
    return FRAME[0] + 5.0, FRAME[2] - TITLE_W - 6.0 - (table_box(d)[2] + 6.0 if under else 0.0)


def _notes_height(d: Drawing) -> float:
    return 5.0 + sum(len(ls) * NOTE_LINE + 0.8 for ls in note_lines(d)) + 3.0


def _notes_block_top(d: Drawing) -> float:
    """Paper y of the notes block's top edge."""
    if d.notes_over_title:  # above the finish symbol over the title block
        return FRAME[3] - TITLE_H - 16.0 - _notes_height(d)
    return d.notes_top


def notes_top(d: Drawing) -> float:
    """Paper y where the views must end: above the notes block (which ends
    3 mm above the frame, or above the title block) and above the hole table, if any
    stands under them."""
    table = (d.table_block_rows + 1) * TABLE_ROW + 8.0 + 8.0 if d.table_rows and not d.table_beside \
        else 0.0
    notes = _notes_block_top(d) if d.notes_over_title else FRAME[3] - _notes_height(d)
    return min(NOTES_TOP, notes, FRAME[3] - table)


def draw_notes(d: Drawing) -> None:
    sh = d.sheet
    x0, y = _notes_column(d)[0], _notes_block_top(d) + 5.0
    # the left centring mark ends at x0: a block that meets it starts 1.5 mm further in
    if not all(sh.is_clear(text_box((x0, y + k * NOTE_LINE), "NOTES", LABEL_TEXT_MM), 0.4)
               for k in range(sum(len(ls) for ls in note_lines(d)) + 3)):
        x0 += 1.5
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


