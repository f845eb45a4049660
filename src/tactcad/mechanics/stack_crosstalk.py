"""Crosstalk of the clamped array: a tip force on one element strains its neighbours' gauges.

Model (both levels). Each row's element bases and spacers, pressed together by
the preloaded bolts, form one stack: a beam along z between the two clamp
plates. The bolt preload is taken to keep every interface closed, so the
layers act bonded over the width the preload holds closed (``b``: the spacer's
contact length, at most the bolt spacing plus one pressure cone, VDI 2230
2015 section 5.1.2.2 with a 30 degree cone from the head's bearing diameter;
the bolts are not modelled otherwise). A tip force F on element j loads
the stack at the element's mid-plane z_j with F (bending about x) and with the
torque F d_j (twist about z, d_j: the tip's x distance from the bonded
section's centre). Each end of the stack rests on a clamp-plate leg: in its
own plane the plate is rigid (no end translation, no end twist); out of its
plane the leg turns about x against the plate's bridge, a thin strip twisted
between the leg and the fixed mounting hole (Saint-Venant torsion,
J = b t^3 (1/3 - 0.21 t/b (1 - t^4 / (12 b^4))), Roark's Formulas for Stress
and Strain, 7th ed., table 10.1 case 4): k_theta = G J / L. The rows
meet only through the mounting holes, taken as fixed, so rows do not couple
here.

Gauge strain. Element i's gauge is centred over its notch. Where the element
is bonded in the stack (x below the spacer's contact length x_c) its top face
reads the stack's bending strain through Poisson's ratio, eps_xx = -nu eps_zz,
eps_zz = -c M(z_i) / (E I) (c: half the section height). Beyond x_c the slice
is free and that strain dies out as a self-equilibrated end effect,
exp(-pi (x - x_c) / l) (Saint-Venant decay of a strip, Timoshenko and Goodier,
Theory of Elasticity, 3rd ed., section 24), with l the section height (the
slower, larger bound; the sheet thickness is the other bound, see the error
estimates); the grid reads the mean of that factor over its length (f_i).
The free arm carries no load from a neighbour (statics of an unloaded
cantilever). Twist gives shear, no eps_xx.
The diagonal adds each gauge's own grid strain
(:func:`tactcad.mechanics.readout_chain.grid_strain_per_N`).

Tip displacement. u_i = F_i / K_i (own stiffness, the stiffness ladder's
closed form) + w(z_i) + d_i phi(z_i): the stack's deflection and twist
carry element i's base as a rigid body.

Solution: the stack is a 1D finite-element beam (two-node elements, exact
for point loads at the nodes) with a node at every element's mid-plane and
every layer face; its stiffness (a few hundred unknowns at most, held dense) is
solved once for all n unit tip loads (``scipy.linalg.solve``, symmetric positive definite).

Levels, declared once in :data:`tactcad.mechanics.crosstalk_ladder.CROSSTALK_LEVELS`
(cheapest first) with the monolithic comb's (:mod:`tactcad.mechanics.comb_crosstalk`):

* ``stack-beam``: Euler-Bernoulli stack. Error estimate: as the stiffness
  ladder's, its distance to the next level up (``stack-timoshenko``, which
  adds the stack's shear) plus that level's own error estimate. The shear
  term alone changes almost nothing (about 4e-12: the stack's ends are held
  against translation, so it bends as a short pinned beam whose shear
  deflection does not reach the gauges' strain); the bonded width and decay
  length, which both levels share, decide the error.
* ``stack-timoshenko``: Timoshenko stack (shear factor 5/6, Timoshenko and
  Gere, Mechanics of Materials). Error estimate: the change of crosstalk_rel
  between the two bounds of the bonded width (pressure-cone width and the
  full spacer contact length) and between the two decay lengths (section height,
  sheet thickness), the model's least known inputs.

* ``stack-fem3d`` (:mod:`tactcad.mechanics.stack_fem3d`): the same bonded
  stack as a 3D solid (triquadratic hexahedra, two mesh levels). Error
  estimate: Richardson over the two meshes.

Units: mm, N, MPa, N/mm, s; strain dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from tactcad.design.array_plan import Plan
# the ladder, its refusals and the result every level gives (one registry for every
# construction's levels), here under their former names too
from tactcad.mechanics.crosstalk_ladder import (CROSSTALK_LADDER, CROSSTALK_LEVELS,  # noqa: F401
                                                CrosstalkInputError, CrosstalkLevel,
                                                CrosstalkResult, UnknownCrosstalkModelError,
                                                construction_levels, crosstalk_models,
                                                crosstalk_of, decoupling_matrix, default_level,
                                                plan_crosstalk, register_crosstalk_level,
                                                result_of, verify_level)

#: Shear correction factor of a rectangle (Timoshenko and Gere).
SHEAR_FACTOR = 5.0 / 6.0
#: Pressure-cone half-angle (VDI 2230-1:2015, 5.1.2.2: tan phi about 0.4 ... 0.6; 30 degrees).
CONE_HALF_ANGLE_DEG = 30.0
#: Sub-elements per layer of the 1D stack mesh (exact for nodal loads; 2 keeps mid-layer nodes).
SUBDIVISIONS = 2


# ---------------------------------------------------------------------------
# Inputs from the plan
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class StackInputs:
    """What the crosstalk models read from a plan (mm, MPa, N/mm, 1/N).

    Per element (plan order): ``numbers``, ``rows``, ``z_mm`` (mid-plane),
    ``lever_mm`` (tip's x distance from the bonded section's centre),
    ``stiffness_N_per_mm`` (own K), ``own_strain_per_N`` (own grid strain),
    ``grid_span_mm`` ((lo, hi) x of the grid, element frame).
    Stack: ``span_mm`` (z of the plates' inner faces), ``sheet_mm``,
    ``spacer_mm`` (layer thicknesses), ``contact_length_mm`` (spacer x length),
    ``height_mm`` (section height), ``bolt_spacing_mm``, ``cone_width_mm``
    (one bolt's pressure-cone diameter at the interface), element and spacer
    ``E``/``nu``, plate ``E``/``nu``, ``plate_thickness_mm``,
    ``bridge_height_mm``, ``bridge_length_mm`` (leg centre to mounting hole).
    """

    numbers: tuple[int, ...]
    rows: tuple[int, ...]
    z_mm: tuple[float, ...]
    lever_mm: tuple[float, ...]
    stiffness_N_per_mm: tuple[float, ...]
    own_strain_per_N: tuple[float, ...]
    grid_span_mm: tuple[tuple[float, float], ...]
    span_mm: tuple[float, float]
    sheet_mm: float
    spacer_mm: float
    contact_length_mm: float
    height_mm: float
    bolt_spacing_mm: float
    cone_width_mm: float
    element_E_MPa: float
    element_nu: float
    spacer_E_MPa: float
    spacer_nu: float
    plate_E_MPa: float
    plate_nu: float
    plate_thickness_mm: float
    bridge_height_mm: float
    bridge_length_mm: float
    bonded_width: str = "cone"  # "cone": min(contact, spacing + cone); "full": contact length
    decay_length: str = "height"  # Saint-Venant decay over the section "height" or the "sheet"

    @property
    def bonded_width_mm(self) -> float:
        """x width of the bonded stack section (mm)."""
        if self.bonded_width == "full":
            return self.contact_length_mm
        return min(self.contact_length_mm, self.bolt_spacing_mm + self.cone_width_mm)


def stack_inputs(plan: Plan, **changes) -> StackInputs:
    """The plan's stack, with ``changes`` (fields of :class:`StackInputs`, e.g.
    ``plate_thickness_mm=4.0``; ``spacer_grade="7075-T6"`` sets the spacer's E
    and nu from the material library).

    Raises:
        CrosstalkInputError: a change names no field, or its value is out of range.
        DesignError: an unknown spacer grade.
    """
    from tactcad.design.bom_section import clamp_grades
    from tactcad.mechanics.closed_form import estimate_closed_form
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain
    from tactcad.vocabulary.material_library import material_grade

    grades = clamp_grades(plan.raw)
    spacer_grade = material_grade(changes.pop("spacer_grade", grades["spacer"]),
                                  "spacer_grade")
    plate = material_grade(grades["clamp_plate"], "clamp.material")
    chain = readout_chain(plan)
    grid = chain.grid_length_mm
    t = plan.sheet_thickness_mm
    c = plan.clamp
    bolt_x = sorted(abs(x) for x, _ in plan.bolt_positions_xy_mm)
    centre_x = 0.5 * (bolt_x[0] + bolt_x[-1])  # |x| of the bolt pattern's centre
    numbers, rows, zs, levers, ks, own, fracs = [], [], [], [], [], [], []
    for s in plan.slots:
        g = s.geometry
        numbers.append(s.number)
        rows.append(s.row)
        zs.append(s.placement.apply(0.0, 0.0, t / 2)[2])
        tip_x = abs(s.placement.apply(g.tip_centre_x_mm, 0.0, 0.0)[0])
        levers.append(centre_x - tip_x)
        ks.append(estimate_closed_form(g, plan.material, element=s.number).stiffness_N_per_mm)
        own.append(grid_strain_per_N(g, plan.material, chain, "closed-form")["grid"])
        fracs.append((g.hinge_x_mm - grid / 2, g.hinge_x_mm + grid / 2))
    head = plan.bolt.head_diameter_mm
    spacing = plan.bolt_positions_xy_mm[1][0] - plan.bolt_positions_xy_mm[0][0]
    inputs = StackInputs(
        numbers=tuple(numbers), rows=tuple(rows), z_mm=tuple(zs), lever_mm=tuple(levers),
        stiffness_N_per_mm=tuple(ks), own_strain_per_N=tuple(own), grid_span_mm=tuple(fracs),
        span_mm=(plan.clamp_plate_z_mm[0] + c.thickness_mm, plan.clamp_plate_z_mm[1]),
        sheet_mm=t, spacer_mm=plan.spacer.thickness_mm, contact_length_mm=plan.spacer.length_mm,
        height_mm=min(plan.spacer.height_mm, min(s.geometry.base_height_mm for s in plan.slots)),
        bolt_spacing_mm=abs(spacing),
        cone_width_mm=head + 2 * math.tan(math.radians(CONE_HALF_ANGLE_DEG)) * (t + plan.spacer.thickness_mm) / 2,
        element_E_MPa=plan.material.youngs_modulus_MPa, element_nu=plan.material.poisson_ratio,
        spacer_E_MPa=spacer_grade.youngs_modulus_MPa, spacer_nu=spacer_grade.poisson_ratio,
        plate_E_MPa=plate.youngs_modulus_MPa, plate_nu=plate.poisson_ratio,
        plate_thickness_mm=c.thickness_mm, bridge_height_mm=c.bridge_height_mm,
        bridge_length_mm=abs(0.5 * (c.half_length_mm + c.window_half_width_mm)
                             - min(abs(h.x_mm) for h in c.holes)))
    return with_changes(inputs, **changes)


#: Ranges of the fields a sweep or a caller may change (mm, MPa).
CHANGE_RANGES = {"plate_thickness_mm": (0.5, 20.0), "bolt_spacing_mm": (0.5, 100.0),
                 "spacer_E_MPa": (1e2, 1e6), "bridge_height_mm": (0.5, 50.0)}


def with_changes(inputs: StackInputs, **changes) -> StackInputs:
    """``inputs`` with ``changes``, each checked against :data:`CHANGE_RANGES`.

    Raises:
        CrosstalkInputError: an unknown field or a value out of its range.
    """
    for key, value in changes.items():
        if key not in CHANGE_RANGES:
            raise CrosstalkInputError(key, value, "one of " + ", ".join(CHANGE_RANGES))
        lo, hi = CHANGE_RANGES[key]
        if not isinstance(value, (int, float)) or not math.isfinite(value) or not lo <= value <= hi:
            raise CrosstalkInputError(key, value, f"a number in [{lo:g}, {hi:g}]")
    return replace(inputs, **{k: float(v) for k, v in changes.items()})


# ---------------------------------------------------------------------------
# The stack as a 1D beam
# ---------------------------------------------------------------------------
def bridge_torsion_stiffness_Nmm(inputs: StackInputs) -> float:
    """Rotational stiffness of one plate leg about x: the bridge strip twisted
    over ``bridge_length_mm`` (N mm/rad; Roark table 10.1 case 4)."""
    b, t = max(inputs.bridge_height_mm, inputs.plate_thickness_mm), \
        min(inputs.bridge_height_mm, inputs.plate_thickness_mm)
    J = b * t ** 3 * (1 / 3 - 0.21 * t / b * (1 - t ** 4 / (12 * b ** 4)))
    G = inputs.plate_E_MPa / (2 * (1 + inputs.plate_nu))
    return G * J / inputs.bridge_length_mm


def grid_transfer(inputs: StackInputs, k: int) -> float:
    """Mean over element ``k``'s grid of the stack strain's share, 1 over the
    bonded contact (x <= x_c), exp(-pi (x - x_c) / l) beyond (dimensionless)."""
    lo, hi = inputs.grid_span_mm[k]
    xc = inputs.contact_length_mm
    ell = inputs.height_mm if inputs.decay_length == "height" else inputs.sheet_mm
    inside = max(0.0, min(hi, xc) - lo)
    a, b = max(lo, xc) - xc, max(hi, xc) - xc
    beyond = ell / math.pi * (math.exp(-math.pi * a / ell) - math.exp(-math.pi * b / ell))
    return (inside + beyond) / (hi - lo)


def _layers(inputs: StackInputs, row: int) -> list[tuple[float, float, bool]]:
    """(z0, z1, is_element) layers of one row's stack between the plates, mm."""
    z0, z1 = inputs.span_mm
    mids = sorted(z for z, r in zip(inputs.z_mm, inputs.rows) if r == row)
    half = inputs.sheet_mm / 2
    cuts = sorted({z0, z1, *[m - half for m in mids], *[m + half for m in mids]})
    cuts = [c for c in cuts if z0 - 1e-9 <= c <= z1 + 1e-9]
    return [(a, b, any(abs((a + b) / 2 - m) < half for m in mids)) for a, b in zip(cuts, cuts[1:])
            if b - a > 1e-9]


def _beam_element(EI: float, kGA: float | None, L: float) -> np.ndarray:
    """Two-node beam stiffness (w1, th1, w2, th2), exact for end loads;
    Timoshenko when ``kGA`` is given (Przemieniecki, Theory of Matrix Structural
    Analysis, 1968, ch. 5), Euler-Bernoulli otherwise."""
    phi = 0.0 if kGA is None else 12 * EI / (kGA * L * L)
    c = EI / (L ** 3 * (1 + phi))
    return c * np.array([[12, 6 * L, -12, 6 * L],
                         [6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L],
                         [-12, -6 * L, 12, -6 * L],
                         [6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L]])


@dataclass(frozen=True)
class RowSolution:
    """One row's stack under unit tip loads: per load j (columns) the
    deflection w (mm/N), twist phi (rad/N) and bending moment M (N mm/N) at
    each element's mid-plane (rows), plus the section's E I (N mm^2) there."""

    w: np.ndarray
    phi: np.ndarray
    moment: np.ndarray
    EI: np.ndarray


def solve_row(inputs: StackInputs, row: int, shear: bool) -> RowSolution:
    """The stack of ``row`` under a unit tip force on each of its elements:
    one factorisation of the bending and one of the twist system serve all loads."""
    idx = [k for k, r in enumerate(inputs.rows) if r == row]
    b, h = inputs.bonded_width_mm, inputs.height_mm
    A, I = b * h, b * h ** 3 / 12
    a, c = max(b, h), min(b, h)
    Jt = a * c ** 3 * (1 / 3 - 0.21 * c / a * (1 - c ** 4 / (12 * a ** 4)))
    nodes, props = [inputs.span_mm[0]], []
    for z0, z1, is_el in _layers(inputs, row):
        E, nu = ((inputs.element_E_MPa, inputs.element_nu) if is_el
                 else (inputs.spacer_E_MPa, inputs.spacer_nu))
        for k in range(1, SUBDIVISIONS + 1):
            nodes.append(z0 + (z1 - z0) * k / SUBDIVISIONS)
            props.append((E, E / (2 * (1 + nu))))
    z = np.array(nodes)
    n = len(z)
    Kb = np.zeros((2 * n, 2 * n))
    Kt = np.zeros((n, n))
    for e, (E, G) in enumerate(props):
        L = z[e + 1] - z[e]
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        Kb[np.ix_(dofs, dofs)] += _beam_element(E * I, SHEAR_FACTOR * G * A if shear else None, L)
        Kt[np.ix_([e, e + 1], [e, e + 1])] += G * Jt / L * np.array([[1, -1], [-1, 1]])
    k_theta = bridge_torsion_stiffness_Nmm(inputs)
    Kb[1, 1] += k_theta
    Kb[2 * n - 1, 2 * n - 1] += k_theta
    free_b = np.array([d for d in range(2 * n) if d not in (0, 2 * n - 2)])  # plates: w = 0
    free_t = np.arange(1, n - 1)  # plates: no twist
    at = [int(np.argmin(abs(z - inputs.z_mm[k]))) for k in idx]
    Fb = np.zeros((2 * n, len(idx)))
    Ft = np.zeros((n, len(idx)))
    for j, (node, k) in enumerate(zip(at, idx)):
        Fb[2 * node, j] = 1.0
        Ft[node, j] = inputs.lever_mm[k]
    import scipy.linalg  # here, not at the top: every command's start would pay its load

    Ub = np.zeros_like(Fb)
    Ub[free_b] = scipy.linalg.solve(Kb[np.ix_(free_b, free_b)], Fb[free_b], assume_a="pos")
    Ut = np.zeros_like(Ft)
    Ut[free_t] = scipy.linalg.solve(Kt[np.ix_(free_t, free_t)], Ft[free_t], assume_a="pos")
    # bending moment at each loaded node from the element to its right (or left at the end)
    moment = np.zeros((len(idx), len(idx)))
    EIs = np.zeros(len(idx))
    for i, node in enumerate(at):
        e = node if node < n - 1 else node - 1
        E, G = props[e]
        ke = _beam_element(E * I, SHEAR_FACTOR * G * A if shear else None, z[e + 1] - z[e])
        f = ke @ Ub[2 * e:2 * e + 4]
        moment[i] = -f[1] if e == node else f[3]
        EIs[i] = E * I
    return RowSolution(Ub[[2 * node for node in at]], Ut[at], moment, EIs)


# ---------------------------------------------------------------------------
# Result
# ---------------------------------------------------------------------------
BASIS = ("stack of element bases and spacers bonded by the bolt preload, a beam between the "
         "clamp plates (rigid in plane, out of plane on the bridge's torsion), the mounting "
         "holes fixed, rows uncoupled")


def matrices(inputs: StackInputs, shear: bool) -> tuple[np.ndarray, np.ndarray]:
    """(sensitivity S (1/N), tip compliance C (mm/N)), n x n in the plan's element order."""
    n = len(inputs.numbers)
    S = np.diag(np.array(inputs.own_strain_per_N, float))
    C = np.diag(1.0 / np.array(inputs.stiffness_N_per_mm, float))
    c = inputs.height_mm / 2
    for row in sorted(set(inputs.rows)):
        idx = [k for k, r in enumerate(inputs.rows) if r == row]
        sol = solve_row(inputs, row, shear)
        lev = np.array([inputs.lever_mm[k] for k in idx])
        nu = np.array([inputs.element_nu] * len(idx))
        frac = np.array([grid_transfer(inputs, k) for k in idx])
        # eps_zz at the top face from the stack's moment; the gauge reads -nu eps_zz over f_i
        eps_zz = -c * sol.moment / sol.EI[:, None]
        S[np.ix_(idx, idx)] += (-nu * frac)[:, None] * eps_zz
        C[np.ix_(idx, idx)] += sol.w + lev[:, None] * sol.phi
    assert S.shape == (n, n)
    return S, C


def _result(model: str, inputs: StackInputs, shear: bool, error: float, t0: float
            ) -> CrosstalkResult:
    S, C = matrices(inputs, shear)
    return result_of(model, inputs.numbers, S, C, error, t0, BASIS)


def _rel_change(a: float, b: float) -> float:
    return abs(a - b) / abs(a) if a else 0.0


def estimate_stack_beam(inputs: StackInputs) -> CrosstalkResult:
    """Euler-Bernoulli stack; error estimate: its distance to the next level up
    (the Timoshenko stack) plus that level's own error estimate."""
    t0 = time.perf_counter()
    rel_e = crosstalk_of(matrices(inputs, False)[0])[0]
    above = estimate_stack_timoshenko(inputs)
    return _result("stack-beam", inputs, False,
                   _rel_change(rel_e, above.crosstalk_rel) + above.error_estimate_rel, t0)


def estimate_stack_timoshenko(inputs: StackInputs) -> CrosstalkResult:
    """Timoshenko stack; error estimate: the spread over the bonded width's two bounds."""
    t0 = time.perf_counter()
    rels = [crosstalk_of(matrices(replace(inputs, bonded_width=w, decay_length=d), True)[0])[0]
            for w in ("cone", "full") for d in ("height", "sheet")]
    rel = crosstalk_of(matrices(inputs, True)[0])[0]
    return _result("stack-timoshenko", inputs, True,
                   max(_rel_change(rel, r) for r in rels), t0)


def estimate_crosstalk(inputs: StackInputs, model: str = "stack-beam") -> CrosstalkResult:
    """The crosstalk of ``inputs`` at level ``model``.

    A meshed level's result is kept in the result store and reused for the
    same stack (:meth:`~tactcad.mechanics.level_registry.LevelRegistry.run`).

    Raises:
        UnknownCrosstalkModelError: ``model`` is not a level of :data:`CROSSTALK_LEVELS`.
    """
    return CROSSTALK_LADDER.run(model, (inputs,), {}, label="stack")


#: The level the verification matrix, the export and the K_obj budget use for the stacked
#: array (both beam levels cost well under a second): the one its registration marks
#: (:func:`~tactcad.mechanics.crosstalk_ladder.verify_level`), ``stack-timoshenko``.
VERIFY_MODEL = verify_level("stacked")


def verify_model(plan: Plan) -> str | None:
    """The level of ``plan``'s ``max_crosstalk_rel`` record: its construction's
    :func:`~tactcad.mechanics.crosstalk_ladder.verify_level` (:data:`VERIFY_MODEL` for the
    stacked array, a comb's cheapest level; None: no level describes it)."""
    return verify_level(plan.construction)


def crosstalk_in_force(result: CrosstalkResult, full_scale_force_N: float,
                       force_resolution_N: Mapping[int, float]) -> dict:
    """The crosstalk in newtons against the force resolution: a neighbour loaded to
    the full-scale force reads on gauge i as the force |S_ij / S_ii| x F_fs, set
    against one force-resolution step of element i; the worst pair.

    Args:
        result: a level's crosstalk. full_scale_force_N: the rated full-scale force (N).
        force_resolution_N: per element number, its force resolution (N, 1 sigma;
            :func:`tactcad.mechanics.readout_chain.element_force_resolution_N`).

    Returns:
        ``gauge``, ``loaded_element``, ``force_per_N_of_neighbour_load`` (N/N),
        ``full_scale_force_N``, ``crosstalk_force_N`` (N, at the full-scale force),
        ``force_resolution_N`` (gauge's element, N) and ``force_resolution_steps``
        (crosstalk force / resolution: below 1, the crosstalk hides in the noise).
    """
    S = result.sensitivity
    ratio = np.abs(S) / np.abs(np.diag(S))[:, None]
    np.fill_diagonal(ratio, 0.0)
    step = np.array([force_resolution_N[e] for e in result.elements], float)
    steps = ratio * full_scale_force_N / step[:, None]
    i, j = np.unravel_index(int(np.argmax(steps)), steps.shape)
    return {"gauge": result.elements[i], "loaded_element": result.elements[j],
            "force_per_N_of_neighbour_load": float(ratio[i, j]),
            "full_scale_force_N": full_scale_force_N,
            "crosstalk_force_N": float(ratio[i, j] * full_scale_force_N),
            "force_resolution_N": float(step[i]),
            "force_resolution_steps": float(steps[i, j])}


def stated_max_crosstalk(plan: Plan) -> float | None:
    """``requirements.max_crosstalk_rel`` of the design, or None when not stated."""
    table = plan.raw.get("requirements") if isinstance(plan.raw, Mapping) else None
    value = table.get("max_crosstalk_rel") if isinstance(table, Mapping) else None
    return None if value is None else float(value)


def crosstalk_records(plan: Plan, full_scale_force_N: float | None = None,
                      force_resolution_N: Mapping[int, float] | None = None) -> list[dict]:
    """The verification matrix's ``max_crosstalk_rel`` record when the design
    states it (at :data:`VERIFY_MODEL` for the stacked array), else none; with the full-scale force and
    the elements' force resolution it also states the crosstalk in newtons
    (:func:`crosstalk_in_force`). A construction of another level than the stack's is
    verified at its cheapest (:func:`verify_model`)."""
    target = stated_max_crosstalk(plan)
    model = verify_model(plan) or VERIFY_MODEL  # no level: plan_crosstalk refuses it
    return [] if target is None else [crosstalk_record(plan, target, model,
                                                       full_scale_force_N, force_resolution_N)]


def crosstalk_record(plan: Plan, target_rel: float, model: str = VERIFY_MODEL,
                     full_scale_force_N: float | None = None,
                     force_resolution_N: Mapping[int, float] | None = None) -> dict:
    """``max_crosstalk_rel`` for the verification matrix: predicted crosstalk_rel
    against the target (margin target / predicted - 1; an upper bound); with
    ``full_scale_force_N`` and ``force_resolution_N`` (per element number, N) the
    record's ``in_force`` gives :func:`crosstalk_in_force`."""
    r = plan_crosstalk(plan, model)
    margin = target_rel / r.crosstalk_rel - 1.0 if r.crosstalk_rel > 0 else math.inf
    return {"requirement": "max_crosstalk_rel", "target": target_rel,
            "predicted": r.crosstalk_rel,
            "error_estimate_rel": r.error_estimate_rel,
            "margin_rel": margin if math.isfinite(margin) else None, "model": model,
            "pass": r.crosstalk_rel <= target_rel,
            "worst": {"gauge": r.worst[0], "loaded_element": r.worst[1]}, "basis": r.basis,
            **({} if full_scale_force_N is None or force_resolution_N is None else
               {"in_force": crosstalk_in_force(r, full_scale_force_N, force_resolution_N)})}
