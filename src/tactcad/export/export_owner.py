"""Whose export an export folder holds, and the one rule every product's export keeps: an
export goes into an empty or new folder, or one holding an export of the same design (an
earlier one, which it replaces), never beside another design's export (an array's files
would delete a die's, a die's would be mixed with an array's).

The owner is read from the folder's ``manifest.json``: its ``product`` (an array's manifest
names none: the default product's) and its design's ``name``.
"""

from __future__ import annotations

import json
from pathlib import Path

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
