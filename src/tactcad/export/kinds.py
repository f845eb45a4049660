"""The kinds of file an export writes, declared once.

Each :class:`ExportKind` names the ``--only`` word, the job-name prefixes it
selects, what it writes (for ``--help``) and the function that plans its
jobs. The run's job list (:func:`tactcad.export.jobs.all_jobs`), ``--only``'s
choices and help and the job selection (:mod:`tactcad.export.selection`) read
:data:`EXPORT_KINDS`; a new format is one module with its job function plus
one :func:`register_kind`.

Planning needs no CAD kernel: the job function is imported by name when a
run plans its jobs, and its jobs import their writers when they run.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Iterable, Sequence

from tactcad.errors import DesignError

if TYPE_CHECKING:
    from tactcad.export.job import Job, Run


@dataclass(frozen=True)
class ExportKind:
    """One kind of export file.

    Attributes:
        name: the ``--only`` word (``step``, ``dxf`` ...).
        prefixes: job-name prefixes (the word before the colon) it selects.
        writes: what it writes, for ``--help`` (paths relative to the export folder).
        module, function: ``function(run, before) -> list[Job]`` plans the
            kind's jobs, ``before`` the jobs of the kinds registered before it
            (a job that reads their files holds their keys).
        part_prefix: the prefix of its jobs that write one part alone, named
            after the colon (``step:cart``), or None.
        in_full_export: False for a kind written only when ``--only`` names it.
        part_files: the name of a function in ``module``,
            ``function(plan, assemblies) -> files(part, found) -> [path, ...]``,
            giving the files of the kind that describe a part (``found``: the
            files of the kinds before it in the BOM), for the BOM's files
            column; None when its files describe no single part.
        bom_rank: the place of its files in that column (smaller first: a
            shop reads the drawing, then the DXF, then the models).
        manifest_section: ``(key, "module:function")``, ``function(plan)``
            -> the kind's own section of ``manifest.json``
            (:mod:`tactcad.export.manifest`), or None.
    """

    name: str
    prefixes: tuple[str, ...]
    writes: str
    module: str
    function: str
    part_prefix: str | None = None
    in_full_export: bool = True
    part_files: str | None = None
    bom_rank: int = 0
    manifest_section: tuple[str, str] | None = None

    def jobs(self, run: "Run", before: list["Job"]) -> list["Job"]:
        """The kind's jobs for ``run``, after the jobs ``before``."""
        return getattr(importlib.import_module(self.module), self.function)(run, before)

    def files_of_parts(self, plan, assemblies) -> Callable[[str, Sequence[str]], list[str]]:
        """``files(part, found)``: the kind's files describing ``part`` (see
        :attr:`part_files`); no files when the kind names none."""
        if self.part_files is None:
            return lambda part, found: []
        return getattr(importlib.import_module(self.module), self.part_files)(plan, assemblies)


#: The kinds in run order (the manifest's order of files).
EXPORT_KINDS: dict[str, ExportKind] = {}


def register_kind(kind: ExportKind) -> None:
    """Add a kind of file to every export (its jobs after the others').

    Raises:
        ValueError: the name or a prefix is taken.
    """
    if kind.name in EXPORT_KINDS:
        raise ValueError(f"an export kind {kind.name!r} is registered already")
    taken = {p for k in EXPORT_KINDS.values() for p in k.prefixes} & set(kind.prefixes)
    if taken:
        raise ValueError(f"export kind {kind.name!r}: job prefix(es) {', '.join(sorted(taken))} "
                         "belong to another kind")
    EXPORT_KINDS[kind.name] = kind


_JOBS = "tactcad.export.jobs"
for _kind in (
        ExportKind("step", ("step",), "step/<part>.step, step/array.step", _JOBS, "step_jobs",
                   part_prefix="step", part_files="step_part_files", bom_rank=3),
        ExportKind("dxf", ("dxf",), "dxf/<part>_qty<n>.dxf, dxf/sheet_<material>_<t>mm.dxf",
                   _JOBS, "dxf_jobs", part_files="dxf_part_files", bom_rank=2,
                   manifest_section=("shop", "tactcad.export.dxf_sheet:shop_section")),
        ExportKind("scenes", ("scene",), "scenes/<scene>.step (Z up) and .glb", _JOBS,
                   "scene_and_review_jobs", part_files="scene_part_files", bom_rank=4),
        ExportKind("drawings", ("drawing", "drawings"), "drawings/<part>.svg, drawings.pdf",
                   _JOBS, "drawing_jobs", part_prefix="drawing", part_files="drawing_part_files",
                   bom_rank=1),
        ExportKind("images", ("image",), "images/*.png", _JOBS, "image_jobs"),
        ExportKind("bom", ("bom",), "bom.csv, bom.md", _JOBS, "bom_jobs"),
        ExportKind("instructions", ("instructions",),
                   "instructions/index.html, build_book.pdf, steps.json, step_*.png (the build book)",
                   "tactcad.export.instructions", "instructions_jobs"),
        # the FreeCAD review files are planned with the scenes they show
        ExportKind("review", ("review",),
                   "review/index.html, review/<scene>.FCStd (with FreeCAD installed)", _JOBS,
                   "review_page_jobs"),
        ExportKind("stl", ("stl",), "stl/<part>.stl", "tactcad.export.stl", "stl_jobs",
                   part_prefix="stl", in_full_export=False, part_files="stl_part_files",
                   bom_rank=5),
        ExportKind("crosstalk", ("crosstalk",),
                   "crosstalk/decoupling.csv and .json (the construction's verification "
                   "crosstalk level: the Timoshenko stack, a comb's beam)",
                   "tactcad.export.crosstalk_files", "crosstalk_jobs")):
    register_kind(_kind)


def bom_file_kinds() -> list[ExportKind]:
    """The kinds whose files the BOM names per part, in the column's order."""
    return sorted((k for k in EXPORT_KINDS.values() if k.part_files is not None),
                  key=lambda k: k.bom_rank)


def full_export_kinds() -> tuple[str, ...]:
    """The kinds a full export writes, in run order."""
    return tuple(name for name, kind in EXPORT_KINDS.items() if kind.in_full_export)


def kinds_help() -> str:
    """``step (step/<part>.step, ...), dxf (...), ...`` for ``--help``."""
    return "; ".join(f"{k.name} ({k.writes}{'' if k.in_full_export else ', only when asked'})"
                     for k in EXPORT_KINDS.values())


def parse_only(values: Iterable[str] | None) -> list[str]:
    """``--only`` values (each a comma-separated list) -> kinds in
    :data:`~tactcad.export.kinds.EXPORT_KINDS` order.

    Raises:
        DesignError: an unknown kind, naming the allowed ones.
    """
    asked = [v.strip() for text in values or () for v in text.split(",") if v.strip()]
    for kind in asked:
        if kind not in EXPORT_KINDS:
            raise DesignError("--only", kind, "one or more of " + ", ".join(EXPORT_KINDS),
                              "comma-separated")
    return [kind for kind in EXPORT_KINDS if kind in asked]
