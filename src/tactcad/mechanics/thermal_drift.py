"""Thermal drift of each element's gauge read-out: apparent strain, tip force and K_obj per kelvin.

Apparent strain (thermal output). Micro-Measurements Tech Note TN-504
("Strain Gage Thermal Output and Gage Factor Variation with Temperature")
gives a gauge's thermal output on a substrate S per kelvin as

    eps_TO / dT = beta_G / F_G + (1 + K_t) / (1 - nu_0 K_t) (alpha_S - alpha_G),

(beta_G: the grid's resistance temperature coefficient, F_G its gauge factor,
alpha_G its expansion, K_t the transverse sensitivity, nu_0 = 0.285 the
Poisson ratio of the maker's calibration beam). A self-temperature-compensated
(STC) gauge's alloy is heat treated so that the bracket vanishes on a
substrate of alpha_STC; subtracting that zero leaves, near room temperature,

    eps_TO / dT = (1 + K_t) / (1 - nu_0 K_t) (alpha_S - alpha_STC)      (1/K).

The STC number is the matched expansion in ppm/degF (06: 6 ppm/degF =
10.8 ppm/K, steel; 13: 23.4 ppm/K, aluminium). The lot's residual
thermal-output polynomial (printed on each package, a few microstrain per
kelvin away from 24 degC) is not included.

Gauge factor temperature coefficient. The reading at strain eps is GF(T) eps;
per kelvin it moves by eps_FS x TC_GF, i.e. the full-scale force times
TC_GF (N/K). Both elements of a unit move by the same factor, so R and K_obj
do not see it.

Equivalent tip force. Apparent strain / grid-averaged strain per newton
(:func:`tactcad.mechanics.readout_chain.gauge_strain_per_N` at the ladder
level asked; its error estimate is the level's K error estimate, the same
field gives both). Worst case per element: |apparent force| + F_FS |TC_GF|.

K_obj per kelvin (eq. 1-3): each force is read off by its own apparent
force f, so R = F_m K_r / (F_r K_m) moves by dR / R = f_m / F_m - f_r / F_r
(the reference pressed to F_FS, F_m = F_FS R K_m / K_r) and
dK_obj = |dK_obj / dR| dR; the worst over the required K_obj range.

Self-heating. Quarter bridge of four equal arms: the gauge dissipates
P = V_ex^2 / (4 R_g); its grid of area L_g w_g warms above the element by
dT = P / (h L_g w_g) with the grid-to-element heat transfer h
(``[readout] gauge_heat_transfer_W_per_mm2_K``).

Half bridge with a dummy gauge. An unstrained gauge of the same lot on the
same material in the adjacent arm has the same thermal output; the bridge
subtracts it, so the apparent-strain term and the self-heating offset cancel
(while both gauges share one temperature); the gauge-factor term stays.

Units: K, ppm/K, N, N/K, W, mm; strain dimensionless.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tactcad.design.array_plan import Plan
from tactcad.design.readout_section import ReadoutChain
from tactcad.errors import DesignError
from tactcad.mechanics.readout_chain import gauge_strain_per_N, readout_chain
from tactcad.mechanics.verdicts import deciding_item, judged

#: Poisson ratio of the calibration beam of the maker's thermal-output data (TN-504).
CALIBRATION_POISSON = 0.285
#: STC numbers of foil gauge series (ppm/degF of the matched substrate), Micro-Measurements
#: Tech Note TN-505 (Strain Gage Selection), self-temperature-compensation numbers.
STC_NUMBERS = (0, 3, 5, 6, 9, 13, 15, 18, 30, 40, 50)
PPM_PER_F_TO_PER_K = 1.8


def stc_ppm_per_K(stc_number: float) -> float:
    """An STC number (ppm/degF) as the matched expansion in ppm/K (06 -> 10.8)."""
    return stc_number * PPM_PER_F_TO_PER_K


def matched_stc_ppm_per_K(substrate_cte_ppm_per_K: float) -> tuple[float, int]:
    """(ppm/K, STC number) of the gauge series nearest the substrate's CTE."""
    n = min(STC_NUMBERS, key=lambda s: abs(stc_ppm_per_K(s) - substrate_cte_ppm_per_K))
    return stc_ppm_per_K(n), n


def apparent_strain_per_K(substrate_cte_ppm_per_K: float, stc_ppm: float,
                          transverse_sensitivity: float = 0.0) -> float:
    """TN-504 thermal output of an STC gauge per kelvin (strain/K):
    (1 + K_t) / (1 - nu_0 K_t) (alpha_S - alpha_STC)."""
    kt = transverse_sensitivity
    return (1 + kt) / (1 - CALIBRATION_POISSON * kt) * (substrate_cte_ppm_per_K - stc_ppm) * 1e-6


def self_heating_K(chain: ReadoutChain) -> tuple[float, float]:
    """(power in the grid W, temperature rise K) of a quarter-bridge gauge at its excitation."""
    power = chain.excitation_V ** 2 / (4.0 * chain.gauge_resistance_ohm)
    area = chain.grid_length_mm * chain.grid_width_mm
    return power, power / (chain.gauge_heat_transfer_W_per_mm2_K * area)


@dataclass(frozen=True)
class ThermalSetting:
    """The thermal inputs of one design, resolved with their sources."""

    substrate_cte_ppm_per_K: float
    stc_ppm_per_K: float
    gf_tc_per_K: float
    transverse_sensitivity: float
    dummy: bool
    sources: dict

    def as_json(self) -> dict:
        return {"substrate_cte_ppm_per_K": self.substrate_cte_ppm_per_K,
                "gauge_stc_ppm_per_K": self.stc_ppm_per_K,
                "gauge_factor_tc_per_K": self.gf_tc_per_K,
                "gauge_transverse_sensitivity": self.transverse_sensitivity,
                "dummy_gauge": "half-bridge" if self.dummy else "none", "sources": self.sources}


def thermal_setting(plan: Plan, chain: ReadoutChain | None = None) -> ThermalSetting:
    """Substrate CTE (the file's, else the grade's), STC (the file's, else the series nearest
    the substrate, said so), gauge factor TC, K_t and the dummy gauge.

    Raises:
        DesignError: no CTE known (the material names no grade and ``[readout]`` none).
    """
    from tactcad.vocabulary.material_library import material_grade

    chain = chain or readout_chain(plan)
    src = dict(chain.sources)
    cte = chain.substrate_cte_ppm_per_K
    if cte is None:
        if plan.material.grade is None:
            raise DesignError("readout.substrate_cte_ppm_per_K", None, "a number 0 ... 200 ppm/K",
                              "the material names no library grade, so its CTE is unknown")
        grade = material_grade(plan.material.grade)
        cte = grade.cte_ppm_per_K
        src["substrate_cte_ppm_per_K"] = f"grade {grade.name}: {grade.source('cte_ppm_per_K')}"
    stc = chain.gauge_stc_ppm_per_K
    if stc is None:
        stc, n = matched_stc_ppm_per_K(cte)
        src["gauge_stc_ppm_per_K"] = (f"not stated: STC {n:02d} ({stc:.3g} ppm/K), the series "
                                      f"nearest the element's CTE {cte:g} ppm/K")
    return ThermalSetting(cte, stc, chain.gauge_factor_tc_pct_per_100K / 100.0 / 100.0,
                          chain.gauge_transverse_sensitivity, chain.dummy_gauge == "half-bridge",
                          {k: src[k] for k in ("substrate_cte_ppm_per_K", "gauge_stc_ppm_per_K",
                                               "gauge_factor_tc_pct_per_100K",
                                               "gauge_transverse_sensitivity",
                                               "gauge_heat_transfer_W_per_mm2_K", "dummy_gauge")})


@dataclass(frozen=True)
class ThermalReport:
    """What ``tactcad thermal`` prints; :meth:`as_json` is its JSON."""

    design: str
    model: str
    setting: ThermalSetting
    apparent_strain_per_K: float
    grid_power_W: float
    self_heating_K: float
    full_scale_force_N: float
    records: list[dict]
    seconds: float

    @property
    def worst(self) -> dict:
        """The element with the largest drift per kelvin as read (after a dummy gauge)."""
        return max(self.records, key=lambda r: r["drift_N_per_K"])

    def as_json(self) -> dict:
        return {"design": self.design, "model": self.model, "setting": self.setting.as_json(),
                "apparent_strain_per_K": self.apparent_strain_per_K,
                "grid_power_W": self.grid_power_W, "self_heating_K": self.self_heating_K,
                "full_scale_force_N": self.full_scale_force_N,
                "worst_drift_N_per_K": self.worst["drift_N_per_K"],
                "worst_element": self.worst["element"], "seconds": self.seconds,
                "elements": self.records,
                "notes": ["apparent strain: TN-504 thermal output of an STC gauge, "
                          "(1+K_t)/(1-0.285 K_t)(alpha_S - alpha_STC); the lot's residual "
                          "polynomial is not included",
                          "drift_N_per_K: |apparent force| + F_FS |TC_GF| per kelvin (worst "
                          "case at full scale); with a half-bridge dummy the apparent term "
                          "cancels",
                          "kobj_error_rel_per_K: eq. 1-3 with both elements' apparent forces"]}


def _kobj_error_rel_per_K(km: float, kr: float, fm: float, fr: float,
                          rng: tuple[float, float], F: float) -> float:
    """Worst |dK_obj| / K_obj per kelvin over the range (eq. 1-3), apparent forces fm, fr (N/K)."""
    from tactcad.mechanics.lumped_model import deflection_ratio, sensitivity
    from tactcad.mechanics.resolution import KOBJ_POINTS

    k_obj = np.geomspace(*rng, KOBJ_POINTS)
    R = deflection_ratio(np.full_like(k_obj, km), np.full_like(k_obj, kr), k_obj).value
    dk_dr = sensitivity(R, np.full_like(k_obj, km), np.full_like(k_obj, kr)).value
    F_m = F * R * km / kr
    dR = R * np.abs(fm / F_m - fr / F)
    return float(np.max(np.abs(dk_dr) * dR / k_obj))


def thermal_report(plan: Plan, requirements, model: str = "closed-form",
                   stiffness: dict[str, float] | None = None,
                   errors: dict[str, float] | None = None) -> ThermalReport:
    """Per element: apparent strain, tip force and K_obj error per kelvin, self-heating offset.

    Args:
        plan: the design. requirements: its requirements (full-scale force N, K_obj range).
        model: ladder level for K and the gauge strain per newton.
        stiffness, errors: K (N/mm) and its relative error estimate per distinct part already
            computed at ``model`` (``verify`` passes its own); ``None`` estimates them.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
        DesignError: no CTE is known for the element's material.
    """
    from tactcad.mechanics.ladder import estimate

    t0 = time.perf_counter()
    chain = readout_chain(plan)
    s = thermal_setting(plan, chain)
    app = apparent_strain_per_K(s.substrate_cte_ppm_per_K, s.stc_ppm_per_K,
                                s.transverse_sensitivity)
    power, rise = self_heating_K(chain)
    F, rng = requirements.full_scale_force_N, requirements.kobj_range_N_per_mm
    parts: dict[str, dict] = {}
    for name, g in plan.distinct_elements.items():
        if stiffness is None or errors is None:
            est = estimate(model, g, plan.material)
            k, err = est.stiffness_N_per_mm, est.error_estimate_rel
        else:
            k, err = stiffness[name], errors[name]
        eps = gauge_strain_per_N(g, plan.material, chain, model)["grid"]
        parts[name] = {"K": k, "err": err, "eps": eps, "f": app / eps}
    gf_term = F * abs(s.gf_tc_per_K)
    records = []
    for slot in plan.slots:
        d = parts[slot.geometry.part_name]
        ref = plan.reference_of(slot.row)
        r = parts[ref.geometry.part_name]
        apparent = abs(d["f"])
        kobj = None
        if d["K"] < r["K"] * (1 - 1e-9) and not s.dummy:
            kobj = _kobj_error_rel_per_K(d["K"], r["K"], d["f"], r["f"], rng, F)
        elif d["K"] < r["K"] * (1 - 1e-9):
            kobj = 0.0  # the dummy cancels the offsets; the GF term cancels in R
        records.append({
            "element": slot.number, "part": slot.geometry.part_name,
            "role": "reference" if slot.number == ref.number else "measuring",
            "gauge_strain_per_N": d["eps"], "error_estimate_rel": d["err"],
            "apparent_force_N_per_K": d["f"], "gauge_factor_force_N_per_K": gf_term,
            "drift_quarter_N_per_K": apparent + gf_term,
            "drift_N_per_K": gf_term if s.dummy else apparent + gf_term,
            "half_bridge_cancels_N_per_K": apparent,
            "half_bridge_cancels_rel": apparent / (apparent + gf_term) if apparent + gf_term
            else 0.0,
            "self_heating_offset_N": 0.0 if s.dummy else d["f"] * rise,
            "kobj_error_rel_per_K": kobj,
            "reference_element": None if slot.number == ref.number else ref.number})
    return ThermalReport(plan.name, model, s, app, power, rise, F, records,
                         time.perf_counter() - t0)


def thermal_record(plan: Plan, fig, req) -> dict | None:
    """``max_thermal_drift_N_per_K`` when the design states it (None otherwise): each
    element's drift per kelvin as read, margin target / drift - 1, error the level's K error
    estimate of that element (the strain per newton comes from the same model), judged on
    its own (``elements``); the record shows the element with the worst verdict (among
    equals the largest drift; :func:`tactcad.mechanics.verdicts.deciding_item`)."""
    from tactcad.design.requirements_section import stated_thermal_drift

    target = stated_thermal_drift(plan.raw)
    if target is None:
        return None
    rep = thermal_report(plan, req, fig.model, stiffness=fig.k, errors=fig.k_error)
    items = [judged({"element": r["element"], "drift_N_per_K": r["drift_N_per_K"],
                     "error_estimate_rel": r["error_estimate_rel"],
                     "margin_rel": target / r["drift_N_per_K"] - 1.0
                     if r["drift_N_per_K"] > 0 else None}) for r in rep.records]
    w = deciding_item(items)  # each element on its own error: the worst verdict decides
    return {"requirement": "max_thermal_drift_N_per_K", "target": target,
            "predicted": w["drift_N_per_K"], "error_estimate_rel": w["error_estimate_rel"],
            "margin_rel": w["margin_rel"], "model": fig.model,
            "pass": all(it["drift_N_per_K"] <= target for it in items),
            "binding_element": w["element"], "elements": items,
            "self_heating_K": rep.self_heating_K,
            "basis": "TN-504 thermal output of the STC gauge / grid strain per newton, plus "
                     "the gauge factor's temperature coefficient at full scale"}
