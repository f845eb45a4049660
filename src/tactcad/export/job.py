"""What the jobs of one export run share (:class:`Run`) and what a job is (:class:`Job`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any, Callable

from tactcad.assembly.inventory import design_assemblies, fabricated_parts, scene_models
from tactcad.assembly.rig_models import RigModel
from tactcad.catalogue.array_catalogue import Instance, PartSpec, array_instances, array_parts
from tactcad.design.array_plan import Plan
from tactcad.design.project import Project
from tactcad.design.scene_specs import SceneSpec
from tactcad.store import Store, content_key

Log = Callable[[str], None]


@dataclass
class Run:
    """What the jobs of one run share: the validated project, the staging
    folder, the log, the part inventory (kernel-free) and the part cache
    (kernel, made on first use)."""

    project: Project
    staging: Path
    log: Log = print
    store: Store = field(default_factory=lambda: Store(None))  # also memoises costly steps
    dxf_version: str | None = None  # of the shop DXF files; None: R2010 (or $TACTCAD_DXF_VERSION)
    #: jobs the run's second process made (:mod:`tactcad.export.worker`), in the order collected
    worker_made: list[str] = field(default_factory=list)
    #: files asked for that a failed program left out, as the manifest's ``not_written``
    #: records them (:func:`tactcad.export.freecad_review.not_written_record`)
    not_written: list[dict] = field(default_factory=list)
    #: the scenes solved in this run by name, with their parts' solids (:meth:`scene`)
    _scenes: dict[str, tuple[Any, dict[str, Any]]] = field(default_factory=dict, repr=False)

    @property
    def plan(self) -> Plan:
        """The array's plan (``project.plan``)."""
        return self.project.plan

    @cached_property
    def array(self) -> tuple[dict[str, PartSpec], list[Instance]]:
        """(the array's distinct parts by name, its placed instances), made once
        for every job that needs them."""
        return array_parts(self.plan), array_instances(self.plan)

    @cached_property
    def scenes(self) -> dict[str, tuple[SceneSpec, RigModel]]:
        """Every scene with its rig model; see :func:`tactcad.assembly.inventory.scene_models`."""
        return scene_models(self.project)

    @cached_property
    def inventory(self) -> tuple[dict[str, PartSpec], dict[str, list]]:
        """(every distinct part by name, {assembly: instances}); see
        :func:`tactcad.assembly.inventory.design_assemblies`."""
        return design_assemblies(self.project, self.scenes)

    @property
    def distinct_parts(self) -> int:
        """Distinct parts the design's files show: every part of an assembly and the kit's
        samples no scene shows (each drawn; :func:`tactcad.assembly.inventory.fabricated_parts`)."""
        made, _ = fabricated_parts(self.project, self.inventory)
        return len(set(self.inventory[0]) | {s.name for s in made})

    def scene(self, name: str) -> tuple[Any, dict[str, Any]]:
        """Scene ``name`` solved, with its shown parts' solids by part name
        (:func:`~tactcad.assembly.scene_solver.build_scene` on :attr:`parts`), once per
        run: the scene's STEP and glTF job, its review file and the build book's
        pictures read the same one. Shared: read it, do not change it.

        Raises:
            SceneError: as :func:`~tactcad.assembly.scene_solver.build_scene`.
        """
        if name not in self._scenes:
            from tactcad.assembly.scene_solver import build_scene

            self._scenes[name] = build_scene(self.project, name, self.parts)
        return self._scenes[name]

    @cached_property
    def parts(self):
        """The run's :class:`~tactcad.solids.cache.PartCache` (imports the CAD kernel)."""
        from tactcad.solids.cache import PartCache

        return PartCache(self.plan)


@dataclass(frozen=True)
class Job:
    """One unit of output: ``make(run)`` writes its files into ``run.staging``
    and returns their records (dicts with at least ``path``, ``part``, ``kind``)."""

    name: str
    key: str
    make: Callable[[Run], list[dict]] | None
    needs: tuple[PartSpec, ...] = ()  # solids the job reads, built before the jobs run
    after: tuple[str, ...] = ()  # jobs whose files this one reads
    #: for work done by another program: ``start(run)`` launches it and returns
    #: a handle with ``result() -> records`` and ``cancel()``; the run goes on
    #: with the other jobs meanwhile (both cores busy) and collects it at the end;
    #: a handle whose ``keep`` is False after ``result()`` is not kept in the store
    start: Callable[[Run], Any] | None = None
    #: for such a job: ``ahead()`` starts that program's start-up before this process
    #: imports the CAD kernel (the second core is idle then), returning a function that
    #: ends it if ``start`` never took it
    ahead: Callable[[], Callable[[], None]] | None = None
    #: may run in the run's second process (:mod:`tactcad.export.worker`): it
    #: reads only the plan, the solids in ``needs`` and the files of ``after``
    worker: bool = False
    #: work of ``make`` that reads no file (e.g. the design's facts), done
    #: while this process would otherwise wait for the worker's files
    prepare: Callable[[Run], None] | None = None
    #: for a job of many parts whose files include parts' own (the shop DXF's profiles):
    #: ``for_part(name)`` is the job writing only part ``name``'s own files, None when it
    #: writes none of that part's (``tactcad export --part``)
    for_part: Callable[[str], "Job | None"] | None = None


def solid_key(spec: PartSpec) -> str:
    """A part's solid named by its content (the part spec), as the store names
    a part's STEP file, so it is the same solid in every run that has the part."""
    return content_key("solid", spec)
