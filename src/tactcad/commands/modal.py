"""``tactcad modal``: natural frequencies (Hz) and mode shapes of the elements."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view, progress_from_args)
from tactcad.commands.options import (check_element_option, count, element_number,
                                      keep_option_defaults, number, output_folder)
from tactcad.errors import TactcadError
from tactcad.mechanics.modal_ladder import MODAL_LEVELS, modal_levels_help, modal_models
from tactcad.mechanics.modal_result import PLUS_MINUS_LIMIT_REL, error_words
from tactcad.studies.project_reports import MAX_TIP_MASS_MG


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("modal", help="natural frequencies (Hz) of each element as clamped",
                       description="The lowest natural frequencies and mode families of each "
                                   "distinct element (or one), clamped as in the stiffness "
                                   "model, at a modal level, with the error estimate of the "
                                   "first and the wall time. Units: Hz, s.")
    p.add_argument("--element", type=element_number, default=None,
                   help="element number of the design (default: every distinct element)")
    p.add_argument("--model", choices=modal_models(), default="closed-form",
                   help=f"modal level: {modal_levels_help()}; a silicon die's design: "
                        "closed-form or fem3d (each row's beam on its frame, as `tactcad die "
                        "--fem3d` solves it, about a minute and a half) (default %(default)s)")
    p.add_argument("--modes", type=count(1, 20, "modes per element"), default=3,
                   help="modes per element, 1 ... 20 (FEM levels; the closed form gives the "
                        "first; default %(default)s)")
    p.add_argument("--bare", action="store_true",
                   help="leave out the gauge installation's mass (gauge, adhesive, lead, "
                        "terminals; counted by default at their places); the stiffness stays "
                        "the element's with its bonded gauge")
    p.add_argument("--tip-mass-mg", type=number(0.0, MAX_TIP_MASS_MG, "mg"), default=0.0,
                   metavar="MG",
                   help="a further mass at the contact centre (mg; a tip cover, a pad), "
                        "0 ... 10000 (default 0)")
    p.add_argument("--vtu", metavar="DIR", type=output_folder, default=None,
                   help="fem2d/fem3d: also write each element's mode shapes as "
                        "DIR/<part>_modes_<model>.vtu (ParaView)")
    add_design_arg(p)
    add_cache_args(p)
    add_output_args(p, "print JSON")
    p.set_defaults(func=run_modal)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def run_modal(args: argparse.Namespace) -> int:
    shown = product_view("modal", args)  # a silicon die's design: its own figures
    if shown is not None:
        return shown
    from tactcad.mechanics.fem.fem_modal import write_modes_vtu
    from tactcad.studies.project_reports import modes_record

    meshed = MODAL_LEVELS[args.model].meshed
    if args.vtu is not None and not meshed:
        raise TactcadError(f"--vtu {args.vtu}: allowed with --model fem2d or fem3d only "
                           f"(got --model {args.model})")
    plan = plan_from_args(args)
    report = progress_from_args(args)
    if args.element is not None:
        check_element_option(args.element, plan)
    record, results = modes_record(plan, args.model, args.modes, args.element, args.bare,
                                   args.tip_mass_mg, report, keep_shapes=args.vtu is not None)
    records = record["elements"]
    for rec, (part, r) in zip(records, results):
        if args.vtu is not None:
            path = write_modes_vtu(Path(args.vtu) / f"{part}_modes_{args.model}.vtu", r.solve)
            rec["vtu"] = str(path)
            report(f"wrote {path} ({len(r.modes)} mode shapes)")
    lowest = min(records, key=lambda rec: rec["first_Hz"])
    if args.json:
        print(json.dumps(record, indent=2))
        return 0
    families = MODAL_LEVELS[args.model].families
    print(f"natural frequencies, model {args.model} (clamped as in the stiffness model; "
          f"{' and '.join(families)} modes"
          + ("" if "out-of-plane" in families else
             ", fem3d adds the out-of-plane ones" if args.model != "closed-form" else
             "; the first out-of-plane one estimated between its bounds") + "; "
          + ("without the gauge installation's mass (its glue line and carrier still in K)"
             if args.bare else "with the gauge installation's mass")
          + (f" and {args.tip_mass_mg:g} mg at the tip" if args.tip_mass_mg else "") + ")")
    for rec in records:
        els = ", ".join(str(n) for n in rec["elements"])
        freqs = ", ".join(f"{m['frequency_Hz']:.1f} ({m['family']}"
                          + error_words(m.get("frequency_Hz_error_rel"),
                                        m.get("frequency_Hz_bounds")) + ")"
                          for m in rec["modes"])
        first = rec["modes"][0]
        first_error = (f"{100 * rec['first_Hz_error_rel']:.2f} %"
                       if rec["first_Hz_error_rel"] <= PLUS_MINUS_LIMIT_REL
                       or "frequency_Hz_bounds" not in first else
                       error_words(rec["first_Hz_error_rel"],
                                   first["frequency_Hz_bounds"]).strip())
        bare = (f"; {rec['bare_first_Hz']:.1f} Hz without the {1e3 * rec['added_mass_g']:.3g} mg"
                if rec["bare_first_Hz"] is not None else "")
        print(f"  {rec['part']} (element {els}): {freqs} Hz{bare}; the first's error estimate "
              f"{first_error}, {rec['wall_time_s']:.3g} s")
    print(f"lowest first frequency: {lowest['first_Hz']:.1f} Hz ({lowest['part']})")
    return 0
