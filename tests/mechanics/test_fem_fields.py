"""FEM fields: nodal stress recovery, von Mises, VTU files read back with meshio."""

from __future__ import annotations

import json

import meshio
import numpy as np
import pytest

from tactcad.cli import main
from tactcad.mechanics.fem.field_files import write_element_vtu
from tactcad.mechanics.fem.fields import (FaceStrain, face_rectangle_average, top_face_strain,
                                          von_mises)


def test_von_mises_of_simple_states():
    s = np.zeros((3, 3, 3))
    s[0, 0, 0] = 100.0                      # uniaxial
    s[1, 0, 1] = s[1, 1, 0] = 50.0          # pure shear
    s[2] = np.eye(3) * 70.0                 # hydrostatic
    assert von_mises(s) == pytest.approx([100.0, 50.0 * np.sqrt(3), 0.0])


def _check_vtu(path, n_points, plan_stress_per_N, tip_deflection_mm):
    m = meshio.read(path)
    assert m.points.shape == (n_points, 3)
    assert set(m.point_data) == {"displacement", "von_mises_MPa"}
    u, vm = m.point_data["displacement"], m.point_data["von_mises_MPa"]
    assert u.shape == (n_points, 3) and vm.shape == (n_points,)
    assert np.all(np.isfinite(u)) and np.all(vm >= 0)
    # under 1 N the arm turns about the hinge: the far end of the tip (lever
    # a + w/2) rises (a + w/2)/a times the load point's 1/K; the peak von
    # Mises (the notch root) is the closed form's within 15 %
    assert u[:, 1].max() == pytest.approx(tip_deflection_mm, rel=0.05)
    assert vm.max() == pytest.approx(plan_stress_per_N, rel=0.15)
    return m


def test_fem2d_vtu_round_trip(plan, tmp_path):
    from tactcad.mechanics.element_strength import peak_stress_per_newton

    g = plan.element(4).geometry
    out = write_element_vtu(tmp_path, g, plan.material, "fem2d")
    assert out.path.name == "element_a8mm_fem2d.vtu" and out.force_N == 1.0
    m = _check_vtu(out.path, meshio.read(out.path).points.shape[0],
                   float(peak_stress_per_newton(0.25, 0.5, 8.0, 3.0)),
                   (8.0 + 1.0) / 8.0 / out.stiffness_N_per_mm)
    assert m.cells[0].type == "triangle"
    assert np.allclose(m.points[:, 2], 0.0)


def test_stiffness_vtk_needs_a_fem_model(tmp_path, capsys):
    assert main(["stiffness", "--element", "1", "--vtk", str(tmp_path)]) == 2
    assert "--vtk" in capsys.readouterr().err


def test_stiffness_command_writes_vtu(tmp_path, capsys):
    assert main(["stiffness", "--element", "1", "--model", "fem2d", "--json",
                 "--vtk", str(tmp_path / "vtk")]) == 0
    out = json.loads(capsys.readouterr().out)
    m = meshio.read(out["vtu"])
    assert m.point_data["von_mises_MPa"].shape == (m.points.shape[0],)


@pytest.mark.slow
def test_fem3d_vtu_is_the_whole_element(plan, tmp_path):
    g = plan.element(1).geometry
    out = write_element_vtu(tmp_path, g, plan.material, "fem3d")
    m = meshio.read(out.path)
    assert m.cells[0].type == "tetra"
    z = m.points[:, 2]
    assert z.min() == pytest.approx(0.0, abs=1e-9) and z.max() == pytest.approx(3.0, abs=1e-9)
    # mirrored half: u_z is odd about the mid-plane, u_y even
    n = m.points.shape[0] // 2
    u = m.point_data["displacement"]
    assert np.allclose(u[n:, 2], -u[:n, 2]) and np.allclose(u[n:, 1], u[:n, 1])
    assert u[:, 1].max() == pytest.approx((4.0 + 1.0) / 4.0 / out.stiffness_N_per_mm, rel=0.05)


def test_recovered_stress_at_the_gauge_is_uniaxial(plan):
    """On the free flat top face over the web the plane-stress state is
    uniaxial: sigma_xx = E eps_xx, sigma_yy ~ 0 (recovered stress against the
    solver's own gauge strain), and its magnitude is below the notch-root peak."""
    from tactcad.mechanics.fem.fem2d import solve_fem2d
    from tactcad.mechanics.fem.fields import peak_notch_stress, vertex_stress

    g = plan.element(2).geometry
    sol = solve_fem2d(g, plan.material, web_divisions=12, keep_field=True, force_N=1.0)
    mesh = sol.field.basis.mesh
    gv = int(np.argmin(np.hypot(mesh.p[0] - g.hinge_x_mm, mesh.p[1] - g.base_height_mm)))
    sig = vertex_stress(sol.field)[gv]
    E = plan.material.youngs_modulus_MPa
    assert sig[0, 0] == pytest.approx(E * sol.gauge_strain, rel=0.01)
    assert abs(sig[1, 1]) < 0.02 * abs(sig[0, 0]) and sig[2, 2] == 0.0
    assert abs(sig[0, 0]) < peak_notch_stress(sol.field, g).von_mises_MPa


# ---------------------------------------------------------------------------
# The face average integrates a piecewise-linear face strain exactly
# ---------------------------------------------------------------------------
def _grid_face(nx: int, nz: int, x1: float, z1: float, f, sym_plane_z=None) -> FaceStrain:
    xs, zs = np.linspace(0, x1, nx + 1), np.linspace(0, z1, nz + 1)
    tris = []
    for i in range(nx):
        for j in range(nz):
            a, b = (xs[i], zs[j]), (xs[i + 1], zs[j])
            c, d = (xs[i + 1], zs[j + 1]), (xs[i], zs[j + 1])
            tris += [(a, b, c), (a, c, d)]
    corners = np.array(tris)
    return FaceStrain(corners, f(corners[..., 0], corners[..., 1]), sym_plane_z)


def test_face_average_is_exact_for_a_linear_strain():
    face = _grid_face(7, 5, 4.0, 3.0, lambda x, z: 2.0 + 3.0 * x - 0.5 * z)
    # a rectangle that cuts the triangles anywhere: the mean of a linear field is its centre value
    got = face_rectangle_average(face, (0.37, 2.91), (0.55, 2.2))
    assert got == pytest.approx(2.0 + 3.0 * (0.37 + 2.91) / 2 - 0.5 * (0.55 + 2.2) / 2, rel=1e-12)


def test_face_average_folds_a_grid_across_the_mid_plane_of_a_half_model():
    f = lambda x, z: 1.0 + x + 2.0 * z  # noqa: E731
    half = _grid_face(6, 6, 2.0, 1.5, f, sym_plane_z=1.5)
    # the grid 1.0 ... 2.0 across z reads 1.0 ... 1.5 and its mirror 1.0 ... 1.5 (mean z 1.25)
    got = face_rectangle_average(half, (0.5, 1.5), (1.0, 2.0))
    assert got == pytest.approx(1.0 + 1.0 + 2.0 * 1.25, rel=1e-12)
    with pytest.raises(ValueError, match="covers"):
        face_rectangle_average(_grid_face(2, 2, 1.0, 1.0, f), (0.5, 1.5), (0.0, 1.0))


def test_top_face_strain_of_a_fem3d_solve_meets_its_gauge_point(plan):
    """The face's per-cell strain over a tiny square at the gauge point agrees with the
    solve's nodal-averaged gauge strain there (one coarse mesh, about a second)."""
    from tactcad.mechanics.fem.fem3d import solve_fem3d

    g = plan.element(1).geometry
    sol = solve_fem3d(g, plan.material, size_factor=2.0, keep_field=True)
    face = top_face_strain(sol.field, g.base_height_mm)
    b, x = g.sheet_thickness_mm, g.hinge_x_mm
    tiny = face_rectangle_average(face, (x - 0.005, x + 0.005), (b / 2 - 0.01, b / 2 + 0.01))
    assert tiny == pytest.approx(sol.gauge_strain / sol.force_N, rel=0.02)
    assert face.sym_plane_z == b / 2


def _quadratic_field_on_p2_tetrahedra():
    """A scalar P2 basis on a small tetrahedral box and the three components of the quadratic
    displacement u = (x^2 + y z, x y - z^2, 3 x z + y), which P2 holds exactly (mm)."""
    from skfem import Basis, ElementTetP2, MeshTet

    mesh = MeshTet.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 0.5, 3),
                               np.linspace(0, 0.3, 3))
    sb = Basis(mesh, ElementTetP2())
    x, y, z = sb.doflocs
    return sb, [x ** 2 + y * z, x * y - z ** 2, 3 * x * z + y]


def _exact_gradient(p: np.ndarray) -> np.ndarray:
    x, y, z = p
    return np.array([[2 * x, z, y], [y, x, -2 * z], [3 * z, 1.0, 3 * x]])


def test_vertex_gradient_of_a_quadratic_field_is_exact_at_every_vertex_tried():
    from tactcad.mechanics.fem.fem2d import vertex_gradient

    sb, u = _quadratic_field_on_p2_tetrahedra()
    for v in (0, 7, sb.mesh.nvertices // 2, sb.mesh.nvertices - 1):
        assert vertex_gradient(sb, u, v) == pytest.approx(_exact_gradient(sb.mesh.p[:, v]),
                                                          abs=1e-12)


def test_basis_gradients_agree_with_scikit_fem_interpolation_on_a_subset_of_cells():
    from skfem import CellBasis

    from tactcad.mechanics.fem.fem2d import basis_gradients

    sb, u = _quadratic_field_on_p2_tetrahedra()
    cells = np.array([3, 0, 11, 5])
    points = np.array([[0.1, 0.25, 0.6], [0.2, 0.25, 0.1], [0.3, 0.25, 0.2]])  # (dim, q)
    ours = basis_gradients(sb, u, cells, points)
    cb = CellBasis(sb.mesh, sb.elem, elements=cells, quadrature=(points, np.ones(3)))
    theirs = np.array([np.array(cb.interpolate(c).grad) for c in u])
    assert ours.shape == (3, 3, len(cells), 3)
    assert ours == pytest.approx(theirs, abs=1e-12)
    # and the field's exact gradient at the mapped points
    xq = np.array(cb.global_coordinates())  # (dim, cells, q)
    exact = np.array([[_exact_gradient(xq[:, e, q]) for q in range(3)] for e in range(4)])
    assert ours == pytest.approx(exact.transpose(2, 3, 0, 1), abs=1e-12)
