"""``tactcad check``: build, export to a scratch folder and run every check."""

from __future__ import annotations

import argparse
import tempfile

from tactcad.commands import add_design_arg


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("check", help="run part, DXF, STEP and interference checks",
                       description="Export the design to a scratch folder (or --out) and run every "
                                   "check; exit 1 if any fails.")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", default=None,
                   help="export here instead of a temporary folder")
    p.add_argument("--failures-only", action="store_true", help="print failing checks only")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="check only this scene (repeatable): interference, geometry sanity, STEP "
                        "and GLB read-back; without it the array and every scene are checked")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.checks.array import run_checks
    from tactcad.checks.result import failures
    from tactcad.checks.scenes import run_scene_checks
    from tactcad.design.array import load_design
    from tactcad.export.run import export, export_scenes
    from tactcad.parts.cache import PartCache

    plan = load_design(args.design)
    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or tmp
        cache = PartCache(plan)
        if args.scene:
            export_scenes(plan, out, args.scene, log=lambda s: None, parts=cache)
            results = run_scene_checks(plan, out, args.scene, cache=cache)
        else:
            export(plan, out, log=lambda s: None, parts=cache)
            results = run_checks(plan, out, cache) + run_scene_checks(plan, out, cache=cache)
    for r in results:
        if r.passed and args.failures_only:
            continue
        print(r.line())
    bad = failures(results)
    print(f"{len(results) - len(bad)} passed, {len(bad)} failed")
    return 1 if bad else 0
