"""Every limit on an element's tip force, at one ladder level, with the one that binds.

For one element geometry (its peak hinge stress per N, grid strain per N
(what the gauge's grid reads, ``grid_strain_per_N``) and K at a ladder level, :class:`tactcad.mechanics.element_strength.ElementStress`):

* ``yield``: yield strength / (peak stress per N x safety factor);
* ``fatigue``: fatigue strength / peak stress per N (absent without one);
* ``gauge_fatigue``: the gauge's fatigue strain / grid strain per N;
* ``gauge_max``: the gauge's maximum strain / grid strain per N;
* ``travel``: K x the tip travel that closes the notch. Pressed on its
  contact face the arm turns about the web and its underside swings toward
  the base's front face across the notch, a gap 2R wide, at a depth
  d = arm height - t/2 below the web's mid-plane; the gap closes at a
  rotation 2R / d, i.e. a tip travel a 2R / d (small rotations).

Stress-based limits carry the stress's error estimate, strain- and
travel-based ones K's; below fem3d the stress is plane stress, so the
stress-based limits also carry the plane model's bound against 3D: a wide
web is near plane strain at mid-width, its von Mises stress lower by about
1 - nu^2, so the plane-stress force limit is low by up to nu^2 of the 3D one
(default design: fem3d's peak stress 9.8 % below the closed form's). The
gauge strain of the closed form and beam carries the fem3d-fitted plane-strain
factor (:mod:`tactcad.mechanics.gauge_strain`), so their strain-based limits
carry that fit's error instead; fem2d's strain is still plane stress (nu^2).
Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

from dataclasses import dataclass

from tactcad.design.array_plan import ElementGeometry, Plan
from tactcad.mechanics.gauge_strain import grid_strain_factor
from tactcad.mechanics.ladder import is_meshed
from tactcad.mechanics.element_strength import notch_fatigue_strength

#: Names of the limits, in the order they are listed.
LIMIT_NAMES = ("yield", "fatigue", "gauge_fatigue", "gauge_max", "travel")
LIMIT_WORDS = {"yield": "yield strength / safety factor",
               "fatigue": "material fatigue strength",
               "gauge_fatigue": "gauge fatigue strain",
               "gauge_max": "gauge maximum strain",
               "travel": "notch closing travel"}


@dataclass(frozen=True)
class ForceLimit:
    """One limit of one element.

    Attributes:
        limit: one of :data:`LIMIT_NAMES`. element: element number.
        part_name: distinct part. force_N: largest tip force it allows (N).
        error_estimate_rel: relative error of ``force_N``.
        detail: what it compares, in words with numbers.
    """

    limit: str
    element: int
    part_name: str
    force_N: float
    error_estimate_rel: float
    detail: str

    def as_json(self, binding: bool = False) -> dict:
        return {"limit": self.limit, "words": LIMIT_WORDS[self.limit], "element": self.element,
                "part": self.part_name, "force_N": self.force_N,
                "error_estimate_rel": self.error_estimate_rel, "detail": self.detail,
                "binding": binding}


def notch_closing_travel_mm(g: ElementGeometry) -> float:
    """Tip travel (mm) at which the notch gap (2R) closes: a 2R / (h - t/2)."""
    depth = g.arm_height_mm - g.web_thickness_mm / 2
    return g.arm_length_mm * 2 * g.notch_radius_mm / depth


def element_limits(number: int, g: ElementGeometry, plan: Plan, es, k_error_rel: float,
                   plane_error_rel: float = 0.0,
                   strain_model_error_rel: float | None = None) -> list[ForceLimit]:
    """Every :class:`ForceLimit` of one element from its per-newton response ``es``
    (:class:`tactcad.mechanics.element_strength.ElementStress`), K's error estimate and,
    for the levels whose stress is plane stress (closed form, beam, fem2d), the plane
    model's bound against 3D (nu^2), added to the stress-based limits' errors; the
    strain-based ones add ``strain_model_error_rel`` (the gauge strain's own model
    error; ``None``: the same plane bound)."""
    mat, st = plan.material, plan.strength
    s, eps, k = es.stress_MPa_per_N, es.read_strain_per_N(), es.stiffness_N_per_mm
    stress_err = es.stress_error_rel + plane_error_rel
    strain_err = k_error_rel + (plane_error_rel if strain_model_error_rel is None
                                else strain_model_error_rel)
    out = [ForceLimit("yield", number, g.part_name, mat.yield_strength_MPa / (s * st.safety_factor),
                      stress_err,
                      f"{mat.yield_strength_MPa:g} MPa / ({s:.4g} MPa/N x {st.safety_factor:g})")]
    notch = notch_fatigue_strength(mat)
    if notch is not None:
        out.append(ForceLimit("fatigue", number, g.part_name, notch.strength_MPa / s,
                              stress_err,
                              f"{notch.smooth_MPa:.4g} MPa x surface factor "
                              f"{notch.surface_factor:.2f} ({notch.surface}) / {s:.4g} MPa/N"))
    gauge = st.gauge
    out.append(ForceLimit("gauge_fatigue", number, g.part_name, gauge.fatigue_strain / eps,
                          strain_err, f"{1e6 * gauge.fatigue_strain:.0f} microstrain "
                          f"({gauge.name}) / {1e6 * eps:.4g} microstrain/N"))
    out.append(ForceLimit("gauge_max", number, g.part_name, gauge.max_strain / eps, strain_err,
                          f"{1e6 * gauge.max_strain:.0f} microstrain / {1e6 * eps:.4g} "
                          "microstrain/N"))
    travel = notch_closing_travel_mm(g)
    out.append(ForceLimit("travel", number, g.part_name, k * travel, k_error_rel,
                          f"K {k:.4g} N/mm x {1e3 * travel:.0f} um notch closing travel"))
    return out


def limit_k_error(model: str, g: ElementGeometry, material, made=None) -> float:
    """The K error estimate (relative) every strain- and travel-based force limit of ``g``
    at ``model`` carries: the level's own K error (its stiffness estimate's
    ``error_estimate_rel``). The one figure ``verify``'s ``full_scale_force_N`` row and
    ``strength``'s ``element_force_limit_error_rel`` judge the rated full-scale force by
    (a stress-based limit carries the stress's own error instead).

    Args:
        model: a ladder level. g: the element (mm). material: its material (MPa).
        made: the level's estimate of ``g`` already made (None: made here; a FEM level's
            is kept in the result store).

    Returns:
        The relative error (>= 0).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    from tactcad.mechanics.ladder import estimate

    return (made if made is not None else estimate(model, g, material)).error_estimate_rel


def plan_limits(plan: Plan, model: str = "closed-form", stresses=None, k_errors=None,
                grid_level: str | None = None) -> list[ForceLimit]:
    """Every limit of every element of ``plan`` at ``model`` (distinct geometries once).

    Args:
        stresses, k_errors: per part name, :class:`ElementStress` and K's
            error estimate already computed (else computed here: the stresses at the
            closed form and beam only, the FEM levels' come from
            :mod:`tactcad.studies.strength_studies`; K's error by :func:`limit_k_error`
            at every level).
        grid_level: the level the grid strain is read at (:func:`~tactcad.mechanics.
            element_strength.at_the_grid`); None: each stress's own. A verification level
            whose limits no open requirement reads passes "closed-form"
            (:attr:`tactcad.studies.verification.Figures.grids_from`).

    Raises:
        DesignError: the material has no yield strength.
        ValueError: an FEM model without its ``stresses``.
    """
    from tactcad.mechanics.element_strength import (at_the_grid, closed_form_stress,
                                                    require_yield)

    element_stress = closed_form_stress
    require_yield(plan.material)
    from tactcad.mechanics.fem.fem2d import plane_model_error

    from tactcad.mechanics.readout_chain import readout_chain

    chain = readout_chain(plan)
    stresses = dict(stresses or {})
    k_errors = dict(k_errors or {})
    out = []
    graded: dict[str, ElementGeometry] = {}  # part -> the geometry its grid strain is read on
    for slot in plan.slots:
        g = slot.geometry
        if g.part_name not in stresses:
            stresses[g.part_name] = element_stress(g, plan.material, model)
        # the gauge limits on the strain the grid reads (the read-out's), not the face's;
        # read once per part and geometry: at_the_grid sets the grid strain from g alone,
        # so reading it again on the same g gives the same stress
        if graded.get(g.part_name) != g:
            stresses[g.part_name] = at_the_grid(stresses[g.part_name], g, plan, grid_level)
            graded[g.part_name] = g
        if g.part_name not in k_errors:
            k_errors[g.part_name] = limit_k_error(model, g, plan.material)
        # the plane-strain bound of a plane-stress surface stress and strain
        # (a wide web at mid-width): nu^2 below fem3d
        bound = 0.0 if model == "fem3d" else plan.material.poisson_ratio ** 2
        # fem2d's K error already holds its plane model error for K: not for the strain
        k_err = k_errors[g.part_name] - (plane_model_error(g, plan.material)
                                         if model == "fem2d" else 0.0)
        # the closed form's and the beam's grid strain carry the fitted grid factor's error
        strain_err = None if is_meshed(model) else grid_strain_factor(
            g, plan.material, chain.grid_length_mm, chain.grid_width_mm).error_rel
        out.extend(element_limits(slot.number, g, plan, stresses[g.part_name],
                                  max(k_err, 0.0), bound, strain_err))
    return out


def closed_form_gauge_error_rel(g: ElementGeometry, material, chain) -> float:
    """The closed form's error on element ``g``'s gauge limits, as :func:`plan_limits` gives
    it at that level: K's error estimate plus the fitted grid-strain factor's (its fit
    residual, and outside its range the extrapolation's change), relative.

    Args:
        g: the element; material: its material; chain: the design's read-out chain
            (:func:`tactcad.mechanics.readout_chain.readout_chain`: the grid's size).
    """
    from tactcad.mechanics.closed_form import closed_form_error_estimate_rel

    # the closed-form level's own error estimate, without the face strain it also works out
    k_err = closed_form_error_estimate_rel(g, material)
    return max(k_err, 0.0) + grid_strain_factor(g, material, chain.grid_length_mm,
                                                chain.grid_width_mm).error_rel


#: The limits on the gauge's strain: their closed-form error is two-sided (a higher level
#: may read more strain), unlike the stress limits' plane-stress bound.
GAUGE_LIMITS = ("gauge_fatigue", "gauge_max")


def uncleared_gauge_limits(limits: list[ForceLimit], force_N: float) -> list[ForceLimit]:
    """The gauge limits among ``limits`` whose force does not clear ``force_N`` by their
    error estimate, ``F_limit < F (1 + e)``: a design held to them at this level may fail
    a higher one (fem3d reading more strain than the closed form's fit)."""
    return [lim for lim in limits if lim.limit in GAUGE_LIMITS
            and lim.force_N < force_N * (1.0 + lim.error_estimate_rel)]


def binding(limits: list[ForceLimit]) -> ForceLimit:
    """The limit allowing the smallest force (ties: the first listed)."""
    return min(limits, key=lambda lim: lim.force_N)


def per_kind_binding(limits: list[ForceLimit]) -> dict[str, ForceLimit]:
    """For each kind of limit, its binding element (the smallest force)."""
    out: dict[str, ForceLimit] = {}
    for lim in limits:
        if lim.limit not in out or lim.force_N < out[lim.limit].force_N:
            out[lim.limit] = lim
    return out


def full_scale_text(limits: list[ForceLimit]) -> str:
    """One line for notes and manifests: the largest full-scale force and the limit that binds."""
    b = binding(limits)
    return (f"full-scale force at most {b.force_N:.3g} N per element, bound by "
            f"{LIMIT_WORDS[b.limit]} (element {b.element})")
