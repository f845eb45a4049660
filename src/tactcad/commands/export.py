"""``tactcad export``: write STEP, DXF and the manifest for a design."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from tactcad.commands.options import output_folder
from tactcad.atomic import SYSTEM_RULE
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, project_from_args,
                              progress_from_args, refuse_unknown_scenes, store_from_args)
from tactcad.export.kinds import EXPORT_KINDS, kinds_help, parse_only


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export", help="write STEP, wire-EDM DXF, scenes, drawings, BOM and manifest",
                       description="Build the design's parts and write exports/: "
                                   + ", ".join(k.writes for k in EXPORT_KINDS.values())
                                   + " and manifest.json (`tactcad scenes` lists the scenes). "
                                   "Progress (one line per job run) goes to stderr.")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", type=output_folder, default="exports",
                   help="output folder (default: exports), " + SYSTEM_RULE + "; not the home, "
                        "working or /tmp folder itself either (an export replaces its folder "
                        "as a whole)")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="write only this scene: scenes/NAME.step, scenes/NAME.glb and "
                        "review/NAME.FCStd "
                        "(repeatable; the manifest is left as it is). `tactcad scenes` lists them")
    p.add_argument("--only", metavar="KINDS", action="append", default=None,
                   help="write only these kinds of file, comma-separated: " + kinds_help()
                        + "; into an export of the same design the other files are kept "
                          "and the manifest lists them all, naming under \"partial\" what was "
                          "written now; another design's export is refused (default: every "
                          "kind)")
    p.add_argument("--part", metavar="NAME", action="append", default=None,
                   help="write only this part's own files: its STEP, its drawing and, for "
                        "a part cut from sheet, its DXF profile dxf/<part>_qty<n>.dxf, not the "
                        "nested sheet (which holds every part cut from it) (repeatable; "
                        "combines with --only, e.g. --only dxf --part NAME for the wire-EDM "
                        "shop)")
    add_cache_args(p)
    add_output_args(p, "print a JSON summary (seconds, jobs run and reused, builds, files)")
    p.add_argument("--dxf-version", choices=("R2010", "R12"), default=None,
                   help="DXF version of the shop files: R2010 (default) or R12 for old CAM "
                        "(POLYLINE with bulges instead of LWPOLYLINE))")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.commands import design_and_product
    from tactcad.errors import DesignError

    found = design_and_product(args)
    if found is not None and not found[1].is_default:  # another product's export (a die's)
        return found[1].hook("export")(found[0], args)
    # the options first, before the design and the writers are loaded: a refusal is quick
    only, parts = parse_only(args.only), list(args.part or ())
    if args.scene and (only or parts):
        raise DesignError("--scene", args.scene, "alone, without --only or --part")

    from tactcad.export.live import unmet_line
    from tactcad.export.run import export, export_scenes
    from tactcad.export.selection import (ReportingParts, partial_record, select_jobs,
                                          with_progress)

    project = project_from_args(args)  # validation next: a bad design writes nothing
    refuse_unknown_scenes(project, args.scene)  # before --out is looked at or a job planned
    plan = project.plan
    report = progress_from_args(args)
    store = store_from_args(args)
    cache = ReportingParts(plan, report)
    if args.scene:
        result = export_scenes(project, args.out, args.scene, log=lambda s: None, store=store,
                               parts=cache)
    else:
        partial = {} if only or parts else None  # filled in once the jobs are known

        def select(jobs):  # called once --out is found fit, before any job runs
            report(f"tactcad export: design {plan.name} ({plan.source}), "
                   f"sha256 {plan.design_hash[:12]}")
            chosen = select_jobs(jobs, only, parts) if partial is not None else list(jobs)
            if partial is not None:
                partial.update(partial_record(only, parts, chosen))
            report(f"{len(chosen)} jobs" + (f" of {len(jobs)}" if len(chosen) < len(jobs) else "")
                   + "; those not in the store run now")
            return with_progress(chosen, report)

        result = export(project, args.out, log=lambda s: None, store=store, parts=cache,
                        dxf_version=args.dxf_version, select=select,
                        partial=partial, kinds=only)
    # the requirements the export's manifest fails, as watch reads them (closed form)
    unmet = "" if args.scene else unmet_line(Path(result.out_dir))
    if args.json:
        print(json.dumps(result.as_json(), indent=1))
        if unmet:  # stdout stays one JSON document; the manifest holds the table
            print(unmet, file=sys.stderr)
        return 0
    for line in result.summary_lines():
        print(line)
    if args.scene:
        print("manifest.json not rewritten (full export only)")
    if unmet:
        print(unmet)
    return 0
