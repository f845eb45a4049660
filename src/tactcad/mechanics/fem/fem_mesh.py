"""FEM region of a flexure sensing element and its gmsh meshes (2D and 3D).

The finite-element scene holds only what the tip stiffness depends on: the
web over the flexure hinge (single-sided circular notch), the measuring arm,
the tip, and a strip of the base behind the notch. The rest of the base is
replaced by a boundary condition: all displacements are fixed on the clamp
line ``x = x_clamp``. :func:`fem_region` is the one place that makes this
choice; the 2D and 3D meshers both use it.

The clamp line is a modelling choice, not the edge of the clamp plates. In
the stack the plates hold each base from its back end up to
``x = clamp_leg_length`` (:mod:`tactcad.design`: the shortest base, i.e.
the one of the longest arm, less the arm clearance; 12 mm in the default
design), the same for every element of the array, while the FEM clamp line
sits ``max(R, arm height)`` behind the notch's back wall (capped in front of
the bolt holes). So:

* for the shorter arms (4-6 mm in the default design) the clamp line lies
  0.5-2.5 mm in front of the plate edge, nearer the notch: the base strip
  between the plate edge and the clamp line is free in the stack but
  modelled rigid, so K is high; clamping at the plate edge instead changes
  the fem3d K by -0.18 % (4 mm), -0.12 % (5 mm), -0.06 % (6 mm);
* for the longer arms the clamp line lies behind the plate edge: base
  material the plates hold is modelled free, and clamping at the plate edge
  gives +0.11 % (7 mm, 0.5 mm behind) and +1.32 % (8 mm, where the plates
  reach within the 0.5 mm arm clearance of the notch and the clamp line sits
  1.5 mm behind their edge).

Both stay below the closed form's 2 % goal; fem3d itself agrees with
CalculiX on the same region and clamp within 0.01 %.

The cropped outline is cut from the exact wire-cut profile
(:func:`tactcad.geometry.profile.element_profile`, the same lines and arcs the DXF
exports): the closed chain is clipped against the half plane
``x >= x_clamp`` and closed by a line on the clamp line. Arcs stay arcs in
gmsh (OpenCASCADE kernel, three-point circle arcs).

Mesh size: a gmsh background field (``MathEval`` expressions of x and y,
so one field serves the plane mesh and the extruded 3D mesh) puts
``web_divisions`` elements through the local material height over the notch
(``t / web_divisions`` at the neck of the flexure hinge, t = web thickness),
resolves the notch arc and the tip-root fillet, and grows linearly to a
coarse size on the arm and the base. ``size_factor`` scales every size,
which gives the mesh sequence for Richardson extrapolation. In 3D the plane
mesh is extruded in graded layers (prisms split into tetrahedra).

Frames and units: element frame of :mod:`tactcad.design` (x along the arm,
y up, z through the sheet), mm.

Sources: gmsh reference manual (OpenCASCADE kernel, ``extrude`` with
layers, mesh size fields ``MathEval``, ``Threshold``, ``Min``; option
``Mesh.MeshSizeFactor``); scikit-fem documentation (``MeshTri2``,
``MeshTet2`` isoparametric meshes).
"""

from __future__ import annotations

import contextlib
import math
import os
import tempfile
from dataclasses import dataclass
from typing import Iterator, NamedTuple, Sequence

import numpy as np

from tactcad.design.array_plan import ElementGeometry
from tactcad.geometry.profile import Arc, Line, Segment, contour_area, element_profile
from tactcad.stopping import signal_dispositions_kept

#: Default clamp margin, as a multiple of the larger of the notch radius and
#: the arm height (see :func:`default_clamp_margin_mm`).
CLAMP_MARGIN_FACTOR = 1.0

#: Default element size at the neck: web thickness / WEB_DIVISIONS.
WEB_DIVISIONS = 6.0

_GEOM_TOL = 1e-9


# ---------------------------------------------------------------------------
# The FEM region (cropped outline)
# ---------------------------------------------------------------------------
class FemRegion(NamedTuple):
    """Cropped outline that the FEM meshes, and where it is clamped.

    Attributes:
        outline: closed CCW chain of :class:`~tactcad.geometry.profile.Line` /
            :class:`~tactcad.geometry.profile.Arc` segments (mm); its last segment is
            the clamp line, running down ``x = x_clamp``.
        x_clamp: x of the clamp line (mm, element frame).
        reason: why the clamp line sits where it does.
    """

    outline: tuple[Segment, ...]
    x_clamp: float
    reason: str

    @property
    def area_mm2(self) -> float:
        return contour_area(self.outline)

    def arcs(self) -> tuple[Arc, ...]:
        return tuple(s for s in self.outline if isinstance(s, Arc))


def _bolt_room_mm(g: ElementGeometry) -> float:
    """Distance (mm) from the notch's back wall back to the nearest bolt-hole edge."""
    x_back = g.hinge_x_mm - g.notch_radius_mm
    x_free = max((h.x_mm + h.diameter_mm / 2 for h in g.bolt_holes), default=0.0)
    return x_back - x_free


def default_clamp_margin_mm(g: ElementGeometry) -> float:
    """Default distance (mm) from the notch's back wall to the clamp line.

    ``CLAMP_MARGIN_FACTOR * max(R, arm height)``: the web's bending moment
    enters the base through a corner region whose size is set by the notch
    radius R and the arm height (the notch's front wall); beyond about one
    such length into the base little strain energy is left (the clamp-line
    tests measure the change of K when the line moves further in). Capped at
    90 % of the room in front of the bolt holes. This line is not the clamp
    plates' edge (``clamp_leg_length`` of the plan): see the module docstring
    for where it lies relative to that edge and what that does to K.
    """
    want = CLAMP_MARGIN_FACTOR * max(g.notch_radius_mm, g.arm_height_mm)
    return min(want, 0.9 * _bolt_room_mm(g))


def fem_region(g: ElementGeometry, margin_mm: float | None = None) -> FemRegion:
    """The profile cropped at the clamp line ``x_clamp = hinge_x - R - margin``.

    Args:
        g: element geometry (mm).
        margin_mm: strip of clamped base kept behind the notch's back wall
            (mm, > 0); ``None`` uses :func:`default_clamp_margin_mm`.

    Returns:
        :class:`FemRegion` ``(outline, x_clamp, reason)``; a NamedTuple, so it
        also unpacks as a 3-tuple.

    Raises:
        ValueError: margin not positive, or the clamp line would reach a
            bolt hole (the region is the base strip in front of the bolts).
    """
    auto = margin_mm is None
    margin = default_clamp_margin_mm(g) if auto else float(margin_mm)
    if not (margin > 0 and math.isfinite(margin)):
        raise ValueError(f"clamp margin must be a positive length in mm, got {margin_mm!r}")
    x_back = g.hinge_x_mm - g.notch_radius_mm
    x_clamp = x_back - margin
    room = _bolt_room_mm(g)
    if margin >= room - _GEOM_TOL:
        raise ValueError(
            f"clamp line x = {x_clamp:.4g} mm (margin {margin:.4g} mm behind the notch's back "
            f"wall at x = {x_back:.4g} mm) must stay in front of the bolt holes; allowed "
            f"margin < {room:.4g} mm")
    outline = clip_chain(element_profile(g).outer, x_clamp)
    if auto:
        want = CLAMP_MARGIN_FACTOR * max(g.notch_radius_mm, g.arm_height_mm)
        why = (f"{CLAMP_MARGIN_FACTOR:g} x max(notch radius {g.notch_radius_mm:g} mm, arm height "
               f"{g.arm_height_mm:g} mm)")
        if margin < want:
            why += f", capped at 90 % of the {room:.4g} mm in front of the bolt holes"
        reason = (f"clamp line {margin:.4g} mm behind the notch's back wall ({why}): the base "
                  f"beyond it carries little strain energy; all displacements fixed there "
                  f"(a modelling choice, not the clamp plates' edge)")
    else:
        reason = (f"clamp line {margin:.4g} mm behind the notch's back wall (margin given by "
                  f"the caller); all displacements fixed there")
    return FemRegion(outline, x_clamp, reason)


def _line_pieces(s: Line, xc: float) -> list[Segment]:
    (x0, y0), (x1, y1) = s.start, s.end
    if (x0 - xc) * (x1 - xc) < 0:
        f = (xc - x0) / (x1 - x0)
        pm = (xc, y0 + f * (y1 - y0))
        return [Line(s.start, pm), Line(pm, s.end)]
    return [s]


def _arc_pieces(s: Arc, xc: float) -> list[Segment]:
    cx, cy = s.centre
    r = s.radius
    c = (xc - cx) / r
    if abs(c) >= 1.0:
        return [s]
    a0 = math.atan2(s.start[1] - cy, s.start[0] - cx)
    sweep = s.sweep
    th = math.acos(c)
    fracs = []
    for ang in (th, -th):
        d = ang - a0
        if sweep > 0:
            d = d % (2 * math.pi)
        else:
            d = -((-d) % (2 * math.pi))
        f = d / sweep
        if 1e-12 < f < 1 - 1e-12:
            fracs.append(f)
    if not fracs:
        return [s]
    fracs.sort()
    pts = [s.start]
    for f in fracs:
        a = a0 + f * sweep
        pts.append((xc, cy + r * math.sin(a)))
    pts.append(s.end)
    return [Arc(pts[i], pts[i + 1], s.centre, s.ccw) for i in range(len(pts) - 1)]


def _mid_x(s: Segment) -> float:
    if isinstance(s, Arc):
        return s.midpoint[0]
    return 0.5 * (s.start[0] + s.end[0])


def clip_chain(segments: Sequence[Segment], x_clamp: float) -> tuple[Segment, ...]:
    """Clip a closed CCW chain of lines and arcs to ``x >= x_clamp``.

    Segments crossing the line are split at the crossing (arcs into sub-arcs
    of the same circle); the kept pieces are closed by one line along
    ``x = x_clamp``, which becomes the last segment of the returned chain.

    Raises:
        ValueError: the clamp line does not cross the chain exactly twice
            (the cropped region would not be one simply connected piece).
    """
    pieces: list[Segment] = []
    for s in segments:
        pieces.extend(_arc_pieces(s, x_clamp) if isinstance(s, Arc) else _line_pieces(s, x_clamp))
    keep = [_mid_x(p) > x_clamp for p in pieces]
    n = len(pieces)
    exits = [i for i in range(n) if keep[i] and not keep[(i + 1) % n]]
    if len(exits) != 1 or all(keep):
        raise ValueError(f"clamp line x = {x_clamp:.6g} mm must cross the profile exactly twice")
    # the kept pieces are consecutive (one exit): start after the re-entry
    entry = next(i for i in range(n) if keep[i] and not keep[i - 1])
    kept = [pieces[(entry + k) % n] for k in range(n) if keep[(entry + k) % n]]
    closing = Line(kept[-1].end, kept[0].start)
    if abs(closing.start[0] - x_clamp) > 1e-9 or abs(closing.end[0] - x_clamp) > 1e-9:
        raise ValueError("clamp line crossing is not on x_clamp")
    return tuple(kept) + (closing,)


# ---------------------------------------------------------------------------
# gmsh
# ---------------------------------------------------------------------------
def initialize_gmsh() -> None:
    """Start gmsh as tactcad runs it: no configuration files read, no interrupt handler
    of its own, this process's signal dispositions kept (gmsh leaves SIGPIPE, SIGTERM and
    the fault signals at their defaults; a host process, the API, a watch session, a test
    worker, keeps its own) and the user's home left untouched: the GUI toolkit linked into
    gmsh writes its preferences (``~/.fltk/fltk.org/fltk.prefs``) under ``$HOME`` as gmsh
    starts, so ``$HOME`` names a temporary folder, removed after, for that moment.
    """
    import gmsh

    home = os.environ.get("HOME")
    with tempfile.TemporaryDirectory(prefix="tactcad-gmsh-") as scratch, \
            signal_dispositions_kept():
        os.environ["HOME"] = scratch
        try:
            gmsh.initialize(readConfigFiles=False, interruptible=False)
        finally:
            if home is None:
                os.environ.pop("HOME", None)
            else:
                os.environ["HOME"] = home


@contextlib.contextmanager
def gmsh_session(name: str) -> Iterator[object]:
    """A quiet gmsh model; gmsh is initialised (and finalised) here unless a
    caller already holds it, in which case only the model is added/removed."""
    import gmsh

    own = not gmsh.isInitialized()
    if own:
        initialize_gmsh()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.model.add(name)
        yield gmsh
    finally:
        try:
            if not own:
                gmsh.model.remove()
        finally:
            if own:
                gmsh.finalize()


@dataclass(frozen=True)
class MeshSizes:
    """Element sizes (mm) of a region mesh before ``size_factor``.

    Attributes:
        web_divisions: elements through the local material height over the
            notch: size(d) = (t + d^2 / 2R) / web_divisions at distance d from
            the neck (t + d^2/2R is the material height over a circular
            notch to second order; the neck is the notch's top point, a line
            along z in 3D).
        web_thickness: t (mm).
        notch_radius: R (mm).
        arc: largest size along the notch arc (resolves its curvature).
        far: size on the arm and base, far from the notch.
        growth: size increase per unit distance from an arc (mm/mm).
        fillet: size at the tip-root fillet.
    """

    web_divisions: float
    web_thickness: float
    notch_radius: float
    arc: float
    far: float
    growth: float
    fillet: float

    @property
    def neck(self) -> float:
        """Element size at the neck (mm)."""
        return self.web_thickness / self.web_divisions


def default_sizes(g: ElementGeometry, web_divisions: float = WEB_DIVISIONS) -> MeshSizes:
    """Mesh sizes for P2 elements.

    ``web_divisions`` elements through the material height over the notch
    (``t / web_divisions`` at the neck), at most ``R pi / 16`` along the
    notch arc (with isoparametric P2 cells this represents the circle far
    below the FEM error), half the fillet radius at the tip-root fillet, a
    quarter of the arm height (or tip width) far away, growing by 0.5 mm per
    mm from the arcs.
    """
    far = min(g.arm_height_mm / 4, g.tip_width_mm / 4)
    R = g.notch_radius_mm
    return MeshSizes(web_divisions=float(web_divisions), web_thickness=g.web_thickness_mm,
                     notch_radius=R, arc=min(R * math.pi / 16, far), far=far, growth=0.5,
                     fillet=min(g.inside_corner_radius_mm / 2, far))


#: Cells through a bonded layer's height (P2: its bending and axial strain, linear and
#: constant through so thin a layer, are carried by one: the macro array's K rise moves by
#: 0.006 points of its 7 % from one cell to two, while two cells cost half the mesh again).
LAYER_CELLS = 1


def graded_layers(depth: float, n_layers: int, grading: float) -> list[float]:
    """Layer thicknesses (mm) of an extrusion of ``depth`` into ``n_layers``,
    growing geometrically from z = 0 so that the last layer is ``grading``
    times the first: z_k = depth (q^(k/n) - 1) / (q - 1), q = grading.
    Refining (more layers, same q) shrinks every layer by the same factor.

    Raises:
        ValueError: depth <= 0, n_layers < 1 or grading <= 0.
    """
    if not depth > 0 or n_layers < 1 or not grading > 0:
        raise ValueError("depth > 0, n_layers >= 1 and grading > 0 are required")
    s = np.arange(n_layers + 1) / n_layers
    z = depth * s if abs(grading - 1.0) < 1e-12 else depth * (grading**s - 1) / (grading - 1)
    return list(np.diff(z))


def _build_surface(gm, region: FemRegion, split_points: Sequence[tuple[float, float]]):
    """OCC plane surface of the outline; lines containing a split point are
    split there (gives a mesh vertex, e.g. the gauge point). Returns
    (surface tag, {curve tag: segment})."""
    curves, curve_seg = occ_outline_curves(gm.model.occ, region.outline, split_points)
    loop = gm.model.occ.addCurveLoop(curves)
    surf = gm.model.occ.addPlaneSurface([loop])
    return surf, curve_seg


def occ_outline_curves(occ, outline: Sequence[Segment],
                       split_points: Sequence[tuple[float, float]] = ()
                       ) -> tuple[list[int], dict[int, Segment]]:
    """The OCC curves of a closed outline of lines and arcs (mm), in its order, each
    corner one shared point; a line holding a split point is split there (a mesh vertex,
    e.g. a gauge's grid end).

    Args:
        occ: gmsh's ``model.occ``. outline: the segments, closed, in order.
        split_points: points on lines of the outline to split them at.

    Returns:
        (the curve tags in order, {curve tag: the segment it draws}).
    """
    cache: dict[tuple[float, float], int] = {}

    def pt(p):
        key = (round(p[0], 12), round(p[1], 12))
        if key not in cache:
            cache[key] = occ.addPoint(p[0], p[1], 0.0)
        return cache[key]

    curves: list[int] = []
    curve_seg: dict[int, Segment] = {}
    for s in outline:
        if isinstance(s, Arc):
            m = s.midpoint
            tag = occ.addCircleArc(pt(s.start), occ.addPoint(m[0], m[1], 0.0), pt(s.end),
                                   center=False)
            curves.append(tag)
            curve_seg[tag] = s
            continue
        parts = [s]
        for q in split_points:
            new = []
            for ln in parts:
                (x0, y0), (x1, y1) = ln.start, ln.end
                cross = (x1 - x0) * (q[1] - y0) - (y1 - y0) * (q[0] - x0)
                L = ln.length()
                if abs(cross) < 1e-9 * L:
                    f = ((q[0] - x0) * (x1 - x0) + (q[1] - y0) * (y1 - y0)) / (L * L)
                    if 1e-9 < f < 1 - 1e-9:
                        new += [Line(ln.start, q), Line(q, ln.end)]
                        continue
                new.append(ln)
            parts = new
        for ln in parts:
            tag = occ.addLine(pt(ln.start), pt(ln.end))
            curves.append(tag)
            curve_seg[tag] = ln
    return curves, curve_seg


def _size_fields(gm, sizes: MeshSizes, neck: tuple[float, float],
                 arcs: Sequence[tuple[Arc, float]],
                 layer: tuple[float, float, float, float] | None = None) -> None:
    """Background size field: the minimum of the web size
    (t + d^2/2R) / web_divisions (d = distance from the neck) and thresholds
    on the distance to each arc's circle; all are MathEval expressions of x
    and y, so the same field serves 2D and the extruded 3D mesh."""
    f = gm.model.mesh.field
    ids = []

    def threshold(expr: str, size_min: float, band: float) -> None:
        d = f.add("MathEval")
        f.setString(d, "F", expr)
        th = f.add("Threshold")
        f.setNumber(th, "InField", d)
        f.setNumber(th, "SizeMin", size_min)
        f.setNumber(th, "SizeMax", sizes.far)
        f.setNumber(th, "DistMin", band)
        f.setNumber(th, "DistMax", band + max(sizes.far - size_min, 1e-9) / sizes.growth)
        ids.append(th)

    def r(cx, cy):
        return f"Sqrt((x-({cx!r}))^2+(y-({cy!r}))^2)"

    web = f.add("MathEval")
    d2 = f"((x-({neck[0]!r}))^2+(y-({neck[1]!r}))^2)"
    f.setString(web, "F", f"({sizes.web_thickness!r}+{d2}/(2*{sizes.notch_radius!r}))"
                          f"/{sizes.web_divisions!r}")
    ids.append(web)
    for arc, size in arcs:
        threshold(f"Abs({r(*arc.centre)}-({arc.radius!r}))", size, 0.0)
    if layer is not None:  # a bonded layer: LAYER_CELLS through its height, grown away from it
        x0, y0, x1, y1 = layer
        inside = (y1 - y0) / LAYER_CELLS
        threshold(f"Max(Max({x0!r}-x,x-({x1!r})),Max({y0!r}-y,y-({y1!r})))", inside, 0.0)
    mn = f.add("Min")
    f.setNumbers(mn, "FieldsList", ids)
    f.setAsBackgroundMesh(mn)
    o = gm.option
    o.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    o.setNumber("Mesh.MeshSizeFromPoints", 0)
    o.setNumber("Mesh.MeshSizeFromCurvature", 0)


@dataclass(frozen=True)
class RegionMesh:
    """A linear simplex mesh of the FEM region, as read from gmsh.

    Attributes:
        p: vertex coordinates, shape (dim, n_vertices), mm.
        t: cells, shape (dim + 1, n_cells), vertex indices (triangles in 2D,
            tetrahedra in 3D).
        region: the cropped outline that was meshed.
        arcs: the outline's arcs (notch, fillet) for placing P2 geometry
            nodes on the exact circles.
        neck_size: element size at the neck (mm), after ``size_factor``.
        depth: extrusion depth along z (mm; 0 for a 2D mesh).
        gauge_vertex: index of the vertex at the gauge point (x = hinge_x,
            y = base height; z = depth in 3D, i.e. the symmetry plane).
        mesh_time_s: wall time spent in gmsh (s).
        layer_cells: cells of a bonded layer (bool, shape (n_cells,)), or None
            when none was meshed.
    """

    p: np.ndarray
    t: np.ndarray
    region: FemRegion
    arcs: tuple[Arc, ...]
    neck_size: float
    depth: float
    gauge_vertex: int
    mesh_time_s: float
    layer_cells: np.ndarray | None = None


def _read_mesh(gm, dim: int) -> tuple[np.ndarray, np.ndarray]:
    etype = 2 if dim == 2 else 4
    tags, coords, _ = gm.model.mesh.getNodes()
    coords = coords.reshape(-1, 3)
    _, enodes = gm.model.mesh.getElementsByType(etype)
    enodes = enodes.reshape(-1, dim + 1)
    lookup = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(len(tags))
    cells = lookup[enodes.astype(np.int64)]
    used, inv = np.unique(cells, return_inverse=True)
    p = coords[used, :dim].T.copy()
    t = inv.reshape(cells.shape).T.copy()
    return p, t


def _classify_arcs(region: FemRegion, g: ElementGeometry):
    notch, fillet = [], []
    for s in region.outline:
        if isinstance(s, Arc):
            if abs(s.radius - g.notch_radius_mm) < 1e-9 and \
                    abs(s.centre[0] - g.hinge_x_mm) < 1e-9:
                notch.append(s)
            else:
                fillet.append(s)
    return notch, fillet


def mesh_region(g: ElementGeometry, region: FemRegion | None = None, *, dim: int = 2,
                size_factor: float = 1.0, web_divisions: float = WEB_DIVISIONS,
                depth_mm: float | None = None, sizes: MeshSizes | None = None,
                z_layers: Sequence[float] | None = None,
                layer_box: tuple[float, float, float, float] | None = None,
                layer_marks_x: Sequence[float] = ()) -> RegionMesh:
    """Mesh the FEM region with linear triangles (2D) or tetrahedra (3D).

    Args:
        g: element geometry (mm).
        region: cropped outline; ``None`` uses :func:`fem_region` (g).
        dim: 2 (plane) or 3 (outline extruded along +z by ``depth_mm``).
        size_factor: multiplies every element size (< 1 refines).
        web_divisions: elements through the material height over the notch
            (neck element size = web thickness / web_divisions).
        depth_mm: extrusion depth in 3D; ``None`` = half the sheet thickness
            (half model cut at the symmetry plane z = b/2).
        sizes: explicit sizes; overrides ``web_divisions``.
        z_layers: 3D only: layer thicknesses from z = 0 (see
            :func:`graded_layers`); their sum is scaled to ``depth_mm``.
            ``None`` meshes the solid with unstructured tetrahedra.
        layer_box: (x0, y0, x1, y1) of a bonded layer's rectangle on the top face
            (mm; :meth:`tactcad.mechanics.bonded_layer.BondedLayer.box`), meshed with
            the body (shared nodes on the joint; in 3D extruded with it);
            :attr:`RegionMesh.layer_cells` marks its cells.
        layer_marks_x: x of mesh vertices on the layer's top edge (the grid's ends).

    Returns:
        :class:`RegionMesh` (vertex coordinates and cells; P2 fields are built
        on it by the solvers).

    Raises:
        ValueError: bad ``dim`` or non-positive ``size_factor``.
        RuntimeError: gmsh failed to mesh the region.
    """
    import time

    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    if not size_factor > 0:
        raise ValueError(f"size_factor must be > 0, got {size_factor!r}")
    region = fem_region(g) if region is None else region
    sizes = default_sizes(g, web_divisions) if sizes is None else sizes
    depth = (g.sheet_thickness_mm / 2 if depth_mm is None else float(depth_mm)) if dim == 3 else 0.0
    gauge = (g.hinge_x_mm, g.base_height_mm)
    notch_segs, fillet_segs = _classify_arcs(region, g)
    neck = (g.hinge_x_mm, g.notch_centre_y_mm + g.notch_radius_mm)
    t0 = time.perf_counter()
    with gmsh_session(f"tactcad_fem{dim}d") as gm:
        occ = gm.model.occ
        surf, _ = _build_surface(gm, region, [gauge])
        faces = [(2, surf)]
        if layer_box is not None:
            x0, y0, x1, y1 = layer_box
            top = sorted(x for x in layer_marks_x if x0 < x < x1)
            corners = [(x0, y0), (x1, y0), (x1, y1), *[(x, y1) for x in reversed(top)],
                       (x0, y1)]
            ids = [occ.addPoint(x, y, 0.0) for x, y in corners]
            edges = [occ.addLine(a, b) for a, b in zip(ids, ids[1:] + ids[:1])]
            rect = occ.addPlaneSurface([occ.addCurveLoop(edges)])
            joined, _ = occ.fragment([(2, surf)], [(2, rect)])
            faces = [(d, t) for d, t in joined if d == 2]
        if dim == 3:
            if z_layers is None:
                occ.extrude(faces, 0.0, 0.0, depth)
            else:
                zs = np.cumsum(np.asarray(z_layers, dtype=float))
                occ.extrude(faces, 0.0, 0.0, depth, numElements=[1] * len(zs),
                            heights=list(zs / zs[-1]))
            if len(faces) > 1:  # the two extruded bodies share their joint's nodes
                occ.removeAllDuplicates()
        occ.synchronize()
        _size_fields(gm, sizes, neck, [(a, sizes.arc) for a in notch_segs]
                     + [(a, sizes.fillet) for a in fillet_segs], layer_box)
        gm.option.setNumber("Mesh.MeshSizeFactor", size_factor)
        gm.option.setNumber("Mesh.Algorithm", 6)
        gm.option.setNumber("Mesh.Algorithm3D", 1)
        gm.option.setNumber("General.NumThreads", 1)
        try:
            gm.model.mesh.generate(dim)
        except Exception as exc:  # gmsh raises a bare Exception
            raise RuntimeError(f"gmsh could not mesh the FEM region: {exc}") from exc
        p, t = _read_mesh(gm, dim)
    mesh_time = time.perf_counter() - t0
    target = np.array(gauge + ((depth,) if dim == 3 else ()))
    dist = np.linalg.norm(p - target[:, None], axis=0)
    gv = int(np.argmin(dist))
    if dist[gv] > 1e-8:
        raise RuntimeError("gauge point is not a mesh vertex")
    layer_cells = None
    if layer_box is not None:
        cx, cy = p[0][t].mean(axis=0), p[1][t].mean(axis=0)
        x0, y0, x1, y1 = layer_box
        layer_cells = (cy > y0) & (cy < y1) & (cx > x0) & (cx < x1)
        if not layer_cells.any():
            raise RuntimeError("the bonded layer was not meshed")
    return RegionMesh(p=p, t=t, region=region, arcs=tuple(notch_segs + fillet_segs),
                      neck_size=sizes.neck * size_factor, depth=depth, gauge_vertex=gv,
                      mesh_time_s=mesh_time, layer_cells=layer_cells)


def curved_doflocs(doflocs: np.ndarray, p: np.ndarray, edge_vertices: np.ndarray,
                   edge_dofs: np.ndarray, arcs: Sequence[Arc], tol: float = 1e-7) -> np.ndarray:
    """Move P2 edge geometry nodes onto the exact circles of the outline's arcs.

    An edge whose two vertices lie on one arc's circle (in x, y; any z) gets
    its midside node projected radially onto that circle, so a quadratic
    (isoparametric) mesh follows the notch and fillet exactly to O(h^3).

    Args:
        doflocs: geometry node coordinates, shape (dim, n_nodes); a copy is
            returned.
        p: vertex coordinates, shape (dim, n_vertices).
        edge_vertices: shape (2, n_edges), vertex indices of each edge.
        edge_dofs: shape (n_edges,), index in ``doflocs`` of each edge's
            midside node.
        arcs: circles to project onto.
    """
    out = doflocs.copy()
    for a in arcs:
        cx, cy = a.centre
        r = a.radius
        rv = np.hypot(p[0] - cx, p[1] - cy)
        on = np.abs(rv - r) < tol * max(1.0, r)
        sel = on[edge_vertices[0]] & on[edge_vertices[1]]
        if not np.any(sel):
            continue
        d = edge_dofs[sel]
        dx, dy = out[0, d] - cx, out[1, d] - cy
        rr = np.hypot(dx, dy)
        ok = rr > 1e-12
        out[0, d[ok]] = cx + dx[ok] * r / rr[ok]
        out[1, d[ok]] = cy + dy[ok] * r / rr[ok]
    return out
