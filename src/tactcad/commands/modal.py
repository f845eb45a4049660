"""``tactcad modal``: natural frequencies (Hz) and mode shapes of the elements."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              progress_from_args)
from tactcad.commands.options import count
from tactcad.errors import TactcadError
from tactcad.mechanics.modal_ladder import MODAL_LEVELS, modal_levels_help, modal_models


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("modal", help="natural frequencies (Hz) of each element as clamped",
                       description="The lowest natural frequencies and mode families of each "
                                   "distinct element (or one), clamped as in the stiffness "
                                   "model, at a modal level, with the error estimate of the "
                                   "first and the wall time. Units: Hz, s.")
    p.add_argument("--element", type=count(1, 10_000, "an element number"), default=None,
                   help="element number of the design (default: every distinct element)")
    p.add_argument("--model", choices=modal_models(), default="closed-form",
                   help=f"modal level: {modal_levels_help()} (default %(default)s)")
    p.add_argument("--modes", type=count(1, 20, "modes per element"), default=3,
                   help="modes per element, 1 ... 20 (FEM levels; the closed form gives the "
                        "first; default %(default)s)")
    p.add_argument("--vtu", metavar="DIR", default=None,
                   help="fem2d/fem3d: also write each element's mode shapes as "
                        "DIR/<part>_modes_<model>.vtu (ParaView)")
    add_design_arg(p)
    add_cache_args(p)
    add_output_args(p, "print JSON")
    p.set_defaults(func=run_modal)


def run_modal(args: argparse.Namespace) -> int:
    from tactcad.mechanics.fem.fem_modal import write_modes_vtu
    from tactcad.mechanics.modal_ladder import estimate_modes

    meshed = MODAL_LEVELS[args.model].meshed
    if args.vtu is not None and not meshed:
        raise TactcadError(f"--vtu {args.vtu}: allowed with --model fem2d or fem3d only "
                           f"(got --model {args.model})")
    plan = plan_from_args(args)
    report = progress_from_args(args)
    if args.element is not None:
        slot = plan.element(args.element)
        chosen = {slot.geometry.part_name: (slot.geometry, [slot.number])}
    else:
        chosen = {}
        for s in plan.slots:
            chosen.setdefault(s.geometry.part_name, (s.geometry, []))[1].append(s.number)
    records = []
    for part, (g, numbers) in chosen.items():
        opts = {"progress": report, "keep_shapes": args.vtu is not None} if meshed else {}
        r = estimate_modes(args.model, g, plan.material, element=numbers[0], modes=args.modes,
                           **opts)
        rec = {"part": part, "elements": numbers, **r.as_json()}
        if args.vtu is not None:
            path = write_modes_vtu(Path(args.vtu) / f"{part}_modes_{args.model}.vtu", r.solve)
            rec["vtu"] = str(path)
            report(f"wrote {path} ({len(r.modes)} mode shapes)")
        records.append(rec)
    lowest = min(records, key=lambda rec: rec["first_Hz"])
    if args.json:
        print(json.dumps({"model": args.model, "families": list(MODAL_LEVELS[args.model].families),
                          "elements": records,
                          "lowest_first_Hz": lowest["first_Hz"],
                          "lowest_part": lowest["part"]}, indent=2))
        return 0
    families = MODAL_LEVELS[args.model].families
    print(f"natural frequencies, model {args.model} (clamped as in the stiffness model; "
          f"{' and '.join(families)} modes"
          + ("" if "out-of-plane" in families else ", fem3d adds the out-of-plane ones") + ")")
    for rec in records:
        els = ", ".join(str(n) for n in rec["elements"])
        freqs = ", ".join(f"{m['frequency_Hz']:.1f} ({m['family']})" for m in rec["modes"])
        print(f"  {rec['part']} (element {els}): {freqs} Hz; error estimate "
              f"{100 * rec['error_estimate_rel']:.2f} %, {rec['wall_time_s']:.3g} s")
    print(f"lowest first frequency: {lowest['first_Hz']:.1f} Hz ({lowest['part']})")
    return 0
