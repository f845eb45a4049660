"""Does the toleranced design hold its K band, and which tolerance to tighten to what.

The Monte Carlo of :mod:`tactcad.studies.tolerance_montecarlo` gives each element's
K distribution under the design's ``[tolerances]``; the predicted band is
the worst element's larger end of its 95 % interval relative to nominal
(JCGM 101 coverage interval), checked against ``[requirements]
k_tolerance_rel``.

Budget: each tolerance's share of an element's K scatter is its linear
contribution c_i = (K(x_i + tol_i) - K(x_i - tol_i)) / (2 K), the others
nominal (corrected closed form). The band grows as sqrt(sum c_i^2) (root
sum of squares of independent scatter). When the band is too wide, the
largest contributor is tightened by the factor that brings the
root-sum-square, scaled to the Monte Carlo band, to the requirement; when
even a zero tolerance of it would not do, it is set to zero in the budget
and the next one follows.

Units: mm, relative for the modulus and the band.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Callable

from tactcad.store import kept_per_process
from tactcad.vocabulary.rounding import round_down
from tactcad.design.array_plan import Plan
from tactcad.mechanics.correction import Correction, load_correction
from tactcad.studies.tolerance_montecarlo import (MONTE_CARLO_SAMPLES, MONTE_CARLO_SEED, ToleranceReport,
                                         Tolerances, corrected_stiffness, element_band_report)

#: [tolerances] key -> field of :class:`~tactcad.studies.tolerance_montecarlo.Tolerances`.
FIELDS = {"web_thickness_mm": "web_mm", "notch_radius_mm": "notch_radius_mm",
          "arm_length_mm": "arm_length_mm", "sheet_thickness_mm": "sheet_mm",
          "youngs_modulus_rel": "modulus_rel"}
#: Tightest value the budget proposes for each tolerance: the process limit (wire EDM with
#: several skim cuts holds about +/-0.005 mm; ground plate +/-0.01 mm; a modulus measured on
#: the sheet's own coupon to about +/-0.5 %).
PROCESS_LIMITS = {"web_thickness_mm": 0.005, "notch_radius_mm": 0.005, "arm_length_mm": 0.005,
                  "sheet_thickness_mm": 0.01, "youngs_modulus_rel": 0.005}


def contributions(plan: Plan, tol: Tolerances, correction: Correction | None = None
                  ) -> dict[str, dict[str, float]]:
    """Per distinct part, each tolerance's relative K change c_i (see module docstring):
    a pure function of the distinct parts (name and geometry), the material, the
    tolerances and the correction, kept per process by those (the verification of a
    design search's candidate and of the design it writes of it ask the same)."""
    corr = load_correction() if correction is None else correction
    parts = tuple(plan.distinct_elements.items())
    out = _part_contributions(parts, plan.material, tol, corr)
    return {name: dict(c) for name, c in out.items()}


@kept_per_process(maxsize=256)
def _part_contributions(parts: tuple, m, tol: Tolerances, corr: Correction
                        ) -> dict[str, dict[str, float]]:
    # contributions' work, on its hashable inputs (each caller copies the answer)
    out = {}
    for name, g in parts:
        base = dict(web=g.web_thickness_mm, r=g.notch_radius_mm, a=g.arm_length_mm,
                    E=m.youngs_modulus_MPa)

        def k(**moved) -> float:
            v = {**base, **moved}
            return float(corrected_stiffness(v["web"], v["r"], v["a"], v["E"], g,
                                             m.poisson_ratio, corr))

        k0 = k()
        c = {"web_thickness_mm": (k(web=base["web"] + tol.web_mm)
                                  - k(web=base["web"] - tol.web_mm)) / (2 * k0),
             "notch_radius_mm": (k(r=base["r"] + tol.notch_radius_mm)
                                 - k(r=base["r"] - tol.notch_radius_mm)) / (2 * k0),
             "arm_length_mm": (k(a=base["a"] + tol.arm_length_mm)
                               - k(a=base["a"] - tol.arm_length_mm)) / (2 * k0),
             "sheet_thickness_mm": tol.sheet_mm / g.sheet_thickness_mm,  # K proportional to b
             "youngs_modulus_rel": tol.modulus_rel}
        out[name] = {key: abs(v) for key, v in c.items()}
    return out


def mc_band(report: ToleranceReport) -> tuple[float, int]:
    """(worst relative end of the 95 % K interval over the elements, that element)."""
    worst, element = 0.0, 0
    for e in report.elements:
        k0 = e["K_nominal_N_per_mm"]
        band = max(abs(e["K_p2_5_N_per_mm"] / k0 - 1), abs(e["K_p97_5_N_per_mm"] / k0 - 1))
        if band > worst:
            worst, element = band, e["element"]
    return worst, element


def tighten(c: dict[str, float], tol: Tolerances, band: float, target: float) -> list[dict]:
    """Tolerances to tighten (largest contributor first) and their new values, so that the
    root-sum-square budget ``c`` scaled to the Monte Carlo ``band`` meets ``target``."""
    rss = math.sqrt(sum(v * v for v in c.values()))
    if band <= target or rss == 0:
        return []
    goal = target * rss / band  # the requirement in the budget's scale
    left = dict(c)
    out = []
    for key in sorted(c, key=c.get, reverse=True):
        others = sum(v * v for k, v in left.items() if k != key)
        now = getattr(tol, FIELDS[key])
        floor = min(PROCESS_LIMITS[key], now)
        if now <= 0 or c[key] == 0:
            continue
        need = math.sqrt(max(goal * goal - others, 0.0)) / c[key] * now
        if need >= floor:
            out.append({"tolerance": f"tolerances.{key}", "from": now,
                        "to": max(round_down(min(need, now), 2), floor)})
            return out
        out.append({"tolerance": f"tolerances.{key}", "from": now, "to": floor,
                    "note": "to its process limit, not enough alone"})
        left[key] = c[key] * floor / now
    out.append({"tolerance": "none left", "from": None, "to": None,
                "note": "every tolerance at its process limit still misses the band: change "
                        "the design (a thicker web) or widen k_tolerance_rel"})
    return out


def band_check(plan: Plan, report: ToleranceReport, target: float,
               correction: Correction | None = None) -> dict:
    """Whether the toleranced design holds ``target`` (= k_tolerance_rel) and what to tighten.

    Returns:
        ``{"requirement": "k_tolerance_rel", "target", "predicted_band_rel", "coverage",
        "worst_element", "pass", "contributions_rel", "tighten"}``.
    """
    band, element = mc_band(report)
    part = plan.element(element).geometry.part_name if element else \
        next(iter(plan.distinct_elements))
    c = contributions(plan, report.tolerances, correction)[part]
    return {"requirement": "k_tolerance_rel", "target": target, "predicted_band_rel": band,
            "coverage": "95 % interval of K per element (Monte Carlo)",
            "worst_element": element, "pass": bool(band <= target),
            "contributions_rel": c, "tighten": tighten(c, report.tolerances, band, target)}


def toleranced_band_record(plan: Plan, target: float, error: float,
                           derive: Callable[[float], float] | None = None) -> dict:
    """``verify``'s record ``k_tolerance_rel_toleranced``: the Monte Carlo band under every
    ``[tolerances]`` value (not the web alone) against the requirement.

    Args:
        plan: the design. target: ``k_tolerance_rel``. error: the closed form's K error.
        derive: where the design file does not state ``k_tolerance_rel`` (it was derived
            from the web band alone), the rule that derives a K band requirement from a band
            (:func:`tactcad.studies.verification.padded_band_requirement`): this record's
            target is then the band under every tolerance so derived, where that is larger
            (a derived target is checked as it was derived).
    """
    tol = Tolerances.of_plan(plan)
    # the band reads the elements' K alone: the units' K_obj and the 5 % web are not drawn
    report = element_band_report(plan, samples=MONTE_CARLO_SAMPLES, seed=MONTE_CARLO_SEED,
                                 tolerances=tol)
    if derive is not None:
        target = max(target, derive(mc_band(report)[0]))
    check = band_check(plan, report, target)
    band = check["predicted_band_rel"]
    return {"requirement": "k_tolerance_rel_toleranced", "target": target, "predicted": band,
            "error_estimate_rel": error, "margin_rel": target / band - 1.0 if band > 0 else None,
            "model": "closed-form", "pass": check["pass"],
            "tighten": check["tighten"], "samples": MONTE_CARLO_SAMPLES, "seed": MONTE_CARLO_SEED,
            "basis": "Monte Carlo over the design's [tolerances] (95 % interval)"}


def with_tolerance(tol: Tolerances, key: str, value: float) -> Tolerances:
    """``tol`` with one [tolerances] key replaced."""
    return replace(tol, **{FIELDS[key]: value})

