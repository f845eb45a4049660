"""``tactcad evaluate``: the paper's array evaluation rig, simulated for a design.

Examples::

    tactcad evaluate
    tactcad evaluate --samples 10.01,3.85,2.34 --coupling layer --thickness 5 --json
    tactcad evaluate --stiffness table1 --plot exports/reports/evaluate_fig7.png
"""

from __future__ import annotations

import argparse
import math

from tactcad.commands import add_cache_args, add_design_arg, add_output_args, project_from_args
from tactcad.commands.options import PLOT_SUFFIXES, count, number, output_file

from tactcad.mechanics.ladder import models


def register(subparsers) -> None:
    """Add the ``evaluate`` sub-command."""
    p = subparsers.add_parser(
        "evaluate", help="simulate the array evaluation rig: R per element, sample and load step",
        description="The array evaluation rig, simulated: the array pressed into rubber samples "
                    "(the paper's design: by 3.235 N then 100 g steps, its eight samples; any "
                    "other design: by its rigs file's evaluation rig, the preload then each "
                    "weight added, or with --steps, or where the rigs state no preload, in "
                    "equal steps until the most loaded element carries the design's full-scale "
                    "force; samples over its K_obj range); each element's deflection over the "
                    "reference (stiffest) element's gives R. Sample: independent springs "
                    "(eq. 1-2) or rigid punches at the tips on an elastic half-space or layer "
                    "(modulus from K_obj through a punch of the design's own tip face). Units: "
                    "N/mm, N, mm, um.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--samples", default=None, metavar="K1,K2,...",
                   help="sample stiffnesses K_obj (N/mm); default: five over the design's "
                        "required K_obj range (the paper's design: its eight samples)")
    p.add_argument("--coupling", choices=("none", "halfspace", "layer"), default="halfspace",
                   help="sample model (default halfspace)")
    p.add_argument("--poisson", type=number(0, 0.5), default=0.5, help="sample Poisson ratio (0 ... 0.5; default %(default)s, incompressible rubber)")
    p.add_argument("--thickness", type=number(0, 1e4, "mm", lo_open=True), default=10.0, metavar="MM",
                   help="sample thickness on its rigid base for --coupling layer (mm), default 10")
    p.add_argument("--stiffness", choices=("ladder", "table1"), default="ladder",
                   help="element K: the ladder's prediction for the design, or the measured "
                        "K of a design that cites them (ladder for elements without one); "
                        "default %(default)s")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level of the element stiffness (default %(default)s)")
    p.add_argument("--steps", type=count(1, 1000, "load steps"), default=None,
                   help="equal load steps up to the full-scale force (>= 1) instead of the "
                        "rig's; default: the rigs file's evaluation rig (preload, then each "
                        "weight), else 6 (the paper's design: 6 of its steps)")
    p.add_argument("--plot", metavar="PNG", type=output_file(*PLOT_SUFFIXES), default=None,
                   help="write a Fig. 7-like plot (R against K_m/K_obj per K_r/K_m) here")
    p.add_argument("--plot-fig6", metavar="PNG", type=output_file(*PLOT_SUFFIXES), default=None,
                   help="write a Fig. 6-like plot (R against grasping force) of one sample: "
                        "the middle of --samples (the paper's design: its sample nearest "
                        "3.85 N/mm)")
    add_output_args(p, "print one JSON object")
    p.set_defaults(func=run)


#: Equal load steps of a design whose rigs state no evaluation rig, and of the paper's.
DEFAULT_STEPS = 6


def design_load_steps(project, steps: int | None, force_N: float,
                      equal_steps) -> tuple[list[float], str]:
    """The grasping forces (N) ``evaluate`` loads a design that does not cite the
    paper with, and where they come from: the project's evaluation rig as its
    rigs file states it (preload, then each weight added:
    :func:`tactcad.studies.rig_sizing.evaluation_rig_steps`) unless ``--steps``
    asks for equal ones; equal steps up to the full-scale force also where the
    rigs state no preload, or the project has no test rigs.

    Args:
        project: the validated project (its ``rigs`` may be None).
        steps: ``--steps``, or None.
        force_N: the design's full-scale force (N).
        equal_steps: n -> n equal grasping forces up to the full-scale load (N).

    Returns:
        (loads, words saying where they come from).
    """
    from tactcad.studies.rig_sizing import evaluation_rig_steps

    rig = None if steps is not None or project.rigs is None else evaluation_rig_steps(project.rigs)
    if rig is not None:
        loads, how = rig
        where = project.rigs_file or "the rigs made for the design"
        return loads, f"the project's evaluation rig ({where}): {how}, one weight per step"
    n = DEFAULT_STEPS if steps is None else steps
    why = ("--steps" if steps is not None else "no test rigs" if project.rigs is None
           else "the rigs state no [evaluation] preload_N")
    return [float(v) for v in equal_steps(n)], (
        f"{n} equal steps up to the load at which the most loaded element carries the "
        f"full-scale force {force_N:g} N ({why})")


def warn_samples_outside_range(samples: list[float], kobj_range) -> None:
    """Warn (one line per sample) where a ``--samples`` stiffness lies outside the design's
    required K_obj range: the design is not made to read it, so its R is shown, not rated.

    Args:
        samples: the samples' K_obj (N/mm).
        kobj_range: the design's required K_obj range (N/mm), or None (no range stated).
    """
    import warnings

    from tactcad.errors import PastRatingWarning
    from tactcad.in_use.grasp_experiment import in_kobj_range

    if not kobj_range:
        return
    lo, hi = kobj_range
    for k in samples:
        if not in_kobj_range(k, (lo, hi)):
            warnings.warn(f"--samples {k:g} N/mm is outside the design's K_obj range "
                          f"{lo:g} ... {hi:g} N/mm: the design is not made to read it (its R "
                          "is shown, not rated)", PastRatingWarning, stacklevel=2)


def warn_tip_forces_past_limits(plan, report: dict) -> None:
    """Warn (one line per element) where the evaluation's loads put a tip force past the
    element's rating (the design's rated full-scale force) or its yield-limited force,
    naming the element, the largest tip force (N), the sample (N/mm) and load (N) it is
    at, and the limits (N).

    Args:
        plan: the design's plan.
        report: :func:`tactcad.mechanics.evaluation.evaluation_report`'s record (N, N/mm).
    """
    import warnings

    from tactcad.errors import PastRatingWarning
    from tactcad.studies.reference_loads import strength_summary
    from tactcad.studies.verification import rated_full_scale_force

    rated = rated_full_scale_force(plan)
    yield_N = {r["element"]: r["yield_limited_force_N"] for r in strength_summary(plan)}
    top: dict[int, tuple[float, float, float]] = {}
    for sample in report["samples"]:
        for e in sample["elements"]:
            for load, force in zip(sample["loads_N"], e["tip_force_N"]):
                if force > top.get(e["element"], (-math.inf,))[0]:
                    top[e["element"]] = (force, sample["K_obj_N_per_mm"], load)
    for element, (force, k_obj, load) in sorted(top.items()):
        limit = yield_N.get(element)
        past = ([f"its yield-limited force {limit:.3g} N"] if limit is not None
                and force > limit * (1 + 1e-9) else [])
        if force > rated * (1 + 1e-9):
            past.insert(0, f"the rated full-scale force {rated:.3g} N "
                           f"(by {100 * (force / rated - 1):.0f} %)")
        if past:
            warnings.warn(f"evaluate: element {element} carries up to {force:.3g} N (K_obj "
                          f"{k_obj:g} N/mm at {load:.4g} N), past {' and '.join(past)}: its "
                          "R there is a reading past full scale", PastRatingWarning,
                          stacklevel=2)


def parse_stiffness_list(field: str, text: str) -> list[float]:
    """Comma-separated stiffnesses (N/mm), each finite and > 0.

    Raises:
        TactcadError: an entry that is not a number or not > 0, or an empty list.
    """
    from tactcad.errors import DesignError

    values = []
    for part in text.split(","):
        try:
            v = float(part)
        except ValueError:
            raise DesignError(field, part.strip(), "numbers > 0 N/mm separated by commas") from None
        if not (math.isfinite(v) and v > 0):
            raise DesignError(field, v, "> 0 N/mm")
        values.append(v)
    if not values:
        raise DesignError(field, text, "at least one number > 0 N/mm")
    return values


def run(args: argparse.Namespace) -> int:
    """Handler of ``tactcad evaluate``; returns the exit code."""
    from tactcad.paper import data as paper_data
    from tactcad.mechanics import evaluation as ev
    from tactcad.paper.table2_models import paper_stiffness_by_element
    from tactcad.commands.finite_json import dumps

    from tactcad.design.requirements_section import cites_paper
    from tactcad.studies.design_loads import design_samples, loads_to_full_scale
    from tactcad.studies.verification import requirements_of

    project = project_from_args(args)
    plan = project.plan
    paper = cites_paper(plan.raw)
    if args.stiffness == "table1" and not paper:
        from tactcad.errors import DesignError

        raise DesignError("--stiffness", "table1", "ladder (the measured stiffnesses belong to "
                          "a design that cites them in requirements.source)")
    samples = (parse_stiffness_list("samples", args.samples) if args.samples
               else list(paper_data.SAMPLE_STIFFNESSES_N_PER_MM) if paper
               else design_samples(plan))
    if args.samples and not paper:
        warn_samples_outside_range(samples, requirements_of(plan).kobj_range_N_per_mm)
    spec = ev.SampleSpec(args.coupling, args.poisson,
                         args.thickness if args.coupling == "layer" else None)
    stiffness = (paper_stiffness_by_element(plan, args.model) if args.stiffness == "table1"
                 else ev.ladder_stiffness_by_element(plan, args.model))
    steps = DEFAULT_STEPS if args.steps is None else args.steps
    if steps < 1:
        raise ev.ContactError("--steps", steps, ">= 1")
    loads, source = None, (f"the paper's rig: 3.235 N, then 100 g per step ({steps} steps)")
    if not paper:  # the paper's rig loads only its design; others load as their own rig does
        force = requirements_of(plan).full_scale_force_N
        loads, source = design_load_steps(project, args.steps, force, lambda n: (
            loads_to_full_scale(plan, stiffness, samples, spec, n, force)))
    middle = samples[len(samples) // 2]
    # each row reads against its own reference; the paper's rig read one for both rows
    rows = None if paper else {s.number: plan.reference_for(s).number for s in plan.slots}
    report = ev.evaluation_report(plan, stiffness, samples, spec, n_steps=steps,
                                  loads_N=loads, references=rows,
                                  **({} if paper else {"fig6_sample": middle}))
    report["load_steps_from"] = source
    warn_tip_forces_past_limits(plan, report)
    if not paper:
        report["full_scale_force_N"] = force
    if args.plot:
        from tactcad.paper.figures import plot_ratio_map

        title = (f"{plan.name}: R against K_m/K_obj ({args.coupling} sample, K from "
                 f"{args.stiffness}, reference element {report['reference_element']})")
        report["plot"] = str(plot_ratio_map(report["R_against_K_m_over_K_obj"], args.plot,
                                            title))
    if args.plot_fig6:
        from tactcad.paper.figures import plot_ratio_vs_load

        fig6 = report["R_against_load"]
        report["plot_fig6"] = str(plot_ratio_vs_load(
            fig6["loads_N"], {f"element {k}": v for k, v in fig6["R"].items()}, args.plot_fig6,
            f"{plan.name}: R against grasping force, K_obj = {fig6['K_obj_N_per_mm']:g} N/mm "
            f"({args.coupling})"))
    if args.json:
        print(dumps(report))
        return 0
    _print_text(report)
    return 0


def _print_text(report: dict) -> None:
    refs = report.get("row_references")
    which = (f"each row against its reference (elements {', '.join(map(str, refs))})" if refs
             else f"reference element {report['reference_element']} "
                  f"(K_r = {report['K_r_N_per_mm']:.4g} N/mm)")
    print(f"design {report['design']}: sample model {report['coupling']}, {which}")
    numbers = [e["element"] for e in report["elements"]]
    first = report["R_against_load"]["loads_N"][0]
    print(f"load steps: {report['load_steps_from']}")
    print(f"R at the first load step ({first:.4g} N); rows: K_obj (N/mm), columns: element")
    print("    K_obj  " + "".join(f"{n:>9d}" for n in numbers) + "    E (MPa)")
    for s in report["samples"]:
        cells = "".join(f"{e['R'][0]:9.4g}" for e in s["elements"])
        modulus = "-" if s["youngs_modulus_MPa"] is None else f"{s['youngs_modulus_MPa']:.3g}"
        print(f"{s['K_obj_N_per_mm']:9.4g}  {cells}   {modulus:>8s}")
    spread = max(max(e["R"]) - min(e["R"]) for s in report["samples"] for e in s["elements"])
    print(f"largest change of R over the load steps: {spread:.2e} (the model is linear)")
    lost = [e["element"] for s in report["samples"] for e in s["elements"] if e["contact_lost"]]
    if lost:
        print(f"warning: tensile tip force (contact lost) at elements {sorted(set(lost))}")
    for key in ("plot", "plot_fig6"):
        if key in report:
            print(f"{key.replace('_', ' ')}: {report[key]}")
