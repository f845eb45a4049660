"""Placements: locations built from tactcad's own numbers (offsets in mm,
angles in degrees, frames as origin and axes), composed, and read back as
points and 4 x 4 matrices."""

from __future__ import annotations

from typing import Sequence

import build123d as bd
import numpy as np

#: The kernel's location type, for annotations above the wall.
Location = bd.Location

Point3 = tuple[float, float, float]


def offset(dx: float, dy: float, dz: float, turned: bool = False) -> bd.Location:
    """Location shifted by (dx, dy, dz) mm, turned 180 degrees about y when ``turned``."""
    return bd.Location((dx, dy, dz), (0, 180 if turned else 0, 0))


def at(point: Sequence[float]) -> bd.Location:
    """Location at ``point`` (mm), axes unturned."""
    return bd.Location(tuple(point))


def frame(origin: Point3, x_dir: Point3, z_dir: Point3) -> bd.Location:
    """Location of a right-handed frame given by its origin (mm) and unit x and z axes."""
    return bd.Location(bd.Plane(origin=origin, x_dir=x_dir, z_dir=z_dir))


def turned_about_x(degrees: float) -> bd.Location:
    """Location turned ``degrees`` about the x axis through the origin."""
    return bd.Location((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), degrees)


def point(loc: bd.Location, local: Sequence[float] = (0.0, 0.0, 0.0)) -> bd.Vector:
    """Where the point ``local`` (mm, in the frame of ``loc``) lies: a vector
    with ``X``, ``Y``, ``Z``, ``dot`` and arithmetic."""
    return (loc * bd.Location(tuple(local))).position


def matrix(loc: bd.Location) -> np.ndarray:
    """Row-major 4 x 4 homogeneous matrix (float64, mm) of a location."""
    t = loc.wrapped.Transformation()
    return np.array([[t.Value(r, c) for c in range(1, 5)] for r in range(1, 4)] + [[0, 0, 0, 1]],
                    dtype=float)


def placed(shape: bd.Shape, loc: bd.Location) -> bd.Shape:
    """A copy of ``shape`` moved by ``loc`` (its label and colour kept)."""
    return shape.moved(loc)


def relative(a: bd.Location, b: bd.Location) -> bd.Location:
    """The location of ``b`` seen from ``a`` (``a`` inverted, then ``b``)."""
    return a.inverse() * b
