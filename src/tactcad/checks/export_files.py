"""The ``export files`` check group: every file an export's manifest lists is as the export
wrote it (sha256). A file changed or removed by hand since is one failing check and is left
as it is: ``tactcad check`` never overwrites work done by hand
(:func:`tactcad.export.reuse.export_state`, the rule of every product's check)."""

from __future__ import annotations

import shlex
from pathlib import Path
from typing import Iterator, Mapping, Sequence

from tactcad.catalogue.files import MANIFEST
from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found

#: The check each edited file fails (:func:`edited_results`).
EDITED_CHECK = "export_file"


def edited_results(out_dir: str | Path, edited: Mapping[str, str]) -> list[CheckResult]:
    """The export's files as checks: one failing check per file changed or removed since
    the export (it is left as it is, and ``tactcad export --out DIR`` writes it again),
    or one passing check when none was.

    Args:
        out_dir: the export folder, as the user named it (shown in the hint).
        edited: ``ExportState.edited``.

    Returns:
        :class:`~tactcad.checks.check_result.CheckResult` s.
    """
    again = f"`tactcad export --out {shlex.quote(str(out_dir))}` writes it again"
    if not edited:
        return [CheckResult(EDITED_CHECK, MANIFEST, True,
                            "every file as the export wrote it (sha256 as listed)")]
    words = {"changed": "edited since the export: sha256 differs from manifest.json",
             "missing": "removed since the export: missing, manifest.json lists it"}
    return [CheckResult(EDITED_CHECK, rel, False, f"{words[how]}; {again}")
            for rel, how in edited.items()]


#: The check an export older than its inputs fails (:func:`stale_results`).
STALE_CHECK = "export_inputs"


def stale_results(out_dir: str | Path, stale: Sequence[str]) -> list[CheckResult]:
    """One failing check when the export checked as it is (it holds files edited by hand,
    which a check never writes over) is older than the project's inputs, naming them and
    the command that writes the export again; nothing when it is current.

    Args:
        out_dir: the export folder, as the user named it (shown in the hint).
        stale: ``ExportState.stale``.

    Returns:
        :class:`~tactcad.checks.check_result.CheckResult` s.
    """
    if not stale:
        return []
    from tactcad.export.reuse import stale_said

    again = f"`tactcad export --out {shlex.quote(str(out_dir))}` writes it again"
    return [CheckResult(STALE_CHECK, MANIFEST, False,
                        f"the export is {stale_said(tuple(stale))}: its files may not be what "
                        f"the project makes now; {again}")]


#: The check a file the export left out notes (:func:`not_written_results`).
NOT_WRITTEN_CHECK = "export_not_written"


def not_written_results(out_dir: str | Path, recorded: Sequence[Mapping]) -> list[CheckResult]:
    """One note (``info``: reported, not judged) per set of files the export left out
    because a program failed (the manifest's ``not_written``: FreeCAD's review files),
    naming why and the command that writes them once the program works; the files the
    manifest lists are checked as they are.

    Args:
        out_dir: the export folder, as the user named it (shown in the hint).
        recorded: the manifest's ``not_written`` records (``what``, ``reason``).

    Returns:
        :class:`~tactcad.checks.check_result.CheckResult` s (none when nothing was left out).
    """
    again = f"`tactcad export --out {shlex.quote(str(out_dir))}` writes them once FreeCAD works"
    return [CheckResult(NOT_WRITTEN_CHECK, str(r.get("what", "?")), True,
                        f"not written by the export ({r.get('reason', 'its program failed')}); "
                        f"manifest.json does not list them and the files it lists are "
                        f"consistent; {again}", info=True)
            for r in recorded if isinstance(r, Mapping)]


def recorded_not_written(folder: Path) -> list:
    """The ``not_written`` records of the manifest in ``folder`` (empty when it has none,
    or no manifest can be read).

    Args:
        folder: the export folder.

    Returns:
        The records, as the manifest holds them.
    """
    import json

    try:
        found = json.loads((Path(folder) / MANIFEST).read_text()).get("not_written")
    except (OSError, ValueError, AttributeError):
        return []
    return found if isinstance(found, list) else []


def export_files_group(context: CheckContext) -> Iterator[Found]:
    """``export files``: :func:`edited_results` of ``context.edited``, the files the check
    found changed by hand before it read the folder, :func:`stale_results` of
    ``context.stale`` and :func:`not_written_results` of the files the export left out;
    nothing when it did not look (a ``--scene`` check that wrote the scenes alone, the
    manifest left as it was)."""
    if context.edited is not None:
        yield "export files", (edited_results(context.folder, context.edited)
                               + stale_results(context.folder, context.stale)
                               + not_written_results(context.folder,
                                                     recorded_not_written(context.folder)))
