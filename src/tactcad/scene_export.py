"""Scene exports: ``scenes/<scene>.step`` (flat, labelled, coloured,
instanced STEP AP214 in mm, Z up (see :mod:`tactcad.export.z_up`), via
:func:`tactcad.export.step.write_step`) and
``scenes/<scene>.glb`` (binary glTF 2.0 for a quick look), plus the scene
checks.

The GLB is written here byte by byte (no time stamps, fixed key order, fixed
float formatting), so the same design writes the same bytes. Its meshes are
in mm (the meshes of the interference check, made once per part) under a
root node that scales to metres (glTF's unit) and has the scene's y axis up
(glTF's up axis); every instance is a node named after it,
carrying its part name, group and attributes (such as a sample's stiffness)
in ``extras``.
"""

from __future__ import annotations

import json
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable



def scene_step_name(name: str) -> str:
    return f"scenes/{name}.step"


def scene_glb_name(name: str) -> str:
    return f"scenes/{name}.glb"


def write_scene_files(plan, staging: Path, log: Callable[[str], None],
                      names: Iterable[str] | None = None, cache=None) -> list[dict]:
    """Writer of the main job (see :data:`tactcad.exporter.WRITERS`): every
    scene of the plan's scenes file (or ``names``) as STEP and GLB in
    ``staging/scenes/``.

    Returns:
        File records: the STEP records carry ``solids``, ``volume_mm3``,
        ``bbox_mm`` and ``labels`` for review, plus the scene's parts with
        their kind, process, quantity, level and attributes.

    Raises:
        SceneError: unknown scene or a rig that cannot be assembled.
    """
    from .export.step import StepInstance, StepPart, write_step
    from .scenes import SceneCache, build_scene, review_record, scene_names
    from .export.freecad_review import scene_review_assembly, write_review_files
    from .export.z_up import z_up_location

    z_up = z_up_location()  # STEP is Z up, the GLB keeps glTF's y up
    cache = cache or SceneCache(plan)
    records: list[dict] = []
    review_assemblies = []  # FreeCAD review files (tactcad.export.freecad_review), written at the end
    for name in (list(names) if names is not None else scene_names(plan)):
        scene, solids = build_scene(plan, name, cache)
        parts = [StepPart(n, solids[n], spec.color) for n, spec in scene.parts().items()]
        inst = [StepInstance(i.name, i.part, z_up * i.location) for i in scene.instances]
        rel = scene_step_name(name)
        write_step(staging / rel, parts, inst, name)
        review = review_record(scene)
        records.append({"path": rel, "part": name, "kind": "step-scene", **review})
        rel_glb = scene_glb_name(name)
        tri = write_glb(staging / rel_glb, scene,
                        {n: cache.mesh(scene.specs[n], lvl) for n, lvl in
                         {i.part: i.level for i in scene.instances}.items()})
        records.append({"path": rel_glb, "part": name, "kind": "glb-scene",
                        "nodes": len(scene.instances), "meshes": len(parts), "triangles": tri})
        log(f"  wrote {rel} and {rel_glb} ({len(scene.instances)} parts)")
        review_assemblies.append(scene_review_assembly(scene, solids, rel))
    # --- FreeCAD review files (tactcad.export.freecad_review) ---
    records += write_review_files(staging, review_assemblies, log)
    return records


@dataclass
class SceneExportResult:
    out_dir: Path
    files: list[dict]
    seconds: float

    def summary_lines(self) -> list[str]:
        lines = [f"{f['path']:<34} {f['bytes']:>9,d} B  {f['part']}" for f in self.files]
        lines.append(f"{len(self.files)} files in {self.out_dir} ({self.seconds:.1f} s); "
                     "manifest.json not rewritten (full export only)")
        return lines


def export_scenes(plan, out_dir: str | Path, names: Iterable[str], cache=None,
                  log: Callable[[str], None] = lambda s: None) -> SceneExportResult:
    """Write only the named scenes into ``out_dir/scenes`` (staged, then moved
    into place; the manifest is not touched).

    Raises:
        SceneError: an unknown scene name (nothing is written); the message
            lists the scenes.
    """
    import os
    import shutil
    import tempfile
    import time

    from .scenes import get_scene_spec

    names = list(names)
    for n in names:
        get_scene_spec(plan, n)  # unknown names fail before anything is written
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=".staging-", dir=out_dir))
    try:
        records = write_scene_files(plan, staging, log, names, cache)
        for r in records:
            target = out_dir / r["path"]
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(staging / r["path"], target)
            r["bytes"] = target.stat().st_size
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return SceneExportResult(out_dir, records, time.perf_counter() - t0)


# ---------------------------------------------------------------------------
# GLB (binary glTF 2.0)
# ---------------------------------------------------------------------------
def _matrix(location) -> list[float]:
    """Column-major 4 x 4 matrix of a build123d ``Location`` (glTF node matrix)."""
    t = location.wrapped.Transformation()
    m = [[t.Value(i, j) for j in range(1, 5)] for i in range(1, 4)] + [[0.0, 0.0, 0.0, 1.0]]
    return [_num(m[r][c]) for c in range(4) for r in range(4)]


def _num(v: float) -> float:
    v = round(float(v), 9)
    return 0.0 if v == 0 else v


def _mesh_arrays(mesh) -> tuple[bytes, bytes, list[float], list[float], int, int]:
    import numpy as np

    v = np.ascontiguousarray(mesh[0], dtype=np.float32)
    t = np.ascontiguousarray(mesh[1], dtype=np.uint32)
    return (v.tobytes(), t.tobytes(), [float(x) for x in v.min(axis=0)],
            [float(x) for x in v.max(axis=0)], len(v), len(t))


def _pad(data: bytes, fill: bytes = b"\x00") -> bytes:
    return data + fill * (-len(data) % 4)


def write_glb(path: str | Path, scene, part_meshes: dict) -> int:
    """Write ``scene`` as a binary glTF file (atomically); returns the triangle count.

    Args:
        part_meshes: part name -> (vertices (n, 3) mm, triangles (m, 3)) in the part's frame.

    Raises:
        OSError: the file cannot be written.
    """
    from .export.atomic import write_bytes_atomic

    bin_chunks: list[bytes] = []
    views, accessors, meshes, materials = [], [], [], []
    mesh_index: dict[str, int] = {}
    offset = 0
    triangles = 0

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        padded = _pad(data)
        bin_chunks.append(padded)
        offset += len(padded)
        return len(views) - 1

    for name, spec in scene.parts().items():
        vb, ib, vmin, vmax, nv, nt = _mesh_arrays(part_meshes[name])
        triangles += nt
        pos = add_view(vb, 34962)
        idx = add_view(ib, 34963)
        accessors.append({"bufferView": pos, "componentType": 5126, "count": nv, "type": "VEC3",
                          "min": [_num(x) for x in vmin], "max": [_num(x) for x in vmax]})
        accessors.append({"bufferView": idx, "componentType": 5125, "count": nt * 3,
                          "type": "SCALAR"})
        materials.append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [_num(c) for c in spec.color] + [1.0],
            "metallicFactor": 0.0 if spec.kind == "fabricated" and "rubber" in spec.material else 0.3,
            "roughnessFactor": 0.6}})
        meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1,
            "material": len(materials) - 1, "mode": 4}]})
        mesh_index[name] = len(meshes) - 1
    nodes = [{"name": scene.name, "scale": [0.001, 0.001, 0.001], "children": [],
              "extras": {"units": "mm, scaled to m by this node", "rig": scene.spec.rig}}]
    for i in scene.instances:
        spec = scene.specs[i.part]
        extras = {"part": i.part, "group": i.group, "kind": spec.kind, "level": i.level,
                  **{k: v for k, v in dict(getattr(spec, "attributes", {})).items()}}
        nodes.append({"name": i.name, "mesh": mesh_index[i.part], "matrix": _matrix(i.location),
                      "extras": extras})
        nodes[0]["children"].append(len(nodes) - 1)
    doc = {
        "asset": {"version": "2.0", "generator": "tactcad"},
        "scene": 0,
        "scenes": [{"name": scene.name, "nodes": [0]}],
        "nodes": nodes, "meshes": meshes, "materials": materials, "accessors": accessors,
        "bufferViews": views, "buffers": [{"byteLength": offset}],
    }
    js = _pad(json.dumps(doc, separators=(",", ":"), sort_keys=True).encode(), b" ")
    binary = b"".join(bin_chunks)
    body = (struct.pack("<II", len(js), 0x4E4F534A) + js
            + struct.pack("<II", len(binary), 0x004E4942) + binary)
    data = struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body
    write_bytes_atomic(path, data)
    return triangles


def read_glb(path: str | Path) -> dict:
    """The JSON chunk of a GLB file, with ``_bin_length`` added (for checks).

    Raises:
        ValueError: not a glTF 2.0 binary file.
    """
    data = Path(path).read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2 or length != len(data):
        raise ValueError(f"{path}: not a glTF 2.0 binary")
    jlen, jtype = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + jlen])
    blen, _ = struct.unpack_from("<II", data, 20 + jlen)
    doc["_bin_length"] = blen
    return doc


# ---------------------------------------------------------------------------
# Scene checks
# ---------------------------------------------------------------------------
def run_scene_checks(plan, out_dir: str | Path, names: Iterable[str] | None = None,
                     cache=None, confirm: bool = True) -> list:
    """Every check of the scenes on the files in ``out_dir``: rig part solids,
    interference (manifold3d fast path, OpenCascade confirmation), geometry
    sanity, STEP re-import and GLB read-back against the review records."""
    from .checks.mesh_interference import check_mesh_interference
    from .checks.result import CheckResult
    from .checks.scene_sanity import check_scene_sanity
    from .checks.solids import check_solid
    from .checks.step import check_step
    from .rig_catalogue import RigPartSpec
    from .scenes import SceneCache, build_scene, placed_shapes, review_record, scene_names

    out_dir = Path(out_dir)
    cache = cache or SceneCache(plan)
    results = []
    checked_parts: set[str] = set()
    for name in (list(names) if names is not None else scene_names(plan)):
        scene, solids = build_scene(plan, name, cache)
        for pname, spec in scene.parts().items():
            if isinstance(spec, RigPartSpec) and pname not in checked_parts:
                checked_parts.add(pname)
                results += check_solid(spec, solids[pname])
        placed = placed_shapes(scene, solids)
        rep = check_mesh_interference(
            placed, scene.contacts, {i.name: i.part for i in scene.instances}, solids,
            {i.name: i.location for i in scene.instances}, confirm=confirm,
            part_meshes={i.part: cache.mesh(scene.specs[i.part], i.level) for i in scene.instances})
        results += [CheckResult(r.check, f"{name}: {r.subject}", r.passed, r.detail)
                    for r in rep.results]
        results += check_scene_sanity(scene, {p.name: p.shape for p in placed})
        rec = review_record(scene)
        step = out_dir / scene_step_name(name)
        results += check_step(step, scene_step_name(name), rec["solids"], rec["volume_mm3"],
                              tuple(rec["bbox_mm"]), set(rec["labels"]))
        glb = out_dir / scene_glb_name(name)
        try:
            doc = read_glb(glb)
            nodes = [n for n in doc["nodes"][1:]]
            ok = (len(nodes) == len(scene.instances)
                  and sorted(n["name"] for n in nodes) == sorted(i.name for i in scene.instances)
                  and sorted(m["name"] for m in doc["meshes"]) == sorted(rec["labels"]))
            detail = f"{len(nodes)} nodes, {len(doc['meshes'])} meshes"
        except (OSError, ValueError, KeyError) as exc:
            ok, detail = False, f"{type(exc).__name__}: {exc}"
        results.append(CheckResult("glb_readback", scene_glb_name(name), ok, detail))
    return results
