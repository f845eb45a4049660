"""The ``[requirements]`` section of a design file: what the sensor must do.

Every key is optional; a key the file leaves out is derived from the
design's own geometry by :func:`tactcad.studies.verification.requirements_of`,
with the reason stated, never taken from the paper.

Keys (units in the names):

* ``full_scale_force_N``: the tip force every element must carry within its
  limits (yield / safety factor, fatigue strength, the gauge's fatigue and
  maximum strain, the notch's travel).
* ``kobj_range_N_per_mm = [LO, HI]``: object stiffnesses the array must read.
* ``kr_over_km``: stiffness ratio K_r / K_m of the sensing units (eq. 2).
* ``k_tolerance_rel``: the band each element's K must hold over the web's
  fabrication tolerance (relative, e.g. 0.1 for +/-10 %); judged only when the lab
  states it (left out, ``verify`` reports the K spread, not judged, and notes a large one).
* ``kobj_resolution_rel``: the relative K_obj resolution the array must reach
  over the whole range at the full-scale force.
* ``footprint_mm = [X, Y]`` or ``[X, Y, Z]``: the envelope the clamped array
  must fit (plan view X by Y, height Z), as its assembly STEP's box; never
  derived (without it nothing is checked).
* ``min_first_resonance_Hz``: the lowest first natural frequency any
  element may have as clamped (``tactcad modal``): a flexure ringing near
  the scan or sampling rate aliases; never derived (without it the first
  frequencies are reported, not checked).
* ``max_thermal_drift_N_per_K``: the largest equivalent tip force per kelvin
  any element's read-out may drift (:mod:`tactcad.mechanics.thermal_drift`);
  never derived (without it nothing is checked).
* ``max_crosstalk_rel``: the largest gauge crosstalk allowed (a neighbour's
  strain over the loaded gauge's own, :mod:`tactcad.mechanics.stack_crosstalk`);
  never derived (without it nothing is checked).
* ``kobj_accuracy_rel``: the largest relative K_obj error the array may read with over
  the whole K_obj range: the RSS of the K_obj error budget after correction
  (:mod:`tactcad.in_use.kobj_budget`) at the full-scale force and its default
  temperature step, each K_obj read by its best unit; never derived (without it the
  budget is reported, not judged).
* ``max_grasp_force_N``: the largest grasp force the tips may put on the tissue (N): at it
  (the grasp's force mode, :mod:`tactcad.in_use.grasp_experiment`, on the design's stated
  ``[grasper_jaw]`` and ``[tissue_slab]`` or the default jaw and tissue) every element's force on its spring must stay within its overload limit
  (yield with the safety factor, the gauge's largest strain), a hard stop taking the rest; never derived (without it nothing is checked).
* ``grid_power_density_W_per_mm2``: the largest power density the lab accepts in the gauge's
  grid (W/mm^2), stated where a design deliberately excites its gauges above
  Micro-Measurements TN-502's thin-section guidance (2 W/in^2: guidance on self-heating,
  which costs zero stability, not a strength limit); without it that guidance is the
  target, and a grid above it, short of the failure by heat, is undecided (the lab has not
  said it accepts the offset).
* ``source``: where the values come from (a citation); only a design whose
  source cites the paper gets the paper's loads, samples and text.
"""

from __future__ import annotations

from typing import Any, Mapping

from tactcad.vocabulary.schema import (Problems, Section, Text, fmt, listing, number,
                                       reason_as_read)

#: Title of the paper the macro array comes from; a design whose
#: ``requirements.source`` names it is the paper's design.
PAPER_TITLE = "Spring-based tactile array for assistive robotic surgical applications"

#: Keys of the section that are requirements (``source`` is their citation).
REQUIREMENT_KEYS = ("full_scale_force_N", "kobj_range_N_per_mm", "kr_over_km",
                    "k_tolerance_rel", "kobj_resolution_rel")

#: Requirements checked only when the file states them (never derived).
STATED_ONLY_KEYS = ("min_first_resonance_Hz", "max_thermal_drift_N_per_K", "max_crosstalk_rel",
                    "kobj_accuracy_rel", "max_grasp_force_N", "grid_power_density_W_per_mm2")


# the ranges, kept where nothing heavy is imported (a command's --help reads them)
from tactcad.design.requirement_limits import (  # noqa: E402,F401 (their names here too)
    MAX_FULL_SCALE_FORCE_N, MAX_GRASP_FORCE_N, MAX_GRID_POWER_DENSITY_W_PER_MM2,
    MAX_KOBJ_N_PER_MM, MAX_KR_OVER_KM, MIN_FULL_SCALE_FORCE_N, MIN_KOBJ_N_PER_MM)


class RequirementsSection(Section):
    """``[requirements]``: every key optional (derived from the design when absent)."""

    full_scale_force_N: number(MIN_FULL_SCALE_FORCE_N, MAX_FULL_SCALE_FORCE_N, unit="N",
                               why="tip force every element must carry") = None
    kobj_range_N_per_mm: listing(number(MIN_KOBJ_N_PER_MM, MAX_KOBJ_N_PER_MM, unit="N/mm"), 2, 2,
                                 f"[LO, HI] with {MIN_KOBJ_N_PER_MM:g} <= LO < HI <= "
                                 f"{MAX_KOBJ_N_PER_MM:g} N/mm",
                                 "object stiffnesses the array must read") = None
    kr_over_km: number(1.0, MAX_KR_OVER_KM, lo_open=True, unit="",
                       why="eq. 2 needs a reference stiffer than the measuring element") = None
    kr_over_km_tolerance_rel: number(0.0, 1.0, lo_open=True, unit="",
                                     why="how far below kr_over_km a row's K_r/K_m may lie "
                                         "(default 0.1)") = None
    k_tolerance_rel: number(0.0, 1.0, lo_open=True, unit="",
                            why="relative K band over the web tolerance") = None
    kobj_resolution_rel: number(0.0, 10.0, lo_open=True, unit="",
                                why="relative K_obj resolution over the range") = None
    footprint_mm: listing(number(0.0, 1e4, lo_open=True, unit="mm"), 2, 3,
                          "[X, Y] or [X, Y, Z] (mm)",
                          "the envelope the clamped array must fit") = None
    min_first_resonance_Hz: number(0.0, 1e7, lo_open=True, unit="Hz",
                                   why="lowest first natural frequency of any element") = None
    max_thermal_drift_N_per_K: number(0.0, 100.0, lo_open=True, unit="N/K",
                                      why="equivalent tip force per kelvin of any element") = None
    max_crosstalk_rel: number(0.0, 1.0, lo_open=True, unit="",
                              why="largest off-diagonal gauge strain over its diagonal") = None
    kobj_accuracy_rel: number(0.0, 10.0, lo_open=True, unit="",
                              why="relative K_obj error (RSS of the K_obj error budget) over "
                                  "the range") = None
    max_grasp_force_N: number(0.0, MAX_GRASP_FORCE_N, lo_open=True, unit="N",
                              why="grasp force at which every element must stay within its "
                                  "overload limit") = None
    grid_power_density_W_per_mm2: number(0.0, MAX_GRID_POWER_DENSITY_W_PER_MM2, lo_open=True,
                                         unit="W/mm^2",
                                         why="largest gauge-grid power density the lab "
                                             "accepts (above TN-502's guidance)") = None
    source: Text = None


def stated_thermal_drift(raw: Mapping[str, Any]) -> float | None:
    """``requirements.max_thermal_drift_N_per_K`` (N/K), or None when not stated."""
    return stated_number(raw, "max_thermal_drift_N_per_K")


def stated_kobj_accuracy(raw: Mapping[str, Any]) -> float | None:
    """``requirements.kobj_accuracy_rel`` (relative), or None when not stated."""
    return stated_number(raw, "kobj_accuracy_rel")


def stated_max_grasp_force(raw: Mapping[str, Any]) -> float | None:
    """``requirements.max_grasp_force_N`` (N), or None when not stated."""
    return stated_number(raw, "max_grasp_force_N")


def stated_grid_power_density(raw: Mapping[str, Any]) -> float | None:
    """``requirements.grid_power_density_W_per_mm2`` (W/mm^2), or None when not stated."""
    return stated_number(raw, "grid_power_density_W_per_mm2")


def stated_number(raw: Mapping[str, Any], key: str) -> float | None:
    """``requirements.<key>`` as a float, or None when the design does not state it."""
    table = raw.get("requirements") if isinstance(raw, Mapping) else None
    value = table.get(key) if isinstance(table, Mapping) else None
    return None if value is None else float(value)


def stated_footprint(raw: Mapping[str, Any]) -> tuple[float, ...] | None:
    """``requirements.footprint_mm`` as floats (mm), or None when not stated."""
    table = raw.get("requirements") if isinstance(raw, Mapping) else None
    value = table.get("footprint_mm") if isinstance(table, Mapping) else None
    return None if value is None else tuple(float(v) for v in value)


def check_requirements(d: Any, p: Problems) -> None:
    """Cross-field rule: ``kobj_range_N_per_mm`` is [LO, HI] with LO < HI."""
    req = getattr(d, "requirements", None)
    rng = getattr(req, "kobj_range_N_per_mm", None)
    if rng is not None and len(rng) == 2 and not rng[0] < rng[1]:
        p.add("requirements.kobj_range_N_per_mm", list(rng),
              f"[LO, HI] with LO < HI (got LO = {fmt(rng[0])}, HI = {fmt(rng[1])} N/mm)",
              "a range of object stiffnesses")


def stated_requirements(raw: Mapping[str, Any]) -> dict[str, Any]:
    """The requirement values a design's raw tables state (``{}`` without the section);
    ``kobj_range_N_per_mm`` as a tuple of floats."""
    table = raw.get("requirements") if isinstance(raw, Mapping) else None
    if not isinstance(table, Mapping):
        return {}
    out = {k: table[k] for k in REQUIREMENT_KEYS + STATED_ONLY_KEYS if k in table}
    if "kobj_range_N_per_mm" in out:
        out["kobj_range_N_per_mm"] = tuple(float(v) for v in out["kobj_range_N_per_mm"])
    return out


#: How a design file says a requirement was derived by ``tactcad design`` from the design's
#: own prediction, not stated by the lab: the start of its reason under ``[assumptions]``
#: (``"requirements.kobj_resolution_rel" = "Derived by tactcad design ..."``; an earlier
#: ``design`` also wrote ``k_tolerance_rel`` so, which ``verify`` now reads as not stated).
DERIVED_BY_DESIGN = "Derived by tactcad design from the design's own prediction"


def derived_requirements(raw: Mapping[str, Any]) -> dict[str, str]:
    """The ``[requirements]`` values a design file marks as derived by ``tactcad design``
    (their reason under ``[assumptions]`` starts with :data:`DERIVED_BY_DESIGN`), each with
    that reason: ``verify`` reports them as derived, not as stated by the lab.

    Args:
        raw: the design's raw tables.

    Returns:
        Requirement key -> its reason (empty where the file marks none).
    """
    stated = stated_requirements(raw)
    why = raw.get("assumptions") if isinstance(raw, Mapping) else None
    if not isinstance(why, Mapping):
        return {}
    read = {key: reason_as_read(f"requirements.{key}", why[f"requirements.{key}"], raw)
            for key in stated if isinstance(why.get(f"requirements.{key}"), str)}
    # a value edited since design derived it is the lab's now, not derived
    return {key: text for key, (text, applies) in read.items()
            if applies and text.startswith(DERIVED_BY_DESIGN)}


def requirements_source(raw: Mapping[str, Any]) -> str | None:
    """The ``requirements.source`` citation of a design, or None."""
    table = raw.get("requirements") if isinstance(raw, Mapping) else None
    return table.get("source") if isinstance(table, Mapping) else None


def cites_paper(raw: Mapping[str, Any]) -> bool:
    """True when the design file's ``requirements.source`` cites the paper
    (:data:`PAPER_TITLE`): only then do outputs carry the paper's loads,
    samples and text."""
    src = requirements_source(raw)
    return isinstance(src, str) and PAPER_TITLE.lower() in src.lower()
