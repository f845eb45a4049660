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

An array's export is also current only while every other input it was made from
is: its manifest's ``inputs`` (:func:`tactcad.export.jobs.export_inputs`: the
rigs and scenes files, and one sha256 over the keys the store of finished jobs
reuses each job by) must match the same record planned from the project now
(:func:`changed_inputs`). An export older than an edit of rigs.toml, say, is
exported again (nothing edited by hand), or, with files edited by hand, checked as
it is with one failing check naming the files edited since and the command that
writes it again.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping

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
        stale: what the export is older than (:func:`changed_inputs`): the project's
            files edited since it was written, by name (``rigs.toml``), or words for its
            other inputs; empty when it is current or when not compared.
    """

    refusal: str | None
    edited: dict[str, str] = field(default_factory=dict)
    stale: tuple[str, ...] = ()


def reuse_state(plan: Plan, out_dir: str | Path, project: Any = None) -> ExportState:
    """:func:`export_state` of an array's export: its manifest must name ``plan``'s design
    sha256 and, given ``project``, the inputs it was made from must be the project's now
    (:func:`changed_inputs`).

    Args:
        plan: the array's plan.
        out_dir: the export folder.
        project: the validated :class:`tactcad.design.project.Project` of ``plan`` (None:
            the design's sha256 alone is compared).

    Returns:
        :class:`ExportState`.
    """
    inputs = None if project is None else (lambda recorded: changed_inputs(recorded, project))
    return export_state(out_dir, {"sha256": plan.design_hash}, inputs)


#: What an export is older than when its manifest records no inputs.
UNRECORDED_INPUTS = "its inputs (not recorded)"
#: What an export is older than when its files are as recorded but a job's key is not.
OTHER_INPUTS = "its other inputs"


def changed_inputs(recorded: Any, project: Any) -> list[str]:
    """What an export is older than: its manifest's ``inputs`` against the same record
    planned from ``project`` now (:func:`tactcad.export.jobs.export_inputs`, the keys the
    store of finished jobs uses, so no input the export reads is left out).

    Args:
        recorded: the manifest's ``inputs`` (None when it has none).
        project: the validated :class:`tactcad.design.project.Project`.

    Returns:
        The project's files whose validated tables differ from those recorded, by name
        (``rigs.toml``), in design, rigs, scenes order; :data:`OTHER_INPUTS` when the files
        are as recorded but a job's key is not; :data:`UNRECORDED_INPUTS` when nothing (or
        nothing readable) is recorded; empty when the export is current.
    """
    from tactcad.export.job import Run
    from tactcad.export.jobs import export_inputs

    try:
        then = {f["role"]: (f["file"], f["sha256"]) for f in recorded["files"]}
        version = recorded.get("dxf_version")
        jobs_then = recorded["jobs_sha256"]
    except (TypeError, KeyError, AttributeError):
        return [UNRECORDED_INPUTS]
    # planned with the DXF version the export was written in (--dxf-version R12 stays R12)
    now = export_inputs(Run(project, Path(), lambda line: None,
                            dxf_version=version if isinstance(version, str) else None))
    roles_now = {f["role"]: (f["file"], f["sha256"]) for f in now["files"]}
    changed = [name for role, (name, sha) in roles_now.items()
               if then.get(role, (None, None))[1] != sha]
    changed += [name for role, (name, _) in then.items() if role not in roles_now]
    if not changed and now["jobs_sha256"] != jobs_then:
        changed = [OTHER_INPUTS]
    return changed


def stale_said(stale: tuple[str, ...] | list[str]) -> str:
    """One line for an export older than its inputs (:func:`changed_inputs`): ``older than
    rigs.toml (changed since it was written)``."""
    if list(stale) == [UNRECORDED_INPUTS]:
        return ("made without a record of its inputs (an earlier tactcad's export): it may be "
                "older than the project's other files (an array's rigs and scenes files, a "
                "die's jaw file)")
    if list(stale) == [OTHER_INPUTS]:
        return ("older than its other inputs (changed since it was written: the project's "
                "atlas files, tactcad's data or the installed CAD tools)")
    return f"older than {', '.join(stale)} (changed since it was written)"


def export_state(out_dir: str | Path, design: Mapping[str, Any],
                 inputs: Callable[[Any], list[str]] | None = None) -> ExportState:
    """Whether the export in ``out_dir`` is checked as it is or the design is exported
    there first, and which of its files were edited by hand (see module doc): every
    product's check asks this before it reads an export.

    The design is exported first when the folder holds no readable manifest, an export
    of another design, or, with no file edited, a partial export, one of another
    tactcad version or CAD stack, or one older than its inputs (``inputs``). An export of
    the same design with files changed or removed since is checked as it is, those files
    listed in ``edited`` (and what it is older than in ``stale``).

    Args:
        out_dir: the export folder.
        design: what its manifest's ``design`` table must hold (key -> value, compared as
            JSON reads them back), e.g. ``{"sha256": ...}`` for an array, the design file's
            sha256 and its ``--set`` values for a die.
        inputs: given the manifest's ``inputs`` (None when it has none), what the export is
            older than (:func:`changed_inputs`); None: not compared.

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
    stale = tuple(inputs(man.get("inputs"))) if inputs is not None else ()
    edited = {rel: how for rel, want in listed if (how := file_change(out / rel, want))}
    if edited:  # work done by hand is never overwritten by a check
        return ExportState(None, edited, stale)
    if "partial" in man:
        return ExportState("a partial export (--only/--part)")
    if man.get("tactcad_version") != VERSION or man.get("cad_stack") != stack_versions():
        return ExportState("made by another tactcad version or CAD stack")
    if stale:
        return ExportState(stale_said(stale), stale=stale)
    return ExportState(None)


def file_change(path: Path, sha256: object) -> str | None:
    """``changed`` when the file at ``path`` has another sha256, ``missing`` when it cannot
    be read, None when it is as listed."""
    try:
        return None if file_sha256(path) == sha256 else "changed"
    except OSError:
        return "missing"
