"""The K_obj error budget of a design: what each source does to the K_obj a sensing unit reads.

A sensing unit is a row's reference element (K_r) and a softer element of the same row
(K_m) (:func:`tactcad.mechanics.readout_chain.row_units`). The unit is pressed into an
object of stiffness K_obj until the reference carries the stated force F_r; eq. 1 then
gives the element deflections

    e_r = F_r / K_r,   Δ = e_r (K_r + K_obj) / K_obj,   e_m = K_obj Δ / (K_obj + K_m),

and the reading is eq. 3 on the deflection ratio R = e_m / e_r (paper eq. 2):

    K_obj = (K_r − R K_m) / (R − 1).

Its derivatives (first order, GUM 5.1.2; :func:`eq3_partials`):

    ∂K_obj/∂R   = −(K_r − K_m) / (R − 1)²
    ∂K_obj/∂e_m = (∂K_obj/∂R) / e_r                 (R = e_m / e_r)
    ∂K_obj/∂e_r = −(∂K_obj/∂R) e_m / e_r²
    ∂K_obj/∂K_m = −R / (R − 1)
    ∂K_obj/∂K_r = 1 / (R − 1)

A grasp presses every tip into one sample, and a corrected sensor reads K_obj by the
coupled inversion (:mod:`tactcad.in_use.tissue_coupling`), not by eq. 3. So every source
that moves a reading or a spring is carried to K_obj on the coupled sample: the unit's
coupled R (every tip pressing) moves by what the source does to it, and ln K_obj by that
shift over the coupled slope ∂R/∂ln K_obj (:func:`coupled_slope`). A relative error
(de_m, de_r) of the two deflection readings moves R by R (de_m − de_r)
(:func:`reading_error_rel`): creep, noise and quantisation, the thermal zero, the gauge
model, K_v's calibration error and the crosstalk take this path; a K error moves the
coupled R of the true springs (:func:`stiffness_error_rel`). A common scale on both
deflections cancels in R and a common scale on every K moves K_obj by the same fraction
in both models. On the macro array the coupled slope is about half of eq. 3's, so eq. 3's
partials understated these terms there by as much as 36 %.

Sources (one function each, :data:`SOURCES`; each returns the relative K_obj error at
every K_obj of the grid, before and after the correction the lab applies):

(a) read-out noise and quantisation: each element's force resolution through the
    design's read-out chain (:func:`tactcad.mechanics.readout_chain.element_force_resolution_N`,
    1 sigma) as a deflection resolution dF / K over the element's deflection on the
    coupled sample; the two are independent (quadrature). It is
    :func:`tactcad.mechanics.resolution.noise_kobj_rel`, the function of ``readout``'s and
    ``verify``'s K_obj resolution, with the coupled R and slope in place of eq. 2's: the
    unit alone (that resolution, :func:`unit_alone_resolution_rel`, same force, noise and
    K_obj) differs from the term only by the tips' coupling, and each unit's record states
    both and their ratio. A unit reads no K_obj where that resolution exceeds the required
    ``kobj_resolution_rel`` (``verify``'s readable range judges so,
    :func:`tactcad.mechanics.resolution.reads_within`): there the term is unreadable (inf),
    never the small figure the coupling alone would leave a unit whose K_r / K_m is near 1.
(b) thermal zero: each element's apparent tip force per kelvin (TN-504 thermal output
    over the grid strain per newton, :func:`tactcad.mechanics.thermal_drift.thermal_report`;
    zero with a half-bridge dummy gauge) times the temperature step over the element's
    force on the coupled sample; both elements share the step (signed). It scales as 1 / F_r.
(c) thermal span: the gauge factor's coefficient scales both deflections alike (cancels
    in R); the modulus's coefficient (1/E) dE/dT scales K_m and K_r alike, and eq. 3 or
    the coupled inversion with the calibration's K then reads K_obj off by that fraction.
(d) manufacturing tolerance: each element's K change over its web ± web tolerance
    (the ladder's closed form); signs taken worst. Calibration measures each K (eq. 5),
    so it removes this fixed error entirely: what remains is the calibration's own
    uncertainty, source (h). After calibration (d) is 0.
(e) crosstalk (``crosstalk``, every construction's: a stacked array's clamped stack, a
    monolithic comb's row sheets and spine; it was keyed ``stack_crosstalk``, a key the
    record still writes beside it, deprecated: :data:`DEPRECATED_KEYS`): the neighbours' tip
    forces (every tip pressed by the same body travel Δ, eq. 1) times each gauge's crosstalk
    in newtons per newton of neighbour load (S_ij / S_ii of
    :func:`tactcad.mechanics.crosstalk_ladder.plan_crosstalk` at the construction's
    :func:`~tactcad.mechanics.crosstalk_ladder.verify_level`: ``stack-timoshenko`` for the
    stacked array, ``comb-beam`` for a monolithic comb), over each element's own force on
    the coupled sample; after the decoupling matrix what remains is its level's error
    estimate times that.
(f) tissue coupling: the array's tips pressed into one half-space sample couple through
    it (:mod:`tactcad.in_use.tissue_coupling`: rigid flat punches of the design's own tip
    faces, the sample's modulus set so that one tip face alone reads K_obj, nu 0.5);
    eq. 3 on the coupled R against the true K_obj. After the
    coupled inversion what remains is the coupled model's own error,
    :data:`COUPLING_MODEL_ERROR_REL` of the R shift it predicts plus its mesh error
    (``CoupledSample.error_rel``), through the coupled model's own slope ∂R/∂ln K_obj
    (about half eq. 3's on the macro array: eq. 3's slope understated it).
(i) tip coplanarity: the measuring tip recessed and the reference proud by the drawing's
    tip-height tolerance (``[tolerances] tip_height_mm``; a mismatch of twice it, either
    sign) on the coupled sample at the reference force, read by the coupled inversion.
    After every unit is zeroed on a rigid flat (each tip's height offset read as its
    deflection with every tip on one plane), the offset is known to the two elements'
    deflection resolutions (the read-out chain's force resolution / K) and the flat's
    flatness, in quadrature, which is what remains. With ``requirements.kobj_accuracy_rel`` stated,
    :func:`tip_height_tolerance_for_accuracy_mm` gives the tolerance the drawing must hold
    for the uncorrected term to fit in what the other terms leave, at each K_obj in the unit
    that reads it (the array's best, as the accuracy's verification reads it); the drawings
    print it where machining holds it, else name the zeroing
    (:mod:`tactcad.in_use.tip_height_drawing`).
(g) gauge model: each element's grid strain per newton at the budget's level against
    the next level that computes the strain anew (:func:`gauge_model_error_rel`); read
    with the predicted K_v it moves each deflection by that fraction. Calibration
    measures K_v (eq. 4), so after calibration it leaves the reading and stays only in
    the budget's own uncertainty (it scales (a) and (b)).
(h) calibration uncertainty: the standard errors of the fitted K and K_v (eq. 4-6,
    :func:`tactcad.mechanics.calibration.fit_calibration`) of each element, from a
    calibration file when given, else the expected standard errors of the static
    calibration ``calibrate`` drives (:func:`expected_calibration_stderr_rel` at its Z steps:
    the paper's for the paper's design, else six equal steps to each element's travel at the
    full-scale force; the force read by the design's calibration gauge, the project's rigs'
    force gauge where it has rigs (:func:`tactcad.studies.verification.calibration_gauge`,
    the one ``calibrate`` uses); the signal through the design's read-out chain), all
    independent. :func:`calibration_resolution_need` says how much of the term the force
    gauge's resolution makes and which resolution would bring it within its allowance.
(j) gauge creep: a bonded gauge's reading under a held load creeps by a fraction of the
    reading (glue line and carrier relaxing; :data:`GAUGE_CREEP_REL` over
    :data:`GAUGE_CREEP_MINUTES`, the figure beyond which a gauge maker calls an
    installation faulty), each element's independently (two installations), in
    quadrature; the same creep in both would cancel in R. Creep compensation (the end
    loops a gauge maker matches to the spring) brings it to :data:`COMPENSATED_CREEP_REL`,
    which remains.
(k) gauge hysteresis: a bonded gauge reads a force reached unloading differently from the
    same force reached loading (glue line and carrier again). ``readout.gauge_hysteresis_rel``
    states it from a load-unload cycle of the bonded element at its rated force (the largest
    unloading minus loading reading at one force over the reading at the rated force, OIML
    R 60's hysteresis error of a load cell); not stated, 0.1 % is assumed and its source says
    so (no gauge maker's figure for a bonded foil gauge was found). Each element's reading is
    off by that fraction of itself, the two independently (quadrature), as creep; nothing
    corrects it.

Totals: the RSS and the worst-case sum of the contributions after correction (as a
calibrated, corrected sensor reads), and of those before. The budget's own relative
uncertainty (:func:`budget_uncertainty_rel`) is the unit's largest gauge-model error
plus its largest K error estimate of the level.

Units: N, N/mm, mm, K; the contributions are relative (dimensionless).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable, Mapping, NamedTuple

import numpy as np

from tactcad.errors import DesignError
from tactcad.in_use.tip_zeroing import ZEROING_FLAT_FLATNESS_MM
from tactcad.mechanics.contact import ContactError

if TYPE_CHECKING:  # annotations only: the design model costs a second to import
    from tactcad.design.array_plan import Plan

#: Points of the log-spaced K_obj grid the budget is evaluated on (ends included).
BUDGET_POINTS = 7
#: Default temperature step between calibration (tare) and reading (K).
DEFAULT_DELTA_T_K = 5.0
#: Allowed temperature step (K) and reference force (N) of the options.
DELTA_T_RANGE_K = (0.0, 100.0)
#: Relative error of the coupled (punch) model that remains after the coupled inversion:
#: the bound its independent check holds it to (5 %; the scikit-fem block of
#: tests/in_use/test_tissue_coupling_fem.py measures -2.3 % at 4 mm and -1.6 % at 1.5 mm pitch).
COUPLING_MODEL_ERROR_REL = 0.05
#: Runs of the static calibration over its Z steps (as the paper's "Calibration" did).
CALIBRATION_REPEATS = 3


class Operating(NamedTuple):
    """One unit pressed into objects of stiffness ``k_obj`` until its reference carries
    ``force_r`` (eq. 1); arrays over the K_obj grid (N/mm, N, mm)."""

    k_m: float
    k_r: float
    k_obj: np.ndarray
    force_r: float
    e_m: np.ndarray
    e_r: np.ndarray
    travel: np.ndarray

    @property
    def ratio(self) -> np.ndarray:
        """R = e_m / e_r (eq. 2)."""
        return self.e_m / self.e_r

    @property
    def force_m(self) -> np.ndarray:
        return self.k_m * self.e_m


def operating_point(k_m: float, k_r: float, k_obj, force_r_N: float) -> Operating:
    """The deflections of a unit (K_m < K_r, N/mm) pressed until the reference carries
    ``force_r_N`` (N) into objects ``k_obj`` (N/mm, array): eq. 1.

    Raises:
        DesignError: K_r <= K_m, a stiffness or the force <= 0.
    """
    k_obj = np.atleast_1d(np.asarray(k_obj, float))
    if not (0 < k_m < k_r):
        raise DesignError("K_m, K_r", (k_m, k_r), "0 < K_m < K_r N/mm (a sensing unit)")
    if not force_r_N > 0 or np.any(k_obj <= 0):
        raise DesignError("force_N, K_obj", (force_r_N, k_obj.tolist()), "> 0 N and > 0 N/mm")
    e_r = np.full_like(k_obj, force_r_N / k_r)
    travel = e_r * (k_r + k_obj) / k_obj
    e_m = k_obj * travel / (k_obj + k_m)
    return Operating(float(k_m), float(k_r), k_obj, float(force_r_N), e_m, e_r, travel)


def eq3_partials(op: Operating) -> dict[str, np.ndarray]:
    """The derivatives of eq. 3 at the operating point (see the module docstring):
    ``dR`` (N/mm), ``de_m``, ``de_r`` (N/mm per mm), ``dK_m``, ``dK_r`` (dimensionless)."""
    R = op.ratio
    d_dr = -(op.k_r - op.k_m) / (R - 1.0) ** 2
    return {"dR": d_dr, "de_m": d_dr / op.e_r, "de_r": -d_dr * op.e_m / op.e_r ** 2,
            "dK_m": -R / (R - 1.0), "dK_r": 1.0 / (R - 1.0)}


def kobj_from_deflections(e_m, e_r, k_m: float, k_r: float):
    """Eq. 3 on R = e_m / e_r (N/mm), as the read-out forms it."""
    R = np.asarray(e_m, float) / np.asarray(e_r, float)
    return (k_r - R * k_m) / (R - 1.0)


# ---------------------------------------------------------------------------
# The design's context: per-design inputs computed once, on demand
# ---------------------------------------------------------------------------
@dataclass
class Context:
    """What every source reads: the plan, the level, K and its error per distinct part,
    the reference force (N), the temperature step (K), the calibration fits (element ->
    :class:`~tactcad.mechanics.calibration.Calibration`) and a cache of per-design inputs."""

    plan: Plan
    model: str
    k: Mapping[str, float]
    k_error: Mapping[str, float]
    force_N: float
    delta_T_K: float
    calibrations: Mapping[int, object] = field(default_factory=dict)
    #: the calibration rig (:class:`~tactcad.mechanics.calibration.CalibrationGauge`): its
    #: force gauge (``model``, ``range_N``, ``resolution_N`` (N), ``stiffness_N_per_mm``
    #: (N/mm)), where it comes from, and the force its Z steps load each element to
    force_gauge: Any = None
    cache: dict = field(default_factory=dict)
    #: the largest relative K_obj resolution of the unit alone that reads K_obj (the
    #: requirement's ``kobj_resolution_rel``); inf judges no unit unreadable
    readable_within_rel: float = math.inf

    def once(self, key: str, compute: Callable[[], object]):
        if key not in self.cache:
            self.cache[key] = compute()
        return self.cache[key]

    def k_of(self, number: int) -> float:
        return float(self.k[self.plan.element(number).geometry.part_name])


class Unit(NamedTuple):
    """A sensing unit: its row's reference and its measuring element (element numbers)."""

    reference: int
    measuring: int


class Contribution(NamedTuple):
    """One source's relative K_obj error over the grid, before and after correction."""

    before: np.ndarray
    after: np.ndarray


# ---------------------------------------------------------------------------
# The sources: (context, unit, operating point) -> Contribution
# ---------------------------------------------------------------------------
def readout_noise(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(a) :func:`coupled_readout_noise_rel`, unreadable (inf) where the unit alone does not
    read K_obj within ``ctx.readable_within_rel`` (:func:`unit_reads`)."""
    rel = np.where(unit_reads(ctx, unit, op), coupled_readout_noise_rel(ctx, unit, op), np.inf)
    return Contribution(rel, rel)


def coupled_readout_noise_rel(ctx: Context, unit: Unit, op: Operating) -> np.ndarray:
    """Each element's force resolution (1 sigma) through the read-out chain as a deflection
    resolution dF / K, independent, relative to its deflection on the coupled sample and
    read by the coupled inversion: :func:`tactcad.mechanics.resolution.noise_kobj_rel` with
    the coupled R and slope.

    Args:
        ctx, unit: the design's context and the sensing unit.
        op: its operating point (the K_obj grid, N/mm, and the reference force, N).

    Returns:
        sigma_K_obj / K_obj over the grid (inf where the coupled R does not move).
    """
    from tactcad.mechanics.resolution import noise_kobj_rel

    return noise_kobj_rel(_cached_coupled_ratio(ctx, unit, op.k_obj),
                          _cached_coupled_slope(ctx, unit, op.k_obj), op.e_r,
                          deflection_resolution_mm(ctx, unit.measuring),
                          deflection_resolution_mm(ctx, unit.reference))


def unit_alone_resolution_rel(ctx: Context, unit: Unit, op: Operating) -> np.ndarray:
    """The unit's own K_obj resolution (1 sigma) at each K_obj of ``op``: pressed alone until
    its reference carries ``op.force_r``, each element read to its force resolution through
    the read-out chain, eq. 1-3 (:func:`tactcad.mechanics.resolution.unit_resolution`, what
    ``readout`` and ``verify`` report, worst over their range).

    Args:
        ctx, unit: the design's context and the sensing unit.
        op: its operating point (the K_obj grid, N/mm, and the reference force, N).

    Returns:
        sigma_K_obj / K_obj over the grid.
    """
    from tactcad.mechanics.resolution import unit_resolution

    df = _force_resolutions(ctx)
    part = lambda n: ctx.plan.element(n).geometry.part_name  # noqa: E731
    return unit_resolution(op.k_m, op.k_r, op.k_obj, op.force_r, df[part(unit.measuring)]["dF"],
                           force_resolution_reference_N=df[part(unit.reference)]["dF"]
                           )["K_obj_resolution_rel"]


def unit_reads(ctx: Context, unit: Unit, op: Operating) -> np.ndarray:
    """Where the unit reads K_obj, or may within the level's error: its own resolution
    (:func:`unit_alone_resolution_rel`) within ``ctx.readable_within_rel``, as ``verify``'s
    readable range judges it (:func:`tactcad.mechanics.resolution.reads_within`), at its
    nominal K or at any K and grid strain its level's error allows
    (:func:`resolution_bounds_rel`). A unit that misses the required resolution only
    inside that error is not judged unreadable: whether it reads there is undecided
    (:func:`unit_reads_undecided`), and its terms are summed as read. The coupling moves R
    even between springs of one K; without K_r / K_m the unit has nothing of its own to
    read.

    Returns:
        A boolean array over the grid of ``op``.
    """
    from tactcad.mechanics.resolution import reads_within

    best, _ = resolution_bounds_rel(ctx, unit, op)
    return reads_within(best, ctx.readable_within_rel)


def unit_reads_undecided(ctx: Context, unit: Unit, op: Operating) -> np.ndarray:
    """Where the level cannot tell whether the unit reads K_obj: its own resolution within
    ``ctx.readable_within_rel`` at some K and grid strain inside the level's error and
    beyond it at others (:func:`resolution_bounds_rel`).

    Returns:
        A boolean array over the grid of ``op``.
    """
    from tactcad.mechanics.resolution import reads_within

    best, worst = resolution_bounds_rel(ctx, unit, op)
    return reads_within(best, ctx.readable_within_rel) & \
        ~reads_within(worst, ctx.readable_within_rel)


def resolution_bounds_rel(ctx: Context, unit: Unit, op: Operating
                          ) -> tuple[np.ndarray, np.ndarray]:
    """The least and the largest of the unit's own K_obj resolution
    (:func:`unit_alone_resolution_rel`) at each K_obj with each K moved by its level's error
    estimate (``ctx.k_error``, every sign combination) and each force resolution by its grid
    strain's error (a strain read e low leaves it 1 / (1 - e) coarser, e high 1 / (1 + e)
    finer), as verify's K_obj resolution record bounds its own
    (:func:`tactcad.studies.verification.worst_and_error`).

    Args:
        ctx, unit: the design's context and the sensing unit.
        op: its operating point (the K_obj grid, N/mm, and the reference force, N).

    Returns:
        (least, largest) relative resolution over the grid (the largest inf where a grid
        strain's error reaches 1).
    """
    from tactcad.mechanics.resolution import unit_resolution
    from tactcad.mechanics.readout_chain import grid_strain_error_rel

    nominal = unit_alone_resolution_rel(ctx, unit, op)
    if not math.isfinite(ctx.readable_within_rel):  # every unit reads: nothing to bound
        return nominal, nominal
    df = _force_resolutions(ctx)
    part = lambda n: ctx.plan.element(n).geometry.part_name  # noqa: E731
    r, m = part(unit.reference), part(unit.measuring)
    er, em = float(ctx.k_error.get(r, 0.0)), float(ctx.k_error.get(m, 0.0))
    moved = [nominal] + [
        unit_resolution(op.k_m * (1 + sm * em), op.k_r * (1 + sr * er), op.k_obj, op.force_r,
                        df[m]["dF"], force_resolution_reference_N=df[r]["dF"]
                        )["K_obj_resolution_rel"]
        for sr in (-1, 1) for sm in (-1, 1)]
    e = max(grid_strain_error_rel(df[p]["eps"]) for p in (r, m))
    moved = np.array(moved, float)
    low = np.min(moved, axis=0) / (1.0 + e)
    high = np.max(moved, axis=0) / (1.0 - e) if e < 1.0 else np.full(low.shape, np.inf)
    return low, high


def deflection_resolution_mm(ctx: Context, number: int) -> float:
    """Element ``number``'s deflection resolution (mm, 1 sigma): its force resolution through
    the read-out chain over its K."""
    df = _force_resolutions(ctx)
    return df[ctx.plan.element(number).geometry.part_name]["dF"] / ctx.k_of(number)


def _force_resolutions(ctx: Context) -> dict[str, dict]:
    # element_force_resolution_N of the design at the budget's level, once per context
    from tactcad.mechanics.readout_chain import element_force_resolution_N

    return ctx.once("readout", lambda: element_force_resolution_N(ctx.plan, ctx.model))


def _unit_thermal(ctx: Context, unit: Unit, op: Operating):
    """The thermal model's K_obj error of ``unit`` at ``op`` (one call per force and grid):
    :func:`tactcad.mechanics.thermal_drift.kobj_thermal_error`."""
    from tactcad.mechanics.thermal_drift import kobj_thermal_error

    key = f"thermal {op.force_r!r} {op.k_obj.tolist()!r}"
    errors = ctx.once(key, lambda: kobj_thermal_error(
        ctx.plan, None, op.force_r, ctx.delta_T_K, op.k_obj, ctx.model, dict(ctx.k)))
    for e in errors:
        if (e.element, e.reference_element) == (unit.measuring, unit.reference):
            return e
    raise DesignError("unit", f"{unit.reference}/{unit.measuring}",
                      "a measuring element with its row's stiffer reference")


def thermal_zero(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(b) The zero drift over the temperature step (thermal output, and two-wire leads
    when the design has them; none with a half-bridge dummy gauge): each element's
    apparent tip force per kelvin (:func:`tactcad.mechanics.thermal_drift.kobj_thermal_error`)
    times the step over its force on the coupled sample, read by the coupled inversion
    (signed, both elements share the step; scales as 1 / force)."""
    thermal = _unit_thermal(ctx, unit, op)
    e_m, e_r = coupled_deflections_mm(ctx, unit, op)
    rel = reading_error_rel(
        ctx, unit, op.k_obj,
        de_m=thermal.zero_force_m_N_per_K * ctx.delta_T_K / (op.k_m * e_m),
        de_r=thermal.zero_force_r_N_per_K * ctx.delta_T_K / (op.k_r * e_r))
    return Contribution(rel, rel)


def modulus_tc_per_K(plan: Plan) -> tuple[float, str]:
    """(1/E) dE/dT of the plan's elements (1/K) and its source, as the thermal model takes it
    (:func:`tactcad.mechanics.thermal_drift.thermal_setting`: ``[readout]``'s, else the
    library grade's, with its source; a grade no document was found for is marked
    unsourced).

    Raises:
        DesignError: the material names no grade and ``[readout]`` states no coefficient.
    """
    from tactcad.mechanics.thermal_drift import thermal_setting

    setting = thermal_setting(plan)
    return setting.modulus_tc_per_K, setting.sources["substrate_modulus_tc_per_K"]


def thermal_span(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(c) The springs' span drift over the temperature step: the modulus's coefficient and
    the thermal expansion change K_m and K_r alike, which R cannot see (the gauge factor's
    and the leads' span terms are common to both gauges and cancel in R); signed, the same at
    every K_obj: :func:`tactcad.mechanics.thermal_drift.kobj_thermal_error`. Every K scaled
    by s reads K_obj / s by eq. 3 and by the coupled inversion alike (the coupled R depends
    on K and K_obj only through their ratios), so the one figure serves both."""
    rel = np.broadcast_to(np.asarray(_unit_thermal(ctx, unit, op).span_rel, float),
                          op.k_obj.shape).copy()
    return Contribution(rel, rel)


def web_tolerance_k_rel(geometry, material) -> float:
    """Largest relative K change of one element over its web ± web tolerance (the
    ladder's closed form; a web that would vanish is skipped)."""
    return max(web_tolerance_k_change(geometry, material))


def web_tolerance_k_change(geometry, material) -> tuple[float, float]:
    """One element's relative K rise at its web + web tolerance and fall at its web - web
    tolerance (the ladder's corrected closed form, the figures ``verify``'s K band reads;
    dimensionless, each >= 0; a web that would vanish gives a fall of 0, not judged).

    Args:
        geometry: the element (mm). material: its material (MPa).

    Returns:
        (rise, fall), relative to the nominal web's K.
    """
    from tactcad.mechanics.ladder import estimate

    k0 = estimate("closed-form", geometry, material).stiffness_N_per_mm
    change = []
    for sign in (1, -1):
        t = geometry.web_thickness_mm + sign * geometry.web_tolerance_mm
        k = _tolerance_end_k(geometry, material, t) if t > 0 else k0
        change.append(abs(k / k0 - 1.0))
    return change[0], change[1]


def _tolerance_end_k(geometry, material, web_mm: float) -> float:
    """Closed-form K (N/mm) of ``geometry`` cut at ``web_mm`` (an end of its web tolerance).
    A correction range warning or a gauge-strain range warning it gives names that web
    (:func:`tolerance_end_words`): the element as drawn may sit inside a fitted range while
    its tolerance end lies past it."""
    import warnings

    from tactcad.mechanics.correction import CorrectionRangeWarning
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning
    from tactcad.mechanics.ladder import estimate

    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always", CorrectionRangeWarning)
        k = estimate("closed-form", replace(geometry, web_thickness_mm=web_mm),
                     material).stiffness_N_per_mm
    for w in said:
        if issubclass(w.category, CorrectionRangeWarning):
            # with its values and error: a run says it merged with the element as drawn's
            where = (f"web {web_mm:g} mm, drawn {geometry.web_thickness_mm:g} mm")
            warnings.warn(CorrectionRangeWarning(
                f"an element at the end of its web tolerance ({where}; the K band `verify` "
                f"reads): {w.message}", getattr(w.message, "error_rel", 0.0),
                getattr(w.message, "left", None), f"at a web tolerance's end, {where}"),
                stacklevel=2)
        elif issubclass(w.category, GaugeStrainRangeWarning):
            detail = getattr(w.message, "detail", "") or str(w.message)
            warnings.warn(GaugeStrainRangeWarning(
                f"gauge strain of {tolerance_end_words(geometry, web_mm)}: {detail}",
                getattr(w.message, "error_rel", 0.0), detail), stacklevel=2)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return k


def tolerance_end_words(geometry, web_mm: float) -> str:
    """Which element and which end of its web tolerance ``web_mm`` is, in words.

    Args:
        geometry: the element as drawn (mm). web_mm: the web at one end of its tolerance
            (mm).

    Returns:
        e.g. ``"element_a19p541mm at its web's lower tolerance limit, 0.085 mm (drawn
        0.105 +/-0.02 mm; the K band `verify` reads)"``.
    """
    end = "lower" if web_mm < geometry.web_thickness_mm else "upper"
    return (f"{geometry.part_name} at its web's {end} tolerance limit, {web_mm:g} mm (drawn "
            f"{geometry.web_thickness_mm:g} +/-{geometry.web_tolerance_mm:g} mm; the K band "
            f"`verify` reads)")


def manufacturing_tolerance(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(d) Both K off by their web tolerance's change, signs worst, read by the coupled
    inversion (:func:`stiffness_error_rel`); calibration measures each K, so none remains
    after it (its own error is (h))."""
    band = ctx.once("tolerance", lambda: {
        name: web_tolerance_k_rel(g, ctx.plan.material)
        for name, g in ctx.plan.distinct_elements.items()})
    part = lambda n: ctx.plan.element(n).geometry.part_name  # noqa: E731
    rel = (np.abs(stiffness_error_rel(ctx, unit, op.k_obj, dk_m=band[part(unit.measuring)]))
           + np.abs(stiffness_error_rel(ctx, unit, op.k_obj, dk_r=band[part(unit.reference)])))
    return Contribution(rel, np.zeros_like(rel))


class CrosstalkTerm(NamedTuple):
    """What the crosstalk term reads from the crosstalk ladder: the element numbers (matrix
    order), each gauge's force per newton on each other tip (N/N, zero diagonal), the
    level's error estimate (relative) and the level's name ("" where none describes the
    construction: the term is zero and not modelled)."""

    numbers: list
    per_newton: np.ndarray
    error_rel: float
    level: str


def _crosstalk(ctx: Context) -> CrosstalkTerm:
    from tactcad.mechanics.crosstalk_ladder import crosstalk_reason, plan_crosstalk, verify_level

    if crosstalk_reason(ctx.plan):  # no model of this construction's coupling: no term
        numbers = [s.number for s in ctx.plan.slots]
        return CrosstalkTerm(numbers, np.zeros((len(numbers), len(numbers))), 0.0, "")
    r = plan_crosstalk(ctx.plan, verify_level(ctx.plan.construction))
    per_newton = r.sensitivity / np.diag(r.sensitivity)[:, None]  # N on gauge i per N on tip j
    np.fill_diagonal(per_newton, 0.0)
    return CrosstalkTerm(list(r.elements), per_newton, r.error_estimate_rel, r.model)


def _crosstalk_reason(plan) -> str:
    """Why no crosstalk level describes ``plan``'s construction ("" where one does)."""
    from tactcad.mechanics.crosstalk_ladder import crosstalk_reason

    return crosstalk_reason(plan)


def crosstalk(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(e) The neighbours' tip forces (every tip pressed by the same travel Δ, eq. 1) times
    each gauge's crosstalk in N per N of neighbour load at the construction's crosstalk
    level (:class:`CrosstalkTerm`), a fraction of each element's own force, read by the
    coupled inversion; after the decoupling matrix, its level's error estimate of that, at
    most all of it (:func:`left_by_decoupling`)."""
    numbers, per_newton, error, _ = ctx.once("crosstalk", lambda: _crosstalk(ctx))
    k = np.array([ctx.k_of(n) for n in numbers])
    # tip forces of every element at each K_obj: K_j K_obj Δ / (K_j + K_obj), shape (n, grid)
    forces = k[:, None] * op.k_obj * op.travel / (k[:, None] + op.k_obj)
    seen = per_newton @ forces  # equivalent force each gauge reads from its neighbours (N)
    i_m, i_r = numbers.index(unit.measuring), numbers.index(unit.reference)
    e_m, e_r = coupled_deflections_mm(ctx, unit, op)
    rel = np.abs(reading_error_rel(ctx, unit, op.k_obj, de_m=seen[i_m] / (op.k_m * e_m),
                                   de_r=seen[i_r] / (op.k_r * e_r)))
    return Contribution(rel, rel * left_by_decoupling(error))


#: The crosstalk term's earlier name (:func:`crosstalk`), a stacked array's word for every
#: construction's term; deprecated, kept for callers of this module.
stack_crosstalk = crosstalk


def left_by_decoupling(error_rel: float) -> float:
    """The fraction of the crosstalk a decoupling matrix leaves: its model's error estimate,
    at most 1 (a matrix whose model may be off by more than the crosstalk itself is not worth
    applying: it is left out and the whole term remains, never more)."""
    return min(float(error_rel), 1.0)


def _coupled_ratios(ctx: Context, k_obj: np.ndarray) -> dict[int, np.ndarray]:
    """R of every measuring element against its row's reference at each K_obj, every tip of
    the array pressing one half-space sample through its own face
    (:func:`tactcad.in_use.tissue_coupling.coupled_ratio`)."""
    from tactcad.in_use.tissue_coupling import coupled_ratio, coupled_sample

    sample = ctx.once("tissue sample", lambda: coupled_sample(ctx.plan))
    stiffness = {s.number: ctx.k_of(s.number) for s in ctx.plan.slots}
    out = {}
    for s in ctx.plan.slots:
        ref = ctx.plan.reference_for(s).number
        if s.number != ref:
            out[s.number] = np.atleast_1d(coupled_ratio(sample, stiffness, (s.number, ref), k_obj))
    return out


def _tissue_sample(ctx: Context):
    from tactcad.in_use.tissue_coupling import coupled_sample

    return ctx.once("tissue sample", lambda: coupled_sample(ctx.plan))


def _stiffness_by_number(ctx: Context) -> dict[int, float]:
    return {s.number: ctx.k_of(s.number) for s in ctx.plan.slots}


#: Relative K_obj step of the coupled model's slope ∂R/∂ln K_obj (central difference).
SLOPE_STEP_REL = 1e-3


def coupled_slope(ctx: Context, unit: Unit, k_obj: np.ndarray) -> np.ndarray:
    """∂R/∂ln K_obj of ``unit`` on the coupled sample (every tip pressing), over
    ``k_obj`` (N/mm): what a shift of R moves the coupled inversion's K_obj by."""
    from tactcad.in_use.tissue_coupling import coupled_ratio

    sample, stiffness = _tissue_sample(ctx), _stiffness_by_number(ctx)
    pair = (unit.measuring, unit.reference)
    up = np.atleast_1d(coupled_ratio(sample, stiffness, pair, k_obj * (1 + SLOPE_STEP_REL)))
    down = np.atleast_1d(coupled_ratio(sample, stiffness, pair, k_obj * (1 - SLOPE_STEP_REL)))
    return (up - down) / (np.log1p(SLOPE_STEP_REL) - np.log1p(-SLOPE_STEP_REL))


def _cached_coupled_ratio(ctx: Context, unit: Unit, k_obj: np.ndarray) -> np.ndarray:
    """The unit's coupled R over ``k_obj`` (N/mm), every unit's computed once per grid."""
    ratios = ctx.once(f"coupled {k_obj.tolist()}", lambda: _coupled_ratios(ctx, k_obj))
    return ratios[unit.measuring]


def _cached_coupled_slope(ctx: Context, unit: Unit, k_obj: np.ndarray) -> np.ndarray:
    """:func:`coupled_slope` of the unit over ``k_obj`` (N/mm), computed once per grid."""
    key = f"coupled slope {unit.reference}/{unit.measuring} {k_obj.tolist()}"
    return ctx.once(key, lambda: coupled_slope(ctx, unit, k_obj))


def coupled_deflections_mm(ctx: Context, unit: Unit, op: Operating
                           ) -> tuple[np.ndarray, np.ndarray]:
    """The unit's deflections on the coupled sample (every tip pressing) with the reference
    carrying ``op.force_r``: e_r = F_r / K_r as in eq. 1, e_m = R_coupled e_r.

    Args:
        ctx, unit: the design's context and the sensing unit.
        op: its operating point (the K_obj grid, N/mm, and the reference force, N).

    Returns:
        (e_m over the grid, e_r over the grid), mm.
    """
    return _cached_coupled_ratio(ctx, unit, op.k_obj) * op.e_r, op.e_r


def _per_coupled_slope(ctx: Context, unit: Unit, k_obj: np.ndarray,
                       shift: np.ndarray) -> np.ndarray:
    # the K_obj error of an R shift through the coupled inversion; inf where the coupled R
    # does not move with K_obj (no reading)
    with np.errstate(all="ignore"):
        rel = shift / _cached_coupled_slope(ctx, unit, k_obj)
    return np.where(np.isfinite(rel), rel, np.inf)


def reading_error_rel(ctx: Context, unit: Unit, k_obj: np.ndarray, de_m=0.0,
                      de_r=0.0) -> np.ndarray:
    """The signed relative K_obj error when the measuring and reference deflection readings
    are off by the relative errors ``de_m``, ``de_r``, read by the coupled inversion.

    The coupled R moves by R (de_m − de_r), and ln K_obj by that shift over the coupled
    slope ∂R/∂ln K_obj (:func:`coupled_slope`): first order (GUM 5.1.2), as eq. 3's
    partials were.

    Args:
        ctx, unit: the design's context and the sensing unit.
        k_obj: K_obj (N/mm), the grid.
        de_m, de_r: relative errors of e_m and e_r (scalars or arrays over the grid).

    Returns:
        dK_obj / K_obj over the grid (signed; inf where the coupled R does not move).
    """
    shift = _cached_coupled_ratio(ctx, unit, k_obj) * (np.asarray(de_m, float)
                                                      - np.asarray(de_r, float))
    return _per_coupled_slope(ctx, unit, k_obj, shift)


def independent_reading_error_rel(ctx: Context, unit: Unit, k_obj: np.ndarray, de_m=0.0,
                                  de_r=0.0) -> np.ndarray:
    """σ_K_obj / K_obj of independent relative standard errors of the two deflection
    readings: :func:`reading_error_rel` of each, in quadrature (GUM 5.1.2).

    Args:
        ctx, unit: the design's context and the sensing unit.
        k_obj: K_obj (N/mm), the grid.
        de_m, de_r: relative standard errors of e_m and e_r (scalars or arrays over the grid).

    Returns:
        σ_K_obj / K_obj over the grid (inf where the coupled R does not move).
    """
    return np.hypot(reading_error_rel(ctx, unit, k_obj, de_m=de_m),
                    reading_error_rel(ctx, unit, k_obj, de_r=de_r))


def stiffness_error_rel(ctx: Context, unit: Unit, k_obj: np.ndarray, dk_m: float = 0.0,
                        dk_r: float = 0.0) -> np.ndarray:
    """The signed relative K_obj error when the unit's springs are stiffer than the K the
    reading takes by the fractions ``dk_m``, ``dk_r``: the coupled R of the true springs
    (every tip pressing) read by the coupled inversion with the taken K, first order
    (GUM 5.1.2; ∂R/∂ln K by a central difference).

    Args:
        ctx, unit: the design's context and the sensing unit.
        k_obj: K_obj (N/mm), the grid.
        dk_m, dk_r: relative K errors of the measuring and the reference element.

    Returns:
        dK_obj / K_obj over the grid (signed; inf where the coupled R does not move).
    """
    shift = (dk_m * _ratio_per_ln_k(ctx, unit, k_obj, unit.measuring)
             + dk_r * _ratio_per_ln_k(ctx, unit, k_obj, unit.reference))
    return _per_coupled_slope(ctx, unit, k_obj, shift)


def _ratio_per_ln_k(ctx: Context, unit: Unit, k_obj: np.ndarray, element: int) -> np.ndarray:
    # ∂R/∂ln K_element of the unit on the coupled sample (central difference), once per grid
    from tactcad.in_use.tissue_coupling import coupled_ratio

    def compute() -> np.ndarray:
        taken = _stiffness_by_number(ctx)
        pair = (unit.measuring, unit.reference)

        def ratio(scale: float) -> np.ndarray:
            moved = {**taken, element: taken[element] * scale}
            return np.atleast_1d(coupled_ratio(_tissue_sample(ctx), moved, pair, k_obj))

        h = SLOPE_STEP_REL
        return (ratio(1 + h) - ratio(1 - h)) / (np.log1p(h) - np.log1p(-h))

    return ctx.once(f"R per ln K {unit.reference}/{unit.measuring} {element} "
                    f"{k_obj.tolist()}", compute)


def tissue_coupling(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(f) Eq. 3 on the R of tips coupled through a half-space sample against the true
    K_obj (inf where the coupled R leaves eq. 3's domain: eq. 3 cannot read it); after the
    coupled inversion, the coupled model's error (:data:`COUPLING_MODEL_ERROR_REL` of the R
    shift plus the contact solver's mesh error) through the coupled slope
    (:func:`coupled_slope`)."""
    R = _cached_coupled_ratio(ctx, unit, op.k_obj)
    inside = (R > 1.0) & (R < op.k_r / op.k_m)
    with np.errstate(all="ignore"):
        read = np.where(inside, (op.k_r - R * op.k_m) / (R - 1.0), np.nan)
    before = np.where(inside, np.abs(read / op.k_obj - 1.0), np.inf)
    model_error = COUPLING_MODEL_ERROR_REL + _tissue_sample(ctx).error_rel
    with np.errstate(all="ignore"):
        after = np.abs(model_error * (R - op.ratio) / _cached_coupled_slope(ctx, unit, op.k_obj))
    return Contribution(before, np.where(np.isfinite(after), after, np.inf))


def _mismatch_rel(ctx: Context, unit: Unit, op: Operating, mismatch_mm: float) -> np.ndarray:
    """The coupled inversion's worst |K_obj error| (either sign) when the unit's two tips'
    heights differ by ``mismatch_mm`` (mm), over the grid; inf where it has no answer."""
    from tactcad.in_use.tissue_coupling import coupled_object_stiffness, offset_ratio

    sample, stiffness = _tissue_sample(ctx), _stiffness_by_number(ctx)
    out = np.zeros_like(op.k_obj)
    for i, k in enumerate(op.k_obj):
        for sign in (1.0, -1.0):
            half = sign * mismatch_mm / 2
            r = offset_ratio(sample, stiffness, (unit.measuring, unit.reference), float(k),
                             op.force_r, {unit.reference: half, unit.measuring: -half})
            try:
                read = coupled_object_stiffness(sample, stiffness,
                                                (unit.measuring, unit.reference), r)
                out[i] = max(out[i], abs(read / k - 1.0))
            except ContactError:
                out[i] = np.inf
    return out




def tip_mismatch_after_zeroing_mm(ctx: Context, unit: Unit) -> float:
    """The tip-height mismatch left after zeroing on a rigid flat (mm): each element's
    deflection resolution (the read-out chain's force resolution / K) and the flat's own
    flatness (:data:`ZEROING_FLAT_FLATNESS_MM`), in quadrature."""
    return math.hypot(deflection_resolution_mm(ctx, unit.measuring),
                      deflection_resolution_mm(ctx, unit.reference), ZEROING_FLAT_FLATNESS_MM)


def _others_after_sq(record: dict) -> np.ndarray:
    """The sum of squares, over the K_obj grid, of a unit record's terms after correction
    other than the tips' coplanarity (inf where one cannot be read)."""
    return np.sum([finite_or_inf(record["sources"][k]["after_rel"]) ** 2
                   for k in SOURCE_KEYS if k != "tip_coplanarity"], axis=0)


#: Relative tolerance of the tip-height tolerance the accuracy needs (its root find).
TOLERANCE_RTOL = 1e-3


def reading_unit_index(units: list[dict]) -> np.ndarray:
    """At each K_obj of the grid, the index (into ``units``) of the unit that reads it: the
    one with the smallest RSS after correction (an unreadable one, None, never is). The
    array's accuracy (:attr:`KobjBudget.array`) and the tip-height tolerance it leaves
    (:func:`tip_height_tolerance_for_accuracy_mm`) both read each K_obj so.

    Args:
        units: the budget's unit records (:func:`unit_budget`), at least one.

    Returns:
        An integer array over the K_obj grid.
    """
    return np.argmin(np.array([finite_or_inf(u["rss_rel"]) for u in units]), axis=0)


def _exact_tolerance(ctx: Context, pairs: list[Unit], units: list[dict], k_obj: np.ndarray,
                     accuracy_rel: float, linear_mm: float) -> float:
    """The tip-height tolerance (mm) at which the uncorrected coplanarity term, computed on
    the coupled model (not linearised), fills the room the other terms leave at each K_obj
    in the unit that reads it (:func:`reading_unit_index`): a root find from the linear
    estimate ``linear_mm`` (the term grows faster than linearly at the top of the K_obj
    range)."""
    from scipy.optimize import brentq

    reading = reading_unit_index(units)
    # each unit only over the K_obj it reads: a unit the array does not read there does not
    # bound the drawing
    held = [(u, operating_point(ctx.k_of(u.measuring), ctx.k_of(u.reference),
                                k_obj[reading == i], ctx.force_N),
             _others_after_sq(rec)[reading == i])
            for i, (u, rec) in enumerate(zip(pairs, units)) if np.any(reading == i)]

    def excess(tol_mm: float) -> float:
        return max(float(np.max(np.sqrt(_mismatch_rel(ctx, u, op, 2 * tol_mm) ** 2 + rest)))
                   for u, op, rest in held) / accuracy_rel - 1.0

    hi = linear_mm
    while excess(hi) < 0:
        hi *= 2
    lo = hi / 2
    while excess(lo) > 0 and lo > 1e-9:
        lo /= 2
    found = float(brentq(excess, lo, hi, rtol=TOLERANCE_RTOL)) if lo > 1e-9 else lo
    return float(f"{found:.3g}")  # a drawing's tolerance: three digits, never the last bits


def tip_height_tolerance_mm(plan: Plan) -> float:
    """The drawing's tip-height tolerance, +/- mm (``[tolerances] tip_height_mm``)."""
    from tactcad.design.tolerances import tolerances_of

    return tolerances_of(plan.raw).tip_height_mm


def tip_height_tolerance_for_accuracy_mm(units: list[dict], accuracy_rel: float,
                                         mismatch_after_mm: Mapping[tuple[int, int], float]
                                         ) -> float | None:
    """The largest tip-height tolerance (+/- mm) whose uncorrected coplanarity term (a
    mismatch of twice it) fits, at every K_obj in the unit that reads it (the array's best,
    :func:`reading_unit_index`, as the accuracy's verification reads it), within what the
    other terms after correction leave of ``accuracy_rel`` (in quadrature); the term is
    linear in a small mismatch, its slope read from the zeroed residual
    (``mismatch_after_mm``: (reference, measuring) -> mm). A unit the array does not read a
    K_obj with does not bound the tolerance there, so a looser accuracy never leaves a
    tighter one.

    Args:
        units: the budget's unit records (:func:`unit_budget`).
        accuracy_rel: ``requirements.kobj_accuracy_rel``.
        mismatch_after_mm: the zeroed residual mismatch of each unit (mm).

    Returns:
        The tolerance (+/- mm), or None where the other terms leave no room at some K_obj
        (the accuracy is then missed whatever the tips).
    """
    if not units:
        return None
    reading = reading_unit_index(units)
    allowed = math.inf
    for i, u in enumerate(units):
        read = reading == i
        if not np.any(read):
            continue
        own = finite_or_inf(u["sources"]["tip_coplanarity"]["after_rel"])[read]
        room_sq = accuracy_rel ** 2 - _others_after_sq(u)[read]
        if np.any(room_sq <= 0) or not np.all(np.isfinite(own)):
            return None
        residual = mismatch_after_mm[(u["reference_element"], u["measuring_element"])]
        slope = own / residual  # relative K_obj error per mm of mismatch
        with np.errstate(divide="ignore"):
            allowed = min(allowed, float(np.min(np.sqrt(room_sq) / slope)) / 2)
    return allowed if math.isfinite(allowed) else None


def tip_coplanarity(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(i) The tips' height mismatch: twice the drawing's tip-height tolerance before, the
    deflection resolution after zeroing on a rigid flat, each through the coupled model."""
    tol = tip_height_tolerance_mm(ctx.plan)
    before = _mismatch_rel(ctx, unit, op, 2 * tol) if tol > 0 else np.zeros_like(op.k_obj)
    after = _mismatch_rel(ctx, unit, op, tip_mismatch_after_zeroing_mm(ctx, unit))
    return Contribution(before, after)


def gauge_model_error_rel(plan: Plan, model: str) -> dict[str, float]:
    """Per distinct part: the estimated relative error of the grid strain per newton at
    ``model`` (:func:`tactcad.mechanics.readout_chain.grid_strain_per_N`'s ``error_rel``:
    the width correction's fit residual at the closed form and beam, the mesh's at fem3d)."""
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    chain = readout_chain(plan)
    return {name: float(grid_strain_per_N(g, plan.material, chain, model)["error_rel"])
            for name, g in plan.distinct_elements.items()}


def gauge_model(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(g) Each deflection read with the predicted K_v off by its gauge-model error, the two
    elements' errors taken independent (in quadrature: the width correction's residual
    differs from one web to the next, so it need not cancel in R), read by the coupled
    inversion; a calibration measures K_v, so none remains after it."""
    err = ctx.once("gauge", lambda: gauge_model_error_rel(ctx.plan, ctx.model))
    part = lambda n: ctx.plan.element(n).geometry.part_name  # noqa: E731
    rel = independent_reading_error_rel(ctx, unit, op.k_obj, de_m=err[part(unit.measuring)],
                                        de_r=err[part(unit.reference)])
    return Contribution(rel, np.zeros_like(rel))


def expected_calibration_stderr_rel(k_element: float, k_v_V_per_mm: float,
                                    signal_noise_V: float | None = None,
                                    k_sensor_N_per_mm: float | None = None, *,
                                    force_noise_N: float, steps_um) -> tuple[float, float]:
    """(σ_K / K, σ_K_v / |K_v|) a static calibration (eq. 4-6) leaves on one element.

    Ordinary least squares over the Z steps ``steps_um`` (the ones ``calibrate`` drives:
    :meth:`tactcad.mechanics.calibration.CalibrationGauge.steps_um`), :data:`CALIBRATION_REPEATS`
    runs, deflection Δ = z K_s / (K + K_s), the force read to
    ``force_noise_N`` (n, the force gauge's resolution) and the signal to ``signal_noise_V`` (1 sigma;
    default :data:`~tactcad.mechanics.calibration.DEFAULT_NOISE_SIGNAL_V`): σ_slope =
    σ_residual / sqrt(Σ (Δ − mean Δ)²). The deflection is formed as z − F/K_s from the
    read force, so the force's noise enters both axes: the force residual is
    n (1 + K/K_s) (:func:`tactcad.mechanics.calibration.series_error_amplification`) and
    the signal residual adds K_v n / K_s in quadrature.

    Args:
        k_element: K (N/mm). k_v_V_per_mm: K_v (V/mm).
        signal_noise_V: the signal's noise per reading (V, 1 sigma): the budget passes
            its read-out chain's, the calibration reads through the same chain.
        k_sensor_N_per_mm: the force gauge's stiffness (N/mm), default
            :data:`~tactcad.mechanics.calibration.K_SENSOR_N_PER_MM`.
        force_noise_N: the force gauge's resolution (N): the budget passes that of the
            design's calibration gauge (:func:`tactcad.studies.verification.calibration_gauge`).
        steps_um: the Z steps of one run (um), at least two different.

    Returns:
        (σ_K / K, σ_K_v / |K_v|), relative.

    Raises:
        DesignError: fewer than two different steps.
    """
    from tactcad.mechanics.calibration import (DEFAULT_NOISE_SIGNAL_V, K_SENSOR_N_PER_MM,
                                               series_error_amplification)

    k_s = K_SENSOR_N_PER_MM if k_sensor_N_per_mm is None else k_sensor_N_per_mm
    steps = np.asarray(steps_um, float)
    if steps.ndim != 1 or not np.ptp(steps) > 0:
        raise DesignError("steps_um", steps.tolist(), "two or more different Z steps (um)")
    z = np.tile(steps * 1e-3, CALIBRATION_REPEATS)
    defl = z * k_s / (k_element + k_s)
    sxx = math.sqrt(float(np.sum((defl - defl.mean()) ** 2)))
    n = force_noise_N
    force_residual = n * series_error_amplification(k_element, k_s).from_k_apparent
    v_noise = DEFAULT_NOISE_SIGNAL_V if signal_noise_V is None else signal_noise_V
    signal_residual = math.hypot(v_noise, k_v_V_per_mm * n / k_s)
    return force_residual / sxx / k_element, signal_residual / sxx / abs(k_v_V_per_mm)


def calibration_stderr_by_part(plan: Plan, model: str, stiffness: Mapping[str, float],
                               rig, force_noise_N: float | None = None,
                               readout: Mapping[str, Mapping[str, float]] | None = None
                               ) -> dict[str, tuple[float, float]]:
    """(σ_K / K, σ_K_v / |K_v|) a static calibration on ``rig`` is expected to leave on each
    distinct part of ``plan`` (:func:`expected_calibration_stderr_rel` at the steps the
    calibration drives on it, the signal through the design's read-out chain).

    Args:
        plan: the design. model: the ladder level of the gauge strain.
        stiffness: K per distinct part (N/mm).
        rig: the :class:`~tactcad.mechanics.calibration.CalibrationGauge`.
        force_noise_N: the force read to (N); default the rig's gauge's resolution.
        readout: :func:`tactcad.mechanics.readout_chain.element_force_resolution_N` of
            ``plan`` at ``model``, when the caller has it.

    Returns:
        part name -> (σ_K / K, σ_K_v / |K_v|).
    """
    from tactcad.mechanics.readout_chain import (element_force_resolution_N, noise_budget_V,
                                                 readout_chain)

    per_part = readout if readout is not None else element_force_resolution_N(plan, model)
    noise = noise_budget_V(readout_chain(plan))["reading"]
    n = rig.gauge.resolution_N if force_noise_N is None else force_noise_N
    out = {}
    for part in plan.distinct_elements:
        k = float(stiffness[part])
        out[part] = expected_calibration_stderr_rel(
            k, per_part[part]["S"] * k, noise, rig.gauge.stiffness_N_per_mm,
            force_noise_N=n, steps_um=rig.steps_um(k))
    return out


def _calibration_stderr(ctx: Context, force_noise_N: float | None = None
                        ) -> dict[int, tuple[float, float]]:
    """Element number -> (σ_K / K, σ_K_v / |K_v|): the calibration file's fit where it has
    one, else what the design's calibration is expected to leave (force read to
    ``force_noise_N``, N; default the calibration gauge's resolution)."""
    per_part = ctx.once("readout", lambda: _readout(ctx))
    expected = calibration_stderr_by_part(ctx.plan, ctx.model, ctx.k, ctx.force_gauge,
                                          force_noise_N, per_part)
    out = {}
    for s in ctx.plan.slots:
        c = ctx.calibrations.get(s.number)
        out[s.number] = ((c.stderr_K_N_per_mm / abs(c.K_N_per_mm),
                          c.stderr_K_v_V_per_mm / abs(c.K_v_V_per_mm)) if c is not None
                         else expected[s.geometry.part_name])
    return out


def _readout(ctx: Context):
    from tactcad.mechanics.readout_chain import element_force_resolution_N

    return element_force_resolution_N(ctx.plan, ctx.model)


def _calibration_term(ctx: Context, unit: Unit, k_obj: np.ndarray,
                      se: Mapping[int, tuple[float, float]]) -> np.ndarray:
    # the unit's K_obj error of the elements' K and K_v standard errors ``se``, independent
    (km, kvm), (kr, kvr) = se[unit.measuring], se[unit.reference]
    return np.sqrt(independent_reading_error_rel(ctx, unit, k_obj, de_m=kvm, de_r=kvr) ** 2
                   + stiffness_error_rel(ctx, unit, k_obj, dk_m=km) ** 2
                   + stiffness_error_rel(ctx, unit, k_obj, dk_r=kr) ** 2)


def calibration_steps_words(ctx: Context) -> str:
    """The Z steps the calibration drives, in words: the paper's, or each element's
    :data:`~tactcad.mechanics.calibration.FULL_SCALE_STEPS` equal steps to its full-scale
    travel with the range of those travels (um)."""
    from tactcad.mechanics.calibration import FULL_SCALE_STEPS

    rig = ctx.force_gauge
    if rig.full_scale_force_N is None:
        return "the paper's Z steps, 25 um to 150 um"
    tops = [float(rig.steps_um(ctx.k_of(s.number))[-1]) for s in ctx.plan.slots]
    return (f"{FULL_SCALE_STEPS} equal Z steps to each element's travel at the full-scale "
            f"{rig.full_scale_force_N:.4g} N ({min(tops):.3g} ... {max(tops):.3g} um)")


class CalibrationNeed(NamedTuple):
    """What the budget asks of the calibration's force gauge (:func:`calibration_resolution_need`).

    Attributes:
        force_share_rel: the share of the calibration term's variance the force gauge's
            resolution makes, where the term is largest (0 ... 1).
        resolution_needed_N: the resolution (N) at which a gauge of the same stiffness
            brings the term within its allowance; None when it is within already, or when no
            resolution can (``words`` says which).
        fits: the term is within its allowance at every K_obj.
        words: the allowance and the verdict, in words.
        runs_needed: the runs of the calibration (:data:`CALIBRATION_REPEATS` assumed) that
            bring the term within its allowance on the same gauge, the term's variance
            falling as 1 / runs; None when it is within already, or no count can.
    """

    force_share_rel: float
    resolution_needed_N: float | None
    fits: bool
    words: str
    runs_needed: int | None = None


def calibration_resolution_need(ctx: Context, pairs: list[Unit], units: list[dict],
                                k_obj: np.ndarray) -> CalibrationNeed:
    """The calibration term of the array's best unit at each K_obj against its allowance,
    and the force gauge resolution that would bring it within.

    The allowance is what the other terms (after correction) leave of
    ``requirements.kobj_accuracy_rel`` in RSS where the design states it, else the RSS of
    those terms (a calibration should not be the budget's largest error). Every term of the
    calibration is linear in the elements' standard errors, and σ_K grows as the force
    resolution n, σ_K_v as the root of a constant plus n², so the term squared is A + B n²
    (A: the bridge noise alone, n = 0): the resolution needed is n sqrt((T² − A) / (c² − A))
    for a term c and allowance T; none helps where A alone exceeds T. Both parts of the
    variance fall as 1 / runs (every reading independent), so :data:`CALIBRATION_REPEATS`
    x c² / T² runs bring it within on the same gauge.

    Args:
        ctx: the budget's context. pairs, units: its units and their records.
        k_obj: the grid (N/mm).

    Returns:
        :class:`CalibrationNeed`.
    """
    from tactcad.design.requirements_section import stated_kobj_accuracy

    n = float(ctx.force_gauge.gauge.resolution_N)
    if not units:
        return CalibrationNeed(0.0, None, True, "no sensing unit")
    rss = np.array([finite_or_inf(u["rss_rel"]) for u in units])
    best = np.argmin(rss, axis=0)
    quiet = _calibration_stderr(ctx, force_noise_N=0.0)
    accuracy = stated_kobj_accuracy(ctx.plan.raw)
    share, worst, needed, full, noisy = 0.0, -1.0, [], False, False
    runs_ratio = 0.0  # the largest c² / T² where the term misses its allowance
    for i, b in enumerate(best):
        if not math.isfinite(rss[b, i]):
            continue
        c = finite_or_inf(units[b]["sources"]["calibration"]["after_rel"])[i]
        a = float(_calibration_term(ctx, pairs[b], k_obj[i:i + 1], quiet)[0])
        others_sq = max(rss[b, i] ** 2 - c ** 2, 0.0)
        allowance_sq = accuracy ** 2 - others_sq if accuracy is not None else others_sq
        if c > worst:
            worst, share = c, (1.0 - a ** 2 / c ** 2 if c > 0 else 0.0)
        if c ** 2 <= allowance_sq * (1 + 1e-9):
            continue
        if allowance_sq <= 0.0:
            full = True
            continue
        runs_ratio = max(runs_ratio, c ** 2 / allowance_sq)
        if allowance_sq <= a ** 2 or c ** 2 <= a ** 2:
            noisy = True
        else:
            needed.append(n * math.sqrt((allowance_sq - a ** 2) / (c ** 2 - a ** 2)))
    allowance = (f"within what the other terms leave of the stated accuracy "
                 f"{100 * accuracy:g} %" if accuracy is not None
                 else "no larger than the other terms' RSS")
    gauge = ctx.force_gauge.gauge
    runs = math.ceil(CALIBRATION_REPEATS * runs_ratio * (1 - 1e-9)) if runs_ratio else None
    more_runs = (f"; so would {runs} runs of the calibration on this gauge, not "
                 f"{CALIBRATION_REPEATS}" if runs else "")
    head = (f"the calibration term, at most {100 * worst:.3g} % ({100 * share:.0f} % of its "
            f"variance from the force gauge read to {n:g} N), should be {allowance}")
    if full:
        return CalibrationNeed(share, None, False, (
            f"{head}: no force gauge resolution brings it there, the other terms alone fill "
            f"the accuracy"))
    if noisy:
        return CalibrationNeed(share, None, False, (
            f"{head}: no force gauge resolution brings it there, the bridge noise over the "
            f"calibration's deflection span alone exceeds it; more runs ({runs}, not "
            f"{CALIBRATION_REPEATS}), longer averaging or a quieter read-out would"), runs)
    if needed:
        res = listed([min(needed)])[0]
        return CalibrationNeed(share, res, False, (
            f"{head}: {gauge.model} misses it; a gauge of its stiffness "
            f"({gauge.stiffness_N_per_mm:g} N/mm) read to {res:.2g} N would bring it there"
            f"{more_runs}"), runs)
    return CalibrationNeed(share, None, True, f"{head}: it is")


def calibration(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(h) The standard errors of each element's fitted K (eq. 5) and K_v (eq. 4),
    independent: the calibration file's fits, else those a static calibration on the
    design's calibration rig (``force_gauge`` of :func:`kobj_budget`: its force gauge, and
    the Z steps ``calibrate`` drives) is expected to leave; each read by
    the coupled inversion (a K_v error scales its deflection reading, a K error the coupled
    R of the true springs)."""
    se = ctx.once("calibration", lambda: _calibration_stderr(ctx))
    rel = _calibration_term(ctx, unit, op.k_obj, se)
    return Contribution(rel, rel)


#: Creep of a bonded foil gauge's reading under a held load, relative, uncompensated: the
#: limit beyond which the installation is faulty (Vishay Measurements Group, "Creep
#: Compensation": compensation is "generally limited to transducers exhibiting less than
#: +-0.1 % FS creep"; larger creep is generally a faulty gauge installation).
GAUGE_CREEP_REL = 1e-3
#: With the creep compensation a transducer maker matches to its spring (same note:
#: commercial transducers "regularly achieve ... less than +-0.02 % of full scale" in 20 min).
COMPENSATED_CREEP_REL = 2e-4
#: The hold the creep figures are for (min).
GAUGE_CREEP_MINUTES = 20.0


def gauge_creep(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(j) Each element's reading creeping by :data:`GAUGE_CREEP_REL` of itself over a
    held reading, the two independent (quadrature), read by the coupled inversion
    (:func:`independent_reading_error_rel`); after creep compensation
    :data:`COMPENSATED_CREEP_REL` remains."""
    def rel(creep: float) -> np.ndarray:
        return independent_reading_error_rel(ctx, unit, op.k_obj, de_m=creep, de_r=creep)

    return Contribution(rel(GAUGE_CREEP_REL), rel(COMPENSATED_CREEP_REL))


def gauge_hysteresis_rel(ctx: Context) -> tuple[float, str]:
    """The bonded gauge's hysteresis and where it comes from.

    Args:
        ctx: the budget's context (its plan's ``[readout]``).

    Returns:
        (hysteresis relative to the reading, its source): the design's
        ``readout.gauge_hysteresis_rel`` ("design file", from a load-unload cycle at the rated
        force; OIML R 60 defines a load cell's hysteresis error so), else the assumed
        :data:`tactcad.design.readout_section.DEFAULT_GAUGE_HYSTERESIS_REL`, its source saying so.
    """
    from tactcad.mechanics.readout_chain import readout_chain

    chain = ctx.once("readout_chain", lambda: readout_chain(ctx.plan))
    return chain.gauge_hysteresis_rel, dict(chain.sources)["gauge_hysteresis_rel"]


def gauge_hysteresis(ctx: Context, unit: Unit, op: Operating) -> Contribution:
    """(k) Each element's reading off by the gauge's hysteresis (``readout.gauge_hysteresis_rel``
    of itself: a reading taken unloading where the calibration loaded), the two installations
    independent (quadrature), read by the coupled inversion as creep is
    (:func:`independent_reading_error_rel`); no correction removes it."""
    h, _ = gauge_hysteresis_rel(ctx)
    rel = independent_reading_error_rel(ctx, unit, op.k_obj, de_m=h, de_r=h)
    return Contribution(rel, rel)


def crosstalk_basis(plan, term: CrosstalkTerm) -> str:
    """The budget's note on its crosstalk term, naming the crosstalk level it read.

    Args:
        plan: the design's plan. term: what :func:`_crosstalk` read for it.

    Returns:
        "not modelled, left out of the sums: <why>" where no level describes the
        construction, else the largest force a gauge reads per newton on a neighbour's tip
        at ``term.level`` and the fraction the decoupling matrix leaves (its error estimate).
    """
    why = _crosstalk_reason(plan)
    if why:
        return f"not modelled, left out of the sums: {why}"
    head = (f"the largest force a gauge reads per newton on a neighbour's tip "
            f"({term.level}); ")
    if term.error_rel >= 1.0:
        return head + (f"its error estimate, {term.error_rel:.3g}, exceeds the term itself: a "
                       f"decoupling matrix made from it would remove nothing, so all of it "
                       f"remains")
    return head + (f"the decoupling matrix leaves {term.error_rel:.3g} of it (its error "
                   f"estimate)")


class Source(NamedTuple):
    """One source of the budget: its key, its words and its function; ``unmodelled`` gives,
    for a design, why no model of the source describes its construction ("" where one
    does): such a source adds nothing to the sums and its record says so."""

    key: str
    words: str
    function: Callable[[Context, Unit, Operating], Contribution]
    correction: str
    unmodelled: Callable[[Any], str] = lambda plan: ""  # a model for every construction


#: The sources, in the order of the module docstring's list.
SOURCES = (
    Source("readout_noise", "read-out noise and quantisation", readout_noise, "none"),
    Source("thermal_zero", "thermal zero", thermal_zero, "none (a tare at the reading "
           "temperature removes it)"),
    Source("thermal_span", "thermal span", thermal_span, "none"),
    Source("manufacturing_tolerance", "manufacturing tolerance", manufacturing_tolerance,
           "calibration measures each K: none remains (its error is the calibration's)"),
    Source("crosstalk", "crosstalk", crosstalk,
           "the decoupling matrix: its model's error estimate remains", _crosstalk_reason),
    Source("tissue_coupling", "tissue coupling", tissue_coupling,
           "the coupled inversion: the coupled model's error remains"),
    Source("gauge_model", "gauge model", gauge_model,
           "calibration measures K_v: none remains in the reading"),
    Source("calibration", "calibration uncertainty", calibration, "none"),
    Source("tip_coplanarity", "tip coplanarity", tip_coplanarity,
           "every unit zeroed on a rigid flat (tactcad calibrate --flat; lumped --flat takes "
           "the heights out): the offset read to the elements' deflection resolution and the "
           "flat's flatness remains"),
    Source("gauge_creep", f"gauge creep ({GAUGE_CREEP_MINUTES:g} min hold)", gauge_creep,
           "creep compensation matched to the spring: 0.02 % of the reading remains"),
    Source("gauge_hysteresis", "gauge hysteresis (load-unload)", gauge_hysteresis, "none"),
)
SOURCE_KEYS = tuple(s.key for s in SOURCES)


def source_words(source: Source, crosstalk_level: str = "") -> str:
    """A source's words as a budget prints them: the crosstalk term's name its
    construction's crosstalk level, "crosstalk (comb-beam)" for a monolithic comb and
    "crosstalk (stack-timoshenko)" for the stacked array, never another construction's;
    every other source's are its own.

    Args:
        source: one of :data:`SOURCES`.
        crosstalk_level: the level the budget's crosstalk term read ("" where none
            describes the construction).

    Returns:
        The words.
    """
    if source.key == "crosstalk" and crosstalk_level:
        return f"{source.words} ({crosstalk_level})"
    return source.words

#: JSON keys of the budget's record that were renamed, old -> new. The old key is still
#: written beside the new one, with the same value (a source's in each unit's ``sources``,
#: a note's in ``notes``), and the record lists this mapping as ``deprecated_keys``; the
#: sums (``rss_rel``, ``worst_case_rel``, ``dominant``) and the ``sources`` list count each
#: source once, under its new key. The old keys go in a later release.
DEPRECATED_KEYS = {"stack_crosstalk": "crosstalk",
                   "stack_crosstalk_N_per_N": "crosstalk_N_per_N",
                   "stack_crosstalk_basis": "crosstalk_basis"}


def with_deprecated_keys(mapping: dict, renamed: Mapping[str, str] | None = None) -> dict:
    """``mapping`` (a unit's ``sources``, the ``notes``; another record's top level) with
    each old key of ``renamed`` whose new key it holds added after its own keys, the same
    value; a new dict, ``mapping`` unchanged.

    Args:
        mapping: the record (or part of it) written under the new keys.
        renamed: old key -> new key (None: the budget's :data:`DEPRECATED_KEYS`); the
            record lists it as its ``deprecated_keys``.

    Returns:
        The record with the deprecated duplicates.
    """
    renamed = DEPRECATED_KEYS if renamed is None else renamed
    return {**mapping, **{old: mapping[new] for old, new in renamed.items()
                          if new in mapping}}


#: The K_obj range's key before it took the glossary's name (``grasp --json`` and
#: ``tolerance --json``, an array's and a die's, wrote it): kept beside the new one for now.
KOBJ_RANGE_RENAMED = {"K_obj_range_N_per_mm": "kobj_range_N_per_mm"}


def with_declared_deprecated_keys(record: dict, renamed: Mapping[str, str]) -> dict:
    """A record's top level with the old name of each renamed key beside the new one
    (:func:`with_deprecated_keys`) and ``deprecated_keys`` listing the renames (with any it
    lists already).

    Args:
        record: the record, written under the new keys. renamed: old key -> new key.

    Returns:
        A new dict; ``record`` unchanged.
    """
    return {**with_deprecated_keys(record, renamed),
            "deprecated_keys": {**record.get("deprecated_keys", {}), **renamed}}


# ---------------------------------------------------------------------------
# The budget
# ---------------------------------------------------------------------------
def kobj_grid(kobj_range: tuple[float, float], points: int = BUDGET_POINTS) -> np.ndarray:
    """``points`` log-spaced K_obj over [LO, HI] (N/mm), ends included."""
    return np.geomspace(float(kobj_range[0]), float(kobj_range[1]), points)


def budget_uncertainty_rel(ctx: Context, unit: Unit) -> float:
    """The unit's budget's own relative uncertainty: its largest gauge-model error plus its
    largest K error estimate at the level (they scale the read-out and thermal terms)."""
    err = ctx.once("gauge", lambda: gauge_model_error_rel(ctx.plan, ctx.model))
    parts = [ctx.plan.element(n).geometry.part_name for n in unit]
    return max(abs(err[p]) for p in parts) + max(ctx.k_error[p] for p in parts)


#: Significant digits the budget's figures keep: far finer than any of them is known, and
#: coarse enough that the last bits a linear-algebra library leaves (another BLAS, another
#: thread count, another array alignment) neither change the manifest nor flip a tie between
#: symmetric units, after the coupled slope's finite difference (about 1e3 x) and the
#: coplanarity's root finds have amplified them.
BUDGET_DIGITS = 6


def finite_or_inf(values) -> np.ndarray:
    """A :func:`listed` list back as floats, None (a reading that cannot be made) as inf."""
    return np.array([math.inf if v is None else float(v) for v in values])


def listed(values: np.ndarray) -> list[float | None]:
    """``values`` as a list of floats to :data:`BUDGET_DIGITS` significant digits, None
    where not finite (a reading eq. 3 cannot make)."""
    return [float(f"{v:.{BUDGET_DIGITS}g}") if math.isfinite(v) else None
            for v in np.asarray(values, float)]


def unit_budget(ctx: Context, unit: Unit, k_obj: np.ndarray) -> dict:
    """Every source's contribution for one unit over ``k_obj`` (N/mm), with the RSS and
    worst-case sums before and after correction and the source that dominates at each
    K_obj (after correction)."""
    op = operating_point(ctx.k_of(unit.measuring), ctx.k_of(unit.reference), k_obj,
                         ctx.force_N)
    parts = {s.key: s.function(ctx, unit, op) for s in SOURCES}
    after = np.array([parts[k].after for k in SOURCE_KEYS])
    before = np.array([parts[k].before for k in SOURCE_KEYS])
    alone = unit_alone_resolution_rel(ctx, unit, op)
    return {"reference_element": unit.reference, "measuring_element": unit.measuring,
            "K_r_N_per_mm": op.k_r, "K_m_N_per_mm": op.k_m,
            "R": listed(op.ratio), "force_measuring_N": listed(op.force_m),
            "reads_kobj": unit_reads(ctx, unit, op).tolist(),
            "reads_kobj_undecided": unit_reads_undecided(ctx, unit, op).tolist(),
            "readout_alone_rel": listed(alone),
            "readout_coupled_over_alone": listed(coupled_readout_noise_rel(ctx, unit, op)
                                                 / alone),
            "sources": {s.key: {"before_rel": listed(parts[s.key].before),
                                "after_rel": listed(parts[s.key].after),
                                **unmodelled_record(s, ctx.plan)} for s in SOURCES},
            "rss_rel": listed(np.sqrt(np.sum(after ** 2, axis=0))),
            "worst_case_rel": listed(np.sum(np.abs(after), axis=0)),
            "rss_before_rel": listed(np.sqrt(np.sum(before ** 2, axis=0))),
            "worst_case_before_rel": listed(np.sum(np.abs(before), axis=0)),
            "dominant": [SOURCE_KEYS[i] for i in np.argmax(np.abs(after), axis=0)],
            "uncertainty_rel": budget_uncertainty_rel(ctx, unit)}


def unmodelled_record(source: Source, plan) -> dict:
    """``{"not_modelled": why}`` for a source no model describes for ``plan``'s
    construction (its contributions are zeros, left out of every sum), else ``{}``."""
    why = source.unmodelled(plan)
    return {"not_modelled": why} if why else {}


@dataclass(frozen=True)
class KobjBudget:
    """The budget of one design (:func:`kobj_budget`); :meth:`as_json` is its record."""

    design: str
    model: str
    force_N: float
    delta_T_K: float
    kobj_range_N_per_mm: tuple[float, float]
    k_obj: tuple[float, ...]
    units: list[dict]
    notes: dict
    tip_height: dict = field(default_factory=dict)
    #: the crosstalk level the crosstalk term read (``stack-timoshenko``, ``comb-beam`` ...;
    #: "" where none describes the construction): the term's words name it
    crosstalk_level: str = ""

    def source_words(self, source: "Source") -> str:
        """The source's words in this budget (:func:`source_words`)."""
        return source_words(source, self.crosstalk_level)

    def dominant_words(self, key: str) -> str:
        """A ``dominant`` key in words: the key's own words ("tissue coupling"), the
        crosstalk term's with its level ("crosstalk (comb-beam)")."""
        if key == "crosstalk" and self.crosstalk_level:
            return f"crosstalk ({self.crosstalk_level})"
        return key.replace("_", " ")

    @property
    def array(self) -> dict:
        """At each K_obj the unit that reads it best (smallest RSS after correction): its
        RSS, worst case, dominant source and the budget's own uncertainty."""
        if not self.units:
            return {"unit": [], "rss_rel": [], "worst_case_rel": [], "dominant": [],
                    "reads_undecided": [], "uncertainty_rel": []}
        best = reading_unit_index(self.units)
        pick = lambda key: [self.units[b][key][i] for i, b in enumerate(best)]  # noqa: E731
        return {"unit": [f"{self.units[b]['reference_element']}/"
                         f"{self.units[b]['measuring_element']}" for b in best],
                "rss_rel": pick("rss_rel"), "worst_case_rel": pick("worst_case_rel"),
                "dominant": pick("dominant"),
                "reads_undecided": [bool(self.units[b].get("reads_kobj_undecided",
                                                           [False] * len(best))[i])
                                    for i, b in enumerate(best)],
                "uncertainty_rel": [self.units[b]["uncertainty_rel"] for b in best]}

    def worst_array_rss(self) -> tuple[float, float] | None:
        """(worst RSS over the range of the array's best unit, that unit's budget
        uncertainty), or None without a unit."""
        a = self.array
        if not a["rss_rel"]:
            return None
        i = int(np.argmax(finite_or_inf(a["rss_rel"])))
        rss = a["rss_rel"][i]
        return (math.inf if rss is None else float(rss)), float(a["uncertainty_rel"][i])

    def as_json(self) -> dict:
        """The record ``tactcad budget --json`` prints: each unit's ``sources`` and the
        ``notes`` also under the renamed keys' old names, and ``deprecated_keys`` mapping
        each old name to the new (:data:`DEPRECATED_KEYS`; the sums count each source
        once)."""
        units = [{**u, "sources": with_deprecated_keys(u["sources"])} for u in self.units]
        return {"design": self.design, "model": self.model, "force_N": self.force_N,
                "delta_T_K": self.delta_T_K,
                "kobj_range_N_per_mm": list(self.kobj_range_N_per_mm),
                "K_obj_N_per_mm": list(self.k_obj),
                "sources": [{"key": s.key, "words": self.source_words(s),
                             "correction": s.correction} for s in SOURCES],
                "units": units, "array": self.array,
                "notes": with_deprecated_keys(self.notes),
                "tip_height": self.tip_height, "deprecated_keys": dict(DEPRECATED_KEYS)}


def kobj_budget(plan: Plan, kobj_range: tuple[float, float], force_N: float,
                delta_T_K: float = DEFAULT_DELTA_T_K, model: str = "closed-form",
                stiffness: Mapping[str, float] | None = None,
                errors: Mapping[str, float] | None = None,
                calibrations: Mapping[int, object] | None = None,
                points: int = BUDGET_POINTS, *,
                force_gauge: Any, readable_within_rel: float | None = None) -> KobjBudget:
    """The K_obj error budget of every sensing unit of ``plan`` over ``kobj_range``.

    Args:
        plan: the design.
        kobj_range: [LO, HI] of K_obj (N/mm): the requirements' range.
        force_N: the force the reference carries at the reading (N): the design's
            full-scale force by default at the caller.
        delta_T_K: the temperature step between tare and reading (K), 0 ... 100.
        model: ladder level of K and the gauge strain.
        stiffness, errors: K (N/mm) and its relative error per distinct part at ``model``
            (``verify`` passes its own); None estimates them.
        calibrations: element number -> fitted
            :class:`~tactcad.mechanics.calibration.Calibration` (a calibration file);
            the others take the expected standard errors of a static calibration
            (:func:`expected_calibration_stderr_rel`).
        points: K_obj grid points (log-spaced), 2 ... 101.
        force_gauge: the calibration rig
            (:class:`~tactcad.mechanics.calibration.CalibrationGauge`: the force gauge the
            elements are calibrated on, where it comes from, the force its Z steps reach):
            :func:`tactcad.studies.verification.calibration_gauge` of ``plan``, the gauge and
            steps ``calibrate`` uses, so that every caller's budget reads one calibration.
        readable_within_rel: the largest relative K_obj resolution of a unit alone that
            reads K_obj (> 0; the requirement's ``kobj_resolution_rel``, as ``verify``
            judges the readable range): a unit reads none where its own is larger
            (:func:`unit_reads`). None: no limit, every unit reads (the commands pass
            the design's requirement, :func:`tactcad.studies.verification.requirements_of`).

    Returns:
        :class:`KobjBudget`.

    Raises:
        DesignError: force, temperature step, range or points out of range.
        UnknownModelError: ``model`` is not a ladder level.
    """
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.readout_chain import row_units

    lo, hi = (float(v) for v in kobj_range)
    if not (0 < lo < hi):
        raise DesignError("kobj_range_N_per_mm", [lo, hi], "[LO, HI] with 0 < LO < HI N/mm")
    if not (math.isfinite(force_N) and force_N > 0):
        raise DesignError("force_N", force_N, "a number > 0 N")
    if not (math.isfinite(delta_T_K) and DELTA_T_RANGE_K[0] <= delta_T_K <= DELTA_T_RANGE_K[1]):
        raise DesignError("delta_T_K", delta_T_K, "a number 0 ... 100 K")
    if not 2 <= points <= 101:
        raise DesignError("points", points, "an integer 2 ... 101")
    if readable_within_rel is None:  # no requirement given: every unit reads
        readable_within_rel = math.inf
    if not (readable_within_rel > 0):  # nan too
        raise DesignError("readable_within_rel", readable_within_rel, "a number > 0")
    if stiffness is None or errors is None:
        est = {n: estimate(model, g, plan.material) for n, g in plan.distinct_elements.items()}
        stiffness = {n: e.stiffness_N_per_mm for n, e in est.items()}
        errors = {n: e.error_estimate_rel for n, e in est.items()}
    ctx = Context(plan, model, stiffness, errors, float(force_N), float(delta_T_K),
                  dict(calibrations or {}), force_gauge,
                  readable_within_rel=float(readable_within_rel))
    k_obj = kobj_grid((lo, hi), points)
    pairs = [Unit(r.number, m.number) for r, m in row_units(plan, dict(stiffness))]
    units = [unit_budget(ctx, u, k_obj) for u in pairs]
    tip = tip_height_record(ctx, pairs, units, k_obj)
    tc_e, tc_source = modulus_tc_per_K(plan)
    gauge, gauge_source = force_gauge.gauge, force_gauge.source
    need = (calibration_resolution_need(ctx, pairs, units, k_obj) if not calibrations
            else None)
    term = ctx.once("crosstalk", lambda: _crosstalk(ctx))
    expected = (f"expected standard errors of a static calibration on the {gauge.model} "
                f"force gauge (range {gauge.range_N:g} N, read to "
                f"{gauge.resolution_N:g} N, {gauge.stiffness_N_per_mm:g} N/mm; "
                f"{gauge_source}, as tactcad calibrate): {calibration_steps_words(ctx)}, "
                f"{CALIBRATION_REPEATS} runs, the force read to the gauge's resolution and the "
                f"signal to the read-out chain's noise of one averaged reading, 1 sigma")
    unfitted = [s.number for s in plan.slots if s.number not in ctx.calibrations]
    notes = {
        "crosstalk_N_per_N": (float(np.max(np.abs(term.per_newton)))
                              if term.per_newton.size else 0.0),
        "crosstalk_basis": crosstalk_basis(plan, term),
        "operating_point": f"each unit pressed until its reference carries {force_N:.4g} N "
                           f"(eq. 1); the zero terms scale as 1/force",
        "temperature_step": f"{delta_T_K:g} K between tare and reading; the self-heating "
                            f"offset is constant at a fixed excitation and tared with the zero",
        "modulus_tc_per_K": tc_e, "modulus_tc_source": tc_source,
        "gauge_hysteresis_rel": gauge_hysteresis_rel(ctx)[0],
        "gauge_hysteresis_source": gauge_hysteresis_rel(ctx)[1],
        "gauge_model": "the grid strain's own error estimate at the level (the width "
                       "correction's fit residual at closed form and beam; a calibration "
                       "measures K_v, so none remains after it)",
        "calibration": calibration_note(ctx, pairs, expected),
        **({"calibration_unfitted_elements": unfitted} if calibrations else {}),
        "calibration_force_gauge": gauge.model,
        "calibration_force_gauge_source": gauge_source,
        **({"calibration_force_share_rel": listed([need.force_share_rel])[0],
            "calibration_gauge_resolution_needed_N": need.resolution_needed_N,
            "calibration_gauge_fits": need.fits,
            "calibration_runs_needed": need.runs_needed,
            "calibration_allowance": need.words} if need is not None else {}),
        "readout_noise": "1 sigma, each unit pressed into one sample with every tip (the "
                         "coupled inversion's R and slope); readout_alone_rel is the unit "
                         "pressed alone (tactcad readout's and verify's K_obj resolution, eq. "
                         "1-3, the same force, noise and K_obj; they report its worst over "
                         "the range), readout_coupled_over_alone the term over it. A unit "
                         f"whose own resolution exceeds {readable_within_rel:.4g} (the "
                         "required kobj_resolution_rel, as verify's readable range) reads no "
                         "K_obj there (reads_kobj false): its term and sums are unreadable; "
                         "where it misses or meets it only inside the level's error on it "
                         "(each K by its error, each grid strain by its own), whether it "
                         "reads is undecided (reads_kobj_undecided) and its terms are summed "
                         "as read",
        "readable_within_rel": float(readable_within_rel),
        "totals": "RSS and worst-case sum of the contributions after correction (as a "
                  "calibrated, corrected sensor reads); *_before_rel without correction",
        "manufacturing_tolerance": "calibration measures each element's K (eq. 5), so the "
                                   "fixed K error of the web tolerance is removed; the "
                                   "calibration's own standard error remains (calibration)",
        "tissue_coupling": f"half-space sample (nu 0.5), rigid flat punches of the design's tip "
                           f"faces, one face alone reading K_obj, converged in the mesh to "
                           f"{_tissue_sample(ctx).error_rel:.2g}; after the coupled inversion "
                           f"{COUPLING_MODEL_ERROR_REL:g} of its R shift (the coupled model's "
                           f"error) plus that mesh error, through the coupled model's own "
                           f"slope dR/dlnK_obj",
        "tip_coplanarity": tip["basis"]}
    return KobjBudget(plan.name, model, float(force_N), float(delta_T_K), (lo, hi),
                      tuple(float(v) for v in k_obj), units, notes, tip, term.level)


def calibration_note(ctx: Context, pairs: list[Unit], expected: str) -> str:
    """The budget's note on its calibration term: ``expected`` (the standard errors a static
    calibration is expected to leave) without a calibration file; with one, its fitted
    standard errors, and for each element it has no readings of (``calibrate`` flags it
    "not calibrated") the units whose term falls back to ``expected``, as without a file."""
    if not ctx.calibrations:
        return expected
    fitted = "fitted standard errors of the calibration file"
    unfitted = [s.number for s in ctx.plan.slots if s.number not in ctx.calibrations]
    if not unfitted:
        return fitted
    units = [f"{u.reference}/{u.measuring}" for u in pairs
             if u.reference in unfitted or u.measuring in unfitted]
    which = ", ".join(map(str, unfitted))
    return (f"{fitted} where it has readings; element{'s' if len(unfitted) > 1 else ''} "
            f"{which} without readings in it (not calibrated, as tactcad calibrate flags) "
            f"take{'' if len(unfitted) > 1 else 's'} what the budget uses without a "
            f"calibration file, so the calibration term of unit"
            f"{'s' if len(units) != 1 else ''} {', '.join(units) or 'none'} is not fitted: "
            f"{expected}")


def tip_height_record(ctx: Context, pairs: list[Unit], units: list[dict],
                      k_obj: np.ndarray) -> dict:
    """The budget's tip-height record: the drawing's tolerance, each unit's mismatch left
    after zeroing on a rigid flat, and with ``requirements.kobj_accuracy_rel`` stated the
    tolerance the accuracy needs (:func:`tip_height_tolerance_for_accuracy_mm`)."""
    from tactcad.design.requirements_section import stated_kobj_accuracy

    tol = tip_height_tolerance_mm(ctx.plan)
    after = {(u.reference, u.measuring): tip_mismatch_after_zeroing_mm(ctx, u) for u in pairs}
    accuracy = stated_kobj_accuracy(ctx.plan.raw)
    needed = (tip_height_tolerance_for_accuracy_mm(units, accuracy, after)
              if accuracy is not None and units else None)
    if needed is not None:
        needed = _exact_tolerance(ctx, pairs, units, k_obj, accuracy, needed)
    basis = (f"the tips' heights differ by up to twice the drawing's +/-{tol:g} mm "
             f"([tolerances] tip_height_mm) before correction; zeroed on a rigid flat (a gauge "
             f"block face, flat to {1e3 * ZEROING_FLAT_FLATNESS_MM:g} um), by that flatness and "
             f"the elements' deflection resolutions ({1e3 * max(after.values(), default=0):.3g} "
             f"um at most)")
    if accuracy is not None:
        basis += ("; for K_obj within " + f"{100 * accuracy:g} % uncorrected the drawing must "
                  + (f"hold +/-{needed:.3g} mm" if needed is not None else
                     "hold what no tolerance gives (the other terms fill the accuracy): zero on "
                     "a rigid flat"))
    worst_after = listed([max(after.values(), default=0.0)])[0]
    return {"tolerance_mm": tol, "mismatch_after_zeroing_mm": worst_after,
            "kobj_accuracy_rel": accuracy, "tolerance_for_accuracy_mm": needed,
            "basis": basis}
