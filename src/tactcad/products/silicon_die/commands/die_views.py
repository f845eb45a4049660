"""The array commands on a silicon die's design file: ``modal``, ``budget``, ``readout``,
``thermal``, ``verify``, ``grasp``, ``crosstalk``, ``strength``, ``stiffness`` and
``tolerance`` print the die's own resonances (each row's at the closed form or fem3d), K_obj
budget, piezoresistive read-out, its temperature terms, its verification matrix
(:func:`die_verification`), the grasp in its jaw
(:mod:`tactcad.products.silicon_die.in_use.die_grasp`), the crosstalk through its handle and attach
(:mod:`tactcad.products.silicon_die.mechanics.die_crosstalk`), each row's root stress against the strength of
etched silicon, each row's K at the closed form or fem3d, and the Monte Carlo of its process
tolerances (:mod:`tactcad.products.silicon_die.studies.die_tolerance`); the die product's registry
entry (:mod:`tactcad.products.silicon_die`) names them (``<command>_view``), and
:func:`tactcad.commands.product_view` runs them,
planned as the die command plans it and writing no file of theirs (the result store aside).

An option of the array command that has no meaning for a die (a ladder level, an element,
a temperature step, the jaw's pin: the die's mount places it) is refused by name rather than
ignored (:data:`DIE_OPTIONS` are those a die's view reads); ``--model`` is taken at the
levels each view computes (:data:`DIE_MODEL_LEVELS`) and any other refused naming them.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any, Callable

from tactcad.commands.finite_json import dumps
from tactcad.errors import DesignError
from tactcad.products.silicon_die.mechanics import DIE_STIFFNESS_LEVELS  # the die's ladder
from tactcad.products.silicon_die.studies.die_reports import DIE_MODAL_LEVELS
from tactcad.products.silicon_die.studies.die_grasp_report import (  # noqa: F401 (its names)
    die_grasp_record, error_words, rated_words, role_ratings_N)
from tactcad.products.silicon_die.studies.die_verification import die_verification

#: The options of an array command a die's view reads, by command (the others are refused).
DIE_OPTIONS: dict[str, frozenset] = {
    "grasp": frozenset({"angle_deg", "force_N", "slab_thickness_mm", "profile", "kobj",
                        "opening_deg", "coupling"}),
    "crosstalk": frozenset({"model"}),
    "tolerance": frozenset({"samples", "seed", "kobj", "distribution"})}


#: The ``--model`` levels each die view computes at, by command (crosstalk has its own,
#: :func:`check_die_crosstalk_level`); ``--model`` left at the array command's default
#: (``auto`` for verify) is the first.
DIE_MODEL_LEVELS: dict[str, tuple[str, ...]] = {
    "modal": DIE_MODAL_LEVELS, "budget": ("closed-form",), "readout": ("closed-form",),
    "thermal": ("closed-form",), "verify": ("closed-form",), "grasp": ("closed-form",),
    "strength": ("closed-form",), "stiffness": DIE_STIFFNESS_LEVELS}


def die_model(args: argparse.Namespace, command: str) -> str:
    """The level ``tactcad command`` computes a die at: ``--model`` when it is one of the
    die's levels for the command (:data:`DIE_MODEL_LEVELS`), the first of them when it is
    left out or at the array command's default.

    Raises:
        DesignError: ``--model``, its value and the levels the command takes on a die.
    """
    levels = DIE_MODEL_LEVELS.get(command, ("closed-form",))
    model = getattr(args, "model", None)
    default = (getattr(args, "option_defaults", None) or {}).get("model")
    if model is None or model == default and model not in levels:
        return levels[0]
    if model not in levels:
        raise DesignError("--model", model, "one of " + ", ".join(levels) + " for a die",
                          f"`tactcad {command}` on a silicon die computes at "
                          + ("this level" if len(levels) == 1 else "these levels"))
    return model


def _refuse_array_options(args: argparse.Namespace, command: str, design: Path) -> None:
    from tactcad.commands.options import COMMON_OPTIONS, options_given

    takes_model = {"model"} if command in DIE_MODEL_LEVELS else set()
    given = options_given(args, COMMON_OPTIONS | DIE_OPTIONS.get(command, frozenset())
                          | takes_model)
    if takes_model:
        die_model(args, command)
    if given:
        option, value = given[0]
        raise DesignError(option, value, f"no value for a die's design ({design.name})",
                          f"`tactcad {command}` on a silicon die prints the die's own "
                          "figures; this option chooses among an array's")


def _planned(design: Path, args: argparse.Namespace):
    from tactcad.commands.die import _die_args, die_asked, plan_of

    return plan_of(die_asked(_die_args(design, args, Path("."))))


def _modal(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands import progress_from_args
    from tactcad.products.silicon_die.studies.die_reports import modes_report

    model = die_model(args, "modal")  # before the die is planned: a refusal at once
    report, lines = modes_report(_planned(design, args).plan, model, progress_from_args(args))
    return {"design": str(design), **report}, lines


def _budget(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import budget_lines
    from tactcad.products.silicon_die.in_use.die_budget import die_budget

    plan = _planned(design, args).plan
    budget = die_budget(plan)
    return ({"design": str(design), "die": plan.name, "kobj_budget": budget.as_json()},
            [f"die {plan.name}", *budget_lines(budget)])


def _readout(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import resistor_line
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    plan = _planned(design, args).plan
    readout = die_readout(plan)
    lines = [f"die {plan.name}: one p-type resistor per beam and its on-die reference in a "
             "half bridge",
             "| role | dR/R per N | V/N | force resolution N |", "| --- | --- | --- | --- |"]
    for role, r in readout["rows"].items():
        lines.append(f"| {role} | {r['resistance_change_per_N']:.4g} | "
                     f"{r['sensitivity_V_per_N']:.4g} | {r['force_resolution_N']:.3g} |")
    lines += [resistor_line(plan, readout),
              f"sensitivity temperature coefficient {100 * readout['sensitivity_tc_per_K']:+.3g}"
              f" %/K; self-heating {1e3 * readout['self_heating_K']:.3g} mK"]
    return {"design": str(design), "die": plan.name, "readout": readout}, lines


def _thermal(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.products.silicon_die.design.mems_die import REFERENCE_TCR_MISMATCH_REL
    from tactcad.products.silicon_die.in_use.die_budget import TEMPERATURE_STEP_K, die_budget
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    plan = _planned(design, args).plan
    readout = die_readout(plan)
    budget = die_budget(plan, readout)
    tcs, heating = readout["sensitivity_tc_per_K"], readout["self_heating_K"]
    term = budget.terms["temperature"]
    rows = readout["rows"]
    zero_term = budget.terms["resistor zero drift"]
    zero = (f"TCR {1e6 * readout['resistor_tcr_per_K']:+.0f} ppm/K (Arora et al. 1982, every "
            "acceptor ionised), the same in each beam's resistor and its on-die reference: it "
            f"cancels in their half bridge to a {100 * REFERENCE_TCR_MISMATCH_REL:g} % mismatch "
            f"(assumption), so the zero moves {1e6 * readout['zero_drift_V_per_K']:.3g} uV per "
            f"K ({1e3 * readout['uncancelled_zero_drift_V_per_K']:.3g} mV per K uncancelled), "
            f"{1e6 * rows['reference']['zero_drift_N_per_K']:.3g} uN per K on the reference "
            f"beam and {1e6 * rows['measuring']['zero_drift_N_per_K']:.3g} uN per K on the "
            f"measuring beam ({100 * rows['reference']['zero_drift_N_per_K'] / plan.full_scale_force_N:.2g}"
            " % of the rating per K)")
    report = {"design": str(design), "die": plan.name,
              "sensitivity_tc_per_K": tcs, "self_heating_K": heating,
              "temperature_step_K": TEMPERATURE_STEP_K,
              "kobj_error_rel": {"k_obj_N_per_mm": budget.k_obj_N_per_mm.tolist(),
                                 "temperature": [float(v) for v in term],
                                 "reason": budget.reasons["temperature"],
                                 "resistor zero drift": [float(v) for v in zero_term]},
              "resistor_tcr_per_K": readout["resistor_tcr_per_K"],
              "zero_drift_N_per_K": {role: r["zero_drift_N_per_K"] for role, r in rows.items()},
              "zero": zero}
    lines = [f"die {plan.name}: p-type resistors, boron {plan.acceptors_per_cm3:.2g} cm^-3",
             f"span: sensitivity {100 * tcs:+.3g} %/K (d ln P / dT, Richter et al. 2008), "
             "alike in both rows: it cancels in R at one temperature",
             f"self-heating: {1e3 * heating:.3g} mK at the root, P(N, T) moved "
             f"{100 * abs(tcs) * heating:.2g} %",
             f"K_obj error over a {TEMPERATURE_STEP_K:g} K step at K_obj "
             + ", ".join(f"{k:.3g}" for k in budget.k_obj_N_per_mm) + " N/mm: "
             + ", ".join(f"{100 * v:.3f} %" for v in term) + f" ({budget.reasons['temperature']})",
             f"zero: {zero}",
             f"K_obj error of the zero over the step (tared at the other temperature): "
             + ", ".join(f"{100 * v:.3f} %" for v in zero_term)]
    return report, lines


def _crosstalk(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands import progress_from_args
    from tactcad.products.silicon_die.mechanics.die_crosstalk import MAX_DOFS, crosstalk_in_force, mesh_dofs
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    check_die_crosstalk_level(getattr(args, "model", None))  # before the die is planned
    plan = _planned(design, args).plan
    dofs = mesh_dofs(plan)
    if dofs > MAX_DOFS:
        most = max(2, int(plan.columns * MAX_DOFS / dofs))
        raise DesignError("die.columns", plan.columns,
                          f"a die whose crosstalk mesh stays within {MAX_DOFS} degrees of "
                          f"freedom (about {most} columns at {plan.pitch_um:g} um pitch)",
                          f"the die's 3D FE would have up to {dofs} (its memory grows "
                          "faster than that); its units couple only with their nearest neighbours, "
                          f"so a die of {most} columns gives the same worst pair",
                          alternatives=[{"option": f"--set die.columns={most}",
                                         "words": "the same die, fewer columns"}])
    result, reused = _crosstalk_kept(plan, dofs, progress_from_args(args))
    resolution = {role: r["force_resolution_N"] for role, r in die_readout(plan)["rows"].items()}
    in_force = crosstalk_in_force(plan, result, resolution)
    report = {"design": str(design), "die": plan.name, **result.as_json(),
              "reused": reused, "in_force": in_force}
    return report, crosstalk_lines(plan, result, in_force, reused)


def check_die_crosstalk_level(model: str | None) -> None:
    """Refuse a crosstalk ``--model`` a die has not: the array's levels model its clamped
    stack or its comb sheets, a die has its one level.

    Args:
        model: ``--model`` as given, or None when left out (the die's level).

    Raises:
        DesignError: naming ``--model``, its value and the die's level, which is pasted.
    """
    from tactcad.products.silicon_die.mechanics.die_crosstalk import (CROSSTALK_COST,
                                                                      CROSSTALK_LEVEL)

    if model in (None, CROSSTALK_LEVEL):
        return
    raise DesignError("--model", model, f"one of {CROSSTALK_LEVEL} for a die (its only crosstalk "
                      f"level: 3D FE through its handle and die attach, {CROSSTALK_COST})",
                      f"{model} models an array's coupling (a clamped stack of bases and "
                      "spacers, or a comb's row sheets), which a silicon die has not",
                      alternatives=[{"option": f"--model {CROSSTALK_LEVEL}",
                                     "words": "the die's crosstalk, or leave --model out"}])


def _crosstalk_kept(plan, dofs: int, report: Callable[[str], None]) -> tuple[Any, bool]:
    """The die's crosstalk, kept in the result store for the same plan and mesh (``--cache``,
    ``--no-cache``): the second run of the same die solves nothing. ``report`` hears what
    is solved or reused. Returns (the result, whether it was reused: its cost is then the
    solve's that kept it)."""
    from tactcad.products.silicon_die.mechanics.die_crosstalk import MESH, die_crosstalk
    from tactcad.store import kept_result

    reused = []

    def solve():
        # mesh_dofs bounds the mesh before the windows are cut: the run reports fewer
        report(f"crosstalk of die {plan.name}: 3D FE of the die on its attach, at most {dofs} "
               "degrees of freedom, and three coarser meshes for the error estimate (about a "
               "minute on two cores)")
        return die_crosstalk(plan)

    def on_reuse(where: str) -> None:
        reused.append(True)
        report(f"crosstalk of die {plan.name}: {where} (the same die and mesh)")

    return kept_result("die crosstalk", solve, plan, MESH, reused=on_reuse), bool(reused)


def crosstalk_lines(plan, r, in_force: dict, reused: bool = False) -> list[str]:
    """The die's crosstalk as text: the figures, the worst in newtons, each unit's reading
    under every post's force over its own (ppm); ``reused``: from the result store (the
    cost is then the solve's that kept it)."""
    q = in_force
    error = 100 * r.error_estimate_rel
    cost = (f"solved in {r.seconds:.3g} s by an earlier run, reused" if reused
            else f"{r.seconds:.3g} s")
    lines = [f"crosstalk of die {plan.name} ({r.model}, {cost}, {r.dofs} dofs): "
             f"crosstalk_rel {r.crosstalk_rel:.3g} (beam {r.worst[0]}'s half bridge under a "
             f"force on post {r.worst[1]}), error estimate "
             + (f"{error:.0f} %" if error >= 10 else f"{error:.2g} %"),
             f"  in force (the pair with the most resolution steps): post {q['loaded_beam']} "
             f"at the {q['rated_force_N']:.3g} N it carries in use reads "
             f"{q['crosstalk_force_N']:.3g} N on beam {q['beam']}, "
             f"{q['force_resolution_steps']:.3g} times its force resolution "
             f"({q['force_resolution_N']:.3g} N)",
             f"  model: {r.basis}",
             "  in use the tissue between the posts couples the units far more: `tactcad "
             "budget` gives that term and the coupled inversion removes it",
             "  the matrix is not symmetric: each beam's reference resistor lies on the frame "
             "on one side of its root, nearer one neighbour than the other",
             "each beam's half-bridge reading under a force on each post, over its reading "
             "under its own (ppm; own: dR/R per N):",
             "| beam | row | own | " + " | ".join(str(b) for b in r.beams) + " |",
             "| --- | --- | --- |" + " --- |" * len(r.beams)]
    s = r.reading_per_N
    for i, (b, beam) in enumerate(zip(r.beams, plan.beams)):
        cells = ["" if i == j else f"{1e6 * s[i, j] / s[i, i]:.3g}" for j in range(len(r.beams))]
        lines.append(f"| {b} | {beam.role} | {s[i, i]:.4g} | " + " | ".join(cells) + " |")
    return lines


def _verify(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import budget_lines, stale_notes
    from tactcad.products.silicon_die.in_use.die_budget import die_budget
    from tactcad.studies.verification import matrix_passed, matrix_table, undecided

    from tactcad.products.silicon_die.design.die_mount import die_mount

    planned = _planned(design, args)
    plan = planned.plan
    records = die_verification(plan, die_mount(plan, planned.jaw_stated))
    budget = die_budget(plan)
    ok = matrix_passed(records)
    report = {"design": str(design), "die": plan.name, "model": "closed-form",
              "matrix": records, "undecided": undecided(records), "passed": ok,
              "kobj_budget": budget.as_json()}
    lines = [f"die {plan.name}, model closed-form", matrix_table(records),
             *budget_lines(budget), *stale_notes(planned.stale_reasons),  # edited since
             "no requirement fails" if ok else "a requirement is not met"]
    return report, lines


def _grasp(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.options import grasp_option_error
    from tactcad.products.silicon_die.design.die_mount import die_mount

    planned = _planned(design, args)
    plan = planned.plan
    try:
        record, result = die_grasp_record(plan, die_mount(plan, planned.jaw_stated), args,
                                          str(design))
    except DesignError as exc:
        raise grasp_option_error(exc, args) from None
    return record, grasp_lines(plan, record, result)


def reads_why(unit: dict) -> str:
    """Why a unit does not read: its posts (``why``) and a true K_obj outside the die's
    range (``out_of_range``)."""
    return "; ".join(filter(None, [unit["why"], unit["out_of_range"]]))


def per_unit_true(units: list[dict], k_obj_N_per_mm: float) -> bool:
    """Whether a unit's true K_obj differs from the grasp's one K_obj (N/mm; beyond 1e-9
    relative): under the wedge on the layer each unit is judged against its posts' own.

    Args:
        units: the grasp's unit records (``K_obj_true_N_per_mm``).
        k_obj_N_per_mm: the K_obj the grasp was asked with (N/mm).

    Returns:
        True where any unit's true K_obj is its own.
    """
    return any(abs(u["K_obj_true_N_per_mm"] / k_obj_N_per_mm - 1) > 1e-9 for u in units)


def grasp_lines(plan, record: dict, result) -> list[str]:
    """The die's grasp as text: the jaw and tissue, each unit's reading against its true
    K_obj and R (the columns ``K_obj true`` and ``R true``, as an array's grasp table has
    them), each post's force."""
    jaw = record["jaw"]
    um = 1e3
    lines = [f"die {plan.name} in its jaw: jaw {jaw['jaw_length_mm']:g} mm, pin at "
             f"{jaw['pin_x_mm']:g} mm from the heel, pin to tip {jaw['pin_to_tip_mm']:.4g} mm, "
             f"{jaw['opening_angle_deg']:g} degrees open, {record['profile']} of tissue "
             f"{jaw['slab_thickness_mm']:g} mm thick, K_obj {record['K_obj_N_per_mm']:.4g} N/mm "
             f"(tissue coupling: {record['coupling']})"
             + ("; each unit's error is against its own true K_obj (K_obj true: its two "
                "posts' tissue, thinner under the wedge and so stiffer)"
                if per_unit_true(result.units, record["K_obj_N_per_mm"]) else ""),
             f"closed to {result.angle_deg:.4g} degrees: grasp force "
             f"{result.total_force_N:.4g} N ({record['reasons']['force_N']})",
             *record["warnings"],
             "| unit | radius mm | travel r/m um | deflection r/m um | K_obj true | R true | "
             "R read | K_obj read | error | corrected | error | reads |",
             "| --- |" + " --- |" * 11]

    def pct(v):
        return "n/a" if v is None else f"{100 * v:+.1f} %"

    def num(v):
        return "n/a" if v is None else f"{v:.4g}"

    for u in result.units:
        lines.append(f"| {u['unit']} | {u['r_reference_mm']:.3f} | "
                     f"{um * u['travel_reference_mm']:.3g} / {um * u['travel_measuring_mm']:.3g} | "
                     f"{um * u['deflection_reference_mm']:.3g} / "
                     f"{um * u['deflection_measuring_mm']:.3g} | "
                     f"{num(u['K_obj_true_N_per_mm'])} | {num(u['R_true'])} | "
                     f"{num(u['R_read'])} | "
                     f"{num(u['K_obj_read_N_per_mm'])} | {pct(u['error_rel'])} | "
                     f"{num(u['K_obj_corrected_N_per_mm'])} | {pct(u['error_corrected_rel'])} | "
                     f"{'yes' if u['reads'] else reads_why(u)} |")
    over = [t for t in result.tips if t["over_rating"]]
    broken = [t for t in result.tips if t["over_overload_limit"]]
    stopped = [t for t in result.tips if t["on_stop"]]
    face = [t for t in result.tips if t["face_in_contact"]]
    crushed = [t for t in result.tips if t.get("past_linear_tissue")]
    top = max(result.tips, key=lambda t: t["element_force_N"])
    lines += [f"largest beam force {1e3 * top['element_force_N']:.3g} mN (beam {top['site']}, "
              f"rated {1e3 * top['rated_force_N']:.3g} mN); over its own beam's rating "
              f"({rated_words(record['rated_force_N_by_role'])}): "
              f"{', '.join(str(t['site']) for t in over) or 'none'}; on their stops: "
              f"{', '.join(str(t['site']) for t in stopped) or 'none'}; past the breaking "
              f"force: {', '.join(str(t['site']) for t in broken) or 'none'}; the face in "
              f"the tissue beside posts: {', '.join(str(t['site']) for t in face) or 'none'} "
              f"(posts {1e3 * record['post_proud_mm']:.3g} um proud)",
              f"K_obj error of {record['reasons']['error']}"]
    left = result.correction_residual
    if left:  # what the correction leaves, with its size (never a bare corrected column)
        lo, hi = left["range_rel"]
        lines.append(f"the corrected K_obj is still off by {pct(lo)} ... {pct(hi)} (largest "
                     f"{pct(left['largest_rel'])}, unit {left['unit']}): {left['cause']}")
    if crushed:
        from tactcad.in_use.grasp_experiment import LINEAR_TISSUE_STRAIN

        lines.append(f"the tissue is compressed past {100 * LINEAR_TISSUE_STRAIN:g} % under "
                     f"posts {', '.join(str(t['site']) for t in crushed)}: past the linear "
                     "tissue model")
    return lines


def _strength(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.products.silicon_die.studies.die_reports import strength_report

    report, lines = strength_report(_planned(design, args).plan)
    return {"design": str(design), **report}, lines


def _stiffness(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands import progress_from_args
    from tactcad.products.silicon_die.studies.die_reports import stiffness_report

    model = die_model(args, "stiffness")  # before the die is planned: a refusal at once
    report, lines = stiffness_report(_planned(design, args).plan, model,
                                     progress_from_args(args))
    return {"design": str(design), **report}, lines


def _tolerance(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    import time

    from tactcad.in_use.grasp_experiment import kobj_range_warning
    from tactcad.in_use.kobj_budget import KOBJ_RANGE_RENAMED, with_declared_deprecated_keys
    from tactcad.products.silicon_die.studies.die_tolerance import (DieTolerances,
                                                                    check_die_samples,
                                                                    report_lines,
                                                                    run_die_tolerance)

    check_die_samples(args.samples)  # before the die is planned: a refusal at once
    plan = _planned(design, args).plan
    tol = DieTolerances.of_plan(plan, args.distribution or "uniform")
    t0 = time.perf_counter()
    report = run_die_tolerance(plan, args.samples, args.seed, tol, args.kobj)
    wall = time.perf_counter() - t0
    warnings = [w for w in (kobj_range_warning(k, plan.kobj_range_N_per_mm)
                            for k in (args.kobj or ())) if w]
    record = {"design": str(design), "die": plan.name, "source": "the die's process",
              "kobj_range_N_per_mm": list(plan.kobj_range_N_per_mm), "warnings": warnings,
              **report.as_json()}
    return (with_declared_deprecated_keys(record, KOBJ_RANGE_RENAMED),
            [*report_lines(plan.name, report, wall), *warnings])


def _scenes(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import DIE_FILES, die_asked, _die_args
    from tactcad.products.silicon_die.export.die_solid import COLOURS

    name = die_asked(_die_args(design, args, Path(".")))["name"]
    scene = f"{name}_in_jaw"
    asked = getattr(args, "name", None)
    if asked not in (None, scene):
        raise DesignError("NAME", asked, f"{scene} (the die's one scene)",
                          f"{design.name} is a silicon die's design")
    parts = ["grasper_jaw", "die_carrier", *(f"{name}_{layer}" for layer in COLOURS)]
    files = [DIE_FILES[k].format(name=name) for k in ("scene", "glb", "scene_picture")]
    summary = {"name": scene, "rig": "jaw", "parts_placed": len(parts),
               "description": "the die on its carrier in its jaw's face pocket",
               "groups": {"insert": [{"part": p, "quantity": 1, "detail": "full"}
                                     for p in parts]},
               "files": files}
    return ({"design": str(design), "die": name, "scenes": [summary]},
            [f"{scene}  [{summary['rig']}]  {len(parts)} parts placed - "
             f"{summary['description']}",
             "    insert: " + ", ".join(f"{p} x1 (full)" for p in parts),
             f"    written by `tactcad export --out DIR` (the die's export is whole): "
             + ", ".join(files)])


def _viewed(command: str, view: Callable[[Path, argparse.Namespace], tuple[dict, list[str]]]):
    """``view`` as the die's answer to the array command ``command`` (the die product's
    hook, :mod:`tactcad.products.silicon_die`): an option of the array's that means nothing
    for a die is refused by name first."""
    def answer(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
        _refuse_array_options(args, command, design)
        return view(design, args)
    answer.__doc__ = f"``tactcad {command}`` on a silicon die's design file."
    return answer


modal_view = _viewed("modal", _modal)
budget_view = _viewed("budget", _budget)
readout_view = _viewed("readout", _readout)
thermal_view = _viewed("thermal", _thermal)
verify_view = _viewed("verify", _verify)
grasp_view = _viewed("grasp", _grasp)
crosstalk_view = _viewed("crosstalk", _crosstalk)
strength_view = _viewed("strength", _strength)
stiffness_view = _viewed("stiffness", _stiffness)
tolerance_view = _viewed("tolerance", _tolerance)
scenes_view = _viewed("scenes", _scenes)
