"""The sheet's room for a label: a box is clear when no text and no stroke meets it."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.drawings.sheet import Sheet, _segment_meets_box

coord = st.floats(0.0, 60.0, allow_nan=False)
point = st.tuples(coord, coord)


@settings(max_examples=200, deadline=None)
@given(strokes=st.lists(st.lists(point, min_size=2, max_size=6), max_size=12),
       box=st.tuples(coord, coord, st.floats(0.0, 20.0), st.floats(0.0, 20.0)),
       margin=st.sampled_from([0.0, 0.3]))
def test_a_box_is_clear_exactly_when_no_segment_meets_it(strokes, box, margin):
    """The strokes' extents only skip what cannot meet the box: every segment
    checked one by one gives the same answer, added before and after a query."""
    x, y, w, h = box
    query = (x, y, x + w, y + h)
    grown = (x - margin, y - margin, x + w + margin, y + h + margin)
    sheet = Sheet("A4")
    half = len(strokes) // 2
    for pts in strokes[:half]:
        sheet.polyline("g", pts, "thin")
    for upto in (half, len(strokes)):
        if upto == len(strokes):
            for pts in strokes[half:]:
                sheet.polyline("g", pts, "thin")
        every = any(_segment_meets_box(p, q, grown)
                    for pts in strokes[:upto] for p, q in zip(pts, pts[1:]))
        assert sheet.is_clear(query, margin) is (not every)
