"""Tolerance Monte Carlo: what manufacturing scatter does to K, R and K_obj.

Each sample is one as-built array: every element gets its own web thickness,
notch radius and arm length (each flexure is a separate wire-EDM contour),
and the whole array one Young's modulus (the elements come from one sheet).
The corrected closed form (:mod:`tactcad.mechanics.closed_form`, vectorised)
gives K per element; eq. 2 gives the deflection ratio R of each sensing unit
pressing an object of stiffness K_obj; eq. 3 with the *nominal* K_m, K_r (an
array read out with its design stiffnesses, not a per-element calibration)
turns R back into the K_obj the unit reports. The spread of that reported
K_obj around the true one is the error band the tolerances cause.

Distributions (:class:`Tolerances`): each toleranced quantity is drawn
normal with the tolerance as 3 standard deviations (a process with Cp = 1:
99.73 % of parts inside +/-tol), or, with ``distribution="uniform"``,
uniform over +/-tol (the worst case a tolerance allows with no process
knowledge). The tolerances are the design's ``[tolerances]`` table
(:mod:`tactcad.design.tolerances`, the one the drawings print; its defaults
carry their reasons); options of ``tactcad tolerance`` replace them as
what-if overrides. The sheet thickness is drawn once per array (one sheet)
and scales K in proportion (the element width b enters K linearly; the
correction's small width dependence is kept at the nominal b).

Sensing units: the reference elements are the nominally stiffest ones (ties
all count); every other element is paired with the nearest reference tip
(ties to the lower element number), as the lumped model assumes both
elements of a unit press the same object. ``reference=`` overrides this.

Sampling is reproducible: the draw is split into chunks of
:data:`CHUNK_SAMPLES` whose generators are spawned from one
``numpy.random.SeedSequence(seed)``, so a run gives the same numbers whether
its chunks are evaluated in this process or on a Dask cluster
(:mod:`tactcad.studies.sweeps`).

Sources: eq. 1-3 of the paper (:mod:`tactcad.mechanics.lumped_model`);
JCGM 101:2008 (GUM Supplement 1, propagation of distributions by Monte
Carlo; probabilistically symmetric 95 % coverage interval from the 2.5 and
97.5 percentiles).

Units: mm, N, MPa, N/mm; R dimensionless.
"""

from __future__ import annotations

import functools
import math
import threading
from collections import OrderedDict
from dataclasses import dataclass, field, replace
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.errors import DesignError
from tactcad.mechanics.closed_form_batch import corrected_stiffness_batch
from tactcad.mechanics.correction import Correction, load_correction
from tactcad.mechanics.lumped_model import deflection_ratio, object_stiffness

#: The Monte Carlo draw every command shares (``tolerance``'s defaults and
#: ``verify``'s toleranced band), so both print the same band.
MONTE_CARLO_SAMPLES = 10_000
MONTE_CARLO_SEED = 0
#: Sample counts a Monte Carlo takes (a spread needs two; ``tolerance --samples`` too).
SAMPLES_RANGE = (2, 10_000_000)

#: Samples per independently seeded chunk (the unit of work of a Dask run).
CHUNK_SAMPLES = 2500
#: Default tolerances the design file does not carry (see module docstring).
NOTCH_RADIUS_TOLERANCE_MM = 0.01
ARM_LENGTH_TOLERANCE_MM = 0.02
MODULUS_TOLERANCE_REL = 0.02
#: Object stiffnesses of the report (N/mm): the paper's softest, a middle and
#: its stiffest rubber sample.
DEFAULT_K_OBJ_N_PER_MM = (2.34, 5.41, 10.01)
#: K band the web tolerance is sized for (+/-5 %).
K_BAND_REL = 0.05
DISTRIBUTIONS = ("normal", "uniform")


@dataclass(frozen=True)
class Tolerances:
    """Symmetric tolerances (+/-) of the quantities the Monte Carlo draws.

    Attributes:
        web_mm: web thickness tolerance (mm).
        notch_radius_mm: notch radius tolerance (mm).
        arm_length_mm: arm length tolerance (mm).
        modulus_rel: relative Young's modulus tolerance (-).
        distribution: "normal" (tolerance = 3 sigma) or "uniform" (over +/-tol).

    Raises:
        DesignError: a negative or non-finite tolerance, or an unknown
            distribution (the field is named).
    """

    web_mm: float
    notch_radius_mm: float = NOTCH_RADIUS_TOLERANCE_MM
    arm_length_mm: float = ARM_LENGTH_TOLERANCE_MM
    modulus_rel: float = MODULUS_TOLERANCE_REL
    distribution: str = "normal"
    sheet_mm: float = 0.0
    sources: tuple[tuple[str, str], ...] = ()

    def __post_init__(self):
        limits = {"web_mm": 0.1, "notch_radius_mm": 0.5, "arm_length_mm": 0.5, "modulus_rel": 0.2,
                  "sheet_mm": 0.5}
        for name, hi in limits.items():
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 <= v <= hi:
                raise DesignError(f"tolerance.{name}", v, f"0 <= value <= {hi:g}")
        if self.distribution not in DISTRIBUTIONS:
            raise DesignError("tolerance.distribution", self.distribution,
                              " or ".join(DISTRIBUTIONS))

    @classmethod
    def of_plan(cls, plan: Plan, **overrides) -> "Tolerances":
        """The design's ``[tolerances]`` (defaults with reasons where the file gives none);
        ``overrides`` replace fields (what-if) and are recorded as such in ``sources``."""
        from tactcad.design.tolerances import tolerances_of

        t = tolerances_of(plan.raw)
        fields = {"web_mm": ("web_thickness_mm", plan.element(1).geometry.web_tolerance_mm),
                  "notch_radius_mm": ("notch_radius_mm", t.notch_radius_mm),
                  "arm_length_mm": ("arm_length_mm", t.arm_length_mm),
                  "modulus_rel": ("youngs_modulus_rel", t.youngs_modulus_rel),
                  "sheet_mm": ("sheet_thickness_mm", t.sheet_thickness_mm)}
        values = {f: v for f, (_, v) in fields.items()}
        sources = {key: ("design" if t.source(key).startswith("design file") else "default")
                   for key, _ in fields.values()}
        for f, v in overrides.items():
            if f in fields:
                sources[fields[f][0]] = "override (what-if)"
            values[f] = v
        g = plan.element(1).geometry
        for f, nominal, what in (("web_mm", g.web_thickness_mm, "web thickness"),
                                 ("notch_radius_mm", g.notch_radius_mm, "notch radius")):
            v = values[f]
            if isinstance(v, (int, float)) and not isinstance(v, bool) and v > nominal / 2:
                raise DesignError(f"tolerance.{f}", v, f"0 <= value <= {nominal / 2:g} (half the "
                                  f"{what} {nominal:g} mm)",
                                  "a larger tolerance lets the feature vanish in the draw")
        return cls(**values, sources=tuple(sorted(sources.items())))

    def describe(self) -> str:
        how = "normal, tolerance = 3 sigma" if self.distribution == "normal" else \
            "uniform over +/- tolerance"
        return (f"web +/-{self.web_mm:g} mm, notch radius +/-{self.notch_radius_mm:g} mm, arm "
                f"length +/-{self.arm_length_mm:g} mm, sheet +/-{self.sheet_mm:g} mm, modulus "
                f"+/-{100 * self.modulus_rel:g} % ({how})")


@dataclass(frozen=True)
class Samples:
    """Drawn parameters of ``n`` as-built arrays of ``m`` elements.

    Attributes:
        web_mm, notch_radius_mm, arm_length_mm: arrays (n, m) in mm.
        youngs_modulus_MPa: array (n, 1) in MPa (one sheet per array).
    """

    web_mm: np.ndarray
    notch_radius_mm: np.ndarray
    arm_length_mm: np.ndarray
    youngs_modulus_MPa: np.ndarray
    sheet_scale: np.ndarray | float = 1.0


def _deviation(rng: np.random.Generator, tol: float, shape: tuple[int, ...],
               distribution: str) -> np.ndarray:
    if distribution == "normal":
        return rng.normal(0.0, tol / 3.0, shape)
    return rng.uniform(-tol, tol, shape)


def draw_samples(plan: Plan, tol: Tolerances, n: int, rng: np.random.Generator) -> Samples:
    """Draw ``n`` as-built arrays around the plan's nominal geometry.

    Returns:
        :class:`Samples` with arrays (n, number of elements) and (n, 1).
    """
    geoms = [s.geometry for s in plan.slots]
    m = len(geoms)
    nominal = {k: np.array([getattr(g, k) for g in geoms])
               for k in ("web_thickness_mm", "notch_radius_mm", "arm_length_mm")}
    d = tol.distribution
    web = nominal["web_thickness_mm"] + _deviation(rng, tol.web_mm, (n, m), d)
    radius = nominal["notch_radius_mm"] + _deviation(rng, tol.notch_radius_mm, (n, m), d)
    arm = nominal["arm_length_mm"] + _deviation(rng, tol.arm_length_mm, (n, m), d)
    modulus = plan.material.youngs_modulus_MPa * (1.0 + _deviation(rng, tol.modulus_rel, (n, 1), d))
    if tol.sheet_mm <= 0:  # no draw: the stream of a run without a sheet tolerance is unchanged
        return Samples(web, radius, arm, modulus)
    sheet = 1.0 + _deviation(rng, tol.sheet_mm, (n, 1), d) / plan.sheet_thickness_mm
    return Samples(web, radius, arm, modulus, sheet)


def chunk_samples(spec: "ChunkSpec") -> Samples:
    """:func:`draw_samples` of one chunk, the same numbers to the bit: a normal draw is
    its tolerance / 3 times the chunk's standard normal draws, which depend on the chunk's
    seed, its size and the plan's element count alone, so they are drawn once per process
    (:func:`standard_normal_draws`); a uniform draw is drawn anew.

    Args:
        spec: the chunk (its plan, tolerances, sample count and seed).

    Returns:
        :class:`Samples` with arrays (n, number of elements) and (n, 1).
    """
    tol, plan, seed = spec.tolerances, spec.plan, spec.seed
    if tol.distribution != "normal" or not isinstance(seed.entropy, int):
        return draw_samples(plan, tol, spec.n, np.random.default_rng(seed))
    geoms = [s.geometry for s in plan.slots]
    z_web, z_radius, z_arm, z_modulus, z_sheet = standard_normal_draws(
        seed.entropy, tuple(seed.spawn_key), seed.pool_size, spec.n, len(geoms),
        tol.sheet_mm > 0)

    def nominal(key: str) -> np.ndarray:
        return np.array([getattr(g, key) for g in geoms])

    # Generator.normal(0, sigma) is 0 + sigma z of the same stream's standard normal z
    web = nominal("web_thickness_mm") + (0.0 + (tol.web_mm / 3.0) * z_web)
    radius = nominal("notch_radius_mm") + (0.0 + (tol.notch_radius_mm / 3.0) * z_radius)
    arm = nominal("arm_length_mm") + (0.0 + (tol.arm_length_mm / 3.0) * z_arm)
    modulus = plan.material.youngs_modulus_MPa * (
        1.0 + (0.0 + (tol.modulus_rel / 3.0) * z_modulus))
    if z_sheet is None:
        return Samples(web, radius, arm, modulus)
    sheet = 1.0 + (0.0 + (tol.sheet_mm / 3.0) * z_sheet) / plan.sheet_thickness_mm
    return Samples(web, radius, arm, modulus, sheet)


@functools.lru_cache(maxsize=64)
def standard_normal_draws(entropy: int, spawn_key: tuple[int, ...], pool_size: int, n: int,
                          m: int, sheet: bool) -> tuple[np.ndarray, ...]:
    """The standard normal draws of one chunk, in :func:`draw_samples`' order: web, notch
    radius and arm (n, m), modulus (n, 1) and, where ``sheet``, the sheet (n, 1), else None.
    Kept per process (read-only arrays: every chunk of one seed, size and element count
    draws these numbers).

    Args:
        entropy, spawn_key, pool_size: the chunk's ``numpy.random.SeedSequence``.
        n: samples. m: elements. sheet: whether the sheet is drawn.

    Returns:
        The five arrays (the last None without a sheet draw).
    """
    rng = np.random.default_rng(np.random.SeedSequence(entropy, spawn_key=spawn_key,
                                                       pool_size=pool_size))
    draws = [rng.standard_normal((n, m)) for _ in range(3)] + [rng.standard_normal((n, 1))]
    draws.append(rng.standard_normal((n, 1)) if sheet else None)
    for d in draws:
        if d is not None:
            d.setflags(write=False)
    return tuple(draws)


def corrected_stiffness(web_mm, notch_radius_mm, arm_length_mm, youngs_modulus_MPa,
                        g: ElementGeometry, poisson_ratio: float,
                        correction: Correction, out: np.ndarray | None = None) -> np.ndarray:
    """Vectorised corrected closed-form tip stiffness K (N/mm).

    Args:
        web_mm, notch_radius_mm, arm_length_mm: mm; youngs_modulus_MPa: MPa;
            array-like, broadcast together.
        g: the element supplying the other dimensions (arm and tip height,
            tip width, sheet thickness).
        poisson_ratio: nu (-).
        correction: the fem3d-fitted correction; its factor is applied
            without the range check (a Monte Carlo straddles the range
            edges by design; the closed-form estimator warns for nominal
            designs).
        out: optional C-contiguous float array of the broadcast shape for K.

    Returns:
        K of the broadcast shape (N/mm), with the bonded gauge ``g`` carries
        (:func:`~tactcad.mechanics.bonded_layer.with_gauge_layer`), as the
        closed-form level gives it (a modulus drawn per sample enters each
        sample's layer term exactly); the kernel is
        :func:`~tactcad.mechanics.closed_form_batch.corrected_stiffness_batch`.

    Raises:
        ValueError: a non-positive or non-finite input (see
            :func:`~tactcad.mechanics.closed_form.closed_form_compliance`).
    """
    return corrected_stiffness_batch(web_mm, notch_radius_mm, arm_length_mm, youngs_modulus_MPa,
                                     g, poisson_ratio, correction, out=out)


def stiffness_samples(plan: Plan, s: Samples, correction: Correction) -> np.ndarray:
    """K (N/mm) of every element in every sample, array (n, m).

    All elements of a plan share every dimension but the arm length, so one
    broadcast call evaluates the whole draw.
    """
    g = plan.element(1).geometry
    return s.sheet_scale * corrected_stiffness(s.web_mm, s.notch_radius_mm, s.arm_length_mm,
                                               s.youngs_modulus_MPa, g, plan.material.poisson_ratio,
                                               correction)


def nominal_stiffness(plan: Plan, correction: Correction) -> np.ndarray:
    """Nominal K (N/mm) of every element, array (m,), element order: with the shipped
    correction, each distinct element's closed-form level K, the very number ``stiffness``,
    ``verify`` and every other command print (the vectorised kernel agrees with it to
    rounding, not to the last digit); with another correction, the kernel's."""
    from tactcad.mechanics.ladder import estimate

    if correction == load_correction():
        k = {name: estimate("closed-form", g, plan.material).stiffness_N_per_mm
             for name, g in plan.distinct_elements.items()}
        return np.array([k[s.geometry.part_name] for s in plan.slots])
    geoms = [s.geometry for s in plan.slots]
    return corrected_stiffness([g.web_thickness_mm for g in geoms],
                               [g.notch_radius_mm for g in geoms],
                               [g.arm_length_mm for g in geoms], plan.material.youngs_modulus_MPa,
                               geoms[0], plan.material.poisson_ratio, correction)


def reference_elements(numbers: Sequence[int], k: Mapping[int, float]) -> list[int]:
    """The design's reference elements: the nominally stiffest ones, ties all counted.

    Args:
        numbers: element numbers, element order.
        k: nominal K (N/mm) per element number.

    Returns:
        the numbers of every element within 1e-9 (relative) of the stiffest K, in order.
    """
    k_max = max(k[n] for n in numbers)
    return [n for n in numbers if k[n] >= k_max * (1 - 1e-9)]


def sensing_units(plan: Plan, k_nominal: np.ndarray,
                  reference: int | None = None) -> list[tuple[int, int]]:
    """(measuring element, reference element) pairs, paper numbering.

    Args:
        plan: the design.
        k_nominal: nominal K per element (N/mm), element order.
        reference: one of the design's reference elements (:func:`reference_elements`)
            to serve as the reference of every unit; ``None``: each measuring element
            paired with the nearest reference (see the module docstring).

    Returns:
        one (measuring, reference) pair per element that is no reference.

    Raises:
        DesignError: ``reference`` is no element, or not one of the reference elements
            (the refusal names those it accepts).
    """
    numbers = [s.number for s in plan.slots]
    k = dict(zip(numbers, np.asarray(k_nominal, float)))
    refs = reference_elements(numbers, k)
    measuring = [n for n in numbers if n not in refs]
    if reference is not None:
        plan.element(reference)
        if reference not in refs:
            raise DesignError(
                "reference", reference,
                "one of the design's reference elements (the nominally stiffest): "
                + " or ".join(f"--reference {r}" for r in refs),
                f"element {reference} is softer than element {refs[0]}",
                alternatives=[{"option": f"--reference {r}",
                               "words": f"element {r} the reference of every unit"}
                              for r in refs])
        return [(n, reference) for n in measuring]
    tips = {s.number: np.array(s.tip_centre_world_mm) for s in plan.slots}
    units = []
    for n in measuring:
        nearest = min(refs, key=lambda r: (round(float(np.linalg.norm(tips[n] - tips[r])), 9), r))
        units.append((n, nearest))
    return units


def sample_statistics(x: np.ndarray) -> dict:
    """mean, std and the 2.5/97.5 % percentiles of the finite entries of ``x`` (JSON floats;
    each None where none is finite): a Monte Carlo's figures of one quantity."""
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": None, "std": None, "p2_5": None, "p97_5": None}
    lo, hi = np.percentile(x, [2.5, 97.5])
    return {"mean": float(x.mean()), "std": float(x.std(ddof=1)) if x.size > 1 else 0.0,
            "p2_5": float(lo), "p97_5": float(hi)}


@dataclass(frozen=True)
class ChunkSpec:
    """One independently seeded chunk of a Monte Carlo run (picklable)."""

    plan: Plan
    tolerances: Tolerances
    n: int
    seed: np.random.SeedSequence
    correction: Correction


def chunk_specs(plan: Plan, tol: Tolerances, n: int, seed: int,
                correction: Correction | None = None,
                chunk: int = CHUNK_SAMPLES) -> list[ChunkSpec]:
    """Split ``n`` samples into seeded chunks; the split depends on n, seed
    and ``chunk`` only, never on where the chunks run.

    Raises:
        DesignError: ``n`` outside :data:`SAMPLES_RANGE`, or a negative seed.
    """
    least, most = SAMPLES_RANGE
    if isinstance(n, bool) or not isinstance(n, int) or not least <= n <= most:
        raise DesignError("samples", n, f"an integer {least} ... {most}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise DesignError("seed", seed, "an integer >= 0")
    corr = load_correction() if correction is None else correction
    sizes = [chunk] * (n // chunk) + ([n % chunk] if n % chunk else [])
    seeds = np.random.SeedSequence(seed).spawn(len(sizes))
    return [ChunkSpec(plan, tol, k, s, corr) for k, s in zip(sizes, seeds)]


def run_chunk(spec: ChunkSpec) -> dict[str, np.ndarray]:
    """Draw one chunk and evaluate K: ``{"K": (n, m), "E": (n, 1), "web": (n, m)}``."""
    s = chunk_samples(spec)
    return {"K": stiffness_samples(spec.plan, s, spec.correction), "E": s.youngs_modulus_MPa,
            "web": s.web_mm}


def web_tolerance_for_band(g: ElementGeometry, material: Material, correction: Correction,
                           band_rel: float = K_BAND_REL) -> float:
    """Largest symmetric web tolerance (mm) that keeps K within +/-``band_rel``.

    K rises faster than linearly with the web (about t^2.5 for a thin hinge),
    so the thin side limits it: the result is min(t_+ - t, t - t_-) with
    K(t_+) = (1 + band) K(t) and K(t_-) = (1 - band) K(t), solved with
    scipy ``brentq``.
    """
    t0 = g.web_thickness_mm

    def k_of(t: float) -> float:
        return float(corrected_stiffness(t, g.notch_radius_mm, g.arm_length_mm,
                                         material.youngs_modulus_MPa, g, material.poisson_ratio,
                                         correction))

    k0 = k_of(t0)
    from scipy.optimize import brentq  # here: `tactcad --help` need not load scipy.optimize

    up = brentq(lambda t: k_of(t) - (1 + band_rel) * k0, t0, 2 * t0, xtol=1e-12)
    down = brentq(lambda t: k_of(t) - (1 - band_rel) * k0, 0.5 * t0, t0, xtol=1e-12)
    return float(min(up - t0, t0 - down))


@dataclass(frozen=True)
class ToleranceReport:
    """Everything ``tactcad tolerance`` prints; :meth:`as_json` is its JSON."""

    samples: int
    seed: int
    tolerances: Tolerances
    elements: list[dict]
    units: list[dict]
    web_tolerance: list[dict]
    correction_source: str = ""
    notes: list[str] = field(default_factory=list)
    #: Table 1's equal-arm spread, added by a caller that compares with the
    #: paper (:func:`tactcad.paper.table1.equal_arm_spread`); empty otherwise.
    table1_spread: list[dict] = field(default_factory=list)

    def as_json(self) -> dict:
        t = self.tolerances
        return {"samples": self.samples, "seed": self.seed,
                "tolerances": {"web_mm": t.web_mm, "notch_radius_mm": t.notch_radius_mm,
                               "arm_length_mm": t.arm_length_mm, "modulus_rel": t.modulus_rel,
                               "sheet_mm": t.sheet_mm,
                               "distribution": t.distribution, "description": t.describe()},
                "elements": self.elements, "units": self.units,
                "web_tolerance_for_5pct_K": self.web_tolerance,
                "table1_equal_arm_spread": self.table1_spread,
                "correction_source": self.correction_source, "notes": self.notes}


def summarise(plan: Plan, chunks: Sequence[dict[str, np.ndarray]], tol: Tolerances, seed: int,
              correction: Correction, k_obj: Iterable[float] = DEFAULT_K_OBJ_N_PER_MM,
              reference: int | None = None) -> ToleranceReport:
    """Statistics of evaluated chunks (in chunk order): K per element, R and
    the reported K_obj per unit at each true K_obj and the web tolerance for a
    +/-5 % K band.

    Raises:
        DesignError: a K_obj that is not finite and > 0; a bad ``reference``.
    """
    k = np.concatenate([c["K"] for c in chunks], axis=0)
    k_nom = nominal_stiffness(plan, correction)
    numbers = [s.number for s in plan.slots]
    col = {num: i for i, num in enumerate(numbers)}
    elements = element_statistics(plan, k, k_nom)
    units = []
    k_obj = [_check_k_obj(x) for x in k_obj]
    for m, r in sensing_units(plan, k_nom, reference):
        km_nom, kr_nom = float(k_nom[col[m]]), float(k_nom[col[r]])
        km, kr = k[:, col[m]], k[:, col[r]]
        for ko in k_obj:
            ratio = deflection_ratio(km, kr, np.full_like(km, ko))
            reported = object_stiffness(ratio.value, np.full_like(km, km_nom),
                                        np.full_like(km, kr_nom))
            rep = reported.value
            units.append({"measuring": m, "reference": r, "K_obj_true_N_per_mm": ko,
                          "R_nominal": deflection_ratio(km_nom, kr_nom, ko),
                          "R": sample_statistics(ratio.value),
                          "K_obj_reported_N_per_mm": sample_statistics(rep),
                          "K_obj_error_rel": sample_statistics((rep - ko) / ko),
                          "fraction_outside_eq3_domain": float(1.0 - np.mean(reported.valid))})
    webs = []
    for name, g in plan.distinct_elements.items():
        webs.append({"part": name, "arm_length_mm": g.arm_length_mm,
                     "web_mm": g.web_thickness_mm,
                     "design_web_tolerance_mm": g.web_tolerance_mm,
                     "web_tolerance_for_5pct_K_mm": web_tolerance_for_band(g, plan.material,
                                                                           correction)})
    notes = ["K_obj reported = eq. 3 with the nominal K_m, K_r (no per-element calibration); "
             "R from eq. 2 with the drawn K_m, K_r.",
             "E is drawn once per array (one sheet); web, notch radius and arm per element."]
    return ToleranceReport(samples=int(k.shape[0]), seed=seed, tolerances=tol, elements=elements,
                           units=units, web_tolerance=webs,
                           correction_source=correction.source, notes=notes)


def element_statistics(plan: Plan, k: np.ndarray, k_nominal: np.ndarray) -> list[dict]:
    """Each element's K statistics over the drawn arrays, as :func:`summarise` reports them.

    Args:
        plan: the design. k: K (N/mm) of every sample and element, array (n, m), element
            order. k_nominal: nominal K (N/mm) per element, array (m,).

    Returns:
        One dict per element: its number, arm (mm), nominal K, relative std and the mean,
        std and 2.5/97.5 % percentiles of K (N/mm).
    """
    elements = []
    for i, (slot, kn) in enumerate(zip(plan.slots, k_nominal)):
        stats = sample_statistics(k[:, i])
        elements.append({"element": slot.number,
                         "arm_length_mm": plan.element(slot.number).geometry.arm_length_mm,
                         "K_nominal_N_per_mm": float(kn),
                         "K_rel_std": stats["std"] / float(kn),
                         **{f"K_{key}_N_per_mm": v for key, v in stats.items()}})
    return elements


def element_band_report(plan: Plan, samples: int = MONTE_CARLO_SAMPLES,
                        seed: int = MONTE_CARLO_SEED, tolerances: Tolerances | None = None,
                        correction: Correction | None = None) -> ToleranceReport:
    """:func:`run_tolerance`'s report with its elements' K statistics alone (no sensing
    units, no web tolerance for a 5 % band: a K band check reads neither), drawn and
    evaluated as :func:`run_tolerance` draws them, so each element's figures are the same
    numbers.

    Args:
        plan: the design. samples, seed, tolerances, correction: as :func:`run_tolerance`.

    Returns:
        :class:`ToleranceReport` with ``units`` and ``web_tolerance`` empty. A pure
        function of the plan's elements (numbers and geometries), material and sheet, the
        samples, seed, tolerances and correction: kept per process by those
        (:data:`BAND_REPORTS_KEPT` at most), each caller given its own copy.

    Raises:
        DesignError: bad samples or seed (field named).

    Source: JCGM 101:2008 (95 % coverage interval from the 2.5 and 97.5 percentiles).
    """
    tol = Tolerances.of_plan(plan) if tolerances is None else tolerances
    corr = load_correction() if correction is None else correction
    # everything of the plan the draw and its statistics read
    key = (tuple((s.number, s.geometry) for s in plan.slots), plan.material,
           plan.sheet_thickness_mm, samples, seed, tol, corr)
    with _BAND_REPORTS_LOCK:
        kept = _BAND_REPORTS.get(key)
        if kept is not None:
            _BAND_REPORTS.move_to_end(key)
    if kept is None:
        specs = chunk_specs(plan, tol, samples, seed, corr)
        k = np.concatenate([run_chunk(spec)["K"] for spec in specs], axis=0)
        elements = element_statistics(plan, k, nominal_stiffness(plan, specs[0].correction))
        kept = ToleranceReport(samples=int(k.shape[0]), seed=seed, tolerances=tol,
                               elements=elements, units=[], web_tolerance=[],
                               correction_source=specs[0].correction.source)
        with _BAND_REPORTS_LOCK:
            _BAND_REPORTS[key] = kept
            while len(_BAND_REPORTS) > BAND_REPORTS_KEPT:
                _BAND_REPORTS.popitem(last=False)
    return replace(kept, elements=[dict(e) for e in kept.elements], units=[],
                   web_tolerance=[], notes=[], table1_spread=[])


#: Most :func:`element_band_report` answers kept in a process (least recently used dropped
#: first): a design search verifies a candidate, then the design it writes of it, with the
#: same elements; a report holds a few numbers per element.
BAND_REPORTS_KEPT = 256
_BAND_REPORTS: "OrderedDict[tuple, ToleranceReport]" = OrderedDict()
_BAND_REPORTS_LOCK = threading.Lock()  # a Dask worker may run tasks on several threads


def _check_k_obj(x) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x <= 0:
        raise DesignError("kobj", x, "a finite object stiffness > 0 N/mm")
    return float(x)


def run_tolerance(plan: Plan, samples: int = 10_000, seed: int = 0,
                  tolerances: Tolerances | None = None,
                  k_obj: Iterable[float] = DEFAULT_K_OBJ_N_PER_MM,
                  reference: int | None = None, correction: Correction | None = None,
                  mapper: Callable = map) -> ToleranceReport:
    """Tolerance Monte Carlo of a design at the corrected closed form.

    Args:
        plan: the design.
        samples: number of as-built arrays drawn (2 ... 10^7).
        seed: seed of the draw (>= 0); equal seeds give equal numbers.
        tolerances: default :meth:`Tolerances.of_plan` (design web tolerance
            plus the documented defaults).
        k_obj: true object stiffnesses to report the K_obj band at (N/mm).
        reference: force one reference element for every unit.
        correction: default: the stored FEM-fitted correction.
        mapper: ``map``-like callable evaluating :func:`run_chunk` over the
            chunk specs in order (builtin ``map`` here, Dask in
            :mod:`tactcad.studies.sweeps`).

    Returns:
        :class:`ToleranceReport`.

    Raises:
        DesignError: bad samples, seed, K_obj or reference (field named).
    """
    tol = Tolerances.of_plan(plan) if tolerances is None else tolerances
    specs = chunk_specs(plan, tol, samples, seed, correction)
    corr = specs[0].correction
    chunks = list(mapper(run_chunk, specs))
    return summarise(plan, chunks, tol, seed, corr, k_obj, reference)

