"""The read-out's grid strain at fem3d against an independent CalculiX model.

The element's STEP as ``tactcad export`` writes it is read by gmsh, cut at
the stiffness model's clamp line (x = x_clamp), meshed with quadratic
tetrahedra (half the web at the notch, 1 mm elsewhere) and written
as a CalculiX static job: C3D10, every node of the cut face fixed, the tip
force as the consistent nodal loads of a uniform traction along +y on the
contact face (the tip's top face; on a 6-node triangle a uniform load goes
to the mid-side nodes, a third each). The grid's mean eps_xx over its
rectangle on the top face is, exactly, the mean over the grid's width of
(u_x(x1) - u_x(x0)) / (x1 - x0); u_x comes from ccx's top-face nodes. It must
agree with ``readout --model fem3d``'s face average within 2 % (measured: the
paper's 4 mm element 0.80 % at 25k nodes, the Ti example's 19.6 mm element
0.41 % at 43k nodes, 70 s with the modal test; at a third of the web and 0.6 mm,
61k and 116k nodes, 0.17 % and 0.07 %: ccx converges onto fem3d). ``ccx`` is
Debian's ``calculix-ccx`` (the ``ccx`` fixture of tests/conftest.py installs or
skips).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

from calculix_jobs import mesh_element, write_mesh
from conftest import run_cli
from shared_solves import ONE_WORKER, shared_store

#: The paper's stiffest element and the Ti example's softest.
CASES = (("hardware/macro_array/macro_array.toml", "element_a4mm"),
         ("hardware/ti_array_2x3/ti_array_2x3.toml", None))
FORCE_N = 1.0


def write_static_job(step: Path, inp: Path, *, x_clamp: float, neck_box, neck_size: float,
                     size_max: float, E: float, nu: float, contact_y: float, top_y: float,
                     force_N: float) -> int:
    """Mesh ``step`` cut at x >= x_clamp (gmsh, order 2) and write a ccx static job with
    the tip force on the face at y = ``contact_y`` and the top face's nodes (y = ``top_y``)
    printed; returns the node count."""
    mesh = mesh_element(step, x_clamp=x_clamp, neck_box=neck_box, neck_size=neck_size,
                        size_max=size_max, face_ys=(contact_y,))
    where = {int(t): k for k, t in enumerate(mesh.tags)}
    tris = mesh.faces_at_y[contact_y]
    p = mesh.xyz[np.vectorize(where.get)(tris[:, :3])]
    areas = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    loads: dict[int, float] = {}
    for tri, a in zip(tris, areas):  # uniform traction: a third of a triangle's load per mid-side
        for n in tri[3:]:
            loads[int(n)] = loads.get(int(n), 0.0) + force_N * a / areas.sum() / 3.0
    top = [int(t) for t, q in zip(mesh.tags, mesh.xyz) if abs(q[1] - top_y) < 1e-6]
    with open(inp, "w", encoding="ascii") as fh:
        write_mesh(fh, mesh, E, nu)
        fh.write("*NSET, NSET=TOP\n")
        fh.writelines(f"{n},\n" for n in top)
        fh.write("*STEP\n*STATIC\n*CLOAD\n")
        fh.writelines(f"{n}, 2, {v:.12g}\n" for n, v in sorted(loads.items()))
        fh.write("*NODE PRINT, NSET=TOP\nU\n*END STEP\n")
    return len(mesh.tags)


def read_ccx_displacements(dat: Path) -> dict[int, np.ndarray]:
    """Node -> (u_x, u_y, u_z) of ccx's ``*NODE PRINT`` block."""
    text = dat.read_text().split("displacements", 1)[1]
    rows = re.findall(r"^\s+(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", text, re.M)
    return {int(r[0]): np.array([float(v) for v in r[1:]]) for r in rows}


def grid_mean_strain(top_xyz: np.ndarray, ux: np.ndarray, x_span, z_span, n: int = 41) -> float:
    """Mean eps_xx over the rectangle = mean over z of (u_x(x1) - u_x(x0)) / (x1 - x0), u_x
    interpolated over the top face's nodes (cubic Clough-Tocher on the (x, z) nodes)."""
    from scipy.interpolate import CloughTocher2DInterpolator

    near = ((top_xyz[:, 0] > x_span[0] - 1.0) & (top_xyz[:, 0] < x_span[1] + 1.0))
    f = CloughTocher2DInterpolator(top_xyz[near][:, [0, 2]], ux[near])
    zs, wz = np.polynomial.legendre.leggauss(n)
    z = 0.5 * (z_span[1] - z_span[0]) * zs + 0.5 * (z_span[1] + z_span[0])
    du = f(np.full_like(z, x_span[1]), z) - f(np.full_like(z, x_span[0]), z)
    assert np.all(np.isfinite(du)), "grid outside the interpolated top face"
    return float(0.5 * (wz @ du) / (x_span[1] - x_span[0]))


@pytest.mark.slow
@ONE_WORKER  # its fem3d solves are test_bonded_layer's and test_gauge_strain_fem3d's
@pytest.mark.parametrize("design, part", CASES)
def test_fem3d_grid_strain_agrees_with_calculix(design, part, ccx, tmp_path):
    from tactcad.api import load
    from tactcad.mechanics.fem.fem_mesh import fem_region
    from tactcad.mechanics.readout_chain import (grid_span_mm, readout_chain,
                                                 face_mean_strain_as_cut_per_N)
    from tactcad.store import keeping_results

    root = Path(__file__).resolve().parents[2]
    plan = load(root / design).plan
    if part is None:  # the softest element (longest arm)
        part = max(plan.distinct_elements.values(), key=lambda e: e.arm_length_mm).part_name
    done = run_cli("export", "--design", str(root / design), "--no-cache", "--only", "step",
                   "--part", part, "--out", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr
    step = tmp_path / "out" / "step" / f"{part}.step"
    g, mat = plan.distinct_elements[part], plan.material
    t, R = g.web_thickness_mm, g.notch_radius_mm
    xh, yw = g.web_centre_mm
    nodes = write_static_job(step, tmp_path / "job.inp", x_clamp=fem_region(g).x_clamp,
                             neck_box=(xh - R - t, yw - R - t, xh + R + t, yw + 2 * t),
                             neck_size=t / 2.0, size_max=1.0, E=mat.youngs_modulus_MPa,
                             nu=mat.poisson_ratio, contact_y=g.tip_top_y_mm,
                             top_y=g.base_height_mm, force_N=FORCE_N)
    assert nodes > 10_000
    run = subprocess.run([ccx, "-i", "job"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=900)
    assert run.returncode == 0, run.stdout[-2000:]
    u = read_ccx_displacements(tmp_path / "job.dat")
    ids = sorted(u)
    top = np.array(_node_xyz(tmp_path / "job.inp", ids))
    ux = np.array([u[n][0] for n in ids])
    chain = readout_chain(plan)
    zc = 0.5 * (top[:, 2].min() + top[:, 2].max())  # the sheet's mid-width
    w = min(chain.grid_width_mm, g.sheet_thickness_mm)
    ccx_eps = grid_mean_strain(top, ux, grid_span_mm(g, chain.grid_length_mm),
                               (zc - w / 2, zc + w / 2)) / FORCE_N
    with keeping_results(shared_store()):
        ours = face_mean_strain_as_cut_per_N(g, mat, chain.grid_length_mm, chain.grid_width_mm,
                                         "fem3d")
    print(f"{design} {part}: fem3d grid {ours['surface']:.6e}, ccx {ccx_eps:.6e} "
          f"({nodes} nodes), ratio {ours['surface'] / ccx_eps:.5f}")
    assert ours["surface"] == pytest.approx(ccx_eps, rel=0.02)


def _node_xyz(inp: Path, ids: list[int]) -> list[tuple[float, float, float]]:
    want = set(ids)
    out = {}
    with open(inp, encoding="ascii") as fh:
        next(fh)
        for line in fh:
            if line.startswith("*"):
                break
            n, x, y, z = line.split(",")
            if int(n) in want:
                out[int(n)] = (float(x), float(y), float(z))
    return [out[n] for n in ids]
