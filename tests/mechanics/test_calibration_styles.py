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


def test_the_legend_stands_beside_the_axes_and_covers_no_curve():
    """However many elements are drawn, the legend is right of the axes, not over them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tactcad.paper.figures import place_legend

    fig, ax = plt.subplots(figsize=(6.0, 4.0), dpi=120)
    for n in range(10):
        ax.plot([0.5, 1, 2, 4], [1 + 0.1 * n, 1.2 + 0.1 * n, 1.5, 2.0 - 0.05 * n], "o-",
                label=f"element {n + 1}")
    legend = place_legend(ax)
    fig.canvas.draw()
    box, axes = legend.get_window_extent(), ax.get_window_extent()
    assert box.x0 >= axes.x1  # beside, not on the plot
    plt.close(fig)
