"""The limits that bind a design, as codes: what a refusal carries (``DesignError.limit``,
a comb candidate's ``limits``) so that a reader (the design atlas, a report) sorts refusals
by the limit itself and not by the words that explain it.

Each code is set where its limit is decided: the die's rating checks, its read-out's K_obj
resolution, its beam search and its fit in the pocket; the comb's pitch, web solve, plan
validation, verification matrix, hard stops, height and gauge limits.
"""

from __future__ import annotations

#: The material's strength: yield, the die's Weibull failure probability, its roots' mean.
STRENGTH = "strength"
#: Fatigue: an element's or a gauge's fatigue limit at the rated force.
FATIGUE = "fatigue"
#: A hard stop: engaging outside its window, a stop gap or a cavity or post out of reach.
STOP = "stop"
#: The K_obj resolution or range the read-out reaches (eq. 3 and its noise).
RESOLUTION = "resolution"
#: The full-scale force a design's elements carry at the closed form.
FORCE = "force"
#: The footprint: the pocket's length or width, the columns it holds.
FOOTPRINT = "footprint"
#: The height the jaw leaves (its thickness and the tips' proud height).
HEIGHT = "height"
#: The sheet: its pitch, arms and webs the process cuts from it.
SHEET = "sheet"
#: The die's device layer and beam sections: no slender pair fits the window.
LAYER = "layer"
#: Any other limit (a table's own rule).
OTHER = "other"

#: Every code, in the order a summary lists them.
BINDING_LIMITS = (STRENGTH, FATIGUE, STOP, RESOLUTION, FORCE, FOOTPRINT, HEIGHT, SHEET, LAYER,
                  OTHER)

#: A verification requirement's name -> the limit its failure is.
REQUIREMENT_LIMITS = {
    "kobj_resolution_rel": RESOLUTION, "kobj_range_N_per_mm": RESOLUTION,
    "kobj_accuracy_rel": RESOLUTION, "kr_over_km": RESOLUTION,
    "full_scale_force_N": FORCE, "k_tolerance_rel": SHEET,
    "max_grasp_force_N": STRENGTH, "footprint_mm": FOOTPRINT,
}

#: A gauge or element limit of :mod:`tactcad.mechanics.limits` -> its code.
MECHANICS_LIMITS = {"yield": STRENGTH, "fatigue": FATIGUE, "gauge_fatigue": FATIGUE,
                    "gauge_max": STRENGTH, "travel": STOP}


def requirement_limit(requirement: str) -> str:
    """The limit a failed verification requirement is.

    Args:
        requirement: the record's ``requirement`` (e.g. ``full_scale_force_N``).

    Returns:
        Its code of :data:`BINDING_LIMITS` (:data:`OTHER` for a requirement not listed).
    """
    return REQUIREMENT_LIMITS.get(requirement, OTHER)


def field_limit(field: str) -> str:
    """The limit a refused design-file field is, for a plan the validation refuses.

    Args:
        field: the dotted key (``comb.stop_gaps_mm[1]``, ``element.web_thickness_mm``...).

    Returns:
        :data:`STOP` for a stop's field, :data:`HEIGHT` or :data:`FOOTPRINT` for the jaw's
        thickness or length and width, else :data:`SHEET` (the cut comb's own sizes).
    """
    name = field.lower()
    if "stop" in name:
        return STOP
    if "thickness_mm" in name and name.startswith("grasper_jaw"):
        return HEIGHT
    if name.startswith("grasper_jaw") or "footprint" in name:
        return FOOTPRINT
    return SHEET
