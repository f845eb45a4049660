"""``tactcad export``: write STEP, DXF and the manifest for a design."""

from __future__ import annotations

import argparse
import json

from tactcad.commands import add_cache_args, add_design_arg, store_from_args


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export", help="write STEP, wire-EDM DXF, scenes, drawings, BOM and manifest",
                       description="Build the design's parts and write exports/: step/<part>.step, "
                                   "step/array.step, dxf/<part>_qty<n>.dxf and "
                                   "dxf/sheet_<material>_<t>mm.dxf, scenes/<scene>.step (Z up) and "
                                   ".glb (see `tactcad scenes`), review/<scene>.FCStd (when FreeCAD "
                                   "is installed), drawings/<part>.svg and "
                                   "drawings.pdf, bom.csv and bom.md, images/*.png and "
                                   "manifest.json.")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", default="exports", help="output folder (default: exports)")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="write only this scene: scenes/NAME.step, scenes/NAME.glb and "
                        "review/NAME.FCStd "
                        "(repeatable; the manifest is left as it is). `tactcad scenes` lists them")
    add_cache_args(p)
    p.add_argument("--json", action="store_true",
                   help="print a JSON summary (seconds, jobs run and reused, builds, files)")
    p.add_argument("--dxf-version", choices=("R2010", "R12"), default=None,
                   help="DXF version of the shop files: R2010 (default) or R12 for old CAM "
                        "(POLYLINE with bulges instead of LWPOLYLINE))")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.design.array import load_design
    from tactcad.export.run import export, export_scenes

    plan = load_design(args.design)  # validation first: a bad design writes nothing
    log = (lambda s: None) if args.json else print
    log(f"tactcad export: design {plan.name} ({plan.source}), sha256 {plan.design_hash[:12]}")
    store = store_from_args(args)
    if args.scene:
        result = export_scenes(plan, args.out, args.scene, log=log, store=store)
    else:
        result = export(plan, args.out, log=log, store=store, dxf_version=args.dxf_version)
    if args.json:
        print(json.dumps(result.as_json(), indent=1))
        return 0
    for line in result.summary_lines():
        print(line)
    if args.scene:
        print("manifest.json not rewritten (full export only)")
    return 0
