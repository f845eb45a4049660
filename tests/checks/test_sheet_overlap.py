"""The drawings' legibility check (tactcad.checks.sheet_overlap): measured
overlaps of texts with lines and other texts, on made sheets and on every
sheet of both shipped examples."""

from __future__ import annotations

import pytest

from tactcad.checks.groups import CHECK_GROUPS
from tactcad.checks.sheet_overlap import (box_overlap, check_sheet_files, layout_of_svg,
                                          length_in_box, sheet_overlaps)
from tactcad.drawings.sheet import Sheet, text_box, text_width


def test_length_in_box_clips_a_segment():
    box = (0.0, 0.0, 10.0, 4.0)
    assert length_in_box((-5.0, 2.0), (15.0, 2.0), box) == pytest.approx(10.0)
    assert length_in_box((2.0, -1.0), (2.0, 1.0), box) == pytest.approx(1.0)
    assert length_in_box((-5.0, 5.0), (15.0, 5.0), box) == 0.0
    assert box_overlap(box, (8.0, 3.0, 20.0, 9.0)) == pytest.approx(1.0)


def test_a_text_on_a_line_fails_naming_both_and_the_overlap():
    sh = Sheet(title="made to overlap")
    sh.line("view-front", (10.0, 50.0), (200.0, 50.0), "visible")
    sh.text("dimensions", (20.0, 51.0), "H4", 2.5, id="hole-label-4")   # line 1 mm under the cap line
    found = sheet_overlaps(layout_of_svg(sh.svg(), "made.svg"))
    assert len(found) == 1
    o = found[0]
    assert o.sheet == "made.svg" and "'H4'" in o.first and "view-front" in o.second
    # the whole width, plus the 0.5 mm line's ink on both sides
    assert o.overlap_mm == pytest.approx(text_width("H4", 2.5) + 0.5, abs=0.01)


def test_two_texts_on_each_other_fail_and_apart_they_pass():
    sh = Sheet()
    sh.text("notes", (50.0, 50.0), "NOTES", 3.5)
    sh.text("notes", (52.0, 51.0), "second", 2.5)
    found = sheet_overlaps(layout_of_svg(sh.svg(), "x.svg"))
    assert [("'NOTES'" in o.first, "'second'" in o.second) for o in found] == [(True, True)]
    assert found[0].overlap_mm == pytest.approx(
        box_overlap(text_box((50.0, 50.0), "NOTES", 3.5), text_box((52.0, 51.0), "second", 2.5)),
        abs=0.01)
    apart = Sheet()
    apart.text("notes", (50.0, 50.0), "NOTES", 3.5)
    apart.text("notes", (50.0, 60.0), "second", 2.5)
    apart.line("notes", (40.0, 53.0), (90.0, 53.0))           # under the descender
    assert sheet_overlaps(layout_of_svg(apart.svg(), "y.svg")) == []


def test_rotated_text_is_measured_along_its_reading_direction():
    sh = Sheet()
    sh.text("dimensions", (100.0, 100.0), "12.5", 2.5, anchor="middle", rotate=-90)
    sh.line("dimensions", (95.0, 100.0), (105.0, 100.0))   # across the text's middle
    (o,) = sheet_overlaps(layout_of_svg(sh.svg(), "r.svg"))
    assert o.overlap_mm == pytest.approx(2.5 * 1.25 + 0.18, abs=0.01)   # cap line to descender, ink


def test_the_check_fails_on_a_made_sheet_in_an_export_folder(tmp_path):
    (tmp_path / "drawings").mkdir()
    sh = Sheet()
    sh.rect("frame", 20.0, 10.0, 390.0, 277.0, "frame")
    sh.text("notes", (15.0, 100.0), "across the frame", 2.5)
    (tmp_path / "drawings" / "made.svg").write_text(sh.svg(), encoding="utf-8")
    (r,) = check_sheet_files(tmp_path)
    assert not r.passed and r.subject == "drawings/made.svg"
    assert "'across the frame'" in r.detail and "rect of frame" in r.detail and " mm" in r.detail
    assert "drawings" in CHECK_GROUPS


@pytest.mark.slow
@pytest.mark.parametrize("example", ["exported", "example_exported"])
def test_every_sheet_of_both_examples_passes(example, request):
    out = request.getfixturevalue(example)
    out = out[0] if isinstance(out, tuple) else out  # the default design's gives (out, result)
    results = check_sheet_files(out)
    assert len(results) >= 15                     # every part's sheet and the assembly's
    assert [r.detail for r in results if not r.passed] == []


def test_clipping_many_segments_at_once_gives_each_ones_length():
    """The sheet check clips all of a sheet's segments at once; each length is
    the one segment's (axis-parallel, degenerate and outside segments included)."""
    import numpy as np

    from tactcad.checks.sheet_overlap import length_in_box, lengths_in_boxes

    rng = np.random.default_rng(7)
    p = rng.uniform(0, 10, (400, 2))
    q = p + rng.uniform(-8, 8, (400, 2)) * rng.integers(0, 2, (400, 2))  # some axis-parallel
    q[:10] = p[:10]                                                     # some points
    boxes = np.sort(rng.uniform(0, 10, (400, 2, 2)), axis=1).reshape(400, 4)  # x0 y0 x1 y1
    got = lengths_in_boxes(p, q, boxes)
    want = [length_in_box(tuple(a), tuple(b), tuple(box)) for a, b, box in zip(p, q, boxes)]
    assert got == pytest.approx(want, abs=1e-12)
    assert (got > 0).sum() > 50 and (got == 0).sum() > 50  # both cases drawn


def test_a_chain_of_short_dimensions_puts_each_value_away_from_its_neighbour():
    """Two vertical dimensions in a chain (a 2 mm span below a 3 mm one, as an
    element's arm and tip heights): a value too long for its space goes above
    by default, where its neighbour's value stands; the placer finds it other
    room, and told to go below it goes below."""
    def chain(outside):
        sh = Sheet()
        sh.linear_dimension((50.0, 100.0), (50.0, 102.0), "v", 60.0, "0.9", "low", outside=outside)
        sh.linear_dimension((50.0, 97.0), (50.0, 100.0), "v", 60.0, "1.5", "high")
        return sh, sheet_overlaps(layout_of_svg(sh.svg(), "chain.svg"))

    for outside in (None, "below"):
        assert chain(outside)[1] == []
    below, _ = chain("below")
    assert dict(below.text_boxes)["0.9"][1] > 102.0
    with pytest.raises(ValueError, match="outside must be one of"):
        Sheet().linear_dimension((0.0, 0.0), (0.0, 5.0), "v", 10.0, "5", "x", outside="left")
