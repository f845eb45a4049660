"""Every check of the scenes on the files of an export: rig part solids,
interference (manifold3d fast path, OpenCascade confirmation), geometry
sanity, STEP re-import and GLB read-back against the review records."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Mapping

from tactcad.assembly.rig_models import scene_names
from tactcad.assembly.scene_solver import Scene, build_scene, review_record
from tactcad.catalogue.rig_catalogue import RigPartSpec
from tactcad.checks.groups import CheckContext, Found
from tactcad.checks.interference import Placed
from tactcad.kernel.locations import placed
from tactcad.checks.mesh_interference import check_mesh_interference
from tactcad.checks.check_result import CheckResult
from tactcad.checks.scene_sanity import check_scene_sanity
from tactcad.checks.solids import check_solid
from tactcad.checks.step_readback import check_step
from tactcad.design.project import Project
from tactcad.export.glb import read_glb
from tactcad.catalogue.files import scene_glb_name, scene_step_name
from tactcad.solids.cache import PartCache


def placed_shapes(scene: Scene, solids: Mapping[str, Any]) -> list[Placed]:
    """Each shown instance's solid moved into the scene frame."""
    return [Placed(i.name, placed(solids[i.part], i.location)) for i in scene.instances]


def scene_group(context: CheckContext) -> Iterator[Found]:
    """``scene <name>`` for each scene asked for (all without ``--scene``), as each finishes."""
    if context.project is not None:
        yield from scene_checks(context.project, context.folder, context.scenes or None,
                                context.cache)


def run_scene_checks(project: Project, out_dir: str | Path, names: Iterable[str] | None = None,
                     cache: PartCache | None = None, confirm: bool = True,
                     done: Callable[[str, list[CheckResult]], None] | None = None
                     ) -> list[CheckResult]:
    """Every check of the scenes on the files in ``out_dir`` (:func:`scene_checks`);
    ``done(f"scene {name}", results)`` is called as each scene's checks finish."""
    results: list[CheckResult] = []
    for label, found in scene_checks(project, out_dir, names, cache, confirm):
        results += found
        if done is not None:
            done(label, found)
    return results


def scene_checks(project: Project, out_dir: str | Path, names: Iterable[str] | None = None,
                 cache: PartCache | None = None, confirm: bool = True) -> Iterator[Found]:
    """Every check of the scenes on the files in ``out_dir``: rig part solids
    (each once, in the first scene that shows it), interference (manifold3d
    fast path, OpenCascade confirmation), geometry sanity, STEP re-import and
    GLB read-back against the review records; ``(f"scene {name}", results)``
    as each scene's checks finish."""
    out_dir = Path(out_dir)
    cache = cache or PartCache(project.plan)
    results: list[CheckResult] = []
    checked_parts: set[str] = set()
    exact: dict = {}  # the array's stack recurs in every rig scene: confirmed once
    for name in (list(names) if names is not None else scene_names(project)):
        first = len(results)
        scene, solids = build_scene(project, name, cache)
        for pname, spec in scene.parts().items():
            if isinstance(spec, RigPartSpec) and pname not in checked_parts:
                checked_parts.add(pname)
                results += check_solid(spec, solids[pname])
        shown = placed_shapes(scene, solids)
        rep = check_mesh_interference(
            shown, scene.contacts, {i.name: i.part for i in scene.instances}, solids,
            {i.name: i.location for i in scene.instances}, confirm=confirm,
            part_meshes={i.part: cache.mesh(scene.specs[i.part]) for i in scene.instances},
            memo=exact)
        results += [CheckResult(r.check, f"{name}: {r.subject}", r.passed, r.detail)
                    for r in rep.results]
        results += check_scene_sanity(scene, {p.name: p.shape for p in shown})
        rec = review_record(scene)
        step = out_dir / scene_step_name(name)
        results += check_step(step, scene_step_name(name), rec["solids"], rec["volume_mm3"],
                              tuple(rec["bbox_mm"]), set(rec["labels"]))
        glb = out_dir / scene_glb_name(name)
        try:
            doc = read_glb(glb)
            nodes = [n for n in doc["nodes"][1:]]
            ok = (len(nodes) == len(scene.instances)
                  and sorted(n["name"] for n in nodes) == sorted(i.name for i in scene.instances)
                  and sorted(m["name"] for m in doc["meshes"]) == sorted(rec["labels"]))
            detail = f"{len(nodes)} nodes, {len(doc['meshes'])} meshes"
        except (OSError, ValueError, KeyError) as exc:
            ok, detail = False, f"{type(exc).__name__}: {exc}"
        results.append(CheckResult("glb_readback", scene_glb_name(name), ok, detail))
        yield f"scene {name}", results[first:]
