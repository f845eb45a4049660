"""DXF for wire EDM: the nominal contour as closed LWPOLYLINEs with bulges.

What a cutting shop expects: lines and arcs only (no SPLINE/ELLIPSE), each
contour one closed chain, flat on z = 0, units mm (``$INSUNITS = 4``,
``$MEASUREMENT = 1``). The contour is nominal: the wire offset (kerf / 2)
is the shop's CAM setting. Layers:

* ``CUT``: outer contour and closed cut-outs (bolt holes);
* ``START_HOLE``: one drilled start hole (CIRCLE) inside each closed cut-out.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Iterator

import ezdxf

from tactcad.geometry.profile import Arc, Circle, Profile, Segment
from tactcad.atomic import write_atomic

CUT_LAYER = "CUT"
START_LAYER = "START_HOLE"


def bulge_points(segments: tuple[Segment, ...]) -> list[tuple[float, float, float]]:
    """(x, y, bulge) vertices of a closed chain; bulge belongs to the edge leaving the vertex."""
    return [(s.start[0], s.start[1], s.bulge if isinstance(s, Arc) else 0.0) for s in segments]


def circle_points(c: Circle) -> list[tuple[float, float, float]]:
    """A circle as a closed LWPOLYLINE of two half-circle bulges (counter-clockwise)."""
    (x, y), r = c.centre, c.radius
    return [(x + r, y, 1.0), (x - r, y, 1.0)]


def profile_document(profile: Profile, title: str = "") -> ezdxf.document.Drawing:
    """An in-memory DXF (R2010) of the profile: see module doc for layers and units."""
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = 4
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    doc.layers.add(CUT_LAYER, color=1)
    doc.layers.add(START_LAYER, color=3)
    if title:
        doc.header["$PROJECTNAME"] = title
    msp = doc.modelspace()
    cut = {"layer": CUT_LAYER}
    msp.add_lwpolyline(bulge_points(profile.outer), format="xyb", close=True, dxfattribs=cut)
    for hole in profile.holes:
        msp.add_lwpolyline(circle_points(hole), format="xyb", close=True, dxfattribs=cut)
    for start in profile.start_holes:
        msp.add_circle(start.centre, start.radius, dxfattribs={"layer": START_LAYER})
    return doc


@contextlib.contextmanager
def _fixed_metadata() -> Iterator[None]:
    """ezdxf's switch for constant time stamps and GUIDs; it must be on from
    document creation (the CREATED_BY marker) until the file is written."""
    previous = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = previous


def _sort_classes(doc: ezdxf.document.Drawing) -> None:
    """ezdxf collects the CLASSES section from a set of type names, so its
    order follows Python's string hashing; register them now, in name order."""
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))


def write_profile_dxf(path: str | Path, profile: Profile, title: str = "") -> Path:
    """Write the profile's DXF atomically and reproducibly: fixed time stamps
    and GUIDs, sorted classes, so the same profile writes the same bytes."""
    with _fixed_metadata():
        doc = profile_document(profile, title)
        _sort_classes(doc)
        return write_atomic(path, lambda tmp: doc.saveas(tmp))
