"""Measurements of solids for the checks: free boundaries, exact bounding
boxes, boolean common volumes, distances and planar faces (mm, mm^3)."""

from __future__ import annotations

from typing import Sequence

import build123d as bd
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds
from OCP.TopAbs import TopAbs_EDGE
from OCP.TopExp import TopExp_Explorer


def free_edge_count(shape: bd.Shape) -> int:
    """Edges on free boundaries (belonging to one face only); 0 for a closed solid."""
    bounds = ShapeAnalysis_FreeBounds(shape.wrapped, 1e-7, False, False)
    n = 0
    for compound in (bounds.GetClosedWires(), bounds.GetOpenWires()):
        ex = TopExp_Explorer(compound, TopAbs_EDGE)
        while ex.More():
            n += 1
            ex.Next()
    return n


def bbox_tuple(shape: bd.Shape) -> tuple[float, ...]:
    """(xmin, ymin, zmin, xmax, ymax, zmax) of the exact (optimal) bounding box, mm."""
    bb = shape.bounding_box(optimal=True)
    return (bb.min.X, bb.min.Y, bb.min.Z, bb.max.X, bb.max.Y, bb.max.Z)


def common_volume(a: bd.Shape, b: bd.Shape) -> float:
    """Volume (mm^3) of the boolean common of two solids.

    Raises:
        RuntimeError: the boolean did not complete.
    """
    op = BRepAlgoAPI_Common(a.wrapped, b.wrapped)
    if not op.IsDone():
        raise RuntimeError("boolean common failed")
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(op.Shape(), props)
    return abs(props.Mass())


def distance(a: bd.Shape, b: bd.Shape) -> float:
    """Smallest distance (mm) between two shapes.

    Raises:
        RuntimeError: the computation did not complete.
    """
    d = BRepExtrema_DistShapeShape(a.wrapped, b.wrapped)
    if not d.IsDone():
        raise RuntimeError("distance computation failed")
    return d.Value()


def faces_distance(faces_a: Sequence[bd.Face], faces_b: Sequence[bd.Face]) -> float:
    """Smallest distance (mm) between two sets of faces.

    Raises:
        RuntimeError: the computation did not complete.
    """
    return distance(bd.Compound(list(faces_a)), bd.Compound(list(faces_b)))


def extreme_planar_face(shape: bd.Shape, direction: Sequence[float]):
    """The planar face of ``shape`` with outward normal along ``direction``
    lying farthest along it: (centre, (min, max) corners of its box, area),
    the points as vectors (``X``, ``Y``, ``Z``, ``dot``), mm and mm^2.

    Raises:
        ValueError: no planar face faces that way.
    """
    d = bd.Vector(*direction)
    best = None
    for f in shape.faces():
        if f.geom_type != bd.GeomType.PLANE:
            continue
        if f.normal_at(f.center()).dot(d) < 1 - 1e-9:
            continue
        h = f.center().dot(d)
        if best is None or h > best[0] + 1e-9:
            best = (h, f)
    if best is None:
        raise ValueError("no planar face along the direction")
    f = best[1]
    bb = f.bounding_box()
    return f.center(), (bb.min, bb.max), f.area
