"""Modelling verbs: primitive solids by their extents (mm), prisms of planar
profiles and faces, and booleans that must leave one solid.

The part builders (:mod:`tactcad.partlib`, :mod:`tactcad.partlib.array`) are written
in these words only. A solid carries its placement in its geometry, never as
a top-level location: a located shape is written to STEP as an extra,
unnamed product.

This module loads the kernel when a verb is first called, not when it is
imported: the part modules import it at their top and stay free to import
(the design validator reads their schema sections).
"""

from __future__ import annotations

from functools import reduce
from types import ModuleType
from typing import TYPE_CHECKING, Any, Iterable, Protocol, Sequence

if TYPE_CHECKING:
    import build123d as bd
    from build123d import Compound as Compound, Face as Face, Shape as Shape, Solid as Solid

Point3 = tuple[float, float, float]


class ProfileLike(Protocol):
    """A closed 2D profile as :mod:`tactcad.geometry.profile` writes it (mm):
    ``outer``, segments with ``start`` and ``end`` (an arc also has
    ``midpoint``), and ``holes``, circles with ``centre`` and ``radius``."""

    @property
    def outer(self) -> Sequence[Any]: ...

    @property
    def holes(self) -> Sequence[Any]: ...

#: The kernel's types, for annotations above the wall (loaded on first use).
KERNEL_TYPES = ("Solid", "Shape", "Face", "Compound")


def __getattr__(name: str) -> Any:
    if name in KERNEL_TYPES:
        return getattr(_bd(), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _bd() -> ModuleType:
    """build123d, imported on the first call (2-4 s once per process)."""
    import build123d

    return build123d


def _centred_on_base() -> tuple:
    bd = _bd()
    return (bd.Align.CENTER, bd.Align.CENTER, bd.Align.MIN)


def box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> bd.Solid:
    """Axis-aligned box between two corners (mm), the corner built into the geometry."""
    bd = _bd()
    return bd.Solid.make_box(x1 - x0, y1 - y0, z1 - z0, bd.Plane(origin=(x0, y0, z0)))


def box_at_origin(x: float, y: float, z: float) -> bd.Solid:
    """Box from the origin to (x, y, z) (mm)."""
    bd = _bd()
    return bd.Solid.make_box(x, y, z)


def centred_box(length: float, width: float, height: float,
                at: tuple[float, float] = (0.0, 0.0)) -> bd.Shape:
    """Box ``length x width`` centred on (x, y) = ``at``, z = 0 ... ``height`` (mm)."""
    bd = _bd()
    shape = bd.Box(length, width, height, align=_centred_on_base())
    return shape if at == (0.0, 0.0) else bd.Pos(at[0], at[1], 0) * shape


def cylinder(radius: float, start: Point3, axis: Point3, length: float) -> bd.Solid:
    """Cylinder of ``radius`` from ``start`` along the unit vector ``axis`` for ``length`` (mm)."""
    bd = _bd()
    return bd.Solid.make_cylinder(radius, length, bd.Plane(origin=start, z_dir=axis))


def cylinder_z(radius: float, height: float, z0: float = 0.0) -> bd.Solid:
    """Cylinder about the z axis, z = ``z0`` ... ``z0 + height`` (mm)."""
    bd = _bd()
    if z0 == 0.0:
        return bd.Solid.make_cylinder(radius, height)
    return bd.Solid.make_cylinder(radius, height, bd.Plane.XY.offset(z0))


def centred_cylinder(radius: float, height: float, at: tuple[float, float]) -> bd.Shape:
    """Cylinder about the vertical through (x, y) = ``at``, z = 0 ... ``height`` (mm)."""
    bd = _bd()
    return bd.Pos(at[0], at[1], 0) * bd.Cylinder(radius, height, align=_centred_on_base())


def ring(inner_radius: float, outer_radius: float, height: float) -> bd.Solid:
    """Annulus about the z axis, z = 0 ... height (mm)."""
    return single(cylinder(outer_radius, (0, 0, 0), (0, 0, 1), height)
                  .cut(cylinder(inner_radius, (0, 0, 0), (0, 0, 1), height)))


def polygon_prism(circumradius: float, sides: int, height: float) -> bd.Shape:
    """Regular polygon of ``sides`` corners on a circle of ``circumradius``
    (a corner on +x), extruded z = 0 ... ``height`` (mm)."""
    bd = _bd()
    return bd.extrude(bd.RegularPolygon(circumradius, sides), height)


def disc_prism(radius: float, height: float, z0: float = 0.0) -> bd.Shape:
    """Circle of ``radius`` about the z axis extruded z = ``z0`` ... ``z0 + height`` (mm)."""
    bd = _bd()
    return bd.Pos(0, 0, z0) * bd.extrude(bd.Circle(radius), height)


def polygon_face(points: Sequence[Point3],
                 holes: Sequence[Sequence[Point3]] = ()) -> bd.Face:
    """Planar face bounded by the closed polygon through ``points`` (mm), less the
    polygons ``holes`` (each wholly inside it, none touching another or the boundary:
    a face with holes, no boolean)."""
    bd = _bd()
    outer = bd.Wire.make_polygon(points, close=True)
    if not holes:
        return bd.Face(outer)
    return bd.Face(outer, [bd.Wire.make_polygon(h, close=True) for h in holes])


def rounded_rect_face(length: float, width: float, radius: float, z: float = 0.0) -> bd.Face:
    """Rectangle ``length x width`` centred on the z axis at height ``z``,
    corners rounded to ``radius`` (mm)."""
    bd = _bd()
    rect = bd.Face(bd.Wire.make_rect(length, width, bd.Plane.XY.offset(z)))
    return rect.fillet_2d(radius, rect.vertices())


def profile_face(profile: ProfileLike) -> bd.Face:
    """The planar face (z = 0) bounded by a 2D profile's outer contour (lines
    and three-point arcs, :mod:`tactcad.geometry.profile`) minus its round holes."""
    bd = _bd()
    outer = bd.Wire([_edge(s) for s in profile.outer])
    holes = [bd.Wire([bd.Edge.make_circle(c.radius, bd.Plane.XY.shift_origin(
        (c.centre[0], c.centre[1], 0)))]) for c in profile.holes]
    return bd.Face(outer, holes)


def _edge(segment) -> bd.Edge:
    """A profile segment as an edge: an ``Arc`` has a ``midpoint``, a ``Line`` has not."""
    bd = _bd()
    if hasattr(segment, "midpoint"):
        return bd.Edge.make_three_point_arc(bd.Vector(*segment.start), bd.Vector(*segment.midpoint),
                                            bd.Vector(*segment.end))
    return bd.Edge.make_line(bd.Vector(*segment.start), bd.Vector(*segment.end))


def extrude(face: bd.Face, height: float) -> bd.Solid:
    """Prism of a planar face along +z by ``height`` (mm)."""
    bd = _bd()
    return bd.Solid.extrude(face, bd.Vector(0, 0, height))


def extrude_profile(profile: ProfileLike, thickness_mm: float) -> bd.Solid:
    """Prism of a 2D profile: its face at z = 0 extruded along +z (mm)."""
    return extrude(profile_face(profile), thickness_mm)


def moved(shape: bd.Shape, offset: Point3) -> bd.Shape:
    """``shape`` at a location shifted by ``offset`` (mm); for a tool or a
    face, not for a part (see the module doc)."""
    bd = _bd()
    return shape.moved(bd.Location(offset))


def translated(shape: bd.Shape, offset: Point3) -> bd.Shape:
    """``shape`` with its geometry shifted by ``offset`` (mm), no location."""
    bd = _bd()
    return shape.translate(bd.Vector(*offset))


def single(shape: bd.Shape) -> bd.Solid:
    """The one solid of a boolean result.

    Raises:
        RuntimeError: the result holds no solid or more than one (a cut that
            split the part or missed it is a modelling error, never silent).
    """
    bd = _bd()
    solids = shape.solids()
    if len(solids) != 1:
        raise RuntimeError(f"boolean left {len(solids)} solids, expected 1")
    return bd.Solid(solids[0].wrapped)


def fuse(*shapes: bd.Shape) -> bd.Solid:
    """The union of ``shapes`` in one boolean, as one solid (see :func:`single`)."""
    first, *rest = shapes
    return single(first.fuse(*rest))


def union(*shapes: bd.Shape) -> bd.Shape:
    """The union of ``shapes`` fused one after the other (build123d's ``+``),
    as the boolean left it: pass it to :func:`single` or :func:`difference`."""
    return reduce(lambda a, b: a + b, shapes)


def cut(base: bd.Shape, *tools: bd.Shape) -> bd.Solid:
    """``base`` less ``tools`` in one boolean, as one solid (see :func:`single`)."""
    return single(base.cut(*tools))


def difference(base: bd.Shape, tools: bd.Shape | Iterable[bd.Shape]) -> bd.Solid:
    """``base`` less ``tools`` (one shape or a list, build123d's ``-``), as
    one solid (see :func:`single`)."""
    bd = _bd()
    return single(base - (tools if isinstance(tools, bd.Shape) else list(tools)))
