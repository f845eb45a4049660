"""``tactcad budget``: the K_obj error budget of every sensing unit, source by source."""

from __future__ import annotations

import argparse
import warnings

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view, progress_from_args)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import (add_renamed_option, count, keep_option_defaults, number,
                                      output_file)
from tactcad.errors import PastRatingWarning
from tactcad.mechanics.ladder import models


def register(sub: argparse._SubParsersAction) -> None:
    from tactcad.in_use.kobj_budget import BUDGET_POINTS, DEFAULT_DELTA_T_K

    p = sub.add_parser(
        "budget", help="the K_obj error budget: each source's relative K_obj error over the "
                       "K_obj range, their RSS and worst case, the source that dominates",
        description="For every sensing unit (a row's reference and a softer element of the "
                    "row), pressed until the reference carries the reference force, at each "
                    "K_obj of a log-spaced grid over the requirements' K_obj range: the "
                    "relative K_obj error (eq. 3 and its derivatives) from read-out noise and "
                    "quantisation, thermal zero and span over the temperature step, "
                    "manufacturing tolerance, crosstalk, tissue coupling (a half-space "
                    "sample under the design's tip faces), the gauge model and the "
                    "calibration, before and after the correction each gets (calibration, "
                    "decoupling matrix, coupled inversion); their RSS and worst-case sum, and "
                    "the source that dominates. Units: N, K, N/mm; errors in percent.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for K and the gauge strain (default closed-form)")
    force = p.add_argument("--force-N", dest="force_N", type=number(0, 1000, "N", lo_open=True),
                           default=None, help="force on the reference element at the reading "
                                              "(N; default the design's full-scale force)")
    step = p.add_argument("--delta-T-K", dest="delta_T_K", type=number(0, 100, "K"),
                          default=DEFAULT_DELTA_T_K,
                          help="temperature step between tare and reading (K; default "
                               "%(default)s K)")
    # the earlier names (--force is "overwrite" to design and new): taken, said renamed
    add_renamed_option(p, "--force", force)
    add_renamed_option(p, "--delta-T", step)
    p.add_argument("--points", type=count(2, 101, "K_obj grid points"), default=BUDGET_POINTS,
                   help="log-spaced K_obj points over the range (default %(default)s)")
    p.add_argument("--calibration", metavar="FILE", default=None,
                   help="measured calibration readings (as tactcad calibrate --data: CSV, LVM "
                        "or TDMS; read and audited as calibrate reads and audits it, each "
                        "flag a warning): their fitted standard errors of K and K_v, an "
                        "element without readings taking the default's; default the "
                        "expected errors of the static calibration tactcad calibrate drives (its "
                        "steps, on the rigs' force gauge, else the catalogue gauge that leaves "
                        "the least error)")
    p.add_argument("--out", metavar="FILE", type=output_file(".json", ".md"), default=None,
                   help="also write the budget: .json as --json prints it, .md as the text")
    add_output_args(p, "print one JSON object: the budget of every unit and of the array")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def calibrations_from_file(path: str, plan, model: str = "closed-form"):
    """The calibration file ``path`` as the budget reads it: read and audited as ``tactcad
    calibrate --data`` reads and audits it (the same reader, the same refusals, the same
    force gauge where the file states none: the rigs'; the same flags, each a warning of the
    budget; :func:`tactcad.paper.calibration_audit.budget_calibration`).

    Returns:
        :class:`tactcad.studies.project_reports.BudgetCalibration`: the fits (element
        number -> :class:`~tactcad.mechanics.calibration.Calibration`), the audit, the
        warnings.

    Raises:
        CalibrationError: the file cannot be read or fitted, or names an element number the
            design does not have (:func:`tactcad.mechanics.calibration_file.read_calibration`).
    """
    from tactcad.paper.calibration_audit import budget_calibration

    return budget_calibration(plan, path, model, "--calibration")


def run(args: argparse.Namespace) -> int:
    shown = product_view("budget", args)  # a silicon die's design: its own figures
    if shown is not None:
        return shown
    from tactcad.atomic import write_bytes_atomic
    from tactcad.studies.project_reports import budget_record
    from tactcad.studies.verification import requirements_of

    plan = plan_from_args(args)
    progress = progress_from_args(args)
    cal = (calibrations_from_file(args.calibration, plan, args.model) if args.calibration
           else None)
    req = requirements_of(plan)
    force = req.full_scale_force_N if args.force_N is None else args.force_N
    progress(f"budget of {plan.name} at {force:g} N, {args.delta_T_K:g} K ({args.model})")
    record, budget = budget_record(plan, args.model, args.force_N, args.delta_T_K, args.points,
                                   calibration=cal)
    text = render(budget)
    for line in record.get("warnings", []):  # the calibration file's flags, in the text too
        text = f"{text}\n  warning: {line}"
    past = past_rating_words(force, req.full_scale_force_N, overload_forces(plan, budget))
    if past:  # a budget at a force the design is not rated for: said, in the text and --json
        warnings.warn(PastRatingWarning(past))
        text = f"{text}\n  warning: {past}"
    if args.out:
        body = dumps(record, indent=1) if args.out.lower().endswith(".json") else text
        write_bytes_atomic(args.out, (body + "\n").encode("utf-8"))
    print(dumps(record, indent=1) if args.json else text)
    return 0


def overload_forces(plan, budget) -> dict[int, tuple[float, float]]:
    """Each pressed element -> (the ``--force-N`` at which it reaches its overload limit, that
    limit) (N; yield with the design's safety factor or the gauge's largest strain, closed
    form, :func:`tactcad.studies.verification.element_overload_limits_N`). A reference
    carries the force itself; its measuring element F R K_m / K_r (eq. 1), the most at the
    K_obj range's soft end."""
    from tactcad.studies.verification import element_figures, element_overload_limits_N

    limits = element_overload_limits_N(plan, element_figures(plan))
    soft = budget.kobj_range_N_per_mm[0]
    out: dict[int, tuple[float, float]] = {}
    for u in budget.units:
        k_r, k_m = u["K_r_N_per_mm"], u["K_m_N_per_mm"]
        share = (1 + (k_r - k_m) / (k_m + soft)) * k_m / k_r  # F_m / F at the soft end
        for element, per_force in ((u["reference_element"], 1.0),
                                   (u["measuring_element"], share)):
            if element in limits:
                at = limits[element] / per_force
                out[element] = min(out.get(element, (at, limits[element])), (at, limits[element]))
    return out


def past_rating_words(force_N: float, rated_N: float,
                      overload: dict[int, tuple[float, float]]) -> str:
    """What a budget at ``force_N`` past the design's rating means, or "" within it.

    Args:
        force_N: the force on each unit's reference (N), as ``--force-N`` asks.
        rated_N: the design's rated full-scale force (N).
        overload: element -> (the force at which it reaches its overload limit, that limit)
            (N, :func:`overload_forces`).

    Returns:
        One sentence naming ``--force-N``, its value, the rating and, when the force is past
        an element's overload, the least such force and its element; "" at or below the
        rating.
    """
    if force_N <= rated_N * (1 + 1e-9):
        return ""
    words = (f"--force-N = {force_N:g} N is past the design's rated full-scale force "
             f"{rated_N:g} N: the budget is of a reading past full scale")
    if overload:
        element, (at, limit) = min(overload.items(), key=lambda item: item[1])
        if force_N > at * (1 + 1e-9):
            words += (f", and past {at:.4g} N, where element {element} reaches its overload "
                      f"limit {limit:.4g} N (yield with the safety factor, or the gauge's "
                      f"largest strain): it is damaged before it reads")
    return words + f" (allowed without this warning: --force-N <= {rated_N:g})"


def _pct(x) -> str:
    """A relative error as a percentage to 3 digits; "unreadable" when there is none."""
    import math

    # + 0.0: a zero term of a negative coefficient is -0.0, printed "-0 %"
    return "unreadable" if x is None or not math.isfinite(x) else f"{100 * x + 0.0:.3g} %"


def render(budget) -> str:
    """The budget as text: one table per unit (sources down, K_obj across, after correction;
    the before-correction value in brackets where a correction changes it) and the array's
    line of best units."""
    from tactcad.in_use.kobj_budget import SOURCES

    head = " | ".join(f"{k:.3g}" for k in budget.k_obj)
    lines = [f"K_obj error budget of {budget.design} ({budget.model}): reference force "
             f"{budget.force_N:.4g} N, temperature step {budget.delta_T_K:g} K, K_obj "
             f"{budget.kobj_range_N_per_mm[0]:g} ... {budget.kobj_range_N_per_mm[1]:g} N/mm",
             "  relative K_obj error after correction (before it in brackets)"]
    if not budget.units:
        lines.append("  no element is softer than its row's reference: the design reads no K_obj")
    for u in budget.units:
        lines += ["", f"unit {u['reference_element']}/{u['measuring_element']}: K_r "
                      f"{u['K_r_N_per_mm']:.4g} N/mm, K_m {u['K_m_N_per_mm']:.4g} N/mm; budget "
                      f"uncertainty {_pct(u['uncertainty_rel'])}",
                  f"| source | K_obj {head} N/mm |",
                  "| --- |" + " --- |" * len(budget.k_obj)]
        for s in SOURCES:
            v = u["sources"][s.key]
            cells = (["not modelled"] * len(budget.k_obj) if "not_modelled" in v else
                     [_pct(a) if a == b else f"{_pct(a)} ({_pct(b)})"
                      for a, b in zip(v["after_rel"], v["before_rel"])])
            lines.append(f"| {budget.source_words(s)} | " + " | ".join(cells) + " |")
        lines.append("| RSS | " + " | ".join(_pct(x) for x in u["rss_rel"]) + " |")
        lines.append("| worst case | " + " | ".join(_pct(x) for x in u["worst_case_rel"]) + " |")
        lines.append("| dominant | " + " | ".join(budget.dominant_words(d) for d in u["dominant"])
                     + " |")
        lines += readout_alone_lines(u, budget)
    lines += ["", *render_array(budget)]
    lines += [""] + [f"  {k}: {note_text(v)}" for k, v in budget.notes.items()]
    return "\n".join(lines)


def note_text(value) -> str:
    """A note's value as the text prints it: yes / no, "none" for a figure that does not
    apply, a number to four digits, words as they are (``--json`` keeps the values)."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if value is None:
        return "none"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def readout_alone_lines(unit: dict, budget) -> list[str]:
    """How a unit's read-out term differs from ``tactcad readout``'s K_obj resolution, as
    text: the unit alone (eq. 1-3, the same force, noise and K_obj, 1 sigma) and the coupled
    term over it, not summed; and the K_obj it reads none of (its own resolution past the
    required ``kobj_resolution_rel`` beyond the level's error), if any, and the K_obj where
    whether it reads is undecided inside that error."""
    lines = ["| unit alone: tactcad readout's K_obj resolution (1 sigma; not summed) | "
             + " | ".join(_pct(x) for x in unit["readout_alone_rel"]) + " |",
             "| read-out noise on the coupled sample / unit alone | "
             + " | ".join("n/a" if x is None else f"{x:.3g} x"
                          for x in unit["readout_coupled_over_alone"]) + " |"]
    unread = [k for k, reads in zip(budget.k_obj, unit["reads_kobj"]) if not reads]
    if unread:
        lines.append(
            f"  unit {unit['reference_element']}/{unit['measuring_element']} reads no K_obj at "
            + ", ".join(f"{k:.3g}" for k in unread)
            + f" N/mm: alone it resolves K_obj worse than the required "
            f"{_pct(budget.notes['readable_within_rel'])} (requirements.kobj_resolution_rel; "
            f"K_r / K_m = {unit['K_r_N_per_mm'] / unit['K_m_N_per_mm']:.4g}), as tactcad "
            f"verify's readable K_obj range judges; its read-out term is unreadable there")
    open_ = [k for k, o in zip(budget.k_obj, unit.get("reads_kobj_undecided", ())) if o]
    if open_:
        lines.append(
            f"  unit {unit['reference_element']}/{unit['measuring_element']} at "
            + ", ".join(f"{k:.3g}" for k in open_)
            + f" N/mm: alone it resolves K_obj within the required "
            f"{_pct(budget.notes['readable_within_rel'])} only at some K and grid strains "
            f"inside {budget.model}'s error on them: whether it reads there is undecided at "
            f"this level (its terms summed as read; verify's accuracy there is at best "
            f"undecided)")
    return lines


def render_array(budget) -> list[str]:
    """The array's line of best units as text lines: at each K_obj the unit that reads it
    best, its RSS and worst case after correction and the dominant source (none without a
    unit)."""
    a = budget.array
    if not a["unit"]:
        return []
    head = " | ".join(f"{k:.3g}" for k in budget.k_obj)
    return [f"K_obj error budget, array (best unit at each K_obj; {budget.model}, "
            f"{budget.force_N:.4g} N on the reference, {budget.delta_T_K:g} K step):",
            f"| | K_obj {head} N/mm |", "| --- |" + " --- |" * len(budget.k_obj),
            "| unit | " + " | ".join(a["unit"]) + " |",
            "| RSS | " + " | ".join(_pct(x) for x in a["rss_rel"]) + " |",
            "| worst case | " + " | ".join(_pct(x) for x in a["worst_case_rel"]) + " |",
            "| dominant | " + " | ".join(budget.dominant_words(d) for d in a["dominant"])
            + " |",
            *calibration_need_lines(budget)]


def calibration_need_lines(budget) -> list[str]:
    """The calibration's verdict on its force gauge as a text line, when the calibration
    term exceeds its allowance (the budget's ``calibration_allowance`` note), else none."""
    if budget.notes.get("calibration_gauge_fits", True):
        return []
    needed = budget.notes["calibration_gauge_resolution_needed_N"]
    head = f"resolution {needed:.2g} N needed; " if needed is not None else ""
    return [f"calibration force gauge: {head}{budget.notes['calibration_allowance']}"]
