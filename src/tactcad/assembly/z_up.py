"""Z up for the exchange and review files.

Scenes and the array are modelled y up (the array frame: y up, z through the
stack), which is also glTF's convention, so the GLB files keep it. STEP and
FreeCAD files are Z up, as CAD programs show them: the scene root is turned
+90 degrees about x, (x, y, z) -> (x, -z, y), so scene y becomes Z. No CAD
kernel here except in :func:`z_up_location`, which asks it for the turn.
"""

from __future__ import annotations

from typing import Sequence

# Row-major 4 x 4 matrix of the root turn (+90 degrees about x).
Z_UP_MATRIX = ((1.0, 0.0, 0.0, 0.0),
               (0.0, 0.0, -1.0, 0.0),
               (0.0, 1.0, 0.0, 0.0),
               (0.0, 0.0, 0.0, 1.0))


def z_up_point(p: Sequence[float]) -> tuple[float, float, float]:
    """A scene-frame point (mm) in the Z-up frame: (x, y, z) -> (x, -z, y)."""
    x, y, z = p
    return (x, -z, y)


def z_up_bbox(bbox: Sequence[float]) -> list[float]:
    """A scene-frame box [xmin, ymin, zmin, xmax, ymax, zmax] (mm) in the Z-up frame."""
    x0, y0, z0, x1, y1, z1 = bbox
    return [x0, -z1, y0, x1, -z0, y1]


def z_up_location():
    """The root turn as a CAD location (put it left of a scene-frame location)."""
    from tactcad.kernel.locations import turned_about_x

    return turned_about_x(90.0)
