"""Strength of the sensing elements: peak stress at the flexure hinge, the
yield-limited force, and the stress, gauge strain and tip deflection at the
design's rated full-scale force.

Peak stress per newton of tip force, at every level of the ladder:

* ``closed-form`` and ``beam``: nominal bending stress at the thinnest
  section of the web, sigma_nom / F = 6 a / (b t^2) (moment F a at the notch
  centre, Euler-Bernoulli section b x t), times the stress concentration
  factor of the single-sided circular notch,

      K_t = (1 + t / (2 R))^KT_EXPONENT.

  The form is that of the circular-notch hinge in bending of S. T. Smith,
  "Flexures: Elements of Elastic Mechanisms" (Gordon & Breach, 2000), from
  the notch charts of Peterson's Stress Concentration Factors (W. D. Pilkey,
  2nd ed., 1997), whose exponent 9/20 holds for the symmetric (double-sided)
  notch. The single-sided notch of these elements concentrates more (its
  flat face carries no notch); the exponent :data:`KT_EXPONENT` is refitted
  to converged plane-stress P2 FEM (:func:`fem_peak_stress`, Richardson over
  three meshes) by least squares on ln K_t over the ten geometries of
  :data:`KT_FIT_GEOMETRIES` (:func:`fit_kt_exponent` reproduces p = 0.5365),
  t/R = 0.05 ... 1, R = 0.4 ... 1.5 mm, arms 4 ... 8 mm (K_t from 1.014 to 1.240):
  largest residual 0.41 %, Richardson error of the FEM values <= 0.22 %;
  the tests check agreement within :data:`KT_FIT_TOLERANCE` (1 %).
  The free surface at the notch root is in uniaxial stress, so the peak von
  Mises stress equals the peak bending stress there.
* ``fem2d`` (plane stress) and ``fem3d``: the largest vertex von Mises stress
  at the hinge from the P2 field (:mod:`tactcad.mechanics.fem.fields`),
  Richardson-extrapolated over three meshes refined by sqrt(2).

The closed form is the plane-stress peak. A wide web (b/t = 12 in the
default design) is close to plane strain at mid-width, where sigma_z ~ nu
sigma_x lowers von Mises by sqrt(1 - nu + nu^2) = 0.88: fem3d's peak there is
0.90 of the closed form, which is therefore conservative for wide webs.

Two forces, never one name for both:

* the **rated full-scale force** (``full_scale_force_N``) is the design's
  rating, one force for the whole array (``[requirements]
  full_scale_force_N``, derived when absent: :func:`tactcad.studies.
  verification.requirements_of`); the caller passes it in;
* an element's **yield-limited force** (``yield_limited_force_N``) = yield
  strength / (peak stress per N x safety factor), one of the element's own
  force limits (:mod:`tactcad.mechanics.limits` lists them all).

At the rated full-scale force the gauge strain (``grid_strain_per_N`` x force)
is the one the plan's gauge grid reads (:func:`at_the_grid`: the mean strain on
the grid's plane over the grid, the read-out's ``grid_strain_per_N``),
and is compared with the gauge's maximum and fatigue strain, the stress with the
fatigue strength and the force with the yield-limited force; each
exceedance becomes a warning of the record. The fatigue strength at the
notch (:func:`notch_fatigue_strength`) is the library's smooth-specimen
datum converted to the fully reversed amplitude (Goodman:
:func:`tactcad.vocabulary.material_library.fully_reversed_amplitude`) times
the surface factor of the element's process
(:data:`tactcad.vocabulary.process.ELEMENT_PROCESS`: wire EDM, whose recast
layer sits at the notch root). A sensing element is pressed one way (R ~ 0)
while that strength and the gauges' fatigue strains are fully reversed
amplitudes: comparing the peak with them is conservative. The tip
deflection at full scale is F / K at the same level.

Units: mm, N, MPa, N/mm; strain dimensionless.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import asdict, dataclass, field, replace
from typing import Callable, NamedTuple

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.errors import DesignError
from tactcad.vocabulary.material_library import StrengthSettings
from tactcad.vocabulary.process import ELEMENT_PROCESS, Process
from tactcad.mechanics.ladder import estimate, is_meshed, models

#: Exponent of K_t = (1 + t/(2R))^p for the single-sided circular notch in
#: bending, fitted to converged plane-stress P2 FEM (see the module docstring).
KT_EXPONENT = 0.536
#: Stated accuracy of the fitted K_t against converged FEM (largest residual
#: of the fit 0.41 %, FEM error <= 0.22 %; Smith's 9/20 would be 3.2 % low at t/R = 1).
KT_FIT_TOLERANCE = 0.01
#: The geometries (web t mm, notch radius R mm, arm a mm) of the K_t fit;
#: other dimensions are the default design's.
KT_FIT_GEOMETRIES = ((0.075, 1.5, 8.0), (0.1, 1.0, 8.0), (0.2, 1.0, 8.0), (0.25, 0.714, 8.0),
                     (0.25, 0.5, 8.0), (0.25, 0.5, 4.0), (0.3, 0.4, 8.0), (0.4, 0.4, 8.0),
                     (0.15, 0.5, 6.0), (0.4, 1.0, 5.0))
#: t/R range of the K_t fit (outside it the error estimate doubles and a
#: StrengthRangeWarning is issued).
KT_FIT_RANGE = (0.05, 1.0)
#: Mesh refinement of the stress solves: finest neck size = web / divisions.
#: Plane: the notch-root stress needs a finer mesh than K (at t/6 the peak
#: is 1-3 % low; t/24 is within 0.1 % of t/48). 3D: the stiffness meshes'
#: t/6 (the 8 mm arm: 260.2 MPa/N, Richardson error 0.09 %; t/12 gives
#: 260.9, +0.3 %, at 2.6 x the time).
STRESS_WEB_DIVISIONS_2D = 24.0
STRESS_WEB_DIVISIONS_3D = 6.0



class StrengthRangeWarning(UserWarning):
    """A closed-form stress outside the t/R range its K_t was fitted over."""


# ---------------------------------------------------------------------------
# Pure formulas (numpy broadcasting)
# ---------------------------------------------------------------------------
def stress_concentration_factor(web_mm, notch_radius_mm) -> np.ndarray:
    """K_t of a single-sided circular notch hinge in bending (peak / nominal).

    Args:
        web_mm: web thickness t (mm). notch_radius_mm: notch radius R (mm).
            Array-like, broadcast together.

    Returns:
        (1 + t / (2R))^KT_EXPONENT, dimensionless, >= 1.

    Raises:
        ValueError: a non-finite or non-positive input.

    Source: form of S. T. Smith (2000), "Flexures", from Peterson's charts
    (Pilkey 1997); exponent refitted to plane-stress P2 FEM for the
    single-sided notch (:data:`KT_EXPONENT`).
    """
    t = _positive("web_mm", web_mm)
    R = _positive("notch_radius_mm", notch_radius_mm)
    return (1.0 + t / (2.0 * R)) ** KT_EXPONENT


def nominal_stress_per_newton(web_mm, arm_length_mm, sheet_mm) -> np.ndarray:
    """Nominal bending stress at the thinnest section per newton of tip force,
    6 a / (b t^2) (MPa/N; Euler-Bernoulli, moment F a at the notch centre).

    Raises:
        ValueError: a non-finite or non-positive input.
    """
    t = _positive("web_mm", web_mm)
    a = _positive("arm_length_mm", arm_length_mm)
    b = _positive("sheet_mm", sheet_mm)
    return 6.0 * a / (b * t * t)


def peak_stress_per_newton(web_mm, notch_radius_mm, arm_length_mm, sheet_mm) -> np.ndarray:
    """Closed-form peak von Mises stress at the notch root per newton (MPa/N):
    :func:`stress_concentration_factor` x :func:`nominal_stress_per_newton`."""
    return stress_concentration_factor(web_mm, notch_radius_mm) \
        * nominal_stress_per_newton(web_mm, arm_length_mm, sheet_mm)


def yield_limited_force(yield_strength_MPa, stress_MPa_per_N, safety_factor) -> np.ndarray:
    """An element's yield-limited force (N) = yield / (peak stress per N x safety factor).

    Raises:
        ValueError: a non-finite or non-positive input, or a safety factor < 1.
    """
    y = _positive("yield_strength_MPa", yield_strength_MPa)
    s = _positive("stress_MPa_per_N", stress_MPa_per_N)
    sf = _positive("safety_factor", safety_factor)
    if np.any(sf < 1.0):
        raise ValueError(f"safety_factor must be >= 1; got {np.ravel(sf)[:3].tolist()}")
    return y / (s * sf)


class NotchFatigue(NamedTuple):
    """The fatigue strength at the element's notch root.

    Attributes:
        smooth_MPa: fully reversed amplitude of the smooth specimen (MPa).
        surface_factor: the process's surface factor k_a (<= 1).
        strength_MPa: smooth_MPa x surface_factor, what the peak stress is held to (MPa).
        surface: the surface in words and why its factor (with sources).
    """

    smooth_MPa: float
    surface_factor: float
    strength_MPa: float
    surface: str


def notch_fatigue_strength(material: Material, process: Process = ELEMENT_PROCESS
                           ) -> NotchFatigue | None:
    """The fatigue strength at the notch root of an element made by ``process``.

    The material's fully reversed smooth-specimen amplitude times the
    process's surface factor k_a (:class:`tactcad.vocabulary.process.SurfaceFatigue`,
    evaluated at the ultimate strength; at the yield strength, an upper bound
    on k_a, when the design gives no grade and so no ultimate strength).

    Args:
        material: the sheet material. process: how the element is cut
            (default the elements' wire EDM).

    Returns:
        :class:`NotchFatigue`, or None without a fatigue strength.
    """
    smooth = material.fatigue_strength_MPa
    if smooth is None:
        return None
    if process.surface is None:
        return NotchFatigue(smooth, 1.0, smooth, f"{process}: no surface factor stated")
    s_u = material.ultimate_strength_MPa or material.yield_strength_MPa
    if s_u is None:
        return NotchFatigue(smooth, process.surface.ceiling, smooth * process.surface.ceiling,
                            process.surface.surface + " (no ultimate strength: the ceiling)")
    k_a = process.surface.factor(s_u)
    return NotchFatigue(smooth, k_a, smooth * k_a, process.surface.surface)


def force_limits(web_mm, notch_radius_mm, arm_length_mm, sheet_mm, material: Material,
                 settings: StrengthSettings, grid_strain_per_N=None) -> dict[str, np.ndarray]:
    """Closed-form tip-force limits (N) of element geometries, broadcast over
    the geometry arrays (for design searches).

    Args:
        grid_strain_per_N: what the gauge's grid reads per newton on each geometry (1/N,
            either sign; :func:`tactcad.mechanics.readout_chain.closed_form_grid_read_per_N`,
            the number strength and the read-out quote); None: the face strain as cut at
            the notch centre, Euler-Bernoulli's 6 a / (E b t^2) x the fem3d-fitted point factor
            of :mod:`tactcad.mechanics.gauge_strain`.

    Returns:
        ``yield``: yield-limited force, yield / (peak stress per N x safety factor);
        ``fatigue``: fatigue strength at the notch (:func:`notch_fatigue_strength`)
        / peak stress per N (NaN without a fatigue strength); ``gauge_max`` and
        ``gauge_fatigue``: the gauge's maximum and fatigue strain / the gauge strain per
        N; ``binding``: the smallest of them.

    Raises:
        DesignError: the material has no yield strength.
        ValueError: a non-finite or non-positive geometry value.
    """
    y = require_yield(material)
    s = peak_stress_per_newton(web_mm, notch_radius_mm, arm_length_mm, sheet_mm)
    if grid_strain_per_N is None:
        from tactcad.mechanics.gauge_strain import point_factor

        eps = (nominal_stress_per_newton(web_mm, arm_length_mm, sheet_mm)
               / material.youngs_modulus_MPa
               * point_factor(web_mm, notch_radius_mm, sheet_mm, material.poisson_ratio))
    else:
        eps = np.abs(np.asarray(grid_strain_per_N, float))
    notch = notch_fatigue_strength(material)
    out = {"yield": yield_limited_force(y, s, settings.safety_factor),
           "fatigue": (notch.strength_MPa / s) if notch else np.full_like(s, np.nan),
           "gauge_max": settings.gauge.max_strain / eps,
           "gauge_fatigue": settings.gauge.fatigue_strain / eps}
    out["binding"] = np.fmin.reduce([out["yield"], out["fatigue"], out["gauge_max"],
                                     out["gauge_fatigue"]])
    return out


def _positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:  # one value (a search's every element): checked without reductions
        x = float(arr)
        if not (math.isfinite(x) and x > 0):
            raise ValueError(f"{name} must be finite and > 0; got {np.ravel(arr)[:3].tolist()}")
        return arr
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"{name} must be finite and > 0; got {np.ravel(arr)[:3].tolist()}")
    return arr


# ---------------------------------------------------------------------------
# One element at one ladder level
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class ElementStress:
    """Per-newton response of one element geometry at one ladder level.

    Attributes:
        model: ladder level.
        stress_MPa_per_N: peak von Mises stress at the hinge per N (MPa/N).
        stress_error_rel: estimated relative error of the peak (Richardson
            for FEM; the fit tolerance for the closed form).
        stiffness_N_per_mm: K at the same level (N/mm).
        peak_location_mm: where the peak is (element frame, mm); empty for
            the closed form (the notch root, x = hinge_x).
        grid_strain_per_N: what the plan's gauge grid reads per N (1/N, magnitude: the
            mean strain on the grid's plane over the grid, the read-out's
            ``grid_strain_per_N``). None as the stress evaluations give it
            (:func:`closed_form_stress`,
            :func:`tactcad.studies.strength_studies.fem_peak_stress`); strength, the
            limits and ``verify`` set it (:func:`at_the_grid`) before they use it.
    """

    model: str
    stress_MPa_per_N: float
    stress_error_rel: float
    stiffness_N_per_mm: float
    peak_location_mm: tuple[float, ...] = ()
    grid_strain_per_N: float | None = None

    def read_strain_per_N(self) -> float:
        """:attr:`grid_strain_per_N`, which the gauge-strain figures and limits need.

        Raises:
            ValueError: not set (:func:`at_the_grid` sets it).
        """
        if self.grid_strain_per_N is None:
            raise ValueError(f"ElementStress at {self.model}: grid_strain_per_N is not set "
                             "(at_the_grid gives it)")
        return self.grid_strain_per_N


def closed_form_stress(g: ElementGeometry, material: Material, model: str = "closed-form"
                       ) -> ElementStress:
    """Closed-form peak stress with K and gauge strain of ``model``
    ("closed-form" or "beam", which share the stress formula)."""
    r = estimate(model, g, material)
    s = float(peak_stress_per_newton(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
                                     g.sheet_thickness_mm))
    err = KT_FIT_TOLERANCE
    t_over_r = g.web_thickness_mm / g.notch_radius_mm
    if not KT_FIT_RANGE[0] <= t_over_r <= KT_FIT_RANGE[1]:
        err = 2.0 * KT_FIT_TOLERANCE
        warnings.warn(f"{g.part_name}: t/R = {t_over_r:.3g} is outside the K_t fit range "
                      f"{KT_FIT_RANGE[0]:g} ... {KT_FIT_RANGE[1]:g}; estimated error "
                      f"{100 * err:.0f} %", StrengthRangeWarning, stacklevel=2)
    return ElementStress(model, s, err, r.stiffness_N_per_mm)


# ---------------------------------------------------------------------------
# Full scale
# ---------------------------------------------------------------------------
class ReferenceLoad(NamedTuple):
    """A tip load to state each element's stress at, beside its full scale,
    and whose it is: the caller's (e.g. the paper's design-study load for
    the paper's design, :data:`tactcad.paper.paper_load.PAPER_LOAD`); never
    a default of the general code.

    Attributes:
        force_N: the tip load (N).
        whose: the load's owner as a warning names it ("the paper's").
    """

    force_N: float
    whose: str


@dataclass(frozen=True)
class StrengthRecord:
    """Strength of one element of a plan at one ladder level.

    Attributes (units in the names): see :func:`strength_record`.
    ``full_scale_force_N`` is the design's rated full-scale force (the same
    for every element); ``yield_limited_force_N`` this element's own limit
    from yield. ``warnings`` lists every limit exceeded at the rated force, in words.
    """

    element: int
    part_name: str
    arm_length_mm: float
    model: str
    stress_MPa_per_N: float
    stress_error_rel: float
    stress_concentration_factor: float
    full_scale_force_N: float
    yield_limited_force_N: float
    yield_safety_factor_at_full_scale: float
    stress_MPa_at_full_scale: float
    gauge_strain_at_full_scale: float
    tip_deflection_mm_at_full_scale: float
    stiffness_N_per_mm: float
    fatigue_force_N: float | None
    gauge_fatigue_force_N: float
    # at the caller's reference load (the paper's design load for the paper's
    # design: tactcad.paper.paper_load); None without one
    stress_MPa_at_reference_load: float | None
    yield_safety_factor_at_reference_load: float | None
    warnings: tuple[str, ...] = field(default=())
    fatigue_strength_at_notch_MPa: float | None = None
    fatigue_surface_factor: float | None = None

    def as_json(self) -> dict:
        """Plain dict for JSON (all numbers finite; ``warnings`` a list); the
        figures at the reference load only when there is one."""
        d = asdict(self)
        d["warnings"] = list(self.warnings)
        if self.stress_MPa_at_reference_load is None:
            del d["stress_MPa_at_reference_load"], d["yield_safety_factor_at_reference_load"]
        return d


def require_yield(material: Material) -> float:
    """The material's yield strength (MPa).

    Raises:
        DesignError: it has none (the message names the grades that give one).
    """
    if material.yield_strength_MPa is None:
        from tactcad.vocabulary.material_library import material_grades

        raise DesignError("material.yield_strength_MPa", None,
                          "a value in MPa, or a material.grade (one of "
                          + ", ".join(material_grades()) + ")",
                          "the element force limits need the yield strength")
    return float(material.yield_strength_MPa)


def rated_force_warnings(force_N: float, yield_limited_N: float, stress_MPa: float,
                         gauge_strain: float, es: ElementStress, material: Material,
                         settings: StrengthSettings) -> list[str]:
    """Every limit the rated full-scale force ``force_N`` exceeds, in words.

    Args:
        force_N: the design's rated full-scale force (N).
        yield_limited_N: the element's yield-limited force (N).
        stress_MPa, gauge_strain: peak stress and gauge strain at ``force_N``.
        es: the element's per-newton response. material, settings: as the plan's.

    Returns:
        one sentence per exceedance: yield-limited force, fatigue strength,
        gauge maximum strain, gauge fatigue strain (empty when none).
    """
    gauge, notch = settings.gauge, notch_fatigue_strength(material)
    fat = notch.strength_MPa if notch else None
    warn = []
    if force_N > yield_limited_N:
        warn.append(f"the rated full-scale force {force_N:.3g} N exceeds this element's "
                    f"yield-limited force {yield_limited_N:.3g} N (safety factor "
                    f"{settings.safety_factor:g})")
    if fat is not None and stress_MPa > fat:
        cyc = f" ({material.fatigue_cycles:.0e} cycles)" if material.fatigue_cycles else ""
        warn.append(f"cycling to the rated full-scale force {force_N:.3g} N ({stress_MPa:.0f} "
                    f"MPa) exceeds the fatigue strength at the notch {fat:.0f} MPa{cyc}, surface "
                    f"factor {notch.surface_factor:.2f}: cycle below "
                    f"{fat / es.stress_MPa_per_N:.3g} N")
    if gauge_strain > gauge.max_strain:
        warn.append(f"gauge strain at the rated full-scale force {gauge_strain * 1e6:.0f} "
                    f"microstrain exceeds the gauge's maximum {gauge.max_strain * 1e6:.0f} "
                    "microstrain")
    if gauge_strain > gauge.fatigue_strain:
        warn.append(f"gauge strain at the rated full-scale force {gauge_strain * 1e6:.0f} "
                    f"microstrain exceeds the gauge's fatigue strain "
                    f"{gauge.fatigue_strain * 1e6:.0f} microstrain ({gauge.fatigue_cycles:.0e} "
                    f"cycles): cycle below {gauge.fatigue_strain / es.read_strain_per_N():.3g} N")
    return warn


def strength_record(element: int, g: ElementGeometry, material: Material,
                    settings: StrengthSettings, es: ElementStress, full_scale_force_N: float,
                    reference_load: ReferenceLoad | None = None) -> StrengthRecord:
    """Figures of one element at the design's rated full-scale force from its
    per-newton response.

    full_scale_force_N = the rating given (N, the design's, one for the array);
    yield_limited_force_N = yield / (stress_MPa_per_N x safety factor);
    yield_safety_factor_at_full_scale = yield / stress at the rated force;
    gauge_strain_at_full_scale = grid_strain_per_N x rated force (what the grid reads);
    tip_deflection_mm_at_full_scale = rated force / K;
    fatigue_force_N = fatigue strength at the notch / stress per N (None without one);
    fatigue_strength_at_notch_MPa, fatigue_surface_factor: :func:`notch_fatigue_strength`;
    gauge_fatigue_force_N = gauge fatigue strain / grid_strain_per_N;
    warnings: :func:`rated_force_warnings`; stress and yield safety factor
    at ``reference_load``, and a warning when it yields the web, only when
    one is given (None otherwise; the paper's design load for the paper's
    design is :mod:`tactcad.paper.paper_load`'s).

    Args:
        full_scale_force_N: the design's rated full-scale force (N), > 0
            (:func:`tactcad.studies.verification.requirements_of`).

    Raises:
        DesignError: the material has no yield strength.
        ValueError: a rated force that is not finite and > 0.
    """
    y = require_yield(material)
    f_fs = float(_positive("full_scale_force_N", full_scale_force_N))
    f_yield = float(yield_limited_force(y, es.stress_MPa_per_N, settings.safety_factor))
    s_fs = es.stress_MPa_per_N * f_fs
    eps_fs = es.read_strain_per_N() * f_fs
    s_ref = None if reference_load is None else es.stress_MPa_per_N * reference_load.force_N
    nominal = float(nominal_stress_per_newton(g.web_thickness_mm, g.arm_length_mm,
                                              g.sheet_thickness_mm))
    notch = notch_fatigue_strength(material)
    warn = []
    if reference_load is not None and s_ref is not None and s_ref > y:
        warn.append(f"at {reference_load.whose} {reference_load.force_N:g} N the web reaches "
                    f"{s_ref:.0f} MPa, above "
                    f"the yield strength {y:.0f} MPa of {material.grade or material.name}")
    warn += rated_force_warnings(f_fs, f_yield, s_fs, eps_fs, es, material, settings)
    return StrengthRecord(
        element=element, part_name=g.part_name, arm_length_mm=g.arm_length_mm, model=es.model,
        stress_MPa_per_N=es.stress_MPa_per_N, stress_error_rel=es.stress_error_rel,
        stress_concentration_factor=es.stress_MPa_per_N / nominal,
        full_scale_force_N=f_fs, yield_limited_force_N=f_yield,
        yield_safety_factor_at_full_scale=y / s_fs,
        stress_MPa_at_full_scale=s_fs, gauge_strain_at_full_scale=eps_fs,
        tip_deflection_mm_at_full_scale=f_fs / es.stiffness_N_per_mm,
        stiffness_N_per_mm=es.stiffness_N_per_mm,
        fatigue_force_N=None if notch is None else notch.strength_MPa / es.stress_MPa_per_N,
        fatigue_strength_at_notch_MPa=None if notch is None else notch.strength_MPa,
        fatigue_surface_factor=None if notch is None else notch.surface_factor,
        gauge_fatigue_force_N=settings.gauge.fatigue_strain / es.read_strain_per_N(),
        stress_MPa_at_reference_load=s_ref,
        yield_safety_factor_at_reference_load=None if s_ref is None else y / s_ref,
        warnings=tuple(warn))


def at_the_grid(es: ElementStress, g: ElementGeometry, plan: Plan,
                level: str | None = None) -> ElementStress:
    """``es`` with the strain per newton the plan's gauge grid reads on ``g`` at
    ``level`` (:func:`tactcad.mechanics.readout_chain.grid_strain_per_N`'s
    ``grid``: the mean strain on the grid's plane over the grid) as its
    ``grid_strain_per_N``: strength, the hard stops and the read-out then quote one
    gauge strain. Unsigned (1/N).

    Args:
        es: the element's stress figures (MPa/N, N/mm).
        g: the element (mm). plan: the design (its read-out chain and material).
        level: the ladder level the grid strain is read at; None: ``es.model``. A level
            whose figures no open requirement reads passes "closed-form"
            (:func:`tactcad.studies.verification.unread_at_the_grid`): no mesh sequence
            is solved for them.

    Returns:
        ``es`` with ``grid_strain_per_N`` set (1/N).
    """
    from tactcad.mechanics.readout_chain import (grid_strain_per_N, readout_chain,
                                                 unmeshed_grid_strain_per_N)

    level = es.model if level is None else level
    chain = readout_chain(plan)
    if not is_meshed(level):  # a pure function of its inputs: read once per process
        return replace(es, grid_strain_per_N=unmeshed_grid_strain_per_N(
            g, plan.material, chain, level))
    grid = grid_strain_per_N(g, plan.material, chain, level)["grid"]
    return replace(es, grid_strain_per_N=abs(float(grid)))


def peak_stress_sequence(g: ElementGeometry, material: Material, model: str = "fem3d",
                         web_divisions: float | None = None, levels: int = 3):
    """The fem3d mesh sequence :func:`fem_peak_stress` reads the hinge's peak from: the bare
    element's (its gauge's layer left off), kept in the result store, so a process solving
    it beside the command (:mod:`tactcad.studies.parallel_solves`) hands it over.
    Read by :func:`tactcad.studies.strength_studies.fem_peak_stress`.

    Args:
        g: the element as installed (mm); its bare twin is meshed. material: E, nu (MPa).
        model: "fem3d" (the one level with a 3D sequence).
        web_divisions: finest neck size = web / web_divisions (default
            :data:`STRESS_WEB_DIVISIONS_3D`).
        levels: number of meshes (>= 3).

    Returns:
        (the solves without their fields, each mesh's peak at the hinge), coarsest first.

    Raises:
        ValueError: ``model`` is not fem3d.
    """
    if model != "fem3d":
        raise ValueError(f"model must be fem3d for the 3D peak-stress sequence; got {model!r}")
    from tactcad.mechanics.fem.fem3d import fem3d_convergence

    conv = fem3d_convergence(g.bare(), material, levels=levels,
                             web_divisions=web_divisions or STRESS_WEB_DIVISIONS_3D)
    return conv.solutions, conv.peaks


#: Evaluates one element's peak stress at a model: (geometry, material, model) -> ElementStress.
StressModel = Callable[[ElementGeometry, Material, str], ElementStress]


def plan_strength(plan: Plan, full_scale_force_N: float, model: str = "closed-form",
                  progress=None, stress: StressModel | None = None,
                  reference_load: ReferenceLoad | None = None) -> list[StrengthRecord]:
    """:class:`StrengthRecord` of every element of the plan at ``model``;
    distinct geometries are evaluated once.

    Args:
        full_scale_force_N: the design's rated full-scale force (N;
            :func:`tactcad.studies.verification.requirements_of`, which
            :func:`tactcad.studies.strength_studies.plan_strength` reads).
        stress: the peak-stress evaluation; default :func:`closed_form_stress`
            (closed-form and beam). The FEM levels are run by
            :func:`tactcad.studies.strength_studies.plan_strength`, which passes its own.
        reference_load: a load to give each element's stress at
            (:func:`strength_record`); none by default.

    Raises:
        ValueError: unknown model, or an FEM model without its ``stress``.
        DesignError: the material has no yield strength.
    """
    if model not in models():
        raise ValueError(f"model must be one of {', '.join(models())}; got {model!r}")
    if stress is None:
        if is_meshed(model):
            raise ValueError(f"model {model} runs the FEM: use tactcad.studies.strength_studies.plan_strength")
        stress = closed_form_stress
    require_yield(plan.material)
    cache: dict[str, ElementStress] = {}
    out = []
    for slot in plan.slots:
        g = slot.geometry
        if g.part_name not in cache:
            if progress:
                progress(f"{model}: {g.part_name}")
            cache[g.part_name] = at_the_grid(stress(g, plan.material, model), g, plan)
        out.append(strength_record(slot.number, g, plan.material, plan.strength,
                                   cache[g.part_name], full_scale_force_N, reference_load))
    return out


def part_strength(plan: Plan, full_scale_force_N: float) -> dict[str, StrengthRecord]:
    """The closed form's :class:`StrengthRecord` of each distinct part of ``plan``: the
    record :func:`plan_strength` gives its first element (every element of a part has the
    same figures; only the element number differs), without working out the others.

    Args:
        plan: the design. full_scale_force_N: its rated full-scale force (N), > 0.

    Returns:
        Part name -> the record of its first element.

    Raises:
        DesignError: the material has no yield strength.
        ValueError: a rated force that is not finite and > 0.
    """
    require_yield(plan.material)
    out: dict[str, StrengthRecord] = {}
    for slot in plan.slots:
        g = slot.geometry
        if g.part_name not in out:
            es = at_the_grid(closed_form_stress(g, plan.material, "closed-form"), g, plan)
            out[g.part_name] = strength_record(slot.number, g, plan.material, plan.strength,
                                               es, full_scale_force_N)
    return out


def strength_summary(plan: Plan, full_scale_force_N: float, model: str = "closed-form",
                     reference_load: ReferenceLoad | None = None) -> list[dict]:
    """JSON-ready strength records of every element at the design's rated
    ``full_scale_force_N`` (N) (for the CLI, the drawings and the manifest):
    keys ``element``, ``stress_MPa_per_N``, ``full_scale_force_N`` (the
    rating), ``yield_limited_force_N``, ``yield_safety_factor_at_full_scale``,
    ``gauge_strain_at_full_scale``, ``tip_deflection_mm_at_full_scale`` and
    the other fields of :class:`StrengthRecord` (those at ``reference_load``
    only with one). All numbers are finite.

    Raises:
        ValueError: unknown model.
        DesignError: the material has no yield strength.
    """
    recs = [r.as_json() for r in plan_strength(plan, full_scale_force_N, model,
                                               reference_load=reference_load)]
    for r in recs:
        for k, v in r.items():
            if isinstance(v, float) and not math.isfinite(v):
                raise RuntimeError(f"non-finite {k} for element {r['element']}")
    return recs
