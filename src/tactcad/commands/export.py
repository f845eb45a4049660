"""``tactcad export``: write STEP, DXF and the manifest for a design."""

from __future__ import annotations

import argparse

from . import add_design_arg


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
    p.add_argument("--dxf-version", choices=("R2010", "R12"), default=None,
                   help="DXF version of the shop files: R2010 (default) or R12 for old CAM "
                        "(POLYLINE with bulges instead of LWPOLYLINE); same as "
                        "TACTCAD_DXF_VERSION=R12")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..design import load_design
    from ..exporter import export

    if args.dxf_version:
        import os

        from ..export.dxf_sheet import DXF_VERSION_ENV

        os.environ[DXF_VERSION_ENV] = args.dxf_version
    plan = load_design(args.design)  # validation first: a bad design writes nothing
    print(f"tactcad export: design {plan.name} ({plan.source}), sha256 {plan.design_hash[:12]}")
    if args.scene:
        from ..scene_export import export_scenes

        for line in export_scenes(plan, args.out, args.scene).summary_lines():
            print(line)
        return 0
    result = export(plan, args.out)
    for line in result.summary_lines():
        print(line)
    return 0
