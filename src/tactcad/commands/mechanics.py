"""``tactcad stiffness`` and ``tactcad table1``: the element-stiffness ladder."""

from __future__ import annotations

import argparse
import json

from tactcad.mechanics.ladder import is_meshed, levels_help, models
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              progress_from_args, load_from_args, product_view)
from tactcad.commands.options import (check_element_option, element_number, keep_option_defaults,
                                      number, output_folder)
from tactcad.errors import DesignError, TactcadError
from tactcad.products.silicon_die.mechanics import DIE_STIFFNESS_LEVELS


def stiffness_levels_words(ladder: tuple[str, ...], die_levels: tuple[str, ...]) -> str:
    """Which stiffness levels each construction's element takes, for ``--model``'s help:
    a stacked array's and a monolithic comb's element (a flexure of the plan's element
    geometry) every level of the ladder, a silicon die's beams its own.

    Args:
        ladder: the ladder's levels, cheapest first (:func:`tactcad.mechanics.ladder.models`).
        die_levels: the die's levels (:data:`DIE_STIFFNESS_LEVELS`).

    Returns:
        The words, e.g. ``a stacked array's and a monolithic comb's element: closed-form,
        beam, fem2d, fem3d; a silicon die's beams: closed-form, fem3d (not beam, fem2d)``.
    """
    not_die = [n for n in ladder if n not in die_levels]
    return (f"a stacked array's and a monolithic comb's element: {', '.join(ladder)}; "
            f"a silicon die's beams: {', '.join(n for n in ladder if n in die_levels)}"
            + (f" (not {', '.join(not_die)})" if not_die else ""))


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("stiffness", help="tip stiffness K (N/mm) of one element at a ladder level",
                       description="Tip stiffness, face strain at the grid's centre and grid "
                                   "strain per newton, error estimate and wall time of one "
                                   "sensing element (a silicon die: each row's beam on its "
                                   "frame, closed-form or fem3d). Units: N/mm, 1/N, s.")
    p.add_argument("--element", type=element_number, default=None,
                   help="element number of an array's design (1 ... rows x columns, numbered "
                        "along row 1, then row 2; required for an array; a silicon die gives "
                        "each row's beam)")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help=f"ladder level: {levels_help()} (default %(default)s); "
                        f"{stiffness_levels_words(models(), DIE_STIFFNESS_LEVELS)}")
    add_design_arg(p)
    add_cache_args(p)
    add_output_args(p, "print JSON")
    p.add_argument("--vtk", metavar="DIR", type=output_folder, default=None,
                   help="fem2d/fem3d: also write the finest mesh's displacement and von Mises "
                        "stress under 1 N as DIR/<part>_<model>.vtu (ParaView)")
    keep_option_defaults(p)  # a die's design: its view refuses an array's options
    p.set_defaults(func=run_stiffness)

    t = sub.add_parser("table1", help="predicted vs measured stiffness of every element (Table 1)",
                       description="Every calibrated element of the paper's Table 1 at a ladder "
                                   "level, with % error, plus the as-built web thickness and the "
                                   "face strain at the notch centre at 2 N.")
    t.add_argument("--model", choices=models() + ("all",), default="closed-form",
                   help="ladder level, or 'all' for every level side by side (fem3d takes 10 s-2 min an "
                        "element; "
                        "default %(default)s)")
    add_design_arg(t)
    add_cache_args(t)
    add_output_args(t, "print JSON")
    t.set_defaults(func=run_table1)


def missing_element_error(plan) -> DesignError:
    """The refusal of ``stiffness`` without ``--element`` on an array's design: the
    design's element numbers, and its first element to paste.

    Args:
        plan: the design's plan (its ``slots``, numbered 1 ... rows x columns).

    Returns:
        A :class:`~tactcad.errors.DesignError` naming ``--element`` and the numbers allowed.
    """
    numbers = sorted(s.number for s in plan.slots)
    return DesignError("--element", None, f"a value: an element number of the design, "
                       f"{numbers[0]} ... {numbers[-1]} (rows x columns)",
                       "required for an array's design, whose stiffness is one element's (a "
                       "die's file gives each row's beam)",
                       alternatives=[{"option": f"--element {numbers[0]}",
                                      "words": f"its first element; any of {numbers[0]} ... "
                                               f"{numbers[-1]} is one"}])


def run_stiffness(args: argparse.Namespace) -> int:
    shown = product_view("stiffness", args)  # a silicon die's design: each row's beam
    if shown is not None:
        return shown
    project = load_from_args(args)
    if args.element is None:
        raise missing_element_error(project.plan)
    check_element_option(args.element, project.plan)
    plan, element = project.plan, project.element(args.element)
    slot = element.slot
    if args.vtk is not None and not is_meshed(args.model):
        raise TactcadError(f"--vtk {args.vtk}: allowed with --model fem2d or fem3d only "
                           f"(got --model {args.model})")
    levels = {"progress": progress_from_args(args)} if is_meshed(args.model) else {}
    r = element.stiffness(args.model, **levels)
    vtu = None
    if args.vtk is not None:
        from tactcad.mechanics.fem.field_files import write_element_vtu

        vtu = write_element_vtu(args.vtk, slot.geometry, plan.material, args.model).path
        progress_from_args(args)(f"wrote {vtu} (displacement, von Mises stress under 1 N)")
    with_gauge = slot.geometry.gauge is not None
    grid, grid_error = r.grid_strain_per_N, None  # what the grid reads, as `readout` gives it
    if with_gauge:  # its error at this level
        from tactcad.mechanics.readout_chain import (grid_strain_error_rel, grid_strain_per_N,
                                                     readout_chain)

        read = grid_strain_per_N(slot.geometry, plan.material, readout_chain(plan), args.model)
        grid_error = grid_strain_error_rel(read)
    if args.json:
        out = {**r.as_json(), "grid_strain_per_N": grid, "grid_strain_error_rel": grid_error,
               "with_gauge": with_gauge}
        if vtu is not None:
            out["vtu"] = str(vtu)
        print(json.dumps(out, indent=2))
    else:
        print(f"element {r.element} ({slot.geometry.part_name}), model {r.model}")
        print(f"  K                   {r.stiffness_N_per_mm:10.4f} N/mm"
              + ("  (with its bonded gauge's glue line and carrier; `tactcad readout` states "
                 "how much they add)" if with_gauge else ""))
        print(f"  face strain         {r.face_strain_per_N * 1e6:10.2f} microstrain/N"
              "  (magnitude; the top face at the notch centre"
              + (", under the gauge's glue line and carrier)" if with_gauge else ")"))
        if grid is not None:
            print(f"  grid strain         {grid * 1e6:10.2f} microstrain/N"
                  "  (what the gauge reads: its grid's plane averaged over the grid; signed, "
                  "negative where the tip force compresses the face)")
        print(f"  error estimate      {100 * r.error_estimate_rel:10.3f} %  (K)")
        if grid_error is not None:
            print(f"                      {100 * grid_error:10.3f} %  (grid strain)")
        print(f"  wall time           {r.wall_time_s:10.4f} s")
    return 0


def run_table1(args: argparse.Namespace) -> int:
    from tactcad.mechanics.ladder import gauge_rise_error_rel, is_meshed
    from tactcad.paper.table1 import PAPER_STRAIN_RANGE, as_built_webs, gauge_layer_shift, gauge_strain_at_paper_load, require_table1, table1_comparison, table2_predicted

    plan = plan_from_args(args)
    require_table1(plan)
    report = progress_from_args(args)
    progress = (lambda s: report(f"  ... {s}"))
    if args.model == "all":
        return _table1_all_levels(plan, args.json, progress)
    rows = table1_comparison(plan, args.model, progress=progress)
    webs = as_built_webs(plan)
    strains = gauge_strain_at_paper_load(plan)
    t2 = table2_predicted(plan, args.model)
    if args.json:
        print(json.dumps({"model": args.model, "table1": [r.as_json() for r in rows],
                          "gauge_layer": gauge_layer_shift(rows),
                          "as_built_web": webs, "gauge_strain_2N": strains, "table2": t2}, indent=2))
        return 0
    print(f"Table 1, model {args.model}: predicted vs measured K (N/mm)")
    print(f"{'el':>3} {'arm mm':>7} {'measured':>9} {'predicted':>10} {'error %':>8} {'est. err %':>10}"
          f" {'as cut':>8} {'error %':>8} {'as-built web mm':>16}")
    for r, w in zip(rows, webs):
        print(f"{r.element:>3} {r.arm_length_mm:>7.1f} {r.measured_N_per_mm:>9.2f} "
              f"{r.predicted.stiffness_N_per_mm:>10.2f} {r.error_percent:>8.1f} "
              f"{100 * r.predicted.error_estimate_rel:>10.2f} {r.without_gauge_layer_N_per_mm:>8.2f} "
              f"{r.without_gauge_layer_error_percent:>8.1f} {w['web_as_built_mm']:>16.4f}")
    shift = gauge_layer_shift(rows)
    lo, hi = (100 * x for x in shift["k_rise_rel"])
    (m0, m1), (a0, a1) = shift["mean_error_percent"], shift["mean_abs_error_percent"]
    how = ("its glue line and carrier meshed" if is_meshed(args.model) else
           f"the {args.model} level's layer term, within "
           f"{100 * gauge_rise_error_rel(args.model):.0f} % of itself against fem3d with the "
           "layer meshed")
    print(f"predicted: K with the bonded gauge's glue line and carrier on the web, as the paper "
          f"measured its elements (+{lo:.1f}" + ("" if hi - lo < 0.05 else f" ... +{hi:.1f}")
          + f" % on the element as cut, {how}); as cut: without it. Mean error {m0:+.1f} "
          f"(as cut) -> {m1:+.1f} %, mean |error| {a0:.1f} -> {a1:.1f} %; the paper's webs as "
          "built (last column) move K far more")
    lo, hi = PAPER_STRAIN_RANGE
    print("face strain at the notch centre at 2 N, the element as cut, without the gauge "
          "(closed form, %; the paper's ANSYS surface strain): "
          + ", ".join(f"a={s['arm_length_mm']:g}: {s['face_strain_as_cut_percent']:.3f}"
                      for s in strains)
          + f"   paper: {100 * lo:.4f}-{100 * hi:.4f}")
    print(f"Table 2: eq. 2 with predicted K (K_r = {t2['k_r_predicted_N_per_mm']:.2f} N/mm): "
          f"{t2['n_in_domain']}/48 rows in domain, mean |R error| {t2['mean_abs_error']:.3f}, "
          f"max {t2['max_abs_error']:.3f}")
    return 0


def _table1_all_levels(plan, as_json: bool, progress) -> int:
    """Table 1 with every ladder level side by side: K (N/mm) and % error."""
    from tactcad.paper.table1 import table1_comparison

    levels = {m: table1_comparison(plan, m, progress=progress) for m in models()}
    if as_json:
        print(json.dumps({m: [r.as_json() for r in rows] for m, rows in levels.items()}, indent=2))
        return 0
    print("Table 1: measured K vs every level, K in N/mm (error %)")
    print(f"{'el':>3} {'arm mm':>7} {'measured':>9} " + " ".join(f"{m:>17}" for m in models()))
    for i, r in enumerate(levels[models()[0]]):
        cells = " ".join(f"{levels[m][i].predicted.stiffness_N_per_mm:>9.2f} ({levels[m][i].error_percent:+6.1f})"
                         for m in models())
        print(f"{r.element:>3} {r.arm_length_mm:>7.1f} {r.measured_N_per_mm:>9.2f} {cells}")
    return 0
