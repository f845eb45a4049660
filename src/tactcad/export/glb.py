"""``scenes/<scene>.glb``: binary glTF 2.0 of a solved scene, for a quick look.

Written byte by byte (no time stamps, fixed key order, fixed float
formatting), so the same scene writes the same bytes. Meshes are in mm (the
run's part meshes, :meth:`tactcad.solids.cache.PartCache.mesh`) under a root
node that scales to metres (glTF's unit) and keeps the scene's y axis up
(glTF's up axis); every instance is a node named after it, carrying its part
name, group and attributes (such as a sample's stiffness) in ``extras``.
"""

from __future__ import annotations

import json
import struct
from pathlib import Path

import numpy as np

from tactcad.kernel.locations import matrix
from tactcad.atomic import write_bytes_atomic


def _matrix(location) -> list[float]:
    """Column-major 4 x 4 matrix of a build123d ``Location`` (glTF node matrix)."""
    m = matrix(location)
    return [_num(m[r][c]) for c in range(4) for r in range(4)]


def _num(v: float) -> float:
    v = round(float(v), 9)
    return 0.0 if v == 0 else v


def _mesh_arrays(mesh) -> tuple[bytes, bytes, list[float], list[float], int, int]:
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


