"""Scenes solved: every node of a rig placed by its joints (rigid and
linear, :mod:`tactcad.kernel.joints`), slides solved so that the rig's loops
close, and the shown parts built once each.

The rig models (nodes, joints, contacts) come from :mod:`tactcad.assembly.rig_models`
and never need the kernel; this module does. Scene frame: mm, y up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from tactcad.assembly.plan_locations import location
from tactcad.assembly.z_up import z_up_bbox
from tactcad.assembly.rig_models import (SOLVE_TOL_MM, Mate, RigModel, Slide, get_scene_spec,
                                   scene_model, shown_instances)
from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.catalogue.rig_catalogue import level_of
from tactcad.design.array_plan import Plan
from tactcad.design.project import Project
from tactcad.design.scene_specs import SceneSpec
from tactcad.errors import SceneError
from tactcad.geometry.frames import Frame
from tactcad.kernel.joints import carrier, rigid_joint, slide_joint
from tactcad.kernel.locations import point as located_point
from tactcad.solids.cache import PartCache


# ---------------------------------------------------------------------------
# Solving the joints
# ---------------------------------------------------------------------------
def solve(model: RigModel) -> tuple[dict[str, Any], dict[str, Any], dict[str, float]]:
    """Place every node with the kernel's joints and solve the slides.

    Returns:
        (node locations, leaf instance locations, slide positions in mm), the
        locations as CAD locations in the scene frame.

    Raises:
        SceneError: a solved slide position lies outside the slide's range.
        RuntimeError: a joint names a node placed later (a rig model error).
    """

    carriers = {name: carrier(name) for name in model.nodes}
    slides = {s.name: s for s in model.steps if isinstance(s, Slide)}
    slide_carriers = {name: carrier(f"slide:{name}") for name in slides}
    positions = {name: (s.position if s.position is not None else sum(s.range) / 2)
                 for name, s in slides.items()}
    placed = set(model.roots)
    for s in model.steps:
        if s.parent not in placed:
            raise RuntimeError(f"{model.rig}: {s.child} joins {s.parent} before it is placed")
        placed.add(s.child)
    if placed != set(model.nodes):
        raise RuntimeError(f"{model.rig}: unplaced nodes {sorted(set(model.nodes) - placed)}")

    def frame(node: str, name: str) -> Frame:
        try:
            return model.nodes[node].frames[name]
        except KeyError:
            raise RuntimeError(f"{model.rig}: node {node} has no joint frame {name!r}") from None

    def place() -> None:
        for name, f in model.roots.items():
            carriers[name].locate(f.location())
        for s in model.steps:
            parent, child = carriers[s.parent], carriers[s.child]
            child_joint = rigid_joint(f"to:{s.parent}", child,
                                      child.location * frame(s.child, s.child_frame).flipped().location())
            parent_joint = rigid_joint(f"{s.parent_frame}:{s.child}", parent,
                                       parent.location * frame(s.parent, s.parent_frame).location())
            if isinstance(s, Mate):
                parent_joint.connect_to(child_joint)
                continue
            sc = slide_carriers[s.name]
            base = rigid_joint("base", sc, sc.location)
            parent_joint.connect_to(base)  # the slide's frame sits on the parent's frame
            axis = slide_joint("axis", sc, sc.location, s.range)
            try:
                axis.connect_to(child_joint, position=positions[s.name])
            except ValueError:
                raise SceneError(
                    f"{model.rig}: slide {s.name} ({s.child} on {s.parent}) needs position "
                    f"{positions[s.name]:.3f} mm, its range is {s.range[0]:g} ... {s.range[1]:g} mm"
                ) from None

    def point(node: str, name: str):
        return (carriers[node].location * frame(node, name).location()).position

    place()
    for name in model.solve_order:
        s = slides[name]
        (mn, mf), (tn, tf) = s.solve
        d = point(tn, tf) - point(mn, mf)
        positions[name] += d.dot(_x_axis(slide_carriers[name].location))
        lo, hi = s.range
        if not lo - SOLVE_TOL_MM <= positions[name] <= hi + SOLVE_TOL_MM:
            raise SceneError(
                f"{model.rig}: slide {name} ({s.child} on {s.parent}) needs position "
                f"{positions[name]:.3f} mm to bring {mn}.{mf} onto {tn}.{tf}; its range is "
                f"{lo:g} ... {hi:g} mm")
        positions[name] = min(max(positions[name], lo), hi)
        place()
    axes = {name: _x_axis(slide_carriers[name].location) for name in model.solve_order}
    for k, name in enumerate(model.solve_order):
        # a loop must stay closed unless a later slide along the same axis took
        # it over (a coarse slide centres a stage, the stage's travel then aims)
        if any(abs(axes[name].dot(axes[later])) > 1 - 1e-9 for later in model.solve_order[k + 1:]):
            continue
        s = slides[name]
        (mn, mf), (tn, tf) = s.solve
        res = (point(tn, tf) - point(mn, mf)).dot(axes[name])
        if abs(res) > 1e-6:
            raise SceneError(f"{model.rig}: slide {name} left {res:.2e} mm between {mn}.{mf} "
                             f"and {tn}.{tf}")
    node_locs = {n: carriers[n].location for n in model.nodes}
    leaf_locs = {}
    for n in model.nodes.values():
        if n.part is not None:
            leaf_locs[n.name] = node_locs[n.name]
        for m in n.members:
            leaf_locs[m.name] = node_locs[n.name] * location(m.placement)
    return node_locs, leaf_locs, positions


def _x_axis(loc):
    return located_point(loc, (1, 0, 0)) - located_point(loc, (0, 0, 0))


# ---------------------------------------------------------------------------
# Scenes
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class PlacedPart:
    """One shown instance of a scene."""

    name: str
    part: str
    group: str
    level: str
    location: Any  # CAD location (tactcad.kernel.locations), scene frame


@dataclass
class Scene:
    """A solved scene: its shown instances and everything the checks need."""

    spec: SceneSpec
    plan: Plan
    model: RigModel
    instances: list[PlacedPart]
    specs: dict[str, PartSpec]
    contacts: set[frozenset[str]]
    node_locations: dict[str, Any]
    slide_positions: dict[str, float]

    @property
    def name(self) -> str:
        return self.spec.name

    def parts(self) -> dict[str, PartSpec]:
        """Distinct shown parts, in order of first use."""
        out: dict[str, PartSpec] = {}
        for i in self.instances:
            out.setdefault(i.part, self.specs[i.part])
        return out

    def world_point(self, node: str, frame: str):
        """Scene-frame position of a node's joint frame origin (mm)."""
        return (self.node_locations[node] * self.model.nodes[node].frames[frame].location()).position

    def joint_axes(self) -> dict[str, tuple[float, float, float]]:
        """Each shown instance's joint axis (unit vector, scene frame): the z axis
        of the parent's joint frame that its node, or the sub-assembly it is a
        member of, is mated or slid onto; it points out of the parent, towards
        the child. Instances of a root node have none."""
        from tactcad.kernel.locations import matrix

        step_of = {s.child: s for s in self.model.steps}
        member_of = {m.name: n.name for n in self.model.nodes.values() for m in n.members}
        out = {}
        for inst in self.instances:
            step = step_of.get(inst.name if inst.name in self.model.nodes else
                               member_of.get(inst.name, ""))
            if step is None:
                continue
            z = matrix(self.node_locations[step.parent]
                       * self.model.nodes[step.parent].frames[step.parent_frame].location())[:3, 2]
            norm = math.sqrt(sum(float(c) ** 2 for c in z))
            out[inst.name] = tuple(float(c) / norm for c in z)
        return out


def assemble(project: Project, name: str) -> Scene:
    """Solve scene ``name`` of ``project``: place every part by its joints and
    keep the shown ones. Builds no part.

    Raises:
        SceneError: unknown scene or group, or a slide out of its range.
        DesignError: a scene option outside the rigs' values.
    """
    plan = project.plan
    spec = get_scene_spec(project, name)
    model = scene_model(plan, spec, project.rigs)
    node_locs, leaf_locs, positions = solve(model)
    inst = [PlacedPart(iname, part, group, spec.detail[model.specs[part].kind], leaf_locs[iname])
            for iname, part, group in shown_instances(model, spec)]
    names = {i.name for i in inst}
    contacts = {c for c in model.contacts() if c <= names}
    specs = {i.part: model.specs[i.part] for i in inst}
    colors: dict[tuple, str] = {}
    for p in specs.values():
        if p.color in colors:
            raise RuntimeError(f"scene {name}: parts {colors[p.color]} and {p.name} share a colour")
        colors[p.color] = p.name
    return Scene(spec, plan, model, inst, specs, contacts, node_locs, positions)


def build_scene(project: Project, name: str,
                cache: PartCache | None = None) -> tuple[Scene, dict[str, Any]]:
    """Assemble scene ``name`` and build its shown parts (only those), each
    once per ``cache``.

    Returns:
        (scene, part solids by part name).

    Raises:
        SceneError: as :func:`assemble`, or a part asked at a level of detail
            it is not modelled at.
    """
    scene = assemble(project, name)
    cache = cache or PartCache(project.plan)
    solids = {}
    for i in scene.instances:
        spec = scene.specs[i.part]
        if i.level != level_of(spec):
            raise SceneError(f"part {spec.name} is modelled at level {level_of(spec)}, "
                             f"not {i.level}")
        if i.part not in solids:
            solids[i.part] = cache.solid(spec)
    return scene, solids


def review_record(scene: Scene) -> dict:
    """What a reviewer should find on re-import of the scene's STEP: solid
    count, total volume (mm^3), bounding box (mm, the STEP's Z-up frame) and part labels, from the
    expected part volumes and boxes and the solved placements (not from the CAD)."""
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for i in scene.instances:
        x0, y0, z0, x1, y1, z1 = scene.specs[i.part].expected_bbox_mm
        for c in ((x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)):
            p = located_point(i.location, c)
            for k, v in enumerate((p.X, p.Y, p.Z)):
                lo[k], hi[k] = min(lo[k], v), max(hi[k], v)
    counts: dict[str, int] = {}
    for i in scene.instances:
        counts[i.part] = counts.get(i.part, 0) + 1
    parts = {}
    for n, s in scene.parts().items():
        parts[n] = {"kind": s.kind, "process": s.process, "material": s.material,
                    "level": scene.spec.detail[s.kind], "quantity": counts[n],
                    "volume_mm3": s.expected_volume_mm3, **dict(getattr(s, "attributes", {}))}
    return {"solids": len(scene.instances),
            "volume_mm3": sum(scene.specs[i.part].expected_volume_mm3 for i in scene.instances),
            "bbox_mm": [_r(v) for v in z_up_bbox(lo + hi)],  # the STEP file is Z up
            "labels": sorted(counts),
            "instances": len(scene.instances), "rig": scene.spec.rig,
            "groups": list(scene.spec.groups), "parts": parts,
            "slides_mm": {k: _r(v) for k, v in sorted(scene.slide_positions.items())},
            "contacts": len(scene.contacts)}


def _r(v: float) -> float:
    """Round away the last bits of float noise so records are reproducible."""
    v = round(v, 9)
    return 0.0 if v == 0 else v


