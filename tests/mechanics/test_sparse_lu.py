"""The one sparse direct factorisation: minimum degree and METIS's nested dissection of the
node graph solve a 3D elastic solid alike, and a node size that does not divide the matrix
is refused."""

from __future__ import annotations

import numpy as np
import pytest

from tactcad.mechanics.fem.sparse_lu import nested_dissection_order, spd_lu


def _block():
    """(scalar basis, full stiffness N/mm numbered 3 s + a) of an isotropic steel-like
    4 x 1 x 1 mm block of triquadratic hexahedra (E 200 GPa, nu 0.3), nothing held."""
    from skfem import Basis, ElementHex2, MeshHex

    from tactcad.products.silicon_die.mechanics.die_fem3d import assemble_anisotropic

    mesh = MeshHex.init_tensor(np.linspace(0, 4, 9), np.linspace(0, 1, 3), np.linspace(0, 1, 3))
    scalar = Basis(mesh, ElementHex2())
    e, nu = 200e3, 0.3
    lam, mu = e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))
    eye = np.eye(3)
    c = (lam * np.einsum("ij,kl->ijkl", eye, eye)
         + mu * (np.einsum("ik,jl->ijkl", eye, eye) + np.einsum("il,jk->ijkl", eye, eye)))
    return scalar, assemble_anisotropic(scalar, c).tocsr()


def _clamped_block_stiffness():
    """The stiffness (N/mm) of an isotropic 4 x 1 x 1 mm block of triquadratic hexahedra,
    its x = 0 face held, numbered 3 s + a."""
    scalar, k = _block()
    held = scalar.get_dofs(lambda x: np.isclose(x[0], 0.0)).all()
    clamped = (3 * held[:, None] + np.arange(3)).ravel()
    free = np.setdiff1d(np.arange(3 * scalar.N), clamped)
    return k[free][:, free]


def test_nested_dissection_solves_as_minimum_degree_does_and_keeps_each_nodes_dofs_together():
    k = _clamped_block_stiffness()
    b = np.random.default_rng(3).standard_normal((k.shape[0], 2))
    order = nested_dissection_order(k, 3)
    assert sorted(order) == list(range(k.shape[0]))  # a permutation of every dof
    assert np.all(order[1::3] == order[::3] + 1) and np.all(order[2::3] == order[::3] + 2)
    by_degree = spd_lu(k).solve(b)
    dissected = spd_lu(k, dofs_per_node=3)
    assert np.abs(k @ dissected.solve(b) - b).max() < 1e-9 * np.abs(b).max()
    scale = np.abs(by_degree).max()
    assert dissected.solve(b) == pytest.approx(by_degree, rel=1e-9, abs=1e-12 * scale)
    assert dissected.solve(b[:, 0]) == pytest.approx(dissected.solve(b)[:, 0], rel=1e-12)


@pytest.mark.parametrize("dofs_per_node", [-1, 7])
def test_a_node_size_that_does_not_divide_the_matrix_is_refused(dofs_per_node):
    k = _clamped_block_stiffness()  # 400 nodes of 3 dofs: 1200 rows
    with pytest.raises(ValueError, match=f"dofs_per_node = {dofs_per_node}.*allowed"):
        spd_lu(k, dofs_per_node=dofs_per_node)


def _held_and_rolled_block():
    """The 4 x 1 x 1 mm block's full stiffness (numbered 3 s + a) and the mask of its free
    dofs: the x = 0 face held, u_z = 0 on z = 1 (a mid-plane), so nodes keep 3, 2 or 0 dofs."""
    scalar, k = _block()
    kept = np.ones(3 * scalar.N, dtype=bool)
    kept[(3 * scalar.get_dofs(lambda x: np.isclose(x[0], 0.0)).all()[:, None]
          + np.arange(3)).ravel()] = False
    kept[3 * scalar.get_dofs(lambda x: np.isclose(x[2], 1.0)).all() + 2] = False
    return k, kept


def test_a_node_order_restricted_to_the_free_dofs_solves_the_reduced_system():
    from tactcad.mechanics.fem.sparse_lu import graph_nested_dissection, node_dof_order

    k, kept = _held_and_rolled_block()
    free = np.flatnonzero(kept)
    reduced = k[free][:, free]
    order = node_dof_order(graph_nested_dissection(k[::3, ::3]), 3, kept)
    assert sorted(order) == list(range(len(free)))  # every free dof once, renumbered
    assert (kept.reshape(-1, 3).sum(axis=1) == 2).any()  # nodes on the mid-plane keep two
    b = np.random.default_rng(5).standard_normal(len(free))
    x = spd_lu(reduced, order=order).solve(b)
    assert np.abs(reduced @ x - b).max() < 1e-9 * np.abs(b).max()
    assert x == pytest.approx(spd_lu(reduced).solve(b), rel=1e-9, abs=1e-12 * np.abs(x).max())


def test_an_order_that_is_not_a_permutation_is_refused():
    k, kept = _held_and_rolled_block()
    with pytest.raises(ValueError, match="order: allowed a permutation"):
        spd_lu(k, order=np.zeros(k.shape[0], dtype=int))
