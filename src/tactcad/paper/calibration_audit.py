"""Calibration rig for a design, and the audit of measured calibrations against the design.

Simulation: each element of a plan gets K from the stiffness ladder and the grid
strain per newton ε (what its gauge reads, ``grid_strain_per_N``); its signal per
deflection is K_v = G ε K with a gauge gain G (V per unit strain, bridge and amplifier together); the paper's
rig (:func:`.calibration.synthetic_calibration`) then gives readings with
noise, the data of the paper's Fig. 4.

Audit, per element, of measured K, K_v (paper Table 1 or fits of a CSV):

* as-built web: the web thickness at which the ladder level reproduces the
  measured K (other dimensions nominal), against the design web ± tolerance;
* signal against force: the measured signal per newton S = K_v/K (V/N)
  against G ε(as-built web); G is one gain common to all elements, fitted
  by least squares through the origin, S ≈ G ε. Each element is judged
  against the gain fitted on the *other* elements (leave-one-out), so one
  bad element does not pull the gain toward itself;
* the K its signal implies: the K of the web t at which G ε(t) equals the
  measured S (S is read against the force sensor, so it does not pass
  through the series-spring correction that K and K_v share);
* twins (equal nominal geometry): the stiffness ratio against the largest
  ratio the web tolerance allows at this ladder level, and the ratio of
  their S against the ratio of their predicted ε;
* the series-spring correction's error amplification 1 + K/K_s.

Units: mm, N, V, N/mm, V/mm, V/N, strain (dimensionless).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from tactcad.mechanics import calibration as cal
from tactcad.paper import data as paper_data
from tactcad.paper.calibration_table1 import table1_kv_over_k_check

if TYPE_CHECKING:
    from tactcad.studies.project_reports import BudgetCalibration

#: Gauge gain of the simulated rig (V per unit strain of the grid's strain): quarter
#: bridge at 2.5 V excitation, gauge factor 2.0 and an amplifier gain of 96 give 120 V per
#: unit strain; the grid over the web is compressed, so K_v is negative, as Table 1's
#: (assumption; the paper gives no figure).
DEFAULT_GAUGE_GAIN_V_PER_STRAIN = 120.0
#: Relative disagreement of signal and force data taken as a flag: gauge factor
#: (±1 %), gauge position on a 0.25 mm web and bonding make ±25 % plausible.
DEFAULT_GAIN_TOLERANCE = 0.25
#: The paper's worst linearity error of an element (%).
PAPER_MAX_LINEARITY_PCT = 2.32
#: Web thicknesses searched for the as-built web (mm).
WEB_SEARCH_MM = (0.08, 0.8)


@dataclass(frozen=True)
class ElementCalibration:
    """Calibration constants of one element as the audit uses them.

    Attributes:
        element: paper element number.
        K_N_per_mm: stiffness K (N/mm).
        K_v_V_per_mm: signal per deflection K_v (V/mm).
        V0_V: signal at zero deflection (V).
        linearity_force_pct, linearity_signal_pct: linearity errors (%), None if unknown.
        stderr_K_N_per_mm, stderr_K_v_V_per_mm: standard errors, None if unknown.
        source: ``table1``, ``csv`` or ``simulated``.
    """

    element: int
    K_N_per_mm: float
    K_v_V_per_mm: float
    V0_V: float
    linearity_force_pct: float | None = None
    linearity_signal_pct: float | None = None
    stderr_K_N_per_mm: float | None = None
    stderr_K_v_V_per_mm: float | None = None
    source: str = "table1"

    @property
    def signal_per_N(self) -> float:
        """S = K_v/K (V/N)."""
        return self.K_v_V_per_mm / self.K_N_per_mm


def from_table1() -> list[ElementCalibration]:
    """Paper Table 1 as the measured input (no linearity or standard errors per element)."""
    return [ElementCalibration(r.element, r.stiffness_N_per_mm, r.K_v_V_per_mm, r.V0_V)
            for r in paper_data.table1()]


def from_fits(fits: dict[int, cal.Calibration], source: str = "csv") -> list[ElementCalibration]:
    """Fitted calibrations (:func:`.calibration.fit_calibration`) keyed by element."""
    return [ElementCalibration(e, c.K_N_per_mm, c.K_v_V_per_mm, c.V0_V, c.linearity_force_pct,
                               c.linearity_signal_pct, c.stderr_K_N_per_mm, c.stderr_K_v_V_per_mm,
                               source) for e, c in fits.items()]


def fit_all(data: dict[int, cal.CalibrationData]) -> dict[int, cal.Calibration]:
    """:func:`.calibration.fit_calibration` of every element's readings."""
    return {e: cal.fit_calibration(d.z_travel_um, d.force_N, d.signal_V, d.k_sensor_N_per_mm)
            for e, d in data.items()}


# ---------------------------------------------------------------------------
# Ladder evaluations at a web thickness
# ---------------------------------------------------------------------------
def _at_web(model: str, g, material, web_mm: float):
    from tactcad.mechanics import ladder

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # correction range warnings: the search leaves it on purpose
        return ladder.estimate(model, replace(g, web_thickness_mm=float(web_mm)), material)


def _grid_at_web(plan, model: str, g, web_mm: float) -> float:
    """What the design's grid reads per newton (1/N, signed: the gauge over the web is
    compressed) on ``g`` with the web ``web_mm``: the read-out's own strain
    (:func:`tactcad.mechanics.readout_chain.grid_strain_per_N`), so the gain fitted to it
    is the read-out chain's V per unit strain."""
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the webs searched leave the fitted ranges on purpose
        return float(grid_strain_per_N(replace(g, web_thickness_mm=float(web_mm)), plan.material,
                                       readout_chain(plan), model)["grid"])


def as_built_web(g, material, k_target: float, model: str = "closed-form") -> float | None:
    """Web thickness (mm) at which ``model`` gives stiffness ``k_target`` (N/mm), other dimensions nominal.

    Returns None when no web in :data:`WEB_SEARCH_MM` reproduces it.
    """
    lo, hi = WEB_SEARCH_MM
    f = lambda t: _at_web(model, g, material, t).stiffness_N_per_mm - k_target  # noqa: E731
    f_lo, f_hi = f(lo), f(hi)
    if f_lo * f_hi > 0:
        return None
    return float(brentq(f, lo, hi, xtol=1e-6))


def _signal_web(plan, g, signal_per_N: float, gain: float, model: str) -> float | None:
    """Web at which the predicted signal per newton G ε(t) equals the measured S = K_v/K,
    ε the grid's strain (:func:`_grid_at_web`).

    S is read against the force sensor directly, so unlike K and K_v it does
    not pass through the series-spring correction; ε falls as 1/t², so the
    web is well determined by it.
    """
    lo, hi = WEB_SEARCH_MM
    def f(t):
        return gain * _grid_at_web(plan, model, g, t) - signal_per_N
    if f(lo) * f(hi) > 0:
        return None
    return float(brentq(f, lo, hi, xtol=1e-6))


# ---------------------------------------------------------------------------
# Simulated calibration of a design
# ---------------------------------------------------------------------------
def simulate_design_calibration(plan, model: str = "closed-form",
                                gauge_gain_V_per_strain: float | None = None,
                                noise_force_N: float = 0.001,
                                noise_signal_V: float = cal.DEFAULT_NOISE_SIGNAL_V,
                                seed: int | None = 0,
                                full_scale_force_N: float | None = None,
                                k_sensor_N_per_mm: float = cal.K_SENSOR_N_PER_MM,
                                ) -> dict[int, cal.CalibrationData]:
    """The paper's calibration rig run on every element of a plan (Fig. 4 data).

    K and ε from the ladder at ``model``; K_v = G ε K; V0 = 0. Without a
    ``gauge_gain_V_per_strain``, G and ε are the design's read-out chain's
    (:func:`tactcad.mechanics.readout_chain.readout_chain`: G V_ex GF / 4 on the
    grid-averaged strain), so each element's V/N is ``tactcad readout``'s;
    with one, G is that gain on the same grid strain (the audit's G reads it back). 25 um
    steps to
    150 um (with ``full_scale_force_N``: six equal steps up to the Z travel at
    which the element carries that force), three runs, Gaussian noise on
    force and signal; the force gauge in series has stiffness
    ``k_sensor_N_per_mm`` (N/mm; the design's rigs give it).

    Returns:
        {element: :class:`.calibration.CalibrationData`}.

    Raises:
        CalibrationError: a gain of 0 or non-finite, or negative noise.
    """
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    if gauge_gain_V_per_strain is not None and not (
            np.isfinite(gauge_gain_V_per_strain) and gauge_gain_V_per_strain != 0):
        raise cal.CalibrationError(
            f"gauge_gain_V_per_strain = {gauge_gain_V_per_strain!r}: allowed a finite value != 0")
    chain = readout_chain(plan)
    gain = chain.volts_per_strain if gauge_gain_V_per_strain is None else gauge_gain_V_per_strain
    rng = np.random.default_rng(seed)
    out = {}
    cache = {}
    for slot in plan.slots:
        key = slot.geometry.part_name
        if key not in cache:
            cache[key] = _at_web(model, slot.geometry, plan.material, slot.geometry.web_thickness_mm)
        r = cache[key]
        # the grid's strain, as the read-out reports its volts per newton
        eps = grid_strain_per_N(slot.geometry, plan.material, chain, model)
        k_v = gain * eps["grid"] * r.stiffness_N_per_mm
        steps = cal.calibration_steps_um(r.stiffness_N_per_mm, k_sensor_N_per_mm,
                                         full_scale_force_N)
        out[slot.number] = cal.synthetic_calibration(
            r.stiffness_N_per_mm, k_v, 0.0, noise_force_N=noise_force_N,
            noise_signal_V=noise_signal_V, seed=int(rng.integers(2 ** 31)),
            k_sensor_N_per_mm=k_sensor_N_per_mm, steps_um=steps)
    return out


# ---------------------------------------------------------------------------
# Audit
# ---------------------------------------------------------------------------
def _gain_through_origin(s: np.ndarray, eps: np.ndarray) -> float:
    """Least-squares G of S ≈ G ε (no intercept)."""
    return float(s @ eps / (eps @ eps))


def _flag(elements, check: str, value: float, limit: float, text: str) -> dict:
    return {"elements": list(elements), "check": check, "value": float(value),
            "limit": float(limit), "text": text}


def unread_elements(plan, calibrations: list[ElementCalibration], source: str
                    ) -> tuple[list[int], list[dict]]:
    """The design's elements a reading file left out, and a flag for each.

    Args:
        plan: the design. calibrations: the fitted elements. source: the file, for the words.

    Returns:
        (the element numbers without readings, ascending; their flags, as :func:`audit`'s).
    """
    unread = sorted({slot.number for slot in plan.slots} - {c.element for c in calibrations})
    return unread, [_flag([e], "readings", 0.0, 1.0,
                          f"element {e}: no readings in {source}; not calibrated")
                    for e in unread]


def audit_file(plan, read, source: str, model: str = "closed-form",
               gain_tolerance: float = DEFAULT_GAIN_TOLERANCE) -> dict:
    """The audit of a calibration data file against the design, as ``tactcad calibrate
    --data`` and ``tactcad budget --calibration`` both give it: :func:`audit` of every
    fitted element, at the file's force gauge (its ``k_sensor_N_per_mm``, else the one it
    was read with), with the paper's linearity limit only for a design that cites the
    paper; and a flag for each element of the design the file has no readings of
    (:func:`unread_elements`).

    Args:
        plan: the design.
        read: the file, read and fitted
            (:class:`tactcad.mechanics.calibration_file.CalibrationFile`).
        source: the file as the user named it, for the flags' words.
        model: ladder level for the as-built web and the gauge strain.
        gain_tolerance: relative disagreement of signal and force that is flagged, > 0.

    Returns:
        :func:`audit`'s dict (K in N/mm, web in mm, signal per newton in V/N) with the flags of
        the elements without readings added to ``flags`` and their numbers, ascending, as
        ``elements_without_readings``.

    Raises:
        CalibrationError: ``gain_tolerance`` <= 0, a fitted K <= 0.
    """
    from tactcad.design.requirements_section import cites_paper

    k_sensor = float(next(iter(read.data.values())).k_sensor_N_per_mm)
    calibrations = from_fits(read.fits, "csv")
    report = audit(plan, calibrations, model, gain_tolerance, k_sensor,
                   paper_criteria=cites_paper(plan.raw))
    unread, flags = unread_elements(plan, calibrations, source)
    report["flags"] += flags
    report["elements_without_readings"] = unread
    return report


def audit(plan, calibrations: list[ElementCalibration], model: str = "closed-form",
          gain_tolerance: float = DEFAULT_GAIN_TOLERANCE,
          k_sensor: float = paper_data.K_SENSOR_N_PER_MM,
          paper_criteria: bool = True) -> dict:
    """Audit measured calibrations against the plan (see module docstring).

    Args:
        plan: design plan; element numbers of ``calibrations`` must exist in it.
        calibrations: measured constants, one per element (>= 1).
        model: ladder level for the as-built web and ε.
        gain_tolerance: relative disagreement that raises a flag, > 0.
        k_sensor: force sensor stiffness K_s (N/mm): the data file's, else
            the design's rigs (``force_gauge.stiffness_N_per_mm``).
        paper_criteria: judge linearity against the paper's worst element
            (2.32 %); only for a design that cites the paper.

    Returns:
        dict: "gauge_gain_V_per_strain", "elements" (one record each),
        "twins", "flags" (each with the checked number and its limit).

    Raises:
        CalibrationError: no calibrations, K <= 0, gain_tolerance <= 0.
        DesignError: an element number the plan does not have.
    """
    if not calibrations:
        raise cal.CalibrationError("calibrations = []: allowed >= 1 element")
    if not (np.isfinite(gain_tolerance) and gain_tolerance > 0):
        raise cal.CalibrationError(f"gain_tolerance = {gain_tolerance!r}: allowed > 0")
    for c in calibrations:
        cal._check_positive(f"K of element {c.element}", c.K_N_per_mm)
    slots = {c.element: plan.element(c.element) for c in calibrations}
    flags: list[dict] = []
    records = []
    for c in calibrations:
        g = slots[c.element].geometry
        web = as_built_web(g, plan.material, c.K_N_per_mm, model)
        eps = _grid_at_web(plan, model, g, web) if web else None
        amp = cal.series_error_amplification(c.K_N_per_mm, k_sensor)
        records.append({
            "element": c.element, "part": g.part_name, "arm_length_mm": g.arm_length_mm,
            "K_N_per_mm": c.K_N_per_mm, "K_v_V_per_mm": c.K_v_V_per_mm, "V0_V": c.V0_V,
            "signal_per_N_V_per_N": c.signal_per_N,
            "stderr_K_N_per_mm": c.stderr_K_N_per_mm, "stderr_K_v_V_per_mm": c.stderr_K_v_V_per_mm,
            "linearity_force_pct": c.linearity_force_pct,
            "linearity_signal_pct": c.linearity_signal_pct,
            "series_amplification": amp.from_k_apparent,
            "sensor_stiffness_amplification": amp.from_k_sensor,
            "element_share_of_travel": amp.element_share_of_travel,
            "stiffer_than_sensor": bool(c.K_N_per_mm > k_sensor),
            "web_design_mm": g.web_thickness_mm, "web_tolerance_mm": g.web_tolerance_mm,
            "web_as_built_mm": web,
            "web_deviation_mm": None if web is None else web - g.web_thickness_mm,
            "grid_strain_per_N": eps,
        })
        if web is None:
            flags.append(_flag([c.element], "as-built web", c.K_N_per_mm, 0.0,
                               f"element {c.element}: no web in {WEB_SEARCH_MM} mm gives "
                               f"K = {c.K_N_per_mm:g} N/mm (design {g.web_thickness_mm:g} ± "
                               f"{g.web_tolerance_mm:g} mm)"))
        elif abs(web - g.web_thickness_mm) > g.web_tolerance_mm:
            flags.append(_flag([c.element], "web deviation (mm)", web - g.web_thickness_mm,
                               g.web_tolerance_mm,
                               f"element {c.element}: K = {c.K_N_per_mm:g} N/mm needs a "
                               f"{web:.3f} mm web, design {g.web_thickness_mm:g} ± "
                               f"{g.web_tolerance_mm:g} mm"))
        if c.K_N_per_mm > k_sensor:
            flags.append(_flag([c.element], "series amplification", amp.from_k_apparent, 2.0,
                               f"element {c.element}: K = {c.K_N_per_mm:g} N/mm > K_s = "
                               f"{k_sensor:g} N/mm; a 1 % error in the series stiffness is "
                               f"{amp.from_k_apparent:.2f} % in K"))
        for kind, value in (("force", c.linearity_force_pct), ("signal", c.linearity_signal_pct)):
            if paper_criteria and value is not None and value > PAPER_MAX_LINEARITY_PCT:
                flags.append(_flag([c.element], f"linearity {kind} (%)", value,
                                   PAPER_MAX_LINEARITY_PCT,
                                   f"element {c.element}: {kind} linearity error {value:.2f} % "
                                   f"above the paper's worst {PAPER_MAX_LINEARITY_PCT} %"))
    gain = _signal_gain(records, flags, gain_tolerance, plan, model, slots)
    twins = _twins(records, flags, gain_tolerance, plan, model, slots)
    return {"model": model, "k_sensor_N_per_mm": k_sensor, "gain_tolerance": gain_tolerance,
            "paper_criteria": paper_criteria if paper_criteria else
            "not applied: the design does not cite the paper, so its worst linearity "
            f"({PAPER_MAX_LINEARITY_PCT} %) is no limit of this design",
            "gauge_gain_V_per_strain": gain, "elements": records, "twins": twins, "flags": flags}


def _signal_gain(records, flags, tolerance, plan, model, slots) -> float | None:
    """Fit the common gain; per element the leave-one-out gain, S/(G ε) and the K its signal implies."""
    usable = [r for r in records if r["grid_strain_per_N"]]
    if not usable:
        return None
    s = np.array([r["signal_per_N_V_per_N"] for r in usable])
    eps = np.array([r["grid_strain_per_N"] for r in usable])
    gain = _gain_through_origin(s, eps)
    for i, r in enumerate(usable):
        others = np.arange(len(usable)) != i
        if not others.any():
            r["gain_leave_one_out_V_per_strain"] = r["signal_ratio"] = r["K_implied_by_signal_N_per_mm"] = None
            continue
        g_loo = _gain_through_origin(s[others], eps[others])
        ratio = s[i] / (g_loo * eps[i])
        r["gain_leave_one_out_V_per_strain"] = g_loo
        r["signal_ratio"] = ratio
        geom = slots[r["element"]].geometry
        web_sig = _signal_web(plan, geom, r["signal_per_N_V_per_N"], g_loo, model)
        r["web_implied_by_signal_mm"] = web_sig
        r["K_implied_by_signal_N_per_mm"] = (
            None if web_sig is None else _at_web(model, geom, plan.material, web_sig).stiffness_N_per_mm)
        if abs(ratio - 1.0) > tolerance:
            implied = r["K_implied_by_signal_N_per_mm"]
            tail = "" if implied is None else f"; its signal per newton fits K = {implied:.3g} N/mm"
            flags.append(_flag([r["element"]], "signal per N / (G ε)", ratio, 1.0 + tolerance,
                               f"element {r['element']}: signal per newton {s[i]:.3g} V/N is "
                               f"{ratio:.2f} x the {g_loo * eps[i]:.3g} V/N its K predicts with the "
                               f"other elements' gain{tail}"))
    return gain


def _twins(records, flags, tolerance, plan, model, slots) -> list[dict]:
    """Pairs of elements of equal nominal geometry: stiffness and signal-per-newton ratios."""
    by_part: dict[str, list[dict]] = {}
    for r in records:
        by_part.setdefault(r["part"], []).append(r)
    out = []
    for part, group in by_part.items():
        for i in range(len(group)):
            for j in range(i + 1, len(group)):
                a, b = sorted((group[i], group[j]), key=lambda r: r["K_N_per_mm"])
                g = slots[a["element"]].geometry
                k_hi = _at_web(model, g, plan.material, g.web_thickness_mm + g.web_tolerance_mm)
                k_lo = _at_web(model, g, plan.material, g.web_thickness_mm - g.web_tolerance_mm)
                allowed = k_hi.stiffness_N_per_mm / k_lo.stiffness_N_per_mm
                ratio = b["K_N_per_mm"] / a["K_N_per_mm"]
                s_ratio = b["signal_per_N_V_per_N"] / a["signal_per_N_V_per_N"]
                e_ratio = (None if not (a["grid_strain_per_N"] and b["grid_strain_per_N"])
                           else b["grid_strain_per_N"] / a["grid_strain_per_N"])
                pair = [a["element"], b["element"]]
                out.append({"part": part, "elements": pair, "stiffness_ratio": ratio,
                            "allowed_stiffness_ratio": allowed,
                            "signal_per_N_ratio": s_ratio, "predicted_signal_per_N_ratio": e_ratio})
                if ratio > allowed:
                    flags.append(_flag(pair, "twin stiffness ratio", ratio, allowed,
                                       f"elements {pair[0]} and {pair[1]} ({part}): K differ "
                                       f"{ratio:.2f}x; web ± {g.web_tolerance_mm:g} mm allows "
                                       f"{allowed:.2f}x"))
                if e_ratio and abs(s_ratio / e_ratio - 1.0) > tolerance:
                    flags.append(_flag(pair, "twin signal per N ratio / predicted", s_ratio / e_ratio,
                                       1.0 + tolerance,
                                       f"elements {pair[0]} and {pair[1]} ({part}): signal per "
                                       f"newton ratio {s_ratio:.2f}, their as-built webs predict "
                                       f"{e_ratio:.2f}"))
    return out


def table1_consistency(k_sensor: float = paper_data.K_SENSOR_N_PER_MM,
                       z_max_um: float = paper_data.CALIBRATION_STEPS_UM[-1]) -> list[dict]:
    """Table 1's own columns against each other, per element.

    * F_max/δ_max (N/mm) against K: a line through the origin would give K;
    * Z travel implied by the largest step, δ_max + F_max/K_s (um), against
      the stated 150 um (two springs in series);
    * the printed K_v/K against K_v and K within rounding
      (:func:`.calibration_table1.table1_kv_over_k_check`).
    """
    kv_check = {c.element: c for c in table1_kv_over_k_check()}
    out = []
    for r in paper_data.table1():
        secant = r.max_support_force_N / (r.max_deflection_um * 1e-3)
        z_implied = r.max_deflection_um + 1e3 * r.max_support_force_N / k_sensor
        out.append({"element": r.element, "K_N_per_mm": r.stiffness_N_per_mm,
                    "secant_F_max_over_delta_max_N_per_mm": secant,
                    "secant_over_K": secant / r.stiffness_N_per_mm,
                    "z_travel_implied_um": z_implied, "z_travel_stated_um": z_max_um,
                    "kv_over_k_printed_consistent": kv_check[r.element].consistent})
    return out


def budget_calibration(plan, path, model: str = "closed-form",
                       option: str = "--calibration") -> "BudgetCalibration":
    """Read a calibration file for the budget as ``tactcad calibrate --data`` reads it: the
    same reader and refusals (:func:`tactcad.mechanics.calibration_file.read_calibration`,
    the rigs' force gauge where the file states none) and the same audit
    (:func:`audit_file`), each of whose flags is a warning.

    Args:
        plan: the design's plan. path: the CSV, LVM or TDMS file.
        model: ladder level of the audit's as-built web and gauge strain.
        option: the option (or keyword) that named the file, for the refusals and warnings.

    Returns:
        :class:`tactcad.studies.project_reports.BudgetCalibration`.

    Raises:
        CalibrationError: the file cannot be read or fitted, or names an element the design
            does not have (the message names ``option`` and the file).
    """
    from tactcad.mechanics.calibration_file import read_calibration
    from tactcad.studies.project_reports import BudgetCalibration
    from tactcad.studies.verification import calibration_gauge

    k_sensor = float(calibration_gauge(plan).gauge.stiffness_N_per_mm)
    read = read_calibration(path, option, default_k_sensor=k_sensor,
                            element_numbers=[s.number for s in plan.slots])
    audit = audit_file(plan, read, str(path), model)
    lines = []
    for flag in audit["flags"]:
        tail = (": its units' calibration term is the expected one of a static calibration, "
                "as without a calibration file" if flag["check"] == "readings" else "")
        lines.append(f"{option} = {path}: {flag['text']}{tail} (tactcad calibrate --data "
                     f"flags it)")
    return BudgetCalibration(dict(read.fits), audit, lines)
