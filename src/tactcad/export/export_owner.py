"""Whose export an export folder holds, and the one rule every product's export keeps: an
export goes into an empty or new folder, or one holding an export of the same design (an
earlier one, which it replaces), never beside another design's export (an array's files
would delete a die's, a die's would be mixed with an array's).

The owner is read from the folder's ``manifest.json``: its ``product`` (an array's manifest
names none: the default product's) and its design's ``name``. A partial export
(``--only``/``--part``) keeps the other files of an earlier export of the same design content
(its sha256, :func:`kept_by_partial_export`) and refuses one of another content whose files
it would leave beside its own; check results of another design are never carried over
(:func:`stale_check_results`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

from tactcad.catalogue.files import MANIFEST
from tactcad.errors import DesignError


def default_product_name() -> str:
    """The name of the product whose manifests name no product (the metal array's)."""
    from tactcad.products import products

    return next(p.name for p in products() if p.is_default)


def export_owner(out: Path) -> tuple[str, str] | None:
    """(product name, design name) of the export in the folder ``out``, from its manifest;
    None when the folder holds no readable manifest naming a design."""
    try:
        manifest = json.loads((Path(out) / MANIFEST).read_text(encoding="utf-8"))
        name = manifest["design"]["name"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    if not isinstance(name, str):
        return None
    product = manifest.get("product") or default_product_name()
    return str(product), name


def refuse_another_designs_export(out: Path, product: str, name: str) -> None:
    """Refuse ``--out`` unless it is a new or empty folder, or holds an export of the design
    ``name`` of ``product`` (an earlier export of it, to be replaced).

    Args:
        out: the export folder asked for.
        product: the exporting design's product name (``metal-array``, ``silicon-die``).
        name: the exporting design's name (as its manifest names it).

    Raises:
        DesignError: ``--out`` is a file, or a folder holding files but no export of that
            design (another design's export, or files no export wrote).
    """
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise DesignError("--out", str(out), "a folder", f"{out} is a file")
    if not out.is_dir() or not any(out.iterdir()):
        return
    owner = export_owner(out)
    if owner == (product, name):
        return
    allowed = (f"an empty or new folder, or one holding an export of the {product} {name} "
               "(which it replaces)")
    if owner is None:
        raise DesignError("--out", str(out), allowed,
                          f"{out} holds files but no {MANIFEST} naming a design: {name}'s "
                          "export would be mixed with them")
    raise DesignError("--out", str(out), allowed,
                      f"{out} holds the export of the {owner[0]} {owner[1]}: {name}'s export "
                      "would be mixed with it or delete it; name another folder")


def written_by_tactcad(out: Path) -> set[str]:
    """The paths (relative, POSIX) the export now in ``out`` wrote: its manifest's files
    and the manifest, whatever the product; only the manifest when it cannot be read.

    Args:
        out: an export folder.

    Returns:
        The paths an export replacing it replaces; the folder's other files are the lab's,
        carried over (:func:`tactcad.atomic.carry_over`).
    """
    try:
        man = json.loads((Path(out) / MANIFEST).read_text(encoding="utf-8"))
        return {f["path"] for f in man["files"]} | {MANIFEST}
    except (OSError, ValueError, KeyError, TypeError):
        return {MANIFEST}


@dataclass(frozen=True)
class EarlierExport:
    """What a partial export (``--only``/``--part``) keeps of the export of the same design
    in its folder (:func:`kept_by_partial_export`).

    Attributes:
        kept: the earlier manifest's records of the files the partial export does not write,
            each file as the manifest lists it (sha256 checked), in the manifest's order.
        changed: the paths of those files changed by hand since (sha256 not as listed): kept
            in the folder as the lab's files, no longer listed as the export's.
        order: every path the earlier manifest lists, in its order.
        not_written: the earlier manifest's ``not_written`` records (files a failed
            program left out, :func:`tactcad.export.freecad_review.not_written_record`).
    """

    kept: tuple[dict, ...] = ()
    changed: tuple[str, ...] = ()
    order: tuple[str, ...] = ()
    not_written: tuple[dict, ...] = ()


def kept_by_partial_export(out: Path, name: str, design_sha256: str,
                           written: Iterable[str]) -> EarlierExport:
    """The files of the export in ``out`` that a partial export writing ``written`` keeps:
    every file the earlier export of the same design (its manifest's design sha256 equal
    to ``design_sha256``) lists and the partial export does not write again. A partial
    export refreshes some kinds; the other kinds of the same design stay as they were.

    Args:
        out: the export folder (its export is the earlier one).
        name: the design's name, for the refusal.
        design_sha256: the exported design's sha256.
        written: the paths (relative, POSIX) the partial export writes.

    Returns:
        :class:`EarlierExport` (empty when ``out`` holds no readable manifest).

    Raises:
        DesignError: ``out`` holds an export of another content of the design (another
            sha256) with files the partial export does not write again: the folder would
            mix the two designs' files.
    """
    from tactcad.export.reuse import file_change

    try:
        manifest = json.loads((Path(out) / MANIFEST).read_text(encoding="utf-8"))
        earlier_sha = manifest["design"]["sha256"]
        listed = [dict(f) for f in manifest["files"] if isinstance(f.get("path"), str)]
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return EarlierExport()
    written = set(written)
    others = [f for f in listed if f["path"] not in written and f["path"] != MANIFEST]
    if earlier_sha != design_sha256:
        if others:
            raise DesignError(
                "--out", str(out), "a folder holding an export of this design (sha256 "
                f"{design_sha256[:12]}), an empty or new folder, or no --only/--part",
                f"{out} holds an export of {name} made from another design (sha256 "
                f"{str(earlier_sha)[:12]}); a partial export of sha256 {design_sha256[:12]} "
                f"would leave {len(others)} of its files (e.g. {others[0]['path']}) beside "
                "the new ones; export every kind (no --only/--part) or name another folder")
        return EarlierExport(order=tuple(f["path"] for f in listed))
    kept, changed = [], []
    for f in others:
        how = file_change(Path(out) / f["path"], f.get("sha256"))
        if how is None:
            kept.append(f)
        elif how == "changed":
            changed.append(f["path"])
    return EarlierExport(tuple(kept), tuple(changed), tuple(f["path"] for f in listed),
                         manifest_not_written(manifest))


def manifest_not_written(manifest: dict) -> tuple[dict, ...]:
    """A manifest's ``not_written`` records, each with its ``files`` a list of paths.

    Args:
        manifest: the manifest as read.

    Returns:
        The well-formed records (none when it has none).
    """
    found = manifest.get("not_written")
    if not isinstance(found, list):
        return ()
    return tuple(dict(r) for r in found
                 if isinstance(r, dict) and isinstance(r.get("files"), list))


def files_of_same_design(out: Path, design_sha256: str) -> tuple[dict, ...]:
    """The files of the earlier export in ``out`` that a partial export of the design
    ``design_sha256`` finds in its folder before its jobs run: every file that export's
    manifest lists (the manifest itself aside), unchanged since (sha256 as listed), when it
    is an export of the same design content; none otherwise (no export, another design's:
    that one is refused once the run knows what it wrote, :func:`kept_by_partial_export`).

    Args:
        out: the export folder.
        design_sha256: the exported design's sha256.

    Returns:
        The earlier manifest's records of those files (each with its ``path`` and
        ``sha256``), in its order; empty when there are none.
    """
    try:
        manifest = json.loads((Path(out) / MANIFEST).read_text(encoding="utf-8"))
        earlier_sha = manifest["design"]["sha256"]
    except (OSError, ValueError, KeyError, TypeError):
        return ()
    if earlier_sha != design_sha256:
        return ()
    return kept_by_partial_export(out, "", design_sha256, ()).kept


def check_results_design(out: Path) -> str | None:
    """The design sha256 the check results in ``out`` (``review/checks.js``, written by
    ``tactcad check``) are for; None when there are none or they cannot be read."""
    from tactcad.export.live_page import checks_json
    from tactcad.export.review_page import CHECKS_SCRIPT

    try:
        text = checks_json((Path(out) / CHECKS_SCRIPT).read_text(encoding="utf-8"))
        design = json.loads(text)["design_sha256"] if text is not None else None
    except (OSError, UnicodeError, ValueError, KeyError, TypeError):
        return None
    return design if isinstance(design, str) else None


def stale_check_results(out: Path, design_sha256: str) -> set[str]:
    """The paths in ``out`` of check results made for another design than ``design_sha256``:
    an export of that design must not carry them over (a check's results belong to the
    export they checked).

    Args:
        out: the export folder about to be replaced.
        design_sha256: the sha256 of the design being exported.

    Returns:
        ``{"review/checks.js"}`` when that file is there and is not for the design (or cannot
        be read), else an empty set.
    """
    from tactcad.export.review_page import CHECKS_SCRIPT

    if not (Path(out) / CHECKS_SCRIPT).is_file():
        return set()
    return set() if check_results_design(out) == design_sha256 else {CHECKS_SCRIPT}
