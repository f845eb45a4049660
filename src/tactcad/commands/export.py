"""``tactcad export``: write STEP, DXF and the manifest for a design."""

from __future__ import annotations

import argparse

from tactcad.commands import add_design_arg


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export", help="write STEP, wire-EDM DXF, scenes, drawings, BOM and manifest",
                       description="Build the design's parts and write exports/: step/<part>.step, "
                                   "step/array.step, dxf/element_<n>.dxf, scenes/<scene>.step and "
                                   ".glb (see `tactcad scenes`), drawings/<part>.svg and "
                                   "drawings.pdf, bom.csv and bom.md, images/*.png and "
                                   "manifest.json.")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", default="exports", help="output folder (default: exports)")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="write only this scene: scenes/NAME.step and scenes/NAME.glb "
                        "(repeatable; the manifest is left as it is). `tactcad scenes` lists them")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.design.array import load_design
    from tactcad.export.run import export

    plan = load_design(args.design)  # validation first: a bad design writes nothing
    print(f"tactcad export: design {plan.name} ({plan.source}), sha256 {plan.design_hash[:12]}")
    if args.scene:
        from tactcad.export.scenes import export_scenes

        for line in export_scenes(plan, args.out, args.scene).summary_lines():
            print(line)
        return 0
    result = export(plan, args.out)
    for line in result.summary_lines():
        print(line)
    return 0
