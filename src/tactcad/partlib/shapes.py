"""Primitive solids by their extents (mm) and a boolean that must leave one
solid, for the builders of the part modules and of :mod:`tactcad.parts`
(which takes them from here). build123d is imported inside each function, so
this layer stays kernel-free until a part is built."""

from __future__ import annotations


def box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float):
    """Axis-aligned box (build123d ``Solid``) between two corners (mm). The
    corner is built into the geometry (no top-level location): a located
    shape would be written to STEP as an extra, unnamed product."""
    import build123d as bd

    return bd.Solid.make_box(x1 - x0, y1 - y0, z1 - z0, bd.Plane(origin=(x0, y0, z0)))


def cylinder(radius: float, start: tuple[float, float, float],
             axis: tuple[float, float, float], length: float):
    """Cylinder (``Solid``) of ``radius`` from ``start`` along the unit vector
    ``axis`` for ``length`` (mm)."""
    import build123d as bd

    return bd.Solid.make_cylinder(radius, length, bd.Plane(origin=start, z_dir=axis))


def ring(inner_radius: float, outer_radius: float, height: float):
    """Annulus (``Solid``) about the z axis, z = 0 ... height (mm)."""
    return single(cylinder(outer_radius, (0, 0, 0), (0, 0, 1), height)
                  .cut(cylinder(inner_radius, (0, 0, 0), (0, 0, 1), height)))


def single(shape):
    """The one solid (``Solid``) of a boolean result (a build123d ``Shape``).

    Raises:
        RuntimeError: the result holds no solid or more than one (a cut that
            split the part or missed it is a modelling error, never silent).
    """
    import build123d as bd

    solids = shape.solids()
    if len(solids) != 1:
        raise RuntimeError(f"boolean left {len(solids)} solids, expected 1")
    return bd.Solid(solids[0].wrapped)


def fuse(*shapes):
    """The union of ``shapes`` as one ``Solid`` (see :func:`single`)."""
    first, *rest = shapes
    return single(first.fuse(*rest))


def rounded_rect_face(length: float, width: float, radius: float, z: float = 0.0):
    """Rectangle ``length x width`` (a build123d ``Face``) centred on the z
    axis at height ``z``, corners rounded to ``radius`` (mm)."""
    import build123d as bd

    rect = bd.Face(bd.Wire.make_rect(length, width, bd.Plane.XY.offset(z)))
    return rect.fillet_2d(radius, rect.vertices())
