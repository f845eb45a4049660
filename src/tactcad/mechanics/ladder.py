"""The element-stiffness ladder and its comparison with the paper.

Four levels, cheapest first: ``closed-form`` (exact Euler-Bernoulli notch
integrals + arm bending + shear, FEM-fitted correction), ``beam`` (1D
Timoshenko along the real profile), ``fem2d`` (P2 triangles, plane stress or
strain, Richardson error), ``fem3d`` (P2 tetrahedra, the reference). Every
level returns a :class:`~tactcad.mechanics.result.StiffnessResult` with its
cost (wall time) and error estimate. Heavy modules are imported only when
their level is asked for.

The levels are declared once, in :data:`LEVELS` (:class:`Level`: name,
estimator, whether it meshes, typical cost); every command's ``--model``
choices and help, the strength study, the read-out and the Python API read
it. A new level is one estimator function plus one :func:`register_level`.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

from tactcad.design.array import ElementGeometry, Material, Plan
from tactcad.errors import TactcadError
from tactcad.mechanics.result import StiffnessResult

@dataclass(frozen=True)
class Level:
    """One rung of the stiffness ladder, declared once: every command's
    ``--model`` choices and help, the strength study and the read-out read it.

    Attributes:
        name: the level's name (``--model NAME``).
        module, function: its estimator, imported when the level is asked
            for: ``function(g, material, *, element=None, **options)`` ->
            :class:`~tactcad.mechanics.result.StiffnessResult`.
        meshed: a FEM level: it reports its mesh levels through a
            ``progress`` option, writes fields and gives the peak stress
            from its own mesh; otherwise the closed-form stress formula serves.
        cost: its typical wall time per distinct element, for help texts.
    """

    name: str
    module: str
    function: str
    meshed: bool
    cost: str


#: The ladder, cheapest first (:func:`register_level` adds to it).
LEVELS: dict[str, Level] = {}


def register_level(level: Level) -> None:
    """Add a level to the ladder (after the others).

    Raises:
        ValueError: a level of that name is there already.
    """
    if level.name in LEVELS:
        raise ValueError(f"a ladder level {level.name!r} is registered already")
    LEVELS[level.name] = level


for _level in (Level("closed-form", "tactcad.mechanics.closed_form", "estimate_closed_form",
                     meshed=False, cost="~1 ms"),
               Level("beam", "tactcad.mechanics.beam", "estimate_beam", meshed=False,
                     cost="~10 ms"),
               Level("fem2d", "tactcad.mechanics.fem.fem2d", "estimate_fem2d", meshed=True,
                     cost="~1 s"),
               Level("fem3d", "tactcad.mechanics.fem.fem3d", "estimate_fem3d", meshed=True,
                     cost="~30 s")):
    register_level(_level)


def models() -> tuple[str, ...]:
    """Every ladder level's name, cheapest first."""
    return tuple(LEVELS)


def meshed_models() -> tuple[str, ...]:
    """The FEM levels (:attr:`Level.meshed`)."""
    return tuple(n for n, level in LEVELS.items() if level.meshed)


def is_meshed(model: str) -> bool:
    """True for a FEM level (False for an unknown name)."""
    level = LEVELS.get(model)
    return level is not None and level.meshed


def levels_help() -> str:
    """``closed-form ~1 ms, beam ~10 ms, ...``: the levels with their cost, for help texts."""
    return ", ".join(f"{n} {level.cost}" for n, level in LEVELS.items())


#: The built-in levels' names (what :func:`models` gives before any registration).
MODELS = models()
PAPER_LOAD_N = 2.0  # the paper's FEM design study load on the tip
PAPER_STRAIN_RANGE = (0.2711e-2, 0.6316e-2)  # surface strain at 2 N, arms 4-8 mm


class UnknownModelError(TactcadError, ValueError):
    def __init__(self, model: str):
        super().__init__(f"model = {model!r}: allowed {', '.join(models())}")


def estimate(model: str, g: ElementGeometry, material: Material, *, element: int | None = None,
             **options) -> StiffnessResult:
    """Tip stiffness of one element at the given ladder level.

    ``element`` and the level's ``options`` are keyword-only (each level's
    estimator takes them so).

    Raises:
        UnknownModelError: ``model`` is not a level of :data:`LEVELS`.
    """
    level = LEVELS.get(model)
    if level is None:
        raise UnknownModelError(model)
    return getattr(importlib.import_module(level.module), level.function)(
        g, material, element=element, **options)


@dataclass(frozen=True)
class Table1Row:
    """Predicted against measured stiffness of one element (paper Table 1)."""

    element: int
    arm_length_mm: float
    measured_N_per_mm: float
    predicted: StiffnessResult

    @property
    def error_percent(self) -> float:
        """(predicted - measured) / measured x 100."""
        return 100.0 * (self.predicted.stiffness_N_per_mm - self.measured_N_per_mm) / self.measured_N_per_mm

    def as_json(self) -> dict:
        return {"element": self.element, "arm_length_mm": self.arm_length_mm,
                "measured_N_per_mm": self.measured_N_per_mm,
                "predicted_N_per_mm": self.predicted.stiffness_N_per_mm,
                "error_percent": self.error_percent,
                "error_estimate_rel": self.predicted.error_estimate_rel,
                "gauge_strain_per_N": self.predicted.gauge_strain_per_N,
                "wall_time_s": self.predicted.wall_time_s}


def table1_comparison(plan: Plan, model: str = "closed-form", progress=None) -> list[Table1Row]:
    """Every calibrated element of Table 1 (element 5 has no measurement):
    the plan's geometry at ``model`` level against the measured K.

    Distinct geometries are evaluated once (elements with equal arms share them).
    """
    from tactcad.mechanics.paper.data import table1

    cache: dict[str, StiffnessResult] = {}
    rows = []
    for meas in table1():
        slot = plan.element(meas.element)
        key = slot.geometry.part_name
        if key not in cache:
            if progress:
                progress(f"{model}: {key}")
            cache[key] = estimate(model, slot.geometry, plan.material)
        res = cache[key]
        rows.append(Table1Row(meas.element, slot.geometry.arm_length_mm, meas.stiffness_N_per_mm,
                              StiffnessResult(meas.element, res.model, res.stiffness_N_per_mm,
                                              res.gauge_strain_per_N, res.error_estimate_rel,
                                              res.wall_time_s)))
    return rows


def table1_not_applicable(plan: Plan) -> str | None:
    """Why the paper's Table 1 cannot be compared with ``plan`` (one line), or
    None when it can: the design cites the paper (``requirements.source``),
    has every element Table 1 numbers, and each element's geometry reaches
    its measured K within the closed form's web range (0.05 ... 1 mm)."""
    import warnings

    from tactcad.design.requirements import cites_paper
    from tactcad.mechanics.closed_form import web_for_stiffness
    from tactcad.mechanics.correction import CorrectionRangeWarning
    from tactcad.mechanics.paper.data import table1

    if not cites_paper(plan.raw):
        return "the design does not cite the paper (requirements.source), so Table 1 is not its"
    rows = table1()
    numbers = {slot.number for slot in plan.slots}
    missing = sorted(r.element for r in rows if r.element not in numbers)
    if missing:
        return (f"Table 1 numbers elements up to {max(r.element for r in rows)}; the design has "
                f"{len(numbers)}")
    for meas in rows:
        try:
            with warnings.catch_warnings():  # a probe of reach, not an estimate to warn about
                warnings.simplefilter("ignore", CorrectionRangeWarning)
                web_for_stiffness(meas.stiffness_N_per_mm, plan.element(meas.element).geometry,
                                  plan.material)
        except ValueError as exc:
            return (f"element {meas.element}'s geometry cannot reach Table 1's "
                    f"{meas.stiffness_N_per_mm:g} N/mm at any web ({exc})")
    return None


def require_table1(plan: Plan, option: str = "--design") -> None:
    """Refuse a design Table 1 cannot be compared with (:func:`table1_not_applicable`).

    Raises:
        DesignError: naming ``option``, the design and why.
    """
    from pathlib import Path

    from tactcad.errors import DesignError

    why = table1_not_applicable(plan)
    if why is not None:
        raise DesignError(option, Path(plan.source).name,
                          "a design that cites the paper and can reproduce its Table 1", why)


def as_built_webs(plan: Plan) -> list[dict]:
    """For each calibrated element, the web thickness (mm) that makes the
    corrected closed form reproduce its measured K, and the deviation from the
    design web against the design tolerance (the fabrication spread it implies)."""
    from tactcad.mechanics.closed_form import web_for_stiffness
    from tactcad.mechanics.paper.data import table1

    out = []
    for meas in table1():
        g = plan.element(meas.element).geometry
        t = web_for_stiffness(meas.stiffness_N_per_mm, g, plan.material)
        out.append({"element": meas.element, "measured_N_per_mm": meas.stiffness_N_per_mm,
                    "web_as_built_mm": t, "web_design_mm": g.web_thickness_mm,
                    "deviation_mm": t - g.web_thickness_mm,
                    "within_tolerance": abs(t - g.web_thickness_mm) <= g.web_tolerance_mm})
    return out


def gauge_strain_at_paper_load(plan: Plan, model: str = "closed-form",
                               arms_mm: tuple[float, ...] = (4.0, 5.0, 6.0, 7.0, 8.0)) -> list[dict]:
    """Surface strain at the gauge under the paper's 2 N tip load for each arm
    length, next to the paper's reported 0.2711-0.6316 % range."""
    from dataclasses import replace

    g0 = plan.element(1).geometry
    out = []
    for a in arms_mm:
        r = estimate(model, replace(g0, arm_length_mm=a), plan.material)
        out.append({"arm_length_mm": a, "strain_percent": 100 * PAPER_LOAD_N * r.gauge_strain_per_N})
    return out


def table2_predicted(plan: Plan, model: str = "closed-form") -> dict:
    """Eq. 2 with the ladder's predicted K_m and K_r (element 8) against Table 2's
    48 measured R, reported as it is (nothing tuned to Table 2).

    Rows whose predicted pair leaves eq. 2's domain (K_r <= K_m: element 1 and
    the reference element 8 have the same 4 mm arm, so nominal geometry makes
    them equal) are returned as NaN with ``in_domain`` False.
    """
    import numpy as np

    from tactcad.mechanics.paper.lumped import deflection_ratio
    from tactcad.mechanics.paper.data import table2

    rows = table2()
    k_pred = {r.element: r.predicted.stiffness_N_per_mm for r in table1_comparison(plan, model)}
    k_r = k_pred[8]
    k_m = np.array([k_pred[r.element] for r in rows])
    k_obj = np.array([r.K_obj_N_per_mm for r in rows])
    r_meas = np.array([r.R for r in rows])
    pred = deflection_ratio(k_m, np.full_like(k_m, k_r), k_obj)
    r_pred = np.asarray(pred.value if hasattr(pred, "value") else pred, dtype=float)
    ok = np.isfinite(r_pred)
    err = r_meas - r_pred
    return {"model": model, "k_r_predicted_N_per_mm": k_r,
            "rows": [{"element": r.element, "K_obj_N_per_mm": r.K_obj_N_per_mm,
                      "R_measured": r.R, "R_predicted": float(p), "in_domain": bool(o)}
                     for r, p, o in zip(rows, r_pred, ok)],
            "n_in_domain": int(ok.sum()),
            "mean_abs_error": float(np.mean(np.abs(err[ok]))) if ok.any() else float("nan"),
            "max_abs_error": float(np.max(np.abs(err[ok]))) if ok.any() else float("nan")}
