"""Triangle meshes of part solids (OpenCascade ``BRepMesh`` through build123d),
shared by the interference checks, the GLB scenes and the rendered images."""

from __future__ import annotations

import numpy as np

MESH_TOLERANCE_MM = 0.01  # chordal deflection of the tessellation
MESH_ANGULAR_TOLERANCE = 0.2  # rad


def tessellate(solid, tolerance_mm: float = MESH_TOLERANCE_MM,
               angular_tolerance: float = MESH_ANGULAR_TOLERANCE) -> tuple[np.ndarray, np.ndarray]:
    """Triangle mesh of a solid: vertices (n, 3) float64 in mm, triangles
    (m, 3) int64, outward winding; chordal tolerance in mm, angular in rad."""
    from tactcad.kernel.inspect import triangulate

    return triangulate(solid, tolerance_mm, angular_tolerance)
