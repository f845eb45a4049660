"""Monte Carlo of a silicon die's process tolerances: each row's beam K, each unit's R and
the K_obj it reads.

The die's own process tolerances, as its budget
(:mod:`tactcad.products.silicon_die.in_use.die_budget`) states them, are drawn per die:

* device layer: the SOI maker's +- on the layer's thickness
  (``plan.stack.device_tolerance_um``), one thickness for both rows (K ~ t^3);
* cavity alignment: the front masks' shift against the buried cavities
  (:data:`~tactcad.products.silicon_die.vocabulary.soi_process.CAVITY_ALIGNMENT_UM`),
  which lengthens every measuring beam and shortens every reference beam by the same
  shift, as the budget takes it (K ~ (L + dL)^-3).

Each row's K is the die's closed form on every drawn die
(:func:`tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`: Euler-Bernoulli
over L + dL with Timoshenko's shear, Timoshenko and Gere). Each unit (a measuring beam and
the reference beam of its column) is pressed with every post into one tissue, as the
budget's unit is (rigid flat punches on a half-space, :mod:`tactcad.in_use.tissue_coupling`):
R = e_m / e_r is eq. 2 corrected for the coupling, and the K_obj read is the coupled
inversion (eq. 3 corrected) with the die's nominal K_r and K_m, as a corrected die reads.
A +- bound is drawn uniform over it (the budget's sigma, bound / sqrt 3) or normal with
the bound at 3 sigma (the metal arrays' default).

Units: um for the die's features, N/mm for K and K_obj; R dimensionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tactcad.studies.tolerance_montecarlo import sample_statistics
from tactcad.in_use.tissue_coupling import coupled_deflections
from tactcad.errors import DesignError

#: Drawn dies per chunk: the batched solves of a chunk (and the K_obj read from them) stay a
#: few tens of MB, whatever the dies drawn.
CHUNK_SAMPLES = 20_000
#: Dies a Monte Carlo draws (``tolerance --samples`` on a die): every drawn die's K, coupled R
#: and K_obj read are kept for the percentiles, and each die is a coupled solve per true
#: K_obj (10^6 dies of the shipped 2 x 5 die: about 1.5 min and 0.34 GB at the peak on one
#: core); the K_obj read's std and 95 % interval move by at most 0.2 % from 10^5 to 10^6.
DIE_SAMPLES_RANGE = (2, 1_000_000)
#: Points of the nominal R(K_obj) table the inversion starts from (log-spaced over its
#: bracket); two Newton steps on the coupled model follow.
INVERSION_TABLE_POINTS = 4001
#: The draws a +- bound may take: uniform over it (the budget's) or normal at 3 sigma.
DISTRIBUTIONS = ("uniform", "normal")


@dataclass(frozen=True)
class DieTolerances:
    """The die's process tolerances drawn (+- um) and how.

    Attributes:
        device_um: the device layer's thickness tolerance (+- um).
        alignment_um: the front masks' alignment to the cavities (+- um).
        distribution: ``uniform`` over +- the bound, or ``normal`` with the bound 3 sigma.
    """

    device_um: float
    alignment_um: float
    distribution: str = "uniform"

    @classmethod
    def of_plan(cls, plan, distribution: str = "uniform") -> "DieTolerances":
        """The tolerances where the die's budget reads them: the plan's SOI stack (device
        layer) and the process's cavity alignment
        (:data:`~tactcad.products.silicon_die.vocabulary.soi_process.CAVITY_ALIGNMENT_UM`).

        Raises:
            DesignError: ``distribution`` not one of :data:`DISTRIBUTIONS`.
        """
        from tactcad.products.silicon_die.vocabulary import soi_process

        if distribution not in DISTRIBUTIONS:
            raise DesignError("--distribution", distribution, " or ".join(DISTRIBUTIONS))
        return cls(float(plan.stack.device_tolerance_um), float(soi_process.CAVITY_ALIGNMENT_UM),
                   distribution)

    @property
    def sigma_over_bound(self) -> float:
        """One sigma of a draw over its +- bound: 1/sqrt 3 (uniform) or 1/3 (normal)."""
        return 1 / math.sqrt(3) if self.distribution == "uniform" else 1 / 3

    def describe(self) -> str:
        """The tolerances in words, e.g. ``device layer +-0.5 um, cavity alignment +-2 um
        (uniform over +-tolerance)``."""
        how = ("uniform over +-tolerance, as the die's budget takes it"
               if self.distribution == "uniform" else "normal, tolerance = 3 sigma")
        return (f"device layer +-{self.device_um:g} um, cavity alignment "
                f"+-{self.alignment_um:g} um ({how})")

    def as_json(self) -> dict:
        """The tolerances (um), their distribution and their words, for ``--json``."""
        return {"device_layer_um": self.device_um, "cavity_alignment_um": self.alignment_um,
                "distribution": self.distribution, "description": self.describe()}


def check_die_samples(samples: int) -> int:
    """``samples`` when a die's Monte Carlo takes that many dies (:data:`DIE_SAMPLES_RANGE`).

    Args:
        samples: the dies asked (``--samples``).

    Returns:
        ``samples``.

    Raises:
        DesignError: ``--samples`` outside the range, naming it and why it ends there.
    """
    lo, hi = DIE_SAMPLES_RANGE
    if not lo <= samples <= hi:
        raise DesignError("--samples", samples, f"an integer {lo} ... {hi} (dies drawn)",
                          "a die's Monte Carlo keeps every drawn die's K, R and K_obj read for "
                          "its percentiles and solves each die's tissue coupling: 10^6 dies "
                          "take minutes and settle the statistics")
    return samples


def draw_offsets_um(tol: DieTolerances, samples: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Each drawn die's device-layer offset and cavity shift (um), seeded.

    Args:
        tol: the tolerances and their distribution.
        samples: dies drawn (>= 2). seed: the generator's seed (numpy's default_rng).

    Returns:
        (dt, dl), each shape (samples,): the layer's thickness minus nominal and the
        masks' shift (um; the measuring beams longer by dl, the reference beams shorter).
    """
    rng = np.random.default_rng(seed)
    if tol.distribution == "uniform":
        unit = rng.uniform(-1.0, 1.0, size=(2, samples))
    else:
        unit = rng.standard_normal(size=(2, samples)) / 3.0
    return tol.device_um * unit[0], tol.alignment_um * unit[1]


def row_stiffness_N_per_mm(plan, beam, dt_um: np.ndarray, dl_um: np.ndarray) -> np.ndarray:
    """K (N/mm) of ``beam``'s row on every drawn die, by the die's closed form
    (:func:`~tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`) at the
    drawn thickness t + dt and length L + dl (measuring) or L - dl (reference).

    Args:
        plan: the die's plan. beam: a beam of the row.
        dt_um, dl_um: the drawn offsets (um), as :func:`draw_offsets_um` gives them.

    Returns:
        K per drawn die (N/mm), the shape of ``dt_um``.
    """
    from tactcad.products.silicon_die.design.mems_die import beam_stiffnesses_N_per_mm

    sign = 1.0 if beam.role == "measuring" else -1.0
    return beam_stiffnesses_N_per_mm(plan.youngs_modulus_MPa, beam.width_um,
                                     beam.thickness_um + np.asarray(dt_um, dtype=float),
                                     beam.length_um + sign * np.asarray(dl_um, dtype=float))


def die_units(plan) -> list[tuple[int, int]]:
    """Each column's (measuring, reference) beam numbers, left to right.

    Args:
        plan: the die's plan (its beams: the reference row, then the measuring row).

    Returns:
        [(measuring, reference)] per column.
    """
    return [(plan.beams[plan.columns + c].number, plan.beams[c].number)
            for c in range(plan.columns)]


def die_sample(plan):
    """Every post of ``plan`` on one tissue: rigid flat punches of the posts' faces on a
    half-space (:func:`tactcad.in_use.tissue_coupling.coupled_sample_from_punches`, the
    default :class:`~tactcad.in_use.tissue_coupling.Tissue`), as the die's budget presses
    its unit.

    Args:
        plan: the die's plan (post side and tip positions, um).

    Returns:
        :class:`~tactcad.in_use.tissue_coupling.CoupledSample`, its posts in the plan's
        beams' order.
    """
    from tactcad.in_use.tissue_coupling import Tissue, coupled_sample_from_punches
    from tactcad.mechanics.contact import Punch

    side = plan.post_um * 1e-3
    punches = [Punch(b.x_um * 1e-3, b.tip_y_um * 1e-3, side, side) for b in plan.beams]
    return coupled_sample_from_punches([b.number for b in plan.beams], punches, Tissue())


@dataclass(frozen=True)
class _Inverse:
    """The nominal die's coupled R(K_obj) of one unit, tabulated for its inversion."""

    c_hat: np.ndarray
    k_nominal: np.ndarray
    im: int
    ir: int
    log_k: np.ndarray
    r: np.ndarray

    def ratio(self, k_obj: np.ndarray) -> np.ndarray:
        k = np.broadcast_to(self.k_nominal, (k_obj.size, self.k_nominal.size))
        e = coupled_deflections(self.c_hat, k, k_obj)
        return e[:, self.im] / e[:, self.ir]

    def read(self, r: np.ndarray) -> np.ndarray:
        """K_obj (N/mm) whose nominal coupled R is ``r``; nan where no K_obj in the bracket
        gives it."""
        inside = np.isfinite(r) & (r >= self.r[-1]) & (r <= self.r[0])
        log_k = np.interp(r, self.r[::-1], self.log_k[::-1])
        slope = np.gradient(self.r, self.log_k)
        for _ in range(2):  # Newton on ln K_obj from the table's point
            k = np.exp(np.clip(log_k, self.log_k[0], self.log_k[-1]))
            local = np.interp(log_k, self.log_k, slope)
            log_k = log_k + (r - self.ratio(k)) / local
        return np.where(inside, np.exp(log_k), np.nan)


def _inverse(c_hat: np.ndarray, k_nominal: np.ndarray, im: int, ir: int) -> _Inverse:
    # the bracket coupled_object_stiffness searches: K_m / 1000 ... 1000 K_r
    from tactcad.in_use.tissue_coupling import INVERSION_BRACKET

    lo, hi = k_nominal[im] / INVERSION_BRACKET, k_nominal[ir] * INVERSION_BRACKET
    log_k = np.linspace(math.log(lo), math.log(hi), INVERSION_TABLE_POINTS)
    table = _Inverse(c_hat, k_nominal, im, ir, log_k, np.empty(0))
    return _Inverse(c_hat, k_nominal, im, ir, log_k, table.ratio(np.exp(log_k)))


def kobj_bracket_N_per_mm(plan) -> tuple[float, float]:
    """The K_obj the die's coupled inversion reads (N/mm): K_m / 1000 ... 1000 K_r
    (:data:`tactcad.in_use.tissue_coupling.INVERSION_BRACKET`).

    Args:
        plan: the die's plan (its nominal K_r, K_m, N/mm).

    Returns:
        (lo, hi) in N/mm.
    """
    from tactcad.in_use.tissue_coupling import INVERSION_BRACKET

    return (plan.k_m_N_per_mm / INVERSION_BRACKET, plan.k_r_N_per_mm * INVERSION_BRACKET)


def check_kobj(plan, k_obj) -> list[float]:
    """The true K_obj values (N/mm) a die's Monte Carlo reports, each inside what its coupled
    inversion reads (:func:`kobj_bracket_N_per_mm`).

    Args:
        plan: the die's plan. k_obj: the values asked (N/mm, ``--kobj``).

    Returns:
        The values as floats.

    Raises:
        DesignError: ``--kobj`` with a value outside that range (named with it).
    """
    lo, hi = kobj_bracket_N_per_mm(plan)
    for k in k_obj:
        if not (math.isfinite(k) and lo < k < hi):
            raise DesignError("--kobj", k, f"{lo:.4g} < K_obj < {hi:.4g} N/mm",
                              "the die's coupled inversion searches K_m / 1000 ... 1000 K_r")
    return [float(k) for k in k_obj]


@dataclass(frozen=True)
class DieToleranceReport:
    """The die's tolerance Monte Carlo (N/mm, um).

    Attributes:
        samples, seed: the draw. tolerances: :class:`DieTolerances`.
        rows: each row's K statistics (keys as the metal arrays' elements).
        units: each unit at each true K_obj: R and the K_obj read (N/mm).
        budget_check: the middle unit's K_obj spread against the budget's device-layer and
            cavity-alignment terms at the budget's K_obj values.
    """

    samples: int
    seed: int
    tolerances: DieTolerances
    rows: list
    units: list
    budget_check: dict

    def as_json(self) -> dict:
        return {"samples": self.samples, "seed": self.seed,
                "tolerances": self.tolerances.as_json(), "rows": self.rows,
                "units": self.units, "budget_check": self.budget_check}


def _row_record(role: str, beams: list[int], k: np.ndarray, k_nominal: float) -> dict:
    stats = sample_statistics(k)
    return {"row": role, "beams": beams, "K_nominal_N_per_mm": k_nominal,
            "K_rel_std": stats["std"] / k_nominal,
            **{f"K_{key}_N_per_mm": v for key, v in stats.items()}}


def _unit_record(unit: tuple[int, int], k_obj: float, r_nominal: float, r: np.ndarray,
                 read: np.ndarray) -> dict:
    from tactcad.in_use.tissue_coupling import unit_label

    stats = sample_statistics(read)
    return {"unit": unit_label(unit), "measuring": unit[0], "reference": unit[1],
            "K_obj_true_N_per_mm": k_obj, "R_nominal": r_nominal, "R": sample_statistics(r),
            "K_obj_reported_N_per_mm": stats,
            "K_obj_rel_std": None if stats["std"] is None else stats["std"] / k_obj,
            "K_obj_mean_error_rel": None if stats["mean"] is None else stats["mean"] / k_obj - 1,
            "fraction_unreadable": float(np.mean(~np.isfinite(read)))}


def run_die_tolerance(plan, samples: int, seed: int, tolerances: DieTolerances | None = None,
                      k_obj=None) -> DieToleranceReport:
    """The die's tolerance Monte Carlo (see the module doc).

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`.
        samples: dies drawn (>= 2). seed: the draw's seed.
        tolerances: default :meth:`DieTolerances.of_plan` (uniform, as the budget).
        k_obj: true K_obj values (N/mm); default the die's K_obj range's ends and its
            geometric centre (the budget's).

    Returns:
        :class:`DieToleranceReport`.

    Raises:
        DesignError: a K_obj outside what the inversion reads (``--kobj``), or ``samples``
            outside :data:`DIE_SAMPLES_RANGE` (``--samples``).
    """
    check_die_samples(samples)
    tol = tolerances or DieTolerances.of_plan(plan)
    budget_ks = budget_kobj_N_per_mm(plan)
    ks = check_kobj(plan, budget_ks if k_obj is None else k_obj)
    dt, dl = draw_offsets_um(tol, samples, seed)
    ref, meas = plan.beams[0], plan.beams[plan.columns]
    k_rows = {"reference": row_stiffness_N_per_mm(plan, ref, dt, dl),
              "measuring": row_stiffness_N_per_mm(plan, meas, dt, dl)}
    roles = [b.role for b in plan.beams]
    k_nominal = np.array([plan.k_r_N_per_mm if r == "reference" else plan.k_m_N_per_mm
                          for r in roles])
    rows = [_row_record(role, [b.number for b in plan.beams if b.role == role], k_rows[role],
                        float(k_nominal[roles.index(role)])) for role in ("reference", "measuring")]
    sample = die_sample(plan)
    index = {n: i for i, n in enumerate(sample.numbers)}
    is_reference = np.array(roles) == "reference"  # the sample's posts in plan.beams' order
    units = die_units(plan)
    inverses = {u: _inverse(sample.normalised, k_nominal, index[u[0]], index[u[1]])
                for u in units}
    records, middle = [], units[plan.columns // 2]
    middle_read = {}
    for k in sorted(set(ks) | set(budget_ks)):
        wanted = units if k in ks else [middle]
        drawn = _chunked_reads(sample.normalised, k_rows, is_reference, k,
                               [(index[m], index[r]) for m, r in wanted],
                               [inverses[u] for u in wanted])
        for u, (r, read) in zip(wanted, drawn):
            if u == middle:
                middle_read[k] = read
            if k in ks:
                r_nom = float(inverses[u].ratio(np.array([k]))[0])
                records.append(_unit_record(u, k, r_nom, r, read))
    records.sort(key=lambda rec: (ks.index(rec["K_obj_true_N_per_mm"]), units.index(
        (rec["measuring"], rec["reference"]))))
    check = budget_check(plan, tol, middle, budget_ks, [middle_read[k] for k in budget_ks])
    return DieToleranceReport(samples, seed, tol, rows, records, check)


def _chunked_reads(c_hat: np.ndarray, k_rows: dict, is_reference: np.ndarray, k_obj: float,
                   pairs: list[tuple[int, int]],
                   inverses: list[_Inverse]) -> list[tuple[np.ndarray, np.ndarray]]:
    # each pair's (measuring, reference indices) coupled R on every drawn die and the K_obj
    # its inverse reads from it, both worked out CHUNK_SAMPLES dies at a time: the solves and
    # the inversion's Newton steps (one (m, m) system per die) never hold more than a chunk
    n = len(k_rows["reference"])
    ratios = [np.empty(n) for _ in pairs]
    reads = [np.empty(n) for _ in pairs]
    for i in range(0, n, CHUNK_SAMPLES):
        part = slice(i, i + CHUNK_SAMPLES)
        k = np.where(is_reference, k_rows["reference"][part, None],
                     k_rows["measuring"][part, None])
        e = coupled_deflections(c_hat, k, np.full(len(k), k_obj))
        for r, read, inverse, (im, ir) in zip(ratios, reads, inverses, pairs):
            r[part] = e[:, im] / e[:, ir]
            read[part] = inverse.read(r[part])
    return list(zip(ratios, reads))


def budget_kobj_N_per_mm(plan) -> list[float]:
    """The K_obj values the die's budget is given at (N/mm): its range's ends and their
    geometric mean (:func:`tactcad.products.silicon_die.in_use.die_budget.die_budget`).

    Args:
        plan: the die's plan (its ``kobj_range_N_per_mm``).

    Returns:
        [lo, sqrt(lo hi), hi] in N/mm.
    """
    lo, hi = plan.kobj_range_N_per_mm
    return [float(lo), math.sqrt(lo * hi), float(hi)]


def thickness_exponent(plan, beam, step_um: float = 1e-4) -> float:
    """d ln K / d ln t of ``beam`` by the die's closed form (central difference over
    +-``step_um`` um): 3 for K ~ t^3 alone, a little less with the root's give (dL ~ t) and
    shear (:func:`~tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`).

    Args:
        plan: the die's plan. beam: a beam of the row. step_um: the difference's step (um).

    Returns:
        The exponent (dimensionless).
    """
    k = row_stiffness_N_per_mm(plan, beam, np.array([-step_um, step_um]), np.zeros(2))
    return float(math.log(k[1] / k[0]) / (2 * step_um / beam.thickness_um))


def budget_check(plan, tol: DieTolerances, unit: tuple[int, int], ks: list[float],
                 reads: list[np.ndarray]) -> dict:
    """The middle unit's K_obj spread against the die budget's root sum square of its
    device-layer and cavity-alignment terms (each 1 sigma of a uniform +- bound,
    :func:`~tactcad.products.silicon_die.in_use.die_budget.die_budget`), the budget's terms
    scaled to the drawn sigma (a normal draw: sqrt 3 / 3 of the uniform's).

    Args:
        plan: the die. tol: the drawn tolerances. unit: the budget's (middle) unit.
        ks: the budget's K_obj values (N/mm). reads: the K_obj read on every drawn die at
            each of ``ks`` (N/mm).

    Returns:
        A dict: the K_obj values, the Monte Carlo's relative std, each budget term, their
        root sum square and the ratio Monte Carlo / budget at each K_obj.
    """
    from tactcad.in_use.tissue_coupling import unit_label
    from tactcad.products.silicon_die.in_use.die_budget import die_budget

    budget = die_budget(plan)
    scale = tol.sigma_over_bound * math.sqrt(3)
    device = [scale * float(v) for v in budget.terms["device layer"]]
    alignment = [scale * float(v) for v in budget.terms["cavity alignment"]]
    rss = [math.hypot(a, b) for a, b in zip(device, alignment)]
    mc = [float(np.nanstd(x, ddof=1)) / k for x, k in zip(reads, ks)]
    return {"unit": unit_label(unit), "K_obj_N_per_mm": list(ks), "monte_carlo_rel_std": mc,
            "budget_device_layer_rel": device, "budget_cavity_alignment_rel": alignment,
            "budget_rss_rel": rss,
            "ratio": [m / b if b > 0 else None for m, b in zip(mc, rss)],
            "closed_form_dlnK_dlnt": {b.role: thickness_exponent(plan, b) for b in
                                      (plan.beams[0], plan.beams[plan.columns])},
            "note": "the budget's terms at its own tolerances, each 1 sigma of the bound "
                    "taken uniform" + ("" if tol.distribution == "uniform" else
                                       ", scaled to the normal draw's sigma (bound / 3)")
                    + "; the budget takes K ~ t^3, the closed form a little less"}


def report_lines(name: str, report: DieToleranceReport, seconds: float) -> list[str]:
    """The report as text: the rows' K, each unit's R and K_obj read, the budget check.

    Args:
        name: the die's name. report: :func:`run_die_tolerance`'s. seconds: its wall time.
    """
    lines = [f"tolerance Monte Carlo of die {name}: {report.samples} samples, seed "
             f"{report.seed}, {seconds:.2f} s",
             f"  {report.tolerances.describe()}",
             "K per row (N/mm, the closed form): nominal, mean, std, 95 % interval"]
    for r in report.rows:
        lines.append(f"  {r['row']:<9} {r['K_nominal_N_per_mm']:8.4g} {r['K_mean_N_per_mm']:8.4g} "
                     f"{r['K_std_N_per_mm']:8.3g} ({100 * r['K_rel_std']:4.2f} %)  "
                     f"[{r['K_p2_5_N_per_mm']:.4g}, {r['K_p97_5_N_per_mm']:.4g}]")
    lines += ["units (measuring/reference): coupled R and the K_obj read at each true K_obj "
              "(eq. 3 corrected for the tissue's coupling, nominal K_r and K_m)",
              f"  {'unit':>6} {'K_obj':>7} {'R nom':>8} {'R mean':>8} {'R std':>8}  "
              f"{'K_obj mean':>10} {'std':>8} {'rel std':>8} {'95 % interval':>19} "
              f"{'unreadable':>10}"]
    for u in report.units:
        k = u["K_obj_reported_N_per_mm"]
        if k["mean"] is None:
            read = f"{'n/a':>10} {'':>8} {'':>8} {'n/a':>19}"
        else:
            read = (f"{k['mean']:10.4g} {k['std']:8.3g} {100 * u['K_obj_rel_std']:6.2f} % "
                    f"{'[' + format(k['p2_5'], '.4g') + ', ' + format(k['p97_5'], '.4g') + ']':>19}")
        lines.append(f"  {u['unit']:>6} {u['K_obj_true_N_per_mm']:7.4g} {u['R_nominal']:8.4f} "
                     f"{u['R']['mean']:8.4f} {u['R']['std']:8.4f}  {read} "
                     f"{100 * u['fraction_unreadable']:9.1f}%")
    c = report.budget_check
    lines.append(f"against the die's budget (unit {c['unit']}, the budget's): K_obj relative "
                 "std, Monte Carlo / root sum square of the device-layer and cavity-alignment "
                 "terms")
    for k, m, d, a, b, q in zip(c["K_obj_N_per_mm"], c["monte_carlo_rel_std"],
                                c["budget_device_layer_rel"], c["budget_cavity_alignment_rel"],
                                c["budget_rss_rel"], c["ratio"]):
        lines.append(f"  K_obj {k:.4g} N/mm: {100 * m:.3f} % / {100 * b:.3f} % (device "
                     f"{100 * d:.3f} %, alignment {100 * a:.3f} %), ratio {q:.3f}")
    exponents = ", ".join(f"{e:.3g} {role}" for role, e in c["closed_form_dlnK_dlnt"].items())
    lines.append(f"  the budget takes K ~ t^3; the closed form's d ln K / d ln t is {exponents} "
                 "(the root's give grows with t, and shear): the Monte Carlo's spread is the "
                 "smaller")
    if report.tolerances.distribution != "uniform":
        lines.append("  the budget's terms scaled to the normal draw's sigma (bound / 3)")
    return lines
