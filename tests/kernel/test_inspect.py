"""The kernel's measurements of solids: triangle meshes."""

import numpy as np

import tactcad
from tactcad.kernel.inspect import triangulate

#: flat and notched faces, a hex socket and thread-free shank, a bore with
#: balls, a pocketed plastic part
KINDS = ("element_a4mm", "bolt_M2x30", "bearing_624ZZ", "cart")


def test_a_mesh_is_build123ds_tessellation_to_the_bit():
    """The arrays hold build123d's own ``tessellate`` result (same faces, nodes,
    winding of reversed faces) for parts of every kind, also when moved and turned."""
    import build123d as bd

    parts = tactcad.load().parts
    for name in KINDS:
        for solid in (parts[name], parts[name].moved(bd.Location((1.5, -2, 3), (0, 1, 1), 30))):
            for tolerance in (0.01, 0.005):
                verts, tris = triangulate(solid, tolerance, 0.2)
                ref_verts, ref_tris = solid.tessellate(tolerance, 0.2)
                assert verts.dtype == np.float64 and tris.dtype == np.int64
                assert np.array_equal(verts, np.array([tuple(v) for v in ref_verts])), name
                assert np.array_equal(tris, np.array(ref_tris)), name
