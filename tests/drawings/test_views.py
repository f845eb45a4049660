"""Hidden-line views: the polygonal path for solids with free-form edges
draws what the exact path draws, and segment chaining is exact and
order-independent."""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.drawings.views import CAMERAS, project
from tactcad.kernel.hlr import _edge_points, _hlr, _poly_hlr, chain_segments, has_freeform_edges


def _cross_drilled_block():
    """A block with a channel along x and a hole from the top into it: the
    hole meets the channel on a free-form (B-spline) saddle curve."""
    import build123d as bd

    block = bd.Box(20, 10, 8)
    channel = bd.Cylinder(1.5, 30, rotation=(0, 90, 0))
    hole = bd.Pos(0, 0, 2) * bd.Cylinder(0.75, 4)
    return (block - channel - hole).solids()[0]


def test_chain_joins_segments_in_any_order():
    square = [((0, 0), (1, 0)), ((1, 0), (1, 1)), ((1, 1), (0, 1)), ((0, 1), (0, 0))]
    tail = [((5, 5), (6, 5)), ((7, 5), (6, 5))]  # one reversed
    segs = square + tail + [((0, 0), (1, 0))] + [((9, 9), (9, 9))]  # a duplicate, a point
    expected = None
    rng = random.Random(3)
    for _ in range(20):
        shuffled = [s if rng.random() < 0.5 else (s[1], s[0]) for s in segs]
        rng.shuffle(shuffled)
        lines = chain_segments(shuffled)
        got = sorted(sorted(map(tuple, line)) for line in lines)
        expected = expected or got
        assert got == expected
    assert len(expected) == 2  # the closed square and the open tail
    square_line = next(line for line in chain_segments(segs) if len(line) == 5)
    assert square_line[0] == square_line[-1]


def test_chain_stops_at_junctions():
    star = [((0, 0), (1, 0)), ((0, 0), (0, 1)), ((0, 0), (-1, 0))]
    assert sorted(len(line) for line in chain_segments(star)) == [2, 2, 2]


def test_analytic_parts_keep_the_exact_path(plan):
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.solids.cache import PartCache

    cache = PartCache(plan)
    for spec in array_parts(plan).values():
        if spec.builder in ("element", "spacer", "clamp_plate"):
            assert not has_freeform_edges(cache.solid(spec)), spec.name


@pytest.mark.parametrize("view", sorted(CAMERAS))
def test_polygonal_view_draws_what_the_exact_view_draws(view):
    """Every point of the exact view's visible edges lies within the line
    width (0.02 mm on this 20 mm part, far finer than a drawn line) of the
    polygonal view's visible edges, and the other way round."""
    import numpy as np
    from scipy.spatial import cKDTree

    from tactcad.drawings.views import _resample

    solid = _cross_drilled_block()
    assert has_freeform_edges(solid)
    step = 0.01
    exact_vis, _ = _hlr(solid, *CAMERAS[view])
    exact = [_edge_points(e, step) for e in exact_vis]
    poly, _ = _poly_hlr(solid, *CAMERAS[view], step)

    def cloud(lines):
        return np.array([q for line in lines for q in _resample(line, step)])

    a, b = cloud(exact), cloud(poly)
    assert cKDTree(b).query(a)[0].max() < 0.02
    assert cKDTree(a).query(b)[0].max() < 0.02


def test_free_form_solid_view_is_the_same_every_time():
    solid = _cross_drilled_block()
    first = project(solid, "left")
    again = project(solid, "left")
    assert (first.visible, first.hidden, first.bbox) == (again.visible, again.hidden, again.bbox)
    assert first.visible and first.hidden


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.floats(-100, 100), st.floats(-100, 100)), min_size=1, max_size=8),
       st.floats(0.05, 50))
def test_resampled_array_is_the_resampled_polyline_to_the_last_bit(poly, step):
    """The hidden-line filter's array resampling gives every point exactly as
    the polyline resampling does, so a view keeps its bytes."""
    from tactcad.drawings.views import _resample, _resampled

    got = _resampled(poly, step)
    assert got.shape == (len(_resample(poly, step)), 2)
    assert got.tolist() == [list(p) for p in _resample(poly, step)]


def test_hidden_polylines_under_visible_ones_are_dropped_and_the_others_kept():
    from tactcad.drawings.views import _uncovered

    visible = [[(0.0, 0.0), (10.0, 0.0)]]
    under = [(1.0, 0.0), (9.0, 0.0)]
    beside = [(1.0, 0.0), (9.0, 0.5)]  # leaves the visible line by more than the spacing
    assert _uncovered([under, beside, [(2.0, 0.05)]], visible, 0.1) == [beside]
    assert _uncovered([under], [], 0.1) == [under] and _uncovered([], visible, 0.1) == []
