"""The array picture's anti-aliasing filter: exact integer means, whatever the
supersampling, so the PNG's bytes depend on the scene only."""

import numpy as np
import pytest

from tactcad.export.render import box_filter


@pytest.mark.parametrize("k", [1, 2, 3, 17])
def test_box_filter_is_the_rounded_mean_of_each_block(k):
    rng = np.random.default_rng(k)
    px = rng.integers(0, 256, (5 * k, 7 * k, 3), dtype=np.uint8)
    blocks = px.reshape(5, k, 7, k, 3).astype(np.int64)
    expected = np.floor(blocks.mean(axis=(1, 3)) + 0.5).astype(np.uint8)
    assert np.array_equal(box_filter(px, k), expected)


def test_box_filter_of_a_full_white_block_stays_white():
    px = np.full((32, 32, 3), 255, dtype=np.uint8)  # 255 * 16 * 16 = 65280: the largest 16-bit sum
    assert (box_filter(px, 16) == 255).all()
