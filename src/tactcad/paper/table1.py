"""Paper Table 1 against the design: each calibrated element's measured K
next to the stiffness ladder's prediction, whether the comparison applies to a
design (it cites the paper and its geometry can reach the measured K), the
as-built webs that reproduce the measured K, the gauge strain at the paper's
2 N design load, Table 2's R from the predicted K, the read-out chain's
sensitivity against the measured K_v/K, the spread of equal-arm elements, and
each element's yield-limited force against the calibration's largest force.

Everything here compares with the paper; the general estimators
(:mod:`tactcad.mechanics`) never import it. Units: mm, N, N/mm, V.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from tactcad.design.array_plan import Plan
from tactcad.mechanics.closed_form import web_for_stiffness
from tactcad.mechanics.ladder import estimate
from tactcad.mechanics.lumped_model import deflection_ratio
from tactcad.mechanics.readout_chain import ReadoutChain, grid_strain_per_N, rel_std
from tactcad.mechanics.stiffness_result import StiffnessResult
from tactcad.mechanics.element_strength import peak_stress_per_newton, require_yield
from tactcad.paper.data import table1, table2
from tactcad.paper.paper_load import PAPER_LOAD_N
from tactcad.studies.strength_studies import plan_strength

#: The surface strain the paper reports at 2 N for arms of 4-8 mm.
PAPER_STRAIN_RANGE = (0.2711e-2, 0.6316e-2)


@dataclass(frozen=True)
class Table1Prediction:
    """Predicted against measured stiffness of one element (paper Table 1)."""

    element: int
    arm_length_mm: float
    measured_N_per_mm: float
    #: K with the element's bonded gauge (glue line and carrier) on the web, as the paper
    #: measured its elements
    predicted: StiffnessResult
    #: K's relative rise from that gauge at the same level
    #: (:func:`tactcad.mechanics.ladder.gauge_k_rise`; 0: a bare element)
    gauge_layer_k_rel: float = 0.0

    @property
    def error_percent(self) -> float:
        """(predicted - measured) / measured x 100."""
        return 100.0 * (self.predicted.stiffness_N_per_mm - self.measured_N_per_mm) / self.measured_N_per_mm

    @property
    def without_gauge_layer_N_per_mm(self) -> float:
        """The prediction for the element as cut, without its gauge (N/mm)."""
        return self.predicted.stiffness_N_per_mm / (1.0 + self.gauge_layer_k_rel)

    @property
    def without_gauge_layer_error_percent(self) -> float:
        """(prediction without the gauge - measured) / measured x 100."""
        return (100.0 * (self.without_gauge_layer_N_per_mm - self.measured_N_per_mm)
                / self.measured_N_per_mm)

    def as_json(self) -> dict:
        return {"element": self.element, "arm_length_mm": self.arm_length_mm,
                "measured_N_per_mm": self.measured_N_per_mm,
                "predicted_N_per_mm": self.predicted.stiffness_N_per_mm,
                "error_percent": self.error_percent,
                "error_estimate_rel": self.predicted.error_estimate_rel,
                "face_strain_per_N": self.predicted.face_strain_per_N,
                "wall_time_s": self.predicted.wall_time_s,
                "gauge_layer_k_rel": self.gauge_layer_k_rel,
                "without_gauge_layer_N_per_mm": self.without_gauge_layer_N_per_mm,
                "without_gauge_layer_error_percent": self.without_gauge_layer_error_percent}


def table1_comparison(plan: Plan, model: str = "closed-form", progress=None) -> list[Table1Prediction]:
    """Every calibrated element of Table 1 (element 5 has no measurement):
    the plan's geometry at ``model`` level against the measured K.

    Distinct geometries are evaluated once (elements with equal arms share them).
    """
    from tactcad.mechanics.ladder import gauge_k_rise

    cache: dict[str, StiffnessResult] = {}
    layer: dict[str, float] = {}
    rows = []
    for meas in table1():
        slot = plan.element(meas.element)
        key = slot.geometry.part_name
        if key not in cache:
            if progress:
                progress(f"{model}: {key}")
            cache[key] = estimate(model, slot.geometry, plan.material)
            layer[key] = gauge_k_rise(model, slot.geometry, plan.material)
        res = cache[key]
        rows.append(Table1Prediction(meas.element, slot.geometry.arm_length_mm, meas.stiffness_N_per_mm,
                              StiffnessResult(meas.element, res.model, res.stiffness_N_per_mm,
                                              res.face_strain_per_N, res.error_estimate_rel,
                                              res.wall_time_s), layer[key]))
    return rows


def gauge_layer_shift(rows: list[Table1Prediction]) -> dict:
    """How the bonded gauge's stiffening moves Table 1: the mean signed and mean absolute
    error (%) over the rows without and with it, and the rise's range (relative)."""
    bare = np.array([r.without_gauge_layer_error_percent for r in rows])
    layered = np.array([r.error_percent for r in rows])
    rise = [r.gauge_layer_k_rel for r in rows]
    return {"mean_error_percent": [float(bare.mean()), float(layered.mean())],
            "mean_abs_error_percent": [float(np.abs(bare).mean()), float(np.abs(layered).mean())],
            "k_rise_rel": [float(min(rise)), float(max(rise))]}


def table1_not_applicable(plan: Plan) -> str | None:
    """Why the paper's Table 1 cannot be compared with ``plan`` (one line), or
    None when it can: the design cites the paper (``requirements.source``),
    has every element Table 1 numbers, and each element's geometry reaches
    its measured K within the closed form's web range (0.05 ... 1 mm)."""
    from tactcad.design.requirements_section import cites_paper
    from tactcad.mechanics.closed_form import web_for_stiffness
    from tactcad.mechanics.correction import range_warnings_unsaid
    if not cites_paper(plan.raw):
        return "the design does not cite the paper (requirements.source), so Table 1 is not its"
    rows = table1()
    numbers = {slot.number for slot in plan.slots}
    missing = sorted(r.element for r in rows if r.element not in numbers)
    if missing:
        return (f"Table 1 numbers elements up to {max(r.element for r in rows)}; the design has "
                f"{len(numbers)}")
    for meas in rows:
        try:
            with range_warnings_unsaid():  # a probe of reach, not an estimate to warn about
                web_for_stiffness(meas.stiffness_N_per_mm, plan.element(meas.element).geometry,
                                  plan.material)
        except ValueError as exc:
            return (f"element {meas.element}'s geometry cannot reach Table 1's "
                    f"{meas.stiffness_N_per_mm:g} N/mm at any web ({exc})")
    return None


#: What each command refused by :func:`require_table1` reproduces of the paper.
_TABLES = {"table1": "its Table 1", "table2": "its Table 2 (built on its Table 1)"}


def require_table1(plan: Plan, option: str = "--design", command: str = "table1") -> None:
    """Refuse a design the paper's measurements cannot be compared with
    (:func:`table1_not_applicable`): its Table 1 (``table1``) and the Table 2 built on it
    (``table2``).

    Args:
        plan: the design. option: the option the refusal names. command: the command
            refused, named in the alternative it pastes.

    Raises:
        DesignError: naming ``option``, the design and why.
    """
    from pathlib import Path

    from tactcad.errors import DesignError

    why = table1_not_applicable(plan)
    if why is not None:
        raise DesignError(option, Path(plan.source).name,
                          "a design that cites the paper and can reproduce "
                          + _TABLES.get(command, _TABLES["table1"]), why,
                          alternatives=[{"option": "tactcad new paper --example macro_array",
                                         "words": "the paper's 2 x 5 array as a project of "
                                                  f"its own; run {command} in it"}])


def as_built_webs(plan: Plan) -> list[dict]:
    """For each calibrated element, the web thickness (mm) that makes the
    corrected closed form reproduce its measured K, and the deviation from the
    design web against the design tolerance (the fabrication spread it implies)."""
    from tactcad.mechanics.closed_form import web_for_stiffness
    out = []
    for meas in table1():
        g = plan.element(meas.element).geometry
        t = web_for_stiffness(meas.stiffness_N_per_mm, g, plan.material)
        out.append({"element": meas.element, "measured_N_per_mm": meas.stiffness_N_per_mm,
                    "web_as_built_mm": t, "web_design_mm": g.web_thickness_mm,
                    "deviation_mm": t - g.web_thickness_mm,
                    "within_tolerance": abs(t - g.web_thickness_mm) <= g.web_tolerance_mm})
    return out


def gauge_strain_at_paper_load(plan: Plan, model: str = "closed-form",
                               arms_mm: tuple[float, ...] = (4.0, 5.0, 6.0, 7.0, 8.0)) -> list[dict]:
    """The face strain at the notch centre of the element as cut (without its gauge's glue
    line and carrier) under the paper's 2 N tip load for each arm length (%), next to the
    paper's reported 0.2711-0.6316 % range (its ANSYS surface strain of the bare
    element): ``{"arm_length_mm", "face_strain_as_cut_percent"}``. The level's
    ``face_strain_per_N`` on the bare geometry (:meth:`ElementGeometry.bare`); on the
    element as installed the face under the layer strains about 11 % less."""
    from dataclasses import replace

    g0 = plan.element(1).geometry.bare()
    out = []
    for a in arms_mm:
        r = estimate(model, replace(g0, arm_length_mm=a), plan.material)
        out.append({"arm_length_mm": a,
                    "face_strain_as_cut_percent": 100 * PAPER_LOAD_N * r.face_strain_per_N})
    return out


def table2_predicted(plan: Plan, model: str = "closed-form") -> dict:
    """Eq. 2 with the ladder's predicted K_m and K_r (element 8) against Table 2's
    48 measured R, reported as it is (nothing tuned to Table 2).

    Rows whose predicted pair leaves eq. 2's domain (K_r <= K_m: element 1 and
    the reference element 8 have the same 4 mm arm, so nominal geometry makes
    them equal) are returned as NaN with ``in_domain`` False.
    """
    import numpy as np


    rows = table2()
    k_pred = {r.element: r.predicted.stiffness_N_per_mm for r in table1_comparison(plan, model)}
    k_r = k_pred[8]
    k_m = np.array([k_pred[r.element] for r in rows])
    k_obj = np.array([r.K_obj_N_per_mm for r in rows])
    r_meas = np.array([r.R for r in rows])
    pred = deflection_ratio(k_m, np.full_like(k_m, k_r), k_obj)
    r_pred = np.asarray(pred.value if hasattr(pred, "value") else pred, dtype=float)
    ok = np.isfinite(r_pred)
    err = r_meas - r_pred
    return {"model": model, "k_r_predicted_N_per_mm": k_r,
            "rows": [{"element": r.element, "K_obj_N_per_mm": r.K_obj_N_per_mm,
                      "R_measured": r.R, "R_predicted": float(p), "in_domain": bool(o)}
                     for r, p, o in zip(rows, r_pred, ok)],
            "n_in_domain": int(ok.sum()),
            "mean_abs_error": float(np.mean(np.abs(err[ok]))) if ok.any() else float("nan"),
            "max_abs_error": float(np.max(np.abs(err[ok]))) if ok.any() else float("nan")}


def readout_table1(records: list[dict], chain: ReadoutChain, plan: Plan,
                      model: str = "closed-form") -> dict:
    """Adds the measured K_v and K_v/K of each calibrated element to its record
    (``table1_k_v_V_per_mm``, ``table1_sensitivity_V_per_N``, measured / predicted
    ratios and the amplifier gain that would reconcile the sensitivity) and
    returns the summary: the gain fitted through all elements (least squares
    through the origin) and the ratios' spread.

    Also per element the sensitivity ratio at its as-built web (the web at which
    the corrected closed form gives the measured K,
    :func:`as_built_webs`): what is left of the spread
    once each element's own web is known (gauge placement, bonding, gain).
    """
    from dataclasses import replace


    as_built: list[float] = []
    unreachable: list[str] = []  # elements of Table 1's arm whose geometry cannot be it

    by_element = {r.element: r for r in table1()}
    ratios = []
    num = den = num_built = den_built = 0.0
    for rec in records:
        row = by_element.get(rec["element"])
        if row is not None and abs(row.flexing_arm_length_mm - rec["arm_length_mm"]) > 1e-9:
            row = None  # a variant of the design: this element is not Table 1's
        g0 = plan.element(rec["element"]).geometry
        try:  # the web at which this geometry has the measured K, if any web has
            web = None if row is None else web_for_stiffness(row.stiffness_N_per_mm, g0,
                                                             plan.material)
        except ValueError as exc:
            web = None
            unreachable.append(f"element {rec['element']} cannot reach Table 1's "
                               f"{row.stiffness_N_per_mm:g} N/mm at any web ({exc})")
        if web is None:
            rec["table1_k_v_V_per_mm"] = rec["table1_sensitivity_V_per_N"] = None
            continue
        s_ratio = row.K_v_over_K_V_per_N / rec["sensitivity_V_per_N"]
        rec.update(table1_k_v_V_per_mm=row.K_v_V_per_mm,
                   table1_sensitivity_V_per_N=row.K_v_over_K_V_per_N,
                   table1_k_v_ratio=row.K_v_V_per_mm / rec["k_v_V_per_mm"],
                   table1_sensitivity_ratio=s_ratio,
                   reconciling_gain=chain.amplifier_gain * s_ratio)
        ratios.append(s_ratio)
        g = replace(g0, web_thickness_mm=web)
        s_built = chain.volts_per_strain * grid_strain_per_N(
            g, plan.material, chain, "closed-form")["grid"]
        rec["table1_as_built_web_mm"] = web
        rec["table1_sensitivity_ratio_as_built_web"] = row.K_v_over_K_V_per_N / s_built
        as_built.append(rec["table1_sensitivity_ratio_as_built_web"])
        e_built = s_built / chain.volts_per_strain  # S = K_v / K, as calibrate reads Table 1
        num_built += e_built * row.K_v_V_per_mm / row.stiffness_N_per_mm
        den_built += e_built * e_built
        e = rec["grid_strain_per_N"]
        num += e * row.K_v_over_K_V_per_N
        den += e * e
    fitted = num / den if den else None
    fitted_built = num_built / den_built if den_built else None
    if not ratios:  # the comparison does not apply: said in one line, the sensor's answers stand
        return {"elements": 0, "not_applicable": "; ".join(unreachable) or
                "no element of the design has a Table 1 element's arm"}
    return {"elements": len(ratios), "elements_not_comparable": unreachable,
            "sensitivity_ratio_min": min(ratios), "sensitivity_ratio_max": max(ratios),
            "sensitivity_ratio_mean": float(np.mean(ratios)),
            "sensitivity_ratio_rel_std": rel_std(ratios),
            "as_built_web_ratio_mean": float(np.mean(as_built)),
            "as_built_web_ratio_rel_std": rel_std(as_built),
            "gain_at_as_built_webs": chain.amplifier_gain * float(np.mean(as_built)),
            # one gain through the signals at the as-built webs: `tactcad calibrate`'s G
            "fitted_volts_per_strain_as_built": fitted_built,
            "fitted_volts_per_strain": fitted,
            "assumed_volts_per_strain": chain.volts_per_strain,
            "fitted_gain_at_assumed_excitation": (fitted / (chain.excitation_V * chain.gauge_factor
                                                            / 4.0)) if fitted else None}


def equal_arm_spread(plan: Plan) -> list[dict]:
    """Groups of Table 1 elements with equal arms: measured K, max/min ratio
    and the as-built webs (mm) that reproduce them on ``plan`` at the
    corrected closed form (:func:`as_built_webs`);
    empty where Table 1 does not apply to ``plan``
    (:func:`table1_not_applicable`)."""
    if table1_not_applicable(plan) is not None:
        return []
    web_of = {w["element"]: w["web_as_built_mm"] for w in as_built_webs(plan)}
    groups: dict[float, list] = {}
    for row in table1():
        groups.setdefault(row.flexing_arm_length_mm, []).append(row)
    out = []
    for arm, rows in sorted(groups.items()):
        if len(rows) < 2:
            continue
        ks = [r.stiffness_N_per_mm for r in rows]
        out.append({"arm_length_mm": arm, "elements": [r.element for r in rows],
                    "measured_N_per_mm": ks, "ratio_max_over_min": max(ks) / min(ks),
                    "as_built_web_mm": [web_of[r.element] for r in rows]})
    return out


def table1_force_comparison(plan: Plan, model: str = "closed-form") -> list[dict]:
    """Each element's yield-limited force against Table 1's "max support force"
    (the largest force of each element's calibration), per calibrated element.

    For each element: the yield-limited force (``yield_limited_force_N``) at
    ``model`` with the design web; the as-built web that reproduces the
    measured K (corrected closed form, :func:`as_built_webs`) and the
    closed-form yield-limited force (``yield_limited_force_as_built_N``) and
    peak stress at the measured maximum force with that web; and the yield
    safety factor the calibration ran at.

    Returns:
        one dict per Table 1 element (element 5 has no calibration).

    Raises:
        DesignError: the material has no yield strength.
    """
    y = require_yield(plan.material)
    sf = plan.strength.safety_factor
    design = {r.element: r for r in plan_strength(plan, model)}
    webs = {w["element"]: w["web_as_built_mm"] for w in as_built_webs(plan)}
    out = []
    for meas in table1():
        g = plan.element(meas.element).geometry
        t_built = webs[meas.element]
        gb = replace(g, web_thickness_mm=t_built)
        s_built = float(peak_stress_per_newton(t_built, gb.notch_radius_mm, gb.arm_length_mm,
                                               gb.sheet_thickness_mm))
        s_max = s_built * meas.max_support_force_N
        out.append({"element": meas.element, "arm_length_mm": g.arm_length_mm,
                    "max_support_force_N": meas.max_support_force_N,
                    "yield_limited_force_N": design[meas.element].yield_limited_force_N,
                    "web_as_built_mm": t_built,
                    "yield_limited_force_as_built_N": y / (s_built * sf),
                    "stress_MPa_at_max_support_force_as_built": s_max,
                    "yield_safety_factor_at_max_support_force_as_built": y / s_max})
    return out


def with_measured_sensitivities(report, plan: Plan, model: str):
    """A read-out report (:func:`tactcad.studies.project_reports.readout_record`) with the
    paper's measured sensitivities beside the predicted ones, for the paper's design only
    (a design that does not cite the paper gets its report as it is).

    Args:
        report: the read-out report. plan: its design's plan. model: its ladder level.

    Returns:
        The report, with ``table1`` set for the paper's design.
    """
    from dataclasses import replace

    from tactcad.design.requirements_section import cites_paper

    if not cites_paper(plan.raw):
        return report
    return replace(report, table1=readout_table1(report.records, report.chain, plan, model))


def with_equal_arm_spread(report, plan: Plan):
    """A tolerance report (:func:`tactcad.studies.project_reports.tolerance_record`) with
    Table 1's measured spread of equal-arm elements (:func:`equal_arm_spread`: measured K in
    N/mm, as-built webs in mm) beside the predicted K band, for the paper's design only (a
    design that does not cite the paper gets its report as it is).

    Args:
        report: the :class:`~tactcad.studies.tolerance_montecarlo.ToleranceReport`.
        plan: its design's plan.

    Returns:
        The report, with ``table1_spread`` set for the paper's design.
    """
    from tactcad.design.requirements_section import cites_paper

    if not cites_paper(plan.raw):
        return report
    return replace(report, table1_spread=equal_arm_spread(plan))
