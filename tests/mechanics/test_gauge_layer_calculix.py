"""The bonded gauge's stiffening of K, checked by a finite-element model of another kind.

tactcad's plane and 3D models mesh the glue line and carrier as a second region on the
top face (:class:`tactcad.mechanics.bonded_layer.BondedLayer`, scikit-fem P2 with the
layer's modulus spread over the sheet). Here CalculiX solves the element's own profile in
plane stress (CPS6, quadratic triangles, gmsh) with the layer as a second region bonded on
the top face over the notch (its modulus, and the carrier's width as its section
thickness), clamped on the stiffness model's clamp line and loaded by a unit force spread
over the contact face; the same mesh with the layer's modulus a millionth of it gives the
bare element.

CalculiX expands a plane element into a layer of 3D wedges as thick as its section: a
3 mm section over a 0.25 mm web is then a stiff 3D slab, not plane stress (the bare
element reads 27.9 N/mm where plane stress gives 25.0 and 3D 27.4). Every section is
therefore given :data:`SECTION_SCALE` of its thickness, which keeps the plane-stress
condition, and the compliance scaled back.

Sources: CalculiX CrunchiX user's manual (CPS6, its expansion into 3D elements, ``*SOLID
SECTION`` thickness, ``*CLOAD``, ``*NODE PRINT``); gmsh reference manual (OpenCASCADE
``fragment``, Box size field).
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from tactcad.design.array_plan import EXAMPLES, load_design
from tactcad.design.readout_section import CARRIER_SIDE_MM, carrier_width_mm
from tactcad.geometry.profile import Arc
from tactcad.mechanics.fem.fem_mesh import fem_region
from tactcad.mechanics.bonded_layer import chain_layer
from tactcad.mechanics.fem.fem2d import solve_fem2d
from tactcad.mechanics.readout_chain import readout_chain

#: Each section's thickness in CalculiX, relative (a thin section stays plane stress).
SECTION_SCALE = 1e-3

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX not installed")]


def _mesh(g, layer_box, fine_mm: float, coarse_mm: float):
    """(node coordinates (n, 2), CPS6 connectivity of the element's and the layer's
    triangles, the contact face's quadratic edges) of the profile cut at the clamp line
    and the layer rectangle, fragmented so they share the nodes of their joint."""
    import gmsh

    region = fem_region(g)
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        occ = gmsh.model.occ
        points: dict[tuple, int] = {}

        def pt(p):
            key = (round(p[0], 12), round(p[1], 12))
            if key not in points:
                points[key] = occ.addPoint(p[0], p[1], 0.0)
            return points[key]
        curves = []
        for s in region.outline:
            if isinstance(s, Arc):
                m = s.midpoint
                curves.append(occ.addCircleArc(pt(s.start), occ.addPoint(m[0], m[1], 0.0),
                                               pt(s.end), center=False))
            else:
                curves.append(occ.addLine(pt(s.start), pt(s.end)))
        body = occ.addPlaneSurface([occ.addCurveLoop(curves)])
        x0, y0, x1, y1 = layer_box
        layer = occ.addRectangle(x0, y0, 0.0, x1 - x0, y1 - y0)
        out, _ = occ.fragment([(2, body)], [(2, layer)])
        occ.synchronize()
        surfaces = [tag for dim, tag in out if dim == 2]
        in_layer = [s for s in surfaces
                    if abs(occ.getCenterOfMass(2, s)[1] - (y0 + y1) / 2) < (y1 - y0)]
        field = gmsh.model.mesh.field
        box = field.add("Box")
        field.setNumber(box, "VIn", fine_mm)
        field.setNumber(box, "VOut", coarse_mm)
        for k, v in zip(("XMin", "XMax", "YMin", "YMax"),
                        (x0 - 1.0, x1 + 1.0, g.notch_centre_y_mm, y1 + 0.2)):
            field.setNumber(box, k, v)
        field.setAsBackgroundMesh(box)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        index = {int(t): i for i, t in enumerate(tags)}
        coords = xyz.reshape(-1, 3)[:, :2]
        regions = {}
        for s in surfaces:
            _, _, conn = gmsh.model.mesh.getElements(2, s)
            tri = np.array([index[int(t)] for t in conn[0]]).reshape(-1, 6)
            regions.setdefault("layer" if s in in_layer else "element", []).append(tri)
        # the contact face: the tip's top edge at y = tip top
        x_tip0 = g.tip_centre_x_mm - g.tip_width_mm / 2
        edges = []
        for dim, tag in gmsh.model.getEntities(1):
            lo = gmsh.model.getBoundingBox(dim, tag)
            if abs(lo[1] - g.tip_top_y_mm) < 1e-5 and abs(lo[4] - g.tip_top_y_mm) < 1e-5 \
                    and lo[0] >= x_tip0 - 1e-5:
                _, _, conn = gmsh.model.mesh.getElements(1, tag)
                edges += [[index[int(t)] for t in conn[0][i:i + 3]]
                          for i in range(0, len(conn[0]), 3)]
    finally:
        gmsh.finalize()
    return coords, {k: np.vstack(v) for k, v in regions.items()}, np.array(edges)


def _compliance(g, material, coords, regions, edges, layer_E, layer_width, folder: Path) -> float:
    """F^T u / F^2 of a unit force over the contact face (mm/N)."""
    lines = ["*NODE"] + [f"{i + 1}, {x:.12g}, {y:.12g}" for i, (x, y) in enumerate(coords)]
    eid = 1
    for name, tri in regions.items():
        lines.append(f"*ELEMENT, TYPE=CPS6, ELSET={name.upper()}")
        for row in tri:
            lines.append(f"{eid}, " + ", ".join(str(n + 1) for n in row))
            eid += 1
    clamp = np.flatnonzero(np.isclose(coords[:, 0], fem_region(g).x_clamp)) + 1
    lines += ["*NSET, NSET=CLAMP"] + [", ".join(map(str, clamp[i:i + 12]))
                                      for i in range(0, len(clamp), 12)]
    weights: dict[int, float] = {}
    for a, b, mid in edges:  # gmsh's 3-node line: the ends, then the middle
        length = abs(coords[b, 0] - coords[a, 0])
        for n, w in ((a, length / 6), (b, length / 6), (mid, 4 * length / 6)):
            weights[n] = weights.get(n, 0.0) + w
    total = sum(weights.values())
    assert total == pytest.approx(g.tip_width_mm), "the contact face's edges were not found"
    loaded = sorted(weights)
    lines += ["*NSET, NSET=LOADED"] + [", ".join(str(n + 1) for n in loaded[i:i + 12])
                                       for i in range(0, len(loaded), 12)]
    lines += ["*MATERIAL, NAME=BODY", "*ELASTIC", f"{material.youngs_modulus_MPa}, "
              f"{material.poisson_ratio}", "*MATERIAL, NAME=LAYER", "*ELASTIC",
              f"{layer_E:.9g}, 0.35",
              "*SOLID SECTION, ELSET=ELEMENT, MATERIAL=BODY",
              f"{g.sheet_thickness_mm * SECTION_SCALE:.9g}",
              "*SOLID SECTION, ELSET=LAYER, MATERIAL=LAYER", f"{layer_width * SECTION_SCALE:.9g}",
              "*BOUNDARY", "CLAMP, 1, 2, 0.0", "*STEP", "*STATIC", "*CLOAD"]
    lines += [f"{n + 1}, 2, {w / total:.12g}" for n, w in sorted(weights.items())]
    lines += ["*NODE PRINT, NSET=LOADED", "U", "*END STEP"]
    (folder / "layer.inp").write_text("\n".join(lines) + "\n", encoding="ascii")
    subprocess.run(["ccx", "layer"], cwd=folder, capture_output=True, check=True, timeout=600)
    u = {}
    for row in (folder / "layer.dat").read_text().splitlines():
        parts = row.split()
        if len(parts) >= 3 and parts[0].isdigit():
            u[int(parts[0]) - 1] = float(parts[2])
    return SECTION_SCALE * sum(w / total * u[n] for n, w in weights.items())


@pytest.mark.parametrize("example", ["macro_array", "ti_array_2x3", "grasper_jaw_10mm"])
def test_the_plane_models_bonded_layer_matches_calculix(example, tmp_path):
    plan = load_design(EXAMPLES / example / f"{example}.toml")
    chain = readout_chain(plan)
    g, material = plan.slots[0].geometry, plan.material
    half = chain.grid_length_mm / 2 + CARRIER_SIDE_MM
    box = (g.hinge_x_mm - half, g.base_height_mm, g.hinge_x_mm + half,
           g.base_height_mm + chain.grid_height_mm)
    coords, regions, edges = _mesh(g, box, fine_mm=min(g.web_thickness_mm / 8,
                                                       chain.grid_height_mm / 2), coarse_mm=0.3)
    width = carrier_width_mm(chain.grid_width_mm, g.sheet_thickness_mm)
    bonded = _compliance(g, material, coords, regions, edges, chain.gauge_backing_modulus_MPa,
                         width, tmp_path)
    bare = _compliance(g, material, coords, regions, edges,
                       chain.gauge_backing_modulus_MPa * 1e-6, width, tmp_path)
    ours_bare = solve_fem2d(g, material, force_N=1.0)
    ours = solve_fem2d(g, material, force_N=1.0, layer=chain_layer(g, chain))
    rise, fe_rise = ours.stiffness_N_per_mm / ours_bare.stiffness_N_per_mm - 1, bare / bonded - 1
    print(f"{example}: K bare {ours_bare.stiffness_N_per_mm:.4f} / CalculiX {1 / bare:.4f}, "
          f"bonded {ours.stiffness_N_per_mm:.4f} / {1 / bonded:.4f} N/mm, rise {rise:.5f} / "
          f"{fe_rise:.5f}")
    assert fe_rise > 0.02
    assert ours_bare.stiffness_N_per_mm == pytest.approx(1 / bare, rel=1e-3)
    assert ours.stiffness_N_per_mm == pytest.approx(1 / bonded, rel=1e-3)
    assert rise == pytest.approx(fe_rise, rel=0.01)
