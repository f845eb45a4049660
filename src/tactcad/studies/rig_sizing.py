"""Test rigs sized to a design: the force gauge, the evaluation rig's weights,
and the loads the rigs put on the elements against the design's rating.

* **Force gauge** (calibration and sample-stiffness rigs share it): its range
  covers the largest force the rigs read: the rated full-scale force F
  (calibration: six Z steps up to F), or the stiffest sample pressed as deep
  as one element at F presses the softest, F / K_lo (the sample rig presses
  every sample to one depth, as the paper's did to 300 um): F K_hi / K_lo,
  which follows the design's K_obj range; its resolution is at most
  :data:`RESOLUTION_SHARE` of F. The rigs made for a design take the
  catalogue gauge (:mod:`tactcad.vocabulary.force_gauge_catalogue`) of
  smallest range that fits, of equal ranges the finest.
* **Weights** (evaluation rig): the array hangs on a vertical axis and is
  pressed into the sample by the axis's own weight (the preload) and the
  weights stacked on it. Every element's tip force is linear in that load
  (:func:`tactcad.studies.design_loads.element_tip_force_per_newton`, the
  ``evaluate`` command's sample model), so the rig's top load is F over the
  largest tip force per newton over its samples. The weights are the largest
  of the 1-2-5 series of calibration masses (OIML R 111 nominal values) of
  which at least :data:`WEIGHT_COUNT_RANGE`'s lower end fit under the top load
  after a preload of one weight (the moving axis counterbalanced to that);
  as many as fit, up to the range's upper end.
* **Loads against the rating**: :func:`evaluation_rig_load` gives the most
  loaded element's tip force at the rig's top load, which ``check`` fails
  above F.

Units: N, N/mm, g, mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.design.array_plan import Plan
from tactcad.errors import DesignError
from tactcad.mechanics.evaluation import STANDARD_GRAVITY, SampleSpec, ladder_stiffness_by_element
from tactcad.vocabulary.force_gauge_catalogue import RESOLUTION_SHARE, GaugeNeed

#: How many weights the evaluation rig stacks (at least, at most) above its preload.
WEIGHT_COUNT_RANGE = (4, 10)
#: The weights' steel (g/cm^3).
STEEL_DENSITY_G_PER_CM3 = 7.85
#: The weight cylinder's height over its diameter (a squat, stable stack).
WEIGHT_HEIGHT_OVER_DIAMETER = 0.5
#: Weight diameters allowed on the carrier's shelf (mm).
WEIGHT_DIAMETER_RANGE_MM = (5.0, 40.0)


def evaluation_sample_spec() -> SampleSpec:
    """The sample model the rig loads are judged with: ``evaluate``'s default
    (rubber half-space, nu 0.5)."""
    return SampleSpec()


# ---------------------------------------------------------------------------
# Force gauge
# ---------------------------------------------------------------------------
def gauge_need(rated_N: float, samples_N_per_mm) -> GaugeNeed:
    """The force gauge a design's rigs need (see the module docstring).

    Args:
        rated_N: the design's rated full-scale force (N), > 0.
        samples_N_per_mm: the samples' K_obj (N/mm), each > 0.
    """
    depth = rated_N / min(samples_N_per_mm)
    sample = max(samples_N_per_mm) * depth
    return GaugeNeed(rated_N, depth, sample, max(rated_N, sample), RESOLUTION_SHARE * rated_N)


# ---------------------------------------------------------------------------
# Evaluation rig: weights and loads
# ---------------------------------------------------------------------------
def element_loads_per_newton(plan: Plan, samples) -> dict[int, float]:
    """Each element's largest tip force (N) per newton of the evaluation rig's
    load over ``samples`` (N/mm), closed-form K, ``evaluate``'s sample model."""
    from tactcad.studies.design_loads import element_tip_force_per_newton

    return element_tip_force_per_newton(plan, ladder_stiffness_by_element(plan), samples,
                                        evaluation_sample_spec())


def weight_series_g(largest_g: float) -> list[float]:
    """The 1-2-5 series of calibration masses (g) from 1 mg up to ``largest_g``, largest first."""
    out = [m * 10.0 ** e for e in range(-3, 6) for m in (1.0, 2.0, 5.0)]
    return sorted((round(m, 6) for m in out if m <= largest_g * (1 + 1e-12)), reverse=True)


@dataclass(frozen=True)
class WeightSet:
    """The evaluation rig's weights for a design.

    Attributes:
        mass_g: one weight (g). count: how many are stacked.
        preload_N: the moving axis's net weight on the sample (N): one weight.
        diameter_mm: the steel cylinder's diameter (mm).
        top_load_N: preload + every weight (N).
        element: the most loaded element at the top load.
        element_load_N: its tip force there (N).
    """

    mass_g: float
    count: int
    preload_N: float
    diameter_mm: float
    top_load_N: float
    element: int
    element_load_N: float


def weight_diameter_mm(mass_g: float) -> float:
    """A steel weight's diameter (mm, to 0.5 mm) for a cylinder
    :data:`WEIGHT_HEIGHT_OVER_DIAMETER` as high as wide, within
    :data:`WEIGHT_DIAMETER_RANGE_MM`."""
    volume = mass_g / STEEL_DENSITY_G_PER_CM3 * 1000.0
    d = (4.0 * volume / (math.pi * WEIGHT_HEIGHT_OVER_DIAMETER)) ** (1.0 / 3.0)
    lo, hi = WEIGHT_DIAMETER_RANGE_MM
    return min(max(round(2.0 * d) / 2.0, lo), hi)


def weights_for(per_newton: dict[int, float], rated_N: float) -> WeightSet:
    """The weights that take the most loaded element to at most ``rated_N``
    (N) at the rig's top load (see the module docstring).

    Args:
        per_newton: each element's tip force per newton of rig load
            (:func:`element_loads_per_newton`).

    Raises:
        DesignError: not even the series' smallest mass fits (a rating too
            small for any stack of calibration weights).
    """
    element, share = max(per_newton.items(), key=lambda kv: (kv[1], -kv[0]))
    top = rated_N / share  # rig load (N) at which the most loaded element reaches the rating
    least, most = WEIGHT_COUNT_RANGE
    for mass in weight_series_g(1000.0 * top / STANDARD_GRAVITY / (least + 1)):
        step = mass / 1000.0 * STANDARD_GRAVITY
        count = min(int(math.floor(top / step * (1 + 1e-12))) - 1, most)
        if count >= least:
            load = step * (count + 1)
            return WeightSet(mass, count, step, weight_diameter_mm(mass), load, element,
                             load * share)
    raise DesignError("requirements.full_scale_force_N", rated_N,
                      f"a rating the evaluation rig can load in {least} steps of 1 mg at least",
                      f"the rig's top load would be {top:.3g} N")


@dataclass(frozen=True)
class RigLoad:
    """The largest tip force a rig puts on an element, against the rating.

    Attributes:
        rig: the rig, in words. part: the rig part that loads (name as in the BOM).
        load_N: the rig's load (N). element: the most loaded element.
        element_load_N: its tip force (N). rated_N: the design's rated full-scale force (N).
        how: the load in words (preload, weights).
    """

    rig: str
    part: str
    load_N: float
    element: int
    element_load_N: float
    rated_N: float
    how: str

    @property
    def within_rating(self) -> bool:
        return self.element_load_N <= self.rated_N * (1 + 1e-9)


def evaluation_rig_steps(rigs) -> tuple[list[float], str] | None:
    """The evaluation rig's load steps as its rigs file states them: the
    preload (``[evaluation] preload_N``), then each of the ``[weights]`` added
    one at a time (N), and those words ("0.1961 N preload + 4 x 20 g").

    Args:
        rigs: the project's :class:`~tactcad.design.rig_plan.RigDesign`.

    Returns:
        (loads, words), or None when the rigs state no preload.
    """
    if rigs.evaluation_preload_N is None:
        return None
    w = rigs.part("weights")
    step = w.mass_g / 1000.0 * STANDARD_GRAVITY
    loads = [rigs.evaluation_preload_N + k * step for k in range(w.count + 1)]
    return loads, f"{rigs.evaluation_preload_N:.4g} N preload + {w.count} x {w.mass_g:g} g"


def evaluation_rig_load(plan: Plan, rigs, rated_N: float) -> RigLoad | None:
    """The evaluation rig's top load (preload and every weight) and the most
    loaded element's tip force there over the rig's samples; None when the
    rigs state no preload (``[evaluation] preload_N``)."""
    steps = evaluation_rig_steps(rigs)
    if steps is None:
        return None
    loads, how = steps
    per_newton = element_loads_per_newton(plan, rigs.sample_stiffness_N_per_mm)
    element, share = max(per_newton.items(), key=lambda kv: (kv[1], -kv[0]))
    return RigLoad("array evaluation rig", rigs.library["weights"].name, loads[-1], element,
                   loads[-1] * share, rated_N, how)
