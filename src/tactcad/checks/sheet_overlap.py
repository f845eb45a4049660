"""The drawings' legibility check: on every sheet, no text crosses a line of
the drawing or another text, measured in paper mm on the sheet's own vector
data (the SVG a drawing is written as: lines, paths, rectangles, circles and
texts in sheet millimetres), never on a rendered picture.

A text covers the box of :func:`tactcad.drawings.sheet.text_box` (its advance
width in Helvetica's metrics, from the cap line to the descender). A stroke
crosses a text when more than :data:`TOLERANCE_MM` of its length lies inside
that box grown by half the stroke's width (the ink of the line); two texts
overlap when their boxes share more than :data:`TOLERANCE_MM` in both
directions. The measures are :mod:`tactcad.drawings.room`'s, the ones the
sheets' labels are placed by, so a label set clear is measured clear.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

import numpy as np

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found
from tactcad.drawings.room import (Box, Point, Segments, box_overlap, length_in_box,
                                   lengths_in_boxes)
from tactcad.drawings.sheet import CAP_HEIGHT_EM, text_box

TOLERANCE_MM = 0.05     # overlap below this is rounding of the written coordinates
CIRCLE_SEGMENTS = 72    # a circle as a polygon: 5 deg chords, off the arc by < 0.001 r

__all__ = ["Box", "Point", "SheetLayout", "Overlap", "box_overlap", "length_in_box",
           "lengths_in_boxes", "sheet_overlaps", "layout_of_svg", "check_sheet_files",
           "sheet_group"]
_SVG = "{http://www.w3.org/2000/svg}"


@dataclass
class SheetLayout:
    """What a sheet shows, in paper mm: each text's box and each stroke's points.

    Attributes:
        name: the sheet, as a check names it (``drawings/clamp_plate.svg``).
        texts: ``(label, box)`` per text; the label is the text in quotes and its id.
        strokes: ``(label, points, half width mm)`` per line, outline,
            rectangle, circle or arrowhead (a filled arrowhead: 0).
    """

    name: str
    texts: list[tuple[str, Box]] = field(default_factory=list)
    strokes: list[tuple[str, list[Point], float]] = field(default_factory=list)


@dataclass(frozen=True)
class Overlap:
    """One text over a stroke or another text: the two items and the overlap (mm)."""

    sheet: str
    first: str
    second: str
    overlap_mm: float

    def text(self) -> str:
        return f"{self.first} overlaps {self.second} by {self.overlap_mm:.2f} mm"


def sheet_overlaps(layout: SheetLayout, tol: float = TOLERANCE_MM) -> list[Overlap]:
    """Every text over a stroke (the stroke's ink inside the text's box,
    :meth:`~tactcad.drawings.room.Segments.ink_in`) and every pair of
    overlapping texts (:func:`~tactcad.drawings.room.box_overlap`) of one
    sheet, larger than ``tol`` mm: the measure the sheet's labels were placed by."""
    ink = Segments()
    for _, pts, half in layout.strokes:
        ink.add(pts, half)
    found = []
    for i, (label, box) in enumerate(layout.texts):
        for other, obox in layout.texts[i + 1:]:
            if (o := box_overlap(box, obox)) > tol:
                found.append(Overlap(layout.name, label, other, o))
        inside = ink.ink_in(box)
        found += [Overlap(layout.name, label, layout.strokes[k][0], float(inside[k]))
                  for k in np.flatnonzero(inside > tol)]
    return found


# --- a written sheet's vector data --------------------------------------------------------------
def _f(el: ET.Element, key: str) -> float:
    return float(el.get(key, "0"))


def _path_points(d: str) -> list[list[Point]]:
    """The sub-paths of an SVG path written by :class:`~tactcad.drawings.sheet.Sheet`
    (``M x y L x y ... [Z]``), closed ones with their first point repeated."""
    out: list[list[Point]] = []
    for token in re.findall(r"[MLZ][^MLZ]*", d):
        cmd, nums = token[0], [float(v) for v in token[1:].split()]
        if cmd == "M":
            out.append([(nums[0], nums[1])])
        elif cmd == "L":
            out[-1].append((nums[0], nums[1]))
        elif out:
            out[-1].append(out[-1][0])
    return out


def _rotation(el: ET.Element) -> float:
    m = re.match(r"rotate\(([-\d.]+)", el.get("transform", ""))
    return float(m.group(1)) if m else 0.0


def layout_of_svg(svg: str, name: str) -> SheetLayout:
    """The :class:`SheetLayout` of a sheet's SVG text (as written by
    :class:`~tactcad.drawings.sheet.Sheet`); the white page is not a stroke.

    Raises:
        xml.etree.ElementTree.ParseError: ``svg`` is not XML.
    """
    layout = SheetLayout(name)
    root = ET.fromstring(svg)
    for group in root.iter(f"{_SVG}g"):
        gid = group.get("id", "")
        for el in group:
            tag = el.tag.removeprefix(_SVG)
            what = f"{tag} of {gid}" + (f" ({el.get('class')})" if el.get("class") else "")
            half = _f(el, "stroke-width") / 2 if el.get("stroke", "none") != "none" else 0.0
            if tag == "text":
                height = _f(el, "font-size") * CAP_HEIGHT_EM
                box = text_box((_f(el, "x"), _f(el, "y")), el.text or "", height,
                               el.get("text-anchor", "start"), _rotation(el))
                label = f"text {el.text!r}" + (f" ({el.get('id')})" if el.get("id") else "")
                layout.texts.append((label, box))
            elif tag == "line":
                layout.strokes.append((what, [(_f(el, "x1"), _f(el, "y1")),
                                              (_f(el, "x2"), _f(el, "y2"))], half))
            elif tag == "path":
                layout.strokes += [(what, pts, half) for pts in _path_points(el.get("d", ""))]
            elif tag == "rect":
                x, y, w, h = _f(el, "x"), _f(el, "y"), _f(el, "width"), _f(el, "height")
                layout.strokes.append((what, [(x, y), (x + w, y), (x + w, y + h), (x, y + h),
                                              (x, y)], half))
            elif tag == "circle":
                cx, cy, r = _f(el, "cx"), _f(el, "cy"), _f(el, "r")
                layout.strokes.append((what, [
                    (cx + r * math.cos(2 * math.pi * k / CIRCLE_SEGMENTS),
                     cy + r * math.sin(2 * math.pi * k / CIRCLE_SEGMENTS))
                    for k in range(CIRCLE_SEGMENTS + 1)], half))
    return layout


def check_sheet_files(folder: Path) -> list[CheckResult]:
    """One result per drawing sheet (``drawings/*.svg`` under ``folder``):
    passed when nothing overlaps, else the overlaps, largest first."""
    return [result for path in sorted((folder / "drawings").glob("*.svg"))
            for result in sheet_file_results(path, path.relative_to(folder).as_posix())]


def sheet_file_results(path: Path, name: str | None = None) -> list[CheckResult]:
    """The one result of the sheet ``path`` (named ``name``, default the file's name):
    passed when nothing overlaps, else the overlaps, largest first."""
    name = name or path.name
    found = sorted(sheet_overlaps(layout_of_svg(path.read_text(encoding="utf-8"), name)),
                   key=lambda o: -o.overlap_mm)
    detail = ("no text over a line or another text" if not found else
              f"{len(found)} overlaps: " + "; ".join(o.text() for o in found[:5])
              + (" ..." if len(found) > 5 else ""))
    return [CheckResult("text overlap", name, not found, detail)]


def sheet_group(context: CheckContext) -> Iterator[Found]:
    """``drawings``: every drawing sheet of the export, text against lines and texts."""
    found = check_sheet_files(context.folder)
    if not found:
        found = [CheckResult("text overlap", "drawings/", False, "no drawing sheet in the export")]
    yield "drawings", found
