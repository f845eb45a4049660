"""The ``[readout]`` section of a design file: the chain from gauge to number.

A foil strain gauge bonded on the flat top face over each element's web, in
a quarter Wheatstone bridge, an instrumentation amplifier and a DAQ. Every
key is optional; a key the file leaves out takes the default below, each
with its source (a datasheet) or, where no document fixes it, the stated
assumption. Gauge factor and resistance default to the design's library
gauge (``[strength] gauge``), so the strength limits and the read-out use
one gauge.

Keys (units in the names):

* ``gauge_factor`` (-), ``gauge_resistance_ohm``;
* ``grid_length_mm`` (along the arm), ``grid_width_mm`` (across the sheet):
  the active grid, over which the gauge averages the strain;
* ``gauge_backing_thickness_mm``, ``adhesive_thickness_mm``,
  ``gauge_backing_modulus_MPa``: the carrier and glue line under the grid
  (default: the library gauge's), which lift the grid above the web's
  surface and stiffen a thin web (:func:`tactcad.mechanics.readout_chain.bonded_grid_factor`);
* ``bridge``: ``"quarter"`` (one active gauge, three completion resistors);
* ``excitation_V``: bridge supply (not stated: the highest the grid's power density
  allows, Micro-Measurements TN-502, see :func:`tn502_excitation_V`);
* ``lead_wires``: ``"three-wire"`` (one lead in the gauge's arm, one in the adjacent
  completion arm, one sense line: the leads' temperature change cancels) or
  ``"two-wire"`` (both leads in the gauge's arm); ``lead_length_mm`` (gauge to bridge
  completion, one conductor) and ``lead_resistance_ohm_per_m`` (one conductor);
* ``amplifier``, ``amplifier_gain``, ``amplifier_noise_nV_per_rtHz``,
  ``bandwidth_Hz``: the instrumentation amplifier and its white noise;
  ``amplifier_flicker_nV_per_rtHz_at_1Hz``: its 1/f noise, the density e_f of the
  1/f part at 1 Hz (e_n(f)^2 = e_w^2 + e_f^2 / f; not stated for the AD621: from its
  data sheet's 0.1-10 Hz peak-to-peak figure, :func:`flicker_density_at_1Hz`; for
  another amplifier: 0, named unstated); ``tare_interval_s``: the time from a tare to
  the reading it zeroes, the lowest frequency the reading's 1/f noise reaches;
* ``filter_corner_Hz``, ``filter_order``: the anti-alias low-pass filter
  before the DAQ (Butterworth; order 0: none), which sets the noise bandwidth
  (:attr:`ReadoutChain.noise_bandwidth_Hz`);
* ``daq``, ``daq_ranges_V`` (the DAQ's +/- input ranges), ``daq_range_V``
  (the range used; not stated: the smallest of ``daq_ranges_V`` that holds
  ``daq_range_margin`` x the signal at the gauge's fatigue strain,
  :func:`chosen_daq_range`), ``daq_bits``, ``daq_noise_uV_rms`` (random noise
  of that range, one sample), ``samples_averaged``, ``sample_rate_Hz`` (with the
  noise bandwidth it sets how much averaging gains: :attr:`ReadoutChain.effective_samples`);
* thermal (:mod:`tactcad.mechanics.thermal_drift`): ``gauge_stc_ppm_per_K``
  (the gauge's self-temperature-compensation number: 06 steel-matched =
  10.8, 13 aluminium-matched = 23.4; not stated: matched to the element's
  material), ``gauge_factor_tc_pct_per_100K`` (gauge factor temperature
  coefficient), ``gauge_transverse_sensitivity`` (K_t),
  ``substrate_cte_ppm_per_K`` (not stated: the material grade's),
  ``substrate_modulus_tc_per_K`` ((1/E) dE/dT of the element; not stated: the grade's),
  ``gauge_heat_transfer_W_per_mm2_K`` (grid to substrate, self-heating),
  ``dummy_gauge``: ``"none"`` or ``"half-bridge"`` (an unstrained gauge of the
  same lot on the same material in the adjacent arm).
* the gauge installation (:mod:`tactcad.in_use.kobj_budget`): ``gauge_hysteresis_rel``
  (the bonded gauge's hysteresis relative to the reading, from a load-unload cycle at the
  rated force; not stated: an assumed 0.1 %, said so in its source).

Units: V, ohm, mm, Hz, K, ppm/K (1e-6 /K), W.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from tactcad.vocabulary.schema import (Problems, ResolvedSection, Section, Text, choice, fmt,
                                       integer, listing, number, section_with_defaults)

#: Input ranges (+/- V) of the NI USB-6258 and the random noise of one sample
#: in each (uV rms). Source: NI 625x Specifications (371291H), AI absolute
#: accuracy table, "Random noise, sigma".
NI_6258_NOISE_UV_RMS = {0.1: 15.0, 0.2: 16.0, 0.5: 21.0, 1.0: 32.0, 2.0: 57.0, 5.0: 140.0,
                        10.0: 280.0}
#: The amplifier the read-out assumes when the design names none: its noise and bandwidth
#: defaults are its data sheet's.
DEFAULT_AMPLIFIER = "AD621"
def is_default_amplifier(name: str) -> bool:
    """Whether ``name`` names :data:`DEFAULT_AMPLIFIER` (any case, spaces around)."""
    return name.strip().casefold() == DEFAULT_AMPLIFIER.casefold()


#: AD621 pin-strapped gains and the amplifier's -3 dB bandwidth at each (Hz).
#: Source: Analog Devices AD621 data sheet (gain 10: 800 kHz; gain 100: 200 kHz).
AD621_BANDWIDTH_HZ = {10.0: 800e3, 100.0: 200e3}

#: AD621 input voltage noise over 0.1 ... 10 Hz, peak to peak (uV), with its white floor
#: (nV/sqrt(Hz) at 1 kHz). Source: Analog Devices AD621 data sheet, features: "0.28 uV p-p
#: Noise (0.1 Hz to 10 Hz)", "9 nV/sqrt(Hz), @ 1 kHz, Input Voltage Noise".
AD621_LOW_BAND_NOISE_UV_PP, AD621_LOW_BAND_HZ = 0.28, (0.1, 10.0)
#: A data sheet's peak-to-peak noise over its rms (Gaussian noise: +-3.3 sigma, the band
#: exceeded 0.1 % of the time).
PEAK_TO_PEAK_OVER_RMS = 6.6


def flicker_density_at_1Hz(peak_to_peak_uV: float, band_Hz: tuple[float, float],
                           white_nV_per_rtHz: float) -> float:
    """The 1/f part of an amplifier's input noise density at 1 Hz (nV/sqrt(Hz)) from its
    data sheet's low-band peak-to-peak figure: the band's rms (p-p / 6.6) squared is
    e_w^2 (f_hi - f_lo) + e_f^2 ln(f_hi / f_lo), the integral of e_n(f)^2 = e_w^2 + e_f^2 / f;
    0 when the white floor alone accounts for it.

    Args:
        peak_to_peak_uV: the p-p noise over ``band_Hz`` (uV). band_Hz: (f_lo, f_hi), Hz.
        white_nV_per_rtHz: the white floor e_w (nV/sqrt(Hz)).
    """
    f_lo, f_hi = band_Hz
    rms_nV = 1e3 * peak_to_peak_uV / PEAK_TO_PEAK_OVER_RMS
    excess = rms_nV ** 2 - white_nV_per_rtHz ** 2 * (f_hi - f_lo)
    return math.sqrt(max(excess, 0.0) / math.log(f_hi / f_lo))


#: The NI USB-6258's +/- input ranges (V). Source: NI 625x Specifications (371291H).
NI_6258_RANGES_V = tuple(sorted(NI_6258_NOISE_UV_RMS))

def butterworth_noise_bandwidth_ratio(order: int) -> float:
    """ENBW / f_c of a Butterworth low-pass of ``order`` >= 1 (dimensionless).

    The equivalent noise bandwidth is the integral of |H(f)|^2 = 1 / (1 + (f/f_c)^2n)
    over f: (pi / 2n) / sin(pi / 2n) x f_c (1.571 at n = 1, the RC filter's pi/2;
    1.111 at 2; 1.026 at 4).

    Raises:
        ValueError: an order below 1.
    """
    if order < 1:
        raise ValueError(f"filter order must be >= 1; got {order!r}")
    x = math.pi / (2 * order)
    return x / math.sin(x)


#: Random noise per volt of range (uV rms / V) where no table applies: the
#: NI 625x figure at +/-5 and +/-10 V (28 ppm of the range).
NOISE_UV_PER_V_RANGE = 28.0

BRIDGES = ("quarter",)
#: Lead-wire connections of a quarter bridge (``lead_wires``).
LEAD_WIRES = ("three-wire", "two-wire")

#: Grid power density (W/mm^2) the default excitation is set to: 1 W/in^2, the low end of
#: Micro-Measurements Tech Note TN-502's 1-2 W/in^2 for thin steel sections. Assumption: a
#: web a few tenths of a mm thick (titanium or steel conduct heat poorly, a thin aluminium
#: web has little mass to sink it) is a thin section, and a static reading asks the low end.
TN502_POWER_DENSITY_W_PER_MM2 = 1.0 / 645.16
#: TN-502's range for thin steel sections, 1-2 W/in^2, in W/mm^2: above its top the thermal
#: report flags the excitation.
TN502_THIN_SECTION_W_PER_MM2 = (1.0 / 645.16, 2.0 / 645.16)
#: The most TN-502 says a gauge's backing is derated under high excitation (it names 10-30 C
#: off a backing's +120 C rating: the grid runs that much above its substrate), in K: a grid
#: warmer than this above the element is past what the gauge maker's note covers.
TN502_HIGH_EXCITATION_DERATING_K = 30.0
#: The lead wire of every quarter bridge, one wire for the thermal report's lead resistance,
#: the BOM and the bundle through a grasper's shaft: AWG 36 copper (ASTM B258: 0.127 mm) in
#: PTFE insulation to 0.25 mm outside diameter, the wire the gauge catalogue's lead mass
#: (``lead_mass_mg_per_mm``) assumes.
LEAD_WIRE = {"awg": 36, "conductor_diameter_mm": 0.127, "insulated_diameter_mm": 0.25}
#: Annealed copper's resistivity at 20 C (ohm m; IEC 60028).
COPPER_RESISTIVITY_OHM_M = 1.724e-8


def lead_resistance_ohm_per_m(conductor_diameter_mm: float = LEAD_WIRE["conductor_diameter_mm"]
                              ) -> float:
    """Resistance per metre (ohm/m) of a round copper conductor: rho / (pi d^2 / 4)."""
    return COPPER_RESISTIVITY_OHM_M / (math.pi * (conductor_diameter_mm * 1e-3) ** 2 / 4.0)


#: The lead wire's resistance per metre (ohm/m, 4 decimals as the thermal report quotes it).
LEAD_RESISTANCE_OHM_PER_M = round(lead_resistance_ohm_per_m(), 4)
#: Excitations are set in steps of this (V), rounded down.
EXCITATION_STEP_V = 0.1


def tn502_excitation_V(resistance_ohm: float, grid_area_mm2: float,
                       power_density_W_per_mm2: float = TN502_POWER_DENSITY_W_PER_MM2) -> float:
    """Bridge excitation that puts ``power_density_W_per_mm2`` into the grid of an equal-arm
    bridge (TN-502: V = 2 sqrt(R_g P_g A_g)), rounded down to 0.1 V (at least 0.1 V).

    Args:
        resistance_ohm: gauge resistance (ohm). grid_area_mm2: active grid area (mm^2).
        power_density_W_per_mm2: allowed grid power density (W/mm^2).

    Returns:
        Excitation (V).
    """
    exact = 2.0 * math.sqrt(resistance_ohm * power_density_W_per_mm2 * grid_area_mm2)
    return max(EXCITATION_STEP_V, math.floor(exact / EXCITATION_STEP_V + 1e-9) * EXCITATION_STEP_V)


def grid_power_density_W_per_mm2(excitation_V: float, resistance_ohm: float,
                                 grid_area_mm2: float) -> float:
    """Power per grid area of a quarter-bridge gauge (equal arms: V_ex^2 / (4 R_g A_g))."""
    return excitation_V ** 2 / (4.0 * resistance_ohm * grid_area_mm2)
#: The grid widths a design file may state (mm).
GRID_WIDTH_RANGE_MM = (0.1, 20.0)
#: Temperature compensation by a dummy gauge (``dummy_gauge``).
DUMMY_GAUGES = ("none", "half-bridge")

#: Hysteresis of a bonded gauge's reading when the design file states none (relative to the
#: reading): an assumption, marked so in its source (``DEFAULTS["gauge_hysteresis_rel"]``).
DEFAULT_GAUGE_HYSTERESIS_REL = 1e-3

#: Defaults: value and source (datasheet) or stated assumption. Gauge factor
#: and resistance come from the library gauge unless the file gives them.
DEFAULTS: dict[str, tuple[Any, str]] = {
    "grid_length_mm": (0.6, "assumption: the shortest common 120 ohm foil grid (0.6 mm); it "
                            "spans the notch's thin part, and a longer grid reads less of the "
                            "peak strain (readout gives the grid average)"),
    "grid_width_mm": (1.0, "assumption: 1.0 mm grid width, the usual width of a 0.6 mm 120 ohm "
                           "grid, narrower than the sheet"),
    "bridge": ("quarter", "one active gauge per element in a quarter Wheatstone bridge with "
                          "three completion resistors"),
    "excitation_V": (None, "assumption: the grid power density of Micro-Measurements TN-502 "
                           "for thin sections, 1 W/in^2 (low end of 1-2 W/in^2: a thin web "
                           "sinks little heat, a static reading), V = 2 sqrt(R_g P A_g) "
                           "rounded down to 0.1 V; state excitation_V to change it"),
    "amplifier": (DEFAULT_AMPLIFIER, "Analog Devices AD621 instrumentation amplifier"),
    "amplifier_gain": (100.0, "assumption: the AD621's pin-strapped gain 100 (data sheet: fixed "
                              "gains 10 and 100)"),
    "amplifier_noise_nV_per_rtHz": (9.0, "AD621 data sheet: input voltage noise 9 nV/sqrt(Hz) "
                                         "at 1 kHz, gain 100"),
    "bandwidth_Hz": (None, "AD621 data sheet: -3 dB bandwidth at the gain (200 kHz at 100, "
                           "800 kHz at 10)"),
    "amplifier_flicker_nV_per_rtHz_at_1Hz": (
        None, "AD621 data sheet: 0.28 uV p-p over 0.1-10 Hz (rms = p-p / 6.6) less its "
              "9 nV/sqrt(Hz) white floor over that band, the rest a 1/f density: e_f = "
              "sqrt((rms^2 - e_w^2 9.9 Hz) / ln 100), 14.7 nV/sqrt(Hz) at 1 Hz (a 1/f corner "
              "of 2.7 Hz)"),
    "tare_interval_s": (10.0, "assumption: a reading taken 10 s after the tare that zeroes "
                              "it (zeroed with the jaw open, read once it holds the tissue); "
                              "its 1/f noise reaches down to 1 / 10 s"),
    "filter_corner_Hz": (1000.0, "assumption: a 1 kHz anti-alias low-pass before the DAQ: a "
                                 "grasp's force changes within tens of Hz; without it the "
                                 "amplifier's whole bandwidth carries its noise to the DAQ"),
    "filter_order": (1, "assumption: a first-order (RC) filter, noise bandwidth pi/2 x the "
                        "corner (Butterworth order n: (pi/2n)/sin(pi/2n) x the corner)"),
    "daq": ("NI USB-6258", "NI USB-6258 M Series DAQ"),
    "daq_ranges_V": (list(NI_6258_RANGES_V), "NI 625x specifications: input ranges +/-0.1, "
                                              "0.2, 0.5, 1, 2, 5, 10 V"),
    "daq_range_margin": (1.25, "assumption: the range holds 1.25 x the largest signal (room "
                               "for the nulled bridge's residual offset and a short overload)"),
    "daq_range_V": (None, "chosen: the smallest of readout.daq_ranges_V that holds "
                          "readout.daq_range_margin x the signal at the gauge's fatigue strain "
                          "(the most the rated full-scale force may put on any gauge: strength "
                          "holds it there)"),
    "daq_bits": (16, "NI 625x specifications: 16-bit ADC"),
    "daq_noise_uV_rms": (None, "NI 625x specifications: random noise sigma of the chosen range "
                               "(+/-5 V: 140 uV rms)"),
    "samples_averaged": (10, "assumption: 10 readings averaged per value"),
    "sample_rate_Hz": (1000.0, "assumption: 1 kS/s per channel (the filtered noise's "
                               "correlation time, 1 / (4 x the noise bandwidth), sets how "
                               "much averaging the samples gains)"),
    "gauge_stc_ppm_per_K": (None, "not stated: the gauge's STC number matched to the element "
                                  "material's CTE (the gauge one orders for that material)"),
    "gauge_factor_tc_pct_per_100K": (1.15, "HBM Y series (constantan) data sheet: temperature "
                                           "coefficient of the gauge factor about "
                                           "115 x 1e-6 /K (a gauge of that series; another "
                                           "gauge's own data sheet governs)"),
    "gauge_transverse_sensitivity": (0.0, "assumption: K_t = 0 (the lot's package states it; "
                                          "foil gauges under 1 %)"),
    "substrate_cte_ppm_per_K": (None, "the material grade's CTE (materials library)"),
    "gauge_heat_transfer_W_per_mm2_K": (
        0.0067, "assumption: conduction from grid to element through about 30 um of cured "
                "epoxy and carrier at about 0.2 W/(m K) (0.2 / 30e-6 W/(m^2 K))"),
    "dummy_gauge": ("none", "one active gauge; no dummy gauge compensates temperature"),
    "lead_wires": ("three-wire", "three-wire quarter bridge, as the BOM's lead wire assumes "
                                 "([bom] lead_wire_m_per_element: three conductors)"),
    "lead_length_mm": (500.0, "assumption: 0.5 m from gauge to bridge completion, as the BOM's "
                              "lead wire ([bom] lead_wire_m_per_element = 3 x 0.5 m)"),
    "lead_resistance_ohm_per_m": (LEAD_RESISTANCE_OHM_PER_M,
                                  "the lead wire's (LEAD_WIRE): AWG 36 copper, "
                                        "0.127 mm diameter (ASTM B258), 1.724e-8 ohm m at 20 C "
                                        "(annealed copper, IEC 60028)"),
    "substrate_modulus_tc_per_K": (None, "the material grade's (1/E) dE/dT (materials library)"),
    "gauge_hysteresis_rel": (
        DEFAULT_GAUGE_HYSTERESIS_REL,
        "assumption (a default, not measured): 0.1 % of the reading, the size of the "
        "uncompensated creep beyond which a gauge maker calls an installation faulty (Vishay "
        "Measurements Group, 'Creep Compensation'; creep and hysteresis both come from the glue "
        "line and carrier). Measure it on the bonded element: load it in steps to its rated "
        "force and back to zero, reading at each step; the largest difference between the "
        "unloading and the loading reading at one force, over the reading at the rated force, "
        "is its hysteresis (OIML R 60's hysteresis error of a load cell, defined so); state it "
        "as readout.gauge_hysteresis_rel"),
}


class ReadoutSection(Section):
    """``[readout]``: every key optional (defaults in :data:`DEFAULTS`)."""

    gauge_factor: number(0.5, 10.0, unit="", why="foil gauges 2 ... 2.2, semiconductor more") = None
    gauge_resistance_ohm: number(10.0, 10000.0, unit="ohm") = None
    grid_length_mm: number(0.1, 20.0, why="active grid length along the arm") = None
    grid_width_mm: number(*GRID_WIDTH_RANGE_MM, why="active grid width across the sheet") = None
    gauge_backing_thickness_mm: number(0.0, 0.5, why="carrier under the foil grid") = None
    adhesive_thickness_mm: number(0.0, 0.5, why="cured glue line under the carrier") = None
    gauge_backing_modulus_MPa: number(0.0, 200000.0, unit="MPa",
                                      why="Young's modulus of carrier and glue line") = None
    bridge: choice(BRIDGES, "one active gauge per element") = None
    excitation_V: number(0.1, 15.0, unit="V", why="bridge supply") = None
    amplifier: Text = None
    amplifier_gain: number(1.0, 10000.0, unit="", why="instrumentation amplifier gain") = None
    amplifier_noise_nV_per_rtHz: number(0.1, 1000.0, unit="nV/sqrt(Hz)") = None
    bandwidth_Hz: number(0.1, 10e6, unit="Hz", why="-3 dB bandwidth of the amplifier") = None
    amplifier_flicker_nV_per_rtHz_at_1Hz: number(
        0.0, 10000.0, unit="nV/sqrt(Hz)", why="the amplifier's 1/f noise density at 1 Hz "
        "(its 1/f part: e_n^2 = e_w^2 + e_f^2 / f)") = None
    tare_interval_s: number(0.01, 1e6, unit="s", why="time from a tare to the reading it "
                            "zeroes") = None
    filter_corner_Hz: number(0.1, 10e6, unit="Hz", why="-3 dB corner of the anti-alias "
                             "low-pass before the DAQ") = None
    filter_order: integer(0, 8, why="Butterworth order of the anti-alias filter; 0: none") = None
    daq: Text = None
    daq_ranges_V: listing(number(0.01, 100.0, unit="V"), 1, 16,
                          "a list of the DAQ's +/- input ranges, 0.01 ... 100 V") = None
    daq_range_margin: number(1.0, 10.0, unit="", why="the chosen range over the largest "
                             "signal") = None
    daq_range_V: number(0.01, 100.0, unit="V", why="+/- input range of the DAQ") = None
    daq_bits: integer(8, 32, why="ADC resolution") = None
    daq_noise_uV_rms: number(0.01, 10000.0, unit="uV rms",
                             why="random noise of one DAQ sample in the chosen range") = None
    samples_averaged: integer(1, 1_000_000, why="readings averaged per value") = None
    sample_rate_Hz: number(0.1, 10e6, unit="Hz", why="samples per second per channel; "
                           "with the noise bandwidth it sets the averaging gain") = None
    gauge_stc_ppm_per_K: number(0.0, 50.0, unit="ppm/K",
                                why="the gauge's self-temperature-compensation number") = None
    gauge_factor_tc_pct_per_100K: number(-10.0, 10.0, unit="%/100 K",
                                         why="gauge factor temperature coefficient") = None
    gauge_transverse_sensitivity: number(-0.1, 0.1, unit="",
                                         why="K_t of the gauge lot, foil gauges within +/-10 %"
                                         ) = None
    substrate_cte_ppm_per_K: number(0.0, 200.0, unit="ppm/K",
                                    why="CTE of the element under the gauge") = None
    gauge_heat_transfer_W_per_mm2_K: number(1e-5, 1.0, unit="W/(mm^2 K)",
                                            why="grid-to-element heat transfer per grid area"
                                            ) = None
    dummy_gauge: choice(DUMMY_GAUGES, "an unstrained dummy gauge in the adjacent bridge arm"
                        ) = None
    lead_wires: choice(LEAD_WIRES, "the quarter bridge's lead-wire connection") = None
    lead_length_mm: number(0.0, 100_000.0, why="one lead conductor, gauge to bridge completion"
                           ) = None
    lead_resistance_ohm_per_m: number(0.0, 100.0, unit="ohm/m",
                                      why="resistance of one lead conductor per metre") = None
    substrate_modulus_tc_per_K: number(-2e-3, 1e-4, unit="1/K",
                                       why="(1/E) dE/dT of the element under the gauge") = None
    gauge_hysteresis_rel: number(0.0, 0.05, unit="", why="the bonded gauge's hysteresis: the "
                                 "largest unloading minus loading reading at one force over "
                                 "the reading at the rated force, from a load-unload cycle") = None


def effective_grid_size(ro: Any, key: str) -> tuple[float, str]:
    """The grid size the read-out chain uses (mm): the design file's, else the default.

    Args:
        ro: the validated ``[readout]`` section, or None when the file has none.
        key: ``"grid_width_mm"`` or ``"grid_length_mm"``.

    Returns:
        (size in mm, "design file" or the default's source).
    """
    stated = getattr(ro, key, None) if ro is not None else None
    if stated is not None:
        return float(stated), "design file"
    value, source = DEFAULTS[key]
    return float(value), source


def _grid_fits(p: Problems, ro: Any, key: str, most_mm: float, allowed: str, why: str,
               remedy: str) -> None:
    """Refuse the grid's ``key`` (its width or length, mm) beyond ``most_mm``, stated or the
    library default's (:func:`effective_grid_size`); a default's refusal says what to state
    (``remedy``)."""
    value, source = effective_grid_size(ro, key)
    if value > most_mm:
        p.add(f"readout.{key}", value, allowed, why + (
            "" if source == "design file" else
            f"; not stated, so the library default's: state {remedy}"))


def check_readout(d: Any, p: Problems) -> None:
    """Cross-field rule: the gauge grid fits on the element's top face over the web."""
    ro = getattr(d, "readout", None)
    sheet = d.sheet.thickness_mm
    _grid_fits(p, ro, "grid_width_mm", sheet, f"<= sheet.thickness_mm = {fmt(sheet)} mm",
               "the grid lies on the element's top face, one sheet thick",
               "the narrower grid of the gauge bonded, or a thicker sheet")
    shortest = min(d.arms.lengths_mm)
    _grid_fits(p, ro, "grid_length_mm", shortest, f"<= {fmt(shortest)} mm (shortest arm)",
               "the grid is centred over the web and must stay on the arm's top face",
               "the shorter grid of the gauge bonded, or longer arms")
    if ro is None:
        return
    if ro.filter_corner_Hz is not None and ro.filter_order == 0:
        p.add("readout.filter_corner_Hz", ro.filter_corner_Hz, "no corner with filter_order = 0",
              "order 0 means no anti-alias filter; give an order of 1 ... 8 for the corner")
    if ro.amplifier is not None and not is_default_amplifier(ro.amplifier) \
            and ro.amplifier_noise_nV_per_rtHz is None:
        p.add("readout.amplifier_noise_nV_per_rtHz", None,
              f"its value from the {ro.amplifier} data sheet (nV/sqrt(Hz))",
              f"readout.amplifier = {ro.amplifier!r}: the noise defaults are the "
              f"{DEFAULT_AMPLIFIER}'s data sheet's, not this amplifier's (state its 1/f "
              "density at 1 Hz too, amplifier_flicker_nV_per_rtHz_at_1Hz, or it is left out)")


@dataclass(frozen=True)
class ReadoutChain(ResolvedSection):
    """The resolved read-out chain of a design (units in the names).

    ``sources`` gives, per key, "design file" or the default's source /
    assumption; ``assumed`` lists the keys whose value is an assumption.
    """

    gauge_name: str
    gauge_factor: float
    gauge_resistance_ohm: float
    grid_length_mm: float
    grid_width_mm: float
    bridge: str
    excitation_V: float
    amplifier: str
    amplifier_gain: float
    amplifier_noise_nV_per_rtHz: float
    bandwidth_Hz: float
    daq: str
    daq_range_V: float
    daq_bits: int
    daq_noise_uV_rms: float
    samples_averaged: int
    gauge_stc_ppm_per_K: float | None = None
    gauge_factor_tc_pct_per_100K: float = 0.0
    gauge_transverse_sensitivity: float = 0.0
    substrate_cte_ppm_per_K: float | None = None
    gauge_heat_transfer_W_per_mm2_K: float = 0.0067
    dummy_gauge: str = "none"
    lead_wires: str = "three-wire"
    lead_length_mm: float = 500.0
    lead_resistance_ohm_per_m: float = LEAD_RESISTANCE_OHM_PER_M
    substrate_modulus_tc_per_K: float | None = None
    gauge_hysteresis_rel: float = DEFAULT_GAUGE_HYSTERESIS_REL
    gauge_backing_thickness_mm: float = 0.0
    adhesive_thickness_mm: float = 0.0
    gauge_backing_modulus_MPa: float = 0.0
    filter_corner_Hz: float = math.inf
    filter_order: int = 0
    daq_ranges_V: tuple[float, ...] = ()
    daq_range_margin: float = 1.0
    sample_rate_Hz: float = 1000.0
    amplifier_flicker_nV_per_rtHz_at_1Hz: float = 0.0
    tare_interval_s: float = 10.0

    @property
    def lead_resistance_ohm(self) -> float:
        """Resistance of one lead conductor (ohm)."""
        return self.lead_resistance_ohm_per_m * self.lead_length_mm / 1000.0

    @property
    def grid_power_density_W_per_mm2(self) -> float:
        """Power per grid area at the excitation (W/mm^2)."""
        return grid_power_density_W_per_mm2(self.excitation_V, self.gauge_resistance_ohm,
                                            self.grid_length_mm * self.grid_width_mm)

    @property
    def grid_height_mm(self) -> float:
        """Height of the foil grid above the web's top face: glue line + carrier (mm)."""
        return self.gauge_backing_thickness_mm + self.adhesive_thickness_mm

    @property
    def noise_bandwidth_Hz(self) -> float:
        """Equivalent noise bandwidth of the chain (Hz): the anti-alias filter's
        (:func:`butterworth_noise_bandwidth_ratio` x its corner) where it is below the
        amplifier's single pole (pi/2 x ``bandwidth_Hz``), else the amplifier's."""
        amplifier = 0.5 * math.pi * self.bandwidth_Hz
        if self.filter_order < 1:
            return amplifier
        return min(amplifier, butterworth_noise_bandwidth_ratio(self.filter_order)
                   * self.filter_corner_Hz)

    @property
    def noise_correlation_time_s(self) -> float:
        """Correlation time of the filtered analog noise (s): 1 / (4 B), B the noise
        bandwidth; exact for a first-order low-pass (tau = RC, B = 1 / (4 RC)), the
        equal-bandwidth first-order stand-in for the others."""
        return 1.0 / (4.0 * self.noise_bandwidth_Hz)

    @property
    def effective_samples(self) -> float:
        """How many independent samples the average of ``samples_averaged`` correlated ones
        is worth: N / (1 + 2 sum_k (1 - k/N) rho^k), rho = exp(-dt / tau) the correlation of
        neighbouring samples (dt = 1 / sample_rate_Hz; exponential correlation: the
        variance of a mean of correlated samples, e.g. Bendat and Piersol, *Random Data*).
        N for samples far apart, 1 for samples much closer than tau."""
        n = self.samples_averaged
        rho = math.exp(-1.0 / (self.sample_rate_Hz * self.noise_correlation_time_s))
        k = np.arange(1, n)
        return n / (1.0 + 2.0 * float(np.sum((1.0 - k / n) * rho ** k)))

    @property
    def flicker_band_Hz(self) -> tuple[float, float]:
        """The band a reading's 1/f noise spans (Hz): from 1 / ``tare_interval_s`` (the
        tare removes what is slower) to the averaging window's noise bandwidth,
        ``sample_rate_Hz`` / (2 ``samples_averaged``) (the mean of N samples is a boxcar of
        N / f_s seconds), or the chain's noise bandwidth where that is lower; empty (f_hi =
        f_lo) when the window is as long as the interval."""
        f_lo = 1.0 / self.tare_interval_s
        f_hi = min(self.noise_bandwidth_Hz, self.sample_rate_Hz / (2.0 * self.samples_averaged))
        return f_lo, max(f_hi, f_lo)

    @property
    def volts_per_strain(self) -> float:
        """Linearised quarter-bridge gain at the DAQ: G V_ex GF / 4 (V per unit strain)."""
        return self.amplifier_gain * self.excitation_V * self.gauge_factor / 4.0

    @property
    def lsb_V(self) -> float:
        """One ADC step over the +/- range (V)."""
        return 2.0 * self.daq_range_V / 2 ** self.daq_bits

    def derived_json(self) -> dict:
        return {"volts_per_strain": self.volts_per_strain,
                "grid_power_density_W_per_mm2": self.grid_power_density_W_per_mm2,
                "lead_resistance_ohm": self.lead_resistance_ohm,
                "noise_bandwidth_Hz": self.noise_bandwidth_Hz,
                "noise_correlation_time_s": self.noise_correlation_time_s,
                "effective_samples": self.effective_samples,
                "flicker_band_Hz": list(self.flicker_band_Hz)}


#: Carrier beyond the grid at each side across the sheet (mm): catalogue outlines of
#: 0.6 mm grids are about 2.5 x 2 mm.
CARRIER_SIDE_MM = 0.5


def carrier_width_mm(grid_width_mm: float, sheet_mm: float) -> float:
    """Width of the gauge's carrier across the sheet: the grid and a side margin each
    way, no wider than the sheet (mm)."""
    return min(grid_width_mm + 2 * CARRIER_SIDE_MM, sheet_mm)


def _nearest(table: Mapping[float, float], key: float) -> float | None:
    """The table's value at ``key`` when it is one of the table's keys, else None."""
    for k, v in table.items():
        if math.isclose(k, key, rel_tol=1e-9):
            return v
    return None


def chosen_daq_range(ranges_V, signal_V: float, margin: float) -> tuple[float, bool]:
    """The smallest of ``ranges_V`` (+/- V) that holds ``margin`` x ``signal_V`` (V), and
    whether one does (else the largest range, False)."""
    need = margin * abs(signal_V)
    holding = sorted(r for r in ranges_V if r >= need)
    return (holding[0], True) if holding else (max(ranges_V), False)


#: The gauge series whose data sheet gives the default gauge-factor temperature coefficient.
GF_TC_SERIES = "HBM Y series"


def gauge_factor_tc_source(gauge) -> str:
    """Where the default temperature coefficient of the gauge factor comes from, for the
    design's library gauge: the data sheet of :data:`GF_TC_SERIES` where the gauge is of that
    series; for any other, a typical constantan value from that data sheet, the gauge's own
    data sheet governing (the catalogue entry names the gauge it is).

    Args:
        gauge: the library :class:`~tactcad.vocabulary.material_library.StrainGauge`.

    Returns:
        The source in words.
    """
    value = "temperature coefficient of the gauge factor about 115 x 1e-6 /K"
    if gauge.description.startswith(GF_TC_SERIES):
        return f"library gauge {gauge.name}: {GF_TC_SERIES} data sheet: {value}"
    return (f"typical of constantan foil ({GF_TC_SERIES} data sheet: {value}), not a figure "
            f"of library gauge {gauge.name} ({gauge.description}): its own data sheet governs; "
            "state readout.gauge_factor_tc_pct_per_100K from it")


#: Most read-out chains :func:`readout_of` keeps in a process: a design search reads the
#: chain of every candidate's plan (its stops, limits and verification matrix), and every
#: candidate of a search has the same ``[readout]`` and gauge.
READOUTS_KEPT = 256
_READOUTS: dict[tuple, "ReadoutChain"] = {}


def readout_of(raw: Mapping[str, Any], gauge) -> ReadoutChain:
    """The read-out chain of a design's raw tables (validated before): a function of their
    ``[readout]`` table and the gauge alone (:func:`resolved_readout`), kept per process
    by the two (the table's entries by their type and repr, so 2 and 2.0 are apart); the
    chain is frozen, so the kept one is shared.

    Args:
        raw: the design's tables (``[readout]`` optional).
        gauge: the design's library :class:`~tactcad.vocabulary.material_library.StrainGauge`
            (gauge factor and resistance unless the file gives them).

    Returns:
        The chain (:func:`resolved_readout`'s).
    """
    table = raw.get("readout") if isinstance(raw, Mapping) else None
    try:
        key = (gauge, readout_key(table))
        kept = _READOUTS.get(key)
    except TypeError:  # a gauge or an entry that does not hash: not a library's or TOML's
        return resolved_readout(raw, gauge)
    if kept is None:
        kept = resolved_readout(raw, gauge)
        if len(_READOUTS) >= READOUTS_KEPT:
            _READOUTS.clear()
        _READOUTS[key] = kept
    return kept


def readout_key(table: Any) -> tuple:
    """A key of a ``[readout]`` table that tells apart every two tables a chain may tell
    apart: each entry by its key, its type and its repr (lists item by item), in the
    table's order.

    Args:
        table: the table (a mapping), or anything else (no table: its type alone).

    Returns:
        A hashable key.
    """
    if not isinstance(table, Mapping):
        return ("no table", type(table).__name__)
    return tuple((k, _entry_key(v)) for k, v in table.items())


def _entry_key(value: Any) -> tuple:
    if isinstance(value, (list, tuple)):
        return (type(value).__name__, tuple(_entry_key(v) for v in value))
    return (type(value).__name__, repr(value))


def resolved_readout(raw: Mapping[str, Any], gauge) -> ReadoutChain:
    """:func:`readout_of` worked out afresh.

    Args:
        raw: the design's tables (``[readout]`` optional).
        gauge: the design's library :class:`~tactcad.vocabulary.material_library.StrainGauge`
            (gauge factor and resistance unless the file gives them).

    Returns:
        The chain: the table's values, the rest from the gauge and the defaults, each with
        its source.
    """
    gs = dict(gauge.sources)
    from_gauge = {"gauge_factor": (gauge.gauge_factor, gs.get("gauge_factor", "")),
                  "gauge_resistance_ohm": (gauge.resistance_ohm, gs.get("resistance_ohm", "")),
                  "gauge_backing_thickness_mm": (gauge.backing_thickness_mm,
                                                 gs.get("backing_thickness_mm", "")),
                  "adhesive_thickness_mm": (gauge.adhesive_thickness_mm,
                                            gs.get("adhesive_thickness_mm", "")),
                  "gauge_backing_modulus_MPa": (gauge.backing_modulus_MPa,
                                                gs.get("backing_modulus_MPa", ""))}
    values, sources = section_with_defaults(raw, "readout", {
        **{k: (v, f"library gauge {gauge.name}: {why}".rstrip(": "))
           for k, (v, why) in from_gauge.items()}, **DEFAULTS,
        "gauge_factor_tc_pct_per_100K": (DEFAULTS["gauge_factor_tc_pct_per_100K"][0],
                                         gauge_factor_tc_source(gauge))})
    if values["excitation_V"] is None:
        values["excitation_V"] = tn502_excitation_V(
            float(values["gauge_resistance_ohm"]),
            float(values["grid_length_mm"]) * float(values["grid_width_mm"]))
    gain = float(values["amplifier_gain"])
    if values["bandwidth_Hz"] is None:
        bw = (_nearest(AD621_BANDWIDTH_HZ, gain) if is_default_amplifier(values["amplifier"])
              else None)
        values["bandwidth_Hz"] = bw if bw is not None else 10e3
        if bw is None:
            sources["bandwidth_Hz"] = "assumption: 10 kHz noise bandwidth (no data for this gain)"
    if not is_default_amplifier(values["amplifier"]) and sources["amplifier_gain"] != "design file":
        sources["amplifier_gain"] = (f"assumption: gain {gain:g} (the {DEFAULT_AMPLIFIER}'s "
                                     f"pin-strapped 100; state readout.amplifier_gain for "
                                     f"{values['amplifier']})")
    if values["amplifier_flicker_nV_per_rtHz_at_1Hz"] is None:
        if is_default_amplifier(values["amplifier"]):
            values["amplifier_flicker_nV_per_rtHz_at_1Hz"] = flicker_density_at_1Hz(
                AD621_LOW_BAND_NOISE_UV_PP, AD621_LOW_BAND_HZ,
                float(DEFAULTS["amplifier_noise_nV_per_rtHz"][0]))
        else:
            values["amplifier_flicker_nV_per_rtHz_at_1Hz"] = 0.0
            sources["amplifier_flicker_nV_per_rtHz_at_1Hz"] = (
                f"not stated for {values['amplifier']}: its 1/f noise is left out (state "
                "readout.amplifier_flicker_nV_per_rtHz_at_1Hz from its data sheet's 0.1-10 Hz "
                "figure)")
    values["daq_ranges_V"] = tuple(float(r) for r in values["daq_ranges_V"])
    if values["daq_range_V"] is None:  # the smallest range for the largest signal in service
        signal = (gain * float(values["excitation_V"]) * float(values["gauge_factor"]) / 4.0
                  * gauge.fatigue_strain)
        rng, holds = chosen_daq_range(values["daq_ranges_V"], signal,
                                      float(values["daq_range_margin"]))
        values["daq_range_V"] = rng
        sources["daq_range_V"] = (
            f"chosen: +/-{rng:g} V, the smallest of readout.daq_ranges_V holding "
            f"{float(values['daq_range_margin']):g} x {signal:.3g} V, the signal at the gauge's "
            f"fatigue strain {gauge.fatigue_strain:g} ({gauge.name})" if holds else
            f"chosen: +/-{rng:g} V, the largest of readout.daq_ranges_V; none holds "
            f"{float(values['daq_range_margin']):g} x {signal:.3g} V, the signal at the gauge's "
            f"fatigue strain: lower readout.amplifier_gain or readout.excitation_V")
    if values["filter_order"] == 0:
        values["filter_corner_Hz"] = math.inf
        sources["filter_corner_Hz"] = "no anti-alias filter (readout.filter_order = 0)"
    if values["daq_noise_uV_rms"] is None:
        noise = _nearest(NI_6258_NOISE_UV_RMS, float(values["daq_range_V"])) \
            if values["daq"] == "NI USB-6258" else None
        if noise is None:  # between its ranges or another DAQ: scale with the range
            noise = NOISE_UV_PER_V_RANGE * float(values["daq_range_V"])
            sources["daq_noise_uV_rms"] = ("assumption: 28 ppm of the range, as the NI 625x "
                                           "random noise at +/-5 and 10 V")
        values["daq_noise_uV_rms"] = noise
    return ReadoutChain(gauge_name=gauge.name, sources=tuple(sorted(sources.items())),
                        **{k: values[k] for k in ReadoutChain.__dataclass_fields__
                           if k not in ("gauge_name", "sources")})
