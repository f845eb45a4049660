"""``tactcad check``: check the export of a design (reused, or written with the store)."""

from __future__ import annotations

import argparse
import tempfile
import time

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              progress_from_args, store_from_args)
from tactcad.commands.finite_json import dumps


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("check", help="run part, DXF, STEP and interference checks",
                       description="Check the export of the design and exit 1 if any check "
                                   "fails. With --out DIR holding an export of the same design "
                                   "(manifest design sha256 and every file's sha256 matching) "
                                   "those files are checked as they are; otherwise the design "
                                   "is exported there (or to a temporary folder) first, reusing "
                                   "the store of finished jobs. Each group's results are printed "
                                   "as it finishes.")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", default=None,
                   help="the export to check (exported here first unless it is the design's "
                        "current one); default: a temporary folder")
    p.add_argument("--failures-only", action="store_true", help="print failing checks only")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="check only this scene (repeatable): interference, geometry sanity, STEP "
                        "and GLB read-back; without it the array and every scene are checked")
    add_cache_args(p)
    add_output_args(p, "print one JSON object: the export checked, each check and the counts")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.checks.array import run_checks
    from tactcad.checks.result import failures
    from tactcad.checks.scenes import run_scene_checks
    from tactcad.export.reuse import reuse_refusal
    from tactcad.export.selection import ReportingParts

    plan = plan_from_args(args)
    report = progress_from_args(args)
    cache = ReportingParts(plan, report)
    results = []
    t0 = time.perf_counter()

    def done(group: str, found: list) -> None:
        results.extend(found)
        bad = len(failures(found))
        report(f"{group}: {len(found) - bad} passed, {bad} failed "
               f"({time.perf_counter() - t0:.1f} s)")
        if not args.json:
            for r in found:
                if not (r.passed and args.failures_only):
                    print(r.line(), flush=True)

    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or tmp
        refusal = reuse_refusal(plan, out)
        if refusal is None:
            report(f"checking the export in {out} (same design, every file as listed)")
        else:
            report(f"exporting to {out} first: {refusal}")
            export_for_check(plan, out, args, cache, report)
        if args.scene:
            run_scene_checks(plan, out, args.scene, cache=cache, done=done)
        else:
            run_checks(plan, out, cache, done=done)
            run_scene_checks(plan, out, cache=cache, done=done)
    bad = failures(results)
    if args.out:  # the export's review page shows them (review/checks.js)
        from tactcad.export.review_page import write_checks_script

        write_checks_script(args.out, plan.design_hash, results)
    if args.json:
        print(dumps({"out": args.out, "reused_export": refusal is None,
                          "export_refusal": refusal, "passed": len(results) - len(bad),
                          "failed": len(bad),
                          "checks": [{"check": r.check, "subject": r.subject, "passed": r.passed,
                                      "detail": r.detail} for r in results
                                     if not (r.passed and args.failures_only)]}, indent=1))
    else:
        print(f"{len(results) - len(bad)} passed, {len(bad)} failed")
    return 1 if bad else 0


def export_for_check(plan, out: str, args: argparse.Namespace, cache, report) -> None:
    """Export ``plan`` (or only ``--scene``) into ``out`` with the store, reporting each job."""
    from tactcad.export.run import export, export_scenes
    from tactcad.export.selection import with_progress

    store = store_from_args(args)
    if args.scene:
        export_scenes(plan, out, args.scene, log=lambda s: None, store=store, parts=cache)
    else:
        export(plan, out, log=lambda s: None, store=store, parts=cache,
               select=lambda jobs: with_progress(jobs, report))
