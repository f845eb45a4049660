"""A metal array's reports as ``tactcad readout``, ``thermal``, ``budget``, ``crosstalk`` and
``tolerance`` print them with ``--json`` and :class:`tactcad.api.Project` returns them: one
computation for the command and the API, so both give the same numbers.

Units: mm, N, N/mm, V, K, s; errors relative.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping, NamedTuple, Sequence

from tactcad.errors import DesignError


def readout_record(plan, model: str = "closed-form",
                   progress: Callable[[str], None] | None = None) -> Any:
    """The read-out chain of every element: gauge strain over the grid, K_v, K_v/K, the
    force and K_obj resolution (:func:`tactcad.mechanics.readout_chain.readout_report`);
    the paper's measured sensitivities are added beside them, for the paper's design only,
    by :func:`tactcad.paper.table1.with_measured_sensitivities`.

    Args:
        plan: the design's plan. model: ladder level of K and the strain field.
        progress: told what is solved (None: nothing).

    Returns:
        The report (``as_json()`` is ``tactcad readout --json``), its chain's thermal keys
        resolved as ``tactcad thermal`` resolves them
        (:func:`tactcad.mechanics.thermal_drift.with_thermal_values`).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    from dataclasses import replace

    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.mechanics.thermal_drift import with_thermal_values
    from tactcad.studies.verification import requirements_of

    report = readout_report(plan, requirements_of(plan), model, progress or (lambda s: None))
    # the thermal keys a design leaves unstated, as `thermal` resolves them: one key, one value
    return replace(report, chain=with_thermal_values(plan, report.chain))


def thermal_record(plan, model: str = "closed-form", element: int | None = None) -> Any:
    """Every element's zero and span drift per kelvin, self-heating offset and K_obj error
    per kelvin (:func:`tactcad.mechanics.thermal_drift.thermal_report`), or one element's.

    Args:
        plan: the design's plan. model: ladder level. element: one element's number, or
            None for all.

    Returns:
        The report (``as_json()`` is ``tactcad thermal --json``).

    Raises:
        DesignError: ``--element`` not an element of the design (the allowed numbers named).
    """
    from dataclasses import replace

    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    report = thermal_report(plan, requirements_of(plan), model)
    if element is None:
        return report
    chosen = [r for r in report.records if r["element"] == element]
    if not chosen:
        raise DesignError("--element", element, f"1 ... {len(report.records)}",
                          "an element number of the design")
    return replace(report, records=chosen)


class BudgetCalibration(NamedTuple):
    """A calibration file as the K_obj budget reads it
    (:func:`tactcad.paper.calibration_audit.budget_calibration`).

    Attributes:
        fits: element number -> its fit (:class:`tactcad.mechanics.calibration.Calibration`),
            the elements the file has readings of.
        audit: the audit ``tactcad calibrate --data`` gives of the same file
            (:func:`tactcad.paper.calibration_audit.audit_file`).
        warnings: one line per flag of the audit, naming the option and the file.
    """

    fits: dict
    audit: dict
    warnings: list


def budget_record(plan, model: str = "closed-form", force_N: float | None = None,
                  delta_T_K: float | None = None, points: int | None = None,
                  calibrations: dict | None = None,
                  calibration: BudgetCalibration | None = None) -> tuple[dict, Any]:
    """The K_obj error budget of every sensing unit and of the array
    (:func:`tactcad.in_use.kobj_budget.kobj_budget`) at the design's K_obj range, with the
    reasons of its range and force.

    Args:
        plan: the design's plan. model: ladder level of K and the gauge strain.
        force_N: force on the reference at the reading (N; None: the design's full-scale
            force). delta_T_K: temperature step between tare and reading (K; None: the
            budget's default). points: K_obj grid points (None: the default).
        calibrations: measured calibrations' standard errors, element -> fit; None: the
            expected errors of the calibration ``calibrate`` drives.
        calibration: a calibration file read and audited
            (:func:`tactcad.paper.calibration_audit.budget_calibration`,
            ``budget --calibration``): its fits are the calibrations, each of its audit's
            flags is issued as a warning and listed in the record's ``warnings``, and the
            record's ``calibration_file`` holds the audit's flags and the elements without
            readings.

    Returns:
        (the record ``tactcad budget --json`` prints, the budget object).
    """
    import warnings

    from tactcad.errors import CalibrationAuditWarning
    from tactcad.in_use.kobj_budget import BUDGET_POINTS, DEFAULT_DELTA_T_K, kobj_budget
    from tactcad.studies.verification import calibration_gauge, requirements_of

    if calibration is not None:
        calibrations = calibration.fits
        for line in calibration.warnings:
            warnings.warn(CalibrationAuditWarning(line), stacklevel=2)
    req = requirements_of(plan)
    force = req.full_scale_force_N if force_N is None else force_N
    budget = kobj_budget(plan, req.kobj_range_N_per_mm, force,
                         DEFAULT_DELTA_T_K if delta_T_K is None else delta_T_K, model,
                         calibrations=calibrations,
                         points=BUDGET_POINTS if points is None else points,
                         force_gauge=calibration_gauge(plan),
                         readable_within_rel=req.kobj_resolution_rel)
    record = {**budget.as_json(), "kobj_range_reason": req.reasons["kobj_range_N_per_mm"],
              "force_reason": "--force-N" if force_N is not None
              else f"full-scale force: {req.reasons['full_scale_force_N']}"}
    if calibration is not None:
        record["calibration_file"] = {
            "elements_without_readings": calibration.audit["elements_without_readings"],
            "flags": calibration.audit["flags"]}
        record["warnings"] = list(calibration.warnings)
    return record, budget


def crosstalk_record(plan, model: str | None = None) -> tuple[dict, Any]:
    """The array's crosstalk (:func:`tactcad.mechanics.crosstalk_ladder.plan_crosstalk`: the
    stacked array's clamped stack or a monolithic comb's row sheets; the n x n gauge
    sensitivity, tip displacements, crosstalk_rel, the decoupling matrix) and, at the rated
    full-scale force, each gauge's crosstalk in newtons against its force resolution through
    the design's read-out chain (closed form).

    Args:
        plan: the design's plan. model: a crosstalk level of its construction
            (``stack-beam`` ..., ``comb-beam`` ...; None: its construction's cheapest).

    Returns:
        (the record ``tactcad crosstalk --json`` prints, less its ``--sweep``; the result).

    Raises:
        UnknownCrosstalkModelError: ``model`` is no crosstalk level.
        DesignError: no level describes the plan's construction, or ``model`` describes
            another construction (refused before anything is solved).
    """
    from tactcad.mechanics.crosstalk_ladder import plan_crosstalk
    from tactcad.mechanics.readout_chain import element_force_resolution_N
    from tactcad.mechanics.stack_crosstalk import crosstalk_in_force
    from tactcad.studies.verification import rated_full_scale_force

    result = plan_crosstalk(plan, model)
    per_part = element_force_resolution_N(plan)
    step = {s.number: per_part[s.geometry.part_name]["dF"] for s in plan.slots}
    return {"design": plan.name, **result.as_json(),
            "in_force": crosstalk_in_force(result, rated_full_scale_force(plan), step)}, result


def tolerance_record(plan, samples: int, seed: int, kobj: Sequence[float] | None = None,
                     reference: int | None = None, distribution: str | None = None,
                     what_if: Mapping[str, float] | None = None,
                     mapper: Callable = map) -> tuple[Any, dict, float]:
    """The Monte Carlo of the design's manufacturing tolerances
    (:func:`tactcad.studies.tolerance_montecarlo.run_tolerance`: K per element, R and the
    reported K_obj per sensing unit, the web tolerance for a +/-5 % K band), whether the K
    band holds ``[requirements] k_tolerance_rel``
    (:func:`tactcad.studies.tolerance_budget.band_check`) and the tolerances drawn from
    (:func:`tolerances_used`). The paper's measured spread of equal-arm elements is added,
    for the paper's design only, by :func:`tactcad.paper.table1.with_equal_arm_spread`.

    Args:
        plan: the design's plan. samples: as-built arrays drawn. seed: seed of the draw.
        kobj: true object stiffnesses to report (N/mm; None: the paper's samples for the
            paper's design, else the ends and middle of the design's K_obj range).
        reference: one reference element for every unit (None: each unit the nearest).
        distribution: ``normal`` (tolerance = 3 sigma) or ``uniform`` (None: normal).
        what_if: ``Tolerances`` fields replacing the design's ``[tolerances]``
            (``notch_radius_mm``, ``arm_length_mm`` in mm, ``modulus_rel`` relative).
        mapper: ``map``-like callable evaluating the chunks (builtin ``map``: in this
            process; a Dask mapper, :func:`tactcad.studies.sweeps.dask_mapper`).

    Returns:
        (the report, whose ``as_json()`` with the fields is ``tactcad tolerance --json``;
        the fields ``design`` (its name), ``source``, ``kobj_range_N_per_mm`` (also under its
        deprecated name ``K_obj_range_N_per_mm``, listed in ``deprecated_keys``), ``warnings``
        (a ``kobj`` outside that range, as a die's record has them), ``tolerances_used``,
        ``k_tolerance_check`` (:func:`k_tolerance_check`); the draw's wall time, s).

    Raises:
        DesignError: a what-if tolerance that lets its feature vanish, a bad ``reference``,
            ``samples``, ``seed`` or ``kobj``.
    """
    import time

    from tactcad.design.requirements_section import cites_paper
    from tactcad.in_use.kobj_budget import KOBJ_RANGE_RENAMED, with_declared_deprecated_keys
    from tactcad.studies.design_loads import design_samples
    from tactcad.studies.tolerance_budget import band_check
    from tactcad.studies.tolerance_montecarlo import (DEFAULT_K_OBJ_N_PER_MM, Tolerances,
                                                      run_tolerance)
    from tactcad.studies.verification import requirements_of

    tol = Tolerances.of_plan(plan, distribution=distribution or "normal",
                             **{k: v for k, v in (what_if or {}).items() if v is not None})
    t0 = time.perf_counter()
    # the paper's samples for its design only; any other reports its own K_obj range
    k_obj = kobj or (DEFAULT_K_OBJ_N_PER_MM if cites_paper(plan.raw) else design_samples(plan, 3))
    report = run_tolerance(plan, samples=samples, seed=seed, tolerances=tol, k_obj=k_obj,
                           reference=reference, mapper=mapper)
    wall = time.perf_counter() - t0
    req = requirements_of(plan)
    check = k_tolerance_check(band_check(plan, report, req.k_tolerance_rel),
                              "k_tolerance_rel" in req.stated)
    fields = {"design": plan.name, "source": "design",
              "kobj_range_N_per_mm": list(req.kobj_range_N_per_mm),
              "warnings": kobj_range_warnings(kobj or (), req.kobj_range_N_per_mm),
              "tolerances_used": tolerances_used(plan, tol), "k_tolerance_check": check}
    return report, with_declared_deprecated_keys(fields, KOBJ_RANGE_RENAMED), wall


def k_tolerance_check(check: dict, stated: bool) -> dict:
    """``tactcad tolerance``'s ``k_tolerance_check``: the K band check
    (:func:`tactcad.studies.tolerance_budget.band_check`) with its ``verdict`` and
    ``stated``; where the lab states no ``k_tolerance_rel`` its target is the design's own
    padded spread, not a requirement, so the check is reported, not judged, as verify's row
    (:func:`tactcad.mechanics.verdicts.reported_not_judged`: verdict ``info``, ``pass`` and
    ``target`` None, the padded spread as ``reference_value``).

    Args:
        check: the band check (``target``, ``predicted_band_rel``, ``pass``, ...; relative).
        stated: whether the design file states ``k_tolerance_rel``.

    Returns:
        A new dict (``check`` unchanged).
    """
    from tactcad.mechanics.verdicts import reported_not_judged

    out = {**check, "stated": stated}
    if not stated:
        return reported_not_judged(out)
    return {**out, "verdict": "pass" if check["pass"] else "fail"}


def kobj_range_warnings(kobj: Sequence[float], kobj_range: Sequence[float]) -> list[str]:
    """One warning per true K_obj asked (``--kobj``) outside the design's required K_obj
    range, as a die's tolerance and every grasp say it
    (:func:`tactcad.in_use.grasp_experiment.kobj_range_warning`).

    Args:
        kobj: the true object stiffnesses asked (N/mm). kobj_range: the design's (lo, hi)
            K_obj range (N/mm).

    Returns:
        The warnings, in the order asked (empty when every value lies in the range).
    """
    from tactcad.in_use.grasp_experiment import kobj_range_warning

    lo, hi = kobj_range
    found = (kobj_range_warning(k, (lo, hi)) for k in kobj)
    return [w for w in found if w]


def tolerances_used(plan, tol) -> dict:
    """Every [tolerances] value the study drew from, with where it comes from
    ("design": the design file, "default": the table's default, which the drawings print too,
    "override (what-if)": an option of this run).

    Args:
        plan: the design's plan. tol: the drawn
            :class:`~tactcad.studies.tolerance_montecarlo.Tolerances` (mm, relative).

    Returns:
        ``{key: {"value", "source"}}`` per tolerance, ``contact_face_mm`` (with a note) and
        ``general`` (the drawings' general tolerance text).
    """
    from tactcad.design.tolerances import tolerances_of
    from tactcad.studies.tolerance_budget import FIELDS

    t = tolerances_of(plan.raw)
    src = dict(tol.sources)
    out = {key: {"value": getattr(tol, field), "source": src.get(key, "design")}
           for key, field in FIELDS.items()}
    out["contact_face_mm"] = {"value": t.contact_face_mm, "source": "design" if
                              t.source("contact_face_mm") == "design file" else "default",
                              "note": "does not enter K (the face's size moves no lever)"}
    out["general"] = {"value": t.general_text, "source": "design" if
                      t.source("general") == "design file" else "default"}
    return out


def strength_record(plan, model: str = "closed-form",
                    progress: Callable[[str], None] | None = None) -> tuple[dict, list]:
    """Every distinct element's peak stress per newton, yield-limited force and its stress,
    gauge strain and tip deflection at the rated full-scale force, and that rating judged
    against every element force limit (:func:`full_scale_judgement`).

    Args:
        plan: the design's plan. model: a ladder level (``closed-form`` ... ``fem3d``).
        progress: called with each step's line (None: silent).

    Returns:
        (the record ``tactcad strength --json`` prints: ``{"elements": [...],
        "requirement": {...}}`` in MPa, N, mm; the element records).

    Raises:
        UnknownModelError: ``model`` is no ladder level.
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.ladder import UnknownModelError, models
    from tactcad.studies.reference_loads import reference_load_of
    from tactcad.studies.strength_studies import plan_strength

    if not isinstance(model, str) or model not in models():
        raise UnknownModelError(model)
    records = plan_strength(plan, model, progress=progress,
                            reference_load=reference_load_of(plan))
    return ({"elements": [r.as_json() for r in records],
             "requirement": full_scale_judgement(plan, model, records)}, records)


#: ``model`` of :func:`strength_auto`: the rating judged as ``verify --model auto`` judges it.
AUTO = "auto"


def strength_auto(plan, envelope_mm: Sequence[float],
                  progress: Callable[[str], None] | None = None,
                  notice: Callable[[str], None] | None = None) -> tuple[dict, list]:
    """:func:`strength_record` at the level that decides the rated full-scale force, as
    ``tactcad verify --model auto`` decides it: the closed form, and when it leaves the rating
    undecided, verify's own climb (:func:`tactcad.studies.verification.verification_auto`,
    its solves kept in the active store and read back from it), then the record at the level
    its ``full_scale_force_N`` row names (the one that decided it, or, still undecided, the
    most accurate one tried).

    Args:
        plan: the design's plan.
        envelope_mm: the array's envelope (mm, :func:`tactcad.assembly.inventory.
            array_envelope_mm`), for verify's footprint row.
        progress: called with each step's line (None: silent).
        notice: called once with a line saying the closed form left the rating undecided
            and what the climb costs, before it starts (None: silent).

    Returns:
        As :func:`strength_record`, the ``requirement`` with ``decided_by`` (the level that
        decided the rating, None when no level did) and ``levels_tried`` (cheapest first).

    Raises:
        DesignError: the material has no yield strength.
    """
    record, records = strength_record(plan, "closed-form", progress)
    tried = ["closed-form"]
    if record["requirement"]["verdict"] == "undecided":
        if notice is not None:
            notice(climb_notice(record["requirement"], len(records)))
        row = climbed_rating_row(plan, envelope_mm, progress)
        level, tried = row["model"], list(row.get("levels_tried") or [row["model"]])
        if level != "closed-form":
            record, records = strength_record(plan, level, progress)
    said = record["requirement"]["verdict"]
    record["requirement"].update(decided_by=None if said == "undecided"
                                 else record["requirement"]["model"], levels_tried=tried)
    return record, records


def climb_notice(judged: Mapping[str, Any], elements: int) -> str:
    """What ``strength --model auto`` says before it climbs the ladder.

    Args:
        judged: the closed form's ``requirement`` record (``margin_rel``,
            ``element_force_limit_error_rel``). elements: distinct elements judged.

    Returns:
        One line: the margin inside the error, the climb and its rough cost (fem3d about
        10 s a distinct element on two cores, less where the result store holds it).
    """
    return (f"the closed form leaves the rated force undecided (margin "
            f"{100 * judged['margin_rel']:+.1f} % inside its error "
            f"{100 * judged['element_force_limit_error_rel']:.1f} %): climbing as verify "
            f"does, up to fem3d for {elements} distinct element{'s' * (elements != 1)} "
            f"(about 10 s each, less where the result store holds them); --model "
            f"closed-form for the closed form alone")


def climbed_rating_row(plan, envelope_mm: Sequence[float],
                       progress: Callable[[str], None] | None = None) -> dict:
    """The ``full_scale_force_N`` row of verify's climb
    (:func:`tactcad.studies.verification.verification_auto`, with every element's stress).

    Args:
        plan: the design's plan. envelope_mm: the array's envelope (mm).
        progress: each step's line (None: silent).

    Returns:
        The verification record (``model``, ``verdict``, ``decided_by``, ``levels_tried``).
    """
    from tactcad.studies.strength_studies import element_stress
    from tactcad.studies.verification import requirements_of, verification_auto

    records, _ = verification_auto(plan, progress, requirements_of(plan), stress=element_stress,
                                   envelope_mm=envelope_mm)
    return next(r for r in records if r["requirement"] == "full_scale_force_N")


def full_scale_judgement(plan, model: str, records) -> dict:
    """The design's rated full-scale force against every element force limit at ``model``
    (the stress figures of ``records`` reused; ``element_force_limit_N`` is the
    lowest element force limit, the largest force every element carries).

    The verdict is verify's on its ``full_scale_force_N`` row, by the same rule
    (:func:`tactcad.mechanics.verdicts.verdict`): margin limit / rating - 1 against the
    binding limit's error estimate, so a rating met within that error is ``undecided``.

    Returns:
        ``{"full_scale_force_N", "reason", "element_force_limit_N", "binding_limit",
        "binding_element", "margin_rel", "element_force_limit_error_rel", "verdict", "met",
        "model"}`` (N; relative): ``verdict`` one of ``pass``, ``fail``, ``undecided``, the
        judgement; ``met`` True only when ``verdict`` is ``pass`` (False when undecided or
        failing: :func:`tactcad.studies.verification.passed_flag`), as verify's ``pass`` and
        the manifest's ``full_scale_force.met``.
    """
    from tactcad.mechanics.element_strength import ElementStress
    from tactcad.mechanics.limits import LIMIT_WORDS, binding, limit_k_error, plan_limits
    from tactcad.mechanics.verdicts import verdict
    from tactcad.studies.verification import passed_flag, requirements_of

    req = requirements_of(plan)
    stresses = {r.part_name: ElementStress(model, r.stress_MPa_per_N, r.stress_error_rel,
                                           r.stiffness_N_per_mm, grid_strain_per_N=(
                                               r.gauge_strain_at_full_scale
                                               / r.full_scale_force_N))
                for r in records}
    # the K error verify's row carries (limit_k_error), not the stress's: one quantity
    errors = {part: limit_k_error(model, g, plan.material)
              for part, g in plan.distinct_elements.items()}
    b = binding(plan_limits(plan, model, stresses, errors))
    rated = req.full_scale_force_N
    margin = b.force_N / rated - 1.0
    said = verdict(margin, b.error_estimate_rel, 0.0, b.force_N >= rated)
    return {"full_scale_force_N": rated,
            "reason": req.reasons["full_scale_force_N"], "element_force_limit_N": b.force_N,
            "binding_limit": LIMIT_WORDS[b.limit], "binding_element": b.element,
            "margin_rel": margin, "element_force_limit_error_rel": b.error_estimate_rel,
            "verdict": said, "met": passed_flag(said), "model": model}


#: Largest further tip mass (mg) a modal record takes (``--tip-mass-mg``).
MAX_TIP_MASS_MG = 10_000.0
#: Most modes per element a modal record solves (``--modes``).
MAX_MODES = 20


def modes_record(plan, model: str = "closed-form", modes: int = 3,
                 element: int | None = None, bare: bool = False, tip_mass_mg: float = 0.0,
                 progress: Callable[[str], None] | None = None,
                 keep_shapes: bool = False) -> tuple[dict, list]:
    """The lowest natural frequencies of every distinct element (or one), clamped as in the
    stiffness model, with the gauge installation's point masses (none when ``bare``) and a
    further ``tip_mass_mg`` at the contact centre.

    Args:
        plan: the design's plan. model: a modal level (``closed-form`` ... ``fem3d``).
        modes: modes per element (FEM levels). element: one element's number (None: every
            distinct element). bare: leave out the gauge installation's mass.
        tip_mass_mg: a further mass at the tip, 0 ... :data:`MAX_TIP_MASS_MG` mg.
        progress: meshed levels' progress lines. keep_shapes: keep the mode shapes (for a
            VTU file).

    Returns:
        (the record ``tactcad modal --json`` prints (Hz, g, mm, s); ``(part, result)`` per
        distinct element).

    Raises:
        DesignError: ``tip_mass_mg`` or ``modes`` out of range.
        UnknownModalModelError: ``model`` is no modal level.
    """
    from tactcad.mechanics.gauge_mass import gauge_installation_masses
    from tactcad.mechanics.modal_ladder import (MODAL_LEVELS, UnknownModalModelError,
                                                estimate_modes)
    from tactcad.mechanics.modal_result import PointMass

    if model not in MODAL_LEVELS:
        raise UnknownModalModelError(model)
    if not 0.0 <= tip_mass_mg <= MAX_TIP_MASS_MG:  # NaN fails both
        raise DesignError("tip_mass_mg", tip_mass_mg, f"0 ... {MAX_TIP_MASS_MG:g} mg")
    if not 1 <= modes <= MAX_MODES:
        raise DesignError("modes", modes, f"1 ... {MAX_MODES} modes per element")
    meshed = MODAL_LEVELS[model].meshed
    if element is not None:
        slot = plan.element(element)
        chosen = {slot.geometry.part_name: (slot.geometry, [slot.number])}
    else:
        chosen = {}
        for s in plan.slots:
            chosen.setdefault(s.geometry.part_name, (s.geometry, []))[1].append(s.number)
    records, results = [], []
    for part, (g, numbers) in chosen.items():
        opts = {"progress": progress or (lambda line: None), "keep_shapes": keep_shapes} \
            if meshed else {}
        masses = () if bare else gauge_installation_masses(plan, g)
        if tip_mass_mg:
            masses += (PointMass("tip mass (--tip-mass-mg)", tip_mass_mg * 1e-3,
                                 *g.contact_centre_mm, "command line"),)
        r = estimate_modes(model, g, plan.material, element=numbers[0], modes=modes,
                           added_masses=masses, **opts)
        records.append({"part": part, "elements": numbers, **r.as_json(),
                        "added_masses": [{"name": m.name, "mass_g": m.mass_g, "x_mm": m.x_mm,
                                          "y_mm": m.y_mm, "source": m.source} for m in masses]})
        results.append((part, r))
    lowest = min(records, key=lambda rec: rec["first_Hz"])
    return ({"model": model, "families": list(MODAL_LEVELS[model].families),
             "elements": records, "lowest_first_Hz": lowest["first_Hz"],
             "lowest_part": lowest["part"]}, results)
