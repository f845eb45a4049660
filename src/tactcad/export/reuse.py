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
from typing import Any, Mapping

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
    return export_refusal(out_dir, {"sha256": plan.design_hash})


def export_refusal(out_dir: str | Path, design: Mapping[str, Any]) -> str | None:
    """Why the export in ``out_dir`` is not the one a design would write now, or ``None``
    when it is (see module doc): every product's check asks this before it reads an export.

    Args:
        out_dir: the export folder.
        design: what its manifest's ``design`` table must hold (key -> value, compared as
            JSON reads them back), e.g. ``{"sha256": ...}`` for an array, the design file's
            sha256 and its ``--set`` values for a die.

    Returns:
        One line naming the first difference (a file by its path), or None.
    """
    out = Path(out_dir)
    try:
        man = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        stated, files = man["design"], man["files"]
        listed = [(f["path"], f["sha256"]) for f in files]
        same = all(stated.get(k) == v for k, v in json.loads(json.dumps(dict(design))).items())
    except FileNotFoundError:
        return f"no {MANIFEST} in {out}"
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        return f"{MANIFEST} unreadable ({type(exc).__name__})"
    if not same:
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
