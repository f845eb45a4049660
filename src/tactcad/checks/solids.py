"""Per-part solid checks: validity is more than ``is_valid``.

valid, exactly the expected number of solids, closed (no free boundaries),
volume equal to an independent estimate, bounding box as designed, and a
watertight, consistently wound triangle mesh.
"""

from __future__ import annotations

import trimesh

from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.kernel.inspect import bbox_tuple, free_edge_count, is_valid, solid_count, volume
from tactcad.kernel.shapes import Shape
from tactcad.solids.tessellation import tessellate
from tactcad.checks.check_result import CheckResult

VOLUME_RTOL = 1e-6
BBOX_TOL_MM = 1e-6
MESH_TOLERANCE_MM = 0.005
MESH_VOLUME_RTOL = 5e-3  # chordal error of the tessellation on the arcs


def to_trimesh(shape: Shape, tolerance_mm: float = MESH_TOLERANCE_MM) -> trimesh.Trimesh:
    """Triangle mesh of a shape (mm), vertices merged so edges can be paired."""
    verts, tris = tessellate(shape, tolerance_mm)
    mesh = trimesh.Trimesh(verts, tris, process=True)
    mesh.merge_vertices()
    return mesh


def check_solid(spec: PartSpec, solid: Shape, expected_solids: int = 1) -> list[CheckResult]:
    """All solid checks of one part against its catalogue entry."""
    name = spec.name
    out = [CheckResult("is_valid", name, is_valid(solid))]
    n = solid_count(solid)
    out.append(CheckResult("solid_count", name, n == expected_solids, f"{n} (expected {expected_solids})"))
    free = free_edge_count(solid)
    out.append(CheckResult("no_free_boundaries", name, free == 0, f"{free} free edges"))
    vol = volume(solid)
    rel = abs(vol - spec.expected_volume_mm3) / spec.expected_volume_mm3
    out.append(CheckResult("volume", name, vol > 0 and rel <= VOLUME_RTOL,
                           f"{vol:.6f} mm3 vs {spec.expected_volume_mm3:.6f} (rel {rel:.1e})"))
    bb = bbox_tuple(solid)
    dev = max(abs(a - b) for a, b in zip(bb, spec.expected_bbox_mm))
    out.append(CheckResult("bounding_box", name, dev <= BBOX_TOL_MM, f"max deviation {dev:.1e} mm"))
    mesh = to_trimesh(solid)
    mrel = abs(mesh.volume - vol) / vol if vol > 0 else float("inf")  # an open shell has none
    ok = mesh.is_watertight and mesh.is_winding_consistent and mrel <= MESH_VOLUME_RTOL
    out.append(CheckResult("watertight_mesh", name, ok,
                           f"watertight={mesh.is_watertight} winding={mesh.is_winding_consistent} "
                           f"volume rel {mrel:.1e}"))
    return out
