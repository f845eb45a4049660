"""Strength studies: the FEM peak stress at the hinge (plane-stress fem2d or
fem3d over three meshes, Richardson-extrapolated), the refit of the K_t
exponent from it and the plan's strength at any ladder level (the comparison
with the paper's Table 1 calibration forces runs it:
:func:`tactcad.paper.table1.table1_force_comparison`). The models they run are in
:mod:`tactcad.mechanics.element_strength` and :mod:`tactcad.mechanics.fem`.

Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.mechanics.fem.fem2d import (REFINEMENT_RATIO, richardson, single_threaded_blas,
                                        size_factors, solve_fem2d)
from tactcad.mechanics.fem.fields import peak_notch_stress
from tactcad.mechanics.fem.fem_mesh import fem_region
from tactcad.mechanics.ladder import is_meshed, meshed_models, models
from tactcad.mechanics.element_strength import (KT_FIT_GEOMETRIES,
                                        STRESS_WEB_DIVISIONS_2D, STRESS_WEB_DIVISIONS_3D,
                                        ElementStress, ReferenceLoad, StrengthRecord,
                                        closed_form_stress, nominal_stress_per_newton,
                                        peak_stress_sequence)
from tactcad.mechanics.element_strength import plan_strength as _plan_strength
from tactcad.store import kept_result


def fem_peak_stress(g: ElementGeometry, material: Material, model: str = "fem2d", *,
                    web_divisions: float | None = None, levels: int = 3) -> ElementStress:
    """Peak von Mises stress at the hinge from the FEM field, Richardson-
    extrapolated over ``levels`` meshes (sizes sqrt(2)^k times the finest).

    Args:
        g, material: element and material.
        model: "fem2d" (plane stress) or "fem3d".
        web_divisions: finest neck size = web / web_divisions (default
            :data:`STRESS_WEB_DIVISIONS_2D` / ``_3D``).
        levels: number of meshes (>= 3).

    Returns:
        :class:`ElementStress`: the extrapolated peak per N (the finest mesh's
        value when the sequence is not monotone), its Richardson error, K and where
        the peak is (its ``grid_strain_per_N``: :func:`~tactcad.mechanics.element_strength.at_the_grid`).

    Raises:
        ValueError: unknown model.
    """
    if not is_meshed(model):
        raise ValueError(f"model must be a FEM level ({', '.join(meshed_models())}), got {model!r}")
    installed = g
    # the hinge's peak on the element as cut: the gauge's glue line and carrier take a few
    # per cent of the moment (6 % at fem2d on the paper's 8 mm element), left as margin; the
    # singular corners at the carrier's ends slow the 3D peak's mesh convergence (178.6,
    # 180.8, 183.0 MPa/N over three meshes, a 35 % Richardson error, against the bare
    # element's 188.0, 194.1, 194.9)
    g = g.bare()
    if model == "fem2d":
        divisions = web_divisions or STRESS_WEB_DIVISIONS_2D
        sols, peaks = kept_result("fem2d peak stress",
                                  lambda: _fem2d_peaks(g, material, divisions, levels),
                                  g, material, divisions, levels)
    else:  # the bare element's mesh sequence (the stiffness level's, without the layer)
        sols, peaks = peak_stress_sequence(installed, material, model, web_divisions, levels)
    rich = richardson([p.per_newton_MPa_per_N for p in peaks], REFINEMENT_RATIO)
    fin = sols[-1]
    from tactcad.mechanics.ladder import estimate

    k = estimate(model, installed, material).stiffness_N_per_mm  # K in use, with the gauge
    return ElementStress(model, rich.extrapolated, rich.error_rel, k, peaks[-1].location_mm)


def _fem2d_peaks(g: ElementGeometry, material: Material, web_divisions: float, levels: int):
    """(solves without their fields, peak stresses) of the plane-stress mesh sequence of
    ``g`` (with its bonded gauge's layer where it carries one)."""
    from tactcad.mechanics.bonded_layer import layer_of

    region = fem_region(g)
    peaks, sols = [], []
    with single_threaded_blas():
        for s in size_factors(levels, REFINEMENT_RATIO):
            sol = solve_fem2d(g, material, size_factor=s, region=region, keep_field=True,
                              web_divisions=web_divisions, layer=layer_of(g))
            peaks.append(peak_notch_stress(sol.field, g))
            sols.append(replace(sol, field=None))  # frees the mesh and basis
    return tuple(sols), tuple(peaks)


def element_stress(g: ElementGeometry, material: Material, model: str = "closed-form"
                   ) -> ElementStress:
    """Peak stress per N, K and gauge strain of one geometry at ``model``.

    Raises:
        ValueError: unknown model.
    """
    if model not in models():
        raise ValueError(f"model must be one of {', '.join(models())}; got {model!r}")
    if is_meshed(model):
        return fem_peak_stress(g, material, model)
    return closed_form_stress(g, material, model)


def plan_strength(plan: Plan, model: str = "closed-form", progress=None,
                  reference_load: ReferenceLoad | None = None,
                  full_scale_force_N: float | None = None) -> list[StrengthRecord]:
    """:func:`tactcad.mechanics.element_strength.plan_strength` at any ladder level,
    the FEM ones (:func:`fem_peak_stress`) included, with the caller's
    ``reference_load`` (none by default), at the design's rated full-scale
    force: ``full_scale_force_N`` (N) when given, else
    :func:`tactcad.studies.verification.rated_full_scale_force`.

    Raises:
        ValueError: unknown model.
        DesignError: the material has no yield strength.
    """
    from tactcad.studies.verification import rated_full_scale_force

    force = rated_full_scale_force(plan) if full_scale_force_N is None else full_scale_force_N
    return _plan_strength(plan, force, model, progress, stress=element_stress,
                          reference_load=reference_load)



class KtFit(NamedTuple):
    """Least-squares fit of K_t = (1 + t/(2R))^p to FEM peaks.

    Attributes:
        exponent: p. t_over_R: shape (n,). kt_fem: FEM K_t (peak / nominal), shape (n,).
        residual_rel: fitted / FEM - 1, shape (n,).
    """

    exponent: float
    t_over_R: np.ndarray
    kt_fem: np.ndarray
    residual_rel: np.ndarray


def fit_kt_exponent(g0: ElementGeometry, material: Material,
                    geometries=KT_FIT_GEOMETRIES) -> KtFit:
    """Refit :data:`KT_EXPONENT` from converged plane-stress FEM peaks
    (:func:`fem_peak_stress`) at ``geometries`` ((t, R, a) in mm, the rest of
    ``g0``): p minimises sum (ln K_t,FEM - p ln(1 + t/2R))^2, i.e.
    p = sum(x y) / sum(x^2) with x = ln(1 + t/2R), y = ln K_t,FEM.
    About 3 s per geometry on two cores."""
    s, kt = [], []
    for t, R, a in geometries:
        g = replace(g0, web_thickness_mm=t, notch_radius_mm=R, arm_length_mm=a)
        peak = fem_peak_stress(g, material, "fem2d").stress_MPa_per_N
        s.append(t / R)
        kt.append(peak / float(nominal_stress_per_newton(t, a, g.sheet_thickness_mm)))
    s_arr, kt_arr = np.array(s), np.array(kt)
    x, y = np.log1p(s_arr / 2.0), np.log(kt_arr)
    p = float(x @ y / (x @ x))
    return KtFit(p, s_arr, kt_arr, (1.0 + s_arr / 2.0) ** p / kt_arr - 1.0)
