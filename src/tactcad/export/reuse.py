"""Is the export in a folder the one a design would write now? (``tactcad check --out DIR``)

An export is taken as it is when its manifest names the same design content
(sha256), the same tactcad version and CAD stack, is not partial, and every
file it lists is there with the sha256 it lists. The checks then test those
files against the current plan, rigs and scenes, so a file the current rigs
would shape differently fails its check rather than pass unseen.

An export of the same design whose files a person changed or removed since is
taken as it is too: a check never overwrites work done by hand. Each such file
is one failing check (:func:`tactcad.checks.export_files.edited_results`);
``tactcad export`` writes it again. Every product's check keeps this one rule
(:func:`export_state`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from tactcad.version import VERSION
from tactcad.atomic import file_sha256
from tactcad.catalogue.files import MANIFEST
from tactcad.design.array_plan import Plan
from tactcad.store import stack_versions


@dataclass(frozen=True)
class ExportState:
    """What a check finds in an export folder.

    Attributes:
        refusal: why the design is exported there first (one line naming the first
            difference), or None when the export is checked as it is.
        edited: the files the manifest lists that were changed (``changed``) or removed
            (``missing``) since, by path, in the manifest's order; found only in an
            export of the same design, which is then checked as it is (never
            overwritten).
    """

    refusal: str | None
    edited: dict[str, str] = field(default_factory=dict)


def reuse_state(plan: Plan, out_dir: str | Path) -> ExportState:
    """:func:`export_state` of an array's export: its manifest must name ``plan``'s design
    sha256.

    Args:
        plan: the array's plan.
        out_dir: the export folder.

    Returns:
        :class:`ExportState`.
    """
    return export_state(out_dir, {"sha256": plan.design_hash})


def export_state(out_dir: str | Path, design: Mapping[str, Any]) -> ExportState:
    """Whether the export in ``out_dir`` is checked as it is or the design is exported
    there first, and which of its files were edited by hand (see module doc): every
    product's check asks this before it reads an export.

    The design is exported first when the folder holds no readable manifest, an export
    of another design, or, with no file edited, a partial export or one of another
    tactcad version or CAD stack. An export of the same design with files changed or
    removed since is checked as it is, those files listed in ``edited``.

    Args:
        out_dir: the export folder.
        design: what its manifest's ``design`` table must hold (key -> value, compared as
            JSON reads them back), e.g. ``{"sha256": ...}`` for an array, the design file's
            sha256 and its ``--set`` values for a die.

    Returns:
        :class:`ExportState`.
    """
    out = Path(out_dir)
    try:
        man = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        stated, files = man["design"], man["files"]
        listed = [(f["path"], f["sha256"]) for f in files]
        same = all(stated.get(k) == v for k, v in json.loads(json.dumps(dict(design))).items())
    except FileNotFoundError:
        return ExportState(f"no {MANIFEST} in {out}")
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        return ExportState(f"{MANIFEST} unreadable ({type(exc).__name__})")
    if not same:
        return ExportState("made from another design")
    edited = {rel: how for rel, want in listed if (how := file_change(out / rel, want))}
    if edited:  # work done by hand is never overwritten by a check
        return ExportState(None, edited)
    if "partial" in man:
        return ExportState("a partial export (--only/--part)")
    if man.get("tactcad_version") != VERSION or man.get("cad_stack") != stack_versions():
        return ExportState("made by another tactcad version or CAD stack")
    return ExportState(None)


def file_change(path: Path, sha256: object) -> str | None:
    """``changed`` when the file at ``path`` has another sha256, ``missing`` when it cannot
    be read, None when it is as listed."""
    try:
        return None if file_sha256(path) == sha256 else "changed"
    except OSError:
        return "missing"
