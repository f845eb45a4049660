"""The punch solve by the layout's mirror symmetry against the dense solve it replaces."""

from __future__ import annotations

import numpy as np
import pytest

from tactcad.mechanics.contact import Punch, Sample


@pytest.mark.parametrize("columns, shifted", [(8, False), (5, False), (3, True)])
def test_the_solve_by_mirror_symmetry_is_the_full_solve(columns, shifted):
    # two rows of tips: the two mirrors split the dense solve into four; an odd column count
    # puts a tip (and a cell row) on the mirror line; a shifted tip leaves no mirror
    from tactcad.mechanics.contact import (influence_matrix, mesh_punches, mirror_maps,
                                           solve_by_symmetry)

    punches = [Punch(c * 1.0 + (0.1 if shifted and (c, r) == (0, 0) else 0.0), r * 1.5, 0.8, 0.6)
               for r in range(2) for c in range(columns)]
    mesh = mesh_punches(punches, 0.15, 9)
    a = influence_matrix(mesh, Sample(1.0, 0.5))
    rhs = np.zeros((len(mesh.punch), len(punches)))
    rhs[np.arange(len(mesh.punch)), mesh.punch] = 1.0
    maps = mirror_maps(mesh)
    assert len(maps) == (0 if shifted else 2)  # the shifted tip breaks both
    for m in maps:
        assert np.array_equal(m[m], np.arange(len(m)))  # each an involution
        assert np.allclose(a[np.ix_(m, m)], a, rtol=1e-9, atol=1e-14 * abs(a).max())  # commutes
    full = np.linalg.solve(a, rhs)
    assert np.allclose(solve_by_symmetry(a, rhs, maps), full, rtol=0, atol=1e-10 * abs(full).max())


def _corner_primitive_by_arcsinh(u, v):
    """F(u, v) = u asinh(v/|u|) + v asinh(u/|v|) as written (the reference)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(u != 0, u * np.arcsinh(v / np.abs(u)), 0.0)
        b = np.where(v != 0, v * np.arcsinh(u / np.abs(v)), 0.0)
    return a + b


def test_the_corner_primitive_is_the_arcsinh_form_at_every_ratio_and_on_the_axes():
    from tactcad.mechanics.contact import _corner_primitive

    rng = np.random.default_rng(3)
    u = rng.choice([-1.0, 1.0], 20_000) * np.exp(rng.uniform(-14, 4, 20_000))
    v = rng.choice([-1.0, 1.0], 20_000) * np.exp(rng.uniform(-14, 4, 20_000))
    got, want = _corner_primitive(u, v), _corner_primitive_by_arcsinh(u, v)
    assert np.max(np.abs(got / want - 1.0)) < 1e-14
    axes = np.array([0.0, 0.0, 2.0, -3.0, 0.0])
    other = np.array([0.0, 1.5, 0.0, 0.0, -7.0])
    assert np.array_equal(_corner_primitive(axes, other), np.zeros(5))
    assert np.array_equal(_corner_primitive(other, axes), np.zeros(5))


def test_a_block_on_a_faces_edge_grid_is_the_cell_by_cell_love_integral():
    """The influence of a face's cells, from the corner primitive on its grid of edges
    (each node once), against Love's integral cell by cell (each cell's four corners)."""
    from tactcad.mechanics.contact import (_influence_block, _tensor_edges, mesh_punches,
                                           rectangle_inverse_distance_integral)

    target, source = Punch(0.0, 0.0, 0.8, 0.6), Punch(2.3, -1.1, 0.5, 0.9)
    mesh = mesh_punches([target, source], 0.1, 7)
    mine, theirs = mesh.punch == 0, mesh.punch == 1
    centres, src, half = mesh.centres[mine], mesh.centres[theirs], mesh.half[theirs]
    assert _tensor_edges(src, half) is not None
    assert _tensor_edges(src[::-1], half[::-1]) is None  # not laid out as a face's grid
    sample = Sample(2.0, 0.4)
    got = _influence_block(centres, src, half, sample, 0)
    lo, hi = src - half, src + half
    want = (1 - 0.4 ** 2) / (np.pi * 2.0) * rectangle_inverse_distance_integral(
        centres[:, None, 0], centres[:, None, 1], lo[None, :, 0], hi[None, :, 0],
        lo[None, :, 1], hi[None, :, 1])
    # the edges rebuilt from centre +- half differ in the last bit, and a far cell's
    # four-corner difference cancels about log10(distance / cell) digits
    np.testing.assert_allclose(got, want, rtol=1e-10)
    # cells out of a grid's order take the cell-by-cell integral: the same numbers
    np.testing.assert_allclose(_influence_block(centres, src[::-1], half[::-1], sample, 0),
                               want[:, ::-1], rtol=1e-15)


def test_the_rectangle_integral_takes_scalars_and_broadcasts_any_shapes_as_one_by_one():
    """Points as a column against corners as a row, and plain floats: each value the same as
    the point and rectangle taken alone."""
    import numpy as np

    from tactcad.mechanics.contact import rectangle_inverse_distance_integral as integral

    xs = np.array([[-0.7], [0.0], [0.4], [2.5]])
    x2 = np.array([[0.5, 1.0, 3.0]])
    grid = integral(xs, 0.2, -0.5, x2, -0.3, 0.8)
    assert grid.shape == (4, 3)
    for i, x in enumerate(xs[:, 0]):
        for j, right in enumerate(x2[0]):
            alone = integral(float(x), 0.2, -0.5, float(right), -0.3, 0.8)
            assert np.ndim(alone) == 0 and float(alone) == grid[i, j]


def _two_rows(columns: int, x0_mm: float = 0.75, z0_mm: float = 0.7, face_mm: float = 0.1,
              row_mm: float = 0.25) -> list:
    """A die-like layout: two rows of square tips at a 1 mm pitch."""
    return [Punch(x0_mm + c, z0_mm + r * row_mm, face_mm, face_mm)
            for r in range(2) for c in range(columns)]


def test_the_representatives_rows_solve_as_the_whole_matrix_does():
    """The symmetric solve reads only the representatives' rows: built for the punches
    holding them, they are the whole matrix's rows and give its solution."""
    from tactcad.mechanics.contact import (influence_matrix, mesh_punches, mirror_maps,
                                           representatives, solve_by_symmetry, target_cells)

    punches = _two_rows(5)
    mesh = mesh_punches(punches, 1.0, 8)
    sample = Sample(1.0, 0.5)
    maps = mirror_maps(mesh)
    targets = np.unique(mesh.punch[representatives(maps, len(mesh.punch))])
    assert 0 < len(targets) < len(punches)  # the odd column's tip holds some, not all
    rows = target_cells(mesh, targets)
    full = influence_matrix(mesh, sample)
    part = influence_matrix(mesh, sample, targets)
    assert part.shape == (len(rows), len(mesh.punch))
    assert np.array_equal(part, full[rows])
    rhs = np.zeros((len(mesh.punch), len(punches)))
    rhs[np.arange(len(mesh.punch)), mesh.punch] = 1.0
    want = np.linalg.solve(full, rhs)
    got = solve_by_symmetry(part, rhs, maps, rows)
    assert np.allclose(got, want, rtol=0, atol=1e-10 * abs(want).max())



@pytest.mark.parametrize("columns, cells", [(5, 8), (4, 9), (3, 8)])
def test_the_representatives_rows_alone_are_the_whole_matrix_rows_to_the_bit(columns, cells):
    """Built for the representatives alone (not every cell of the punches holding them),
    the rows are the whole matrix's to the bit, in :func:`built_cells`' order; the
    symmetric solve on them needs no gather and gives the whole matrix's solution."""
    from tactcad.mechanics.contact import (built_cells, influence_matrix, mesh_punches,
                                           mirror_maps, representatives, solve_by_symmetry)

    punches = _two_rows(columns)
    mesh = mesh_punches(punches, 1.0, cells)
    sample = Sample(1.0, 0.5)
    maps = mirror_maps(mesh)
    reps = representatives(maps, len(mesh.punch))
    rows = built_cells(mesh, reps)
    assert np.array_equal(np.sort(rows), reps)
    full = influence_matrix(mesh, sample)
    part = influence_matrix(mesh, sample, cells=rows)
    assert part.shape == (len(reps), len(mesh.punch))
    assert part.tobytes() == full[rows].tobytes()
    rhs = np.zeros((len(mesh.punch), len(punches)))
    rhs[np.arange(len(mesh.punch)), mesh.punch] = 1.0
    want = np.linalg.solve(full, rhs)
    got = solve_by_symmetry(part, rhs, maps, rows)
    assert np.allclose(got, want, rtol=0, atol=1e-10 * abs(want).max())


def test_the_corner_primitive_on_its_own_axes_is_the_broadcast_one_to_the_bit():
    """u and v on separate axes (as a tensor grid of cell edges passes them) give the bits
    of the same values broadcast to one shape first, zeros and signs included; scalars
    stay scalars."""
    from tactcad.mechanics.contact import _corner_primitive

    rng = np.random.default_rng(7)
    u = rng.normal(size=(30, 9, 1))
    v = rng.normal(size=(30, 1, 11))
    u[0, 2, 0], v[1, 0, 3], v[2, 0, 0] = 0.0, 0.0, -0.0
    got = _corner_primitive(u, v)
    want = np.stack([_corner_primitive(a.ravel(), b.ravel())
                     for a, b in zip(*np.broadcast_arrays(u, v))]).reshape(got.shape)
    assert got.shape == (30, 9, 11)
    assert got.tobytes() == want.tobytes()
    assert np.shape(_corner_primitive(1.5, -2.0)) == ()
    assert _corner_primitive(0.0, 3.0) == 0.0


def test_the_blas_libraries_are_looked_up_again_only_after_an_import(monkeypatch):
    """The thread controls are found once and reused while no module is imported (a
    design search's hundred solves read the process's maps once, not twice a solve)."""
    import sys

    from tactcad.mechanics import blas_threads

    looked = []
    monkeypatch.setattr(blas_threads, "_openblas_paths", lambda: looked.append(1) or [])
    monkeypatch.setattr(blas_threads, "_FOUND", [None, None])
    assert blas_threads.blas_thread_controls() == []
    assert blas_threads.blas_thread_controls() == []
    assert len(looked) == 1
    monkeypatch.setitem(sys.modules, "tactcad_imported_since", sys)
    blas_threads.blas_thread_controls()
    assert len(looked) == 2


def test_a_kept_block_is_the_block_computed_afresh_wherever_the_array_lies():
    """Blocks kept across meshes: the same layout moved across the plane (its cells'
    relative coordinates differ in their last bits) has the same influence matrix to the
    bit, whether its blocks were kept or computed afresh, and the matrix is Love's
    integral cell by cell."""
    from tactcad.mechanics import contact
    from tactcad.mechanics.contact import (influence_matrix, mesh_punches,
                                           rectangle_inverse_distance_integral)

    sample = Sample(1.0, 0.5)
    # binary fractions: the faces' offsets are exact, wherever the layout lies
    here = mesh_punches(_two_rows(3, x0_mm=0.5, z0_mm=0.5), 1.0, 8)
    there = mesh_punches(_two_rows(3, x0_mm=6.25, z0_mm=-3.75), 1.0, 8)
    assert not np.array_equal(here.centres - here.centres[0], there.centres - there.centres[0])
    contact._BLOCKS.clear()
    fresh = influence_matrix(here, sample)
    computed = contact._BLOCKS.misses
    kept = influence_matrix(there, sample)
    assert contact._BLOCKS.hits > 0 and contact._BLOCKS.misses == computed  # none recomputed
    assert np.array_equal(fresh, kept)
    contact._BLOCKS.clear()
    assert np.array_equal(influence_matrix(there, sample), kept)
    c, h = here.centres, here.half
    love = rectangle_inverse_distance_integral(c[:, None, 0], c[:, None, 1],
                                               (c[:, 0] - h[:, 0])[None], (c[:, 0] + h[:, 0])[None],
                                               (c[:, 1] - h[:, 1])[None], (c[:, 1] + h[:, 1])[None])
    assert np.allclose(fresh, 0.75 / np.pi * love, rtol=1e-9, atol=1e-12 * abs(love).max())


def test_the_block_cache_keeps_within_its_budget():
    from tactcad.mechanics.contact import _BlockCache

    cache = _BlockCache(3 * 800)
    for k in range(5):
        cache.put(k, np.full(100, float(k)))  # 800 bytes each
    assert cache.bytes <= 3 * 800 and cache.get(0) is None and cache.get(4)[0] == 4.0
    with pytest.raises(ValueError):
        cache.get(4)[0] = 1.0  # kept blocks are read-only


def test_the_punch_solve_runs_its_dense_algebra_on_one_blas_thread(monkeypatch):
    """The collocation solve runs with BLAS on one thread (a second one's idle spinning
    tripled a design search's CPU time on a shared two-core machine), the process's thread
    count is restored after it, and the compliances are those of a threaded solve to
    round-off."""
    import contextlib

    from tactcad.mechanics import contact
    from tactcad.mechanics.blas_threads import blas_thread_counts, blas_threads
    from tactcad.mechanics.contact import solve_punches

    with blas_threads(2):
        if not blas_thread_counts() or set(blas_thread_counts()) != {2}:
            pytest.skip("no OpenBLAS whose thread count can be set to 2")
        seen = []
        solve = contact.solve_by_symmetry

        def watched(*args, **kwargs):
            seen.append(blas_thread_counts())
            return solve(*args, **kwargs)

        monkeypatch.setattr(contact, "solve_by_symmetry", watched)
        punches, sample = _two_rows(3), Sample(1.0, 0.5)
        one = solve_punches(punches, sample, 1.0, 8)
        assert seen and all(set(counts) == {1} for counts in seen)
        assert set(blas_thread_counts()) == {2}  # restored
        monkeypatch.setattr(contact, "single_threaded_blas", contextlib.nullcontext)
        threaded = solve_punches(punches, sample, 1.0, 8)
        assert set(seen[-1]) == {2}
    c = threaded.compliance_mm_per_N
    assert np.allclose(one.compliance_mm_per_N, c, rtol=1e-12, atol=1e-14 * abs(c).max())


@pytest.mark.parametrize("count", [0, -1, 1.5, True, "2"])
def test_a_blas_thread_count_outside_its_range_is_refused_by_name(count):
    from tactcad.mechanics.blas_threads import blas_threads

    with pytest.raises(ValueError, match=r"count = .*allowed an integer >= 1"):
        with blas_threads(count):
            pass
