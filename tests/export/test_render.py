"""The array picture: the scan-line z-buffer against a pixel-by-pixel
reference, its window against the full raster, the sparse outline search
against the dense one, and the anti-aliasing as exact integer means, so the
PNG's bytes depend on the scene only."""

from pathlib import Path

import numpy as np
import pytest

from tactcad.export.render import (FIT_CONTEXT, FIT_LEAST, _camera, _depth_planes, _screen,
                                   filtered_lookup, framed_extent, outline_mask, raster_window,
                                   rasterise)


def _reference_raster(tris, size_px, cam, margin=0.06):
    """Pixel by pixel: a pixel centre is covered between the two edges its row
    crosses (half-open in y and in x); strictly nearer replaces, so ties keep
    the earlier triangle."""
    w, h = size_px
    X, Y, Z = _screen(tris, size_px, cam, margin)
    ok, a, b, c = _depth_planes(X, Y, Z)
    yc = np.arange(h)[:, None] + 0.5
    xc = np.arange(w)[None, :] + 0.5
    best, best_z = np.full((h, w), -1), np.full((h, w), -np.inf)
    for i in np.nonzero(ok)[0]:
        lo, hi, crossings = np.full((h, 1), np.inf), np.full((h, 1), -np.inf), np.zeros((h, 1))
        for p, q in ((0, 1), (1, 2), (2, 0)):
            ya, yb, xa, xb = Y[i, p], Y[i, q], X[i, p], X[i, q]
            cross = (min(ya, yb) <= yc) & (yc < max(ya, yb))
            x = xa + (yc - ya) * (xb - xa) / (yb - ya if yb != ya else 1.0)
            lo = np.where(cross, np.minimum(lo, x), lo)
            hi = np.where(cross, np.maximum(hi, x), hi)
            crossings += cross
        z = a[i] * xc + b[i] * yc + c[i]
        nearer = (crossings == 2) & (lo <= xc) & (xc < hi) & (z > best_z)
        best[nearer], best_z[nearer] = i, z[nearer]
    return best


def _scene(seed: int, n: int = 40) -> np.ndarray:
    """Random triangles (mm) crossing each other in depth, two sharing an
    edge, one with no area on screen and one repeated (a tie in depth)."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform(-10, 10, (n, 1, 3))
    tris = centres + rng.uniform(-4, 4, (n, 3, 3))
    quad = np.array([[0, 0, 0], [6, 0, 0], [6, 5, 1], [0, 5, 1.0]])
    flat = np.array([[[1, 1, 1], [2, 2, 2], [3, 3, 3.0]]])  # a line
    return np.concatenate([tris, quad[None, [0, 1, 2]], quad[None, [0, 2, 3]], flat, tris[:1]])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_scanline_z_buffer_is_the_pixel_by_pixel_one(seed):
    tris, cam = _scene(seed), _camera(28.0, -58.0)
    expected = _reference_raster(tris, (96, 64), cam)
    assert (expected >= 0).any() and len(np.unique(expected)) > 10
    assert np.array_equal(rasterise(tris, (96, 64), cam), expected)


def test_edges_through_pixel_centres_follow_the_half_open_rule():
    """Vertices on pixel centres (8 px per mm, looking down z): pixels on a
    shared edge or a row through a vertex are decided as pixel by pixel."""
    rng = np.random.default_rng(11)
    cam = _camera(0.0, 0.0)  # screen x = x, screen y = y, depth = z (mm)
    centre = lambda col, row: ((col + 0.5) / 8, (63.5 - row) / 8)  # noqa: E731
    lattice = [[(*centre(*rng.integers(0, 95, 1), *rng.integers(0, 63, 1)), z) for _ in range(3)]
               for z in rng.uniform(-3, 3, 30)]
    fan = [[(*centre(55, 22), 4.0), (*centre(c0, r0), 4.0), (*centre(c1, r1), 4.0)]
           for (c0, r0), (c1, r1) in [((10, 10), (70, 12)), ((70, 12), (80, 50)), ((80, 50), (10, 10))]]
    flat = [[(*centre(5, 40), 5.0), (*centre(30, 55), 5.0), (*centre(5, 55), 5.0)],  # flat bottom
            [(*centre(84, 40), 5.0), (*centre(94, 40), 5.0), (*centre(90, 60), 5.0)]]  # flat top
    extent = [[(0, 0, -9.0), (12, 0, -9.0), (12, 8, -9.0)]]  # 96 x 64 px exactly with no margin
    tris = np.array(lattice + fan + flat + extent)
    expected = _reference_raster(tris, (96, 64), cam, margin=0.0)
    assert np.array_equal(rasterise(tris, (96, 64), cam, margin=0.0), expected)
    # the fan in front covers its outer triangle without gaps or double rows
    outer = np.array([[(*centre(10, 10), 4.0), (*centre(70, 12), 4.0), (*centre(80, 50), 4.0)]])
    whole = rasterise(np.concatenate([outer, tris[-1:]]), (96, 64), cam, margin=0.0) == 0
    assert whole.sum() > 500 and np.array_equal(np.isin(expected, [30, 31, 32]), whole)


@pytest.mark.parametrize("align", [1, 2, 4])
def test_window_holds_every_covered_pixel_on_whole_blocks(align):
    tris, cam = _scene(7) * 0.5, _camera(35.0, 20.0)
    full = _reference_raster(tris, (96, 64), cam)
    win = raster_window(tris, (96, 64), cam, align=align, chunk=500)  # many chunks
    h, w = win.tri.shape
    assert win.top % align == win.left % align == h % align == w % align == 0
    pasted = np.full_like(full, -1)
    pasted[win.top: win.top + h, win.left: win.left + w] = win.tri
    assert np.array_equal(pasted, full)
    # one pixel of background around the covered box, where the raster allows
    rows, cols = np.nonzero(full >= 0)
    assert win.top <= rows.min() - 1 and win.top + h >= rows.max() + 2
    assert win.left <= cols.min() - 1 and win.left + w >= cols.max() + 2


def test_nothing_to_draw_gives_an_empty_window():
    assert raster_window(np.zeros((0, 3, 3)), (32, 20), _camera(28.0, -58.0)).tri.size == 0


def _dense_outlines(tri, inst_id, normals, cos_crease):
    """The outline rule over whole shifted rasters."""
    h, w = tri.shape
    inst_px = np.where(tri >= 0, inst_id[np.maximum(tri, 0)], -1)
    edge = np.zeros((h, w), dtype=bool)
    for dy, dx in ((0, 1), (1, 0), (1, 1)):
        ta, tb = tri[: h - dy, : w - dx], tri[dy:, dx:]
        e = inst_px[: h - dy, : w - dx] != inst_px[dy:, dx:]
        crease = (~e) & (ta != tb) & (ta >= 0)
        crease &= (normals[ta] * normals[tb]).sum(-1) < cos_crease
        edge[: h - dy, : w - dx] |= e | crease
    return edge


def test_outlines_found_where_the_triangle_changes_are_the_dense_rule():
    rng = np.random.default_rng(3)
    normals = rng.normal(size=(30, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    inst_id = rng.integers(0, 4, 30).astype(np.int32)
    # blocks of one triangle each, so most neighbours agree, with background
    tri = np.kron(rng.integers(-1, 30, (12, 16)), np.ones((3, 3), dtype=np.int64)).astype(np.int32)
    edge = outline_mask(tri, inst_id, normals)
    assert 0 < edge.sum() < edge.size
    assert np.array_equal(edge, _dense_outlines(tri, inst_id, normals, np.cos(np.radians(25.0))))


@pytest.mark.parametrize("k", [1, 2, 3, 17])
def test_filtered_lookup_is_the_rounded_mean_of_each_block(k):
    rng = np.random.default_rng(k)
    table = rng.integers(0, 256, (9, 3), dtype=np.uint8)
    index = rng.integers(0, 9, (5 * k, 7 * k))
    blocks = table[index].reshape(5, k, 7, k, 3).astype(np.int64)
    expected = np.floor(blocks.mean(axis=(1, 3)) + 0.5).astype(np.uint8)
    assert np.array_equal(filtered_lookup(table, index, k), expected)


def test_filtered_lookup_of_a_full_white_block_stays_white():
    table = np.full((1, 3), 255, dtype=np.uint8)  # 255 * 16 * 16 = 65280: the largest 16-bit sum
    assert (filtered_lookup(table, np.zeros((32, 32), dtype=np.intp), 16) == 255).all()


@pytest.mark.slow
def test_picture_is_the_same_from_kept_meshes_as_from_a_fresh_run(tmp_path):
    """Under ``tactcad watch`` the picture reads part meshes kept from earlier
    runs, of solids other jobs have meshed before; a fresh run meshes them
    itself. Same input, same bytes."""
    from tactcad.catalogue.files import ARRAY_PNG
    from tactcad.design.project import load_project
    from tactcad.export.jobs import image_jobs
    from tactcad.export.job import Run
    from tactcad.export.live_parts import LiveParts
    from tactcad.solids.tessellation import tessellate
    from tactcad.store import Store

    project = load_project(Path(__file__).resolve().parents[2] / "hardware/ti_array_2x3/ti_array_2x3.toml")
    pictures = []
    for warm in (False, True):
        run = Run(project, tmp_path / str(warm), lambda s: None, Store(None))
        (run.staging / ARRAY_PNG).parent.mkdir(parents=True)
        if warm:
            run.parts = LiveParts(project.plan, {}, {})
            specs, _ = run.array
            for spec in specs.values():
                tessellate(run.parts.solid(spec), 0.2)  # a coarser mesh made first, elsewhere
                run.parts.mesh(spec)
        image_jobs(run, [])[0].make(run)
        pictures.append((run.staging / ARRAY_PNG).read_bytes())
    assert pictures[0] == pictures[1]


def test_a_picture_framed_on_a_few_parts_shows_them_with_context_within_the_model():
    """A build step's picture frames its new parts, not the whole rig: their box
    with context around it, at least a share of the whole, never beyond it."""
    rng = np.random.default_rng(3)
    xy = rng.uniform(0.0, 100.0, (200, 3, 2))  # the rig on screen, 100 x 100
    xy[:4] = rng.uniform([60.0, 20.0], [70.0, 24.0], (4, 3, 2))  # a step's small parts
    fit = np.zeros(len(xy), dtype=bool)
    fit[:4] = True
    whole = framed_extent(xy)
    lo, hi = framed_extent(xy, fit)
    mine = xy[:4].reshape(-1, 2)
    assert np.all(lo <= mine.min(axis=0)) and np.all(hi >= mine.max(axis=0))  # shown whole
    assert np.all(lo >= whole[0]) and np.all(hi <= whole[1])  # no empty room past the rig
    span = np.ptp(mine, axis=0).max()
    assert np.all(hi - lo >= np.minimum(np.ptp(mine, axis=0) + 2 * FIT_CONTEXT * span,
                                        whole[1] - whole[0]) - 1e-9)  # context around them
    assert np.all(hi - lo >= FIT_LEAST * (whole[1] - whole[0]) - 1e-9)
    assert np.all(hi - lo < 0.5 * (whole[1] - whole[0]))  # they fill the picture, not the rig
    X, _, _ = _screen(np.concatenate([xy, np.zeros((len(xy), 3, 1))], axis=2), (400, 300),
                      np.eye(3), 0.0, fit)
    assert X[:4].min() >= 0 and X[:4].max() <= 400 and (X < 0).any()  # the rest is cut off
