"""Thermal drift of each element's gauge read-out: zero and span per kelvin, self-heating,
and the K_obj error they cause across the reading's force range.

A temperature change moves a strain-gauge force reading two ways: its zero (an offset in
newtons, whatever the load) and its span (a relative change of the reading, proportional to
the load). They are kept apart because they reach K_obj differently.

Zero (offset) per kelvin, as an equivalent tip force (apparent strain / grid strain per N):

* Thermal output (apparent strain). Micro-Measurements Tech Note TN-504 ("Strain Gage
  Thermal Output and Gage Factor Variation with Temperature") gives a gauge's thermal output
  on a substrate S per kelvin as

      eps_TO / dT = beta_G / F_G + c (alpha_S - alpha_G),   c = (1 + K_t) / (1 - nu_0 K_t)

  (beta_G: the grid's resistance temperature coefficient, F_G its gauge factor, alpha_G its
  expansion, K_t the transverse sensitivity, nu_0 = 0.285 the Poisson ratio of the maker's
  calibration beam). A self-temperature-compensated (STC) gauge's alloy is treated so that
  the right side vanishes on a substrate of alpha_STC, i.e. beta_G / F_G = c (alpha_G -
  alpha_STC); what is left near room temperature is

      eps_TO / dT = c (alpha_S - alpha_STC)                                    (1/K).

  The STC number is the matched expansion in ppm/degF (06: 10.8 ppm/K, steel; 13: 23.4 ppm/K,
  aluminium). The lot's residual thermal-output polynomial is not included.
* Lead wires (Micro-Measurements Tech Tip TT-612, "The Three-Wire Quarter-Bridge Circuit").
  A two-wire quarter bridge puts both leads (2 R_L) in series with the gauge: their change
  with temperature, 2 R_L TCR_Cu dT, reads as an apparent strain 2 R_L TCR_Cu / (F_G (R_g +
  2 R_L)) per kelvin. A three-wire one puts one lead in the gauge's arm and one in the
  adjacent completion arm: the bridge stays balanced while both leads share one temperature
  (zero to first order). The leads are taken to change temperature with the element (worst
  case: the whole lead length sees the same step).

Span per kelvin (relative change of the force reading, at any load):

* Modulus. The gauge reads strain; a force F bends the web to eps = M c / (E I), so the
  strain per newton goes as 1 / E: its term is -(1/E) dE/dT, the grade's
  ``youngs_modulus_tc_per_K`` (6061-T6: +5.28e-4 /K from the NIST cryogenic E(T) fit).
* Expansion. All lengths grow by alpha_S dT; the strain per newton 6 L / (E b t^2) goes as
  1 / length^2: -2 alpha_S.
* Gauge factor: its temperature coefficient (``gauge_factor_tc_pct_per_100K``).
* Lead wires (TT-612): the leads in the gauge's arm (n = 2 two-wire, 1 three-wire) desensitise
  the bridge by R_g / (R_g + n R_L); that factor moves by -n R_L TCR_Cu / (R_g + n R_L) per
  kelvin. The calibration absorbs the static part; only this change drifts.

A load cell's span drift is the sum of these unless compensated; a half-bridge dummy gauge
does not touch it (the dummy carries no strain).

Self-heating (TN-502, "Optimizing Strain Gage Excitation Levels"; grid form from TN-504's
relation). The quarter-bridge gauge dissipates P = V_ex^2 / (4 R_g); its grid of area
L_g w_g warms above the element by dT_g = P / (h L_g w_g) (``[readout]
gauge_heat_transfer_W_per_mm2_K``). The substrate under it stays at the element's
temperature, so the substrate-mismatch form above does not apply: the grid's own resistance
change beta_G dT_g and its restrained expansion -c alpha_G dT_g give, with the STC condition,

      eps_grid = beta_G / F_G dT_g - c alpha_G dT_g = -c alpha_STC dT_g.

It is an offset at switch-on (the tare removes it once the grid is warm; it comes back when
the excitation changes). A dummy gauge of the same lot and power cancels it.

Half bridge with a dummy gauge: an unstrained gauge of the same lot on the same material in
the adjacent arm has the same thermal output, leads and self-heating; the bridge subtracts
them (the zero terms cancel while both share one temperature); the span terms stay.

K_obj (eq. 1-3). Each force is read through its own element, so R = F_m K_r / (F_r K_m):

* zero: each reading is off by its offset f dT, so R moves by R (f_m / F_m - f_r / F_r) dT
  and K_obj by dK_obj/dR times that. F_r is the reference element's force, F_m = F_r R
  K_m / K_r: the error scales as 1 / F. At full scale it is the smallest; at 10 % of full
  scale ten times larger. :data:`READING_FORCE_FRACTIONS` are the force levels reported.
* span: the gauge factor and lead terms are common to both elements of a unit and cancel in
  R; the spring's own terms do not. Both springs' K scale by (1 + (1/E) dE/dT dT)(1 +
  alpha_S dT) (K ~ E x length), and R is a function of K_obj / K only (eq. 2), so eq. 3 with
  the calibration-temperature K returns K_obj / that factor: about -((1/E) dE/dT + alpha_S)
  per kelvin, whatever the force. A dummy gauge does not cancel it.

Units: K, ppm/K, 1/K, N, N/K, W, mm, ohm; strain dimensionless.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from tactcad.design.array_plan import Plan
from tactcad.design.readout_section import (TN502_POWER_DENSITY_W_PER_MM2, ReadoutChain)
from tactcad.errors import DesignError
from tactcad.mechanics.readout_chain import (force_resolution_N, grid_strain_error_rel,
                                             grid_strain_per_N, noise_budget_V, readout_chain)
from tactcad.mechanics.verdicts import deciding_item, judged

#: Poisson ratio of the calibration beam of the maker's thermal-output data (TN-504).
CALIBRATION_POISSON = 0.285
#: STC numbers of foil gauge series (ppm/degF of the matched substrate), Micro-Measurements
#: Tech Note TN-505 (Strain Gage Selection), self-temperature-compensation numbers.
STC_NUMBERS = (0, 3, 5, 6, 9, 13, 15, 18, 30, 40, 50)
PPM_PER_F_TO_PER_K = 1.8
#: Resistance temperature coefficient of annealed copper at 20 C (1/K), IEC 60028
#: (International Standard of Resistance for Copper): 0.00393 /K.
COPPER_TCR_PER_K = 3.93e-3
#: Force levels of the reading the K_obj drift is reported at: the reference element's force
#: as a fraction of full scale (the zero part grows as 1 / F; 10 % is the worst reported).
READING_FORCE_FRACTIONS = (0.1, 0.25, 0.5, 1.0)
#: Leads in the gauge's bridge arm per connection (TT-612).
LEADS_IN_GAUGE_ARM = {"two-wire": 2, "three-wire": 1}


def stc_ppm_per_K(stc_number: float) -> float:
    """An STC number (ppm/degF) as the matched expansion in ppm/K (06 -> 10.8)."""
    return stc_number * PPM_PER_F_TO_PER_K


def matched_stc_ppm_per_K(substrate_cte_ppm_per_K: float) -> tuple[float, int]:
    """(ppm/K, STC number) of the gauge series nearest the substrate's CTE."""
    n = min(STC_NUMBERS, key=lambda s: abs(stc_ppm_per_K(s) - substrate_cte_ppm_per_K))
    return stc_ppm_per_K(n), n


def transverse_factor(transverse_sensitivity: float) -> float:
    """TN-504's (1 + K_t) / (1 - nu_0 K_t): the gauge's reading of an equal biaxial strain
    relative to the uniaxial calibration."""
    kt = transverse_sensitivity
    return (1 + kt) / (1 - CALIBRATION_POISSON * kt)


def apparent_strain_per_K(substrate_cte_ppm_per_K: float, stc_ppm: float,
                          transverse_sensitivity: float = 0.0) -> float:
    """TN-504 thermal output of an STC gauge whose grid and substrate share one temperature,
    per kelvin (strain/K): (1 + K_t) / (1 - nu_0 K_t) (alpha_S - alpha_STC)."""
    return transverse_factor(transverse_sensitivity) * (substrate_cte_ppm_per_K - stc_ppm) * 1e-6


def grid_heating_strain(stc_ppm: float, grid_rise_K: float,
                        transverse_sensitivity: float = 0.0) -> float:
    """Apparent strain of an STC gauge whose grid alone is ``grid_rise_K`` above its substrate
    (self-heating): -(1 + K_t) / (1 - nu_0 K_t) alpha_STC dT_g (module docstring).

    Args:
        stc_ppm: the gauge's matched expansion alpha_STC (ppm/K).
        grid_rise_K: grid temperature above the substrate (K).
        transverse_sensitivity: K_t.

    Returns:
        Apparent strain (dimensionless; negative for a warm grid).
    """
    return -transverse_factor(transverse_sensitivity) * stc_ppm * 1e-6 * grid_rise_K


def self_heating_K(chain: ReadoutChain) -> tuple[float, float]:
    """(power in the grid W, temperature rise of the grid above the element K) of a
    quarter-bridge gauge at its excitation (equal arms: P = V_ex^2 / (4 R_g))."""
    power = chain.excitation_V ** 2 / (4.0 * chain.gauge_resistance_ohm)
    area = chain.grid_length_mm * chain.grid_width_mm
    return power, power / (chain.gauge_heat_transfer_W_per_mm2_K * area)


def lead_wire_terms(chain: ReadoutChain) -> dict[str, float]:
    """The leads' zero and span drift per kelvin of lead temperature (TT-612).

    Returns:
        ``leads_in_gauge_arm`` (n), ``lead_resistance_ohm`` (one conductor),
        ``desensitisation`` (n R_L / (R_g + n R_L), static, absorbed by the calibration),
        ``zero_strain_per_K`` (apparent strain per K: two-wire 2 R_L TCR / (F_G (R_g + 2 R_L)),
        three-wire 0), ``span_rel_per_K`` (-n R_L TCR / (R_g + n R_L)).
    """
    n = LEADS_IN_GAUGE_ARM[chain.lead_wires]
    r_l, r_g = chain.lead_resistance_ohm, chain.gauge_resistance_ohm
    arm = r_g + n * r_l
    zero = (n * r_l * COPPER_TCR_PER_K / (chain.gauge_factor * arm)
            if chain.lead_wires == "two-wire" else 0.0)
    return {"leads_in_gauge_arm": n, "lead_resistance_ohm": r_l,
            "desensitisation": n * r_l / arm, "zero_strain_per_K": zero,
            "span_rel_per_K": -n * r_l * COPPER_TCR_PER_K / arm}


@dataclass(frozen=True)
class ThermalSetting:
    """The thermal inputs of one design, resolved with their sources.

    Attributes:
        substrate_cte_ppm_per_K: alpha_S (ppm/K). stc_ppm_per_K: alpha_STC (ppm/K).
        gf_tc_per_K: gauge factor temperature coefficient (1/K).
        transverse_sensitivity: K_t. dummy: a half-bridge dummy gauge.
        modulus_tc_per_K: (1/E) dE/dT of the element (1/K).
        modulus_tc_sourced: False when the grade's coefficient is a stand-in (unsourced).
        lead_wires: ``"three-wire"`` or ``"two-wire"``. sources: key -> where it comes from.
    """

    substrate_cte_ppm_per_K: float
    stc_ppm_per_K: float
    gf_tc_per_K: float
    transverse_sensitivity: float
    dummy: bool
    sources: dict
    modulus_tc_per_K: float = 0.0
    modulus_tc_sourced: bool = True
    lead_wires: str = "three-wire"

    def as_json(self) -> dict:
        return {"substrate_cte_ppm_per_K": self.substrate_cte_ppm_per_K,
                "gauge_stc_ppm_per_K": self.stc_ppm_per_K,
                "gauge_factor_tc_per_K": self.gf_tc_per_K,
                "gauge_transverse_sensitivity": self.transverse_sensitivity,
                "substrate_modulus_tc_per_K": self.modulus_tc_per_K,
                "substrate_modulus_tc_sourced": self.modulus_tc_sourced,
                "lead_wires": self.lead_wires,
                "dummy_gauge": "half-bridge" if self.dummy else "none", "sources": self.sources}


def _grade_of(plan: Plan, key: str, what: str, allowed: str):
    """The plan's library grade, or a DesignError naming the [readout] key to state instead."""
    from tactcad.vocabulary.material_library import material_grade

    if plan.material.grade is None:
        raise DesignError(f"readout.{key}", None, allowed,
                          f"the material names no library grade, so its {what} is unknown")
    return material_grade(plan.material.grade)


def thermal_setting(plan: Plan, chain: ReadoutChain | None = None) -> ThermalSetting:
    """Substrate CTE and modulus coefficient (the file's, else the grade's), STC (the file's,
    else the series nearest the substrate, said so), gauge factor TC, K_t, leads and dummy.

    Raises:
        DesignError: no CTE or modulus coefficient known (the material names no grade and
            ``[readout]`` states none).
    """
    chain = chain or readout_chain(plan)
    src = dict(chain.sources)
    cte = chain.substrate_cte_ppm_per_K
    if cte is None:
        grade = _grade_of(plan, "substrate_cte_ppm_per_K", "CTE", "a number 0 ... 200 ppm/K")
        cte = grade.cte_ppm_per_K
        src["substrate_cte_ppm_per_K"] = f"grade {grade.name}: {grade.source('cte_ppm_per_K')}"
    modulus_tc, sourced = chain.substrate_modulus_tc_per_K, True
    if modulus_tc is None:
        grade = _grade_of(plan, "substrate_modulus_tc_per_K", "modulus coefficient",
                          "a number -0.002 ... 0.0001 1/K")
        modulus_tc = grade.youngs_modulus_tc_per_K
        sourced = grade.is_sourced("youngs_modulus_tc_per_K")
        src["substrate_modulus_tc_per_K"] = (f"grade {grade.name}: "
                                             f"{grade.provenance('youngs_modulus_tc_per_K')}")
    stc = chain.gauge_stc_ppm_per_K
    if stc is None:
        stc, n = matched_stc_ppm_per_K(cte)
        src["gauge_stc_ppm_per_K"] = (f"not stated: STC {n:02d} ({stc:.3g} ppm/K), the series "
                                      f"nearest the element's CTE {cte:g} ppm/K")
    keys = ("substrate_cte_ppm_per_K", "substrate_modulus_tc_per_K", "gauge_stc_ppm_per_K",
            "gauge_factor_tc_pct_per_100K", "gauge_transverse_sensitivity", "excitation_V",
            "gauge_heat_transfer_W_per_mm2_K", "lead_wires", "lead_length_mm",
            "lead_resistance_ohm_per_m", "dummy_gauge")
    return ThermalSetting(cte, stc, chain.gauge_factor_tc_pct_per_100K / 100.0 / 100.0,
                          chain.gauge_transverse_sensitivity, chain.dummy_gauge == "half-bridge",
                          {k: src[k] for k in keys}, modulus_tc, sourced, chain.lead_wires)


#: The [readout] keys a design may leave unstated that the thermal model resolves (the
#: material grade's CTE and modulus coefficient, the STC series matched to that CTE):
#: {chain key: :class:`~tactcad.mechanics.thermal_drift.ThermalSetting` attribute}.
THERMAL_RESOLVED = {"substrate_cte_ppm_per_K": "substrate_cte_ppm_per_K",
                    "gauge_stc_ppm_per_K": "stc_ppm_per_K",
                    "substrate_modulus_tc_per_K": "modulus_tc_per_K"}


def with_thermal_values(plan: Plan, chain: ReadoutChain) -> ReadoutChain:
    """``chain`` with the thermal keys the design leaves unstated set to the values
    ``tactcad thermal`` uses, and their sources to where those come from, so that a key
    names one quantity in both outputs.

    Args:
        plan: the design. chain: its resolved ``[readout]``.

    Returns:
        The chain (ppm/K, 1/K); unchanged where the material names no library grade, so
        the values stay unknown (``None``, their sources saying what is missing).
    """
    if all(getattr(chain, key) is not None for key in THERMAL_RESOLVED):
        return chain
    try:
        setting = thermal_setting(plan, chain)
    except DesignError:
        return chain
    values = {key: getattr(setting, attr) for key, attr in THERMAL_RESOLVED.items()
              if getattr(chain, key) is None}
    sources = {**dict(chain.sources), **{key: setting.sources[key] for key in values}}
    return replace(chain, **values, sources=tuple(sources.items()))


def span_terms_per_K(setting: ThermalSetting, chain: ReadoutChain) -> dict[str, float]:
    """The span drift of a force reading per kelvin, term by term (relative, 1/K).

    Returns:
        ``modulus`` (-(1/E) dE/dT), ``expansion`` (-2 alpha_S), ``gauge_factor`` (its TC),
        ``lead_wires`` (-n R_L TCR / (R_g + n R_L)); their sum is the span drift.
    """
    return {"modulus": -setting.modulus_tc_per_K,
            "expansion": -2.0 * setting.substrate_cte_ppm_per_K * 1e-6,
            "gauge_factor": setting.gf_tc_per_K,
            "lead_wires": lead_wire_terms(chain)["span_rel_per_K"]}


def spring_stiffness_scale(setting: ThermalSetting, delta_T_K: float) -> float:
    """Factor on every element's K after ``delta_T_K``: (1 + (1/E) dE/dT dT)(1 + alpha_S dT)
    (K ~ E x length)."""
    return ((1.0 + setting.modulus_tc_per_K * delta_T_K)
            * (1.0 + setting.substrate_cte_ppm_per_K * 1e-6 * delta_T_K))


def zero_strain_per_K(setting: ThermalSetting, chain: ReadoutChain) -> float:
    """Apparent strain per kelvin the quarter bridge reads at no load: thermal output plus the
    leads' (0 with a half-bridge dummy gauge, which subtracts both)."""
    if setting.dummy:
        return 0.0
    return (apparent_strain_per_K(setting.substrate_cte_ppm_per_K, setting.stc_ppm_per_K,
                                  setting.transverse_sensitivity)
            + lead_wire_terms(chain)["zero_strain_per_K"])


@dataclass(frozen=True)
class KobjThermalError:
    """One sensing unit's K_obj error after a temperature step (:func:`kobj_thermal_error`).

    Attributes:
        element, reference_element: the measuring element and its reference (numbers).
        k_obj_N_per_mm: the K_obj values (N/mm).
        zero_rel: relative K_obj error from the zero drift (signed, per K_obj).
        span_rel: relative K_obj error from the springs' span drift (signed; the same for
            every K_obj and force).
        zero_force_m_N_per_K, zero_force_r_N_per_K: the apparent tip force per kelvin the
            measuring and the reference element read at no load (N/K; 0 with a dummy gauge).
    """

    element: int
    reference_element: int
    k_obj_N_per_mm: np.ndarray
    zero_rel: np.ndarray
    span_rel: np.ndarray
    zero_force_m_N_per_K: float = 0.0
    zero_force_r_N_per_K: float = 0.0

    @property
    def total_rel(self) -> np.ndarray:
        """zero + span (signed) per K_obj."""
        return self.zero_rel + self.span_rel


def _part_figures(plan: Plan, chain: ReadoutChain, model: str,
                  stiffness: dict[str, float] | None) -> dict[str, dict]:
    """Per distinct part: K (N/mm), its error estimate, the grid strain per newton and the
    grid strain's own error estimate (``stiffness --json``'s ``grid_strain_error_rel``)."""
    from tactcad.mechanics.ladder import estimate

    out = {}
    for name, g in plan.distinct_elements.items():
        if stiffness is None:
            est = estimate(model, g, plan.material)
            k, err = est.stiffness_N_per_mm, est.error_estimate_rel
        else:
            k, err = stiffness[name], None
        read = grid_strain_per_N(g, plan.material, chain, model)
        out[name] = {"K": k, "err": err, "eps": read["grid"],
                     "eps_err": grid_strain_error_rel(read)}
    return out


def _unit_error(km: float, kr: float, fm: float, fr: float, k_obj: np.ndarray,
                force_N: float, delta_T_K: float, stiffness_scale: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """(zero, span) relative K_obj error of one unit (eq. 1-3), offsets fm, fr (N/K) at the
    reference force ``force_N``."""
    from tactcad.mechanics.lumped_model import deflection_ratio, sensitivity

    km_a, kr_a = np.full_like(k_obj, km), np.full_like(k_obj, kr)
    R = deflection_ratio(km_a, kr_a, k_obj).value
    F_m = force_N * R * km / kr
    R_read = R * (1.0 + fm * delta_T_K / F_m) / (1.0 + fr * delta_T_K / force_N)
    zero = sensitivity(R, km_a, kr_a).value * (R_read - R) / k_obj
    span = np.full_like(k_obj, 1.0 / stiffness_scale - 1.0)
    return zero, span


def kobj_thermal_error(plan: Plan, chain: ReadoutChain | None, force_N: float,
                       delta_T_K: float, k_obj_N_per_mm, model: str = "closed-form",
                       stiffness: dict[str, float] | None = None) -> list[KobjThermalError]:
    """The zero and span contributions of a temperature step to K_obj's relative error, per
    sensing unit, for the K_obj error budget.

    The zero part (thermal output, two-wire leads; none with a half-bridge dummy) enters R
    through each element's offset and scales as 1 / ``force_N``; the span part (modulus and
    expansion of both springs) is K_obj / K_obj_true - 1 = 1 / ((1 + (1/E) dE/dT dT)(1 +
    alpha_S dT)) - 1, whatever the force. The gauge factor's and the leads' span terms are
    common to both elements and cancel in R. The zero part is first order in the offsets
    (dK_obj/dR x the exact change of R).

    Args:
        plan: the design. chain: its read-out chain (None: the plan's).
        force_N: force on the reference element of each unit (N), > 0.
        delta_T_K: temperature step from calibration (K), element and leads together.
        k_obj_N_per_mm: K_obj values (N/mm), e.g. the requirements' range at
            :data:`tactcad.mechanics.resolution.KOBJ_POINTS` log-spaced points.
        model: ladder level for K and the strain per newton.
        stiffness: K (N/mm) per distinct part already computed at ``model`` (None estimates).

    Returns:
        One :class:`KobjThermalError` per measuring element that has a stiffer reference.

    Raises:
        DesignError: ``force_N`` not > 0, or no CTE / modulus coefficient known.
    """
    if not force_N > 0:
        raise DesignError("force_N", force_N, "a force > 0 N on the reference element")
    chain = chain or readout_chain(plan)
    s = thermal_setting(plan, chain)
    k_obj = np.atleast_1d(np.asarray(k_obj_N_per_mm, float))
    parts = _part_figures(plan, chain, model, stiffness)
    zero_eps = zero_strain_per_K(s, chain)
    scale = spring_stiffness_scale(s, delta_T_K)
    out = []
    for slot in plan.slots:
        ref = plan.reference_for(slot)
        d, r = parts[slot.geometry.part_name], parts[ref.geometry.part_name]
        if not d["K"] < r["K"] * (1 - 1e-9):
            continue
        f_m, f_r = zero_eps / d["eps"], zero_eps / r["eps"]
        zero, span = _unit_error(d["K"], r["K"], f_m, f_r, k_obj, force_N, delta_T_K, scale)
        out.append(KobjThermalError(slot.number, ref.number, k_obj, zero, span, float(f_m),
                                    float(f_r)))
    return out


@dataclass(frozen=True)
class ThermalReport:
    """What ``tactcad thermal`` prints; :meth:`as_json` is its JSON.

    ``span_terms_per_K``: :func:`span_terms_per_K`; ``lead_wires``: :func:`lead_wire_terms`;
    ``self_heating_strain``: :func:`grid_heating_strain` at the grid's rise;
    ``force_fractions``: the reference element's force levels the K_obj error is given at.
    """

    design: str
    model: str
    setting: ThermalSetting
    apparent_strain_per_K: float
    grid_power_W: float
    self_heating_K: float
    full_scale_force_N: float
    records: list[dict]
    seconds: float
    span_terms_per_K: dict[str, float] = field(default_factory=dict)
    lead_wires: dict[str, float] = field(default_factory=dict)
    grid_power_density_W_per_mm2: float = 0.0
    self_heating_strain: float = 0.0
    force_fractions: tuple = READING_FORCE_FRACTIONS

    @property
    def span_rel_per_K(self) -> float:
        """Span drift of a force reading per kelvin (relative, signed): the sum of the terms."""
        return float(sum(self.span_terms_per_K.values()))

    @property
    def worst(self) -> dict:
        """The element with the largest drift per kelvin as read (after a dummy gauge)."""
        return max(self.records, key=lambda r: r["drift_N_per_K"])

    @property
    def worst_kobj(self) -> dict | None:
        """The measuring element with the largest K_obj error per kelvin over the force range
        (None without a unit)."""
        units = [r for r in self.records if r["kobj_error_rel_per_K"] is not None]
        return max(units, key=lambda r: r["kobj_error_rel_per_K"]) if units else None

    def as_json(self) -> dict:
        wk = self.worst_kobj
        return {"design": self.design, "model": self.model, "setting": self.setting.as_json(),
                "apparent_strain_per_K": self.apparent_strain_per_K,
                "span_terms_rel_per_K": self.span_terms_per_K,
                "span_rel_per_K": self.span_rel_per_K,
                "span_drift_N_per_K_at_full_scale":
                    self.full_scale_force_N * abs(self.span_rel_per_K),
                "lead_wires": self.lead_wires,
                "grid_power_W": self.grid_power_W,
                "grid_power_density_W_per_mm2": self.grid_power_density_W_per_mm2,
                "tn502_power_density_W_per_mm2": TN502_POWER_DENSITY_W_PER_MM2,
                "self_heating_K": self.self_heating_K,
                "self_heating_strain": self.self_heating_strain,
                "full_scale_force_N": self.full_scale_force_N,
                "force_fractions": list(self.force_fractions),
                "worst_drift_N_per_K": self.worst["drift_N_per_K"],
                "worst_element": self.worst["element"],
                "worst_kobj_element": wk["element"] if wk else None,
                "worst_kobj_error_rel_per_K": wk["kobj_error_rel_per_K"] if wk else None,
                "worst_kobj_force_fraction": min(self.force_fractions) if wk else None,
                "seconds": self.seconds, "elements": self.records,
                "notes": NOTES}


#: What the report's figures mean (the JSON's ``notes``; the text header says the same).
NOTES = ["zero_drift_N_per_K: thermal output (TN-504, (1+K_t)/(1-0.285 K_t)(alpha_S - "
         "alpha_STC); the lot's residual polynomial not included) plus two-wire leads (TT-612), "
         "as an equivalent tip force; a half-bridge dummy cancels it",
         "span: -(1/E)dE/dT - 2 alpha_S + TC_GF - n R_L TCR_Cu/(R_g + n R_L) of the reading per "
         "kelvin; span_drift_N_per_K at full scale; a dummy gauge does not cancel it",
         "drift_N_per_K: |zero| + F_FS |span| per kelvin (worst case, full scale)",
         "self_heating_offset_N: the grid warmer than its substrate, -(1+K_t)/(1-0.285 K_t) "
         "alpha_STC dT_grid / strain per N; an offset at switch-on, removed by the tare",
         "error_estimate_rel: the element's K's relative error estimate, and "
         "grid_strain_error_rel its grid_strain_per_N's, as `stiffness` names them",
         "kobj_error_rel_per_K: eq. 1-3, worst |zero| + |span| over the K_obj range at the "
         "lowest force fraction (reference element at that fraction of full scale); the zero "
         "part scales as 1/F, so the full-scale figure is the best case"]


def _unit_record(km: float, kr: float, fm: float, fr: float, k_obj: np.ndarray, F: float,
                 scale: float, fractions: tuple) -> dict:
    """K_obj error per kelvin of one unit at each force fraction: zero, span and their worst
    case |zero| + |span| (the thermal output's sign rests on the lot's residual, which is not
    modelled, so no cancellation is counted on)."""
    span = abs(1.0 / scale - 1.0)
    by_fraction, zero_fs = {}, None
    for phi in fractions:
        zero, _ = _unit_error(km, kr, fm, fr, k_obj, phi * F, 1.0, scale)
        by_fraction[f"{phi:g}"] = float(np.max(np.abs(zero))) + span
        if phi == max(fractions):
            zero_fs = float(np.max(np.abs(zero)))
    return {"kobj_zero_rel_per_K_at_full_scale": zero_fs,
            "kobj_span_rel_per_K": span,
            "kobj_error_rel_per_K_by_force_fraction": by_fraction,
            "kobj_error_rel_per_K_at_full_scale": by_fraction[f"{max(fractions):g}"],
            "kobj_error_rel_per_K": by_fraction[f"{min(fractions):g}"]}


def thermal_report(plan: Plan, requirements, model: str = "closed-form",
                   stiffness: dict[str, float] | None = None,
                   errors: dict[str, float] | None = None) -> ThermalReport:
    """Per element: zero and span drift per kelvin as tip forces, self-heating offset, and the
    K_obj error per kelvin across the reading's force range.

    Args:
        plan: the design. requirements: its requirements (full-scale force N, K_obj range).
        model: ladder level for K and the gauge strain per newton.
        stiffness, errors: K (N/mm) and its relative error estimate per distinct part already
            computed at ``model`` (``verify`` passes its own); ``None`` estimates them.

    Returns:
        The :class:`ThermalReport`.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
        DesignError: no CTE or modulus coefficient is known for the element's material.
    """
    from tactcad.mechanics.resolution import KOBJ_POINTS

    t0 = time.perf_counter()
    chain = readout_chain(plan)
    s = thermal_setting(plan, chain)
    app = apparent_strain_per_K(s.substrate_cte_ppm_per_K, s.stc_ppm_per_K,
                                s.transverse_sensitivity)
    leads = lead_wire_terms(chain)
    power, rise = self_heating_K(chain)
    heating_strain = grid_heating_strain(s.stc_ppm_per_K, rise, s.transverse_sensitivity)
    span_terms = span_terms_per_K(s, chain)
    span = sum(span_terms.values())
    scale = spring_stiffness_scale(s, 1.0)
    F, rng = requirements.full_scale_force_N, requirements.kobj_range_N_per_mm
    k_obj = np.geomspace(*rng, KOBJ_POINTS)
    given = stiffness is not None and errors is not None
    parts = _part_figures(plan, chain, model, stiffness if given else None)
    if given:
        for name in parts:
            parts[name]["err"] = errors[name]
    zero_read = zero_strain_per_K(s, chain)
    quarter = app + leads["zero_strain_per_K"]
    reading_noise_V = noise_budget_V(chain)["reading"]
    records = []
    for slot in plan.slots:
        d = parts[slot.geometry.part_name]
        ref = plan.reference_for(slot)
        r = parts[ref.geometry.part_name]
        zero_quarter = quarter / d["eps"]
        zero = zero_read / d["eps"] + 0.0  # + 0.0: a cancelled zero prints 0, not -0
        span_N = F * abs(span)
        rec = {"element": slot.number, "part": slot.geometry.part_name,
               "role": "reference" if slot.number == ref.number else "measuring",
               # K's error as `stiffness --json` names it; the grid strain's beside it
               "grid_strain_per_N": d["eps"], "grid_strain_error_rel": d["eps_err"],
               "error_estimate_rel": d["err"],
               "apparent_force_N_per_K": app / d["eps"],
               "lead_wire_force_N_per_K": leads["zero_strain_per_K"] / d["eps"],
               "zero_drift_N_per_K": zero,
               "span_drift_N_per_K": span_N,
               "gauge_factor_force_N_per_K": F * abs(s.gf_tc_per_K),
               "modulus_force_N_per_K": F * abs(span_terms["modulus"]),
               "drift_quarter_N_per_K": abs(zero_quarter) + span_N,
               "drift_N_per_K": abs(zero) + span_N,
               "half_bridge_cancels_N_per_K": abs(zero_quarter),
               "half_bridge_cancels_rel": abs(zero_quarter) / (abs(zero_quarter) + span_N)
               if abs(zero_quarter) + span_N else 0.0,
               "self_heating_offset_N": 0.0 if s.dummy else heating_strain / d["eps"],
               "force_resolution_N": force_resolution_N(chain, d["eps"], reading_noise_V),
               "reference_element": None if slot.number == ref.number else ref.number}
        if d["K"] < r["K"] * (1 - 1e-9):
            rec.update(_unit_record(d["K"], r["K"], zero_read / d["eps"], zero_read / r["eps"],
                                    k_obj, F, scale, READING_FORCE_FRACTIONS))
        else:
            rec.update({"kobj_zero_rel_per_K_at_full_scale": None, "kobj_span_rel_per_K": None,
                        "kobj_error_rel_per_K_by_force_fraction": None,
                        "kobj_error_rel_per_K_at_full_scale": None,
                        "kobj_error_rel_per_K": None})
        records.append(rec)
    return ThermalReport(plan.name, model, s, app, power, rise, F, records,
                         time.perf_counter() - t0, span_terms, leads,
                         chain.grid_power_density_W_per_mm2, heating_strain)


def thermal_record(plan: Plan, fig, req) -> dict | None:
    """``max_thermal_drift_N_per_K`` when the design states it (None otherwise): each
    element's drift per kelvin as read (zero + span at full scale), margin target / drift - 1,
    error the level's K error estimate of that element (the strain per newton comes from the
    same model), judged on its own (``elements``); the record shows the element with the worst
    verdict (among equals the largest drift; :func:`tactcad.mechanics.verdicts.deciding_item`)
    and the span and K_obj figures beside it."""
    from tactcad.design.requirements_section import stated_thermal_drift

    target = stated_thermal_drift(plan.raw)
    if target is None:
        return None
    rep = thermal_report(plan, req, fig.model, stiffness=fig.k, errors=fig.k_error)
    items = [judged({"element": r["element"], "drift_N_per_K": r["drift_N_per_K"],
                     "zero_drift_N_per_K": r["zero_drift_N_per_K"],
                     "span_drift_N_per_K": r["span_drift_N_per_K"],
                     "error_estimate_rel": r["error_estimate_rel"],
                     "margin_rel": target / r["drift_N_per_K"] - 1.0
                     if r["drift_N_per_K"] > 0 else None}) for r in rep.records]
    w = deciding_item(items)  # each element on its own error: the worst verdict decides
    wk = rep.worst_kobj
    return {"requirement": "max_thermal_drift_N_per_K", "target": target,
            "predicted": w["drift_N_per_K"], "error_estimate_rel": w["error_estimate_rel"],
            "margin_rel": w["margin_rel"], "model": fig.model,
            "pass": all(it["drift_N_per_K"] <= target for it in items),
            "binding_element": w["element"], "elements": items,
            "self_heating_K": rep.self_heating_K,
            "span_rel_per_K": rep.span_rel_per_K,
            "span_terms_rel_per_K": rep.span_terms_per_K,
            "substrate_modulus_tc_sourced": rep.setting.modulus_tc_sourced,
            "kobj_error_rel_per_K_worst": wk["kobj_error_rel_per_K"] if wk else None,
            "kobj_error_worst_element": wk["element"] if wk else None,
            "kobj_error_force_fraction": min(rep.force_fractions) if wk else None,
            "basis": "zero: TN-504 thermal output of the STC gauge and the leads (TT-612) / grid "
                     "strain per newton; span at full scale: modulus (1/E dE/dT), expansion, "
                     "gauge factor TC and leads"}
