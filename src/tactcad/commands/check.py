"""``tactcad check``: check the export of a design (reused, or written with the store)."""

from __future__ import annotations

import argparse
import time

from tactcad.commands.options import output_file, output_folder
from tactcad.checks.check_result import counts_text, reported_passed, status_counts, status_of
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, progress_from_args,
                              load_from_args, refuse_unknown_scenes)
from tactcad.commands.finite_json import dumps

#: The statuses ``--failures-only`` leaves out: passed, and info (reported, not judged).
SHOWN_IN_FULL_ONLY = ("pass", "info")


def register(sub: argparse._SubParsersAction) -> None:
    from tactcad.checks.groups import groups_help

    p = sub.add_parser("check", help="run part, DXF, STEP and interference checks",
                       description="Check the export of the design and exit 1 if any check "
                                   "fails. With --out DIR holding an export of the same design "
                                   "(the manifest's design sha256 matching) its files are "
                                   "checked as they are; a file changed or removed by hand "
                                   "since (sha256 not as the manifest lists) is never written "
                                   "over: it fails the export files check, and `tactcad export "
                                   "--out DIR` writes it again. A DIR holding the export of "
                                   "a design of another name (or product), or files no "
                                   "export wrote, is refused, as export refuses it. An "
                                   "export of this design's name made from other content "
                                   "(another sha256, e.g. another --set) is exported over, "
                                   "as export replaces it, even with files edited by hand "
                                   "(the line says `made from another design`; use another "
                                   "--out to keep it). Only "
                                   "when DIR holds no export, such an earlier export of this "
                                   "design's name, or (nothing edited) a partial one, one "
                                   "of another tactcad version or one older than an edit of "
                                   "the project's rigs, scenes or other files it was made from "
                                   "(the manifest's inputs; with files edited by hand that "
                                   "fails the export files check instead), is the design "
                                   "exported there "
                                   "(or to a temporary folder without --out) first, reusing "
                                   "the store of finished jobs. Each group's results are printed "
                                   "as it finishes. The groups, in order: " + groups_help() + ".")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help="the export to check (exported here first unless it holds an export "
                        "of the design; files edited by hand are never written over); default: "
                        "a temporary folder")
    p.add_argument("--failures-only", action="store_true",
                   help="print failing and undecided checks only")
    p.add_argument("--scene", metavar="NAME", action="append", default=None,
                   help="check only this scene (repeatable): interference, geometry sanity, STEP "
                        "and GLB read-back; without it the array and every scene are checked")
    p.add_argument("--junit", metavar="FILE", type=output_file(), default=None,
                   help="also write the results as JUnit XML (one test case per check, one test "
                        "suite per part, sheet, the array and each scene) for CI")
    add_cache_args(p)
    add_output_args(p, "print one JSON object: the export checked, each check and the counts")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.commands import design_and_product
    from tactcad.export.selection import ReportingParts

    if args.junit is not None:
        junit_target(args.junit)  # a bad path is refused before the checks run
    if args.out:  # every product's export folder: refused before anything is read
        from tactcad.atomic import refuse_system_folder

        refuse_system_folder("--out", args.out, args.out)
    found = design_and_product(args)
    if found is not None and not found[1].is_default:  # another product's check (a die's)
        return found[1].hook("check")(found[0], args)
    project = load_from_args(args)
    refuse_unknown_scenes(project, args.scene)  # every option's value before any check runs
    report = progress_from_args(args)
    say_the_export_left_unread(args, report)
    t0 = time.perf_counter()

    def done(group: str, found: list) -> None:
        report(f"{group}: {counts_text(status_counts(found))} "
               f"({time.perf_counter() - t0:.1f} s)")
        if not args.json:
            for r in found:
                if not (status_of(r) in SHOWN_IN_FULL_ONLY and args.failures_only):
                    print(r.line(), flush=True)

    result = project.check(args.out, args.scene, cache=store_choice(args), progress=report,
                           on_group=done)
    if args.junit is not None:
        from tactcad.checks.junit import write_junit

        write_junit(args.junit, result.groups, project.parts)
        report(f"wrote {args.junit} (JUnit XML, {len(result)} test cases)")
    bad = result.failures
    counts = status_counts(result.results)
    if args.out:  # the export's review page shows them (review/checks.js)
        from tactcad.checks.review_results import update_checks_script

        update_checks_script(args.out, project.plan.design_hash, result.groups)
    if args.json:
        print(dumps({"out": args.out, "reused_export": result.reused_export,
                     "export_refusal": result.export_refusal, **counts, "junit": args.junit,
                     "checks": [{"check": r.check, "subject": r.subject, "passed": reported_passed(r),
                                 "status": status_of(r), "detail": r.detail} for r in result.results
                                if not (status_of(r) in SHOWN_IN_FULL_ONLY
                                        and args.failures_only)]}, indent=1))
    else:
        print(counts_text(counts))
    return 1 if bad else 0


def say_the_export_left_unread(args: argparse.Namespace, report) -> None:
    """Without ``--out`` the check exports to a temporary folder: where the working folder's
    ``exports`` holds an export (its ``manifest.json``), one progress line says it is left
    unread and that ``--out exports`` checks it as it is.

    Args:
        args: the check's options (``out``). report: the run's progress line writer.
    """
    from pathlib import Path

    if args.out is None and (Path("exports") / "manifest.json").is_file():
        report("exports/ holds an export, not read: without --out the design is exported to a "
               "temporary folder and checked there; --out exports checks that export as it is")


def junit_target(path: str) -> None:
    """Refuse a ``--junit`` path whose folder is missing or which is a folder.

    Raises:
        DesignError: naming the option, the path and what is allowed.
    """
    from pathlib import Path

    from tactcad.errors import DesignError

    target = Path(path)
    if target.is_dir() or not target.parent.is_dir():
        raise DesignError("--junit", path, "a file path in an existing folder, e.g. "
                                           "check-report.xml")


def store_choice(args: argparse.Namespace):
    """``--cache``/``--no-cache`` as :meth:`tactcad.api.Project.check` takes it."""
    return False if args.no_cache else (args.cache or True)
