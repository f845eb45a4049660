"""A piezoresistive cantilever's read-out: the resistance change of a resistor diffused at
the root of a silicon cantilever under a tip force, the bridge's output, and the noise that
sets its force resolution (the read-out a silicon die carries in place of a foil gauge).

The cantilever (length L from its clamped root to the tip force F, width w, thickness t)
carries a surface bending stress sigma(x) = 6 F (L - x) / (w t^2) at a distance x from the
root (Euler-Bernoulli). A resistor of length l_r along the beam from the root, its carriers in
a layer near the surface, reads the stress averaged over its length,
sigma_avg = 6 F (L - l_r / 2) / (w t^2), times the depth efficiency beta* (1 for carriers at
the surface, 0 at the neutral axis; Park, Doll, Rastegar and Pruitt, "Piezoresistive
cantilever performance, Part I", J. Microelectromech. Syst. 19(1), 2010, eq. 2-4), so
dR / R = pi_l P(N, T) sigma_avg beta* gamma (pi_l along the resistor at low doping:
:mod:`tactcad.vocabulary.crystal`). P(N, T) scales pi_l down with the doping N and the
temperature T (Richter, Pedersen, Brandbyge, Thomsen and Hansen, "Piezoresistance in p-type
silicon revisited", J. Appl. Phys. 104, 023715, 2008: :func:`piezoresistance_factor`); gamma
is the strained share of the resistance: the legs on the beam over the whole resistor with
its unstrained run onto the frame and its far bar (Park et al. 2010's gamma, the resistor's
share of the total, taken here on the resistor's own squares).

A Wheatstone bridge with ``active`` of its four arms strained (1: a quarter bridge, its
reference resistors on the die off the beam) gives V_out = V_bias active / 4 dR / R.

Noise over the band [f_lo, f_hi] (Hz), each as an rms voltage at the bridge output:

* Johnson noise of the bridge's resistance R (a quarter bridge's output sees R):
  v^2 = 4 k_B T R (f_hi - f_lo) (Nyquist, Phys. Rev. 32, 1928);
* Hooge 1/f noise of the active resistor with N carriers, biased at V_r across it:
  v^2 = alpha_H V_r^2 / N ln(f_hi / f_lo) (Hooge, Phys. Lett. A 29, 1969; alpha_H 1e-7 for
  annealed implants to 1e-4: Harley and Kenny, J. Microelectromech. Syst. 9(2), 2000);
* the instrumentation amplifier's voltage and current noise, each a white floor and a 1/f
  part stated at 1 Hz, its current noise through R / 2 at each input:
  v^2 = e_w^2 (f_hi - f_lo) + e_f^2 ln(f_hi / f_lo) + 2 (R/2)^2 (i_w^2 (f_hi - f_lo)
  + i_f^2 ln(f_hi / f_lo)) (:class:`Amplifier`; the form of Doll and Pruitt's PiezoD,
  ``cantilever.m``, ``integrated_noise``).

Units: N, m inside the formulas, inputs and outputs as named (um, V, ohm, K, Hz, 1/Pa).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

#: Boltzmann's constant (J/K, exact since the 2019 SI).
BOLTZMANN_J_PER_K = 1.380649e-23


@dataclass(frozen=True)
class PiezoCantilever:
    """A silicon cantilever with one diffused resistor at its root (um, 1/Pa).

    Attributes:
        length_um: root to the tip force.
        width_um, thickness_um: the beam's section.
        resistor_length_um: the resistor along the beam, from the root.
        pi_longitudinal_per_Pa: pi_l along the resistor at low doping (1/Pa: Smith's x 1e-11).
        depth_efficiency: beta*'s depth part, 0 ... 1 (carriers' depth below the surface).
        doping_factor: P(N, T), 0 ... 1 (:func:`piezoresistance_factor`).
        strained_share: gamma, 0 ... 1: the share of the resistance under the beam's stress.
    """

    length_um: float
    width_um: float
    thickness_um: float
    resistor_length_um: float
    pi_longitudinal_per_Pa: float
    depth_efficiency: float = 1.0
    doping_factor: float = 1.0
    strained_share: float = 1.0

    def __post_init__(self):
        for name in ("length_um", "width_um", "thickness_um", "resistor_length_um"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} = {value!r}: a finite length > 0 um")
        if self.resistor_length_um > self.length_um:
            raise ValueError(f"resistor_length_um = {self.resistor_length_um!r}: at most the "
                             f"beam's length {self.length_um!r} um")
        for name in ("depth_efficiency", "doping_factor", "strained_share"):
            value = getattr(self, name)
            if not 0.0 <= value <= 1.0:
                raise ValueError(f"{name} = {value!r}: 0 ... 1")

    def average_stress_Pa_per_N(self) -> float:
        """The surface bending stress averaged over the resistor, per newton at the tip (Pa/N):
        6 (L - l_r / 2) / (w t^2)."""
        um = 1e-6
        arm = (self.length_um - self.resistor_length_um / 2) * um
        return 6 * arm / (self.width_um * um * (self.thickness_um * um) ** 2)

    def resistance_change_per_N(self) -> float:
        """dR / R per newton at the tip (1/N): pi_l P sigma_avg beta* gamma."""
        return (self.pi_longitudinal_per_Pa * self.doping_factor * self.average_stress_Pa_per_N()
                * self.depth_efficiency * self.strained_share)

    def bridge_sensitivity_V_per_N(self, bias_V: float, active: int = 1) -> float:
        """The bridge's output per newton (V/N): V_bias active / 4 dR / R per N.

        Raises:
            ValueError: ``active`` not 1, 2 or 4, or a non-finite bias.
        """
        if active not in (1, 2, 4):
            raise ValueError(f"active = {active!r}: 1, 2 or 4 strained arms")
        if not math.isfinite(bias_V):
            raise ValueError(f"bias_V = {bias_V!r}: a finite voltage")
        return bias_V * active / 4 * self.resistance_change_per_N()


def johnson_noise_V(resistance_ohm: float, temperature_K: float, f_lo_Hz: float,
                    f_hi_Hz: float) -> float:
    """The rms Johnson noise (V) of ``resistance_ohm`` at ``temperature_K`` over
    [f_lo, f_hi]: sqrt(4 k_B T R (f_hi - f_lo)) (Nyquist 1928).

    Raises:
        ValueError: a negative resistance or temperature, or f_hi < f_lo.
    """
    _band(f_lo_Hz, f_hi_Hz, allow_zero=True)
    if resistance_ohm < 0 or temperature_K < 0:
        raise ValueError(f"resistance {resistance_ohm!r} ohm and temperature {temperature_K!r} "
                         "K: >= 0")
    return math.sqrt(4 * BOLTZMANN_J_PER_K * temperature_K * resistance_ohm
                     * (f_hi_Hz - f_lo_Hz))


def hooge_noise_V(alpha_H: float, resistor_bias_V: float, carriers: float, f_lo_Hz: float,
                  f_hi_Hz: float) -> float:
    """The rms Hooge 1/f noise (V) of a resistor with ``carriers`` carriers biased at
    ``resistor_bias_V`` over [f_lo, f_hi]: sqrt(alpha_H V^2 / N ln(f_hi / f_lo)) (Hooge 1969).

    Raises:
        ValueError: alpha_H < 0, carriers <= 0, f_lo <= 0 or f_hi < f_lo.
    """
    _band(f_lo_Hz, f_hi_Hz, allow_zero=False)
    if alpha_H < 0 or not carriers > 0:
        raise ValueError(f"alpha_H {alpha_H!r} >= 0 and carriers {carriers!r} > 0")
    return math.sqrt(alpha_H * resistor_bias_V ** 2 / carriers * math.log(f_hi_Hz / f_lo_Hz))


@dataclass(frozen=True)
class Amplifier:
    """An instrumentation amplifier's input noise: white floors and 1/f parts at 1 Hz.

    Attributes:
        name: the part. voltage_white_V: e_w (V/sqrt(Hz)). voltage_1f_V: e_f at 1 Hz.
        current_white_A: i_w (A/sqrt(Hz)). current_1f_A: i_f at 1 Hz. source: where from.
    """

    name: str
    voltage_white_V: float
    voltage_1f_V: float
    current_white_A: float
    current_1f_A: float
    source: str

    def noise_V(self, source_resistance_ohm: float, f_lo_Hz: float, f_hi_Hz: float) -> float:
        """The rms input noise (V) over [f_lo, f_hi] with a bridge of output resistance
        ``source_resistance_ohm`` (R / 2 at each input; module doc).

        Raises:
            ValueError: a negative resistance, f_lo <= 0 or f_hi < f_lo.
        """
        _band(f_lo_Hz, f_hi_Hz, allow_zero=False)
        if not source_resistance_ohm >= 0:
            raise ValueError(f"source resistance {source_resistance_ohm!r} ohm: >= 0")
        white, decades = f_hi_Hz - f_lo_Hz, math.log(f_hi_Hz / f_lo_Hz)
        half = source_resistance_ohm / 2
        return math.sqrt(self.voltage_white_V ** 2 * white + self.voltage_1f_V ** 2 * decades
                         + 2 * half ** 2 * (self.current_white_A ** 2 * white
                                            + self.current_1f_A ** 2 * decades))


#: A low-noise bridge amplifier, as Doll and Pruitt's PiezoD states it (``cantilever.m``,
#: ``amplifier = 'INA103'``): 1.2 nV/sqrt(Hz) floor, 6 nV/sqrt(Hz) at 1 Hz, 2 pA/sqrt(Hz)
#: floor, 25 pA/sqrt(Hz) at 1 Hz.
INA103 = Amplifier("INA103", 1.2e-9, 6e-9, 2e-12, 25e-12,
                   "Texas Instruments INA103 as PiezoD (Doll and Pruitt, cantilever.m) states it")

#: Richter et al. 2008's P(N, T) for p-type silicon (module doc): N_b, N_c (cm^-3) and the
#: exponents, as PiezoD's ``piezoresistance_factor`` takes them.
RICHTER_P_TYPE = {"n_b": 6e19, "n_c": 7e20, "alpha": 0.43, "gamma": 1.6, "beta": 0.1,
                  "eta": 3.0, "theta": 0.9}


def piezoresistance_factor(acceptors_per_cm3: float, temperature_K: float = 300.0) -> float:
    """P(N, T): pi_l at a boron doping N and temperature T over pi_l lightly doped at 300 K,
    Theta^-theta / (1 + Theta^-beta (N / N_b)^alpha + Theta^-eta (N / N_c)^gamma),
    Theta = T / 300 K (Richter et al. 2008; :data:`RICHTER_P_TYPE`).

    Raises:
        ValueError: a doping not finite and >= 0, or a temperature not finite and > 0.
    """
    n, c = acceptors_per_cm3, RICHTER_P_TYPE
    if not (math.isfinite(n) and n >= 0):
        raise ValueError(f"acceptors_per_cm3 = {n!r}: finite and >= 0")
    if not (math.isfinite(temperature_K) and temperature_K > 0):
        raise ValueError(f"temperature_K = {temperature_K!r}: finite and > 0")
    theta = temperature_K / 300.0
    return theta ** -c["theta"] / (1 + theta ** -c["beta"] * (n / c["n_b"]) ** c["alpha"]
                                   + theta ** -c["eta"] * (n / c["n_c"]) ** c["gamma"])


def step_profile_depth_efficiency(junction_depth_um: float, thickness_um: float) -> float:
    """beta*'s depth part for carriers uniform from the surface to x_j: 1 - x_j / t (the
    layer's mean distance from the neutral axis over t / 2; Park et al. 2010's beta* with a
    step profile and P taken apart).

    Raises:
        ValueError: x_j not within (0, t].
    """
    if not 0 < junction_depth_um <= thickness_um:
        raise ValueError(f"junction depth {junction_depth_um!r} um: within (0, "
                         f"{thickness_um!r}] um, the beam's thickness")
    return 1.0 - junction_depth_um / thickness_um


def carriers_in(doping_per_cm3: float, length_um: float, width_um: float,
                junction_depth_um: float) -> float:
    """The carriers of a uniformly doped resistor (count): doping x its volume (every dopant
    ionised at room temperature)."""
    volume_cm3 = length_um * width_um * junction_depth_um * 1e-12
    return doping_per_cm3 * volume_cm3


def force_resolution_N(cantilever: PiezoCantilever, bias_V: float, noise_V: float,
                       active: int = 1) -> float:
    """The smallest force (N, 1 sigma) the bridge resolves: its output noise over its
    sensitivity."""
    return noise_V / abs(cantilever.bridge_sensitivity_V_per_N(bias_V, active))


def _band(f_lo: float, f_hi: float, allow_zero: bool) -> None:
    low_ok = f_lo >= 0 if allow_zero else f_lo > 0
    if not (math.isfinite(f_lo) and math.isfinite(f_hi) and low_ok and f_hi >= f_lo):
        raise ValueError(f"band {f_lo!r} ... {f_hi!r} Hz: finite, "
                         f"{'0 <=' if allow_zero else '0 <'} f_lo <= f_hi")


#: Masetti, Severi and Solmi, "Modeling of carrier mobility against carrier concentration
#: in arsenic-, phosphorus- and boron-doped silicon", IEEE Trans. Electron Devices 30(7),
#: 1983: the boron (hole) constants (cm^2/(V s), cm^-3).
MASETTI_BORON = {"mu_max": 470.5, "mu_min1": 44.9, "mu_min2": 0.0, "mu_1": 29.0,
                 "p_c": 9.23e16, "c_r": 2.23e17, "c_s": 6.10e20, "alpha": 0.719, "beta": 2.0}
#: The elementary charge (C, exact since the 2019 SI).
ELEMENTARY_CHARGE_C = 1.602176634e-19


def hole_mobility_cm2_per_Vs(acceptors_per_cm3: float, temperature_K: float = 300.0) -> float:
    """Hole mobility in boron-doped silicon (cm^2/(V s)): the one mobility the die's sheet
    resistance and TCR both read. At 300 K Masetti's fit (:func:`hole_mobility_masetti_cm2_per_Vs`,
    fitted to heavily doped layers, where Arora's runs high); away from it that value
    carried by Arora's relative change mu_A(N, T) / mu_A(N, 300 K)
    (:func:`hole_mobility_arora_cm2_per_Vs`, the fit that has a temperature), so that
    d ln mu / dT is Arora's.

    Raises:
        ValueError: a doping not finite and > 0, or a temperature outside 250-500 K.
    """
    at = hole_mobility_arora_cm2_per_Vs(acceptors_per_cm3, temperature_K)
    return (hole_mobility_masetti_cm2_per_Vs(acceptors_per_cm3) * at
            / hole_mobility_arora_cm2_per_Vs(acceptors_per_cm3, 300.0))


def hole_mobility_masetti_cm2_per_Vs(acceptors_per_cm3: float) -> float:
    """Hole mobility in boron-doped silicon at 300 K (cm^2/(V s)), Masetti's fit:
    mu = mu_min1 exp(-P_c / N) + (mu_max - mu_min2) / (1 + (N / C_r)^alpha)
    - mu_1 / (1 + (C_s / N)^beta) (:data:`MASETTI_BORON`).

    Raises:
        ValueError: a doping not finite and > 0.
    """
    n = acceptors_per_cm3
    if not (math.isfinite(n) and n > 0):
        raise ValueError(f"acceptors_per_cm3 = {n!r}: finite and > 0")
    m = MASETTI_BORON
    return (m["mu_min1"] * math.exp(-m["p_c"] / n)
            + (m["mu_max"] - m["mu_min2"]) / (1 + (n / m["c_r"]) ** m["alpha"])
            - m["mu_1"] / (1 + (m["c_s"] / n) ** m["beta"]))


#: Arora, Hauser and Roulston, "Electron and hole mobilities in silicon as a function of
#: concentration and temperature", IEEE Trans. Electron Devices 29(2), 1982, pp. 292-295:
#: the hole constants (cm^2/(V s), K, cm^-3); the fit holds over 250-500 K.
ARORA_HOLES = {"mu_min": 54.3, "mu_min_exp": -0.57, "mu_0": 1.36e8, "mu_0_exp": -2.23,
               "n_ref": 2.35e17, "n_ref_exp": 2.4, "alpha": 0.88, "alpha_exp": -0.146}
#: The temperatures Arora's fit holds over (K).
MOBILITY_FIT_RANGE_K = (250.0, 500.0)


def hole_mobility_arora_cm2_per_Vs(acceptors_per_cm3: float, temperature_K: float) -> float:
    """Hole mobility in boron-doped silicon at a temperature (cm^2/(V s)), Arora's fit:
    mu = mu_min Tn^-0.57 + mu_0 T^-2.23 / (1 + (N / (N_ref Tn^2.4))^(alpha Tn^-0.146)),
    Tn = T / 300 K (:data:`ARORA_HOLES`).

    Raises:
        ValueError: a doping not finite and > 0, or a temperature outside 250-500 K.
    """
    n, t = acceptors_per_cm3, temperature_K
    if not (math.isfinite(n) and n > 0):
        raise ValueError(f"acceptors_per_cm3 = {n!r}: finite and > 0")
    if not (math.isfinite(t) and MOBILITY_FIT_RANGE_K[0] <= t <= MOBILITY_FIT_RANGE_K[1]):
        raise ValueError(f"temperature_K = {t!r}: {MOBILITY_FIT_RANGE_K[0]:g} ... "
                         f"{MOBILITY_FIT_RANGE_K[1]:g} K (the fit's range)")
    a, tn = ARORA_HOLES, t / 300.0
    exponent = a["alpha"] * tn ** a["alpha_exp"]
    return (a["mu_min"] * tn ** a["mu_min_exp"]
            + a["mu_0"] * t ** a["mu_0_exp"] / (1 + (n / (a["n_ref"] * tn ** a["n_ref_exp"]))
                                                 ** exponent))


def resistor_tcr_per_K(acceptors_per_cm3: float, temperature_K: float = 300.0) -> float:
    """A p-type resistor's temperature coefficient of resistance (1/K): d ln rho / dT =
    -d ln mu / dT with every acceptor ionised (:func:`hole_mobility_cm2_per_Vs`, Arora's
    slope; a difference over 1 K, one-sided at the fit's ends); positive, the lattice
    scattering's rise with T.

    Raises:
        ValueError: a temperature outside :data:`MOBILITY_FIT_RANGE_K`, or a doping not
            finite and > 0.
    """
    lo, hi = MOBILITY_FIT_RANGE_K
    if not (isinstance(temperature_K, numbers.Real) and lo <= temperature_K <= hi):
        raise ValueError(f"temperature_K = {temperature_K!r}: {lo:g} ... {hi:g} K (the fit's "
                         "range)")
    return -log_slope_per_K(lambda T: hole_mobility_cm2_per_Vs(acceptors_per_cm3, T),
                            temperature_K, within_K=MOBILITY_FIT_RANGE_K)


def log_slope_per_K(of_temperature, temperature_K: float,
                    within_K: tuple[float, float] | None = None) -> float:
    """d ln f / dT of a positive ``f(T)`` (1/K), by a difference over 1 K centred on
    ``temperature_K`` (every temperature law here is smooth on that scale), moved inside
    ``within_K`` (lo, hi) where the law holds only there (so its ends take a one-sided
    difference)."""
    lo = temperature_K - 0.5
    if within_K is not None and within_K[0] <= temperature_K <= within_K[1]:
        lo = min(max(lo, within_K[0]), within_K[1] - 1.0)  # outside it, the law refuses
    return math.log(of_temperature(lo + 1.0) / of_temperature(lo))


def sheet_resistance_ohm(acceptors_per_cm3: float, junction_depth_um: float,
                         temperature_K: float = 300.0) -> float:
    """A uniformly doped layer's sheet resistance (ohm per square) at a temperature (K):
    1 / (q mu N x_j) (:func:`hole_mobility_cm2_per_Vs`)."""
    return 1.0 / (ELEMENTARY_CHARGE_C * hole_mobility_cm2_per_Vs(acceptors_per_cm3, temperature_K)
                  * acceptors_per_cm3 * junction_depth_um * 1e-4)


def die_resistor(plan, beam, temperature_K: float = 300.0) -> PiezoCantilever:
    """A die beam's root piezoresistor (:class:`tactcad.products.silicon_die.design.mems_die.DiePlan`,
    :class:`~tactcad.products.silicon_die.design.mems_die.Beam`): its legs along the beam from the root, the
    plan's resistor length and pi_l, carriers in a box of the plan's junction depth x_j at
    the surface (:func:`step_profile_depth_efficiency`), P(N, T) at the implant's doping
    and gamma the legs' squares on the beam over the resistor's (:func:`die_squares`)."""
    from tactcad.products.silicon_die.design.mems_die import JUNCTION_DEPTH_UM

    squares = die_squares(plan)
    return PiezoCantilever(beam.length_um, beam.width_um, beam.thickness_um,
                           plan.resistor_length_um, plan.pi_longitudinal_per_Pa,
                           step_profile_depth_efficiency(JUNCTION_DEPTH_UM, beam.thickness_um),
                           piezoresistance_factor(plan.acceptors_per_cm3, temperature_K),
                           squares["strained"] / squares["total"])


def die_squares(plan, resistor_length_um: float | None = None) -> dict[str, float]:
    """The U-shaped resistor's squares: ``strained``, its two legs on the beam
    (length less the bar's leg width, over the leg width), and ``total``, with the legs'
    run onto the frame and the bar (leg gap + 2 legs) / leg width at the far end;
    ``resistor_length_um`` another U's legs (None: the beam resistor's)."""
    from tactcad.products.silicon_die.design import mems_die as md

    length = plan.resistor_length_um if resistor_length_um is None else resistor_length_um
    strained = 2 * (length - md.LEG_UM) / md.LEG_UM
    run = 2 * md.RESISTOR_RUN_UM / md.LEG_UM
    bar = (md.LEG_GAP_UM + 2 * md.LEG_UM) / md.LEG_UM
    return {"strained": strained, "total": strained + run + bar}


def die_resistance_ohm(plan, resistor_length_um: float | None = None,
                       temperature_K: float = 300.0) -> float:
    """One U-shaped resistor's resistance (ohm) at a temperature (K): the sheet resistance
    of the plan's implant times its squares (:func:`die_squares`); ``resistor_length_um``
    another U's legs (the on-die reference's), None the beam resistor's."""
    from tactcad.products.silicon_die.design import mems_die as md

    return (sheet_resistance_ohm(plan.acceptors_per_cm3, md.JUNCTION_DEPTH_UM, temperature_K)
            * die_squares(plan, resistor_length_um)["total"])


#: Silicon's thermal conductivity at 300 K (W/(m K)): Glassbrenner and Slack, "Thermal
#: conductivity of silicon and germanium from 3 K to the melting point", Phys. Rev. 134,
#: A1058, 1964.
SILICON_CONDUCTIVITY_W_PER_MK = 148.0


def sensitivity_temperature_coefficient_per_K(acceptors_per_cm3: float,
                                              temperature_K: float = 300.0) -> float:
    """The piezoresistive sensitivity's temperature coefficient (1/K): d ln P(N, T) / dT
    (:func:`piezoresistance_factor`, central difference over 1 K)."""
    return log_slope_per_K(lambda T: piezoresistance_factor(acceptors_per_cm3, T), temperature_K)


def root_self_heating_K(power_W: float, resistor_length_um: float, width_um: float,
                        thickness_um: float) -> float:
    """The resistor's mean temperature rise (K) over the frame: its power, spread evenly
    along its legs from the root, conducted along the beam into the frame,
    dT = P l_r / (2 k w t) (one-dimensional conduction; the air's share left out, so an
    upper bound; k: :data:`SILICON_CONDUCTIVITY_W_PER_MK`)."""
    area_m2 = width_um * 1e-6 * thickness_um * 1e-6
    return power_W * resistor_length_um * 1e-6 / (2 * SILICON_CONDUCTIVITY_W_PER_MK * area_m2)


def die_readout(plan, bias_V: float = 2.0, f_lo_Hz: float = 0.1, f_hi_Hz: float = 100.0,
                alpha_H: float = 1e-5, temperature_K: float = 300.0,
                amplifier: Amplifier = INA103) -> dict:
    """Each row's read-out of a die: each beam's resistor and its on-die reference resistor
    in series, a half bridge on the beam's three pads, completed off the die by two equal
    fixed arms, biased at ``bias_V`` (V), over the band [f_lo, f_hi] (Hz). With rho =
    R_ref / R, the output per relative change of R is V rho / (1 + rho)^2 (V / 4 at rho = 1);
    the two resistors' common TCR cancels, and the zero drifts by their TCR mismatch,
    V rho / (1 + rho)^2 TCR m per K (m: :data:`~tactcad.products.silicon_die.design.mems_die.REFERENCE_TCR_MISMATCH_REL`).

    Returns:
        ``{"resistance_ohm", "sheet_resistance_ohm_per_sq", "hole_mobility_cm2_per_Vs",
        "carriers", "doping_factor", "strained_share", "sensitivity_tc_per_K",
        "resistor_tcr_per_K", "zero_drift_V_per_K", "self_heating_K", "noise_V": {"johnson",
        "hooge", "amplifier", "total"}, "rows": {role: {
        "resistance_change_per_N", "sensitivity_V_per_N", "force_resolution_N",
        "full_scale_signal_V", "zero_drift_N_per_K"}}, "reference_resistance_ohm",
        "uncancelled_zero_drift_V_per_K", "assumptions": [...]}``. Noise: the bridge's
        Johnson noise (its output resistance, about R), the Hooge noise of both die resistors
        at their share of V_bias across each (alpha_H, default 1e-5: the middle of Harley and
        Kenny's 1e-7 ... 1e-4) and ``amplifier``'s (default :data:`INA103`).

    Raises:
        ValueError: a bias or band out of range.
    """
    from tactcad.products.silicon_die.design import mems_die as md

    if not (math.isfinite(bias_V) and 0 < bias_V <= 20):
        raise ValueError(f"bias_V = {bias_V!r}: 0 < V <= 20")
    r = die_resistance_ohm(plan, temperature_K=temperature_K)
    r_ref = die_resistance_ohm(plan, plan.reference_resistor_length_um, temperature_K)
    rho = r_ref / r
    divider = 4 * rho / (1 + rho) ** 2  # the half bridge's output against V/4 dR/R
    v_active, v_ref = bias_V / (1 + rho), bias_V * rho / (1 + rho)

    def carriers_of(length_um: float) -> float:
        legs_um = 2 * (md.RESISTOR_RUN_UM + length_um)
        return carriers_in(plan.acceptors_per_cm3, legs_um, md.LEG_UM, md.JUNCTION_DEPTH_UM)

    carriers = carriers_of(plan.resistor_length_um)
    johnson = johnson_noise_V(r * rho / (1 + rho) + r / 2, temperature_K, f_lo_Hz, f_hi_Hz)
    hooge = math.hypot(hooge_noise_V(alpha_H, v_active, carriers, f_lo_Hz, f_hi_Hz),
                       hooge_noise_V(alpha_H, v_ref,
                                     carriers_of(plan.reference_resistor_length_um),
                                     f_lo_Hz, f_hi_Hz))
    amp = amplifier.noise_V(r, f_lo_Hz, f_hi_Hz)
    total = math.sqrt(johnson ** 2 + hooge ** 2 + amp ** 2)
    tcs = sensitivity_temperature_coefficient_per_K(plan.acceptors_per_cm3, temperature_K)
    tcr = resistor_tcr_per_K(plan.acceptors_per_cm3, temperature_K)
    uncancelled_V = bias_V / 4 * divider * tcr  # one resistor alone against fixed arms
    zero_V = uncancelled_V * md.REFERENCE_TCR_MISMATCH_REL  # the half bridge's, per K
    heating = root_self_heating_K(v_active ** 2 / r, plan.resistor_length_um,
                                  plan.beams[0].width_um, plan.beams[0].thickness_um)
    rows = {}
    for beam in (plan.beams[0], plan.beams[plan.columns]):
        c = die_resistor(plan, beam, temperature_K)
        sens = c.bridge_sensitivity_V_per_N(bias_V) * divider
        rows[beam.role] = {"resistance_change_per_N": c.resistance_change_per_N(),
                           "sensitivity_V_per_N": sens,
                           "force_resolution_N": total / abs(sens),
                           # at the most the beam carries in use (strength's rated force)
                           "full_scale_signal_V": sens * plan.rated_force_N(beam),
                           "zero_drift_N_per_K": zero_V / sens}
    return {"resistance_ohm": r, "reference_resistance_ohm": r_ref,
            "uncancelled_zero_drift_V_per_K": uncancelled_V,
            "sheet_resistance_ohm_per_sq": sheet_resistance_ohm(
                plan.acceptors_per_cm3, md.JUNCTION_DEPTH_UM, temperature_K),
            "hole_mobility_cm2_per_Vs": hole_mobility_cm2_per_Vs(plan.acceptors_per_cm3,
                                                                 temperature_K),
            "carriers": carriers, "bias_V": bias_V, "band_Hz": [f_lo_Hz, f_hi_Hz],
            "doping_factor": c.doping_factor, "strained_share": c.strained_share,
            "sensitivity_tc_per_K": tcs, "resistor_tcr_per_K": tcr,
            "zero_drift_V_per_K": zero_V, "self_heating_K": heating,
            "noise_V": {"johnson": johnson, "hooge": hooge, "amplifier": amp, "total": total},
            "rows": rows,
            "assumptions": [
                f"alpha_H {alpha_H:g} (Harley and Kenny 2000: 1e-7 annealed ... 1e-4)",
                f"pi_l at Smith's 7.8 ohm cm times P(N, T) = {c.doping_factor:.3f} at "
                f"{plan.acceptors_per_cm3:.2g} cm^-3 and {temperature_K:g} K (Richter et al. "
                "2008)",
                f"gamma {c.strained_share:.3f}: the legs on the beam over the resistor's squares "
                "(no contact resistance)",
                f"amplifier {amplifier.name} ({amplifier.source})",
                f"sensitivity {100 * tcs:+.3f} %/K (d ln P / dT); alike in both rows, so it "
                "cancels in R at one temperature",
                f"TCR {1e6 * tcr:+.0f} ppm/K (Arora et al. 1982's hole mobility's slope on "
                f"Masetti et al. 1983's 300 K value, every acceptor "
                f"ionised), alike in the beam's resistor and its on-die reference "
                f"({r_ref / 1e3:.4g} kohm): it cancels in the half bridge to their mismatch, "
                f"{100 * md.REFERENCE_TCR_MISMATCH_REL:g} % (assumption), so the zero moves "
                f"{1e6 * zero_V:.3g} uV per K (one resistor against fixed arms: "
                f"{1e3 * uncancelled_V:.3g} mV per K)",
                f"self-heating {heating * 1e3:.3g} mK at the root (V_R^2 / R = "
                f"{1e6 * v_active ** 2 / r:.3g} uW conducted along the beam to the frame, "
                "k 148 W/(m K), Glassbrenner and Slack 1964): its P(N, T) change "
                f"{100 * abs(tcs) * heating:.2g} %"]}
