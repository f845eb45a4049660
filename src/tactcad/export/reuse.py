"""Is the export in a folder the one a design would write now? (``tactcad check --out DIR``)

An export is taken as it is when its manifest names the same design content
(sha256), the same tactcad version and CAD stack, is not partial, and every
file it lists is there with the sha256 it lists. The checks then test those
files against the current plan, rigs and scenes, so a file the current rigs
would shape differently fails its check rather than pass unseen.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from tactcad.version import VERSION
from tactcad.catalogue.files import MANIFEST
from tactcad.design.array_plan import Plan
from tactcad.store import stack_versions


def file_sha256(path: Path) -> str:
    """sha256 (hex) of a file's bytes."""
    with open(path, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def reuse_refusal(plan: Plan, out_dir: str | Path) -> str | None:
    """Why the export in ``out_dir`` is not the one ``plan`` would write now,
    or ``None`` when it is (see module doc)."""
    out = Path(out_dir)
    try:
        man = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        sha, files = man["design"]["sha256"], man["files"]
        listed = [(f["path"], f["sha256"]) for f in files]
    except FileNotFoundError:
        return f"no {MANIFEST} in {out}"
    except (OSError, ValueError, KeyError, TypeError) as exc:
        return f"{MANIFEST} unreadable ({type(exc).__name__})"
    if sha != plan.design_hash:
        return "made from another design"
    if "partial" in man:
        return "a partial export (--only/--part)"
    if man.get("tactcad_version") != VERSION or man.get("cad_stack") != stack_versions():
        return "made by another tactcad version or CAD stack"
    for rel, want in listed:
        try:
            if file_sha256(out / rel) != want:
                return f"{rel} changed since the export"
        except OSError:
            return f"{rel} missing"
    return None
