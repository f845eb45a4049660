"""The tissue under the tips: rigid flat punches of the design's tip faces on one elastic sample.

Eq. 1-3 of the paper treat the object under each tip as its own spring K_obj.
Tips pressed into one sample interact through it: a force on one tip lowers
the surface under its neighbours. The model here:

* the sample is an elastic half-space, or a layer of stated thickness on a
  rigid base (:mod:`tactcad.mechanics.contact`: Love's (1929) rectangle and
  Boussinesq's point load, K. L. Johnson, *Contact Mechanics*, 1985, sec. 3.2-3.3;
  Steinbrenner's layer), with Poisson ratio ν (default 0.5, soft tissue and
  rubber are nearly incompressible: an assumption the user can change);
* the tips are rigid flat punches of the design's own contact faces
  (``slot.geometry.contact_face_mm``, a face wide across the sheet) at the
  design's tip positions (pitch and row spacing), all pressing the sample
  (a grasp presses every tip);
* K_obj is what one tip alone reads: the single-punch stiffness of the
  design's tip face, so Young's modulus is E = K_obj C₁ with C₁ the
  single-punch compliance at E = 1, and the tips' compliance matrix is
  C = Ĉ / K_obj with Ĉ = C(E = 1) / C₁ (dimensionless, diagonal about 1).

With every tip on a spring K_i moved by one travel Δ, the tip forces are
P = (diag(1/K) + Ĉ/K_obj)⁻¹ 1 Δ and the element deflections e_i = P_i/K_i, so
a unit's coupled deflection ratio R = e_m / e_r does not depend on Δ. For two
tips alone it is eq. 2 with K_obj replaced by K_obj / (1 − κ), κ = Ĉ_mr/Ĉ_mm
the coupling coefficient: eq. 3 then reads K_obj / (1 − κ). The coupled
inversion (eq. 3 corrected) solves R_coupled(K_obj) = R by a bracketing root
find on ln K_obj (R_coupled falls monotonically with K_obj).

Limits: linear elastic, frictionless, small strain; no viscoelasticity nor
strain-stiffening (soft tissue has both: K_obj then depends on rate and depth).

Units: mm, N, MPa, N/mm; R and κ dimensionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from tactcad.mechanics.contact import (CONVERGED_KIND, CONVERGED_REL, ContactError, Punch, Sample,
                                       check_sample, converged_punches)
from tactcad.mechanics.lumped_model import deflection_ratio, object_stiffness
from tactcad.store import active_store, kept_per_process, kept_result

#: Soft tissue and rubber phantoms are nearly incompressible (an assumption the user can change).
TISSUE_POISSON_RATIO = 0.5
#: How far beyond the asked K_obj the coupled inversion searches for its root (factor either way).
INVERSION_BRACKET = 1e3
#: Relative tolerance of the coupled inversion's root (on ln K_obj): near the machine's, so
#: the root is set by the function, not by the path the root find took (a path that last
#: bits of the compliance change would otherwise move the answer by the tolerance).
INVERSION_RTOL = 4 * np.finfo(float).eps
#: Absolute tolerance of that root (on ln K_obj).
INVERSION_XTOL = 1e-14
#: Decimals the coupled inversion's residual bias is given to: a step above the root
#: tolerance, so the root find's and the solver's last bits (another numpy build) never
#: show; below it the residual is 0.
CORRECTED_DECIMALS = 9
#: Which tips press the sample: the whole array (a grasp) or the unit's two tips alone.
PRESSING = ("array", "unit")


@dataclass(frozen=True)
class Tissue:
    """The sample under the tips, besides its stiffness K_obj.

    Attributes:
        poisson_ratio: ν, 0 ... 0.5 (default 0.5: nearly incompressible tissue).
        thickness_mm: layer thickness on a rigid base (mm), or None for a half-space.
        convergence_rel: how closely the contact solver's successive mesh extrapolations
            must agree (:func:`~tactcad.mechanics.contact.converged_punches`; default 0.1 %).
        indenter_face_mm: (width across the sheet, depth along it) of the flat
            indenter K_obj is defined against (mm); None: the design's own tip face.

    Raises:
        ContactError: naming the field, value and allowed range.
    """

    poisson_ratio: float = TISSUE_POISSON_RATIO
    thickness_mm: float | None = None
    convergence_rel: float = CONVERGED_REL
    indenter_face_mm: tuple[float, float] | None = None

    def __post_init__(self):
        check_sample(Sample(1.0, self.poisson_ratio, self.thickness_mm))
        if not (np.isfinite(self.convergence_rel) and 1e-6 <= self.convergence_rel <= 0.1):
            raise ContactError("tissue.convergence_rel", self.convergence_rel, "1e-6 ... 0.1")

    def describe(self) -> str:
        """One line for an assumption: the sample model and ν."""
        body = ("an elastic half-space" if self.thickness_mm is None
                else f"an elastic layer {self.thickness_mm:g} mm thick on a rigid base")
        return (f"the tissue is {body} (ν = {self.poisson_ratio:g}), linear and frictionless, "
                "the tips rigid flat punches of the design's faces at its pitch and row spacing; "
                "K_obj is one tip's stiffness on it alone")


def tip_punches(plan) -> tuple[tuple[int, ...], tuple[Punch, ...]]:
    """Element numbers and their contact faces as punches on the sample plane (x, z) (mm).

    The face is centred on ``slot.tip_centre_world_mm``; its size is
    ``slot.contact_face_world_mm`` (the element's face turned with it: a quarter-turned
    element, a comb's rows, has its sheet along the sample's x and its tip's width along z).
    """
    numbers, punches = [], []
    for slot in plan.slots:
        x, _, z = slot.tip_centre_world_mm
        w, d = slot.contact_face_world_mm
        numbers.append(int(slot.number))
        punches.append(Punch(float(x), float(z), float(w), float(d)))
    return tuple(numbers), tuple(punches)


@dataclass(frozen=True, eq=False)
class CoupledSample:
    """The tips' normalised compliance on one sample: C = ``normalised`` / K_obj.

    Attributes:
        numbers: element numbers, shape (m,).
        normalised: Ĉ = C(E = 1) / C₁, shape (m, m) (dimensionless).
        tissue: the :class:`Tissue` it was built for.
        indenter_face_mm: the face K_obj is defined against (mm).
        error_rel: the contact solver's mesh error on Ĉ (the last change of its
            extrapolation, relative; :class:`~tactcad.mechanics.contact.ConvergedPunches`).
    """

    numbers: tuple[int, ...]
    normalised: np.ndarray
    tissue: Tissue
    indenter_face_mm: tuple[float, float]
    error_rel: float = 0.0

    def index(self, number: int) -> int:
        if number not in self.numbers:
            raise ContactError("element", number, f"one of {list(self.numbers)}")
        return self.numbers.index(number)

    def coupling(self, a: int, b: int) -> float:
        """κ_ab = C_ab / C_aa: the travel of tip a per travel of tip b's own load (dimensionless)."""
        i, j = self.index(a), self.index(b)
        return float(self.normalised[i, j] / self.normalised[i, i])


def coupled_sample_from_punches(numbers: Sequence[int], punches: Sequence[Punch],
                                tissue: Tissue = Tissue()) -> CoupledSample:
    """:class:`CoupledSample` of the given punches (see the module docstring).

    Raises:
        ContactError: bad punches or tissue; two faces overlap (the punch solution holds
            separate faces only), named by their elements.
    """
    _refuse_overlapping_faces(numbers, punches)
    face = indenter_face(tissue, punches)
    normalised, error = _normalised_compliance(tuple(punches), tissue, face)
    return CoupledSample(tuple(int(n) for n in numbers), normalised.copy(), tissue, face, error)


def _refuse_overlapping_faces(numbers: Sequence[int], punches: Sequence[Punch]) -> None:
    """Raise :class:`ContactError` naming the first two elements whose contact faces overlap
    on the sample plane by more than round-off (faces that only touch are allowed)."""
    for i, a in enumerate(punches):
        for j in range(i + 1, len(punches)):
            b = punches[j]
            gap_x = abs(a.x_mm - b.x_mm) - (a.width_x_mm + b.width_x_mm) / 2
            gap_z = abs(a.z_mm - b.z_mm) - (a.depth_z_mm + b.depth_z_mm) / 2
            if gap_x < -1e-9 and gap_z < -1e-9:
                raise ContactError(
                    "tip faces", f"elements {numbers[i]} and {numbers[j]}",
                    "contact faces apart on the sample (these overlap by "
                    f"{-gap_x:.4g} x {-gap_z:.4g} mm)")


def indenter_face(tissue: Tissue, punches: Sequence[Punch]) -> tuple[float, float]:
    """The face K_obj is defined against (mm): the tissue's stated indenter, else the first
    tip's own face."""
    face = tissue.indenter_face_mm or (punches[0].width_x_mm, punches[0].depth_z_mm)
    return float(face[0]), float(face[1])


@kept_per_process(maxsize=8)
def _face_alone(face: tuple[float, float], tissue: Tissue):
    """The converged solve of the indenter's face alone on the unit sample (E = 1) of
    ``tissue`` (:func:`~tactcad.mechanics.contact.converged_punches`): the C_1 every
    layout's compliance is normalised by, a function of the face (mm) and the tissue alone,
    so solved once per process where no result store keeps it (a design search's or an
    atlas's task judges many layouts against one face).

    Args:
        face: the indenter's face (width x depth, mm). tissue: the sample.

    Returns:
        The :class:`~tactcad.mechanics.contact.ConvergedPunches` (read, never changed).
    """
    unit = Sample(1.0, tissue.poisson_ratio, tissue.thickness_mm)
    return converged_punches([Punch(0.0, 0.0, face[0], face[1])], unit, tissue.convergence_rel)


@kept_per_process(maxsize=32)
def _normalised_compliance(punches: tuple[Punch, ...], tissue: Tissue,
                           face: tuple[float, float]) -> tuple[np.ndarray, float]:
    """(Ĉ of the punches, its mesh error), converged in the mesh
    (:func:`~tactcad.mechanics.contact.converged_punches`); cached: a design search asks
    the same tips again and again, and kept in the result store, so a design pasted from
    a refusal, and the verify and export after it, read its layouts' solves back."""
    unit = Sample(1.0, tissue.poisson_ratio, tissue.thickness_mm)

    def solved(tips: list[Punch]):
        return kept_result(CONVERGED_KIND,
                           lambda: converged_punches(tips, unit, tissue.convergence_rel),
                           tuple(tips), unit, tissue.convergence_rel)

    # the indenter's face alone: the same solve for every layout of one face and tissue
    alone = (solved([Punch(0.0, 0.0, face[0], face[1])]) if active_store() is not None
             else _face_alone(face, tissue))
    tips = solved(list(punches))
    c1 = float(alone.compliance_mm_per_N[0, 0])
    return tips.compliance_mm_per_N / c1, max(alone.error_rel, tips.error_rel)


def coupled_sample(plan, tissue: Tissue = Tissue()) -> CoupledSample:
    """:class:`CoupledSample` of a design's tips (:func:`tip_punches`)."""
    numbers, punches = tip_punches(plan)
    return coupled_sample_from_punches(numbers, punches, tissue)


@dataclass(frozen=True)
class CheckLevel:
    """The design's tips on the check model (:func:`check_level`).

    Attributes:
        sample: Ĉ extrapolated from cells h and h/2 (:class:`CoupledSample`).
        coarser: Ĉ extrapolated one step coarser, from cells 2h and h: a result's change
            between the two is its error estimate at this level.
        refinement: k, the cells being the default check's halved k times.
        finer_fits: whether the next refinement stays within the check's cell budget
            (:data:`tactcad.mechanics.contact_uniform.MAX_CHECK_CELLS`).
        cell_mm: h of the tips' mesh (mm).
    """

    sample: CoupledSample
    coarser: CoupledSample
    refinement: int
    finer_fits: bool
    cell_mm: float


def check_level(plan, tissue: Tissue = Tissue(), refinement: int = 0) -> CheckLevel | None:
    """The design's tips on the check model of another discretisation
    (:mod:`tactcad.mechanics.contact_uniform`: uniform cells, point-load quadrature,
    first-order extrapolation), normalised as :func:`coupled_sample`, with the cells of
    the default check halved ``refinement`` times; None for a layer (the check model is
    a half-space).

    Raises:
        ContactError: ``refinement`` < 0, or as :func:`tip_punches`.
    """
    from tactcad.mechanics.contact_uniform import (check_cell_mm, finer_check_cell_mm,
                                                   uniform_check)

    if not (isinstance(refinement, int) and refinement >= 0):
        raise ContactError("refinement", refinement, "an integer >= 0")
    if tissue.thickness_mm is not None:
        return None
    numbers, punches = tip_punches(plan)
    face = [Punch(0.0, 0.0, *indenter_face(tissue, punches))]
    scale = 0.5 ** refinement
    alone = uniform_check(face, check_cell_mm(face) * scale)
    h = check_cell_mm(punches) * scale
    tips = uniform_check(punches, h)
    ids = tuple(int(n) for n in numbers)

    def normalised(c_tips: np.ndarray, c_alone: np.ndarray, error: float) -> CoupledSample:
        return CoupledSample(ids, c_tips / c_alone[0, 0], tissue, (face[0].width_x_mm,
                                                                 face[0].depth_z_mm), error)

    error = max(alone.error_rel, tips.error_rel)
    return CheckLevel(normalised(tips.compliance_mm_per_N, alone.compliance_mm_per_N, error),
                      normalised(tips.coarser_mm_per_N, alone.coarser_mm_per_N, error),
                      refinement, finer_check_cell_mm(punches, h) is not None, h)


def check_level_sample(plan, tissue: Tissue = Tissue()) -> CoupledSample | None:
    """The design's tips on the default check level (:func:`check_level`'s ``sample``);
    None for a layer. Its ``error_rel`` is its own mesh error on Ĉ."""
    level = check_level(plan, tissue)
    return None if level is None else level.sample


def cross_level_bias(working: CoupledSample, check: CoupledSample,
                     stiffness: Mapping[int, float], unit: tuple[int, int], k_obj_values,
                     pressing: str = "array") -> np.ndarray:
    """K_obj the working model's coupled inversion reads from R made on the ``check``
    sample, over the true K_obj (N/mm), minus 1: the two levels' disagreement on one unit
    (NaN where the working model cannot read the check's R).

    Raises:
        ContactError: as :func:`coupled_ratio`.
    """
    ks = np.atleast_1d(np.asarray(k_obj_values, float))
    r = np.atleast_1d(coupled_ratio(check, stiffness, unit, ks, pressing))
    read = np.array([_inverted_or_nan(working, stiffness, unit, float(x), pressing) for x in r])
    return np.round(read / ks - 1.0, CORRECTED_DECIMALS) + 0.0  # no -0.0


def _pressing(sample: CoupledSample, unit: tuple[int, int], pressing: str) -> list[int]:
    if pressing not in PRESSING:
        raise ContactError("pressing", pressing, " | ".join(PRESSING))
    return list(range(len(sample.numbers))) if pressing == "array" else \
        [sample.index(unit[0]), sample.index(unit[1])]


def _stiffness_vector(sample: CoupledSample, stiffness: Mapping[int, float], rows: list[int]) -> np.ndarray:
    k = np.array([float(stiffness[sample.numbers[i]]) for i in rows])
    if not np.all(np.isfinite(k) & (k > 0)):
        raise ContactError("element stiffness (N/mm)", k.tolist(), "finite values > 0 N/mm")
    return k


def coupled_ratio(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
                  k_obj, pressing: str = "array") -> np.ndarray:
    """R = e_m / e_r of a unit on the coupled sample (eq. 2 corrected).

    Args:
        sample: :class:`CoupledSample`.
        stiffness: K per element number (N/mm), every pressing tip's.
        unit: (measuring element, reference element).
        k_obj: K_obj (N/mm), scalar or array, each > 0.
        pressing: ``array`` (every tip presses, as in a grasp) or ``unit`` (its two tips alone).

    Returns:
        R, the shape of ``k_obj`` (a float for a scalar).

    Raises:
        ContactError: K_obj <= 0, a stiffness <= 0, an unknown element.
    """
    kobj = np.asarray(k_obj, float)
    if not np.all(np.isfinite(kobj) & (kobj > 0)):
        raise ContactError("K_obj_N_per_mm", kobj.tolist(), "> 0 N/mm")
    if kobj.ndim == 0:
        return _unit_ratio_scalar(sample, stiffness, unit, pressing)(float(kobj))
    return _unit_ratio(sample, stiffness, unit, pressing)(kobj.reshape(-1)).reshape(kobj.shape)


def coupled_deflections(c_hat: np.ndarray, k: np.ndarray, k_obj: np.ndarray) -> np.ndarray:
    """Every pressing tip's deflection per unit travel, all tips on one sample, for a batch
    of element stiffnesses and K_obj: e = P / K with P = (diag(1/K) + Ĉ / K_obj)⁻¹ 1 (this
    module's model; one batched LAPACK solve).

    Args:
        c_hat: the tips' normalised compliance Ĉ (dimensionless), shape (m, m).
        k: each pressing element's K (N/mm), shape (n, m), every value > 0.
        k_obj: K_obj (N/mm), shape (n,), every value > 0.

    Returns:
        e, shape (n, m) (mm per mm of travel).

    Raises:
        numpy.linalg.LinAlgError: a singular system (not met with K, K_obj > 0 and a
            compliance matrix of a sample, which is positive definite).
    """
    a = c_hat[None, :, :] / k_obj[:, None, None]
    idx = np.arange(k.shape[1])
    a[:, idx, idx] += 1.0 / k
    force = np.linalg.solve(a, np.ones(k.shape + (1,)))[..., 0]
    return force / k


def _unit_ratio(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
                pressing: str) -> Callable[[np.ndarray], np.ndarray]:
    # R of one unit over an array of K_obj > 0, its inputs checked and gathered once (a
    # budget evaluates it over thousands of K_obj)
    k, c_hat, im, ir = _unit_system(sample, stiffness, unit, pressing)

    def ratio(k_obj: np.ndarray) -> np.ndarray:
        e = coupled_deflections(c_hat, np.broadcast_to(k, (k_obj.size, k.size)), k_obj)
        return e[:, im] / e[:, ir]

    return ratio


def _unit_ratio_scalar(sample: CoupledSample, stiffness: Mapping[int, float],
                       unit: tuple[int, int], pressing: str) -> Callable[[float], float]:
    # the same R at one K_obj at a time, for a root find (a plain solve: a third of the
    # batched one's cost on one system)
    k, c_hat, im, ir = _unit_system(sample, stiffness, unit, pressing)
    compliance, ones = np.diag(1.0 / k), np.ones(len(k))

    def ratio(k_obj: float) -> float:
        force = np.linalg.solve(compliance + c_hat / k_obj, ones)
        return float((force[im] / k[im]) / (force[ir] / k[ir]))

    return ratio


def _unit_system(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
                 pressing: str) -> tuple[np.ndarray, np.ndarray, int, int]:
    # the pressing tips' K (N/mm) and Ĉ, and the unit's two rows among them
    rows = _pressing(sample, unit, pressing)
    k = _stiffness_vector(sample, stiffness, rows)
    c_hat = sample.normalised[np.ix_(rows, rows)]
    return k, c_hat, rows.index(sample.index(unit[0])), rows.index(sample.index(unit[1]))


def _root_on_log_k(ratio: Callable[[float], float], r: float, bracket: tuple[float, float],
                   spanned: Callable[[float, float], str]) -> float:
    # the K_obj in ``bracket`` (N/mm) where ratio(K_obj) = r, by Brent's method on ln K_obj;
    # outside what the ratio spans over the bracket, the error names the span (``spanned``
    # words the model and the bracket)
    lo, hi = bracket

    def excess(log_k: float) -> float:
        return ratio(float(np.exp(log_k))) - r

    f_lo, f_hi = excess(np.log(lo)), excess(np.log(hi))
    if not (np.isfinite(r) and np.isfinite(f_lo) and np.isfinite(f_hi) and f_lo * f_hi <= 0):
        span = sorted((f_hi + r, f_lo + r))
        raise ContactError("R", r, f"{span[0]:.6g} ... {span[1]:.6g} ({spanned(lo, hi)})")
    from scipy.optimize import brentq  # here: scipy.optimize costs every command ~0.3 s to load

    return float(np.exp(brentq(excess, np.log(lo), np.log(hi), rtol=INVERSION_RTOL,
                               xtol=INVERSION_XTOL)))


def coupled_object_stiffness(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
                             r: float, pressing: str = "array",
                             bracket_N_per_mm: tuple[float, float] | None = None) -> float:
    """K_obj from a measured R with the coupling (eq. 3 corrected), by a root find on ln K_obj.

    Args:
        sample, stiffness, unit, pressing: as :func:`coupled_ratio`.
        r: the measured deflection ratio R.
        bracket_N_per_mm: (lo, hi) K_obj to search (N/mm); default K_m/1000 ... 1000 K_r.

    Returns:
        K_obj (N/mm).

    Raises:
        ContactError: R outside the range the coupled model spans over the bracket
            (named with that range).
    """
    return _root_on_log_k(_unit_ratio_scalar(sample, stiffness, unit, pressing), r,
                          _bracket(stiffness, unit, bracket_N_per_mm),
                          lambda lo, hi: f"the coupled R over K_obj {lo:.3g} ... {hi:.3g} N/mm")


def _bracket(stiffness: Mapping[int, float], unit: tuple[int, int],
             stated: tuple[float, float] | None) -> tuple[float, float]:
    # the K_obj an inversion searches (N/mm): as stated, else K_m/1000 ... 1000 K_r
    k_m, k_r = float(stiffness[unit[0]]), float(stiffness[unit[1]])
    return stated or (k_m / INVERSION_BRACKET, k_r * INVERSION_BRACKET)


def contact_forces(sample: CoupledSample, k: np.ndarray, heights_mm: np.ndarray, k_obj: float,
                   travel_mm: float) -> np.ndarray:
    """Each tip's force (N, in ``sample.numbers``' order) with the array body moved
    ``travel_mm`` towards the tissue and the tips standing ``heights_mm`` proud: a tip in
    contact satisfies P/K + (Ĉ P / K_obj) = travel + d; a tip clear of the tissue carries
    no force and stands above the surface its neighbours press down (a linear
    complementarity problem, solved by active set: the most negative force leaves, the
    deepest penetration joins, until neither remains).

    The one-change-at-a-time active set can cycle where a row of equal tips and a
    recessed one trade places (a comb of twelve tips, one 0.02 mm proud, one recessed);
    the problem is then solved as the bound-constrained least squares it is equivalent to
    (the system is symmetric positive definite: min 1/2 P^T A P - q^T P over P >= 0 is
    min ||L^T P - L^-1 q|| with A = L L^T; Lawson and Hanson's NNLS, which terminates),
    and its contact set solved as above.

    Raises:
        ContactError: no contact set satisfies the complementarity conditions to round-off
            (named with the travel).
    """
    n = len(k)
    system = np.diag(1.0 / k) + sample.normalised / k_obj
    load = travel_mm + heights_mm
    active = np.ones(n, bool)
    for _ in range(4 * n + 4):
        force = _forces_on(system, load, active)
        penetration = np.where(active, -np.inf,
                               travel_mm + heights_mm - sample.normalised @ force / k_obj)
        if force.min() < 0.0:
            active[int(np.argmin(force))] = False
        elif penetration.max() > 0.0:
            active[int(np.argmax(penetration))] = True
        else:
            return force
    return _settled_by_nnls(system, load, travel_mm)


def _forces_on(system: np.ndarray, load: np.ndarray, active: np.ndarray) -> np.ndarray:
    """Forces (N) with the ``active`` tips in contact (the others carry none)."""
    force = np.zeros(len(load))
    idx = np.flatnonzero(active)
    if idx.size:
        force[idx] = np.linalg.solve(system[np.ix_(idx, idx)], load[idx])
    return force


def _settled_by_nnls(system: np.ndarray, load: np.ndarray, travel_mm: float) -> np.ndarray:
    """:func:`contact_forces`' problem solved as non-negative least squares (scipy's NNLS),
    its contact set then solved exactly.

    Raises:
        ContactError: the result breaks a complementarity condition beyond round-off.
    """
    from scipy.linalg import cholesky, solve_triangular
    from scipy.optimize import nnls

    try:
        lower = cholesky(0.5 * (system + system.T), lower=True)
    except np.linalg.LinAlgError:  # not a compliance: no contact problem to solve
        raise ContactError("travel_mm", travel_mm, "a travel whose contact set settles (the "
                           "tips' compliance is not positive definite)") from None
    guess, _ = nnls(lower.T, solve_triangular(lower, load, lower=True))
    force = _forces_on(system, load, guess > 0.0)
    gap = system @ force - load  # >= 0 where clear, 0 in contact
    scale = float(np.max(np.abs(load))) or 1.0
    if force.min() < -1e-12 * max(float(force.max()), 1e-300) or gap.min() < -1e-9 * scale:
        raise ContactError("travel_mm", travel_mm, "a travel whose contact set settles")
    return np.maximum(force, 0.0)


def offset_ratio(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
                 k_obj: float, force_r_N: float, offsets_mm: Mapping[int, float]) -> float:
    """R = e_m / e_r of a unit on the coupled sample (every tip pressing) when tips stand
    proud of a common datum by ``offsets_mm``, pressed until the reference carries
    ``force_r_N``: P = (diag(1/K) + Ĉ/K_obj)⁻¹ (Δ 1 + d) while every tip touches, the
    travel Δ set by the reference's force. At a light load a recessed tip may stand clear
    of the tissue: it then carries nothing (:func:`contact_forces`), and R is 0 when it is
    the measuring tip. With no offsets it is :func:`coupled_ratio` at any force.

    Args:
        sample, stiffness: as :func:`coupled_ratio`.
        unit: (measuring element, reference element).
        k_obj: K_obj (N/mm), > 0.
        force_r_N: the reference element's force at the reading (N; K_r e_r), > 0.
        offsets_mm: element -> its tip's height (mm, + towards the tissue); missing: 0.

    Returns:
        R (dimensionless), >= 0.

    Raises:
        ContactError: K_obj or the force not > 0, an offset not finite.
    """
    if not (math.isfinite(k_obj) and k_obj > 0):
        raise ContactError("K_obj_N_per_mm", k_obj, "> 0 N/mm")
    if not (math.isfinite(force_r_N) and force_r_N > 0):
        raise ContactError("force_r_N", force_r_N, "> 0 N (the reference element's force)")
    numbers = sample.numbers
    k = np.array([float(stiffness[n]) for n in numbers])
    d = np.array([float(offsets_mm.get(n, 0.0)) for n in numbers])
    if not np.all(np.isfinite(d)):
        raise ContactError("tip offsets_mm", d.tolist(), "finite heights (mm)")
    i_m, i_r = numbers.index(unit[0]), numbers.index(unit[1])
    system = np.diag(1.0 / k) + sample.normalised / float(k_obj)
    per_travel, fixed = np.linalg.solve(system, np.ones(len(k))), np.linalg.solve(system, d)
    travel = (force_r_N - fixed[i_r]) / per_travel[i_r]
    force = travel * per_travel + fixed
    if force.min() < 0.0:  # a tip clear of the tissue: the travel that gives the reference F_r
        from scipy.optimize import brentq

        def excess(t: float) -> float:
            return contact_forces(sample, k, d, float(k_obj), t)[i_r] - force_r_N

        lo = -float(d.max())  # every tip at most touching the undisturbed surface: no force
        hi = max(travel, lo) + 1e-9
        while excess(hi) < 0.0:
            hi = lo + 2.0 * (hi - lo)
        force = contact_forces(sample, k, d, float(k_obj),
                               brentq(excess, lo, hi, xtol=1e-15, rtol=INVERSION_RTOL))
    e = force / k
    return float(e[i_m] / e[i_r])


def offset_object_stiffness(sample: CoupledSample, stiffness: Mapping[int, float],
                            unit: tuple[int, int], r: float, force_r_N: float,
                            offsets_mm: Mapping[int, float],
                            bracket_N_per_mm: tuple[float, float] | None = None) -> float:
    """K_obj from a measured R with the coupling and the tips' measured heights taken out
    (eq. 3 corrected for both): a root find on ln K_obj of :func:`offset_ratio` = R. The
    heights are those read on a rigid flat (:mod:`tactcad.in_use.tip_zeroing`); with every
    offset 0 this is :func:`coupled_object_stiffness`.

    Args:
        sample, stiffness, unit, force_r_N, offsets_mm: as :func:`offset_ratio`.
        r: the measured deflection ratio R.
        bracket_N_per_mm: (lo, hi) K_obj to search (N/mm); default K_m/1000 ... 1000 K_r.

    Returns:
        K_obj (N/mm).

    Raises:
        ContactError: R outside what the model spans over the bracket at this force and
            these heights (named with that range), or an input as :func:`offset_ratio`.
    """
    return _root_on_log_k(
        lambda k_obj: offset_ratio(sample, stiffness, unit, k_obj, force_r_N, offsets_mm), r,
        _bracket(stiffness, unit, bracket_N_per_mm),
        lambda lo, hi: f"R with the tips' heights at the reference's {force_r_N:.4g} N, "
                       f"K_obj {lo:.3g} ... {hi:.3g} N/mm")


@dataclass(frozen=True)
class UnitBias:
    """One unit's K_obj bias over a K_obj range.

    Attributes:
        unit: (measuring, reference) element numbers.
        coupling: κ between its two tips (dimensionless).
        k_obj_N_per_mm: the K_obj points (N/mm).
        ratio_eq2, ratio_coupled: R by eq. 2 and on the coupled sample.
        bias_eq3_rel: eq. 3's K_obj from the coupled R over the true K_obj, minus 1.
        bias_corrected_rel: the coupled inversion's, minus 1 (its round-off and root
            tolerance), to :data:`CORRECTED_DECIMALS` decimals.
    """

    unit: tuple[int, int]
    coupling: float
    k_obj_N_per_mm: tuple[float, ...]
    ratio_eq2: tuple[float, ...]
    ratio_coupled: tuple[float, ...]
    bias_eq3_rel: tuple[float, ...]
    bias_corrected_rel: tuple[float, ...]

    @property
    def worst_eq3_rel(self) -> float:
        """The largest |bias| of eq. 3 over the range, signed; inf where eq. 3 has no answer."""
        if not all(np.isfinite(self.bias_eq3_rel)):
            return float("inf")
        return max(self.bias_eq3_rel, key=abs)

    @property
    def worst_corrected_rel(self) -> float:
        """The largest |bias| of the coupled inversion, signed; inf where it has no answer."""
        if not all(np.isfinite(self.bias_corrected_rel)):
            return float("inf")
        return max(self.bias_corrected_rel, key=abs)

    def as_json(self) -> dict:
        """The unit as JSON: ``unit`` is (measuring, reference), as the coupling's solves take
        it; ``reference_element`` and ``measuring_element`` name each, and ``unit_label`` is
        the ``reference/measuring`` every other record prints (:func:`unit_label`)."""
        return {"unit": list(self.unit), "reference_element": self.unit[1],
                "measuring_element": self.unit[0], "unit_label": unit_label(self.unit),
                "coupling": self.coupling,
                "K_obj_N_per_mm": list(self.k_obj_N_per_mm), "R_eq2": list(self.ratio_eq2),
                "R_coupled": list(self.ratio_coupled),
                "bias_eq3_rel": [b if np.isfinite(b) else None for b in self.bias_eq3_rel],
                "bias_corrected_rel": [b if np.isfinite(b) else None
                                       for b in self.bias_corrected_rel],
                "worst_eq3_rel": self.worst_eq3_rel if np.isfinite(self.worst_eq3_rel) else None,
                "worst_corrected_rel": self.worst_corrected_rel
                if np.isfinite(self.worst_corrected_rel) else None}


def _inverted_or_nan(sample: CoupledSample, stiffness: Mapping[int, float],
                     unit: tuple[int, int], r: float, pressing: str) -> float:
    """The coupled inversion's K_obj of ``r`` (N/mm), NaN where the coupled R over the
    search bracket does not reach it (no answer: an unreadable K_obj)."""
    try:
        return coupled_object_stiffness(sample, stiffness, unit, r, pressing)
    except ContactError:
        return math.nan


def unit_bias(sample: CoupledSample, stiffness: Mapping[int, float], unit: tuple[int, int],
              k_obj_values, pressing: str = "array") -> UnitBias:
    """The K_obj bias eq. 3 makes on a coupled sample, and the coupled inversion's, for one unit.

    Raises:
        ContactError: as :func:`coupled_ratio`.
    """
    m, r = unit
    k_m, k_r = float(stiffness[m]), float(stiffness[r])
    ks = np.asarray(k_obj_values, float)
    r_c = np.atleast_1d(coupled_ratio(sample, stiffness, unit, ks, pressing))
    r_2 = np.array([deflection_ratio(k_m, k_r, float(k)) for k in ks])
    # eq. 3 has no answer where the coupled R leaves 1 < R < K_r/K_m: NaN, an unreadable K_obj
    eq3 = object_stiffness(r_c, np.full_like(r_c, k_m), np.full_like(r_c, k_r)).value
    corrected = np.array([_inverted_or_nan(sample, stiffness, unit, float(x), pressing)
                          for x in r_c])
    return UnitBias((int(m), int(r)), sample.coupling(m, r), tuple(map(float, ks)),
                    tuple(map(float, r_2)), tuple(map(float, r_c)),
                    tuple(map(float, eq3 / ks - 1)),
                    tuple(round(float(x), CORRECTED_DECIMALS) + 0.0  # no -0.0
                          if math.isfinite(x) else math.nan for x in corrected / ks - 1))


def unit_label(unit: Sequence[int]) -> str:
    """A (measuring, reference) unit as the house names a sensing unit everywhere a user
    reads one (grasp, budget, verify): ``"reference/measuring"``."""
    return f"{unit[1]}/{unit[0]}"


#: Digits a unit's |bias| is rounded to before the worst unit is chosen: mirrored units tie
#: to round-off, and a tie goes to the first unit in the array's order.
WORST_TIE_DIGITS = 9


def worst_unit(units: Sequence[Any], bias_of: Callable[[Any], float | None]) -> Any:
    """The unit whose K_obj bias is worst, the one rule ``design``'s and ``verify``'s reports
    name a unit by: one with no answer (``bias_of`` None, or not finite) first, else the
    largest |bias| rounded to :data:`WORST_TIE_DIGITS` digits; a tie goes to the first unit
    in ``units``' order (the array's).

    Args:
        units: the units' records, in the array's order. bias_of: a record's bias (relative,
            signed) or None.

    Returns:
        The worst record.

    Raises:
        ValueError: ``units`` is empty.
    """
    def rank(unit: Any) -> float:
        bias = bias_of(unit)
        return math.inf if bias is None or not math.isfinite(bias) else \
            round(abs(bias), WORST_TIE_DIGITS)

    return max(units, key=rank)  # max keeps the first of equal ranks


def design_units(plan, stiffness: Mapping[int, float]) -> list[tuple[int, int]]:
    """(measuring, reference) element numbers of the plan's sensing units: every element softer
    than its row's reference (:func:`tactcad.mechanics.readout_chain.row_units`)."""
    from tactcad.mechanics.readout_chain import row_units

    by_part = {s.geometry.part_name: float(stiffness[s.number]) for s in plan.slots}
    return [(int(m.number), int(r.number)) for r, m in row_units(plan, by_part)]


def apparent_kobj_factor(sample: CoupledSample, stiffness: Mapping[int, float],
                         units: Sequence[tuple[int, int]], k_obj_range: tuple[float, float],
                         pressing: str = "array") -> float:
    """The factor eq. 3 reads K_obj high by on the coupled sample, geometric mean over units and range ends.

    The K_obj a unit's elements see through eq. 2 is this factor times the
    true one (exactly 1/(1 − κ) for two tips alone); ``design`` centres its
    stiffnesses on the range so seen.
    """
    logs = []
    for unit in units:
        k_m, k_r = float(stiffness[unit[0]]), float(stiffness[unit[1]])
        for k in k_obj_range:
            r = float(coupled_ratio(sample, stiffness, unit, float(k), pressing))
            r = min(max(r, 1 + 1e-12), (k_r / k_m) * (1 - 1e-12))  # outside eq. 3's domain: its end
            logs.append(np.log(object_stiffness(r, k_m, k_r) / float(k)))
    return float(np.exp(np.mean(logs)))


#: The centring's fixed point stops when the factor moves less than this (relative).
CENTRING_TOL = 1e-3
#: At most this many rounds of the centring's fixed point.
CENTRING_ROUNDS = 8


def centred_seen_factor(plan, units: Sequence[tuple[int, int]], kr_over_km: float,
                        k_obj_range: tuple[float, float], tissue: Tissue = Tissue()) -> float:
    """The K_obj factor s at which elements K_m = s sqrt(K_lo K_hi / X), K_r = X K_m see the range
    centred through the coupling: s = :func:`apparent_kobj_factor` of those very stiffnesses
    (a fixed point; the tips' places and faces do not depend on the arms).

    Args:
        plan: a design (its tips' positions and faces; the arms are not used).
        units: (measuring, reference) element numbers.
        kr_over_km: X.
        k_obj_range: (K_lo, K_hi) (N/mm).
        tissue: the sample model.

    Returns:
        s (dimensionless).
    """
    sample = coupled_sample(plan, tissue)
    refs = {r for _, r in units}
    lo, hi = k_obj_range
    s = 1.0
    for _ in range(CENTRING_ROUNDS):
        k_m = s * float(np.sqrt(lo * hi / kr_over_km))
        stiffness = {n: (kr_over_km * k_m if n in refs else k_m) for n in sample.numbers}
        new = apparent_kobj_factor(sample, stiffness, units, k_obj_range)
        done = abs(new / s - 1.0) <= CENTRING_TOL
        s = new
        if done:
            break
    return s


def coupling_report(plan, stiffness: Mapping[int, float], units: Sequence[tuple[int, int]],
                    k_obj_values, tissue: Tissue = Tissue()) -> dict:
    """Per unit: κ, R by eq. 2 and coupled, eq. 3's K_obj bias and the coupled inversion's
    over ``k_obj_values`` (N/mm), with the tissue model stated.

    Raises:
        ContactError: as :func:`coupled_ratio`.
    """
    sample = coupled_sample(plan, tissue)
    return {"tissue": tissue.describe(), "poisson_ratio": tissue.poisson_ratio,
            "thickness_mm": tissue.thickness_mm,
            "units": [unit_bias(sample, stiffness, u, k_obj_values).as_json() for u in units]}
