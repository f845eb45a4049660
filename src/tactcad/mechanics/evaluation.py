"""The paper's array evaluation rig, simulated: the array pressed by dead weights into a sample.

Rig (paper, "Evaluation of rubber samples"): the array hangs on a vertical
linear axis whose moving part weighs 3.235 N; 100 g weights are added one at a
time; each element's deflection is divided by that of the stiffest element
(the reference, element 8 in the paper) to give R. The model:

* every element i is a spring K_i (N/mm) between the array body and its tip;
  all tips touch the sample (the element that did not work still presses it);
* the array body moves by Δ (mm); tip i indents the sample by w_i; element
  deflection e_i = Δ − w_i; tip force P_i = K_i e_i; the forces sum to the
  grasping force W;
* sample, ``coupling="none"``: independent springs, w_i = P_i/K_obj (paper
  eq. 1), which gives R_i = (K_r + K_obj)/(K_i + K_obj) (eq. 2) at every load;
* sample, ``"halfspace"`` or ``"layer"``: w = C P with C the compliance matrix
  of rigid flat punches at the tips' contact faces (:mod:`tactcad.mechanics.contact`),
  its modulus set so that one tip face of the design alone has stiffness K_obj
  (K_obj is what one tip reads; the paper measured it with a 2 x 3 mm indenter,
  its tips' own face).

Then P = (diag(1/K) + C)⁻¹ 1 Δ, linear in Δ, so R does not depend on the load
(what the paper's Fig. 6 shows within scatter).

Units: mm, N, N/mm; deflections reported in um.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from tactcad.mechanics.contact import ContactError, Punch, modulus_from_punch_stiffness
from tactcad.mechanics.contact import unit_punch_compliance as converged_unit_compliance

#: Weight of the moving axis with the array (N), the first grasping force.
DEAD_WEIGHT_N = 3.235
#: Standard gravity (m/s^2, CGPM 1901): a mass in kg times it is its weight in N.
STANDARD_GRAVITY = 9.80665
#: One added weight: 100 g under standard gravity (N).
STEP_WEIGHT_N = 0.1 * STANDARD_GRAVITY
#: Load steps reported by default: the dead weight and five added weights
#: (the paper speaks of six average values of R per graph).
DEFAULT_LOAD_STEPS = 6
#: Rubber is nearly incompressible; the paper gives no Poisson ratio.
DEFAULT_POISSON_RATIO = 0.5
COUPLINGS = ("none", "halfspace", "layer")


#: The element a tie for the stiffest goes to: the paper's reference element 8 (Table 2).
PREFERRED_REFERENCE = 8

@dataclass(frozen=True)
class ArrayElement:
    """One element of the array as the rig sees it.

    Attributes:
        number: paper element number.
        stiffness_N_per_mm: K (N/mm), > 0.
        punch: its contact face on the sample surface (mm).
    """

    number: int
    stiffness_N_per_mm: float
    punch: Punch


@dataclass(frozen=True)
class SampleSpec:
    """The sample model besides its stiffness K_obj.

    Attributes:
        coupling: ``none`` (eq. 1-2), ``halfspace`` or ``layer``.
        poisson_ratio: ν of the sample, 0 ... 0.5.
        thickness_mm: layer thickness (mm) for ``layer``; ignored otherwise.
    """

    coupling: str = "halfspace"
    poisson_ratio: float = DEFAULT_POISSON_RATIO
    thickness_mm: float | None = None

    def __post_init__(self):
        if self.coupling not in COUPLINGS:
            raise ContactError("coupling", self.coupling, " | ".join(COUPLINGS))
        if self.coupling == "layer" and self.thickness_mm is None:
            raise ContactError("thickness_mm", None, "> 0 mm for coupling 'layer'")

    @property
    def layer_thickness_mm(self) -> float | None:
        return self.thickness_mm if self.coupling == "layer" else None


def elements_from_plan(plan, stiffness_N_per_mm: dict[int, float]) -> tuple[ArrayElement, ...]:
    """Array elements at the plan's tip positions with the given stiffness per element number.

    The contact face lies in the world (x, z) plane, centred on
    ``slot.tip_centre_world_mm`` with ``slot.contact_face_world_mm`` (turned with the element).
    """
    out = []
    for slot in plan.slots:
        x, _, z = slot.tip_centre_world_mm
        w, d = slot.contact_face_world_mm
        out.append(ArrayElement(slot.number, float(stiffness_N_per_mm[slot.number]),
                                Punch(x, z, w, d)))
    return tuple(out)


def reference_element(elements, preferred: int = PREFERRED_REFERENCE) -> int:
    """The stiffest element, as in the paper; ties (within 1e-9) go to ``preferred``, else the lowest number."""
    k = np.array([e.stiffness_N_per_mm for e in elements])
    stiffest = [e.number for e in elements if e.stiffness_N_per_mm >= k.max() * (1 - 1e-9)]
    return preferred if preferred in stiffest else min(stiffest)


def load_steps_N(n_steps: int = DEFAULT_LOAD_STEPS) -> np.ndarray:
    """Grasping forces of the rig (N): 3.235 N, then one more 100 g weight per step, shape (n_steps,)."""
    if n_steps < 1:
        raise ContactError("load_steps", n_steps, ">= 1")
    return DEAD_WEIGHT_N + STEP_WEIGHT_N * np.arange(n_steps)


def _check_elements(elements) -> None:
    if not elements:
        raise ContactError("elements", 0, "at least one element")
    for e in elements:
        if not (np.isfinite(e.stiffness_N_per_mm) and e.stiffness_N_per_mm > 0):
            raise ContactError(f"K of element {e.number} (N/mm)", e.stiffness_N_per_mm, "> 0 N/mm")


def _check_k_obj(k_obj: float) -> None:
    if not (np.isfinite(k_obj) and k_obj > 0):
        raise ContactError("K_obj_N_per_mm", k_obj, "> 0 N/mm")


def indenter_face_mm(elements) -> tuple[float, float]:
    """The face K_obj is defined against: the design's own tip face (the first element's) (mm)."""
    p = elements[0].punch
    return (p.width_x_mm, p.depth_z_mm)


def sample_compliance(elements, k_obj: float, spec: SampleSpec,
                      unit_compliance: np.ndarray | None = None) -> np.ndarray:
    """Compliance matrix of the sample seen by the tips (mm/N), shape (m, m).

    ``none``: diag(1/K_obj). Coupled: the punch compliance matrix at modulus
    E = K_obj C_tip(E = 1) (one tip face alone, :func:`indenter_face_mm`), i.e. C = C(E = 1)/E. ``unit_compliance``
    (the E = 1 matrix) may be passed to avoid solving it again per sample.
    """
    _check_k_obj(k_obj)
    if spec.coupling == "none":
        return np.eye(len(elements)) / k_obj
    modulus = modulus_from_punch_stiffness(k_obj, *indenter_face_mm(elements), spec.poisson_ratio,
                                           spec.layer_thickness_mm)
    if unit_compliance is None:
        unit_compliance = unit_punch_compliance(elements, spec)
    return unit_compliance / modulus


def unit_punch_compliance(elements, spec: SampleSpec) -> np.ndarray:
    """Punch compliance matrix of the elements' faces on a sample with E = 1 MPa (mm/N),
    converged in the mesh (:func:`tactcad.mechanics.contact.unit_punch_compliance`)."""
    return converged_unit_compliance([e.punch for e in elements], spec.poisson_ratio,
                                     spec.layer_thickness_mm)


@dataclass(frozen=True, eq=False)
class RigResult:
    """The rig's readings for one sample.

    Attributes:
        elements: element numbers, shape (m,).
        stiffness_N_per_mm: K of each element, shape (m,).
        reference: element number of the reference.
        k_obj_N_per_mm: sample stiffness K_obj (N/mm).
        loads_N: grasping forces W, shape (s,).
        body_travel_mm: array body displacement Δ per load, shape (s,).
        deflection_mm: element deflections e, shape (s, m).
        tip_force_N: tip forces P, shape (s, m).
        ratio: R = e_i/e_ref, shape (s, m) (the reference column is 1).
        contact_lost: True where a tip force came out tensile (the model then
            does not hold: that tip would lift off), shape (m,).
    """

    elements: np.ndarray
    stiffness_N_per_mm: np.ndarray
    reference: int
    k_obj_N_per_mm: float
    loads_N: np.ndarray
    body_travel_mm: np.ndarray
    deflection_mm: np.ndarray
    tip_force_N: np.ndarray
    ratio: np.ndarray
    contact_lost: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))


def simulate_rig(elements, k_obj: float, spec: SampleSpec, loads_N=None, reference: int | None = None,
                 unit_compliance: np.ndarray | None = None,
                 references: Mapping[int, int] | None = None) -> RigResult:
    """Simulate the evaluation rig for one sample.

    Args:
        elements: sequence of :class:`ArrayElement` (all in contact).
        k_obj: sample stiffness K_obj, one tip face alone on it (N/mm), > 0.
        spec: :class:`SampleSpec` (coupling, ν, thickness).
        loads_N: grasping forces (N), default :func:`load_steps_N`.
        reference: element number of the reference; default :func:`reference_element`.
        unit_compliance: optional E = 1 punch compliance matrix (reuse across samples).
        references: element number -> the reference its R is read against (each
            row's own); None: every R against ``reference``.

    Returns:
        :class:`RigResult`.

    Raises:
        ContactError: a stiffness <= 0, unknown reference, bad sample spec.
    """
    _check_elements(elements)
    numbers = np.array([e.number for e in elements])
    k = np.array([e.stiffness_N_per_mm for e in elements])
    ref = reference_element(elements) if reference is None else reference
    if ref not in numbers:
        raise ContactError("reference", ref, f"one of {numbers.tolist()}")
    loads = load_steps_N() if loads_N is None else np.asarray(loads_N, float)
    if loads.ndim != 1 or not np.all(np.isfinite(loads)) or np.any(loads <= 0):
        raise ContactError("loads_N", loads.tolist(), "finite values > 0 N")
    compliance = sample_compliance(elements, k_obj, spec, unit_compliance)
    # Tip forces for a unit body travel: P = (diag(1/K) + C)^-1 1.
    per_travel = np.linalg.solve(np.diag(1.0 / k) + compliance, np.ones(len(k)))
    travel = loads / per_travel.sum()
    forces = np.outer(travel, per_travel)
    deflection = forces / k
    own = references or {}
    for r in set(own.values()) - set(numbers.tolist()):
        raise ContactError("references", r, f"one of {numbers.tolist()}")
    iref = [int(np.flatnonzero(numbers == own.get(int(n), ref))[0]) for n in numbers]
    ratio = deflection / deflection[:, iref]
    return RigResult(numbers, k, int(ref), float(k_obj), loads, travel, deflection, forces, ratio,
                     per_travel < 0)


# ---------------------------------------------------------------------------
# The whole experiment: every sample, every load step
# ---------------------------------------------------------------------------
def ladder_stiffness_by_element(plan, model: str = "closed-form") -> dict[int, float]:
    """Predicted K (N/mm) of every element of the plan at a ladder level (distinct profiles once)."""
    from tactcad.mechanics import ladder

    cache: dict[str, float] = {}
    out = {}
    for slot in plan.slots:
        key = slot.geometry.part_name
        if key not in cache:
            cache[key] = ladder.estimate(model, slot.geometry, plan.material).stiffness_N_per_mm
        out[slot.number] = cache[key]
    return out


def _rig_record(res: RigResult, spec: SampleSpec, face_mm: tuple[float, float]) -> dict:
    modulus = None
    if spec.coupling != "none":
        modulus = modulus_from_punch_stiffness(res.k_obj_N_per_mm, *face_mm,
                                               spec.poisson_ratio, spec.layer_thickness_mm)
    return {
        "K_obj_N_per_mm": res.k_obj_N_per_mm,
        "youngs_modulus_MPa": modulus,
        "loads_N": res.loads_N.tolist(),
        "body_travel_um": (1e3 * res.body_travel_mm).tolist(),
        "elements": [
            {"element": int(n), "K_m_over_K_obj": float(k / res.k_obj_N_per_mm),
             "R": res.ratio[:, i].tolist(), "deflection_um": (1e3 * res.deflection_mm[:, i]).tolist(),
             "tip_force_N": res.tip_force_N[:, i].tolist(), "contact_lost": bool(res.contact_lost[i])}
            for i, (n, k) in enumerate(zip(res.elements, res.stiffness_N_per_mm))],
    }


#: The evaluation report's renamed keys, old -> new: the old ones (the paper's figure
#: numbers) are written too, as duplicates, and listed in ``deprecated_keys``.
EVALUATION_RENAMED = {"fig6": "R_against_load", "fig7": "R_against_K_m_over_K_obj"}


def evaluation_report(plan, stiffness: dict[int, float], samples_N_per_mm, spec: SampleSpec,
                      n_steps: int = DEFAULT_LOAD_STEPS, fig6_sample: float = 3.85,
                      loads_N=None, references: Mapping[int, int] | None = None) -> dict:
    """The simulated evaluation experiment for a plan: R per element, sample and load step.

    Args:
        plan: design plan (tip positions and contact faces).
        stiffness: K per element number (N/mm), e.g. :func:`ladder_stiffness_by_element`.
        samples_N_per_mm: sample stiffnesses K_obj (N/mm), each > 0.
        spec: :class:`SampleSpec`.
        n_steps: load steps (3.235 N, then +100 g each).
        fig6_sample: the sample whose R against load is singled out as Fig. 6
            (the listed sample nearest to it; the paper shows 3.85 N/mm).
        loads_N: grasping forces (N) instead of the paper's steps (``n_steps`` ignored).
        references: element number -> its row's reference (each element's R and
            K_r/K_m against it); None: one reference for all
            (:func:`reference_element`), as the paper's rig.

    Returns:
        dict with the reference element, the elements' K and K_r/K_m, one
        record per sample (loads, body travel, and per element R, deflection,
        tip force per step), the ``R_against_load`` series (R of each element against
        the grasping force (N) on one sample; the paper's Fig. 6) and the
        ``R_against_K_m_over_K_obj`` series (R of each element against K_m/K_obj; the
        paper's Fig. 7), also under their deprecated names ``fig6`` and ``fig7``, listed
        in ``deprecated_keys``.

    Raises:
        ContactError: no sample, a stiffness <= 0, bad spec.
    """
    samples = [float(s) for s in samples_N_per_mm]
    if not samples:
        raise ContactError("samples", samples, "at least one K_obj > 0 N/mm")
    for s in samples:
        _check_k_obj(s)
    elements = elements_from_plan(plan, stiffness)
    _check_elements(elements)
    ref = reference_element(elements) if references is None else min(set(references.values()))
    own = dict(references or {e.number: ref for e in elements})
    k_ref = stiffness[ref]
    unit = None if spec.coupling == "none" else unit_punch_compliance(elements, spec)
    loads = load_steps_N(n_steps) if loads_N is None else np.asarray(loads_N, float)
    results = [simulate_rig(elements, s, spec, loads, ref, unit, references) for s in samples]
    records = [_rig_record(r, spec, indenter_face_mm(elements)) for r in results]
    fig6_index = int(np.argmin([abs(s - fig6_sample) for s in samples]))
    refs = set(own.values())
    measuring = [e for e in elements if e.number not in refs]
    k_own = {e.number: stiffness[own[e.number]] for e in elements}
    fig7 = [{"element": e.number, "label": f"element {e.number}, K_r/K_m = "
                                           f"{k_own[e.number] / e.stiffness_N_per_mm:.3g}",
             "K_r_over_K_m": k_own[e.number] / e.stiffness_N_per_mm,
             "K_m_over_K_obj": [e.stiffness_N_per_mm / s for s in samples],
             "R": [float(r.ratio[0, list(r.elements).index(e.number)]) for r in results]}
            for e in measuring]
    report = {
        "design": plan.name,
        "coupling": spec.coupling,
        "poisson_ratio": spec.poisson_ratio if spec.coupling != "none" else None,
        "thickness_mm": spec.layer_thickness_mm,
        "reference_element": ref,
        **({} if references is None else {"row_references": sorted(refs)}),
        "K_r_N_per_mm": k_ref,
        "elements": [{"element": e.number, "K_N_per_mm": e.stiffness_N_per_mm,
                      "K_r_over_K_m": k_own[e.number] / e.stiffness_N_per_mm,
                      **({} if references is None else {"reference_element": own[e.number]}),
                      "tip_x_mm": e.punch.x_mm, "tip_z_mm": e.punch.z_mm} for e in elements],
        "samples": records,
        "R_against_load": {"K_obj_N_per_mm": samples[fig6_index], "loads_N": loads.tolist(),
                           "R": {str(e["element"]): e["R"]
                                 for e in records[fig6_index]["elements"]
                                 if e["element"] not in refs}},
        "R_against_K_m_over_K_obj": fig7,
        # the paper's figure numbers, the keys' old names: duplicates, to go in a later release
        **{old: None for old in EVALUATION_RENAMED},
        "deprecated_keys": dict(EVALUATION_RENAMED),
    }
    for old, new in EVALUATION_RENAMED.items():
        report[old] = report[new]
    return report
