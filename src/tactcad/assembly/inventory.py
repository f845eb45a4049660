"""Which assemblies the design has and how many of each part they hold,
without the CAD kernel: the array and every scene of the scenes file.

The scenes are set-ups of one set of hardware (the array moves from the array
scene to the calibration and evaluation rigs; the rigs share base plate and
column), so a part's quantity is its largest count in any one assembly, never
the sum.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

from tactcad.assembly.z_up import z_up_bbox
from tactcad.assembly.rig_models import RigModel, scene_model, shown_instances
from tactcad.catalogue.array_catalogue import PartSpec, array_instances, array_parts
from tactcad.catalogue.rig_catalogue import rig_parts
from tactcad.design.array_plan import Plan
from tactcad.design.project import Project
from tactcad.design.scene_specs import SceneSpec
from tactcad.partlib.sample import stiffnesses


@dataclass(frozen=True)
class Shown:
    """An instance of an assembly: its name and its part's name."""

    name: str
    part: str


def instance_counts(instances: Sequence) -> dict[str, int]:
    """Number of instances of each part name, in order of first use."""
    counts: dict[str, int] = {}
    for inst in instances:
        counts[inst.part] = counts.get(inst.part, 0) + 1
    return counts


def scene_models(project: Project) -> dict[str, tuple[SceneSpec, RigModel]]:
    """Every scene of the project with its rig model.

    Raises:
        DesignError: a scene option outside the rigs' values.
        SceneError: a scene names a group its rig does not have.
    """
    return {name: (spec, scene_model(project.plan, spec, project.rigs))
            for name, spec in project.scenes.items()}


def design_assemblies(project: Project,
                      models: Mapping[str, tuple[SceneSpec, RigModel]] | None = None
                      ) -> tuple[dict[str, PartSpec], dict[str, list]]:
    """Every distinct part of the design and every assembly's instances.

    Args:
        models: the result of :func:`scene_models`, if already at hand.

    Returns:
        (parts by name, {assembly name: instances}): the array of the
        catalogue first, then each scene of the project (instances
        have ``name`` and ``part``).

    Raises:
        DesignError: a scene option outside the rigs' values.
        SceneError: a scene names a group its rig does not have.
    """
    plan = project.plan
    specs = dict(array_parts(plan))
    assemblies: dict[str, list] = {"array": array_instances(plan)}
    for name, (spec, model) in (models if models is not None else scene_models(project)).items():
        shown = shown_instances(model, spec)
        for _, part, _ in shown:
            specs.setdefault(part, model.specs[part])
        assemblies[name] = [Shown(i, part) for i, part, _ in shown]
    return specs, assemblies


def part_quantities(assemblies: Mapping[str, Sequence]) -> dict[str, int]:
    """Quantity of each part to make or buy: its largest instance count in any one assembly."""
    total: dict[str, int] = {}
    for inst in assemblies.values():
        for part, n in instance_counts(inst).items():
            total[part] = max(total.get(part, 0), n)
    return total


def sample_kit(project: Project) -> dict[str, tuple[float, PartSpec]]:
    """Every sample the rigs file names, shown in a scene or not:
    ``{part: (stiffness N/mm, spec)}``, in the file's order; each its own part
    (:func:`tactcad.partlib.sample.sample_name`), the same spec a scene places."""
    data = project.rigs.library.get("sample") if project.rigs is not None else None
    if data is None:
        return {}
    specs = rig_parts(project.plan, project.rigs)
    return {d.name: (k, specs[d.name]) for d, k in zip((data, *data.companions), stiffnesses(data))}


def fabricated_parts(project: Project, assembled=None) -> tuple[list[PartSpec], dict[str, int]]:
    """(fabricated part specs, quantity of every part): the parts placed in an
    assembly, in catalogue order, then the kit's samples no scene shows (one
    each: the rigs file names them, so each is cast and drawn). Other parts
    placed in no assembly are left out.

    Args:
        assembled: the result of :func:`design_assemblies`, if already at hand.
    """
    specs, assemblies = assembled or design_assemblies(project)
    qty = part_quantities(assemblies)
    placed = [s for s in specs.values() if s.kind == "fabricated" and qty.get(s.name, 0) > 0]
    unshown = [s for _, s in sample_kit(project).values() if qty.get(s.name, 0) == 0]
    return placed + unshown, {**qty, **{s.name: 1 for s in unshown}}


def array_envelope_mm(plan: Plan) -> tuple[float, float, float]:
    """The clamped array's envelope (mm): X, Y and Z of its assembly STEP's box
    (Z up: X by Y in plan view, Z the height), from the expected part boxes."""
    box = assembly_review(array_parts(plan), array_instances(plan))["bbox_mm"]
    return tuple(float(box[k + 3] - box[k]) for k in range(3))


def assembly_review(specs: dict[str, PartSpec], instances) -> dict:
    """What a reviewer should find on re-import of an assembly STEP: solid
    count, total volume (mm^3), bounding box (mm, the STEP's Z-up frame) and part labels. The box is
    computed from the expected part boxes and placements, not from the CAD."""
    corners = []
    for i in instances:
        x0, y0, z0, x1, y1, z1 = specs[i.part].expected_bbox_mm
        corners += [i.placement.apply(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    lo = [min(c[k] for c in corners) for k in range(3)]
    hi = [max(c[k] for c in corners) for k in range(3)]
    return {"solids": len(instances),
            "volume_mm3": sum(specs[i.part].expected_volume_mm3 for i in instances),
            "bbox_mm": z_up_bbox(lo + hi),  # the STEP file is Z up
            "labels": sorted({i.part for i in instances})}
