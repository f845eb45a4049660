"""The gmsh mesh of one row's comb sheet: spine, posts and elements in the sheet's plane.

The outline is the sheet's exact wire-cut outline
(:func:`tactcad.geometry.profile.comb_sheet_profile`: lines and arcs, the fastener holes),
cut into faces by what the plane model tells apart: each gauge's glue line and carrier (a
rectangle on its element's top face, the grid's ends as vertices on its top edge) and
each screw's head (a disk about the screw's hole: the annulus under the head is what the
screw holds). gmsh's OpenCASCADE kernel fragments the faces so the mesh is conforming
across them (:func:`mesh_comb_sheet`).

Sizes: ``web_divisions`` elements through the material over each notch (``t /
web_divisions`` at its neck, growing as the notch opens, as the single element's mesh,
:mod:`tactcad.mechanics.fem.fem_mesh`), one cell through each bonded layer (grown away from
it by 0.5 mm per mm), every arc and circle (notches, fillets, holes, heads) at gmsh's size
from its curvature (:data:`CURVE_DIVISIONS` a full circle), spread from the boundary, a far
size of a quarter of the arm's height (or the tip's width) over the elements and their
posts, and an eighth of the spine's height in the spine below them. ``size_factor`` scales
every size (the error estimate's second mesh). Sheet frame, mm.

Sources: gmsh reference manual (OpenCASCADE kernel, ``fragment``, mesh size fields
``MathEval``, ``Distance``, ``Threshold``, ``Box``, ``Min``; ``Mesh.MeshSizeFactor``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Protocol, Sequence

import numpy as np

from tactcad.geometry.profile import Arc, CombSheetOutline, comb_sheet_profile
from tactcad.mechanics.fem.fem_mesh import (WEB_DIVISIONS, _read_mesh, gmsh_session,
                                            occ_outline_curves)

#: Growth of the element size away from a layer (mm per mm), as the element's mesh.
GROWTH = 0.5
#: Elements per full circle on every arc and circle of the outline (gmsh's size from
#: curvature): 2 pi r / 12, about half the radius, the element mesh's size on an inside
#: fillet (the notch near its neck is finer, on the web's size). On the 10 mm grasper's
#: comb 32 moves crosstalk_rel by 0.7 % and costs two and a half times as long.
CURVE_DIVISIONS = 12
#: Elements through the spine's height far from the elements and the fasteners.
SPINE_DIVISIONS = 8


class CombSheetBody(CombSheetOutline, Protocol):
    """What the mesh reads of a row's sheet: its outline and its spine's height (mm)."""

    @property
    def spine_height_mm(self) -> float: ...


@dataclass(frozen=True)
class LayerBox:
    """One gauge's glue line and carrier on the sheet (sheet frame, mm).

    Attributes:
        x0_mm, x1_mm: the carrier's ends. grid_x0_mm, grid_x1_mm: the grid's ends.
        y0_mm, y1_mm: the top face it is bonded to and the grid's plane (the layer's top).
    """

    x0_mm: float
    x1_mm: float
    grid_x0_mm: float
    grid_x1_mm: float
    y0_mm: float
    y1_mm: float


@dataclass(frozen=True)
class Circle2:
    """A circle of the sheet (sheet frame, mm): a hole's rim or a screw head's edge."""

    centre: tuple[float, float]
    radius: float


@dataclass(frozen=True)
class SheetMesh:
    """A linear triangle mesh of one row's sheet, as read from gmsh.

    Attributes:
        p: vertices, shape (2, n), mm. t: triangles, shape (3, m).
        arcs: every arc and circle of the outline (notches, fillets, holes) and the heads'
            edges, for the P2 geometry nodes on the exact circles.
        layer_cells: per layer, the cells inside it (bool, shape (m,)).
        head_cells: cells under any screw head, outside its hole (bool, shape (m,)).
        grid_vertices: per layer, the vertex indices of the grid's two ends.
        mesh_time_s: gmsh's wall time (s).
    """

    p: np.ndarray
    t: np.ndarray
    arcs: tuple
    layer_cells: tuple[np.ndarray, ...]
    head_cells: np.ndarray
    grid_vertices: tuple[tuple[int, int], ...]
    mesh_time_s: float


def _size_fields(gm, sheet: CombSheetBody, necks: Sequence[tuple[int, float, float]],
                 layers: Sequence[LayerBox], web_divisions: float, far: float) -> None:
    """The background size field: the minimum of each web's size and a ``Box`` about each
    layer, capped at ``far``; the arcs' and circles' sizes are gmsh's own from their
    curvature (:data:`CURVE_DIVISIONS`) and spread from the boundary.

    Args:
        necks: (point tag of the neck, web t, notch radius R) of each element: the webs of
            one (t, R) share one ``Distance`` field from their necks and one ``MathEval``
            (t + d^2 / 2R) / web_divisions of it.
    """
    f = gm.model.mesh.field
    ids = []
    groups: dict[tuple[float, float], list[int]] = {}
    for tag, t, R in necks:
        groups.setdefault((t, R), []).append(tag)
    for (t, R), tags in sorted(groups.items()):
        d = f.add("Distance")
        f.setNumbers(d, "PointsList", tags)
        web = f.add("MathEval")
        f.setString(web, "F", f"({t!r}+F{d}^2/(2*{R!r}))/{float(web_divisions)!r}")
        ids.append(web)
    spine_far = max(far, sheet.spine_height_mm / SPINE_DIVISIONS)
    for b in layers:  # one cell through the layer, grown away from it
        inside = b.y1_mm - b.y0_mm
        box = f.add("Box")
        for key, value in (("VIn", inside), ("VOut", spine_far), ("XMin", b.x0_mm),
                           ("XMax", b.x1_mm), ("YMin", b.y0_mm), ("YMax", b.y1_mm),
                           ("ZMin", -1.0), ("ZMax", 1.0),
                           ("Thickness", max(far - inside, 1e-9) / GROWTH)):
            f.setNumber(box, key, value)
        ids.append(box)
    # the elements' band (from a far size under the lowest ledge up) at the far size, the
    # spine below it at the spine's, grown between them
    band = f.add("Box")
    for key, value in (("VIn", far), ("VOut", spine_far), ("XMin", -1.0),
                       ("XMax", sheet.length_mm + 1.0), ("YMin", min(sheet.ledges_mm) - far),
                       ("YMax", 1e3), ("ZMin", -1.0), ("ZMax", 1.0),
                       ("Thickness", max(spine_far - far, 1e-9) / GROWTH)):
        f.setNumber(band, key, value)
    ids.append(band)
    mn = f.add("Min")
    f.setNumbers(mn, "FieldsList", ids)
    f.setAsBackgroundMesh(mn)
    o = gm.option
    o.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
    o.setNumber("Mesh.MeshSizeFromPoints", 0)
    o.setNumber("Mesh.MeshSizeFromCurvature", CURVE_DIVISIONS)
    o.setNumber("Mesh.MeshSizeMax", spine_far)


def mesh_comb_sheet(sheet: CombSheetBody, layers: Sequence[LayerBox],
                    heads: Sequence[Circle2], *, size_factor: float = 1.0,
                    web_divisions: float = WEB_DIVISIONS) -> SheetMesh:
    """Mesh one row's sheet with linear triangles (the solver makes them P2).

    Args:
        sheet: the row's sheet (its outline, :class:`~tactcad.geometry.profile.
            CombSheetOutline`, and its spine's height).
        layers: each gauge's glue line and carrier (sheet frame).
        heads: each screw head's edge (a circle about its hole, inside the sheet).
        size_factor: multiplies every size (< 1 refines).
        web_divisions: elements through each web at its neck.

    Returns:
        :class:`SheetMesh`.

    Raises:
        ValueError: a non-positive ``size_factor``.
        RuntimeError: gmsh could not mesh the sheet, or a grid's end is no vertex.
    """
    if not size_factor > 0:
        raise ValueError(f"size_factor must be > 0, got {size_factor!r}")
    prof = comb_sheet_profile(sheet)
    arcs = [s for s in prof.outer if isinstance(s, Arc)]
    holes = [Circle2(tuple(h.centre), h.radius) for h in prof.holes]
    t0 = time.perf_counter()
    with gmsh_session("tactcad_comb_sheet") as gm:
        occ = gm.model.occ
        curves, _ = occ_outline_curves(occ, prof.outer)
        loops = [occ.addCurveLoop(curves)]
        loops += [occ.addCurveLoop([occ.addCircle(c.centre[0], c.centre[1], 0.0, c.radius)])
                  for c in holes]
        body = occ.addPlaneSurface(loops)
        tools = []
        for b in layers:
            top = sorted({b.grid_x0_mm, b.grid_x1_mm})
            corners = [(b.x0_mm, b.y0_mm), (b.x1_mm, b.y0_mm), (b.x1_mm, b.y1_mm),
                       *[(x, b.y1_mm) for x in reversed(top)], (b.x0_mm, b.y1_mm)]
            ids = [occ.addPoint(x, y, 0.0) for x, y in corners]
            edges = [occ.addLine(a, c) for a, c in zip(ids, ids[1:] + ids[:1])]
            tools.append((2, occ.addPlaneSurface([occ.addCurveLoop(edges)])))
        for h in heads:  # the annulus under the head: the disk less the hole it is about
            disk = occ.addDisk(h.centre[0], h.centre[1], 0.0, h.radius, h.radius)
            inner = [c for c in holes if math.dist(c.centre, h.centre) < 1e-9]
            if inner:
                cut = occ.addDisk(h.centre[0], h.centre[1], 0.0, inner[0].radius,
                                  inner[0].radius)
                tools += [e for e in occ.cut([(2, disk)], [(2, cut)])[0] if e[0] == 2]
            else:
                tools.append((2, disk))
        if tools:
            occ.fragment([(2, body)], tools)
        occ.synchronize()
        far = min(min(g.arm_height_mm, g.tip_width_mm) for g in sheet.elements) / 4
        necks = [(occ.addPoint(x0 + g.hinge_x_mm, g.notch_centre_y_mm + g.notch_radius_mm, 0.0),
                  g.web_thickness_mm, g.notch_radius_mm)
                 for g, x0 in zip(sheet.elements, sheet.offsets_mm)]
        occ.synchronize()
        _size_fields(gm, sheet, necks, layers, web_divisions, far)
        gm.option.setNumber("Mesh.MeshSizeFactor", size_factor)
        gm.option.setNumber("Mesh.Algorithm", 6)
        gm.option.setNumber("General.NumThreads", 1)
        try:
            gm.model.mesh.generate(2)
        except Exception as exc:  # gmsh raises a bare Exception
            raise RuntimeError(f"gmsh could not mesh the comb sheet: {exc}") from exc
        p, t = _read_mesh(gm, 2)
    cx, cy = p[0][t].mean(axis=0), p[1][t].mean(axis=0)
    layer_cells = tuple((cx > b.x0_mm) & (cx < b.x1_mm) & (cy > b.y0_mm) & (cy < b.y1_mm)
                        for b in layers)
    head_cells = np.zeros(t.shape[1], dtype=bool)
    for h in heads:
        head_cells |= np.hypot(cx - h.centre[0], cy - h.centre[1]) < h.radius
    grid = []
    for b in layers:
        ends = []
        for x in (b.grid_x0_mm, b.grid_x1_mm):
            d = np.hypot(p[0] - x, p[1] - b.y1_mm)
            k = int(np.argmin(d))
            if d[k] > 1e-8:
                raise RuntimeError(f"the grid's end x = {x:g} mm is not a mesh vertex")
            ends.append(k)
        grid.append((ends[0], ends[1]))
    circles = tuple(arcs) + tuple(holes) + tuple(heads)
    return SheetMesh(p=p, t=t, arcs=circles, layer_cells=layer_cells, head_cells=head_cells,
                     grid_vertices=tuple(grid), mesh_time_s=time.perf_counter() - t0)
