"""A piezoresistive cantilever's read-out: the stress its root resistor reads (against the
beam's M c / I), the bridge's output, Johnson and Hooge noise (against their definitions and a
numerical integral of the 1/f spectrum)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from tactcad.mechanics.piezoresistor import (BOLTZMANN_J_PER_K, PiezoCantilever, carriers_in,
                                             force_resolution_N, hooge_noise_V, johnson_noise_V)
from tactcad.vocabulary.crystal import SILICON_P_TYPE, WAFER_110

PI_L = SILICON_P_TYPE.longitudinal(WAFER_110) * 1e-11  # 1/Pa
BEAM = PiezoCantilever(length_um=500.0, width_um=50.0, thickness_um=5.0,
                       resistor_length_um=100.0, pi_longitudinal_per_Pa=PI_L,
                       depth_efficiency=0.8)


def test_the_resistor_reads_the_bending_stress_averaged_over_its_length():
    # M c / I of the section at each x, averaged numerically over the resistor
    w, t, length = 50e-6, 5e-6, 500e-6
    inertia, c = w * t ** 3 / 12, t / 2
    x = np.linspace(0.0, 100e-6, 20001)
    stress = (length - x) * c / inertia  # per newton
    assert BEAM.average_stress_Pa_per_N() == pytest.approx(np.mean(stress), rel=1e-6)
    root = PiezoCantilever(500.0, 50.0, 5.0, 1e-6, PI_L)
    assert root.average_stress_Pa_per_N() == pytest.approx(length * c / inertia, rel=1e-8)


def test_the_bridge_gives_a_quarter_of_the_bias_per_strained_arm():
    per_n = BEAM.resistance_change_per_N()
    assert per_n == pytest.approx(PI_L * BEAM.average_stress_Pa_per_N() * 0.8)
    quarter = BEAM.bridge_sensitivity_V_per_N(2.0)
    assert quarter == pytest.approx(2.0 / 4 * per_n)
    assert BEAM.bridge_sensitivity_V_per_N(2.0, active=4) == pytest.approx(4 * quarter)


def test_johnson_noise_of_10_kohm_at_300_k_in_1_hz_is_12_9_nv():
    assert johnson_noise_V(10e3, 300.0, 0.0, 1.0) == pytest.approx(12.87e-9, rel=1e-3)
    assert johnson_noise_V(10e3, 300.0, 1.0, 101.0) == pytest.approx(
        math.sqrt(4 * BOLTZMANN_J_PER_K * 300.0 * 10e3 * 100.0))


def test_hooge_noise_is_the_integral_of_its_one_over_f_spectrum():
    alpha, volts, n = 1e-6, 1.0, carriers_in(1e19, 100.0, 5.0, 0.5)
    assert n == pytest.approx(1e19 * 100e-4 * 5e-4 * 0.5e-4)
    psd = lambda f: alpha * volts ** 2 / (n * f)  # noqa: E731 (V^2/Hz)
    integral, _ = quad(psd, 1.0, 1000.0, epsabs=0.0, epsrel=1e-12, limit=200)
    assert hooge_noise_V(alpha, volts, n, 1.0, 1000.0) == pytest.approx(math.sqrt(integral),
                                                                        rel=1e-8)


def test_the_force_resolution_is_the_noise_over_the_sensitivity():
    noise = math.hypot(johnson_noise_V(10e3, 300.0, 1.0, 1000.0),
                       hooge_noise_V(1e-6, 1.0, 2.5e7, 1.0, 1000.0))
    dF = force_resolution_N(BEAM, 2.0, noise)
    assert dF * abs(BEAM.bridge_sensitivity_V_per_N(2.0)) == pytest.approx(noise)
    assert 1e-9 < dF < 1e-5  # nN to 10 uN: the range piezoresistive cantilevers resolve


@pytest.mark.parametrize("kwargs, words", [
    ({"thickness_um": 0.0}, "thickness_um"), ({"resistor_length_um": 600.0}, "at most"),
    ({"depth_efficiency": 1.5}, "depth_efficiency"), ({"length_um": math.nan}, "length_um")])
def test_a_cantilever_outside_its_meaning_is_refused_naming_the_value(kwargs, words):
    base = dict(length_um=500.0, width_um=50.0, thickness_um=5.0, resistor_length_um=100.0,
                pi_longitudinal_per_Pa=PI_L)
    with pytest.raises(ValueError, match=words):
        PiezoCantilever(**{**base, **kwargs})
    with pytest.raises(ValueError, match="band"):
        hooge_noise_V(1e-6, 1.0, 1e7, 0.0, 10.0)
    with pytest.raises(ValueError, match="active"):
        BEAM.bridge_sensitivity_V_per_N(2.0, active=3)
