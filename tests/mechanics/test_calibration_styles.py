"""The calibration plot tells every element apart: a 2 x 8 strip's 16 elements in 16
colours (10 repeated over 16 before), and past the colour table by marker."""

from __future__ import annotations

import pytest

from tactcad.paper.figures import distinct_styles


@pytest.mark.parametrize("n", [1, 10, 16, 20, 24, 60])
def test_every_element_of_the_plot_has_a_style_of_its_own(n):
    styles = distinct_styles(n)
    assert len(styles) == n and len(set(styles)) == n
    assert len({colour for colour, _ in styles}) == min(n, 20)
