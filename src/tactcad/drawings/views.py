"""Orthographic views of a solid: its visible and hidden edges as polylines
in view coordinates, by hidden-line removal (:mod:`tactcad.kernel.hlr`),
hidden edges under visible ones dropped, in a canonical order.

Views follow first-angle projection (ISO 128-30 / ISO 5456-2, method E):

* ``front``: seen from +z, u = x, v = y (the sketch plane of the profile);
* ``top``: seen from above (+y), placed below the front view: u = x, v = -z;
* ``left``: seen from the left (-x), placed right of the front view: u = z, v = y.

View coordinates are model millimetres; a :class:`View` maps them onto the
paper with its scale and origin.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import numpy as np

Point = tuple[float, float]
Polyline = list[Point]

# camera position (direction from the look-at point) and up vector per view
CAMERAS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]] = {
    "front": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "top": ((0.0, 1.0, 0.0), (0.0, 0.0, -1.0)),
    "left": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
}

# ISO 5455 preferred scales, largest first (enlargement : reduction as a float)
ISO_5455_SCALES: tuple[float, ...] = (50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1)


def fitting_scale(extent_mm: tuple[float, float], room_mm: tuple[float, float],
                  scales: tuple[float, ...] = ISO_5455_SCALES) -> float:
    """The largest of ``scales`` (largest first) at which a view of ``extent_mm`` (model
    mm, width and height) fits ``room_mm`` (paper mm), else the smallest."""
    return next((sc for sc in scales
                 if all(e * sc <= r for e, r in zip(extent_mm, room_mm))), scales[-1])


def scale_text(scale: float) -> str:
    """``5:1``, ``1:1``, ``1:2`` for a scale factor (paper mm per model mm)."""
    if scale >= 1:
        return f"{scale:g}:1"
    return f"1:{1 / scale:g}"


@dataclass
class View:
    """Projected edges of one view, and where it sits on the paper.

    Attributes:
        name: ``front``, ``top``, ``left`` or a detail name.
        visible / hidden: polylines in view coordinates (mm).
        bbox: (umin, vmin, umax, vmax) of all edges (mm).
        scale: paper mm per model mm.
        origin: paper point of view coordinate (0, 0).
    """

    name: str
    visible: list[Polyline]
    hidden: list[Polyline]
    bbox: tuple[float, float, float, float]
    scale: float = 1.0
    origin: Point = (0.0, 0.0)
    clip: tuple[Point, float] | None = field(default=None)
    hatch: list[Polyline] = field(default_factory=list)  # section hatching (ISO 128-50)

    def paper(self, u: float, v: float) -> Point:
        """Paper point (mm, y down) of view point (u, v)."""
        return (self.origin[0] + self.scale * u, self.origin[1] - self.scale * v)

    @property
    def width(self) -> float:
        return (self.bbox[2] - self.bbox[0]) * self.scale

    @property
    def height(self) -> float:
        return (self.bbox[3] - self.bbox[1]) * self.scale

    def place(self, left: float, top: float) -> None:
        """Put the view's bounding box's top-left corner at paper (left, top)."""
        self.origin = (left - self.bbox[0] * self.scale, top + self.bbox[3] * self.scale)

    def paper_box(self) -> tuple[float, float, float, float]:
        """(left, top, right, bottom) on paper."""
        x0, y1 = self.paper(self.bbox[0], self.bbox[1])
        x1, y0 = self.paper(self.bbox[2], self.bbox[3])
        return (x0, y0, x1, y1)


def _uncovered(hidden: list[Polyline], visible: list[Polyline], spacing: float) -> list[Polyline]:
    """The polylines of ``hidden`` not drawn under visible ones: those with some
    point (resampled ``spacing`` apart) farther than ``spacing`` from every
    point of ``visible`` (resampled alike). One nearest-point query for all."""
    from scipy.spatial import cKDTree

    if not hidden or not visible:
        return hidden
    tree = cKDTree(np.concatenate([_resampled(p, spacing) for p in visible]))
    pts = [_resampled(h, spacing) for h in hidden]
    dist, _ = tree.query(np.concatenate(pts), k=1)
    starts = np.cumsum([0] + [len(q) for q in pts[:-1]])
    far = np.maximum.reduceat(dist, starts) > spacing
    return [h for h, keep in zip(hidden, far) if keep]


def _canonical(poly: Polyline) -> tuple:
    r = [(round(x, 4) + 0.0, round(y, 4) + 0.0) for x, y in poly]
    return min(tuple(r), tuple(reversed(r)))


def cameras_for(normal: tuple[float, float, float],
                up: tuple[float, float, float]) -> dict[str, tuple[tuple, tuple]]:
    """First-angle view set for a front view seen from ``+normal`` with ``up``
    upwards: the view from above (camera along ``up``, placed below) and the
    view from the left (placed on the right)."""
    n, u = np.array(normal, float), np.array(up, float)
    right = np.cross(u, n)
    t = lambda v: tuple(float(c) + 0.0 for c in v)
    return {"front": (t(n), t(u)), "top": (t(u), t(-n)), "left": (t(-right), t(u))}


def orientation(bbox: tuple[float, float, float, float, float, float]) -> dict[str, tuple]:
    """View set for a part of bounding box (xmin, ymin, zmin, xmax, ymax, zmax):
    the front view looks along the axis of smallest extent, so it shows the
    part's outline at its largest; the longer remaining axis runs across the
    sheet. A plate in the xy plane gets :data:`CAMERAS`."""
    ext = [bbox[3] - bbox[0], bbox[4] - bbox[1], bbox[5] - bbox[2]]
    normal = min((2, 0, 1), key=lambda k: (ext[k] - 1e-9 * (k == 2)))
    rest = [k for k in (0, 1, 2) if k != normal]
    across = max(rest, key=lambda k: (ext[k], -k))
    upward = next(k for k in rest if k != across)
    if normal == 2 and across == 0:
        return dict(CAMERAS)
    n = [0.0, 0.0, 0.0]
    n[normal] = 1.0
    u = [0.0, 0.0, 0.0]
    u[upward] = 1.0
    return cameras_for(tuple(n), tuple(u))


def project(solid, view: str, step_mm: float | None = None,
            cameras: dict[str, tuple] | None = None) -> View:
    """Visible and hidden edges of ``solid`` in one view of ``cameras``
    (default :data:`CAMERAS`).

    Curves are sampled at most ``step_mm`` apart (default: 1/2000 of the
    part's bounding-box diagonal). Hidden edges that lie under visible ones
    are dropped, and the polylines are put in a canonical order so the same
    solid gives the same view in every run.

    Raises:
        KeyError: unknown view name.
    """
    from tactcad.kernel.hlr import projected  # the kernel, only when a view is drawn
    from tactcad.kernel.inspect import bounding_box

    direction, up = (cameras or CAMERAS)[view]
    if step_mm is None:
        step_mm = max(bounding_box(solid).diagonal / 2000.0, 1e-4)
    visible, hidden = projected(solid, direction, up, step_mm)
    hidden = _uncovered(hidden, visible, step_mm)
    visible = sorted({_canonical(p): p for p in visible}.values(), key=_canonical)
    hidden = sorted({_canonical(p): p for p in hidden}.values(), key=_canonical)
    allp = [q for p in visible + hidden for q in p]
    xs = [q[0] for q in allp]
    ys = [q[1] for q in allp]
    bbox = (min(xs), min(ys), max(xs), max(ys))
    return View(view, [list(p) for p in visible], [list(p) for p in hidden], bbox)


#: The result store's name for one part view's projected edges (:func:`kept_projection`).
PROJECTION_KIND = "part view projection"


def kept_projection(spec, solid, view: str, cameras: dict[str, tuple] | None = None) -> View:
    """:func:`project` of a part's solid, kept in the result store
    (:func:`tactcad.store.kept_result`) by the part's spec, the view's name and its
    camera: a solid is built from its spec alone (:func:`tactcad.solids.build.build_part`),
    so a run where one part changed projects that part's views only, and a run of
    the same design projects none. The sampling step follows from the solid, and
    tactcad's code and the CAD stack's versions are in every key.

    Args:
        spec: the part's :class:`~tactcad.catalogue.array_catalogue.PartSpec`.
        solid: its solid in the part frame (mm), built from ``spec``.
        view: the view's name in ``cameras``.
        cameras: view name -> (direction, up) (default :data:`CAMERAS`).

    Returns:
        a fresh :class:`View` (the caller may place and scale it; the kept one stays as made).

    Raises:
        KeyError: unknown view name.
    """
    from tactcad.store import kept_result

    camera = (cameras or CAMERAS)[view]
    kept = kept_result(PROJECTION_KIND, lambda: project(solid, view, cameras=cameras),
                       spec, view, camera)
    return copy.copy(kept)


def _resampled(poly: Polyline, step: float) -> np.ndarray:
    """``poly``'s points with each segment cut into equal pieces at most
    ``step`` long, as an (n, 2) array; every point as :func:`_resample` computes
    it, to the last bit (the same operations in the same order)."""
    p = np.asarray(poly, dtype=float)
    d = p[1:] - p[:-1]
    n = np.array([max(1, int(math.ceil(math.hypot(dx, dy) / step))) for dx, dy in d.tolist()],
                 dtype=np.int64)
    seg = np.repeat(np.arange(len(n)), n)
    k = np.arange(1, len(seg) + 1) - np.repeat(np.cumsum(n) - n, n)
    return np.concatenate([p[:1], p[seg] + d[seg] * k[:, None] / n[seg][:, None]])


def _resample(poly: Polyline, step: float) -> Polyline:
    out = [poly[0]]
    for (x0, y0), (x1, y1) in zip(poly, poly[1:]):
        n = max(1, int(math.ceil(math.hypot(x1 - x0, y1 - y0) / step)))
        out += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(1, n + 1)]
    return out


def clip_to_circle(polys: list[Polyline], centre: Point, radius: float,
                   step: float) -> list[Polyline]:
    """The parts of ``polys`` inside a circle (view coordinates), resampled at
    ``step`` so each run ends within ``step`` of the boundary."""
    out: list[Polyline] = []
    cx, cy = centre
    for poly in polys:
        run: Polyline = []
        for p in _resample(poly, step):
            if math.hypot(p[0] - cx, p[1] - cy) <= radius:
                run.append(p)
            else:
                if len(run) > 1:
                    out.append(run)
                run = []
        if len(run) > 1:
            out.append(run)
    return [_simplify(r) for r in out]


def _simplify(poly: Polyline, tol: float = 1e-7) -> Polyline:
    """Drop points that lie on the straight line through their neighbours."""
    if len(poly) < 3:
        return poly
    out = [poly[0]]
    for p, q in zip(poly[1:], poly[2:]):
        a = out[-1]
        cross = (p[0] - a[0]) * (q[1] - a[1]) - (p[1] - a[1]) * (q[0] - a[0])
        if abs(cross) > tol:
            out.append(p)
    out.append(poly[-1])
    return out


def detail(front: View, centre: Point, radius: float, scale: float, name: str) -> View:
    """A detail view: the front view's edges inside a circle, at another scale."""
    step = radius / 400
    vis = clip_to_circle(front.visible, centre, radius, step)
    hid = clip_to_circle(front.hidden, centre, radius, step)
    bbox = (centre[0] - radius, centre[1] - radius, centre[0] + radius, centre[1] + radius)
    return View(name, vis, hid, bbox, scale=scale, clip=(centre, radius))
