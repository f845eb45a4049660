"""DXF for the cutting shop: each contour as a closed polyline with bulges.

What a cutting shop expects: lines and arcs only (no SPLINE/ELLIPSE), each
contour one closed chain, flat on z = 0, units mm. The contour is nominal:
the wire offset (kerf / 2) is the shop's CAM setting. Layers:

* ``CUT``: outer contour (closed polyline with bulges) and round holes (CIRCLE);
* ``START_HOLE``: one drilled start hole (CIRCLE) inside each closed cut-out;
* ``LEAD_IN``: where the wire starts each cut: a POINT at the start and a LINE
  from it to the entry point on the contour (outside the part for the outer
  contour, from the start hole for an inner cut); the caller keeps the entry
  off the flexure web and the contact face;
* ``MARK``: part marks (TEXT), never cut;
* ``TAB``: holding tabs (micro-joints): a LINE along the outer contour over
  each stretch the cut leaves standing, cut or broken off last;
* ``CUT_ORDER``: the cut order, a TEXT number at each contour's lead-in start
  (inner contours first, then the outer one; the tabs last).

What the drawn contour is follows the part's process
(:mod:`tactcad.vocabulary.process`): the nominal contour for a cutting tool
whose offset is the CAM's (wire EDM, laser), the compensated outline for etch
artwork.

Two DXF versions: ``R2010`` (default; closed LWPOLYLINE, ``$INSUNITS = 4``,
``$MEASUREMENT = 1``) and ``R12`` for old CAM (no LWPOLYLINE: a closed
POLYLINE with per-vertex bulges; R12 has no units variable, the files are
in mm). ``$EXTMIN``/``$EXTMAX`` hold the real extents of what is drawn.
"""

from __future__ import annotations

import contextlib
import logging
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Iterator, Sequence

if TYPE_CHECKING:  # loaded where a file is written: planning an export does not need it
    import ezdxf

from tactcad.atomic import write_atomic
from tactcad.geometry.profile import Arc, Circle, Point, Profile, Segment, contour_bbox

CUT_LAYER = "CUT"
START_LAYER = "START_HOLE"
LEAD_LAYER = "LEAD_IN"
MARK_LAYER = "MARK"
TAB_LAYER = "TAB"
ORDER_LAYER = "CUT_ORDER"
DXF_VERSIONS = ("R2010", "R12")
DEFAULT_DXF_VERSION = "R2010"
LAYER_COLOURS = {CUT_LAYER: 1, START_LAYER: 3, LEAD_LAYER: 6, MARK_LAYER: 5, TAB_LAYER: 2,
                 ORDER_LAYER: 4}


@dataclass(frozen=True)
class LeadIn:
    """Where the wire starts a cut (mm): ``start`` (POINT) and ``entry`` on the contour."""

    start: Point
    entry: Point


@dataclass(frozen=True)
class Mark:
    """A part mark: TEXT of ``height_mm`` with its lower-left corner at ``position``."""

    text: str
    position: Point
    height_mm: float


@dataclass(frozen=True)
class Tab:
    """A holding tab: the stretch of the outer contour from ``start`` to ``end``
    (mm, on a straight edge) the cut leaves standing."""

    start: Point
    end: Point

    @property
    def width_mm(self) -> float:
        return math.dist(self.start, self.end)


@dataclass(frozen=True)
class PlacedProfile:
    """A profile moved by ``offset`` (mm), with its lead-ins, marks, tabs and
    cut-order labels (layer ``CUT_ORDER``) in the profile's own frame (they
    move with it)."""

    profile: Profile
    offset: Point = (0.0, 0.0)
    lead_ins: tuple[LeadIn, ...] = ()
    marks: tuple[Mark, ...] = ()
    tabs: tuple[Tab, ...] = ()
    order: tuple[Mark, ...] = ()


@dataclass(frozen=True)
class DxfFile:
    """What one DXF file holds: placed profiles and header properties (name -> text,
    written as custom header properties in R2010)."""

    items: tuple[PlacedProfile, ...]
    title: str = ""
    properties: dict[str, str] = field(default_factory=dict)


def bulge_points(segments: Sequence[Segment], offset: Point = (0.0, 0.0)) -> list[tuple[float, float, float]]:
    """(x, y, bulge) vertices of a closed chain moved by ``offset``; the bulge
    belongs to the edge leaving the vertex."""
    dx, dy = offset
    return [(s.start[0] + dx, s.start[1] + dy, s.bulge if isinstance(s, Arc) else 0.0)
            for s in segments]


def _moved(p: Point, offset: Point) -> Point:
    return (p[0] + offset[0], p[1] + offset[1])


def placed_extents(items: Sequence[PlacedProfile]) -> tuple[float, float, float, float]:
    """(xmin, ymin, xmax, ymax) of what the file draws outside the marks: the
    outer contours (exact for arcs) and the lead-in start points. Marks are
    placed inside their part, so they do not widen it."""
    xs: list[float] = []
    ys: list[float] = []
    for it in items:
        x0, y0, x1, y1 = contour_bbox(it.profile.outer)
        xs += [x0 + it.offset[0], x1 + it.offset[0]]
        ys += [y0 + it.offset[1], y1 + it.offset[1]]
        for li in it.lead_ins:
            x, y = _moved(li.start, it.offset)
            xs.append(x)
            ys.append(y)
    return (min(xs), min(ys), max(xs), max(ys))


def _add_closed_chain(msp, version: str, segments: Sequence[Segment], offset: Point) -> None:
    pts = bulge_points(segments, offset)
    attribs = {"layer": CUT_LAYER}
    if version == "R12":
        msp.add_polyline2d(pts, format="xyb", close=True, dxfattribs=attribs)
    else:
        msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs=attribs)


def _add_circle(msp, c: Circle, offset: Point, layer: str) -> None:
    msp.add_circle(_moved(c.centre, offset), c.radius, dxfattribs={"layer": layer})


def _add_item(msp, version: str, it: PlacedProfile) -> None:
    p, off = it.profile, it.offset
    _add_closed_chain(msp, version, p.outer, off)
    for hole in p.holes:
        _add_circle(msp, hole, off, CUT_LAYER)
    for start in p.start_holes:
        _add_circle(msp, start, off, START_LAYER)
    for li in it.lead_ins:
        s, e = _moved(li.start, off), _moved(li.entry, off)
        msp.add_point(s, dxfattribs={"layer": LEAD_LAYER})
        msp.add_line(s, e, dxfattribs={"layer": LEAD_LAYER})
    for tab in it.tabs:
        msp.add_line(_moved(tab.start, off), _moved(tab.end, off), dxfattribs={"layer": TAB_LAYER})
    for layer, marks in ((MARK_LAYER, it.marks), (ORDER_LAYER, it.order)):
        for m in marks:
            text = msp.add_text(m.text, height=m.height_mm, dxfattribs={"layer": layer})
            text.dxf.insert = _moved(m.position, off)


def dxf_document(content: DxfFile, version: str = DEFAULT_DXF_VERSION) -> ezdxf.document.Drawing:
    """An in-memory DXF of ``content`` (see module doc for layers, units, versions).

    Raises:
        ValueError: ``version`` is not one of :data:`DXF_VERSIONS`.
    """
    import ezdxf

    if version not in DXF_VERSIONS:
        raise ValueError(f"DXF version {version!r} is not one of {', '.join(DXF_VERSIONS)}")
    with _quiet_units_warning():
        doc = ezdxf.new(version, setup=False, units=4)  # mm, $MEASUREMENT = 1 (metric)
    if version != "R12":  # R12 has no units variables; its files are mm by convention
        for key, value in content.properties.items():
            doc.header.custom_vars.append(key, value)
        if content.title:
            doc.header["$PROJECTNAME"] = content.title
    doc.header["$LUNITS"] = 2
    for name, colour in LAYER_COLOURS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    for it in content.items:
        _add_item(msp, version, it)
    # ezdxf copies the modelspace's extents into the header on save, unless
    # one of them is the origin (a false vector): set both places
    x0, y0, x1, y1 = placed_extents(content.items)
    msp.dxf.extmin, msp.dxf.extmax = (x0, y0, 0.0), (x1, y1, 0.0)
    doc.header["$EXTMIN"], doc.header["$EXTMAX"] = (x0, y0, 0.0), (x1, y1, 0.0)
    msp.dxf.limmin, msp.dxf.limmax = (x0, y0), (x1, y1)
    return doc


class _DropUnitsWarning(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        return "$INSUNITS" not in record.getMessage()


@contextlib.contextmanager
def _quiet_units_warning() -> Iterator[None]:
    """ezdxf warns that R12 cannot store units; the module doc says so once."""
    log = logging.getLogger("ezdxf")
    f = _DropUnitsWarning()
    log.addFilter(f)
    try:
        yield
    finally:
        log.removeFilter(f)


@contextlib.contextmanager
def _fixed_metadata() -> Iterator[None]:
    """ezdxf's switch for constant time stamps and GUIDs; it must be on from
    document creation (the CREATED_BY marker) until the file is written."""
    import ezdxf

    previous = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = previous


def _sort_classes(doc: ezdxf.document.Drawing) -> None:
    """ezdxf collects the CLASSES section from a set of type names, so its
    order follows Python's string hashing; register them now, in name order."""
    import ezdxf

    if doc.dxfversion == ezdxf.const.DXF12:
        return
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))


def write_dxf(path: str | Path, content: DxfFile, version: str = DEFAULT_DXF_VERSION) -> Path:
    """Write ``content`` as DXF atomically and reproducibly: fixed time stamps
    and GUIDs, sorted classes, so the same content writes the same bytes.

    Raises:
        ValueError: unknown ``version``.
    """
    with _fixed_metadata():
        doc = dxf_document(content, version)
        _sort_classes(doc)
        return write_atomic(path, lambda tmp: doc.saveas(tmp))


def write_profile_dxf(path: str | Path, profile: Profile, title: str = "",
                      version: str = DEFAULT_DXF_VERSION) -> Path:
    """Write one profile's DXF (no lead-ins, no marks): see :func:`write_dxf`."""
    return write_dxf(path, DxfFile((PlacedProfile(profile),), title), version)


def circle_entry(hole: Circle, away_from: Point | None) -> Point:
    """The point of ``hole`` farthest from ``away_from`` (the -x point when None)."""
    (cx, cy), r = hole.centre, hole.radius
    if away_from is None or math.dist(away_from, hole.centre) == 0:
        return (cx - r, cy)
    dx, dy = cx - away_from[0], cy - away_from[1]
    n = math.hypot(dx, dy)
    return (cx + r * dx / n, cy + r * dy / n)
