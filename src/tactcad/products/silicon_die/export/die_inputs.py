"""What a die's export is made from: the manifest's ``inputs``, as an array's export records
its rigs and scenes files (:func:`tactcad.export.jobs.export_inputs`).

A die project's inputs are its design file and, when the design names one, the lab's jaw
file beside it (``die.jaw = "die55_jaw.toml"``): the pin, the opening and the pocket it
states shape the mount, the scene, the grasp and the review page, though not always the
die's plan. A check compares the record with the files now
(:func:`changed_die_inputs`): an export older than an edit of the jaw file is exported
again, or, with files edited by hand, checked as it is with a failing ``export_inputs``
check, as an array's export older than an edit of rigs.toml is
(:func:`tactcad.export.reuse.export_state`).
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any, Mapping

#: The roles a die's ``inputs`` names its files by, in order.
INPUT_ROLES = ("design", "jaw")


def file_record(role: str, path: Path, folder: Path) -> dict:
    """One input file as the manifest's ``inputs`` lists it.

    Args:
        role: ``design`` or ``jaw`` (:data:`INPUT_ROLES`).
        path: the file.
        folder: the design file's folder: the name is given relative to it (an export
            names no path of the machine it was made on).

    Returns:
        ``{"role", "file", "sha256"}``: the sha256 of the file's bytes, as the manifest's
        ``design.sha256`` is of the design file's.

    Raises:
        OSError: the file cannot be read.
    """
    try:
        name = path.resolve().relative_to(folder.resolve()).as_posix()
    except (ValueError, OSError):
        name = path.name
    return {"role": role, "file": name, "sha256": hashlib.sha256(path.read_bytes()).hexdigest()}


def die_inputs(design: str | Path | None, jaw_file: str | Path | None) -> dict:
    """The manifest's ``inputs`` of a die's export.

    Args:
        design: the die's design file (None: a die asked by options, which has none).
        jaw_file: the jaw file the die seats in (None or empty: a trocar class, no file).

    Returns:
        ``{"files": [{"role", "file", "sha256"}]}``, the design file first, then the jaw
        file; an empty list when the die has neither.

    Raises:
        OSError: a file cannot be read.
    """
    folder = Path(design).parent if design else Path(jaw_file or ".").parent
    paths = {"design": design, "jaw": jaw_file}
    return {"files": [file_record(role, Path(paths[role]), folder)
                      for role in INPUT_ROLES if paths[role]]}


def changed_die_inputs(recorded: Any, now: Mapping[str, Any]) -> list[str]:
    """What a die's export is older than: its manifest's ``inputs`` against the record made
    from the files now (:func:`die_inputs`).

    Args:
        recorded: the manifest's ``inputs`` (None when it has none).
        now: :func:`die_inputs` of the design and jaw files as they are now.

    Returns:
        The files whose sha256 differs from the one recorded (or that are recorded no
        longer, or newly), by name (``die55_jaw.toml``), in design, jaw order;
        :data:`tactcad.export.reuse.UNRECORDED_INPUTS` when nothing readable is recorded and the die has a jaw file
        (a die of a trocar class has no other input than its design file, which the
        manifest's ``design.sha256`` covers); empty when the export is current.
    """
    from tactcad.export.reuse import UNRECORDED_INPUTS

    roles_now = {f["role"]: (f["file"], f["sha256"]) for f in now["files"]}
    try:
        then = {f["role"]: (f["file"], f["sha256"]) for f in recorded["files"]}
    except (TypeError, KeyError, AttributeError):
        return [UNRECORDED_INPUTS] if "jaw" in roles_now else []
    changed = [name for role, (name, sha) in roles_now.items()
               if then.get(role, (None, None))[1] != sha]
    return changed + [name for role, (name, _) in then.items() if role not in roles_now]
