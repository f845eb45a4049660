"""Plan placements as CAD locations, and locations as 4 x 4 matrices."""

from __future__ import annotations

import build123d as bd
import numpy as np

from tactcad.design.array import Placement


def location(p: Placement) -> bd.Location:
    """CAD location of a plan placement (turned = 180 degrees about y; mm)."""
    return bd.Location((p.dx_mm, p.dy_mm, p.dz_mm), (0, 180 if p.turned else 0, 0))


def matrix(loc: bd.Location) -> np.ndarray:
    """Row-major 4 x 4 homogeneous matrix (float64, mm) of a build123d ``Location``."""
    t = loc.wrapped.Transformation()
    return np.array([[t.Value(r, c) for c in range(1, 5)] for r in range(1, 4)] + [[0, 0, 0, 1]],
                    dtype=float)
