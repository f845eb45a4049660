"""``tactcad diff OLD NEW``: what changed between two exports or two design files."""

from __future__ import annotations

import argparse
from pathlib import Path

from tactcad.commands.options import output_folder
from tactcad.commands import add_cache_args, add_output_args, progress_from_args


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "diff", help="what changed between two exports (or two design files)",
        description="Compare two exports from their manifests: parts added, removed and "
                    "changed, elements whose stiffness K or strength changed (their fatigue "
                    "limits included; a silicon die's rows, named with their role), the "
                    "closed-form verification's requirements whose prediction, margin or "
                    "verdict changed (the rated full-scale force's among them), derived "
                    "dimensions, the values the design file states (by dotted key, listed as "
                    "stated), the BOM's items added, removed and whose quantity changed, "
                    "and drawing sheets; elements are paired by row and column; with --out, "
                    "an overlay (old red, new blue) and a "
                    "side-by-side PNG of every changed sheet (unchanged sheets are not rendered), "
                    "listed in the folder's diff.json: a later diff into the folder replaces "
                    "them (a diff finding no change writes diff.json listing none), and a folder "
                    "holding files its diff.json does not list, or no diff.json, is refused. "
                    "A design file (.toml) is exported to a temporary folder first, through the "
                    "store of finished jobs. Exit 0: nothing changed; 1: something changed; "
                    "2: bad input.")
    p.add_argument("old", metavar="OLD", help="export folder (with manifest.json) or design file")
    p.add_argument("new", metavar="NEW", help="export folder (with manifest.json) or design file")
    p.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help="write the changed sheets' overlay and side-by-side PNG here "
                        "(an earlier diff's pictures there are replaced)")
    add_cache_args(p)
    add_output_args(p, "print one JSON object: parts, elements, rows (a die's), requirements, "
                       "derived, stated, sheets, bom, files")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import tempfile

    from tactcad.commands.check import store_choice
    from tactcad.commands.finite_json import dumps
    from tactcad.export.manifest_diff import (clear_earlier_diff, compare, earlier_diff_files,
                                              render_sheets, write_diff_record)

    report = progress_from_args(args)
    inputs = [_input(args.old, "OLD"), _input(args.new, "NEW")]
    if args.out is not None:
        from tactcad.atomic import refuse_system_folder

        refuse_system_folder("--out", args.out, args.out)  # before any export is made
    if args.out is not None and Path(args.out).exists() and not Path(args.out).is_dir():
        from tactcad.errors import DesignError

        raise DesignError("--out", args.out, "a folder (new or existing)")
    if args.out is not None and not Path(args.out).is_dir():
        from tactcad.atomic import unmakeable_folder
        from tactcad.errors import DesignError

        reason = unmakeable_folder(args.out)
        if reason is not None:  # said before the exports it compares are made
            raise DesignError("--out", args.out, "a folder that can be made", reason)
    if args.out is not None:
        earlier_diff_files(args.out)  # a folder with the lab's files: refused before exporting
    with tempfile.TemporaryDirectory() as tmp:
        folders = []
        for (kind, path), label in zip(inputs, ("old", "new")):
            if kind == "export":
                folders.append(path)
                continue
            from tactcad.api import load

            folder = Path(tmp) / label
            report(f"exporting {path} to a temporary folder")
            load(path).export(folder, cache=store_choice(args), progress=report)
            folders.append(folder)
        diff = compare(*folders)
        diff.old, diff.new = args.old, args.new
        if args.out is not None:
            clear_earlier_diff(args.out)  # the folder holds this comparison's files only
            written = render_sheets(diff, folders[0], folders[1], args.out)
            write_diff_record(diff, written, args.out)
            report(f"wrote {len(written)} pictures to {args.out}")
    if args.json:
        print(dumps(diff.as_json(), indent=1))
    else:
        for line in diff.lines():
            print(line)
    return 1 if diff.changed else 0


def _input(text: str, name: str) -> tuple[str, Path]:
    """("export", folder) or ("design", file) for an OLD or NEW argument.

    Raises:
        DesignError: neither an export folder nor a design file.
    """
    from tactcad.catalogue.files import MANIFEST
    from tactcad.errors import DesignError

    path = Path(text)
    if path.is_dir() and (path / MANIFEST).is_file():
        return "export", path
    if path.is_file() and path.suffix == ".toml":
        return "design", path
    raise DesignError(name, text, f"an export folder (with {MANIFEST}) or a design file (.toml)",
                      "not found" if not path.exists() else "neither")
