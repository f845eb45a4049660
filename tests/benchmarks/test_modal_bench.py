"""``tactcad bench modal``'s designs and its per-level summary (the figures
themselves are the benchmark's to print, not a test's)."""

from __future__ import annotations

import pytest

from tactcad.benchmarks.modal_bench import CORNERS, designs, summary


def test_the_designs_are_the_extreme_arms_and_the_domains_corners(plan):
    own = designs(plan, "own")
    assert [g.arm_length_mm for _, g, _ in own] == [4.0, 8.0]
    corners = designs(plan, "corners")
    assert len(corners) == len(CORNERS)
    assert all(m.density_g_per_cm3 > 0 for _, _, m in corners)
    assert {g.sheet_thickness_mm for _, g, _ in corners} == {0.5, 10.0}
    assert len(designs(plan, "all")) == len(own) + len(corners)


def test_the_summary_says_whether_each_error_lies_within_its_estimate():
    rows = [{"model": "closed-form", "seconds": 0.01, "error_vs_fem3d_rel": -0.02,
             "error_estimate_rel": 0.03},
            {"model": "closed-form", "seconds": 0.03, "error_vs_fem3d_rel": 0.01,
             "error_estimate_rel": 0.03},
            {"model": "fem2d", "seconds": 1.0, "error_vs_fem3d_rel": -0.05,
             "error_estimate_rel": 0.04},
            {"model": "fem3d", "seconds": 20.0, "error_vs_fem3d_rel": 0.0,
             "error_estimate_rel": 0.001}]
    cf, f2, f3 = summary(rows)
    assert cf["n"] == 2 and cf["time_per_element_s"] == pytest.approx(0.02)
    assert cf["max_error_vs_fem3d_rel"] == pytest.approx(0.02) and cf["within_estimate"]
    assert cf["mean_error_vs_fem3d_rel"] == pytest.approx(0.015)
    assert f2["within_estimate"] is False
    assert f3["within_estimate"] is None  # the reference
