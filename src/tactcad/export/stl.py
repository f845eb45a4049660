"""STL files of the parts (``stl/<part>.stl``, binary, mm), written only when
asked (``tactcad export --only stl``): for a slicer, to print a fixture, a
sample mould or a stand-in part, or for a viewer that reads no STEP.

Each file is the run's triangle mesh of the part in its own frame (the mesh
the scenes and pictures use: chordal tolerance
:data:`tactcad.solids.tessellation.MESH_TOLERANCE_MM`), outward winding, as trimesh
writes binary STL: the same part writes the same bytes.
"""

from __future__ import annotations

from tactcad.export.job import Job, Run
from tactcad.solids.tessellation import MESH_TOLERANCE_MM
from tactcad.store import content_key

STL_FOLDER = "stl"


def stl_name(part: str) -> str:
    """``stl/<part>.stl``, relative to the export folder."""
    return f"{STL_FOLDER}/{part}.stl"


def stl_jobs(run: Run, before: list[Job]) -> list[Job]:
    """One job per distinct part of the design (the array's and the rigs'),
    keyed by its spec and the mesh tolerance."""
    specs, _ = run.inventory
    return [Job(f"stl:{name}", content_key("stl-part", spec, MESH_TOLERANCE_MM), _part_stl(spec),
                (spec,)) for name, spec in specs.items()]


def stl_part_files(plan, assemblies):
    """``stl/<part>.stl``, for the BOM's files column when the STL files are written."""
    return lambda part, found: [stl_name(part)]


def _part_stl(spec):
    def make(run: Run) -> list[dict]:
        import trimesh

        from tactcad.atomic import write_bytes_atomic

        vertices, triangles = run.parts.mesh(spec)
        data = trimesh.Trimesh(vertices, triangles, process=False).export(file_type="stl")
        rel = stl_name(spec.name)
        write_bytes_atomic(run.staging / rel, data)
        run.log(f"  wrote {rel} ({len(triangles)} triangles)")
        return [{"path": rel, "part": spec.name, "kind": "stl-part", "triangles": len(triangles)}]
    return make
