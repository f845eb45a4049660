"""BREP files (OpenCascade's native format), as FreeCAD 0.20 reads them."""

from __future__ import annotations

from pathlib import Path

from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepTools import BRepTools
from OCP.TopTools import TopTools_FormatVersion


def write_brep(shape, path: Path) -> None:
    """Write ``shape`` to ``path`` as BREP version 1 without triangulation.

    Raises:
        RuntimeError: OpenCascade could not write the file.
    """
    # A fresh copy: the shape's flags (free, modified ...) change as other
    # writers use it, and the file must not depend on what ran before.
    fresh = BRepBuilderAPI_Copy(shape.wrapped, True, False).Shape()
    # Version 1 without triangulation: what FreeCAD's older OpenCascade reads.
    if not BRepTools.Write_s(fresh, str(path), False, False,
                             TopTools_FormatVersion.TopTools_FormatVersion_VERSION_1):
        raise RuntimeError(f"OpenCascade could not write {path}")
