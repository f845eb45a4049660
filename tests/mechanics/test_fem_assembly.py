"""The elasticity assembly on the scalar pattern against the chunk-by-chunk assembly it
replaced, entry by entry, on P2 triangles, P2 tetrahedra and triquadratic hexahedra."""

import numpy as np
import pytest


def chunked_assembly(sb, lam, mu, chunk=4000):
    """The previous assembly: a sparse matrix per chunk of cells from the full local
    matrices (cells x (nbf dim)^2 entries), the chunks added."""
    import scipy.sparse as sp

    dim = sb.mesh.dim()
    nbf = sb.Nbfun
    G = np.array([sb.basis[i][0].grad for i in range(nbf)])
    W = sb.dx
    edofs = sb.element_dofs
    nel = edofs.shape[1]
    n = dim * sb.N
    lam_q = np.broadcast_to(np.asarray(lam, dtype=float), W.shape)
    mu_q = np.broadcast_to(np.asarray(mu, dtype=float), W.shape)
    total = sp.csr_matrix((n, n))
    eye = np.eye(dim)
    for e0 in range(0, nel, chunk):
        sl = slice(e0, min(nel, e0 + chunk))
        g = G[:, :, sl, :]
        M_lam = np.einsum("iaeq,jbeq,eq->eiajb", g, g, W[sl] * lam_q[sl])
        M_mu = np.einsum("iaeq,jbeq,eq->eiajb", g, g, W[sl] * mu_q[sl])
        lap = np.einsum("eicjc->eij", M_mu)
        Kl = M_lam + M_mu.transpose(0, 1, 4, 3, 2) \
            + lap[:, :, None, :, None] * eye[None, None, :, None, :]
        gd = (dim * edofs[:, sl].T[:, :, None] + np.arange(dim)[None, None, :])
        gd = gd.reshape(-1, nbf * dim)
        ne = gd.shape[0]
        rows = np.broadcast_to(gd[:, :, None], (ne, nbf * dim, nbf * dim)).ravel()
        cols = np.broadcast_to(gd[:, None, :], (ne, nbf * dim, nbf * dim)).ravel()
        total = total + sp.csr_matrix((Kl.reshape(-1), (rows, cols)), shape=(n, n))
    return total.tocsr()


def _basis(kind):
    from skfem import (Basis, ElementHex2, ElementTetP2, ElementTriP2, MeshHex, MeshTet,
                       MeshTri)

    axis = np.array([0.0, 0.3, 0.5, 1.2])
    if kind == "tri-p2":
        return Basis(MeshTri.init_tensor(axis, np.array([0.0, 0.2, 0.7])), ElementTriP2(),
                     intorder=4)
    if kind == "tet-p2":
        return Basis(MeshTet.init_tensor(axis, axis, axis), ElementTetP2(), intorder=2)
    return Basis(MeshHex.init_tensor(axis, axis, axis), ElementHex2(), intorder=4)


def _moduli(sb, how):
    """(lam, mu) in MPa: numbers, one pair per cell (two layers) or a field over the
    quadrature points."""
    if how == "numbers":
        return 1.3e5, 0.8e5
    x = np.asarray(sb.global_coordinates())
    if how == "per cell":
        soft = (x[0].mean(axis=1) > 0.6)[:, None]
        return np.where(soft, 2.0e3, 1.3e5), np.where(soft, 1.1e3, 0.8e5)
    return 1.0e5 * (1.0 + x[0] ** 2), 0.7e5 * (1.0 + x[1])  # varies within each cell


@pytest.mark.parametrize("kind", ["tri-p2", "tet-p2", "hex2"])
@pytest.mark.parametrize("how", ["numbers", "per cell", "field"])
def test_the_pattern_assembly_is_the_chunked_one_entry_by_entry(kind, how):
    from tactcad.mechanics.fem.fem2d import assemble_elasticity

    sb = _basis(kind)
    lam, mu = _moduli(sb, how)
    old = chunked_assembly(sb, lam, mu, chunk=7)
    new = assemble_elasticity(sb, lam, mu, chunk=5)
    scale = abs(old).max()
    assert new.shape == old.shape
    assert abs(new - old).max() <= 1e-12 * scale
    assert new.has_sorted_indices
    # no stored entry of the old one outside the new pattern (which keeps exact cancellations)
    in_new = new.copy()
    in_new.data[:] = 1.0
    assert abs(old).multiply(in_new).nnz == old.nnz


@pytest.mark.parametrize("kind", ["tri-p2", "tet-p2", "hex2"])
def test_the_free_block_assembled_is_the_rows_and_columns_kept(kind):
    from tactcad.mechanics.fem.fem2d import assemble_elasticity, free_block

    sb = _basis(kind)
    dim = sb.mesh.dim()
    lam, mu = _moduli(sb, "per cell")
    # a clamp face (all components) and a symmetry plane (the last component only)
    clamp = np.flatnonzero(sb.doflocs[0] < 1e-9)
    plane = np.flatnonzero(sb.doflocs[1] > 0.69)
    fixed = np.union1d((dim * clamp[:, None] + np.arange(dim)).ravel(), dim * plane + dim - 1)
    free = np.setdiff1d(np.arange(dim * sb.N), fixed)
    expected = free_block(chunked_assembly(sb, lam, mu), free)
    got = assemble_elasticity(sb, lam, mu, free=free)
    assert got.shape == (len(free), len(free))
    assert abs(got - expected).max() <= 1e-12 * abs(expected).max()
    assert np.all(np.diff(got.indptr) > 0)  # every kept row holds its diagonal at least
    assert np.all(got.diagonal() > 0)


def test_each_cell_entry_lands_on_its_rows_and_columns():
    from tactcad.mechanics.fem.fem_assembly import scalar_pattern

    sb = _basis("tet-p2")
    pattern = scalar_pattern(sb.element_dofs, sb.N)
    rows = np.repeat(np.arange(sb.N), np.diff(pattern.indptr))
    cells = sb.element_dofs.T
    assert np.array_equal(pattern.indices[pattern.entry], np.broadcast_to(
        cells[:, None, :], pattern.entry.shape))
    assert np.array_equal(rows[pattern.entry], np.broadcast_to(cells[:, :, None],
                                                               pattern.entry.shape))
    # the mirror of the mirror is the entry; rows and columns swap
    assert np.array_equal(pattern.transpose[pattern.transpose], np.arange(pattern.nnz))
    assert np.array_equal(rows[pattern.transpose], pattern.indices)


def test_bad_free_unknowns_and_dofs_are_refused_by_name():
    from tactcad.mechanics.fem.fem_assembly import scalar_pattern
    from tactcad.mechanics.fem.fem2d import assemble_elasticity

    sb = _basis("tri-p2")
    with pytest.raises(ValueError, match="free must be ascending"):
        assemble_elasticity(sb, 1.0e5, 0.8e5, free=np.array([3, 2]))
    with pytest.raises(ValueError, match="element_dofs must lie in 0 .. 4"):
        scalar_pattern(np.array([[0, 1], [5, 2]]), 5)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_free_embedding_is_the_full_one_restricted(dim):
    """P on the kept unknowns equals kron(P1 embedding, I)[free][:, kept vertex unknowns]."""
    import scipy.sparse as sp

    from tactcad.mechanics.fem.fem2d import free_p1_embedding, p1_embedding

    sb = _basis("tri-p2" if dim == 2 else "tet-p2")
    mesh, nv = sb.mesh, sb.mesh.nvertices
    rng = np.random.default_rng(5)
    free = np.sort(rng.choice(dim * sb.N, int(0.8 * dim * sb.N), replace=False))
    full = sp.kron(p1_embedding(mesh, sb.N), sp.eye(dim), format="csr")
    kept = np.zeros(dim * sb.N, dtype=bool)
    kept[free] = True
    expected = full[free][:, np.flatnonzero(kept[:dim * nv])]
    P, coarse_kept = free_p1_embedding(mesh, sb.N, free)
    assert np.array_equal(coarse_kept, kept[:dim * nv])
    assert P.shape == expected.shape and (P != expected).nnz == 0
