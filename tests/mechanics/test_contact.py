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
