"""A piezoresistive cantilever's read-out: the stress its root resistor reads (against the
beam's M c / I), the bridge's output, Johnson and Hooge noise (against their definitions and a
numerical integral of the 1/f spectrum)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from tactcad.products.silicon_die.mechanics.piezoresistor import (BOLTZMANN_J_PER_K,
                                                                  PiezoCantilever, carriers_in,
                                                                  force_resolution_N,
                                                                  hooge_noise_V, johnson_noise_V)
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


# --- against Doll and Pruitt's model, on a cantilever they state ------------------------------
#: Harley and Kenny's 89 nm epitaxial cantilever as the test of Doll and Pruitt's PiezoD states
#: it (MicrosystemsLab/PiezoD, matlab/tests/cantileverEpitaxyTest.m; the model of Park, Doll,
#: Rastegar and Pruitt, "Piezoresistive cantilever performance, Part I", J. Microelectromech.
#: Syst. 19(1), 2010): l 300 um, w 44 um, t 89 nm, l_pr 45 um (its U: legs w / 2 wide, a 2 um
#: gap), boron 4e19 cm^-3 in the top 30 nm, 5 V on a quarter bridge, 10-1000 Hz, two 170 ohm
#: contacts; and the figures that test expects (to 1 %).
HARLEY = {"l_um": 300.0, "w_um": 44.0, "t_um": 0.089, "l_pr_um": 45.0, "gap_um": 2.0,
          "bias_V": 5.0, "contact_ohm": 170.0, "pi_max_per_Pa": 72e-11}
PIEZOD_EXPECTS = {"k_N_per_m": 4.85384e-05, "R_ohm": 6147.41, "Rs_ohm_per_sq": 946.393,
                  "Nz_per_m2": 1.2e18, "beta_star": 0.315295, "S_V_per_N": 800764.0}


def test_the_sensitivity_agrees_with_doll_and_pruitts_model_on_harleys_cantilever():
    """Our quarter-bridge sensitivity V/4 pi_l beta* sigma_avg gamma, given the figures PiezoD
    states (beta* with its P at the resistor's temperature, sheet and total resistance),
    within 5 % of PiezoD's S. PiezoD divides dR by the whole R, contacts held, and multiplies
    by gamma = R / (R + 2 R_c) again; gamma here is the strained legs' share of the whole R,
    the contacts counted once, so S is compared with that second factor taken out. What is
    left is the far bar's transverse pull (p-type pi_t = -pi_l), about 1 %, not modelled."""
    h, e = HARLEY, PIEZOD_EXPECTS
    w_pr = h["w_um"] / 2
    strained_ohm = 2 * e["Rs_ohm_per_sq"] * h["l_pr_um"] / w_pr
    beam = PiezoCantilever(h["l_um"], h["w_um"], h["t_um"], h["l_pr_um"], h["pi_max_per_Pa"],
                           depth_efficiency=e["beta_star"],
                           strained_share=strained_ohm / e["R_ohm"])
    contacts_gamma = e["R_ohm"] / (e["R_ohm"] + 2 * h["contact_ohm"])
    ours = beam.bridge_sensitivity_V_per_N(h["bias_V"])
    assert ours == pytest.approx(e["S_V_per_N"] / contacts_gamma, rel=0.05)
    assert ours > e["S_V_per_N"] / contacts_gamma  # the bar's pull is negative, and left out


def test_harleys_stiffness_carriers_and_hooge_noise_by_the_same_equations():
    """k = E w t^3 / (4 l^3) at PiezoD's 169 GPa; N z = N x_j; the Hooge noise of PiezoD's
    integrated_noise, alpha V^2 / (4 N) ln(f2 / f1) for one strained arm, equals ours at V / 2
    across the resistor, its carriers over the U's area w_pr (2 l_pr + w + gap)."""
    from tactcad.products.silicon_die.design.mems_die import clamped_beam_stiffness_N_per_mm

    h, e = HARLEY, PIEZOD_EXPECTS
    k = clamped_beam_stiffness_N_per_mm(169e3, h["w_um"], h["t_um"], h["l_um"]) * 1e3  # N/m
    assert k == pytest.approx(e["k_N_per_m"], rel=0.01)
    nz = 4e19 * 30e-7 * 1e4  # cm^-3 x cm -> m^-2
    assert nz == pytest.approx(e["Nz_per_m2"], rel=1e-9)
    w_pr = h["w_um"] / 2
    carriers = nz * w_pr * 1e-6 * (2 * h["l_pr_um"] + h["w_um"] + h["gap_um"]) * 1e-6
    assert carriers == pytest.approx(carriers_in(4e19, (2 * h["l_pr_um"] + h["w_um"]
                                                        + h["gap_um"]), w_pr, 0.030), rel=1e-9)
    piezod = math.sqrt(1e-5 * h["bias_V"] ** 2 / (4 * carriers) * math.log(1000 / 10))
    assert hooge_noise_V(1e-5, h["bias_V"] / 2, carriers, 10, 1000) == pytest.approx(piezod,
                                                                                   rel=1e-12)


def test_the_sensitivitys_temperature_coefficient_is_richters_slope():
    """Lightly doped, P(N, T) is Theta^-0.9: d ln P / dT = -0.9 / 300 K at 300 K; doping
    flattens it (Richter et al. 2008, Fig. 4's trend)."""
    from tactcad.products.silicon_die.mechanics.piezoresistor import sensitivity_temperature_coefficient_per_K as tcs

    assert tcs(1e14) == pytest.approx(-0.9 / 300, rel=1e-3)
    assert tcs(1e14) < tcs(1e19) < tcs(1e20) < 0


@pytest.mark.parametrize("temperature_K", [250.0, 500.0])
def test_the_tcr_holds_to_the_ends_of_the_mobilitys_range(temperature_K):
    """At the ends of Arora's 250-500 K the TCR takes a one-sided difference (a centred one
    would ask the fit half a kelvin outside it); it lies beside the TCR a kelvin inside."""
    from tactcad.products.silicon_die.mechanics.piezoresistor import resistor_tcr_per_K

    inside = temperature_K + (1.0 if temperature_K < 300 else -1.0)
    at_end = resistor_tcr_per_K(1e19, temperature_K)
    assert at_end > 0 and at_end == pytest.approx(resistor_tcr_per_K(1e19, inside), rel=0.02)
    outside = temperature_K + (-0.1 if temperature_K < 300 else 0.1)
    with pytest.raises(ValueError, match="250 ... 500 K"):  # beyond the fit it is refused
        resistor_tcr_per_K(1e19, outside)


def test_the_dies_readout_states_its_sensitivitys_drift_and_self_heating():
    from tactcad.products.silicon_die.design.mems_die import die_plan
    from tactcad.products.silicon_die.mechanics.piezoresistor import SILICON_CONDUCTIVITY_W_PER_MK, die_readout
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.studies.inverse_design import Targets

    plan = die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"))
    r = die_readout(plan, bias_V=2.0)
    beam = plan.beams[0]
    power = 1.0 / r["resistance_ohm"]  # (2 V / 2)^2 / R
    expected = power * plan.resistor_length_um * 1e-6 / (
        2 * SILICON_CONDUCTIVITY_W_PER_MK * beam.width_um * 1e-6 * beam.thickness_um * 1e-6)
    assert r["self_heating_K"] == pytest.approx(expected, rel=1e-12)
    assert -0.004 < r["sensitivity_tc_per_K"] < -0.001
    assert any("self-heating" in a for a in r["assumptions"])
    doubled = die_readout(plan, bias_V=4.0)  # heating goes as the bias squared
    assert doubled["self_heating_K"] == pytest.approx(4 * r["self_heating_K"], rel=1e-12)


def test_each_rows_full_scale_signal_is_at_the_force_strength_rates_it_for():
    """One name, one quantity: a row's full-scale signal is its sensitivity times the most its
    beam carries in use, strength's ``rated_force_N`` (a measuring beam carries less than the
    die's rated force while its reference reads up to it)."""
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.design.mems_die import die_plan
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout
    from tactcad.products.silicon_die.studies.die_reports import strength_report
    from tactcad.studies.inverse_design import Targets

    plan = die_plan(Targets(6.0, (1.0, 8.0), 0.008), jaw_room("5"))
    rows = die_readout(plan)["rows"]
    rated = {r["role"]: r["rated_force_N"] for r in strength_report(plan)[0]["rows"]}
    assert rated["measuring"] < 0.9 * rated["reference"]  # the two differ: the check can fail
    for role, row in rows.items():
        assert row["full_scale_signal_V"] == pytest.approx(
            row["sensitivity_V_per_N"] * rated[role], rel=1e-12), role
