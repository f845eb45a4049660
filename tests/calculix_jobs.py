"""An element's STEP as an independent CalculiX model, for the tests that check fem3d
against it (tests/mechanics/test_modal_calculix.py, test_gauge_strain_calculix.py).

gmsh reads the STEP ``tactcad export`` wrote, cuts it at the stiffness model's clamp
line (x >= x_clamp), meshes it with quadratic tetrahedra (refined in a box around the
notch) and the mesh is written as CalculiX C3D10 elements with every node of the cut
face in the node set CLAMP. Sources: gmsh reference manual (OpenCASCADE import,
Box size field, ``getElements``); CalculiX CrunchiX user's manual (C3D10 node order,
``*NODE``, ``*ELEMENT``, ``*NSET``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


@dataclass
class ElementMesh:
    """A gmsh mesh of the cut element: node tags and coordinates (mm), C3D10
    connectivity (CalculiX order), the clamp face's nodes, and per face asked for by
    its y the 6-node triangles lying on it."""

    tags: np.ndarray
    xyz: np.ndarray
    conn: np.ndarray
    clamp: list[int]
    faces_at_y: dict[float, np.ndarray] = field(default_factory=dict)


def mesh_element(step: Path, *, x_clamp: float, neck_box, neck_size: float, size_max: float,
                 face_ys: tuple[float, ...] = ()) -> ElementMesh:
    """Mesh ``step`` cut at x >= ``x_clamp`` (gmsh, order 2): ``neck_size`` inside the
    (x0, y0, x1, y1) box, ``size_max`` elsewhere (mm). ``face_ys``: planes y = const whose
    boundary faces' triangles (6 nodes) to return."""
    import gmsh

    gmsh.initialize(readConfigFiles=False, interruptible=False)  # Ctrl-C stays this process's
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        occ = gmsh.model.occ
        vols = occ.importShapes(str(step))
        cut, _ = occ.intersect(vols, [(3, occ.addBox(x_clamp, -1e3, -1e3, 2e3, 2e3, 2e3))])
        occ.synchronize()
        boundary = [t for _, t in gmsh.model.getBoundary(cut, oriented=False)]

        def flat(t, axis, value):
            box = gmsh.model.getBoundingBox(2, t)
            return abs(box[axis] - value) < 1e-6 and abs(box[axis + 3] - value) < 1e-6

        clamp_faces = [t for t in boundary if flat(t, 0, x_clamp)]
        assert clamp_faces, "the cut face at the clamp line was not found"
        (x0, y0, x1, y1) = neck_box
        f = gmsh.model.mesh.field.add("Box")
        for k, v in dict(VIn=neck_size, VOut=size_max, XMin=x0, XMax=x1, YMin=y0, YMax=y1,
                         ZMin=-1e3, ZMax=1e3, Thickness=x1 - x0).items():
            gmsh.model.mesh.field.setNumber(f, k, v)
        gmsh.model.mesh.field.setAsBackgroundMesh(f)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size_max)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 24)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        types, _, nodes = gmsh.model.mesh.getElements(3)
        # gmsh's 10-node tetrahedron lists its last two edge nodes the other way round
        conn = nodes[list(types).index(11)].reshape(-1, 10)[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
        clamp = sorted({int(n) for t in clamp_faces
                        for n in gmsh.model.mesh.getNodes(2, t, includeBoundary=True)[0]})
        faces = {}
        for y in face_ys:
            tris = []
            for t in (t for t in boundary if flat(t, 1, y)):
                etypes, _, enodes = gmsh.model.mesh.getElements(2, t)
                tris.append(enodes[list(etypes).index(9)].reshape(-1, 6))
            assert tris, f"no boundary face at y = {y} mm"
            faces[y] = np.vstack(tris).astype(np.int64)
    finally:
        gmsh.finalize()
    return ElementMesh(tags.astype(np.int64), xyz.reshape(-1, 3), conn.astype(np.int64), clamp,
                       faces)


def write_mesh(fh, mesh: ElementMesh, E: float, nu: float, density: float | None = None) -> None:
    """The model part of a ccx input: nodes, C3D10 elements, CLAMP, an elastic material
    (density in t/mm^3 when given) and the clamp's boundary condition."""
    fh.write("*NODE\n")
    fh.writelines(f"{int(t)}, {x:.12g}, {y:.12g}, {z:.12g}\n"
                  for t, (x, y, z) in zip(mesh.tags, mesh.xyz))
    fh.write("*ELEMENT, TYPE=C3D10, ELSET=SOLID\n")
    fh.writelines(f"{i + 1}, " + ", ".join(str(int(n)) for n in row) + "\n"
                  for i, row in enumerate(mesh.conn))
    fh.write("*NSET, NSET=CLAMP\n")
    fh.writelines(f"{n},\n" for n in mesh.clamp)
    fh.write(f"*MATERIAL, NAME=SHEET\n*ELASTIC\n{E}, {nu}\n")
    if density is not None:
        fh.write(f"*DENSITY\n{density}\n")
    fh.write("*SOLID SECTION, ELSET=SOLID, MATERIAL=SHEET\n*BOUNDARY\nCLAMP, 1, 3\n")
