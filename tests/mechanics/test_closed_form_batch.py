"""The vectorised kernel of the corrected closed form gives the element-level path's K (the
compliance of closed_form.py, the correction's factor on its shares, the layer term of
bonded_layer.py) to rounding over random designs across the domain, block by block, for
scalar and per-design moduli, and refuses bad input naming the field."""

from __future__ import annotations

import dataclasses
import re
import threading
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.design.array_plan import EXAMPLES, load_design
from tactcad.mechanics.bonded_layer import with_gauge_layer
from tactcad.mechanics.closed_form import closed_form_compliance, correction_coordinates
from tactcad.mechanics.closed_form_batch import BLOCK, arctan_unit, corrected_stiffness_batch
from tactcad.mechanics.correction import IDENTITY, load_correction

EXAMPLE_NAMES = ("macro_array", "ti_array_2x3", "grasper_jaw_10mm")
_PLANS = {name: load_design(EXAMPLES / name / f"{name}.toml") for name in EXAMPLE_NAMES}


def element_path_k(t, R, a, E, g, nu, correction):
    """The oracle: K (N/mm) composed of the element-level functions, step by step."""
    b = g.sheet_thickness_mm
    parts = closed_form_compliance(t, R, a, arm_height_mm=g.arm_height_mm,
                                   tip_width_mm=g.tip_width_mm, tip_height_mm=g.tip_height_mm,
                                   E=E, nu=nu, b=b)
    factor = correction.factor(**correction_coordinates(parts, t, R, b, nu))
    return with_gauge_layer(factor / parts.total, g, t, R, a, E)


def random_designs(g, n, seed, modulus_MPa, per_design_modulus):
    """Webs 0.03-1 mm, t/R 0.05-10 (log-uniform), levers from the shortest the tip allows
    to 20 mm longer, the modulus fixed or +-50 % per design."""
    rng = np.random.default_rng(seed)
    t = rng.uniform(0.03, 1.0, n)
    R = t / np.exp(rng.uniform(np.log(0.05), np.log(10.0), n))
    a = R + g.tip_width_mm / 2 + rng.uniform(0.0, 20.0, n)
    E = modulus_MPa * rng.uniform(0.5, 1.5, n) if per_design_modulus else modulus_MPa
    return t, R, a, E


@settings(max_examples=30, deadline=None)
@given(name=st.sampled_from(EXAMPLE_NAMES), gauge=st.booleans(),
       per_design_modulus=st.booleans(), identity=st.booleans(),
       n=st.integers(1, 3000), seed=st.integers(0, 2 ** 32 - 1),
       grid_length_mm=st.floats(0.2, 6.0), nu=st.floats(0.05, 0.45))
def test_the_kernel_gives_the_element_paths_k_over_random_designs(
        name, gauge, per_design_modulus, identity, n, seed, grid_length_mm, nu):
    plan = _PLANS[name]
    g = plan.element(1).geometry
    g = dataclasses.replace(g, gauge=dataclasses.replace(g.gauge, grid_length_mm=grid_length_mm)) \
        if gauge else g.bare()
    corr = IDENTITY if identity else load_correction()
    t, R, a, E = random_designs(g, n, seed, plan.material.youngs_modulus_MPa, per_design_modulus)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        want = element_path_k(t, R, a, E, g, nu, corr)
    got = corrected_stiffness_batch(t, R, a, E, g, nu, corr)
    assert got.shape == want.shape
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=0)


def test_many_blocks_a_grid_and_an_output_array_give_the_same_k():
    plan = _PLANS["macro_array"]
    g, mat, corr = plan.element(1).geometry, plan.material, load_correction()
    t, R, a, E = random_designs(g, 2 * BLOCK + 7, 5, mat.youngs_modulus_MPa, True)
    want = element_path_k(t, R, a, E, g, mat.poisson_ratio, corr)
    out = np.full(t.shape, np.nan)
    got = corrected_stiffness_batch(t, R, a, E, g, mat.poisson_ratio, corr, out=out)
    assert got is out
    np.testing.assert_allclose(out, want, rtol=1e-12, atol=0)
    # a grid of webs x levers by broadcasting, one radius for all
    webs, arms = np.linspace(0.1, 0.5, 7)[:, None], np.linspace(3.0, 9.0, 5)[None, :]
    grid = corrected_stiffness_batch(webs, 0.6, arms, mat.youngs_modulus_MPa, g,
                                     mat.poisson_ratio, corr)
    assert grid.shape == (7, 5)
    np.testing.assert_allclose(grid, element_path_k(webs, 0.6, arms, mat.youngs_modulus_MPa,
                                                    g, mat.poisson_ratio, corr), rtol=1e-12)
    scalar = corrected_stiffness_batch(0.25, 0.5, 6.0, mat.youngs_modulus_MPa, g,
                                       mat.poisson_ratio, corr)
    assert np.ndim(scalar) == 0 and float(scalar) == pytest.approx(float(
        element_path_k(0.25, 0.5, 6.0, mat.youngs_modulus_MPa, g, mat.poisson_ratio, corr)),
        rel=1e-12)


def test_two_threads_at_once_each_get_their_own_k():
    plan = _PLANS["ti_array_2x3"]
    g, mat, corr = plan.element(1).geometry, plan.material, load_correction()
    designs = [random_designs(g, BLOCK + 100, seed, mat.youngs_modulus_MPa, False)
               for seed in (1, 2)]
    want = [corrected_stiffness_batch(*d[:3], d[3], g, mat.poisson_ratio, corr) for d in designs]
    got = [None, None]

    def run(i):
        for _ in range(20):
            got[i] = corrected_stiffness_batch(*designs[i][:3], designs[i][3], g,
                                               mat.poisson_ratio, corr)
            assert np.array_equal(got[i], want[i])

    threads = [threading.Thread(target=run, args=(i,)) for i in (0, 1)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert all(np.array_equal(x, y) for x, y in zip(got, want))


def test_blocks_on_two_threads_give_the_same_k_to_the_bit_and_raise_a_blocks_error():
    plan = _PLANS["grasper_jaw_10mm"]
    g, mat, corr = plan.element(1).geometry, plan.material, load_correction()
    t, R, a, E = random_designs(g, 3 * BLOCK + 11, 9, mat.youngs_modulus_MPa, True)
    one = corrected_stiffness_batch(t, R, a, E, g, mat.poisson_ratio, corr)
    two = corrected_stiffness_batch(t, R, a, E, g, mat.poisson_ratio, corr, threads=2)
    assert np.array_equal(one, two)
    np.testing.assert_allclose(two, element_path_k(t, R, a, E, g, mat.poisson_ratio, corr),
                               rtol=1e-12, atol=0)
    short = a.copy()
    short[2 * BLOCK + 3] = R[2 * BLOCK + 3]  # a lever too short in the third block only
    with pytest.raises(ValueError, match="arm_length_mm must be >= notch_radius_mm"):
        corrected_stiffness_batch(t, R, short, E, g, mat.poisson_ratio, corr, threads=2)


@pytest.mark.parametrize("threads", [0, -1, 65, 1.5, True, "2"])
def test_a_thread_count_outside_its_range_is_refused(threads):
    plan = _PLANS["macro_array"]
    g, mat = plan.element(1).geometry, plan.material
    with pytest.raises(ValueError, match=r"threads = .*allowed an integer from 1 to 64"):
        corrected_stiffness_batch([0.2], [0.5], [6.0], mat.youngs_modulus_MPa, g,
                                  mat.poisson_ratio, load_correction(), threads=threads)


def test_the_arctan_holds_numpys_to_three_ulp():
    x2 = np.concatenate([np.linspace(0.0, 1.0, 100_001), np.geomspace(1e-12, 1.0, 1001)])
    want = np.arctan(np.sqrt(x2))
    got = arctan_unit(x2)
    ulp = np.spacing(np.maximum(want, np.finfo(float).tiny))
    assert np.max(np.abs(got - want) / ulp) <= 3.0
    assert got[0] == 0.0 and got[100_000] == pytest.approx(np.pi / 4, rel=1e-15)


@pytest.mark.parametrize("field, args, message", [
    ("web_mm", dict(t=[0.2, -0.1]), "web_mm must be finite and > 0"),
    ("notch_radius_mm", dict(R=[0.5, np.nan]), "notch_radius_mm must be finite and > 0"),
    ("arm_length_mm", dict(a=np.inf), "arm_length_mm must be finite and > 0"),
    ("E", dict(E=0.0), "E must be finite and > 0"),
    ("nu", dict(nu=0.5), "allowed -1 < nu < 0.5"),
    ("lever", dict(a=0.6), "arm_length_mm must be >= notch_radius_mm + tip_width_mm / 2"),
])
def test_bad_input_is_refused_naming_the_field(field, args, message):
    plan = _PLANS["macro_array"]
    g, mat = plan.element(1).geometry, plan.material
    v = dict(t=[0.2, 0.25], R=[0.5, 0.5], a=[6.0, 6.0], E=mat.youngs_modulus_MPa,
             nu=mat.poisson_ratio)
    v.update(args)
    with pytest.raises(ValueError, match=re.escape(message)):
        corrected_stiffness_batch(v["t"], v["R"], v["a"], v["E"], g, v["nu"], load_correction())


def test_the_benchs_two_thread_pass_gives_its_one_thread_pass_values():
    from tactcad.benchmarks.bench_scale import closed_form_rate

    plan = _PLANS["macro_array"]
    rate_one, k_one = closed_form_rate(plan, n=2 * BLOCK + 5, repeat=1, threads=1)
    rate_two, k_two = closed_form_rate(plan, n=2 * BLOCK + 5, repeat=1, threads=2)
    assert rate_one > 0 and rate_two > 0
    assert np.array_equal(k_one, k_two) and k_one.shape == (2 * BLOCK + 5,)
