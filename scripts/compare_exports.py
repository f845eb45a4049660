"""Compare two export folders file by file (sha256); the manifest without its version fields.

Usage: python scripts/compare_exports.py BEFORE AFTER [--allow PATH ...]

Prints one line per file that was added, removed or changed and a summary;
exits 1 when they differ (files named by ``--allow`` may differ or be new).
The manifest (``manifest.json``) is compared as data after dropping the fields
that name the software rather than the design (``tactcad_version``,
``cad_stack``); its ``files`` list is compared on path and sha256.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

MANIFEST = "manifest.json"
VERSION_FIELDS = ("tactcad_version", "cad_stack")


def file_digests(folder: Path) -> dict[str, str]:
    """sha256 of every file under ``folder``, by path relative to it."""
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def manifest_without_versions(path: Path) -> dict:
    data = json.loads(path.read_text(encoding="utf-8"))
    for key in VERSION_FIELDS:
        data.pop(key, None)
    return data


def compare(before: Path, after: Path, allowed: set[str]) -> list[str]:
    """Lines naming each difference not in ``allowed`` (empty: identical)."""
    a, b = file_digests(before), file_digests(after)
    out = []
    for path in sorted(set(a) | set(b)):
        if path == MANIFEST or path in allowed:
            continue
        if path not in b:
            out.append(f"removed  {path}")
        elif path not in a:
            out.append(f"added    {path}")
        elif a[path] != b[path]:
            out.append(f"changed  {path}")
    if MANIFEST in a and MANIFEST in b:
        ma, mb = manifest_without_versions(before / MANIFEST), manifest_without_versions(after / MANIFEST)
        if not allowed and ma != mb:
            keys = sorted(k for k in set(ma) | set(mb) if ma.get(k) != mb.get(k))
            out.append(f"changed  {MANIFEST} (fields: {', '.join(keys)})")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--allow", action="append", default=[], metavar="PATH",
                    help="a file that may differ or be new (repeatable); the manifest is then "
                         "not compared")
    args = ap.parse_args(argv)
    for folder in (args.before, args.after):
        if not folder.is_dir():
            print(f"compare_exports: not a folder: {folder}", file=sys.stderr)
            return 2
    diffs = compare(args.before, args.after, set(args.allow))
    for line in diffs:
        print(line)
    n = len(file_digests(args.after))
    print(f"{n} files in {args.after}; {len(diffs)} differences from {args.before}")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
