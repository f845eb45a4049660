"""The sheet's room for a label: a box is clear when no text and no stroke's
ink meets it, measured as the drawings check measures; labels are set last,
each at the first of its places with room, so a line drawn after a dimension
still moves its value."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.checks.sheet_overlap import layout_of_svg, sheet_overlaps
from tactcad.drawings.room import grown, length_in_box
from tactcad.drawings.sheet import (DIM_TEXT_MM, STYLES, Sheet, Spot, leader_spots, text_box,
                                    text_width, value_spots)

coord = st.floats(0.0, 60.0, allow_nan=False)
point = st.tuples(coord, coord)


@settings(max_examples=200, deadline=None)
@given(strokes=st.lists(st.tuples(st.lists(point, min_size=2, max_size=6),
                                  st.sampled_from(["thin", "visible", "frame"])), max_size=12),
       box=st.tuples(coord, coord, st.floats(0.0, 20.0), st.floats(0.0, 20.0)),
       margin=st.sampled_from([0.0, 0.3]))
def test_a_box_is_clear_exactly_when_no_segment_ink_meets_it(strokes, box, margin):
    """The strokes' extents only skip what cannot meet the box: every segment
    clipped one by one against the box grown by the margin and its ink gives
    the same answer, for strokes added before and after a query."""
    x, y, w, h = box
    query = (x, y, x + w, y + h)
    sheet = Sheet("A4")
    sheet.room = (-100.0, -100.0, 200.0, 200.0)   # the room is another test's
    half = len(strokes) // 2
    for pts, style in strokes[:half]:
        sheet.polyline("g", pts, style)
    for upto in (half, len(strokes)):
        if upto == len(strokes):
            for pts, style in strokes[half:]:
                sheet.polyline("g", pts, style)
        every = any(length_in_box(p, q, grown(query, margin + STYLES[style][0] / 2)) > 0
                    for pts, style in strokes[:upto] for p, q in zip(pts, pts[1:]))
        assert sheet.is_clear(query, margin) is (not every)


def test_a_box_outside_the_room_or_on_a_text_is_not_clear():
    sh = Sheet()
    sh.room = (20.0, 10.0, 410.0, 287.0)
    assert sh.is_clear((30.0, 30.0, 40.0, 33.0))
    assert not sh.is_clear((15.0, 30.0, 25.0, 33.0))          # across the frame
    sh.text("notes", (30.0, 33.0), "NOTES", 3.5)
    assert not sh.is_clear((35.0, 31.0, 45.0, 34.0))


def test_a_label_takes_its_first_spot_with_room_and_brings_its_lines():
    sh = Sheet()
    sh.line("view", (0.0, 50.0), (200.0, 50.0), "visible")
    on_line, free = Spot((20.0, 51.0)), Spot((20.0, 70.0), lines=(((15.0, 71.0), (40.0, 71.0)),))
    sh.label("dimensions", "H4", [on_line, free], id="hole-label-4")
    sh.settle()
    (label, box), = sh.text_boxes
    assert label == "H4" and box == text_box((20.0, 70.0), "H4", DIM_TEXT_MM)
    assert sheet_overlaps(layout_of_svg(sh.svg(), "x.svg")) == []
    assert '<path d="M15 71 L40 71"' in sh.svg()


def test_a_label_with_no_room_anywhere_takes_the_least_crowded_spot():
    sh = Sheet()
    sh.line("view", (0.0, 50.0), (200.0, 50.0), "visible")
    sh.line("view", (21.0, 80.0), (21.0, 79.0), "visible")    # a 1 mm stub
    across, grazed = Spot((20.0, 51.0)), Spot((20.0, 80.0))   # a line through it; the stub in it
    sh.label("dimensions", "H4", [across, grazed])
    sh.settle()
    assert sh.text_boxes[0][1] == text_box((20.0, 80.0), "H4", DIM_TEXT_MM)


def test_a_line_drawn_after_a_dimension_still_moves_its_value():
    """Values are set last: a view outline drawn after the dimension, right
    through the value's first place, sends the value to its next one."""
    sh = Sheet()
    sh.linear_dimension((50.0, 100.0), (90.0, 100.0), "h", 90.0, "40", "length")
    sh.line("view", (60.0, 88.5), (80.0, 88.5), "visible")   # where "40" would stand
    found = sheet_overlaps(layout_of_svg(sh.svg(), "late.svg"))
    assert found == []
    (_, box), = sh.text_boxes
    assert box[1] > 90.0          # under the dimension line now, the other side


def test_value_spots_start_where_iso_129_puts_the_value():
    """Between the arrows above the line when it fits; a long value beyond
    the end asked for, then the other end, then over the middle clear of the
    arrowheads, then the other side."""
    fits = next(value_spots((50.0, 90.0), (90.0, 90.0), "h", "40", True, True, None))
    assert fits.at == (70.0, 89.0) and fits.anchor == "middle"
    w = text_width("12.345", DIM_TEXT_MM)
    spots = list(value_spots((50.0, 90.0), (58.0, 90.0), "h", "12.345", True, False, "left"))
    assert spots[0].at == pytest.approx((50.0 - 1.5 - w / 2, 89.0))
    assert spots[1].at == pytest.approx((58.0 + 1.5 + w / 2, 89.0))
    assert spots[2].at[0] == spots[3].at[0] == pytest.approx(54.0)
    assert spots[2].at[1] < 89.0 and spots[3].at[1] > 90.0
    # the value further out carries the dimension line on under it
    far = next(s for s in spots if s.lines)
    (a, b), = far.lines
    assert a[1] == b[1] == 90.0 and min(a[0], b[0]) <= far.at[0] - w / 2


def test_a_leader_near_the_frame_turns_its_shoulder_back_onto_the_sheet():
    """A long note on a leader whose end lies near the frame's right edge:
    the text would cross the frame, so the leader ends on the other side."""
    sh = Sheet()
    sh.room = (20.0, 10.0, 410.0, 287.0)
    text = "M6x1 depth 4 (tap drill Ø5), onto the gauge shaft"
    sh.leader([(360.0, 60.0), (390.0, 40.0)], text, "mount_thread")
    assert sheet_overlaps(layout_of_svg(sh.svg(), "lead.svg")) == []
    (_, box), = sh.text_boxes
    assert box[2] < 360.0               # left of where the leader starts
    first = next(leader_spots([(360.0, 60.0), (390.0, 40.0)], text))
    assert first.at[0] > 390.0          # the end asked for was tried first


def test_a_title_block_value_too_long_for_its_cell_goes_on_two_lines_then_shortens():
    from tactcad.drawings.frame import MIN_VALUE_MM, value_lines

    room = 0.9 * (60 - 3)  # the drawing number's cell
    short = "ti_array_2x3-spacer"
    assert value_lines(short, 3.5, room) == (3.5, [short])
    h, lines = value_lines("abcdefghij_abcdefghij_abcdefghij", 3.5, room)
    assert MIN_VALUE_MM < h < 3.5 and len(lines) == 1
    number = "abcdefghij_" * 5 + "abcdefghi-terminal_board"
    h, lines = value_lines(number, 3.5, room)
    assert h == MIN_VALUE_MM and "".join(lines) == number and lines[0].endswith("_")
    number = "W" * 64 + "-terminal_board"
    h, lines = value_lines(number, 3.5, room)
    assert lines[0].startswith("W") and lines[1].startswith("…") and number.endswith(lines[1][1:])
    text = "bought-in grasper jaw, machined for the insert: pocket and window by wire EDM"
    h, lines = value_lines(text, 3.5, text_width(text, 1.8) * 0.6)
    assert " ".join(lines) == text
    for value in (text, number, "abcdefghij_" * 5 + "abcdefghi-terminal_board"):
        h, lines = value_lines(value, 3.5, room)
        assert all(text_width(line, h) <= room for line in lines)


